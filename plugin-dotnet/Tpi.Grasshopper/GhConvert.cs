// Checked against: RhinoCommon 8 and Grasshopper 8 (stubs 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md). Conversions between RhinoCommon types and Tpi.Logic data.
using System.Collections.Generic;
using System.Linq;
using Rhino.Geometry;
using Tpi.Logic;
using Domain = Tpi.Native.Domain;
using FacetPlane = Tpi.Native.FacetPlane;
using PatternPoint = Tpi.Native.PatternPoint;
using Vec3 = Tpi.Native.Vec3;

namespace Tpi.GhComponents
{
    internal static class GhConvert
    {
        public static NurbsSurfaceSpec ToSpec(Surface surface) { return Tpi.Plugin.SurfaceSpecs.ToSpec(surface); }

        public static Point3d ToPoint(Vec3 v) { return new Point3d(v.X, v.Y, v.Z); }

        public static Polyline ToPolyline(Vec3[] points) { return new Polyline(points.Select(ToPoint)); }

        public static Plane ToPlane(FacetPlane p)
        {
            return new Plane(ToPoint(p.Point), new Vector3d(p.Normal.X, p.Normal.Y, p.Normal.Z));
        }

        public static Mesh ToMesh(NgonMesh ngonMesh)
        {
            var mesh = new Mesh();
            mesh.Vertices.UseDoublePrecisionVertices = true;
            foreach (var v in ngonMesh.Vertices) mesh.Vertices.Add(v.X, v.Y, v.Z);
            for (int t = 0; t < ngonMesh.TriangleCount; t++)
                mesh.Faces.AddFace(ngonMesh.Triangles[3 * t], ngonMesh.Triangles[3 * t + 1], ngonMesh.Triangles[3 * t + 2]);
            foreach (var ngon in ngonMesh.Ngons) mesh.Ngons.AddNgon(MeshNgon.Create(ngon.BoundaryVertices, ngon.Faces));
            mesh.Normals.ComputeNormals();
            return mesh;
        }

        /// <summary>A flat closed loop at height <paramref name="z"/> as a polyline curve.</summary>
        public static PolylineCurve ToCurve(Point2[] loop, double z)
        {
            return new PolylineCurve(loop.Select(p => new Point3d(p.X, p.Y, z)));
        }

        /// <summary>(u, v) of the closest surface points, in the surface's domain; unreachable points are skipped.</summary>
        public static List<PatternPoint> ClosestParameters(Surface surface, IEnumerable<Point3d> points, List<string> problems)
        {
            var result = new List<PatternPoint>();
            int index = 0;
            foreach (var p in points)
            {
                double u, v;
                if (surface.ClosestPoint(p, out u, out v)) result.Add(new PatternPoint(u, v));
                else problems.Add("point " + index + ": no closest point on the surface");
                index++;
            }
            return result;
        }

        public static Point3d PointAt(Surface surface, PatternPoint p)
        {
            var du = surface.Domain(0);
            var dv = surface.Domain(1);
            return surface.PointAt(du.T0 + p.S * (du.T1 - du.T0), dv.T0 + p.T * (dv.T1 - dv.T0));
        }
    }
}
