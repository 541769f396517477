using System;
using System.Collections.Generic;
using System.Linq;
using NUnit.Framework;
using Tpi.Logic;
using Tpi.Native;

namespace Tpi.Tests
{
    /// <summary>
    /// The Rhino-free side of TpiFabricate / TPI Fabricate: the library's panels.json and
    /// panels.obj read into plain geometry, checked against the discretisation they came from and
    /// against geometry computed here (pairwise distances, shoelace areas, the prismatoid volume,
    /// edge pairing of the triangulated solids), not against the library's own numbers alone.
    /// </summary>
    [TestFixture]
    public class FabricationLayoutTests
    {
        static MeshData DomeMesh(int n = 6)
        {
            var output = ComponentSolvers.Discretise(new DiscretiseInput { Surface = LogicData.Dome(), Points = LogicData.Hex(n, n) });
            Assert.IsTrue(output.Success, string.Join("; ", output.Errors));
            return output.Mesh;
        }

        static FabricationSettings Settings(int slots = 0, PanelSide side = PanelSide.Inside)
        {
            return new FabricationSettings
            {
                Thickness = 0.03, Side = side, SlotsPerEdge = slots, SheetWidth = 1.5, SheetHeight = 1.0, Gap = 0.02, ToolDiameter = 0.006,
            };
        }

        static double Dist(Vec3 a, Vec3 b) { var d = a - b; return Math.Sqrt(Vec3.Dot(d, d)); }

        static double Dist(Point2 a, Point2 b) { return Math.Sqrt((a.X - b.X) * (a.X - b.X) + (a.Y - b.Y) * (a.Y - b.Y)); }

        /// <summary>Area of a 3D planar polygon (half the Newell normal's length).</summary>
        static double Area(IList<Vec3> loop)
        {
            var n = new Vec3(0, 0, 0);
            for (int k = 0; k < loop.Count; k++) n = n + Vec3.Cross(loop[k], loop[(k + 1) % loop.Count]);
            return 0.5 * Math.Sqrt(Vec3.Dot(n, n));
        }

        [Test]
        public void OnePanelPerFacetWhoseTopIsTheFacet()
        {
            var mesh = DomeMesh();
            var result = FabricationRun.Run(mesh, Settings(), 4);
            Assert.IsTrue(result.Success, string.Join("; ", result.Errors));
            var layout = result.Layout;
            Assert.AreEqual(mesh.FacetCount, layout.Panels.Count, "one panel per facet");
            Assert.AreEqual(mesh.FacetCount, layout.PanelSolids.Count, "one solid per facet");
            Assert.AreEqual(layout.PanelSolids.SelectMany(q => q.Vertices).Min(v => v.Z), layout.LowestZ(), 1e-12, "the solids' lowest point");
            Assert.IsEmpty(layout.CleatSolids, "no slots asked, no cleats");
            for (int i = 0; i < layout.Panels.Count; i++)
            {
                var panel = layout.Panels[i];
                Assert.AreEqual(i, panel.Seed);
                Assert.AreEqual("panel_" + i, layout.PanelSolids[i].Name);
                var facet = mesh.Facet(i).Select(v => mesh.Vertices[v]).ToArray();
                // Every top vertex is a vertex of the facet and every facet vertex is on the top.
                foreach (var v in panel.Top) Assert.Less(facet.Min(f => Dist(f, v)), 1e-9, "panel " + i + ": top vertex off the facet");
                foreach (var f in facet) Assert.Less(panel.Top.Min(v => Dist(f, v)), 1e-9, "panel " + i + ": facet vertex missing from the top");
                Assert.AreEqual(panel.Top.Length, panel.Bottom.Length);
                // The bottom lies at the thickness from the top plane.
                var normal = Vec3.Cross(panel.Top[1] - panel.Top[0], panel.Top[2] - panel.Top[0]);
                normal = (1 / Math.Sqrt(Vec3.Dot(normal, normal))) * normal;
                foreach (var b in panel.Bottom)
                    Assert.AreEqual(0.03, Math.Abs(Vec3.Dot(b - panel.Top[0], normal)), 1e-9, "panel " + i + ": bottom vertex off the offset plane");
            }
            StringAssert.Contains(mesh.FacetCount + " panels", result.Summary());
            StringAssert.Contains(layout.Sheets.Count + " sheets", result.Summary());
        }

