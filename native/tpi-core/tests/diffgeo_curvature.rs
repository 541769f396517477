//! Curvature of the analytic surfaces through `LocalGeometry::from_derivatives`, against closed
//! forms written here independently of the code under test.
//!
//! For a graph z = f(x, y) (Monge patch) with W = sqrt(1 + fx^2 + fy^2) and the +z-ish normal
//! n = (-fx, -fy, 1) / W:
//!   K = (fxx fyy - fxy^2) / W^4
//!   H = ((1 + fy^2) fxx - 2 fx fy fxy + (1 + fx^2) fyy) / (2 W^3)
//!   k1, k2 = H -/+ sqrt(H^2 - K)
//! and a principal direction d (3D, tangent) satisfies Rodrigues' condition dN(d) = -k d, where
//! for d = alpha Su + beta Sv (alpha = d.x, beta = d.y on a graph) dN(d) = alpha Nx + beta Ny.

use glam::DVec3;
use tpi_core::{AnalyticSurface, LocalGeometry, Surface};

/// Closed-form height derivatives (f, fx, fy, fxx, fxy, fyy), written independently.
type Jet = [f64; 6];

fn sphere_jet(r: f64, x: f64, y: f64) -> Jet {
    let z = (r * r - x * x - y * y).sqrt();
    // d/dx of -x/z = -1/z - x^2/z^3
    let fxx = -1.0 / z - x * x / z.powi(3);
    let fyy = -1.0 / z - y * y / z.powi(3);
    let fxy = -x * y / z.powi(3);
    [z, -x / z, -y / z, fxx, fxy, fyy]
}

fn paraboloid_jet(a: f64, b: f64, x: f64, y: f64) -> Jet {
    [
        a * x * x + b * y * y,
        2.0 * a * x,
        2.0 * b * y,
        2.0 * a,
        0.0,
        2.0 * b,
    ]
}

fn hypar_jet(a: f64, b: f64, x: f64, y: f64) -> Jet {
    [
        a * x * x - b * y * y,
        2.0 * a * x,
        -2.0 * b * y,
        2.0 * a,
        0.0,
        -2.0 * b,
    ]
}

fn ellipsoid_jet(a: f64, b: f64, c: f64, x: f64, y: f64) -> Jet {
    let g = 1.0 - (x / a).powi(2) - (y / b).powi(2);
    let s = g.sqrt();
    let fx = -c * x / (a * a * s);
    let fy = -c * y / (b * b * s);
    let fxx = -c / (a * a * s) - c * x * x / (a.powi(4) * s.powi(3));
    let fyy = -c / (b * b * s) - c * y * y / (b.powi(4) * s.powi(3));
    let fxy = -c * x * y / (a * a * b * b * s.powi(3));
    [c * s, fx, fy, fxx, fxy, fyy]
}

fn egg_jet(amp: f64, x: f64, y: f64) -> Jet {
    let f = amp * x.sin() * y.sin();
    [
        f,
        amp * x.cos() * y.sin(),
        amp * x.sin() * y.cos(),
        -f,
        amp * x.cos() * y.cos(),
        -f,
    ]
}

fn cylinder_jet(r: f64, x: f64) -> Jet {
    let z = (r * r - x * x).sqrt();
    [z, -x / z, 0.0, -1.0 / z - x * x / z.powi(3), 0.0, 0.0]
}

/// (k1, k2, K, H) from the Monge-patch formulas.
fn monge_curvatures(j: &Jet) -> (f64, f64, f64, f64) {
    let [_, fx, fy, fxx, fxy, fyy] = *j;
    let w2 = 1.0 + fx * fx + fy * fy;
    let k = (fxx * fyy - fxy * fxy) / (w2 * w2);
    let h = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy)
        / (2.0 * w2.powf(1.5));
    let disc = (h * h - k).max(0.0).sqrt();
    (h - disc, h + disc, k, h)
}

/// Derivatives of the unit normal along x and along y, closed form.
fn normal_derivatives(j: &Jet) -> (DVec3, DVec3) {
    let [_, fx, fy, fxx, fxy, fyy] = *j;
    let w = (1.0 + fx * fx + fy * fy).sqrt();
    let m = DVec3::new(-fx, -fy, 1.0);
    let wx = (fx * fxx + fy * fxy) / w;
    let wy = (fx * fxy + fy * fyy) / w;
    let nx = DVec3::new(-fxx, -fxy, 0.0) / w - m * wx / (w * w);
    let ny = DVec3::new(-fxy, -fyy, 0.0) / w - m * wy / (w * w);
    (nx, ny)
}

