// The Grasshopper components' solve logic as plain data in, plain data out. The components
// (Tpi.Grasshopper) only convert RhinoCommon types to these inputs and the outputs back, and
// run Solve on a worker task. Solve never throws for bad input: the library's messages come
// back in Errors (and become the component's runtime messages).
using System;
using System.Collections.Generic;
using System.Linq;
using System.Threading;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Inputs of "TPI Discretise".</summary>
    public sealed class DiscretiseInput
    {
        /// <summary>The surface.</summary>
        public SurfaceSpec Surface { get; set; }
        /// <summary>The pattern points: normalised (s, t), or (u, v) in the surface's domain when <see cref="PointsInSurfaceDomain"/>.</summary>
        public IList<PatternPoint> Points { get; set; }
        /// <summary>True if <see cref="Points"/> are (u, v) in the surface's domain (e.g. from Surface.ClosestPoint).</summary>
        public bool PointsInSurfaceDomain { get; set; }
        /// <summary>Options; null for the library's defaults.</summary>
        public DiscretisationOptions Options { get; set; }
    }

    /// <summary>Outputs of "TPI Discretise".</summary>
    public sealed class DiscretiseOutput
    {
        /// <summary>The whole mesh (passed on to "TPI Quality"); null on failure.</summary>
        public MeshData Mesh { get; internal set; }
        /// <summary>One closed polyline per facet.</summary>
        public Vec3[][] Polylines { get; internal set; }
        /// <summary>The tangent plane of each facet.</summary>
        public FacetPlane[] Planes { get; internal set; }
        /// <summary>The triangle mesh with one n-gon per facet.</summary>
        public NgonMesh NgonMesh { get; internal set; }
        /// <summary>The quality report as JSON ("" when switched off).</summary>
        public string QualityJson { get; internal set; }
        /// <summary>The pattern points actually used (normalised).</summary>
        public PatternPoint[] Points { get; internal set; }
        /// <summary>Problems that stopped the solve.</summary>
        public List<string> Errors { get; private set; }
        /// <summary>Problems worth a look (diagnostics, flagged facets, clamped points).</summary>
        public List<string> Warnings { get; private set; }
        /// <summary>True if a mesh was made.</summary>
        public bool Success { get { return Mesh != null; } }
        /// <summary>True if the solve was cancelled (no mesh; Errors says where it stopped).</summary>
        public bool Cancelled { get; internal set; }

        internal DiscretiseOutput() { Errors = new List<string>(); Warnings = new List<string>(); }
    }

    /// <summary>Inputs of "TPI Pattern": a generator, or a spec string that wins when not empty.</summary>
    public sealed class PatternInput
    {
        /// <summary>The generator and its parameters.</summary>
        public PatternGenerator Generator { get; set; }
        /// <summary>A spec in the library's syntax ("hex:12x12", "grid:spacing=0.05", or one made on the surface such as "relax:20:random:500"); overrides Generator.</summary>
        public string Spec { get; set; }
        /// <summary>The surface, needed by a pattern made on it (a spec such as fit:D or relax:N:..., or <see cref="OnSurface"/>); may be null otherwise.</summary>
        public SurfaceSpec Surface { get; set; }
        /// <summary>Tolerance, relaxation, alignment and density, combined with the generator (or the spec) into one spec; null for none.</summary>
        public SurfacePatternInputs OnSurface { get; set; }
        /// <summary>Options of the discretisations a pattern made on the surface runs; null for the library's defaults.</summary>
        public DiscretisationOptions Options { get; set; }
    }

    /// <summary>Outputs of "TPI Pattern".</summary>
    public sealed class PatternOutput
    {
        /// <summary>The points (normalised).</summary>
        public PatternPoint[] Points { get; internal set; }
        /// <summary>The spec that made them.</summary>
        public string Spec { get; internal set; }
        /// <summary>Problems that stopped the solve.</summary>
        public List<string> Errors { get; private set; }
        /// <summary>Problems worth a look (a tolerance that was not met).</summary>
        public List<string> Warnings { get; private set; }
        /// <summary>For a tolerance-driven pattern (fit:D), how the fit went; else null.</summary>
        public FitReport? Fit { get; internal set; }
        /// <summary>True if the solve was cancelled (no points; Errors says where it stopped).</summary>
        public bool Cancelled { get; internal set; }
        internal PatternOutput() { Errors = new List<string>(); Warnings = new List<string>(); Points = new PatternPoint[0]; Spec = string.Empty; }

        /// <summary>An output with no points that carries why the inputs could not be used (the task-capable component's result for an iteration it cannot solve).</summary>
        public static PatternOutput Rejected(IEnumerable<string> errors)
        {
            var output = new PatternOutput();
            if (errors != null) output.Errors.AddRange(errors);
            if (output.Errors.Count == 0) output.Errors.Add("no pattern: the inputs could not be used");
            return output;
        }

        /// <summary>
        /// One line for a command prompt: the point count and the spec, and for a fit the
        /// largest vertex deviation against the tolerance and whether it was met.
        /// </summary>
        public string Summary()
        {
            var c = System.Globalization.CultureInfo.InvariantCulture;
            var line = string.Format(c, "{0} points ({1})", Points.Length, Spec);
            if (Fit.HasValue)
            {
                var f = Fit.Value;
                line += string.Format(c, "; largest vertex deviation {0:G4} for a tolerance of {1:G4}: {2} ({3} discretisations)",
                    f.MaxDeviation, f.Tolerance, f.Met == 1 ? "met" : "NOT met", f.Discretisations);
            }
            return line;
        }
    }

    /// <summary>Outputs of "TPI Quality" (one entry per facet, plus the report).</summary>
    public sealed class QualityOutput
    {
        /// <summary>Largest vertex distance from the facet's plane (model units).</summary>
        public double[] Planarity { get; internal set; }
        /// <summary>Number of sides of each facet.</summary>
        public int[] Sides { get; internal set; }
        /// <summary>TPI_FACET_* bits of each facet.</summary>
        public int[] Flags { get; internal set; }
        /// <summary>Flag names of each facet ("" when none), e.g. "NonConvex, Diagnostic".</summary>
        public string[] FlagNames { get; internal set; }
        /// <summary>Diagnostic kinds naming each facet ("" when none).</summary>
        public string[] Diagnostics { get; internal set; }
        /// <summary>Area of each facet.</summary>
        public double[] Areas { get; internal set; }
        /// <summary>Largest vertex distance from the surface (model units; NaN without a report).</summary>
        public double MaxDeviation { get; internal set; }
        /// <summary>Mean vertex distance from the surface (NaN without a report).</summary>
        public double MeanDeviation { get; internal set; }
        /// <summary>Largest planarity error relative to the bounding-box diagonal (NaN without a report).</summary>
        public double MaxPlanarityError { get; internal set; }
        /// <summary>Facet count per number of sides.</summary>
        public SortedDictionary<int, int> SideHistogram { get; internal set; }
        /// <summary>The report as JSON ("" without a report).</summary>
        public string Json { get; internal set; }
        /// <summary>Open, non-simple or overlapping facets: 0 for a valid mesh (-1 without a report).</summary>
        public long InvalidFacets { get; internal set; }
    }

    /// <summary>The components' solve functions.</summary>
    public static class ComponentSolvers
    {
        /// <summary>
        /// "TPI Discretise". The task-capable component's one result per solve: when reading the inputs failed
        /// (<paramref name="input"/> null) an output without a mesh that carries
        /// <paramref name="errors"/> and <paramref name="warnings"/>, else the discretisation
        /// with <paramref name="warnings"/> (from reading the inputs) in front of its own.
        /// So the pre-solve pass adds exactly one task per iteration, valid or not, and the
        /// results never shift by one iteration.
        /// </summary>
        public static DiscretiseOutput DiscretiseOrReject(DiscretiseInput input, IEnumerable<string> errors, IEnumerable<string> warnings)
        {
            return DiscretiseOrReject(input, errors, warnings, null, CancellationToken.None);
        }

        /// <summary>
        /// <see cref="DiscretiseOrReject(DiscretiseInput, IEnumerable{string}, IEnumerable{string})"/>
        /// that shows its progress through <paramref name="progress"/> (texts of
        /// <see cref="ProgressText.Format"/>, each new one once; may be null) and stops when
        /// <paramref name="cancel"/> is cancelled: then the output has no mesh,
        /// <see cref="DiscretiseOutput.Cancelled"/> set and an error naming the stage.
        /// </summary>
        public static DiscretiseOutput DiscretiseOrReject(DiscretiseInput input, IEnumerable<string> errors, IEnumerable<string> warnings, Action<string> progress, CancellationToken cancel)
        {
            DiscretiseOutput output;
            if (input == null)
            {
                output = new DiscretiseOutput();
                if (errors != null) output.Errors.AddRange(errors);
            }
            else
            {
                output = Discretise(input, progress, cancel);
            }
            if (warnings != null) output.Warnings.InsertRange(0, warnings);
            return output;
        }

        /// <summary>"TPI Discretise": problems are reported in the output, never thrown.</summary>
        public static DiscretiseOutput Discretise(DiscretiseInput input)
        {
            return Discretise(input, null, CancellationToken.None);
        }

        /// <summary>
        /// "TPI Discretise" with progress texts and cancelling (see
        /// <see cref="DiscretiseOrReject(DiscretiseInput, IEnumerable{string}, IEnumerable{string}, Action{string}, CancellationToken)"/>).
        /// </summary>
        public static DiscretiseOutput Discretise(DiscretiseInput input, Action<string> progress, CancellationToken cancel)
        {
            var output = new DiscretiseOutput();
            if (input == null || input.Surface == null) { output.Errors.Add("no surface"); return output; }
            if (input.Points == null || input.Points.Count == 0) { output.Errors.Add("no pattern points"); return output; }
            try
            {
                using (var surface = input.Surface.CreateNative())
                {
                    var domain = input.PointsInSurfaceDomain ? surface.Domain : new Domain(0, 1, 0, 1);
                    var points = new List<PatternPoint>(input.Points.Count);
                    for (int i = 0; i < input.Points.Count; i++)
                    {
                        PatternPoint p;
                        string error;
                        if (InputValidation.TryNormalise(domain, input.Points[i].S, input.Points[i].T, out p, out error)) points.Add(p);
                        else output.Errors.Add("point " + i + ": " + error);
                    }
                    if (output.Errors.Count > 0) return output;
                    Action<DiscretisationProgress> report = null;
                    if (progress != null) report = new ProgressMessages(progress).Report;
                    using (var pattern = Native.Pattern.FromPoints(points))
                    using (var mesh = Discretisation.Create(surface, pattern, input.Options, report, cancel))
                    {
                        var data = MeshData.From(mesh);
                        data.Source = new DiscreteSurfaceDocument { Surface = input.Surface, Points = points, Options = input.Options };
                        output.Points = points.ToArray();
                        output.Mesh = data;
                        output.Polylines = MeshConversion.FacetPolylines(data);
                        output.Planes = (FacetPlane[])data.Planes.Clone();
                        output.NgonMesh = MeshConversion.ToNgonMesh(data);
                        output.QualityJson = data.QualityJson ?? string.Empty;
                        int flagged = data.Flags.Count(f => f != FacetFlags.None);
                        if (flagged > 0) output.Warnings.Add(flagged + " of " + data.FacetCount + " facets are flagged (see TPI Quality)");
                        string far = data.Quality.HasValue ? QualityWarnings.FarVertex(data.Quality.Value) : null;
                        if (far != null) output.Warnings.Add(far);
                        if (data.Diagnostics.Length > 0)
                            output.Warnings.Add(data.Diagnostics.Select(d => d.Diagnostic).Distinct().Count() + " diagnostics: " + data.DiagnosticsJson);
                    }
                }
            }
            catch (TpiException e)
            {
                output.Mesh = null;
                output.Errors.Add(TpiLibrary.StatusName(e.Status) + ": " + e.NativeMessage);
            }
            catch (OperationCanceledException e)
            {
                output.Mesh = null;
                output.Cancelled = true;
                output.Errors.Add(ProgressText.Cancelled + ": " + e.Message);
            }
            return output;
        }

        /// <summary>"TPI Pattern".</summary>
        public static PatternOutput Pattern(PatternInput input)
        {
            return Pattern(input, null, CancellationToken.None);
        }

        /// <summary>
        /// "TPI Pattern" showing the progress of the discretisations a pattern made on the
        /// surface runs through <paramref name="progress"/> (texts of
        /// <see cref="ProgressText.FormatRun"/>, each new one once; may be null) and stopping
        /// when <paramref name="cancel"/> is cancelled: then the output has no points,
        /// <see cref="PatternOutput.Cancelled"/> set and an error naming the stage.
        /// </summary>
        public static PatternOutput Pattern(PatternInput input, Action<string> progress, CancellationToken cancel)
        {
            var output = new PatternOutput();
            try
            {
                bool bySpec = input != null && !string.IsNullOrWhiteSpace(input.Spec);
                var generator = input == null || input.Generator == null ? new PatternGenerator() : input.Generator;
                string spec = bySpec ? input.Spec.Trim() : generator.ToSpec();
                var onSurface = input == null ? null : input.OnSurface;
                if (onSurface != null && onSurface.Any)
                {
                    string error;
                    if (!onSurface.TryCompose(spec, out spec, out error)) { output.Errors.Add(error); return output; }
                }
                if (input != null && input.Surface != null)
                {
                    // Any spec, surface-aware or not, through the one entry point that knows the surface.
                    Action<DiscretisationProgress> report = null;
                    if (progress != null) report = new ProgressMessages(progress, true).Report;
                    using (var surface = input.Surface.CreateNative())
                    using (var pattern = Native.Pattern.ForSurface(surface, spec, input.Options, report, cancel))
                    {
                        output.Points = pattern.Points.ToArray();
                        output.Fit = pattern.Fit;
                    }
                    if (output.Fit.HasValue && output.Fit.Value.Met == 0)
                    {
                        var f = output.Fit.Value;
                        output.Warnings.Add(string.Format(System.Globalization.CultureInfo.InvariantCulture,
                            "the tolerance {0} is not met: the closest pattern found has a vertex {1} off the surface (exact planes cannot meet a tolerance where neighbouring tangent planes are nearly parallel: try adjusted planes)",
                            f.Tolerance, f.MaxDeviation));
                    }
                }
                else if ((onSurface != null && onSurface.Any) || SurfacePatternInputs.NeedsSurface(spec))
                {
                    output.Errors.Add("a tolerance, relaxation, alignment or density needs a surface (S)");
                    return output;
                }
                else
                {
                    using (var pattern = bySpec ? Native.Pattern.FromSpec(spec) : generator.Create())
                        output.Points = pattern.Points.ToArray();
                }
                output.Spec = spec;
            }
            catch (TpiException e)
            {
                output.Errors.Add(TpiLibrary.StatusName(e.Status) + ": " + e.NativeMessage);
            }
            catch (OperationCanceledException e)
            {
                output.Points = new PatternPoint[0];
                output.Fit = null;
                output.Cancelled = true;
                output.Errors.Add(ProgressText.Cancelled + ": " + e.Message);
            }
            return output;
        }

        /// <summary>"TPI Quality".</summary>
        public static QualityOutput Quality(MeshData mesh)
        {
            if (mesh == null) throw new ArgumentNullException("mesh");
            var perFacet = new List<string>[mesh.FacetCount];
            foreach (var entry in mesh.Diagnostics)
            {
                if (entry.Point == DiagnosticEntry.NoPoint || entry.Point >= mesh.FacetCount) continue;
                var list = perFacet[entry.Point] ?? (perFacet[entry.Point] = new List<string>());
                var name = entry.Kind.ToString();
                if (!list.Contains(name)) list.Add(name);
            }
            var histogram = new SortedDictionary<int, int>();
            foreach (var s in mesh.FacetSizes) { int n; histogram.TryGetValue(s, out n); histogram[s] = n + 1; }
            var q = mesh.Quality;
            return new QualityOutput
            {
                Planarity = MeshConversion.PlanarityErrors(mesh),
                Sides = MeshConversion.SideCounts(mesh),
                Flags = mesh.Flags.Select(f => (int)f).ToArray(),
                FlagNames = mesh.Flags.Select(f => f == FacetFlags.None ? string.Empty : f.ToString()).ToArray(),
                Diagnostics = perFacet.Select(l => l == null ? string.Empty : string.Join(", ", l)).ToArray(),
                Areas = MeshConversion.FacetAreas(mesh),
                MaxDeviation = q.HasValue ? q.Value.MaxDeviation : double.NaN,
                InvalidFacets = q.HasValue ? (long)q.Value.InvalidFacets : -1,
                MeanDeviation = q.HasValue ? q.Value.MeanDeviation : double.NaN,
                MaxPlanarityError = q.HasValue ? q.Value.MaxPlanarityError : double.NaN,
                SideHistogram = histogram,
                Json = mesh.QualityJson ?? string.Empty,
            };
        }
    }
}
