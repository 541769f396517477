// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Collections.Generic;
using Rhino;
using Rhino.Commands;
using Rhino.DocObjects;
using ComponentIndexType = Rhino.Geometry.ComponentIndexType;
using Rhino.Input;
using Rhino.Input.Custom;
using Tpi.Logic;
using PatternPoint = Tpi.Native.PatternPoint;

namespace Tpi.RhinoPlugIn
{
    /// <summary>
    /// TpiDiscreteSurface: pick a surface or a polysurface (its faces joined as one surface; one
    /// face of it with Ctrl+Shift), choose a generator or existing points, get a live discrete
    /// surface.
    /// </summary>
    public sealed class TpiDiscreteSurfaceCommand : Command
    {
        /// <inheritdoc/>
        public override string EnglishName { get { return "TpiDiscreteSurface"; } }

        /// <inheritdoc/>
        protected override Result RunCommand(RhinoDoc doc, RunMode mode)
        {
            ObjRef surfaceRef;
            var rc = RhinoGet.GetOneObject("Select a surface or polysurface to discretise", false,
                ObjectType.Surface | ObjectType.Brep, out surfaceRef);
            if (rc != Result.Success) return rc;
            // A face picked on a polysurface (Ctrl+Shift) is that face; a whole polysurface is
            // all its faces joined (PolysurfaceSpec.FromFaces refuses trimmed faces with a reason).
            bool pickedFace = surfaceRef.GeometryComponentIndex.ComponentIndexType == ComponentIndexType.BrepFace;
            var brep = pickedFace ? null : surfaceRef.Brep();
            bool wholePolysurface = brep != null && brep.Faces != null && brep.Faces.Count > 1;
            var surface = wholePolysurface ? null : surfaceRef.Surface();
            SurfaceSpec spec;
            if (wholePolysurface)
            {
                string error;
                spec = Tpi.Plugin.SurfaceSpecs.FromBrep(brep, out error);
                if (spec == null) { RhinoApp.WriteLine("TPI: " + error); return Result.Failure; }
            }
            else
            {
                spec = RhinoConvert.ToSpec(surface);
                if (spec == null) { RhinoApp.WriteLine("TPI: the surface has no NURBS form."); return Result.Failure; }
            }

            var generator = new PatternGenerator();
            var onSurface = new SurfacePatternInputs();
            bool existingPoints;
            rc = CommandOptions.GetGenerator("Pattern", generator, true, out existingPoints, null, onSurface);
            if (rc != Result.Success) return rc;

            // Exact tangent planes, or adjusted ones where exact planes cannot make a facet valid.
            var adjusted = new OptionToggle(false, "Exact", "Adjusted");
            while (true)
            {
                var get = new GetOption();
                get.SetCommandPrompt("Facet planes (Enter accepts)");
                get.AcceptNothing(true);
                get.AddOptionToggle("Planes", ref adjusted);
                var result = get.Get();
                if (result == GetResult.Nothing) break;
                if (result != GetResult.Option) return get.CommandResult();
            }
            var options = Tpi.Native.DiscretisationOptions.Default();
            options.Planes = adjusted.CurrentValue ? Tpi.Native.PlaneMode.Adjusted : Tpi.Native.PlaneMode.Exact;

            List<PatternPoint> points;
            string generatorSpec = string.Empty;
            if (existingPoints && wholePolysurface)
            {
                RhinoApp.WriteLine("TPI: points in space cannot be placed on a polysurface yet: use a generator, or pick one face (Ctrl+Shift).");
                return Result.Failure;
            }
            if (existingPoints)
            {
                if (onSurface.Any) RhinoApp.WriteLine("TPI: Tolerance, Relax and Align make their own points: ignored for existing points.");
                ObjRef[] pointRefs;
                rc = RhinoGet.GetMultipleObjects("Select pattern points (projected onto the surface)", false, ObjectType.Point, out pointRefs);
                if (rc != Result.Success) return rc;
                points = new List<PatternPoint>();
                foreach (var r in pointRefs)
                {
                    PatternPoint st;
                    string error;
                    var point = r.Point();
                    if (point == null) continue;
                    if (!RhinoConvert.TryNormalisedClosest(surface, point.Location, out st, out error))
                    {
                        RhinoApp.WriteLine("TPI: skipped a point: " + error);
                        continue;
                    }
                    points.Add(st);
                }
            }
            else
            {
                // A pattern made on the surface is made with the chosen planes (they decide what a fit measures).
                var input = new PatternInput
                {
                    Generator = generator,
                    Surface = onSurface.Any ? spec : null,
                    OnSurface = onSurface,
                    Options = options,
                };
                // A fit or a relaxation runs many discretisations: on a worker, Escape cancels it.
                var output = Escapable.Run("TPI pattern", (progress, cancel) => ComponentSolvers.Pattern(input, progress, cancel));
                if (output.Errors.Count > 0) RhinoApp.WriteLine("TPI: " + output.Errors[0]);
                if (output.Cancelled) return Result.Cancel;
                if (output.Errors.Count > 0) return Result.Failure;
                foreach (var w in output.Warnings) RhinoApp.WriteLine("TPI: " + w);
                if (onSurface.Any) RhinoApp.WriteLine("TPI: pattern " + output.Summary());
                points = new List<PatternPoint>(output.Points);
                generatorSpec = output.Spec;
            }

            try
            {
                var document = new DiscreteSurfaceDocument
                {
                    Surface = spec,
                    Points = points,
                    Options = options,
                    Generator = generatorSpec,
                    SourceSurfaceId = surfaceRef.ObjectId,
                    // A face picked on a polysurface: the watcher follows that face.
                    SourceFaceIndex = surfaceRef.GeometryComponentIndex.ComponentIndexType == ComponentIndexType.BrepFace
                        ? surfaceRef.GeometryComponentIndex.Index : -1,
                };
                using (var state = new DiscreteSurfaceState(document))
                {
                    DiscreteSurfaceObject.Add(doc, state, document);
                    RhinoApp.WriteLine("TPI: {0} planar panels, max deviation {1:G4}.", state.Mesh.FacetCount,
                        state.Mesh.Quality.HasValue ? state.Mesh.Quality.Value.MaxDeviation : double.NaN);
                    string far = state.Mesh.Quality.HasValue ? QualityWarnings.FarVertex(state.Mesh.Quality.Value) : null;
                    if (far != null) RhinoApp.WriteLine("TPI: " + far);
                }
            }
            catch (Tpi.Native.TpiException e)
            {
                RhinoApp.WriteLine("TPI: " + e.NativeMessage);
                return Result.Failure;
            }
            doc.Views.Redraw();
            return Result.Success;
        }
    }

