//! Every invalid analytic parameter gives its specific typed error, naming the field.

use tpi_core::AnalyticKind;
use tpi_core::{AnalyticSurface, Direction, TpiError};

const X: [f64; 2] = [-1.0, 1.0];
const Y: [f64; 2] = [-0.5, 0.5];

fn invalid_field(e: TpiError) -> String {
    match e {
        TpiError::InvalidParameter { field, .. } => field,
        other => panic!("expected InvalidParameter, got {other:?}"),
    }
}

fn non_finite_field(e: TpiError) -> String {
    match e {
        TpiError::NonFinite { field, .. } => field,
        other => panic!("expected NonFinite, got {other:?}"),
    }
}

#[test]
fn non_finite_parameters_are_named() {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    let cases: Vec<(AnalyticKind, &str)> = vec![
        (AnalyticKind::EllipticParaboloid { a: nan, b: 1.0 }, "a"),
        (AnalyticKind::EllipticParaboloid { a: 1.0, b: inf }, "b"),
        (AnalyticKind::HyperbolicParaboloid { a: -inf, b: 1.0 }, "a"),
        (AnalyticKind::SphereCap { radius: nan }, "radius"),
        (
            AnalyticKind::EllipsoidCap {
                a: 2.0,
                b: 2.0,
                c: nan,
            },
            "c",
        ),
        (
            AnalyticKind::EllipsoidCap {
                a: 2.0,
                b: inf,
                c: 1.0,
            },
            "b",
        ),
        (AnalyticKind::EggCrate { amplitude: nan }, "amplitude"),
        (AnalyticKind::Cylinder { radius: inf }, "radius"),
        (
            AnalyticKind::Plane {
                p: 0.0,
                q: nan,
                c0: 0.0,
            },
            "q",
        ),
        (
            AnalyticKind::Plane {
                p: 0.0,
                q: 0.0,
                c0: -inf,
            },
            "c0",
        ),
    ];
    for (kind, field) in cases {
        let e = AnalyticSurface::new(kind, X, Y).unwrap_err();
        assert_eq!(non_finite_field(e), field, "{kind:?}");
    }
    for (x, y, field) in [
        ([f64::NAN, 1.0], Y, "x[0]"),
        ([0.0, f64::INFINITY], Y, "x[1]"),
        (X, [f64::NEG_INFINITY, 0.0], "y[0]"),
        (X, [0.0, f64::NAN], "y[1]"),
    ] {
        let e = AnalyticSurface::plane(0.0, 0.0, 0.0, x, y).unwrap_err();
        assert_eq!(non_finite_field(e), field);
    }
}

#[test]
fn empty_rectangles_are_rejected_per_direction() {
    let e = AnalyticSurface::plane(0.0, 0.0, 0.0, [1.0, 1.0], Y).unwrap_err();
    assert_eq!(
        e,
        TpiError::EmptyDomain {
            direction: Direction::U,
            min: 1.0,
            max: 1.0
        }
    );
    let e = AnalyticSurface::elliptic_paraboloid(1.0, 1.0, X, [0.5, -0.5]).unwrap_err();
    assert_eq!(
        e,
        TpiError::EmptyDomain {
            direction: Direction::V,
            min: 0.5,
            max: -0.5
        }
    );
}

#[test]
fn radii_and_semi_axes_must_be_positive() {
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap(0.0, X, Y).unwrap_err()),
        "radius"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap(-2.0, X, Y).unwrap_err()),
        "radius"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::cylinder(-1.0, X, Y).unwrap_err()),
        "radius"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::ellipsoid_cap(0.0, 2.0, 1.0, X, Y).unwrap_err()),
        "a"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::ellipsoid_cap(2.0, -2.0, 1.0, X, Y).unwrap_err()),
        "b"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::ellipsoid_cap(2.0, 2.0, 0.0, X, Y).unwrap_err()),
        "c"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap_square(2.0, 0.0).unwrap_err()),
        "half_width"
    );
    assert_eq!(
        non_finite_field(AnalyticSurface::sphere_cap_square(2.0, f64::NAN).unwrap_err()),
        "half_width"
    );
}

