//! G-code for a 3-axis router: one program per sheet, in sequence (`M0` pauses between them),
//! XY in the sheet's coordinates and model units, Z = 0 on the top of the stock.
//!
//! Profile: the tool centre runs at exactly the tool radius r outside each part's cut outline
//! (counter-clockwise). Along an edge that is the edge moved by r along its outward normal
//! `n = (e.y, -e.x) / |e|`; at a convex corner p an arc of radius r about p (`G3`) joins the
//! two moved edges; at a reflex corner the moved edges meet at `p + r (n0 + n1) / (1 + n0 . n1)`,
//! which is at distance r from both edges. Step-downs of at most `step_down` to the full
//! depth `T + breakthrough`; on the last pass the two longest straight moves of each profile
//! keep a holding tab (the tool lifts to `-T + tab_height` over `tab_length`). Slots are
//! pocketed by straight passes along their edge, r apart, from r outside the part edge to
//! `D - r` inside. Rapid moves (`G0`) at `safe_height` above the stock.

use std::fmt::Write;

use glam::DVec2;

use super::{Fabrication, FabricationError, Units};

/// Most step-down passes per profile.
const MAX_PASSES: f64 = 10_000.0;

/// Parameters of the G-code.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ToolpathOptions {
    /// Tool diameter (model units). Default value: 0.006.
    pub tool_diameter: f64,
    /// Largest depth per pass; None: the tool diameter. Default value: None.
    pub step_down: Option<f64>,
    /// Rapid height above the stock; None: the thickness. Default value: None.
    pub safe_height: Option<f64>,
    /// Cut this far below the stock (into the spoil board). Default value: 0.
    pub breakthrough: f64,
    /// Feed rate (units per minute, as written). Default value: 6000.
    pub feed: f64,
    /// Plunge rate. Default value: 1500.
    pub plunge: f64,
    /// Holding tab length; 0 for none; None: four tool diameters. Default value: None.
    pub tab_length: Option<f64>,
    /// Holding tab height above the bottom of the cut; None: a third of the thickness.
    /// Default value: None.
    pub tab_height: Option<f64>,
    /// Units (G20 for inches, G21 otherwise). Default value: metres.
    pub units: Units,
}

impl Default for ToolpathOptions {
    fn default() -> Self {
        Self {
            tool_diameter: 0.006,
            step_down: None,
            safe_height: None,
            breakthrough: 0.0,
            feed: 6000.0,
            plunge: 1500.0,
            tab_length: None,
            tab_height: None,
            units: Units::Metres,
        }
    }
}

/// A coordinate in the G-code: 9 decimals, written straight into the text.
struct Fixed9(f64);

impl std::fmt::Display for Fixed9 {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:.9}", self.0)
    }
}

/// The feed word of a profile's first move (` F6000`), nothing on the others.
struct Feed(Option<f64>);

impl std::fmt::Display for Feed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            Some(feed) => write!(f, " F{feed}"),
            None => Ok(()),
        }
    }
}

/// One move of a profile: a line to a point, or a counter-clockwise arc to a point about a
/// centre.
#[derive(Clone, Copy, Debug)]
enum Move {
    Line(DVec2),
    Arc(DVec2, DVec2),
}

/// The profile at distance r outside a counter-clockwise polygon: start point and moves.
fn profile(poly: &[DVec2], r: f64) -> (DVec2, Vec<Move>) {
    let n = poly.len();
    let normal = |e: DVec2| DVec2::new(e.y, -e.x).normalize();
    let mut moves = Vec::with_capacity(2 * n + 1);
    let mut start = DVec2::ZERO;
    for q in 0..=n {
        let i = q % n;
        let p = poly[i];
        let e0 = p - poly[(i + n - 1) % n];
        let e1 = poly[(i + 1) % n] - p;
        let (n0, n1) = (normal(e0), normal(e1));
        if e0.perp_dot(e1) > 0.0 {
            // Convex: arc from p + r n0 to p + r n1.
            if q == 0 {
                start = p + n1 * r;
            } else {
                moves.push(Move::Line(p + n0 * r));
                moves.push(Move::Arc(p + n1 * r, p));
            }
        } else {
            let corner = p + (n0 + n1) * (r / (1.0 + n0.dot(n1)));
            if q == 0 {
                start = corner;
            } else {
                moves.push(Move::Line(corner));
            }
        }
    }
    (start, moves)
}

