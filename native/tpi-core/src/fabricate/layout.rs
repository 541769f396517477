//! Flat parts on sheets: each part turned to its smallest bounding rectangle (an edge of its
//! convex hull along x, then lying wide), then a shelf fill: parts by decreasing height, left
//! to right along a shelf, a new shelf above the tallest part of the last one, a new sheet
//! when the shelf does not fit. Rectangles are kept `gap` apart and `gap` from the sheet's
//! edges, so the parts are too.

use glam::DVec2;
use serde::Serialize;

use super::{polygon_area, FabricationDiagnostic, FabricationError, Panel, Sheet};

/// Where a flat part lies: sheet point = R(angle) . flat + (x, y).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Placement {
    /// Sheet index.
    pub sheet: usize,
    /// Translation x.
    pub x: f64,
    /// Translation y.
    pub y: f64,
    /// Rotation, degrees counter-clockwise.
    pub angle_deg: f64,
}

impl Placement {
    /// Maps a flat point of the part onto its sheet.
    pub fn apply(&self, p: DVec2) -> DVec2 {
        let (s, c) = self.angle_deg.to_radians().sin_cos();
        DVec2::new(c * p.x - s * p.y + self.x, s * p.x + c * p.y + self.y)
    }
}

/// Convex hull (counter-clockwise, Andrew's monotone chain).
pub(super) fn convex_hull(points: &[DVec2]) -> Vec<DVec2> {
    let mut p: Vec<DVec2> = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<DVec2> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &DVec2>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2 {
                let a = hull[hull.len() - 2];
                let b = hull[hull.len() - 1];
                if (b - a).perp_dot(q - a) <= 0.0 {
                    hull.pop();
                } else {
                    break;
                }
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// Whether p lies inside the polygon (even-odd rule).
pub(super) fn point_in_polygon(p: DVec2, poly: &[DVec2]) -> bool {
    let n = poly.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Distance from p to the segment ab.
pub(super) fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let l2 = ab.length_squared();
    let t = if l2 > 0.0 {
        ((p - a).dot(ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length()
}

fn rotate(p: DVec2, angle: f64) -> DVec2 {
    let (s, c) = angle.sin_cos();
    DVec2::new(c * p.x - s * p.y, s * p.x + c * p.y)
}

fn bounds(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// Places every panel's cut outline on sheets; returns the sheets.
pub(super) fn nest(
    panels: &mut [Panel],
    sheet: [f64; 2],
    gap: f64,
    _diagnostics: &mut Vec<FabricationDiagnostic>,
) -> Result<Vec<Sheet>, FabricationError> {
    let [w_sheet, h_sheet] = sheet;
    // Orientation of each part: (angle in radians, width, height, min corner after rotation).
    let mut parts: Vec<(usize, f64, f64, f64, DVec2)> = Vec::with_capacity(panels.len());
    for (q, p) in panels.iter().enumerate() {
        let hull = convex_hull(&p.cut_outline);
        let mut best: Option<(f64, f64, f64, f64)> = None;
        for k in 0..hull.len() {
            let e = hull[(k + 1) % hull.len()] - hull[k];
            if e.length() == 0.0 {
                continue;
            }
            let angle = -e.y.atan2(e.x);
            let rotated: Vec<DVec2> = hull.iter().map(|&x| rotate(x, angle)).collect();
            let (lo, hi) = bounds(&rotated);
            let (w, h) = (hi.x - lo.x, hi.y - lo.y);
            if best.is_none_or(|(_, bw, bh, _)| w * h < bw * bh) {
                best = Some((angle, w, h, 0.0));
            }
        }
        let (mut angle, mut w, mut h, _) = best.unwrap_or((0.0, 0.0, 0.0, 0.0));
        if h > w {
            angle += std::f64::consts::FRAC_PI_2;
            std::mem::swap(&mut w, &mut h);
        }
        let fits = |w: f64, h: f64| w + 2.0 * gap <= w_sheet && h + 2.0 * gap <= h_sheet;
        if !fits(w, h) {
            if fits(h, w) {
                angle += std::f64::consts::FRAC_PI_2;
                std::mem::swap(&mut w, &mut h);
            } else {
                return Err(FabricationError::PartTooLarge {
                    panel: p.seed,
                    width: w + 2.0 * gap,
                    height: h + 2.0 * gap,
                    sheet_width: w_sheet,
                    sheet_height: h_sheet,
                });
            }
        }
        let rotated: Vec<DVec2> = p.cut_outline.iter().map(|&x| rotate(x, angle)).collect();
        let (lo, hi) = bounds(&rotated);
        parts.push((q, angle, hi.x - lo.x, hi.y - lo.y, lo));
    }
    parts.sort_by(|a, b| b.3.total_cmp(&a.3).then(a.0.cmp(&b.0)));
    let mut sheets: Vec<Sheet> = Vec::new();
    let mut used: Vec<f64> = Vec::new();
    let (mut x, mut y, mut shelf) = (gap, gap, 0.0f64);
    let mut current: Option<usize> = None;
    for (q, angle, w, h, lo) in parts {
        if current.is_some() && x + w + gap > w_sheet {
            y += shelf + gap;
            x = gap;
            shelf = 0.0;
        }
        if current.is_none() || y + h + gap > h_sheet {
            sheets.push(Sheet {
                size: sheet,
                utilisation: 0.0,
            });
            used.push(0.0);
            current = Some(sheets.len() - 1);
            x = gap;
            y = gap;
            shelf = 0.0;
        }
        let k = current.unwrap_or(0);
        panels[q].placement = Placement {
            sheet: k,
            x: x - lo.x,
            y: y - lo.y,
            angle_deg: angle.to_degrees(),
        };
        used[k] += polygon_area(&panels[q].cut_outline).abs();
        x += w + gap;
        shelf = shelf.max(h);
    }
    for (s, u) in sheets.iter_mut().zip(used) {
        s.utilisation = u / (w_sheet * h_sheet);
    }
    Ok(sheets)
}
