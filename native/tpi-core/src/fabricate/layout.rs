//! Flat parts on sheets: a bottom-left fill of the parts' convex hulls (see [`nest`]).

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

/// The separating axes of a convex counter-clockwise polygon: for each edge longer than
/// `1e-9` of its bounds' diagonal (a shorter edge has no reliable direction, its normal
/// proves nothing), the unit outward normal `out` and the edge line's offset `out . p[k]`.
fn axes(hull: &[DVec2], lo: DVec2, hi: DVec2) -> Vec<(DVec2, f64)> {
    let n = hull.len();
    let shortest = 1e-9 * (hi - lo).length();
    let mut axes = Vec::with_capacity(n);
    for k in 0..n {
        let e = hull[(k + 1) % n] - hull[k];
        let len = e.length();
        if len <= shortest {
            continue;
        }
        let out = DVec2::new(e.y, -e.x) / len;
        axes.push((out, out.dot(hull[k])));
    }
    axes
}

/// A part in one of its four turns, at the origin of its own coordinates: the turned hull,
/// its bounds and its separating axes. Moved by `shift`, an axis `(out, edge)` becomes
/// `(out, edge + out . shift)`: the axes are made once per turn, not once per test.
struct Turn {
    angle: f64,
    hull: Vec<DVec2>,
    lo: DVec2,
    hi: DVec2,
    axes: Vec<(DVec2, f64)>,
}

/// Whether the part `turn`, moved by `shift`, and the placed part `o` (both convex,
/// counter-clockwise) are at least `gap` apart: some edge normal of either separates their
/// projections by `gap` or more. (The distance of convex sets is the largest such separation
/// over all directions, so this never passes closer parts; it may refuse a few that are far
/// enough apart at a vertex-to-vertex contact.)
fn separated(turn: &Turn, shift: DVec2, o: &Placed, gap: f64) -> bool {
    o.axes
        .iter()
        .any(|&(out, edge)| turn.hull.iter().all(|&x| out.dot(x + shift) - edge >= gap))
        || turn.axes.iter().any(|&(out, edge)| {
            let edge = edge + out.dot(shift);
            o.hull.iter().all(|&x| out.dot(x) - edge >= gap)
        })
}

/// A part placed on a sheet: its hull in sheet coordinates, the hull's bounds, its
/// separating axes (see [`axes`]) and the grid cell of its lower bound.
struct Placed {
    hull: Vec<DVec2>,
    lo: DVec2,
    hi: DVec2,
    axes: Vec<(DVec2, f64)>,
    cell: (usize, usize),
}

/// A uniform grid over a sheet: the placed parts by cell, each part in every cell its bounds
/// meet. Indices are clamped to the grid, so a query reaching past the sheet reads the edge
/// cells (all parts lie on the sheet).
struct Grid {
    cell: f64,
    nx: usize,
    ny: usize,
    cells: Vec<Vec<u32>>,
}

/// Most grid cells along a side of a sheet: parts much smaller than the sheet get cells of
/// at least this fraction of it (which changes only how many parts a query reads).
const GRID_MAX_CELLS: f64 = 256.0;

impl Grid {
    fn new(sheet: [f64; 2], cell: f64) -> Grid {
        let cell = cell
            .max(sheet[0] / GRID_MAX_CELLS)
            .max(sheet[1] / GRID_MAX_CELLS);
        let count = |w: f64| ((w / cell).floor() as usize).saturating_add(1);
        let (nx, ny) = (count(sheet[0]), count(sheet[1]));
        Grid {
            cell,
            nx,
            ny,
            cells: Vec::new(),
        }
    }

    fn index(x: f64, cell: f64, n: usize) -> usize {
        // `as` saturates: negative values and NaN give 0.
        ((x / cell).floor().max(0.0) as usize).min(n - 1)
    }

    /// The cells [i0, i1] x [j0, j1] that [lo, hi] meets.
    fn range(&self, lo: DVec2, hi: DVec2) -> (usize, usize, usize, usize) {
        (
            Self::index(lo.x, self.cell, self.nx),
            Self::index(lo.y, self.cell, self.ny),
            Self::index(hi.x, self.cell, self.nx),
            Self::index(hi.y, self.cell, self.ny),
        )
    }

    fn insert(&mut self, lo: DVec2, hi: DVec2, part: u32) {
        if self.cells.is_empty() {
            self.cells = vec![Vec::new(); self.nx * self.ny];
        }
        let (i0, j0, i1, j1) = self.range(lo, hi);
        for j in j0..=j1 {
            for i in i0..=i1 {
                self.cells[j * self.nx + i].push(part);
            }
        }
    }
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
    /// Placed parts by grid cell: the feasibility test reads only the parts in the cells a
    /// candidate's bounds, widened by the gap, meet, which are all the parts its bounds can
    /// come within the gap of.
    grid: Grid,
}

impl OpenSheet {
    fn new(gap: f64, grid: Grid) -> OpenSheet {
        OpenSheet {
            placed: Vec::new(),
            corners: vec![DVec2::splat(gap)],
            used: 0.0,
            misses: 0,
            grid,
        }
    }

