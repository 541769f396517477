//! Pattern relaxation: Lloyd iterations of a centroidal tessellation measured on the surface,
//! so that panels come out even in size whatever the parametrisation.
//!
//! One iteration discretises the surface with the current points and moves each point to the
//! foot on the surface of its facet's centroid. The facet is the point's cell on the surface
//! (its tangent plane cut by its neighbours', ending on the boundary wall), so its centroid
//! is the centroid of the cell as the surface measures it, not as the parameters do:
//!
//! ```text
//! c_i = sum_k A_k g_k / sum_k A_k   over the triangles (m, x_k, x_k+1) of facet i's fan
//!       around its vertex mean m, A_k their areas, g_k their centroids;
//! (u_i, v_i) <- foot of c_i on the surface (Newton from the seed), clamped into the domain.
//! ```
//!
//! A point keeps its place when its facet is flagged invalid (its centroid would mean
//! nothing) or when the centroid is not finite. The points stay distinct: those that stay
//! are placed first, and a move that would land within [`DUPLICATE_UV_TOLERANCE`] of a
//! point already placed stops short of it ([`place_moves`]). Lloyd's iteration lowers the
//! tessellation energy sum_i integral |x - p_i|^2 at every step and converges to a centroidal
//! Voronoi tessellation, whose cells have nearly equal areas under a uniform density.

use glam::DVec3;

use crate::discretise::{discretise_with_progress, DiscretiseOptions};
use crate::error::TpiError;
use crate::progress::{NoProgress, Progress};
use crate::projection::foot;
use crate::quality::INVALID_FLAGS;
use crate::surface::Surface;
use crate::tolerance::DUPLICATE_UV_TOLERANCE;

/// Most relaxation iterations accepted in one call.
pub const MAX_RELAX_ITERATIONS: usize = 1000;

/// `pattern` (normalised, as [`crate::discretise()`]) after `iterations` Lloyd iterations on
/// `surface` (see the module doc); `options` are those of each discretisation (the quality
/// report is switched on, its flags decide which points move).
///
/// Errors: [`TpiError::InvalidParameter`] for more than [`MAX_RELAX_ITERATIONS`]; those of
/// [`crate::discretise()`] for the pattern and the surface.
pub fn relax(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    iterations: usize,
    options: &DiscretiseOptions,
) -> Result<Vec<[f64; 2]>, TpiError> {
    relax_with_progress(surface, pattern, iterations, options, &NoProgress)
}

/// [`relax`], reporting the stages of every discretisation it runs to `progress`
/// ([`crate::Progress`]), which can cancel it between them ([`TpiError::Cancelled`]); the
/// result is the same as without an observer.
pub fn relax_with_progress(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    iterations: usize,
    options: &DiscretiseOptions,
    progress: &dyn Progress,
) -> Result<Vec<[f64; 2]>, TpiError> {
    if iterations > MAX_RELAX_ITERATIONS {
        return Err(TpiError::InvalidParameter {
            field: "iterations".into(),
            value: iterations as f64,
            reason: format!("at most {MAX_RELAX_ITERATIONS} relaxation iterations"),
        });
    }
    relax_weighted(surface, pattern, iterations, options, None, progress)
}

/// A density of points over the normalised square: Lloyd's iteration weighted by it makes
/// cells of surface area proportional to density^(-1/2) (sizing.rs).
pub(crate) type Density<'a> = &'a (dyn Fn([f64; 2]) -> f64 + Sync);

/// [`relax`] with an optional `density` (None: uniform): the cell centroids are weighted by
/// it, and the first spreading follows area times density. Over-relaxed by
/// [`OVER_RELAXATION`] without a density, plain Lloyd steps with one. Each step's
/// discretisation reports to `progress`, which can cancel it.
pub(crate) fn relax_weighted(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    iterations: usize,
    options: &DiscretiseOptions,
    density: Option<Density<'_>>,
    progress: &dyn Progress,
) -> Result<Vec<[f64; 2]>, TpiError> {
    if iterations == 0 {
        return Ok(pattern.to_vec());
    }
    let mut points = spread_by_area(surface, pattern, density);
    for _ in 0..iterations {
        points = lloyd_step(surface, &points, options, density, progress)?.0;
    }
    Ok(points)
}

