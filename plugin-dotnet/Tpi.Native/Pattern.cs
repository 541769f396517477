using System;
using System.Collections.Generic;
using System.Threading;
using Tpi.Native.Interop;

namespace Tpi.Native
{
    /// <summary>
    /// Pattern points (TpiPattern): normalised (s, t) in [0, 1]^2, mapped linearly onto a
    /// surface's domain. Immutable; may be used from several threads.
    /// </summary>
    public sealed class Pattern : IDisposable
    {
        internal readonly PatternHandle Handle;
        static readonly PatternHandle NullHandle = new PatternHandle();
        PatternPoint[] _points;

        Pattern(PatternHandle handle) { Handle = handle; }

        internal static PatternHandle HandleOf(Pattern pattern)
        {
            return pattern == null ? NullHandle : pattern.Handle;
        }

        static Pattern Created(Status status, PatternHandle handle, string function)
        {
            if (status != Status.Ok)
            {
                var error = new TpiException(status, TpiLibrary.LastErrorMessage(), function);
                if (handle != null) handle.Dispose();
                throw error;
            }
            handle.Track();
            return new Pattern(handle);
        }

        /// <summary>From s0, t0, s1, t1, ... (validated by the library: finite, inside the square, no duplicates).</summary>
        public static Pattern FromPoints(IList<double> st)
        {
            var uv = TpiLibrary.ArrayOrNull(st);
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new(uv, TpiLibrary.Length(uv), out h);
            return Created(s, h, "tpi_pattern_new");
        }

        /// <summary>From (s, t) points.</summary>
        public static Pattern FromPoints(IEnumerable<PatternPoint> points)
        {
            var flat = new List<double>();
            if (points != null)
                foreach (var p in points) { flat.Add(p.S); flat.Add(p.T); }
            return FromPoints(flat.ToArray());
        }

        /// <summary>The square grid of nu x nv cell centres (generator grid:NUxNV).</summary>
        public static Pattern Grid(int nu, int nv)
        {
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new_grid(TpiLibrary.Size(nu), TpiLibrary.Size(nv), out h);
            return Created(s, h, "tpi_pattern_new_grid");
        }

        /// <summary>The hexagonal grid of nu x nv points (generator hex:NUxNV).</summary>
        public static Pattern Hex(int nu, int nv)
        {
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new_hex(TpiLibrary.Size(nu), TpiLibrary.Size(nv), out h);
            return Created(s, h, "tpi_pattern_new_hex");
        }

        /// <summary>The jittered grid (generator jitter:NUxNV:amount=A:seed=S).</summary>
        public static Pattern Jitter(int nu, int nv, double amount, ulong seed)
        {
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new_jitter(TpiLibrary.Size(nu), TpiLibrary.Size(nv), amount, seed, out h);
            return Created(s, h, "tpi_pattern_new_jitter");
        }

        /// <summary>Uniform random points (generator random:N:seed=S).</summary>
        public static Pattern Random(int count, ulong seed)
        {
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new_random(TpiLibrary.Size(count), seed, out h);
            return Created(s, h, "tpi_pattern_new_random");
        }

        /// <summary>Poisson-disk sampling with minimum distance radius (generator poisson:R:seed=S).</summary>
        public static Pattern Poisson(double radius, ulong seed)
        {
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new_poisson(radius, seed, out h);
            return Created(s, h, "tpi_pattern_new_poisson");
        }

        /// <summary>From a generator spec in the command line's syntax, e.g. "hex:12x12" or "grid:spacing=0.05".</summary>
        public static Pattern FromSpec(string spec)
        {
            PatternHandle h;
            var s = UnsafeNativeMethods.tpi_pattern_new_from_spec(spec == null ? null : TpiLibrary.EncodeUtf8(spec), out h);
            return Created(s, h, "tpi_pattern_new_from_spec");
        }

        /// <summary>
        /// A pattern made on <paramref name="surface"/> from a pattern spec (tpi_pattern_new_for_surface):
        /// a generator, or "fit:D[:seed=S]", "relax:N:SPEC", "align:LATTICE:FIELD" (FIELD principal,
        /// asymptotic, uv:ANGLE or a direction field's JSON), "density:{JSON}". The library reads no
        /// files: JSON goes inline. <paramref name="options"/>: null for the defaults. A fit that misses
        /// its tolerance still gives a pattern: see <see cref="Fit"/>.
        /// </summary>
        public static Pattern ForSurface(Surface surface, string spec, DiscretisationOptions options = null)
        {
            PatternHandle h;
            Status s;
            var text = spec == null ? null : TpiLibrary.EncodeUtf8(spec);
            if (options == null)
            {
                s = UnsafeNativeMethods.tpi_pattern_new_for_surface_defaults(Surface.HandleOf(surface), text, IntPtr.Zero, out h);
            }
            else
            {
                var native = options.ToNative();
                s = UnsafeNativeMethods.tpi_pattern_new_for_surface(Surface.HandleOf(surface), text, ref native, out h);
            }
            GC.KeepAlive(surface);
            return Created(s, h, "tpi_pattern_new_for_surface");
        }

