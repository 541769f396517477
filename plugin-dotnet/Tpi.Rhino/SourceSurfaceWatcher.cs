// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: see
// plugin-dotnet/API-CHECK.md.
//
// Keeps discrete surfaces following the surface they were made from: when that surface object
// is replaced (control points moved, rebuilt, ...), every discrete surface whose stored
// SourceSurfaceId names it takes the new surface and recomputes its panels. The document must
// not be changed inside ReplaceRhinoObject, so the work waits for the next Idle.
using System;
using System.Collections.Generic;
using System.Linq;
using Rhino;
using Rhino.DocObjects;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    internal static class SourceSurfaceWatcher
    {
        static readonly HashSet<Guid> s_changed = new HashSet<Guid>();
        static uint s_docSerial;
        static bool s_started;

        public static void Start()
        {
            if (s_started) return;
            s_started = true;
            RhinoDoc.ReplaceRhinoObject += OnReplace;
            RhinoApp.Idle += OnIdle;
        }

        static void OnReplace(object sender, RhinoReplaceObjectEventArgs e)
        {
            if (e.NewRhinoObject is DiscreteSurfaceObject) return;
            lock (s_changed)
            {
                s_changed.Add(e.ObjectId);
                s_docSerial = e.Document.RuntimeSerialNumber;
            }
        }

        static void OnIdle(object sender, EventArgs e)
        {
            Guid[] changed;
            uint serial;
            lock (s_changed)
            {
                if (s_changed.Count == 0) return;
                changed = s_changed.ToArray();
                serial = s_docSerial;
                s_changed.Clear();
            }
            var doc = RhinoDoc.FromRuntimeSerialNumber(serial);
            if (doc == null) return;
            var settings = new ObjectEnumeratorSettings { HiddenObjects = true, LockedObjects = true };
            var followers = doc.Objects.GetObjectList(settings).OfType<DiscreteSurfaceObject>().ToList();
            foreach (var obj in followers)
            {
                var document = obj.Document;
                if (document == null || !changed.Contains(document.SourceSurfaceId)) continue;
                var source = new ObjRef(doc, document.SourceSurfaceId).Surface();
                var spec = RhinoConvert.ToSpec(source);
                if (spec == null) continue;
                try
                {
                    using (var state = new DiscreteSurfaceState(document))
                    {
                        state.ReplaceSurface(spec);
                        string error;
                        if (!state.TryRecompute(out error))
                        {
                            RhinoApp.WriteLine("TPI: the discrete surface could not follow its surface: " + error);
                            continue;
                        }
                        DiscreteSurfaceObject.Replace(doc, new ObjRef(doc, obj.Id), state, document.SourceSurfaceId);
                    }
                }
                catch (Tpi.Native.TpiException ex)
                {
                    RhinoApp.WriteLine("TPI: " + ex.Message);
                }
            }
            doc.Views.Redraw();
        }
    }
}
