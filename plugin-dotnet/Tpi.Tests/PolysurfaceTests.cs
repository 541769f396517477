using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>
    /// Polysurfaces: the saddle z = 0.4 x^2 - 0.4 y^2 split at x = 0 into two faces and joined
    /// again (Surface.Join, PolysurfaceSpec) gives the single face's mesh; faces that cannot be
    /// joined, or trimmed faces of a Brep, are refused with a reason naming the face.
    /// </summary>
    [TestFixture]
    public class PolysurfaceTests
    {
        static AnalyticSurfaceSpec Saddle(double x0, double x1)
        {
            return new AnalyticSurfaceSpec(AnalyticKind.HyperbolicParaboloid, 0.4, 0.4, x0, x1, -1, 1);
        }

        /// <summary>Facet by facet, vertex by vertex: the same loops at the same points.</summary>
        static void AssertSameFacets(Discretisation expected, Discretisation actual, double tolerance)
        {
            Assert.AreEqual(expected.FacetCount, actual.FacetCount, "facets");
            CollectionAssert.AreEqual(expected.FacetSizes, actual.FacetSizes, "facet sizes");
            double worst = 0;
            for (int f = 0; f < expected.FacetCount; f++)
            {
                var a = expected.GetFacet(f);
                var b = actual.GetFacet(f);
                for (int k = 0; k < a.Length; k++)
                {
                    var p = expected.Vertices[a[k]];
                    var q = actual.Vertices[b[k]];
                    double d = Math.Sqrt((p.X - q.X) * (p.X - q.X) + (p.Y - q.Y) * (p.Y - q.Y) + (p.Z - q.Z) * (p.Z - q.Z));
                    worst = Math.Max(worst, d);
                }
            }
            Assert.LessOrEqual(worst, tolerance, "largest vertex distance");
        }

        [Test]
        public void TwoSaddleHalvesJoinedGiveTheSingleFaceMesh()
        {
            using (var single = Surface.HyperbolicParaboloid(0.4, 0.4, -1, 1, -1, 1))
            using (var pattern = Pattern.Hex(12, 14))
            using (var expected = Discretisation.Create(single, pattern))
            {
                Surface joined;
                // Right half first: the layout comes from the geometry.
                using (var right = Surface.HyperbolicParaboloid(0.4, 0.4, 0, 1, -1, 1))
                using (var left = Surface.HyperbolicParaboloid(0.4, 0.4, -1, 0, -1, 1))
                    joined = Surface.Join(new[] { right, left });
                // The faces are disposed: the polysurface holds its own copies.
                using (joined)
                using (var actual = Discretisation.Create(joined, pattern))
                {
                    Assert.AreEqual(12 * 14, expected.FacetCount);
                    AssertSameFacets(expected, actual, 1e-9);
                    var d = joined.Domain;
                    Assert.AreEqual(0.0, d.UMin);
                    Assert.AreEqual(0.0, d.VMin);
                    // Halfway across the domain is the seam x = 0 (the halves are equally long).
                    var p = joined.Evaluate(0.5 * d.UMax, 0.25 * d.VMax).Point;
                    Assert.AreEqual(0.0, p.X, 1e-12);
                    Assert.AreEqual(-0.5, p.Y, 1e-12);
                    Assert.AreEqual(-0.4 * 0.25, p.Z, 1e-12);
                }
            }
        }

        [Test]
        public void FacesThatCannotBeJoinedAreNamed()
        {
            using (var left = Surface.HyperbolicParaboloid(0.4, 0.4, -1, 0, -1, 1))
            using (var apart = Surface.HyperbolicParaboloid(0.4, 0.4, 2, 3, -1, 1))
            {
                var e = Assert.Throws<TpiException>(() => Surface.Join(new[] { left, apart }));
                Assert.AreEqual(Status.InvalidArgument, e.Status);
                StringAssert.StartsWith("faces[1]: shares no whole side", e.NativeMessage);
                Assert.AreEqual("tpi_surface_new_polysurface", e.Function);

                e = Assert.Throws<TpiException>(() => Surface.Join(new[] { left, null }));
                Assert.AreEqual(Status.NullPointer, e.Status);
                Assert.AreEqual("faces[1] is NULL", e.NativeMessage);

                e = Assert.Throws<TpiException>(() => Surface.Join(new Surface[0]));
                Assert.AreEqual(Status.InvalidArgument, e.Status);
                StringAssert.StartsWith("faces: ", e.NativeMessage);

                e = Assert.Throws<TpiException>(() => Surface.Join(null));
                Assert.AreEqual(Status.InvalidArgument, e.Status);

                var gone = Surface.HyperbolicParaboloid(0.4, 0.4, 0, 1, -1, 1);
                gone.Dispose();
                Assert.Throws<ObjectDisposedException>(() => Surface.Join(new[] { left, gone }));
                // A failed join leaves the faces usable.
                Assert.AreEqual(-1.0, left.Domain.UMin);
            }
        }

        [Test]
        public void BrepFacesBecomeOnePolysurfaceOrAReason()
        {
            string error;
            var one = Saddle(-1, 1);
            Assert.AreSame(one, PolysurfaceSpec.FromFaces(new SurfaceSpec[] { one }, out error), "one face is that face");
            Assert.IsNull(error);

            var spec = PolysurfaceSpec.FromFaces(new SurfaceSpec[] { Saddle(0, 1), Saddle(-1, 0) }, out error);
            Assert.IsNull(error);
            Assert.IsInstanceOf<PolysurfaceSpec>(spec);
            Assert.AreEqual(2, ((PolysurfaceSpec)spec).Faces.Count);
            using (var pattern = Pattern.Grid(9, 9))
            using (var single = one.CreateNative())
            using (var joined = spec.CreateNative())
            using (var expected = Discretisation.Create(single, pattern))
            using (var actual = Discretisation.Create(joined, pattern))
                AssertSameFacets(expected, actual, 1e-9);

            // A face trimmed beyond its natural boundary: refused with a reason, never dropped.
            var trim = new SurfaceTrim(new double[] { 0.1, -0.9, 0.9, -0.9, 0.9, 0.9, 0.1, 0.9 });
            var trimmed = Saddle(0, 1).WithTrim(trim);
            using (var alone = trimmed.CreateNative()) Assert.IsNotNull(alone, "the trim is valid on its own");
            Assert.IsNull(PolysurfaceSpec.FromFaces(new SurfaceSpec[] { Saddle(-1, 0), trimmed }, out error));
            StringAssert.Contains("face 1 of the 2-face polysurface is trimmed", error);
            StringAssert.Contains("trimmed faces are not supported in a polysurface yet", error);
            // A face alone keeps its trim.
            Assert.AreSame(trimmed, PolysurfaceSpec.FromFaces(new SurfaceSpec[] { trimmed }, out error));

            Assert.IsNull(PolysurfaceSpec.FromFaces(new SurfaceSpec[] { Saddle(-1, 0), null }, out error));
            StringAssert.Contains("face 1", error);
            Assert.IsNull(PolysurfaceSpec.FromFaces(new SurfaceSpec[0], out error));
            Assert.IsNotNull(error);

            // Faces apart: the library's reason, from CreateNative.
            var apart = new PolysurfaceSpec(new SurfaceSpec[] { Saddle(-1, 0), Saddle(2, 3) });
            var e = Assert.Throws<TpiException>(() => apart.CreateNative());
            StringAssert.StartsWith("faces[1]: ", e.NativeMessage);
        }

        [Test]
        public void APolysurfaceDocumentRoundTripsAndFollowsTheWholeObject()
        {
            var faces = new SurfaceSpec[] { Saddle(0, 1), Saddle(-1, 0) };
            var points = new List<PatternPoint>();
            for (int i = 0; i < 6; i++)
                for (int j = 0; j < 5; j++) points.Add(new PatternPoint((i + 0.5) / 6, (j + 0.5) / 5));
            var document = new DiscreteSurfaceDocument
            {
                Surface = new PolysurfaceSpec(faces),
                Points = points,
                Options = DiscretisationOptions.Default(),
                SourceSurfaceId = Guid.NewGuid(),
            };
            var bytes = UserDataFormat.Write(document);
            Assert.AreEqual(3, bytes[4] | bytes[5] << 8, "polysurfaces are format 3");
            var back = UserDataFormat.Read(bytes);
            Assert.IsTrue(back.SameAs(document));
            Assert.IsInstanceOf<PolysurfaceSpec>(back.Surface);
            using (var fromBack = new DiscreteSurfaceState(back))
            using (var single = new DiscreteSurfaceState(Saddle(-1, 1), points))
            {
                var a = single.Mesh;
                var b = fromBack.Mesh;
                Assert.AreEqual(30, b.FacetCount);
                CollectionAssert.AreEqual(a.FacetSizes, b.FacetSizes);
                double worst = 0;
                for (int f = 0; f < a.FacetCount; f++)
                {
                    var la = a.Facet(f);
                    var lb = b.Facet(f);
                    for (int k = 0; k < la.Length; k++)
                    {
                        var p = a.Vertices[la[k]];
                        var q = b.Vertices[lb[k]];
                        worst = Math.Max(worst, Math.Abs(p.X - q.X) + Math.Abs(p.Y - q.Y) + Math.Abs(p.Z - q.Z));
                    }
                }
                Assert.LessOrEqual(worst, 1e-9, "the joined halves are the saddle");
            }

            // Kind 3 under a format 2 header is not a format 2 surface.
            var old = (byte[])bytes.Clone();
            old[4] = 2;
            var error = Assert.Throws<FormatException>(() => UserDataFormat.Read(Fixtures.Reseal(old)));
            StringAssert.Contains("unknown surface kind 3", error.Message);

            // The watcher follows the whole object, whatever its faces now.
            var follow = SourceFollow.Decide(document, SourceShape.Polysurface, 3);
            Assert.IsTrue(follow.Follow && follow.WholeObject);
            Assert.AreEqual(-1, follow.FaceIndex);
            Assert.IsTrue(SourceFollow.Decide(document, SourceShape.Surface, 1).WholeObject);
            Assert.IsFalse(SourceFollow.Decide(document, SourceShape.Missing, 0).Follow);
            Assert.IsFalse(SourceFollow.Decide(document, SourceShape.Other, 0).Follow);
            // A single-surface document still refuses a polysurface as ambiguous.
            var plain = document.Clone();
            plain.Surface = Saddle(-1, 1);
            var refused = SourceFollow.Decide(plain, SourceShape.Polysurface, 2);
            Assert.IsFalse(refused.Follow || refused.WholeObject);
        }
    }
}
