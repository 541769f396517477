//! Many random patterns on strictly convex surfaces (analytic and NURBS, rational too): every
//! mesh must be a valid disc. Topology, convexity, orientation and planarity are all checked
//! here from the mesh itself (helpers in `common`), not taken from the quality report.

mod common;

use common::*;
use tpi_core::{discretise, AnalyticSurface, DiscretiseOptions, Surface};

fn check_many(name: &str, surface: &dyn Surface, seed: u64, runs: usize) {
    let mut rng = Rng::new(seed);
    let mut failures = Vec::new();
    for k in 0..runs {
        let n = 100 + (rng.f64() * 1400.0) as usize;
        let pattern = if k % 2 == 0 {
            uniform_pattern(&mut rng, n)
        } else {
            jittered_pattern(&mut rng, n)
        };
        let d = discretise(surface, &pattern, &DiscretiseOptions::default()).expect("discretises");
        let topo = topology(&d);
        let diagonal = seed_diagonal(&d);
        let (planarity, _) = max_planarity(&d, diagonal);
        let mut bad_facets = 0;
        for i in 0..d.facet_count() {
            let points = facet_points(&d, i);
            let flat = to_2d(d.seeds[i].point, d.seeds[i].normal, &points);
            if points.len() < 3 || !(signed_area(&flat) > 0.0) || !is_convex(&flat) {
                bad_facets += 1;
            }
        }
        if topo.euler != 1
            || topo.boundary_loops != 1
            || topo.components != 1
            || !topo.problems.is_empty()
            || bad_facets > 0
            || !(planarity <= 1e-9)
        {
            failures.push(format!(
                "{name} run {k} ({n} points): Euler {}, {} boundary loops, {} components, {} clockwise/non-convex facets, planarity {planarity:e}, problems {:?}",
                topo.euler,
                topo.boundary_loops,
                topo.components,
                bad_facets,
                &topo.problems[..topo.problems.len().min(2)]
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn oblique_nurbs_dome_is_always_a_valid_disc() {
    check_many("oblique dome", &dome_a(), 901, 16);
}

#[test]
fn rational_nurbs_dome_is_always_a_valid_disc() {
    check_many("rational dome", &dome_c(), 902, 16);
}

#[test]
fn analytic_convex_surfaces_are_always_valid_discs() {
    check_many(
        "sphere cap",
        &AnalyticSurface::sphere_cap_square(1.0, 0.6).unwrap(),
        903,
        8,
    );
    check_many(
        "ellipsoid cap",
        &AnalyticSurface::ellipsoid_cap(2.0, 1.2, 0.8, [-1.3, 1.1], [-0.7, 0.75]).unwrap(),
        904,
        8,
    );
    check_many(
        "paraboloid 10:1",
        &AnalyticSurface::elliptic_paraboloid(10.0, 1.0, [-0.4, 0.4], [-1.0, 1.0]).unwrap(),
        905,
        8,
    );
}