        [Test]
        public void FlatOutlinesAreCongruentToTheirTopFaces()
        {
            var layout = FabricationRun.Run(DomeMesh(), Settings(), 4).Layout;
            foreach (var panel in layout.Panels)
            {
                Assert.AreEqual(panel.Top.Length, panel.Flat.Length);
                var placed = FabricationLayout.PlacedOutline(panel, layout.SheetOrigin(panel.Sheet));
                Assert.AreEqual(panel.Flat.Length + 1, placed.Length, "closed");
                for (int a = 0; a < panel.Top.Length; a++)
                    for (int b = a + 1; b < panel.Top.Length; b++)
                    {
                        double d3 = Dist(panel.Top[a], panel.Top[b]);
                        Assert.AreEqual(d3, Dist(panel.Flat[a], panel.Flat[b]), 1e-9, "panel " + panel.Seed + ": flat distance " + a + "-" + b);
                        Assert.AreEqual(d3, Dist(placed[a], placed[b]), 1e-9, "panel " + panel.Seed + ": placed distance " + a + "-" + b);
                    }
            }
        }

        [Test]
        public void PlacedOutlinesLieInsideTheirSheetBesideTheModel()
        {
            var settings = Settings(2);
            var layout = FabricationRun.Run(DomeMesh(), settings, 4).Layout;
            Assert.Greater(layout.Sheets.Count, 1, "the parts do not fit one 1.5 x 1 sheet");
            double modelMaxX = layout.Panels.SelectMany(p => p.Top.Concat(p.Bottom)).Max(v => v.X);
            var rectangles = Enumerable.Range(0, layout.Sheets.Count).Select(k => layout.SheetRectangle(k, layout.SheetOrigin(k))).ToArray();
            for (int k = 0; k < rectangles.Length; k++)
            {
                Assert.AreEqual(1.5, rectangles[k][1].X - rectangles[k][0].X, 1e-12);
                Assert.AreEqual(1.0, rectangles[k][2].Y - rectangles[k][1].Y, 1e-12);
                Assert.Greater(rectangles[k][0].X, modelMaxX, "sheet " + k + " lies beside the model");
                if (k > 0) Assert.Greater(rectangles[k][0].X, rectangles[k - 1][1].X, "sheets do not overlap");
            }
            int slots = 0;
            foreach (var panel in layout.Panels)
            {
                var r = rectangles[panel.Sheet];
                var loops = new[] { FabricationLayout.PlacedOutline(panel, r[0]) }.Concat(FabricationLayout.PlacedSlots(panel, r[0]));
                foreach (var loop in loops)
                    foreach (var p in loop)
                    {
                        // At least the gap from the sheet's edges (the top outline lies inside the cut outline).
                        Assert.GreaterOrEqual(p.X, r[0].X + settings.Gap - 1e-9, "panel " + panel.Seed);
                        Assert.LessOrEqual(p.X, r[1].X - settings.Gap + 1e-9, "panel " + panel.Seed);
                        Assert.GreaterOrEqual(p.Y, r[0].Y + settings.Gap - 1e-9, "panel " + panel.Seed);
                        Assert.LessOrEqual(p.Y, r[2].Y - settings.Gap + 1e-9, "panel " + panel.Seed);
                    }
                slots += panel.Slots.Length;
            }
            Assert.Greater(slots, 0, "two slots per interior edge asked");
            Assert.AreEqual(slots / 2, layout.CleatSolids.Count, "one cleat fills the two notches of a slot");
        }

        static double ShoelaceArea(IList<Point2> loop)
        {
            double a = 0;
            for (int k = 0; k < loop.Count; k++) a += loop[k].X * loop[(k + 1) % loop.Count].Y - loop[(k + 1) % loop.Count].X * loop[k].Y;
            return 0.5 * a;
        }

        static double DistanceToSegment(Point2 p, Point2 a, Point2 b)
        {
            double dx = b.X - a.X, dy = b.Y - a.Y;
            double t = Math.Max(0, Math.Min(1, ((p.X - a.X) * dx + (p.Y - a.Y) * dy) / (dx * dx + dy * dy)));
            return Dist(p, new Point2(a.X + t * dx, a.Y + t * dy));
        }

