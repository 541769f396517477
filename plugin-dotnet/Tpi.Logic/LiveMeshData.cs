// The mesh of a discrete surface while it is edited, kept in step with the library's change
// snapshots (MeshChanges) instead of copying the whole mesh out after every edit: vertex
// positions by the library's live vertex ids, one loop and one plane per facet. Applying the
// changes of one dragged point touches about 7 facets and 12 vertices whatever the mesh's size;
// a snapshot that lists everything (the first one, and after a recompute that ran the whole
// pipeline) rebuilds it. ToMeshData() gives the same vertices and loops as MeshData.From of the
// library's own mesh (vertices numbered by first appearance in facet order, as the library
// numbers them).
using System;
using System.Collections.Generic;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>A discrete surface's mesh kept up to date from <see cref="MeshChanges"/>. Not thread-safe.</summary>
    public sealed class LiveMeshData
    {
        /// <summary>Change lists kept for <see cref="ChangedSince"/>: older ones are forgotten.</summary>
        public const int ChangeHistory = 64;

        Vec3[] _positions = new Vec3[0];
        int[][] _loops = new int[0][];
        FacetPlane[] _planes = new FacetPlane[0];
        int _facetCount;
        int _version;
        int _everythingVersion;
        // (version, facets listed by that application), oldest first.
        readonly Queue<KeyValuePair<int, int[]>> _history = new Queue<KeyValuePair<int, int[]>>();

        /// <summary>An empty mesh; the first <see cref="Apply"/> (a snapshot of everything) fills it.</summary>
        public LiveMeshData() { }

        /// <summary>Number of facets (facet i belongs to pattern point i).</summary>
        public int FacetCount { get { return _facetCount; } }

        /// <summary>One more than the largest vertex id.</summary>
        public int VertexIdBound { get { return _positions.Length; } }

        /// <summary>Incremented by every <see cref="Apply"/>.</summary>
        public int Version { get { return _version; } }

        /// <summary>Positions by vertex id (ids no facet holds have stale or default positions).</summary>
        internal Vec3[] Positions { get { return _positions; } }

        /// <summary>Facet f's loop in vertex ids (the array itself: do not modify).</summary>
        internal int[] Loop(int facet) { return _loops[facet]; }

        /// <summary>Facet <paramref name="facet"/>'s loop in vertex ids (a copy).</summary>
        public int[] GetFacet(int facet)
        {
            CheckFacet(facet);
            return (int[])_loops[facet].Clone();
        }

        /// <summary>The position of vertex <paramref name="id"/>.</summary>
        public Vec3 GetVertex(int id)
        {
            if (id < 0 || id >= _positions.Length) throw new ArgumentOutOfRangeException("id", id, "there are " + _positions.Length + " vertex ids");
            return _positions[id];
        }

        /// <summary>Facet <paramref name="facet"/>'s plane.</summary>
        public FacetPlane GetPlane(int facet)
        {
            CheckFacet(facet);
            return _planes[facet];
        }

        /// <summary>Facet <paramref name="facet"/>'s vertex positions, counter-clockwise seen from its normal.</summary>
        public Vec3[] FacetPoints(int facet)
        {
            CheckFacet(facet);
            var loop = _loops[facet];
            var points = new Vec3[loop.Length];
            for (int k = 0; k < loop.Length; k++) points[k] = _positions[loop[k]];
            return points;
        }

        void CheckFacet(int facet)
        {
            if (facet < 0 || facet >= _facetCount) throw new ArgumentOutOfRangeException("facet", facet, "there are " + _facetCount + " facets");
        }

        /// <summary>
        /// Brings the mesh to the state after <paramref name="changes"/> (which must be the next
        /// snapshot of the same discrete surface, or one of everything); returns the facets it
        /// listed (every facet for a snapshot of everything).
        /// </summary>
        public int[] Apply(MeshChanges changes)
        {
            if (changes == null) throw new ArgumentNullException("changes");
            if (!changes.Everything && _version == 0) throw new ArgumentException("the first changes applied must list everything", "changes");
            int n = changes.FacetCount;
            if (changes.Everything)
            {
                _positions = new Vec3[changes.VertexIdBound];
                _loops = new int[n][];
                _planes = new FacetPlane[n];
            }
            else
            {
                if (changes.VertexIdBound > _positions.Length) Array.Resize(ref _positions, Math.Max(changes.VertexIdBound, _positions.Length + _positions.Length / 2));
                if (n > _loops.Length)
                {
                    int capacity = Math.Max(n, _loops.Length + _loops.Length / 8 + 4);
                    Array.Resize(ref _loops, capacity);
                    Array.Resize(ref _planes, capacity);
                }
                for (int f = n; f < _facetCount; f++) _loops[f] = null;
            }
            _facetCount = n;
            var facets = changes.Facets;
            for (int k = 0; k < facets.Length; k++)
            {
                int f = facets[k], start = changes.FacetStarts[k];
                var loop = new int[changes.FacetStarts[k + 1] - start];
                Array.Copy(changes.FacetIndices, start, loop, 0, loop.Length);
                _loops[f] = loop;
                _planes[f] = changes.Planes[k];
            }
            var ids = changes.VertexIds;
            for (int k = 0; k < ids.Length; k++) _positions[ids[k]] = changes.Vertices[k];
            _version++;
            if (changes.Everything)
            {
                _everythingVersion = _version;
                _history.Clear();
            }
            else
            {
                _history.Enqueue(new KeyValuePair<int, int[]>(_version, facets));
                while (_history.Count > ChangeHistory) _history.Dequeue();
            }
            return facets;
        }

        /// <summary>
        /// The facets listed by the applications after version <paramref name="version"/>
        /// (sorted, without repeats; facets at or past <see cref="FacetCount"/> left out), or null
        /// when they are not known: a snapshot of everything was applied since, or it is more than
        /// <see cref="ChangeHistory"/> applications ago.
        /// </summary>
        public int[] ChangedSince(int version)
        {
            if (version < _everythingVersion || version > _version) return null;
            if (version == _version) return new int[0];
            if (_history.Count == 0 || _history.Peek().Key > version + 1) return null;
            var union = new SortedSet<int>();
            foreach (var entry in _history)
            {
                if (entry.Key <= version) continue;
                foreach (var f in entry.Value)
                    if (f < _facetCount) union.Add(f);
            }
            var result = new int[union.Count];
            union.CopyTo(result);
            return result;
        }

        /// <summary>
        /// The mesh as plain data: vertices numbered by first appearance in facet order (as the
        /// library numbers them, so vertices and loops equal those of MeshData.From of the
        /// library's mesh), facet loops and planes. Flags, seeds, dual triangles, the quality
        /// report and diagnostics are not kept here (empty or default). O(n).
        /// </summary>
        public MeshData ToMeshData()
        {
            var number = new int[_positions.Length];
            for (int i = 0; i < number.Length; i++) number[i] = -1;
            var vertices = new List<Vec3>();
            var loops = new int[_facetCount][];
            for (int f = 0; f < _facetCount; f++)
            {
                var loop = _loops[f];
                var renumbered = new int[loop.Length];
                for (int k = 0; k < loop.Length; k++)
                {
                    int id = loop[k];
                    if (number[id] < 0)
                    {
                        number[id] = vertices.Count;
                        vertices.Add(_positions[id]);
                    }
                    renumbered[k] = number[id];
                }
                loops[f] = renumbered;
            }
            var planes = new FacetPlane[_facetCount];
            Array.Copy(_planes, planes, _facetCount);
            return MeshData.FromLoops(vertices.ToArray(), loops, planes);
        }
    }
}
