// The Voronoi diagram of pattern points in the unit square, for TpiPattern's preview (the
// paper's figure 9a: pattern points and their Voronoi cells). Each cell is the square clipped
// by the bisector half-planes of the other points (Sutherland-Hodgman), O(n^2) per diagram:
// meant for previews of up to a few thousand points, not for the discretisation itself.
using System.Collections.Generic;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Voronoi cells of normalised pattern points, clipped to [0, 1]^2.</summary>
    public static class VoronoiCells
    {
        /// <summary>One convex polygon per point (counter-clockwise, not closed), in (s, t).</summary>
        public static PatternPoint[][] Compute(IReadOnlyList<PatternPoint> points)
        {
            var cells = new PatternPoint[points.Count][];
            for (int i = 0; i < points.Count; i++)
            {
                var cell = new List<PatternPoint>
                {
                    new PatternPoint(0, 0), new PatternPoint(1, 0), new PatternPoint(1, 1), new PatternPoint(0, 1),
                };
                var p = points[i];
                for (int j = 0; j < points.Count && cell.Count > 0; j++)
                {
                    if (j == i) continue;
                    var q = points[j];
                    // Keep x with (x - m) . (q - p) <= 0, m the midpoint.
                    double nx = q.S - p.S, ny = q.T - p.T;
                    double c = nx * 0.5 * (p.S + q.S) + ny * 0.5 * (p.T + q.T);
                    cell = Clip(cell, nx, ny, c);
                }
                cells[i] = cell.ToArray();
            }
            return cells;
        }

        static List<PatternPoint> Clip(List<PatternPoint> polygon, double nx, double ny, double c)
        {
            var result = new List<PatternPoint>(polygon.Count + 1);
            for (int k = 0; k < polygon.Count; k++)
            {
                var a = polygon[k];
                var b = polygon[(k + 1) % polygon.Count];
                double da = nx * a.S + ny * a.T - c, db = nx * b.S + ny * b.T - c;
                if (da <= 0) result.Add(a);
                if ((da < 0 && db > 0) || (da > 0 && db < 0))
                {
                    double f = da / (da - db);
                    result.Add(new PatternPoint(a.S + f * (b.S - a.S), a.T + f * (b.T - a.T)));
                }
            }
            return result;
        }

        /// <summary>Area of a polygon in (s, t) (shoelace).</summary>
        public static double Area(PatternPoint[] polygon)
        {
            double twice = 0;
            for (int k = 0; k < polygon.Length; k++)
            {
                var a = polygon[k];
                var b = polygon[(k + 1) % polygon.Length];
                twice += a.S * b.T - b.S * a.T;
            }
            return 0.5 * twice;
        }
    }
}
