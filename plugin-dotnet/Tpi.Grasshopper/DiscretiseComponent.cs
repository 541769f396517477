// Checked against: Grasshopper 8 (grasshopper-stubs-typed 8.20.25157; GH_TaskCapableComponent<T>
// and the nested GH_InputParamManager/GH_OutputParamManager, which the stubs omit, against the
// Grasshopper SDK). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Collections.Generic;
using System.Drawing;
using System.Linq;
using System.Threading.Tasks;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Types;
using Rhino.Geometry;
using Tpi.Logic;
using PatternPoint = Tpi.Native.PatternPoint;

namespace Tpi.GhComponents
{
    /// <summary>"TPI Discretise": surface or polysurface + points or uv -> planar panels, planes, n-gon mesh, quality report.</summary>
    public sealed class DiscretiseComponent : GH_TaskCapableComponent<DiscretiseOutput>
    {
        /// <summary>Made by Grasshopper.</summary>
        public DiscretiseComponent()
            : base("TPI Discretise", "TPI", "Planar panels on a surface by tangent plane intersection: one planar panel per pattern point.", Tab.Name, Tab.Panels)
        {
        }

        /// <summary>Never change: old .gh files find the component by it.</summary>
        public override Guid ComponentGuid { get { return new Guid("A1E4C7B2-0D53-4F6A-9B8E-2C5D7F1A3E64"); } }

        /// <inheritdoc/>
        protected override Bitmap Icon { get { return Icons.Load("discretise"); } }

        /// <inheritdoc/>
        public override GH_Exposure Exposure { get { return GH_Exposure.primary; } }

        /// <inheritdoc/>
        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            // A Brep parameter (surfaces convert to it): a polysurface's faces are joined as one
            // surface. Name, nickname and position are the old surface parameter's.
            pManager.AddBrepParameter("Surface", "S", "The surface or polysurface to panel (a polysurface's untrimmed four-sided faces sharing whole sides are joined as one surface).", GH_ParamAccess.item);
            pManager.AddPointParameter("Points", "P", "Pattern points in space (pulled to the surface).", GH_ParamAccess.list);
            pManager.AddPointParameter("UV", "UV", "Pattern points as normalised (s, t, 0) in [0, 1]^2 (used when P is empty).", GH_ParamAccess.list);
            pManager.AddBooleanParameter("Envelope", "E", "Verify and repair neighbours against the envelope of tangent planes (K > 0).", GH_ParamAccess.item, true);
            // Last, so that the wires of files made before it keep their places.
            pManager.AddBooleanParameter("Adjusted", "A", "Adjusted planes: tilt the planes of the few facets that exact tangent planes cannot make valid (at most 5 degrees, each through its seed; saddles and mixed curvature). Off: every facet in its exact tangent plane.", GH_ParamAccess.item, false);
            pManager[1].Optional = true;
            pManager[2].Optional = true;
            pManager[3].Optional = true;
            pManager[4].Optional = true;
        }

