//! Ghost seeds beyond the domain boundary, so that the neighbour decision on surfaces that
//! are not convex everywhere sees every real facet as a closed polygon.
//!
//! A facet at the boundary is closed by the boundary itself: the mesh ends near the wall,
//! the ruled surface of the surface normals along the boundary curve (DESIGN.md, item 6). A
//! seed within [`GHOST_BAND`] spacings of a side gets a ghost across it: its position mirrored
//! in the triangulation's plane, and the tangent plane of the surface *continued* beyond the
//! side at the mirrored parameters, by the second-order Taylor expansion about the boundary
//! point b = S(u_b, v) (or the corner, for a ghost across two sides):
//!
//! ```text
//! S(u_b + du, v + dv) ~ S + S_u du + S_v dv + (S_uu du^2 + 2 S_uv du dv + S_vv dv^2) / 2,
//! du = -(depth beyond the side), the seed's distance from the side mirrored (see
//! [`ghost_depth`]), in parameters.
//! ```
//!
//! On the continued surface the ghosts are ordinary seeds, so a boundary facet meets them as
//! an interior facet meets its neighbours; in the quadric approximation the top view of the
//! edge between a seed and its own ghost is their bisector, the side itself. The ghosts take
//! part in every flip and let the validity flips judge boundary facets as closed polygons;
//! the vertices of triangles with a ghost are the mesh's boundary vertices.

use crate::boundary::Boundary;
use crate::diffgeo::{flat_curvatures, LocalGeometry};
use crate::planes::{coincident, Plane};
use crate::surface::{Surface, SurfaceDerivatives};
use crate::tolerance::{GHOST_BAND, GHOST_FLAT_MIRROR, GHOST_MIN_DEPTH};

/// The depth beyond the side of the ghost of a seed at distance d >= 0 inside it, for mean
/// spacing h: the mirror distance d from h / 2 on, and d + m (1 - 2 d / h) with
/// m = [`GHOST_MIN_DEPTH`] h below it. Strictly increasing in d (ghosts of distinct seeds on
/// one normal line stay distinct) and at least m: a seed on the side gets its ghost at depth
/// m, and its facet ends about m / 2 beyond the side.
fn ghost_depth(d: f64, h: f64) -> f64 {
    let m = GHOST_MIN_DEPTH * h;
    if d >= 0.5 * h {
        d
    } else {
        d + m * (1.0 - 2.0 * d / h)
    }
}

/// The depth beyond the boundary of the ghost of a seed at distance d inside it: a flat seed
/// (a plane, or a ruling of a developable surface) is mirrored exactly, unless it is on its
/// side, since where its ghost's plane coincides with its own their bisector is the side
/// itself and neighbouring seeds at different distances would otherwise end at different
/// depths, in steps; any other seed at [`ghost_depth`].
fn mirror_depth(flat: bool, d: f64, spacing: f64) -> f64 {
    if flat && d >= GHOST_FLAT_MIRROR * spacing {
        d
    } else {
        ghost_depth(d, spacing)
    }
}

/// The real seeds followed by their ghosts.
pub(crate) struct Augmented {
    /// Triangulation-plane coordinates.
    pub(crate) plane_uv: Vec<[f64; 2]>,
    /// Local geometry (ghosts: that of the continued surface at the ghost's parameters).
    pub(crate) geometry: Vec<LocalGeometry>,
    /// Tangent planes.
    pub(crate) planes: Vec<Plane>,
    /// Convex side per seed (a ghost takes its seed's).
    pub(crate) convex_side: Vec<i8>,
    /// The real seed of every point (itself for real seeds).
    pub(crate) source: Vec<u32>,
}

/// The seeds alone, their tangent planes from their local geometry.
fn seeds_only(plane_uv: &[[f64; 2]], geometry: &[LocalGeometry], convex_side: &[i8]) -> Augmented {
    Augmented {
        plane_uv: plane_uv.to_vec(),
        geometry: geometry.to_vec(),
        planes: geometry.iter().map(LocalGeometry::tangent_plane).collect(),
        convex_side: convex_side.to_vec(),
        source: (0..plane_uv.len() as u32).collect(),
    }
}

