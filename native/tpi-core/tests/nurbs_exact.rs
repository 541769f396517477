//! NURBS surfaces whose point and derivatives are known in closed form: a bilinear patch, a
//! planar patch, the paraboloid z = x^2 + y^2 as a degree (2, 2) Bezier patch and as B-splines of
//! any degree on non-uniform knots (polynomial precision), and exact circles from rational
//! quadratic arcs (a quarter cylinder and a full cylinder with double knots).

use glam::DVec3;
use tpi_core::{NurbsSurface, Surface, SurfaceDerivatives};

/// Closed forms agree to this (absolute, on surfaces of unit size; relative to the point's
/// magnitude where coordinates grow).
const EXACT: f64 = 1e-12;

fn assert_derivatives(
    label: &str,
    uv: (f64, f64),
    found: &SurfaceDerivatives,
    expected: &SurfaceDerivatives,
    scale: f64,
) {
    let pairs = [
        ("point", found.point, expected.point),
        ("Su", found.su, expected.su),
        ("Sv", found.sv, expected.sv),
        ("Suu", found.suu, expected.suu),
        ("Suv", found.suv, expected.suv),
        ("Svv", found.svv, expected.svv),
    ];
    for (what, found, expected) in pairs {
        let error = (found - expected).length();
        assert!(
            error <= EXACT * scale,
            "{label}: {what} at {uv:?} = {found}, closed form {expected}, error {error:e}"
        );
    }
}

/// A grid of parameters over [u0, u1] x [v0, v1], corners and edges included.
fn parameter_grid(u: (f64, f64), v: (f64, f64), steps: usize) -> Vec<(f64, f64)> {
    let mut grid = Vec::new();
    for i in 0..=steps {
        for j in 0..=steps {
            let (s, t) = (i as f64 / steps as f64, j as f64 / steps as f64);
            grid.push((u.0 + s * (u.1 - u.0), v.0 + t * (v.1 - v.0)));
        }
    }
    grid
}

#[test]
fn bilinear_patch_matches_its_closed_form() {
    let (u0, u1, v0, v1) = (2.5, 4.0, -3.0, -1.0);
    let (lu, lv) = (u1 - u0, v1 - v0);
    let p00 = DVec3::new(0.0, 0.0, 0.1);
    let p01 = DVec3::new(0.1, 1.0, -0.3);
    let p10 = DVec3::new(1.2, -0.1, 0.4);
    let p11 = DVec3::new(0.9, 1.1, 0.8);
    // Point (i, j) at i * nv + j.
    let points = [p00, p01, p10, p11];
    for weights in [None, Some([2.5; 4])] {
        let surface = NurbsSurface::new(
            [1, 1],
            [2, 2],
            &[u0, u1],
            &[v0, v1],
            &points,
            weights.as_ref().map(|w| &w[..]),
        )
        .expect("a valid bilinear patch");
        for (u, v) in parameter_grid((u0, u1), (v0, v1), 8) {
            let (s, t) = ((u - u0) / lu, (v - v0) / lv);
            let expected = SurfaceDerivatives {
                point: (1.0 - s) * (1.0 - t) * p00
                    + s * (1.0 - t) * p10
                    + (1.0 - s) * t * p01
                    + s * t * p11,
                su: ((1.0 - t) * (p10 - p00) + t * (p11 - p01)) / lu,
                sv: ((1.0 - s) * (p01 - p00) + s * (p11 - p10)) / lv,
                suu: DVec3::ZERO,
                suv: (p11 - p10 - p01 + p00) / (lu * lv),
                svv: DVec3::ZERO,
            };
            assert_derivatives("bilinear", (u, v), &surface.evaluate(u, v), &expected, 1.0);
        }
    }
}