/// One Lloyd iteration (module doc), weighted by `density` where given: the points after it
/// and the discretisation of the points before it.
pub(crate) fn lloyd_step(
    surface: &dyn Surface,
    points: &[[f64; 2]],
    options: &DiscretiseOptions,
    density: Option<Density<'_>>,
    progress: &dyn Progress,
) -> Result<(Vec<[f64; 2]>, crate::Discretisation), TpiError> {
    let options = DiscretiseOptions {
        quality_report: true,
        ..*options
    };
    let domain = surface.domain();
    let [margin_s, margin_t] = seam_margins(surface);
    let over = if density.is_some() {
        1.0
    } else {
        OVER_RELAXATION
    };
    let d = discretise_with_progress(surface, points, &options, progress)?;
    let mut moved: Vec<Option<[f64; 2]>> = vec![None; points.len()];
    for i in 0..d.facet_count() {
        if d.facet_flags
            .get(i)
            .is_some_and(|&f| f & INVALID_FLAGS != 0)
        {
            continue;
        }
        let corners: Vec<DVec3> = d.facet(i).iter().map(|&v| d.vertices[v as usize]).collect();
        let seed = d.seeds[i].uv;
        let centroid = match density {
            None => polygon_centroid(&corners),
            Some(rho) => {
                let at_seed = surface.evaluate(seed[0], seed[1]);
                let to_st = |x: DVec3| {
                    // First order: the parameters of x's foot near the seed.
                    let (su, sv) = (at_seed.su, at_seed.sv);
                    let r = x - at_seed.point;
                    let (e, f, g) = (su.dot(su), su.dot(sv), sv.dot(sv));
                    let det = e * g - f * f;
                    let (a, b) = (su.dot(r), sv.dot(r));
                    let uv = [
                        seed[0] + (g * a - f * b) / det,
                        seed[1] + (e * b - f * a) / det,
                    ];
                    let [s, t] = domain.to_normalised(uv);
                    [s.clamp(0.0, 1.0), t.clamp(0.0, 1.0)]
                };
                weighted_centroid(&corners, |x| rho(to_st(x)))
            }
        };
        let Some(centroid) = centroid else {
            continue;
        };
        let target = foot(surface, &domain, centroid, seed);
        // Over-relaxed without a density: a step past the centroid, which Lloyd's iteration
        // otherwise approaches slowly where the density has far to travel.
        let uv = [
            seed[0] + over * (target[0] - seed[0]),
            seed[1] + over * (target[1] - seed[1]),
        ];
        let [s, t] = domain.to_normalised(uv);
        if s.is_finite() && t.is_finite() {
            moved[d.pattern_index(i)] = Some([
                s.clamp(margin_s, 1.0 - margin_s),
                t.clamp(margin_t, 1.0 - margin_t),
            ]);
        }
    }
    Ok((place_moves(points, &moved), d))
}

/// How far (normalised) a moved pattern point keeps from the sides of the domain in s and
/// in t: [`POLE_MARGIN`] in a direction with a pole at one of its ends (a point on a pole is
/// refused), [`SEAM_MARGIN`] in a closed direction (a point on the seam would be one with its
/// image), 0 otherwise.
pub(crate) fn seam_margins(surface: &dyn Surface) -> [f64; 2] {
    let layout = crate::closed::surface_layout(surface);
    let margin = |k: usize| {
        if layout.poles[2 * k] || layout.poles[2 * k + 1] {
            POLE_MARGIN
        } else if layout.closed[k] {
            SEAM_MARGIN
        } else {
            0.0
        }
    };
    [margin(0), margin(1)]
}

/// The points after one iteration's moves (`moved[i]`: where point i goes, None where it
/// stays), all distinct beyond [`DUPLICATE_UV_TOLERANCE`] as the distinct `points` were:
/// the points that stay are placed first (their places are distinct), then the moves in
/// pattern order. A move landing on a point already placed goes as far towards its target
/// as it can without (the whole way, else back home, else half, a quarter or three quarters
/// of the way), and where even its home is taken (two points clamped onto one corner or
/// side) it steps towards the middle of the domain by [`INWARD_STEP`] at a time.
fn place_moves(points: &[[f64; 2]], moved: &[Option<[f64; 2]>]) -> Vec<[f64; 2]> {
    let mut placed = PlacedPoints::default();
    for (&old, new) in points.iter().zip(moved) {
        if new.is_none() {
            placed.insert(old);
        }
    }
    let mut result = points.to_vec();
    for ((&old, new), out) in points.iter().zip(moved).zip(result.iter_mut()) {
        let Some(target) = *new else {
            continue;
        };
        let along = [1.0, 0.0, 0.5, 0.25, 0.75].into_iter().map(|f| {
            [
                old[0] + f * (target[0] - old[0]),
                old[1] + f * (target[1] - old[1]),
            ]
        });
        let inward = (1..=INWARD_TRIES).map(|k| {
            let step = k as f64 * INWARD_STEP;
            [
                target[0] + step * (0.5 - target[0]),
                target[1] + step * (0.5 - target[1]),
            ]
        });
        // Every try taken needs 21 placed points within micro-units of these places; then
        // the point stays home, and a clash there is named by the next discretisation.
        let chosen = along
            .chain(inward)
            .find(|&p| !placed.clashes(p))
            .unwrap_or(old);
        placed.insert(chosen);
        *out = chosen;
    }
    result
}

