//! The files: panels.json, panels.obj, bevels.csv, sheets.svg and sheets.dxf (ASCII DXF R2000:
//! header and tables by the `dxf` crate, entities streamed in its format).

use std::fmt::Write;

use glam::DVec2;
use serde::Serialize;

use super::{
    Fabrication, FabricationDiagnostic, FabricationError, Panel, Placement, Polyhedron, Sheet,
    Side, Slot,
};

pub use crate::units::Units;

#[derive(Serialize)]
struct PanelView<'a> {
    seed: u32,
    top: Vec<[f64; 3]>,
    bottom: Vec<[f64; 3]>,
    sides: &'a [Side],
    flat: Vec<[f64; 2]>,
    placement: &'a Placement,
    slots: &'a [Slot],
    volume: f64,
}

#[derive(Serialize)]
struct CleatView {
    panels: [u32; 2],
    t: f64,
    vertices: Vec<[f64; 3]>,
    faces: Vec<Vec<u32>>,
}

#[derive(Serialize)]
struct Document<'a> {
    units: Option<Units>,
    thickness: f64,
    panels: Vec<PanelView<'a>>,
    cleats: Vec<CleatView>,
    sheets: &'a [Sheet],
    diagnostics: &'a [FabricationDiagnostic],
}

impl Fabrication {
    /// panels.json (the contract in docs/fabrication.md).
    pub fn to_json(&self) -> String {
        let doc = Document {
            units: self.units,
            thickness: self.thickness,
            panels: self
                .panels
                .iter()
                .map(|p| PanelView {
                    seed: p.seed,
                    top: p.top.iter().map(|v| v.to_array()).collect(),
                    bottom: p.bottom.iter().map(|v| v.to_array()).collect(),
                    sides: &p.sides,
                    flat: p.flat.iter().map(|v| v.to_array()).collect(),
                    placement: &p.placement,
                    slots: &p.slots,
                    volume: p.solid.volume(),
                })
                .collect(),
            cleats: self
                .cleats
                .iter()
                .map(|c| CleatView {
                    panels: c.panels,
                    t: c.t,
                    vertices: c.solid.vertices.iter().map(|v| v.to_array()).collect(),
                    faces: c.solid.faces.clone(),
                })
                .collect(),
            sheets: &self.sheets,
            diagnostics: &self.diagnostics,
        };
        serde_json::to_string(&doc).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }

