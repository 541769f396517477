using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;
using Tpi.Native.Interop;

namespace Tpi.Tests
{
    /// <summary>
    /// Patterns made on a surface (issue 15): the binding of tpi_pattern_new_for_surface,
    /// tpi_pattern_fit_report and tpi_pattern_hex_baseline, checked against what the test can
    /// compute itself (the sphere's closed-form distance, facet areas from the mesh's vertices,
    /// the plain generator's points), and the Rhino-free composition of the component's inputs.
    /// </summary>
    [TestFixture]
    public class SurfacePatternTests
    {
        const double Radius = 10.0;

        static Surface Sphere() { return Surface.SphereCap(Radius, -3, 3, -3, 3); }

        /// <summary>Largest | |x| - R | over the vertices the facets use: the distance to the whole sphere.</summary>
        static double WorstSphereDistance(Discretisation mesh)
        {
            var v = mesh.GetVertexArray();
            double worst = 0;
            foreach (var i in mesh.FacetIndices)
            {
                double x = v[3 * i], y = v[3 * i + 1], z = v[3 * i + 2];
                worst = Math.Max(worst, Math.Abs(Math.Sqrt(x * x + y * y + z * z) - Radius));
            }
            return worst;
        }

        /// <summary>Coefficient of variation of the facet areas (Newell's vector area from the vertices).</summary>
        static double AreaVariation(Discretisation mesh)
        {
            var v = mesh.GetVertexArray();
            var areas = new List<double>();
            for (int f = 0; f < mesh.FacetCount; f++)
            {
                var loop = mesh.GetFacet(f);
                double nx = 0, ny = 0, nz = 0;
                for (int k = 0; k < loop.Length; k++)
                {
                    int a = 3 * loop[k], b = 3 * loop[(k + 1) % loop.Length];
                    nx += v[a + 1] * v[b + 2] - v[a + 2] * v[b + 1];
                    ny += v[a + 2] * v[b] - v[a] * v[b + 2];
                    nz += v[a] * v[b + 1] - v[a + 1] * v[b];
                }
                areas.Add(0.5 * Math.Sqrt(nx * nx + ny * ny + nz * nz));
            }
            double mean = areas.Average();
            return Math.Sqrt(areas.Select(a => (a - mean) * (a - mean)).Average()) / mean;
        }

        [Test]
        public void APlainGeneratorOnASurfaceGivesTheGeneratorsPoints()
        {
            using (var sphere = Sphere())
            using (var onSurface = Pattern.ForSurface(sphere, "hex:6x5"))
            using (var plain = Pattern.Hex(6, 5))
            {
                CollectionAssert.AreEqual(plain.GetPointArray(), onSurface.GetPointArray());
                Assert.IsNull(onSurface.Fit);
            }
        }

        [Test]
        public void AFitMeetsItsToleranceAtEveryVertexByTheSpheresClosedForm()
        {
            const double d = 0.01;
            using (var sphere = Sphere())
            using (var pattern = Pattern.ForSurface(sphere, "fit:0.01:seed=2"))
            {
                var fit = pattern.Fit;
                Assert.IsTrue(fit.HasValue);
                Assert.AreEqual(1u, fit.Value.Met);
                Assert.AreEqual(d, fit.Value.Tolerance);
                Assert.AreEqual((uint)FitReport.SizeV1, fit.Value.StructSize);
                using (var mesh = Discretisation.Create(sphere, pattern))
                {
                    double worst = WorstSphereDistance(mesh);
                    Assert.Greater(worst, 0.0);
                    Assert.LessOrEqual(worst, d * (1 + 1e-9), "own measure");
                }
                double hexDeviation;
                int hex = Pattern.HexBaseline(sphere, d, 100000, out hexDeviation);
                Assert.Greater(hex, 0);
                Assert.LessOrEqual(hexDeviation, d);
                Assert.AreEqual(0, Pattern.HexBaseline(sphere, d, 10, out hexDeviation));
                Assert.IsTrue(double.IsNaN(hexDeviation));
            }
        }

        [Test]
        public void RelaxingRandomPointsOnTheSurfaceEvensTheFacetAreas()
        {
            using (var sphere = Sphere())
            using (var start = Pattern.ForSurface(sphere, "random:80:seed=3"))
            using (var relaxed = Pattern.ForSurface(sphere, "relax:10:random:80:seed=3"))
            using (var before = Discretisation.Create(sphere, start))
            using (var after = Discretisation.Create(sphere, relaxed))
            {
                Assert.AreEqual(80, relaxed.Count);
                double cvBefore = AreaVariation(before), cvAfter = AreaVariation(after);
                Assert.Less(cvAfter, 0.5 * cvBefore, "before " + cvBefore + ", after " + cvAfter);
            }
        }

