//! Wall flips: edge flips of the dual triangulation near the wall that close the notches the
//! extension ([`super::extend_to_wall`]) cannot.
//!
//! Facets i and j of a triangle (i, j, g) with a ghost g end at V = T_i ∩ T_j ∩ T_g; where V
//! lies inside the region and the line T_i ∩ T_j misses the ghost's wedge at V (facet i or j
//! reflex there, or four planes through nearly one point), no planar facet pair can close the
//! notch: the real facets' edges on ghost planes (T_r ∩ T_g, r real) form a chain that runs
//! inside the region, and the clip leaves the ghost's part between chain and wall empty. A
//! flip changes the chain: flipping (i, j) of the quad (g, i, x, j) to (x, g) brings facet x
//! to the ghost between i and j (vertices T_i ∩ T_x ∩ T_g and T_x ∩ T_j ∩ T_g); flipping a
//! real-ghost edge (i, g) hands the end of i to another ghost's plane or another facet.
//!
//! *Score.* The notch of the chain around a flip's quad: for every real-ghost edge (r, g) of
//! the triangles around the quad's four points, the segment P Q between its two triangles'
//! vertices (each as the extension leaves it) is sampled at [`NOTCH_SAMPLES`] + 1 points x_k;
//! with d_k = max(0, inside measure of the foot of x_k) (normalised parameters) and s_k the
//! foot's arclength along the wall,
//!
//!   notch(P Q) = -sum_k (d_k + d_{k+1}) / 2 * (s_{k+1} - s_k),
//!
//! the area between the chain and the wall by the trapezoid rule (the chain runs clockwise
//! along the wall; the signed advance makes a segment that runs out and back along one line
//! enclose nothing). The chain outside the quad's triangles is the same before and after the
//! flip, so the difference of the sums is the change of the notches' area.
//!
//! *Moves.* Each triangle with one or two ghosts whose vertex stays inside (deeper than
//! [`WALL_EXTENSION_MIN_DEPTH`] of its reach, after the extension) gets its real edge tried
//! first, then its edges to ghosts; a flip is kept when the score drops and no facet among
//! those it can change turns invalid by the validity flips' local test
//! ([`crate::validity_flips::State::try_flip_scored`], the closed facets, ghosts keeping one
//! run around every point). Rounds over the triangles still notched, at most
//! [`WALL_FLIP_ROUNDS`]. The caller clips the result and refuses the flips near facets that
//! come out of the clip invalid ([`super::WallClip`]).

use std::borrow::Cow;

use glam::DVec3;

use super::{
    extension, extension_key, triangle_vertex, Bits, Context, TriangleVertex, VertexCache,
};
use crate::planes::Plane;
use crate::tolerance::{WALL_EXTENSION_MIN_DEPTH, WALL_FLIP_ROUNDS};
use crate::triangulation::{DualTriangulation, IndexMap, NO_TRIANGLE};
use crate::validity_flips::State;

/// Pieces of a segment sampled for its notch (module doc).
const NOTCH_SAMPLES: usize = 4;

/// The notches of the chain of real facets' edges on ghost planes, with the triangle vertices
/// (by their points) and the segments' notches (by their ends) cached.
struct Notches<'c, 'a> {
    ctx: &'c Context<'a>,
    real_count: usize,
    far_factor: f64,
    /// The triangle vertices and their extensions: the caller's, shared with its clips.
    vertices: &'c mut VertexCache,
    /// The notch of every segment sampled, by its ends' bits.
    segments: IndexMap<Bits<6>, f64>,
    /// Every final vertex computed ([`Notches::final_vertex`]), by [`final_key`].
    finals: IndexMap<[u32; 12], TriangleVertex>,
}

/// What triangle t's final vertex depends on: its points in order, and the points of the
/// triangles across its edges in ascending order (`u32::MAX` where there is none), which
/// give their vertices.
fn final_key(tri: &DualTriangulation, t: usize) -> [u32; 12] {
    let mut key = [u32::MAX; 12];
    key[..3].copy_from_slice(&tri.triangles[t]);
    for (k, &other) in tri.neighbours[t].iter().enumerate() {
        if other != NO_TRIANGLE {
            let mut ids = tri.triangles[other as usize];
            ids.sort_unstable();
            key[3 + 3 * k..6 + 3 * k].copy_from_slice(&ids);
        }
    }
    key
}

