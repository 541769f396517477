// Checked against: Grasshopper 8 (grasshopper-stubs-typed 8.20.25157; GH_TaskCapableComponent<T>
// and the nested param managers, which the stubs omit, against the Grasshopper SDK). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Collections.Generic;
using System.Drawing;
using System.Linq;
using System.Threading.Tasks;
using Grasshopper.Kernel;
using Rhino.Geometry;
using Tpi.Logic;

namespace Tpi.GhComponents
{
    /// <summary>"TPI Pattern": the pattern generators with their parameters, and the patterns made on a surface (tolerance, relaxation, alignment, density; logic in Tpi.Logic).</summary>
    public sealed class PatternComponent : GH_TaskCapableComponent<PatternOutput>
    {
        /// <summary>Made by Grasshopper.</summary>
        public PatternComponent()
            : base("TPI Pattern", "TPIPat", "Pattern points in the unit square from a generator (grid, hex, jitter, random, poisson) or a spec such as hex:12x12; on a surface also tolerance-driven, relaxed, aligned or density-graded (specs such as fit:0.01 or relax:20:random:500).", Tab.Name, Tab.Pattern)
        {
        }

        /// <summary>Never change: old .gh files find the component by it.</summary>
        public override Guid ComponentGuid { get { return new Guid("B7F25D90-3C1E-4A84-8E6B-0F9A2D4C5B17"); } }

        /// <inheritdoc/>
        protected override Bitmap Icon { get { return Icons.Load("pattern"); } }

        /// <inheritdoc/>
        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        /// <inheritdoc/>
        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddTextParameter("Generator", "G", "grid, hex, jitter, random or poisson.", GH_ParamAccess.item, "hex");
            pManager.AddIntegerParameter("CountU", "U", "Points in u (the count for random).", GH_ParamAccess.item, 10);
            pManager.AddIntegerParameter("CountV", "V", "Points in v.", GH_ParamAccess.item, 10);
            pManager.AddNumberParameter("Jitter", "J", "Jitter amount in [0, 1].", GH_ParamAccess.item, 0.5);
            pManager.AddNumberParameter("Radius", "R", "Poisson-disk radius in the unit square (>= 0.001).", GH_ParamAccess.item, 0.08);
            pManager.AddIntegerParameter("Seed", "Sd", "Random seed.", GH_ParamAccess.item, 1);
            pManager.AddTextParameter("Spec", "Sp", "A generator spec (e.g. grid:spacing=0.05); overrides the inputs above.", GH_ParamAccess.item);
            pManager.AddSurfaceParameter("Surface", "S", "Optional surface to place the points on; needed by the inputs below (patterns made on the surface).", GH_ParamAccess.item);
            pManager.AddNumberParameter("Tolerance", "D", "Tolerance-driven pattern (fit:D): few points whose mesh keeps every vertex within D model units of S. 0: off. Replaces the generator.", GH_ParamAccess.item, 0.0);
            pManager.AddIntegerParameter("Relax", "N", "Lloyd iterations on S (areas measured on the surface) so that the panels come out even. 0: off.", GH_ParamAccess.item, 0);
            pManager.AddTextParameter("Align", "Al", "Lay the hex or grid generator along a direction field on S: principal, asymptotic, uv:ANGLE or a direction field's JSON. Empty: off.", GH_ParamAccess.item);
            pManager.AddTextParameter("Density", "De", "A density field's JSON (attractors, curves, curvature; docs/formats.md): a graded pattern on S, replacing the generator. Empty: off.", GH_ParamAccess.item);
            for (int i = 0; i < 12; i++) pManager[i].Optional = true;
        }