impl Fabrication {
    /// cut.nc: the G-code of every sheet (see the module doc of `toolpath`).
    pub fn gcode(&self, options: &ToolpathOptions) -> Result<String, FabricationError> {
        let invalid = |field: &'static str, value: f64, reason: &'static str| {
            FabricationError::InvalidOption {
                field,
                value,
                reason,
            }
        };
        let d = options.tool_diameter;
        if !(d.is_finite() && d > 0.0) {
            return Err(invalid("tool diameter", d, "must be a finite number > 0"));
        }
        if self.gap < d {
            return Err(invalid(
                "gap",
                self.gap,
                "must be at least the tool diameter, or the tool would cut into the next part",
            ));
        }
        let t = self.thickness;
        let r = d / 2.0;
        let step = options.step_down.unwrap_or(d);
        if !(step.is_finite() && step > 0.0) {
            return Err(invalid("step down", step, "must be a finite number > 0"));
        }
        let safe = options.safe_height.unwrap_or(t);
        if !(safe.is_finite() && safe > 0.0) {
            return Err(invalid("safe height", safe, "must be a finite number > 0"));
        }
        let depth = t + options.breakthrough.max(0.0);
        let passes = (depth / step).ceil().max(1.0);
        if passes > MAX_PASSES {
            return Err(invalid(
                "step down",
                step,
                "needs more than 10000 passes for the thickness; use a larger step",
            ));
        }
        let passes = passes as usize;
        let tab_length = options.tab_length.unwrap_or(4.0 * d).max(0.0);
        let tab_z = -depth + options.tab_height.unwrap_or(t / 3.0).clamp(0.0, depth);
        let mut out = String::new();
        let units = if options.units == Units::Inches {
            "G20"
        } else {
            "G21"
        };
        let f = Fixed9;
        for (k, sheet) in self.sheets.iter().enumerate() {
            let _ = writeln!(
                out,
                "(tpi fabricate: sheet {k} of {}, {} x {}, thickness {t}, tool diameter {d})",
                self.sheets.len(),
                sheet.size[0],
                sheet.size[1]
            );
            let _ = writeln!(out, "{units} G90 G17\nG0 Z{}", f(safe));
            for p in self.panels.iter().filter(|p| p.placement.sheet == k) {
                let outline: Vec<DVec2> = p
                    .cut_outline
                    .iter()
                    .map(|&q| p.placement.apply(q))
                    .collect();
                // Slots first, while the part is still held by the whole sheet.
                for s in &p.slots {
                    let c: Vec<DVec2> = s
                        .flat
                        .iter()
                        .map(|&q| p.placement.apply(DVec2::from_array(q)))
                        .collect();
                    let along = (c[3] - c[0]).normalize_or_zero();
                    let inward = (c[1] - c[0]).normalize_or_zero();
                    let (len, dep) = ((c[3] - c[0]).length(), (c[1] - c[0]).length());
                    if len < 2.0 * r || dep < r {
                        return Err(invalid(
                            "slot size",
                            len.min(dep),
                            "a slot must be at least one tool diameter long and one tool radius deep",
                        ));
                    }
                    let _ = writeln!(out, "(part {} slot)", p.seed);
                    let lanes = ((dep) / r).ceil().max(1.0) as usize;
                    for pass in 1..=passes {
                        let z = -(depth * pass as f64 / passes as f64);
                        for lane in 0..=lanes {
                            let off = -r + dep * lane as f64 / lanes as f64;
                            let off = off.min(dep - r);
                            let a = c[0] + inward * off + along * r;
                            let b = c[0] + inward * off + along * (len - r);
                            let (a, b) = if lane % 2 == 0 { (a, b) } else { (b, a) };
                            if lane == 0 {
                                let _ = writeln!(out, "G0 X{} Y{}", f(a.x), f(a.y));
                                let _ = writeln!(out, "G1 Z{} F{}", f(z), options.plunge);
                            } else {
                                let _ =
                                    writeln!(out, "G1 X{} Y{} F{}", f(a.x), f(a.y), options.feed);
                            }
                            let _ = writeln!(out, "G1 X{} Y{}", f(b.x), f(b.y));
                        }
                        let _ = writeln!(out, "G0 Z{}", f(safe));
                    }
                }
                let (start, moves) = profile(&outline, r);
                // Tabs on the two longest straight moves.
                let mut lengths: Vec<(f64, usize)> = Vec::new();
                let mut at = start;
                for (q, m) in moves.iter().enumerate() {
                    let to = match *m {
                        Move::Line(p) | Move::Arc(p, _) => p,
                    };
                    if let Move::Line(p) = *m {
                        lengths.push(((p - at).length(), q));
                    }
                    at = to;
                }
                lengths.sort_by(|a, b| b.0.total_cmp(&a.0));
                let tabbed: Vec<usize> = lengths
                    .iter()
                    .take(2)
                    .filter(|(l, _)| tab_length > 0.0 && *l > 3.0 * tab_length)
                    .map(|&(_, q)| q)
                    .collect();
                let _ = writeln!(out, "(part {} profile)", p.seed);
                for pass in 1..=passes {
                    let z = -(depth * pass as f64 / passes as f64);
                    let last = pass == passes;
                    let _ = writeln!(out, "G0 X{} Y{}", f(start.x), f(start.y));
                    let _ = writeln!(out, "G1 Z{} F{}", f(z), options.plunge);
                    let mut at = start;
                    let mut first = true;
                    for (q, m) in moves.iter().enumerate() {
                        let feed = Feed(first.then_some(options.feed));
                        first = false;
                        match *m {
                            Move::Line(to) => {
                                if last && tabbed.contains(&q) && tab_z > z {
                                    let dir = (to - at).normalize();
                                    let mid = (at + to) / 2.0;
                                    let (a, b) = (
                                        mid - dir * (tab_length / 2.0),
                                        mid + dir * (tab_length / 2.0),
                                    );
                                    let _ = writeln!(out, "G1 X{} Y{}{feed}", f(a.x), f(a.y));
                                    let _ = writeln!(out, "G1 Z{}", f(tab_z));
                                    let _ = writeln!(out, "G1 X{} Y{}", f(b.x), f(b.y));
                                    let _ = writeln!(out, "G1 Z{}", f(z));
                                    let _ = writeln!(out, "G1 X{} Y{}", f(to.x), f(to.y));
                                } else {
                                    let _ = writeln!(out, "G1 X{} Y{}{feed}", f(to.x), f(to.y));
                                }
                                at = to;
                            }
                            Move::Arc(to, centre) => {
                                let ij = centre - at;
                                let _ = writeln!(
                                    out,
                                    "G3 X{} Y{} I{} J{}{feed}",
                                    f(to.x),
                                    f(to.y),
                                    f(ij.x),
                                    f(ij.y)
                                );
                                at = to;
                            }
                        }
                    }
                    let _ = writeln!(out, "G0 Z{}", f(safe));
                }
            }
            if k + 1 < self.sheets.len() {
                let _ = writeln!(out, "M0 (next sheet)");
            }
        }
        out.push_str("M30\n");
        Ok(out)
    }
}
