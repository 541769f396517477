//! Acceptance (exact combinatorics): near-degenerate inputs built on purpose give valid discs,
//! and `Discretisation::sanity_check` holds on them and fails on broken meshes.
//!
//! Oracles, independent of the code under test:
//! - on the paraboloid of revolution z = c (x^2 + y^2) the top view of the mesh is the Voronoi
//!   diagram of the projected pattern points; for a square grid of spacing h that is the grid
//!   of squares around the points, whose corners (the half-integer positions) are where four
//!   tangent planes meet: each must be one mesh vertex, exactly (N - 1)^2 of them;
//! - topology (Euler characteristic, boundary loops, orientation) and facet simplicity
//!   computed from the loops in `common`.
#![allow(clippy::needless_range_loop)]

mod common;

use common::*;
use glam::DVec2;
use tpi_core::VertexKind;
use tpi_core::INVALID_FLAGS;
use tpi_core::{
    discretise, AnalyticSurface, Discretisation, DiscretiseOptions, SanityError, TpiError,
};

const C: f64 = 0.6;

fn paraboloid_of_revolution() -> AnalyticSurface {
    AnalyticSurface::elliptic_paraboloid(C, C, [-1.0, 1.0], [-1.0, 1.0]).unwrap()
}

fn grid(n: usize) -> Vec<[f64; 2]> {
    let last = (n - 1) as f64;
    (0..n)
        .flat_map(|j| (0..n).map(move |i| [i as f64 / last, j as f64 / last]))
        .collect()
}

/// Every facet simple and counter-clockwise in its plane, and the mesh a disc (from `common`).
/// No facet carries a flag of `forbidden` either.
fn assert_valid_disc(d: &Discretisation, what: &str, forbidden: u8) {
    for i in 0..d.facet_count() {
        let flat = to_2d(d.seeds[i].point, d.seeds[i].normal, &facet_points(d, i));
        assert!(
            is_simple(&flat),
            "{what}: facet {i} is not simple: {:?}",
            d.facet(i)
        );
    }
    let t = topology(d);
    assert!(
        t.problems.is_empty(),
        "{what}: {:?}",
        &t.problems[..t.problems.len().min(5)]
    );
    assert_eq!((t.euler, t.boundary_loops), (1, 1), "{what}: not a disc");
    d.sanity_check()
        .unwrap_or_else(|e| panic!("{what}: sanity check: {e}"));
    let flagged: Vec<(usize, u8)> = d
        .facet_flags
        .iter()
        .copied()
        .enumerate()
        .filter(|&(_, f)| f & forbidden != 0)
        .collect();
    assert!(flagged.is_empty(), "{what}: flagged facets {flagged:?}");
}

/// A square grid on the paraboloid of revolution: every quad of neighbouring points is
/// cocircular, so four tangent planes meet at every cell corner. Each corner must be one
/// vertex, at the Voronoi vertex (the half-integer grid position).
fn cocircular_grid(n: usize) {
    let surface = paraboloid_of_revolution();
    let d = discretise(&surface, &grid(n), &DiscretiseOptions::default()).unwrap();
    assert_valid_disc(&d, &format!("grid {n}x{n}"), u8::MAX);
    let h = 2.0 / (n - 1) as f64;
    let interior: Vec<DVec2> = d
        .vertices
        .iter()
        .zip(&d.vertex_kinds)
        .filter(|(_, &k)| k == VertexKind::Interior)
        .map(|(v, _)| DVec2::new(v.x, v.y))
        .collect();
    assert_eq!(
        interior.len(),
        (n - 1) * (n - 1),
        "one vertex per cell corner"
    );
    let mut seen = vec![false; (n - 1) * (n - 1)];
    for p in &interior {
        // The corner between grid points i and i + 1 lies at -1 + (i + 1/2) h.
        let (fi, fj) = ((p.x + 1.0) / h - 0.5, (p.y + 1.0) / h - 0.5);
        let (i, j) = (fi.round(), fj.round());
        assert!(
            (fi - i).abs() < 1e-6 && (fj - j).abs() < 1e-6,
            "vertex {p} is not at a cell corner"
        );
        let k = j as usize * (n - 1) + i as usize;
        assert!(!seen[k], "two vertices at corner ({i}, {j})");
        seen[k] = true;
    }
}

