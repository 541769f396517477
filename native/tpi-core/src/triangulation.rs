//! The dual structure: a triangulation of the pattern points whose edges are "true neighbour"
//! pairs and whose triangles each give one facet vertex.
//!
//! It starts as the Delaunay triangulation of the pattern points in (scaled) parameter space,
//! built with spade's bulk loader, and is then changed only by edge flips (Lawson's scheme
//! driven by a geometric criterion, see [`crate::neighbours`]). A flip replaces the diagonal
//! (a, b) of the convex quadrilateral (c, a, d, b) by (c, d); because it is only applied to
//! strictly convex quadrilaterals, the structure stays a valid planar triangulation of the
//! points at all times: the neighbour relation is symmetric and the triangles around every
//! interior point close up.
//!
//! Layout: triangle t has counter-clockwise vertices `triangles[t] = [v0, v1, v2]` and
//! `neighbours[t][k]`, the triangle across the edge opposite vertex k, i.e. across
//! (v(k+1), v(k+2)); [`NO_TRIANGLE`] on the convex hull.

use std::collections::HashMap;

use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation as _};

use crate::error::TpiError;

/// Marks a missing neighbour (a hull edge) or an unset index.
pub(crate) const NO_TRIANGLE: u32 = u32::MAX;

/// A hash map keyed by point or triangle indices (or tuples of them), hashed by
/// [`IndexHasher`] instead of SipHash: the keys are the pipeline's own indices, looked up far
/// more often than the maps are built, and no map keyed this way is iterated, so the hasher
/// changes no result.
pub(crate) type IndexMap<K, V> = HashMap<K, V, std::hash::BuildHasherDefault<IndexHasher>>;

/// A multiply-rotate hasher for integer keys (as rustc's FxHasher).
#[derive(Default)]
pub(crate) struct IndexHasher(u64);

impl std::hash::Hasher for IndexHasher {
    /// Eight bytes a step (little-endian words, the last one padded with zeros): a key of
    /// integer arrays (`[u32; 3]`, `Vec<u64>`) hashes its elements as one run of bytes.
    fn write(&mut self, bytes: &[u8]) {
        let mut words = bytes.chunks_exact(8);
        for word in &mut words {
            let mut x = [0u8; 8];
            x.copy_from_slice(word);
            self.write_u64(u64::from_le_bytes(x));
        }
        let rest = words.remainder();
        if !rest.is_empty() {
            let mut x = [0u8; 8];
            x[..rest.len()].copy_from_slice(rest);
            self.write_u64(u64::from_le_bytes(x));
        }
    }

    fn write_u32(&mut self, x: u32) {
        self.write_u64(u64::from(x));
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x517C_C1B7_2722_0A95);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

#[derive(Clone, Copy)]
struct Site {
    position: Point2<f64>,
    index: u32,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The three edges of each triangle, in its own direction.
pub(crate) fn triangle_edges(triangles: &[[u32; 3]]) -> impl Iterator<Item = [u32; 2]> + '_ {
    triangles
        .iter()
        .flat_map(|t| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]])
}

/// `edges` as undirected pairs i < j, sorted, each once.
pub(crate) fn sorted_pairs(edges: impl Iterator<Item = [u32; 2]>) -> Vec<[u32; 2]> {
    let mut pairs: Vec<[u32; 2]> = edges.map(|[a, b]| [a.min(b), a.max(b)]).collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// A triangulation of points 0..n with counter-clockwise triangles and adjacency.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct DualTriangulation {
    /// Counter-clockwise vertex triples.
    pub triangles: Vec<[u32; 3]>,
    /// Triangle across the edge opposite each vertex, or [`NO_TRIANGLE`].
    pub neighbours: Vec<[u32; 3]>,
}

/// One undirected edge of the triangulation with its (up to) two triangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Edge {
    /// Smaller endpoint.
    pub lo: u32,
    /// Larger endpoint.
    pub hi: u32,
    /// Triangle holding the directed edge lo -> hi (counter-clockwise), or [`NO_TRIANGLE`].
    pub left: u32,
    /// Triangle holding the directed edge hi -> lo, or [`NO_TRIANGLE`].
    pub right: u32,
}

