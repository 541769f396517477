//! Flat parts on sheets: a bottom-left fill of the parts' convex hulls (see [`nest`]).

use std::collections::HashMap;

use glam::DVec2;
use rayon::prelude::*;
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
                // Not a clear left turn (rounding included): drop b.
                if (b - a).perp_dot(q - a) <= 1e-12 * (b - a).length() * (q - a).length() {
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

pub(super) fn rotate(p: DVec2, angle: f64) -> DVec2 {
    let (s, c) = angle.sin_cos();
    DVec2::new(c * p.x - s * p.y, s * p.x + c * p.y)
}

fn bounds(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    )
}

/// Whether two convex counter-clockwise polygons are at least `gap` apart: some edge normal
/// of either separates their projections by `gap` or more. (The distance of convex sets is the
/// largest such separation over all directions, so this never passes closer parts; it may
/// refuse a few that are far enough apart at a vertex-to-vertex contact.)
fn separated(a: &[DVec2], b: &[DVec2], gap: f64) -> bool {
    for (p, q) in [(a, b), (b, a)] {
        let n = p.len();
        let (lo, hi) = bounds(p);
        // An edge this short has no reliable direction: its normal proves nothing.
        let shortest = 1e-9 * (hi - lo).length();
        for k in 0..n {
            let e = p[(k + 1) % n] - p[k];
            let len = e.length();
            if len <= shortest {
                continue;
            }
            let out = DVec2::new(e.y, -e.x) / len;
            let edge = out.dot(p[k]);
            if q.iter().all(|x| out.dot(*x) - edge >= gap) {
                return true;
            }
        }
    }
    false
}

/// A part placed on a sheet: its hull in sheet coordinates and the hull's bounds.
struct Placed {
    hull: Vec<DVec2>,
    lo: DVec2,
    hi: DVec2,
}

