//! Flat surfaces: every tangent plane is one plane T, so tangent planes cannot separate the
//! facets. Their limit as the curvature vanishes does: on z = e (x^2 + y^2) / 2 the tangent
//! planes of p and q meet above the perpendicular bisector of p and q for every e > 0, so the
//! facets of a plane are the Voronoi cells of their seeds in T ([`crate::planes::meeting_point`]).
//! Their dual structure is the Delaunay triangulation of the seeds in orthonormal
//! coordinates of T,
//!
//! ```text
//! x_i = ((p_i - p_0) . e1, (p_i - p_0) . e2),   e1 ⟂ n,  e2 = n x e1,
//! ```
//!
//! (the surface's own metric, whatever its parametrisation), and the facet stage clips the
//! cells on the boundary or the trim exactly as on the convex paths: the wall along the
//! boundary is the plane's normal swept along it.
//!
//! Rounding in those coordinates can make three collinear seeds on the hull (a grid row along
//! a straight side) a sliver triangle whose circumcentre is at infinity; such hull triangles
//! are removed ([`DEGENERATE_SLIVER_FACTOR`]), as the exact triangulation has none.

use glam::DVec3;

use crate::error::TpiError;
use crate::planes::{meeting_point, Plane};
use crate::tolerance::DEGENERATE_SLIVER_FACTOR;
use crate::triangulation::{DualTriangulation, NO_TRIANGLE};

/// The Voronoi dual of the seeds of a flat surface (module doc): their Delaunay triangulation
/// in the plane, without hull slivers.
pub(crate) fn voronoi_dual(planes: &[Plane]) -> Result<DualTriangulation, TpiError> {
    let mut tri = DualTriangulation::delaunay(&in_plane(planes))?;
    loop {
        let removed: Vec<bool> = (0..tri.len())
            .map(|t| tri.neighbours[t].contains(&NO_TRIANGLE) && sliver(planes, tri.triangles[t]))
            .collect();
        if !removed.contains(&true) || removed.iter().all(|&r| r) {
            return Ok(tri);
        }
        tri.remove_triangles(&removed);
    }
}

/// Whether the circumcentre of three seeds is at infinity or farther than
/// [`DEGENERATE_SLIVER_FACTOR`] times their largest distance from their centroid.
fn sliver(planes: &[Plane], mut ids: [u32; 3]) -> bool {
    ids.sort_unstable();
    let [a, b, c] = ids.map(|i| &planes[i as usize]);
    let vertex = meeting_point(a, b, c).point;
    let centroid = (a.point + b.point + c.point) / 3.0;
    let size = a
        .point
        .distance(b.point)
        .max(b.point.distance(c.point))
        .max(c.point.distance(a.point));
    !vertex.is_finite() || vertex.distance(centroid) > DEGENERATE_SLIVER_FACTOR * size
}

/// The points of `planes`, all one plane, in orthonormal coordinates of that plane (module
/// doc): counter-clockwise there is counter-clockwise seen from the normal.
fn in_plane(planes: &[Plane]) -> Vec<[f64; 2]> {
    let Some(first) = planes.first() else {
        return Vec::new();
    };
    let e1 = first.normal.any_orthonormal_vector();
    let e2 = first.normal.cross(e1);
    planes
        .iter()
        .map(|p| {
            let d: DVec3 = p.point - first.point;
            [d.dot(e1), d.dot(e2)]
        })
        .collect()
}
