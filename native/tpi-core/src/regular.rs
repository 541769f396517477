//! The envelope's dual structure built directly: the regular triangulation of the lifted
//! slopes by incremental insertion, without a Delaunay triangulation to flip from.
//!
//! **Geometry.** On a convex surface the envelope of the tangent planes is dual to the lower
//! convex hull of the lifted points P_i = (s_i, h_i) (slopes s_i in the slope frame, heights
//! h_i; [`crate::neighbours::SlopeFrame::lift`]): its triangles are the regular triangulation
//! of the slopes. Every plane touches the envelope, so every P_i is on that hull (no point is
//! redundant) and the triangulation covers the convex hull of the slopes.
//!
//! **Construction** (Edelsbrunner and Shah's incremental flipping, with an infinite vertex
//! as in CGAL's triangulations). The points are inserted along a Hilbert curve of their slopes,
//! so that each point is found by a short walk from the last one. The hull is closed by *ghost*
//! triangles (b, a, oo), one beyond each hull edge a -> b, so that a point outside the hull
//! falls in a ghost. A point p is located by a visibility walk (orient2d), inserted by
//! splitting its triangle in three (or, exactly on an edge, as in grids and lattices, the two
//! triangles beside the edge in four), and the edges opposite p are made legal by flips:
//! - between two real triangles (p, a, b) and (b, a, d), by the exact power test with its
//!   symbolic tie-break ([`crate::predicates::power_below`], the envelope flips' test for a
//!   counter-clockwise triangle): the edge (a, b) is illegal when P_d lies below the plane
//!   through P_p, P_a, P_b, and is flipped where the quadrilateral is strictly convex;
//! - between two ghosts (p, a, oo) and (a, d, oo) (p outside the hull), when p strictly sees
//!   the hull edge d -> a: orient2d(p, a, d) > 0, the flip making the real triangle (p, a, d);
//!   likewise (p, oo, b) and (b, oo, d) with orient2d(p, d, b) > 0 (p on the edge's line,
//!   beyond it, makes its end a hull vertex between collinear hull edges: no flip);
//! - a hull edge between a real triangle and a ghost stays.
//!
//! The power test's tie-break is one generic lifting, so the result is the unique regular
//! triangulation of the perturbed points, the one the Delaunay-then-flip path
//! ([`crate::neighbours::decide_convex`]) reaches whatever its flip order: the two paths give
//! the same triangles. Where that uniqueness argument does not hold or the input is
//! degenerate, the builder gives up (None) and the caller takes the Delaunay-then-flip path:
//! fewer than three points, all of them collinear, two with the same slopes, a redundant point
//! (P_p on or above its triangle's plane or lifted edge, or an illegal edge whose
//! quadrilateral is not convex: a flip could not remove it), a walk or a flip count beyond
//! its budget.

#[cfg(test)]
use crate::predicates::power_illegal;
use crate::predicates::{orient2d, power_below};
use crate::triangulation::DualTriangulation;
#[cfg(test)]
use crate::triangulation::NO_TRIANGLE;

/// Walk steps allowed per inserted point before the builder gives up (a visibility walk in a
/// regular triangulation may cycle; a Hilbert-ordered walk takes a few steps).
const WALK_STEPS_PER_POINT: usize = 10_000;

/// Flips allowed per point (amortised: an insertion flips about three edges on average).
const FLIPS_PER_POINT: usize = 64;

/// The regular triangulation of the `lifted` points (slopes, then height) in slope space:
/// counter-clockwise, hull edges [`crate::triangulation::NO_TRIANGLE`]; None where the module
/// doc says the builder gives up.
pub(crate) fn regular_triangulation(lifted: &[[f64; 3]]) -> Option<DualTriangulation> {
    let n = lifted.len();
    if n < 3 || n >= u32::MAX as usize / 2 {
        return None;
    }
    // The builder numbers the points in Hilbert order (consecutive points near in memory
    // too); the tie-break keys stay the pattern indices.
    let order = hilbert_order(lifted)?;
    let local: Vec<[f64; 3]> = order.iter().map(|&i| lifted[i as usize]).collect();
    let mut builder = Builder {
        lifted: &local,
        keys: &order,
        infinite: n as u32,
        tri: DualTriangulation {
            triangles: Vec::with_capacity(2 * n + 2),
            neighbours: Vec::with_capacity(2 * n + 2),
        },
        stack: Vec::new(),
        flips_left: FLIPS_PER_POINT.saturating_mul(n),
    };
    let third =
        (2..n as u32).find(|&c| orient2d(builder.at(0), builder.at(1), builder.at(c)) != 0.0)?;
    let mut last = builder.start(0, 1, third);
    for p in 2..n as u32 {
        if p != third {
            last = builder.insert(p, last)?;
        }
    }
    let mut tri = builder.tri;
    tri.retain_points(n);
    for t in &mut tri.triangles {
        *t = t.map(|v| order[v as usize]);
    }
    Some(tri)
}

