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
    let mut used = vec![false; d.vertices.len()];
    for &v in &d.facet_loops {
        used[v as usize] = true;
    }
    let max = d
        .vertices
        .iter()
        .zip(&used)
        .filter(|(_, &u)| u)
        .map(|(&x, _)| {
            let [u, v] = closest_parameters(surface, x, 12);
            surface.point_at(u, v).distance(x)
        })
        .fold(0.0, f64::max);
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
