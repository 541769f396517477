//! Validity flips: the last step of the neighbour decision on surfaces that are not convex
//! everywhere (saddles, mixed curvature).
//!
//! Where K < 0 there is no envelope to define the right neighbours. The curvature-compensated
//! Delaunay triangulation ([`crate::neighbours`]) is the right start: on a locally quadratic
//! surface z = x^T II x / 2 the top view of the vertex T_i ∩ T_j ∩ T_k is the circumcentre of
//! (p_i, p_j, p_k) in the metric II, so Delaunay triangles in |II| keep those centres near their
//! triangles. But II is indefinite, its "circles" are hyperbolas, and a few triangles still give
//! centres far from their seeds: the facets around them turn non-simple or fold over a
//! neighbour. Those facets are repaired here by edge flips chosen by the facets themselves.
//!
//! For an interior facet i (its fan of dual triangles closes), its polygon is the sequence of
//! the vertices T_i ∩ T_j ∩ T_k of the triangles around i, counter-clockwise. It is *valid*
//! when (DESIGN.md, item 8)
//! - it is simple and counter-clockwise in its own plane T_i (frame (e1, e2, n_i)), and
//! - it does not overlap a facet that shares an edge with it: projected along the mean of the
//!   two normals, no edge of one crosses a non-shared edge of the other properly and no
//!   vertex of one lies strictly inside the other.
//!
//! A round visits the invalid facets in index order. For each, the edges of its star (i, j)
//! and of its link (j, k) are tried one by one: the edge is flipped (a topological move: the
//! structure stays a triangulated disc whatever the quad's shape in the plane, since facet
//! loops follow adjacency; only a flip whose new diagonal exists already is refused), the
//! invalid facets among those the flip can change (the quad's four points and their
//! neighbours) are counted before and after, and the flip is kept only if the count drops.
//! Every kept flip lowers the number of invalid facets, so the loop ends; it is bounded by
//! [`MAX_VALIDITY_ROUNDS`] rounds in any case. Facets on the hull (open fans) are built with
//! the boundary later ([`crate::facets`]); they are not judged here.

use glam::{DVec2, DVec3};

use crate::neighbours::three_plane_vertex;
use crate::planes::Plane;
use crate::triangulation::{DualTriangulation, Fan, NO_TRIANGLE};

/// Rounds of validity flips at most (each round visits every invalid facet once).
pub const MAX_VALIDITY_ROUNDS: usize = 8;

/// What the validity flips did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ValidityFlipStats {
    /// Flips kept.
    pub flips: usize,
    /// Interior facets still invalid by the local test afterwards.
    pub unresolved: usize,
}

/// Repairs invalid interior facets of the points `0..judged` by flips (module doc).
/// `embedding` holds the triangulation's points (ghosts included); `planes` the tangent
/// planes of all of them.
pub fn validity_flips(tri: &mut DualTriangulation, embedding: &[[f64; 2]], planes: &[Plane], judged: usize) -> ValidityFlipStats {
    let n = judged;
    let mut stats = ValidityFlipStats::default();
    let mut incident = tri.incident_triangles(embedding.len());
    let (lo, hi) = crate::discretise::bounding_box(planes[..n].iter().map(|p| p.point));
    let weld = crate::discretise::DEFAULT_WELD_TOLERANCE * (hi - lo).length();
    let mut judge = Judge { fan: Vec::new(), polygon: Vec::new(), other: Vec::new(), weld };
    for _ in 0..MAX_VALIDITY_ROUNDS {
        let invalid: Vec<u32> = (0..n as u32).filter(|&i| judge.invalid(tri, &incident, planes, i)).collect();
        if std::env::var_os("TPI_DEBUG_FLIPS").is_some() {
            eprintln!("round: {} invalid: {:?}", invalid.len(), &invalid[..invalid.len().min(12)]);
        }
        if invalid.is_empty() {
            break;
        }
        let mut kept = 0;
        for &i in &invalid {
            if !judge.invalid(tri, &incident, planes, i) {
                continue;
            }
            if try_repair(tri, &mut incident, planes, &mut judge, i, n) {
                kept += 1;
            }
        }
        stats.flips += kept;
        if kept == 0 {
            break;
        }
    }
    stats.unresolved = (0..n as u32).filter(|&i| judge.invalid(tri, &incident, planes, i)).count();
    stats
}