        /// <inheritdoc/>
        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddCurveParameter("Panels", "P", "One closed planar polyline per pattern point.", GH_ParamAccess.list);
            pManager.AddPlaneParameter("Planes", "Pl", "The tangent plane of each panel.", GH_ParamAccess.list);
            pManager.AddMeshParameter("Mesh", "M", "The panels as one mesh with one n-gon per panel.", GH_ParamAccess.item);
            pManager.AddTextParameter("Quality", "Q", "The quality report (JSON).", GH_ParamAccess.item);
            pManager.AddGenericParameter("Result", "R", "The whole result, for TPI Quality.", GH_ParamAccess.item);
        }

        /// <inheritdoc/>
        protected override void SolveInstance(IGH_DataAccess DA)
        {
            var problem = Native.Problem;
            if (problem != null) { AddRuntimeMessage(GH_RuntimeMessageLevel.Error, problem); return; }

            List<string> errors, warnings;
            if (InPreSolve)
            {
                // One task per iteration, valid input or not, so GetSolveResults stays in step.
                var input = CollectInput(DA, out errors, out warnings);
                if (input == null) TaskList.Add(Task.FromResult(ComponentSolvers.DiscretiseOrReject(null, errors, warnings)));
                else
                {
                    // Grasshopper cancels the token when the solution is aborted (Escape) or
                    // expires again; the library stops where its running stage ends.
                    var cancel = CancelToken;
                    TaskList.Add(Task.Run(() => ComponentSolvers.DiscretiseOrReject(input, errors, warnings, ShowProgress, cancel), cancel));
                }
                return;
            }

            DiscretiseOutput output;
            if (!GetSolveResults(DA, out output))
            {
                var input = CollectInput(DA, out errors, out warnings);
                output = ComponentSolvers.DiscretiseOrReject(input, errors, warnings, ShowProgress, System.Threading.CancellationToken.None);
            }
            if (output == null) return;
            foreach (var e in output.Errors) AddRuntimeMessage(GH_RuntimeMessageLevel.Error, e);
            foreach (var w in output.Warnings) AddRuntimeMessage(GH_RuntimeMessageLevel.Warning, w);
            // Under the component: the progress while it runs (ShowProgress), then the size of
            // the result, or that it was cancelled.
            Message = output.Success ? output.Mesh.FacetCount + " panels" : output.Cancelled ? ProgressText.Cancelled : null;
            if (!output.Success) return;
            DA.SetDataList(0, output.Polylines.Select(p => new PolylineCurve(GhConvert.ToPolyline(p))));
            DA.SetDataList(1, output.Planes.Select(GhConvert.ToPlane));
            DA.SetData(2, GhConvert.ToMesh(output.NgonMesh));
            DA.SetData(3, output.QualityJson);
            DA.SetData(4, new GH_ObjectWrapper(output.Mesh));
        }

        /// <summary>
        /// Shows a progress text (ProgressText.Format, each new one once) under the component and
        /// asks for a canvas redraw on the UI thread; called from the solve's worker thread.
        /// </summary>
        void ShowProgress(string text)
        {
            SolveProgress.Show(this, text);
        }

        /// <summary>Reads the inputs on the UI thread (RhinoCommon calls stay off the worker).</summary>
        /// Returns null when the inputs cannot be used; the messages go into the lists (they are
        /// reported with the result, on the UI thread).
        DiscretiseInput CollectInput(IGH_DataAccess DA, out List<string> errors, out List<string> warnings)
        {
            errors = new List<string>();
            warnings = new List<string>();
            Brep brep = null;
            if (!DA.GetData(0, ref brep) || brep == null) return null; // Grasshopper itself warns about a missing S
            if (brep.Faces == null || brep.Faces.Count == 0) { errors.Add("the Brep has no faces"); return null; }
            // One face: that face, with its trim. Several: all joined, each face untrimmed (a
            // trimmed face is refused with a reason, never dropped).
            Surface surface = brep.Faces.Count == 1 ? brep.Faces[0] : null;
            SurfaceSpec spec;
            if (surface != null)
            {
                spec = GhConvert.ToSpec(surface);
                if (spec == null) { errors.Add("the surface has no NURBS form"); return null; }
            }
            else
            {
                string error;
                spec = Tpi.Plugin.SurfaceSpecs.FromBrep(brep, out error);
                if (spec == null) { errors.Add(error); return null; }
            }
            var points = new List<Point3d>();
            DA.GetDataList(1, points);
            var uv = new List<Point3d>();
            DA.GetDataList(2, uv);
            bool envelope = true;
            DA.GetData(3, ref envelope);
            bool adjusted = false;
            DA.GetData(4, ref adjusted);
            var options = Tpi.Native.DiscretisationOptions.Default();
            options.EnvelopeRepair = envelope;
            options.Planes = adjusted ? Tpi.Native.PlaneMode.Adjusted : Tpi.Native.PlaneMode.Exact;
            var input = new DiscretiseInput { Surface = spec, Options = options };
            if (points.Count > 0 && surface == null)
            {
                errors.Add("pattern points in space (P) cannot be pulled to a polysurface yet: give normalised uv (UV)");
                return null;
            }
            if (points.Count > 0)
            {
                input.Points = GhConvert.ClosestParameters(surface, points, warnings);
                input.PointsInSurfaceDomain = true;
                // ClosestPoint works on the original surface; its domain is the NURBS form's.
            }
            else if (uv.Count > 0)
            {
                input.Points = uv.Select(p => new PatternPoint(p.X, p.Y)).ToList();
            }
            else
            {
                warnings.Add("give pattern points (P) or normalised uv (UV)");
                return null;
            }
            return input;
        }
    }
}
