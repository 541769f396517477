using System;
using System.Threading;

namespace Tpi.Native.Interop
{
    /// <summary>
    /// A managed progress handler and cancellation token as the library's TpiProgressCallback,
    /// for the calls that take one (tpi_discretise_with_progress,
    /// tpi_pattern_new_for_surface_with_progress). The callback reports to the handler and
    /// answers "cancel" once the token is cancelled; no exception crosses into the library: one
    /// the handler throws is kept, cancels the call and is rethrown by <see cref="Finish"/>.
    /// </summary>
    internal sealed class ProgressRelay
    {
        readonly Action<DiscretisationProgress> _progress;
        readonly CancellationToken _cancel;
        Exception _thrown;

        /// <summary>The callback to pass; kept alive by <see cref="Finish"/> until the call has returned.</summary>
        internal readonly UnsafeNativeMethods.ProgressCallback Callback;

        internal ProgressRelay(Action<DiscretisationProgress> progress, CancellationToken cancel)
        {
            _progress = progress;
            _cancel = cancel;
            Callback = Report;
        }

        int Report(IntPtr userData, uint stage, ulong done, ulong total)
        {
            try
            {
                if (_progress != null) _progress(new DiscretisationProgress((Stage)stage, done, total));
                return _cancel.IsCancellationRequested ? 1 : 0;
            }
            catch (Exception e)
            {
                if (_thrown == null) _thrown = e;
                return 1;
            }
        }

        /// <summary>
        /// After the call: disposes the handle made (if any) and throws when the handler threw
        /// (<see cref="InvalidOperationException"/> around it) or the call was cancelled
        /// (<see cref="OperationCanceledException"/> for the token, with the library's message);
        /// otherwise returns, leaving the status to the caller.
        /// </summary>
        internal void Finish(Status status, TpiHandle handle)
        {
            GC.KeepAlive(Callback);
            if (_thrown != null)
            {
                if (handle != null) handle.Dispose();
                throw new InvalidOperationException("the progress handler threw: " + _thrown.Message, _thrown);
            }
            if (status == Status.Cancelled)
            {
                var message = TpiLibrary.LastErrorMessage();
                if (handle != null) handle.Dispose();
                throw new OperationCanceledException(message, _cancel);
            }
        }
    }
}
