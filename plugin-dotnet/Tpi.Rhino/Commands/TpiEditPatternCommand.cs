// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Collections.Generic;
using System.Drawing;
using System.Linq;
using Rhino;
using Rhino.Commands;
using Rhino.DocObjects;
using Rhino.Geometry;
using Rhino.Input;
using Rhino.Input.Custom;
using Tpi.Logic;
using PatternPoint = Tpi.Native.PatternPoint;

namespace Tpi.RhinoPlugIn
{
    /// <summary>
    /// TpiEditPattern: the pattern points of a discrete surface as grips constrained to its
    /// surface. Click a grip and drag it (the panels follow live), add points, remove points,
    /// undo and redo inside the command; Enter stores the result as one Rhino undo step.
    /// </summary>
    public sealed class TpiEditPatternCommand : Command
    {
        /// <inheritdoc/>
        public override string EnglishName { get { return "TpiEditPattern"; } }

        enum Mode { Move, Add, Remove }

        /// <inheritdoc/>
        protected override Result RunCommand(RhinoDoc doc, RunMode mode)
        {
            var get = new GetObject();
            get.SetCommandPrompt("Select a discrete surface");
            get.GeometryFilter = ObjectType.Mesh;
            get.SetCustomGeometryFilter((obj, geometry, ci) => DiscreteSurfaceObject.IsDiscreteSurface(obj));
            if (get.Get() != GetResult.Object) return get.CommandResult();
            var objRef = get.Object(0);
            // A plain mesh carrying the data (opened or pasted, not upgraded yet) works too: the
            // replace below makes it a discrete surface object.
            var document = DiscreteSurfaceObject.StoredDocumentOf(objRef.Object());
            if (document == null) { RhinoApp.WriteLine("TPI: the object's discrete surface data cannot be read."); return Result.Failure; }
            if (document.Surface is PolysurfaceSpec)
            {
                RhinoApp.WriteLine("TPI: the pattern of a discrete surface made from a polysurface cannot be edited by hand yet (its points are placed on one face's surface); run TpiDiscreteSurface again with another generator.");
                return Result.Failure;
            }
            var spec = document.Surface as NurbsSurfaceSpec;
            if (spec == null) { RhinoApp.WriteLine("TPI: only NURBS-based discrete surfaces can be edited."); return Result.Failure; }
            var surface = RhinoConvert.ToNurbsSurface(spec);
            if (surface == null) return Result.Failure;

            DiscreteSurfaceState state;
            try { state = new DiscreteSurfaceState(document); }
            catch (Tpi.Native.TpiException e) { RhinoApp.WriteLine("TPI: " + e.NativeMessage); return Result.Failure; }

            var conduit = new PreviewConduit { PointColor = Color.Black, LineColor = Color.DimGray };
            var grips = new GripMap(state.Points.Count);
            var editMode = Mode.Move;
            bool changed = false;
            using (state)
            {
                try
                {
                    conduit.Enabled = true;
                    while (true)
                    {
                        var gripPoints = Enumerable.Range(0, grips.Count)
                            .Select(g => RhinoConvert.PointAt(surface, state.Points[grips.PointOf(g)])).ToList();
                        conduit.Set(gripPoints, Panels(state.Mesh));
                        doc.Views.Redraw();

                        var pick = new GetPoint();
                        pick.SetCommandPrompt(editMode == Mode.Move ? "Pick a pattern point to move" :
                            editMode == Mode.Add ? "Pick where to add a pattern point" : "Pick a pattern point to remove");
                        pick.Constrain(surface, false);
                        pick.AcceptNothing(true);
                        int modeIndex = pick.AddOptionList("Mode", new[] { "Move", "Add", "Remove" }, (int)editMode);
                        int undoIndex = pick.AddOption("Undo");
                        int redoIndex = pick.AddOption("Redo");
                        var result = pick.Get();
                        if (result == GetResult.Nothing) break;
                        if (result == GetResult.Option)
                        {
                            var option = pick.Option();
                            if (option.Index == modeIndex) editMode = (Mode)option.CurrentListOptionIndex;
                            else if (option.Index == undoIndex || option.Index == redoIndex)
                            {
                                bool done = option.Index == undoIndex ? state.Undo() : state.Redo();
                                if (!done) RhinoApp.WriteLine("TPI: nothing to " + (option.Index == undoIndex ? "undo." : "redo."));
                                Recompute(state);
                                grips = new GripMap(state.Points.Count);
                                changed = true;
                            }
                            continue;
                        }
                        if (result != GetResult.Point) return pick.CommandResult();
                        var picked = pick.Point();

                        if (editMode == Mode.Add)
                        {
                            PatternPoint st;
                            string error;
                            if (!RhinoConvert.TryNormalisedClosest(surface, picked, out st, out error)) { RhinoApp.WriteLine("TPI: " + error); continue; }
                            int index = Try(() => state.AddPoint(st.S, st.T), -1);
                            if (index < 0) continue;
                            grips.OnPointAdded(index);
                            changed |= Recompute(state);
                            continue;
                        }

                        int grip = GripMap.Nearest(gripPoints.Select(RhinoConvert.ToVec3).ToList(), RhinoConvert.ToVec3(picked), PickRadius(gripPoints));
                        if (grip < 0) { RhinoApp.WriteLine("TPI: no pattern point there."); continue; }
                        int point = grips.PointOf(grip);
                        if (editMode == Mode.Remove)
                        {
                            if (Try(() => { state.RemovePoint(point); return true; }, false))
                            {
                                grips.OnPointRemoved(point);
                                changed |= Recompute(state);
                            }
                            continue;
                        }

                        // Move: drag the grip along the surface with the panels following live.
                        var moved = DragTo(doc, surface, state, point, gripPoints[grip]);
                        if (moved == null) continue;
                        if (Try(() => { state.MovePoint(point, moved.Value.S, moved.Value.T); return true; }, false))
                            changed |= Recompute(state);
                    }
                }
                finally
                {
                    conduit.Enabled = false;
                    doc.Views.Redraw();
                }
                if (!changed || state.PendingEdits > 0) return Result.Nothing;
                DiscreteSurfaceObject.Replace(doc, objRef, state, document);
            }
            doc.Views.Redraw();
            return Result.Success;
        }