        /// <summary>Inside the polygon by the crossing rule, or within tol of its boundary.</summary>
        static bool InsideOrOn(Point2 p, IList<Point2> loop, double tol)
        {
            bool inside = false;
            for (int k = 0; k < loop.Count; k++)
            {
                Point2 a = loop[k], b = loop[(k + 1) % loop.Count];
                if (DistanceToSegment(p, a, b) <= tol) return true;
                if ((a.Y > p.Y) != (b.Y > p.Y) && p.X < a.X + (p.Y - a.Y) * (b.X - a.X) / (b.Y - a.Y)) inside = !inside;
            }
            return inside;
        }

        [Test]
        public void CutOutlinesFromTheDxfAreTheTopOutlinesInsideAndContainThemOutside()
        {
            var inside = FabricationRun.Run(DomeMesh(), Settings(), 4).Layout;
            Assert.AreEqual(inside.Panels.Count, inside.CutOutlines.Count, "one CUT polyline per panel");
            Assert.Greater(inside.LabelStrokes.Count, inside.Panels.Count, "panel and neighbour numbers");
            foreach (var panel in inside.Panels)
            {
                // On the concave side no panel widens towards its bottom: the cut outline, moved from
                // the drawing to the model, is the top outline placed on its sheet.
                var cut = inside.ToModel(inside.CutOutlines[panel.Seed], false);
                var top = FabricationLayout.PlacedOutline(panel, inside.SheetOrigin(panel.Sheet)).Take(panel.Flat.Length).ToArray();
                Assert.AreEqual(top.Length, cut.Length, "panel " + panel.Seed);
                foreach (var c in cut) Assert.Less(top.Min(t => Dist(t, c)), 1e-9, "panel " + panel.Seed + ": cut vertex off the top outline");
                foreach (var t in top) Assert.Less(cut.Min(c => Dist(t, c)), 1e-9, "panel " + panel.Seed + ": top vertex missing from the cut");
            }

            var outside = FabricationRun.Run(DomeMesh(), Settings(0, PanelSide.Outside), 4).Layout;
            int wider = 0;
            foreach (var panel in outside.Panels)
            {
                var cut = outside.ToModel(outside.CutOutlines[panel.Seed], false);
                var top = FabricationLayout.PlacedOutline(panel, outside.SheetOrigin(panel.Sheet)).Take(panel.Flat.Length).ToArray();
                foreach (var t in top) Assert.IsTrue(InsideOrOn(t, cut, 1e-9), "panel " + panel.Seed + ": top vertex outside the cut outline");
                double cutArea = Math.Abs(ShoelaceArea(cut)), topArea = Math.Abs(ShoelaceArea(top));
                Assert.GreaterOrEqual(cutArea, topArea - 1e-12, "panel " + panel.Seed);
                if (cutArea > topArea * (1 + 1e-6)) wider++;
                // The cut outline keeps the gap from its sheet's edges too.
                var r = outside.SheetRectangle(panel.Sheet, outside.SheetOrigin(panel.Sheet));
                foreach (var c in cut)
                {
                    Assert.GreaterOrEqual(c.X, r[0].X + 0.02 - 1e-9);
                    Assert.LessOrEqual(c.X, r[1].X - 0.02 + 1e-9);
                    Assert.GreaterOrEqual(c.Y, r[0].Y + 0.02 - 1e-9);
                    Assert.LessOrEqual(c.Y, r[2].Y - 0.02 + 1e-9);
                }
            }
            Assert.Greater(wider, 0, "on the convex side of a dome panels widen towards the bottom");
            Assert.AreEqual(outside.CutOutlines[0].Length + 1, outside.ToModel(outside.CutOutlines[0], true).Length);
        }

