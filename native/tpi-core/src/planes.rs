//! Tangent planes and their intersections.
//!
//! Pattern point i has surface point p_i and unit normal n_i; its tangent plane is
//! T_i = {x : n_i . x = n_i . p_i}. Three tangent planes meet in the solution of
//!
//! ```text
//! [n_i; n_j; n_k] x = [n_i.p_i; n_j.p_j; n_k.p_k]
//! ```
//!
//! solved here by Cramer's rule relative to the centroid c of the three points (to keep the
//! right-hand side small): x = c + (b_i (n_j x n_k) + b_j (n_k x n_i) + b_k (n_i x n_j)) / det
//! with b_m = n_m . (p_m - c) and det = n_i . (n_j x n_k). |det| is the volume spanned by the
//! normals: near 0 the planes are nearly parallel (flat or developable regions) and the
//! vertex runs away, which callers detect and report.
//!
//! The three indices are always processed in ascending order so that the same vertex is
//! computed bit-identically by every facet that shares it.
//!
//! **Coincident planes** (flat regions, the rulings of developable surfaces: [`coincident`])
//! meet in no line, and TPI alone cannot separate their facets. Their limit as the curvature
//! vanishes does: on z = e (x^2 + y^2) / 2 the tangent planes of p and q meet above the
//! perpendicular bisector of p and q, for every e > 0. So where two of a vertex's three planes
//! coincide, say T_i = T_j, the vertex is T_i ∩ T_k ∩ B_ij with the bisector plane
//!
//! ```text
//! B_ij = {x : m . (x - (p_i + p_j) / 2) = 0},  m = d - n_i (n_i . d),  d = p_j - p_i,
//! ```
//!
//! perpendicular to T_i; where all three coincide it is T_i ∩ B_ij ∩ B_ik, the circumcentre
//! of the three points in their plane: the facets of a plane are the Voronoi cells of their
//! seeds ([`meeting_point`]). The edge of two coincident facets lies on their bisector, in
//! both planes, so the facets stay exactly planar and the mesh closed.

use glam::DVec3;

use crate::tolerance::PLANE_COINCIDENCE;

/// A plane through `point` with unit `normal`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Plane {
    /// A point of the plane.
    pub point: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

impl Plane {
    /// Signed distance of `x` from the plane (positive on the normal's side).
    pub(crate) fn signed_distance(&self, x: DVec3) -> f64 {
        self.normal.dot(x - self.point)
    }
}

/// The meeting point of three planes and the determinant of their normals.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ThreePlanePoint {
    /// The intersection point (only meaningful when `determinant` is not ~0).
    pub point: DVec3,
    /// n_a . (n_b x n_c) for the planes in ascending index order.
    pub determinant: f64,
}

/// Intersects three planes given in ascending index order (the caller sorts).
pub(crate) fn intersect_three(a: &Plane, b: &Plane, c: &Plane) -> ThreePlanePoint {
    let centroid = (a.point + b.point + c.point) / 3.0;
    let bc = b.normal.cross(c.normal);
    let ca = c.normal.cross(a.normal);
    let ab = a.normal.cross(b.normal);
    let determinant = a.normal.dot(bc);
    let rhs_a = a.normal.dot(a.point - centroid);
    let rhs_b = b.normal.dot(b.point - centroid);
    let rhs_c = c.normal.dot(c.point - centroid);
    let point = centroid + (rhs_a * bc + rhs_b * ca + rhs_c * ab) / determinant;
    ThreePlanePoint { point, determinant }
}

/// Whether planes `a` and `b` coincide to within [`PLANE_COINCIDENCE`] (module doc).
pub(crate) fn coincident(a: &Plane, b: &Plane) -> bool {
    let gap = (b.point - a.point).length();
    a.normal.cross(b.normal).length() <= PLANE_COINCIDENCE
        && a.signed_distance(b.point).abs() <= PLANE_COINCIDENCE * gap
        && b.signed_distance(a.point).abs() <= PLANE_COINCIDENCE * gap
}

/// The bisector plane B_ab of the points of coincident planes `a` and `b`, perpendicular to
/// `a` (module doc); a plane with a zero normal when the two points coincide.
pub(crate) fn bisector(a: &Plane, b: &Plane) -> Plane {
    let d = b.point - a.point;
    Plane {
        point: (a.point + b.point) * 0.5,
        normal: (d - a.normal * a.normal.dot(d)).normalize_or_zero(),
    }
}

/// The vertex of three planes given in ascending index order, with coincident planes
/// separated by the bisectors of their points (module doc); [`intersect_three`] when no two
/// coincide. Every pair is tested, so the vertex does not depend on which facet asks.
pub(crate) fn meeting_point(a: &Plane, b: &Plane, c: &Plane) -> ThreePlanePoint {
    match (coincident(a, b), coincident(b, c), coincident(a, c)) {
        (false, false, false) => intersect_three(a, b, c),
        (true, false, false) => on_bisector(a, c, &bisector(a, b)),
        (false, true, false) => on_bisector(a, b, &bisector(b, c)),
        (false, false, true) => on_bisector(a, b, &bisector(a, c)),
        _ => intersect_three(a, &bisector(a, b), &bisector(a, c)),
    }
}

/// T_p ∩ T_q ∩ B for a bisector B, moved along the line T_p ∩ T_q onto B exactly. Where T_p
/// and T_q are nearly parallel (neighbouring rulings of a developable surface) the solve
/// is off by about the rounding over their angle in every direction; along their line only B
/// decides, so that step leaves the point on both planes and puts it on B to rounding (the
/// ends of strips, on their walls, would otherwise wobble along the line).
fn on_bisector(p: &Plane, q: &Plane, bisector: &Plane) -> ThreePlanePoint {
    let mut meeting = intersect_three(p, q, bisector);
    let along = p.normal.cross(q.normal);
    let slope = bisector.normal.dot(along);
    let step = bisector.signed_distance(meeting.point) / slope;
    let moved = meeting.point - along * step;
    if slope.abs() > PLANE_COINCIDENCE * along.length() && moved.is_finite() {
        meeting.point = moved;
    }
    meeting
}

/// The point nearest to `anchor` that minimises the summed squared distances to the three
/// planes, Tikhonov-regularised with weight `mu`: stays near `anchor` when the planes are
/// nearly parallel. Used only as a finite stand-in for an ill-conditioned vertex.
pub(crate) fn regularised_meeting_point(planes: [&Plane; 3], anchor: DVec3, mu: f64) -> DVec3 {
    // Normal equations (A^T A + mu I) y = A^T r, y = x - anchor, r_m = n_m.(p_m - anchor).
    let mut m = [[0.0f64; 3]; 3];
    let mut rhs = [0.0f64; 3];
    for plane in planes {
        let n = plane.normal.to_array();
        let r = plane.normal.dot(plane.point - anchor);
        for i in 0..3 {
            rhs[i] += n[i] * r;
            for j in 0..3 {
                m[i][j] += n[i] * n[j];
            }
        }
    }
    for (i, row) in m.iter_mut().enumerate() {
        row[i] += mu;
    }
    let m = glam::DMat3::from_cols_array_2d(&m).transpose();
    let y = m.inverse() * DVec3::from_array(rhs);
    if y.is_finite() {
        anchor + y
    } else {
        anchor
    }
}
