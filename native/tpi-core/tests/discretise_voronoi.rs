//! Acceptance: on the paraboloid of revolution z = c (x^2 + y^2) the top view of the mesh is
//! the Voronoi diagram of the projected pattern points (DESIGN.md, geometry item 3; paper,
//! figure 5).
//!
//! The Voronoi oracle is computed in the test: the Delaunay triangulation of the projected
//! points by a plain Bowyer-Watson written here (checked afterwards by brute force: every
//! triangle's circumcircle is empty), or for the grids by brute force over local triples
//! (every triple among a point's 12 nearest neighbours whose circumcircle is empty), and the
//! Voronoi vertices are the distinct circumcentres.
//!
//! Both directions are checked to 1e-9 of the bounding-box diagonal:
//! - every Interior mesh vertex projects onto a point equidistant from the seeds of the facets
//!   meeting there, with no seed closer (empty circle, brute force over all seeds);
//! - every Voronoi vertex inside the domain, farther than 1e-6 from its boundary, is the top
//!   view of an Interior mesh vertex. (On the centred square domain the meeting point of the
//!   three planes lies below the paraboloid and its closest surface point is radially inward
//!   from the circumcentre, hence inside the domain too: such a vertex must be kept.)
// NaN-safe negated comparisons are intended; index loops read better in geometry checks.
#![allow(
    clippy::neg_cmp_op_on_partial_ord,
    clippy::needless_range_loop,
    clippy::unnecessary_map_or
)]

mod common;

use common::*;
use glam::DVec2;
use tpi_core::VertexKind;
use tpi_core::{discretise, AnalyticSurface, Discretisation, DiscretiseOptions};

const TOL: f64 = 1e-9;
const C: f64 = 0.6;

fn surface() -> AnalyticSurface {
    AnalyticSurface::elliptic_paraboloid(C, C, [-1.0, 1.0], [-1.0, 1.0]).unwrap()
}

fn to_xy(st: [f64; 2]) -> DVec2 {
    DVec2::new(-1.0 + 2.0 * st[0], -1.0 + 2.0 * st[1])
}

/// Circumcentre of three points (own formula), None when collinear.
fn circumcentre(a: DVec2, b: DVec2, c: DVec2) -> Option<DVec2> {
    let (b, c) = (b - a, c - a);
    let d = 2.0 * (b.x * c.y - b.y * c.x);
    if d == 0.0 {
        return None;
    }
    let (bb, cc) = (b.length_squared(), c.length_squared());
    Some(a + DVec2::new((c.y * bb - b.y * cc) / d, (b.x * cc - c.x * bb) / d))
}

/// Bowyer-Watson Delaunay triangulation (indices into `p`), super-triangle removed.
fn bowyer_watson(p: &[DVec2]) -> Vec<[usize; 3]> {
    let n = p.len();
    let mut pts = p.to_vec();
    let big = 1e4;
    pts.push(DVec2::new(-big, -big));
    pts.push(DVec2::new(big, -big));
    pts.push(DVec2::new(0.0, big));
    struct Tri {
        v: [usize; 3],
        centre: DVec2,
        r2: f64,
    }
    let make = |pts: &[DVec2], v: [usize; 3]| {
        let centre =
            circumcentre(pts[v[0]], pts[v[1]], pts[v[2]]).unwrap_or(DVec2::splat(f64::INFINITY));
        Tri {
            v,
            centre,
            r2: centre.distance_squared(pts[v[0]]),
        }
    };
    let mut tris = vec![make(&pts, [n, n + 1, n + 2])];
    for i in 0..n {
        let q = pts[i];
        let (bad, good): (Vec<Tri>, Vec<Tri>) = tris
            .into_iter()
            .partition(|t| t.centre.distance_squared(q) < t.r2);
        tris = good;
        let mut edges: Vec<(usize, usize)> = Vec::new();
        for t in &bad {
            for k in 0..3 {
                edges.push((t.v[k], t.v[(k + 1) % 3]));
            }
        }
        for &(a, b) in &edges {
            if !edges.contains(&(b, a)) {
                // Keep counter-clockwise orientation: the cavity edge (a, b) plus q.
                tris.push(make(&pts, [a, b, i]));
            }
        }
    }
    tris.into_iter()
        .filter(|t| t.v.iter().all(|&v| v < n))
        .map(|t| t.v)
        .collect()
}

