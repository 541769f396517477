// The Rhino-free side of "TpiFabricate" and "TPI Fabricate": settings with defaults in the
// model's units, their validation, running the library's fabrication from a discrete surface's
// stored data, and reading its panels.json and panels.obj into plain geometry (solids as
// triangulated closed meshes, flat outlines placed on sheets, sheet rectangles beside the model).
using System;
using System.Collections.Generic;
using System.Globalization;
using System.Linq;
using Tpi.Native;

namespace Tpi.Logic
{
    /// <summary>A point in a plane (flat parts, sheets).</summary>
    public struct Point2
    {
        /// <summary>First coordinate.</summary>
        public double X;
        /// <summary>Second coordinate.</summary>
        public double Y;
        /// <summary>A point.</summary>
        public Point2(double x, double y) { X = x; Y = y; }
    }

    /// <summary>What the user chooses for a fabrication. Lengths in model units.</summary>
    public sealed class FabricationSettings
    {
        /// <summary>Panel thickness.</summary>
        public double Thickness { get; set; }
        /// <summary>Which side the panels are thickened to.</summary>
        public PanelSide Side { get; set; }
        /// <summary>Cleat slots per interior edge (0: none).</summary>
        public int SlotsPerEdge { get; set; }
        /// <summary>Sheet width.</summary>
        public double SheetWidth { get; set; }
        /// <summary>Sheet height.</summary>
        public double SheetHeight { get; set; }
        /// <summary>Gap between parts and from the sheet's edges.</summary>
        public double Gap { get; set; }
        /// <summary>Router tool diameter for the G-code.</summary>
        public double ToolDiameter { get; set; }

        /// <summary>A copy.</summary>
        public FabricationSettings Clone() { return (FabricationSettings)MemberwiseClone(); }

        /// <summary>
        /// Metres per model unit for Rhino's <c>UnitSystem</c> values (1 microns, 2 mm, 3 cm,
        /// 4 m, 5 km, 6 microinches, 7 mils, 8 inches, 9 feet, 10 miles, 12 angstroms,
        /// 13 nm, 14 dm, 15 dam, 16 hm, 19 yards); NaN for none (0), custom units and others.
        /// </summary>
        public static double MetresPerUnit(int rhinoUnitSystem)
        {
            switch (rhinoUnitSystem)
            {
                case 1: return 1e-6;
                case 2: return 1e-3;
                case 3: return 1e-2;
                case 4: return 1.0;
                case 5: return 1e3;
                case 6: return 2.54e-8;
                case 7: return 2.54e-5;
                case 8: return 0.0254;
                case 9: return 0.3048;
                case 10: return 1609.344;
                case 12: return 1e-10;
                case 13: return 1e-9;
                case 14: return 0.1;
                case 15: return 10.0;
                case 16: return 100.0;
                case 19: return 0.9144;
                default: return double.NaN;
            }
        }

        /// <summary>
        /// True for the unit systems the library writes to its files (the <c>TPI_UNITS_*</c> of
        /// include/tpi.h: mm, cm, m, km, microns, inches, feet, miles, yards); others are
        /// fabricated unitless.
        /// </summary>
        public static bool LibraryKnowsUnits(int rhinoUnitSystem)
        {
            switch (rhinoUnitSystem)
            {
                case 1: case 2: case 3: case 4: case 5: case 8: case 9: case 10: case 19: return true;
                default: return false;
            }
        }

        /// <summary>
        /// Defaults for <paramref name="mesh"/> in a model of <paramref name="rhinoUnitSystem"/>:
        /// the CLI's defaults in metres (40 mm panels, 2.5 x 1.25 m sheets, 20 mm gap, 6 mm tool)
        /// converted to model units, but the thickness at most a tenth of the median facet edge
        /// (short edges limit the thickness, docs/fabrication.md) and the sheet enlarged so the
        /// largest facet fits. A unitless model is taken as metres.
        /// </summary>
        public static FabricationSettings Defaults(MeshData mesh, int rhinoUnitSystem)
        {
            double m = MetresPerUnit(rhinoUnitSystem);
            if (double.IsNaN(m)) m = 1.0;
            var s = new FabricationSettings
            {
                Thickness = 0.04 / m,
                Side = PanelSide.Inside,
                SlotsPerEdge = 0,
                SheetWidth = 2.5 / m,
                SheetHeight = 1.25 / m,
                Gap = 0.02 / m,
                ToolDiameter = 0.006 / m,
            };
            if (mesh == null || mesh.FacetCount == 0) return s;
            var edges = new List<double>();
            double largest = 0;
            for (int f = 0; f < mesh.FacetCount; f++)
            {
                var loop = mesh.Facet(f);
                for (int a = 0; a < loop.Length; a++)
                {
                    var p = mesh.Vertices[loop[a]];
                    edges.Add(Length(mesh.Vertices[loop[(a + 1) % loop.Length]] - p));
                    for (int b = a + 1; b < loop.Length; b++) largest = Math.Max(largest, Length(mesh.Vertices[loop[b]] - p));
                }
            }
            edges.Sort();
            double median = edges[edges.Count / 2];
            if (median > 0) s.Thickness = Math.Min(s.Thickness, 0.1 * median);
            // The gap and the tool scale with the thickness when the thickness had to shrink.
            double shrink = s.Thickness / (0.04 / m);
            s.Gap *= shrink;
            s.ToolDiameter *= shrink;
            double need = largest + 2 * s.Gap;
            if (s.SheetHeight < need) { s.SheetWidth *= need / s.SheetHeight; s.SheetHeight = need; }
            return s;
        }

