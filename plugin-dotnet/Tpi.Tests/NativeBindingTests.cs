using System;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Runtime.InteropServices;
using System.Text.RegularExpressions;
using NUnit.Framework;
using Tpi.Native;
using Tpi.Native.Interop;

namespace Tpi.Tests
{
    /// <summary>The binding itself: every entry point resolves, struct sizes, version.</summary>
    [TestFixture]
    public class NativeBindingTests
    {
        static MethodInfo[] Imports()
        {
            return typeof(UnsafeNativeMethods).GetMethods(BindingFlags.Static | BindingFlags.NonPublic | BindingFlags.Public)
                .Where(m => m.GetCustomAttributes(typeof(DllImportAttribute), false).Length > 0).ToArray();
        }

        static string EntryPoint(MethodInfo m)
        {
            var attribute = (DllImportAttribute)m.GetCustomAttributes(typeof(DllImportAttribute), false)[0];
            return attribute.EntryPoint ?? m.Name;
        }

        [Test]
        public void EveryDeclarationResolvesInTheRealLibrary()
        {
            foreach (var m in Imports())
            {
                var attribute = (DllImportAttribute)m.GetCustomAttributes(typeof(DllImportAttribute), false)[0];
                Assert.AreEqual(CallingConvention.Cdecl, attribute.CallingConvention, m.Name);
                Assert.AreEqual("tpi", attribute.Value, m.Name);
                Marshal.Prelink(m); // throws EntryPointNotFoundException if the symbol is missing
            }
        }

        [Test]
        public void EveryHeaderFunctionIsDeclared()
        {
            var header = Environment.GetEnvironmentVariable("TPI_HEADER");
            Assert.IsNotNull(header, "TPI_HEADER (path of include/tpi.h) is not set");
            var declared = Regex.Matches(File.ReadAllText(header), @"\b(tpi_[a-z0-9_]+)\(")
                .Cast<Match>().Select(m => m.Groups[1].Value).Distinct().OrderBy(s => s).ToArray();
            var imported = Imports().Select(EntryPoint).Distinct().OrderBy(s => s).ToArray();
            Assert.AreEqual(78, declared.Length, "functions in the header");
            CollectionAssert.AreEquivalent(declared, imported);
        }

        [Test]
        public void StructSizesMatchTheHeader()
        {
            Assert.AreEqual(48, Marshal.SizeOf(typeof(NativeOptions)), "TpiOptions (TPI_OPTIONS_SIZE_V2)");
            Assert.AreEqual(40, (int)Marshal.OffsetOf(typeof(NativeOptions), "PlaneMode"), "TpiOptions.plane_mode (TPI_OPTIONS_SIZE_V1)");
            Assert.AreEqual(248, Marshal.SizeOf(typeof(QualityReport)), "TpiQualityReport (TPI_QUALITY_REPORT_SIZE_V3)");
            Assert.AreEqual(232, (int)Marshal.OffsetOf(typeof(QualityReport), "FarVertexFacets"), "TpiQualityReport.far_vertex_facets (TPI_QUALITY_REPORT_SIZE_V2)");
            Assert.AreEqual(32, Marshal.SizeOf(typeof(Domain)), "TpiDomain");
            Assert.AreEqual(120, Marshal.SizeOf(typeof(Sample)), "TpiSample");
            Assert.AreEqual(80, Marshal.SizeOf(typeof(Seed)), "TpiSeed");
            Assert.AreEqual(48, Marshal.SizeOf(typeof(FacetPlane)), "TpiPlane");
            Assert.AreEqual(12, Marshal.SizeOf(typeof(DiagnosticEntry)), "TpiDiagnosticEntry");
            Assert.AreEqual(40, Marshal.SizeOf(typeof(FitReport)), "TpiFitReport (TPI_FIT_REPORT_SIZE_V1)");
            Assert.AreEqual(16, (int)Marshal.OffsetOf(typeof(FitReport), "MaxDeviation"));
            Assert.AreEqual(168, (int)Marshal.OffsetOf(typeof(QualityReport), "CompensationFlips"));
            Assert.AreEqual(112, (int)Marshal.OffsetOf(typeof(QualityReport), "BoundaryLoops"));
        }

        [Test]
        public void VersionAndStatusNames()
        {
            StringAssert.IsMatch(@"^\d+\.\d+\.\d+$", TpiLibrary.Version);
            Assert.IsTrue(TpiLibrary.IsCompatible, TpiLibrary.Version);
            Assert.AreEqual("TPI_STATUS_INVALID_NURBS", TpiLibrary.StatusName(Status.InvalidNurbs));
            Assert.AreEqual("TPI_STATUS_UNAVAILABLE", TpiLibrary.StatusName(Status.Unavailable));
            Assert.AreEqual("TPI_STATUS_UNKNOWN", TpiLibrary.StatusName((Status)999));
        }

        [Test]
        public void DefaultOptionsComeFromTheLibrary()
        {
            var o = DiscretisationOptions.Default();
            Assert.IsTrue(o.EnvelopeRepair);
            Assert.IsTrue(o.QualityReport);
            Assert.AreEqual(8.0, o.FarVertexFactor);
            Assert.AreEqual(1e-10, o.WeldTolerance);
            Assert.AreEqual(1e-6, o.FlatTolerance);
        }
    }
}