    /// Frees what only placing needs (the sheet takes no more parts).
    fn close(&mut self) {
        self.placed = Vec::new();
        self.corners = Vec::new();
        self.grid.cells = Vec::new();
    }

    fn insert(&mut self, hull: Vec<DVec2>, gap: f64) {
        let (lo, hi) = bounds(&hull);
        // A corner inside a placed hull can take no part whose hull reaches its bounds'
        // corner, which is nearly every part: it is dropped for good.
        self.corners
            .retain(|&c| !(inside_bounds(c, lo, hi) && strictly_inside(c, &hull)));
        for c in [
            DVec2::new(hi.x + gap, lo.y),
            DVec2::new(lo.x, hi.y + gap),
            DVec2::new(hi.x + gap, gap),
            DVec2::new(gap, hi.y + gap),
        ] {
            let inside = |o: &Placed| inside_bounds(c, o.lo, o.hi) && strictly_inside(c, &o.hull);
            let free = self.all_near(c, c, 0.0, |o| !inside(o));
            let lowest_first = |a: &DVec2| a.y.total_cmp(&c.y).then(a.x.total_cmp(&c.x));
            if let (true, Err(at)) = (free, self.corners.binary_search_by(lowest_first)) {
                self.corners.insert(at, c);
            }
        }
        let index = self.placed.len() as u32;
        self.grid.insert(lo, hi, index);
        let (i0, j0, _, _) = self.grid.range(lo, hi);
        let axes = axes(&hull, lo, hi);
        self.placed.push(Placed {
            hull,
            lo,
            hi,
            axes,
            cell: (i0, j0),
        });
    }

    /// Whether every placed part whose bounds could come within `gap` of [lo, hi] passes
    /// `clear` (each is asked once: in the first cell of the query that it is filed in).
    fn all_near(&self, lo: DVec2, hi: DVec2, gap: f64, clear: impl Fn(&Placed) -> bool) -> bool {
        if self.grid.cells.is_empty() {
            return true;
        }
        let (i0, j0, i1, j1) = self
            .grid
            .range(lo - DVec2::splat(gap), hi + DVec2::splat(gap));
        for j in j0..=j1 {
            for i in i0..=i1 {
                for &k in &self.grid.cells[j * self.grid.nx + i] {
                    let o = &self.placed[k as usize];
                    if (i, j) == (o.cell.0.max(i0), o.cell.1.max(j0)) && !clear(o) {
                        return false;
                    }
                }
            }
        }
        true
    }
}

fn inside_bounds(c: DVec2, lo: DVec2, hi: DVec2) -> bool {
    c.x > lo.x && c.x < hi.x && c.y > lo.y && c.y < hi.y
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
        let turns: Vec<Turn> = (0..4)
            .map(|k| {
                let angle = base + f64::from(k) * std::f64::consts::FRAC_PI_2;
                let r: Vec<DVec2> = hull.iter().map(|&x| rotate(x, angle)).collect();
                let (lo, hi) = bounds(&r);
                let axes = axes(&r, lo, hi);
                Turn {
                    angle,
                    hull: r,
                    lo,
                    hi,
                    axes,
                }
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
                .map(|turn| {
                    let mut best: Option<(f64, DVec2, f64)> = None;
                    let (lo, size) = (turn.lo, turn.hi - turn.lo);
                    let feasible = |at: DVec2| -> bool {
                        if at.x < gap - 1e-12
                            || at.y < gap - 1e-12
                            || at.x + size.x > w_sheet - gap
                            || at.y + size.y > h_sheet - gap
                        {
                            return false;
                        }
                        let shift = at - lo;
                        let (plo, phi) = (at, at + size);
                        open.all_near(plo, phi, gap, |o| {
                            o.lo.x >= phi.x + gap
                                || o.hi.x + gap <= plo.x
                                || o.lo.y >= phi.y + gap
                                || o.hi.y + gap <= plo.y
                                || separated(turn, shift, o, gap)
                        })
                    };
                    // The two lowest feasible candidates (then leftmost) are dropped: the
                    // corners are kept in that order, so the search stops at the second.
                    let mut feasible_corners =
                        open.corners.iter().copied().filter(|&c| feasible(c));
                    let feasible_corners = [feasible_corners.next(), feasible_corners.next()];
                    for c in feasible_corners.into_iter().flatten() {
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
                            best = Some((turn.angle, at - lo, score));
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
                sheets.push(OpenSheet::new(gap, Grid::new(sheet, cell)));
                // Only the last few sheets are tried: the one before them is closed.
                if let Some(closed) = sheets.len().checked_sub(OPEN_SHEETS + 1) {
                    sheets[closed].close();
                }
                let t0 = &turns[0];
                let (angle, lo) = if t0.hi.x - t0.lo.x + 2.0 * gap <= w_sheet
                    && t0.hi.y - t0.lo.y + 2.0 * gap <= h_sheet
                {
                    (t0.angle, t0.lo)
                } else {
                    (turns[1].angle, turns[1].lo)
                };
                (sheets.len() - 1, angle, DVec2::splat(gap) - lo)
            }
        };
        let placed: Vec<DVec2> = hull.iter().map(|&x| rotate(x, angle) + shift).collect();
        sheets[s].misses = 0;
        sheets[s].insert(placed, gap);
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