        [Test]
        public void DxfPolylinesAreReadByLayerAndMalformedOnesRefused()
        {
            var dxf = "0\nSECTION\n2\nENTITIES\n0\nPOLYLINE\n8\nCUT\n66\n1\n70\n1\n10\n0.0\n20\n0.0\n30\n0.0\n"
                + "0\nVERTEX\n8\nCUT\n10\n1.5\n20\n2\n30\n0.0\n0\nVERTEX\n8\nCUT\n10\n3\n20\n-4e-1\n30\n0.0\n0\nSEQEND\n8\nCUT\n"
                + "0\nPOLYLINE\n8\nSLOT\n66\n1\n70\n0\n0\nVERTEX\n8\nSLOT\n10\n7\n20\n8\n0\nSEQEND\n0\nENDSEC\n0\nEOF\n";
            var read = DxfPolyline.Parse(dxf.Replace("\n", "\r\n"));
            Assert.AreEqual(2, read.Count);
            Assert.AreEqual("CUT", read[0].Layer);
            Assert.IsTrue(read[0].Closed);
            Assert.AreEqual(2, read[0].Points.Length, "the POLYLINE's own 10/20 codes are not a vertex");
            Assert.AreEqual(1.5, read[0].Points[0].X);
            Assert.AreEqual(-0.4, read[0].Points[1].Y);
            Assert.AreEqual("SLOT", read[1].Layer);
            Assert.IsFalse(read[1].Closed);
            Assert.Throws<FormatException>(() => DxfPolyline.Parse("0\nPOLYLINE\n8\nCUT\n0\nVERTEX\n10\n1\n20\n2\n"), "no SEQEND");

            // LWPOLYLINE (what the library writes): the vertices are the 10/20 pairs, the entity ends at the next 0.
            var lw = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n5\n2A\n100\nAcDbEntity\n8\nENGRAVE\n100\nAcDbPolyline\n90\n3\n70\n0\n"
                + "10\n1\n20\n2\n10\n3.5\n20\n-4\n10\n5\n20\n6\n0\nLWPOLYLINE\n8\nCUT\n90\n1\n70\n1\n10\n9\n20\n8\n0\nENDSEC\n0\nEOF\n";
            var lwRead = DxfPolyline.Parse(lw);
            Assert.AreEqual(2, lwRead.Count);
            Assert.AreEqual("ENGRAVE", lwRead[0].Layer);
            Assert.IsFalse(lwRead[0].Closed);
            Assert.AreEqual(3, lwRead[0].Points.Length);
            Assert.AreEqual(3.5, lwRead[0].Points[1].X);
            Assert.AreEqual(-4.0, lwRead[0].Points[1].Y);
            Assert.AreEqual("CUT", lwRead[1].Layer);
            Assert.IsTrue(lwRead[1].Closed);
            Assert.Throws<FormatException>(() => DxfPolyline.Parse("0\nLWPOLYLINE\n8\nCUT\n10\n1\n10\n2\n20\n3\n0\nEOF\n"), "x without y");
        }

        [Test]
        public void SolidsAreClosedAndHoldThePrismatoidVolume()
        {
            var layout = FabricationRun.Run(DomeMesh(), Settings(), 4).Layout;
            foreach (var panel in layout.Panels)
            {
                var solid = layout.PanelSolids[panel.Seed];
                var t = solid.Triangles();
                // Closed and consistently oriented: every directed edge has its reverse, once.
                var edges = new Dictionary<long, int>();
                for (int k = 0; k < t.Length; k += 3)
                    for (int e = 0; e < 3; e++)
                    {
                        long key = (long)t[k + e] * 1000000 + t[k + (e + 1) % 3];
                        int c; edges.TryGetValue(key, out c); edges[key] = c + 1;
                    }
                foreach (var e in edges)
                {
                    Assert.AreEqual(1, e.Value, "panel " + panel.Seed + ": directed edge used twice");
                    long reverse = (e.Key % 1000000) * 1000000 + e.Key / 1000000;
                    Assert.IsTrue(edges.ContainsKey(reverse), "panel " + panel.Seed + ": open edge");
                }
                // Volume of the triangulated OBJ solid = T (A_top + 4 A_mid + A_bottom) / 6 from panels.json.
                var mid = panel.Top.Select((v, k) => 0.5 * (v + panel.Bottom[k])).ToArray();
                double prismatoid = layout.Thickness * (Area(panel.Top) + 4 * Area(mid) + Area(panel.Bottom)) / 6;
                Assert.AreEqual(prismatoid, solid.Volume(), 1e-9 * prismatoid + 1e-15, "panel " + panel.Seed);
                Assert.AreEqual(panel.Volume, solid.Volume(), 1e-9 * prismatoid + 1e-15, "panel " + panel.Seed + ": the library's volume");
            }
            // With slots the top and bottom faces are notched (not convex): the triangulated
            // volume is still the library's, and a notch takes away L D T (docs/fabrication.md).
            var notched = FabricationRun.Run(DomeMesh(), Settings(2), 4).Layout;
            int checkedNotches = 0;
            foreach (var panel in notched.Panels)
            {
                var whole = layout.PanelSolids[panel.Seed].Volume();
                var solid = notched.PanelSolids[panel.Seed];
                Assert.AreEqual(panel.Volume, solid.Volume(), 1e-9 * whole, "notched panel " + panel.Seed);
                double removed = panel.Slots.Sum(q => Dist(q[0], q[1]) * Dist(q[1], q[2]) * notched.Thickness);
                Assert.AreEqual(whole - removed, solid.Volume(), 1e-9 * whole, "notched panel " + panel.Seed + ": whole minus L D T per notch");
                checkedNotches += panel.Slots.Length;
            }
            Assert.Greater(checkedNotches, 0);
        }