/// Delaunay triangles by brute force over the triples of each point's 12 nearest neighbours
/// (complete for lattices, where every Delaunay neighbour is among the 8 nearest).
fn local_brute_force(p: &[DVec2]) -> Vec<[usize; 3]> {
    let n = p.len();
    let mut out = Vec::new();
    for i in 0..n {
        let mut near: Vec<(f64, usize)> = (0..n)
            .filter(|&j| j != i)
            .map(|j| (p[i].distance_squared(p[j]), j))
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        near.truncate(12);
        for a in 0..near.len() {
            for b in a + 1..near.len() {
                let (j, k) = (near[a].1, near[b].1);
                if !(i < j && i < k) {
                    continue;
                }
                let Some(m) = circumcentre(p[i], p[j], p[k]) else {
                    continue;
                };
                let r = m.distance(p[i]);
                if (0..n).all(|l| p[l].distance(m) >= r * (1.0 - 1e-12)) {
                    out.push([i, j, k]);
                }
            }
        }
    }
    out
}

/// Distinct circumcentres (merged within `tol`).
fn distinct_centres(p: &[DVec2], tris: &[[usize; 3]], tol: f64) -> Vec<DVec2> {
    let mut centres: Vec<DVec2> = tris
        .iter()
        .filter_map(|t| circumcentre(p[t[0]], p[t[1]], p[t[2]]))
        .collect();
    centres.sort_by(|a, b| a.x.total_cmp(&b.x));
    let mut out: Vec<DVec2> = Vec::new();
    for c in centres {
        let duplicate = out
            .iter()
            .rev()
            .take_while(|o| c.x - o.x <= tol)
            .any(|o| o.distance(c) <= tol);
        if !duplicate {
            out.push(c);
        }
    }
    out
}

struct Outcome {
    interior_vertices: usize,
    voronoi_inside: usize,
    max_equidistance: f64,
    valences: Vec<usize>,
}

