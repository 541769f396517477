//! Developable surfaces whose rulings are parameter lines (cylinders, cones, extrusions): the
//! exact TPI structure is a sequence of strips, one per ruling, which a triangulation of
//! the seeds cannot give.
//!
//! **Why strips.** Along a ruling the normal is constant, so every seed on one ruling has the
//! same tangent plane T_k. Three planes of three different rulings meet at infinity (a
//! cylinder: all contain the axis direction) or at the apex (a cone), never near the surface.
//! The envelope of the planes is then made of strips: with the rulings in their order across
//! the surface (the order of the parameter s across them), the facets on ruling k lie in T_k
//! between the lines L(k-1, k) and L(k, k+1), L(k, k+1) = T_k ∩ T_(k+1), and the seeds on one
//! ruling share that strip by the perpendicular bisectors of their points, the Voronoi limit
//! of TPI in one plane ([`crate::planes::meeting_point`]).
//!
//! **The dual structure** is built directly, not by flips: the seeds of each ruling form a
//! chain sorted by the parameter t along it, closed at both ends by an *end ghost*, the chain's
//! end seed mirrored across the wall at the ruling's end (the plane through the end point
//! E = S(s, t_end) spanned by the normal n and the end curve's tangent dS/ds, normal
//! w = n x dS/ds):
//!
//! ```text
//! ghost = p - 2 ((p - E) . w) w,   in T_k (w is perpendicular to n),
//! ```
//!
//! so that the bisector of the end seed and its ghost is that wall plane. Two neighbouring
//! chains A and B are zipped along L(A, B): every consecutive pair (a_i, a_i+1) of A has its
//! bisector crossing L at a position alpha_i along L (direction n_A x n_B, oriented along the
//! rulings), likewise beta_j for B; merged in order of position, each crossing adds one
//! triangle, (a_i, b_j, a_i+1) or (a_i, b_j, b_j+1), whose vertex T_A ∩ T_B ∩ bisector is that
//! crossing. The positions compared are those of the two candidate triangles' vertices as the
//! facet stage computes them, so rounding cannot reverse a facet's vertices along L. Beyond
//! the first and the last ruling of an open surface a *side ghost* takes the wall of the side
//! ruling as its plane (the plane through the side ruling containing its
//! normal, which is constant along it), so the outermost facets end exactly on that wall. On a
//! surface closed across its rulings the last chain is zipped to the first: an annulus.
//!
//! Every triangle has two points of one chain and one of its neighbour, so every vertex is a
//! crossing of a bisector with L: finite and exact.
//!
//! **Trimmed.** On a trimmed surface the strips are those of the seeds inside the trim, with
//! the end and side walls moved a margin beyond the domain (`margin` of
//! [`strip_structure`]), so that every vertex on a wall lies clearly outside any trim; the
//! facet stage then clips each strip on the trim's wall ([`crate::facets`]). Strips are
//! defined by their seeds alone, so the clipped strips are the strips of the trimmed region,
//! as a Voronoi diagram clipped on a boundary is.

use glam::DVec3;

use crate::diffgeo::LocalGeometry;
use crate::planes::{coincident, meeting_point, Plane};
use crate::samples::bounding_diagonal;
use crate::surface::Surface;
use crate::tolerance::{LAYOUT_SAMPLES, RULING_TOLERANCE, STRIP_END_MIN_DEPTH};
use crate::triangulation::DualTriangulation;

/// The parameter lines of a developable surface that are its rulings.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Rulings {
    /// The parameter that varies along a ruling (0: u, 1: v); the other one, s, is constant
    /// on each ruling and orders them across the surface.
    pub(crate) along: usize,
}

impl Rulings {
    /// Domain parameters of the point at `s` across and `t` along the rulings.
    fn at(&self, s: f64, t: f64) -> [f64; 2] {
        if self.along == 1 {
            [s, t]
        } else {
            [t, s]
        }
    }
}

