// The trim of a surface as plain data: closed polylines in the surface's own (u, v)
// parameters, the outer loop counter-clockwise and the holes clockwise, as the library takes
// them (Surface.WithTrim, tpi_surface_with_trim). FromLoops turns loops as a host samples them
// (a Brep face's 2D trim curves: any orientation, often with the closing point repeated) into
// that form, and says "untrimmed" when the outer loop is the whole domain rectangle.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>A trim in surface parameters: outer loop counter-clockwise, holes clockwise (flat u, v per point).</summary>
    public sealed class SurfaceTrim : IEquatable<SurfaceTrim>
    {
        readonly double[] _outer;
        readonly double[][] _holes;

        /// <summary>Copies the loops as they are (nothing is reordered or validated: the library validates).</summary>
        public SurfaceTrim(IEnumerable<double> outer, IEnumerable<IEnumerable<double>> holes = null)
        {
            _outer = outer == null ? new double[0] : outer.ToArray();
            _holes = holes == null ? new double[0][] : holes.Select(h => h == null ? new double[0] : h.ToArray()).ToArray();
        }

        /// <summary>The outer loop, flat u, v.</summary>
        public IReadOnlyList<double> Outer { get { return Array.AsReadOnly(_outer); } }

        /// <summary>The holes, each flat u, v.</summary>
        public IReadOnlyList<IReadOnlyList<double>> Holes { get { return _holes.Select(h => (IReadOnlyList<double>)Array.AsReadOnly(h)).ToList(); } }

        /// <summary>A copy of <paramref name="surface"/> with this trim (the caller disposes both).</summary>
        public Surface Apply(Surface surface)
        {
            return surface.WithTrim(_outer, _holes.Cast<IList<double>>().ToList());
        }

        /// <summary>
        /// The trim from loops sampled in the surface's parameters (flat u, v, any orientation):
        /// a point within <paramref name="tolerance"/> outside the domain is moved onto it, a
        /// point within tolerance of the one before it and a closing point within tolerance of
        /// the first are dropped, the
        /// outer loop is made counter-clockwise and the holes clockwise. Returns null (untrimmed)
        /// when there are no holes and every outer point lies within tolerance of the
        /// boundary of <paramref name="domain"/> with the loop's area that of the domain (the
        /// face's outer loop is its whole domain rectangle).
        /// </summary>
        public static SurfaceTrim FromLoops(IList<double> outer, IEnumerable<IList<double>> holes, Domain domain, double tolerance)
        {
            if (outer == null) throw new ArgumentNullException("outer");
            if (tolerance < 0 || double.IsNaN(tolerance)) tolerance = 0;
            var o = Open(outer, domain, tolerance);
            var hs = holes == null ? new List<double[]>() : holes.Where(h => h != null && h.Count > 0).Select(h => Open(h, domain, tolerance)).ToList();
            if (hs.Count == 0 && IsWholeDomain(o, domain, tolerance)) return null;
            if (SignedArea(o) < 0) o = Reversed(o);
            for (int k = 0; k < hs.Count; k++)
                if (SignedArea(hs[k]) > 0) hs[k] = Reversed(hs[k]);
            return new SurfaceTrim(o, hs);
        }

        /// <summary>
        /// The chord tolerance for sampling trim curves in parameter space, and the tolerance of
        /// <see cref="FromLoops"/>: 1e-5 of the larger side of the domain (parameters have no
        /// model units, so the document's absolute tolerance does not apply to them directly).
        /// </summary>
        public static double SamplingTolerance(Domain domain)
        {
            return 1e-5 * Math.Max(Math.Abs(domain.UMax - domain.UMin), Math.Abs(domain.VMax - domain.VMin));
        }

        /// <summary>
        /// A trim that the library refuses with a message naming <c>trim.outer</c>: what an
        /// adapter uses when a face's trim curve cannot be sampled, so that the trim is
        /// reported rather than silently left out.
        /// </summary>
        public static SurfaceTrim Unsampled() { return new SurfaceTrim(new double[0]); }

        /// <summary>The shoelace area of a flat u, v loop, positive counter-clockwise.</summary>
        public static double SignedArea(IList<double> loop)
        {
            int n = loop.Count / 2;
            double sum = 0;
            for (int k = 0; k < n; k++)
            {
                int j = (k + 1) % n;
                sum += loop[2 * k] * loop[2 * j + 1] - loop[2 * j] * loop[2 * k + 1];
            }
            return 0.5 * sum;
        }

        // Clamps points within tolerance outside the domain onto it (a sampled edge curve may
        // stray by rounding; the library refuses a point outside the domain), drops a point
        // within tolerance of the one before it (curve joins) and the closing point.
        static double[] Open(IList<double> loop, Domain domain, double tolerance)
        {
            if (loop.Count % 2 != 0) throw new ArgumentException("a loop is u, v pairs: an even count of numbers", "loop");
            var points = new List<double>(loop.Count);
            for (int k = 0; k < loop.Count / 2; k++)
            {
                double u = Clamp(loop[2 * k], domain.UMin, domain.UMax, tolerance);
                double v = Clamp(loop[2 * k + 1], domain.VMin, domain.VMax, tolerance);
                int n = points.Count;
                if (n >= 2 && Math.Sqrt((u - points[n - 2]) * (u - points[n - 2]) + (v - points[n - 1]) * (v - points[n - 1])) <= tolerance) continue;
                points.Add(u); points.Add(v);
            }
            while (points.Count >= 4)
            {
                int n = points.Count;
                double du = points[n - 2] - points[0], dv = points[n - 1] - points[1];
                if (Math.Sqrt(du * du + dv * dv) > tolerance) break;
                points.RemoveRange(n - 2, 2);
            }
            return points.ToArray();
        }

        static double Clamp(double x, double min, double max, double tolerance)
        {
            if (x < min && x >= min - tolerance) return min;
            if (x > max && x <= max + tolerance) return max;
            return x;
        }

        static double[] Reversed(double[] loop)
        {
            int n = loop.Length / 2;
            var r = new double[loop.Length];
            for (int k = 0; k < n; k++) { r[2 * k] = loop[2 * (n - 1 - k)]; r[2 * k + 1] = loop[2 * (n - 1 - k) + 1]; }
            return r;
        }

        static bool IsWholeDomain(double[] loop, Domain d, double tolerance)
        {
            double width = d.UMax - d.UMin, height = d.VMax - d.VMin;
            for (int k = 0; k < loop.Length / 2; k++)
            {
                double u = loop[2 * k], v = loop[2 * k + 1];
                bool onU = Math.Abs(u - d.UMin) <= tolerance || Math.Abs(u - d.UMax) <= tolerance;
                bool onV = Math.Abs(v - d.VMin) <= tolerance || Math.Abs(v - d.VMax) <= tolerance;
                bool inside = u >= d.UMin - tolerance && u <= d.UMax + tolerance && v >= d.VMin - tolerance && v <= d.VMax + tolerance;
                if (!inside || !(onU || onV)) return false;
            }
            // Points all on the boundary could still cut a corner off: the area decides.
            return Math.Abs(Math.Abs(SignedArea(loop)) - width * height) <= tolerance * 2 * (width + height);
        }

        /// <inheritdoc/>
        public bool Equals(SurfaceTrim other)
        {
            return other != null && _outer.SequenceEqual(other._outer) && _holes.Length == other._holes.Length
                && _holes.Zip(other._holes, (a, b) => a.SequenceEqual(b)).All(x => x);
        }

        /// <inheritdoc/>
        public override bool Equals(object obj) { return Equals(obj as SurfaceTrim); }

        /// <inheritdoc/>
        public override int GetHashCode() { return _outer.Length * 31 + _holes.Length; }
    }
}
