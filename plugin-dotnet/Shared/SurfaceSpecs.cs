// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157). Members used: read from the
// compiled adapters and checked against the stubs (plugin-dotnet/API-CHECK.md). Linked into
// Tpi.Rhino and Tpi.Grasshopper: a RhinoCommon surface (a Brep face with its trim) as the
// library takes it, in one place for both adapters.
using System.Collections.Generic;
using Rhino.Geometry;
using Tpi.Logic;
using Domain = Tpi.Native.Domain;

namespace Tpi.Plugin
{
    internal static class SurfaceSpecs
    {
        /// <summary>The NURBS form of a surface as the library takes it (Rhino knot convention, u-major, Euclidean points), with a Brep face's trim.</summary>
        public static NurbsSurfaceSpec ToSpec(Surface surface)
        {
            var ns = surface == null ? null : surface.ToNurbsSurface();
            if (ns == null) return null;
            int cu = ns.Points.CountU, cv = ns.Points.CountV;
            var ku = new double[ns.KnotsU.Count];
            for (int k = 0; k < ku.Length; k++) ku[k] = ns.KnotsU[k];
            var kv = new double[ns.KnotsV.Count];
            for (int k = 0; k < kv.Length; k++) kv[k] = ns.KnotsV[k];
            var points = new double[3 * cu * cv];
            var weights = ns.IsRational ? new double[cu * cv] : null;
            for (int i = 0, k = 0; i < cu; i++)
                for (int j = 0; j < cv; j++, k++)
                {
                    var cp = ns.Points.GetControlPoint(i, j);
                    points[3 * k] = cp.Location.X; points[3 * k + 1] = cp.Location.Y; points[3 * k + 2] = cp.Location.Z;
                    if (weights != null) weights[k] = cp.Weight;
                }
            var spec = new NurbsSurfaceSpec(ns.Degree(0), ns.Degree(1), cu, cv, ku, kv, points, weights);
            // A Brep face keeps its trim: the library leaves the pattern points outside it out
            // (or refuses the trim with a message), it never discretises the untrimmed surface.
            var trim = TrimOf(surface);
            return trim == null ? spec : (NurbsSurfaceSpec)spec.WithTrim(trim);
        }

        /// <summary>
        /// The surface of a whole Brep: its only face (with the face's trim), or all its faces
        /// joined as one polysurface, each face as its untrimmed NURBS surface. A face trimmed
        /// beyond its natural boundary in a Brep of several faces is not dropped silently: the
        /// result is null and <paramref name="error"/> says that trimmed faces are not supported
        /// in a polysurface yet (PolysurfaceSpec.FromFaces decides, Rhino-free).
        /// </summary>
        public static SurfaceSpec FromBrep(Brep brep, out string error)
        {
            error = null;
            if (brep == null || brep.Faces == null) { error = "the object is not a surface or polysurface"; return null; }
            var faces = new List<SurfaceSpec>(brep.Faces.Count);
            for (int k = 0; k < brep.Faces.Count; k++) faces.Add(ToSpec(brep.Faces[k]));
            return PolysurfaceSpec.FromFaces(faces, out error);
        }

        /// <summary>
        /// The trim of a Brep face (its outer and inner loops' 2D curves sampled into polylines
        /// in the face's parameters), or null for a plain surface or a face that is its whole
        /// domain. The geometry (orientation, closing point, "whole domain") is SurfaceTrim's.
        /// </summary>
        public static SurfaceTrim TrimOf(Surface surface)
        {
            var face = surface as BrepFace;
            if (face == null || face.Loops == null) return null;
            var du = face.Domain(0);
            var dv = face.Domain(1);
            var domain = new Domain(du.T0, du.T1, dv.T0, dv.T1);
            double tolerance = SurfaceTrim.SamplingTolerance(domain);
            double[] outer = null;
            var holes = new List<IList<double>>();
            for (int k = 0; k < face.Loops.Count; k++)
            {
                var loop = face.Loops[k];
                if (loop == null || (loop.LoopType != BrepLoopType.Outer && loop.LoopType != BrepLoopType.Inner)) continue;
                var curve = loop.To2dCurve();
                var polyline = curve == null ? null : curve.ToPolyline(tolerance, 0.01, 0, 0);
                if (polyline == null) return SurfaceTrim.Unsampled();
                var flat = new double[2 * polyline.PointCount];
                for (int i = 0; i < polyline.PointCount; i++)
                {
                    var p = polyline.Point(i);
                    flat[2 * i] = p.X; flat[2 * i + 1] = p.Y;
                }
                if (loop.LoopType == BrepLoopType.Outer) outer = flat; else holes.Add(flat);
            }
            if (outer == null) return holes.Count == 0 ? null : SurfaceTrim.Unsampled();
            return SurfaceTrim.FromLoops(outer, holes, domain, tolerance);
        }
    }
}