        [Test]
        public void MalformedSpecsThrowNamingThePiece()
        {
            using (var sphere = Sphere())
            {
                var cases = new[]
                {
                    new[] { "relax:abc:hex:4x4", "relax:abc" },
                    new[] { "fit:-1", "fit:-1" },
                    new[] { "density:@graded.json", "inline" },
                    new[] { "align:random:40:principal", "align:random" },
                };
                foreach (var c in cases)
                {
                    var e = Assert.Throws<TpiException>(() => Pattern.ForSurface(sphere, c[0]).Dispose(), c[0]);
                    Assert.AreEqual(Status.InvalidPattern, e.Status, c[0]);
                    StringAssert.Contains(c[1], e.NativeMessage, c[0]);
                }
                var n = Assert.Throws<TpiException>(() => Pattern.ForSurface(null, "hex:4x4").Dispose());
                Assert.AreEqual(Status.NullPointer, n.Status);
                var s = Assert.Throws<TpiException>(() => Pattern.ForSurface(sphere, null).Dispose());
                Assert.AreEqual(Status.NullPointer, s.Status);
            }
        }

        [Test]
        public void TheComponentsInputsComposeOneSpec()
        {
            string spec, error;
            Assert.IsTrue(new SurfacePatternInputs { MaxDeviation = 0.025 }.TryCompose("hex:10x10", out spec, out error));
            Assert.AreEqual("fit:0.025", spec);
            Assert.IsTrue(new SurfacePatternInputs { Relax = 20 }.TryCompose("random:500:seed=1", out spec, out error));
            Assert.AreEqual("relax:20:random:500:seed=1", spec);
            Assert.IsTrue(new SurfacePatternInputs { Align = " uv:30 " }.TryCompose("grid:8x8", out spec, out error));
            Assert.AreEqual("align:grid:8x8:uv:30", spec);
            Assert.IsTrue(new SurfacePatternInputs { Relax = 3, Align = "principal" }.TryCompose("hex:6x6", out spec, out error));
            Assert.AreEqual("relax:3:align:hex:6x6:principal", spec);
            Assert.IsTrue(new SurfacePatternInputs { Relax = 2, DensityJson = "{\"spacing\": 1, \"terms\": []}" }.TryCompose("hex:6x6", out spec, out error));
            Assert.AreEqual("relax:2:density:{\"spacing\": 1, \"terms\": []}", spec);
            Assert.IsFalse(new SurfacePatternInputs().Any);

            Assert.IsFalse(new SurfacePatternInputs { MaxDeviation = 0.1, Relax = 2 }.TryCompose("hex:4x4", out spec, out error));
            StringAssert.Contains("tolerance", error);
            Assert.IsFalse(new SurfacePatternInputs { Align = "principal", DensityJson = "{}" }.TryCompose("hex:4x4", out spec, out error));
            StringAssert.Contains("not both", error);
            Assert.IsFalse(new SurfacePatternInputs { Relax = -1 }.TryCompose("hex:4x4", out spec, out error));
            Assert.IsFalse(new SurfacePatternInputs { MaxDeviation = double.NaN }.TryCompose("hex:4x4", out spec, out error));

            Assert.IsTrue(SurfacePatternInputs.NeedsSurface(" relax:2:hex:4x4"));
            Assert.IsTrue(SurfacePatternInputs.NeedsSurface("fit:0.1"));
            Assert.IsFalse(SurfacePatternInputs.NeedsSurface("hex:4x4"));
            Assert.IsFalse(SurfacePatternInputs.NeedsSurface(null));
        }

        [Test]
        public void TheCommandsAlignmentChoicesAreFieldsTheLibraryTakes()
        {
            // The Rhino commands offer Align as a list; each choice must compose a spec whose
            // points are those of the spec written by hand in the library's grammar.
            var sphere = new AnalyticSurfaceSpec(AnalyticKind.SphereCap, Radius, -3, 3, -3, 3);
            var hex = new PatternGenerator { Kind = GeneratorKind.Hex, CountU = 8, CountV = 8 };
            Assert.AreEqual("None", SurfacePatternInputs.AlignChoices[0]);
            Assert.IsNull(SurfacePatternInputs.AlignField(0));
            Assert.IsNull(SurfacePatternInputs.AlignField(SurfacePatternInputs.AlignChoices.Length));
            Assert.IsNull(SurfacePatternInputs.AlignField(-1));
            var byHand = new[] { null, "align:hex:8x8:principal", "align:hex:8x8:asymptotic" };
            Assert.AreEqual(byHand.Length, SurfacePatternInputs.AlignChoices.Length);
            for (int i = 0; i < byHand.Length; i++)
            {
                var field = SurfacePatternInputs.AlignField(i);
                Assert.AreEqual(i, SurfacePatternInputs.AlignChoiceOf(field));
                Assert.AreEqual(i, SurfacePatternInputs.AlignChoiceOf(field == null ? null : " " + field.ToUpperInvariant() + " "));
                var output = ComponentSolvers.Pattern(new PatternInput
                {
                    Generator = hex,
                    Surface = sphere,
                    OnSurface = new SurfacePatternInputs { Align = field },
                });
                Assert.IsEmpty(output.Errors);
                Assert.AreEqual(byHand[i] ?? "hex:8x8", output.Spec);
                using (var surface = sphere.CreateNative())
                using (var direct = Pattern.ForSurface(surface, byHand[i] ?? "hex:8x8"))
                    CollectionAssert.AreEqual(direct.Points.ToArray(), output.Points);
                StringAssert.StartsWith(output.Points.Length + " points (" + output.Spec + ")", output.Summary());
            }
            Assert.AreEqual(0, SurfacePatternInputs.AlignChoiceOf("uv:30"));
        }