        [Test]
        public void NotchedFacesAreTriangulatedWithoutOverlap()
        {
            // An L-shaped (non-convex) face tilted in space: the triangles cover its shoelace area
            // exactly and all turn the polygon's way (a fan from the reflex corner would not).
            var flat = new[] { new Point2(0, 0), new Point2(3, 0), new Point2(3, 1), new Point2(1, 1), new Point2(1, 3), new Point2(0, 3) };
            var vertices = flat.Select(p => new Vec3(p.X, 0.6 * p.Y, 0.8 * p.Y)).ToArray();
            var normal = Vec3.Cross(vertices[1] - vertices[0], vertices[5] - vertices[0]);
            for (int start = 0; start < 6; start++)
            {
                // Every starting vertex: the reflex corner (3) comes first in one of them.
                var loop = Enumerable.Range(0, 6).Select(k => (start + k) % 6).ToArray();
                var t = FabricationLayout.Triangulate(vertices, loop);
                Assert.AreEqual(3 * (loop.Length - 2), t.Length);
                double sum = 0;
                for (int k = 0; k < t.Length; k += 3)
                {
                    var cross = Vec3.Cross(vertices[t[k + 1]] - vertices[t[k]], vertices[t[k + 2]] - vertices[t[k]]);
                    Assert.Greater(Vec3.Dot(cross, normal), 0, "start " + start + ": triangle " + k / 3 + " turns the wrong way");
                    sum += 0.5 * Math.Sqrt(Vec3.Dot(cross, cross));
                }
                Assert.AreEqual(5.0, sum, 1e-12, "L of 3 x 1 + 1 x 2 (the tilt keeps lengths: (0.6, 0.8) is a unit vector)");
            }
        }