fn close(found: f64, expected: f64, tol: f64) -> bool {
    (found - expected).abs() <= tol * expected.abs().max(1.0)
}

/// Checks k1, k2, K, H, the directions (Rodrigues), orthonormality and handedness.
fn check_point(s: &AnalyticSurface, x: f64, y: f64, jet: Jet, label: &str) -> LocalGeometry {
    let g = LocalGeometry::from_derivatives(&s.evaluate(x, y));
    let (k1, k2, k, h) = monge_curvatures(&jet);
    let tol = 1e-9;
    assert!(g.regular, "{label}: regular");
    // k = H -/+ sqrt(H^2 - K) loses half the digits near an umbilic (the oracle, not the code
    // under test): there the pair is checked through K and H, which determine it.
    let separated = h * h - k > 1e-12 * h * h;
    if separated {
        assert!(
            close(g.k1, k1, tol),
            "{label} at ({x}, {y}): k1 {} vs {k1}",
            g.k1
        );
        assert!(
            close(g.k2, k2, tol),
            "{label} at ({x}, {y}): k2 {} vs {k2}",
            g.k2
        );
    } else {
        assert!(
            close(g.k1, h, 1e-6) && close(g.k2, h, 1e-6),
            "{label}: umbilic k = H"
        );
    }
    assert!(
        close(g.gaussian(), k, tol),
        "{label}: K {} vs {k}",
        g.gaussian()
    );
    assert!(close(g.mean(), h, tol), "{label}: H {} vs {h}", g.mean());
    assert!(g.k1 <= g.k2, "{label}: k1 <= k2");
    let n_expected = DVec3::new(-jet[1], -jet[2], 1.0).normalize();
    assert!((g.normal - n_expected).length() < 1e-12, "{label}: normal");
    check_frame(&g, label);
    let (nx, ny) = normal_derivatives(&jet);
    // Rodrigues only pins the direction where k1 != k2 (at an umbilic every direction works).
    for (d, kk, name) in [(g.d1, g.k1, "d1"), (g.d2, g.k2, "d2")] {
        let dn = nx * d.x + ny * d.y;
        let residual = (dn + kk * d).length();
        assert!(
            residual < tol * kk.abs().max(1.0),
            "{label} at ({x}, {y}): Rodrigues for {name}: |dN(d) + k d| = {residual:e}"
        );
        // The same direction as a normal-curvature ratio II(d)/I(d) = k.
        let (alpha, beta) = (d.x, d.y);
        let [e, f, gg] = g.first_form;
        let [l, m, nn] = g.second_form;
        let ratio = (l * alpha * alpha + 2.0 * m * alpha * beta + nn * beta * beta)
            / (e * alpha * alpha + 2.0 * f * alpha * beta + gg * beta * beta);
        assert!(close(ratio, kk, tol), "{label}: II(d)/I(d) {ratio} vs {kk}");
    }
    g
}

fn check_frame(g: &LocalGeometry, label: &str) {
    for v in [g.d1, g.d2, g.normal] {
        assert!(v.is_finite(), "{label}: finite frame");
        assert!((v.length() - 1.0).abs() < 1e-12, "{label}: unit vectors");
    }
    assert!(g.d1.dot(g.d2).abs() < 1e-12, "{label}: d1 . d2 = 0");
    assert!(g.d1.dot(g.normal).abs() < 1e-12, "{label}: d1 tangent");
    assert!(g.d2.dot(g.normal).abs() < 1e-12, "{label}: d2 tangent");
    assert!(
        (g.d1.cross(g.d2) - g.normal).length() < 1e-12,
        "{label}: (d1, d2, n) right-handed"
    );
    assert!(
        g.k1.is_finite() && g.k2.is_finite(),
        "{label}: finite curvatures"
    );
}

fn grid(x: [f64; 2], y: [f64; 2], n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            out.push((
                x[0] + (x[1] - x[0]) * i as f64 / n as f64,
                y[0] + (y[1] - y[0]) * j as f64 / n as f64,
            ));
        }
    }
    out
}

