//! End-to-end checks of the discretisation against oracles computed here, independently of
//! the production code: the Voronoi diagram for a paraboloid of revolution (DESIGN.md, item 3),
//! plane distances for planarity, and mesh topology counted from the facet loops.

use std::collections::{HashMap, HashSet};

use glam::DVec3;
use tpi_core::VertexKind;
use tpi_core::{discretise, AnalyticSurface, DiscretiseOptions, Surface, TpiError};

fn random_points(n: usize, mut seed: u64) -> Vec<[f64; 2]> {
    let mut next = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(|_| [next(), next()]).collect()
}

/// Euler characteristic and boundary edge count, from the loops alone.
fn topology(loops: &[Vec<u32>]) -> (i64, usize) {
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    let mut vertices = HashSet::new();
    for l in loops {
        for k in 0..l.len() {
            let (a, b) = (l[k], l[(k + 1) % l.len()]);
            *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            vertices.insert(a);
        }
    }
    let boundary = edges.values().filter(|&&c| c == 1).count();
    (
        vertices.len() as i64 - edges.len() as i64 + loops.len() as i64,
        boundary,
    )
}

fn check_valid_disc(surface: &dyn Surface, n: usize, seed: u64) {
    let pattern = random_points(n, seed);
    let result = discretise(surface, &pattern, &DiscretiseOptions::default()).expect("discretises");
    assert_eq!(result.facet_count(), n, "no facet dropped");
    result.sanity_check().expect("structural contract");
    let loops: Vec<Vec<u32>> = (0..n).map(|i| result.facet(i).to_vec()).collect();
    let (euler, boundary_edges) = topology(&loops);
    assert_eq!(euler, 1, "a disc");
    assert!(boundary_edges > 0);
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for v in &result.vertices {
        assert!(v.is_finite());
        lo = lo.min(*v);
        hi = hi.max(*v);
    }
    let diagonal = (hi - lo).length();
    for (i, l) in loops.iter().enumerate() {
        assert!(l.len() >= 3, "facet {i} has {} vertices", l.len());
        let seed = &result.seeds[i];
        for &v in l {
            let distance = seed
                .normal
                .dot(result.vertices[v as usize] - seed.point)
                .abs();
            assert!(
                distance <= 1e-9 * diagonal,
                "facet {i} not planar: {distance}"
            );
        }
        // Counter-clockwise seen from the normal: positive signed area.
        let mut area = DVec3::ZERO;
        for k in 0..l.len() {
            area += result.vertices[l[k] as usize]
                .cross(result.vertices[l[(k + 1) % l.len()] as usize]);
        }
        assert!(area.dot(seed.normal) > 0.0, "facet {i} runs clockwise");
    }
    assert_eq!(result.quality.as_ref().map(|q| q.flagged_facets), Some(0));
}

#[test]
fn paraboloid_of_revolution_gives_the_voronoi_diagram() {
    let surface = AnalyticSurface::elliptic_paraboloid(0.7, 0.7, [-1.0, 1.0], [-1.0, 1.0]).unwrap();
    for seed in [1u64, 2, 3] {
        let pattern = random_points(300, seed);
        let result = discretise(&surface, &pattern, &DiscretiseOptions::default()).unwrap();
        let sites: Vec<[f64; 2]> = result
            .seeds
            .iter()
            .map(|s| [s.point.x, s.point.y])
            .collect();
        let mut facets_of: HashMap<u32, Vec<usize>> = HashMap::new();
        for i in 0..result.facet_count() {
            for &v in result.facet(i) {
                facets_of.entry(v).or_default().push(i);
            }
        }
        let mut checked = 0;
        for (v, facets) in &facets_of {
            if result.vertex_kinds[*v as usize] != VertexKind::Interior {
                continue;
            }
            let x = result.vertices[*v as usize];
            let d = |i: usize| (sites[i][0] - x.x).hypot(sites[i][1] - x.y);
            let radius = d(facets[0]);
            for &f in facets {
                assert!((d(f) - radius).abs() <= 1e-9, "vertex {v} not equidistant");
            }
            let nearest = (0..sites.len()).map(d).fold(f64::INFINITY, f64::min);
            assert!(
                nearest >= radius - 1e-9,
                "vertex {v}: a site is closer than its facets' seeds"
            );
            checked += 1;
        }
        assert!(checked > 400, "checked {checked} Voronoi vertices");
    }
}

#[test]
fn sphere_cap_gives_a_planar_disc() {
    check_valid_disc(
        &AnalyticSurface::sphere_cap_square(2.0, 1.0).unwrap(),
        500,
        11,
    );
}

#[test]
fn anisotropic_paraboloid_gives_a_planar_disc() {
    check_valid_disc(
        &AnalyticSurface::elliptic_paraboloid(1.0, 10.0, [-1.0, 1.0], [-1.0, 1.0]).unwrap(),
        800,
        12,
    );
}

#[test]
fn degenerate_input_gets_specific_errors() {
    let paraboloid =
        AnalyticSurface::elliptic_paraboloid(1.0, 1.0, [-1.0, 1.0], [-1.0, 1.0]).unwrap();
    let options = DiscretiseOptions::default();
    assert_eq!(
        discretise(&paraboloid, &[[0.1, 0.1], [0.5, 0.5]], &options).unwrap_err(),
        TpiError::TooFewPatternPoints {
            found: 2,
            needed: 3
        }
    );
    let collinear: Vec<[f64; 2]> = (0..10).map(|k| [0.05 + 0.09 * k as f64, 0.5]).collect();
    assert_eq!(
        discretise(&paraboloid, &collinear, &options).unwrap_err(),
        TpiError::CollinearPattern { count: 10 }
    );
}

#[test]
fn one_and_two_threads_give_identical_json() {
    let surface = AnalyticSurface::sphere_cap_square(2.0, 1.0).unwrap();
    let pattern = random_points(700, 31);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            discretise(&surface, &pattern, &DiscretiseOptions::default())
                .unwrap()
                .to_json(false)
        })
    };
    let one = run(1);
    assert_eq!(one, run(2));
    assert_eq!(one, run(2));
}