        static double Length(Vec3 v) { return Math.Sqrt(Vec3.Dot(v, v)); }

        /// <summary>What is wrong with the settings, one message each (empty: usable).</summary>
        public List<string> Validate()
        {
            var errors = new List<string>();
            Positive(errors, "thickness", Thickness);
            Positive(errors, "sheet width", SheetWidth);
            Positive(errors, "sheet height", SheetHeight);
            Positive(errors, "tool diameter", ToolDiameter);
            if (double.IsNaN(Gap) || double.IsInfinity(Gap) || Gap < 0) errors.Add("the gap must be a finite number >= 0 (got " + Gap.ToString(CultureInfo.InvariantCulture) + ")");
            if (SlotsPerEdge < 0) errors.Add("slots per edge must be >= 0 (got " + SlotsPerEdge + ")");
            if (Side != PanelSide.Inside && Side != PanelSide.Outside) errors.Add("the side must be inside or outside");
            if (errors.Count == 0 && 2 * Gap >= Math.Min(SheetWidth, SheetHeight)) errors.Add("the gap leaves no room on the sheet");
            return errors;
        }

        static void Positive(List<string> errors, string name, double value)
        {
            if (double.IsNaN(value) || double.IsInfinity(value) || value <= 0)
                errors.Add("the " + name + " must be a finite number > 0 (got " + value.ToString(CultureInfo.InvariantCulture) + ")");
        }
    }

    /// <summary>A closed polyhedron: vertices and planar polygon faces (outward), as in panels.obj.</summary>
    public sealed class PolyhedronData
    {
        /// <summary>The OBJ object name (panel_SEED or cleat_A_B_Q).</summary>
        public string Name { get; set; }
        /// <summary>Vertices.</summary>
        public Vec3[] Vertices { get; set; }
        /// <summary>Faces as vertex index loops (0-based).</summary>
        public int[][] Faces { get; set; }

        /// <summary>Every face split into triangles (ear clipping in the face's plane: notched faces are not convex), 3 indices each.</summary>
        public int[] Triangles()
        {
            var result = new List<int>();
            foreach (var f in Faces) result.AddRange(FabricationLayout.Triangulate(Vertices, f));
            return result.ToArray();
        }

        /// <summary>Enclosed volume by the divergence theorem over <see cref="Triangles"/>.</summary>
        public double Volume()
        {
            var t = Triangles();
            double v = 0;
            for (int k = 0; k < t.Length; k += 3)
                v += Vec3.Dot(Vertices[t[k]], Vec3.Cross(Vertices[t[k + 1]], Vertices[t[k + 2]]));
            return v / 6.0;
        }
    }

    /// <summary>A polyline of an ASCII DXF drawing: an LWPOLYLINE (R14 and later, what the library
    /// writes) or a POLYLINE with its VERTEX points (R12); x and y.</summary>
    public sealed class DxfPolyline
    {
        /// <summary>Layer name (code 8).</summary>
        public string Layer { get; set; }
        /// <summary>Closed (flag 1 of code 70).</summary>
        public bool Closed { get; set; }
        /// <summary>The vertices.</summary>
        public Point2[] Points { get; set; }

