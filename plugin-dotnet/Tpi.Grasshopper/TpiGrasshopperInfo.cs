// Checked against: Grasshopper 8 (grasshopper-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Drawing;
using System.Reflection;
using Grasshopper.Kernel;

namespace Tpi.GhComponents
{
    /// <summary>The .gha's description.</summary>
    public sealed class TpiGrasshopperInfo : GH_AssemblyInfo
    {
        /// <inheritdoc/>
        public override string Name { get { return "TPI"; } }
        /// <inheritdoc/>
        public override Bitmap Icon { get { return Icons.Load("discretise"); } }
        /// <inheritdoc/>
        public override string Description { get { return "Planar panels on free-form surfaces by tangent plane intersection."; } }
        /// <summary>Never change: identifies the library in .gh files.</summary>
        public override Guid Id { get { return LibraryId; } }
        internal static readonly Guid LibraryId = new Guid("3C8A1F52-6E0D-4D7B-A2B9-51F0E7C4D6A3");
        /// <inheritdoc/>
        public override string AuthorName { get { return "TPI contributors"; } }
        /// <inheritdoc/>
        public override string AuthorContact { get { return ProjectUrl; } }

        /// <summary>
        /// The project's address, set at build time (-p:TpiProjectUrl=..., the release workflow
        /// passes the GitHub repository's); the README's section otherwise.
        /// </summary>
        static string ProjectUrl
        {
            get
            {
                foreach (AssemblyMetadataAttribute a in typeof(TpiGrasshopperInfo).Assembly.GetCustomAttributes(typeof(AssemblyMetadataAttribute), false))
                    if (a.Key == "TpiProjectUrl" && !string.IsNullOrEmpty(a.Value)) return a.Value;
                return "see plugin-dotnet/README.md of the TPI sources";
            }
        }
        /// <inheritdoc/>
        public override string Version { get { return "0.1.0"; } }
    }

    /// <summary>Where the components sit: our own "TPI" tab, one panel per step.</summary>
    internal static class Tab
    {
        public const string Name = "TPI";
        public const string Pattern = "1 Pattern";
        public const string Panels = "2 Panels";
        public const string Analysis = "3 Analysis";
    }

    /// <summary>The 24x24 icons, embedded as Tpi.Grasshopper.Icons.NAME.png.</summary>
    internal static class Icons
    {
        public static Bitmap Load(string name)
        {
            var stream = typeof(Icons).Assembly.GetManifestResourceStream("Tpi.Grasshopper.Icons." + name + ".png");
            return stream == null ? null : new Bitmap(stream);
        }
    }

    /// <summary>Loads the native library once for all components.</summary>
    internal static class Native
    {
        public static string Problem
        {
            get { return Tpi.Plugin.NativeLoader.Ensure(GhaFolder()); }
        }

        /// <summary>
        /// The .gha's folder as Grasshopper knows it: with "memory load" (COFF byte arrays) the
        /// assembly has no Location, but Grasshopper's assembly record still has the file.
        /// </summary>
        static string GhaFolder()
        {
            var server = Grasshopper.Instances.ComponentServer;
            var info = server == null ? null : server.FindAssembly(TpiGrasshopperInfo.LibraryId);
            var location = info == null ? null : info.Location;
            return string.IsNullOrEmpty(location) ? null : System.IO.Path.GetDirectoryName(location);
        }
    }
}
