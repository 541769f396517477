// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from the
// compiled adapters and checked against the stubs (plugin-dotnet/API-CHECK.md). Linked into
// Tpi.Rhino and Tpi.Grasshopper: a fabricated solid as a RhinoCommon mesh, in one place for both.
using System.Collections.Generic;
using Rhino.Geometry;
using Tpi.Logic;

namespace Tpi.Plugin
{
    internal static class SolidMeshes
    {
        /// <summary>A closed polyhedron (a fabricated panel or cleat) as a mesh: each planar face ear-clipped into triangles and kept as one n-gon.</summary>
        public static Mesh ToMesh(PolyhedronData solid)
        {
            var mesh = new Mesh();
            mesh.Vertices.UseDoublePrecisionVertices = true;
            foreach (var v in solid.Vertices) mesh.Vertices.Add(v.X, v.Y, v.Z);
            foreach (var face in solid.Faces)
            {
                var triangles = FabricationLayout.Triangulate(solid.Vertices, face);
                var faceIndices = new List<int>();
                for (int t = 0; t < triangles.Length; t += 3)
                    faceIndices.Add(mesh.Faces.AddFace(triangles[t], triangles[t + 1], triangles[t + 2]));
                if (faceIndices.Count > 0) mesh.Ngons.AddNgon(MeshNgon.Create(face, faceIndices));
            }
            mesh.Normals.ComputeNormals();
            return mesh;
        }
    }
}