#[test]
fn planar_patch_stays_in_its_plane() {
    // A degree (3, 2) rational patch whose control points all lie in one plane.
    let origin = DVec3::new(1.0, -2.0, 0.5);
    let e1 = DVec3::new(0.6, 0.8, 0.0);
    let e2 = DVec3::new(-0.48, 0.36, 0.8);
    let normal = e1.cross(e2).normalize();
    let (nu, nv) = (5, 4);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (a, b) = (
                i as f64 + 0.3 * ((i * j) as f64).sin(),
                j as f64 + 0.2 * (i as f64).cos(),
            );
            points.push(origin + a * e1 + b * e2);
            weights.push(0.5 + 0.25 * ((i + 2 * j) % 5) as f64);
        }
    }
    let knots_u = [10.0, 10.0, 10.0, 10.5, 13.0, 13.0, 13.0];
    let knots_v = [-4.0, -4.0, -3.2, -1.0, -1.0];
    let surface = NurbsSurface::new(
        [3, 2],
        [nu, nv],
        &knots_u,
        &knots_v,
        &points,
        Some(&weights),
    )
    .expect("a valid planar patch");
    for (u, v) in parameter_grid((10.0, 13.0), (-4.0, -1.0), 12) {
        let d = surface.evaluate(u, v);
        assert!(
            normal.dot(d.point - origin).abs() <= EXACT,
            "point off the plane at ({u}, {v})"
        );
        for (what, vector) in [
            ("Su", d.su),
            ("Sv", d.sv),
            ("Suu", d.suu),
            ("Suv", d.suv),
            ("Svv", d.svv),
        ] {
            assert!(
                normal.dot(vector).abs() <= EXACT * vector.length().max(1.0),
                "{what} leaves the plane at ({u}, {v})"
            );
        }
        let surface_normal = d.su.cross(d.sv).normalize();
        assert!(
            (surface_normal - normal).length() <= EXACT,
            "normal {surface_normal} at ({u}, {v})"
        );
    }
}

/// z = x^2 + y^2 over [x0, x1] x [y0, y1] as a degree (2, 2) Bezier patch: along x the control
/// abscissae x0, (x0 + x1) / 2, x1 and heights x0^2, x0 x1 (the tangents' intersection), x1^2;
/// the same along y; the heights add because the Bernstein polynomials sum to 1.
#[test]
fn bezier_paraboloid_matches_its_closed_form() {
    let (x0, x1, y0, y1) = (-1.0, 1.5, -0.5, 2.0);
    let (u0, u1, v0, v1) = (3.0, 5.0, -7.0, -6.0);
    let (lu, lv) = (u1 - u0, v1 - v0);
    let xs = [x0, 0.5 * (x0 + x1), x1];
    let hx = [x0 * x0, x0 * x1, x1 * x1];
    let ys = [y0, 0.5 * (y0 + y1), y1];
    let hy = [y0 * y0, y0 * y1, y1 * y1];
    let mut points = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            points.push(DVec3::new(xs[i], ys[j], hx[i] + hy[j]));
        }
    }
    let rhino = ([u0, u0, u1, u1], [v0, v0, v1, v1]);
    let textbook = ([u0, u0, u0, u1, u1, u1], [v0, v0, v0, v1, v1, v1]);
    for (knots_u, knots_v) in [
        (&rhino.0[..], &rhino.1[..]),
        (&textbook.0[..], &textbook.1[..]),
    ] {
        let surface = NurbsSurface::new([2, 2], [3, 3], knots_u, knots_v, &points, None)
            .expect("a valid Bezier patch");
        for (u, v) in parameter_grid((u0, u1), (v0, v1), 10) {
            let x = x0 + (x1 - x0) * (u - u0) / lu;
            let y = y0 + (y1 - y0) * (v - v0) / lv;
            let (dx, dy) = ((x1 - x0) / lu, (y1 - y0) / lv);
            let expected = SurfaceDerivatives {
                point: DVec3::new(x, y, x * x + y * y),
                su: dx * DVec3::new(1.0, 0.0, 2.0 * x),
                sv: dy * DVec3::new(0.0, 1.0, 2.0 * y),
                suu: DVec3::new(0.0, 0.0, 2.0 * dx * dx),
                suv: DVec3::ZERO,
                svv: DVec3::new(0.0, 0.0, 2.0 * dy * dy),
            };
            assert_derivatives(
                "Bezier paraboloid",
                (u, v),
                &surface.evaluate(u, v),
                &expected,
                1.0,
            );
        }
    }
}