#[test]
fn rectangles_must_stay_strictly_inside_the_square_roots() {
    // Sphere: a centred square of half-width h needs h sqrt(2) < r.
    assert!(AnalyticSurface::sphere_cap_square(1.0, 0.7).is_ok());
    let e = AnalyticSurface::sphere_cap_square(1.0, 0.71).unwrap_err();
    assert_eq!(invalid_field(e.clone()), "x, y");
    assert!(e.to_string().contains("radius 1"), "{e}");
    // Exactly on the sphere is rejected too (the normal would be horizontal).
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap(5.0, [0.0, 3.0], [0.0, 4.0]).unwrap_err()),
        "x, y"
    );
    // Off-centre rectangles are judged by their farthest corner.
    assert!(AnalyticSurface::sphere_cap(5.0, [-4.0, 0.5], [-2.9, 0.0]).is_ok());
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap(5.0, [-4.0, 0.5], [-3.1, 0.0]).unwrap_err()),
        "x, y"
    );
    // Ellipse x^2/4 + y^2 < 1.
    assert!(AnalyticSurface::ellipsoid_cap(2.0, 1.0, 1.0, [-1.4, 1.4], [-0.7, 0.7]).is_ok());
    assert_eq!(
        invalid_field(
            AnalyticSurface::ellipsoid_cap(2.0, 1.0, 1.0, [-1.5, 1.4], [-0.7, 0.7]).unwrap_err()
        ),
        "x, y"
    );
    // Cylinder: |x| < r, y free.
    assert!(AnalyticSurface::cylinder(1.0, [-0.99, 0.5], [-100.0, 100.0]).is_ok());
    assert_eq!(
        invalid_field(AnalyticSurface::cylinder(1.0, [-0.5, 1.0], Y).unwrap_err()),
        "x"
    );
}

#[test]
fn coefficients_must_give_the_promised_curvature_class() {
    // Elliptic paraboloid: a, b non-zero, same sign (a = b = 0 would be a plane).
    assert_eq!(
        invalid_field(AnalyticSurface::elliptic_paraboloid(0.0, 0.0, X, Y).unwrap_err()),
        "a"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::elliptic_paraboloid(1.0, 0.0, X, Y).unwrap_err()),
        "b"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::elliptic_paraboloid(1.0, -1.0, X, Y).unwrap_err()),
        "b"
    );
    assert!(AnalyticSurface::elliptic_paraboloid(-1.0, -0.1, X, Y).is_ok());
    assert!(AnalyticSurface::elliptic_paraboloid(1.0, 0.1, X, Y).is_ok());
    // Hyperbolic paraboloid z = a x^2 - b y^2: a, b non-zero, same sign.
    assert_eq!(
        invalid_field(AnalyticSurface::hyperbolic_paraboloid(0.0, 1.0, X, Y).unwrap_err()),
        "a"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::hyperbolic_paraboloid(1.0, 0.0, X, Y).unwrap_err()),
        "b"
    );
    let e = AnalyticSurface::hyperbolic_paraboloid(1.0, -1.0, X, Y).unwrap_err();
    assert_eq!(invalid_field(e.clone()), "b");
    assert!(e.to_string().contains("same sign"), "{e}");
    // Egg crate: amplitude 0 is a plane.
    assert_eq!(
        invalid_field(AnalyticSurface::egg_crate(0.0, X, Y).unwrap_err()),
        "amplitude"
    );
    // A plane takes any finite coefficients.
    assert!(AnalyticSurface::plane(0.0, 0.0, 0.0, X, Y).is_ok());
}