        [Test]
        public void DefaultsFollowTheModelUnitsAndFabricate()
        {
            var mesh = DomeMesh();
            var metres = FabricationSettings.Defaults(null, 4);
            Assert.AreEqual(0.04, metres.Thickness, 1e-15);
            Assert.AreEqual(2.5, metres.SheetWidth, 1e-15);
            var mm = FabricationSettings.Defaults(null, 2);
            Assert.AreEqual(40, mm.Thickness, 1e-12);
            Assert.AreEqual(1250, mm.SheetHeight, 1e-9);
            var inches = FabricationSettings.Defaults(null, 8);
            Assert.AreEqual(0.04 / 0.0254, inches.Thickness, 1e-12);
            Assert.AreEqual(0.02 / 0.9144, FabricationSettings.Defaults(null, 19).Gap, 1e-12, "19 is Rhino's yards");
            Assert.AreEqual(0.4, FabricationSettings.Defaults(null, 14).Thickness, 1e-12, "14 is Rhino's decimetres");
            Assert.AreEqual(0.04, FabricationSettings.Defaults(null, 0).Thickness, 1e-15, "unitless: as metres");
            // Units the library does not write (decimetres) still fabricate, unitless.
            var dm = FabricationRun.Run(mesh, Settings(), 14);
            Assert.IsTrue(dm.Success, string.Join("; ", dm.Errors));

            // This dome is 2 units wide: in millimetres 40 mm panels would be far too thick and
            // the sheets far too small for its parts; the defaults scale to the mesh and work.
            var edges = new List<double>();
            double largest = 0;
            for (int f = 0; f < mesh.FacetCount; f++)
            {
                var loop = mesh.Facet(f).Select(v => mesh.Vertices[v]).ToArray();
                for (int a = 0; a < loop.Length; a++)
                {
                    edges.Add(Dist(loop[a], loop[(a + 1) % loop.Length]));
                    for (int b = 0; b < loop.Length; b++) largest = Math.Max(largest, Dist(loop[a], loop[b]));
                }
            }
            edges.Sort();
            var scaled = FabricationSettings.Defaults(mesh, 2);
            Assert.AreEqual(0.1 * edges[edges.Count / 2], scaled.Thickness, 1e-12);
            Assert.GreaterOrEqual(scaled.SheetHeight, largest + 2 * scaled.Gap);
            Assert.IsEmpty(scaled.Validate());
            var result = FabricationRun.Run(mesh, scaled, 2);
            Assert.IsTrue(result.Success, string.Join("; ", result.Errors));
            // The model's units reach the DXF header: $INSUNITS 4 is millimetres.
            var lines = result.SheetsDxf.Split('\n').Select(l => l.Trim()).ToArray();
            int at = Array.IndexOf(lines, "$INSUNITS");
            Assert.GreaterOrEqual(at, 0);
            Assert.AreEqual("70", lines[at + 1]);
            Assert.AreEqual("4", lines[at + 2]);
        }

        [Test]
        public void BadInputIsReportedNotThrown()
        {
            var bad = Settings();
            bad.Thickness = -1;
            bad.Gap = double.NaN;
            bad.SlotsPerEdge = -2;
            bad.ToolDiameter = 0;
            var errors = bad.Validate();
            Assert.AreEqual(4, errors.Count, string.Join("; ", errors));
            StringAssert.Contains("thickness", errors[0]);
            Assert.IsTrue(errors.Any(e => e.Contains("gap")));
            Assert.IsTrue(errors.Any(e => e.Contains("slots")));
            Assert.IsTrue(errors.Any(e => e.Contains("tool diameter")));
            var wideGap = Settings();
            wideGap.Gap = 0.6;
            StringAssert.Contains("no room", wideGap.Validate().Single());

            var mesh = DomeMesh();
            var rejected = FabricationRun.Run(mesh, bad, 4);
            Assert.IsFalse(rejected.Success);
            Assert.AreEqual(errors, rejected.Errors);

            // The library's refusal (a thickness beyond the mesh's limit) comes back as a message.
            var thick = Settings();
            thick.Thickness = 5;
            var refused = FabricationRun.Run(mesh, thick, 4);
            Assert.IsFalse(refused.Success);
            Assert.IsNull(refused.Layout);
            StringAssert.Contains("thickness", refused.Errors.Single());
            StringAssert.StartsWith("fabrication failed: ", refused.Summary());

            // A part larger than the sheet.
            var small = Settings();
            small.SheetWidth = 0.1;
            small.SheetHeight = 0.1;
            small.Gap = 0.01;
            Assert.IsFalse(FabricationRun.Run(mesh, small, 4).Success);

            // A mesh that does not come from TPI Discretise.
            var plain = MeshData.FromLoops(mesh.Vertices, Enumerable.Range(0, mesh.FacetCount).Select(mesh.Facet).ToArray(), null);
            StringAssert.Contains("Result output of TPI Discretise", FabricationRun.Run(plain, Settings(), 4).Errors.Single());
        }

