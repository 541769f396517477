// The surface of a discrete surface as plain data: either a NURBS surface exactly as
// RhinoCommon hands it over (degrees, counts, Rhino-convention knots, Euclidean control points
// u-major, optional weights) or one of the library's analytic surfaces. This is what the
// Rhino object stores in its user data and what the Grasshopper components pass on.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>A surface description that can make a native <see cref="Surface"/>.</summary>
    public abstract class SurfaceSpec : IEquatable<SurfaceSpec>
    {
        /// <summary>Makes the native surface, trimmed when <see cref="Trim"/> is set (the caller disposes it). Errors are the library's <see cref="TpiException"/>s.</summary>
        public Surface CreateNative()
        {
            var surface = CreateUntrimmed();
            if (Trim == null) return surface;
            try { return Trim.Apply(surface); }
            finally { surface.Dispose(); }
        }

        /// <summary>Makes the native surface without the trim.</summary>
        protected abstract Surface CreateUntrimmed();

        /// <summary>The trim in the surface's parameters, or null for the whole surface.</summary>
        public SurfaceTrim Trim { get; private set; }

        /// <summary>A copy with <paramref name="trim"/> (null: untrimmed). Transforms and control point edits keep it.</summary>
        public SurfaceSpec WithTrim(SurfaceTrim trim)
        {
            var copy = (SurfaceSpec)MemberwiseClone();
            copy.Trim = trim;
            return copy;
        }

        /// <summary>Whether the two trims are equal (both null included).</summary>
        protected bool SameTrim(SurfaceSpec other)
        {
            return Trim == null ? other.Trim == null : Trim.Equals(other.Trim);
        }

        /// <summary>
        /// The surface moved by the 4x4 row-major matrix <paramref name="m"/> (as RhinoCommon's
        /// Transform: x' = m[0] x + m[1] y + m[2] z + m[3], ...). Exact for affine transforms.
        /// </summary>
        public abstract SurfaceSpec Transformed(double[] m);

        /// <inheritdoc/>
        public abstract bool Equals(SurfaceSpec other);

        /// <inheritdoc/>
        public override bool Equals(object obj) { return Equals(obj as SurfaceSpec); }

        /// <inheritdoc/>
        public override int GetHashCode() { return GetType().GetHashCode(); }

        internal static Vec3 Apply(double[] m, Vec3 p, out double w)
        {
            if (m == null || m.Length != 16) throw new ArgumentException("a transform is 16 numbers, row-major", "m");
            w = m[12] * p.X + m[13] * p.Y + m[14] * p.Z + m[15];
            return new Vec3(m[0] * p.X + m[1] * p.Y + m[2] * p.Z + m[3],
                            m[4] * p.X + m[5] * p.Y + m[6] * p.Z + m[7],
                            m[8] * p.X + m[9] * p.Y + m[10] * p.Z + m[11]);
        }

        internal static bool SameArray(double[] a, double[] b)
        {
            if (a == null || b == null) return a == b;
            return a.Length == b.Length && a.SequenceEqual(b);
        }
    }

    /// <summary>A NURBS surface in RhinoCommon's terms.</summary>
    public sealed class NurbsSurfaceSpec : SurfaceSpec
    {
        /// <summary>Degree in u.</summary>
        public int DegreeU { get; private set; }
        /// <summary>Degree in v.</summary>
        public int DegreeV { get; private set; }
        /// <summary>Control point count in u.</summary>
        public int CountU { get; private set; }
        /// <summary>Control point count in v.</summary>
        public int CountV { get; private set; }
        readonly double[] _knotsU, _knotsV, _points, _weights;

        /// <summary>Copies the arrays. Weights null for a non-rational surface. Nothing is validated here: the library does it.</summary>
        public NurbsSurfaceSpec(int degreeU, int degreeV, int countU, int countV,
            IEnumerable<double> knotsU, IEnumerable<double> knotsV, IEnumerable<double> points, IEnumerable<double> weights = null)
        {
            DegreeU = degreeU; DegreeV = degreeV; CountU = countU; CountV = countV;
            _knotsU = knotsU == null ? new double[0] : knotsU.ToArray();
            _knotsV = knotsV == null ? new double[0] : knotsV.ToArray();
            _points = points == null ? new double[0] : points.ToArray();
            _weights = weights == null ? null : weights.ToArray();
        }

        /// <summary>Knots in u (Rhino convention: CountU + DegreeU - 1).</summary>
        public IReadOnlyList<double> KnotsU { get { return Array.AsReadOnly(_knotsU); } }
        /// <summary>Knots in v.</summary>
        public IReadOnlyList<double> KnotsV { get { return Array.AsReadOnly(_knotsV); } }
        /// <summary>Euclidean control points x, y, z, u-major: point (i, j) at 3 (i CountV + j).</summary>
        public IReadOnlyList<double> Points { get { return Array.AsReadOnly(_points); } }
        /// <summary>Weights in the same order, or null.</summary>
        public IReadOnlyList<double> Weights { get { return _weights == null ? null : Array.AsReadOnly(_weights); } }
        /// <summary>True with weights.</summary>
        public bool IsRational { get { return _weights != null; } }

        /// <summary>Control point (i, j).</summary>
        public Vec3 ControlPoint(int i, int j)
        {
            int k = 3 * (i * CountV + j);
            return new Vec3(_points[k], _points[k + 1], _points[k + 2]);
        }

        /// <summary>A copy with control point (i, j) moved to <paramref name="p"/>.</summary>
        public NurbsSurfaceSpec WithControlPoint(int i, int j, Vec3 p)
        {
            var points = (double[])_points.Clone();
            int k = 3 * (i * CountV + j);
            points[k] = p.X; points[k + 1] = p.Y; points[k + 2] = p.Z;
            return (NurbsSurfaceSpec)new NurbsSurfaceSpec(DegreeU, DegreeV, CountU, CountV, _knotsU, _knotsV, points, _weights).WithTrim(Trim);
        }

        /// <inheritdoc/>
        protected override Surface CreateUntrimmed()
        {
            return Surface.FromNurbs(DegreeU, DegreeV, CountU, CountV, _knotsU, _knotsV, _points, _weights);
        }

        /// <inheritdoc/>
        public override SurfaceSpec Transformed(double[] m)
        {
            // Homogeneous control point (w P, w) maps to w (M P~): the new Euclidean point is
            // (M P~)xyz / (M P~)w and the new weight w (M P~)w. Affine transforms keep w = 1.
            int n = _points.Length / 3;
            var points = new double[_points.Length];
            var scale = new double[n];
            bool projective = false;
            for (int i = 0; i < n; i++)
            {
                double w;
                var p = Apply(m, new Vec3(_points[3 * i], _points[3 * i + 1], _points[3 * i + 2]), out w);
                points[3 * i] = p.X / w; points[3 * i + 1] = p.Y / w; points[3 * i + 2] = p.Z / w;
                scale[i] = w;
                if (w != 1.0) projective = true;
            }
            double[] weights = _weights == null ? null : (double[])_weights.Clone();
            if (projective)
            {
                if (weights == null) weights = Enumerable.Repeat(1.0, n).ToArray();
                for (int i = 0; i < n; i++) weights[i] *= scale[i];
            }
            // A transform moves the points, not the parameters: the trim stays.
            return new NurbsSurfaceSpec(DegreeU, DegreeV, CountU, CountV, _knotsU, _knotsV, points, weights).WithTrim(Trim);
        }

        /// <inheritdoc/>
        public override bool Equals(SurfaceSpec other)
        {
            var o = other as NurbsSurfaceSpec;
            return o != null && o.DegreeU == DegreeU && o.DegreeV == DegreeV && o.CountU == CountU && o.CountV == CountV
                && SameArray(_knotsU, o._knotsU) && SameArray(_knotsV, o._knotsV) && SameArray(_points, o._points)
                && SameArray(_weights, o._weights) && SameTrim(o);
        }

        /// <inheritdoc/>
        public override int GetHashCode() { return (DegreeU * 31 + DegreeV) * 31 + CountU * 7 + CountV; }
    }

    /// <summary>The analytic surfaces of the library (for tests, samples and Grasshopper).</summary>
    public enum AnalyticKind
    {
        /// <summary>z = a x^2 + b y^2: parameters a, b, x0, x1, y0, y1.</summary>
        EllipticParaboloid = 1,
        /// <summary>z = a x^2 - b y^2: parameters a, b, x0, x1, y0, y1.</summary>
        HyperbolicParaboloid = 2,
        /// <summary>Sphere cap: radius, x0, x1, y0, y1.</summary>
        SphereCap = 3,
        /// <summary>Sphere cap over a centred square: radius, half width.</summary>
        SphereCapSquare = 4,
        /// <summary>Ellipsoid cap: a, b, c, x0, x1, y0, y1.</summary>
        EllipsoidCap = 5,
        /// <summary>z = A sin x sin y: amplitude, x0, x1, y0, y1.</summary>
        EggCrate = 6,
        /// <summary>Cylinder: radius, x0, x1, y0, y1.</summary>
        Cylinder = 7,
        /// <summary>Plane z = p x + q y + c0: p, q, c0, x0, x1, y0, y1.</summary>
        Plane = 8,
    }

    /// <summary>An analytic surface: a kind and its parameters, in the order of the C functions.</summary>
    public sealed class AnalyticSurfaceSpec : SurfaceSpec
    {
        /// <summary>The kind.</summary>
        public AnalyticKind Kind { get; private set; }
        readonly double[] _parameters;

        /// <summary>Number of parameters each kind takes.</summary>
        public static int ParameterCount(AnalyticKind kind)
        {
            switch (kind)
            {
                case AnalyticKind.EllipticParaboloid: case AnalyticKind.HyperbolicParaboloid: return 6;
                case AnalyticKind.SphereCap: case AnalyticKind.EggCrate: case AnalyticKind.Cylinder: return 5;
                case AnalyticKind.SphereCapSquare: return 2;
                case AnalyticKind.EllipsoidCap: case AnalyticKind.Plane: return 7;
                default: throw new ArgumentOutOfRangeException("kind", kind, "not an analytic surface kind");
            }
        }

        /// <summary>Makes the spec; the parameter count must fit the kind.</summary>
        public AnalyticSurfaceSpec(AnalyticKind kind, params double[] parameters)
        {
            int n = ParameterCount(kind);
            if (parameters == null || parameters.Length != n)
                throw new ArgumentException(kind + " takes " + n + " parameters", "parameters");
            Kind = kind;
            _parameters = (double[])parameters.Clone();
        }

        /// <summary>The parameters.</summary>
        public IReadOnlyList<double> Parameters { get { return Array.AsReadOnly(_parameters); } }

        /// <inheritdoc/>
        protected override Surface CreateUntrimmed()
        {
            var p = _parameters;
            switch (Kind)
            {
                case AnalyticKind.EllipticParaboloid: return Surface.EllipticParaboloid(p[0], p[1], p[2], p[3], p[4], p[5]);
                case AnalyticKind.HyperbolicParaboloid: return Surface.HyperbolicParaboloid(p[0], p[1], p[2], p[3], p[4], p[5]);
                case AnalyticKind.SphereCap: return Surface.SphereCap(p[0], p[1], p[2], p[3], p[4]);
                case AnalyticKind.SphereCapSquare: return Surface.SphereCapSquare(p[0], p[1]);
                case AnalyticKind.EllipsoidCap: return Surface.EllipsoidCap(p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
                case AnalyticKind.EggCrate: return Surface.EggCrate(p[0], p[1], p[2], p[3], p[4]);
                case AnalyticKind.Cylinder: return Surface.Cylinder(p[0], p[1], p[2], p[3], p[4]);
                case AnalyticKind.Plane: return Surface.Plane(p[0], p[1], p[2], p[3], p[4], p[5], p[6]);
                default: throw new InvalidOperationException("unknown analytic kind " + Kind);
            }
        }

        /// <summary>Analytic surfaces are defined in their own frame: a transform is not representable.</summary>
        public override SurfaceSpec Transformed(double[] m)
        {
            throw new NotSupportedException("an analytic surface cannot be transformed; convert it to NURBS first");
        }

        /// <inheritdoc/>
        public override bool Equals(SurfaceSpec other)
        {
            var o = other as AnalyticSurfaceSpec;
            return o != null && o.Kind == Kind && SameArray(_parameters, o._parameters) && SameTrim(o);
        }

        /// <inheritdoc/>
        public override int GetHashCode() { return (int)Kind; }
    }
}
