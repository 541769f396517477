// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157; CustomMeshObject's protected
// constructors against the RhinoCommon source). Members used: see plugin-dotnet/API-CHECK.md.
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

        /// <summary>The stored document, or null if the user data is missing.</summary>
        public DiscreteSurfaceDocument Document
        {
            get
            {
                var data = DiscreteSurfaceUserData.Find(MeshGeometry);
                return data == null || data.Data == null ? null : data.Document;
            }
        }

        /// <summary>The mesh of <paramref name="state"/> with the state's document attached.</summary>
        public static Mesh MeshOf(DiscreteSurfaceState state, Guid sourceSurfaceId)
        {
            var mesh = RhinoConvert.ToMesh(state.Mesh);
            var document = state.Document;
            document.SourceSurfaceId = sourceSurfaceId;
            mesh.UserData.Add(new DiscreteSurfaceUserData(document));
            return mesh;
        }

        /// <summary>Adds a new discrete surface for <paramref name="state"/>; returns its id.</summary>
        public static Guid Add(RhinoDoc doc, DiscreteSurfaceState state, Guid sourceSurfaceId)
        {
            var obj = new DiscreteSurfaceObject(MeshOf(state, sourceSurfaceId));
            doc.Objects.AddRhinoObject(obj);
            return obj.Id;
        }

        /// <summary>Replaces the object <paramref name="objRef"/> with one showing <paramref name="state"/> (one undo step).</summary>
        public static bool Replace(RhinoDoc doc, ObjRef objRef, DiscreteSurfaceState state, Guid sourceSurfaceId)
        {
            var obj = new DiscreteSurfaceObject(MeshOf(state, sourceSurfaceId));
            return doc.Objects.Replace(objRef, obj);
        }
    }
}
