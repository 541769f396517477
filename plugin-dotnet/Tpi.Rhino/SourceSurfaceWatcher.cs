// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from the
// compiled adapter and checked against the stubs by tests/check_rhino_api.py.
//
// The document events of the plug-in. They only record (Tpi.Logic.DocumentWorkQueue, per
// document: a document must not be changed inside its own events); the Idle handler does the
// work of each document that has some, outside commands:
//   - upgrades: an object read from a file (open, import, worksession attach), pasted or
//     undeleted comes back as a plain mesh carrying DiscreteSurfaceUserData; it is replaced by a
//     DiscreteSurfaceObject showing the same mesh (Tpi.Logic.DiscreteSurfaceUpgrade decides,
//     and migrates old user data). Not recorded for undo: it changes nothing the user sees.
//   - followers: when a surface object is replaced (control points moved, rebuilt, ...), every
//     discrete surface whose stored SourceSurfaceId names it takes the new surface (or its
//     stored face of a polysurface, Tpi.Logic.SourceFollow), mapped by its stored source
//     transform, and recomputes; inside one undo record per document, so Undo restores them.
//   - recomputes: a discrete surface moved by a transform that is not a similarity.
using System;
using System.Collections.Generic;
using System.Linq;
using Rhino;
using Rhino.DocObjects;
using Rhino.Geometry;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    internal static class SourceSurfaceWatcher
    {
        static readonly DocumentWorkQueue s_queue = new DocumentWorkQueue();
        static bool s_started;

        public static void Start()
        {
            if (s_started) return;
            s_started = true;
            RhinoDoc.BeginOpenDocument += OnBeginOpen;
            RhinoDoc.EndOpenDocument += OnEndOpen;
            RhinoDoc.CloseDocument += OnClose;
            RhinoDoc.AddRhinoObject += OnAdd;
            RhinoDoc.UndeleteRhinoObject += OnAdd;
            RhinoDoc.ReplaceRhinoObject += OnReplace;
            RhinoApp.Idle += OnIdle;
        }

        static void OnBeginOpen(object sender, DocumentOpenEventArgs e)
        {
            s_queue.BeginOpen(e.DocumentSerialNumber);
        }

        /// <summary>After open, import or attach: every object carrying the data is looked at (whether or not Rhino raised AddRhinoObject for it while reading).</summary>
        static void OnEndOpen(object sender, DocumentOpenEventArgs e)
        {
            var doc = e.Document;
            if (doc != null)
            {
                // Keyed by the document's own serial number, as the Idle handler looks it up.
                uint serial = doc.RuntimeSerialNumber;
                var settings = new ObjectEnumeratorSettings { HiddenObjects = true, LockedObjects = true };
                foreach (var obj in doc.Objects.GetObjectList(settings))
                    s_queue.ObjectAdded(serial, obj.Id, DiscreteSurfaceUserData.Find(obj.Geometry) != null, obj is DiscreteSurfaceObject);
                s_queue.EndOpen(serial);
            }
            s_queue.EndOpen(e.DocumentSerialNumber);
        }

        static void OnClose(object sender, DocumentEventArgs e)
        {
            s_queue.DocumentClosed(e.DocumentSerialNumber);
        }

        static void OnAdd(object sender, RhinoObjectEventArgs e)
        {
            var obj = e.TheObject;
            var doc = obj == null ? null : obj.Document;
            if (doc == null) return;
            s_queue.ObjectAdded(doc.RuntimeSerialNumber, e.ObjectId, DiscreteSurfaceUserData.Find(obj.Geometry) != null, obj is DiscreteSurfaceObject);
        }

        static void OnReplace(object sender, RhinoReplaceObjectEventArgs e)
        {
            if (e.Document == null) return;
            uint serial = e.Document.RuntimeSerialNumber;
            bool discrete = e.NewRhinoObject is DiscreteSurfaceObject;
            s_queue.ObjectReplaced(serial, e.ObjectId, discrete);
            if (discrete)
            {
                var data = DiscreteSurfaceUserData.Find(e.NewRhinoObject.Geometry);
                if (data != null && data.NeedsRecompute) s_queue.RecomputeLater(serial, e.ObjectId);
            }
        }

        static void OnIdle(object sender, EventArgs e)
        {
            if (Rhino.Commands.Command.InCommand()) return; // never under a running command's feet
            foreach (var serial in s_queue.DocumentsWithWork())
            {
                var doc = RhinoDoc.FromRuntimeSerialNumber(serial);
                if (doc == null) { s_queue.DocumentClosed(serial); continue; }
                var work = s_queue.Take(serial);
                if (work.IsEmpty) continue;
                try
                {
                    Upgrade(doc, work.Upgrades);
                    if (work.Recompute.Count > 0 || work.ChangedSources.Count > 0)
                    {
                        uint undo = doc.BeginUndoRecord("TPI: update discrete surfaces");
                        try
                        {
                            foreach (var id in work.Recompute) Recompute(doc, id);
                            if (work.ChangedSources.Count > 0) Follow(doc, work.ChangedSources);
                        }
                        finally
                        {
                            if (undo != 0) doc.EndUndoRecord(undo);
                        }
                    }
                }
                catch (Exception ex)
                {
                    // An event handler must never take Rhino down.
                    RhinoApp.WriteLine("TPI: updating discrete surfaces failed: " + ex.Message);
                }
                doc.Views.Redraw();
            }
        }

        static void Upgrade(RhinoDoc doc, IReadOnlyList<Guid> ids)
        {
            if (ids.Count == 0) return;
            bool recording = doc.UndoRecordingEnabled;
            doc.UndoRecordingEnabled = false;
            try
            {
                foreach (var id in ids)
                {
                    var obj = doc.Objects.FindId(id);
                    if (obj == null || obj.IsDeleted) continue;
                    var mesh = obj.Geometry as Mesh;
                    var data = DiscreteSurfaceUserData.Find(obj.Geometry);
                    var decision = DiscreteSurfaceUpgrade.Decide(mesh != null, obj is DiscreteSurfaceObject, data == null ? null : data.Data);
                    if (decision.Action == UpgradeAction.Refuse)
                    {
                        if (s_queue.ShouldReport(doc.RuntimeSerialNumber, id)) RhinoApp.WriteLine("TPI: object {0} {1}.", id, decision.Message);
                        continue;
                    }
                    if (decision.Action != UpgradeAction.Upgrade) continue;
                    var copy = mesh.DuplicateMesh();
                    var copyData = DiscreteSurfaceUserData.Find(copy);
                    if (copyData == null) copy.UserData.Add(new DiscreteSurfaceUserData(decision.Document));
                    else if (decision.Migrated) copyData.Data = UserDataFormat.Write(decision.Document);
                    if (!doc.Objects.Replace(new ObjRef(doc, id), new DiscreteSurfaceObject(copy))
                        && s_queue.ShouldReport(doc.RuntimeSerialNumber, id))
                        RhinoApp.WriteLine("TPI: object {0} could not be made a discrete surface again (a locked or reference object?).", id);
                }
            }
            finally
            {
                doc.UndoRecordingEnabled = recording;
            }
        }

        static void Recompute(RhinoDoc doc, Guid id)
        {
            var obj = doc.Objects.FindId(id);
            var document = DiscreteSurfaceObject.StoredDocumentOf(obj);
            if (document == null) return;
            try
            {
                using (var state = new DiscreteSurfaceState(document))
                    DiscreteSurfaceObject.Replace(doc, new ObjRef(doc, id), state, document);
            }
            catch (Tpi.Native.TpiException ex)
            {
                RhinoApp.WriteLine("TPI: the transformed discrete surface {0} could not be recomputed: {1}", id, ex.NativeMessage);
            }
        }

        static void Follow(RhinoDoc doc, IReadOnlyList<Guid> changed)
        {
            var settings = new ObjectEnumeratorSettings { HiddenObjects = true, LockedObjects = true };
            var followers = doc.Objects.GetObjectList(settings).OfType<DiscreteSurfaceObject>().ToList();
            foreach (var obj in followers)
            {
                var document = obj.StoredDocument;
                if (document == null || !changed.Contains(document.SourceSurfaceId)) continue;
                var source = new ObjRef(doc, document.SourceSurfaceId);
                var brep = source.Object() == null ? null : source.Brep();
                SourceShape shape;
                int faceCount = brep == null ? 0 : brep.Faces.Count;
                if (source.Object() == null) shape = SourceShape.Missing;
                else if (brep != null) shape = faceCount == 1 ? SourceShape.Surface : SourceShape.Polysurface;
                else shape = source.Surface() != null ? SourceShape.Surface : SourceShape.Other;
                var decision = SourceFollow.Decide(document, shape, faceCount);
                if (!decision.Follow)
                {
                    if (decision.Message != null) RhinoApp.WriteLine("TPI: discrete surface {0} does not follow: {1}.", obj.Id, decision.Message);
                    continue;
                }
                SurfaceSpec spec;
                if (decision.WholeObject)
                {
                    // Made from a whole polysurface: its faces joined again.
                    string error;
                    spec = Tpi.Plugin.SurfaceSpecs.FromBrep(brep, out error);
                    if (spec == null) { RhinoApp.WriteLine("TPI: discrete surface {0} does not follow: {1}", obj.Id, error); continue; }
                }
                else
                {
                    Surface surface = decision.FaceIndex >= 0 && brep != null ? brep.Faces[decision.FaceIndex] : source.Surface();
                    spec = RhinoConvert.ToSpec(surface);
                }
                if (spec == null) { RhinoApp.WriteLine("TPI: discrete surface {0} does not follow: its source has no NURBS form.", obj.Id); continue; }
                try
                {
                    using (var state = new DiscreteSurfaceState(document))
                    {
                        state.ReplaceSurface(document.SurfaceFromSource(spec));
                        string error;
                        if (!state.TryRecompute(out error))
                        {
                            RhinoApp.WriteLine("TPI: discrete surface {0} could not follow its surface: {1}", obj.Id, error);
                            continue;
                        }
                        DiscreteSurfaceObject.Replace(doc, new ObjRef(doc, obj.Id), state, document);
                    }
                }
                catch (Tpi.Native.TpiException ex)
                {
                    RhinoApp.WriteLine("TPI: " + ex.NativeMessage);
                }
            }
        }
    }
}
