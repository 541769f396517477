// What changed in a discrete surface's mesh between two DiscreteSurface.TakeChanges calls
// (tpi_discrete_surface_changes), copied out into plain arrays. Vertices are named by the
// library's live vertex ids, not by the vertex numbers of DiscreteSurface.GetMesh: an id keeps
// its position until a later snapshot lists it with a new one (docs/c-abi.md, "What changed").
using System;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>
    /// A snapshot of what changed in a discrete surface's mesh (the changed facets with their
    /// loops in vertex ids and their planes, the vertices whose positions are new). Immutable by
    /// convention: the arrays are handed out as they are, do not modify them.
    /// </summary>
    public sealed class MeshChanges
    {
        /// <summary>
        /// True when the vertex numbering started over (the first snapshot; after a recompute
        /// that ran the whole pipeline): every facet and every vertex is listed.
        /// </summary>
        public bool Everything { get; private set; }

        /// <summary>Number of facets of the mesh now (facets from this count on are gone).</summary>
        public int FacetCount { get; private set; }

        /// <summary>One more than the largest vertex id in use.</summary>
        public int VertexIdBound { get; private set; }

        /// <summary>The changed facets (= pattern point indices), ascending.</summary>
        public int[] Facets { get; private set; }

        /// <summary>Start of each changed facet's loop in <see cref="FacetIndices"/> (Facets.Length + 1 entries).</summary>
        public int[] FacetStarts { get; private set; }

        /// <summary>The changed facets' loops in vertex ids, concatenated; each starts where the mesh's loop of that facet starts.</summary>
        public int[] FacetIndices { get; private set; }

        /// <summary>The changed facets' planes.</summary>
        public FacetPlane[] Planes { get; private set; }

        /// <summary>Ids of the vertices whose position is new, ascending.</summary>
        public int[] VertexIds { get; private set; }

        /// <summary>Their positions.</summary>
        public Vec3[] Vertices { get; private set; }

        /// <summary>Copies a snapshot out of the library (the handle stays the caller's).</summary>
        internal static MeshChanges Read(MeshChangesHandle h)
        {
            uint everything;
            UIntPtr facetCount, bound;
            TpiLibrary.Check(UnsafeNativeMethods.tpi_mesh_changes_counts(h, out everything, out facetCount, out bound), "tpi_mesh_changes_counts");
            var facets = TpiLibrary.CopyOut<uint>((uint[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_mesh_changes_facets(h, b, c, out n), "tpi_mesh_changes_facets");
            var sizes = TpiLibrary.CopyOut<uint>((uint[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_mesh_changes_facet_sizes(h, b, c, out n), "tpi_mesh_changes_facet_sizes");
            var loops = TpiLibrary.CopyOut<uint>((uint[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_mesh_changes_facet_indices(h, b, c, out n), "tpi_mesh_changes_facet_indices");
            var planes = TpiLibrary.CopyOut<FacetPlane>((FacetPlane[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_mesh_changes_planes(h, b, c, out n), "tpi_mesh_changes_planes");
            var ids = TpiLibrary.CopyOut<uint>((uint[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_mesh_changes_vertex_ids(h, b, c, out n), "tpi_mesh_changes_vertex_ids");
            var xyz = TpiLibrary.CopyOut<double>((double[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_mesh_changes_vertices(h, b, c, out n), "tpi_mesh_changes_vertices");
            var starts = new int[sizes.Length + 1];
            for (int k = 0; k < sizes.Length; k++) starts[k + 1] = checked(starts[k] + (int)sizes[k]);
            var vertices = new Vec3[xyz.Length / 3];
            for (int k = 0; k < vertices.Length; k++) vertices[k] = new Vec3(xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]);
            var changes = new MeshChanges
            {
                Everything = everything != 0,
                FacetCount = TpiLibrary.ToInt(facetCount),
                VertexIdBound = TpiLibrary.ToInt(bound),
                Facets = ToInt(facets),
                FacetStarts = starts,
                FacetIndices = ToInt(loops),
                Planes = planes,
                VertexIds = ToInt(ids),
                Vertices = vertices,
            };
            if (changes.Facets.Length != sizes.Length || planes.Length != sizes.Length || starts[sizes.Length] != loops.Length
                || vertices.Length != ids.Length)
                throw new TpiException(Status.Panic, "the changes' arrays do not fit together", "tpi_mesh_changes_*");
            return changes;
        }

        static int[] ToInt(uint[] values)
        {
            var result = new int[values.Length];
            for (int i = 0; i < result.Length; i++) result[i] = checked((int)values[i]);
            return result;
        }
    }
}