        /// <summary>The LWPOLYLINE and POLYLINE entities of <paramref name="dxf"/> in file order;
        /// FormatException on a malformed one.</summary>
        public static List<DxfPolyline> Parse(string dxf)
        {
            var lines = (dxf ?? string.Empty).Replace("\r", string.Empty).Split('\n');
            var result = new List<DxfPolyline>();
            DxfPolyline current = null;
            List<Point2> points = null;
            bool inVertex = false, light = false, haveX = false;
            double x = 0;
            for (int i = 0; i + 1 < lines.Length; i += 2)
            {
                var code = lines[i].Trim();
                var value = lines[i + 1].Trim();
                if (code == "0")
                {
                    if (light)
                    {
                        // An LWPOLYLINE ends at the next entity.
                        if (haveX) throw new FormatException("DXF: an LWPOLYLINE vertex without y at line " + (i + 1));
                        current.Points = points.ToArray();
                        result.Add(current);
                        current = null;
                        light = false;
                    }
                    if (value == "LWPOLYLINE")
                    {
                        if (current != null) throw new FormatException("DXF: an LWPOLYLINE inside a POLYLINE at line " + (i + 1));
                        current = new DxfPolyline(); points = new List<Point2>(); light = true; haveX = false;
                    }
                    else if (value == "POLYLINE") { current = new DxfPolyline(); points = new List<Point2>(); inVertex = false; }
                    else if (value == "VERTEX")
                    {
                        if (current == null) throw new FormatException("DXF: VERTEX outside a POLYLINE at line " + (i + 1));
                        inVertex = true;
                    }
                    else if (value == "SEQEND" && current != null)
                    {
                        current.Points = points.ToArray();
                        result.Add(current);
                        current = null;
                        inVertex = false;
                    }
                    else inVertex = false;
                    continue;
                }
                if (current == null) continue;
                if (light)
                {
                    if (code == "8") current.Layer = value;
                    else if (code == "70") current.Closed = (int.Parse(value, CultureInfo.InvariantCulture) & 1) != 0;
                    else if (code == "10")
                    {
                        if (haveX) throw new FormatException("DXF: an LWPOLYLINE vertex without y at line " + (i + 1));
                        x = double.Parse(value, NumberStyles.Float, CultureInfo.InvariantCulture);
                        haveX = true;
                    }
                    else if (code == "20")
                    {
                        if (!haveX) throw new FormatException("DXF: an LWPOLYLINE y without x at line " + (i + 1));
                        points.Add(new Point2(x, double.Parse(value, NumberStyles.Float, CultureInfo.InvariantCulture)));
                        haveX = false;
                    }
                    continue;
                }
                if (code == "8" && !inVertex) current.Layer = value;
                else if (code == "70" && !inVertex) current.Closed = (int.Parse(value, CultureInfo.InvariantCulture) & 1) != 0;
                else if (code == "10" && inVertex) x = double.Parse(value, NumberStyles.Float, CultureInfo.InvariantCulture);
                else if (code == "20" && inVertex) points.Add(new Point2(x, double.Parse(value, NumberStyles.Float, CultureInfo.InvariantCulture)));
            }
            if (light) throw new FormatException("DXF: an LWPOLYLINE without an end");
            if (current != null) throw new FormatException("DXF: a POLYLINE without SEQEND");
            return result;
        }
    }

    /// <summary>One panel as panels.json gives it.</summary>
    public sealed class FabricatedPanel
    {
        /// <summary>The seed (facet index).</summary>
        public int Seed { get; set; }
        /// <summary>Top outline (the facet).</summary>
        public Vec3[] Top { get; set; }
        /// <summary>Bottom outline: bottom[k] the offset of top[k], or where a collapsed edge was clipped the corner where side k's bottom edge starts (docs/fabrication.md).</summary>
        public Vec3[] Bottom { get; set; }
        /// <summary>Top outline in panel coordinates, same order as <see cref="Top"/>.</summary>
        public Point2[] Flat { get; set; }
        /// <summary>Neighbour across side k (top[k] to top[k+1]), -1 on the boundary.</summary>
        public int[] Neighbours { get; set; }
        /// <summary>Bevel of side k, degrees.</summary>
        public double[] BevelsDeg { get; set; }
        /// <summary>Slot notches in panel coordinates (4 points each).</summary>
        public Point2[][] Slots { get; set; }
        /// <summary>Sheet index.</summary>
        public int Sheet { get; set; }
        /// <summary>Placement: sheet point = R(angle) flat + (X, Y).</summary>
        public double X { get; set; }
        /// <summary>Placement translation, y.</summary>
        public double Y { get; set; }
        /// <summary>Placement rotation, degrees.</summary>
        public double AngleDeg { get; set; }
        /// <summary>Volume (the library's, notches cut).</summary>
        public double Volume { get; set; }

        /// <summary>A flat point moved to its place on the sheet (sheet coordinates).</summary>
        public Point2 Place(Point2 p)
        {
            double a = AngleDeg * Math.PI / 180.0, c = Math.Cos(a), s = Math.Sin(a);
            return new Point2(c * p.X - s * p.Y + X, s * p.X + c * p.Y + Y);
        }
    }

    /// <summary>One sheet.</summary>
    public sealed class SheetData
    {
        /// <summary>Width.</summary>
        public double Width { get; set; }
        /// <summary>Height.</summary>
        public double Height { get; set; }
        /// <summary>Cut-outline area over sheet area.</summary>
        public double Utilisation { get; set; }
    }

