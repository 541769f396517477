// A discretisation copied out of the library into plain arrays, so Rhino and Grasshopper
// code (and the undo history) never hold native handles longer than a call.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>The mesh of one discretisation as plain data. Immutable by convention.</summary>
    public sealed class MeshData
    {
        /// <summary>Mesh vertices.</summary>
        public Vec3[] Vertices { get; private set; }
        /// <summary>Vertex count of each facet (facet i belongs to pattern point i).</summary>
        public int[] FacetSizes { get; private set; }
        /// <summary>Facet loops concatenated, each counter-clockwise seen from its facet's normal.</summary>
        public int[] FacetIndices { get; private set; }
        /// <summary>Start of each facet's loop in <see cref="FacetIndices"/> (FacetCount + 1 entries).</summary>
        public int[] FacetStarts { get; private set; }
        /// <summary>Per-facet flags (all None when the quality report was off).</summary>
        public FacetFlags[] Flags { get; private set; }
        /// <summary>Seed of each facet.</summary>
        public Seed[] Seeds { get; private set; }
        /// <summary>Tangent plane of each facet.</summary>
        public FacetPlane[] Planes { get; private set; }
        /// <summary>Dual triangles, 3 pattern point indices each.</summary>
        public int[] DualTriangles { get; private set; }
        /// <summary>The quality report, or null when it was switched off.</summary>
        public QualityReport? Quality { get; private set; }
        /// <summary>The quality report as JSON, or null.</summary>
        public string QualityJson { get; private set; }
        /// <summary>Diagnostic entries (point, kind, diagnostic).</summary>
        public DiagnosticEntry[] Diagnostics { get; private set; }
        /// <summary>Diagnostics as JSON text.</summary>
        public string DiagnosticsJson { get; private set; }

        /// <summary>
        /// What this mesh was computed from (surface, normalised points, options), so a later
        /// stage (fabrication) can recompute the native discretisation; null when unknown.
        /// </summary>
        public DiscreteSurfaceDocument Source { get; internal set; }

        /// <summary>Number of facets.</summary>
        public int FacetCount { get { return FacetSizes.Length; } }

        /// <summary>Copies everything out of <paramref name="mesh"/>.</summary>
        public static MeshData From(Discretisation mesh)
        {
            if (mesh == null) throw new ArgumentNullException("mesh");
            var sizes = ToInt(mesh.GetFacetSizeArray());
            var flags = mesh.Flags.ToArray();
            if (flags.Length == 0) flags = new FacetFlags[sizes.Length];
            QualityReport report;
            bool hasQuality = mesh.TryGetQuality(out report);
            var data = new MeshData
            {
                Vertices = mesh.Vertices.ToArray(),
                FacetSizes = sizes,
                FacetIndices = ToInt(mesh.GetFacetIndexArray()),
                Flags = flags,
                Seeds = mesh.Seeds.ToArray(),
                Planes = mesh.Planes.ToArray(),
                DualTriangles = ToInt(mesh.DualTriangles),
                Quality = hasQuality ? report : (QualityReport?)null,
                QualityJson = hasQuality ? mesh.QualityJson : null,
                Diagnostics = mesh.DiagnosticEntries.ToArray(),
                DiagnosticsJson = mesh.DiagnosticsJson,
            };
            data.FacetStarts = Starts(sizes);
            return data;
        }

        /// <summary>uint to int with a plain loop (LINQ's Select costs more than the copy out of the library).</summary>
        static int[] ToInt(IReadOnlyList<uint> values)
        {
            var result = new int[values.Count];
            for (int i = 0; i < result.Length; i++) result[i] = checked((int)values[i]);
            return result;
        }

        /// <summary>Plain mesh from vertices and facet loops (for tests and conversions).</summary>
        public static MeshData FromLoops(Vec3[] vertices, int[][] loops, FacetPlane[] planes)
        {
            var data = new MeshData
            {
                Vertices = vertices,
                FacetSizes = loops.Select(l => l.Length).ToArray(),
                FacetIndices = loops.SelectMany(l => l).ToArray(),
                Flags = new FacetFlags[loops.Length],
                Seeds = new Seed[loops.Length],
                Planes = planes ?? new FacetPlane[loops.Length],
                DualTriangles = new int[0],
                Diagnostics = new DiagnosticEntry[0],
                DiagnosticsJson = "[]",
            };
            data.FacetStarts = Starts(data.FacetSizes);
            return data;
        }

        static int[] Starts(int[] sizes)
        {
            var starts = new int[sizes.Length + 1];
            for (int i = 0; i < sizes.Length; i++) starts[i + 1] = starts[i] + sizes[i];
            return starts;
        }

        /// <summary>The vertex indices of facet <paramref name="facet"/>.</summary>
        public int[] Facet(int facet)
        {
            var loop = new int[FacetSizes[facet]];
            Array.Copy(FacetIndices, FacetStarts[facet], loop, 0, loop.Length);
            return loop;
        }

        /// <summary>True if both have the same vertices (bit for bit) and facet loops.</summary>
        public bool SameMesh(MeshData other)
        {
            return other != null && Vertices.SequenceEqual(other.Vertices) && FacetSizes.SequenceEqual(other.FacetSizes)
                && FacetIndices.SequenceEqual(other.FacetIndices);
        }
    }
}