impl Notches<'_, '_> {
    /// The vertex of the triangle of points `ids`, as the walk computes it.
    fn vertex(&mut self, ids: [u32; 3]) -> TriangleVertex {
        let mut key = ids;
        key.sort_unstable();
        let (ctx, far) = (self.ctx, self.far_factor);
        *self
            .vertices
            .vertices
            .entry(key)
            .or_insert_with(|| triangle_vertex(ctx, key, far))
    }

    /// Triangle t's vertex as the walk leaves it: extended to the wall where
    /// [`extension`] moves it. Taken from `finals` where there: it depends only on
    /// [`final_key`].
    fn final_vertex(&mut self, tri: &DualTriangulation, t: usize) -> TriangleVertex {
        let key = final_key(tri, t);
        if let Some(&v) = self.finals.get(&key) {
            return v;
        }
        let v = self.final_vertex_of(tri, t);
        self.finals.insert(key, v);
        v
    }

    /// [`Notches::final_vertex`] computed.
    fn final_vertex_of(&mut self, tri: &DualTriangulation, t: usize) -> TriangleVertex {
        let ids = tri.triangles[t];
        let v = self.vertex(ids);
        let across: [Option<DVec3>; 3] = std::array::from_fn(|k| {
            let other = tri.neighbours[t][k];
            (other != NO_TRIANGLE).then(|| self.vertex(tri.triangles[other as usize]).point)
        });
        let key = extension_key(ids, across);
        if let Some(&moved) = self.vertices.extensions.get(&key) {
            return moved.unwrap_or(v);
        }
        let moved = extension(self.ctx, self.real_count, ids, &v, |k| across[k]);
        self.vertices.extensions.insert(key, moved);
        moved.unwrap_or(v)
    }

    /// Whether triangle t's vertex stays inside the region deeper than the extension's
    /// minimum depth once extended.
    fn notched(&mut self, tri: &DualTriangulation, t: usize) -> bool {
        let ids = tri.triangles[t];
        let ghosts = ids
            .iter()
            .filter(|&&p| p as usize >= self.real_count)
            .count();
        if !(1..=2).contains(&ghosts) {
            return false;
        }
        let v = self.final_vertex(tri, t);
        v.inside > WALL_EXTENSION_MIN_DEPTH * v.reach
    }

    /// The notch along the segment P Q of a real facet's edge on a ghost's plane: the area
    /// between it and the wall, the depth inside the region integrated over the signed
    /// advance along the wall (module doc).
    fn segment_notch(&mut self, p: &TriangleVertex, q: &TriangleVertex) -> f64 {
        let [a, b] = [p.point, q.point].map(|x| x.to_array().map(f64::to_bits));
        let key = Bits([a[0], a[1], a[2], b[0], b[1], b[2]]);
        if let Some(&area) = self.segments.get(&key) {
            return area;
        }
        // Every field of P and Q the notch reads: a segment an earlier call sampled (the
        // retries' flips share most of the chain) takes that area.
        let mut words = [0u64; 12];
        for (k, v) in [p, q].into_iter().enumerate() {
            let fields = [
                v.point.x, v.point.y, v.point.z, v.foot[0], v.foot[1], v.inside,
            ];
            for (j, w) in fields.into_iter().enumerate() {
                words[6 * k + j] = w.to_bits();
            }
        }
        let full = Bits(words);
        if let Some(&area) = self.vertices.notches.get(&full) {
            self.segments.insert(key, area);
            return area;
        }
        let boundary = self.ctx.boundary;
        let mut guess = p.foot;
        let mut previous = (p.inside.max(0.0), boundary.position(p.foot));
        let mut area = 0.0;
        for k in 1..=NOTCH_SAMPLES {
            let (foot, inside) = if k == NOTCH_SAMPLES {
                (q.foot, q.inside)
            } else {
                let x = p.point.lerp(q.point, k as f64 / NOTCH_SAMPLES as f64);
                self.ctx.measure(x, guess)
            };
            guess = foot;
            let next = (inside.max(0.0), boundary.position(foot));
            // The signed advance along the wall: a segment that runs out and back along one
            // line encloses nothing.
            let advance = match (
                boundary.ahead(previous.1, next.1),
                boundary.ahead(next.1, previous.1),
            ) {
                (Some(a), Some(b)) => {
                    if a <= b {
                        a
                    } else {
                        -b
                    }
                }
                _ => 0.0,
            };
            // The chain runs clockwise along the wall (the real seeds on its right).
            // The chain runs clockwise along the wall (the real seeds on its right).
            area -= 0.5 * (previous.0 + next.0) * advance;
            previous = next;
        }
        self.segments.insert(key, area);
        self.vertices.notches.insert(full, area);
        area
    }