    /// panels.obj: one closed polyhedron per panel (`o panel_SEED`) and per cleat
    /// (`o cleat_A_B_Q`), faces outward.
    pub fn to_obj(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "# tpi fabricate: {} panels of thickness {}, {} cleats",
            self.panels.len(),
            self.thickness,
            self.cleats.len()
        );
        let _ = writeln!(out, "# units: {}", crate::units::units_label(self.units));
        let mut base = 1usize;
        let mut put = |out: &mut String, name: &str, s: &Polyhedron| {
            let _ = writeln!(out, "o {name}\ng {name}");
            for v in &s.vertices {
                let _ = writeln!(out, "v {} {} {}", v.x, v.y, v.z);
            }
            for f in &s.faces {
                out.push('f');
                for &q in f {
                    let _ = write!(out, " {}", base + q as usize);
                }
                out.push('\n');
            }
            base += s.vertices.len();
        };
        for p in &self.panels {
            put(&mut out, &format!("panel_{}", p.seed), &p.solid);
        }
        for (q, c) in self.cleats.iter().enumerate() {
            put(
                &mut out,
                &format!("cleat_{}_{}_{q}", c.panels[0], c.panels[1]),
                &c.solid,
            );
        }
        out
    }

    /// bevels.csv: one row per panel side.
    pub fn bevels_csv(&self) -> String {
        let mut out = String::from("panel,side,neighbour,length,dihedral_deg,bevel_deg\n");
        for p in &self.panels {
            for (k, s) in p.sides.iter().enumerate() {
                let nb = s.neighbour.map(|j| j.to_string()).unwrap_or_default();
                let dihedral = s.dihedral_deg.map(|d| d.to_string()).unwrap_or_default();
                let _ = writeln!(
                    out,
                    "{},{k},{nb},{},{dihedral},{}",
                    p.seed, s.length, s.bevel_deg
                );
            }
        }
        out
    }

    /// Horizontal offset of sheet k in the combined SVG / DXF drawing (sheets side by side).
    pub fn sheet_offset(&self, k: usize) -> f64 {
        self.sheets[..k]
            .iter()
            .map(|s| s.size[0] * 1.1)
            .sum::<f64>()
    }

    /// The parts of sheet k, each as (panel, placed cut outline, placed slot outlines).
    fn placed(&self, p: &Panel) -> (Vec<DVec2>, Vec<Vec<DVec2>>, DVec2) {
        let pl = p.placement;
        let dx = DVec2::new(self.sheet_offset(pl.sheet), 0.0);
        let outline = p.cut_outline.iter().map(|&q| pl.apply(q) + dx).collect();
        let slots = p
            .slots
            .iter()
            .map(|s| {
                s.flat
                    .iter()
                    .map(|&q| pl.apply(DVec2::from_array(q)) + dx)
                    .collect()
            })
            .collect();
        let centre = p.flat.iter().copied().sum::<DVec2>() / p.flat.len() as f64;
        (outline, slots, pl.apply(centre) + dx)
    }

    /// A part's bottom outline (seen through the part along its normal) on its sheet.
    fn placed_bottom(&self, p: &Panel) -> Vec<DVec2> {
        let pl = p.placement;
        let dx = DVec2::new(self.sheet_offset(pl.sheet), 0.0);
        p.flat_bottom.iter().map(|&q| pl.apply(q) + dx).collect()
    }

    /// sheets.svg: the sheets side by side (model units, y up), cut outlines, bottom outlines
    /// (dashed), slots and labels.
    pub fn sheets_svg(&self) -> String {
        let total: f64 = self.sheet_offset(self.sheets.len());
        let height = self.sheets.iter().map(|s| s.size[1]).fold(0.0, f64::max);
        let stroke = height / 1000.0;
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 {} {} {}" width="{}mm" height="{}mm">"#,
            -height,
            total.max(f64::MIN_POSITIVE),
            height,
            (total / height * 200.0).round(),
            200
        );
        let _ = writeln!(
            out,
            r#"<g transform="scale(1,-1)" fill="none" stroke-width="{stroke}">"#
        );
        for (k, s) in self.sheets.iter().enumerate() {
            let _ = writeln!(
                out,
                r##"<rect x="{}" y="0" width="{}" height="{}" stroke="#888"/>"##,
                self.sheet_offset(k),
                s.size[0],
                s.size[1]
            );
        }
        let text_size = self.label_height();
        for p in &self.panels {
            let (outline, slots, _) = self.placed(p);
            let _ = writeln!(
                out,
                r##"<polygon stroke="#c00" points="{}"/>"##,
                points(&outline)
            );
            let _ = writeln!(
                out,
                r##"<polygon stroke="#999" stroke-dasharray="{} {}" points="{}"/>"##,
                stroke * 4.0,
                stroke * 4.0,
                points(&self.placed_bottom(p))
            );
            for s in &slots {
                let _ = writeln!(out, r##"<polyline stroke="#00c" points="{}"/>"##, points(s));
            }
            let mut d = String::new();
            for stroke in self.labels(p, text_size) {
                for (q, a) in stroke.iter().enumerate() {
                    let _ = write!(d, "{}{:.6},{:.6}", if q == 0 { 'M' } else { 'L' }, a.x, a.y);
                }
            }
            let _ = writeln!(out, r##"<path stroke="#080" d="{d}"/>"##);
        }
        out.push_str("</g>\n</svg>\n");
        out
    }

    /// A part's engraving on its sheet (sheet offset included): its seed at the centre, and
    /// each interior side's neighbour beside the side, inside the part, along the side.
    fn labels(&self, p: &Panel, h: f64) -> Vec<Vec<DVec2>> {
        let pl = p.placement;
        let dx = DVec2::new(self.sheet_offset(pl.sheet), 0.0);
        let centre = pl.apply(p.flat.iter().copied().sum::<DVec2>() / p.flat.len() as f64) + dx;
        let mut strokes = number_strokes(&p.seed.to_string(), centre, h, 0.0);
        let r = p.flat.len();
        for (k, s) in p.sides.iter().enumerate() {
            let Some(j) = s.neighbour else { continue };
            let (a, b) = (p.flat[k], p.flat[(k + 1) % r]);
            let label = j.to_string();
            if (b - a).length() < (label.len() as f64 + 1.0) * h * 0.6 {
                continue;
            }
            let inward = (b - a).perp().normalize();
            let at = pl.apply((a + b) / 2.0 + inward * h) + dx;
            let dir = pl.apply(b) - pl.apply(a);
            strokes.extend(number_strokes(&label, at, h * 0.6, dir.y.atan2(dir.x)));
        }
        strokes
    }

    fn label_height(&self) -> f64 {
        let mut sizes: Vec<f64> = self
            .panels
            .iter()
            .map(|p| p.top_area().abs().sqrt())
            .collect();
        sizes.sort_by(f64::total_cmp);
        sizes.get(sizes.len() / 2).copied().unwrap_or(1.0) / 6.0
    }

    /// sheets.dxf: ASCII DXF R2000 (`$ACADVER` AC1015, the first version with `$INSUNITS`),
    /// layers SHEET, CUT (part outlines), BOTTOM (the bottom outline seen through the part, for
    /// the bevels), SLOT (notches) and ENGRAVE (panel labels at the centre, and each side's
    /// neighbour id beside the side, as single strokes), every curve an LWPOLYLINE; sheets side
    /// by side, 10 % apart.
    ///
    /// The header and the tables are the `dxf` crate's (a drawing with the layers and no
    /// entities); the entities are streamed into the text here, code pair by code pair, as
    /// the crate writes an LWPOLYLINE (handles numbered on from the tables', `$HANDSEED` the
    /// next free one, coordinates with 12 decimals less trailing zeros): the same bytes as
    /// the crate's own `save` of the whole drawing, without building ~30 entities' worth of
    /// code pairs per part.
    ///
    /// Errors: [`FabricationError::Output`] if the crate refuses to write the drawing.
    pub fn sheets_dxf(&self, units: Units) -> Result<String, FabricationError> {
        let fail = |reason: String| FabricationError::Output {
            file: "sheets.dxf",
            reason,
        };
        let drawing = dxf_drawing(units);
        let first = drawing.header.next_available_handle.0;
        let mut bytes = Vec::new();
        drawing.save(&mut bytes).map_err(|e| fail(e.to_string()))?;
        let prelude = String::from_utf8(bytes).map_err(|e| fail(e.to_string()))?;
        let section = prelude
            .find(DXF_ENTITIES)
            .map(|at| at + DXF_ENTITIES.len())
            .ok_or_else(|| fail("the dxf crate wrote no ENTITIES section".into()))?;
        let seed = format!("$HANDSEED\r\n  5\r\n{first:X}\r\n");
        if !prelude[..section].contains(&seed) {
            return Err(fail("the dxf crate wrote no $HANDSEED".into()));
        }
        let mut entities = DxfEntities {
            out: String::with_capacity(300 * self.panels.len()),
            handle: first,
        };
        let offsets = self.sheet_offsets();
        for (k, s) in self.sheets.iter().enumerate() {
            let x0 = offsets[k];
            let rect = [
                DVec2::new(x0, 0.0),
                DVec2::new(x0 + s.size[0], 0.0),
                DVec2::new(x0 + s.size[0], s.size[1]),
                DVec2::new(x0, s.size[1]),
            ];
            entities.polyline("SHEET", &rect, true);
        }
        let h = self.label_height();
        for p in &self.panels {
            let (outline, slots, _) = self.placed(p);
            entities.polyline("CUT", &outline, true);
            entities.polyline("BOTTOM", &self.placed_bottom(p), true);
            for s in &slots {
                entities.polyline("SLOT", s, false);
            }
            for stroke in self.labels(p, h) {
                entities.polyline("ENGRAVE", &stroke, false);
            }
        }
        let head = prelude[..section].replacen(
            &seed,
            &format!("$HANDSEED\r\n  5\r\n{:X}\r\n", entities.handle),
            1,
        );
        let tail = &prelude[section..];
        let mut text = String::with_capacity(head.len() + entities.out.len() + tail.len());
        text.push_str(&head);
        text.push_str(&entities.out);
        text.push_str(tail);
        Ok(text)
    }

    /// The horizontal offset of every sheet (see [`Fabrication::sheet_offset`]).
    fn sheet_offsets(&self) -> Vec<f64> {
        (0..self.sheets.len())
            .map(|k| self.sheet_offset(k))
            .collect()
    }
}

