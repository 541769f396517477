// Grip bookkeeping for TpiEditPattern: which grip shows which pattern point. Grips are
// numbered 0..Count-1 in the order they were made; each shows one pattern point. When a
// point is added it gets a new grip at the end; when a point is removed its grip goes away and
// both the later grips and the later pattern point indices move down by one, as the library's
// tpi_discrete_surface_remove_point renumbers the points.
using System;
using System.Collections.Generic;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>Grip index &lt;-&gt; pattern point index, kept in step with adds and removes.</summary>
    public sealed class GripMap
    {
        readonly List<int> _points; // grip -> point, ascending

        /// <summary>One grip per point: grip i shows point i.</summary>
        public GripMap(int pointCount)
        {
            if (pointCount < 0) throw new ArgumentOutOfRangeException("pointCount");
            _points = Enumerable.Range(0, pointCount).ToList();
        }

        /// <summary>Grips for some points only (e.g. the unlocked ones), in ascending point order.</summary>
        public GripMap(IEnumerable<int> points)
        {
            _points = points.Distinct().OrderBy(p => p).ToList();
            if (_points.Count > 0 && _points[0] < 0) throw new ArgumentOutOfRangeException("points", "negative point index");
        }

        /// <summary>Number of grips.</summary>
        public int Count { get { return _points.Count; } }

        /// <summary>The pattern point grip <paramref name="grip"/> shows.</summary>
        public int PointOf(int grip)
        {
            if (grip < 0 || grip >= _points.Count)
                throw new ArgumentOutOfRangeException("grip", grip, "there are " + _points.Count + " grips");
            return _points[grip];
        }

        /// <summary>The grip showing <paramref name="point"/>, or -1 if it has none.</summary>
        public int GripOf(int point)
        {
            int grip = _points.BinarySearch(point);
            return grip >= 0 ? grip : -1;
        }

        /// <summary>The points shown by <paramref name="grips"/>, in the same order.</summary>
        public int[] PointsOf(IEnumerable<int> grips) { return grips.Select(PointOf).ToArray(); }

        /// <summary>A point was appended at index <paramref name="point"/>: gives it a grip; returns the grip index.</summary>
        public int OnPointAdded(int point)
        {
            if (_points.Count > 0 && point <= _points[_points.Count - 1])
                throw new ArgumentException("points are appended: " + point + " is not after the last point with a grip", "point");
            _points.Add(point);
            return _points.Count - 1;
        }

        /// <summary>
        /// Point <paramref name="point"/> was removed: drops its grip (returns its former index,
        /// or -1 if it had none) and moves the later point indices down by one.
        /// </summary>
        public int OnPointRemoved(int point)
        {
            int grip = GripOf(point);
            if (grip >= 0) _points.RemoveAt(grip);
            for (int g = 0; g < _points.Count; g++)
                if (_points[g] > point) _points[g]--;
            return grip;
        }

        /// <summary>A point was inserted back at <paramref name="point"/> (undo of a removal): later indices move up, it gets a grip.</summary>
        public int OnPointInserted(int point)
        {
            for (int g = 0; g < _points.Count; g++)
                if (_points[g] >= point) _points[g]++;
            int at = ~_points.BinarySearch(point);
            _points.Insert(at, point);
            return at;
        }

        /// <summary>
        /// The grip nearest to <paramref name="pick"/> among <paramref name="gripLocations"/>
        /// (indexed by grip) within <paramref name="maxDistance"/>, or -1.
        /// </summary>
        public static int Nearest(IReadOnlyList<Vec3> gripLocations, Vec3 pick, double maxDistance)
        {
            int best = -1;
            double bestDistance = maxDistance;
            for (int g = 0; g < gripLocations.Count; g++)
            {
                double d = (gripLocations[g] - pick).Length;
                if (d <= bestDistance) { best = g; bestDistance = d; }
            }
            return best;
        }
    }
}