/// The control coefficients that reproduce 1, t and t^2 with the B-splines of `degree` on the
/// textbook knot vector U (Marsden's identity): for basis function i, with U_(i+1) .. U_(i+p),
/// t = sum_i xi_i N_i (Greville abscissa xi_i = mean of those knots) and
/// t^2 = sum_i c_i N_i (c_i = their pairwise products' mean).
fn polynomial_coefficients(
    full_knots: &[f64],
    degree: usize,
    count: usize,
) -> (Vec<f64>, Vec<f64>) {
    let mut linear = Vec::with_capacity(count);
    let mut quadratic = Vec::with_capacity(count);
    for i in 0..count {
        let window = &full_knots[i + 1..=i + degree];
        linear.push(window.iter().sum::<f64>() / degree as f64);
        let mut products = 0.0;
        for a in 0..degree {
            for b in a + 1..degree {
                products += window[a] * window[b];
            }
        }
        let pairs = (degree * (degree - 1) / 2) as f64;
        quadratic.push(if degree >= 2 {
            products / pairs
        } else {
            f64::NAN
        });
    }
    (linear, quadratic)
}

/// Polynomial precision on non-uniform knots with repeated interior knots, clamped or not, for
/// every degree 1..=MAX_NURBS_DEGREE, rational with equal weights or not: with the Marsden
/// coefficients the surface is exactly S(u, v) = (u, v, u^2 + v^2) (degrees >= 2) or
/// (u, v, u v) (degree 1 in either direction).
#[test]
fn polynomial_precision_holds_for_every_degree() {
    for degree in 1..=tpi_core::tolerance::MAX_NURBS_DEGREE {
        for (clamped, rational) in [(true, false), (false, true)] {
            let degree_v = 1 + (degree * 7) % tpi_core::tolerance::MAX_NURBS_DEGREE;
            let degrees = [degree, degree_v];
            let counts = [degree + 4, degree_v + 3];
            let full_knots: Vec<Vec<f64>> = (0..2)
                .map(|direction| {
                    let (p, n) = (degrees[direction], counts[direction]);
                    // Domain [-1.25, 1.75] in u and [0.5, 2.0] in v, uneven interior knots, one of
                    // them repeated when the degree allows it.
                    let (start, end) = if direction == 0 {
                        (-1.25, 1.75)
                    } else {
                        (0.5, 2.0)
                    };
                    let interior_count = n - p - 1;
                    let mut interior: Vec<f64> = (1..=interior_count)
                        .map(|k| {
                            start
                                + (end - start) * (k as f64 / (interior_count + 1) as f64).powf(1.3)
                        })
                        .collect();
                    if p >= 2 && interior_count >= 2 {
                        interior[1] = interior[0];
                    }
                    let outside = |k: usize| if clamped { 0.0 } else { 0.1 * k as f64 + 0.05 };
                    let mut knots: Vec<f64> = (0..=p).rev().map(|k| start - outside(k)).collect();
                    knots.extend(interior);
                    knots.extend((0..=p).map(|k| end + outside(k)));
                    assert_eq!(knots.len(), n + p + 1);
                    knots
                })
                .collect();
            let (xu, cu) = polynomial_coefficients(&full_knots[0], degrees[0], counts[0]);
            let (xv, cv) = polynomial_coefficients(&full_knots[1], degrees[1], counts[1]);
            let bilinear = degrees[0] == 1 || degrees[1] == 1;
            let mut points = Vec::new();
            for i in 0..counts[0] {
                for j in 0..counts[1] {
                    let height = if bilinear {
                        xu[i] * xv[j]
                    } else {
                        cu[i] + cv[j]
                    };
                    points.push(DVec3::new(xu[i], xv[j], height));
                }
            }
            let weights = vec![1.7; points.len()];
            let surface = NurbsSurface::new(
                degrees,
                counts,
                &full_knots[0],
                &full_knots[1],
                &points,
                rational.then_some(&weights[..]),
            )
            .unwrap_or_else(|e| panic!("degree {degrees:?}: {e}"));
            let domain = surface.domain();
            let label = format!("degree {degrees:?}, clamped {clamped}, rational {rational}");
            let mut parameters = parameter_grid(
                (domain.u.min, domain.u.max),
                (domain.v.min, domain.v.max),
                9,
            );
            // Exactly on the interior knots too.
            for &ku in &full_knots[0][degrees[0] + 1..counts[0]] {
                parameters.push((ku, domain.v.lerp(0.3)));
            }
            for (u, v) in parameters {
                let expected = if bilinear {
                    SurfaceDerivatives {
                        point: DVec3::new(u, v, u * v),
                        su: DVec3::new(1.0, 0.0, v),
                        sv: DVec3::new(0.0, 1.0, u),
                        suu: DVec3::ZERO,
                        suv: DVec3::new(0.0, 0.0, 1.0),
                        svv: DVec3::ZERO,
                    }
                } else {
                    SurfaceDerivatives {
                        point: DVec3::new(u, v, u * u + v * v),
                        su: DVec3::new(1.0, 0.0, 2.0 * u),
                        sv: DVec3::new(0.0, 1.0, 2.0 * v),
                        suu: DVec3::new(0.0, 0.0, 2.0),
                        suv: DVec3::ZERO,
                        svv: DVec3::new(0.0, 0.0, 2.0),
                    }
                };
                // Second-derivative basis coefficients grow like degree^2, and so does their
                // rounding: 1e-12 up to degree 5, scaled by (degree / 5)^2 beyond.
                let scale = (degree.max(degree_v) as f64 / 5.0).powi(2).max(1.0);
                assert_derivatives(&label, (u, v), &surface.evaluate(u, v), &expected, scale);
            }
        }
    }
}

