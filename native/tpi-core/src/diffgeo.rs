//! Differential geometry at one point of a surface.
//!
//! With the derivatives of [`SurfaceDerivatives`] and the unit normal n = (Su x Sv) / |Su x Sv|
//! (orientation as Rhino's `NormalAt`):
//!
//! - first fundamental form  I  = [[E, F], [F, G]],  E = Su.Su, F = Su.Sv, G = Sv.Sv
//! - second fundamental form II = [[L, M], [M, N]],  L = Suu.n, M = Suv.n, N = Svv.n
//! - Gaussian curvature K = (LN - M^2) / (EG - F^2)
//! - mean curvature     H = (EN + GL - 2FM) / (2 (EG - F^2))
//!
//! Principal curvatures are the eigenvalues of the shape operator. To stay well defined at
//! umbilics they are computed in the orthonormal tangent frame a = Su / |Su|, b = n x a: with
//! J = [[|Su|, Sv.a], [0, Sv.b]] mapping (du, dv) to frame coordinates, the symmetric matrix
//! B = J^-T II J^-1 is diagonalised by one Jacobi rotation of angle
//! phi = atan2(2 B01, B00 - B11) / 2, never NaN. At an umbilic (k2 - k1 below
//! [`UMBILIC_RELATIVE_TOLERANCE`] of the curvature) the rotation is skipped: k1 = k2 and the
//! directions are a, b, deterministic rather than rounding noise.
//! Curvature signs are relative to n: k > 0 where the surface bends towards n.

use glam::DVec3;

use crate::planes::Plane;
use crate::surface::SurfaceDerivatives;
use crate::tolerance::{DEFAULT_FLAT_TOLERANCE, UMBILIC_RELATIVE_TOLERANCE};

/// Whether principal curvatures k1, k2 make a flat point (a plane, or a ruling of a
/// developable surface): |k1 k2| <= [`DEFAULT_FLAT_TOLERANCE`] max(|k1|, |k2|)^2, so K ~ 0
/// relative to the larger curvature (true where both vanish).
pub(crate) fn flat_curvatures(k1: f64, k2: f64) -> bool {
    let largest = k1.abs().max(k2.abs());
    (k1 * k2).abs() <= DEFAULT_FLAT_TOLERANCE * largest * largest
}

/// Curvature data at one surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalGeometry {
    /// Surface point.
    pub point: DVec3,
    /// Unit normal, Su x Sv normalised (a fallback where [`LocalGeometry::regular`] is false).
    pub normal: DVec3,
    /// First fundamental form (E, F, G).
    pub first_form: [f64; 3],
    /// Second fundamental form (L, M, N).
    pub second_form: [f64; 3],
    /// Smaller principal curvature k1 <= k2.
    pub k1: f64,
    /// Larger principal curvature.
    pub k2: f64,
    /// Unit principal direction of k1 (3D, tangent).
    pub d1: DVec3,
    /// Unit principal direction of k2; (d1, d2, normal) is right-handed.
    pub d2: DVec3,
    /// False where Su x Sv vanishes (a pole or a degenerate edge): the normal is then a
    /// fallback and the curvatures are reported as 0.
    pub regular: bool,
}

impl LocalGeometry {
    /// The tangent plane at the point.
    pub(crate) fn tangent_plane(&self) -> Plane {
        Plane {
            point: self.point,
            normal: self.normal,
        }
    }

    /// Gaussian curvature k1 k2.
    pub fn gaussian(&self) -> f64 {
        self.k1 * self.k2
    }

    /// Mean curvature (k1 + k2) / 2.
    pub fn mean(&self) -> f64 {
        0.5 * (self.k1 + self.k2)
    }

