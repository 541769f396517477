//! Acceptance: degenerate patterns give their specific error, and a partly flat surface its
//! diagnostics and the Voronoi vertices of its flat region (issue 3, item 6; issue 16, item 4).
// NaN-safe negated comparisons are intended; index loops read better in geometry checks.
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::unnecessary_map_or
)]

mod common;

use std::collections::BTreeSet;

use common::*;
use tpi_core::{
    discretise, AnalyticSurface, Diagnostic, DiscretiseOptions, NurbsSurface, Surface, TpiError,
};

fn sphere() -> AnalyticSurface {
    AnalyticSurface::sphere_cap_square(1.0, 0.6).unwrap()
}

fn run(pattern: &[[f64; 2]]) -> Result<tpi_core::Discretisation, TpiError> {
    discretise(&sphere(), pattern, &DiscretiseOptions::default())
}

#[test]
fn fewer_than_three_points() {
    for n in 0..3 {
        let pattern: Vec<[f64; 2]> = (0..n)
            .map(|k| [0.2 + 0.3 * k as f64, 0.7 - 0.2 * k as f64])
            .collect();
        match run(&pattern) {
            Err(TpiError::TooFewPatternPoints { found, needed }) => {
                assert_eq!((found, needed), (n, 3));
            }
            other => panic!("{n} points: expected TooFewPatternPoints, got {other:?}"),
        }
    }
}

#[test]
fn collinear_patterns() {
    let lines: [Vec<[f64; 2]>; 3] = [
        (0..7)
            .map(|k| [0.1 + 0.12 * k as f64, 0.1 + 0.12 * k as f64])
            .collect(),
        (0..5).map(|k| [0.05 + 0.2 * k as f64, 0.5]).collect(),
        (0..4).map(|k| [0.3, 0.9 - 0.25 * k as f64]).collect(),
    ];
    for pattern in lines {
        match run(&pattern) {
            Err(TpiError::CollinearPattern { count }) => assert_eq!(count, pattern.len()),
            other => panic!("{pattern:?}: expected CollinearPattern, got {other:?}"),
        }
    }
}

fn base() -> Vec<[f64; 2]> {
    vec![
        [0.1, 0.2],
        [0.5, 0.5],
        [0.9, 0.3],
        [0.3, 0.8],
        [0.75, 0.85],
        [0.6, 0.1],
    ]
}

#[test]
fn exact_duplicates() {
    let mut pattern = base();
    pattern.push([0.5, 0.5]);
    match run(&pattern) {
        Err(TpiError::DuplicatePatternPoint {
            index,
            duplicate_of,
            distance,
        }) => {
            assert_eq!((index, duplicate_of), (6, 1));
            assert_eq!(distance, 0.0);
        }
        other => panic!("expected DuplicatePatternPoint, got {other:?}"),
    }
    // The duplicate first, the original later: the later index is reported.
    let mut pattern = base();
    pattern.insert(0, [0.75, 0.85]);
    match run(&pattern) {
        Err(TpiError::DuplicatePatternPoint {
            index,
            duplicate_of,
            ..
        }) => assert_eq!((index, duplicate_of), (5, 0)),
        other => panic!("expected DuplicatePatternPoint, got {other:?}"),
    }
}

#[test]
fn near_duplicates_1e_12_apart() {
    for (offset, label) in [
        ([1e-12, 0.0], "along s"),
        ([0.0, -1e-12], "along t"),
        ([7e-13, 7e-13], "diagonal"),
        ([-1e-12, 0.0], "smaller s first"),
    ] {
        let mut pattern = base();
        pattern.push([0.9 + offset[0], 0.3 + offset[1]]);
        match run(&pattern) {
            Err(TpiError::DuplicatePatternPoint {
                index,
                duplicate_of,
                distance,
            }) => {
                assert_eq!((index, duplicate_of), (6, 2), "{label}");
                let expected = (offset[0] * offset[0] + offset[1] * offset[1]).sqrt();
                assert!(
                    (distance - expected).abs() < 1e-15,
                    "{label}: distance {distance:e}, expected {expected:e}"
                );
            }
            other => panic!("{label}: expected DuplicatePatternPoint, got {other:?}"),
        }
    }
    // Two points well above the duplicate tolerance (1e-9) are distinct.
    let mut pattern = base();
    pattern.push([0.9 + 1e-6, 0.3]);
    let d = run(&pattern).expect("points 1e-6 apart are not duplicates");
    assert_eq!(d.facet_count(), 7);
    assert!(d.vertices.iter().all(|v| v.is_finite()));
}

