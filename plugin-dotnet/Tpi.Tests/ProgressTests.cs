using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>
    /// Issue 13, item 4: a long discretisation reports its progress and a cancellation token
    /// stops it (Discretisation.Create with progress, ComponentSolvers with progress texts), and
    /// the component message texts.
    /// </summary>
    [TestFixture]
    public class ProgressTests
    {
        [Test]
        public void ProgressIsReportedStageByStageAndTheResultIsUnchanged()
        {
            var reports = new List<DiscretisationProgress>();
            using (var surface = TestData.Dome())
            using (var pattern = Pattern.Hex(60, 60))
            using (var plain = Discretisation.Create(surface, pattern))
            using (var watched = Discretisation.Create(surface, pattern, null, p => { lock (reports) reports.Add(p); }, CancellationToken.None))
            {
                TestData.AssertSameMesh(plain, watched);
                Assert.AreEqual(plain.QualityJson, watched.QualityJson);
            }
            var stages = new List<Stage>();
            foreach (var r in reports) if (stages.Count == 0 || stages[stages.Count - 1] != r.Stage) stages.Add(r.Stage);
            CollectionAssert.AreEqual(new[] { Stage.Samples, Stage.Delaunay, Stage.Neighbours, Stage.Facets, Stage.Mesh, Stage.Report }, stages);
            Assert.AreEqual(new DiscretisationProgress(Stage.Samples, 0, 3600), reports[0]);
            foreach (var stage in stages)
            {
                var of = reports.Where(r => r.Stage == stage).ToList();
                Assert.AreEqual(0UL, of[0].Done, stage.ToString());
                Assert.AreEqual(of[0].Total, of[of.Count - 1].Done, stage + " ends at its total");
                Assert.IsTrue(of.Zip(of.Skip(1), (a, b) => a.Done <= b.Done).All(x => x), stage + " never goes back");
            }
        }

        [Test]
        public void ACancellationTokenStopsALongSolveWithNothingCreated()
        {
            // 250,000 points (a few seconds of work); the token is cancelled from the first
            // report of the neighbour stage, so the call stops where that stage ends.
            var seen = new List<Stage>();
            using (var cts = new CancellationTokenSource())
            using (var surface = TestData.Dome())
            using (var pattern = Pattern.Hex(500, 500))
            {
                Action<DiscretisationProgress> progress = p =>
                {
                    lock (seen) seen.Add(p.Stage);
                    if (p.Stage == Stage.Neighbours) cts.Cancel();
                };
                var e = Assert.Throws<OperationCanceledException>(() => Discretisation.Create(surface, pattern, null, progress, cts.Token));
                Assert.AreEqual(cts.Token, e.CancellationToken);
                StringAssert.Contains("cancelled by the caller (neighbours stage)", e.Message);
                Assert.AreEqual(Stage.Neighbours, seen.Max(), "no stage after the neighbours started");
                // An already cancelled token stops before any work.
                seen.Clear();
                Assert.Throws<OperationCanceledException>(() => Discretisation.Create(surface, pattern, null, progress, cts.Token));
                Assert.AreEqual(0, seen.Count);
                // The inputs are untouched: a small solve with them still works.
                using (var small = Pattern.Hex(8, 8))
                using (var d = Discretisation.Create(surface, small, null, null, CancellationToken.None))
                    Assert.AreEqual(64, d.FacetCount);
            }
        }

        [Test]
        public void AnExceptionInTheProgressHandlerStopsTheSolveAndIsRethrown()
        {
            using (var surface = TestData.Dome())
            using (var pattern = Pattern.Hex(20, 20))
            {
                var e = Assert.Throws<InvalidOperationException>(() => Discretisation.Create(surface, pattern, null, p => { throw new FormatException("boom"); }, CancellationToken.None));
                Assert.IsInstanceOf<FormatException>(e.InnerException);
            }
        }

        [Test]
        public void TheComponentSolveShowsProgressTextsAndReportsACancel()
        {
            var input = new DiscretiseInput { Surface = LogicData.Dome(), Points = LogicData.Hex(300, 300) };
            var texts = new List<string>();
            var solved = ComponentSolvers.DiscretiseOrReject(input, null, null, t => { lock (texts) texts.Add(t); }, CancellationToken.None);
            Assert.IsTrue(solved.Success, string.Join("; ", solved.Errors));
            Assert.IsFalse(solved.Cancelled);
            Assert.AreEqual("1/6 samples 0%", texts[0]);
            Assert.AreEqual("6/6 report 100%", texts[texts.Count - 1]);
            CollectionAssert.Contains(texts, "2/6 delaunay");
            CollectionAssert.Contains(texts, "4/6 facets 100%");
            Assert.AreEqual(texts.Count, texts.Distinct().Count(), "each text once");
            Assert.LessOrEqual(texts.Count, 6 * 101 + 1);

            // The token of a Grasshopper solve, cancelled while it runs (from the first text).
            using (var cts = new CancellationTokenSource())
            {
                texts.Clear();
                var cancelled = ComponentSolvers.DiscretiseOrReject(input, null, new[] { "a warning" }, t => { lock (texts) texts.Add(t); cts.Cancel(); }, cts.Token);
                Assert.IsFalse(cancelled.Success);
                Assert.IsTrue(cancelled.Cancelled);
                Assert.IsNull(cancelled.Mesh);
                Assert.AreEqual("cancelled: cancelled by the caller (samples stage)", cancelled.Errors.Single());
                CollectionAssert.AreEqual(new[] { "a warning" }, cancelled.Warnings);
                CollectionAssert.AreEqual(new[] { "1/6 samples 0%" }, texts.Take(1));
                Assert.IsTrue(texts.All(t => t.StartsWith("1/6 samples")), string.Join(", ", texts));
            }
        }

        [Test]
        public void MessageTexts()
        {
            Assert.AreEqual("1/6 samples 0%", ProgressText.Format(new DiscretisationProgress(Stage.Samples, 0, 10)));
            Assert.AreEqual("3/6 neighbours 33%", ProgressText.Format(new DiscretisationProgress(Stage.Neighbours, 1, 3)));
            // Rounded down: 100% only when everything is done.
            Assert.AreEqual("4/6 facets 99%", ProgressText.Format(new DiscretisationProgress(Stage.Facets, 999, 1000)));
            Assert.AreEqual("5/6 mesh 100%", ProgressText.Format(new DiscretisationProgress(Stage.Mesh, 1000, 1000)));
            // No total: no percentage. A count beyond its total is shown as the total.
            Assert.AreEqual("2/6 delaunay", ProgressText.Format(new DiscretisationProgress(Stage.Delaunay, 0, 0)));
            Assert.AreEqual("6/6 report 100%", ProgressText.Format(new DiscretisationProgress(Stage.Report, 12, 10)));
            Assert.AreEqual("1/6 samples 50%", ProgressText.Format(new DiscretisationProgress(Stage.Samples, 1UL << 55, 1UL << 56)));

            var shown = new List<string>();
            var messages = new ProgressMessages(shown.Add);
            messages.Report(new DiscretisationProgress(Stage.Facets, 0, 200));
            messages.Report(new DiscretisationProgress(Stage.Facets, 1, 200));
            messages.Report(new DiscretisationProgress(Stage.Facets, 2, 200));
            messages.Report(new DiscretisationProgress(Stage.Facets, 200, 200));
            CollectionAssert.AreEqual(new[] { "4/6 facets 0%", "4/6 facets 1%", "4/6 facets 100%" }, shown);
            Assert.AreEqual(3, messages.Shown);
            Assert.Throws<ArgumentNullException>(() => new ProgressMessages(null));
        }
    }
}
