using System;
using System.Linq;
using NUnit.Framework;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>Every failure of the library arrives as a TpiException with its status and message.</summary>
    [TestFixture]
    public class NativeErrorTests
    {
        static TpiException Fails(Status expected, TestDelegate call, string messagePart)
        {
            var e = Assert.Throws<TpiException>(call);
            Assert.AreEqual(expected, e.Status, e.Message);
            Assert.IsNotNullOrEmpty(e.NativeMessage, "the native message is carried");
            StringAssert.Contains(messagePart, e.NativeMessage);
            StringAssert.Contains(e.NativeMessage, e.Message);
            StringAssert.Contains(TpiLibrary.StatusName(expected), e.Message);
            StringAssert.StartsWith("tpi_", e.Function);
            return e;
        }

        [Test]
        public void NullHandlesReachTheLibraryAsNull()
        {
            using (var pattern = Pattern.Grid(4, 4))
            using (var dome = TestData.Dome())
            using (var live = DiscreteSurface.Create(dome, pattern))
            {
                Fails(Status.NullPointer, () => Discretisation.Create(null, pattern), "surface");
                Fails(Status.NullPointer, () => Discretisation.Create(dome, null), "pattern");
                Fails(Status.NullPointer, () => DiscreteSurface.Create(null, pattern), "surface");
                Fails(Status.NullPointer, () => live.ReplaceSurface(null), "surface");
                Fails(Status.NullPointer, () => Pattern.FromSpec(null), "spec");
                Assert.AreEqual(0, live.PendingEdits, "a failed edit changes nothing");
            }
        }

        [Test]
        public void InvalidNurbsNamesTheArgument()
        {
            var badKnots = new double[] { 0, 0, 0, 1, 1 };
            var e = Fails(Status.InvalidNurbs,
                () => Surface.FromNurbs(3, 3, 4, 4, badKnots, TestData.BezierKnots, TestData.DomePoints()), "knots_u has 5 knots");
            StringAssert.Contains("Rhino convention", e.NativeMessage);
            Fails(Status.InvalidNurbs, () => Surface.FromNurbs(0, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, TestData.DomePoints()), "degree");
            Fails(Status.InvalidNurbs, () => Surface.FromNurbs(3, 3, 4, 4, null, TestData.BezierKnots, TestData.DomePoints()), "knots_u");
            var negativeWeights = Enumerable.Repeat(-1.0, 16).ToArray();
            Fails(Status.InvalidNurbs, () => Surface.FromNurbs(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, TestData.DomePoints(), negativeWeights), "weight");
            Fails(Status.InvalidArgument, () => Surface.FromNurbs(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, new double[47]), "points");
            Fails(Status.InvalidNurbs, () => Surface.FromNurbs(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, new double[45]), "points");
        }

        [Test]
        public void NaNIsRejectedWithTheNativeMessage()
        {
            var points = TestData.DomePoints();
            points[7] = double.NaN;
            Fails(Status.NonFinite, () => Surface.FromNurbs(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, points), "NaN");
            Fails(Status.NonFinite, () => Surface.EllipticParaboloid(double.NaN, 1, -1, 1, -1, 1), "");
            Fails(Status.NonFinite, () => Pattern.FromPoints(new[] { 0.1, 0.1, double.NaN, 0.5, 0.9, 0.9 }), "NaN");
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Grid(4, 4))
            using (var live = DiscreteSurface.Create(dome, pattern))
            {
                Fails(Status.NonFinite, () => dome.Evaluate(double.NaN, 0.5), "");
                Fails(Status.NonFinite, () => live.MovePoint(2, double.NaN, 0.5), "");
                Fails(Status.NonFinite, () => live.AddPoint(0.5, double.PositiveInfinity), "");
                var options = DiscretisationOptions.Default();
                options.FarVertexFactor = double.NaN;
                var e = Assert.Throws<TpiException>(() => Discretisation.Create(dome, pattern, options));
                Assert.IsTrue(e.Status == Status.InvalidArgument || e.Status == Status.NonFinite, e.Message);
                StringAssert.Contains("far_vertex_factor", e.NativeMessage);
                Assert.AreEqual(0, live.PendingEdits);
            }
        }

        [Test]
        public void IndexOutOfRangeNamesTheIndex()
        {
            using (var dome = TestData.Dome())
            using (var pattern = Pattern.Grid(4, 4))
            using (var live = DiscreteSurface.Create(dome, pattern))
            {
                var e = Fails(Status.IndexOutOfRange, () => live.MovePoint(47, 0.5, 0.5), "47");
                StringAssert.Contains("16", e.NativeMessage);
                Fails(Status.IndexOutOfRange, () => live.RemovePoint(16), "16");
                Fails(Status.IndexOutOfRange, () => live.RemovePoint(-1), "out of range");
                Assert.AreEqual(0, live.PendingEdits);
                Assert.AreEqual(16, live.PointCount);
            }
        }

        [Test]
        public void PatternAndDomainErrors()
        {
            Fails(Status.InvalidPattern, () => Pattern.FromPoints(new[] { 0.1, 0.1, 1.5, 0.5, 0.9, 0.9 }), "1");
            Fails(Status.InvalidPattern, () => Pattern.FromPoints(new[] { 0.1, 0.1, 0.1, 0.1, 0.9, 0.9 }), "");
            Fails(Status.InvalidArgument, () => Pattern.FromPoints(new[] { 0.1, 0.1, 0.5 }), "");
            Fails(Status.InvalidPattern, () => Pattern.Grid(0, 4), "");
            Fails(Status.InvalidPattern, () => Pattern.FromSpec("hexagons please"), "");
            using (var dome = TestData.Dome())
            {
                Fails(Status.OutOfDomain, () => dome.Evaluate(1.5, 0.5), "");
                using (var two = Pattern.FromPoints(new[] { 0.1, 0.1, 0.9, 0.9 }))
                    Fails(Status.InvalidPattern, () => Discretisation.Create(dome, two), "");
                using (var pattern = Pattern.Grid(4, 4))
                using (var live = DiscreteSurface.Create(dome, pattern))
                {
                    Fails(Status.InvalidPattern, () => live.MovePoint(0, 1.2, 0.5), "");
                    // A duplicate passes the edit and fails the recompute, which keeps the old mesh.
                    var p = live.Points[1];
                    live.MovePoint(0, p.S, p.T);
                    Fails(Status.InvalidPattern, () => live.Recompute(), "");
                    Assert.AreEqual(1, live.PendingEdits, "the edit stays pending");
                    using (var mesh = live.GetMesh()) Assert.AreEqual(16, mesh.FacetCount, "the previous mesh stays current");
                }
            }
            using (var plane = Surface.Plane(0.1, 0.2, 0, -1, 1, -1, 1))
            using (var pattern = Pattern.Grid(4, 4))
            using (var mesh = Discretisation.Create(plane, pattern))
                Assert.AreEqual(16, mesh.FacetCount, "a plane gives its Voronoi cells");
            Fails(Status.InvalidArgument, () => Surface.SphereCap(1, -2, 2, -2, 2), "");
        }

        [Test]
        public void LastErrorIsEmptyAfterSuccess()
        {
            Assert.Throws<TpiException>(() => Pattern.Grid(0, 0));
            Assert.IsNotEmpty(TpiLibrary.LastErrorMessage());
            Assert.AreEqual(TpiLibrary.LastErrorMessage(), TpiLibrary.LastErrorMessage(), "reading does not change it");
            using (Pattern.Grid(2, 2)) { }
            Assert.AreEqual("", TpiLibrary.LastErrorMessage());
        }

        [Test]
        public void DisposedObjectsThrowObjectDisposedException()
        {
            var dome = TestData.Dome();
            dome.Dispose();
            dome.Dispose();
            Assert.IsTrue(dome.IsDisposed);
            Assert.Throws<ObjectDisposedException>(() => { var unused = dome.Domain; });
            using (var pattern = Pattern.Grid(3, 3))
                Assert.Throws<ObjectDisposedException>(() => Discretisation.Create(dome, pattern));
        }
    }
}
