// Library-wide calls (version, status names, last error) and the helpers every wrapper uses:
// turning a status into a TpiException, and the copy-out convention (out, capacity, needed).
using System;
using System.Collections.Generic;
using System.Runtime.InteropServices;
using System.Text;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>Library-wide information and error handling.</summary>
    public static class TpiLibrary
    {
        /// <summary>The ABI version this binding was written against (TPI_VERSION_MAJOR.MINOR).</summary>
        public const int AbiMajor = 0;
        /// <summary>Minor version of the ABI this binding was written against.</summary>
        public const int AbiMinor = 1;

        /// <summary>The native library's version, "MAJOR.MINOR.PATCH".</summary>
        public static string Version { get { return ReadStaticUtf8(UnsafeNativeMethods.tpi_version()); } }

        /// <summary>
        /// True if the loaded library speaks the ABI of this binding (before 1.0 the minor
        /// version breaks the ABI, after it the major version).
        /// </summary>
        public static bool IsCompatible
        {
            get
            {
                var parts = Version.Split('.');
                int major, minor;
                if (parts.Length < 2 || !int.TryParse(parts[0], out major) || !int.TryParse(parts[1], out minor)) return false;
                return major == AbiMajor && (major > 0 || minor == AbiMinor);
            }
        }

        /// <summary>The name of a status, e.g. "TPI_STATUS_INVALID_NURBS" (from the library).</summary>
        public static string StatusName(Status status)
        {
            return ReadStaticUtf8(UnsafeNativeMethods.tpi_status_name((uint)status));
        }

        /// <summary>Handles created through this binding and not freed yet (all kinds together).</summary>
        public static long LiveHandleCount { get { return TpiHandle.LiveCount; } }

        /// <summary>
        /// The calling thread's last error message ("" after a successful call). Reading it
        /// does not change it.
        /// </summary>
        public static string LastErrorMessage()
        {
            UIntPtr needed;
            var status = UnsafeNativeMethods.tpi_last_error_message(null, UIntPtr.Zero, out needed);
            if (status == Status.Ok) return string.Empty;
            for (int attempt = 0; attempt < 4 && status == Status.BufferTooSmall; attempt++)
            {
                var buffer = new byte[checked((int)needed.ToUInt64())];
                status = UnsafeNativeMethods.tpi_last_error_message(buffer, needed, out needed);
                if (status == Status.Ok) return DecodeUtf8(buffer);
            }
            return "(the last error message could not be read: " + status + ")";
        }

        internal static void Check(Status status, string function)
        {
            if (status != Status.Ok) throw new TpiException(status, LastErrorMessage(), function);
        }

        internal static UIntPtr Size(int value)
        {
            // A negative index reaches the library as a huge size_t, which it reports as out of
            // range with its own message.
            return new UIntPtr(unchecked((ulong)(long)value));
        }

        internal static UIntPtr Size(long value)
        {
            return new UIntPtr(unchecked((ulong)value));
        }

        internal static int ToInt(UIntPtr value)
        {
            return checked((int)value.ToUInt64());
        }

        internal static double[] ArrayOrNull(IList<double> values)
        {
            if (values == null) return null;
            var array = values as double[];
            if (array != null) return array;
            array = new double[values.Count];
            values.CopyTo(array, 0);
            return array;
        }

        internal static UIntPtr Length(Array array)
        {
            return array == null ? UIntPtr.Zero : new UIntPtr((ulong)array.LongLength);
        }

        /// <summary>One call of a copy-out function: (out, capacity, &amp;needed).</summary>
        internal delegate Status CopyOutCall<T>(T[] buffer, UIntPtr capacity, out UIntPtr needed);

        /// <summary>
        /// The copy-out convention: ask for the size with (NULL, 0), allocate, copy. Retries if
        /// the data grew in between (a discrete surface edited on another thread).
        /// </summary>
        internal static T[] CopyOut<T>(CopyOutCall<T> call, string function)
        {
            UIntPtr needed;
            var status = call(null, UIntPtr.Zero, out needed);
            if (status == Status.Ok) return new T[0];
            for (int attempt = 0; attempt < 8 && status == Status.BufferTooSmall; attempt++)
            {
                var buffer = new T[ToInt(needed)];
                UIntPtr written;
                status = call(buffer, needed, out written);
                if (status == Status.Ok)
                {
                    if (written == needed) return buffer;
                    var shorter = new T[ToInt(written)];
                    Array.Copy(buffer, shorter, shorter.Length);
                    return shorter;
                }
                needed = written;
            }
            Check(status, function);
            throw new TpiException(Status.BufferTooSmall, "the data kept growing while it was copied", function);
        }

        /// <summary>Copy-out of NUL-terminated UTF-8 text.</summary>
        internal static string CopyOutText(CopyOutCall<byte> call, string function)
        {
            return DecodeUtf8(CopyOut(call, function));
        }

        internal static string DecodeUtf8(byte[] bytes)
        {
            int length = Array.IndexOf(bytes, (byte)0);
            if (length < 0) length = bytes.Length;
            return Encoding.UTF8.GetString(bytes, 0, length);
        }

        internal static byte[] EncodeUtf8(string text)
        {
            var bytes = Encoding.UTF8.GetBytes(text);
            var terminated = new byte[bytes.Length + 1];
            Buffer.BlockCopy(bytes, 0, terminated, 0, bytes.Length);
            return terminated;
        }

        static string ReadStaticUtf8(IntPtr text)
        {
            if (text == IntPtr.Zero) return string.Empty;
            var bytes = new List<byte>();
            for (int offset = 0; ; offset++)
            {
                byte b = Marshal.ReadByte(text, offset);
                if (b == 0) break;
                bytes.Add(b);
            }
            return Encoding.UTF8.GetString(bytes.ToArray());
        }
    }
}
