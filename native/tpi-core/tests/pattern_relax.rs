//! Issue 15, relaxation: Lloyd iterations measured on the surface make facet areas even,
//! whatever the parametrisation. Facet areas are measured here from the output vertices
//! (Newell's vector area), independently of the relaxation's own centroids.

mod common;

use common::*;
use glam::DVec3;
use tpi_core::{discretise, relax, DiscretiseOptions, Generator, Surface, TpiError};

fn facet_areas(surface: &dyn Surface, pattern: &[[f64; 2]]) -> Vec<f64> {
    let d = discretise(surface, pattern, &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();
    (0..d.facet_count())
        .map(|i| {
            let p = facet_points(&d, i);
            let newell: DVec3 = (0..p.len()).map(|k| p[k].cross(p[(k + 1) % p.len()])).sum();
            0.5 * newell.length()
        })
        .collect()
}

fn variation(values: &[f64]) -> f64 {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / n;
    var.sqrt() / mean
}

/// A convex bicubic dome whose x runs with the square of its parameter: cells uniform in the
/// parameters are nine times longer at one end than at the other.
fn stretched_dome() -> tpi_core::NurbsSurface {
    lifted_net(
        [3, 3],
        &[0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0],
        &[0.0, 0.0, 0.0, 1.0, 2.0, 2.0, 2.0],
        |s, t| (-6.0 + 12.0 * s * s, -4.0 + 8.0 * t),
        |x, y, _, _| 4.0 - 0.05 * x * x - 0.08 * y * y,
        None,
    )
}

#[test]
fn twenty_lloyd_iterations_make_facet_areas_even_on_a_stretched_dome() {
    let surface = stretched_dome();
    let start = Generator::parse("random:400:seed=3").unwrap().generate().uv;
    let before = variation(&facet_areas(&surface, &start));
    let relaxed = relax(&surface, &start, 20, &DiscretiseOptions::default()).unwrap();
    assert_eq!(relaxed.len(), start.len());
    assert!(relaxed
        .iter()
        .all(|p| (0.0..=1.0).contains(&p[0]) && (0.0..=1.0).contains(&p[1])));
    let after = variation(&facet_areas(&surface, &relaxed));
    println!("coefficient of variation of facet areas: {before:.3} -> {after:.3}");
    assert!(before >= 0.5, "the random start is already even: {before}");
    assert!(after <= 0.10, "after 20 iterations: {after}");
}

#[test]
fn relaxation_limits_are_named() {
    let surface = stretched_dome();
    let start = Generator::parse("hex:5x5").unwrap().generate().uv;
    assert!(matches!(
        relax(&surface, &start, 1_000_000, &DiscretiseOptions::default()),
        Err(TpiError::InvalidParameter { .. })
    ));
    assert_eq!(
        relax(&surface, &start, 0, &DiscretiseOptions::default()).unwrap(),
        start
    );
}

#[test]
fn relaxation_keeps_a_closed_surface_closed() {
    // Two half ellipsoids would do as well; one face closed in u with poles is the common case:
    // no point may end on a pole or on the seam twice.
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../samples/ellipsoid.json"
    ))
    .unwrap();
    let surface = tpi_core::SurfaceSpec::from_json(&text, "ellipsoid.json")
        .unwrap()
        .build()
        .unwrap();
    let start = Generator::parse("random:300:seed=5").unwrap().generate().uv;
    let relaxed = relax(&surface, &start, 10, &DiscretiseOptions::default()).unwrap();
    let d = discretise(&surface, &relaxed, &DiscretiseOptions::default()).unwrap();
    assert_eq!((d.topology.euler, d.topology.boundary_loops), (2, 0));
    d.sanity_check().unwrap();
    let areas = facet_areas(&surface, &relaxed);
    assert!(variation(&areas) < variation(&facet_areas(&surface, &start)) / 3.0);
}
