//! Mesh validity as DESIGN.md item 8 defines it, checked independently of the crate's quality
//! report: every facet has at least 3 distinct vertices and a simple, counter-clockwise loop in
//! its own tangent plane; no two facets that share a vertex overlap when projected along the
//! mean of their two seed normals (intersection area from the `geo` polygon library); the mesh
//! is a disc (Euler characteristic and boundary loops from the loops alone).
// Test helpers: `pub` is how the test files that include this module reach them.
#![allow(unreachable_pub)]

use std::collections::BTreeSet;

use geo::{Area, BooleanOps, Coord, LineString, Polygon};
use glam::{DVec2, DVec3};
use tpi_core::Discretisation;

use super::{facet_points, frame, is_simple, to_2d, topology};

/// Two facets overlap when the area of their projected intersection exceeds this fraction of
/// the smaller facet's projected area (shared edges and vertices give zero area up to rounding).
pub const OVERLAP_AREA_FRACTION: f64 = 1e-6;

/// What the independent check found.
#[derive(Debug, Default, Clone)]
pub struct Validity {
    /// Facets with fewer than 3 distinct vertices.
    pub open: Vec<usize>,
    /// Facets whose loop is not simple and counter-clockwise in their own plane.
    pub non_simple: Vec<usize>,
    /// Pairs (f < g) of facets sharing a vertex that overlap along their mean normal.
    pub overlapping_pairs: Vec<(usize, usize)>,
    /// Euler characteristic V - E + F.
    pub euler: i64,
    /// Boundary loops.
    pub boundary_loops: usize,
    /// Non-manifold edges or vertices, inconsistent orientation.
    pub topology_problems: usize,
}

impl Validity {
    /// Facets that are open, non-simple or in an overlapping pair (each once).
    pub fn invalid_facets(&self) -> BTreeSet<usize> {
        let mut out: BTreeSet<usize> = self.open.iter().chain(&self.non_simple).copied().collect();
        for &(f, g) in &self.overlapping_pairs {
            out.insert(f);
            out.insert(g);
        }
        out
    }

    /// The facets this check finds invalid that `d`'s report does not flag invalid.
    pub fn unflagged(&self, d: &Discretisation) -> Vec<usize> {
        self.invalid_facets()
            .into_iter()
            .filter(|&i| d.facet_flags[i] & tpi_core::INVALID_FLAGS == 0)
            .collect()
    }

    /// A disc: Euler characteristic 1, one boundary loop, no topology problem.
    pub fn is_disc(&self) -> bool {
        self.euler == 1 && self.boundary_loops == 1 && self.topology_problems == 0
    }
}

fn polygon(points: &[DVec2]) -> Polygon<f64> {
    let ring: Vec<Coord<f64>> = points.iter().map(|p| Coord { x: p.x, y: p.y }).collect();
    Polygon::new(LineString::from(ring), vec![])
}

/// Runs every check on `d`.
pub fn check(d: &Discretisation) -> Validity {
    let n = d.facet_count();
    let mut v = Validity::default();
    let points: Vec<Vec<DVec3>> = (0..n).map(|i| facet_points(d, i)).collect();
    for i in 0..n {
        let distinct: BTreeSet<u32> = d.facet(i).iter().copied().collect();
        if distinct.len() < 3 {
            v.open.push(i);
            continue;
        }
        if !is_simple(&to_2d(d.seeds[i].point, d.seeds[i].normal, &points[i])) {
            v.non_simple.push(i);
        }
    }
    // Pairs sharing a vertex.
    let mut facets_of: Vec<Vec<usize>> = vec![Vec::new(); d.vertices.len()];
    for i in 0..n {
        for &x in d.facet(i) {
            if facets_of[x as usize].last() != Some(&i) {
                facets_of[x as usize].push(i);
            }
        }
    }
    let mut pairs = BTreeSet::new();
    for list in &facets_of {
        for (a, &f) in list.iter().enumerate() {
            for &g in &list[a + 1..] {
                pairs.insert((f.min(g), f.max(g)));
            }
        }
    }
    // Open and non-simple facets are invalid already; `geo` wants simple rings.
    let mut skip = vec![false; n];
    for &i in v.open.iter().chain(&v.non_simple) {
        skip[i] = true;
    }
    for (f, g) in pairs {
        if skip[f] || skip[g] {
            continue;
        }
        let Some(normal) = (d.seeds[f].normal + d.seeds[g].normal).try_normalize() else {
            continue;
        };
        let (e1, e2) = frame(normal);
        let flat = |xs: &[DVec3]| -> Vec<DVec2> {
            xs.iter()
                .map(|&x| DVec2::new(x.dot(e1), x.dot(e2)))
                .collect()
        };
        let (pf, pg) = (polygon(&flat(&points[f])), polygon(&flat(&points[g])));
        let smaller = pf.unsigned_area().min(pg.unsigned_area());
        // A panic inside the polygon library counts as an overlap (never as valid).
        let common = std::panic::catch_unwind(|| pf.intersection(&pg).unsigned_area())
            .unwrap_or(f64::INFINITY);
        if !(common <= OVERLAP_AREA_FRACTION * smaller) {
            v.overlapping_pairs.push((f, g));
        }
    }
    let t = topology(d);
    v.euler = t.euler;
    v.boundary_loops = t.boundary_loops;
    v.topology_problems = t.problems.len();
    v
}
