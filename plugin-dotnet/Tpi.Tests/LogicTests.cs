using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    static class LogicData
    {
        public static NurbsSurfaceSpec Dome(double height = 1.0, double[] weights = null)
        {
            return new NurbsSurfaceSpec(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, TestData.DomePoints(height), weights);
        }

        public static PatternPoint[] Hex(int nu, int nv)
        {
            using (var p = Pattern.Hex(nu, nv)) return p.Points.ToArray();
        }
    }

    [TestFixture]
    public class SurfaceSpecTests
    {
        [Test]
        public void NurbsSpecMakesTheSameSurface()
        {
            using (var direct = TestData.Dome())
            using (var fromSpec = LogicData.Dome().CreateNative())
                Assert.AreEqual(direct.Evaluate(0.3, 0.7).Point, fromSpec.Evaluate(0.3, 0.7).Point);
        }

        [Test]
        public void AffineTransformMovesTheSurface()
        {
            // Rotation by 90 degrees about z, then a translation by (1, 2, 3).
            var m = new double[] { 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1 };
            var moved = LogicData.Dome().Transformed(m);
            using (var a = LogicData.Dome().CreateNative())
            using (var b = moved.CreateNative())
            {
                var p = a.Evaluate(0.3, 0.7).Point;
                var q = b.Evaluate(0.3, 0.7).Point;
                Assert.AreEqual(-p.Y + 1, q.X, 1e-12);
                Assert.AreEqual(p.X + 2, q.Y, 1e-12);
                Assert.AreEqual(p.Z + 3, q.Z, 1e-12);
            }
            Assert.IsFalse(((NurbsSurfaceSpec)moved).IsRational, "affine transforms keep a surface non-rational");
        }

        [Test]
        public void ProjectiveTransformKeepsTheHomogeneousPoints()
        {
            // x' = x / (1 + 0.1 z): the image of each surface point is the image of the original.
            var m = new double[] { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0.1, 1 };
            var moved = (NurbsSurfaceSpec)LogicData.Dome().Transformed(m);
            Assert.IsTrue(moved.IsRational);
            using (var a = LogicData.Dome().CreateNative())
            using (var b = moved.CreateNative())
            {
                var p = a.Evaluate(0.4, 0.2).Point;
                var q = b.Evaluate(0.4, 0.2).Point;
                double w = 1 + 0.1 * p.Z;
                Assert.AreEqual(p.X / w, q.X, 1e-12);
                Assert.AreEqual(p.Z / w, q.Z, 1e-12);
            }
        }

        [Test]
        public void AnalyticSpecs()
        {
            var spec = new AnalyticSurfaceSpec(AnalyticKind.EllipticParaboloid, 1, 1, -1, 1, -1, 1);
            using (var s = spec.CreateNative()) Assert.AreEqual(2.0, s.Evaluate(1, 1).Point.Z, 1e-12);
            Assert.Throws<ArgumentException>(() => new AnalyticSurfaceSpec(AnalyticKind.SphereCap, 1, 2));
            Assert.Throws<NotSupportedException>(() => spec.Transformed(new double[16]));
            foreach (AnalyticKind kind in Enum.GetValues(typeof(AnalyticKind)))
                Assert.Greater(AnalyticSurfaceSpec.ParameterCount(kind), 0);
            var bad = new AnalyticSurfaceSpec(AnalyticKind.SphereCap, 1, -2, 2, -2, 2);
            var e = Assert.Throws<TpiException>(() => bad.CreateNative());
            Assert.AreEqual(Status.InvalidArgument, e.Status);
        }

        [Test]
        public void EqualityAndControlPointEdits()
        {
            Assert.AreEqual(LogicData.Dome(), LogicData.Dome());
            var edited = LogicData.Dome().WithControlPoint(1, 2, new Vec3(0, 0, 5));
            Assert.AreNotEqual(LogicData.Dome(), edited);
            Assert.AreEqual(new Vec3(0, 0, 5), edited.ControlPoint(1, 2));
            Assert.AreNotEqual(LogicData.Dome(), LogicData.Dome(1.0, Enumerable.Repeat(1.0, 16).ToArray()));
        }
    }

    [TestFixture]
    public class DiscreteSurfaceStateTests
    {
        static MeshData FromScratch(SurfaceSpec surface, IEnumerable<PatternPoint> points)
        {
            using (var s = surface.CreateNative())
            using (var p = Pattern.FromPoints(points))
            using (var m = Discretisation.Create(s, p))
                return MeshData.From(m);
        }

        [Test]
        public void CreateEditRecompute()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(6, 6)))
            {
                Assert.AreEqual(36, state.Mesh.FacetCount);
                Assert.IsTrue(state.Mesh.SameMesh(FromScratch(LogicData.Dome(), LogicData.Hex(6, 6))));
                state.MovePoint(4, 0.4, 0.1);
                Assert.AreEqual(37, state.AddPoint(0.5, 0.52) + 1);
                state.RemovePoint(10);
                Assert.AreEqual(3, state.PendingEdits);
                var before = state.Mesh;
                var after = state.Recompute();
                Assert.AreEqual(0, state.PendingEdits);
                Assert.AreNotSame(before, after);
                Assert.AreEqual(36, after.FacetCount);
                Assert.IsTrue(after.SameMesh(FromScratch(LogicData.Dome(), state.Points)), "same as a discretisation from scratch");
            }
        }

        [Test]
        public void RejectedEditsChangeNothingAndCarryTheNativeMessage()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(4, 4)))
            {
                var e = Assert.Throws<TpiException>(() => state.MovePoint(99, 0.5, 0.5));
                Assert.AreEqual(Status.IndexOutOfRange, e.Status);
                StringAssert.Contains("99", e.NativeMessage);
                Assert.Throws<TpiException>(() => state.AddPoint(double.NaN, 0.5));
                Assert.Throws<TpiException>(() => state.RemovePoint(16));
                var badSurface = new NurbsSurfaceSpec(3, 3, 4, 4, new double[] { 0, 0, 1, 1 }, TestData.BezierKnots, TestData.DomePoints());
                e = Assert.Throws<TpiException>(() => state.ReplaceSurface(badSurface));
                Assert.AreEqual(Status.InvalidNurbs, e.Status);
                Assert.AreEqual(16, state.Points.Count);
                Assert.AreEqual(0, state.PendingEdits);
                Assert.IsFalse(state.CanUndo);
                Assert.AreEqual(LogicData.Dome(), state.Surface);
            }
        }

        [Test]
        public void FailedRecomputeKeepsThePreviousMesh()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(4, 4)))
            {
                var mesh = state.Mesh;
                var p1 = state.Points[1];
                state.MovePoint(0, p1.S, p1.T);
                string error;
                Assert.IsFalse(state.TryRecompute(out error));
                Assert.IsNotNullOrEmpty(error);
                Assert.AreSame(mesh, state.Mesh);
                Assert.AreEqual(1, state.PendingEdits);
                Assert.IsTrue(state.Undo());
                Assert.IsTrue(state.TryRecompute(out error), error);
                Assert.IsTrue(state.Mesh.SameMesh(mesh));
            }
        }

        [Test]
        public void UndoAndRedoEveryKindOfEdit()
        {
            var original = LogicData.Hex(5, 5);
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), original))
            {
                var first = state.Mesh;
                state.MovePoint(3, 0.33, 0.44);
                state.RemovePoint(7);          // from the middle: undo must put it back at 7
                state.AddPoint(0.51, 0.49);
                state.ReplaceSurface(LogicData.Dome(1.5));
                state.Recompute();
                var edited = state.Points.ToArray();
                var editedMesh = state.Mesh;
                while (state.Undo()) { }
                CollectionAssert.AreEqual(original, state.Points.ToArray());
                Assert.AreEqual(LogicData.Dome(), state.Surface);
                state.Recompute();
                Assert.IsTrue(state.Mesh.SameMesh(first), "all undone: the first mesh again");
                while (state.Redo()) { }
                CollectionAssert.AreEqual(edited, state.Points.ToArray());
                state.Recompute();
                Assert.IsTrue(state.Mesh.SameMesh(editedMesh), "all redone: the edited mesh again");
            }
        }

        [Test]
        public void CompoundEditsUndoAsOne()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(4, 4)))
            {
                var p = state.Points;
                state.Apply(new CompoundEdit(new EditRecord[]
                {
                    new MovePointEdit(0, p[0], new PatternPoint(0.05, 0.05)),
                    new MovePointEdit(5, p[5], new PatternPoint(0.45, 0.35)),
                }));
                Assert.AreEqual(new PatternPoint(0.45, 0.35), state.Points[5]);
                Assert.IsTrue(state.Undo());
                CollectionAssert.AreEqual(p.ToArray(), state.Points.ToArray());
                Assert.IsFalse(state.CanUndo);
            }
        }
    }

    [TestFixture]
    public class UserDataFormatTests
    {
        [Test]
        public void RoundTripGivesTheSameMesh()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(6, 6)))
            {
                state.MovePoint(2, 0.2, 0.15);
                state.AddPoint(0.55, 0.45);
                state.Recompute();
                var bytes = state.ToBytes();
                using (var back = DiscreteSurfaceState.FromBytes(bytes))
                {
                    Assert.IsTrue(back.Document.SameAs(state.Document));
                    Assert.IsTrue(back.Mesh.SameMesh(state.Mesh), "same mesh after the round trip");
                    CollectionAssert.AreEqual(bytes, back.ToBytes(), "writing again gives the same bytes");
                }
            }
        }

        [Test]
        public void EverythingStoredComesBack()
        {
            var options = DiscretisationOptions.Default();
            options.EnvelopeRepair = false;
            options.FarVertexFactor = 6.5;
            var document = new DiscreteSurfaceDocument
            {
                Surface = LogicData.Dome(1.2, Enumerable.Range(0, 16).Select(i => 1 + 0.01 * i).ToArray()),
                Points = LogicData.Hex(3, 3).ToList(),
                Options = options,
                Generator = "hex:3x3 ✓",
                SourceSurfaceId = Guid.NewGuid(),
            };
            var back = UserDataFormat.Read(UserDataFormat.Write(document));
            Assert.IsTrue(back.SameAs(document));
            var analytic = new DiscreteSurfaceDocument
            {
                Surface = new AnalyticSurfaceSpec(AnalyticKind.EggCrate, 0.3, -1, 1, -1, 1),
                Points = LogicData.Hex(3, 3).ToList(),
                Options = DiscretisationOptions.Default(),
            };
            Assert.IsTrue(UserDataFormat.Read(UserDataFormat.Write(analytic)).SameAs(analytic));
        }

        [Test]
        public void DamagedDataIsRejectedWithAReason()
        {
            var document = new DiscreteSurfaceDocument { Surface = LogicData.Dome(), Points = LogicData.Hex(3, 3).ToList(), Options = DiscretisationOptions.Default() };
            var bytes = UserDataFormat.Write(document);
            var flipped = (byte[])bytes.Clone();
            flipped[40] ^= 0x10;
            StringAssert.Contains("checksum", Assert.Throws<FormatException>(() => UserDataFormat.Read(flipped)).Message);
            StringAssert.Contains("truncated", Assert.Throws<FormatException>(() => UserDataFormat.Read(bytes.Take(8).ToArray())).Message);
            var wrong = (byte[])bytes.Clone();
            wrong[0] = (byte)'X';
            StringAssert.Contains("magic", Assert.Throws<FormatException>(() => UserDataFormat.Read(wrong)).Message);
            // A newer format version (with a valid checksum) names the reason.
            var newer = bytes.Take(bytes.Length - 4).ToArray();
            newer[4] = 99;
            var withCrc = newer.Concat(BitConverter.GetBytes(UserDataFormat.Crc32(newer, 0, newer.Length))).ToArray();
            StringAssert.Contains("newer", Assert.Throws<FormatException>(() => UserDataFormat.Read(withCrc)).Message);
            Assert.AreEqual(0xCBF43926u, UserDataFormat.Crc32(System.Text.Encoding.ASCII.GetBytes("123456789"), 0, 9), "CRC-32 check value");
        }
    }

    [TestFixture]
    public class GripMapTests
    {
        [Test]
        public void IdentityAddRemoveRenumbering()
        {
            var map = new GripMap(5);
            Assert.AreEqual(5, map.Count);
            Assert.AreEqual(3, map.PointOf(3));
            Assert.AreEqual(5, map.OnPointAdded(5));
            Assert.AreEqual(2, map.OnPointRemoved(2));
            Assert.AreEqual(5, map.Count);
            CollectionAssert.AreEqual(new[] { 0, 1, 2, 3, 4 }, map.PointsOf(Enumerable.Range(0, 5)), "points after 2 moved down");
            Assert.AreEqual(-1, map.GripOf(5));
            Assert.Throws<ArgumentOutOfRangeException>(() => map.PointOf(5));
            Assert.Throws<ArgumentException>(() => map.OnPointAdded(3));
        }

        [Test]
        public void SubsetOfPoints()
        {
            var map = new GripMap(new[] { 7, 2, 4, 4 });
            Assert.AreEqual(3, map.Count);
            CollectionAssert.AreEqual(new[] { 2, 4, 7 }, map.PointsOf(new[] { 0, 1, 2 }));
            Assert.AreEqual(-1, map.GripOf(3));
            Assert.AreEqual(-1, map.OnPointRemoved(3), "a point without a grip");
            CollectionAssert.AreEqual(new[] { 2, 3, 6 }, map.PointsOf(new[] { 0, 1, 2 }));
            Assert.AreEqual(1, map.OnPointInserted(3), "undo of the removal");
            CollectionAssert.AreEqual(new[] { 2, 3, 4, 7 }, map.PointsOf(new[] { 0, 1, 2, 3 }));
            Assert.AreEqual(4, map.OnPointAdded(8));
        }

        [Test]
        public void GripsFollowTheStateThroughEdits()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(4, 4)))
            {
                var map = new GripMap(state.Points.Count);
                var target = state.Points[9];
                state.RemovePoint(map.PointOf(3));
                map.OnPointRemoved(3);
                int grip = map.OnPointAdded(state.AddPoint(0.5, 0.5));
                Assert.AreEqual(state.Points.Count, map.Count);
                Assert.AreEqual(target, state.Points[map.PointOf(8)], "grip 8 shows former point 9");
                Assert.AreEqual(new PatternPoint(0.5, 0.5), state.Points[map.PointOf(grip)]);
            }
        }

        [Test]
        public void NearestGripWithinReach()
        {
            var grips = new[] { new Vec3(0, 0, 0), new Vec3(1, 0, 0), new Vec3(0, 1, 0) };
            Assert.AreEqual(1, GripMap.Nearest(grips, new Vec3(0.9, 0.1, 0), 0.5));
            Assert.AreEqual(-1, GripMap.Nearest(grips, new Vec3(5, 5, 5), 0.5));
        }
    }

    [TestFixture]
    public class ConversionTests
    {
        [Test]
        public void PolylinesAndNgonMeshOfADiscretisation()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(6, 6)))
            {
                var mesh = state.Mesh;
                var polylines = MeshConversion.FacetPolylines(mesh);
                Assert.AreEqual(mesh.FacetCount, polylines.Length);
                for (int f = 0; f < polylines.Length; f++)
                {
                    Assert.AreEqual(mesh.FacetSizes[f] + 1, polylines[f].Length);
                    Assert.AreEqual(polylines[f][0], polylines[f][polylines[f].Length - 1], "closed");
                }
                var ngon = MeshConversion.ToNgonMesh(mesh);
                Assert.AreEqual(mesh.FacetCount, ngon.Ngons.Length);
                Assert.AreEqual(mesh.FacetSizes.Sum(k => k - 2), ngon.TriangleCount);
                var areas = MeshConversion.FacetAreas(mesh);
                for (int f = 0; f < ngon.Ngons.Length; f++)
                {
                    CollectionAssert.AreEqual(mesh.Facet(f), ngon.Ngons[f].BoundaryVertices);
                    double sum = 0;
                    foreach (var t in ngon.Ngons[f].Faces)
                    {
                        var a = ngon.Vertices[ngon.Triangles[3 * t]];
                        var b = ngon.Vertices[ngon.Triangles[3 * t + 1]];
                        var c = ngon.Vertices[ngon.Triangles[3 * t + 2]];
                        var n = Vec3.Cross(b - a, c - a);
                        Assert.Greater(Vec3.Dot(n, mesh.Planes[f].Normal), -1e-12, "triangle oriented like its facet");
                        sum += 0.5 * n.Length;
                    }
                    Assert.AreEqual(areas[f], sum, 1e-9, "the triangles fill the facet exactly");
                }
                Assert.Less(MeshConversion.PlanarityErrors(mesh).Max(), 1e-12);
            }
        }

        [Test]
        public void EarClippingFillsANonConvexFacet()
        {
            // An L-shaped hexagon in the plane z = 0, counter-clockwise seen from +z.
            var v = new[] { new Vec3(0, 0, 0), new Vec3(2, 0, 0), new Vec3(2, 1, 0), new Vec3(1, 1, 0), new Vec3(1, 2, 0), new Vec3(0, 2, 0) };
            var plane = new FacetPlane { Point = new Vec3(0, 0, 0), Normal = new Vec3(0, 0, 1) };
            var mesh = MeshData.FromLoops(v, new[] { new[] { 0, 1, 2, 3, 4, 5 } }, new[] { plane });
            var ngon = MeshConversion.ToNgonMesh(mesh);
            Assert.AreEqual(4, ngon.TriangleCount);
            double area = 0;
            for (int t = 0; t < ngon.TriangleCount; t++)
            {
                var n = Vec3.Cross(v[ngon.Triangles[3 * t + 1]] - v[ngon.Triangles[3 * t]], v[ngon.Triangles[3 * t + 2]] - v[ngon.Triangles[3 * t]]);
                Assert.Greater(n.Z, 0, "counter-clockwise, no overlap");
                area += 0.5 * n.Z;
            }
            Assert.AreEqual(3.0, area, 1e-12, "a fan from vertex 0 would also give 3, but with a clockwise triangle");
        }

        [Test]
        public void NormalisingPickedParameters()
        {
            var domain = new Domain(2, 4, -1, 1);
            PatternPoint p;
            string error;
            Assert.IsTrue(InputValidation.TryNormalise(domain, 3, 0, out p, out error));
            Assert.AreEqual(new PatternPoint(0.5, 0.5), p);
            Assert.IsTrue(InputValidation.TryNormalise(domain, 4 + 1e-12, -1, out p, out error), "rounding is clamped");
            Assert.AreEqual(1.0, p.S);
            Assert.IsFalse(InputValidation.TryNormalise(domain, 5, 0, out p, out error));
            StringAssert.Contains("outside", error);
            Assert.IsFalse(InputValidation.TryNormalise(domain, double.NaN, 0, out p, out error));
            Assert.IsTrue(InputValidation.NurbsShapeLooksRight(4, 4, 48, 0, out error));
            Assert.IsFalse(InputValidation.NurbsShapeLooksRight(4, 4, 47, 0, out error));
        }
    }

    [TestFixture]
    public class ComponentSolverTests
    {
        [Test]
        public void RejectedInputStillGivesOneResultWithItsMessages()
        {
            // The task-capable component adds this as the iteration's task when its inputs are
            // unusable, so the results of later iterations keep their places.
            var rejected = ComponentSolvers.DiscretiseOrReject(null, new[] { "the surface has no NURBS form" }, new[] { "point 3 is off the surface" });
            Assert.IsFalse(rejected.Success);
            CollectionAssert.AreEqual(new[] { "the surface has no NURBS form" }, rejected.Errors);
            CollectionAssert.AreEqual(new[] { "point 3 is off the surface" }, rejected.Warnings);
            var warnedOnly = ComponentSolvers.DiscretiseOrReject(null, null, new[] { "give pattern points (P) or normalised uv (UV)" });
            Assert.IsFalse(warnedOnly.Success);
            Assert.IsEmpty(warnedOnly.Errors);

            var input = new DiscretiseInput { Surface = LogicData.Dome(), Points = LogicData.Hex(4, 4) };
            var solved = ComponentSolvers.DiscretiseOrReject(input, null, new[] { "point 3 was clamped" });
            Assert.IsTrue(solved.Success);
            Assert.AreEqual(16, solved.Mesh.FacetCount);
            Assert.AreEqual("point 3 was clamped", solved.Warnings[0], "input warnings come first");
            Assert.IsTrue(solved.Mesh.SameMesh(ComponentSolvers.Discretise(input).Mesh));
        }

        [Test]
        public void DiscretiseWithNormalisedPoints()
        {
            var output = ComponentSolvers.Discretise(new DiscretiseInput { Surface = LogicData.Dome(), Points = LogicData.Hex(6, 6) });
            Assert.IsTrue(output.Success, string.Join("; ", output.Errors));
            Assert.AreEqual(36, output.Polylines.Length);
            Assert.AreEqual(36, output.Planes.Length);
            Assert.AreEqual(36, output.NgonMesh.Ngons.Length);
            StringAssert.Contains("facet_count", output.QualityJson);
            Assert.IsEmpty(output.Errors);
        }

        [Test]
        public void DiscretiseWithPointsInTheSurfaceDomain()
        {
            var paraboloid = new AnalyticSurfaceSpec(AnalyticKind.EllipticParaboloid, 1, 1, -1, 1, -1, 1);
            var uv = LogicData.Hex(6, 6).Select(p => new PatternPoint(-1 + 2 * p.S, -1 + 2 * p.T)).ToList();
            var output = ComponentSolvers.Discretise(new DiscretiseInput { Surface = paraboloid, Points = uv, PointsInSurfaceDomain = true });
            Assert.IsTrue(output.Success, string.Join("; ", output.Errors));
            var expected = ComponentSolvers.Discretise(new DiscretiseInput { Surface = paraboloid, Points = LogicData.Hex(6, 6) });
            Assert.IsTrue(expected.Mesh.SameMesh(output.Mesh));
        }

        [Test]
        public void DiscretiseReportsTheLibrarysErrors()
        {
            var two = ComponentSolvers.Discretise(new DiscretiseInput { Surface = LogicData.Dome(), Points = new[] { new PatternPoint(0.1, 0.1), new PatternPoint(0.9, 0.9) } });
            Assert.IsFalse(two.Success);
            StringAssert.StartsWith("TPI_STATUS_INVALID_PATTERN: ", two.Errors.Single());
            var outside = ComponentSolvers.Discretise(new DiscretiseInput { Surface = LogicData.Dome(), Points = new[] { new PatternPoint(0.1, 0.1), new PatternPoint(1.5, 0.9), new PatternPoint(0.5, 0.5) } });
            StringAssert.StartsWith("point 1: ", outside.Errors.Single());
            var flat = ComponentSolvers.Discretise(new DiscretiseInput { Surface = new AnalyticSurfaceSpec(AnalyticKind.Plane, 0, 0, 0, -1, 1, -1, 1), Points = LogicData.Hex(4, 4) });
            // A plane is discretised (its facets are the Voronoi cells of their seeds).
            Assert.IsTrue(flat.Success, string.Join("; ", flat.Errors));
            Assert.AreEqual(16, flat.Mesh.FacetCount);
            Assert.AreEqual("no surface", ComponentSolvers.Discretise(new DiscretiseInput { Points = LogicData.Hex(3, 3) }).Errors.Single());
            var badNurbs = new NurbsSurfaceSpec(3, 3, 4, 4, new double[] { 0, 1 }, TestData.BezierKnots, TestData.DomePoints());
            StringAssert.Contains("knots_u", ComponentSolvers.Discretise(new DiscretiseInput { Surface = badNurbs, Points = LogicData.Hex(3, 3) }).Errors.Single());
        }

        [Test]
        public void PatternFromGeneratorOrSpec()
        {
            var hex = ComponentSolvers.Pattern(new PatternInput { Generator = new PatternGenerator { Kind = GeneratorKind.Hex, CountU = 5, CountV = 4 } });
            Assert.AreEqual(20, hex.Points.Length);
            Assert.AreEqual("hex:5x4", hex.Spec);
            var jitter = new PatternGenerator { Kind = GeneratorKind.Jitter, CountU = 4, CountV = 4, Amount = 0.25, Seed = 9 };
            var fromGenerator = ComponentSolvers.Pattern(new PatternInput { Generator = jitter });
            var fromSpec = ComponentSolvers.Pattern(new PatternInput { Spec = jitter.ToSpec() });
            CollectionAssert.AreEqual(fromGenerator.Points, fromSpec.Points, "ToSpec reproduces the generator: " + jitter.ToSpec());
            var poisson = new PatternGenerator { Kind = GeneratorKind.Poisson, Radius = 0.1, Seed = 2 };
            CollectionAssert.AreEqual(ComponentSolvers.Pattern(new PatternInput { Generator = poisson }).Points,
                ComponentSolvers.Pattern(new PatternInput { Spec = poisson.ToSpec() }).Points);
            var random = new PatternGenerator { Kind = GeneratorKind.Random, CountU = 30, Seed = 4 };
            CollectionAssert.AreEqual(ComponentSolvers.Pattern(new PatternInput { Generator = random }).Points,
                ComponentSolvers.Pattern(new PatternInput { Spec = random.ToSpec() }).Points);
            var bad = ComponentSolvers.Pattern(new PatternInput { Spec = "triangles" });
            StringAssert.StartsWith("TPI_STATUS_INVALID_PATTERN: ", bad.Errors.Single());
            GeneratorKind kind;
            Assert.IsTrue(PatternGenerator.TryParseKind("Poisson", out kind));
            Assert.AreEqual(GeneratorKind.Poisson, kind);
            Assert.IsFalse(PatternGenerator.TryParseKind("voronoi", out kind));
        }

        [Test]
        public void AVertexFarOffTheSurfaceIsWarnedAbout()
        {
            var q = new QualityReport { FacetCount = 100, MaxDeviation = 2.9, MaxDeviationSpacings = 2.9 };
            Assert.IsNull(QualityWarnings.FarVertex(q));
            q.FarVertexFacets = 4;
            q.MaxDeviation = 49.7;
            q.MaxDeviationSpacings = 50.2;
            StringAssert.StartsWith("4 facets have a vertex far off the surface (largest deviation 49.7; up to 50 local pattern spacings): ", QualityWarnings.FarVertex(q));
            Assert.IsNull(QualityWarnings.FarVertex(new QualityReport()), "no facets, no warning");
            // A strictly convex dome: every vertex near the surface, no such warning.
            var dome = ComponentSolvers.Discretise(new DiscretiseInput { Surface = LogicData.Dome(), Points = LogicData.Hex(6, 6) });
            Assert.IsTrue(dome.Success, string.Join("; ", dome.Errors));
            Assert.IsFalse(dome.Warnings.Any(w => w.Contains("far off the surface")), string.Join("; ", dome.Warnings));
            // An egg crate (bumps, dips and parabolic lines between) with a hex pattern: exact
            // planes meet far off the surface at the parabolic lines; the library flags those
            // facets, the component names them, and adjusted planes hold every vertex near.
            var egg = new AnalyticSurfaceSpec(AnalyticKind.EggCrate, 0.6, 0.3, 6.0, -0.4, 5.5);
            var exact = ComponentSolvers.Discretise(new DiscretiseInput { Surface = egg, Points = LogicData.Hex(12, 12) });
            Assert.IsTrue(exact.Success, string.Join("; ", exact.Errors));
            var quality = ComponentSolvers.Quality(exact.Mesh);
            int far = quality.Flags.Count(f => (f & (int)FacetFlags.FarVertex) != 0);
            Assert.Greater(far, 0, "far vertices on the egg crate");
            Assert.IsTrue(exact.Warnings.Any(w => w.StartsWith(far + " facets have a vertex far off the surface")), string.Join("; ", exact.Warnings));
            var adjusted = DiscretisationOptions.Default();
            adjusted.Planes = PlaneMode.Adjusted;
            var held = ComponentSolvers.Discretise(new DiscretiseInput { Surface = egg, Points = LogicData.Hex(12, 12), Options = adjusted });
            Assert.IsTrue(held.Success, string.Join("; ", held.Errors));
            Assert.IsFalse(ComponentSolvers.Quality(held.Mesh).Flags.Any(f => (f & (int)FacetFlags.FarVertex) != 0), "adjusted planes");
            Assert.IsFalse(held.Warnings.Any(w => w.Contains("far off the surface")), string.Join("; ", held.Warnings));
        }

        [Test]
        public void QualityPerFacet()
        {
            var saddle = new AnalyticSurfaceSpec(AnalyticKind.HyperbolicParaboloid, 1, 1, -1, 1, -1, 1);
            var output = ComponentSolvers.Discretise(new DiscretiseInput { Surface = saddle, Points = LogicData.Hex(6, 6) });
            Assert.IsTrue(output.Success, string.Join("; ", output.Errors));
            var q = ComponentSolvers.Quality(output.Mesh);
            Assert.AreEqual(36, q.Planarity.Length);
            Assert.AreEqual(36, q.Sides.Length);
            Assert.AreEqual(36, q.Flags.Length);
            Assert.AreEqual(36, q.FlagNames.Length);
            Assert.AreEqual(36, q.Diagnostics.Length);
            Assert.AreEqual(36, q.SideHistogram.Values.Sum());
            Assert.Less(q.Planarity.Max(), 1e-12);
            Assert.Greater(q.MaxDeviation, 0);
            Assert.GreaterOrEqual(q.MaxDeviation, q.MeanDeviation);
            // On a saddle non-convex facets are the expected shape: not flagged.
            Assert.IsFalse(q.Flags.Any(f => (f & (int)FacetFlags.NonConvex) != 0), "saddle facets flagged non-convex");
            const int invalid = (int)(FacetFlags.NonSimple | FacetFlags.Overlap | FacetFlags.Open);
            Assert.AreEqual(q.Flags.Count(f => (f & invalid) != 0), q.InvalidFacets);
            Assert.AreEqual(0, q.InvalidFacets, "a hex pattern on a saddle gives a valid mesh");
            StringAssert.Contains("side_histogram", q.Json);
            var noReport = DiscretisationOptions.Default();
            noReport.QualityReport = false;
            var bare = ComponentSolvers.Discretise(new DiscretiseInput { Surface = saddle, Points = LogicData.Hex(6, 6), Options = noReport });
            var bareQuality = ComponentSolvers.Quality(bare.Mesh);
            Assert.IsNaN(bareQuality.MaxDeviation);
            Assert.AreEqual(-1, bareQuality.InvalidFacets);
            Assert.AreEqual("", bareQuality.Json);
        }
    }
}

namespace Tpi.Tests
{
    [TestFixture]
    public class VoronoiTests
    {
        [Test]
        public void CellsTileTheSquareAndHoldTheirPoints()
        {
            var points = LogicData.Hex(7, 5);
            var cells = VoronoiCells.Compute(points);
            Assert.AreEqual(points.Length, cells.Length);
            Assert.AreEqual(1.0, cells.Sum(c => VoronoiCells.Area(c)), 1e-12, "the cells tile the square");
            for (int i = 0; i < cells.Length; i++)
            {
                Assert.Greater(VoronoiCells.Area(cells[i]), 0, "counter-clockwise");
                // Every corner of cell i is at least as close to point i as to any other point.
                foreach (var corner in cells[i])
                    for (int j = 0; j < points.Length; j++)
                        Assert.LessOrEqual(Dist(corner, points[i]), Dist(corner, points[j]) + 1e-12);
            }
        }

        static double Dist(PatternPoint a, PatternPoint b) { return Math.Sqrt((a.S - b.S) * (a.S - b.S) + (a.T - b.T) * (a.T - b.T)); }
    }
}
