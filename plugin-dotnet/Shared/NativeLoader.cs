// Checked against: .NET Framework 4.8 / .NET 7 (System.Runtime.InteropServices.NativeLibrary);
// uses no RhinoCommon member. Linked into Tpi.Rhino and Tpi.Grasshopper (type-checked here
// against the fakes in the net48 flavour; the net7.0 branch needs the .NET SDK).
//
// Makes DllImport("tpi") find the native library shipped beside the plug-in:
//   - net48 (Rhino 8 on Windows, .NET Framework): loads tpi.dll by full path with LoadLibraryW;
//     later DllImport("tpi") calls bind to the module already loaded;
//   - net7.0 (Rhino 8 on Windows and macOS): registers a DllImport resolver for Tpi.Native
//     that loads tpi.dll / libtpi.dylib by full path.
// Where: the folders the caller names (the .rhp's path from Rhino, the .gha's from
// Grasshopper: a .gha loaded from bytes has an empty Assembly.Location), then the folders of
// this assembly and of Tpi.Native.dll when they have a location. The first folder holding the
// file wins; none: a message naming every folder searched.
// The result (success or the problem) is decided once, after the compatibility check, and
// every later call returns the same: a mismatched library is never used.
using System;
using System.Collections.Generic;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Runtime.InteropServices;

namespace Tpi.Plugin
{
    internal static class NativeLoader
    {
        static readonly object s_lock = new object();
        static bool s_decided;
        static string s_problem;

        /// <summary>The library's file name on this platform.</summary>
        public static string FileName
        {
            get { return Environment.OSVersion.Platform == PlatformID.Win32NT ? "tpi.dll" : "libtpi.dylib"; }
        }

        /// <summary>Returns null when the library is loaded and compatible, else a message for the user (the same on every call).</summary>
        public static string Ensure(params string[] folders)
        {
            lock (s_lock)
            {
                if (!s_decided)
                {
                    s_problem = Load(folders ?? new string[0]);
                    s_decided = true;
                }
                return s_problem;
            }
        }

        static string FolderOf(Assembly assembly)
        {
            try
            {
                var location = assembly.Location; // "" when loaded from bytes
                return string.IsNullOrEmpty(location) ? null : Path.GetDirectoryName(location);
            }
            catch (NotSupportedException)
            {
                return null; // dynamic assemblies
            }
        }

        static string Load(string[] hints)
        {
            var folders = hints.Where(f => !string.IsNullOrEmpty(f))
                .Concat(new[] { FolderOf(typeof(NativeLoader).Assembly), FolderOf(typeof(Tpi.Native.TpiLibrary).Assembly) })
                .Where(f => f != null).Distinct().ToList();
            var file = folders.Select(f => Path.Combine(f, FileName)).FirstOrDefault(File.Exists);
            if (file == null)
                return "the native library " + FileName + " is missing; looked in: " +
                    (folders.Count == 0 ? "(no folder known: the plug-in was loaded from memory)" : string.Join(", ", folders));
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
            try
            {
                if (!Tpi.Native.TpiLibrary.IsCompatible)
                    return "the native library " + file + " (version " + Tpi.Native.TpiLibrary.Version + ") does not match this plug-in (ABI " +
                        Tpi.Native.TpiLibrary.AbiMajor + "." + Tpi.Native.TpiLibrary.AbiMinor + "): install matching versions";
            }
            catch (Exception e) when (e is DllNotFoundException || e is EntryPointNotFoundException || e is BadImageFormatException)
            {
                return "the native library " + file + " cannot be used: " + e.Message;
            }
            return null;
        }

#if NETFRAMEWORK
        [DllImport("kernel32", CharSet = CharSet.Unicode, SetLastError = true)]
        static extern IntPtr LoadLibraryW(string path);
#endif
    }
}
