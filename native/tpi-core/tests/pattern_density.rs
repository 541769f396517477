//! Issue 15, item 4: density fields. The local number of points per unit surface area must
//! follow the field: the ratio of counts per area in two regions is compared with the ratio
//! of the field's mean densities there, both areas and means integrated here on a fine grid
//! from `Surface::evaluate` and this file's own formulas for the terms.
//!
//! Tolerance: 20 % (25 % after relaxation). A maximal Poisson-disk sampling has about
//! 0.7 / r^2 points per unit area with count fluctuations well below sqrt(n) in a region
//! of n points (the points repel); every region here holds at least ~100 points, so the
//! counting noise is under 10 %, and the points straddling a region's edge (perimeter over
//! spacing, a few %) make up most of the rest.

mod common;

use common::sample_surface;
use tpi_core::{density_pattern, DensitySpec, DiscretiseOptions, GreyImage, Surface};

/// Surface area and integral of `rho` over the region `inside` of the normalised square.
fn integrate(
    surface: &dyn Surface,
    inside: &dyn Fn([f64; 2]) -> bool,
    rho: &dyn Fn([f64; 2]) -> f64,
) -> (f64, f64) {
    let n = 400;
    let dom = surface.domain();
    let cell = dom.u.length() * dom.v.length() / (n * n) as f64;
    let (mut area, mut mass) = (0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            let st = [(i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64];
            if !inside(st) {
                continue;
            }
            let [u, v] = dom.from_normalised(st);
            let d = surface.evaluate(u, v);
            let da = d.su.cross(d.sv).length() * cell;
            area += da;
            mass += da * rho(st);
        }
    }
    (area, mass)
}

/// (observed, expected) ratio of points per area between regions a and b.
fn ratios(
    surface: &dyn Surface,
    points: &[[f64; 2]],
    a: &dyn Fn([f64; 2]) -> bool,
    b: &dyn Fn([f64; 2]) -> bool,
    rho: &dyn Fn([f64; 2]) -> f64,
) -> (f64, f64) {
    let (area_a, mass_a) = integrate(surface, a, rho);
    let (area_b, mass_b) = integrate(surface, b, rho);
    let count_a = points.iter().filter(|&&p| a(p)).count() as f64;
    let count_b = points.iter().filter(|&&p| b(p)).count() as f64;
    assert!(count_a >= 80.0 && count_b >= 80.0, "{count_a} {count_b}");
    (
        (count_a / area_a) / (count_b / area_b),
        (mass_a / area_a) / (mass_b / area_b),
    )
}

fn smooth(x: f64) -> f64 {
    if x >= 1.0 {
        0.0
    } else {
        1.0 - 3.0 * x * x + 2.0 * x * x * x
    }
}

const ATTRACTOR: &str = r#"{"spacing": 0.25, "seed": 3, "terms": [
    {"type": "attractor", "uv": [0.3, 0.5], "radius": 0.3, "peak": 9}]}"#;

fn attractor_rho(st: [f64; 2]) -> f64 {
    1.0 + 8.0 * smooth((st[0] - 0.3).hypot(st[1] - 0.5) / 0.3)
}

#[test]
fn points_crowd_around_a_uv_attractor_as_the_field_says() {
    let surface = sample_surface("paraboloid.json");
    let spec = DensitySpec::from_json(ATTRACTOR, "attractor").unwrap();
    let near = |p: [f64; 2]| (p[0] - 0.3).hypot(p[1] - 0.5) < 0.07;
    let far = |p: [f64; 2]| p[0] > 0.7;
    for relax in [0, 10] {
        let points = density_pattern(
            &surface,
            &spec,
            relax,
            1_000_000,
            &DiscretiseOptions::default(),
        )
        .unwrap();
        tpi_core::validate_pattern(&points).unwrap();
        let (observed, expected) = ratios(&surface, &points, &near, &far, &attractor_rho);
        println!(
            "relax {relax}: {} points, density ratio {observed:.3} (field {expected:.3})",
            points.len()
        );
        let tolerance = if relax == 0 { 0.2 } else { 0.25 };
        assert!(
            (observed / expected - 1.0).abs() <= tolerance,
            "relax {relax}: {observed} against {expected}"
        );
    }
}