impl DualTriangulation {
    /// Delaunay triangulation of `points` (any 2D coordinates, validated finite and distinct).
    pub(crate) fn delaunay(points: &[[f64; 2]]) -> Result<Self, TpiError> {
        if points.len() < 3 {
            return Err(TpiError::TooFewPatternPoints {
                found: points.len(),
                needed: 3,
            });
        }
        let sites: Vec<Site> = points
            .iter()
            .enumerate()
            .map(|(index, p)| Site {
                position: Point2::new(p[0], p[1]),
                index: index as u32,
            })
            .collect();
        let delaunay = DelaunayTriangulation::<Site>::bulk_load(sites).map_err(|error| {
            TpiError::DegenerateSurface {
                reason: format!("Delaunay triangulation failed: {error:?}"),
            }
        })?;
        if delaunay.num_inner_faces() == 0 {
            return Err(TpiError::CollinearPattern {
                count: points.len(),
            });
        }
        let mut triangles = Vec::with_capacity(delaunay.num_inner_faces());
        let mut neighbours = Vec::with_capacity(delaunay.num_inner_faces());
        // spade numbers inner faces from 1 (0 is the outer face).
        for face in delaunay.inner_faces() {
            let vertices = face.vertices();
            triangles.push(vertices.map(|v| v.data().index));
            let edges = face.adjacent_edges();
            // edges[k] runs from vertices[k] to vertices[k+1]: it is opposite vertex k+2.
            let mut across = [NO_TRIANGLE; 3];
            for (k, edge) in edges.iter().enumerate() {
                if let Some(other) = edge.rev().face().as_inner() {
                    across[(k + 2) % 3] = (other.fix().index() - 1) as u32;
                }
            }
            neighbours.push(across);
        }
        Ok(Self {
            triangles,
            neighbours,
        })
    }