/// Point indices sorted along a Hilbert curve over the slopes' bounding box (ties by index);
/// None where a slope is not finite.
fn hilbert_order(lifted: &[[f64; 3]]) -> Option<Vec<u32>> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for s in lifted {
        for k in 0..2 {
            if !s[k].is_finite() {
                return None;
            }
            lo[k] = lo[k].min(s[k]);
            hi[k] = hi[k].max(s[k]);
        }
    }
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if !(size > 0.0) || !size.is_finite() {
        return None;
    }
    let mut keyed: Vec<(u64, u32)> = lifted
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let unit = [(s[0] - lo[0]) / size, (s[1] - lo[1]) / size];
            (hilbert_key(unit), i as u32)
        })
        .collect();
    keyed.sort_unstable();
    Some(keyed.into_iter().map(|(_, i)| i).collect())
}

/// Position of a point of the unit square along a Hilbert curve of 2^16 cells a side (also
/// the live state's point order).
pub(crate) fn hilbert_key(p: [f64; 2]) -> u64 {
    const N: u32 = 1 << 16;
    let cell = |t: f64| ((t.clamp(0.0, 1.0) * f64::from(N)) as u32).min(N - 1);
    let (mut x, mut y) = (cell(p[0]), cell(p[1]));
    let mut d = 0u64;
    let mut s = N / 2;
    while s > 0 {
        let rx = u32::from(x & s > 0);
        let ry = u32::from(y & s > 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        if ry == 0 {
            if rx == 1 {
                x = N - 1 - x;
                y = N - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
}

/// Where a walk found a point.
enum Located {
    /// Strictly inside this real triangle, or strictly beyond this ghost's hull edge.
    In(u32),
    /// Inside the edge opposite vertex k of this real triangle (between its ends).
    OnEdge(u32, usize),
    /// On an edge (a hull edge included), or the walk ran out of steps.
    Degenerate,
}

/// The triangulation under construction: real triangles and ghosts (with the vertex
/// `infinite`), all counter-clockwise, in [`DualTriangulation`]'s layout.
struct Builder<'a> {
    /// Slopes and heights in the builder's numbering (the slopes read from here: one array
    /// for the walk and the tests).
    lifted: &'a [[f64; 3]],
    /// Per point in the builder's numbering, its pattern index: the key of the tie-break.
    keys: &'a [u32],
    infinite: u32,
    tri: DualTriangulation,
    /// Triangles (with the new point's position in them) whose edge opposite the new point
    /// is still to be tested.
    stack: Vec<(u32, usize)>,
    flips_left: usize,
}

impl Builder<'_> {
    fn at(&self, i: u32) -> [f64; 2] {
        let [x, y, _] = self.lifted[i as usize];
        [x, y]
    }

    /// The first triangle (a, b, c), made counter-clockwise, and its three ghosts; returns
    /// the real triangle.
    fn start(&mut self, a: u32, b: u32, c: u32) -> u32 {
        let (a, b) = if orient2d(self.at(a), self.at(b), self.at(c)) > 0.0 {
            (a, b)
        } else {
            (b, a)
        };
        let oo = self.infinite;
        // 0 = (a, b, c); the ghost beyond edge (x, y) of it is (y, x, oo).
        // 1 = (c, b, oo) beyond (b, c), 2 = (a, c, oo) beyond (c, a), 3 = (b, a, oo) beyond (a, b).
        self.tri
            .triangles
            .extend([[a, b, c], [c, b, oo], [a, c, oo], [b, a, oo]]);
        self.tri.neighbours.extend([
            [1, 2, 3],
            // (c, b, oo): opposite c the edge (b, oo), held by (b, a, oo) as oo -> b; opposite
            // b the edge (oo, c), held by (a, c, oo) as c -> oo; opposite oo the real triangle.
            [3, 2, 0],
            // (a, c, oo): opposite a (c, oo), held by (c, b, oo) as oo -> c; opposite c
            // (oo, a), held by (b, a, oo) as a -> oo.
            [1, 3, 0],
            // (b, a, oo): opposite b (a, oo), held by (a, c, oo); opposite a (oo, b), held by
            // (c, b, oo).
            [2, 1, 0],
        ]);
        0
    }

    /// Whether P_d lies strictly below the plane through P_c, P_a, P_b for counter-clockwise
    /// (c, a, b), the tie broken by the point keys ([`power_below`]).
    fn below(&self, ids: [u32; 4]) -> bool {
        let [c, a, b, d] = ids.map(|i| i as usize);
        let l = self.lifted;
        let k = self.keys;
        power_below([&l[c], &l[a], &l[b], &l[d]], [k[c], k[a], k[b], k[d]])
    }

    fn is_ghost(&self, t: u32) -> bool {
        self.tri.triangles[t as usize].contains(&self.infinite)
    }

    /// Walks from triangle `start` to the triangle holding the slopes of point `p`.
    fn locate(&self, p: u32, start: u32) -> Located {
        let q = self.at(p);
        let mut t = start;
        for step in 0..WALK_STEPS_PER_POINT {
            let tv = self.tri.triangles[t as usize];
            if let Some(j) = tv.iter().position(|&v| v == self.infinite) {
                // Ghost (x, y, oo): its region lies left of x -> y, beyond the hull edge y -> x.
                let (x, y) = (tv[(j + 1) % 3], tv[(j + 2) % 3]);
                let side = orient2d(self.at(x), self.at(y), q);
                if side > 0.0 {
                    return Located::In(t);
                }
                // Inside, or on the edge's line: on to the real triangle, which q leaves across
                // another edge (beyond the edge's ends) or holds on its edge.
                t = self.tri.neighbours[t as usize][j];
                continue;
            }
            // Real: cross the first edge (starting at a rotating one, so that the walk cannot
            // repeat a cycle for ever) that has q strictly on its far side.
            let mut on_edges = 0;
            let mut on = 0;
            let mut next = None;
            for r in 0..3 {
                let k = (r + step) % 3;
                let side = orient2d(self.at(tv[(k + 1) % 3]), self.at(tv[(k + 2) % 3]), q);
                if side < 0.0 {
                    next = Some(self.tri.neighbours[t as usize][k]);
                    break;
                }
                if side == 0.0 {
                    on_edges += 1;
                    on = k;
                }
            }
            match (next, on_edges) {
                (Some(other), _) => t = other,
                (None, 0) => return Located::In(t),
                // On two edges: at a vertex, the same slopes as a point inserted before.
                (None, 1) => return Located::OnEdge(t, on),
                (None, _) => return Located::Degenerate,
            }
        }
        Located::Degenerate
    }

    /// Inserts point `p`, walking from triangle `last`; returns a triangle holding `p`.
    fn insert(&mut self, p: u32, last: u32) -> Option<u32> {
        self.stack.clear();
        let parts = match self.locate(p, last) {
            Located::In(t) => {
                let [x, y, z] = self.tri.triangles[t as usize];
                // P_p strictly below the plane of its triangle's lifted points, else
                // redundant.
                if !self.is_ghost(t) && !self.below([x, y, z, p]) {
                    return None;
                }
                let [t1, t2] = self.split(t, p);
                // (triangle, position of p in it): p is last in the three parts.
                self.stack.extend([(t, 2), (t1, 2), (t2, 2)]);
                [t, t1, t2, t]
            }
            Located::OnEdge(t, k) => {
                let parts = self.split_edge(t, k, p)?;
                // p is last in the first part of each side, second in the other.
                let [t0, t1, u0, u1] = parts;
                self.stack.extend([(t0, 2), (t1, 1), (u0, 2), (u1, 1)]);
                parts
            }
            Located::Degenerate => return None,
        };
        // After a flip of (p, a, b) against (b, a, d), p is first in (p, a, d) and last in
        // (d, b, p).
        while let Some((t, k)) = self.stack.pop() {
            if self.illegal(t, k)? {
                if self.flips_left == 0 {
                    return None;
                }
                self.flips_left -= 1;
                let (t1, t2) = self.tri.flip(t, k);
                self.stack.extend([(t1, 0), (t2, 2)]);
            }
        }
        // A real triangle at p, to start the next walk from (flips keep p in the parts).
        let start = parts
            .into_iter()
            .find(|&s| !self.is_ghost(s) && self.tri.triangles[s as usize].contains(&p));
        Some(start.unwrap_or(parts[0]))
    }

    /// Splits the edge (a, b) opposite vertex k of the real triangle t = (c, a, b) at the
    /// point p inside it, and the triangle (d, b, a) across it (a ghost where the edge is on
    /// the hull): (c, a, p) (kept as t), (c, p, b), (d, b, p) (kept as the one across) and
    /// (d, p, a). None where P_p is not strictly below the lifted edge (redundant), judged
    /// against each real side's plane (which contains the edge) and agreeing.
    fn split_edge(&mut self, t: u32, k: usize, p: u32) -> Option<[u32; 4]> {
        let tv = self.tri.triangles[t as usize];
        let (c, a, b) = (tv[k], tv[(k + 1) % 3], tv[(k + 2) % 3]);
        let u = self.tri.neighbours[t as usize][k];
        let d = self.tri.opposite(u as usize, t)?;
        if !self.below([c, a, b, p]) || (d != self.infinite && !self.below([d, b, a, p])) {
            return None;
        }
        let nt = self.tri.neighbours[t as usize];
        let (n_a, n_b) = (nt[(k + 1) % 3], nt[(k + 2) % 3]);
        let ku = self.tri.position_of(u, d)?;
        let nu = self.tri.neighbours[u as usize];
        // In (d, b, a): opposite b the edge (a, d), opposite a the edge (d, b).
        let (m_b, m_a) = (nu[(ku + 1) % 3], nu[(ku + 2) % 3]);
        let t1 = self.tri.triangles.len() as u32;
        let u1 = t1 + 1;
        self.tri.triangles[t as usize] = [c, a, p];
        self.tri.neighbours[t as usize] = [u1, t1, n_b];
        self.tri.triangles.push([c, p, b]);
        self.tri.neighbours.push([u, n_a, t]);
        self.tri.triangles[u as usize] = [d, b, p];
        self.tri.neighbours[u as usize] = [t1, u1, m_a];
        self.tri.triangles.push([d, p, a]);
        self.tri.neighbours.push([t, m_b, u]);
        self.tri.replace_neighbour(n_a, t, t1);
        self.tri.replace_neighbour(m_b, u, u1);
        Some([t, t1, u, u1])
    }

    /// Splits triangle t = (x, y, z) at point p into (x, y, p) (kept as t), (y, z, p) and
    /// (z, x, p) (new); returns the two new ones.
    fn split(&mut self, t: u32, p: u32) -> [u32; 2] {
        let [x, y, z] = self.tri.triangles[t as usize];
        let [n_x, n_y, n_z] = self.tri.neighbours[t as usize];
        let t1 = self.tri.triangles.len() as u32;
        let t2 = t1 + 1;
        self.tri.triangles[t as usize] = [x, y, p];
        self.tri.neighbours[t as usize] = [t1, t2, n_z];
        self.tri.triangles.push([y, z, p]);
        self.tri.neighbours.push([t2, t, n_x]);
        self.tri.triangles.push([z, x, p]);
        self.tri.neighbours.push([t, t1, n_y]);
        self.tri.replace_neighbour(n_x, t, t1);
        self.tri.replace_neighbour(n_y, t, t2);
        [t1, t2]
    }

    /// Whether the edge opposite the new point (vertex k of triangle t) must be flipped;
    /// None where the builder gives up (module doc).
    fn illegal(&self, t: u32, k: usize) -> Option<bool> {
        let tv = self.tri.triangles[t as usize];
        let (p, a, b) = (tv[k], tv[(k + 1) % 3], tv[(k + 2) % 3]);
        let t2 = self.tri.neighbours[t as usize][k];
        let d = self.tri.opposite(t2 as usize, t)?;
        let oo = self.infinite;
        let turn = |u: u32, v: u32, w: u32| orient2d(self.at(u), self.at(v), self.at(w));
        // A ghost edge flips when p strictly sees the next hull edge. Where p is on that
        // edge's line (beyond it, or p on the hull itself after an edge split) nothing flips:
        // the hull keeps collinear edges.
        if a == oo {
            // (p, oo, b) against (b, oo, d): flip when (p, d, b) turns counter-clockwise.
            return Some(turn(p, d, b) > 0.0);
        }
        if b == oo {
            // (p, a, oo) against (a, d, oo) (as (d, oo, a)): flip when (p, a, d) does.
            return Some(turn(p, a, d) > 0.0);
        }
        if d == oo {
            return Some(false);
        }
        if !self.below([p, a, b, d]) {
            return Some(false);
        }
        // Illegal: the quadrilateral (p, a, d, b) must be strictly convex for the flip.
        (turn(p, a, d) > 0.0 && turn(d, b, p) > 0.0).then_some(true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::neighbours::flip_to_regular;
    use crate::pattern::SplitMix64;

    /// Spade's Delaunay triangulation flipped by the power test (the path this one replaces),
    /// in canonical order.
    fn by_delaunay_and_flips(slopes: &[[f64; 2]], lifted: &[[f64; 3]]) -> DualTriangulation {
        let mut tri = DualTriangulation::delaunay(slopes).expect("Delaunay");
        let unresolved = flip_to_regular(&mut tri, slopes, lifted, None);
        assert_eq!(unresolved, 0);
        tri.canonicalise(slopes.len());
        tri
    }

    fn directly(slopes: &[[f64; 2]], lifted: &[[f64; 3]]) -> Option<DualTriangulation> {
        let mut tri = regular_triangulation(lifted)?;
        tri.canonicalise(slopes.len());
        Some(tri)
    }

    /// Lifted to a strictly convex height (so that no point is redundant) plus a smaller
    /// convex bump, so that the regular triangulation is not the Delaunay one.
    fn lift(s: [f64; 2]) -> [f64; 3] {
        let r2 = s[0] * s[0] + s[1] * s[1];
        [
            s[0],
            s[1],
            r2 + 0.3 * (s[0] - 0.2).powi(4) + 0.1 * s[0] * s[1],
        ]
    }

    #[test]
    fn random_slopes_give_the_triangulation_of_delaunay_and_power_flips() {
        for (seed, n) in [
            (1u64, 3usize),
            (2, 4),
            (3, 10),
            (4, 100),
            (5, 1000),
            (6, 5000),
        ] {
            let mut random = SplitMix64::new(seed);
            let slopes: Vec<[f64; 2]> = (0..n)
                .map(|_| [2.0 * random.next_f64() - 1.0, 2.0 * random.next_f64() - 1.0])
                .collect();
            let lifted: Vec<[f64; 3]> = slopes.iter().map(|&s| lift(s)).collect();
            let built = directly(&slopes, &lifted).expect("generic input");
            assert_eq!(
                built,
                by_delaunay_and_flips(&slopes, &lifted),
                "seed {seed}, {n}"
            );
            assert_eq!(built.len(), 2 * n - 2 - hull_size(&built));
        }
    }

    #[test]
    fn clustered_and_sheared_slopes_agree_too() {
        // Points in two tight clusters far apart, and a thin sheared band: long walks and
        // slivers.
        let mut random = SplitMix64::new(9);
        let mut slopes: Vec<[f64; 2]> = (0..400)
            .map(|i| {
                let c = if i % 2 == 0 { 0.0 } else { 100.0 };
                [c + 1e-3 * random.next_f64(), c + 1e-3 * random.next_f64()]
            })
            .collect();
        slopes.extend((0..400).map(|_| {
            let t = random.next_f64();
            [50.0 + 40.0 * t, 50.0 + 40.0 * t + 1e-2 * random.next_f64()]
        }));
        let lifted: Vec<[f64; 3]> = slopes.iter().map(|&s| lift(s)).collect();
        let built = directly(&slopes, &lifted).expect("generic input");
        assert_eq!(built, by_delaunay_and_flips(&slopes, &lifted));
    }

    #[test]
    fn every_edge_is_locally_regular_and_the_hull_is_convex() {
        // Independent of both builders: the power test on every interior edge, and every hull
        // edge with all points on its left or on it.
        let mut random = SplitMix64::new(11);
        let slopes: Vec<[f64; 2]> = (0..300)
            .map(|_| [random.next_f64(), random.next_f64()])
            .collect();
        let lifted: Vec<[f64; 3]> = slopes.iter().map(|&s| lift(s)).collect();
        let tri = regular_triangulation(&lifted).expect("generic input");
        for (t, tv) in tri.triangles.iter().enumerate() {
            assert!(
                orient2d(
                    slopes[tv[0] as usize],
                    slopes[tv[1] as usize],
                    slopes[tv[2] as usize]
                ) > 0.0
            );
            for k in 0..3 {
                let (a, b) = (tv[(k + 1) % 3], tv[(k + 2) % 3]);
                let other = tri.neighbours[t][k];
                if other == NO_TRIANGLE {
                    for (i, &s) in slopes.iter().enumerate() {
                        assert!(
                            orient2d(slopes[a as usize], slopes[b as usize], s) >= 0.0,
                            "point {i} beyond hull edge ({a}, {b})"
                        );
                    }
                } else {
                    let d = tri.opposite(other as usize, t as u32).expect("neighbour");
                    let ids = [tv[k], a, b, d];
                    assert!(!power_illegal(ids.map(|i| lifted[i as usize]), ids));
                }
            }
        }
    }

    #[test]
    fn degenerate_inputs_are_left_to_the_delaunay_path() {
        // Collinear points, a duplicate, a redundant point.
        let collinear: Vec<[f64; 2]> = (0..5).map(|i| [i as f64, 2.0 * i as f64]).collect();
        let lifted: Vec<[f64; 3]> = collinear.iter().map(|&s| lift(s)).collect();
        assert!(regular_triangulation(&lifted).is_none());
        let duplicate = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 0.0]];
        let lifted = duplicate.map(lift);
        assert!(regular_triangulation(&lifted).is_none());
        // A redundant point: lifted above its neighbours' plane.
        let lifted = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.25, 0.25, 1.0],
        ];
        assert!(regular_triangulation(&lifted).is_none());
    }

    #[test]
    fn grids_and_lattices_with_exact_ties_agree_too() {
        // Points on edges and on the hull's lines (rows and columns of an exact grid, a hex
        // lattice), and every quad cocircular on the paraboloid of revolution (exact power
        // ties, broken by the pattern indices), in pattern order and shuffled.
        let paraboloid = |s: [f64; 2]| [s[0], s[1], s[0] * s[0] + s[1] * s[1]];
        let grid: Vec<[f64; 2]> = (0..400)
            .map(|i| [(i % 20) as f64, (i / 20) as f64])
            .collect();
        let hex: Vec<[f64; 2]> = (0..400)
            .map(|i| {
                [
                    (i % 20) as f64 + 0.5 * ((i / 20) % 2) as f64,
                    (i / 20) as f64,
                ]
            })
            .collect();
        let mut shuffled = grid.clone();
        let mut random = SplitMix64::new(5);
        for i in (1..shuffled.len()).rev() {
            shuffled.swap(i, random.below(i + 1));
        }
        for (name, slopes) in [("grid", &grid), ("hex", &hex), ("shuffled grid", &shuffled)] {
            for lifting in [lift, paraboloid] {
                let lifted: Vec<[f64; 3]> = slopes.iter().map(|&s| lifting(s)).collect();
                let built = directly(slopes, &lifted).unwrap_or_else(|| panic!("{name}"));
                assert_eq!(built, by_delaunay_and_flips(slopes, &lifted), "{name}");
            }
        }
    }

    fn hull_size(tri: &DualTriangulation) -> usize {
        tri.neighbours
            .iter()
            .flatten()
            .filter(|&&n| n == NO_TRIANGLE)
            .count()
    }
}