/// What the `dxf` crate writes where the ENTITIES section begins.
const DXF_ENTITIES: &str = "  0\r\nSECTION\r\n  2\r\nENTITIES\r\n";

/// The drawing of sheets.dxf without entities: version R2000, `$INSUNITS`, the layers.
fn dxf_drawing(units: Units) -> dxf::Drawing {
    let mut drawing = dxf::Drawing::new();
    drawing.header.version = dxf::enums::AcadVersion::R2000;
    drawing.header.default_drawing_units = dxf_units(units);
    for (name, colour) in DXF_LAYERS {
        drawing.add_layer(dxf::tables::Layer {
            name: name.to_string(),
            color: dxf::Color::from_index(colour),
            ..Default::default()
        });
    }
    drawing
}

/// The ENTITIES section's text, written as the `dxf` crate writes an LWPOLYLINE.
struct DxfEntities {
    out: String,
    /// The next entity's handle.
    handle: u64,
}

impl DxfEntities {
    /// One LWPOLYLINE on `layer` (a name without control characters).
    fn polyline(&mut self, layer: &str, pts: &[DVec2], closed: bool) {
        let out = &mut self.out;
        let _ = write!(
            out,
            "  0\r\nLWPOLYLINE\r\n  5\r\n{:X}\r\n100\r\nAcDbEntity\r\n  8\r\n{layer}\r\n370\r\n     0\r\n100\r\nAcDbPolyline\r\n 90\r\n{: >9}\r\n 70\r\n{: >6}\r\n",
            self.handle,
            pts.len(),
            u8::from(closed)
        );
        self.handle += 1;
        for p in pts {
            out.push_str(" 10\r\n");
            push_dxf_number(out, p.x);
            out.push_str(" 20\r\n");
            push_dxf_number(out, p.y);
        }
    }
}

