// Checked against: Grasshopper 8 (grasshopper-stubs-typed 8.20.25157) and RhinoCommon 8.
// Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using Grasshopper.Kernel;

namespace Tpi.GhComponents
{
    /// <summary>The progress text under a task-capable component while its solve runs.</summary>
    internal static class SolveProgress
    {
        /// <summary>
        /// Shows <paramref name="text"/> (ProgressText's, each new one once) under the component
        /// and asks for a canvas redraw on the UI thread; called from the solve's worker thread.
        /// </summary>
        public static void Show(GH_Component component, string text)
        {
            component.Message = text;
            Rhino.RhinoApp.InvokeOnUiThread(new Action(Grasshopper.Instances.RedrawCanvas));
        }
    }
}
