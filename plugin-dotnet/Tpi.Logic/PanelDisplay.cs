// The display data of a discrete surface while it is edited (what a display conduit draws):
// per panel a closed polyline and a triangulation (n-gon boundary and faces). After an edit only
// the panels whose vertices changed are rebuilt; the rest keep their arrays. Panels are in the
// order of their pattern points (the library keeps that order), so a panel is compared with the
// panel of the same index.
//
// Two sources: a LiveMeshData (kept in step with the library's change snapshots), whose list of
// changed facets says which panels to look at, so an edit costs O(what changed); or a MeshData
// copied out whole, where every panel's vertices are compared with the previous ones (O(n)).
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
        // The live mesh of the last update and its version then (null after a MeshData update).
        LiveMeshData _live;
        int _liveVersion;

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
            Resize(n);
            _live = null;
            var vertices = mesh.Vertices;
            var indices = mesh.FacetIndices;
            for (int f = 0; f < n; f++)
            {
                int start = mesh.FacetStarts[f], size = mesh.FacetSizes[f];
                if (Same(_polylines[f], vertices, indices, start, size)) continue;
                var loop = new int[size];
                Array.Copy(indices, start, loop, 0, size);
                Rebuild(f, vertices, loop, mesh.Planes[f]);
                changed.Add(f);
            }
            return changed.ToArray();
        }

        /// <summary>
        /// Brings the display data to <paramref name="mesh"/>, looking only at the facets it
        /// changed since the last update from it (<see cref="LiveMeshData.ChangedSince"/>; every
        /// facet the first time, after a change of everything, or after another mesh); returns
        /// the indices of the panels rebuilt: those whose vertices differ from before. Panels
        /// past the new count are dropped.
        /// </summary>
        public int[] Update(LiveMeshData mesh)
        {
            if (mesh == null) throw new ArgumentNullException("mesh");
            int n = mesh.FacetCount;
            var listed = ReferenceEquals(mesh, _live) ? mesh.ChangedSince(_liveVersion) : null;
            Resize(n);
            _live = mesh;
            _liveVersion = mesh.Version;
            var vertices = mesh.Positions;
            var changed = new List<int>();
            int count = listed == null ? n : listed.Length;
            for (int k = 0; k < count; k++)
            {
                int f = listed == null ? k : listed[k];
                var loop = mesh.Loop(f);
                if (Same(_polylines[f], vertices, loop, 0, loop.Length)) continue;
                Rebuild(f, vertices, loop, mesh.GetPlane(f));
                changed.Add(f);
            }
            return changed.ToArray();
        }

        /// <summary>Keeps the first <paramref name="n"/> panels (or adds empty ones up to it).</summary>
        void Resize(int n)
        {
            if (n == _polylines.Length) return;
            var polylines = new Vec3[n][];
            var triangles = new int[n][];
            int keep = Math.Min(n, _polylines.Length);
            Array.Copy(_polylines, polylines, keep);
            Array.Copy(_triangles, triangles, keep);
            _polylines = polylines;
            _triangles = triangles;
        }

        /// <summary>Whether a panel's polyline has exactly the vertices indices[start .. start + size).</summary>
        static bool Same(Vec3[] old, Vec3[] vertices, int[] indices, int start, int size)
        {
            bool same = old != null && old.Length == size + 1;
            for (int k = 0; same && k < size; k++) same = old[k].Equals(vertices[indices[start + k]]);
            return same;
        }

        /// <summary>Panel f's polyline and triangles from its loop (indices into <paramref name="vertices"/>).</summary>
        void Rebuild(int f, Vec3[] vertices, int[] loop, FacetPlane plane)
        {
            int size = loop.Length;
            var polyline = new Vec3[size + 1];
            for (int k = 0; k < size; k++) polyline[k] = vertices[loop[k]];
            polyline[size] = polyline[0];
            var normal = plane.Normal;
            if (normal.Length == 0) normal = MeshConversion.NewellNormal(vertices, loop);
            _polylines[f] = polyline;
            _triangles[f] = MeshConversion.Triangulate(vertices, loop, normal).ToArray();
        }

        /// <summary>
        /// <see cref="Update(MeshData)"/>, then keeps <paramref name="converted"/> (one item per panel, e.g.
        /// the host's point lists) in step: resized to the panel count, and
        /// <paramref name="convert"/> called only for the panels rebuilt. Returns those panels.
        /// </summary>
        public int[] UpdateInto<T>(MeshData mesh, List<T> converted, Func<Vec3[], T> convert)
        {
            if (converted == null) throw new ArgumentNullException("converted");
            if (convert == null) throw new ArgumentNullException("convert");
            return Converted(Update(mesh), converted, convert);
        }

        /// <summary>
        /// <see cref="Update(LiveMeshData)"/>, then keeps <paramref name="converted"/> in step as
        /// <see cref="UpdateInto{T}(MeshData, List{T}, Func{Vec3[], T})"/> does. Returns the panels rebuilt.
        /// </summary>
        public int[] UpdateInto<T>(LiveMeshData mesh, List<T> converted, Func<Vec3[], T> convert)
        {
            if (converted == null) throw new ArgumentNullException("converted");
            if (convert == null) throw new ArgumentNullException("convert");
            return Converted(Update(mesh), converted, convert);
        }

        int[] Converted<T>(int[] changed, List<T> converted, Func<Vec3[], T> convert)
        {
            if (converted.Count > Count) converted.RemoveRange(Count, converted.Count - Count);
            while (converted.Count < Count) converted.Add(default(T));
            foreach (var f in changed) converted[f] = convert(_polylines[f]);
            return changed;
        }
    }
}
