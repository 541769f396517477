using System;
using System.Collections.Generic;
using System.IO;
using NUnit.Framework;
using Tpi.Logic;

namespace Tpi.Tests
{
    [TestFixture]
    public class NativeLoadDecisionTests
    {
        static readonly string Plugins = Path.Combine(Path.GetTempPath(), "rhino-plugins");
        static readonly string Gh = Path.Combine(Path.GetTempPath(), "gh-libraries");

        [Test]
        public void AMismatchedLibraryIsReportedEveryTimeAndLoadedOnce()
        {
            var decision = new NativeLoadDecision();
            int loads = 0, checks = 0;
            Func<string, string> load = f => { loads++; return null; };
            Func<string, string> check = f => { checks++; return "version 9.0.0 does not match"; };
            var folders = new[] { Plugins };
            var first = decision.Ensure("tpi.dll", folders, f => true, load, check);
            StringAssert.Contains("does not match", first);
            var second = decision.Ensure("tpi.dll", folders, f => true, load, check);
            Assert.AreEqual(first, second, "the problem is repeated, the library never reported as usable");
            Assert.AreEqual(1, loads);
            Assert.AreEqual(1, checks);
        }

        [Test]
        public void SuccessIsDecidedOnce()
        {
            var decision = new NativeLoadDecision();
            int loads = 0;
            Assert.IsNull(decision.Ensure("tpi.dll", new[] { Plugins }, f => true, f => { loads++; return null; }, f => null));
            Assert.IsNull(decision.Ensure("tpi.dll", new[] { Plugins }, f => true, f => { loads++; return null; }, f => null));
            Assert.AreEqual(1, loads);
        }

        [Test]
        public void AMemoryLoadedAssemblyUsesTheHostsFolder()
        {
            // Assembly.Location is "" for a .gha loaded from bytes: only Grasshopper's record of the file is left.
            var folders = NativeLoadDecision.Folders(new[] { Gh }, new[] { "", null });
            CollectionAssert.AreEqual(new[] { Gh }, folders);
            string loaded = null;
            var problem = new NativeLoadDecision().Ensure("libtpi.dylib", folders, f => f == Path.Combine(Gh, "libtpi.dylib"),
                f => { loaded = f; return null; }, f => null);
            Assert.IsNull(problem);
            Assert.AreEqual(Path.Combine(Gh, "libtpi.dylib"), loaded);
        }

        [Test]
        public void HostFolderFirstThenAssemblyFoldersOnce()
        {
            var assembly = Path.Combine(Plugins, "Tpi.Rhino.rhp");
            var folders = NativeLoadDecision.Folders(new[] { Plugins, null }, new[] { assembly, Path.Combine(Gh, "Tpi.Native.dll") });
            CollectionAssert.AreEqual(new[] { Plugins, Gh }, folders);
            string loaded = null;
            new NativeLoadDecision().Ensure("tpi.dll", folders, f => f.StartsWith(Gh, StringComparison.Ordinal), f => { loaded = f; return null; }, f => null);
            Assert.AreEqual(Path.Combine(Gh, "tpi.dll"), loaded, "the first folder holding the file wins");
        }

        [Test]
        public void AMissingLibraryNamesEveryFolderSearched()
        {
            var problem = new NativeLoadDecision().Ensure("tpi.dll", new[] { Plugins, Gh }, f => false, f => null, f => null);
            StringAssert.Contains("tpi.dll is missing", problem);
            StringAssert.Contains(Plugins, problem);
            StringAssert.Contains(Gh, problem);
            var none = new NativeLoadDecision().Ensure("tpi.dll", new string[0], f => false, f => null, f => null);
            StringAssert.Contains("loaded from memory", none);
        }

        [Test]
        public void ALibraryWithoutTheEntryPointIsAProblemNotACrash()
        {
            var problem = new NativeLoadDecision().Ensure("tpi.dll", new[] { Plugins }, f => true, f => null,
                f => { throw new EntryPointNotFoundException("tpi_abi_version"); });
            StringAssert.Contains("cannot be used", problem);
            StringAssert.Contains("tpi_abi_version", problem);
        }
    }
}
