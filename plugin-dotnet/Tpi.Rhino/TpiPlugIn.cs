// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157; protected members against the
// RhinoCommon source). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using Rhino;
using Rhino.PlugIns;

namespace Tpi.RhinoPlugIn
{
    /// <summary>The TPI plug-in: planar panels by tangent plane intersection.</summary>
    public sealed class TpiPlugIn : PlugIn
    {
        /// <summary>The loaded instance.</summary>
        public static TpiPlugIn Instance { get; private set; }

        /// <summary>Made by Rhino.</summary>
        public TpiPlugIn() { Instance = this; }

        /// <summary>Loaded at start-up, so discrete surfaces in an opened file find their class and the watcher runs.</summary>
        public override PlugInLoadTime LoadTime { get { return PlugInLoadTime.AtStartup; } }

        /// <inheritdoc/>
        protected override LoadReturnCode OnLoad(ref string errorMessage)
        {
            // The .rhp's own folder as Rhino knows it (Assembly.Location is the fallback).
            string path = PlugIn.PathFromId(Id);
            var problem = Tpi.Plugin.NativeLoader.Ensure(string.IsNullOrEmpty(path) ? null : System.IO.Path.GetDirectoryName(path));
            if (problem != null)
            {
                errorMessage = "TPI: " + problem;
                return LoadReturnCode.ErrorShowDialog;
            }
            SourceSurfaceWatcher.Start();
            return LoadReturnCode.Success;
        }
    }
}
