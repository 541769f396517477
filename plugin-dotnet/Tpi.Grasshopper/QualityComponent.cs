// Checked against: Grasshopper 8 (grasshopper-stubs-typed 8.20.25157; the nested param managers
// against the Grasshopper SDK). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Drawing;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Types;
using Tpi.Logic;

namespace Tpi.GhComponents
{
    /// <summary>"TPI Quality": planarity, deviation, side counts, flags and diagnostics per facet.</summary>
    public sealed class QualityComponent : GH_Component
    {
        /// <summary>Made by Grasshopper.</summary>
        public QualityComponent()
            : base("TPI Quality", "TPIQ", "Per-panel quality of a TPI Discretise result.", Tab.Name, Tab.Analysis)
        {
        }

        /// <summary>Never change: old .gh files find the component by it.</summary>
        public override Guid ComponentGuid { get { return new Guid("C94B0E3A-7D62-4E1F-B5A8-6D3F8E2B9C05"); } }

        /// <inheritdoc/>
        protected override Bitmap Icon { get { return Icons.Load("quality"); } }

        /// <inheritdoc/>
        public override GH_Exposure Exposure { get { return GH_Exposure.secondary; } }

        /// <inheritdoc/>
        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddGenericParameter("Result", "R", "The Result output of TPI Discretise.", GH_ParamAccess.item);
        }

        /// <inheritdoc/>
        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddNumberParameter("Planarity", "Pl", "Largest distance of each panel's vertices from its plane (model units).", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Sides", "N", "Number of sides of each panel.", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Flags", "F", "Flag bits per panel: 1 non-convex where K > 0 around it, 2 non-simple, 4 overlap, 8 diagnostic, 16 open, 32 far vertex.", GH_ParamAccess.list);
            pManager.AddTextParameter("Flag names", "FN", "Flag names per panel.", GH_ParamAccess.list);
            pManager.AddTextParameter("Diagnostics", "D", "Diagnostic kinds per panel.", GH_ParamAccess.list);
            pManager.AddNumberParameter("Areas", "A", "Area of each panel.", GH_ParamAccess.list);
            pManager.AddNumberParameter("Max deviation", "Dmax", "Largest distance of a mesh vertex from the surface.", GH_ParamAccess.item);
            pManager.AddNumberParameter("Mean deviation", "Dmean", "Mean distance of mesh vertices from the surface.", GH_ParamAccess.item);
            pManager.AddTextParameter("Report", "Q", "The quality report (JSON).", GH_ParamAccess.item);
        }

        /// <inheritdoc/>
        protected override void SolveInstance(IGH_DataAccess DA)
        {
            object boxed = null;
            if (!DA.GetData(0, ref boxed)) return;
            var wrapper = boxed as GH_ObjectWrapper;
            var mesh = (wrapper != null ? wrapper.Value : boxed) as MeshData;
            if (mesh == null) { AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "R must be the Result output of TPI Discretise"); return; }
            var q = ComponentSolvers.Quality(mesh);
            DA.SetDataList(0, q.Planarity);
            DA.SetDataList(1, q.Sides);
            DA.SetDataList(2, q.Flags);
            DA.SetDataList(3, q.FlagNames);
            DA.SetDataList(4, q.Diagnostics);
            DA.SetDataList(5, q.Areas);
            DA.SetData(6, q.MaxDeviation);
            DA.SetData(7, q.MeanDeviation);
            DA.SetData(8, q.Json);
            if (double.IsNaN(q.MaxDeviation)) AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, "the quality report was switched off");
        }
    }
}
