// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Threading;
using Rhino;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    /// <summary>
    /// Long work in a command (a fit, a relaxation: many discretisations) run on a worker while
    /// Rhino keeps pumping its messages (ForegroundWait): the command prompt shows the work's
    /// progress texts and Escape cancels it.
    /// </summary>
    internal static class Escapable
    {
        /// <summary>
        /// Runs <paramref name="work"/> (given a progress sink and the token Escape cancels) and
        /// waits for it, showing "<paramref name="what"/> TEXT (Escape cancels)" as the prompt.
        /// </summary>
        public static T Run<T>(string what, Func<Action<string>, CancellationToken, T> work)
        {
            using (var cancel = new CancellationTokenSource())
            {
                EventHandler onEscape = (sender, args) => cancel.Cancel();
                RhinoApp.EscapeKeyPressed += onEscape;
                try
                {
                    return ForegroundWait.Run(work, cancel.Token,
                        text => RhinoApp.SetCommandPrompt(what + " " + text + " (Escape cancels)"),
                        RhinoApp.Wait);
                }
                finally
                {
                    RhinoApp.EscapeKeyPressed -= onEscape;
                }
            }
        }
    }
}
