using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    [TestFixture]
    public class SurfaceTrimTests
    {
        static readonly Domain Unit = new Domain(0, 1, 0, 1);

        // A loop as a host samples it: clockwise, with the closing point repeated.
        static double[] Disc(int n, double r, bool clockwise, bool closed)
        {
            var flat = new List<double>();
            for (int k = 0; k < n; k++)
            {
                double a = 2 * Math.PI * k / n * (clockwise ? -1 : 1);
                flat.Add(0.5 + r * Math.Cos(a)); flat.Add(0.5 + r * Math.Sin(a));
            }
            if (closed) { flat.Add(flat[0]); flat.Add(flat[1]); }
            return flat.ToArray();
        }

        static bool InPolygon(IReadOnlyList<double> loop, double u, double v)
        {
            bool inside = false;
            int n = loop.Count / 2;
            for (int i = 0, j = n - 1; i < n; j = i++)
            {
                double ui = loop[2 * i], vi = loop[2 * i + 1], uj = loop[2 * j], vj = loop[2 * j + 1];
                if ((vi > v) != (vj > v) && u < (uj - ui) * (v - vi) / (vj - vi) + ui) inside = !inside;
            }
            return inside;
        }

        [Test]
        public void FromLoopsOrientsAndDropsTheClosingPoint()
        {
            var trim = SurfaceTrim.FromLoops(Disc(20, 0.4, true, true), new[] { (IList<double>)Disc(8, 0.1, false, true) }, Unit, 1e-9);
            Assert.IsNotNull(trim);
            Assert.AreEqual(40, trim.Outer.Count, "closing point dropped");
            Assert.Greater(SurfaceTrim.SignedArea(trim.Outer.ToArray()), 0, "outer counter-clockwise");
            Assert.AreEqual(1, trim.Holes.Count);
            Assert.AreEqual(16, trim.Holes[0].Count);
            Assert.Less(SurfaceTrim.SignedArea(trim.Holes[0].ToArray()), 0, "hole clockwise");
        }

        [Test]
        public void FromLoopsClampsToTheDomainAndDropsRepeatedPoints()
        {
            // A corner a hair outside the domain, a point repeated at a curve join.
            var loop = new double[] { -1e-12, 0.2, 0.5, 0.2, 0.5, 0.2 + 1e-13, 0.5, 0.8, 0.2, 0.8, -1e-12, 0.2 };
            var trim = SurfaceTrim.FromLoops(loop, null, Unit, 1e-9);
            CollectionAssert.AreEqual(new[] { 0.0, 0.2, 0.5, 0.2, 0.5, 0.8, 0.2, 0.8 }, trim.Outer.ToArray());
            using (var dome = LogicData.Dome().WithTrim(trim).CreateNative()) Assert.IsNotNull(dome);
        }

        [Test]
        public void TheWholeDomainRectangleIsNoTrim()
        {
            var d = new Domain(2, 5, -1, 1);
            // Clockwise, closed, with a midpoint on an edge: still the whole rectangle.
            var rect = new double[] { 2, -1, 2, 1, 5, 1, 5, -1, 3.5, -1, 2, -1 };
            Assert.IsNull(SurfaceTrim.FromLoops(rect, null, d, 1e-6));
            // With a hole it is a trim.
            var hole = new double[] { 3, 0, 3.5, 0.5, 4, 0 };
            Assert.IsNotNull(SurfaceTrim.FromLoops(rect, new[] { (IList<double>)hole }, d, 1e-6));
            // Corners cut off (every point on the boundary): a trim.
            var cut = new double[] { 2, 0, 3, -1, 5, -1, 5, 1, 2, 1 };
            Assert.IsNotNull(SurfaceTrim.FromLoops(cut, null, d, 1e-6));
            // A smaller rectangle: a trim.
            Assert.IsNotNull(SurfaceTrim.FromLoops(new double[] { 2, -1, 4, -1, 4, 1, 2, 1 }, null, d, 1e-6));
        }

        [Test]
        public void ATrimmedSpecDiscretisesOnlyThePointsInside()
        {
            var trim = SurfaceTrim.FromLoops(Disc(40, 0.4, true, true), null, Unit, 1e-9);
            var spec = LogicData.Dome().WithTrim(trim);
            Assert.AreNotEqual(LogicData.Dome(), spec);
            Assert.AreEqual(LogicData.Dome().WithTrim(trim), spec);
            var points = LogicData.Hex(9, 9);
            int inside = points.Count(p => InPolygon(trim.Outer, p.S, p.T));
            Assert.Less(inside, points.Length);
            var output = ComponentSolvers.Discretise(new DiscretiseInput { Surface = spec, Points = points });
            Assert.AreEqual(0, output.Errors.Count, string.Join("; ", output.Errors));
            Assert.AreEqual(inside, output.Polylines.Length);

            var moved = spec.Transformed(new double[] { 1, 0, 0, 3, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 });
            Assert.AreEqual(trim, moved.Trim, "a transform keeps the trim");
            Assert.AreEqual(trim, ((NurbsSurfaceSpec)spec).WithControlPoint(1, 1, new Vec3(0, 0, 1)).Trim);

            // A bad trim reaches the user as the library's message.
            var bad = LogicData.Dome().WithTrim(new SurfaceTrim(Disc(12, 0.4, true, false)));
            var e = Assert.Throws<TpiException>(() => bad.CreateNative());
            StringAssert.Contains("trim.outer", e.Message);
        }

        [Test]
        public void LiveEditingRefusesATrimSoNoTrimmedDocumentIsEverStored()
        {
            // The discrete surface (the only spec that is persisted, UserDataFormat) is made
            // through DiscreteSurfaceState, which the library refuses for a trimmed surface:
            // a trimmed face is reported, never panelled untrimmed or stored without its trim.
            var trim = SurfaceTrim.FromLoops(Disc(40, 0.4, false, false), null, Unit, 1e-9);
            var e = Assert.Throws<TpiException>(() => new DiscreteSurfaceState(LogicData.Dome().WithTrim(trim), LogicData.Hex(6, 6)));
            Assert.AreEqual(Status.InvalidArgument, e.Status);
            StringAssert.Contains("trim", e.Message);
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(6, 6)))
            {
                // A source that became trimmed: the follow step's recompute says why it cannot.
                state.ReplaceSurface(LogicData.Dome().WithTrim(trim));
                string error;
                Assert.IsFalse(state.TryRecompute(out error));
                StringAssert.Contains("trim", error);
            }
        }
    }
}
