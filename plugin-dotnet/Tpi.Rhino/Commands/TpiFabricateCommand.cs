// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Drawing;
using System.Linq;
using Rhino;
using Rhino.Commands;
using Rhino.DocObjects;
using Rhino.Input;
using Rhino.Input.Custom;
using Tpi.Logic;
using PanelSide = Tpi.Native.PanelSide;

namespace Tpi.RhinoPlugIn
{
    /// <summary>
    /// TpiFabricate: panels of a thickness from a discrete surface (mitred solids, cleat slots),
    /// their flat parts nested on sheets beside the model, and optionally the workshop's files
    /// (panels.json/.obj, sheets.svg/.dxf, bevels.csv, cut.nc) in a folder.
    /// </summary>
    public sealed class TpiFabricateCommand : Command
    {
        const string PanelLayer = "TPI panels";
        const string SheetLayer = "TPI sheets";

        // The last choices, kept for the session while the model's units stay the same.
        static FabricationSettings s_settings;
        static int s_units = -1;
        static int s_files; // 0: no files, 1: write files
        static string s_folder = string.Empty;

        /// <inheritdoc/>
        public override string EnglishName { get { return "TpiFabricate"; } }

        /// <inheritdoc/>
        protected override Result RunCommand(RhinoDoc doc, RunMode mode)
        {
            try
            {
                return Run(doc);
            }
            catch (Tpi.Native.TpiException e)
            {
                RhinoApp.WriteLine("TPI: " + e.NativeMessage);
                return Result.Failure;
            }
        }

        static Result Run(RhinoDoc doc)
        {
            var get = new GetObject();
            get.SetCommandPrompt("Select a discrete surface to fabricate");
            get.GeometryFilter = ObjectType.Mesh;
            get.SetCustomGeometryFilter((obj, geometry, ci) => DiscreteSurfaceObject.IsDiscreteSurface(obj));
            if (get.Get() != GetResult.Object) return get.CommandResult();
            var document = DiscreteSurfaceObject.StoredDocumentOf(get.Object(0).Object());
            if (document == null)
            {
                RhinoApp.WriteLine("TPI: the object carries no discrete surface data.");
                return Result.Failure;
            }

            int units = (int)doc.ModelUnitSystem;
            if (s_settings == null || s_units != units)
            {
                MeshData mesh;
                using (var state = new DiscreteSurfaceState(document)) mesh = state.Mesh;
                s_settings = FabricationSettings.Defaults(mesh, units);
                s_units = units;
            }
            var settings = s_settings.Clone();
            var rc = AskSettings(settings);
            if (rc != Result.Success) return rc;
            var errors = settings.Validate();
            if (errors.Count > 0)
            {
                foreach (var e in errors) RhinoApp.WriteLine("TPI: " + e + ".");
                return Result.Failure;
            }
            s_settings = settings;

            if (s_files == 1)
            {
                var folder = s_folder;
                rc = RhinoGet.GetString("Folder for panels.json, panels.obj, sheets.svg, sheets.dxf, bevels.csv and cut.nc", false, ref folder);
                if (rc != Result.Success) return rc;
                s_folder = (folder ?? string.Empty).Trim().Trim('"');
            }

            var result = FabricationRun.Run(document, settings, units);
            if (!result.Success)
            {
                foreach (var e in result.Errors) RhinoApp.WriteLine("TPI: " + e);
                return Result.Failure;
            }

            var layout = result.Layout;
            uint undo = doc.BeginUndoRecord("TpiFabricate");
            try
            {
                int panelLayer = LayerIndex(doc, PanelLayer, Color.Peru);
                int sheetLayer = LayerIndex(doc, SheetLayer, Color.Firebrick);
                foreach (var solid in layout.PanelSolids.Concat(layout.CleatSolids))
                    doc.Objects.AddMesh(Tpi.Plugin.SolidMeshes.ToMesh(solid), new ObjectAttributes { LayerIndex = panelLayer, Name = solid.Name });
                // The sheets lie beside the model, at the height of its lowest point.
                double z = layout.LowestZ();
                for (int k = 0; k < layout.Sheets.Count; k++)
                {
                    var origin = layout.SheetOrigin(k);
                    doc.Objects.AddPolyline(RhinoConvert.ToPoints(layout.SheetRectangle(k, origin), z),
                        new ObjectAttributes { LayerIndex = sheetLayer, Name = "sheet_" + (k + 1) });
                    foreach (var panel in layout.Panels.Where(p => p.Sheet == k))
                    {
                        // The cut outline (the router's, from sheets.dxf), not only the top face's.
                        doc.Objects.AddPolyline(RhinoConvert.ToPoints(layout.ToModel(layout.CutOutlines[panel.Seed], true), z),
                            new ObjectAttributes { LayerIndex = sheetLayer, Name = "panel_" + panel.Seed });
                        foreach (var slot in FabricationLayout.PlacedSlots(panel, origin))
                            doc.Objects.AddPolyline(RhinoConvert.ToPoints(slot, z),
                                new ObjectAttributes { LayerIndex = sheetLayer, Name = "slot_" + panel.Seed });
                    }
                }
                foreach (var stroke in layout.LabelStrokes)
                    doc.Objects.AddPolyline(RhinoConvert.ToPoints(layout.ToModel(stroke, false), z),
                        new ObjectAttributes { LayerIndex = sheetLayer, Name = "label" });
            }
            finally
            {
                doc.EndUndoRecord(undo);
            }

            if (s_files == 1)
            {
                try
                {
                    var paths = FabricationRun.WriteFiles(result, s_folder);
                    RhinoApp.WriteLine("TPI: wrote {0} files to {1}.", paths.Count, s_folder);
                }
                catch (Exception e) when (e is System.IO.IOException || e is UnauthorizedAccessException || e is ArgumentException || e is NotSupportedException)
                {
                    RhinoApp.WriteLine("TPI: could not write the files to \"" + s_folder + "\": " + e.Message);
                }
            }
            RhinoApp.WriteLine("TPI: " + result.Summary() + ".");
            doc.Views.Redraw();
            return Result.Success;
        }