    /// The notches along the real facets' edges on ghost planes around the quad's points.
    fn score(&mut self, tri: &DualTriangulation, incident: &[u32], quad: &[u32; 4]) -> f64 {
        let mut fan = Vec::new();
        let mut triangles = Vec::new();
        for &p in quad {
            tri.fan(p, incident[p as usize], &mut fan);
            triangles.extend_from_slice(&fan);
        }
        triangles.sort_unstable();
        triangles.dedup();
        // Each triangle's final vertex once per score: most are ends of two segments.
        let mut finals: Vec<(u32, TriangleVertex)> = Vec::with_capacity(triangles.len());
        let mut final_vertex = |notches: &mut Self, t: u32| match finals.iter().find(|x| x.0 == t) {
            Some(&(_, v)) => v,
            None => {
                let v = notches.final_vertex(tri, t as usize);
                finals.push((t, v));
                v
            }
        };
        let mut total = 0.0;
        for &t in &triangles {
            let ids = tri.triangles[t as usize];
            for k in 0..3 {
                // The edge (r, g) from r, real, to g, a ghost, counter-clockwise in t; its
                // other triangle is the one across from position k + 2.
                let (r, g) = (ids[k], ids[(k + 1) % 3]);
                if r as usize >= self.real_count || (g as usize) < self.real_count {
                    continue;
                }
                let other = tri.neighbours[t as usize][(k + 2) % 3];
                if other == NO_TRIANGLE {
                    continue;
                }
                let p = final_vertex(self, t);
                let q = final_vertex(self, other);
                total += self.segment_notch(&p, &q);
            }
        }
        total
    }
}

/// A kept wall flip: its quad's points and the real points whose facets it can change.
pub(super) struct WallFlip {
    pub(super) quad: [u32; 4],
    pub(super) region: Vec<u32>,
}

/// Flips edges of the triangles whose vertex stays inside the region (module doc), keeping
/// a flip when the notches around it shrink and no facet turns invalid; no flip touches a
/// real point marked in `blocked`. `planes` are all points' (ghosts included). Triangle
/// vertices and their extensions are taken from `vertices` (computed in `ctx`) where there,
/// and those computed are added to it. Returns the flips kept, in order.
pub(super) fn wall_flips(
    ctx: &Context<'_>,
    real_count: usize,
    tri: &mut DualTriangulation,
    planes: &[Plane],
    far_factor: f64,
    blocked: &[bool],
    vertices: &mut VertexCache,
) -> Vec<WallFlip> {
    let mut notches = Notches {
        ctx,
        real_count,
        far_factor,
        vertices,
        segments: IndexMap::default(),
        finals: IndexMap::default(),
    };
    let targets: Vec<[u32; 3]> = (0..tri.len())
        .filter(|&t| notches.notched(tri, t))
        .map(|t| tri.triangles[t])
        .collect();
    if targets.is_empty() {
        return Vec::new();
    }
    let points = planes.len();
    let mut state = State::unjudged(tri, points, Cow::Borrowed(planes), real_count);
    let mut kept = Vec::new();
    let mut targets = targets;
    for _ in 0..WALL_FLIP_ROUNDS {
        let mut kept_now = 0;
        for ids in &targets {
            if ids
                .iter()
                .any(|&p| (p as usize) < real_count && blocked[p as usize])
            {
                continue;
            }
            // Real edges first: the flip that brings a third facet to the wall.
            let mut edges: Vec<(u32, u32)> = (0..3).map(|k| (ids[k], ids[(k + 1) % 3])).collect();
            edges.sort_by_key(|&(a, b)| {
                usize::from(a as usize >= real_count) + usize::from(b as usize >= real_count)
            });
            for (a, b) in edges {
                let mut score = |tri: &DualTriangulation, incident: &[u32], quad: &[u32; 4]| {
                    notches.score(tri, incident, quad)
                };
                if let Some((quad, region)) =
                    state.try_flip_scored(a, b, 0.0, false, blocked, &mut score)
                {
                    kept.push(WallFlip { quad, region });
                    kept_now += 1;
                    break;
                }
            }
        }
        if kept_now == 0 {
            break;
        }
        let tri = &*state.tri;
        targets = (0..tri.len())
            .filter(|&t| notches.notched(tri, t))
            .map(|t| tri.triangles[t])
            .collect();
    }
    kept
}