        [Test]
        public void ComponentInputsOverrideTheDefaults()
        {
            var mesh = DomeMesh();
            FabricationSettings used;
            var byDefault = FabricationRun.ForComponent(mesh, 2, null, 0, 0, null, null, null, null, out used);
            Assert.IsTrue(byDefault.Success, string.Join("; ", byDefault.Errors));
            Assert.AreEqual(FabricationSettings.Defaults(mesh, 2).Thickness, used.Thickness);
            Assert.AreEqual(used.Thickness, byDefault.Layout.Thickness, 1e-15, "the thickness used is the one in panels.json");

            var given = FabricationRun.ForComponent(mesh, 4, 0.02, 1, 1, 2.0, 1.2, 0.01, 0.004, out used);
            Assert.IsTrue(given.Success, string.Join("; ", given.Errors));
            Assert.AreEqual(0.02, given.Layout.Thickness, 1e-15);
            Assert.AreEqual(PanelSide.Outside, used.Side);
            Assert.IsTrue(given.Layout.Sheets.All(q => q.Width == 2.0 && q.Height == 1.2));
            Assert.Greater(given.Layout.CleatSolids.Count, 0);
            // Outside on a dome: the panels widen towards the bottom (negative bevels), inside they narrow.
            Assert.Less(given.Layout.Panels.SelectMany(p => p.BevelsDeg).Min(), 0);
            Assert.GreaterOrEqual(byDefault.Layout.Panels.SelectMany(p => p.BevelsDeg).Min(), -1e-9);

            var badSide = FabricationRun.ForComponent(mesh, 4, null, 2, 0, null, null, null, null, out used);
            StringAssert.Contains("0 (inside) or 1 (outside)", badSide.Errors.Single());
            var badSlots = FabricationRun.ForComponent(mesh, 4, null, 0, -1, null, null, null, null, out used);
            StringAssert.Contains("slots per edge", badSlots.Errors.Single());
        }

        [Test]
        public void FilesAreWrittenWithTheirContents()
        {
            var result = FabricationRun.Run(DomeMesh(4), Settings(1), 4);
            Assert.IsTrue(result.Success, string.Join("; ", result.Errors));
            var folder = System.IO.Path.Combine(System.IO.Path.GetTempPath(), "tpi-fab-" + Guid.NewGuid().ToString("N"), "out");
            try
            {
                var paths = FabricationRun.WriteFiles(result, folder);
                CollectionAssert.AreEquivalent(new[] { "panels.json", "panels.obj", "sheets.svg", "sheets.dxf", "bevels.csv", "cut.nc" },
                    paths.Select(System.IO.Path.GetFileName));
                Assert.AreEqual(result.GCode, System.IO.File.ReadAllText(System.IO.Path.Combine(folder, "cut.nc")));
                Assert.AreEqual(result.PanelsJson, System.IO.File.ReadAllText(System.IO.Path.Combine(folder, "panels.json")));
                // bevels.csv: one row per panel side, after its header.
                int sides = result.Layout.Panels.Sum(p => p.Neighbours.Length);
                Assert.AreEqual(sides + 1, result.BevelsCsv.Trim().Split('\n').Length);
                StringAssert.Contains("G1", result.GCode);
            }
            finally
            {
                var root = System.IO.Path.GetDirectoryName(folder);
                if (System.IO.Directory.Exists(root)) System.IO.Directory.Delete(root, true);
            }
        }

        [Test]
        public void JsonReaderReadsTheSubsetAndRefusesMalformedText()
        {
            var value = (Dictionary<string, object>)JsonText.Parse("{\"a\": [1, -2.5e1, true, null], \"b\\\"\": \"x\\n\\u0041\", \"c\": {}}");
            CollectionAssert.AreEqual(new object[] { 1.0, -25.0, true, null }, (List<object>)value["a"]);
            Assert.AreEqual("x\nA", value["b\""]);
            Assert.IsEmpty((Dictionary<string, object>)value["c"]);
            Assert.Throws<FormatException>(() => JsonText.Parse("{\"a\": 1,}"));
            Assert.Throws<FormatException>(() => JsonText.Parse("[1 2]"));
            Assert.Throws<FormatException>(() => JsonText.Parse("{\"a\": 1} x"));
            Assert.Throws<FormatException>(() => FabricationLayout.Parse("{\"thickness\": 1}", ""), "no panels");
            Assert.Throws<FormatException>(() => FabricationLayout.ParseObj("o a\nv 0 0 0\nf 1 2 3\n"), "a face outside its object");
        }
    }
}
