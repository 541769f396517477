// Checked against: Grasshopper 8 (grasshopper-stubs-typed 8.20.25157; the nested param managers
// against the Grasshopper SDK). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Drawing;
using System.Linq;
using Grasshopper.Kernel;
using Grasshopper.Kernel.Types;
using Tpi.Logic;

namespace Tpi.GhComponents
{
    /// <summary>"TPI Fabricate": a TPI Discretise result -> panel solids, flat parts nested on sheets, G-code, DXF, bevels.</summary>
    public sealed class FabricateComponent : GH_Component
    {
        /// <summary>Made by Grasshopper.</summary>
        public FabricateComponent()
            : base("TPI Fabricate", "TPIF", "Panels of a thickness with mitred joints and cleat slots, their flat parts nested on sheets beside the model, and the workshop's files (G-code, DXF, bevel table).", Tab.Name, Tab.Panels)
        {
        }

        /// <summary>Never change: old .gh files find the component by it.</summary>
        public override Guid ComponentGuid { get { return new Guid("5B7D2E94-1C36-4A8F-9E0B-7F4C3A1D6E28"); } }

        /// <inheritdoc/>
        protected override Bitmap Icon { get { return Icons.Load("fabricate"); } }

        /// <inheritdoc/>
        public override GH_Exposure Exposure { get { return GH_Exposure.secondary; } }

        /// <inheritdoc/>
        protected override void RegisterInputParams(GH_InputParamManager pManager)
        {
            pManager.AddGenericParameter("Result", "R", "The Result output of TPI Discretise.", GH_ParamAccess.item);
            pManager.AddNumberParameter("Thickness", "T", "Panel thickness (default: 40 mm in model units, at most a tenth of the median panel edge).", GH_ParamAccess.item);
            pManager.AddIntegerParameter("Side", "S", "0: thicken towards the concave side (inside), 1: outside.", GH_ParamAccess.item, 0);
            pManager.AddIntegerParameter("Slots", "N", "Cleat slots per interior edge.", GH_ParamAccess.item, 0);
            pManager.AddNumberParameter("Sheet width", "W", "Sheet width (default 2.5 m in model units, enlarged for the largest part).", GH_ParamAccess.item);
            pManager.AddNumberParameter("Sheet height", "H", "Sheet height (default 1.25 m in model units, enlarged for the largest part).", GH_ParamAccess.item);
            pManager.AddNumberParameter("Gap", "G", "Gap between parts and from the sheet's edges (default 20 mm in model units).", GH_ParamAccess.item);
            pManager.AddNumberParameter("Tool diameter", "D", "Router tool diameter for the G-code (default 6 mm in model units).", GH_ParamAccess.item);
            for (int i = 1; i < 8; i++) pManager[i].Optional = true;
        }

        /// <inheritdoc/>
        protected override void RegisterOutputParams(GH_OutputParamManager pManager)
        {
            pManager.AddMeshParameter("Panels", "P", "One closed mesh per panel (notches cut), in seed order.", GH_ParamAccess.list);
            pManager.AddMeshParameter("Cleats", "C", "One closed mesh per cleat.", GH_ParamAccess.list);
            pManager.AddCurveParameter("Outlines", "O", "Each panel's cut outline (the top outline, widened where the panel widens towards its bottom) placed on its sheet, in seed order.", GH_ParamAccess.list);
            pManager.AddIntegerParameter("Sheet", "K", "The sheet of each outline.", GH_ParamAccess.list);
            pManager.AddCurveParameter("Slots", "SL", "The slot notches, placed on the sheets.", GH_ParamAccess.list);
            pManager.AddCurveParameter("Sheets", "SH", "The sheet rectangles, side by side beside the model.", GH_ParamAccess.list);
            pManager.AddNumberParameter("Utilisation", "U", "Parts' area over sheet area, per sheet.", GH_ParamAccess.list);
            pManager.AddTextParameter("G-code", "NC", "G-code for a 3-axis router, in sheet coordinates.", GH_ParamAccess.item);
            pManager.AddTextParameter("DXF", "DXF", "The sheets as ASCII DXF R2000 (layers SHEET, CUT, BOTTOM, SLOT, ENGRAVE).", GH_ParamAccess.item);
            pManager.AddTextParameter("Bevels", "B", "bevels.csv: panel, side, neighbour, length, dihedral, bevel.", GH_ParamAccess.item);
            pManager.AddCurveParameter("Labels", "L", "Panel and neighbour numbers as single strokes for engraving, on the sheets.", GH_ParamAccess.list);
        }

        /// <inheritdoc/>
        protected override void SolveInstance(IGH_DataAccess DA)
        {
            var problem = Native.Problem;
            if (problem != null) { AddRuntimeMessage(GH_RuntimeMessageLevel.Error, problem); return; }
            object boxed = null;
            if (!DA.GetData(0, ref boxed)) return;
            var wrapper = boxed as GH_ObjectWrapper;
            var mesh = (wrapper != null ? wrapper.Value : boxed) as MeshData;
            if (mesh == null) { AddRuntimeMessage(GH_RuntimeMessageLevel.Error, "R must be the Result output of TPI Discretise"); return; }
            int side = 0, slots = 0;
            DA.GetData(2, ref side);
            DA.GetData(3, ref slots);
            var doc = Rhino.RhinoDoc.ActiveDoc;
            int units = doc != null ? (int)doc.ModelUnitSystem : 0;
            FabricationSettings used;
            var result = FabricationRun.ForComponent(mesh, units, Optional(DA, 1), side, slots, Optional(DA, 4), Optional(DA, 5),
                Optional(DA, 6), Optional(DA, 7), out used);
            foreach (var e in result.Errors) AddRuntimeMessage(GH_RuntimeMessageLevel.Error, e);
            if (!result.Success) { Message = null; return; }
            var layout = result.Layout;
            Message = layout.Panels.Count + " panels, " + layout.Sheets.Count + " sheets";
            AddRuntimeMessage(GH_RuntimeMessageLevel.Remark, result.Summary());
            double z = layout.LowestZ();
            DA.SetDataList(0, layout.PanelSolids.Select(Tpi.Plugin.SolidMeshes.ToMesh));
            DA.SetDataList(1, layout.CleatSolids.Select(Tpi.Plugin.SolidMeshes.ToMesh));
            DA.SetDataList(2, layout.CutOutlines.Select(c => GhConvert.ToCurve(layout.ToModel(c, true), z)));
            DA.SetDataList(3, layout.Panels.Select(p => p.Sheet));
            DA.SetDataList(4, layout.Panels.SelectMany(p => FabricationLayout.PlacedSlots(p, layout.SheetOrigin(p.Sheet))).Select(s => GhConvert.ToCurve(s, z)));
            DA.SetDataList(5, Enumerable.Range(0, layout.Sheets.Count).Select(k => GhConvert.ToCurve(layout.SheetRectangle(k, layout.SheetOrigin(k)), z)));
            DA.SetDataList(6, layout.Sheets.Select(s => s.Utilisation));
            DA.SetData(7, result.GCode);
            DA.SetData(8, result.SheetsDxf);
            DA.SetData(9, result.BevelsCsv);
            DA.SetDataList(10, layout.LabelStrokes.Select(l => GhConvert.ToCurve(layout.ToModel(l, false), z)));
        }

        /// <summary>A number input, or null when nothing is connected.</summary>
        static double? Optional(IGH_DataAccess DA, int index)
        {
            double value = 0;
            return DA.GetData(index, ref value) ? value : (double?)null;
        }
    }
}
