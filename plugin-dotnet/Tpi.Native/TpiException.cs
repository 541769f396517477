using System;

namespace Tpi.Native
{
    /// <summary>
    /// A call into libtpi failed: carries the status and the library's last error message
    /// (read on the failing thread right after the call), e.g. "knots_u has 5 knots; with
    /// count 4 and degree 3 expected 6 (Rhino convention) or 8 (textbook convention)".
    /// </summary>
    [Serializable]
    public sealed class TpiException : Exception
    {
        /// <summary>The status the call returned (never <see cref="Native.Status.Ok"/>).</summary>
        public Status Status { get; private set; }

        /// <summary>The native last-error message, as the library wrote it.</summary>
        public string NativeMessage { get; private set; }

        /// <summary>The C function that failed, e.g. "tpi_surface_new_nurbs".</summary>
        public string Function { get; private set; }

        /// <summary>Makes the exception; the message reads "function: TPI_STATUS_X: native message".</summary>
        public TpiException(Status status, string nativeMessage, string function)
            : base(string.Format("{0}: {1}: {2}", function, TpiLibrary.StatusName(status), nativeMessage))
        {
            Status = status;
            NativeMessage = nativeMessage;
            Function = function;
        }
    }
}
