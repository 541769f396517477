// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157; CustomMeshObject's protected
// constructors against the RhinoCommon source). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System;
using System.Runtime.InteropServices;
using Rhino;
using Rhino.DocObjects;
using Rhino.DocObjects.Custom;
using Rhino.Geometry;
using Tpi.Logic;

namespace Tpi.RhinoPlugIn
{
    /// <summary>
    /// The discrete surface in the document: a mesh of planar panels (one n-gon per pattern
    /// point) whose surface and pattern live in <see cref="DiscreteSurfaceUserData"/> on the mesh.
    /// </summary>
    [Guid("9D3E2A61-2F4B-4F0C-8C1B-6A7E5D4C3B02")]
    public sealed class DiscreteSurfaceObject : CustomMeshObject
    {
        /// <summary>Rhino makes instances with this when it reads a file or duplicates the object.</summary>
        public DiscreteSurfaceObject() : base() { }

        /// <summary>An object showing <paramref name="mesh"/> (which carries the user data).</summary>
        public DiscreteSurfaceObject(Mesh mesh) : base(mesh) { }

        /// <inheritdoc/>
        public override string ShortDescription(bool plural)
        {
            return plural ? "discrete surfaces" : "discrete surface";
        }

        /// <summary>
        /// The stored document, or null if the user data is missing or unreadable. (Not named
        /// Document: that is RhinoObject.Document, the RhinoDoc.)
        /// </summary>
        public DiscreteSurfaceDocument StoredDocument { get { return StoredDocumentOf(this); } }

        /// <summary>
        /// The document stored on any object's geometry: a discrete surface object, or a plain
        /// mesh object carrying the data that has not been upgraded yet (just opened or pasted).
        /// Null if there is none or it cannot be read.
        /// </summary>
        public static DiscreteSurfaceDocument StoredDocumentOf(RhinoObject obj)
        {
            var data = obj == null ? null : DiscreteSurfaceUserData.Find(obj.Geometry);
            if (data == null || data.Data == null) return null;
            try { return UserDataFormat.Read(data.Data); }
            catch (FormatException) { return null; }
        }

        /// <summary>
        /// True if <paramref name="obj"/> is or will become a discrete surface (a filter for
        /// GetObject, called for every candidate: it looks for the data without reading it).
        /// </summary>
        public static bool IsDiscreteSurface(RhinoObject obj)
        {
            if (obj is DiscreteSurfaceObject) return true;
            var data = obj == null ? null : DiscreteSurfaceUserData.Find(obj.Geometry);
            return data != null && data.Data != null;
        }

        /// <summary>The mesh of <paramref name="state"/> with <paramref name="document"/> (the state's, plus source id, face and transform) attached.</summary>
        public static Mesh MeshOf(DiscreteSurfaceState state, DiscreteSurfaceDocument document)
        {
            var mesh = RhinoConvert.ToMesh(state.Mesh);
            mesh.UserData.Add(new DiscreteSurfaceUserData(document));
            return mesh;
        }

        /// <summary>The state's document with the follow fields (source id, face, transform) of <paramref name="follow"/>.</summary>
        public static DiscreteSurfaceDocument WithFollow(DiscreteSurfaceState state, DiscreteSurfaceDocument follow)
        {
            var document = state.Document;
            document.SourceSurfaceId = follow.SourceSurfaceId;
            document.SourceFaceIndex = follow.SourceFaceIndex;
            document.SourceTransform = follow.SourceTransform;
            return document;
        }

        /// <summary>Adds a new discrete surface for <paramref name="state"/>; returns its id.</summary>
        public static Guid Add(RhinoDoc doc, DiscreteSurfaceState state, DiscreteSurfaceDocument follow)
        {
            var obj = new DiscreteSurfaceObject(MeshOf(state, WithFollow(state, follow)));
            doc.Objects.AddRhinoObject(obj);
            return obj.Id;
        }

        /// <summary>Replaces the object <paramref name="objRef"/> with one showing <paramref name="state"/> (one undo step).</summary>
        public static bool Replace(RhinoDoc doc, ObjRef objRef, DiscreteSurfaceState state, DiscreteSurfaceDocument follow)
        {
            var obj = new DiscreteSurfaceObject(MeshOf(state, WithFollow(state, follow)));
            return doc.Objects.Replace(objRef, obj);
        }
    }
}