/// Both directions of the Voronoi check; `centres` are the oracle's Voronoi vertices.
fn check(
    name: &str,
    d: &Discretisation,
    pattern: &[[f64; 2]],
    centres: &[DVec2],
) -> (Outcome, Vec<String>) {
    let mut fail = Vec::new();
    let diag = seed_diagonal(d);
    let tol = TOL * diag;
    let q: Vec<DVec2> = pattern.iter().map(|&st| to_xy(st)).collect();
    let owners = vertex_facets(d);
    let (planarity, worst) = max_planarity(d, diag);
    if !(planarity <= TOL) {
        fail.push(format!(
            "{name}: planarity error {planarity:e} at facet {worst}"
        ));
    }
    if let Some(v) = d.vertices.iter().position(|v| !v.is_finite()) {
        fail.push(format!("{name}: vertex {v} not finite"));
    }
    let mut outcome = Outcome {
        interior_vertices: 0,
        voronoi_inside: 0,
        max_equidistance: 0.0,
        valences: Vec::new(),
    };
    let mut interior: Vec<DVec2> = Vec::new();
    let mut bad = 0;
    for (v, &kind) in d.vertex_kinds.iter().enumerate() {
        if kind != VertexKind::Interior || owners[v].is_empty() {
            continue;
        }
        outcome.interior_vertices += 1;
        outcome.valences.push(owners[v].len());
        let m = d.vertices[v].truncate();
        interior.push(m);
        let distances: Vec<f64> = owners[v].iter().map(|&f| q[f].distance(m)).collect();
        let (lo, hi) = distances
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            });
        outcome.max_equidistance = outcome.max_equidistance.max((hi - lo) / diag);
        let closer = (0..q.len()).find(|&k| q[k].distance(m) < lo - tol);
        if owners[v].len() < 3 || hi - lo > tol || closer.is_some() {
            bad += 1;
            if bad <= 5 {
                fail.push(format!(
                    "{name}: interior vertex {v} at {m} (facets {:?}) is no Voronoi vertex: distances to its seeds {lo} .. {hi}, seed {closer:?} closer",
                    owners[v]
                ));
            }
        }
    }
    if bad > 5 {
        fail.push(format!(
            "{name}: {bad} interior vertices are no Voronoi vertices"
        ));
    }
    interior.sort_by(|a, b| a.x.total_cmp(&b.x));
    let mut missing = 0;
    for &c in centres {
        let margin = (1.0 - c.x.abs()).min(1.0 - c.y.abs());
        if margin <= 1e-6 {
            continue;
        }
        outcome.voronoi_inside += 1;
        let start = interior.partition_point(|v| v.x < c.x - tol);
        let found = interior[start..]
            .iter()
            .take_while(|v| v.x <= c.x + tol)
            .any(|v| v.distance(c) <= tol);
        if !found {
            missing += 1;
            if missing <= 5 {
                fail.push(format!("{name}: Voronoi vertex {c} (margin {margin:.3e} from the boundary) is no mesh vertex"));
            }
        }
    }
    if missing > 5 {
        fail.push(format!(
            "{name}: {missing} Voronoi vertices missing from the mesh"
        ));
    }
    (outcome, fail)
}

