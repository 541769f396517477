//! The structural contract of a [`Discretisation`], checked from its arrays alone:
//! [`Discretisation::sanity_check`].
//!
//! - one facet per pattern point, every vertex index in range, every vertex finite;
//! - every facet a loop of at least three distinct vertices, lying in its plane (the seed's
//!   tangent plane, or the adjusted plane of [`crate::PlaneMode::Adjusted`]: |n . (x - p)| <=
//!   [`SANITY_PLANARITY_TOLERANCE`] times the bounding-box diagonal of the vertices), simple
//!   and counter-clockwise seen from that plane's normal n (for exact planes Su x Sv; positive
//!   signed area, no two non-adjacent edges crossing, in a right-handed frame of the plane);
//! - an oriented 2-manifold: every edge held by one facet (boundary) or by two facets that run
//!   it in opposite directions;
//! - a disc: V - E + F = 1 and the boundary edges form one loop; on a trimmed surface a
//!   disc with holes: V - E + F = 2 - loops.
//!
//! It says nothing about overlaps between facets that share no edge (the quality report's
//! flags do); it is cheap enough to run on every result in tests and fuzzing.

use glam::DVec2;

use crate::discretise::Discretisation;
use crate::mesh::find;
use crate::samples::bounding_diagonal;
use crate::tolerance::SANITY_PLANARITY_TOLERANCE;

