// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from
// the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md). Conversions only: RhinoCommon types <-> Tpi.Logic plain data.
using System.Collections.Generic;
using System.Linq;
using Rhino.Geometry;
using Tpi.Logic;
using Domain = Tpi.Native.Domain;
using FacetPlane = Tpi.Native.FacetPlane;
using PatternPoint = Tpi.Native.PatternPoint;
using Vec3 = Tpi.Native.Vec3;

namespace Tpi.RhinoPlugIn
{
    internal static class RhinoConvert
    {
        /// <summary>The NURBS form of a surface as the library takes it, with a Brep face's trim (Shared/SurfaceSpecs.cs).</summary>
        public static NurbsSurfaceSpec ToSpec(Surface surface) { return Tpi.Plugin.SurfaceSpecs.ToSpec(surface); }

        /// <summary>A RhinoCommon NURBS surface from the stored spec (the exact surface that was discretised).</summary>
        public static NurbsSurface ToNurbsSurface(NurbsSurfaceSpec spec)
        {
            var ns = NurbsSurface.Create(3, spec.IsRational, spec.DegreeU + 1, spec.DegreeV + 1, spec.CountU, spec.CountV);
            if (ns == null) return null;
            for (int k = 0; k < spec.KnotsU.Count && k < ns.KnotsU.Count; k++) ns.KnotsU[k] = spec.KnotsU[k];
            for (int k = 0; k < spec.KnotsV.Count && k < ns.KnotsV.Count; k++) ns.KnotsV[k] = spec.KnotsV[k];
            for (int i = 0; i < spec.CountU; i++)
                for (int j = 0; j < spec.CountV; j++)
                {
                    var p = spec.ControlPoint(i, j);
                    double w = spec.IsRational ? spec.Weights[i * spec.CountV + j] : 1.0;
                    ns.Points.SetControlPoint(i, j, new ControlPoint(p.X, p.Y, p.Z, w));
                }
            return ns.IsValid ? ns : null;
        }

        public static Point3d ToPoint(Vec3 v) { return new Point3d(v.X, v.Y, v.Z); }

        public static Vec3 ToVec3(Point3d p) { return new Vec3(p.X, p.Y, p.Z); }

        public static Polyline ToPolyline(Vec3[] points) { return new Polyline(points.Select(ToPoint)); }

        public static Plane ToPlane(FacetPlane plane)
        {
            return new Plane(ToPoint(plane.Point), new Vector3d(plane.Normal.X, plane.Normal.Y, plane.Normal.Z));
        }

        /// <summary>A mesh with double-precision vertices, one triangle fan per facet and one n-gon per facet.</summary>
        public static Mesh ToMesh(MeshData data)
        {
            var ngonMesh = MeshConversion.ToNgonMesh(data);
            var mesh = new Mesh();
            mesh.Vertices.UseDoublePrecisionVertices = true;
            foreach (var v in ngonMesh.Vertices) mesh.Vertices.Add(v.X, v.Y, v.Z);
            for (int t = 0; t < ngonMesh.TriangleCount; t++)
                mesh.Faces.AddFace(ngonMesh.Triangles[3 * t], ngonMesh.Triangles[3 * t + 1], ngonMesh.Triangles[3 * t + 2]);
            foreach (var ngon in ngonMesh.Ngons)
                mesh.Ngons.AddNgon(MeshNgon.Create(ngon.BoundaryVertices, ngon.Faces));
            mesh.Normals.ComputeNormals();
            return mesh;
        }

        /// <summary>A flat loop at height <paramref name="z"/>.</summary>
        public static Point3d[] ToPoints(Point2[] loop, double z)
        {
            return loop.Select(p => new Point3d(p.X, p.Y, z)).ToArray();
        }

        /// <summary>RhinoCommon's transform as 16 numbers, row-major (SurfaceSpec.Transformed's convention).</summary>
        public static double[] ToMatrix(Transform xform)
        {
            var m = new double[16];
            for (int r = 0; r < 4; r++)
                for (int c = 0; c < 4; c++)
                    m[4 * r + c] = xform[r, c];
            return m;
        }

        /// <summary>The point on <paramref name="surface"/> at normalised (s, t).</summary>
        public static Point3d PointAt(Surface surface, PatternPoint p)
        {
            var du = surface.Domain(0);
            var dv = surface.Domain(1);
            return surface.PointAt(du.T0 + p.S * (du.T1 - du.T0), dv.T0 + p.T * (dv.T1 - dv.T0));
        }

        /// <summary>Normalised (s, t) of the surface point closest to <paramref name="point"/>; false if none or outside.</summary>
        public static bool TryNormalisedClosest(Surface surface, Point3d point, out PatternPoint st, out string error)
        {
            st = new PatternPoint();
            double u, v;
            if (!surface.ClosestPoint(point, out u, out v)) { error = "no closest point on the surface"; return false; }
            var du = surface.Domain(0);
            var dv = surface.Domain(1);
            return InputValidation.TryNormalise(new Domain(du.T0, du.T1, dv.T0, dv.T1), u, v, out st, out error);
        }

        /// <summary>A polyline drawn on the surface through (s, t) points, each segment subdivided so it follows the surface.</summary>
        public static List<Point3d> OnSurface(Surface surface, IReadOnlyList<PatternPoint> loop, int subdivisions)
        {
            var points = new List<Point3d>();
            for (int k = 0; k < loop.Count; k++)
            {
                var a = loop[k];
                var b = loop[(k + 1) % loop.Count];
                for (int i = 0; i < subdivisions; i++)
                {
                    double f = (double)i / subdivisions;
                    points.Add(PointAt(surface, new PatternPoint(a.S + f * (b.S - a.S), a.T + f * (b.T - a.T))));
                }
            }
            if (points.Count > 0) points.Add(points[0]);
            return points;
        }
    }
}
