// Checks made before anything reaches the library, for input that comes from a UI: points
// picked on a surface a hair outside its domain, empty lists, missing surfaces. Everything the
// library itself validates (NURBS data, duplicates, NaN) is left to it, so its messages reach
// the user unchanged.
using System;
using System.Collections.Generic;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Input checks and parameter mapping.</summary>
    public static class InputValidation
    {
        /// <summary>How far outside [0, 1] a normalised parameter may be and still be clamped (closest-point rounding).</summary>
        public const double ClampTolerance = 1e-9;

        /// <summary>
        /// Maps (u, v) in <paramref name="domain"/> to (s, t) in [0, 1]^2, clamping values within
        /// <see cref="ClampTolerance"/> of the square; returns false (and an explanation) for a
        /// pair that is not finite or lies further outside.
        /// </summary>
        public static bool TryNormalise(Domain domain, double u, double v, out PatternPoint point, out string error)
        {
            point = domain.ToNormalised(u, v);
            error = null;
            if (!IsFinite(point.S) || !IsFinite(point.T))
            {
                error = string.Format("(u, v) = ({0}, {1}) is not finite", u, v);
                return false;
            }
            double s = point.S, t = point.T;
            if (s < -ClampTolerance || s > 1 + ClampTolerance || t < -ClampTolerance || t > 1 + ClampTolerance)
            {
                error = string.Format("(u, v) = ({0}, {1}) lies outside the surface's domain [{2}, {3}] x [{4}, {5}]",
                    u, v, domain.UMin, domain.UMax, domain.VMin, domain.VMax);
                return false;
            }
            point = new PatternPoint(Clamp01(s), Clamp01(t));
            return true;
        }

        /// <summary>Clamps normalised points within tolerance; lists the ones that are not (by index).</summary>
        public static List<PatternPoint> CleanNormalised(IList<PatternPoint> points, List<string> errors)
        {
            var clean = new List<PatternPoint>(points.Count);
            for (int i = 0; i < points.Count; i++)
            {
                string error;
                PatternPoint p;
                if (TryNormalise(new Domain(0, 1, 0, 1), points[i].S, points[i].T, out p, out error))
                    clean.Add(p);
                else
                    errors.Add("point " + i + ": " + error);
            }
            return clean;
        }

        /// <summary>The count of control point doubles a NURBS needs (3 per point), checked for overflow.</summary>
        public static bool NurbsShapeLooksRight(int countU, int countV, int pointDoubles, int weightCount, out string error)
        {
            error = null;
            long expected = 3L * countU * countV;
            if (countU <= 0 || countV <= 0) error = "control point counts must be positive";
            else if (pointDoubles != expected) error = string.Format("{0} x {1} control points need {2} coordinates, got {3}", countU, countV, expected, pointDoubles);
            else if (weightCount != 0 && weightCount != countU * countV) error = string.Format("{0} weights for {1} control points", weightCount, countU * countV);
            return error == null;
        }

        static bool IsFinite(double x) { return !double.IsNaN(x) && !double.IsInfinity(x); }

        static double Clamp01(double x) { return x < 0 ? 0 : x > 1 ? 1 : x; }
    }
}