    /// <summary>A fabrication read into plain geometry.</summary>
    public sealed class FabricationLayout
    {
        /// <summary>Panel thickness.</summary>
        public double Thickness { get; private set; }
        /// <summary>The panels in seed order.</summary>
        public List<FabricatedPanel> Panels { get; private set; }
        /// <summary>The sheets.</summary>
        public List<SheetData> Sheets { get; private set; }
        /// <summary>Diagnostic kinds (e.g. slot_skipped), one entry per diagnostic.</summary>
        public List<string> Diagnostics { get; private set; }
        /// <summary>The panel solids (panel_SEED), from panels.obj.</summary>
        public List<PolyhedronData> PanelSolids { get; private set; }
        /// <summary>The cleat solids (cleat_A_B_Q), from panels.obj.</summary>
        public List<PolyhedronData> CleatSolids { get; private set; }

        /// <summary>
        /// Each panel's cut outline (what the router follows: the top outline, widened where the
        /// panel widens towards its bottom), in seed order, in the sheets' drawing coordinates
        /// (sheets.dxf layer CUT: sheet k starts at x = 1.1 times the widths before it, y = 0);
        /// empty when no DXF was given.
        /// </summary>
        public List<Point2[]> CutOutlines { get; private set; }
        /// <summary>The engraved labels (panel and neighbour numbers as single strokes, layer ENGRAVE), drawing coordinates.</summary>
        public List<Point2[]> LabelStrokes { get; private set; }

        /// <summary>
        /// Where the sheets' drawing (sheets.dxf, sheets.svg) lies in the model: its sheet k
        /// starts at <see cref="SheetOrigin(int)"/>, so a drawing point p is at p + this. The
        /// drawing spaces its sheets as <see cref="SheetOrigin(int, double, double)"/> does.
        /// </summary>
        public Point2 DrawingOrigin() { return Sheets.Count == 0 ? new Point2(0, 0) : SheetOrigin(0); }

        /// <summary>A drawing loop moved to the model by <see cref="DrawingOrigin"/>, closed when <paramref name="close"/>.</summary>
        public Point2[] ToModel(Point2[] drawing, bool close)
        {
            var o = DrawingOrigin();
            var moved = drawing.Select(p => new Point2(p.X + o.X, p.Y + o.Y));
            return close ? Closed(moved) : moved.ToArray();
        }

        /// <summary>Mean utilisation of the sheets (0 without sheets).</summary>
        public double MeanUtilisation { get { return Sheets.Count == 0 ? 0 : Sheets.Average(s => s.Utilisation); } }

        /// <summary>Reads panels.json and panels.obj (docs/fabrication.md); FormatException when they do not fit the contract.</summary>
        public static FabricationLayout Parse(string panelsJson, string panelsObj)
        {
            return Parse(panelsJson, panelsObj, null);
        }