        /// <summary>Second click of a move: returns the new (s, t), or null when cancelled.</summary>
        static PatternPoint? DragTo(RhinoDoc doc, NurbsSurface surface, DiscreteSurfaceState state, int point, Point3d from)
        {
            // The preview only draws panels: no quality report per mouse move (the same panels; the
            // report is computed when the move is applied).
            var previewDocument = state.Document;
            previewDocument.Options.QualityReport = false;
            using (var preview = new DiscreteSurfaceState(previewDocument))
            {
                var drag = new GetPoint();
                drag.SetCommandPrompt("New location on the surface");
                drag.Constrain(surface, false);
                drag.SetBasePoint(from, true);
                // The drawn panels: each mouse move takes only the library's changes (LiveMesh), and
                // only the panels whose vertices changed are converted again (PanelDisplay).
                var display = new PanelDisplay();
                var panels = new List<List<Point3d>>();
                Refresh(display, panels, preview.LiveMesh);
                drag.DynamicDraw += (sender, e) =>
                {
                    PatternPoint st;
                    string error;
                    if (RhinoConvert.TryNormalisedClosest(surface, e.CurrentPoint, out st, out error))
                    {
                        try
                        {
                            preview.MovePoint(point, st.S, st.T);
                            if (preview.TryRecompute(out error)) Refresh(display, panels, preview.LiveMesh);
                        }
                        catch (Tpi.Native.TpiException) { }
                    }
                    foreach (var line in panels) e.Display.DrawPolyline(line, Color.OrangeRed, 1);
                    e.Display.DrawLine(from, e.CurrentPoint, Color.Gray);
                };
                if (drag.Get() != GetResult.Point) return null;
                PatternPoint result;
                string message;
                if (!RhinoConvert.TryNormalisedClosest(surface, drag.Point(), out result, out message))
                {
                    RhinoApp.WriteLine("TPI: " + message);
                    return null;
                }
                return result;
            }
        }

        /// <summary>Recomputes; a failing edit is undone with the library's message.</summary>
        static bool Recompute(DiscreteSurfaceState state)
        {
            string error;
            if (state.TryRecompute(out error)) return true;
            RhinoApp.WriteLine("TPI: " + error + " (edit undone)");
            state.Undo();
            state.TryRecompute(out error);
            return false;
        }

        static T Try<T>(Func<T> edit, T failed)
        {
            try { return edit(); }
            catch (Tpi.Native.TpiException e) { RhinoApp.WriteLine("TPI: " + e.NativeMessage); return failed; }
        }

        /// <summary>Brings <paramref name="panels"/> to <paramref name="mesh"/>, converting only the panels that changed.</summary>
        static void Refresh(PanelDisplay display, List<List<Point3d>> panels, LiveMeshData mesh)
        {
            display.UpdateInto(mesh, panels, polyline => polyline.Select(RhinoConvert.ToPoint).ToList());
        }

        static List<List<Point3d>> Panels(MeshData mesh)
        {
            return MeshConversion.FacetPolylines(mesh).Select(p => p.Select(RhinoConvert.ToPoint).ToList()).ToList();
        }

        /// <summary>Half a typical grip spacing: the bounding-box diagonal over the square root of the grip count.</summary>
        static double PickRadius(List<Point3d> grips)
        {
            if (grips.Count == 0) return 0;
            var box = new BoundingBox(grips);
            return 0.5 * box.Diagonal.Length / Math.Sqrt(grips.Count);
        }
    }
}