/// The rulings of `surface` if it is developable, not flat, with its rulings along one family
/// of parameter lines: sampled on a [`LAYOUT_SAMPLES`]^2 grid, along every sampled line of that
/// family the normal is constant and the points lie on one straight line (both to
/// [`RULING_TOLERANCE`]), and the normals differ across the lines.
pub(crate) fn find_rulings(surface: &dyn Surface) -> Option<Rulings> {
    let domain = surface.domain();
    let m = LAYOUT_SAMPLES;
    let f = |i: usize| i as f64 / (m - 1) as f64;
    let mut grid = Vec::with_capacity(m * m);
    for i in 0..m {
        for j in 0..m {
            let d = surface.evaluate(domain.u.lerp(f(i)), domain.v.lerp(f(j)));
            let g = LocalGeometry::from_derivatives(&d);
            if !(g.regular && g.point.is_finite() && g.normal.is_finite()) {
                return None;
            }
            grid.push((g.point, g.normal));
        }
    }
    let diagonal = bounding_diagonal(grid.iter().map(|g| g.0));
    if !(diagonal > 0.0 && diagonal.is_finite()) {
        return None;
    }
    // Sample (line a, position b) of the family whose lines vary along `along`.
    let sample = |along: usize, a: usize, b: usize| {
        if along == 1 {
            grid[a * m + b]
        } else {
            grid[b * m + a]
        }
    };
    let straight_lines = |along: usize| {
        (0..m).all(|a| {
            let (p0, n0) = sample(along, a, 0);
            let (p1, _) = sample(along, a, m - 1);
            let direction = (p1 - p0).normalize_or_zero();
            direction != DVec3::ZERO
                && (0..m).all(|b| {
                    let (p, n) = sample(along, a, b);
                    let off_line = (p - p0) - direction * direction.dot(p - p0);
                    n.cross(n0).length() <= RULING_TOLERANCE
                        && off_line.length() <= RULING_TOLERANCE * diagonal
                })
        })
    };
    let flat = grid
        .iter()
        .all(|g| g.1.cross(grid[0].1).length() <= RULING_TOLERANCE);
    if flat {
        return None;
    }
    (0..2)
        .rev()
        .find(|&along| straight_lines(along))
        .map(|along| Rulings { along })
}

/// The parameter (0: u, 1: v) along which the rulings of a developable, non-flat surface run
/// when they are parameter lines (cylinders, cones, extrusions: discretised as strips, see the
/// module doc), None otherwise.
pub fn ruling_direction(surface: &dyn Surface) -> Option<usize> {
    find_rulings(surface).map(|r| r.along)
}

