//! Issue 15, item 1: tolerance-driven patterns. Every mesh vertex is checked against the
//! tolerance by this file's own projection (`common::closest_parameters`: brute force on a
//! grid, then Newton on |S - x|^2 inside the closed domain), not by the report's number or
//! the crate's projection; the uniform hexagonal baseline is found here by bisection on
//! `hex:spacing=1/N` with the same independent measure.

mod common;

use common::*;
use tpi_core::{discretise, fit_pattern, DiscretiseOptions, Generator, Surface};

/// The largest distance of a mesh vertex from the surface (own projection) and the mesh's
/// invalid facets.
fn independent_check(surface: &dyn Surface, uv: &[[f64; 2]]) -> (f64, usize) {
    let d = discretise(surface, uv, &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();
    let max = max_over_used_vertices(&d, |x| {
        let [u, v] = closest_parameters(surface, x, 12);
        surface.point_at(u, v).distance(x)
    });
    (max, d.quality.unwrap().invalid_facets)
}

/// The smallest `hex:spacing=1/N` meeting the tolerance by the independent measure: N
/// doubled from 4 until it does, then bisected. (count, invalid facets).
fn hex_bisection(surface: &dyn Surface, tolerance: f64) -> (usize, usize) {
    let hex = |n: usize| {
        let uv = Generator::parse(&format!("hex:spacing={}", 1.0 / n as f64))
            .unwrap()
            .generate()
            .uv;
        let (dev, invalid) = independent_check(surface, &uv);
        println!("  hex 1/{n}: {} points, max deviation {dev:.5e}", uv.len());
        (dev <= tolerance, uv.len(), invalid)
    };
    let (mut lo, mut hi) = (2, 4);
    let mut found = loop {
        let h = hex(hi);
        if h.0 {
            break h;
        }
        lo = hi;
        hi *= 2;
        assert!(hi <= 64, "no hex pattern up to 1/64 meets {tolerance}");
    };
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let h = hex(mid);
        if h.0 {
            hi = mid;
            found = h;
        } else {
            lo = mid;
        }
    }
    (found.1, found.2)
}

/// Fits, checks every vertex independently, compares with the hex baseline; returns the
/// ratio of counts.
fn fit_and_compare(name: &str, tolerance: f64) -> f64 {
    let surface = sample_surface(name);
    let fitted = fit_pattern(&surface, tolerance, 0, &DiscretiseOptions::default()).unwrap();
    assert!(fitted.met, "{name}: {fitted:?}");
    let (dev, invalid) = independent_check(&surface, &fitted.uv);
    let (hex_count, hex_invalid) = hex_bisection(&surface, tolerance);
    let ratio = fitted.uv.len() as f64 / hex_count as f64;
    println!(
        "{name} D = {tolerance}: fitted {} points (independent max deviation {dev:.5e}, \
         {invalid} invalid), smallest hex meeting D {hex_count} ({hex_invalid} invalid): \
         ratio {ratio:.3}",
        fitted.uv.len()
    );
    // Rounding of the two projections apart, every vertex within D.
    assert!(
        dev <= tolerance * (1.0 + 1e-9),
        "{name}: {dev} > {tolerance}"
    );
    if hex_invalid == 0 {
        assert_eq!(
            invalid, 0,
            "{name}: invalid facets where uniform hex has none"
        );
    }
    ratio
}

#[test]
fn a_free_form_dome_needs_at_most_60_percent_of_the_uniform_hex_points() {
    let ratio = fit_and_compare("nurbs-dome.json", 0.01);
    assert!(ratio <= 0.6, "{ratio}");
}

#[test]
fn a_free_form_saddle_needs_at_most_60_percent_of_the_uniform_hex_points() {
    let ratio = fit_and_compare("saddle.json", 0.01);
    assert!(ratio <= 0.6, "{ratio}");
}

/// The paraboloid of revolution is nearly the worst case for any adaptive pattern: its
/// curvature and parametrisation are nearly uniform, so the ideal count (the integral of
/// sqrt(K) over the area, over 3 sqrt(3) D) is about 0.75 of the uniform hex's.
/// The 60 % of the issue does not hold here; the pattern still does better than hex.
#[test]
fn on_nearly_uniform_surfaces_the_pattern_still_beats_uniform_hex() {
    for name in ["paraboloid.json", "hypar.json"] {
        let ratio = fit_and_compare(name, 0.01);
        assert!(ratio < 0.9, "{name}: {ratio}");
    }
}

#[test]
fn bad_tolerances_are_named() {
    let surface = sample_surface("paraboloid.json");
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = fit_pattern(&surface, bad, 0, &DiscretiseOptions::default()).unwrap_err();
        assert!(e.to_string().contains("max_deviation"), "{e}");
    }
    // A tolerance needing far too many points is refused before any point is made.
    let e = fit_pattern(&surface, 1e-12, 0, &DiscretiseOptions::default()).unwrap_err();
    assert!(e.to_string().contains("pattern points"), "{e}");
}