/// The local geometry at domain parameters `at + offset` of the surface continued beyond its
/// boundary by its second-order Taylor expansion about `at` (a point of the boundary):
/// S(at) + J offset + offset^T H offset / 2, with the derivatives of that quadric.
fn continued(surface: &dyn Surface, at: [f64; 2], offset: [f64; 2]) -> Option<LocalGeometry> {
    let d = surface.evaluate(at[0], at[1]);
    let [du, dv] = offset;
    let point = d.point
        + d.su * du
        + d.sv * dv
        + (d.suu * (du * du) + d.suv * (2.0 * du * dv) + d.svv * (dv * dv)) * 0.5;
    let su = d.su + d.suu * du + d.suv * dv;
    let sv = d.sv + d.suv * du + d.svv * dv;
    let g = LocalGeometry::from_derivatives(&SurfaceDerivatives { point, su, sv, ..d });
    (g.regular && g.point.is_finite() && g.normal.is_finite()).then_some(g)
}

/// The seeds with their ghosts appended (module doc), across the sides marked in `open`
/// (u0, u1, v0, v1; the others are seams or poles of a closed surface). `extent` is the size
/// of the triangulation's plane rectangle `[0, extent[0]] x [0, extent[1]]`; `uv` the seeds'
/// domain parameters. Ghosts where the continued surface is not regular (a degenerate boundary,
/// such as a pole) are left out.
pub(crate) fn augment(
    surface: &dyn Surface,
    uv: &[[f64; 2]],
    plane_uv: &[[f64; 2]],
    extent: [f64; 2],
    geometry: &[LocalGeometry],
    convex_side: &[i8],
    open: [bool; 4],
) -> Augmented {
    let n = plane_uv.len();
    let spacing = (extent[0] * extent[1] / n as f64).sqrt();
    let band = GHOST_BAND * spacing;
    let mut out = seeds_only(plane_uv, geometry, convex_side);
    let domain = surface.domain();
    let (u0, u1, v0, v1) = (domain.u.min, domain.u.max, domain.v.min, domain.v.max);
    for i in 0..n {
        let [x, y] = plane_uv[i];
        let [u, v] = uv[i];
        // Per side: distance d, the ghost's position at depth ghost_depth(d) beyond the side,
        // the boundary parameter and the ghost's parameter offset from it.
        let scale_u = (u1 - u0) / extent[0];
        let scale_v = (v1 - v0) / extent[1];
        let flat = flat_curvatures(geometry[i].k1, geometry[i].k2);
        let depth = |d: f64| mirror_depth(flat, d, spacing);
        let dx0 = depth(x);
        let dx1 = depth(extent[0] - x);
        let dy0 = depth(y);
        let dy1 = depth(extent[1] - y);
        let sides = [
            (x, [-dx0, y], u0, -dx0 * scale_u),
            (extent[0] - x, [extent[0] + dx1, y], u1, dx1 * scale_u),
            (y, [x, -dy0], v0, -dy0 * scale_v),
            (extent[1] - y, [x, extent[1] + dy1], v1, dy1 * scale_v),
        ];
        let near: Vec<usize> = (0..4).filter(|&s| open[s] && sides[s].0 < band).collect();
        let mut push = |position: [f64; 2], g: Option<LocalGeometry>| {
            let Some(g) = g else { return };
            out.plane_uv.push(position);
            out.planes.push(g.tangent_plane());
            out.geometry.push(g);
            out.convex_side.push(convex_side[i]);
            out.source.push(i as u32);
        };
        let mut side_geometry: [Option<LocalGeometry>; 4] = [None; 4];
        for &s in &near {
            let (at, offset) = if s < 2 {
                ([sides[s].2, v], [sides[s].3, 0.0])
            } else {
                ([u, sides[s].2], [0.0, sides[s].3])
            };
            side_geometry[s] = continued(surface, at, offset);
            push(sides[s].1, side_geometry[s]);
        }
        // Corners: across a u side and a v side at once, continued from the corner.
        for &su in near.iter().filter(|&&s| s < 2) {
            for &sv in near.iter().filter(|&&s| s >= 2) {
                let position = [sides[su].1[0], sides[sv].1[1]];
                let mut g = continued(
                    surface,
                    [sides[su].2, sides[sv].2],
                    [sides[su].3, sides[sv].3],
                );
                // Where the seed's plane continues unchanged across one side (a ruling of a
                // developable surface, or a flat region, crosses it), the corner ghost lies on
                // the ruling of the other side's ghost and takes its plane: the quadric
                // continuation would leave the two nearly but not exactly coincident, and
                // their vertex far away.
                let seed_plane = &geometry[i].tangent_plane();
                let along = |s: usize| {
                    side_geometry[s].filter(|g| coincident(seed_plane, &g.tangent_plane()))
                };
                let other = match (along(su), along(sv)) {
                    (Some(_), None) => side_geometry[sv],
                    (None, Some(_)) => side_geometry[su],
                    _ => None,
                };
                if let (Some(corner), Some(other)) = (g.as_mut(), other) {
                    corner.normal = other.normal;
                    corner.point -= other.normal * other.normal.dot(corner.point - other.point);
                }
                push(position, g);
            }
        }
    }
    out
}