struct OpenSheet {
    placed: Vec<Placed>,
    /// Candidate corners for the next part's bounds: next to and above the placed parts,
    /// less those inside a placed part's hull (see [`nest`]), lowest (then leftmost) first.
    corners: Vec<DVec2>,
    used: f64,
    /// Parts in a row that found no place on this sheet (from [`SHEET_PATIENCE`] on it is
    /// no longer tried).
    misses: usize,
    /// Placed parts by grid cell (each part in every cell its bounds meet): the feasibility
    /// test reads only the parts in the cells a candidate's bounds, widened by the gap, meet,
    /// which are all the parts its bounds can come within the gap of.
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl OpenSheet {
    fn new(gap: f64) -> OpenSheet {
        OpenSheet {
            placed: Vec::new(),
            corners: vec![DVec2::splat(gap)],
            used: 0.0,
            misses: 0,
            cells: HashMap::new(),
        }
    }

    fn cell_range(lo: DVec2, hi: DVec2, cell: f64) -> ((i64, i64), (i64, i64)) {
        let index = |x: f64| (x / cell).floor() as i64;
        ((index(lo.x), index(lo.y)), (index(hi.x), index(hi.y)))
    }

    fn insert(&mut self, part: Placed, cell: f64, gap: f64) {
        // A corner inside a placed hull can take no part whose hull reaches its bounds'
        // corner, which is nearly every part: it is dropped for good.
        self.corners.retain(|&c| !strictly_inside(c, &part.hull));
        let (lo, hi) = (part.lo, part.hi);
        for c in [
            DVec2::new(hi.x + gap, lo.y),
            DVec2::new(lo.x, hi.y + gap),
            DVec2::new(hi.x + gap, gap),
            DVec2::new(gap, hi.y + gap),
        ] {
            let free = self.all_near(c, c, 0.0, cell, |o| !strictly_inside(c, &o.hull));
            let lowest_first = |a: &DVec2| a.y.total_cmp(&c.y).then(a.x.total_cmp(&c.x));
            if let (true, Err(at)) = (free, self.corners.binary_search_by(lowest_first)) {
                self.corners.insert(at, c);
            }
        }
        let ((i0, j0), (i1, j1)) = Self::cell_range(part.lo, part.hi, cell);
        let index = self.placed.len();
        for i in i0..=i1 {
            for j in j0..=j1 {
                self.cells.entry((i, j)).or_default().push(index);
            }
        }
        self.placed.push(part);
    }

    /// Whether every placed part whose bounds could come within `gap` of [lo, hi] passes
    /// `clear` (each may be asked more than once).
    fn all_near(
        &self,
        lo: DVec2,
        hi: DVec2,
        gap: f64,
        cell: f64,
        clear: impl Fn(&Placed) -> bool,
    ) -> bool {
        let ((i0, j0), (i1, j1)) =
            Self::cell_range(lo - DVec2::splat(gap), hi + DVec2::splat(gap), cell);
        (i0..=i1).all(|i| {
            (j0..=j1).all(|j| {
                self.cells
                    .get(&(i, j))
                    .map_or(true, |parts| parts.iter().all(|&k| clear(&self.placed[k])))
            })
        })
    }
}

/// Whether p lies inside the convex counter-clockwise polygon, off its edges.
fn strictly_inside(p: DVec2, hull: &[DVec2]) -> bool {
    let n = hull.len();
    n >= 3
        && (0..n).all(|k| {
            let (a, b) = (hull[k], hull[(k + 1) % n]);
            (b - a).perp_dot(p - a) > 0.0
        })
}

/// How many of the most recently opened sheets a part may still go to.
const OPEN_SHEETS: usize = 3;

/// Parts in a row that may find no place on an open sheet before it is no longer tried: a
/// nearly full sheet otherwise costs every later part a search of all its corners. Measured
/// on 10,000 panels (`tpi bench --fabricate`): the nesting takes a third of the time, for 1 %
/// more sheets (NURBS dome 87 instead of 86).
const SHEET_PATIENCE: usize = 32;

/// Places every panel's cut outline on sheets; returns the sheets.
///
/// Bottom-left fill: parts by decreasing hull area; each tries four turns of its smallest
/// bounding rectangle (0, 90, 180, 270 degrees) on the last few open sheets, at candidate
/// corners next to and above the parts already there (less those inside a placed part's
/// hull, dropped for good), tried from the lowest up to the second that is feasible, then
/// drops as far down and left as it goes; the lowest (then leftmost) feasible place wins,
/// else a new sheet. A sheet on which [`SHEET_PATIENCE`] parts in a row found no place is
/// not tried again. Parts are kept apart by their convex hulls (a separating edge normal
/// with a gap of at least `gap`), and `gap` from the sheet's edges.
pub(super) fn nest(
    panels: &mut [Panel],
    sheet: [f64; 2],
    gap: f64,
    _diagnostics: &mut Vec<FabricationDiagnostic>,
) -> Result<Vec<Sheet>, FabricationError> {
    let [w_sheet, h_sheet] = sheet;
    // (panel, hull, base angle of the smallest bounding rectangle, hull area)
    let mut parts: Vec<(usize, Vec<DVec2>, f64, f64)> = Vec::with_capacity(panels.len());
    for (q, p) in panels.iter().enumerate() {
        let hull = convex_hull(&p.cut_outline);
        let mut best: Option<(f64, f64)> = None;
        for k in 0..hull.len() {
            let e = hull[(k + 1) % hull.len()] - hull[k];
            if e.length() == 0.0 {
                continue;
            }
            let angle = -e.y.atan2(e.x);
            let rotated: Vec<DVec2> = hull.iter().map(|&x| rotate(x, angle)).collect();
            let (lo, hi) = bounds(&rotated);
            let area = (hi.x - lo.x) * (hi.y - lo.y);
            if best.map_or(true, |(_, b)| area < b) {
                best = Some((angle, area));
            }
        }
        let angle = best.map(|b| b.0).unwrap_or(0.0);
        let area = polygon_area(&hull).abs();
        let fits = [0.0, std::f64::consts::FRAC_PI_2].iter().any(|&turn| {
            let (lo, hi) = bounds(
                &hull
                    .iter()
                    .map(|&x| rotate(x, angle + turn))
                    .collect::<Vec<_>>(),
            );
            hi.x - lo.x + 2.0 * gap <= w_sheet && hi.y - lo.y + 2.0 * gap <= h_sheet
        });
        if !fits {
            let (lo, hi) = bounds(&hull.iter().map(|&x| rotate(x, angle)).collect::<Vec<_>>());
            return Err(FabricationError::PartTooLarge {
                panel: p.seed,
                width: hi.x - lo.x + 2.0 * gap,
                height: hi.y - lo.y + 2.0 * gap,
                sheet_width: w_sheet,
                sheet_height: h_sheet,
            });
        }
        parts.push((q, hull, angle, area));
    }
    parts.sort_by(|a, b| b.3.total_cmp(&a.3).then(a.0.cmp(&b.0)));
    // Cells as large as a typical part (the median diagonal of the parts' bounds, which
    // bounds the part in any turn) plus the gap: a query then reads a few parts per cell. A
    // part is filed in every cell its bounds meet, so the queries find every part whatever
    // the cell size; one much larger than the cell is only filed more often, and no part
    // spans more than about 64 cells a side.
    let cell = {
        let mut diagonals: Vec<f64> = parts
            .iter()
            .map(|(_, hull, _, _)| {
                let (lo, hi) = bounds(hull);
                (hi - lo).length()
            })
            .collect();
        diagonals.sort_by(f64::total_cmp);
        let median = diagonals.get(diagonals.len() / 2).copied().unwrap_or(0.0);
        let largest = diagonals.last().copied().unwrap_or(0.0);
        median.max(largest / 64.0) + gap
    };
    let cell = if cell.is_finite() && cell > 0.0 {
        cell
    } else {
        1.0
    };
    let mut sheets: Vec<OpenSheet> = Vec::new();
    for (q, hull, base, area) in parts {
        let turns: Vec<(f64, Vec<DVec2>, DVec2, DVec2)> = (0..4)
            .map(|k| {
                let angle = base + f64::from(k) * std::f64::consts::FRAC_PI_2;
                let r: Vec<DVec2> = hull.iter().map(|&x| rotate(x, angle)).collect();
                let (lo, hi) = bounds(&r);
                (angle, r, lo, hi)
            })
            .collect();
        let first = sheets.len().saturating_sub(OPEN_SHEETS);
        let mut chosen: Option<(usize, f64, DVec2, f64)> = None; // sheet, angle, offset, score
        let mut missed = Vec::new();
        for (s, open) in sheets.iter().enumerate().skip(first) {
            if open.used + area > w_sheet * h_sheet || open.misses >= SHEET_PATIENCE {
                continue;
            }
            // The four turns are tried in parallel; each keeps its first best place, and the
            // turns are then compared in order, as one loop over them would.
            let per_turn: Vec<Option<(f64, DVec2, f64)>> = turns
                .par_iter()
                .map(|(angle, r, lo, hi)| {
                    let mut best: Option<(f64, DVec2, f64)> = None;
                    let size = *hi - *lo;
                    let feasible = |at: DVec2| -> bool {
                        if at.x < gap - 1e-12
                            || at.y < gap - 1e-12
                            || at.x + size.x > w_sheet - gap
                            || at.y + size.y > h_sheet - gap
                        {
                            return false;
                        }
                        let shift = at - *lo;
                        let (plo, phi) = (at, at + size);
                        // The hull moved to `at`, made once, and only if a part comes near.
                        let moved = std::cell::OnceCell::new();
                        open.all_near(plo, phi, gap, cell, |o| {
                            o.lo.x >= phi.x + gap
                                || o.hi.x + gap <= plo.x
                                || o.lo.y >= phi.y + gap
                                || o.hi.y + gap <= plo.y
                                || separated(
                                    moved.get_or_init(|| {
                                        r.iter().map(|&x| x + shift).collect::<Vec<_>>()
                                    }),
                                    &o.hull,
                                    gap,
                                )
                        })
                    };
                    // The two lowest feasible candidates (then leftmost) are dropped: the
                    // corners are kept in that order, so the search stops at the second.
                    let feasible_corners: Vec<DVec2> = open
                        .corners
                        .iter()
                        .copied()
                        .filter(|&c| feasible(c))
                        .take(2)
                        .collect();
                    for c in feasible_corners {
                        // Drop down, then left, then down again (bisection to 1e-4 of the gap).
                        let mut at = c;
                        for axis in [1usize, 0, 1] {
                            let mut lo_v = gap;
                            let mut hi_v = at[axis];
                            let mut probe = at;
                            probe[axis] = lo_v;
                            if feasible(probe) {
                                at = probe;
                                continue;
                            }
                            while hi_v - lo_v > 1e-4 * gap.max(1e-9) {
                                let mid = (lo_v + hi_v) / 2.0;
                                probe[axis] = mid;
                                if feasible(probe) {
                                    hi_v = mid;
                                } else {
                                    lo_v = mid;
                                }
                            }
                            at[axis] = hi_v;
                        }
                        let score = at.y * 4.0 * w_sheet + at.x + (at.y + size.y) * w_sheet;
                        if best.map_or(true, |(_, _, sc)| score < sc) {
                            best = Some((*angle, at - *lo, score));
                        }
                    }
                    best
                })
                .collect();
            for (angle, shift, score) in per_turn.into_iter().flatten() {
                if chosen.map_or(true, |(_, _, _, sc)| score < sc) {
                    chosen = Some((s, angle, shift, score));
                }
            }
            if chosen.is_some() {
                break;
            }
            missed.push(s);
        }
        for s in missed {
            sheets[s].misses += 1;
        }
        let (s, angle, shift) = match chosen {
            Some((s, angle, shift, _)) => (s, angle, shift),
            None => {
                sheets.push(OpenSheet::new(gap));
                let (angle, _, lo, hi) = &turns[0];
                let (angle, lo) =
                    if hi.x - lo.x + 2.0 * gap <= w_sheet && hi.y - lo.y + 2.0 * gap <= h_sheet {
                        (*angle, *lo)
                    } else {
                        (turns[1].0, turns[1].2)
                    };
                (sheets.len() - 1, angle, DVec2::splat(gap) - lo)
            }
        };
        let placed: Vec<DVec2> = hull.iter().map(|&x| rotate(x, angle) + shift).collect();
        let (lo, hi) = bounds(&placed);
        sheets[s].misses = 0;
        sheets[s].insert(
            Placed {
                hull: placed,
                lo,
                hi,
            },
            cell,
            gap,
        );
        sheets[s].used += polygon_area(&panels[q].cut_outline).abs();
        panels[q].placement = Placement {
            sheet: s,
            x: shift.x,
            y: shift.y,
            angle_deg: angle.to_degrees(),
        };
    }
    Ok(sheets
        .iter()
        .map(|o| Sheet {
            size: sheet,
            utilisation: o.used / (w_sheet * h_sheet),
        })
        .collect())
}
