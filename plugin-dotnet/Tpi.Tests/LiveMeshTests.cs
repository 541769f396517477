using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>
    /// Issue 13, item 4: the mesh kept from the library's change snapshots (LiveMeshData) and the
    /// panels rebuilt from it equal an independent fresh discretisation of the same points after
    /// every edit of a random series.
    /// </summary>
    [TestFixture]
    public class LiveMeshTests
    {
        /// <summary>A discretisation from scratch of the state's current points, copied out whole.</summary>
        static MeshData Fresh(DiscreteSurfaceState state)
        {
            using (var surface = state.Surface.CreateNative())
            using (var pattern = Pattern.FromPoints(state.Points))
            using (var mesh = Discretisation.Create(surface, pattern, state.Options))
                return MeshData.From(mesh);
        }

        static void AssertSameAsFresh(LiveMeshData live, MeshData fresh, string what)
        {
            var kept = live.ToMeshData();
            Assert.AreEqual(fresh.FacetCount, kept.FacetCount, what + ": facets");
            CollectionAssert.AreEqual(fresh.FacetSizes, kept.FacetSizes, what + ": facet sizes");
            CollectionAssert.AreEqual(fresh.FacetIndices, kept.FacetIndices, what + ": loops (vertex numbering as the library's)");
            CollectionAssert.AreEqual(fresh.Vertices, kept.Vertices, what + ": vertices, bit for bit");
            for (int f = 0; f < fresh.FacetCount; f++)
            {
                Assert.AreEqual(fresh.Planes[f].Point, kept.Planes[f].Point, what + ": plane of facet " + f);
                Assert.AreEqual(fresh.Planes[f].Normal, kept.Planes[f].Normal, what + ": plane of facet " + f);
            }
            Assert.IsTrue(kept.SameMesh(fresh), what);
        }

        static void AssertDisplayIsFresh(PanelDisplay display, MeshData fresh, string what)
        {
            var polylines = MeshConversion.FacetPolylines(fresh);
            var ngons = MeshConversion.ToNgonMesh(fresh);
            Assert.AreEqual(polylines.Length, display.Count, what);
            for (int f = 0; f < polylines.Length; f++)
            {
                CollectionAssert.AreEqual(polylines[f], display.Polylines[f], what + ": polyline of panel " + f);
                var expected = ngons.Ngons[f].Faces.SelectMany(t => new[] { 0, 1, 2 }.Select(c => ngons.Vertices[ngons.Triangles[3 * t + c]])).ToArray();
                var got = display.Triangles[f].Select(i => display.Polylines[f][i]).ToArray();
                CollectionAssert.AreEqual(expected, got, what + ": triangles of panel " + f);
            }
        }

        [Test]
        public void AfterRandomEditsTheKeptMeshAndPanelsEqualAFreshDiscretisation()
        {
            foreach (var quality in new[] { false, true })
            {
                var options = DiscretisationOptions.Default();
                options.QualityReport = quality;
                using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(28, 28), options))
                {
                    var display = new PanelDisplay();
                    display.Update(state.LiveMesh);
                    AssertSameAsFresh(state.LiveMesh, Fresh(state), "new");
                    AssertDisplayIsFresh(display, Fresh(state), "new");
                    var random = new Random(quality ? 11 : 12);
                    int small = 0;
                    for (int step = 0; step < 40; step++)
                    {
                        int n = state.Points.Count;
                        int roll = random.Next(10);
                        string what;
                        if (roll < 7)
                        {
                            int i = random.Next(n);
                            var p = state.Points[i];
                            double s = Math.Min(1, Math.Max(0, p.S + 0.4 * (random.NextDouble() - 0.5) / 28));
                            double t = Math.Min(1, Math.Max(0, p.T + 0.4 * (random.NextDouble() - 0.5) / 28));
                            state.MovePoint(i, s, t);
                            what = "move " + i;
                        }
                        else if (roll < 8)
                        {
                            int i = random.Next(n);
                            state.MovePoint(i, random.NextDouble(), random.NextDouble());
                            what = "jump " + i;
                        }
                        else if (roll < 9)
                        {
                            state.AddPoint(0.1 + 0.8 * random.NextDouble(), 0.1 + 0.8 * random.NextDouble());
                            what = "add";
                        }
                        else
                        {
                            int i = random.Next(n);
                            state.RemovePoint(i);
                            what = "remove " + i;
                        }
                        what = "step " + step + " (" + what + ", report " + quality + ")";
                        var before = state.LiveMesh.Version;
                        string error;
                        Assert.IsTrue(state.TryRecompute(out error), what + ": " + error);
                        var listed = state.LiveMesh.ChangedSince(before);
                        if (roll < 7 && listed != null)
                        {
                            Assert.Less(listed.Length, 30, what + ": a move lists the facets around the point");
                            small++;
                        }
                        display.Update(state.LiveMesh);
                        var fresh = Fresh(state);
                        AssertSameAsFresh(state.LiveMesh, fresh, what);
                        AssertDisplayIsFresh(display, fresh, what);
                        Assert.IsTrue(state.Mesh.SameMesh(fresh), what + ": the whole mesh copied out");
                    }
                    Assert.Greater(small, 10, "moves away from the boundary take live editing");
                }
            }
        }

        [Test]
        public void ADragRebuildsExactlyThePanelsThatChangedAndCopiesNoWholeMesh()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(30, 30)))
            {
                var display = new PanelDisplay();
                Assert.AreEqual(900, display.Update(state.LiveMesh).Length, "the first update builds every panel");
                var before = state.Mesh;
                var p = state.Points[465];
                state.MovePoint(465, p.S + 0.2 / 30, p.T);
                var listed = state.RecomputeChanges();
                Assert.Less(listed.Length, 20, "the library lists the facets around the point");
                CollectionAssert.Contains(listed, 465);
                var changed = display.Update(state.LiveMesh);
                var after = state.Mesh;
                var expected = new HashSet<int>();
                var a = MeshConversion.FacetPolylines(before);
                var b = MeshConversion.FacetPolylines(after);
                for (int f = 0; f < b.Length; f++) if (!a[f].SequenceEqual(b[f])) expected.Add(f);
                CollectionAssert.AreEquivalent(expected, changed, "exactly the panels whose vertices moved");
                CollectionAssert.IsSubsetOf(changed, listed);
                Assert.AreEqual(0, display.Update(state.LiveMesh).Length, "nothing changed, nothing rebuilt");
                // Several recomputes between two display updates: all their panels.
                p = state.Points[100];
                state.MovePoint(100, p.S, p.T + 0.1 / 30);
                var first = state.RecomputeChanges();
                p = state.Points[700];
                state.MovePoint(700, p.S - 0.1 / 30, p.T);
                var second = state.RecomputeChanges();
                var both = display.Update(state.LiveMesh);
                CollectionAssert.IsSubsetOf(both, first.Concat(second).ToArray());
                CollectionAssert.Contains(both, 100);
                CollectionAssert.Contains(both, 700);
                AssertDisplayIsFresh(display, Fresh(state), "two recomputes, one update");
            }
        }

        [Test]
        public void TheFirstChangesListEverythingThenOnlyWhatChanged()
        {
            using (var surface = LogicData.Dome().CreateNative())
            using (var pattern = Pattern.Hex(12, 12))
            using (var ds = DiscreteSurface.Create(surface, pattern))
            {
                var first = ds.TakeChanges();
                Assert.IsTrue(first.Everything);
                Assert.AreEqual(144, first.FacetCount);
                CollectionAssert.AreEqual(Enumerable.Range(0, 144).ToArray(), first.Facets);
                Assert.AreEqual(first.VertexIds.Length, first.Vertices.Length);
                Assert.AreEqual(first.FacetIndices.Length, first.FacetStarts[144]);
                var none = ds.TakeChanges();
                Assert.IsFalse(none.Everything);
                Assert.AreEqual(0, none.Facets.Length);
                Assert.AreEqual(0, none.VertexIds.Length);
                Assert.AreEqual(144, none.FacetCount);
                var p = ds.Points[77];
                ds.MovePoint(77, p.S + 0.2 / 12, p.T + 0.1 / 12);
                Assert.AreEqual(0, ds.TakeChanges().Facets.Length, "a pending edit is not a change");
                ds.Recompute();
                var moved = ds.TakeChanges();
                Assert.IsFalse(moved.Everything, "an interior move is local");
                CollectionAssert.Contains(moved.Facets, 77);
                Assert.Less(moved.Facets.Length, 20);
                Assert.Greater(moved.VertexIds.Length, 0);
                Assert.IsTrue(moved.VertexIds.All(id => id < moved.VertexIdBound));
                Assert.IsTrue(moved.FacetIndices.All(id => id < moved.VertexIdBound));
            }
        }

        [Test]
        public void ChangedSinceKnowsTheRecentHistoryOnly()
        {
            using (var state = new DiscreteSurfaceState(LogicData.Dome(), LogicData.Hex(16, 16)))
            {
                var live = state.LiveMesh;
                int v0 = live.Version;
                Assert.AreEqual(1, v0, "the first snapshot");
                Assert.IsNull(live.ChangedSince(0), "before a change of everything: unknown");
                Assert.AreEqual(0, live.ChangedSince(v0).Length);
                Assert.IsNull(live.ChangedSince(v0 + 1), "a version not reached yet");
                var p = state.Points[120];
                state.MovePoint(120, p.S + 0.1 / 16, p.T);
                var listed = state.RecomputeChanges();
                CollectionAssert.AreEqual(listed.OrderBy(f => f).ToArray(), live.ChangedSince(v0));
                for (int k = 0; k < LiveMeshData.ChangeHistory + 1; k++)
                {
                    p = state.Points[120];
                    state.MovePoint(120, p.S + (k % 2 == 0 ? -0.1 : 0.1) / 16, p.T);
                    state.RecomputeChanges();
                }
                Assert.IsNull(live.ChangedSince(v0), "forgotten after ChangeHistory applications");
                Assert.IsNotNull(live.ChangedSince(live.Version - LiveMeshData.ChangeHistory));
                Assert.Throws<ArgumentException>(() => new LiveMeshData().Apply(NothingChanged(state)), "a first snapshot must list everything");
            }
        }

        /// <summary>A snapshot that lists nothing (taken right after another).</summary>
        static MeshChanges NothingChanged(DiscreteSurfaceState state)
        {
            using (var surface = state.Surface.CreateNative())
            using (var pattern = Pattern.FromPoints(state.Points))
            using (var ds = DiscreteSurface.Create(surface, pattern))
            {
                ds.TakeChanges();
                return ds.TakeChanges();
            }
        }
    }
}