/// The seeds with ghosts across the loops of a trim (`boundary`), for surfaces the convex
/// paths do not clip (saddles, mixed and curved developable ones): a seed within
/// [`GHOST_BAND`] spacings of a loop segment gets a ghost mirrored across it in the
/// triangulation's plane (at most the two nearest segments, as at a corner of the
/// rectangle), at depth [`ghost_depth`] beyond it, with the tangent plane of the surface
/// continued from the segment's nearest point, as [`augment`] does across a side. A ghost that
/// would land inside the trimmed region (across a segment next to a reflex corner) is left
/// out. The facets then end near the trim, on the ghosts' planes, not exactly on its wall.
pub(crate) fn augment_within_trim(
    surface: &dyn Surface,
    plane_uv: &[[f64; 2]],
    extent: [f64; 2],
    geometry: &[LocalGeometry],
    convex_side: &[i8],
    boundary: &Boundary,
) -> Augmented {
    let n = plane_uv.len();
    let spacing = (extent[0] * extent[1] / n as f64).sqrt();
    let band = GHOST_BAND * spacing;
    let mut out = seeds_only(plane_uv, geometry, convex_side);
    let domain = surface.domain();
    let to_domain = |q: [f64; 2]| domain.from_normalised([q[0] / extent[0], q[1] / extent[1]]);
    let loops: Vec<Vec<[f64; 2]>> = boundary
        .loops()
        .iter()
        .map(|l| {
            l.iter()
                .map(|p| [p[0] * extent[0], p[1] * extent[1]])
                .collect()
        })
        .collect();
    for i in 0..n {
        let p = plane_uv[i];
        // (distance, foot on the segment, unit outward normal) of the segments within reach.
        let mut near: Vec<(f64, [f64; 2], [f64; 2])> = Vec::new();
        for points in &loops {
            for k in 0..points.len() {
                let (a, b) = (points[k], points[(k + 1) % points.len()]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let length = dx.hypot(dy);
                if !(length > 0.0) {
                    continue;
                }
                let tau =
                    (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (length * length)).clamp(0.0, 1.0);
                let foot = [a[0] + tau * dx, a[1] + tau * dy];
                let distance = (p[0] - foot[0]).hypot(p[1] - foot[1]);
                if distance < band {
                    // The region lies on the left of every loop: outwards is to the right.
                    near.push((distance, foot, [dy / length, -dx / length]));
                }
            }
        }
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        let flat = flat_curvatures(geometry[i].k1, geometry[i].k2);
        for &(d, foot, outward) in near.iter().take(2) {
            let depth = mirror_depth(flat, d, spacing);
            let position = [foot[0] + outward[0] * depth, foot[1] + outward[1] * depth];
            if boundary.inside_measure(to_domain(position)) > 0.0 {
                continue;
            }
            let (at, beyond) = (to_domain(foot), to_domain(position));
            let offset = [beyond[0] - at[0], beyond[1] - at[1]];
            if let Some(ghost) = continued(surface, at, offset) {
                out.plane_uv.push(position);
                out.planes.push(ghost.tangent_plane());
                out.geometry.push(ghost);
                out.convex_side.push(convex_side[i]);
                out.source.push(i as u32);
            }
        }
    }
    out
}