/// The rational quadratic quarter circle of radius r from (r, 0) to (0, r): control points (r, 0),
/// (r, r), (0, r) with weights 1, sqrt(2)/2, 1. With t in [0, 1] and c = sqrt(2)/2:
/// x = r (1 + (2c - 2) t + (1 - 2c) t^2) / w, y = r (2c t + (1 - 2c) t^2) / w,
/// w = 1 + (2c - 2) t + (2 - 2c) t^2.
fn quarter_circle(t: f64, r: f64) -> [DVec3; 3] {
    let c = std::f64::consts::FRAC_1_SQRT_2;
    // Numerators and weight as polynomials [a0, a1, a2] in t.
    let nx = [1.0, 2.0 * c - 2.0, 1.0 - 2.0 * c];
    let ny = [0.0, 2.0 * c, 1.0 - 2.0 * c];
    let w = [1.0, 2.0 * c - 2.0, 2.0 - 2.0 * c];
    let value = |a: [f64; 3]| a[0] + a[1] * t + a[2] * t * t;
    let first = |a: [f64; 3]| a[1] + 2.0 * a[2] * t;
    let second = |a: [f64; 3]| 2.0 * a[2];
    let quotient = |n: [f64; 3]| {
        let (f, f1, f2) = (value(n), first(n), second(n));
        let (g, g1, g2) = (value(w), first(w), second(w));
        let q = f / g;
        let q1 = (f1 * g - f * g1) / (g * g);
        let q2 = (f2 * g - f * g2) / (g * g) - 2.0 * g1 * (f1 * g - f * g1) / (g * g * g);
        [q, q1, q2]
    };
    let (x, y) = (quotient(nx), quotient(ny));
    [
        r * DVec3::new(x[0], y[0], 0.0),
        r * DVec3::new(x[1], y[1], 0.0),
        r * DVec3::new(x[2], y[2], 0.0),
    ]
}

