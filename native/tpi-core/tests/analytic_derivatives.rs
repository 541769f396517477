//! Points and derivatives of every analytic surface: exactly (1e-12) against closed forms
//! written here independently, and against central differences of the point (relative 1e-6).

use glam::DVec3;
use tpi_core::{AnalyticSurface, Surface, SurfaceDerivatives};

/// An independent closed form of the height and its derivatives.
type Closed = Box<dyn Fn(f64, f64) -> [f64; 6]>;

fn cases() -> Vec<(&'static str, AnalyticSurface, Closed)> {
    vec![
        (
            "elliptic paraboloid",
            AnalyticSurface::elliptic_paraboloid(1.0, 0.1, [-1.0, 1.5], [-2.0, 1.0]).unwrap(),
            Box::new(|x, y| [x * x + 0.1 * y * y, 2.0 * x, 0.2 * y, 2.0, 0.0, 0.2]),
        ),
        (
            "elliptic paraboloid, downwards",
            AnalyticSurface::elliptic_paraboloid(-0.5, -3.0, [0.5, 1.5], [-1.0, -0.25]).unwrap(),
            Box::new(|x, y| [-0.5 * x * x - 3.0 * y * y, -x, -6.0 * y, -1.0, 0.0, -6.0]),
        ),
        (
            "sphere cap",
            AnalyticSurface::sphere_cap(2.0, [-1.2, 1.0], [-0.9, 1.3]).unwrap(),
            Box::new(|x, y| {
                let r2: f64 = 4.0;
                let z = (r2 - x * x - y * y).sqrt();
                let z3 = z * z * z;
                [
                    z,
                    -x / z,
                    -y / z,
                    -1.0 / z - x * x / z3,
                    -x * y / z3,
                    -1.0 / z - y * y / z3,
                ]
            }),
        ),
        (
            "ellipsoid cap",
            AnalyticSurface::ellipsoid_cap(3.0, 2.0, 1.5, [-2.0, 2.0], [-1.0, 1.2]).unwrap(),
            Box::new(|x, y| {
                let (a, b, c): (f64, f64, f64) = (3.0, 2.0, 1.5);
                // z^2 / c^2 = 1 - x^2/a^2 - y^2/b^2, differentiated implicitly:
                // zx = -c^2 x / (a^2 z), zxx = -(c^2/a^2) (1/z + x zx / z^2 * (-1)) ...
                let z = c * (1.0 - x * x / (a * a) - y * y / (b * b)).sqrt();
                let (pa, pb) = (c * c / (a * a), c * c / (b * b));
                let zx = -pa * x / z;
                let zy = -pb * y / z;
                let zxx = -pa / z + pa * x * zx / (z * z);
                let zyy = -pb / z + pb * y * zy / (z * z);
                let zxy = pa * x * zy / (z * z);
                [z, zx, zy, zxx, zxy, zyy]
            }),
        ),
        (
            "hyperbolic paraboloid",
            AnalyticSurface::hyperbolic_paraboloid(0.5, 2.0, [-1.0, 1.0], [-1.0, 1.0]).unwrap(),
            Box::new(|x, y| [0.5 * x * x - 2.0 * y * y, x, -4.0 * y, 1.0, 0.0, -4.0]),
        ),
        (
            "egg crate",
            AnalyticSurface::egg_crate(0.7, [-3.0, 3.0], [-2.0, 4.0]).unwrap(),
            Box::new(|x, y| {
                let a = 0.7;
                [
                    a * x.sin() * y.sin(),
                    a * x.cos() * y.sin(),
                    a * x.sin() * y.cos(),
                    -a * x.sin() * y.sin(),
                    a * x.cos() * y.cos(),
                    -a * x.sin() * y.sin(),
                ]
            }),
        ),
        (
            "cylinder",
            AnalyticSurface::cylinder(1.5, [-1.2, 1.4], [-3.0, 3.0]).unwrap(),
            Box::new(|x, _y| {
                let r2: f64 = 2.25;
                let z = (r2 - x * x).sqrt();
                [z, -x / z, 0.0, -1.0 / z - x * x / (z * z * z), 0.0, 0.0]
            }),
        ),
        (
            "plane",
            AnalyticSurface::plane(0.25, -1.5, 2.0, [-1.0, 1.0], [0.0, 3.0]).unwrap(),
            Box::new(|x, y| [0.25 * x - 1.5 * y + 2.0, 0.25, -1.5, 0.0, 0.0, 0.0]),
        ),
    ]
}

fn samples(s: &AnalyticSurface, margin: f64) -> Vec<(f64, f64)> {
    let d = s.domain();
    let mut out = Vec::new();
    let n = 9;
    for i in 0..=n {
        for j in 0..=n {
            let a = margin + (1.0 - 2.0 * margin) * i as f64 / n as f64;
            let b = margin + (1.0 - 2.0 * margin) * j as f64 / n as f64;
            out.push((d.u.lerp(a), d.v.lerp(b)));
        }
    }
    out
}

fn close_vec(found: DVec3, expected: DVec3, rel: f64) -> bool {
    (found - expected).length() <= rel * expected.length().max(1.0)
}

