using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>Inputs shared by the tests.</summary>
    static class TestData
    {
        /// <summary>Rhino-convention knots of a cubic Bezier (count 4, degree 3: 6 knots).</summary>
        public static readonly double[] BezierKnots = { 0, 0, 0, 1, 1, 1 };

        /// <summary>
        /// Control points of a bicubic dome, u-major: x and y linear in u and v, z from the
        /// control values (0, 1, 1, 0) in each direction, so z = h (3u(1-u) + 3v(1-v)) / 2: an
        /// elliptic paraboloid over the square, K &gt; 0 everywhere.
        /// </summary>
        public static double[] DomePoints(double height = 1.0)
        {
            var c = new[] { 0.0, 1.0, 1.0, 0.0 };
            var points = new List<double>();
            for (int i = 0; i < 4; i++)
                for (int j = 0; j < 4; j++)
                {
                    points.Add(-1 + 2.0 * i / 3);
                    points.Add(-1 + 2.0 * j / 3);
                    points.Add(height * 0.5 * (c[i] + c[j]));
                }
            return points.ToArray();
        }

        public static Surface Dome(double height = 1.0)
        {
            return Surface.FromNurbs(3, 3, 4, 4, BezierKnots, BezierKnots, DomePoints(height));
        }

        public static double[] Flatten(IEnumerable<PatternPoint> points)
        {
            return points.SelectMany(p => new[] { p.S, p.T }).ToArray();
        }

        public static void AssertSameMesh(Discretisation expected, Discretisation actual)
        {
            NUnit.Framework.Assert.AreEqual(expected.GetVertexArray(), actual.GetVertexArray(), "vertices");
            NUnit.Framework.Assert.AreEqual(expected.GetFacetSizeArray(), actual.GetFacetSizeArray(), "facet sizes");
            NUnit.Framework.Assert.AreEqual(expected.GetFacetIndexArray(), actual.GetFacetIndexArray(), "facet indices");
        }

        /// <summary>Resident set size of this process in bytes (Linux: /proc/self/statm; elsewhere the working set).</summary>
        public static long ResidentBytes()
        {
            if (System.IO.File.Exists("/proc/self/statm"))
            {
                var fields = System.IO.File.ReadAllText("/proc/self/statm").Split(' ');
                return long.Parse(fields[1]) * Environment.SystemPageSize;
            }
            using (var process = System.Diagnostics.Process.GetCurrentProcess()) return process.WorkingSet64;
        }
    }
}