#[test]
fn rational_quarter_cylinder_is_exact() {
    let r = 2.75;
    let c = std::f64::consts::FRAC_1_SQRT_2;
    let (z0, z1) = (-0.5, 1.5);
    let (u0, u1, v0, v1) = (1.5, 4.0, -2.0, 3.0);
    let (lu, lv) = (u1 - u0, v1 - v0);
    let arc = [
        DVec3::new(r, 0.0, 0.0),
        DVec3::new(r, r, 0.0),
        DVec3::new(0.0, r, 0.0),
    ];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for (i, p) in arc.iter().enumerate() {
        for z in [z0, z1] {
            points.push(*p + DVec3::new(0.0, 0.0, z));
            weights.push(if i == 1 { c } else { 1.0 });
        }
    }
    let surface = NurbsSurface::new(
        [2, 1],
        [3, 2],
        &[u0, u0, u1, u1],
        &[v0, v1],
        &points,
        Some(&weights),
    )
    .expect("a valid quarter cylinder");
    for (u, v) in parameter_grid((u0, u1), (v0, v1), 16) {
        let d = surface.evaluate(u, v);
        let t = (u - u0) / lu;
        let [xy, xy1, xy2] = quarter_circle(t, r);
        let z = z0 + (z1 - z0) * (v - v0) / lv;
        let expected = SurfaceDerivatives {
            point: xy + DVec3::new(0.0, 0.0, z),
            su: xy1 / lu,
            sv: DVec3::new(0.0, 0.0, (z1 - z0) / lv),
            suu: xy2 / (lu * lu),
            suv: DVec3::ZERO,
            svv: DVec3::ZERO,
        };
        assert_derivatives("quarter cylinder", (u, v), &d, &expected, r);

        // Independently of the closed form: on the circle, tangent to it, and |S|^2 = r^2
        // differentiated twice: S.Suu + |Su|^2 = 0 (in the xy plane).
        let planar = |a: DVec3| DVec3::new(a.x, a.y, 0.0);
        let (p, pu, puu) = (planar(d.point), planar(d.su), planar(d.suu));
        assert!(
            (p.length() - r).abs() <= EXACT * r,
            "radius {} at u = {u}",
            p.length()
        );
        assert!(
            p.dot(pu).abs() <= EXACT * r * pu.length(),
            "tangent not perpendicular at u = {u}"
        );
        assert!(
            (p.dot(puu) + pu.length_squared()).abs() <= EXACT * r * puu.length(),
            "curvature identity at u = {u}"
        );
        assert!(
            d.point.x >= -EXACT && d.point.y >= -EXACT,
            "outside the first quadrant at u = {u}"
        );
    }
    // The arc runs from (r, 0) to (0, r).
    assert!((surface.point_at(u0, v0) - DVec3::new(r, 0.0, z0)).length() <= EXACT);
    assert!((surface.point_at(u1, v1) - DVec3::new(0.0, r, z1)).length() <= EXACT);
}

/// A full circle as 4 rational quadratic arcs with double interior knots (C0 in the parameter,
/// exact geometrically), swept linearly: every point, at knots too, is at radius r.
#[test]
fn full_rational_cylinder_with_double_knots_is_exact() {
    let r = 0.8;
    let c = std::f64::consts::FRAC_1_SQRT_2;
    let ring = [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, c),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, c),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, c),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, c),
        (1.0, 0.0, 1.0),
    ];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for &(x, y, w) in &ring {
        for z in [0.0, 2.0] {
            points.push(DVec3::new(r * x, r * y, z));
            weights.push(w);
        }
    }
    // Rhino convention: count + degree - 1 = 10 knots.
    let knots_u = [5.0, 5.0, 6.0, 6.0, 7.0, 7.0, 8.0, 8.0, 9.0, 9.0];
    let surface = NurbsSurface::new(
        [2, 1],
        [9, 2],
        &knots_u,
        &[0.25, 0.75],
        &points,
        Some(&weights),
    )
    .expect("a valid cylinder");
    let mut parameters = parameter_grid((5.0, 9.0), (0.25, 0.75), 40);
    parameters.extend([6.0, 7.0, 8.0].iter().map(|&k| (k, 0.5)));
    for (u, v) in parameters {
        let d = surface.evaluate(u, v);
        let radius = DVec3::new(d.point.x, d.point.y, 0.0).length();
        assert!((radius - r).abs() <= EXACT, "radius {radius} at ({u}, {v})");
        // The normal points outwards, radially (Su along the circle, Sv up).
        let normal = d.su.cross(d.sv).normalize();
        let radial = DVec3::new(d.point.x, d.point.y, 0.0) / radius;
        assert!(
            (normal - radial).length() <= 1e-12,
            "normal {normal} at ({u}, {v})"
        );
        assert!((d.point.z - 4.0 * (v - 0.25)).abs() <= EXACT);
    }
    // Quarter arcs: u = 6, 7, 8 are the points at 90, 180, 270 degrees.
    for (k, expected) in [
        (6.0, DVec3::new(0.0, r, 0.0)),
        (7.0, DVec3::new(-r, 0.0, 0.0)),
        (8.0, DVec3::new(0.0, -r, 0.0)),
    ] {
        assert!(
            (surface.point_at(k, 0.25) - expected).length() <= EXACT,
            "u = {k}"
        );
    }
}