#[test]
fn accessors_return_what_was_built() {
    let s = AnalyticSurface::ellipsoid_cap(3.0, 2.0, 1.0, [-1.0, 2.0], [-0.5, 0.25]).unwrap();
    assert_eq!(
        s.kind(),
        AnalyticKind::EllipsoidCap {
            a: 3.0,
            b: 2.0,
            c: 1.0
        }
    );
    assert_eq!(s.x_range(), [-1.0, 2.0]);
    assert_eq!(s.y_range(), [-0.5, 0.25]);
    assert_eq!(s.kind().type_name(), "ellipsoid_cap");
}

#[test]
fn magnitudes_are_bounded_so_evaluation_cannot_overflow() {
    use tpi_core::{MAX_ANALYTIC_MAGNITUDE, MIN_ANALYTIC_LENGTH};
    // a x^2 - b y^2 would be inf - inf = NaN at the corner.
    assert_eq!(
        invalid_field(AnalyticSurface::hyperbolic_paraboloid(1e300, 1e300, X, Y).unwrap_err()),
        "a"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::plane(0.0, 0.0, 0.0, [-1e60, 0.0], Y).unwrap_err()),
        "x[0]"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::plane(0.0, 0.0, 0.0, X, [0.0, 1e51]).unwrap_err()),
        "y[1]"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap(1e200, X, Y).unwrap_err()),
        "radius"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::egg_crate(-1e51, X, Y).unwrap_err()),
        "amplitude"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::plane(0.0, 2e50, 0.0, X, Y).unwrap_err()),
        "q"
    );
    let tiny = [-1e-60, 1e-60];
    assert_eq!(
        invalid_field(AnalyticSurface::sphere_cap(1e-55, tiny, tiny).unwrap_err()),
        "radius"
    );
    assert_eq!(
        invalid_field(AnalyticSurface::ellipsoid_cap(1.0, 1e-51, 1.0, tiny, tiny).unwrap_err()),
        "b"
    );

    // At the limits every surface evaluates to finite numbers, corners included.
    let big = MAX_ANALYTIC_MAGNITUDE;
    let small = MIN_ANALYTIC_LENGTH;
    let h = 0.7;
    let surfaces = [
        AnalyticSurface::hyperbolic_paraboloid(big, big, [-big, big], [-big, big]).unwrap(),
        AnalyticSurface::elliptic_paraboloid(-big, -big, [-big, big], [-big, big]).unwrap(),
        AnalyticSurface::plane(big, -big, big, [-big, big], [-big, big]).unwrap(),
        AnalyticSurface::egg_crate(big, [-big, big], [-big, big]).unwrap(),
        AnalyticSurface::sphere_cap(big, [-h * big, h * big], [-h * big, h * big]).unwrap(),
        AnalyticSurface::sphere_cap(small, [-h * small, h * small], [-h * small, h * small])
            .unwrap(),
        AnalyticSurface::sphere_cap_square(small, small / 2f64.sqrt() * (1.0 - 1e-15)).unwrap(),
        AnalyticSurface::ellipsoid_cap(small, big, big, [-0.99 * small, 0.0], [0.0, 0.1 * big])
            .unwrap(),
        AnalyticSurface::ellipsoid_cap(big, small, small, [-0.99 * big, 0.0], [0.0, 0.1 * small])
            .unwrap(),
        AnalyticSurface::cylinder(small, [-small * (1.0 - 1e-15), 0.0], [-big, big]).unwrap(),
        AnalyticSurface::cylinder(big, [-big * (1.0 - 1e-15), 0.0], [-big, big]).unwrap(),
    ];
    use tpi_core::Surface;
    for s in surfaces {
        let d = s.domain();
        for a in 0..=4 {
            for b in 0..=4 {
                let (u, v) = (d.u.lerp(a as f64 / 4.0), d.v.lerp(b as f64 / 4.0));
                let e = s.evaluate(u, v);
                for w in [e.point, e.su, e.sv, e.suu, e.suv, e.svv] {
                    assert!(w.is_finite(), "{:?} at ({u}, {v}): {e:?}", s.kind());
                }
            }
        }
    }
}