        [Test]
        public void AFitsSummarySaysWhetherTheToleranceWasMet()
        {
            var sphere = new AnalyticSurfaceSpec(AnalyticKind.SphereCap, Radius, -3, 3, -3, 3);
            var fit = ComponentSolvers.Pattern(new PatternInput { Surface = sphere, OnSurface = new SurfacePatternInputs { MaxDeviation = 0.02 } });
            Assert.IsEmpty(fit.Errors);
            var f = fit.Fit.Value;
            var summary = fit.Summary();
            StringAssert.StartsWith(fit.Points.Length + " points (fit:0.02); largest vertex deviation ", summary);
            StringAssert.Contains(f.MaxDeviation.ToString("G4", System.Globalization.CultureInfo.InvariantCulture), summary);
            StringAssert.Contains(f.Met == 1 ? ": met (" : ": NOT met (", summary);
            StringAssert.Contains(f.Discretisations + " discretisations", summary);
        }

        [Test]
        public void AFitShowsTheProgressOfEachRunAndStopsWhenCancelled()
        {
            var sphere = new AnalyticSurfaceSpec(AnalyticKind.SphereCap, Radius, -3, 3, -3, 3);
            var input = new PatternInput { Surface = sphere, OnSurface = new SurfacePatternInputs { MaxDeviation = 0.02 } };
            var plain = ComponentSolvers.Pattern(input);
            var texts = new List<string>();
            var watched = ComponentSolvers.Pattern(input, t => texts.Add(t), System.Threading.CancellationToken.None);
            Assert.IsEmpty(watched.Errors);
            Assert.IsFalse(watched.Cancelled);
            CollectionAssert.AreEqual(plain.Points, watched.Points);
            // One "run k: 1/6 samples 0%" per discretisation the fit says it ran, in order.
            var starts = texts.Where(t => t.EndsWith(": 1/6 samples 0%", StringComparison.Ordinal)).ToList();
            int runs = (int)watched.Fit.Value.Discretisations;
            Assert.GreaterOrEqual(runs, 3);
            CollectionAssert.AreEqual(Enumerable.Range(1, runs).Select(k => "run " + k + ": 1/6 samples 0%"), starts);
            Assert.AreEqual("run " + runs + ": 6/6 report 100%", texts.Last());
            for (int k = 1; k < texts.Count; k++) Assert.AreNotEqual(texts[k - 1], texts[k]);

            // Cancelled while the third run starts: no points, the flag, an error naming the stage.
            using (var source = new System.Threading.CancellationTokenSource())
            {
                var cancelled = ComponentSolvers.Pattern(input, t => { if (t == "run 3: 1/6 samples 0%") source.Cancel(); }, source.Token);
                Assert.IsTrue(cancelled.Cancelled);
                Assert.IsEmpty(cancelled.Points);
                Assert.IsNull(cancelled.Fit);
                StringAssert.StartsWith(ProgressText.Cancelled + ": ", cancelled.Errors.Single());
                StringAssert.Contains("samples", cancelled.Errors.Single());
            }
            using (var surface = sphere.CreateNative())
            using (var source = new System.Threading.CancellationTokenSource())
            {
                source.Cancel();
                Assert.Throws<OperationCanceledException>(() => Pattern.ForSurface(surface, "fit:0.02", null, null, source.Token).Dispose());
                // A handler that throws stops the fit; its exception comes back wrapped.
                var thrown = Assert.Throws<InvalidOperationException>(() =>
                    Pattern.ForSurface(surface, "fit:0.02", null, p => { throw new ArgumentException("boom"); }, System.Threading.CancellationToken.None).Dispose());
                StringAssert.Contains("boom", thrown.Message);
            }
        }

