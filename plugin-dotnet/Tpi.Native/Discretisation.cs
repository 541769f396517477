using System;
using System.Collections.Generic;
using System.Threading;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>
    /// The result of a discretisation (TpiDiscretisation): an indexed polygon mesh with one
    /// planar facet per pattern point (facet i belongs to pattern point i), the dual
    /// triangulation, quality report and diagnostics. Immutable: each array is read from the
    /// library once and cached; the lists handed out are read-only views, the Get*Array
    /// methods return fresh copies. May be used from several threads.
    /// </summary>
    public sealed class Discretisation : IDisposable
    {
        internal readonly DiscretisationHandle Handle;
        readonly object _lock = new object();
        double[] _vertices;
        Vec3[] _vertexPoints;
        uint[] _sizes;
        uint[] _indices;
        int[] _starts;
        byte[] _flags;
        Seed[] _seeds;
        FacetPlane[] _planes;
        uint[] _pairs;
        uint[] _triangles;
        DiagnosticEntry[] _entries;

        internal Discretisation(DiscretisationHandle handle)
        {
            Handle = handle;
        }

        internal static Discretisation Created(Status status, DiscretisationHandle handle, string function)
        {
            if (status != Status.Ok)
            {
                var error = new TpiException(status, TpiLibrary.LastErrorMessage(), function);
                if (handle != null) handle.Dispose();
                throw error;
            }
            handle.Track();
            return new Discretisation(handle);
        }

        /// <summary>Discretises <paramref name="surface"/> with <paramref name="pattern"/>; null options for the library's defaults.</summary>
        public static Discretisation Create(Surface surface, Pattern pattern, DiscretisationOptions options = null)
        {
            DiscretisationHandle h;
            Status s;
            if (options == null)
            {
                s = UnsafeNativeMethods.tpi_discretise_defaults(Surface.HandleOf(surface), Pattern.HandleOf(pattern), IntPtr.Zero, out h);
            }
            else
            {
                var native = options.ToNative();
                s = UnsafeNativeMethods.tpi_discretise(Surface.HandleOf(surface), Pattern.HandleOf(pattern), ref native, out h);
            }
            return Created(s, h, "tpi_discretise");
        }

        /// <summary>
        /// <see cref="Create(Surface, Pattern, DiscretisationOptions)"/> (the same result) that
        /// reports each stage's progress to <paramref name="progress"/> (may be null) and stops
        /// when <paramref name="cancel"/> is cancelled: the library asks between stages, so the
        /// call returns within one stage's time. Then it throws
        /// <see cref="OperationCanceledException"/> for <paramref name="cancel"/> and nothing
        /// is created. <paramref name="progress"/> is called on the calling thread only (a
        /// callback from the library's worker threads would attach them to the runtime, and
        /// Mono waits for them at exit); an exception it throws is kept and rethrown here after
        /// the library has stopped (it cancels the run).
        /// </summary>
        public static Discretisation Create(Surface surface, Pattern pattern, DiscretisationOptions options, Action<DiscretisationProgress> progress, CancellationToken cancel)
        {
            cancel.ThrowIfCancellationRequested();
            var relay = new ProgressRelay(progress, cancel);
            var callback = relay.Callback;
            DiscretisationHandle h;
            Status s;
            if (options == null)
            {
                s = UnsafeNativeMethods.tpi_discretise_with_progress_defaults(Surface.HandleOf(surface), Pattern.HandleOf(pattern), IntPtr.Zero, callback, IntPtr.Zero, out h);
            }
            else
            {
                var native = options.ToNative();
                s = UnsafeNativeMethods.tpi_discretise_with_progress(Surface.HandleOf(surface), Pattern.HandleOf(pattern), ref native, callback, IntPtr.Zero, out h);
            }
            relay.Finish(s, h);
            return Created(s, h, "tpi_discretise_with_progress");
        }

        T[] Cached<T>(ref T[] field, TpiLibrary.CopyOutCall<T> call, string function)
        {
            lock (_lock)
            {
                if (field == null) field = TpiLibrary.CopyOut(call, function);
                return field;
            }
        }

        /// <summary>Number of facets (= pattern points).</summary>
        public int FacetCount
        {
            get
            {
                UIntPtr n;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_discretisation_facet_count(Handle, out n), "tpi_discretisation_facet_count");
                return TpiLibrary.ToInt(n);
            }
        }

        /// <summary>Number of mesh vertices.</summary>
        public int VertexCount
        {
            get
            {
                UIntPtr n;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_discretisation_vertex_count(Handle, out n), "tpi_discretisation_vertex_count");
                return TpiLibrary.ToInt(n);
            }
        }

        double[] RawVertices()
        {
            return Cached(ref _vertices, (double[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_discretisation_vertices(Handle, b, c, out n), "tpi_discretisation_vertices");
        }

        uint[] RawSizes()
        {
            return Cached(ref _sizes, (uint[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_discretisation_facet_sizes(Handle, b, c, out n), "tpi_discretisation_facet_sizes");
        }

        uint[] RawIndices()
        {
            return Cached(ref _indices, (uint[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_discretisation_facet_indices(Handle, b, c, out n), "tpi_discretisation_facet_indices");
        }

        /// <summary>Vertex coordinates x0, y0, z0, x1, ... (a copy).</summary>
        public double[] GetVertexArray() { return (double[])RawVertices().Clone(); }

        /// <summary>Number of vertices of each facet, in facet order (a copy).</summary>
        public uint[] GetFacetSizeArray() { return (uint[])RawSizes().Clone(); }

        /// <summary>The facets' vertex loops, facet after facet, counter-clockwise seen from each facet's normal (a copy).</summary>
        public uint[] GetFacetIndexArray() { return (uint[])RawIndices().Clone(); }

        /// <summary>The vertices as points.</summary>
        public IReadOnlyList<Vec3> Vertices
        {
            get
            {
                lock (_lock)
                {
                    if (_vertexPoints == null)
                    {
                        var raw = RawVertices();
                        var points = new Vec3[raw.Length / 3];
                        for (int i = 0; i < points.Length; i++) points[i] = new Vec3(raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]);
                        _vertexPoints = points;
                    }
                    return Array.AsReadOnly(_vertexPoints);
                }
            }
        }

        /// <summary>Number of vertices of each facet.</summary>
        public IReadOnlyList<uint> FacetSizes { get { return Array.AsReadOnly(RawSizes()); } }

        /// <summary>All facet loops, concatenated.</summary>
        public IReadOnlyList<uint> FacetIndices { get { return Array.AsReadOnly(RawIndices()); } }

        /// <summary>The vertex indices of facet <paramref name="facet"/>, counter-clockwise seen from its normal.</summary>
        public int[] GetFacet(int facet)
        {
            var sizes = RawSizes();
            var indices = RawIndices();
            int[] starts;
            lock (_lock)
            {
                if (_starts == null)
                {
                    var s = new int[sizes.Length + 1];
                    for (int i = 0; i < sizes.Length; i++) s[i + 1] = s[i] + (int)sizes[i];
                    _starts = s;
                }
                starts = _starts;
            }
            if (facet < 0 || facet >= sizes.Length)
                throw new ArgumentOutOfRangeException("facet", facet, "there are " + sizes.Length + " facets");
            var loop = new int[sizes[facet]];
            for (int k = 0; k < loop.Length; k++) loop[k] = (int)indices[starts[facet] + k];
            return loop;
        }

        /// <summary>Per-facet flags (empty when the quality report was switched off).</summary>
        public IReadOnlyList<FacetFlags> Flags
        {
            get
            {
                var raw = Cached(ref _flags, (byte[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_facet_flags(Handle, b, c, out n), "tpi_discretisation_facet_flags");
                var flags = new FacetFlags[raw.Length];
                for (int i = 0; i < raw.Length; i++) flags[i] = (FacetFlags)raw[i];
                return Array.AsReadOnly(flags);
            }
        }

        /// <summary>The seed (pattern point sample) of each facet.</summary>
        public IReadOnlyList<Seed> Seeds
        {
            get
            {
                return Array.AsReadOnly(Cached(ref _seeds, (Seed[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_seeds(Handle, b, c, out n), "tpi_discretisation_seeds"));
            }
        }

        /// <summary>The tangent plane of each facet.</summary>
        public IReadOnlyList<FacetPlane> Planes
        {
            get
            {
                return Array.AsReadOnly(Cached(ref _planes, (FacetPlane[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_planes(Handle, b, c, out n), "tpi_discretisation_planes"));
            }
        }

        /// <summary>Neighbour pairs i0, j0, i1, j1, ... (i &lt; j, sorted).</summary>
        public IReadOnlyList<uint> NeighbourPairs
        {
            get
            {
                return Array.AsReadOnly(Cached(ref _pairs, (uint[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_neighbour_pairs(Handle, b, c, out n), "tpi_discretisation_neighbour_pairs"));
            }
        }

        /// <summary>Dual triangles (3 pattern point indices each, counter-clockwise in parameter space).</summary>
        public IReadOnlyList<uint> DualTriangles
        {
            get
            {
                return Array.AsReadOnly(Cached(ref _triangles, (uint[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_dual_triangles(Handle, b, c, out n), "tpi_discretisation_dual_triangles"));
            }
        }

        /// <summary>The quality report; a <see cref="TpiException"/> with <see cref="Status.Unavailable"/> when it was switched off.</summary>
        public QualityReport Quality
        {
            get
            {
                var report = new QualityReport { StructSize = QualityReport.SizeV3 };
                TpiLibrary.Check(UnsafeNativeMethods.tpi_discretisation_quality(Handle, ref report), "tpi_discretisation_quality");
                return report;
            }
        }

        /// <summary>The quality report, or false when it was switched off.</summary>
        public bool TryGetQuality(out QualityReport report)
        {
            report = new QualityReport { StructSize = QualityReport.SizeV3 };
            var status = UnsafeNativeMethods.tpi_discretisation_quality(Handle, ref report);
            if (status == Status.Unavailable) return false;
            TpiLibrary.Check(status, "tpi_discretisation_quality");
            return true;
        }

        /// <summary>The quality report as JSON (with the side histogram).</summary>
        public string QualityJson
        {
            get
            {
                return TpiLibrary.CopyOutText((byte[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_quality_json(Handle, b, c, out n), "tpi_discretisation_quality_json");
            }
        }

        /// <summary>Number of diagnostics.</summary>
        public int DiagnosticCount
        {
            get
            {
                UIntPtr n;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_discretisation_diagnostic_count(Handle, out n), "tpi_discretisation_diagnostic_count");
                return TpiLibrary.ToInt(n);
            }
        }

        /// <summary>The (point, kind, diagnostic) entries.</summary>
        public IReadOnlyList<DiagnosticEntry> DiagnosticEntries
        {
            get
            {
                return Array.AsReadOnly(Cached(ref _entries, (DiagnosticEntry[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_diagnostic_entries(Handle, b, c, out n), "tpi_discretisation_diagnostic_entries"));
            }
        }

        /// <summary>The diagnostics as a JSON array.</summary>
        public string DiagnosticsJson
        {
            get
            {
                return TpiLibrary.CopyOutText((byte[] b, UIntPtr c, out UIntPtr n) =>
                    UnsafeNativeMethods.tpi_discretisation_diagnostics_json(Handle, b, c, out n), "tpi_discretisation_diagnostics_json");
            }
        }

        /// <summary>The whole result in the project's JSON output contract.</summary>
        public string ToJson(bool includeTimings = false)
        {
            uint timings = includeTimings ? 1u : 0u;
            return TpiLibrary.CopyOutText((byte[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_discretisation_json(Handle, timings, b, c, out n), "tpi_discretisation_json");
        }

        /// <summary>True once disposed.</summary>
        public bool IsDisposed { get { return Handle.IsClosed; } }

        /// <summary>Frees the native result (the cached arrays stay readable).</summary>
        public void Dispose() { Handle.Dispose(); }
    }
}
