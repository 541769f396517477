// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Collections.Generic;
using System.Linq;
using Rhino;
using Rhino.Commands;
using Rhino.DocObjects;
using Rhino.Geometry;
using Rhino.Input;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    /// <summary>
    /// TpiPattern: generate a pattern scheme on a surface, previewing the points and their
    /// Voronoi cells (drawn on the surface, as the paper's figure 9a), then add the points to the
    /// document (for TpiDiscreteSurface's ExistingPoints, or to edit by hand). The options
    /// Tolerance, Relax and Align make the pattern on the surface (a fit, Lloyd iterations on
    /// the surface, a lattice along a curvature field), as the TPI Pattern component's inputs.
    /// </summary>
    public sealed class TpiPatternCommand : Command
    {
        /// <inheritdoc/>
        public override string EnglishName { get { return "TpiPattern"; } }

        /// <inheritdoc/>
        protected override Result RunCommand(RhinoDoc doc, RunMode mode)
        {
            ObjRef surfaceRef;
            var rc = RhinoGet.GetOneObject("Select a surface for the pattern", false, ObjectType.Surface, out surfaceRef);
            if (rc != Result.Success) return rc;
            var surface = surfaceRef.Surface();
            if (surface == null) return Result.Failure;

            var surfaceSpec = RhinoConvert.ToSpec(surface);
            var generator = new PatternGenerator();
            // Tolerance, Relax and Align are offered only where the library can see the surface.
            var onSurface = surfaceSpec == null ? null : new SurfacePatternInputs();
            if (surfaceSpec == null)
                RhinoApp.WriteLine("TPI: the surface has no NURBS form: only patterns in its parameters are offered.");
            var conduit = new PreviewConduit();
            List<Point3d> points = null;
            Action preview = () =>
            {
                var input = new PatternInput
                {
                    Generator = generator,
                    Surface = onSurface != null && onSurface.Any ? surfaceSpec : null,
                    OnSurface = onSurface,
                };
                // A fit or a relaxation runs many discretisations: on a worker, Escape cancels it.
                var output = Escapable.Run("TPI pattern", (progress, cancel) => ComponentSolvers.Pattern(input, progress, cancel));
                if (output.Errors.Count > 0) RhinoApp.WriteLine("TPI: " + output.Errors[0]);
                foreach (var w in output.Warnings) RhinoApp.WriteLine("TPI: " + w);
                points = output.Points.Select(p => RhinoConvert.PointAt(surface, p)).ToList();
                var cells = output.Points.Length <= 5000
                    ? VoronoiCells.Compute(output.Points).Select(c => RhinoConvert.OnSurface(surface, c, 4)).ToList()
                    : new List<List<Point3d>>();
                conduit.Set(points, cells);
                doc.Views.Redraw();
                RhinoApp.WriteLine("TPI: " + output.Summary() + ".");
            };
            try
            {
                conduit.Enabled = true;
                preview();
                bool unused;
                rc = CommandOptions.GetGenerator("Pattern, Enter to add the points", generator, false, out unused, preview, onSurface);
                if (rc != Result.Success) return rc;
            }
            finally
            {
                conduit.Enabled = false;
                doc.Views.Redraw();
            }

            if (points == null || points.Count == 0) return Result.Nothing;
            foreach (var p in points) doc.Objects.AddPoint(p);
            doc.Views.Redraw();
            return Result.Success;
        }
    }
}