        /// <summary>
        /// Reads panels.json, panels.obj and sheets.dxf (its CUT polylines, one per panel in seed
        /// order, and ENGRAVE strokes); FormatException when they do not fit the contract.
        /// </summary>
        public static FabricationLayout Parse(string panelsJson, string panelsObj, string sheetsDxf)
        {
            var root = JsonText.Parse(panelsJson) as Dictionary<string, object>;
            if (root == null) throw new FormatException("panels.json is not an object");
            var layout = new FabricationLayout
            {
                Thickness = Num(Get(root, "thickness")),
                Panels = new List<FabricatedPanel>(),
                Sheets = new List<SheetData>(),
                Diagnostics = new List<string>(),
            };
            foreach (Dictionary<string, object> p in List(root, "panels"))
            {
                var sides = List(p, "sides").Cast<Dictionary<string, object>>().ToList();
                var placement = (Dictionary<string, object>)Get(p, "placement");
                layout.Panels.Add(new FabricatedPanel
                {
                    Seed = (int)Num(Get(p, "seed")),
                    Top = List(p, "top").Select(Vec).ToArray(),
                    Bottom = List(p, "bottom").Select(Vec).ToArray(),
                    Flat = List(p, "flat").Select(Pt).ToArray(),
                    Neighbours = sides.Select(s => s["neighbour"] == null ? -1 : (int)Num(s["neighbour"])).ToArray(),
                    BevelsDeg = sides.Select(s => Num(Get(s, "bevel_deg"))).ToArray(),
                    Slots = List(p, "slots").Cast<Dictionary<string, object>>().Select(s => List(s, "flat").Select(Pt).ToArray()).ToArray(),
                    Sheet = (int)Num(Get(placement, "sheet")),
                    X = Num(Get(placement, "x")),
                    Y = Num(Get(placement, "y")),
                    AngleDeg = Num(Get(placement, "angle_deg")),
                    Volume = Num(Get(p, "volume")),
                });
            }
            foreach (Dictionary<string, object> s in List(root, "sheets"))
            {
                var size = (List<object>)Get(s, "size");
                layout.Sheets.Add(new SheetData { Width = Num(size[0]), Height = Num(size[1]), Utilisation = Num(Get(s, "utilisation")) });
            }
            object diagnostics;
            if (root.TryGetValue("diagnostics", out diagnostics) && diagnostics is List<object>)
                foreach (var d in (List<object>)diagnostics)
                {
                    var dict = d as Dictionary<string, object>;
                    object kind;
                    layout.Diagnostics.Add(dict != null && dict.TryGetValue("kind", out kind) ? Convert.ToString(kind, CultureInfo.InvariantCulture) : "diagnostic");
                }
            var solids = ParseObj(panelsObj ?? string.Empty);
            layout.PanelSolids = solids.Where(s => s.Name.StartsWith("panel_", StringComparison.Ordinal)).ToList();
            layout.CleatSolids = solids.Where(s => s.Name.StartsWith("cleat_", StringComparison.Ordinal)).ToList();
            var drawing = sheetsDxf == null ? new List<DxfPolyline>() : DxfPolyline.Parse(sheetsDxf);
            layout.CutOutlines = drawing.Where(d => d.Layer == "CUT").Select(d => d.Points).ToList();
            layout.LabelStrokes = drawing.Where(d => d.Layer == "ENGRAVE").Select(d => d.Points).ToList();
            if (sheetsDxf != null && layout.CutOutlines.Count != layout.Panels.Count)
                throw new FormatException("sheets.dxf has " + layout.CutOutlines.Count + " cut outlines for " + layout.Panels.Count + " panels");
            return layout;
        }

        /// <summary>The objects of an OBJ file (o, v, f; 1-based global indices, "i/t/n" accepted).</summary>
        public static List<PolyhedronData> ParseObj(string obj)
        {
            var result = new List<PolyhedronData>();
            var all = new List<Vec3>();
            string name = null;
            int first = 0;
            var faces = new List<int[]>();
            Action close = () =>
            {
                if (name == null) return;
                result.Add(new PolyhedronData
                {
                    Name = name,
                    Vertices = all.Skip(first).ToArray(),
                    Faces = faces.Select(f => f.Select(i => i - first).ToArray()).ToArray(),
                });
            };
            foreach (var raw in obj.Split('\n'))
            {
                var line = raw.Trim();
                if (line.Length == 0 || line[0] == '#') continue;
                var parts = line.Split(new[] { ' ', '\t' }, StringSplitOptions.RemoveEmptyEntries);
                switch (parts[0])
                {
                    case "o":
                        close();
                        name = parts.Length > 1 ? parts[1] : "object";
                        first = all.Count;
                        faces = new List<int[]>();
                        break;
                    case "v":
                        all.Add(new Vec3(D(parts[1]), D(parts[2]), D(parts[3])));
                        break;
                    case "f":
                        if (name == null) throw new FormatException("panels.obj: a face before any object");
                        var face = parts.Skip(1).Select(t => int.Parse(t.Split('/')[0], CultureInfo.InvariantCulture) - 1).ToArray();
                        if (face.Any(i => i < first || i >= all.Count)) throw new FormatException("panels.obj: face of " + name + " refers to a vertex outside its object");
                        faces.Add(face);
                        break;
                }
            }
            close();
            return result;
        }

        /// <summary>
        /// The origin of sheet <paramref name="sheet"/> when the sheets are laid beside a model whose
        /// bounding box ends at <paramref name="modelMaxX"/> and starts at <paramref name="modelMinY"/>:
        /// side by side along x, a tenth of the first sheet's width after the model and 10 % of
        /// each sheet's width apart (the SVG and DXF drawings' spacing).
        /// </summary>
        public Point2 SheetOrigin(int sheet, double modelMaxX, double modelMinY)
        {
            if (sheet < 0 || sheet >= Sheets.Count) throw new ArgumentOutOfRangeException("sheet", sheet, "there are " + Sheets.Count + " sheets");
            double x = modelMaxX + 0.1 * Sheets[0].Width;
            for (int k = 0; k < sheet; k++) x += 1.1 * Sheets[k].Width;
            return new Point2(x, modelMinY);
        }