/// Points placed so far, hashed on a grid of cells one [`DUPLICATE_UV_TOLERANCE`] wide (a
/// clash lies in the 3 x 3 cells around a point).
#[derive(Default)]
struct PlacedPoints {
    points: Vec<[f64; 2]>,
    grid: std::collections::HashMap<(i64, i64), Vec<usize>>,
}

impl PlacedPoints {
    fn cell(p: [f64; 2]) -> (i64, i64) {
        (
            (p[0] / DUPLICATE_UV_TOLERANCE).floor() as i64,
            (p[1] / DUPLICATE_UV_TOLERANCE).floor() as i64,
        )
    }

    fn insert(&mut self, p: [f64; 2]) {
        self.grid
            .entry(Self::cell(p))
            .or_default()
            .push(self.points.len());
        self.points.push(p);
    }

    /// Whether p lies within the tolerance of a placed point (in both coordinates).
    fn clashes(&self, p: [f64; 2]) -> bool {
        let (ci, cj) = Self::cell(p);
        (ci - 1..=ci + 1).any(|a| {
            (cj - 1..=cj + 1).any(|b| {
                self.grid.get(&(a, b)).is_some_and(|others| {
                    others.iter().any(|&o| {
                        let q = self.points[o];
                        (q[0] - p[0]).abs() <= DUPLICATE_UV_TOLERANCE
                            && (q[1] - p[1]).abs() <= DUPLICATE_UV_TOLERANCE
                    })
                })
            })
        })
    }
}

/// Fraction of the way to the domain's middle by which a move whose target and home are
/// both taken (two points clamped onto one corner or side) is stepped inwards, per try.
const INWARD_STEP: f64 = 1e-6;

/// Inward steps tried before the point stays home.
const INWARD_TRIES: usize = 16;

/// Over-relaxation factor of each Lloyd step (1 is plain Lloyd; below 2 the iteration still
/// lowers the energy for small steps).
const OVER_RELAXATION: f64 = 1.9;

/// Normalised distance kept from a seam (where a seed would be doubled).
const SEAM_MARGIN: f64 = 1e-6;

/// Normalised distance kept from a pole (where a seed is refused). Larger than
/// [`SEAM_MARGIN`]: where the control net collapses in several rows (Rhino's Flow2 example)
/// the surface leaves its pole as the cube of the parameter, so at 1e-6 every point of the
/// ring lies within 1e-10 of the diagonal of the pole, and seeds clamped there are one.
const POLE_MARGIN: f64 = 1e-3;

/// Cells per side of the grid on which [`spread_by_area`] measures the surface's area.
const AREA_GRID: usize = 64;