#[test]
fn sphere_has_k_minus_one_over_r_everywhere_and_a_valid_frame() {
    for r in [0.5, 1.0, 3.0, 250.0] {
        let h = 0.7 * r;
        let s = AnalyticSurface::sphere_cap_square(r, h).unwrap();
        for (x, y) in grid([-h, h], [-h, h], 8) {
            let g = check_point(&s, x, y, sphere_jet(r, x, y), "sphere");
            // The outward (+z) normal: the sphere bends away from it.
            assert!(
                close(g.k1, -1.0 / r, 1e-9) && close(g.k2, -1.0 / r, 1e-9),
                "sphere k = -1/r"
            );
            assert!(close(g.gaussian(), 1.0 / (r * r), 1e-9));
        }
    }
}

#[test]
fn umbilic_frames_are_su_aligned() {
    // An umbilic has no preferred direction; the documented choice is d1 along Su.
    // Up to a corner at 0.99995 r, where the slope is about 70.
    let h = 1.4141;
    let s = AnalyticSurface::sphere_cap_square(2.0, h).unwrap();
    for (x, y) in grid([-h, h], [-h, h], 10) {
        let d = s.evaluate(x, y);
        let g = LocalGeometry::from_derivatives(&d);
        let su = d.su.normalize();
        assert!(
            (g.d1 - su).length() < 1e-9,
            "sphere at ({x}, {y}): d1 {:?} vs Su {su:?}",
            g.d1
        );
    }
    let p = AnalyticSurface::elliptic_paraboloid(0.7, 0.7, [-1.0, 1.0], [-1.0, 1.0]).unwrap();
    let g = LocalGeometry::from_derivatives(&p.evaluate(0.0, 0.0));
    check_frame(&g, "paraboloid of revolution apex");
    assert!((g.d1 - DVec3::X).length() < 1e-12 && (g.d2 - DVec3::Y).length() < 1e-12);
    assert_eq!((g.k1, g.k2), (1.4, 1.4));
}

#[test]
fn paraboloid_apex_curvatures_and_directions() {
    for (a, b) in [
        (1.0, 0.1),
        (0.1, 1.0),
        (0.5, 2.0),
        (-1.0, -0.25),
        (3.0, 3.0),
        (1e-3, 4.0),
    ] {
        let s = AnalyticSurface::elliptic_paraboloid(a, b, [-1.0, 1.0], [-1.0, 1.0]).unwrap();
        let g = check_point(
            &s,
            0.0,
            0.0,
            paraboloid_jet(a, b, 0.0, 0.0),
            "paraboloid apex",
        );
        let (lo, hi) = if 2.0 * a <= 2.0 * b {
            (2.0 * a, 2.0 * b)
        } else {
            (2.0 * b, 2.0 * a)
        };
        assert!(
            close(g.k1, lo, 1e-12) && close(g.k2, hi, 1e-12),
            "apex k = 2a, 2b for a={a} b={b}"
        );
        if a != b {
            let (e1, e2) = if a < b {
                (DVec3::X, DVec3::Y)
            } else {
                (DVec3::Y, DVec3::X)
            };
            assert!(
                (g.d1.dot(e1).abs() - 1.0).abs() < 1e-12,
                "d1 along {e1:?} for a={a} b={b}: {:?}",
                g.d1
            );
            assert!((g.d2.dot(e2).abs() - 1.0).abs() < 1e-12, "d2 along {e2:?}");
        }
    }
}

#[test]
fn paraboloid_off_apex_matches_monge_formulas() {
    for (a, b) in [(1.0, 0.1), (0.3, 0.7), (-0.5, -2.0), (0.8, 0.8)] {
        let s = AnalyticSurface::elliptic_paraboloid(a, b, [-1.5, 2.0], [-1.0, 1.25]).unwrap();
        for (x, y) in grid([-1.5, 2.0], [-1.0, 1.25], 7) {
            check_point(&s, x, y, paraboloid_jet(a, b, x, y), "paraboloid");
        }
    }
}

