// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157) — uses no RhinoCommon member.
// Linked into Tpi.Rhino and Tpi.Grasshopper (not compiled with Mono here).
//
// Makes DllImport("tpi") find the native library shipped beside the plug-in:
//   - net48 (Rhino 8 on Windows, .NET Framework): loads tpi.dll from the plug-in folder by full
//     path with LoadLibraryW; later DllImport("tpi") calls bind to the module already loaded;
//   - net7.0 (Rhino 8 on Windows and macOS): registers a DllImport resolver for Tpi.Native
//     that loads tpi.dll / libtpi.dylib from the plug-in folder.
// Both plug-ins call Ensure(); the first call wins, later calls do nothing.
using System;
using System.IO;
using System.Reflection;
using System.Runtime.InteropServices;

namespace Tpi.Plugin
{
    internal static class NativeLoader
    {
        static readonly object s_lock = new object();
        static bool s_done;

        /// <summary>Returns null on success, else a message for the user.</summary>
        public static string Ensure()
        {
            lock (s_lock)
            {
                if (s_done) return null;
                var folder = Path.GetDirectoryName(typeof(NativeLoader).Assembly.Location) ?? ".";
                bool windows = Environment.OSVersion.Platform == PlatformID.Win32NT;
                var file = Path.Combine(folder, windows ? "tpi.dll" : "libtpi.dylib");
                if (!File.Exists(file)) return "the native library is missing: " + file;
#if NETFRAMEWORK
                if (LoadLibraryW(file) == IntPtr.Zero) return "could not load " + file + " (error " + Marshal.GetLastWin32Error() + ")";
#else
                try
                {
                    NativeLibrary.SetDllImportResolver(typeof(Tpi.Native.TpiLibrary).Assembly,
                        (name, assembly, path) => name == "tpi" ? NativeLibrary.Load(file) : IntPtr.Zero);
                }
                catch (InvalidOperationException)
                {
                    // The other plug-in (Rhino or Grasshopper) registered it already.
                }
#endif
                s_done = true;
                if (!Tpi.Native.TpiLibrary.IsCompatible)
                    return "native library " + Tpi.Native.TpiLibrary.Version + " does not match this plug-in (ABI " +
                        Tpi.Native.TpiLibrary.AbiMajor + "." + Tpi.Native.TpiLibrary.AbiMinor + ")";
                return null;
            }
        }

#if NETFRAMEWORK
        [DllImport("kernel32", CharSet = CharSet.Unicode, SetLastError = true)]
        static extern IntPtr LoadLibraryW(string path);
#endif
    }
}