    /// Computes the local geometry from the derivatives of a surface at one point.
    pub fn from_derivatives(d: &SurfaceDerivatives) -> Self {
        let cross = d.su.cross(d.sv);
        let cross_len = cross.length();
        let su_len = d.su.length();
        let scale = su_len.max(d.sv.length());
        // Su x Sv vanishes (relative to |Su| |Sv|) only at poles and collapsed edges.
        if !(cross_len > 1e-14 * scale * scale) || !cross_len.is_finite() {
            let normal = fallback_normal(d);
            let (d1, d2) = tangent_basis(normal, d.su);
            return Self {
                point: d.point,
                normal,
                first_form: [d.su.dot(d.su), d.su.dot(d.sv), d.sv.dot(d.sv)],
                second_form: [0.0; 3],
                k1: 0.0,
                k2: 0.0,
                d1,
                d2,
                regular: false,
            };
        }
        let n = cross / cross_len;
        let e = d.su.dot(d.su);
        let f = d.su.dot(d.sv);
        let g = d.sv.dot(d.sv);
        let l = d.suu.dot(n);
        let m = d.suv.dot(n);
        let nn = d.svv.dot(n);

        let a = d.su / su_len;
        let b = n.cross(a);
        // J maps (du, dv) to coordinates in (a, b): [[j00, j01], [0, j11]].
        let j00 = su_len;
        let j01 = d.sv.dot(a);
        let j11 = d.sv.dot(b);
        // Jinv = [[1/j00, -j01/(j00 j11)], [0, 1/j11]]
        let i00 = 1.0 / j00;
        let i01 = -j01 / (j00 * j11);
        let i11 = 1.0 / j11;
        // B = Jinv^T II Jinv with II = [[l, m], [m, nn]].
        let t00 = l * i00;
        let t01 = l * i01 + m * i11;
        let t11 = m * i01 + nn * i11;
        let b00 = i00 * t00;
        let b01 = i00 * t01;
        let b11 = i01 * t01 + i11 * t11;

        // At an umbilic (k2 - k1 = |(B00 - B11, 2 B01)| negligible against the curvature
        // itself) every direction is principal; the rotation angle would only amplify rounding
        // noise, so the frame stays Su-aligned, as documented.
        let spread = (b00 - b11).hypot(2.0 * b01);
        let size = b00.abs().max(b11.abs()).max(b01.abs());
        if spread <= UMBILIC_RELATIVE_TOLERANCE * size {
            let k = 0.5 * (b00 + b11);
            return Self {
                point: d.point,
                normal: n,
                first_form: [e, f, g],
                second_form: [l, m, nn],
                k1: k,
                k2: k,
                d1: a,
                d2: b,
                regular: true,
            };
        }
        let phi = 0.5 * (2.0 * b01).atan2(b00 - b11);
        let (s, c) = phi.sin_cos();
        // Eigenvalues along the rotated axes.
        let along_first = c * c * b00 + 2.0 * s * c * b01 + s * s * b11;
        let along_second = s * s * b00 - 2.0 * s * c * b01 + c * c * b11;
        let first_dir = c * a + s * b;
        let second_dir = -s * a + c * b;
        let (k1, k2, d1) = if along_first <= along_second {
            (along_first, along_second, first_dir)
        } else {
            (along_second, along_first, second_dir)
        };
        let d2 = n.cross(d1);
        Self {
            point: d.point,
            normal: n,
            first_form: [e, f, g],
            second_form: [l, m, nn],
            k1,
            k2,
            d1,
            d2,
            regular: true,
        }
    }
}

/// A normal where Su x Sv vanishes: from the second derivatives if they help, else +z.
fn fallback_normal(d: &SurfaceDerivatives) -> DVec3 {
    let candidates = [
        d.su.cross(d.suv),
        d.suv.cross(d.sv),
        d.su.cross(d.svv),
        d.suu.cross(d.sv),
    ];
    for c in candidates {
        if let Some(n) = c.try_normalize() {
            return n;
        }
    }
    DVec3::Z
}

/// An orthonormal tangent pair (a, b) with a x b = normal, a as close to `hint` as possible.
fn tangent_basis(normal: DVec3, hint: DVec3) -> (DVec3, DVec3) {
    let projected = hint - normal * hint.dot(normal);
    let a = projected
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    (a, normal.cross(a))
}