#[test]
fn nan_and_out_of_range_points() {
    let cases: [([f64; 2], &str); 8] = [
        ([f64::NAN, 0.5], "NaN s"),
        ([0.5, f64::NAN], "NaN t"),
        ([f64::INFINITY, 0.5], "inf"),
        ([0.5, f64::NEG_INFINITY], "-inf"),
        ([-1e-9, 0.5], "below 0"),
        ([0.5, 1.0 + f64::EPSILON], "above 1"),
        ([1.5, 0.5], "1.5"),
        ([-0.0 - 1e-300, 0.2], "tiny negative"),
    ];
    for (bad, label) in cases {
        for at in [0usize, 3, 6] {
            let mut pattern = base();
            pattern.insert(at, bad);
            match run(&pattern) {
                Err(TpiError::PatternPointOutOfRange { index, s, t }) => {
                    assert_eq!(index, at, "{label}");
                    assert_eq!(s.to_bits(), bad[0].to_bits(), "{label}");
                    assert_eq!(t.to_bits(), bad[1].to_bits(), "{label}");
                }
                other => panic!("{label} at {at}: expected PatternPointOutOfRange, got {other:?}"),
            }
        }
    }
    // The ends of the range are valid.
    let corners = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]];
    let d = run(&corners).expect("points on the range ends are valid");
    assert_eq!(d.facet_count(), 5);
    assert!(d.vertices.iter().all(|v| v.is_finite()));
}

/// Bicubic 14 x 14 net, uniform clamped knots (domain [0, 11]^2): control heights
/// 0.08 max(0, rho - 4.6)^2 with rho the index distance from the net's centre. Wherever all
/// 4 x 4 control points of a span have height 0 the surface is exactly the plane z = 0
/// (K = H = 0); around it a bowl (K > 0) with a transition band where K fades to 0.
fn flat_bottomed_bowl() -> (NurbsSurface, Vec<(usize, usize)>) {
    let n = 14usize;
    let mut knots = vec![0.0, 0.0];
    knots.extend((0..=11).map(|k| k as f64));
    knots.extend([11.0, 11.0]);
    assert_eq!(knots.len(), n + 3 - 1);
    let centre = (n as f64 - 1.0) / 2.0;
    let height = |i: usize, j: usize| {
        let rho = ((i as f64 - centre).powi(2) + (j as f64 - centre).powi(2)).sqrt();
        0.08 * (rho - 4.6).max(0.0).powi(2)
    };
    let s = lifted_net(
        [3, 3],
        &knots,
        &knots,
        |s, t| (4.0 * s, 4.0 * t),
        |_, _, i, j| height(i, j),
        None,
    );
    // Span (a, b) covers u in [a, a + 1], v in [b, b + 1]; control points a..a+3, b..b+3.
    let flat: Vec<(usize, usize)> = (0..11)
        .flat_map(|a| (0..11).map(move |b| (a, b)))
        .filter(|&(a, b)| (a..a + 4).all(|i| (b..b + 4).all(|j| height(i, j) == 0.0)))
        .collect();
    (s, flat)
}

fn partly_flat_case() -> (NurbsSurface, Vec<(usize, usize)>, Vec<[f64; 2]>) {
    let (s, flat_spans) = flat_bottomed_bowl();
    let mut rng = Rng::new(53);
    (s, flat_spans, jittered_pattern(&mut rng, 900))
}

/// Pattern points strictly inside a flat span.
fn flat_points(
    s: &NurbsSurface,
    flat_spans: &[(usize, usize)],
    pattern: &[[f64; 2]],
) -> Vec<usize> {
    let dom = s.domain();
    (0..pattern.len())
        .filter(|&i| {
            let [u, v] = dom.from_normalised(pattern[i]);
            flat_spans.iter().any(|&(a, b)| {
                u > a as f64 && u < a as f64 + 1.0 && v > b as f64 && v < b as f64 + 1.0
            })
        })
        .collect()
}

/// The largest principal curvature |k| from the Gaussian and mean curvatures.
fn kmax(k: f64, h: f64) -> f64 {
    h.abs() + (h * h - k).max(0.0).sqrt()
}