/// Tries the star and link edges of facet i; keeps the first flip that lowers the number of
/// invalid facets around it.
fn try_repair(
    tri: &mut DualTriangulation,
    incident: &mut [u32],
    planes: &[Plane],
    judge: &mut Judge,
    i: u32,
    judged: usize,
) -> bool {
    let mut fan = Vec::new();
    if tri.fan(i, incident[i as usize], &mut fan) != Fan::Closed {
        return false;
    }
    // Candidate edges as (a, b) point pairs: star edges, then link edges.
    let mut candidates: Vec<(u32, u32)> = Vec::new();
    for &t in &fan {
        let v = tri.triangles[t as usize];
        let k = v.iter().position(|&x| x == i).unwrap_or(0);
        let (j, m) = (v[(k + 1) % 3], v[(k + 2) % 3]);
        candidates.push((i, j));
        candidates.push((j, m));
    }
    for (a, b) in candidates {
        let Some((t, k)) = find_edge(tri, incident, a, b) else { continue };
        let quad = quad_points(tri, t, k);
        let [c, _, _, d] = quad;
        // A flip is a topological move: the structure stays a triangulated disc whatever the
        // quad's shape in the plane (facet loops follow adjacency, not positions), unless
        // the new diagonal exists already.
        if c == d || has_edge(tri, incident, c, d) {
            continue;
        }
        let mut affected = affected_points(tri, incident, quad);
        affected.retain(|&x| (x as usize) < judged);
        let before = affected.iter().filter(|&&x| judge.invalid(tri, incident, planes, x)).count();
        if before == 0 {
            continue;
        }
        let (t1, t2) = tri.flip(t as u32, k);
        set_incident(tri, incident, t1, t2);
        let after = affected.iter().filter(|&&x| judge.invalid(tri, incident, planes, x)).count();
        if after < before {
            return true;
        }
        // Undo: the new diagonal (c, d) is the edge opposite position 1 of t1 = [c, a, d].
        let (u1, u2) = tri.flip(t1, 1);
        set_incident(tri, incident, u1, u2);
    }
    false
}

/// Whether points a and b are joined by an edge (interior or hull).
fn has_edge(tri: &DualTriangulation, incident: &[u32], a: u32, b: u32) -> bool {
    let mut fan = Vec::new();
    tri.fan(a, incident[a as usize], &mut fan);
    fan.iter().any(|&t| tri.triangles[t as usize].contains(&b))
}