        /// <inheritdoc/>
        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddPointParameter("UV", "UV", "Pattern points as (s, t, 0) in the unit square.", GH_ParamAccess.list);
            pManager.AddPointParameter("Points", "P", "Pattern points on the surface (when S is given).", GH_ParamAccess.list);
            pManager.AddTextParameter("Spec", "Sp", "The pattern spec that made the points (as tpi discretise --pattern takes it).", GH_ParamAccess.item);
            pManager.AddNumberParameter("Deviation", "Dev", "For a tolerance-driven pattern: the largest vertex deviation of its mesh (model units).", GH_ParamAccess.item);
        }

        /// <inheritdoc/>
        protected override void SolveInstance(IGH_DataAccess DA)
        {
            var problem = Native.Problem;
            if (problem != null) { AddRuntimeMessage(GH_RuntimeMessageLevel.Error, problem); return; }
            List<string> errors;
            if (InPreSolve)
            {
                // One task per iteration, valid input or not, so GetSolveResults stays in step. A
                // fit or a relaxation runs many discretisations (seconds on a large surface): on a
                // worker, so the canvas stays responsive. Grasshopper cancels the token when the
                // solution is aborted (Escape) or expires again; the library stops where the
                // running stage of the running discretisation ends.
                var input = CollectInput(DA, out errors);
                var cancel = CancelToken;
                TaskList.Add(input == null
                    ? Task.FromResult(PatternOutput.Rejected(errors))
                    : Task.Run(() => ComponentSolvers.Pattern(input, ShowProgress, cancel), cancel));
                return;
            }

            PatternOutput output;
            if (!GetSolveResults(DA, out output))
            {
                var input = CollectInput(DA, out errors);
                output = input == null ? PatternOutput.Rejected(errors)
                    : ComponentSolvers.Pattern(input, ShowProgress, System.Threading.CancellationToken.None);
            }
            if (output == null) return;
            // Under the component: the progress while it runs, then the count, or that it was cancelled.
            Message = output.Cancelled ? ProgressText.Cancelled : output.Errors.Count == 0 ? output.Points.Length + " points" : null;
            foreach (var e in output.Errors) AddRuntimeMessage(GH_RuntimeMessageLevel.Error, e);
            if (output.Errors.Count > 0) return;
            foreach (var w in output.Warnings) AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, w);
            Surface surface = null;
            DA.GetData(7, ref surface);
            if (output.Fit.HasValue) DA.SetData(3, output.Fit.Value.MaxDeviation);
            DA.SetDataList(0, output.Points.Select(p => new Point3d(p.S, p.T, 0)));
            if (surface != null) DA.SetDataList(1, output.Points.Select(p => GhConvert.PointAt(surface, p)));
            DA.SetData(2, output.Spec);
        }

        void ShowProgress(string text)
        {
            SolveProgress.Show(this, text);
        }

        /// <summary>
        /// Reads the inputs on the UI thread (RhinoCommon calls stay off the worker); null with
        /// the reasons in <paramref name="errors"/> when they cannot be used.
        /// </summary>
        PatternInput CollectInput(IGH_DataAccess DA, out List<string> errors)
        {
            errors = new List<string>();
            string name = "hex", spec = null;
            int countU = 10, countV = 10, seed = 1;
            double amount = 0.5, radius = 0.08;
            Surface surface = null;
            DA.GetData(0, ref name);
            DA.GetData(1, ref countU);
            DA.GetData(2, ref countV);
            DA.GetData(3, ref amount);
            DA.GetData(4, ref radius);
            DA.GetData(5, ref seed);
            DA.GetData(6, ref spec);
            DA.GetData(7, ref surface);
            double tolerance = 0.0;
            int relax = 0;
            string align = null, density = null;
            DA.GetData(8, ref tolerance);
            DA.GetData(9, ref relax);
            DA.GetData(10, ref align);
            DA.GetData(11, ref density);
            var onSurface = new SurfacePatternInputs { MaxDeviation = tolerance, Relax = relax, Align = align, DensityJson = density };
            SurfaceSpec surfaceSpec = null;
            if (surface != null)
            {
                surfaceSpec = GhConvert.ToSpec(surface);
                if (surfaceSpec == null && (onSurface.Any || SurfacePatternInputs.NeedsSurface(spec)))
                {
                    errors.Add("the surface has no NURBS form");
                    return null;
                }
            }
            GeneratorKind kind;
            if (!PatternGenerator.TryParseKind(name, out kind) && string.IsNullOrWhiteSpace(spec))
            {
                errors.Add("unknown generator '" + name + "': use grid, hex, jitter, random or poisson");
                return null;
            }
            var generator = new PatternGenerator { Kind = kind, CountU = countU, CountV = countV, Amount = amount, Radius = radius, Seed = (ulong)Math.Max(0, seed) };
            return new PatternInput { Generator = generator, Spec = spec, Surface = surfaceSpec, OnSurface = onSurface };
        }
    }
}
