// Checked against: .NET Framework 4.8 / .NET 7 (System.Runtime.InteropServices.NativeLibrary);
// uses no RhinoCommon member. Linked into Tpi.Rhino and Tpi.Grasshopper (type-checked here
// against the fakes in the net48 flavour; the net7.0 branch needs the .NET SDK).
//
// Makes DllImport("tpi") find the native library shipped beside the plug-in:
//   - net48 (Rhino 8 on Windows, .NET Framework): loads tpi.dll by full path with LoadLibraryW;
//     later DllImport("tpi") calls bind to the module already loaded;
//   - net7.0 (Rhino 8 on Windows and macOS): registers a DllImport resolver for Tpi.Native
//     that loads tpi.dll / libtpi.dylib by full path.
// Where to look and the decide-once-after-the-compatibility-check rule are
// Tpi.Logic.NativeLoadDecision (tested with Mono): the folders the caller names (the .rhp's
// path from Rhino, the .gha's from Grasshopper: a .gha loaded from bytes has an empty
// Assembly.Location), then this assembly's and Tpi.Native.dll's folders when they have one.
// Every later call returns the first answer: a mismatched library is never used.
using System;
using System.Reflection;
using System.Runtime.InteropServices;
using Tpi.Logic;

namespace Tpi.Plugin
{
    internal static class NativeLoader
    {
        static readonly NativeLoadDecision s_decision = new NativeLoadDecision();

        /// <summary>The library's file name on this platform.</summary>
        public static string FileName
        {
            get { return Environment.OSVersion.Platform == PlatformID.Win32NT ? "tpi.dll" : "libtpi.dylib"; }
        }

        /// <summary>Returns null when the library is loaded and compatible, else a message for the user (the same on every call).</summary>
        public static string Ensure(params string[] folders)
        {
            var searched = NativeLoadDecision.Folders(folders,
                new[] { LocationOf(typeof(NativeLoader).Assembly), LocationOf(typeof(Tpi.Native.TpiLibrary).Assembly) });
            return s_decision.Ensure(FileName, searched, System.IO.File.Exists, Load, CompatibilityProblem);
        }

        static string LocationOf(Assembly assembly)
        {
            try { return assembly.Location; } // "" when loaded from bytes
            catch (NotSupportedException) { return null; } // dynamic assemblies
        }

        static string Load(string file)
        {
#if NETFRAMEWORK
            if (LoadLibraryW(file) == IntPtr.Zero) return "could not load " + file + " (Windows error " + Marshal.GetLastWin32Error() + ")";
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
            return null;
        }

        static string CompatibilityProblem(string file)
        {
            if (Tpi.Native.TpiLibrary.IsCompatible) return null;
            return "the native library " + file + " (version " + Tpi.Native.TpiLibrary.Version + ") does not match this plug-in (ABI " +
                Tpi.Native.TpiLibrary.AbiMajor + "." + Tpi.Native.TpiLibrary.AbiMinor + "): install matching versions";
        }

#if NETFRAMEWORK
        [DllImport("kernel32", CharSet = CharSet.Unicode, SetLastError = true)]
        static extern IntPtr LoadLibraryW(string path);
#endif
    }
}