/// A coordinate as the `dxf` crate prints it: 12 decimals, trailing zeros dropped, at least
/// one decimal; then the line end.
fn push_dxf_number(out: &mut String, x: f64) {
    let start = out.len();
    let _ = write!(out, "{x:.12}");
    let kept = out[start..].trim_end_matches('0').len();
    out.truncate(start + kept);
    if out.ends_with('.') {
        out.push('0');
    }
    out.push_str("\r\n");
}

/// The DXF layers and their colours (AutoCAD colour index: 8 grey, 1 red, 9 light grey, 5 blue,
/// 3 green).
const DXF_LAYERS: [(&str, u8); 5] = [
    ("SHEET", 8),
    ("CUT", 1),
    ("BOTTOM", 9),
    ("SLOT", 5),
    ("ENGRAVE", 3),
];

/// The `$INSUNITS` value of our units in the `dxf` crate's terms (the same numbers as
/// [`Units::insunits`]).
fn dxf_units(units: Units) -> dxf::enums::Units {
    use dxf::enums::Units as D;
    match units {
        Units::Inches => D::Inches,
        Units::Feet => D::Feet,
        Units::Miles => D::Miles,
        Units::Millimetres => D::Millimeters,
        Units::Centimetres => D::Centimeters,
        Units::Metres => D::Meters,
        Units::Kilometres => D::Kilometers,
        Units::Yards => D::Yards,
        Units::Microns => D::Microns,
    }
}

/// Seven-segment digits as polylines in a cell of width 0.6 and height 1, each digit one or
/// two strokes (corners: top left, top right, middle right, bottom right, bottom left, middle
/// left).
const DIGIT_STROKES: [&[&[(f64, f64)]]; 10] = {
    const A: (f64, f64) = (0.0, 1.0);
    const B: (f64, f64) = (0.6, 1.0);
    const C: (f64, f64) = (0.6, 0.5);
    const D: (f64, f64) = (0.6, 0.0);
    const E: (f64, f64) = (0.0, 0.0);
    const F: (f64, f64) = (0.0, 0.5);
    [
        &[&[A, B, D, E, A]],
        &[&[B, D]],
        &[&[A, B, C, F, E, D]],
        &[&[A, B, D, E], &[F, C]],
        &[&[A, F, C], &[B, D]],
        &[&[B, A, F, C, D, E]],
        &[&[B, A, E, D, C, F]],
        &[&[A, B, D]],
        &[&[A, B, D, E, A], &[F, C]],
        &[&[C, F, A, B, D, E]],
    ]
};

/// A number as single strokes (seven-segment digits) a router can engrave: polylines, the
/// text of height `height` centred on `centre`, turned by `angle` radians. Characters other
/// than digits are left out.
pub(super) fn number_strokes(
    text: &str,
    centre: DVec2,
    height: f64,
    angle: f64,
) -> Vec<Vec<DVec2>> {
    let digits: Vec<usize> = text
        .chars()
        .filter_map(|c| c.to_digit(10).map(|d| d as usize))
        .collect();
    let advance = 0.9;
    let width = digits.len() as f64 * advance - 0.3;
    let (sin, cos) = angle.sin_cos();
    let place = |x: f64, y: f64| {
        let local = DVec2::new((x - width / 2.0) * height, (y - 0.5) * height);
        centre + DVec2::new(cos * local.x - sin * local.y, sin * local.x + cos * local.y)
    };
    let mut strokes = Vec::new();
    for (q, &d) in digits.iter().enumerate() {
        let x0 = q as f64 * advance;
        for stroke in DIGIT_STROKES[d] {
            strokes.push(stroke.iter().map(|&(x, y)| place(x0 + x, y)).collect());
        }
    }
    strokes
}

fn points(p: &[DVec2]) -> String {
    let mut s = String::with_capacity(p.len() * 24);
    for q in p {
        let _ = write!(s, "{},{} ", q.x, q.y);
    }
    s.pop();
    s
}
