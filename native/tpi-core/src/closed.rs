//! Closed surfaces: a face closed in one parameter direction (its two sides across it are one
//! seam), each side across the other direction a pole or open. A sphere or ellipsoid made of
//! one face has poles at both ends; a zone has two open sides; a dome of revolution one pole
//! and one open side.
//!
//! **Layout.** A direction is closed when the surface's two sides across it coincide,
//! S(u0, v) = S(u1, v) for every v (sampled at [`LAYOUT_SAMPLES`] parameters, to
//! [`CLOSURE_TOLERANCE`] of the bounding-box diagonal of the samples); a side is a pole when it
//! is one point, S(u, v0) the same for every u.
//!
//! **Envelope.** Where such a surface is strictly convex at every seed, the facets are the
//! faces of the intersection of the half-spaces behind the tangent planes T_i = {x : n_i . x =
//! n_i . p_i}, a closed convex polytope. With c a point inside (the seeds' centroid) and
//! h_i = n_i . (p_i - c) (all of one sign on a closed convex surface), plane i is polar to the
//! dual point
//!
//! ```text
//! d_i = n_i / h_i   (relative to c),
//! ```
//!
//! and the polytope's vertices are polar to the faces of the convex hull of the dual points:
//! a hull face (i, j, k) is the vertex T_i ∩ T_j ∩ T_k, and the hull faces around d_i, in
//! order, are the vertices of facet i. The hull is computed with exact orientation tests
//! ([`crate::hull`]), so the neighbours are exactly the envelope's; four or more planes
//! through one point give hull faces on one plane and one mesh vertex (welded by the mesh
//! stage). With poles at both ends the mesh is a closed sphere: Euler characteristic 2, no
//! boundary. With open sides, the ghost seeds beyond them ([`crate::ghosts`], the surface
//! continued by its Taylor expansion) add their dual points to the hull, the real facets end
//! on their planes, and the mesh has one boundary loop per open side (Euler characteristic
//! 2 - loops); a ghost the envelope cuts away just has no face. The seam needs nothing: the
//! hull does not see the parametrisation.

use glam::DVec3;

use crate::error::TpiError;
use crate::hull::{convex_hull, HullError};
use crate::planes::Plane;
use crate::samples::bounding_diagonal;
use crate::surface::Surface;
use crate::tolerance::{CLOSURE_TOLERANCE, LAYOUT_SAMPLES};
use crate::triangulation::DualTriangulation;

/// Which sides of a surface's domain meet or collapse ([`surface_layout`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SurfaceLayout {
    /// Closed in u (S(u0, v) = S(u1, v) for every v) and in v.
    pub closed: [bool; 2],
    /// Poles: the sides u = u0, u = u1, v = v0, v = v1, each a single point.
    pub poles: [bool; 4],
}

impl SurfaceLayout {
    /// Closed in one direction with a pole at each end of the other: a sphere.
    pub fn is_sphere(&self) -> bool {
        (self.closed[0] && self.poles[2] && self.poles[3])
            || (self.closed[1] && self.poles[0] && self.poles[1])
    }

    /// Closed in exactly one direction: the sides across the other one (u0, u1, v0, v1
    /// order) that are neither a pole nor a seam, where the surface ends. None where the
    /// surface is not closed in exactly one direction.
    pub fn open_sides(&self) -> Option<[bool; 4]> {
        match self.closed {
            [true, false] => Some([false, false, !self.poles[2], !self.poles[3]]),
            [false, true] => Some([!self.poles[0], !self.poles[1], false, false]),
            _ => None,
        }
    }

    /// Whether (u, v) lies on a pole side.
    pub(crate) fn on_pole(&self, surface: &dyn Surface, [u, v]: [f64; 2]) -> bool {
        let d = surface.domain();
        (self.poles[0] && u == d.u.min)
            || (self.poles[1] && u == d.u.max)
            || (self.poles[2] && v == d.v.min)
            || (self.poles[3] && v == d.v.max)
    }
}