#[test]
fn ellipsoid_matches_closed_forms() {
    let (a, b, c) = (2.0, 1.0, 0.5);
    let s = AnalyticSurface::ellipsoid_cap(a, b, c, [-1.3, 1.3], [-0.7, 0.6]).unwrap();
    for (x, y) in grid([-1.3, 1.3], [-0.7, 0.6], 7) {
        let jet = ellipsoid_jet(a, b, c, x, y);
        let g = check_point(&s, x, y, jet, "ellipsoid");
        // The classical ellipsoid formula K = 1 / (a^2 b^2 c^2 (x^2/a^4 + y^2/b^4 + z^2/c^4)^2).
        let z = jet[0];
        let q = x * x / a.powi(4) + y * y / b.powi(4) + z * z / c.powi(4);
        let k = 1.0 / (a * a * b * b * c * c * q * q);
        assert!(
            close(g.gaussian(), k, 1e-9),
            "ellipsoid K {} vs {k}",
            g.gaussian()
        );
        assert!(
            g.k1 < 0.0 && g.k2 < 0.0,
            "the cap bends away from the +z normal"
        );
    }
    // At the top: k = -c/a^2 and -c/b^2 along x and y.
    let g = LocalGeometry::from_derivatives(&s.evaluate(0.0, 0.0));
    assert!(close(g.k1, -c / (b * b), 1e-12) && close(g.k2, -c / (a * a), 1e-12));
    assert!((g.d1.dot(DVec3::Y).abs() - 1.0).abs() < 1e-12);
}

#[test]
fn hyperbolic_paraboloid_matches_closed_forms() {
    for (a, b) in [(1.0, 1.0), (0.5, 2.0), (-0.3, -0.1)] {
        let s = AnalyticSurface::hyperbolic_paraboloid(a, b, [-1.0, 1.0], [-2.0, 0.5]).unwrap();
        for (x, y) in grid([-1.0, 1.0], [-2.0, 0.5], 7) {
            let g = check_point(&s, x, y, hypar_jet(a, b, x, y), "hyperbolic paraboloid");
            assert!(g.gaussian() < 0.0, "K < 0");
        }
        let g = LocalGeometry::from_derivatives(&s.evaluate(0.0, 0.0));
        let (lo, hi) = if a > 0.0 {
            (-2.0 * b, 2.0 * a)
        } else {
            (2.0 * a, -2.0 * b)
        };
        assert!(
            close(g.k1, lo, 1e-12) && close(g.k2, hi, 1e-12),
            "saddle point k = 2a, -2b"
        );
    }
}

#[test]
fn egg_crate_cylinder_and_plane() {
    let s = AnalyticSurface::egg_crate(0.8, [-3.0, 3.0], [-3.0, 3.0]).unwrap();
    let mut signs = (false, false);
    for (x, y) in grid([-3.0, 3.0], [-3.0, 3.0], 9) {
        let g = check_point(&s, x, y, egg_jet(0.8, x, y), "egg crate");
        signs.0 |= g.gaussian() > 1e-3;
        signs.1 |= g.gaussian() < -1e-3;
    }
    assert!(signs.0 && signs.1, "egg crate has both curvature signs");

    let r = 1.5;
    let c = AnalyticSurface::cylinder(r, [-1.2, 1.4], [-5.0, 5.0]).unwrap();
    for (x, y) in grid([-1.2, 1.4], [-5.0, 5.0], 6) {
        let g = check_point(&c, x, y, cylinder_jet(r, x), "cylinder");
        assert!(
            close(g.k1, -1.0 / r, 1e-9) && g.k2.abs() < 1e-12,
            "cylinder k = -1/r, 0"
        );
        assert!(g.gaussian().abs() < 1e-12, "developable");
        assert!(
            (g.d2.dot(DVec3::Y).abs() - 1.0).abs() < 1e-12,
            "zero curvature along the axis"
        );
    }

    let p = AnalyticSurface::plane(0.3, -0.2, 1.0, [0.0, 1.0], [0.0, 1.0]).unwrap();
    for (x, y) in grid([0.0, 1.0], [0.0, 1.0], 3) {
        let g = check_point(&p, x, y, [0.0, 0.3, -0.2, 0.0, 0.0, 0.0], "plane");
        assert_eq!((g.k1, g.k2), (0.0, 0.0));
    }
}

#[test]
fn degenerate_derivatives_give_a_finite_frame() {
    // A collapsed parameter direction (Sv = 0), as at a pole: no NaN, flagged irregular.
    let d = tpi_core::SurfaceDerivatives {
        point: DVec3::ZERO,
        su: DVec3::X,
        sv: DVec3::ZERO,
        suu: DVec3::Z,
        suv: DVec3::Y,
        svv: DVec3::ZERO,
    };
    let g = LocalGeometry::from_derivatives(&d);
    assert!(!g.regular);
    check_frame(&g, "pole");
}