    /// <summary>Command-line options shared by the commands.</summary>
    internal static class CommandOptions
    {
        static readonly string[] Generators = { "Grid", "Hex", "Jitter", "Random", "Poisson" };

        /// <summary>
        /// Lets the user pick a generator and its parameters (Enter accepts). With
        /// <paramref name="offerExisting"/>, the option "ExistingPoints" ends the prompt with
        /// <paramref name="existingPoints"/> true. With <paramref name="onSurface"/>, also the
        /// patterns made on the surface (issue 15): Tolerance (a fit: the fewest points whose
        /// panels stay within it of the surface; 0 for none), Relax (Lloyd iterations on the
        /// surface) and Align (the lattice laid along a curvature field). <paramref name="onChange"/>
        /// runs after every change of an option (for previews).
        /// </summary>
        public static Result GetGenerator(string prompt, PatternGenerator generator, bool offerExisting, out bool existingPoints,
            Action onChange = null, SurfacePatternInputs onSurface = null)
        {
            existingPoints = false;
            var countU = new OptionInteger(generator.CountU, 1, 100000);
            var countV = new OptionInteger(generator.CountV, 1, 100000);
            var amount = new OptionDouble(generator.Amount, 0.0, 1.0);
            var radius = new OptionDouble(generator.Radius, 0.001, 1.0);
            var seed = new OptionInteger((int)generator.Seed, 0, int.MaxValue);
            var tolerance = new OptionDouble(onSurface == null ? 0.0 : Math.Max(0.0, onSurface.MaxDeviation), 0.0, 1e12);
            var relax = new OptionInteger(onSurface == null ? 0 : Math.Max(0, onSurface.Relax), 0, 1000);
            while (true)
            {
                var get = new GetOption();
                get.SetCommandPrompt(prompt + " (" + ShownSpec(generator, onSurface) + ")");
                get.AcceptNothing(true);
                int kindIndex = get.AddOptionList("Generator", Generators, (int)generator.Kind);
                get.AddOptionInteger("CountU", ref countU);
                get.AddOptionInteger("CountV", ref countV);
                get.AddOptionDouble("Jitter", ref amount);
                get.AddOptionDouble("Radius", ref radius);
                get.AddOptionInteger("Seed", ref seed);
                int alignIndex = -1;
                if (onSurface != null)
                {
                    get.AddOptionDouble("Tolerance", ref tolerance);
                    get.AddOptionInteger("Relax", ref relax);
                    alignIndex = get.AddOptionList("Align", SurfacePatternInputs.AlignChoices,
                        SurfacePatternInputs.AlignChoiceOf(onSurface.Align));
                }
                int existingIndex = offerExisting ? get.AddOption("ExistingPoints") : -1;
                var result = get.Get();
                generator.CountU = countU.CurrentValue;
                generator.CountV = countV.CurrentValue;
                generator.Amount = amount.CurrentValue;
                generator.Radius = radius.CurrentValue;
                generator.Seed = (ulong)seed.CurrentValue;
                if (onSurface != null)
                {
                    onSurface.MaxDeviation = tolerance.CurrentValue;
                    onSurface.Relax = relax.CurrentValue;
                }
                if (result == GetResult.Nothing) return Result.Success;
                if (result != GetResult.Option) return get.CommandResult();
                var option = get.Option();
                if (option.Index == kindIndex) generator.Kind = (GeneratorKind)option.CurrentListOptionIndex;
                else if (option.Index == alignIndex) onSurface.Align = SurfacePatternInputs.AlignField(option.CurrentListOptionIndex);
                else if (option.Index == existingIndex) { existingPoints = true; return Result.Success; }
                if (onChange != null) onChange();
            }
        }

        /// <summary>The spec the options stand for, or why they do not combine.</summary>
        static string ShownSpec(PatternGenerator generator, SurfacePatternInputs onSurface)
        {
            string spec = generator.ToSpec(), error;
            if (onSurface == null || !onSurface.Any) return spec;
            return onSurface.TryCompose(spec, out spec, out error) ? spec : error;
        }
    }
}
