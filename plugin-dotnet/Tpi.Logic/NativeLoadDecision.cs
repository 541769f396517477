// The decisions of Shared/NativeLoader.cs (the plug-ins' loader of the native library), without
// the platform calls, so they are tested here: where to look, and that the answer, success or
// the problem, is decided once after the compatibility check and then repeated, so a
// mismatched library is reported on every use and never used.
using System;
using System.Collections.Generic;
using System.IO;
using System.Linq;

namespace Tpi.Logic
{
    /// <summary>Finds, loads and checks the native library once; every later call gets the same answer.</summary>
    public sealed class NativeLoadDecision
    {
        readonly object _lock = new object();
        bool _decided;
        string _problem;

        /// <summary>
        /// The folders to search, in order: the host's folders first (the .rhp's path from Rhino,
        /// the .gha's from Grasshopper: a .gha loaded from bytes has an empty Assembly.Location),
        /// then the assemblies' own locations; empty and missing ones dropped, duplicates once.
        /// </summary>
        public static IReadOnlyList<string> Folders(IEnumerable<string> hostFolders, IEnumerable<string> assemblyLocations)
        {
            var fromAssemblies = (assemblyLocations ?? new string[0])
                .Where(l => !string.IsNullOrEmpty(l)).Select(Path.GetDirectoryName);
            return (hostFolders ?? new string[0]).Concat(fromAssemblies)
                .Where(f => !string.IsNullOrEmpty(f)).Distinct().ToArray();
        }

        /// <summary>
        /// The answer (null: loaded and compatible, else the message for the user). The first
        /// call finds <paramref name="fileName"/> in <paramref name="folders"/>
        /// (<paramref name="exists"/>), loads it (<paramref name="load"/>: null or the problem),
        /// then checks it (<paramref name="compatibilityProblem"/>: null or the problem); later
        /// calls return the first answer without doing anything.
        /// </summary>
        public string Ensure(string fileName, IReadOnlyList<string> folders, Func<string, bool> exists,
            Func<string, string> load, Func<string, string> compatibilityProblem)
        {
            lock (_lock)
            {
                if (_decided) return _problem;
                _problem = Decide(fileName, folders, exists, load, compatibilityProblem);
                _decided = true;
                return _problem;
            }
        }

        static string Decide(string fileName, IReadOnlyList<string> folders, Func<string, bool> exists,
            Func<string, string> load, Func<string, string> compatibilityProblem)
        {
            string file = null;
            foreach (var folder in folders)
            {
                var candidate = Path.Combine(folder, fileName);
                if (exists(candidate)) { file = candidate; break; }
            }
            if (file == null)
                return "the native library " + fileName + " is missing; looked in: " +
                    (folders.Count == 0 ? "(no folder known: the plug-in was loaded from memory)" : string.Join(", ", folders));
            try
            {
                return load(file) ?? compatibilityProblem(file);
            }
            catch (Exception e) when (e is DllNotFoundException || e is EntryPointNotFoundException || e is BadImageFormatException)
            {
                return "the native library " + file + " cannot be used: " + e.Message;
            }
        }
    }
}