        /// <summary>
        /// <see cref="ForSurface(Surface, string, DiscretisationOptions)"/> (the same points)
        /// reporting the stages of every discretisation the spec runs (a fit runs tens of them,
        /// a relaxation one per iteration; each from <see cref="Stage.Samples"/> again) to
        /// <paramref name="progress"/> (may be null), and stopping when <paramref name="cancel"/>
        /// is cancelled: the library asks between stages, so the call returns within one
        /// stage's time. Then it throws <see cref="OperationCanceledException"/> for
        /// <paramref name="cancel"/> and nothing is created
        /// (tpi_pattern_new_for_surface_with_progress). <paramref name="progress"/> is called on
        /// the calling thread only; an exception it throws cancels the call and is rethrown.
        /// </summary>
        public static Pattern ForSurface(Surface surface, string spec, DiscretisationOptions options, Action<DiscretisationProgress> progress, CancellationToken cancel)
        {
            cancel.ThrowIfCancellationRequested();
            var relay = new ProgressRelay(progress, cancel);
            PatternHandle h;
            Status s;
            var text = spec == null ? null : TpiLibrary.EncodeUtf8(spec);
            if (options == null)
            {
                s = UnsafeNativeMethods.tpi_pattern_new_for_surface_with_progress_defaults(Surface.HandleOf(surface), text, IntPtr.Zero, relay.Callback, IntPtr.Zero, out h);
            }
            else
            {
                var native = options.ToNative();
                s = UnsafeNativeMethods.tpi_pattern_new_for_surface_with_progress(Surface.HandleOf(surface), text, ref native, relay.Callback, IntPtr.Zero, out h);
            }
            GC.KeepAlive(surface);
            relay.Finish(s, h);
            return Created(s, h, "tpi_pattern_new_for_surface_with_progress");
        }

        /// <summary>How the fit went (tpi_pattern_fit_report), or null when the pattern was not made by a fit:D spec.</summary>
        public FitReport? Fit
        {
            get
            {
                var report = new FitReport { StructSize = (uint)FitReport.SizeV1 };
                var s = UnsafeNativeMethods.tpi_pattern_fit_report(Handle, ref report);
                if (s == Status.Unavailable) return null;
                TpiLibrary.Check(s, "tpi_pattern_fit_report");
                return report;
            }
        }

        /// <summary>
        /// The point count of the smallest uniform hexagonal pattern hex:spacing=1/N whose mesh on
        /// <paramref name="surface"/> (default options) keeps every vertex within <paramref name="maxDeviation"/>,
        /// looking at no more than <paramref name="maxPoints"/> points (tpi_pattern_hex_baseline); 0 when none
        /// does. <paramref name="deviation"/>: its mesh's largest vertex deviation (NaN when none).
        /// </summary>
        public static int HexBaseline(Surface surface, double maxDeviation, int maxPoints, out double deviation)
        {
            UIntPtr count;
            var s = UnsafeNativeMethods.tpi_pattern_hex_baseline(Surface.HandleOf(surface), maxDeviation, TpiLibrary.Size(maxPoints), IntPtr.Zero, out count, out deviation);
            GC.KeepAlive(surface);
            TpiLibrary.Check(s, "tpi_pattern_hex_baseline");
            return TpiLibrary.ToInt(count);
        }

        /// <summary>Number of points.</summary>
        public int Count
        {
            get
            {
                UIntPtr n;
                TpiLibrary.Check(UnsafeNativeMethods.tpi_pattern_point_count(Handle, out n), "tpi_pattern_point_count");
                return TpiLibrary.ToInt(n);
            }
        }

        /// <summary>The points as s0, t0, s1, t1, ... (a fresh copy).</summary>
        public double[] GetPointArray()
        {
            return TpiLibrary.CopyOut<double>((double[] b, UIntPtr c, out UIntPtr n) =>
                UnsafeNativeMethods.tpi_pattern_points(Handle, b, c, out n), "tpi_pattern_points");
        }

        /// <summary>The points (read once, then cached: the pattern is immutable).</summary>
        public IReadOnlyList<PatternPoint> Points
        {
            get
            {
                if (_points == null) _points = ToPoints(GetPointArray());
                return Array.AsReadOnly(_points);
            }
        }

        internal static PatternPoint[] ToPoints(double[] st)
        {
            var points = new PatternPoint[st.Length / 2];
            for (int i = 0; i < points.Length; i++) points[i] = new PatternPoint(st[2 * i], st[2 * i + 1]);
            return points;
        }

        /// <summary>True once disposed.</summary>
        public bool IsDisposed { get { return Handle.IsClosed; } }

        /// <summary>Frees the native pattern.</summary>
        public void Dispose() { Handle.Dispose(); }
    }
}