    /// The triangulation of counter-clockwise `triangles` (built by other means than
    /// [`DualTriangulation::delaunay`]) with its adjacency; None when a directed edge is used
    /// twice (not a manifold with one orientation).
    pub(crate) fn from_triangles(triangles: Vec<[u32; 3]>) -> Option<Self> {
        let mut edges: HashMap<(u32, u32), u32> = HashMap::with_capacity(3 * triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                if edges.insert((tri[k], tri[(k + 1) % 3]), t as u32).is_some() {
                    return None;
                }
            }
        }
        let neighbours = triangles
            .iter()
            .map(|tri| {
                // Across the edge opposite vertex k, (v(k+1), v(k+2)), run the other way.
                [0, 1, 2].map(|k| {
                    edges
                        .get(&(tri[(k + 2) % 3], tri[(k + 1) % 3]))
                        .copied()
                        .unwrap_or(NO_TRIANGLE)
                })
            })
            .collect();
        Some(Self {
            triangles,
            neighbours,
        })
    }

    /// Puts the triangles in their canonical order, which depends only on the structure (not
    /// on how it was built): each triangle rotated so that its smallest point comes first
    /// (orientation kept), the triangles sorted by (first point, second point). A directed
    /// edge belongs to one triangle, so the key is unique. `point_count` bounds the indices.
    pub(crate) fn canonicalise(&mut self, point_count: usize) {
        let n = self.triangles.len();
        for (t, nb) in self.triangles.iter_mut().zip(self.neighbours.iter_mut()) {
            let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
            *t = rotate(*t, k);
            *nb = rotate(*nb, k);
        }
        // Counting sort on the first point, then each (short) run sorted on the second.
        let mut start = vec![0u32; point_count + 1];
        for t in &self.triangles {
            start[t[0] as usize + 1] += 1;
        }
        for v in 0..point_count {
            start[v + 1] += start[v];
        }
        let mut order = vec![0u32; n];
        let mut fill = start.clone();
        for (t, tv) in self.triangles.iter().enumerate() {
            order[fill[tv[0] as usize] as usize] = t as u32;
            fill[tv[0] as usize] += 1;
        }
        for v in 0..point_count {
            let run = &mut order[start[v] as usize..start[v + 1] as usize];
            if run.len() > 1 {
                run.sort_unstable_by_key(|&t| self.triangles[t as usize][1]);
            }
        }
        if order.iter().enumerate().all(|(k, &t)| k as u32 == t) {
            return;
        }
        let mut new_index = vec![NO_TRIANGLE; n];
        for (k, &t) in order.iter().enumerate() {
            new_index[t as usize] = k as u32;
        }
        let triangles: Vec<[u32; 3]> = order.iter().map(|&t| self.triangles[t as usize]).collect();
        let neighbours: Vec<[u32; 3]> = order
            .iter()
            .map(|&t| {
                self.neighbours[t as usize].map(|x| {
                    if x == NO_TRIANGLE {
                        x
                    } else {
                        new_index[x as usize]
                    }
                })
            })
            .collect();
        self.triangles = triangles;
        self.neighbours = neighbours;
    }

    /// Reverses every triangle's orientation (counter-clockwise becomes clockwise).
    pub(crate) fn reverse(&mut self) {
        for (t, n) in self.triangles.iter_mut().zip(self.neighbours.iter_mut()) {
            t.swap(1, 2);
            n.swap(1, 2);
        }
    }

    /// Number of triangles.
    pub(crate) fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there are no triangles.
    pub(crate) fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The vertex of triangle t across from its neighbour `across` (the fourth point of the
    /// quad around their shared edge), if `across` is a neighbour of t.
    pub(crate) fn opposite(&self, t: usize, across: u32) -> Option<u32> {
        let k = self.neighbours[t].iter().position(|&x| x == across)?;
        Some(self.triangles[t][k])
    }

    /// Position (0, 1, 2) of vertex `v` in triangle `t`.
    pub(crate) fn position_of(&self, t: u32, v: u32) -> Option<usize> {
        self.triangles[t as usize].iter().position(|&x| x == v)
    }

    /// Flips the edge opposite vertex `k` of triangle `t`. The caller has checked that the
    /// quadrilateral is strictly convex. Returns the two new triangles (same indices as before).
    pub(crate) fn flip(&mut self, t: u32, k: usize) -> (u32, u32) {
        let t1 = t as usize;
        let t2 = self.neighbours[t1][k] as usize;
        let [c, a, b] = rotate(self.triangles[t1], k);
        let [n_bc, n_ca] = {
            let n = rotate(self.neighbours[t1], k);
            [n[1], n[2]]
        };
        let k2 = self.neighbours[t2]
            .iter()
            .position(|&x| x as usize == t1)
            .unwrap_or(0);
        let [d, _b, _a] = rotate(self.triangles[t2], k2);
        let [n_ad, n_db] = {
            let n = rotate(self.neighbours[t2], k2);
            [n[1], n[2]]
        };
        self.triangles[t1] = [c, a, d];
        self.neighbours[t1] = [n_ad, t2 as u32, n_ca];
        self.triangles[t2] = [d, b, c];
        self.neighbours[t2] = [n_bc, t1 as u32, n_db];
        self.replace_neighbour(n_ad, t2 as u32, t1 as u32);
        self.replace_neighbour(n_bc, t1 as u32, t2 as u32);
        (t1 as u32, t2 as u32)
    }

    /// Drops the triangles marked in `removed` (their neighbours must already point past
    /// them) and renumbers the rest, keeping their order.
    pub(crate) fn remove_triangles(&mut self, removed: &[bool]) {
        let mut new_index = vec![NO_TRIANGLE; self.triangles.len()];
        let mut next = 0u32;
        for (t, &gone) in removed.iter().enumerate() {
            if !gone {
                new_index[t] = next;
                next += 1;
            }
        }
        let mut t = 0;
        self.triangles.retain(|_| {
            t += 1;
            !removed[t - 1]
        });
        let mut t = 0;
        self.neighbours.retain(|_| {
            t += 1;
            !removed[t - 1]
        });
        for n in self.neighbours.iter_mut().flatten() {
            if *n != NO_TRIANGLE {
                *n = new_index[*n as usize];
            }
        }
    }

    /// Drops every triangle with a point index `>= count` (keeping the order of the rest);
    /// the edges they shared with kept triangles become hull edges.
    pub(crate) fn retain_points(&mut self, count: usize) {
        let removed: Vec<bool> = self
            .triangles
            .iter()
            .map(|t| t.iter().any(|&v| v as usize >= count))
            .collect();
        if !removed.contains(&true) {
            return;
        }
        for t in 0..self.triangles.len() {
            for k in 0..3 {
                let other = self.neighbours[t][k];
                if other != NO_TRIANGLE && removed[other as usize] {
                    self.neighbours[t][k] = NO_TRIANGLE;
                }
            }
        }
        self.remove_triangles(&removed);
    }

    /// Points triangle t's neighbour `old` to `new` (nothing for [`NO_TRIANGLE`]).
    pub(crate) fn replace_neighbour(&mut self, t: u32, old: u32, new: u32) {
        if t == NO_TRIANGLE {
            return;
        }
        for n in self.neighbours[t as usize].iter_mut() {
            if *n == old {
                *n = new;
            }
        }
    }

    /// For every point, one incident triangle (the first in triangle order), or [`NO_TRIANGLE`].
    pub(crate) fn incident_triangles(&self, point_count: usize) -> Vec<u32> {
        let mut incident = vec![NO_TRIANGLE; point_count];
        for (t, tri) in self.triangles.iter().enumerate() {
            for &v in tri {
                if incident[v as usize] == NO_TRIANGLE {
                    incident[v as usize] = t as u32;
                }
            }
        }
        incident
    }

    /// The fan of triangles around point `v` in counter-clockwise order into `out`, starting
    /// from any incident triangle `start`. A hull point's fan starts at the triangle holding
    /// its clockwise-most edge.
    pub(crate) fn fan(&self, v: u32, start: u32, out: &mut Vec<u32>) -> Fan {
        out.clear();
        if start == NO_TRIANGLE {
            return Fan::Broken;
        }
        // Counter-clockwise from `start`: a closed fan comes back to it. Its loop then starts
        // at the triangle after `start` (where the clockwise search below would stop), so
        // `start` is written last; where the fan does not close it is put in front. `walked`
        // counts the triangles walked, `start` included.
        let mut current = start;
        let mut walked = 0;
        while walked <= self.triangles.len() {
            if walked > 0 {
                out.push(current);
            }
            walked += 1;
            let Some(k) = self.position_of(current, v) else {
                out.insert(0, start);
                return Fan::Broken;
            };
            // Counter-clockwise neighbour: across edge (v, v(k+2)), opposite v(k+1).
            let next = self.neighbours[current as usize][(k + 1) % 3];
            if next == NO_TRIANGLE {
                break;
            }
            if next == start {
                out.push(start);
                return Fan::Closed;
            }
            current = next;
        }
        out.insert(0, start);
        if out.len() > self.triangles.len() {
            return Fan::Broken;
        }
        // Open: rotate clockwise from `start` to the hull, then walk counter-clockwise.
        let mut first = start;
        for _ in 0..=self.triangles.len() {
            let Some(k) = self.position_of(first, v) else {
                return Fan::Broken;
            };
            // Clockwise neighbour around v: across edge (v, v(k+1)), opposite v(k+2).
            let previous = self.neighbours[first as usize][(k + 2) % 3];
            if previous == NO_TRIANGLE || previous == start {
                break;
            }
            first = previous;
        }
        if first == start {
            return Fan::Open;
        }
        // Prepend the clockwise part: walk counter-clockwise from `first` up to `start`.
        let mut prefix = Vec::new();
        let mut current = first;
        while current != start && prefix.len() <= self.triangles.len() {
            prefix.push(current);
            let Some(k) = self.position_of(current, v) else {
                return Fan::Broken;
            };
            let next = self.neighbours[current as usize][(k + 1) % 3];
            if next == NO_TRIANGLE {
                return Fan::Broken;
            }
            current = next;
        }
        out.splice(0..0, prefix);
        Fan::Open
    }
}

/// How the triangles around a point close up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fan {
    /// An interior point: the fan closes.
    Closed,
    /// A point on the convex hull: the fan runs from hull edge to hull edge.
    Open,
    /// The adjacency is inconsistent (never for a structure built by this module).
    Broken,
}

/// `x` rotated so that element `k` comes first.
fn rotate<T: Copy>(x: [T; 3], k: usize) -> [T; 3] {
    [x[k], x[(k + 1) % 3], x[(k + 2) % 3]]
}

/// Twice the signed area of (a, b, c): positive when counter-clockwise.
pub(crate) fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// The neighbour pairs (i < j, sorted) among the first `real_count` points (the real seeds
/// before any ghosts).
pub(crate) fn real_pairs(tri: &DualTriangulation, real_count: usize) -> Vec<[u32; 2]> {
    sorted_pairs(
        triangle_edges(&tri.triangles)
            .filter(|&[a, b]| (a as usize) < real_count && (b as usize) < real_count),
    )
}