        /// <summary>The command-line options; Enter accepts them.</summary>
        static Result AskSettings(FabricationSettings settings)
        {
            var go = new GetOption();
            go.SetCommandPrompt("Fabrication options (Enter to fabricate)");
            go.AcceptNothing(true);
            while (true)
            {
                var thickness = new OptionDouble(settings.Thickness, 1e-12, 1e12);
                var slots = new OptionInteger(settings.SlotsPerEdge, 0, 20);
                var sheetWidth = new OptionDouble(settings.SheetWidth, 1e-12, 1e12);
                var sheetHeight = new OptionDouble(settings.SheetHeight, 1e-12, 1e12);
                var gap = new OptionDouble(settings.Gap, 0, 1e12);
                var tool = new OptionDouble(settings.ToolDiameter, 1e-12, 1e12);
                go.ClearCommandOptions();
                go.AddOptionDouble("Thickness", ref thickness);
                int sideIndex = go.AddOptionList("Side", new[] { "Inside", "Outside" }, settings.Side == PanelSide.Outside ? 1 : 0);
                go.AddOptionInteger("SlotsPerEdge", ref slots);
                go.AddOptionDouble("SheetWidth", ref sheetWidth);
                go.AddOptionDouble("SheetHeight", ref sheetHeight);
                go.AddOptionDouble("Gap", ref gap);
                go.AddOptionDouble("ToolDiameter", ref tool);
                int filesIndex = go.AddOptionList("Files", new[] { "None", "WriteToFolder" }, s_files);
                var result = go.Get();
                settings.Thickness = thickness.CurrentValue;
                settings.SlotsPerEdge = slots.CurrentValue;
                settings.SheetWidth = sheetWidth.CurrentValue;
                settings.SheetHeight = sheetHeight.CurrentValue;
                settings.Gap = gap.CurrentValue;
                settings.ToolDiameter = tool.CurrentValue;
                if (result == GetResult.Nothing) return Result.Success;
                if (result != GetResult.Option) return go.CommandResult();
                if (go.Option().Index == sideIndex) settings.Side = go.Option().CurrentListOptionIndex == 1 ? PanelSide.Outside : PanelSide.Inside;
                if (go.Option().Index == filesIndex) s_files = go.Option().CurrentListOptionIndex;
            }
        }

        /// <summary>The index of the layer named <paramref name="name"/>, made if missing.</summary>
        static int LayerIndex(RhinoDoc doc, string name, Color color)
        {
            var layer = doc.Layers.FindName(name);
            return layer != null ? layer.Index : doc.Layers.Add(name, color);
        }
    }
}