/// The strips' dual structure (module doc) over the real seeds `0..uv.len()` followed by the
/// ghosts, with every point's plane and its real seed. `closed`: the surface is closed across
/// its rulings. None where the strips cannot be built (fewer than three rulings on a closed
/// surface, seeds of several rulings on one plane, a degenerate end, a ruling whose seeds'
/// bisectors fail); the caller then takes the general path. `margin` (a length, 0 for the
/// walls themselves) moves the end and side walls that far beyond the domain (module doc).
pub(crate) fn strip_structure(
    surface: &dyn Surface,
    rulings: Rulings,
    uv: &[[f64; 2]],
    planes: &[Plane],
    closed: bool,
    margin: f64,
) -> Option<(DualTriangulation, Vec<Plane>, Vec<u32>)> {
    let domain = surface.domain();
    let (across, along) = (1 - rulings.along, rulings.along);
    let interval = |k: usize| if k == 0 { domain.u } else { domain.v };
    let (t_min, t_max) = (interval(along).min, interval(along).max);
    let (s_min, s_max) = (interval(across).min, interval(across).max);

    // Seeds in ruling order, grouped where their planes coincide.
    let mut order: Vec<u32> = (0..uv.len() as u32).collect();
    order.sort_by(|&a, &b| {
        let (a, b) = (uv[a as usize], uv[b as usize]);
        a[across]
            .total_cmp(&b[across])
            .then(a[along].total_cmp(&b[along]))
    });
    let mut groups: Vec<Vec<u32>> = Vec::new();
    for &i in &order {
        match groups.last_mut() {
            Some(g) if coincident(&planes[g[0] as usize], &planes[i as usize]) => g.push(i),
            _ => groups.push(vec![i]),
        }
    }
    if closed && groups.len() > 1 {
        let (first, last) = (groups[0][0] as usize, groups[groups.len() - 1][0] as usize);
        if coincident(&planes[first], &planes[last]) {
            let last = groups.pop().unwrap_or_default();
            groups[0].extend(last);
        }
    }
    if closed && groups.len() < 3 {
        return None;
    }
    // One plane across several rulings is a flat region (a polysurface of planar faces): its
    // seeds need their Voronoi diagram, not a chain.
    let span = (s_max - s_min).abs();
    let one_ruling = |g: &Vec<u32>| {
        let s0 = uv[g[0] as usize][across];
        g.iter().all(|&i| {
            let gap = (uv[i as usize][across] - s0).abs();
            // Across the seam of a closed surface, s0 and s0 + span are one ruling.
            let gap = if closed { gap.min(span - gap) } else { gap };
            gap <= RULING_TOLERANCE * span
        })
    };
    if !groups.iter().all(one_ruling) {
        return None;
    }
    for g in &mut groups {
        g.sort_by(|&a, &b| uv[a as usize][along].total_cmp(&uv[b as usize][along]));
    }

    let mut all_planes = planes.to_vec();
    let mut source: Vec<u32> = (0..uv.len() as u32).collect();
    let mut push = |plane: Plane, seed: u32| {
        all_planes.push(plane);
        source.push(seed);
        (all_planes.len() - 1) as u32
    };
    // Each ruling's chain: end ghost, its seeds along t, end ghost.
    let mut chains: Vec<Vec<u32>> = Vec::with_capacity(groups.len() + 2);
    let mut directions: Vec<DVec3> = Vec::with_capacity(groups.len() + 2);
    for g in &groups {
        let (first, last) = (g[0], g[g.len() - 1]);
        let s = uv[first as usize][across];
        let bottom_end = point(surface, rulings.at(s, t_min));
        let top_end = point(surface, rulings.at(s, t_max));
        let ruling = top_end - bottom_end;
        let bottom = end_ghost(
            surface,
            rulings.at(s, t_min),
            across,
            planes[first as usize],
            -ruling,
            margin,
        )?;
        let top = end_ghost(
            surface,
            rulings.at(s, t_max),
            across,
            planes[last as usize],
            ruling,
            margin,
        )?;
        let mut chain = vec![push(bottom, first)];
        chain.extend_from_slice(g);
        chain.push(push(top, last));
        chains.push(chain);
        directions.push(ruling);
    }
    if !closed {
        // The side rulings' walls close the first and the last strip.
        let first = groups[0][0];
        let last = groups[groups.len() - 1][0];
        let middle = 0.5 * (s_min + s_max);
        let low = side_wall(surface, rulings, [s_min, middle], [t_min, t_max], margin)?;
        let high = side_wall(surface, rulings, [s_max, middle], [t_min, t_max], margin)?;
        chains.insert(0, vec![push(low, first)]);
        directions.insert(0, directions[0]);
        chains.push(vec![push(high, last)]);
        directions.push(directions[directions.len() - 1]);
    }

    let pairs = if closed {
        chains.len()
    } else {
        chains.len() - 1
    };
    let mut triangles = Vec::new();
    for k in 0..pairs {
        let next = (k + 1) % chains.len();
        let (a, b) = (&chains[k], &chains[next]);
        // Both chains' rulings point the same way; either orients L.
        let ruling = if a.len() > 1 {
            directions[k]
        } else {
            directions[next]
        };
        zip(a, b, &all_planes, ruling, &mut triangles)?;
    }
    if rulings.along == 0 {
        // (s, t) = (v, u) is the mirror image of (u, v): counter-clockwise in (u, v).
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    let triangulation = DualTriangulation::from_triangles(triangles)?;
    Some((triangulation, all_planes, source))
}

/// S(u, v).
fn point(surface: &dyn Surface, [u, v]: [f64; 2]) -> DVec3 {
    surface.point_at(u, v)
}

/// The ghost of the end seed with plane `plane` across the wall at the ruling's end `at`
/// (module doc), on the same plane; `outwards` points along the ruling out of the surface
/// there. A seed on the end, or closer to it than [`STRIP_END_MIN_DEPTH`] of the scale
/// |E| + |ruling|, gets its ghost that depth beyond the wall, so that the two stay coincident
/// planes to [`crate::tolerance::PLANE_COINCIDENCE`] despite the rounding of their points and
/// their bisector is defined; the wall itself moves `margin` outwards. None where the end
/// curve has no tangent (a pole).
fn end_ghost(
    surface: &dyn Surface,
    at: [f64; 2],
    across: usize,
    plane: Plane,
    outwards: DVec3,
    margin: f64,
) -> Option<Plane> {
    let d = surface.evaluate(at[0], at[1]);
    let tangent = if across == 0 { d.su } else { d.sv };
    let mut w = plane.normal.cross(tangent).normalize_or_zero();
    if w == DVec3::ZERO || !w.is_finite() {
        return None;
    }
    if w.dot(outwards) < 0.0 {
        w = -w;
    }
    let p = plane.point;
    let scale = d.point.length() + outwards.length();
    let depth = (d.point - p).dot(w).max(STRIP_END_MIN_DEPTH * scale) + margin;
    let point = p + w * (2.0 * depth);
    point.is_finite().then_some(Plane {
        point,
        normal: plane.normal,
    })
}

/// The wall of the side ruling at `s`, the plane through it that contains its normal, moved
/// `margin` away from the ruling at `inner` (across the surface).
fn side_wall(
    surface: &dyn Surface,
    rulings: Rulings,
    [s, inner]: [f64; 2],
    t: [f64; 2],
    margin: f64,
) -> Option<Plane> {
    let start = point(surface, rulings.at(s, t[0]));
    let end = point(surface, rulings.at(s, t[1]));
    let middle = rulings.at(s, 0.5 * (t[0] + t[1]));
    let normal = LocalGeometry::from_derivatives(&surface.evaluate(middle[0], middle[1])).normal;
    let mut w = normal.cross(end - start).normalize_or_zero();
    if w.dot(point(surface, rulings.at(inner, t[0])) - start) > 0.0 {
        w = -w;
    }
    let point = start + w * margin;
    (w != DVec3::ZERO && w.is_finite() && point.is_finite()).then_some(Plane { point, normal: w })
}

/// Zips chain `a` (the ruling before) and chain `b` along their planes' line (module doc),
/// appending the triangles in (s, t) counter-clockwise order. `ruling` orients the line.
fn zip(
    a: &[u32],
    b: &[u32],
    planes: &[Plane],
    ruling: DVec3,
    triangles: &mut Vec<[u32; 3]>,
) -> Option<()> {
    let (plane_a, plane_b) = (planes[a[0] as usize], planes[b[0] as usize]);
    let mut direction = plane_a.normal.cross(plane_b.normal);
    if direction.dot(ruling) < 0.0 {
        direction = -direction;
    }
    // Where a candidate triangle's vertex lies along the line: computed exactly as the facet
    // stage computes it (points in ascending order), so that every facet's vertices follow
    // the line in the order the triangles were taken, even where two crossings differ only
    // by rounding (nearly parallel planes of close rulings).
    let position = |mut ids: [u32; 3]| {
        ids.sort_unstable();
        let [x, y, z] = ids.map(|k| &planes[k as usize]);
        let at = direction.dot(meeting_point(x, y, z).point);
        at.is_finite().then_some(at)
    };
    let (mut i, mut j) = (0, 0);
    while i + 1 < a.len() || j + 1 < b.len() {
        let take_a = if j + 1 == b.len() {
            true
        } else if i + 1 == a.len() {
            false
        } else {
            // Ties go to the chain before (the same rule everywhere).
            position([a[i], b[j], a[i + 1]])? <= position([a[i], b[j], b[j + 1]])?
        };
        if take_a {
            triangles.push([a[i], b[j], a[i + 1]]);
            i += 1;
        } else {
            triangles.push([a[i], b[j], b[j + 1]]);
            j += 1;
        }
    }
    Some(())
}