#[test]
fn derivatives_match_closed_forms_exactly() {
    for (name, s, closed) in cases() {
        for (x, y) in samples(&s, 0.0) {
            let d = s.evaluate(x, y);
            let [f, fx, fy, fxx, fxy, fyy] = closed(x, y);
            let expected = SurfaceDerivatives {
                point: DVec3::new(x, y, f),
                su: DVec3::new(1.0, 0.0, fx),
                sv: DVec3::new(0.0, 1.0, fy),
                suu: DVec3::new(0.0, 0.0, fxx),
                suv: DVec3::new(0.0, 0.0, fxy),
                svv: DVec3::new(0.0, 0.0, fyy),
            };
            for (label, a, b) in [
                ("point", d.point, expected.point),
                ("su", d.su, expected.su),
                ("sv", d.sv, expected.sv),
                ("suu", d.suu, expected.suu),
                ("suv", d.suv, expected.suv),
                ("svv", d.svv, expected.svv),
            ] {
                assert!(
                    close_vec(a, b, 1e-12),
                    "{name} {label} at ({x}, {y}): {a:?} vs {b:?}"
                );
            }
            assert_eq!(
                s.point_at(x, y),
                d.point,
                "{name}: point_at agrees with evaluate"
            );
        }
    }
}

#[test]
fn derivatives_match_central_differences() {
    for (name, s, _) in cases() {
        let dom = s.domain();
        let scale = dom.u.length().max(dom.v.length());
        let h1 = 1e-4 * scale;
        let h2 = 1e-3 * scale;
        for (x, y) in samples(&s, 0.01) {
            let d = s.evaluate(x, y);
            let p = |u: f64, v: f64| s.point_at(u, v);
            // Central differences of the point, Richardson-extrapolated from steps h and h/2
            // (truncation O(h^4)) so that the comparison is limited by rounding only.
            let rich = |f: &dyn Fn(f64) -> DVec3, h: f64| (4.0 * f(0.5 * h) - f(h)) / 3.0;
            let su = rich(&|h| (p(x + h, y) - p(x - h, y)) / (2.0 * h), h1);
            let sv = rich(&|h| (p(x, y + h) - p(x, y - h)) / (2.0 * h), h1);
            let suu = rich(
                &|h| (p(x + h, y) - 2.0 * p(x, y) + p(x - h, y)) / (h * h),
                h2,
            );
            let svv = rich(
                &|h| (p(x, y + h) - 2.0 * p(x, y) + p(x, y - h)) / (h * h),
                h2,
            );
            let suv = rich(
                &|h| {
                    (p(x + h, y + h) - p(x + h, y - h) - p(x - h, y + h) + p(x - h, y - h))
                        / (4.0 * h * h)
                },
                h2,
            );
            for (label, found, fd) in [
                ("su", d.su, su),
                ("sv", d.sv, sv),
                ("suu", d.suu, suu),
                ("suv", d.suv, suv),
                ("svv", d.svv, svv),
            ] {
                assert!(
                    close_vec(fd, found, 1e-6),
                    "{name} {label} at ({x}, {y}): exact {found:?}, differences {fd:?}"
                );
            }
        }
    }
}

#[test]
fn normals_point_up_and_evaluation_clamps() {
    for (name, s, _) in cases() {
        let dom = s.domain();
        for (x, y) in samples(&s, 0.0) {
            let d = s.evaluate(x, y);
            assert!(d.su.cross(d.sv).z > 0.0, "{name}: Su x Sv points +z");
            for v in [d.point, d.su, d.sv, d.suu, d.suv, d.svv] {
                assert!(v.is_finite(), "{name}: finite at ({x}, {y})");
            }
        }
        // Outside the rectangle: evaluated at the clamped parameters, never NaN.
        let far = [
            (dom.u.min - 10.0, dom.v.max + 3.0),
            (dom.u.max + 1e9, dom.v.min - 1e9),
            (f64::INFINITY, f64::NEG_INFINITY),
        ];
        for (u, v) in far {
            let (cu, cv) = dom.clamp(u, v);
            assert_eq!(
                s.evaluate(u, v),
                s.evaluate(cu, cv),
                "{name}: clamped at ({u}, {v})"
            );
            assert!(s.evaluate(u, v).point.is_finite());
        }
    }
}

#[test]
fn corners_of_tight_caps_stay_finite() {
    // Rectangles whose corners come within a hair of the sphere, the ellipse, the strip.
    let h = 1.0 / 2f64.sqrt() * (1.0 - 1e-12);
    let s = AnalyticSurface::sphere_cap_square(1.0, h).unwrap();
    let e = AnalyticSurface::ellipsoid_cap(2.0, 1.0, 1.0, [-1.99999, 0.0], [0.0, 1e-3]).unwrap();
    let c = AnalyticSurface::cylinder(1.0, [-0.999999, 0.999999], [0.0, 1.0]).unwrap();
    for surface in [s, e, c] {
        let dom = surface.domain();
        for (u, v) in [
            (dom.u.min, dom.v.min),
            (dom.u.min, dom.v.max),
            (dom.u.max, dom.v.min),
            (dom.u.max, dom.v.max),
        ] {
            let d = surface.evaluate(u, v);
            for w in [d.point, d.su, d.sv, d.suu, d.suv, d.svv] {
                assert!(
                    w.is_finite(),
                    "{:?} at a corner ({u}, {v}): {d:?}",
                    surface.kind()
                );
            }
        }
    }
}