/// Points whose validity a flip of the quad's diagonal can change: the quad's four points
/// (their polygons change) and their neighbours (their overlap with those polygons).
fn affected_points(tri: &DualTriangulation, incident: &[u32], quad: [u32; 4]) -> Vec<u32> {
    let mut out: Vec<u32> = quad.to_vec();
    let mut fan = Vec::new();
    for &p in &quad {
        tri.fan(p, incident[p as usize], &mut fan);
        for &t in &fan {
            out.extend_from_slice(&tri.triangles[t as usize]);
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

fn set_incident(tri: &DualTriangulation, incident: &mut [u32], t1: u32, t2: u32) {
    for t in [t1, t2] {
        for &v in &tri.triangles[t as usize] {
            incident[v as usize] = t;
        }
    }
}

/// The four points (c, a, b, d) of the quad around the edge opposite vertex k of triangle t.
fn quad_points(tri: &DualTriangulation, t: usize, k: usize) -> [u32; 4] {
    let v = tri.triangles[t];
    let (c, a, b) = (v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
    let t2 = tri.neighbours[t][k] as usize;
    let k2 = tri.neighbours[t2].iter().position(|&x| x as usize == t).unwrap_or(0);
    [c, a, b, tri.triangles[t2][k2]]
}

/// The interior edge (a, b) as (triangle, opposite position), if it exists.
fn find_edge(tri: &DualTriangulation, incident: &[u32], a: u32, b: u32) -> Option<(usize, usize)> {
    let mut fan = Vec::new();
    tri.fan(a, incident[a as usize], &mut fan);
    for &t in &fan {
        let v = tri.triangles[t as usize];
        let p = v.iter().position(|&x| x == a)?;
        for (next, opposite) in [((p + 1) % 3, (p + 2) % 3), ((p + 2) % 3, (p + 1) % 3)] {
            if v[next] == b && tri.neighbours[t as usize][opposite] != NO_TRIANGLE {
                return Some((t as usize, opposite));
            }
        }
    }
    None
}

/// Scratch buffers of the local validity test, and the weld distance of the mesh (vertices
/// closer than this become one, as in the facet stage's welding).
struct Judge {
    fan: Vec<u32>,
    polygon: Vec<DVec3>,
    other: Vec<DVec3>,
    weld: f64,
}

/// Drops consecutive vertices (cyclically) closer than `weld` to the previous kept one.
fn weld_loop(points: &mut Vec<DVec3>, weld: f64) {
    points.dedup_by(|b, a| a.distance(*b) <= weld);
    while points.len() > 1 && points[0].distance(points[points.len() - 1]) <= weld {
        points.pop();
    }
}

impl Judge {
    /// Whether interior facet i is invalid (module doc); hull facets are never judged.
    fn invalid(&mut self, tri: &DualTriangulation, incident: &[u32], planes: &[Plane], i: u32) -> bool {
        let mut fan = std::mem::take(&mut self.fan);
        let verdict = self.invalid_with(tri, incident, planes, i, &mut fan);
        self.fan = fan;
        verdict
    }

    fn invalid_with(&mut self, tri: &DualTriangulation, incident: &[u32], planes: &[Plane], i: u32, fan: &mut Vec<u32>) -> bool {
        if tri.fan(i, incident[i as usize], fan) != Fan::Closed {
            return false;
        }
        let mut polygon = std::mem::take(&mut self.polygon);
        polygon.clear();
        polygon.extend(fan.iter().map(|&t| three_plane_vertex(planes, tri.triangles[t as usize])));
        weld_loop(&mut polygon, self.weld);
        let plane = &planes[i as usize];
        let mut invalid = !polygon.iter().all(|x| x.is_finite()) || !simple_in_plane(&polygon, plane.normal);
        if !invalid {
            // Overlap with each edge neighbour whose fan closes.
            let neighbours: Vec<u32> = fan
                .iter()
                .map(|&t| {
                    let v = tri.triangles[t as usize];
                    let k = v.iter().position(|&x| x == i).unwrap_or(0);
                    v[(k + 1) % 3]
                })
                .collect();
            let mut other_fan = Vec::new();
            for j in neighbours {
                if tri.fan(j, incident[j as usize], &mut other_fan) != Fan::Closed {
                    continue;
                }
                let mut other = std::mem::take(&mut self.other);
                other.clear();
                other.extend(other_fan.iter().map(|&t| three_plane_vertex(planes, tri.triangles[t as usize])));
                weld_loop(&mut other, self.weld);
                let normal = plane.normal + planes[j as usize].normal;
                let overlapping = other.iter().all(|x| x.is_finite())
                    && simple_in_plane(&other, planes[j as usize].normal)
                    && polygons_overlap(&polygon, &other, normal);
                self.other = other;
                if overlapping {
                    invalid = true;
                    break;
                }
            }
        }
        self.polygon = polygon;
        invalid
    }
}

/// Coordinates in the plane perpendicular to `normal`, frame (e1, e2, normal) right-handed,
/// relative to `origin` (so that rounding is relative to the polygons' own size).
fn flatten(points: &[DVec3], normal: DVec3, origin: DVec3) -> Vec<DVec2> {
    let (e1, e2) = normal.normalize_or(DVec3::Z).any_orthonormal_pair();
    points.iter().map(|&x| DVec2::new((x - origin).dot(e1), (x - origin).dot(e2))).collect()
}

/// Relative tolerance of the local validity tests: orientations smaller than this times the
/// squared size of the polygons count as collinear, distances smaller than this times the
/// size as zero (rounding of the three-plane vertices is far below it).
pub const VALIDITY_TOLERANCE: f64 = 1e-9;

/// Longest edge of a closed polygon.
fn size(p: &[DVec2]) -> f64 {
    (0..p.len()).map(|k| (p[(k + 1) % p.len()] - p[k]).length()).fold(0.0, f64::max)
}

/// Simple and counter-clockwise seen from `normal`, at least three distinct vertices.
pub(crate) fn simple_in_plane(points: &[DVec3], normal: DVec3) -> bool {
    let Some(&origin) = points.first() else { return false };
    let p = flatten(points, normal, origin);
    let n = p.len();
    if n < 3 {
        return false;
    }
    // Strict, as any independent check of the finished mesh is: a fold of any size fails.
    let area: f64 = (0..n).map(|k| p[k].perp_dot(p[(k + 1) % n])).sum();
    if !(area > 0.0) {
        return false;
    }
    let eps = 0.0;
    for a in 0..n {
        for b in a + 2..n {
            if a == 0 && b == n - 1 {
                continue;
            }
            if proper_crossing(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n], eps) {
                return false;
            }
        }
    }
    true
}

/// Whether two simple polygons that may share vertices overlap in area, seen along
/// `normal`: a proper crossing of their edges, or a vertex of one strictly inside the other.
/// Vertices of one closer than the tolerance to a vertex of the other count as shared.
pub(crate) fn polygons_overlap(a: &[DVec3], b: &[DVec3], normal: DVec3) -> bool {
    let Some(&origin) = a.first() else { return false };
    let (pa, mut pb) = (flatten(a, normal, origin), flatten(b, normal, origin));
    let scale = size(&pa).max(size(&pb));
    let tolerance = VALIDITY_TOLERANCE * scale;
    for q in pb.iter_mut() {
        if let Some(p) = pa.iter().find(|p| (**p - *q).length() <= tolerance) {
            *q = *p;
        }
    }
    let eps = VALIDITY_TOLERANCE * scale * scale;
    let (na, nb) = (pa.len(), pb.len());
    for x in 0..na {
        for y in 0..nb {
            if proper_crossing(pa[x], pa[(x + 1) % na], pb[y], pb[(y + 1) % nb], eps) {
                return true;
            }
        }
    }
    let strictly_inside = |p: DVec2, poly: &[DVec2]| {
        !poly.iter().any(|q| (*q - p).length() <= tolerance) && point_in_polygon(p, poly, tolerance)
    };
    pb.iter().any(|&p| strictly_inside(p, &pa)) || pa.iter().any(|&p| strictly_inside(p, &pb))
}

/// Strictly inside (farther than `tolerance` from every edge) by the crossing number.
fn point_in_polygon(p: DVec2, poly: &[DVec2], tolerance: f64) -> bool {
    let n = poly.len();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        if (a + ab * t - p).length() <= tolerance {
            return false;
        }
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * ab.x {
            inside = !inside;
        }
    }
    inside
}

/// The segments ab and cd cross properly: each strictly (beyond `eps`, an area) on both
/// sides of the other.
fn proper_crossing(a: DVec2, b: DVec2, c: DVec2, d: DVec2, eps: f64) -> bool {
    let d1 = (b - a).perp_dot(c - a);
    let d2 = (b - a).perp_dot(d - a);
    let d3 = (d - c).perp_dot(a - c);
    let d4 = (d - c).perp_dot(b - c);
    let opposite = |x: f64, y: f64| (x > eps && y < -eps) || (x < -eps && y > eps);
    opposite(d1, d2) && opposite(d3, d4)
}