#[test]
fn partly_flat_surface_names_its_flat_points() {
    let (s, flat_spans, pattern) = partly_flat_case();
    let dom = s.domain();
    // Sanity of the construction: exactly flat inside the flat spans.
    let flat_points = flat_points(&s, &flat_spans, &pattern);
    assert!(
        flat_points.len() > 60,
        "only {} points in the flat region ({} spans)",
        flat_points.len(),
        flat_spans.len()
    );
    for &i in &flat_points {
        let [u, v] = dom.from_normalised(pattern[i]);
        let d = s.evaluate(u, v);
        assert!(
            d.point.z == 0.0 && d.suu.z == 0.0 && d.suv.z == 0.0 && d.svv.z == 0.0,
            "not flat at {u} {v}"
        );
    }

    let d = discretise(&s, &pattern, &DiscretiseOptions::default())
        .expect("a partly flat surface is not an error");
    let diag = seed_diagonal(&d);
    assert_eq!(d.facet_count(), pattern.len());

    // FlatPoint names every point of the flat region, and no clearly curved point.
    let named_flat: BTreeSet<u32> = d
        .diagnostics
        .iter()
        .filter_map(|g| {
            if let Diagnostic::FlatPoint { point, .. } = g {
                Some(*point)
            } else {
                None
            }
        })
        .collect();
    let missing: Vec<usize> = flat_points
        .iter()
        .copied()
        .filter(|&i| !named_flat.contains(&(i as u32)))
        .collect();
    assert!(
        missing.is_empty(),
        "flat points without FlatPoint diagnostic: {missing:?}"
    );
    let mut curved_named = Vec::new();
    let mut curved = 0;
    for i in 0..pattern.len() {
        let [u, v] = dom.from_normalised(pattern[i]);
        let (k, h) = gaussian_and_mean(&s, u, v);
        if k > 1e-4 * kmax(k, h).powi(2) {
            curved += 1;
            if named_flat.contains(&(i as u32)) {
                curved_named.push(i);
            }
        }
    }
    assert!(curved > 200, "only {curved} clearly curved points");
    assert!(
        curved_named.is_empty(),
        "curved points named flat: {curved_named:?}"
    );

    // Every dual triangle of three flat points has three coincident planes: its vertex is
    // their Voronoi vertex, the circumcentre of the three seeds in the plane z = 0
    // (planes::meeting_point), not an ill-conditioned stand-in.
    let flat_set: BTreeSet<u32> = flat_points.iter().map(|&i| i as u32).collect();
    let flat_triangles: Vec<[u32; 3]> = d
        .dual_triangles
        .iter()
        .map(|t| {
            let mut t = *t;
            t.sort_unstable();
            t
        })
        .filter(|t| t.iter().all(|p| flat_set.contains(p)))
        .collect();
    assert!(
        flat_triangles.len() > 50,
        "only {} flat triangles",
        flat_triangles.len()
    );
    let ill: Vec<[u32; 3]> = d
        .diagnostics
        .iter()
        .filter_map(|g| match g {
            Diagnostic::IllConditionedVertex { points, .. } => Some(*points),
            _ => None,
        })
        .collect();
    let mut circumcentres = 0;
    for t in &flat_triangles {
        assert!(
            !ill.iter().any(|p| {
                let mut p = *p;
                p.sort_unstable();
                p == *t
            }),
            "flat triangle {t:?} got an ill-conditioned stand-in"
        );
        let [a, b, c] = t.map(|i| d.facet(i as usize).to_vec());
        let shared: Vec<u32> = a
            .iter()
            .copied()
            .filter(|v| b.contains(v) && c.contains(v))
            .collect();
        let seeds = t.map(|i| d.seeds[i as usize].point);
        for v in shared {
            let x = d.vertices[v as usize];
            let r = seeds.map(|p| x.distance(p));
            let spread = r.iter().fold(0.0f64, |m, &x| m.max(x))
                - r.iter().fold(f64::INFINITY, |m, &x| m.min(x));
            assert!(
                spread <= 1e-9 * diag && x.z.abs() <= 1e-9 * diag,
                "flat triangle {t:?}: vertex {x} is not the circumcentre of {seeds:?} ({r:?})"
            );
            circumcentres += 1;
        }
    }
    assert!(
        circumcentres > 50,
        "only {circumcentres} flat circumcentres checked"
    );
    assert!(d
        .diagnostics
        .iter()
        .any(|g| matches!(g, Diagnostic::CoincidentPlanes { .. })));
    println!("partly flat: {} flat spans, {} flat points, {} FlatPoint, {} IllConditionedVertex, {} flat triangles", flat_spans.len(), flat_points.len(), named_flat.len(), ill.len(), flat_triangles.len());
}