        [Test]
        public void ACommandsFitRunsOnAWorkerShowsEachTextOnceAndStopsWhenCancelled()
        {
            var sphere = new AnalyticSurfaceSpec(AnalyticKind.SphereCap, Radius, -3, 3, -3, 3);
            var input = new PatternInput { Surface = sphere, OnSurface = new SurfacePatternInputs { MaxDeviation = 0.02 } };
            int caller = System.Threading.Thread.CurrentThread.ManagedThreadId;
            var shown = new List<string>();
            int pumps = 0, workerThread = -1;
            var output = ForegroundWait.Run((progress, token) =>
            {
                workerThread = System.Threading.Thread.CurrentThread.ManagedThreadId;
                return ComponentSolvers.Pattern(input, progress, token);
            }, System.Threading.CancellationToken.None, t =>
            {
                Assert.AreEqual(caller, System.Threading.Thread.CurrentThread.ManagedThreadId);
                shown.Add(t);
            }, () => pumps++);
            Assert.AreNotEqual(caller, workerThread);
            Assert.IsEmpty(output.Errors);
            CollectionAssert.AreEqual(ComponentSolvers.Pattern(input).Points, output.Points);
            for (int k = 1; k < shown.Count; k++) Assert.AreNotEqual(shown[k - 1], shown[k]);
            Assert.IsTrue(shown.All(t => t.StartsWith("run ", StringComparison.Ordinal)));

            // The pump is where the host sees Escape: cancelling there stops the work.
            using (var source = new System.Threading.CancellationTokenSource())
            {
                var started = new System.Threading.ManualResetEventSlim();
                var cancelled = ForegroundWait.Run((progress, token) =>
                {
                    started.Set();
                    // Work that runs until it is cancelled (a fit of a tolerance far too small).
                    while (!token.IsCancellationRequested) System.Threading.Thread.Sleep(1);
                    return ComponentSolvers.Pattern(input, progress, token);
                }, source.Token, null, () => { if (started.IsSet) source.Cancel(); });
                Assert.IsTrue(cancelled.Cancelled);
                Assert.IsEmpty(cancelled.Points);
            }
            // What the work throws comes back as it was thrown.
            Assert.Throws<ArgumentException>(() => ForegroundWait.Run<int>((p, t) => { throw new ArgumentException("x"); },
                System.Threading.CancellationToken.None, null, null));
        }

        [Test]
        public void ARejectedIterationCarriesItsReasonsAndNoPoints()
        {
            var rejected = PatternOutput.Rejected(new[] { "unknown generator 'hexx'", "second" });
            CollectionAssert.AreEqual(new[] { "unknown generator 'hexx'", "second" }, rejected.Errors);
            Assert.IsEmpty(rejected.Points);
            Assert.IsNull(rejected.Fit);
            Assert.AreEqual(string.Empty, rejected.Spec);
            // Never an empty error list: the component would otherwise show nothing at all.
            Assert.AreEqual(1, PatternOutput.Rejected(null).Errors.Count);
            Assert.AreEqual(1, PatternOutput.Rejected(new string[0]).Errors.Count);
        }

        [Test]
        public void ThePatternSolverRunsTheComposedSpecOnTheSurface()
        {
            var sphere = new AnalyticSurfaceSpec(AnalyticKind.SphereCap, Radius, -3, 3, -3, 3);
            var output = ComponentSolvers.Pattern(new PatternInput
            {
                Generator = new PatternGenerator { Kind = GeneratorKind.Random, CountU = 60, Seed = 4 },
                Surface = sphere,
                OnSurface = new SurfacePatternInputs { Relax = 4 },
            });
            Assert.IsEmpty(output.Errors);
            Assert.AreEqual("relax:4:random:60:seed=4", output.Spec);
            Assert.IsNull(output.Fit);
            using (var surface = sphere.CreateNative())
            using (var direct = Pattern.ForSurface(surface, "relax:4:random:60:seed=4"))
                CollectionAssert.AreEqual(direct.Points.ToArray(), output.Points);

            var fit = ComponentSolvers.Pattern(new PatternInput { Surface = sphere, OnSurface = new SurfacePatternInputs { MaxDeviation = 0.02 } });
            Assert.IsEmpty(fit.Errors);
            Assert.AreEqual("fit:0.02", fit.Spec);
            Assert.IsTrue(fit.Fit.HasValue && fit.Fit.Value.Met == 1);
            Assert.IsEmpty(fit.Warnings);

            var noSurface = ComponentSolvers.Pattern(new PatternInput { OnSurface = new SurfacePatternInputs { Relax = 3 } });
            StringAssert.Contains("needs a surface", noSurface.Errors.Single());
            var specNoSurface = ComponentSolvers.Pattern(new PatternInput { Spec = "fit:0.1" });
            StringAssert.Contains("needs a surface", specNoSurface.Errors.Single());
            var bad = ComponentSolvers.Pattern(new PatternInput { Surface = sphere, Spec = "relax:x:hex:4x4" });
            StringAssert.Contains("relax:x", bad.Errors.Single());
        }
    }
}