/// The first way in which a discretisation breaks its structural contract.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SanityError {
    /// The facet count is not the seed count, or the offsets are not a valid partition.
    #[error("{facets} facet loops for {seeds} seeds (offsets inconsistent)")]
    FacetCount {
        /// Facet loops described by the offsets.
        facets: usize,
        /// Pattern points.
        seeds: usize,
    },
    /// A loop names a vertex that does not exist.
    #[error("facet {facet}: vertex index {index} out of range ({vertices} vertices)")]
    VertexIndex {
        /// The facet.
        facet: usize,
        /// The index it names.
        index: u32,
        /// How many vertices there are.
        vertices: usize,
    },
    /// A vertex has a NaN or infinite coordinate.
    #[error("vertex {vertex} is not finite")]
    NonFiniteVertex {
        /// The vertex.
        vertex: usize,
    },
    /// A facet is open (fewer than three distinct vertices, or a vertex repeated), not simple,
    /// or clockwise.
    #[error("facet {facet}: {reason}")]
    BadFacet {
        /// The facet.
        facet: usize,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A facet vertex lies off the facet's plane.
    #[error(
        "facet {facet}: vertex {vertex} lies {distance:e} (relative to the diagonal) off its plane"
    )]
    NonPlanar {
        /// The facet.
        facet: usize,
        /// The vertex.
        vertex: u32,
        /// Its distance from the seed's tangent plane over the diagonal.
        distance: f64,
    },
    /// An edge is held by more than two facets, or twice in the same direction.
    #[error("edge ({a}, {b}): {reason}")]
    Edge {
        /// One end.
        a: u32,
        /// The other end.
        b: u32,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The mesh does not have its expected topology ([`crate::MeshTopology`]: a disc, or a
    /// closed sphere on a closed surface).
    #[error("wrong topology: Euler characteristic {euler}, {loops} boundary loops")]
    NotDisc {
        /// V - E + F (vertices counted when some facet uses them).
        euler: i64,
        /// Connected loops of boundary edges.
        loops: usize,
    },
}

impl Discretisation {
    /// Checks the structural contract of a discretisation from its arrays alone: one facet per
    /// pattern point; every vertex index in range and every vertex finite; every facet a loop
    /// of at least three distinct vertices in its seed's tangent plane (within
    /// [`crate::tolerance::SANITY_PLANARITY_TOLERANCE`] of the diagonal), simple and
    /// counter-clockwise seen from the seed's normal; every edge held by one facet or by two
    /// running it in opposite directions; Euler characteristic 1 and one boundary loop (a
    /// disc). Overlaps of facets that share no edge are the quality report's to flag. The first
    /// violation found is returned, naming its facet, vertex or edge.
    pub fn sanity_check(&self) -> Result<(), SanityError> {
        let facets = self.facet_offsets.len().saturating_sub(1);
        let partition = self.facet_offsets.first() == Some(&0)
            && self.facet_offsets.windows(2).all(|w| w[0] <= w[1])
            && self.facet_offsets.last().map(|&e| e as usize) == Some(self.facet_loops.len());
        if facets != self.seeds.len() || !partition {
            return Err(SanityError::FacetCount {
                facets,
                seeds: self.seeds.len(),
            });
        }
        if let Some(vertex) = self.vertices.iter().position(|v| !v.is_finite()) {
            return Err(SanityError::NonFiniteVertex { vertex });
        }
        let diagonal = bounding_diagonal(self.vertices.iter().copied()).max(f64::MIN_POSITIVE);
        let mut used = vec![false; self.vertices.len()];
        let mut flat = Vec::new();
        for facet in 0..facets {
            let lp = self.facet(facet);
            for &index in lp {
                let Some(u) = used.get_mut(index as usize) else {
                    return Err(SanityError::VertexIndex {
                        facet,
                        index,
                        vertices: self.vertices.len(),
                    });
                };
                *u = true;
            }
            check_facet(self, facet, diagonal, &mut flat)?;
        }
        let (edges, boundary) = edges(&self.facet_offsets, &self.facet_loops)?;
        let vertices = used.iter().filter(|&&u| u).count();
        let euler = vertices as i64 - edges as i64 + facets as i64;
        let loops = boundary_loops(self.vertices.len(), &boundary);
        let expected = self.topology;
        // On a trimmed surface each hole of the trim adds a boundary loop: a disc with holes.
        let trimmed = !self.pattern_indices.is_empty() && loops >= 1;
        let as_expected = euler == expected.euler && loops == expected.boundary_loops;
        if !(as_expected || trimmed && euler == 2 - loops as i64) {
            return Err(SanityError::NotDisc { euler, loops });
        }
        Ok(())
    }
}

fn check_facet(
    d: &Discretisation,
    facet: usize,
    diagonal: f64,
    flat: &mut Vec<DVec2>,
) -> Result<(), SanityError> {
    let bad = |reason| Err(SanityError::BadFacet { facet, reason });
    let lp = d.facet(facet);
    if lp.len() < 3 {
        return bad("fewer than three vertices");
    }
    for (k, v) in lp.iter().enumerate() {
        if lp[k + 1..].contains(v) {
            return bad("a vertex repeated in the loop");
        }
    }
    // The facet's plane: the seed's tangent plane, or its adjusted plane.
    let (origin, normal) = d.facet_plane(facet);
    let (e1, e2) = normal.any_orthonormal_pair();
    flat.clear();
    for &v in lp {
        let r = d.vertices[v as usize] - origin;
        let distance = normal.dot(r).abs() / diagonal;
        if !(distance <= SANITY_PLANARITY_TOLERANCE) {
            return Err(SanityError::NonPlanar {
                facet,
                vertex: v,
                distance,
            });
        }
        flat.push(DVec2::new(r.dot(e1), r.dot(e2)));
    }
    let n = flat.len();
    let area: f64 = (0..n).map(|k| flat[k].perp_dot(flat[(k + 1) % n])).sum();
    if !(area > 0.0) {
        return bad("clockwise or of zero area seen from its normal");
    }
    for a in 0..n {
        for b in a + 2..n {
            if a == 0 && b == n - 1 {
                continue;
            }
            let (p, q) = (flat[a], flat[(a + 1) % n]);
            let (r, s) = (flat[b], flat[(b + 1) % n]);
            if crosses(p, q, r, s) {
                return bad("not simple: two of its edges cross");
            }
        }
    }
    Ok(())
}

/// Whether the closed segments pq and rs share a point (they are non-adjacent edges of one
/// loop, so any contact makes the loop non-simple). The quality report's simplicity test uses
/// it too.
pub(crate) fn crosses(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let side = |a: DVec2, b: DVec2, c: DVec2| (b - a).perp_dot(c - a);
    let (d1, d2) = (side(p, q, r), side(p, q, s));
    let (d3, d4) = (side(r, s, p), side(r, s, q));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    let on = |a: DVec2, b: DVec2, c: DVec2, o: f64| {
        o == 0.0
            && c.x >= a.x.min(b.x)
            && c.x <= a.x.max(b.x)
            && c.y >= a.y.min(b.y)
            && c.y <= a.y.max(b.y)
    };
    on(p, q, r, d1) || on(p, q, s, d2) || on(r, s, p, d3) || on(r, s, q, d4)
}

/// The number of distinct edges, and the boundary edges (held by one facet), after checking
/// that every edge is held once, or twice in opposite directions. Facet f's loop is
/// `loops[offsets[f]..offsets[f + 1]]`.
pub(crate) fn edges(
    offsets: &[u32],
    loops: &[u32],
) -> Result<(usize, Vec<(u32, u32)>), SanityError> {
    // Every directed edge filed under its lower end (a counting sort), then each end's few
    // edges sorted by (upper end, direction): the order of one sort by (lo, hi, direction),
    // in linear time. Entry: hi << 1 | (direction lo -> hi ? 0 : 1).
    let vertex_count = loops.iter().max().map_or(0, |&m| m as usize + 1);
    let mut start = vec![0usize; vertex_count + 1];
    for_each_directed_edge(offsets, loops, |a, b| start[a.min(b) as usize + 1] += 1);
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    let mut filled = start.clone();
    let mut entries = vec![0u64; start[vertex_count]];
    for_each_directed_edge(offsets, loops, |a, b| {
        let (lo, hi, reversed) = if a < b { (a, b, 0) } else { (b, a, 1) };
        entries[filled[lo as usize]] = u64::from(hi) << 1 | reversed;
        filled[lo as usize] += 1;
    });
    let mut count = 0;
    let mut boundary = Vec::new();
    for lo in 0..vertex_count {
        let bucket = &mut entries[start[lo]..start[lo + 1]];
        bucket.sort_unstable();
        let mut k = 0;
        while k < bucket.len() {
            let hi = bucket[k] >> 1;
            let mut end = k + 1;
            while end < bucket.len() && bucket[end] >> 1 == hi {
                end += 1;
            }
            let (a, b) = (lo as u32, hi as u32);
            match end - k {
                1 => boundary.push((a, b)),
                2 if bucket[k] & 1 != bucket[k + 1] & 1 => {}
                2 => {
                    return Err(SanityError::Edge {
                        a,
                        b,
                        reason: "run in the same direction by two facets",
                    })
                }
                _ => {
                    return Err(SanityError::Edge {
                        a,
                        b,
                        reason: "held by more than two facets",
                    })
                }
            }
            count += 1;
            k = end;
        }
    }
    Ok((count, boundary))
}

/// Calls `visit` on the directed edges (a, b) of every facet loop, facet by facet, each loop's
/// closing edge first (the order within a facet does not matter to [`edges`], which sorts
/// each end's entries).
fn for_each_directed_edge(offsets: &[u32], loops: &[u32], mut visit: impl FnMut(u32, u32)) {
    for w in offsets.windows(2) {
        let lp = &loops[w[0] as usize..w[1] as usize];
        if let Some(&last) = lp.last() {
            let mut a = last;
            for &b in lp {
                visit(a, b);
                a = b;
            }
        }
    }
}

/// The boundary loops of the boundary edges `boundary` ([`BoundaryLoops`]).
pub(crate) fn boundary_loops(vertex_count: usize, boundary: &[(u32, u32)]) -> usize {
    let mut loops = BoundaryLoops::new(vertex_count);
    for &(a, b) in boundary {
        loops.add_edge(a, b);
    }
    loops.count()
}

/// Counts the boundary loops that a walk along the facets' turn finds, from the boundary
/// edges (edges held by one facet) given one by one: the connected components of those
/// edges, plus k - 1 at a vertex with 2k boundary edges. There the boundary is pinched (two
/// facets touch at a boundary vertex only), and the walk closes one loop per pair of edges:
/// two discs touching at a vertex have Euler characteristic 1 and two loops. The quality
/// report and [`crate::Discretisation::sanity_check`] count with it, and so does the facet
/// stage when it compares the wall-clipped facets' shape with the closed ones'.
pub(crate) struct BoundaryLoops {
    parent: Vec<u32>,
    /// Boundary edges at each vertex (saturating: a vertex with 255 is pinched many times
    /// over, and the count is a diagnostic).
    edges_at: Vec<u8>,
}

impl BoundaryLoops {
    /// A counter for a mesh of `vertex_count` vertices, no edge given yet.
    pub(crate) fn new(vertex_count: usize) -> Self {
        Self {
            parent: (0..vertex_count as u32).collect(),
            edges_at: vec![0; vertex_count],
        }
    }

    /// Adds the boundary edge between vertices `a` and `b`.
    pub(crate) fn add_edge(&mut self, a: u32, b: u32) {
        for v in [a, b] {
            self.edges_at[v as usize] = self.edges_at[v as usize].saturating_add(1);
        }
        let (ra, rb) = (find(&mut self.parent, a), find(&mut self.parent, b));
        if ra != rb {
            self.parent[ra.max(rb) as usize] = ra.min(rb);
        }
    }

    /// Whether vertex `v` has a boundary edge.
    pub(crate) fn on_boundary(&self, v: usize) -> bool {
        self.edges_at[v] > 0
    }

    /// The number of boundary loops.
    pub(crate) fn count(&mut self) -> usize {
        let mut loops = 0;
        for v in 0..self.edges_at.len() {
            let edges = self.edges_at[v];
            if edges > 0 {
                loops += usize::from(find(&mut self.parent, v as u32) == v as u32);
                loops += usize::from(edges / 2).saturating_sub(1);
            }
        }
        loops
    }
}

#[cfg(test)]
mod tests {
    use super::boundary_loops;

    /// The edges of the triangles' loops, each once: all are boundary edges when no two
    /// triangles share an edge.
    fn loop_edges(triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
        triangles
            .iter()
            .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
            .collect()
    }

    #[test]
    fn a_pinched_boundary_counts_a_loop_per_pair_of_edges_at_the_pinch() {
        assert_eq!(boundary_loops(3, &loop_edges(&[[0, 1, 2]])), 1);
        // Two triangles apart: two loops, as before the pinch count.
        assert_eq!(boundary_loops(6, &loop_edges(&[[0, 1, 2], [3, 4, 5]])), 2);
        // Touching at vertex 0 (4 boundary edges there): the walk closes two loops.
        assert_eq!(boundary_loops(5, &loop_edges(&[[0, 1, 2], [0, 3, 4]])), 2);
        // Three touching at vertex 0 (6 edges): three loops.
        let three = loop_edges(&[[0, 1, 2], [0, 3, 4], [0, 5, 6]]);
        assert_eq!(boundary_loops(7, &three), 3);
        // A square of two triangles sharing the edge 0-2: its four outer edges, one loop.
        assert_eq!(boundary_loops(4, &[(0, 1), (1, 2), (2, 3), (3, 0)]), 1);
    }
}