#[test]
fn the_spacing_ratio_bound_caps_the_density_ratio() {
    let surface = sample_surface("paraboloid.json");
    let spec = DensitySpec::from_json(
        r#"{"spacing": 0.4, "ratio": 2, "terms": [
            {"type": "attractor", "uv": [0.3, 0.5], "radius": 0.3, "peak": 100}]}"#,
        "bounded",
    )
    .unwrap();
    let points =
        density_pattern(&surface, &spec, 0, 1_000_000, &DiscretiseOptions::default()).unwrap();
    // Density clamped to [100 / 2^2, 100]: 25 far away, 100 at the attractor.
    let rho = |st: [f64; 2]| {
        (1.0 + 99.0 * smooth((st[0] - 0.3).hypot(st[1] - 0.5) / 0.3)).clamp(25.0, 100.0)
    };
    let near = |p: [f64; 2]| (p[0] - 0.3).hypot(p[1] - 0.5) < 0.05;
    let far = |p: [f64; 2]| p[0] > 0.7;
    let (observed, expected) = ratios(&surface, &points, &near, &far, &rho);
    println!(
        "bounded: {} points, ratio {observed:.3} (field {expected:.3})",
        points.len()
    );
    assert!(
        (observed / expected - 1.0).abs() <= 0.2,
        "{observed} {expected}"
    );
}

#[test]
fn a_grey_image_grades_the_points() {
    let surface = sample_surface("nurbs-dome.json");
    // 8 x 1 pixels: the left half black, the right half white.
    let image =
        GreyImage::from_pgm(b"P2\n# test\n8 1\n255\n0 0 0 0 255 255 255 255\n", "t.pgm").unwrap();
    let mut spec = DensitySpec::from_json(
        r#"{"spacing": 0.35, "terms": [{"type": "image", "file": "t.pgm", "low": 1, "high": 4}]}"#,
        "image",
    )
    .unwrap();
    assert!(density_pattern(&surface, &spec, 0, 1_000_000, &DiscretiseOptions::default()).is_err());
    spec.attach_image(0, image);
    let points =
        density_pattern(&surface, &spec, 0, 1_000_000, &DiscretiseOptions::default()).unwrap();
    let rho = |st: [f64; 2]| if st[0] < 0.5 { 1.0 } else { 4.0 };
    let (observed, expected) = ratios(&surface, &points, &|p| p[0] > 0.6, &|p| p[0] < 0.4, &rho);
    println!(
        "image: {} points, ratio {observed:.3} (field {expected:.3})",
        points.len()
    );
    assert!(
        (observed / expected - 1.0).abs() <= 0.2,
        "{observed} {expected}"
    );
}

#[test]
fn density_files_are_checked() {
    for (text, culprit) in [
        (r#"{"spacing": 0, "terms": []}"#, "spacing"),
        (r#"{"spacing": 1, "ratio": 0.5, "terms": []}"#, "ratio"),
        (
            r#"{"spacing": 1, "terms": [{"type": "attractor", "radius": 1, "peak": 2}]}"#,
            "terms[0].uv",
        ),
        (
            r#"{"spacing": 1, "terms": [{"type": "attractor", "uv": [0, 0], "radius": -1, "peak": 2}]}"#,
            "terms[0].radius",
        ),
        (
            r#"{"spacing": 1, "terms": [{"type": "curvature", "exponent": -1}]}"#,
            "terms[0].exponent",
        ),
        (r#"{"spacing": 1, "terms": [{"type": "blob"}]}"#, "blob"),
    ] {
        let e = DensitySpec::from_json(text, "d.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains(culprit), "{text}: {e}");
    }
    assert!(GreyImage::from_pgm(b"P5\n2 2\n255\n\x00", "short.pgm").is_err());
    assert!(GreyImage::from_pgm(b"P6\n1 1\n255\n\x00\x00\x00", "colour.ppm").is_err());
}