        /// <summary><see cref="SheetOrigin(int, double, double)"/> beside the panels' own bounding box (top and bottom faces).</summary>
        public Point2 SheetOrigin(int sheet)
        {
            double maxX = double.NegativeInfinity, minY = double.PositiveInfinity;
            foreach (var p in Panels)
                foreach (var v in p.Top.Concat(p.Bottom)) { maxX = Math.Max(maxX, v.X); minY = Math.Min(minY, v.Y); }
            if (double.IsInfinity(maxX)) { maxX = 0; minY = 0; }
            return SheetOrigin(sheet, maxX, minY);
        }

        /// <summary>The height of the panels' lowest point (0 without panels): where the sheets are drawn.</summary>
        public double LowestZ()
        {
            double z = double.PositiveInfinity;
            foreach (var p in Panels)
                foreach (var v in p.Top.Concat(p.Bottom)) z = Math.Min(z, v.Z);
            return double.IsInfinity(z) ? 0 : z;
        }

        /// <summary>Sheet k's rectangle as a closed loop (5 points, first repeated) in sheet coordinates moved by <paramref name="origin"/>.</summary>
        public Point2[] SheetRectangle(int sheet, Point2 origin)
        {
            var s = Sheets[sheet];
            return new[]
            {
                new Point2(origin.X, origin.Y), new Point2(origin.X + s.Width, origin.Y),
                new Point2(origin.X + s.Width, origin.Y + s.Height), new Point2(origin.X, origin.Y + s.Height),
                new Point2(origin.X, origin.Y),
            };
        }

        /// <summary>A panel's top outline placed on its sheet and moved by <paramref name="origin"/>, closed (first point repeated).</summary>
        public static Point2[] PlacedOutline(FabricatedPanel panel, Point2 origin)
        {
            return Closed(panel.Flat.Select(p => Shift(panel.Place(p), origin)));
        }

        /// <summary>A panel's slot notches placed like <see cref="PlacedOutline"/>, each closed.</summary>
        public static Point2[][] PlacedSlots(FabricatedPanel panel, Point2 origin)
        {
            return panel.Slots.Select(s => Closed(s.Select(p => Shift(panel.Place(p), origin)))).ToArray();
        }

        static Point2 Shift(Point2 p, Point2 by) { return new Point2(p.X + by.X, p.Y + by.Y); }

        static Point2[] Closed(IEnumerable<Point2> points)
        {
            var list = points.ToList();
            if (list.Count > 0) list.Add(list[0]);
            return list.ToArray();
        }

        /// <summary>Ear clipping of the polygon <paramref name="loop"/> in its own plane (Newell normal); 3 indices per triangle.</summary>
        public static int[] Triangulate(Vec3[] vertices, int[] loop)
        {
            int n = loop.Length;
            if (n < 3) return new int[0];
            var normal = new Vec3(0, 0, 0);
            for (int k = 0; k < n; k++)
            {
                var a = vertices[loop[k]];
                var b = vertices[loop[(k + 1) % n]];
                normal = normal + new Vec3((a.Y - b.Y) * (a.Z + b.Z), (a.Z - b.Z) * (a.X + b.X), (a.X - b.X) * (a.Y + b.Y));
            }
            var remaining = loop.ToList();
            var result = new List<int>();
            int guard = 0;
            while (remaining.Count > 3 && guard < 4 * n * n)
            {
                guard++;
                bool clipped = false;
                for (int k = 0; k < remaining.Count; k++)
                {
                    int ia = remaining[(k + remaining.Count - 1) % remaining.Count], ib = remaining[k], ic = remaining[(k + 1) % remaining.Count];
                    var a = vertices[ia];
                    var b = vertices[ib];
                    var c = vertices[ic];
                    double turn = Vec3.Dot(Vec3.Cross(b - a, c - b), normal);
                    if (turn <= 0) continue; // reflex or degenerate corner
                    bool inside = false;
                    foreach (var iq in remaining)
                    {
                        if (iq == ia || iq == ib || iq == ic) continue;
                        var q = vertices[iq];
                        if (Vec3.Dot(Vec3.Cross(b - a, q - a), normal) >= 0 && Vec3.Dot(Vec3.Cross(c - b, q - b), normal) >= 0
                            && Vec3.Dot(Vec3.Cross(a - c, q - c), normal) >= 0) { inside = true; break; }
                    }
                    if (inside) continue;
                    result.Add(ia); result.Add(ib); result.Add(ic);
                    remaining.RemoveAt(k);
                    clipped = true;
                    break;
                }
                if (!clipped)
                {
                    // Only degenerate corners left (collinear points): drop one as a zero-area fan.
                    result.Add(remaining[remaining.Count - 1]); result.Add(remaining[0]); result.Add(remaining[1]);
                    remaining.RemoveAt(0);
                }
            }
            if (remaining.Count == 3) result.AddRange(remaining);
            return result.ToArray();
        }

