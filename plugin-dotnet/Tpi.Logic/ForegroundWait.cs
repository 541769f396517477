// Long work started from a Rhino command (a fit, a relaxation: many discretisations) run on
// a worker while the command's thread keeps the application responsive: it polls the work,
// shows each new progress text once and pumps the host's messages in between (where the
// host's Escape handler may cancel). Rhino-free, so the Mono tests check it; the Rhino
// adapter (Tpi.Rhino/Escapable.cs) wires RhinoApp.Wait, the prompt and Escape to it.
using System;
using System.Threading;
using System.Threading.Tasks;

namespace Tpi.Logic
{
    /// <summary>Runs work on a worker and waits for it on the calling thread, pumping in between.</summary>
    public static class ForegroundWait
    {
        /// <summary>How long one wait for the work lasts before the next pump (milliseconds).</summary>
        public const int PollMilliseconds = 50;

        /// <summary>
        /// Runs <paramref name="work"/> (given a progress sink and <paramref name="cancel"/>) on
        /// a worker; until it ends, calls <paramref name="show"/> on the calling thread with each
        /// progress text that differs from the last one shown, and <paramref name="pump"/> every
        /// <see cref="PollMilliseconds"/>. Returns the work's result, or rethrows what it threw
        /// (not wrapped).
        /// </summary>
        public static T Run<T>(Func<Action<string>, CancellationToken, T> work, CancellationToken cancel, Action<string> show, Action pump)
        {
            if (work == null) throw new ArgumentNullException("work");
            var gate = new object();
            string latest = null;
            Action<string> progress = text => { lock (gate) latest = text; };
            var task = Task.Run(() => work(progress, cancel));
            string shown = null;
            // Waiting on the handle, not Task.Wait: a failed task must not throw here, wrapped.
            var done = ((IAsyncResult)task).AsyncWaitHandle;
            while (!done.WaitOne(PollMilliseconds))
            {
                string text;
                lock (gate) text = latest;
                if (text != null && text != shown)
                {
                    if (show != null) show(text);
                    shown = text;
                }
                if (pump != null) pump();
            }
            return task.GetAwaiter().GetResult();
        }
    }
}