#[test]
fn four_cocircular_slopes_meet_in_one_vertex() {
    cocircular_grid(2);
    cocircular_grid(3);
}

#[test]
fn cocircular_grid_of_a_thousand_squared() {
    cocircular_grid(1000);
}

#[test]
fn points_just_apart_are_valid_and_closer_points_are_named_duplicates() {
    let surface = paraboloid_of_revolution();
    let mut rng = Rng::new(7);
    let mut pattern = uniform_pattern(&mut rng, 2000);
    // Pairs just beyond the duplicate tolerance (1e-9 in normalised uv), in several directions.
    for k in 0..20 {
        let p = pattern[k];
        let angle = k as f64 * 0.7;
        pattern.push(
            [p[0] + 2e-9 * angle.cos(), p[1] + 2e-9 * angle.sin()].map(|x| x.clamp(0.0, 1.0)),
        );
    }
    let d = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
    // The neighbours of such a pair hold two vertices about 2e-9 apart whose offset across
    // the edge is rounding: they may be flagged non-convex (a reflex angle made by rounding),
    // never invalid.
    assert_valid_disc(&d, "pairs 2e-9 apart", INVALID_FLAGS);

    let mut closer = pattern.clone();
    closer.push([pattern[5][0] + 1e-12, pattern[5][1]]);
    match discretise(&surface, &closer, &DiscretiseOptions::default()) {
        Err(TpiError::DuplicatePatternPoint {
            index,
            duplicate_of,
            ..
        }) => assert_eq!((index, duplicate_of), (closer.len() - 1, 5)),
        other => panic!(
            "expected a duplicate error, got {:?}",
            other.map(|d| d.facet_count())
        ),
    }
}

#[test]
fn sanity_check_names_what_is_broken() {
    let surface = paraboloid_of_revolution();
    let d = discretise(&surface, &grid(6), &DiscretiseOptions::default()).unwrap();
    d.sanity_check().unwrap();

    let mut reversed = d.clone();
    let (a, b) = (
        reversed.facet_offsets[7] as usize,
        reversed.facet_offsets[8] as usize,
    );
    reversed.facet_loops[a..b].reverse();
    assert!(matches!(
        reversed.sanity_check(),
        Err(SanityError::BadFacet { facet: 7, .. })
    ));

    let mut lifted = d.clone();
    let v = lifted.facet(14)[0] as usize;
    lifted.vertices[v].z += 1e-3;
    assert!(matches!(
        lifted.sanity_check(),
        Err(SanityError::NonPlanar { .. })
    ));

    let mut missing = d.clone();
    missing.seeds.pop();
    assert!(matches!(
        missing.sanity_check(),
        Err(SanityError::FacetCount { .. })
    ));

    let mut nan = d.clone();
    nan.vertices[3].x = f64::NAN;
    assert!(matches!(
        nan.sanity_check(),
        Err(SanityError::NonFiniteVertex { vertex: 3 })
    ));

    // Two facets' loops swapped with their neighbours' vertices: a hole and an overlap.
    let mut torn = d.clone();
    let (a, b) = (
        torn.facet_offsets[20] as usize,
        torn.facet_offsets[21] as usize,
    );
    let fresh = torn.vertices.len() as u32;
    torn.vertices
        .push(torn.vertices[torn.facet_loops[a] as usize]);
    torn.facet_loops[a] = fresh;
    let _ = b;
    assert!(matches!(
        torn.sanity_check(),
        Err(SanityError::NotDisc { .. })
    ));
}