/// The points moved so that their density follows the surface's area at every scale coarser
/// than their spacing, keeping their order: sorted by s, the point of rank r goes to the
/// area quantile (r + 1/2) / n of the marginal in s; then, in strips of about sqrt(n)
/// consecutive points, sorted by t, to the quantiles of the area in t over the strip. The area
/// density |Su x Sv| is measured on a grid of [`AREA_GRID`]^2 cells. Lloyd's iteration evens
/// fine scales quickly but coarse ones only over many steps; this does them at once.
fn spread_by_area(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    density: Option<Density<'_>>,
) -> Vec<[f64; 2]> {
    let domain = surface.domain();
    let g = AREA_GRID;
    let h = 1.0 / g as f64;
    // density[i][j]: area element at the centre of cell (i, j).
    let density: Vec<Vec<f64>> = (0..g)
        .map(|i| {
            (0..g)
                .map(|j| {
                    let st = [(i as f64 + 0.5) * h, (j as f64 + 0.5) * h];
                    let [u, v] = domain.from_normalised(st);
                    let d = surface.evaluate(u, v);
                    // Lloyd with density rho makes cell areas go as rho^(-1/2): the number
                    // of points per area as sqrt(rho).
                    let weight = density.map_or(1.0, |rho| rho(st).max(0.0).sqrt());
                    let a = d.su.cross(d.sv).length() * weight;
                    if a.is_finite() {
                        a
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect();
    let column: Vec<f64> = density.iter().map(|c| c.iter().sum()).collect();
    let total: f64 = column.iter().sum();
    let n = pattern.len();
    if !(total > 0.0 && total.is_finite()) || n < 4 {
        return pattern.to_vec();
    }
    // Inverse of the piecewise-linear CDF over g cells of width h with the given masses.
    let invert = |masses: &[f64], q: f64| -> f64 {
        let sum: f64 = masses.iter().sum();
        if !(sum > 0.0) {
            return q;
        }
        let mut target = q.clamp(0.0, 1.0) * sum;
        for (k, &m) in masses.iter().enumerate() {
            if target <= m || k + 1 == masses.len() {
                let f = if m > 0.0 {
                    (target / m).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                return (k as f64 + f) * h;
            }
            target -= m;
        }
        1.0
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| pattern[a][0].total_cmp(&pattern[b][0]).then(a.cmp(&b)));
    let mut out = pattern.to_vec();
    for (rank, &k) in order.iter().enumerate() {
        out[k][0] = invert(&column, (rank as f64 + 0.5) / n as f64);
    }
    let strips = ((n as f64).sqrt().round() as usize).max(1);
    for strip in 0..strips {
        let members = &order[strip * n / strips..(strip + 1) * n / strips];
        if members.is_empty() {
            continue;
        }
        let lo = ((out[members[0]][0] / h) as usize).min(g - 1);
        let hi = ((out[members[members.len() - 1]][0] / h) as usize).min(g - 1);
        let masses: Vec<f64> = (0..g)
            .map(|j| (lo..=hi).map(|i| density[i][j]).sum())
            .collect();
        let mut by_t = members.to_vec();
        by_t.sort_by(|&a, &b| pattern[a][1].total_cmp(&pattern[b][1]).then(a.cmp(&b)));
        for (rank, &k) in by_t.iter().enumerate() {
            out[k][1] = invert(&masses, (rank as f64 + 0.5) / by_t.len() as f64);
        }
    }
    out
}

/// The centroid of a planar polygon under a density (fan around the vertex mean, each
/// triangle weighted by its area times the density at its centroid); None when it has no
/// weight or is not finite.
fn weighted_centroid(corners: &[DVec3], density: impl Fn(DVec3) -> f64) -> Option<DVec3> {
    if corners.len() < 3 {
        return None;
    }
    let mean = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
    let mut weight = 0.0;
    let mut weighted = DVec3::ZERO;
    for k in 0..corners.len() {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let g = (mean + a + b) / 3.0;
        let w = 0.5 * (a - mean).cross(b - mean).length() * density(g).max(0.0);
        weight += w;
        weighted += w * g;
    }
    let c = weighted / weight;
    (weight > 0.0 && c.is_finite()).then_some(c)
}

/// The area-weighted centroid of a planar polygon (fan around the vertex mean); None when it
/// has no area or is not finite.
fn polygon_centroid(corners: &[DVec3]) -> Option<DVec3> {
    if corners.len() < 3 {
        return None;
    }
    let mean = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
    let mut area = 0.0;
    let mut weighted = DVec3::ZERO;
    for k in 0..corners.len() {
        let (a, b) = (corners[k], corners[(k + 1) % corners.len()]);
        let w = 0.5 * (a - mean).cross(b - mean).length();
        area += w;
        weighted += w * (mean + a + b) / 3.0;
    }
    let c = weighted / area;
    (area > 0.0 && c.is_finite()).then_some(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distinct(points: &[[f64; 2]]) -> bool {
        points.iter().enumerate().all(|(i, p)| {
            points[..i].iter().all(|q| {
                (p[0] - q[0]).abs() > DUPLICATE_UV_TOLERANCE
                    || (p[1] - q[1]).abs() > DUPLICATE_UV_TOLERANCE
            })
        })
    }

    #[test]
    fn free_moves_are_made() {
        let points = [[0.2, 0.2], [0.8, 0.8], [0.5, 0.1]];
        let moved = [Some([0.3, 0.25]), None, Some([0.6, 0.1])];
        assert_eq!(
            place_moves(&points, &moved),
            vec![[0.3, 0.25], [0.8, 0.8], [0.6, 0.1]]
        );
    }

    #[test]
    fn a_move_onto_a_point_that_stays_stops_short() {
        // Point 0 moves (first in pattern order) exactly onto point 1, which stays.
        let points = [[0.2, 0.2], [0.4, 0.4]];
        let moved = [Some([0.4, 0.4]), None];
        let placed = place_moves(&points, &moved);
        assert!(distinct(&placed), "{placed:?}");
        assert_eq!(
            placed[1],
            [0.4, 0.4],
            "the point that stays keeps its place"
        );
    }

    #[test]
    fn moves_clamped_onto_one_corner_stay_distinct() {
        // Point 2 sits on the corner and moves onto it; 0 and 1 are clamped onto it too, and
        // 1's home is where 0 was sent first.
        let points = [[0.001, 0.002], [0.0, 0.0], [0.003, 0.0]];
        let moved = [Some([0.0, 0.0]), Some([0.0, 0.0]), Some([0.0, 0.0])];
        let placed = place_moves(&points, &moved);
        assert!(distinct(&placed), "{placed:?}");
        assert!(placed
            .iter()
            .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
    }
}