        static double D(string s) { return double.Parse(s, NumberStyles.Float, CultureInfo.InvariantCulture); }

        static object Get(Dictionary<string, object> d, string key)
        {
            object v;
            if (!d.TryGetValue(key, out v)) throw new FormatException("panels.json: missing \"" + key + "\"");
            return v;
        }

        static List<object> List(Dictionary<string, object> d, string key)
        {
            var list = Get(d, key) as List<object>;
            if (list == null) throw new FormatException("panels.json: \"" + key + "\" is not a list");
            return list;
        }

        static double Num(object o)
        {
            if (!(o is double)) throw new FormatException("panels.json: expected a number");
            return (double)o;
        }

        static Vec3 Vec(object o)
        {
            var l = (List<object>)o;
            return new Vec3(Num(l[0]), Num(l[1]), Num(l[2]));
        }

        static Point2 Pt(object o)
        {
            var l = (List<object>)o;
            return new Point2(Num(l[0]), Num(l[1]));
        }
    }
}

namespace Tpi.Logic
{
    /// <summary>The outcome of a fabrication: the files as text and their geometry, or the errors.</summary>
    public sealed class FabricationResult
    {
        /// <summary>What went wrong (empty on success).</summary>
        public List<string> Errors { get; private set; }
        /// <summary>Number of facets of the discretisation fabricated.</summary>
        public int FacetCount { get; internal set; }
        /// <summary>The geometry (null on failure).</summary>
        public FabricationLayout Layout { get; internal set; }
        /// <summary>panels.json.</summary>
        public string PanelsJson { get; internal set; }
        /// <summary>panels.obj.</summary>
        public string PanelsObj { get; internal set; }
        /// <summary>sheets.svg.</summary>
        public string SheetsSvg { get; internal set; }
        /// <summary>sheets.dxf.</summary>
        public string SheetsDxf { get; internal set; }
        /// <summary>bevels.csv.</summary>
        public string BevelsCsv { get; internal set; }
        /// <summary>cut.nc (G-code for the settings' tool diameter).</summary>
        public string GCode { get; internal set; }
        /// <summary>True when everything was made.</summary>
        public bool Success { get { return Errors.Count == 0 && Layout != null; } }

        internal FabricationResult() { Errors = new List<string>(); }

        /// <summary>One line for the command line or the component's message.</summary>
        public string Summary()
        {
            if (!Success) return "fabrication failed: " + string.Join("; ", Errors);
            var l = Layout;
            var per = string.Join(", ", l.Sheets.Select((s, k) => "sheet " + (k + 1) + ": " + Percent(s.Utilisation)));
            return string.Format(CultureInfo.InvariantCulture, "{0} panels, {1} cleats, {2} sheets, utilisation {3} mean ({4}){5}",
                l.Panels.Count, l.CleatSolids.Count, l.Sheets.Count, Percent(l.MeanUtilisation), per,
                l.Diagnostics.Count > 0 ? "; " + l.Diagnostics.Count + " diagnostics: " + string.Join(", ", l.Diagnostics.Distinct()) : string.Empty);
        }

        static string Percent(double u) { return (100 * u).ToString("0.0", CultureInfo.InvariantCulture) + " %"; }

        /// <summary>The file names and contents written by <see cref="FabricationRun.WriteFiles"/>.</summary>
        public IEnumerable<KeyValuePair<string, string>> Files()
        {
            yield return new KeyValuePair<string, string>("panels.json", PanelsJson);
            yield return new KeyValuePair<string, string>("panels.obj", PanelsObj);
            yield return new KeyValuePair<string, string>("sheets.svg", SheetsSvg);
            yield return new KeyValuePair<string, string>("sheets.dxf", SheetsDxf);
            yield return new KeyValuePair<string, string>("bevels.csv", BevelsCsv);
            yield return new KeyValuePair<string, string>("cut.nc", GCode);
        }
    }

