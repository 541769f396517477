// Checked against: RhinoCommon 8 (rhino-stubs-typed 8.20.25157; DisplayConduit's protected
// virtuals against the RhinoCommon source). Members used: read from the compiled adapter and checked against the stubs (plugin-dotnet/API-CHECK.md).
using System.Collections.Generic;
using System.Drawing;
using Rhino.Display;
using Rhino.Geometry;

namespace Tpi.RhinoPlugIn
{
    /// <summary>Draws preview points and polylines (pattern points, Voronoi cells, panels) during a command.</summary>
    internal sealed class PreviewConduit : DisplayConduit
    {
        readonly object _lock = new object();
        List<Point3d> _points = new List<Point3d>();
        List<Point3d> _highlighted = new List<Point3d>();
        List<List<Point3d>> _lines = new List<List<Point3d>>();
        BoundingBox _box = BoundingBox.Empty;

        public Color PointColor = Color.Black;
        public Color HighlightColor = Color.Red;
        public Color LineColor = Color.SteelBlue;

        public void Set(List<Point3d> points, List<List<Point3d>> lines, List<Point3d> highlighted = null)
        {
            lock (_lock)
            {
                _points = points ?? new List<Point3d>();
                _lines = lines ?? new List<List<Point3d>>();
                _highlighted = highlighted ?? new List<Point3d>();
                var box = new BoundingBox(_points);
                foreach (var line in _lines) box.Union(new BoundingBox(line));
                _box = box;
            }
        }

        protected override void CalculateBoundingBox(CalculateBoundingBoxEventArgs e)
        {
            lock (_lock) if (_box.IsValid) e.IncludeBoundingBox(_box);
        }

        protected override void PostDrawObjects(DrawEventArgs e)
        {
            lock (_lock)
            {
                foreach (var line in _lines) e.Display.DrawPolyline(line, LineColor, 1);
                if (_points.Count > 0) e.Display.DrawPoints(_points, PointStyle.RoundControlPoint, 3, PointColor);
                if (_highlighted.Count > 0) e.Display.DrawPoints(_highlighted, PointStyle.RoundActivePoint, 4, HighlightColor);
            }
        }
    }
}
