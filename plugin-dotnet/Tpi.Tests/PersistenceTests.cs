using System;
using System.IO;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    static class Fixtures
    {
        /// <summary>An embedded fixture (Tpi.Tests/Fixtures/NAME, embedded as Tpi.Tests.Fixtures.NAME).</summary>
        public static byte[] Load(string name)
        {
            using (var stream = typeof(Fixtures).Assembly.GetManifestResourceStream("Tpi.Tests.Fixtures." + name))
            {
                Assert.IsNotNull(stream, "fixture " + name + " is not embedded");
                var bytes = new MemoryStream();
                stream.CopyTo(bytes);
                return bytes.ToArray();
            }
        }

        /// <summary>A copy of <paramref name="bytes"/> with the checksum made right again after an edit.</summary>
        public static byte[] Reseal(byte[] bytes)
        {
            var copy = (byte[])bytes.Clone();
            var crc = UserDataFormat.Crc32(copy, 0, copy.Length - 4);
            for (int i = 0; i < 4; i++) copy[copy.Length - 4 + i] = (byte)(crc >> (8 * i));
            return copy;
        }

        public static readonly Guid V1Source = new Guid("0f1e2d3c-4b5a-6978-8796-a5b4c3d2e1f0");
    }

    [TestFixture]
    public class UserDataMigrationTests
    {
        [Test]
        public void PreviousVersionBlobReadsWithEveryField()
        {
            var bytes = Fixtures.Load("discrete-surface-v1.bin");
            Assert.AreEqual(728, bytes.Length);
            Assert.AreEqual(1, bytes[4] | bytes[5] << 8, "the fixture is format 1");
            ushort version;
            var document = UserDataFormat.Read(bytes, out version);
            Assert.AreEqual(1, version);
            var expectedSurface = new NurbsSurfaceSpec(3, 3, 4, 4, TestData.BezierKnots, TestData.BezierKnots, TestData.DomePoints(1.0), null);
            Assert.IsTrue(expectedSurface.Equals(document.Surface), "the dome");
            var expectedPoints = new[] { 0.2, 0.5, 0.8 }.SelectMany(s => new[] { 0.15, 0.5, 0.85 }.Select(t => new PatternPoint(s, t))).ToArray();
            CollectionAssert.AreEqual(expectedPoints, document.Points);
            Assert.IsFalse(document.Options.EnvelopeRepair);
            Assert.IsTrue(document.Options.QualityReport);
            Assert.AreEqual(8.0, document.Options.FarVertexFactor);
            Assert.AreEqual(1e-10, document.Options.WeldTolerance);
            Assert.AreEqual(1e-6, document.Options.FlatTolerance);
            Assert.AreEqual("grid:3x3", document.Generator);
            Assert.AreEqual(Fixtures.V1Source, document.SourceSurfaceId);
            // Fields format 1 did not have take their defaults.
            Assert.AreEqual(-1, document.SourceFaceIndex);
            CollectionAssert.AreEqual(new double[] { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }, document.SourceTransform);
        }

        [Test]
        public void PreviousVersionBlobMigratesToTheCurrentFormat()
        {
            var v1 = Fixtures.Load("discrete-surface-v1.bin");
            var decision = DiscreteSurfaceUpgrade.Decide(true, false, v1);
            Assert.AreEqual(UpgradeAction.Upgrade, decision.Action);
            Assert.IsTrue(decision.Migrated);
            Assert.AreEqual(1, decision.FoundVersion);
            var current = UserDataFormat.Write(decision.Document);
            Assert.AreEqual(UserDataFormat.FormatVersion, current[4] | current[5] << 8);
            Assert.Greater(UserDataFormat.FormatVersion, (ushort)1);
            ushort version;
            var back = UserDataFormat.Read(current, out version);
            Assert.AreEqual(UserDataFormat.FormatVersion, version);
            Assert.IsTrue(back.SameAs(UserDataFormat.Read(v1)), "migration loses nothing");
            // The migrated data is a discrete surface of 9 panels, the same as from the old data.
            using (var a = new DiscreteSurfaceState(UserDataFormat.Read(v1)))
            using (var b = new DiscreteSurfaceState(back))
            {
                Assert.AreEqual(9, a.Mesh.FacetCount);
                Assert.IsTrue(a.Mesh.SameMesh(b.Mesh));
            }
        }

        [Test]
        public void CurrentFormatKeepsTheTrimAndThePlaneMode()
        {
            var v1 = UserDataFormat.Read(Fixtures.Load("discrete-surface-v1.bin"));
            // A square hole in the middle of the dome's (u, v) domain [0, 1]^2.
            var trim = new SurfaceTrim(new[] { 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0 },
                new[] { new[] { 0.4, 0.4, 0.4, 0.6, 0.6, 0.6, 0.6, 0.4 } });
            v1.Surface = v1.Surface.WithTrim(trim);
            v1.Options = new DiscretisationOptions { Planes = PlaneMode.Adjusted, QualityReport = true, FarVertexFactor = 8, WeldTolerance = 1e-10, FlatTolerance = 1e-6 };
            var bytes = UserDataFormat.Write(v1);
            ushort version;
            var back = UserDataFormat.Read(bytes, out version);
            Assert.AreEqual(UserDataFormat.FormatVersion, version);
            Assert.IsNotNull(back.Surface.Trim, "the trim was lost");
            Assert.IsTrue(trim.Equals(back.Surface.Trim), "the trim changed");
            Assert.IsTrue(back.Surface.Equals(v1.Surface));
            Assert.AreEqual(PlaneMode.Adjusted, back.Options.Planes, "the plane mode was lost");
            // Untrimmed and exact stay so.
            var plain = UserDataFormat.Read(Fixtures.Load("discrete-surface-v1.bin"));
            var again = UserDataFormat.Read(UserDataFormat.Write(plain));
            Assert.IsNull(again.Surface.Trim);
            Assert.AreEqual(PlaneMode.Exact, again.Options.Planes);
        }

        [Test]
        public void CurrentFormatKeepsTransformAndFace()
        {
            var v1 = UserDataFormat.Read(Fixtures.Load("discrete-surface-v1.bin"));
            var moved = v1.Transformed(new double[] { 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1 });
            moved.SourceFaceIndex = 4;
            var back = UserDataFormat.Read(UserDataFormat.Write(moved));
            Assert.IsTrue(back.SameAs(moved));
            Assert.AreEqual(4, back.SourceFaceIndex);
            CollectionAssert.AreEqual(moved.SourceTransform, back.SourceTransform);
        }

        [Test]
        public void NewerOrDamagedDataIsRefusedWithAReason()
        {
            var current = UserDataFormat.Write(UserDataFormat.Read(Fixtures.Load("discrete-surface-v1.bin")));
            var newer = (byte[])current.Clone();
            newer[4] = (byte)(UserDataFormat.FormatVersion + 1);
            var decision = DiscreteSurfaceUpgrade.Decide(true, false, Fixtures.Reseal(newer));
            Assert.AreEqual(UpgradeAction.Refuse, decision.Action);
            StringAssert.Contains("newer TPI plugin", decision.Message);

            var damaged = (byte[])current.Clone();
            damaged[40] ^= 0x10;
            decision = DiscreteSurfaceUpgrade.Decide(true, false, damaged);
            Assert.AreEqual(UpgradeAction.Refuse, decision.Action);
            StringAssert.Contains("checksum", decision.Message);

            // A face index below -1 in an otherwise valid blob (face index: the 4 bytes before the CRC).
            var badFace = (byte[])current.Clone();
            BitConverter.GetBytes(-5).CopyTo(badFace, badFace.Length - 8);
            var e = Assert.Throws<FormatException>(() => UserDataFormat.Read(Fixtures.Reseal(badFace)));
            StringAssert.Contains("face index -5", e.Message);

            // Trailing bytes are not silently ignored.
            var longer = current.Take(current.Length - 4).Concat(new byte[] { 1, 2, 3, 4, 0, 0, 0, 0 }).ToArray();
            e = Assert.Throws<FormatException>(() => UserDataFormat.Read(Fixtures.Reseal(longer)));
            StringAssert.Contains("trailing", e.Message);
        }
    }

    [TestFixture]
    public class UpgradeDecisionTests
    {
        static byte[] Current() { return UserDataFormat.Write(UserDataFormat.Read(Fixtures.Load("discrete-surface-v1.bin"))); }

        [Test]
        public void OnlyMeshesCarryingOurDataAreUpgraded()
        {
            Assert.AreEqual(UpgradeAction.Keep, DiscreteSurfaceUpgrade.Decide(true, false, null).Action, "a plain mesh");
            Assert.AreEqual(UpgradeAction.Keep, DiscreteSurfaceUpgrade.Decide(false, false, null).Action, "a surface");
            var reopened = DiscreteSurfaceUpgrade.Decide(true, false, Current());
            Assert.AreEqual(UpgradeAction.Upgrade, reopened.Action, "a mesh read from a file, pasted or imported");
            Assert.IsFalse(reopened.Migrated);
            Assert.IsNotNull(reopened.Document);
            var live = DiscreteSurfaceUpgrade.Decide(true, true, Current());
            Assert.AreEqual(UpgradeAction.Keep, live.Action, "already a discrete surface object");
            Assert.AreEqual(UpgradeAction.Upgrade, DiscreteSurfaceUpgrade.Decide(true, true, Fixtures.Load("discrete-surface-v1.bin")).Action,
                "a discrete surface object with old data stores it again");
            var notMesh = DiscreteSurfaceUpgrade.Decide(false, false, Current());
            Assert.AreEqual(UpgradeAction.Refuse, notMesh.Action);
            StringAssert.Contains("not a mesh", notMesh.Message);
        }
    }

    [TestFixture]
    public class TransformFollowTests
    {
        static readonly double[] Rigid = { 0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3, 0, 0, 0, 1 };
        static readonly double[] ScaleTwoAboutOrigin = { 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1 };

        static Vec3 Apply(double[] m, Vec3 p)
        {
            double x = m[0] * p.X + m[1] * p.Y + m[2] * p.Z + m[3];
            double y = m[4] * p.X + m[5] * p.Y + m[6] * p.Z + m[7];
            double z = m[8] * p.X + m[9] * p.Y + m[10] * p.Z + m[11];
            double w = m[12] * p.X + m[13] * p.Y + m[14] * p.Z + m[15];
            return new Vec3(x / w, y / w, z / w);
        }

        static DiscreteSurfaceDocument Dome()
        {
            return new DiscreteSurfaceDocument
            {
                Surface = LogicData.Dome(),
                Points = LogicData.Hex(5, 5).ToList(),
                Options = DiscretisationOptions.Default(),
                SourceSurfaceId = Guid.NewGuid(),
            };
        }

        [Test]
        public void ClassifiesTransforms()
        {
            Assert.AreEqual(TransformKind.Similarity, Transforms.Classify(Transforms.Identity()));
            Assert.AreEqual(TransformKind.Similarity, Transforms.Classify(Rigid));
            Assert.AreEqual(TransformKind.Similarity, Transforms.Classify(Transforms.Multiply(ScaleTwoAboutOrigin, Rigid)));
            Assert.AreEqual(TransformKind.Affine, Transforms.Classify(new double[] { 2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }), "non-uniform scale");
            Assert.AreEqual(TransformKind.Affine, Transforms.Classify(new double[] { -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }), "mirror");
            Assert.AreEqual(TransformKind.Affine, Transforms.Classify(new double[] { 1, 0.5, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 }), "shear");
            Assert.AreEqual(TransformKind.Projective, Transforms.Classify(new double[] { 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0.1, 1 }));
        }

        [Test]
        public void SimilarityMovesTheMeshExactly()
        {
            // Tangent planes and their meeting points map with a similarity, so the recomputed
            // mesh of the moved document is the shown mesh moved (what Rhino does to the mesh).
            var document = Dome();
            foreach (var m in new[] { Rigid, Transforms.Multiply(ScaleTwoAboutOrigin, Rigid) })
            {
                Assert.AreEqual(TransformKind.Similarity, Transforms.Classify(m));
                using (var before = new DiscreteSurfaceState(document))
                using (var after = new DiscreteSurfaceState(document.Transformed(m)))
                {
                    CollectionAssert.AreEqual(before.Mesh.FacetSizes, after.Mesh.FacetSizes);
                    CollectionAssert.AreEqual(before.Mesh.FacetIndices, after.Mesh.FacetIndices);
                    Assert.AreEqual(before.Mesh.Vertices.Length, after.Mesh.Vertices.Length);
                    for (int i = 0; i < before.Mesh.Vertices.Length; i++)
                    {
                        var expected = Apply(m, before.Mesh.Vertices[i]);
                        var got = after.Mesh.Vertices[i];
                        Assert.AreEqual(expected.X, got.X, 1e-9); Assert.AreEqual(expected.Y, got.Y, 1e-9); Assert.AreEqual(expected.Z, got.Z, 1e-9);
                    }
                }
            }
        }

        [Test]
        public void SourceEditedAfterAMoveIsFollowedAtTheNewPlace()
        {
            var document = Dome();
            var source = (NurbsSurfaceSpec)document.Surface;
            var second = new double[] { 1, 0, 0, -4, 0, 1, 0, 0.5, 0, 0, 1, 0, 0, 0, 0, 1 };
            var moved = document.Transformed(Rigid).Transformed(second);
            CollectionAssert.AreEqual(Transforms.Multiply(second, Rigid), moved.SourceTransform);
            // The source is edited where it is (it was not moved): raise one control point.
            var p = source.ControlPoint(1, 2);
            var edited = source.WithControlPoint(1, 2, new Vec3(p.X, p.Y, p.Z + 0.7));
            var followed = moved.SurfaceFromSource(edited);
            using (var e = edited.CreateNative())
            using (var f = followed.CreateNative())
            using (var m = moved.Surface.CreateNative())
                foreach (var st in new[] { new PatternPoint(0.1, 0.2), new PatternPoint(0.5, 0.5), new PatternPoint(0.9, 0.35) })
                {
                    var expected = Apply(second, Apply(Rigid, e.Evaluate(st.S, st.T).Point));
                    var got = f.Evaluate(st.S, st.T).Point;
                    Assert.AreEqual(expected.X, got.X, 1e-12); Assert.AreEqual(expected.Y, got.Y, 1e-12); Assert.AreEqual(expected.Z, got.Z, 1e-12);
                    // Away from the raised control point's influence nothing would differ, but at (0.5, 0.5) it does.
                    if (st.S == 0.5) Assert.AreNotEqual(m.Evaluate(0.5, 0.5).Point.Z, got.Z);
                }
            // Without a move the source is taken as it is.
            Assert.AreSame(edited, document.SurfaceFromSource(edited));
        }

        [Test]
        public void AnalyticSurfacesRefuseATransform()
        {
            var document = Dome();
            document.Surface = new AnalyticSurfaceSpec(AnalyticKind.EggCrate, 0.3, -1, 1, -1, 1);
            Assert.Throws<NotSupportedException>(() => document.Transformed(Rigid));
            Assert.Throws<ArgumentException>(() => document.SourceTransform = new double[] { 1, 2 });
            var nan = Transforms.Identity(); nan[3] = double.NaN;
            Assert.Throws<ArgumentException>(() => document.SourceTransform = nan);
        }
    }

    [TestFixture]
    public class DocumentWorkQueueTests
    {
        static readonly Guid A = new Guid("00000000-0000-0000-0000-00000000000a");
        static readonly Guid B = new Guid("00000000-0000-0000-0000-00000000000b");
        static readonly Guid C = new Guid("00000000-0000-0000-0000-00000000000c");

        [Test]
        public void DocumentsKeepTheirOwnWork()
        {
            var queue = new DocumentWorkQueue();
            queue.ObjectReplaced(1, A, false);
            queue.ObjectReplaced(2, B, false);
            queue.ObjectAdded(2, C, true, false);
            CollectionAssert.AreEqual(new uint[] { 1, 2 }, queue.DocumentsWithWork());
            var one = queue.Take(1);
            CollectionAssert.AreEqual(new[] { A }, one.ChangedSources);
            Assert.AreEqual(0, one.Upgrades.Count);
            Assert.IsFalse(queue.HasWork(1));
            Assert.IsTrue(queue.HasWork(2), "taking document 1's work leaves document 2's");
            var two = queue.Take(2);
            CollectionAssert.AreEqual(new[] { B }, two.ChangedSources);
            CollectionAssert.AreEqual(new[] { C }, two.Upgrades);
            Assert.IsTrue(queue.Take(2).IsEmpty, "taken once");
            Assert.AreEqual(0, queue.DocumentsWithWork().Count);
        }

        [Test]
        public void OwnReplacementsAndPlainObjectsAreIgnored()
        {
            var queue = new DocumentWorkQueue();
            queue.ObjectReplaced(1, A, true);   // our own update: the new object is a discrete surface
            queue.ObjectAdded(1, B, true, true); // our own upgrade adds a discrete surface object
            queue.ObjectAdded(1, C, false, false); // a plain object
            Assert.IsFalse(queue.HasWork(1));
            queue.ObjectReplaced(1, A, false);
            queue.ObjectReplaced(1, A, false);
            CollectionAssert.AreEqual(new[] { A }, queue.Take(1).ChangedSources, "recorded once");
        }

        [Test]
        public void NothingRunsWhileAFileIsRead()
        {
            var queue = new DocumentWorkQueue();
            queue.BeginOpen(3);
            queue.ObjectAdded(3, A, true, false);
            queue.ObjectAdded(3, B, true, false);
            Assert.IsFalse(queue.HasWork(3));
            Assert.IsTrue(queue.Take(3).IsEmpty);
            queue.ObjectAdded(3, A, true, false); // the scan after the read reports it again
            queue.EndOpen(3);
            Assert.IsTrue(queue.HasWork(3));
            CollectionAssert.AreEqual(new[] { A, B }, queue.Take(3).Upgrades, "in the order they were read");
        }

        [Test]
        public void ClosingADocumentDropsItsWork()
        {
            var queue = new DocumentWorkQueue();
            queue.ObjectAdded(4, A, true, false);
            queue.RecomputeLater(4, B);
            queue.RecomputeLater(5, C);
            queue.DocumentClosed(4);
            Assert.IsFalse(queue.HasWork(4));
            CollectionAssert.AreEqual(new uint[] { 5 }, queue.DocumentsWithWork());
            CollectionAssert.AreEqual(new[] { C }, queue.Take(5).Recompute);
        }

        [Test]
        public void RefusalsAreReportedOncePerDocument()
        {
            var queue = new DocumentWorkQueue();
            Assert.IsTrue(queue.ShouldReport(1, A));
            Assert.IsFalse(queue.ShouldReport(1, A));
            Assert.IsTrue(queue.ShouldReport(2, A));
            queue.DocumentClosed(1);
            Assert.IsTrue(queue.ShouldReport(1, A), "a reopened document reports again");
        }
    }

    [TestFixture]
    public class SourceFollowTests
    {
        static DiscreteSurfaceDocument WithFace(int face)
        {
            return new DiscreteSurfaceDocument { Surface = LogicData.Dome(), SourceSurfaceId = Guid.NewGuid(), SourceFaceIndex = face };
        }

        [Test]
        public void SurfacesAndFacesAreFollowed()
        {
            var d = SourceFollow.Decide(WithFace(-1), SourceShape.Surface, 1);
            Assert.IsTrue(d.Follow); Assert.AreEqual(-1, d.FaceIndex);
            d = SourceFollow.Decide(WithFace(2), SourceShape.Polysurface, 6);
            Assert.IsTrue(d.Follow); Assert.AreEqual(2, d.FaceIndex);
            d = SourceFollow.Decide(WithFace(0), SourceShape.Surface, 1);
            Assert.IsTrue(d.Follow); Assert.AreEqual(0, d.FaceIndex);
        }

        [Test]
        public void WhatCannotBeFollowedIsRefusedWithAReason()
        {
            var d = SourceFollow.Decide(WithFace(-1), SourceShape.Polysurface, 3);
            Assert.IsFalse(d.Follow); StringAssert.Contains("polysurface of 3 faces", d.Message);
            d = SourceFollow.Decide(WithFace(5), SourceShape.Polysurface, 3);
            Assert.IsFalse(d.Follow); StringAssert.Contains("face 5", d.Message); StringAssert.Contains("3 faces", d.Message);
            d = SourceFollow.Decide(WithFace(2), SourceShape.Surface, 1);
            Assert.IsFalse(d.Follow); StringAssert.Contains("single surface", d.Message);
            d = SourceFollow.Decide(WithFace(-1), SourceShape.Missing, 0);
            Assert.IsFalse(d.Follow); StringAssert.Contains("not in this document", d.Message);
            d = SourceFollow.Decide(WithFace(-1), SourceShape.Other, 0);
            Assert.IsFalse(d.Follow); StringAssert.Contains("no longer a surface", d.Message);
            var none = new DiscreteSurfaceDocument { Surface = LogicData.Dome() };
            d = SourceFollow.Decide(none, SourceShape.Missing, 0);
            Assert.IsFalse(d.Follow); Assert.IsNull(d.Message, "no source: nothing to follow, nothing to say");
        }
    }
}