/// Which sides of the surface's domain meet (closed directions) or collapse to a point
/// (poles), sampled (module doc).
pub fn surface_layout(surface: &dyn Surface) -> SurfaceLayout {
    let domain = surface.domain();
    let m = LAYOUT_SAMPLES;
    let at = |i: usize| i as f64 / (m - 1) as f64;
    let side = |fixed_u: Option<f64>, fixed_v: Option<f64>| -> Vec<DVec3> {
        (0..m)
            .map(|i| {
                let u = fixed_u.unwrap_or_else(|| domain.u.lerp(at(i)));
                let v = fixed_v.unwrap_or_else(|| domain.v.lerp(at(i)));
                surface.evaluate(u, v).point
            })
            .collect()
    };
    let sides = [
        side(Some(domain.u.min), None),
        side(Some(domain.u.max), None),
        side(None, Some(domain.v.min)),
        side(None, Some(domain.v.max)),
    ];
    let diagonal = bounding_diagonal(sides.iter().flatten().copied());
    if !(diagonal > 0.0 && diagonal.is_finite()) {
        return SurfaceLayout::default();
    }
    let tolerance = CLOSURE_TOLERANCE * diagonal;
    let coincide =
        |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).all(|(p, q)| p.distance(*q) <= tolerance);
    let point = |a: &[DVec3]| a.iter().all(|p| p.distance(a[0]) <= tolerance);
    SurfaceLayout {
        closed: [
            coincide(&sides[0], &sides[1]),
            coincide(&sides[2], &sides[3]),
        ],
        poles: [
            point(&sides[0]),
            point(&sides[1]),
            point(&sides[2]),
            point(&sides[3]),
        ],
    }
}

/// The envelope's dual structure on a closed strictly convex surface (module doc): the hull
/// faces of the dual points, counter-clockwise seen from the side the normals point to, with
/// their adjacency. The first `required` planes must be on the envelope (errors name the first
/// that is not); the others (ghosts beyond an open side) may be cut away by it.
pub(crate) fn envelope_triangulation(
    planes: &[Plane],
    required: usize,
) -> Result<DualTriangulation, TpiError> {
    let n = planes.len() as f64;
    let centre = planes.iter().map(|p| p.point).sum::<DVec3>() / n;
    let heights: Vec<f64> = planes
        .iter()
        .map(|p| p.normal.dot(p.point - centre))
        .collect();
    let outward = heights[0] > 0.0;
    if let Some(i) = heights
        .iter()
        .position(|&h| !(h != 0.0 && (h > 0.0) == outward))
    {
        return Err(TpiError::DegenerateSurface {
            reason: format!(
                "the tangent plane of pattern point {i} does not face away from the surface's centre: the closed surface is not convex there"
            ),
        });
    }
    let dual: Vec<[f64; 3]> = planes
        .iter()
        .zip(&heights)
        .map(|(p, &h)| (p.normal / h).to_array())
        .collect();
    let (mut triangles, mut neighbours, on_hull) =
        convex_hull(&dual).map_err(|e| TpiError::DegenerateSurface {
            reason: match e {
                HullError::Flat => {
                    "the tangent planes of the closed surface do not enclose a volume".into()
                }
                HullError::Inconsistent => {
                    "the envelope of the tangent planes could not be built".into()
                }
            },
        })?;
    if let Some(i) = on_hull[..required].iter().position(|&h| !h) {
        return Err(TpiError::DegenerateSurface {
            reason: format!(
                "the tangent plane of pattern point {i} lies outside the envelope of the others: the closed surface is not strictly convex there"
            ),
        });
    }
    // Hull faces run counter-clockwise seen from outside; facets run counter-clockwise seen
    // from their normals, which point inwards when the heights are negative.
    // Swapping vertices 1 and 2 swaps the edges opposite them.
    if !outward {
        for (t, nb) in triangles.iter_mut().zip(&mut neighbours) {
            t.swap(1, 2);
            nb.swap(1, 2);
        }
    }
    // Sorted by their vertices (each triangle is one key), the hull's neighbours renumbered.
    let mut order: Vec<u32> = (0..triangles.len() as u32).collect();
    order.sort_unstable_by_key(|&t| triangles[t as usize]);
    let mut new_index = vec![0u32; order.len()];
    for (k, &t) in order.iter().enumerate() {
        new_index[t as usize] = k as u32;
    }
    Ok(DualTriangulation {
        triangles: order.iter().map(|&t| triangles[t as usize]).collect(),
        neighbours: order
            .iter()
            .map(|&t| neighbours[t as usize].map(|x| new_index[x as usize]))
            .collect(),
    })
}
