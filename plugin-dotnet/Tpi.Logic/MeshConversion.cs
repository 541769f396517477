// Conversions from the library's facet lists to what Rhino and Grasshopper want: one closed
// polyline per facet, and a triangle mesh with one n-gon per facet (Rhino's MeshNgon: the
// facet's boundary vertices plus the triangles that fill it). Facets on saddle regions are not
// convex, so each facet is triangulated by ear clipping in its own plane, not as a fan.
using System;
using System.Collections.Generic;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>One n-gon: its boundary loop (mesh vertex indices) and the triangles filling it.</summary>
    public sealed class Ngon
    {
        /// <summary>Boundary vertex indices, counter-clockwise seen from the facet normal.</summary>
        public int[] BoundaryVertices { get; internal set; }
        /// <summary>Indices of the triangles (into <see cref="NgonMesh.Triangles"/> / 3) that fill it.</summary>
        public int[] Faces { get; internal set; }
    }

    /// <summary>A triangle mesh with one n-gon per facet.</summary>
    public sealed class NgonMesh
    {
        /// <summary>Vertices (shared by neighbouring facets).</summary>
        public Vec3[] Vertices { get; internal set; }
        /// <summary>Triangles, 3 vertex indices each, oriented like their facet.</summary>
        public int[] Triangles { get; internal set; }
        /// <summary>One n-gon per facet, in facet order.</summary>
        public Ngon[] Ngons { get; internal set; }
        /// <summary>Number of triangles.</summary>
        public int TriangleCount { get { return Triangles.Length / 3; } }
    }

    /// <summary>Facet lists to polylines and n-gon meshes.</summary>
    public static class MeshConversion
    {
        /// <summary>One closed polyline per facet: its vertices with the first repeated at the end.</summary>
        public static Vec3[][] FacetPolylines(MeshData mesh)
        {
            var polylines = new Vec3[mesh.FacetCount][];
            for (int f = 0; f < polylines.Length; f++)
            {
                var loop = mesh.Facet(f);
                var polyline = new Vec3[loop.Length + 1];
                for (int k = 0; k < loop.Length; k++) polyline[k] = mesh.Vertices[loop[k]];
                polyline[loop.Length] = polyline[0];
                polylines[f] = polyline;
            }
            return polylines;
        }

        /// <summary>The triangle mesh with one n-gon per facet.</summary>
        public static NgonMesh ToNgonMesh(MeshData mesh)
        {
            var triangles = new List<int>();
            var ngons = new Ngon[mesh.FacetCount];
            for (int f = 0; f < ngons.Length; f++)
            {
                var loop = mesh.Facet(f);
                var normal = mesh.Planes[f].Normal;
                if (normal.Length == 0) normal = NewellNormal(mesh.Vertices, loop);
                var local = Triangulate(mesh.Vertices, loop, normal);
                var faces = new int[local.Count / 3];
                for (int t = 0; t < faces.Length; t++)
                {
                    faces[t] = triangles.Count / 3;
                    triangles.Add(loop[local[3 * t]]);
                    triangles.Add(loop[local[3 * t + 1]]);
                    triangles.Add(loop[local[3 * t + 2]]);
                }
                ngons[f] = new Ngon { BoundaryVertices = loop, Faces = faces };
            }
            return new NgonMesh { Vertices = (Vec3[])mesh.Vertices.Clone(), Triangles = triangles.ToArray(), Ngons = ngons };
        }

        /// <summary>Number of sides of each facet.</summary>
        public static int[] SideCounts(MeshData mesh) { return (int[])mesh.FacetSizes.Clone(); }

        /// <summary>Largest distance of each facet's vertices from its tangent plane (model units).</summary>
        public static double[] PlanarityErrors(MeshData mesh)
        {
            var errors = new double[mesh.FacetCount];
            for (int f = 0; f < errors.Length; f++)
            {
                double worst = 0;
                foreach (var v in mesh.Facet(f))
                    worst = Math.Max(worst, Math.Abs(mesh.Planes[f].SignedDistance(mesh.Vertices[v])));
                errors[f] = worst;
            }
            return errors;
        }

        /// <summary>Area of each facet (by the shoelace formula in its plane).</summary>
        public static double[] FacetAreas(MeshData mesh)
        {
            var areas = new double[mesh.FacetCount];
            for (int f = 0; f < areas.Length; f++)
            {
                var loop = mesh.Facet(f);
                var normal = NewellNormal(mesh.Vertices, loop);
                areas[f] = 0.5 * normal.Length;
            }
            return areas;
        }

        /// <summary>Newell's normal of a loop: twice the area vector.</summary>
        internal static Vec3 NewellNormal(Vec3[] vertices, int[] loop)
        {
            var n = new Vec3();
            for (int k = 0; k < loop.Length; k++)
            {
                var a = vertices[loop[k]];
                var b = vertices[loop[(k + 1) % loop.Length]];
                n = n + Vec3.Cross(a, b);
            }
            return n;
        }

        /// <summary>
        /// Ear clipping of a simple polygon given counter-clockwise about <paramref name="normal"/>;
        /// returns local corner indices, 3 per triangle (k - 2 triangles). A polygon that is not
        /// simple falls back to a fan for what is left, so every facet is always filled.
        /// </summary>
        internal static List<int> Triangulate(Vec3[] vertices, int[] loop, Vec3 normal)
        {
            int n = loop.Length;
            var result = new List<int>(3 * Math.Max(0, n - 2));
            if (n < 3) return result;
            // A 2D frame in the facet's plane.
            var nz = (1 / Math.Max(normal.Length, 1e-300)) * normal;
            var helper = Math.Abs(nz.X) < 0.9 ? new Vec3(1, 0, 0) : new Vec3(0, 1, 0);
            var ex = Vec3.Cross(helper, nz); ex = (1 / ex.Length) * ex;
            var ey = Vec3.Cross(nz, ex);
            var x = new double[n]; var y = new double[n];
            for (int k = 0; k < n; k++)
            {
                var p = vertices[loop[k]];
                x[k] = Vec3.Dot(p, ex); y[k] = Vec3.Dot(p, ey);
            }
            var remaining = new List<int>();
            for (int k = 0; k < n; k++) remaining.Add(k);
            int guard = 0;
            while (remaining.Count > 3 && guard < n * n)
            {
                guard++;
                bool clipped = false;
                for (int i = 0; i < remaining.Count; i++)
                {
                    int a = remaining[(i + remaining.Count - 1) % remaining.Count], b = remaining[i], c = remaining[(i + 1) % remaining.Count];
                    double cross = (x[b] - x[a]) * (y[c] - y[a]) - (y[b] - y[a]) * (x[c] - x[a]);
                    if (cross <= 0) continue; // reflex or degenerate corner
                    bool inside = false;
                    foreach (int p in remaining)
                    {
                        if (p == a || p == b || p == c) continue;
                        if (InTriangle(x[p], y[p], x[a], y[a], x[b], y[b], x[c], y[c])) { inside = true; break; }
                    }
                    if (inside) continue;
                    result.Add(a); result.Add(b); result.Add(c);
                    remaining.RemoveAt(i);
                    clipped = true;
                    break;
                }
                if (!clipped) break;
            }
            // Three left (the usual end), or a polygon that is not simple: fan what is left.
            for (int i = 1; i + 1 < remaining.Count; i++)
            {
                result.Add(remaining[0]); result.Add(remaining[i]); result.Add(remaining[i + 1]);
            }
            return result;
        }

        static bool InTriangle(double px, double py, double ax, double ay, double bx, double by, double cx, double cy)
        {
            double d1 = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
            double d2 = (cx - bx) * (py - by) - (cy - by) * (px - bx);
            double d3 = (ax - cx) * (py - cy) - (ay - cy) * (px - cx);
            return d1 >= 0 && d2 >= 0 && d3 >= 0;
        }
    }
}