    /// <summary>Runs the library's fabrication on a discrete surface's stored data.</summary>
    public static class FabricationRun
    {
        /// <summary>
        /// Recomputes the discretisation of <paramref name="source"/> (surface, points, options:
        /// the stored data recomputes to the mesh that was shown) and fabricates it. The model's
        /// units (Rhino's UnitSystem value, 0: none) go to the files. Problems are reported in
        /// the result, never thrown.
        /// </summary>
        public static FabricationResult Run(DiscreteSurfaceDocument source, FabricationSettings settings, int rhinoUnitSystem)
        {
            var result = new FabricationResult();
            if (source == null || source.Surface == null) { result.Errors.Add("no discrete surface to fabricate"); return result; }
            if (source.Points == null || source.Points.Count == 0) { result.Errors.Add("the discrete surface has no pattern points"); return result; }
            if (settings == null) { result.Errors.Add("no settings"); return result; }
            result.Errors.AddRange(settings.Validate());
            if (result.Errors.Count > 0) return result;
            try
            {
                using (var plain = source.Surface.CreateNative())
                using (var surface = FabricationSettings.LibraryKnowsUnits(rhinoUnitSystem) ? plain.WithUnits(rhinoUnitSystem) : null)
                using (var pattern = Pattern.FromPoints(source.Points))
                using (var mesh = Discretisation.Create(surface ?? plain, pattern, source.Options))
                using (var fab = Fabrication.Create(mesh, settings.Thickness, settings.Side, (uint)settings.SlotsPerEdge,
                    settings.SheetWidth, settings.SheetHeight, settings.Gap))
                {
                    result.FacetCount = mesh.FacetCount;
                    result.PanelsJson = fab.File(FabricationFile.PanelsJson);
                    result.PanelsObj = fab.File(FabricationFile.PanelsObj);
                    result.SheetsSvg = fab.File(FabricationFile.SheetsSvg);
                    result.SheetsDxf = fab.File(FabricationFile.SheetsDxf);
                    result.BevelsCsv = fab.File(FabricationFile.BevelsCsv);
                    result.GCode = fab.GCode(settings.ToolDiameter);
                }
                result.Layout = FabricationLayout.Parse(result.PanelsJson, result.PanelsObj, result.SheetsDxf);
            }
            catch (TpiException e)
            {
                result.Layout = null;
                result.Errors.Add(TpiLibrary.StatusName(e.Status) + ": " + e.NativeMessage);
            }
            catch (FormatException e)
            {
                result.Layout = null;
                result.Errors.Add("could not read the library's output: " + e.Message);
            }
            return result;
        }

        /// <summary>
        /// "TPI Fabricate": fabricates the mesh of a TPI Discretise result (its <see cref="MeshData.Source"/>
        /// recomputed), checking that the recomputed mesh has the same facets.
        /// </summary>
        public static FabricationResult Run(MeshData mesh, FabricationSettings settings, int rhinoUnitSystem)
        {
            if (mesh == null || mesh.Source == null)
            {
                var failed = new FabricationResult();
                failed.Errors.Add("the discretisation must be the Result output of TPI Discretise");
                return failed;
            }
            var result = Run(mesh.Source, settings, rhinoUnitSystem);
            if (result.Success && result.FacetCount != mesh.FacetCount)
            {
                result.Layout = null;
                result.Errors.Add("the recomputed discretisation has " + result.FacetCount + " facets, the given one " + mesh.FacetCount);
            }
            return result;
        }

        /// <summary>
        /// "TPI Fabricate": the inputs given (null: not connected) over the defaults for the mesh
        /// and the model's units; <paramref name="side"/> 0 inside, 1 outside. Problems are
        /// reported in the result, never thrown.
        /// </summary>
        public static FabricationResult ForComponent(MeshData mesh, int rhinoUnitSystem, double? thickness, int side, int slotsPerEdge,
            double? sheetWidth, double? sheetHeight, double? gap, double? toolDiameter, out FabricationSettings used)
        {
            used = FabricationSettings.Defaults(mesh, rhinoUnitSystem);
            if (thickness.HasValue) used.Thickness = thickness.Value;
            used.SlotsPerEdge = slotsPerEdge;
            if (sheetWidth.HasValue) used.SheetWidth = sheetWidth.Value;
            if (sheetHeight.HasValue) used.SheetHeight = sheetHeight.Value;
            if (gap.HasValue) used.Gap = gap.Value;
            if (toolDiameter.HasValue) used.ToolDiameter = toolDiameter.Value;
            if (side == 0 || side == 1) used.Side = side == 0 ? PanelSide.Inside : PanelSide.Outside;
            else
            {
                var rejected = new FabricationResult();
                rejected.Errors.Add("the side must be 0 (inside) or 1 (outside), got " + side);
                return rejected;
            }
            return Run(mesh, used, rhinoUnitSystem);
        }

        /// <summary>Writes the six files into <paramref name="folder"/> (created if missing); returns their paths.</summary>
        public static List<string> WriteFiles(FabricationResult result, string folder)
        {
            if (result == null || !result.Success) throw new InvalidOperationException("nothing to write: the fabrication failed");
            if (string.IsNullOrWhiteSpace(folder)) throw new ArgumentException("no folder given", "folder");
            System.IO.Directory.CreateDirectory(folder);
            var paths = new List<string>();
            foreach (var f in result.Files())
            {
                var path = System.IO.Path.Combine(folder, f.Key);
                System.IO.File.WriteAllText(path, f.Value);
                paths.Add(path);
            }
            return paths;
        }
    }
}
