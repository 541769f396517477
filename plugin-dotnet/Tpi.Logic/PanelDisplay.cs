// The display data of a discrete surface while it is edited (what a display conduit draws):
// per panel a closed polyline and a triangulation (n-gon boundary and faces). After an edit only
// the panels whose vertices changed are rebuilt; the rest keep their arrays. Panels are in the
// order of their pattern points (the library keeps that order), so a panel is compared with the
// panel of the same index.
//
// The library reports no changed-panel list, so finding the changed panels compares every
// panel's vertices with the previous ones: O(n) comparisons per edit (cheap next to the
// recompute and the copy of the mesh out of the library, both also O(n) today).
using System;
using System.Collections.Generic;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Per-panel display arrays kept in step with a changing mesh.</summary>
    public sealed class PanelDisplay
    {
        Vec3[][] _polylines = new Vec3[0][];
        int[][] _triangles = new int[0][];

        /// <summary>Closed polyline per panel (first vertex repeated at the end).</summary>
        public IReadOnlyList<Vec3[]> Polylines { get { return _polylines; } }

        /// <summary>Triangles per panel as vertex positions' indices into the panel's polyline (3 per triangle).</summary>
        public IReadOnlyList<int[]> Triangles { get { return _triangles; } }

        /// <summary>Number of panels.</summary>
        public int Count { get { return _polylines.Length; } }

        /// <summary>
        /// Brings the display data to <paramref name="mesh"/>; returns the indices of the panels
        /// rebuilt (all of them the first time). Panels past the new count are dropped.
        /// </summary>
        public int[] Update(MeshData mesh)
        {
            if (mesh == null) throw new ArgumentNullException("mesh");
            int n = mesh.FacetCount;
            var changed = new List<int>();
            if (n != _polylines.Length)
            {
                var polylines = new Vec3[n][];
                var triangles = new int[n][];
                int keep = Math.Min(n, _polylines.Length);
                Array.Copy(_polylines, polylines, keep);
                Array.Copy(_triangles, triangles, keep);
                _polylines = polylines;
                _triangles = triangles;
            }
            var vertices = mesh.Vertices;
            var indices = mesh.FacetIndices;
            for (int f = 0; f < n; f++)
            {
                int start = mesh.FacetStarts[f], size = mesh.FacetSizes[f];
                var old = _polylines[f];
                bool same = old != null && old.Length == size + 1;
                for (int k = 0; same && k < size; k++) same = old[k].Equals(vertices[indices[start + k]]);
                if (same) continue;
                var loop = new int[size];
                Array.Copy(indices, start, loop, 0, size);
                var polyline = new Vec3[size + 1];
                for (int k = 0; k < size; k++) polyline[k] = vertices[loop[k]];
                polyline[size] = polyline[0];
                var normal = mesh.Planes[f].Normal;
                if (normal.Length == 0) normal = MeshConversion.NewellNormal(vertices, loop);
                _polylines[f] = polyline;
                _triangles[f] = MeshConversion.Triangulate(vertices, loop, normal).ToArray();
                changed.Add(f);
            }
            return changed.ToArray();
        }

        /// <summary>
        /// <see cref="Update"/>, then keeps <paramref name="converted"/> (one item per panel, e.g.
        /// the host's point lists) in step: resized to the panel count, and
        /// <paramref name="convert"/> called only for the panels rebuilt. Returns those panels.
        /// </summary>
        public int[] UpdateInto<T>(MeshData mesh, List<T> converted, Func<Vec3[], T> convert)
        {
            if (converted == null) throw new ArgumentNullException("converted");
            if (convert == null) throw new ArgumentNullException("convert");
            var changed = Update(mesh);
            if (converted.Count > Count) converted.RemoveRange(Count, converted.Count - Count);
            while (converted.Count < Count) converted.Add(default(T));
            foreach (var f in changed) converted[f] = convert(_polylines[f]);
            return changed;
        }
    }
}