/// A roof with crests, flanks and parabolic lines between them: where neighbouring tangent
/// planes are nearly parallel, exact vertices run away from the surface whatever points are
/// added there, so a refinement that keeps adding points never ends (it ran for more than
/// 15 minutes, each mesh slower than the last). The fit must stop refining a round that no
/// longer gets closer, and still return a pattern that meets D at every vertex by this
/// file's own projection, with no invalid facet.
#[test]
fn a_mixed_curvature_roof_is_fitted_without_endless_refinement() {
    let surface = sample_surface("mixed-roof.json");
    let tolerance = 0.01;
    let fitted = fit_pattern(&surface, tolerance, 0, &DiscretiseOptions::default()).unwrap();
    assert!(fitted.met, "{fitted:?}");
    let (dev, invalid) = independent_check(&surface, &fitted.uv);
    println!(
        "mixed-roof D = {tolerance}: {} points, {} discretisations, independent max deviation \
         {dev:.5e}, {invalid} invalid",
        fitted.uv.len(),
        fitted.discretisations
    );
    assert!(dev <= tolerance * (1.0 + 1e-9), "{dev} > {tolerance}");
    assert_eq!(invalid, 0);
}

/// A closed surface with poles: the refinement adds points at the feet of offending
/// vertices, and near a pole or the seam those feet used to be clamped onto the pole side
/// (a seed there is refused: "it lies on a pole") or onto both sides of the seam. Now they
/// keep clear of both, and neighbourhoods are judged on the surface, not in parameters.
#[test]
fn a_closed_surface_with_poles_is_fitted() {
    let surface = sample_surface("ellipsoid.json");
    let tolerance = 0.05;
    let fitted = fit_pattern(&surface, tolerance, 0, &DiscretiseOptions::default()).unwrap();
    assert!(fitted.met, "{fitted:?}");
    // The sample is the ellipsoid with semi-axes 12, 8, 5 about the origin: the oracle is
    // its closed-form distance (a projection from a grid stalls at the poles).
    let d = discretise(&surface, &fitted.uv, &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();
    let dev = max_over_used_vertices(&d, |x| ellipsoid_distance([12.0, 8.0, 5.0], x));
    let invalid = d.quality.as_ref().unwrap().invalid_facets;
    println!(
        "ellipsoid D = {tolerance}: {} points, closed-form max deviation {dev:.5e}, {invalid} invalid",
        fitted.uv.len()
    );
    assert!(dev <= tolerance * (1.0 + 1e-9), "{dev} > {tolerance}");
    assert_eq!(invalid, 0);
}

/// The paraboloid z = -0.08 (x^2 + y^2) over [-5, 5]^2 with a bump 1e-4 high and 1e-5 wide
/// at its apex, where one node of the fit's curvature field lies: there the curvature is
/// 2e6, ten million times the rest. Real faces have such nodes next to degenerate poles
/// (curvature 1e13 at 2 of 4,225 nodes): taken as the surface's largest curvature they
/// floored the field everywhere and the fit asked for 1e14 points. The bump is far below
/// the tolerance, so the fit should not see it: about as many points as on the smooth
/// paraboloid, and every vertex within D by the independent projection.
#[test]
fn an_isolated_singular_curvature_does_not_set_the_spacing() {
    struct Bumped;
    const A: f64 = -0.08;
    const HEIGHT: f64 = 1e-4;
    const WIDTH: f64 = 1e-5;
    impl tpi_core::Surface for Bumped {
        fn domain(&self) -> tpi_core::Domain {
            tpi_core::Domain::new(
                tpi_core::Interval::new(-5.0, 5.0),
                tpi_core::Interval::new(-5.0, 5.0),
            )
        }
        fn evaluate(&self, x: f64, y: f64) -> tpi_core::SurfaceDerivatives {
            // z = A r^2 + H exp(-r^2 / w^2).
            let w2 = WIDTH * WIDTH;
            let e = HEIGHT * (-(x * x + y * y) / w2).exp();
            let z = A * (x * x + y * y) + e;
            let zx = 2.0 * A * x - 2.0 * x / w2 * e;
            let zy = 2.0 * A * y - 2.0 * y / w2 * e;
            let zxx = 2.0 * A + (4.0 * x * x / (w2 * w2) - 2.0 / w2) * e;
            let zyy = 2.0 * A + (4.0 * y * y / (w2 * w2) - 2.0 / w2) * e;
            let zxy = 4.0 * x * y / (w2 * w2) * e;
            tpi_core::SurfaceDerivatives {
                point: glam::DVec3::new(x, y, z),
                su: glam::DVec3::new(1.0, 0.0, zx),
                sv: glam::DVec3::new(0.0, 1.0, zy),
                suu: glam::DVec3::new(0.0, 0.0, zxx),
                suv: glam::DVec3::new(0.0, 0.0, zxy),
                svv: glam::DVec3::new(0.0, 0.0, zyy),
            }
        }
    }
    let tolerance = 0.01;
    let options = DiscretiseOptions::default();
    let smooth = fit_pattern(&sample_surface("paraboloid.json"), tolerance, 0, &options).unwrap();
    let bumped = fit_pattern(&Bumped, tolerance, 0, &options).unwrap();
    assert!(bumped.met, "{bumped:?}");
    // The bumped surface lies within HEIGHT of the smooth paraboloid, so a vertex's distance
    // to it is within HEIGHT of its distance to the paraboloid (projected independently).
    let (smooth_dev, invalid) = independent_check(&sample_surface("paraboloid.json"), &bumped.uv);
    let dev = smooth_dev + HEIGHT;
    println!(
        "bumped paraboloid: {} points (smooth {}), independent max deviation {dev:.5e}",
        bumped.uv.len(),
        smooth.uv.len()
    );
    assert!(dev <= tolerance * (1.0 + 1e-9), "{dev} > {tolerance}");
    assert_eq!(invalid, 0);
    assert!(
        (bumped.uv.len() as f64) < 1.5 * smooth.uv.len() as f64,
        "{} points against {} on the smooth paraboloid",
        bumped.uv.len(),
        smooth.uv.len()
    );
}
