using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading.Tasks;
using NUnit.Framework;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>The managed API against the real library: the happy path.</summary>
    [TestFixture]
    public class NativeApiTests
    {
        [Test]
        public void NurbsDomeSamplesLikeTheClosedForm()
        {
            using (var dome = TestData.Dome())
            {
                var d = dome.Domain;
                Assert.AreEqual(0.0, d.UMin); Assert.AreEqual(1.0, d.UMax);
                Assert.AreEqual(0.0, d.VMin); Assert.AreEqual(1.0, d.VMax);
                // z = (3u(1-u) + 3v(1-v)) / 2, x = 2u - 1, y = 2v - 1.
                var s = dome.Evaluate(0.25, 0.5);
                Assert.AreEqual(-0.5, s.Point.X, 1e-12);
                Assert.AreEqual(0.0, s.Point.Y, 1e-12);
                Assert.AreEqual(0.5 * (3 * 0.25 * 0.75 + 3 * 0.25), s.Point.Z, 1e-12);
                Assert.IsTrue(s.IsRegular);
                // Su = (2, 0, 1.5 (1 - 2u)), Sv = (0, 2, 0) at v = 1/2: normal ~ Su x Sv.
                var su = new Vec3(2, 0, 1.5 * (1 - 2 * 0.25));
                var sv = new Vec3(0, 2, 0);
                var n = Vec3.Cross(su, sv);
                n = (1 / n.Length) * n;
                Assert.AreEqual(n.X, s.Normal.X, 1e-12);
                Assert.AreEqual(n.Z, s.Normal.Z, 1e-12);
                Assert.Less(s.K1, 0.0, "the dome bends away from the upward normal");
                var many = dome.Evaluate(new[] { 0.0, 0.0, 1.0, 1.0, 0.5, 0.5 });
                Assert.AreEqual(3, many.Length);
                Assert.AreEqual(1.0, many[1].Point.X, 1e-12);
            }
        }

        [Test]
        public void UnitsAreRhinoUnitSystemValuesOnACopy()
        {
            using (var plain = TestData.Dome())
            using (var mm = plain.WithUnits(2))
            {
                Assert.AreEqual(0, plain.Units, "a new surface is unitless");
                Assert.AreEqual(2, mm.Units, "UnitSystem.Millimeters");
                Assert.AreEqual(plain.Evaluate(0.3, 0.6).Point.Z, mm.Evaluate(0.3, 0.6).Point.Z, "nothing is rescaled");
                var e = Assert.Throws<TpiException>(() => plain.WithUnits(6));
                StringAssert.Contains("units 6", e.Message);
            }
        }

        static double[] Disc(int n, double r, bool clockwise)
        {
            var flat = new double[2 * n];
            for (int k = 0; k < n; k++)
            {
                double a = 2 * Math.PI * k / n * (clockwise ? -1 : 1);
                flat[2 * k] = 0.5 + r * Math.Cos(a);
                flat[2 * k + 1] = 0.5 + r * Math.Sin(a);
            }
            return flat;
        }

        static bool InPolygon(double[] loop, double u, double v)
        {
            bool inside = false;
            int n = loop.Length / 2;
            for (int i = 0, j = n - 1; i < n; j = i++)
            {
                double ui = loop[2 * i], vi = loop[2 * i + 1], uj = loop[2 * j], vj = loop[2 * j + 1];
                if ((vi > v) != (vj > v) && u < (uj - ui) * (v - vi) / (vj - vi) + ui) inside = !inside;
            }
            return inside;
        }

        [Test]
        public void WithTrimKeepsThePatternPointsInside()
        {
            var outer = Disc(40, 0.4, false);
            var hole = Disc(12, 0.1, true);
            using (var dome = TestData.Dome())
            using (var trimmed = dome.WithTrim(outer))
            using (var holed = dome.WithTrim(outer, new List<IList<double>> { hole }))
            using (var pattern = Pattern.Hex(9, 9))
            {
                var points = pattern.Points;
                int inside = points.Count(p => InPolygon(outer, p.S, p.T));
                int kept = points.Count(p => InPolygon(outer, p.S, p.T) && !InPolygon(hole, p.S, p.T));
                Assert.Less(kept, inside);
                Assert.Less(inside, points.Count);
                using (var mesh = Discretisation.Create(trimmed, pattern)) Assert.AreEqual(inside, mesh.FacetCount);
                using (var mesh = Discretisation.Create(holed, pattern)) Assert.AreEqual(kept, mesh.FacetCount);
                Assert.AreEqual(dome.Evaluate(0.1, 0.1).Point.Z, trimmed.Evaluate(0.1, 0.1).Point.Z);

                var e = Assert.Throws<TpiException>(() => dome.WithTrim(Disc(40, 0.4, true)));
                Assert.AreEqual(Status.InvalidArgument, e.Status);
                StringAssert.Contains("trim.outer", e.Message);
                e = Assert.Throws<TpiException>(() => dome.WithTrim(outer, new List<IList<double>> { Disc(12, 0.1, false) }));
                StringAssert.Contains("trim.holes[0]", e.Message);
                e = Assert.Throws<TpiException>(() => dome.WithTrim(new[] { 0.1, 0.1, 0.9 }));
                StringAssert.Contains("outer_uv", e.Message);
                e = Assert.Throws<TpiException>(() => DiscreteSurface.Create(trimmed, pattern));
                Assert.AreEqual(Status.InvalidArgument, e.Status);
                StringAssert.Contains("trim", e.Message);
            }
        }

        [Test]
        public void RationalNurbsWithUnitWeightsEqualsNonRational()
        {
            var weights = Enumerable.Repeat(1.0, 16).ToArray();
            using (var plain = TestData.Dome())
            using (var rational = Surface.FromNurbs(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, TestData.DomePoints(), weights))
            {
                var a = plain.Evaluate(0.3, 0.6);
                var b = rational.Evaluate(0.3, 0.6);
                Assert.AreEqual(a.Point.Z, b.Point.Z, 1e-12);
            }
        }

        [Test]
        public void PatternGeneratorsAndPoints()
        {
            using (var grid = Pattern.Grid(3, 2))
            {
                Assert.AreEqual(6, grid.Count);
                var p = grid.Points;
                Assert.AreEqual(new PatternPoint(1.0 / 6, 0.25), p[0]);
                Assert.AreEqual(new PatternPoint(1.0 / 6, 0.75), p[1]);
                Assert.AreEqual(12, grid.GetPointArray().Length);
            }
            using (var hex = Pattern.Hex(4, 4)) Assert.AreEqual(16, hex.Count);
            using (var a = Pattern.Jitter(5, 5, 0.5, 7))
            using (var b = Pattern.Jitter(5, 5, 0.5, 7))
                CollectionAssert.AreEqual(a.GetPointArray(), b.GetPointArray(), "deterministic for a seed");
            using (var r = Pattern.Random(50, 1)) Assert.AreEqual(50, r.Count);
            using (var poisson = Pattern.Poisson(0.1, 3)) Assert.Greater(poisson.Count, 20);
            using (var spec = Pattern.FromSpec("hex:6x5")) Assert.AreEqual(30, spec.Count);
            using (var explicitPoints = Pattern.FromPoints(new[] { new PatternPoint(0.1, 0.1), new PatternPoint(0.9, 0.2), new PatternPoint(0.5, 0.8) }))
                Assert.AreEqual(3, explicitPoints.Count);
        }

        [Test]
        public void DiscretiseTheDome()
        {
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Hex(6, 6))
            using (var mesh = Discretisation.Create(dome, pattern))
            {
                Assert.AreEqual(36, mesh.FacetCount);
                Assert.AreEqual(mesh.VertexCount, mesh.Vertices.Count);
                Assert.AreEqual(3 * mesh.VertexCount, mesh.GetVertexArray().Length);
                Assert.AreEqual(36, mesh.FacetSizes.Count);
                Assert.AreEqual(mesh.FacetSizes.Sum(s => (long)s), mesh.FacetIndices.Count);
                Assert.AreEqual(36, mesh.Seeds.Count);
                Assert.AreEqual(36, mesh.Planes.Count);
                Assert.AreEqual(36, mesh.Flags.Count);
                // Every facet vertex lies in its facet's tangent plane.
                var q = mesh.Quality;
                for (int f = 0; f < mesh.FacetCount; f++)
                    foreach (var v in mesh.GetFacet(f))
                        Assert.AreEqual(0.0, mesh.Planes[f].SignedDistance(mesh.Vertices[v]), 1e-9 * q.BoundingBoxDiagonal);
                Assert.AreEqual(QualityReport.SizeV3, (int)q.StructSize);
                Assert.AreEqual(0ul, q.FarVertexFacets);
                Assert.Greater(q.MaxDeviationSpacings, 0.0);
                Assert.Less(q.MaxDeviationSpacings, 1.0);
                Assert.AreEqual(1u, q.AllFinite);
                Assert.AreEqual(0ul, q.InvalidFacets);
                Assert.AreEqual(0ul, q.OpenFacets);
                Assert.AreEqual(36ul, q.FacetCount);
                Assert.AreEqual(1L, q.EulerCharacteristic);
                Assert.AreEqual(1ul, q.BoundaryLoops);
                Assert.Less(q.MaxPlanarityError, 1e-9);
                StringAssert.Contains("\"side_histogram\"", mesh.QualityJson);
                Assert.AreEqual((int)q.DiagnosticCount, mesh.DiagnosticCount);
                StringAssert.StartsWith("[", mesh.DiagnosticsJson);
                StringAssert.Contains("\"vertices\"", mesh.ToJson());
                Assert.IsFalse(mesh.ToJson().Contains("timings_ms"));
                Assert.IsTrue(mesh.ToJson(true).Contains("timings_ms"));
                Assert.Greater(mesh.NeighbourPairs.Count, 0);
                Assert.AreEqual(0, mesh.DualTriangles.Count % 3);
                var seed = mesh.Seeds[0];
                var p0 = pattern.Points[0];
                Assert.AreEqual(p0.S, seed.U, 1e-15);
                Assert.AreEqual(p0.T, seed.V, 1e-15);
                Assert.IsNotNull(mesh.DiagnosticEntries);
            }
        }

        [Test]
        public void OptionsReachTheLibrary()
        {
            var options = DiscretisationOptions.Default();
            options.QualityReport = false;
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Grid(5, 5))
            using (var mesh = Discretisation.Create(dome, pattern, options))
            {
                QualityReport report;
                Assert.IsFalse(mesh.TryGetQuality(out report));
                var e = Assert.Throws<TpiException>(() => { var unused = mesh.Quality; });
                Assert.AreEqual(Status.Unavailable, e.Status);
                Assert.AreEqual(0, mesh.Flags.Count, "no flags without the report");
            }
        }

        [Test]
        public void AdjustedPlanesReachTheLibraryAndEachFacetGetsItsPlane()
        {
            var options = DiscretisationOptions.Default();
            Assert.AreEqual(PlaneMode.Exact, options.Planes, "exact planes by default");
            options.Planes = PlaneMode.Adjusted;
            using (var hypar = Surface.HyperbolicParaboloid(0.1, 0.1, -3, 3, -3, 3))
            using (var pattern = Pattern.Random(2000, 7))
            using (var exact = Discretisation.Create(hypar, pattern))
            using (var adjusted = Discretisation.Create(hypar, pattern, options))
            {
                int tilted = 0;
                for (int f = 0; f < adjusted.FacetCount; f++)
                {
                    var plane = adjusted.Planes[f];
                    var seed = adjusted.Seeds[f];
                    double cos = Math.Min(1.0, Vec3.Dot(plane.Normal, seed.Normal));
                    double degrees = Math.Acos(cos) * 180.0 / Math.PI;
                    Assert.LessOrEqual(degrees, 5.0 + 1e-6, "facet {0} tilted", f);
                    if (degrees > 1e-9) tilted++;
                    foreach (var v in adjusted.GetFacet(f))
                        Assert.AreEqual(0.0, plane.SignedDistance(adjusted.Vertices[v]), 1e-9, "facet {0} off its plane", f);
                    Assert.AreEqual(exact.Seeds[f].Normal.X, exact.Planes[f].Normal.X, 0.0, "exact planes are the seeds'");
                }
                Assert.Greater(tilted, 0, "no plane adjusted");
                Assert.AreEqual(0ul, adjusted.Quality.InvalidFacets);
                Assert.Greater(exact.Quality.InvalidFacets, 0ul, "the case needs adjusting");
            }
        }

        [Test]
        public void FabricationFromADiscretisation()
        {
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Hex(6, 6))
            using (var mesh = Discretisation.Create(dome, pattern))
            using (var fab = Fabrication.Create(mesh, 0.05, PanelSide.Inside, 2, 4.0, 2.0, 0.05))
            {
                Assert.AreEqual(mesh.FacetCount, fab.PanelCount, "one panel per facet");
                Assert.Greater(fab.SheetCount, 0);
                StringAssert.Contains("\"panels\"", fab.File(FabricationFile.PanelsJson));
                StringAssert.StartsWith("<", fab.File(FabricationFile.SheetsSvg).TrimStart());
                StringAssert.Contains("EOF", fab.File(FabricationFile.SheetsDxf));
                StringAssert.Contains("G1", fab.GCode(0.01));
                var bad = Assert.Throws<TpiException>(() => Fabrication.Create(mesh, -1.0, PanelSide.Inside, 0, 4.0, 2.0, 0.05));
                StringAssert.Contains("thickness", bad.Message);
            }
        }

        [Test]
        public void DiscreteSurfaceEditsThenRecomputeEqualADiscretisationFromScratch()
        {
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Hex(6, 6))
            using (var live = DiscreteSurface.Create(dome, pattern))
            {
                Assert.AreEqual(36, live.PointCount);
                Assert.AreEqual(0, live.PendingEdits);
                Discretisation first;
                using (first = live.GetMesh()) Assert.AreEqual(36, first.FacetCount);

                live.MovePoint(3, 0.31, 0.12);
                int added = live.AddPoint(0.52, 0.49);
                Assert.AreEqual(36, added);
                live.RemovePoint(0);
                Assert.AreEqual(3, live.PendingEdits);
                Assert.AreEqual(36, live.PointCount);
                using (var stale = live.GetMesh()) Assert.AreEqual(36, stale.FacetCount, "the mesh changes only at recompute");

                live.Recompute();
                Assert.AreEqual(0, live.PendingEdits);
                var points = live.GetPointArray();
                Assert.AreEqual(0.31, points[2 * 2]);
                Assert.AreEqual(0.52, points[2 * 35]);
                using (var edited = live.GetMesh())
                using (var editedPattern = Pattern.FromPoints(points))
                using (var fromScratch = Discretisation.Create(dome, editedPattern))
                    TestData.AssertSameMesh(fromScratch, edited);
            }
        }

        [Test]
        public void ReplaceSurfaceKeepsThePatternAndRecomputes()
        {
            using (var dome = TestData.Dome())
            using (var higher = TestData.Dome(2.0))
            using (var pattern = Pattern.Grid(5, 5))
            using (var live = DiscreteSurface.Create(dome, pattern))
            {
                live.ReplaceSurface(higher);
                Assert.AreEqual(1, live.PendingEdits);
                live.Recompute();
                using (var mesh = live.GetMesh())
                using (var expected = Discretisation.Create(higher, pattern))
                    TestData.AssertSameMesh(expected, mesh);
            }
        }

        [Test]
        public void MeshSnapshotOutlivesItsDiscreteSurface()
        {
            Discretisation mesh;
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Grid(4, 4))
            using (var live = DiscreteSurface.Create(dome, pattern))
                mesh = live.GetMesh();
            using (mesh) Assert.AreEqual(16, mesh.FacetCount);
        }

        [Test]
        public void HandlesMayBeUsedFromSeveralThreads()
        {
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Hex(6, 6))
            using (var reference = Discretisation.Create(dome, pattern))
            using (var live = DiscreteSurface.Create(dome, pattern))
            {
                var expected = reference.GetVertexArray();
                var tasks = Enumerable.Range(0, 4).Select(k => Task.Run(() =>
                {
                    for (int i = 0; i < 10; i++)
                    {
                        using (var mesh = Discretisation.Create(dome, pattern))
                            CollectionAssert.AreEqual(expected, mesh.GetVertexArray());
                        live.MovePoint(k, 0.1 + 0.01 * i, 0.05 + 0.2 * k);
                        var e = Assert.Throws<TpiException>(() => live.MovePoint(1000 + k, 0.5, 0.5));
                        StringAssert.Contains((1000 + k).ToString(), e.NativeMessage, "last error is per thread");
                    }
                })).ToArray();
                Task.WaitAll(tasks);
                live.Recompute();
                Assert.AreEqual(0, live.PendingEdits);
            }
        }
    }
}
