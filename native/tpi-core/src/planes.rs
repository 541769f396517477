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

use glam::DVec3;

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