#[test]
fn voronoi_random_patterns() {
    let s = surface();
    let mut rng = Rng::new(31);
    let mut failures = Vec::new();
    for (k, n) in [300usize, 900, 1600].into_iter().enumerate() {
        let pattern = if k == 1 {
            jittered_pattern(&mut rng, n)
        } else {
            uniform_pattern(&mut rng, n)
        };
        let name = format!("random n={n}");
        let d = discretise(&s, &pattern, &DiscretiseOptions::default()).unwrap();
        let p: Vec<DVec2> = pattern.iter().map(|&st| to_xy(st)).collect();
        let tris = bowyer_watson(&p);
        // The oracle's own check: Euler's formula and empty circumcircles.
        for t in &tris {
            let m = circumcentre(p[t[0]], p[t[1]], p[t[2]]).unwrap();
            let r = m.distance(p[t[0]]);
            assert!(
                p.iter().all(|x| x.distance(m) >= r * (1.0 - 1e-12)),
                "oracle: triangle {t:?} not Delaunay"
            );
        }
        let centres = distinct_centres(&p, &tris, 1e-12);
        let (o, f) = check(&name, &d, &pattern, &centres);
        println!(
            "{name}: {} Delaunay triangles, {} Voronoi vertices inside, {} interior mesh vertices, max equidistance error {:.2e}",
            tris.len(),
            o.voronoi_inside,
            o.interior_vertices,
            o.max_equidistance
        );
        assert!(
            o.voronoi_inside > n,
            "{name}: too few Voronoi vertices inside ({})",
            o.voronoi_inside
        );
        failures.extend(f);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Square (rectangular) grid: four cocircular points per cell, four planes through one point.
#[test]
fn voronoi_square_grid_welds_four_planes() {
    let s = surface();
    let (nx, ny) = (18usize, 14usize);
    let pattern: Vec<[f64; 2]> = (0..ny)
        .flat_map(|j| {
            (0..nx).map(move |i| [(i as f64 + 0.5) / nx as f64, (j as f64 + 0.5) / ny as f64])
        })
        .collect();
    let d = discretise(&s, &pattern, &DiscretiseOptions::default()).unwrap();
    let p: Vec<DVec2> = pattern.iter().map(|&st| to_xy(st)).collect();
    let tris = local_brute_force(&p);
    let centres = distinct_centres(&p, &tris, 1e-9);
    // Rounding makes the collinear hull rows slightly convex or concave, so a few slivers
    // with huge circles far outside the domain may appear; inside there is one vertex per cell.
    let inside: Vec<DVec2> = centres
        .iter()
        .copied()
        .filter(|c| c.x.abs() < 1.0 && c.y.abs() < 1.0)
        .collect();
    assert_eq!(
        inside.len(),
        (nx - 1) * (ny - 1),
        "oracle: a rectangular grid has one Voronoi vertex per cell"
    );
    assert!(
        centres
            .iter()
            .all(|c| c.x.abs() < 0.95 || c.y.abs() < 0.95 || c.length() > 10.0),
        "oracle: unexpected centre near the boundary"
    );
    let (o, f) = check("square grid", &d, &pattern, &centres);
    println!("square grid {nx}x{ny}: {} Voronoi vertices inside, {} interior mesh vertices, valences {:?}", inside.len(), o.interior_vertices, histogram(&o.valences));
    assert!(f.is_empty(), "{}", f.join("\n"));
    assert_eq!(
        o.interior_vertices,
        inside.len(),
        "interior vertex count vs distinct Voronoi vertices"
    );
    assert!(
        o.valences.iter().all(|&v| v == 4),
        "valences {:?}",
        histogram(&o.valences)
    );
}

/// Hexagonal grid: rows offset by half a spacing (0.25 and 0.75 of a cell, so that the
/// circumcentres of the triangles on the left and right hull lie a quarter spacing outside
/// the domain, never on its boundary).
#[test]
fn voronoi_hex_grid() {
    let s = surface();
    let nx = 16usize;
    let ny = (nx as f64 * 2.0 / 3f64.sqrt()).round() as usize;
    let pattern: Vec<[f64; 2]> = (0..ny)
        .flat_map(|j| {
            let offset = if j % 2 == 0 { 0.25 } else { 0.75 };
            (0..nx).map(move |i| {
                [
                    (i as f64 + offset) / nx as f64,
                    (j as f64 + 0.5) / ny as f64,
                ]
            })
        })
        .collect();
    let d = discretise(&s, &pattern, &DiscretiseOptions::default()).unwrap();
    let p: Vec<DVec2> = pattern.iter().map(|&st| to_xy(st)).collect();
    let tris = local_brute_force(&p);
    let centres = distinct_centres(&p, &tris, 1e-9);
    let dx = 2.0 / nx as f64;
    let inside: Vec<DVec2> = centres
        .iter()
        .copied()
        .filter(|c| c.x.abs() < 1.0 && c.y.abs() < 1.0)
        .collect();
    for c in &centres {
        let margin = (1.0 - c.x.abs()).min(1.0 - c.y.abs()).abs();
        assert!(
            margin > 0.2 * dx,
            "oracle: Voronoi vertex {c} too close to the boundary"
        );
    }
    let (o, f) = check("hex grid", &d, &pattern, &centres);
    println!(
        "hex grid {nx}x{ny}: {} Voronoi vertices inside, {} interior mesh vertices, valences {:?}",
        inside.len(),
        o.interior_vertices,
        histogram(&o.valences)
    );
    assert!(f.is_empty(), "{}", f.join("\n"));
    assert_eq!(
        o.interior_vertices,
        inside.len(),
        "interior vertex count vs distinct Voronoi vertices inside the domain"
    );
    assert!(
        o.valences.iter().all(|&v| v == 3),
        "valences {:?}",
        histogram(&o.valences)
    );
}

fn histogram(v: &[usize]) -> std::collections::BTreeMap<usize, usize> {
    let mut h = std::collections::BTreeMap::new();
    for &x in v {
        *h.entry(x).or_insert(0) += 1;
    }
    h
}
