//! Facets: one planar polygon per pattern point, closed on the surface's boundary.
//!
//! - **Interior vertices.** Every triangle (i, j, k) of the dual structure gives the vertex
//!   T_i ∩ T_j ∩ T_k ([`crate::planes`]), shared by the three facets. Each facet's loop visits
//!   the triangles around its point counter-clockwise in parameter space, which is
//!   counter-clockwise seen from the normal Su x Sv.
//! - **Boundary.** A vertex is inside when its foot on the surface lies in the domain
//!   ([`crate::projection`]). Each facet edge is the segment of the line T_i ∩ T_j between the
//!   vertices of the edge's two triangles; on the convex hull of the pattern it is a ray,
//!   followed outwards until it leaves the domain. Where an edge crosses the boundary, the
//!   crossing is found by regula falsi on the inside measure: a point of the line T_i ∩ T_j
//!   whose foot is on the domain boundary, i.e. where the edge meets the ruled surface of the
//!   normals along the boundary curve. It is computed once per edge and shared by both
//!   facets. Where only the side of a point
//!   matters (the samples of an edge with both ends outside, the far end of an edge leaving
//!   the domain, the march along a ray) Newton stops once two steps s_(k-1), s_k contract,
//!   s_k <= s_(k-1) / 2, and the iterate is outside by more than 4 s_k (the iterates move by
//!   at most s_k q / (1 - q) <= s_k more: [`crate::projection::outside_foot`]). Between leaving and re-entering the domain, a facet follows the boundary
//!   counter-clockwise and picks up the domain corners it passes; corner c contributes the
//!   point where the corner's normal line meets T_i. Every vertex of facet i lies in T_i by
//!   construction, so every facet is exactly planar.
//! - **Mesh.** The loops, as items (triangle vertices, crossings, edge points, corners), go to
//!   [`crate::mesh`], which welds the vertices where four or more planes meet in one point,
//!   numbers them and writes the loops.

mod wall_flips;

use std::cell::RefCell;
use std::collections::HashSet;

use glam::DVec3;
use rayon::prelude::*;

use crate::boundary::{Boundary, Position};
use crate::diagnostics::Diagnostic;
use crate::mesh::{
    assemble, drop_coincident_crossings, find, weld_coincident_crossings, Assembly, FacetMesh,
    SlopeView,
};
use crate::neighbours::SlopeFrame;
use crate::planes::{coincident, meeting_point, regularised_meeting_point, Plane, ThreePlanePoint};
use crate::progress::{NoProgress, Stage, Stages, Tally};
use crate::projection::{outside_foot, periodic_foot};
use crate::samples::Samples;
use crate::structure::{DualStructure, FacetPlan};
use crate::surface::{Domain, Surface};
use crate::tolerance::{
    CORNER_ON_CROSSING, CROSSING_ACCEPTANCE, CROSSING_ITERATIONS, CROSSING_TOLERANCE,
    DEFAULT_FAR_VERTEX_FACTOR, GRAZING_CROSSING_SLACK, NEAR_SURFACE_RATIO, OUTSIDE_SEGMENT_SAMPLES,
    RAY_DOUBLINGS, RAY_FAR_FACTOR, UNREACHABLE_VERTEX_FACTOR, WALL_CLIP_HYBRID_ROUNDS,
    WALL_CLIP_SHORT_EDGE, WALL_EXTENSION_MIN_DEPTH, WALL_EXTENSION_OWN_STEPS,
    WALL_EXTENSION_ROUNDS, WALL_EXTENSION_STEPS, WALL_FLIP_CORNER_REACH, WALL_FLIP_DEVIATION_SLACK,
    WALL_FLIP_MIN_AREA, WALL_FLIP_NOTCH_SAMPLES, WALL_FLIP_NOTCH_SLACK, WALL_FLIP_RETRIES,
};
use crate::triangulation::{
    real_pairs, triangle_edges, DualTriangulation, Edge, Fan, IndexMap, NO_TRIANGLE,
};

/// What a mesh vertex is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VertexKind {
    /// Meeting point of three (or more) tangent planes inside the domain.
    Interior,
    /// Where a facet edge meets the surface's boundary wall.
    Boundary,
    /// Over a domain corner.
    Corner,
}

/// Parameters of facet construction.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FacetParams {
    /// See [`DEFAULT_FAR_VERTEX_FACTOR`].
    pub far_vertex_factor: f64,
    /// Absolute weld distance (model units).
    pub weld_distance: f64,
    /// Adjacent vertices farther apart than this (model units) are not tested for a reversed
    /// edge ([`crate::tolerance::REVERSAL_CHECK_TOLERANCE`] times the diagonal).
    pub reversal_distance: f64,
    /// The dual structure is exact whatever its vertices' distances (the Delaunay
    /// triangulation of a flat surface's seeds, [`crate::flat`]): a far vertex is believed as
    /// on the convex path, not replaced by a stand-in.
    pub exact_dual: bool,
}

/// What the facet stage knows about a mesh vertex's closest point on the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum FootHint {
    /// The foot (Newton's converged projection, in the surface's parameters).
    Known([f64; 2]),
    /// Project by Newton from this first-order estimate; accept the result if it lies within
    /// `2 reach + 1e-9` (normalised) of it, else project from the first facet's seed.
    Guess {
        /// First-order foot from the vertex's triangle.
        linear: [f64; 2],
        /// Largest normalised distance of the triangle's points from `linear`.
        reach: f64,
    },
    /// Project from the parameters of the first facet that holds the vertex.
    FromSeed,
}

/// Every mesh vertex's [`FootHint`], as the report reads them.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FootHints<'a> {
    /// One per vertex (a vertex beyond the list: [`FootHint::FromSeed`]).
    Listed(&'a [FootHint]),
    /// As the facet stage's mesh knows them without a list of its own (which would copy
    /// every triangle vertex's): a triangle's vertex its [`TriangleVertex::hint`], a vertex
    /// listed in `known` that foot, any other [`FootHint::FromSeed`].
    Mesh {
        /// Per triangle of the dual structure, its vertex; empty where the facet stage let
        /// them go (the closed facets', every one [`FootHint::FromSeed`]).
        triangle_vertices: &'a [TriangleVertex],
        /// Per mesh vertex, its triangle, or `u32::MAX` ([`crate::mesh::FacetMesh`]).
        vertex_source: &'a [u32],
        /// The Newton feet of the other vertices where known, by vertex, ascending.
        known: &'a [(u32, [f64; 2])],
    },
    /// As `Mesh`, the triangle vertices' hints in place of the triangle vertices.
    ByTriangle {
        /// Per triangle of the dual structure, its vertex's hint (empty: as in `Mesh`).
        hints: &'a [FootHint],
        /// Per mesh vertex, its triangle, or `u32::MAX`.
        vertex_source: &'a [u32],
        /// The Newton feet of the other vertices where known, by vertex, ascending.
        known: &'a [(u32, [f64; 2])],
    },
}

impl FootHints<'_> {
    /// Vertex v's hint.
    pub(crate) fn get(&self, v: usize) -> FootHint {
        match *self {
            FootHints::Listed(list) => list.get(v).copied().unwrap_or(FootHint::FromSeed),
            FootHints::Mesh {
                triangle_vertices,
                vertex_source,
                known,
            } => mesh_hint(vertex_source, known, v, |t| {
                triangle_vertices.get(t).map(TriangleVertex::hint)
            }),
            FootHints::ByTriangle {
                hints,
                vertex_source,
                known,
            } => mesh_hint(vertex_source, known, v, |t| hints.get(t).copied()),
        }
    }
}

/// Vertex v's hint in the facet stage's mesh: that of its triangle t (`of_triangle(t)`) where
/// it is a triangle's vertex, else its Newton foot if `known` (by vertex, ascending) holds it;
/// otherwise (or where `of_triangle` has none) [`FootHint::FromSeed`].
fn mesh_hint(
    vertex_source: &[u32],
    known: &[(u32, [f64; 2])],
    v: usize,
    of_triangle: impl FnOnce(usize) -> Option<FootHint>,
) -> FootHint {
    match vertex_source.get(v) {
        Some(&t) if t != u32::MAX => of_triangle(t as usize).unwrap_or(FootHint::FromSeed),
        _ => known
            .binary_search_by_key(&(v as u32), |&(w, _)| w)
            .map_or(FootHint::FromSeed, |k| FootHint::Known(known[k].1)),
    }
}

#[derive(Clone, Copy, Debug)]
pub(crate) struct Crossing {
    pub(crate) point: DVec3,
    wall: Position,
    /// Leaving the domain when walking the edge in canonical direction (right to left).
    exit: bool,
    /// Whether the search ended on the boundary (|inside measure| below tolerance).
    converged: bool,
    /// The Newton foot of `point`, when the search computed it.
    pub(crate) foot: Option<[f64; 2]>,
    /// The foot of `point` as the search last estimated it (for in-polygon tests).
    uv: [f64; 2],
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Item {
    Triangle(u32),
    /// An ill-conditioned triangle's stand-in, moved onto the line of one of its edges
    /// (shared by the two facets of that edge).
    EdgePoint {
        triangle: u32,
        lo: u32,
        hi: u32,
    },
    Crossing(u32),
    Corner(u32),
}

struct Context<'a> {
    surface: &'a dyn Surface,
    domain: Domain,
    /// Where facets end: the domain rectangle or the trim's loops.
    boundary: &'a Boundary,
    planes: &'a [Plane],
    uv: &'a [[f64; 2]],
    tangents: &'a [[DVec3; 2]],
    convex_side: &'a [i8],
    /// The dual structure is the exact regular triangulation of the slopes (the convex path):
    /// every vertex is on the envelope, so a far one (a sliver of nearly collinear slopes) is
    /// believed up to [`UNREACHABLE_VERTEX_FACTOR`] instead of replaced by a stand-in.
    regular: bool,
    /// Facet edges may be long against the boundary's features (strips): every edge is
    /// searched for crossings where its feet's segment crosses a loop, not only edges with
    /// an outside end.
    long_edges: bool,
    /// Vertices of triangles with a ghost that lie inside the region are moved out past the
    /// wall along their real facets' common line ([`extend_to_wall`]), except where the
    /// triangle holds a real seed marked here (Some: the any-curvature path's clip).
    extend_to_wall: Option<&'a [bool]>,
    /// How the any-curvature path's clip treats the wall ([`WallMoves::PLAIN`] elsewhere).
    wall: WallMoves,
    /// Real seeds whose facets keep their closed fan, with the crossings of their edges
    /// inserted, while the others are clipped ([`closed_fan_items`]; Some: the hybrid clip of
    /// [`WallClip::clip`]).
    keep_closed: Option<&'a [bool]>,
}

/// How the any-curvature path's clip on the wall moves and keeps vertices ([`Context`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct WallMoves {
    /// Triangle vertices outside the region that no chain of outside vertices joins to a
    /// triangle with a ghost count as inside ([`enclosed_outside`]): the clip's retry.
    keep_enclosed: bool,
    /// Quarter-side steps a vertex of one real facet and two ghosts may move out
    /// ([`extension`]): [`WALL_EXTENSION_OWN_STEPS`] with exact planes.
    own_steps: usize,
}

impl WallMoves {
    /// No enclosed vertex kept; every vertex at most [`WALL_EXTENSION_STEPS`].
    pub(crate) const PLAIN: WallMoves = WallMoves {
        keep_enclosed: false,
        own_steps: WALL_EXTENSION_STEPS,
    };
}

impl Context<'_> {
    fn measure(&self, x: DVec3, guess: [f64; 2]) -> ([f64; 2], f64) {
        let uv = periodic_foot(
            self.surface,
            &self.domain,
            x,
            guess,
            self.boundary.periodic(),
            self.boundary.poles(),
        );
        (uv, self.boundary.inside_measure(uv))
    }

    /// [`Context::measure`] where only the side matters and the foot serves as a guess (the
    /// samples of an edge whose ends are both outside, the far end of an edge leaving the
    /// domain, the march out along a ray): a foot decided outside may stop short of Newton's
    /// convergence ([`crate::projection::outside_foot`]); its inside measure is then off by at
    /// most the estimated remaining movement, a quarter of its size, so the side is right and
    /// a regula falsi bracketed by it stays bracketed. Inside, the same foot as `measure`.
    fn measure_side(&self, x: DVec3, guess: [f64; 2]) -> ([f64; 2], f64) {
        let uv = outside_foot(
            self.surface,
            &self.domain,
            x,
            guess,
            (self.boundary.periodic(), self.boundary.poles()),
            &|uv| self.boundary.inside_measure(uv),
        );
        (uv, self.boundary.inside_measure(uv))
    }

    /// First-order foot of x seen from pattern point i ([`first_order_foot`]).
    fn linear_foot(&self, i: u32, x: DVec3) -> [f64; 2] {
        let i = i as usize;
        first_order_foot(self.uv[i], self.tangents[i], self.planes[i].point, x)
    }

    /// The mean first-order foot of x from the three points, and the largest normalised
    /// distance of the points from it.
    fn linear_estimate(&self, ids: [u32; 3], x: DVec3) -> ([f64; 2], f64) {
        let mut feet = ids.map(|i| self.linear_foot(i, x));
        let mut seeds = ids.map(|i| self.uv[i as usize]);
        // Across a band's seam the three points' parameters are taken within half a period of
        // the first one's, so that their mean is near them, not on the far side.
        for (k, periodic) in self.boundary.periodic().into_iter().enumerate() {
            if !periodic {
                continue;
            }
            let period = if k == 0 { self.domain.u } else { self.domain.v }.length();
            let reference = seeds[0][k];
            for j in 1..3 {
                let shift = ((seeds[j][k] - reference) / period).round() * period;
                seeds[j][k] -= shift;
                feet[j][k] -= shift;
            }
        }
        let linear = [
            (feet[0][0] + feet[1][0] + feet[2][0]) / 3.0,
            (feet[0][1] + feet[1][1] + feet[2][1]) / 3.0,
        ];
        let reach = seeds
            .iter()
            .map(|&p| normalised_distance(&self.domain, p, linear))
            .fold(0.0, f64::max);
        (linear, reach)
    }

    /// Foot of a triangle vertex: Newton from the mean first-order foot `linear` of its three
    /// points. On strongly curved saddles Newton may run to another local minimum far away;
    /// then the first-order estimate, which stays with the triangle (within `reach`), is kept.
    /// Returns the foot, its inside measure, and whether Newton's result was kept.
    fn measure_from(&self, x: DVec3, linear: [f64; 2], reach: f64) -> ([f64; 2], f64, bool) {
        let (newton, inside) = self.measure(x, linear);
        // Across a seam the two feet differ by a period; a band is flat (crate::flat), where
        // Newton's foot is the only one.
        if self.boundary.periodic() != [false; 2]
            || accept_newton(&self.domain, newton, linear, reach)
        {
            (newton, inside, true)
        } else {
            (linear, self.boundary.inside_measure(linear), false)
        }
    }
}

/// Whether Newton's foot `newton`, started from the first-order estimate `linear` of a
/// triangle vertex whose points lie within `reach` of it, stayed with the triangle.
pub(crate) fn accept_newton(
    domain: &Domain,
    newton: [f64; 2],
    linear: [f64; 2],
    reach: f64,
) -> bool {
    normalised_distance(domain, newton, linear) <= 2.0 * reach + 1e-9
}

/// Whether a vertex whose first-order foot is `linear` (triangle reach `reach`) is inside
/// the domain whatever Newton does: the foot that `Context::measure_from` keeps lies within
/// 2 reach + 1e-9 of `linear` (normalised), and the inside measure is 1-Lipschitz there, so
/// a margin beyond that (with room for rounding) decides the test without projecting.
fn surely_inside(boundary: &Boundary, linear: [f64; 2], reach: f64) -> bool {
    let margin = 2.0 * reach + 1e-9;
    boundary.inside_measure(linear) > margin * (1.0 + 1e-9) + 1e-12
}

/// The facet stage's result.
pub(crate) struct Facets {
    /// The facets and their mesh.
    pub(crate) mesh: FacetMesh,
    /// The dual structure's triangles over the real seeds alone (ghosts dropped).
    pub(crate) triangulation: DualTriangulation,
    /// On strips, every neighbour pair of real seeds (their triangles nearly all hold a ghost);
    /// empty otherwise.
    pub(crate) ghost_neighbours: Vec<[u32; 2]>,
}

/// Stage 3 of the pipeline: dual structure -> facets, as its [`FacetPlan`] says: clipped on
/// `boundary` (or the plan's band), or closed by the ghosts' planes (clipped on a trim where
/// there is one). With `release_tangents` (no live editing) the clipped facets let the
/// samples' tangents go before their assembly.
pub(crate) fn build_stage(
    surface: &dyn Surface,
    boundary: &Boundary,
    samples: &mut Samples,
    structure: DualStructure,
    params: &FacetParams,
    release_tangents: bool,
    stages: &Stages<'_>,
) -> Facets {
    let n = samples.uv.len();
    let DualStructure {
        mut triangulation,
        plan,
        ..
    } = structure;
    stages.enter(Stage::Facets, Some(triangulation.len() + n));
    // `ghosts`: the structure holds more points than the real seeds.
    let (mesh, ghosts, strips) = match &plan {
        FacetPlan::Clipped { band } => {
            let mesh = build_facets(
                surface,
                band.as_ref().unwrap_or(boundary),
                samples,
                &triangulation,
                params,
                release_tangents,
                stages,
            );
            (mesh, false, false)
        }
        FacetPlan::Ghosts {
            planes,
            source,
            strips,
        } => {
            let mesh = if boundary.is_trim() {
                let seeds = GhostSeeds {
                    uv: &samples.uv,
                    tangents: &samples.tangents,
                    planes,
                    source,
                    all: None,
                };
                build_ghost_clipped_facets(
                    surface,
                    boundary,
                    &seeds,
                    &triangulation,
                    params,
                    None,
                    WallMoves::PLAIN,
                    None,
                    None,
                    stages,
                )
                .0
            } else {
                // Not strips: the convex hull of the dual points, the envelope itself.
                let envelope = !*strips;
                build_closed_facets(&triangulation, planes, n, source, envelope, params, stages)
            };
            (mesh, planes.len() > n, *strips)
        }
        FacetPlan::Augmented { seeds, on_wall } => {
            let mesh = if *on_wall {
                let wall = WallClip {
                    surface,
                    boundary,
                    samples,
                    seeds,
                    params,
                    vertices: RefCell::new(VertexCache::default()),
                    ghost_arrays: std::cell::OnceCell::new(),
                    hybrid_keep: RefCell::new(Vec::new()),
                };
                let (flipped, mesh) = wall.flipped_and_clipped(&triangulation, stages);
                if let Some(flipped) = flipped {
                    triangulation = flipped;
                }
                mesh
            } else {
                build_closed_facets(
                    &triangulation,
                    &seeds.planes,
                    n,
                    &seeds.source,
                    false,
                    params,
                    stages,
                )
            };
            (mesh, true, false)
        }
    };
    drop(plan);
    let ghost_neighbours = if strips {
        real_pairs(&triangulation, n)
    } else {
        Vec::new()
    };
    // The dual structure reported is the real seeds' part.
    let mut real = triangulation;
    if ghosts {
        real.retain_points(n);
        real.canonicalise(n);
    }
    Facets {
        mesh,
        triangulation: real,
        ghost_neighbours,
    }
}

/// What the any-curvature path's clip on the wall reads.
struct WallClip<'a> {
    surface: &'a dyn Surface,
    boundary: &'a Boundary,
    samples: &'a Samples,
    seeds: &'a crate::ghosts::Augmented,
    params: &'a FacetParams,
    /// The triangle vertices computed so far, shared by the wall flips' tries and every
    /// clip: all in one ghost context ([`with_ghost_context`]), so a triangle's vertex is
    /// the same wherever it is asked for ([`VertexCache`]).
    vertices: RefCell<VertexCache>,
    /// Every point's parameters and tangents in the ghost context ([`ghost_arrays`]), made
    /// at the first clip or flips' try.
    ghost_arrays: std::cell::OnceCell<GhostArrays>,
    /// The real seeds whose facets the last hybrid clip that kept its shape left closed
    /// (empty before one; [`WallClip::clip`]).
    hybrid_keep: RefCell<Vec<bool>>,
}

/// A mesh with its facets' verdicts ([`mesh_shape`]), from which another mesh's facet of
/// the same polygon takes its verdict.
type Judged<'m> = (&'m FacetMesh, &'m [Verdict]);

/// A facet's simplicity in its plane, as [`crate::quality::facet_shape_into`] judges it:
/// `simple` = at least 3 vertices, positive area and no two non-adjacent edges touching
/// (`crossing`).
#[derive(Clone, Copy, Debug)]
struct Verdict {
    simple: bool,
    crossing: bool,
}

/// Triangle vertices and their extensions to the wall, all computed in one context, so that
/// a triangle that several triangulations share (the unflipped and flipped ones of the wall
/// flips, [`WallClip`]) is computed once. Only looked up, never iterated: the cache changes
/// no result.
#[derive(Default)]
pub(crate) struct VertexCache {
    /// [`triangle_vertex`] by the triangle's points in ascending order: a vertex depends only
    /// on its three points' planes, parameters and tangents, and on the boundary.
    vertices: IndexMap<[u32; 3], TriangleVertex>,
    /// [`extension`] by [`extension_key`]: it depends only on the triangle's points in their
    /// order, its vertex (given by the points) and the vertices across its edges.
    extensions: IndexMap<ExtensionKey, Option<TriangleVertex>>,
    /// [`long_edge_crossings`] by [`crossing_key`] of the edge's two triangle vertices: it
    /// depends only on them.
    crossings: IndexMap<Bits<16>, Vec<Crossing>>,
    /// The wall flips' notch of a chain segment ([`wall_flips`]) by the bits of its ends'
    /// points, feet and inside measures: it depends only on them.
    notches: IndexMap<Bits<12>, f64>,
}

/// Bits of floats as a hash key, hashed word by word.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) struct Bits<const N: usize>([u64; N]);

impl<const N: usize> std::hash::Hash for Bits<N> {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        for &x in &self.0 {
            state.write_u64(x);
        }
    }
}

/// The key of [`long_edge_crossings`] of the edge from the vertex `right` to `left`: every
/// field of theirs it reads.
fn crossing_key(right: &TriangleVertex, left: &TriangleVertex) -> Bits<16> {
    let mut bits = [0u64; 16];
    for (k, v) in [right, left].into_iter().enumerate() {
        let words = [
            v.point.x, v.point.y, v.point.z, v.foot[0], v.foot[1], v.inside, v.reach,
        ];
        for (j, w) in words.into_iter().enumerate() {
            bits[8 * k + j] = w.to_bits();
        }
        bits[8 * k + 7] = u64::from(v.measured);
    }
    Bits(bits)
}

/// A triangle's points in their order, the bits of the vertices across its edges (0 where
/// none) and which of those there are.
type ExtensionKey = Bits<13>;

/// The key of [`extension`] of the triangle `ids` with the vertices `across` its edges.
fn extension_key(ids: [u32; 3], across: [Option<DVec3>; 3]) -> ExtensionKey {
    let mut bits = [0u64; 13];
    for k in 0..3 {
        bits[k] = u64::from(ids[k]);
        if let Some(p) = across[k] {
            for (j, w) in p.to_array().into_iter().enumerate() {
                bits[3 + 3 * k + j] = w.to_bits();
            }
            bits[12] |= 1 << k;
        }
    }
    Bits(bits)
}

/// How far a part of the mesh's edge (edges held by one facet) stands inside the region, in
/// normalised parameters: each edge sampled at [`WALL_FLIP_NOTCH_SAMPLES`] + 1 points x_k
/// with feet u_k and depths d_k = max(0, inside measure of u_k),
///
///   area = sum_k (d_k + d_(k+1)) / 2 |u_(k+1) - u_k|,   depth = max_k d_k,
///
/// the area between the mesh's edge and the wall, and its deepest point.
#[derive(Clone, Copy, Debug, Default)]
struct Notch {
    area: f64,
    depth: f64,
}

impl Notch {
    /// Two parts of the mesh's edge together.
    fn join(self, other: Notch) -> Notch {
        Notch {
            area: self.area + other.area,
            depth: self.depth.max(other.depth),
        }
    }

    /// Whether this notch is larger than `before` in area or depth by more than
    /// [`WALL_FLIP_NOTCH_SLACK`].
    fn exceeds(self, before: Notch) -> bool {
        self.area > before.area + WALL_FLIP_NOTCH_SLACK
            || self.depth > before.depth + WALL_FLIP_NOTCH_SLACK
    }
}

/// The outcome of one clip on the wall ([`WallClip::clip`]).
struct WallOutcome {
    /// The clipped facets when they keep the closed facets' shape, else the closed facets.
    mesh: FacetMesh,
    /// Whether the clipped facets were kept.
    clipped: bool,
    /// The facets among those marked that came out of the clip invalid (ascending), or
    /// whose extension to the wall was taken back.
    culprits: Vec<usize>,
    /// The mesh's [`crate::sanity::edges`] (None: an edge held wrongly).
    edges: Option<(usize, Vec<(u32, u32)>)>,
    /// Per facet, whether it is simple in its plane ([`mesh_shape`]; None where not judged).
    simple: Option<Vec<Verdict>>,
}

impl WallClip<'_> {
    /// The facets of `tri` clipped on the wall, after the wall flips
    /// ([`wall_flips::wall_flips`]) where they keep the clip sound and no vertex farther
    /// from the surface than before: the flipped triangulation (None where no flip is kept)
    /// and the mesh.
    ///
    /// Each try clips the flipped triangulation and compares it with the unflipped clip over
    /// every flip's region (the facets it can change). A flip is refused (its quad's points
    /// blocked, the flips redone) when its region comes out of the clip invalid, or when,
    /// against the unflipped clip ([`WallClip::measure`]),
    /// - its region's deviation, the largest distance of the vertices from the surface,
    ///   grows by more than [`WALL_FLIP_DEVIATION_SLACK`] spacings: the flips' score weighs
    ///   the area between the chain and the wall, not how far the new vertices stand off the
    ///   surface (on samples/saddle.json, hex:spacing=0.0714, a flip handed a domain corner
    ///   to another facet, whose plane stands 0.0433 off the surface there; 0.0193 at most
    ///   without the flips);
    /// - its region's part of the mesh's edge ([`Notch`]) grows in area or depth;
    /// - a corner near its region lies farther from the mesh's edge ([`corner_cut`]).
    fn flipped_and_clipped(
        &self,
        tri: &DualTriangulation,
        stages: &Stages<'_>,
    ) -> (Option<DualTriangulation>, FacetMesh) {
        let n = self.samples.uv.len();
        let unreported = Stages::new(&NoProgress);
        let mut blocked = vec![false; n];
        let mut reported = false;
        // Exact planes only: with adjusted ones (`samples.tangent_planes` set) a flip left a
        // facet thin enough on a rotated hypar (grid, 300 points) that its vertices gave a
        // plane 4.5 degrees off its reported tilt of 0.
        let tries = if self.samples.tangent_planes.is_none() {
            WALL_FLIP_RETRIES
        } else {
            0
        };
        let spacing = self.samples.diagonal / (2.0 * n as f64).sqrt();
        // The unflipped clip, made once where a flip is kept, with its marked facets measured.
        let mut unflipped: Option<Measured> = None;
        // The measures taken so far, by facet and shape ([`measure_key`]).
        let mut measures = IndexMap::default();
        // The boundary's corners on the surface.
        let corners: Vec<DVec3> = self
            .boundary
            .corners()
            .iter()
            .map(|&([u, v], _)| self.surface.point_at(u, v))
            .collect();
        for _ in 0..tries {
            let mut flipped = tri.clone();
            let ghost_seeds = self.ghost_seeds();
            let flips = with_ghost_context(
                self.surface,
                self.boundary,
                &ghost_seeds,
                None,
                WallMoves {
                    keep_enclosed: false,
                    own_steps: self.own_steps(),
                },
                None,
                |ctx| {
                    wall_flips::wall_flips(
                        ctx,
                        n,
                        &mut flipped,
                        &self.seeds.planes,
                        self.params.far_vertex_factor,
                        &blocked,
                        &mut self.vertices.borrow_mut(),
                    )
                },
            );
            if flips.is_empty() {
                break;
            }
            let mut marked = vec![false; n];
            for flip in &flips {
                for &x in &flip.region {
                    marked[x as usize] = true;
                }
            }
            let before = unflipped.get_or_insert_with(|| {
                let outcome = self.clip(tri, &vec![false; n], None, stages);
                reported = true;
                Measured::new(outcome)
            });
            self.measure(before, &marked, &mut measures);
            let before = &*before;
            let reference = before
                .outcome
                .simple
                .as_deref()
                .map(|simple| (&before.outcome.mesh, simple));
            let outcome = self.clip(
                &flipped,
                &marked,
                reference,
                if reported { &unreported } else { stages },
            );
            reported = true;
            let mut after = Measured::new(outcome);
            self.measure(&mut after, &marked, &mut measures);
            let region_notch = |notch: &[Option<Notch>], flip: &wall_flips::WallFlip| {
                flip.region
                    .iter()
                    .filter_map(|&x| notch.get(x as usize).copied().flatten())
                    .fold(Notch::default(), Notch::join)
            };
            let region_deviation = |deviation: &[f64], flip: &wall_flips::WallFlip| {
                flip.region
                    .iter()
                    .filter_map(|&x| deviation.get(x as usize).copied())
                    .fold(0.0, f64::max)
            };
            let raised: Vec<bool> = flips
                .iter()
                .map(|flip| {
                    region_deviation(&after.deviation, flip)
                        > region_deviation(&before.deviation, flip)
                            + WALL_FLIP_DEVIATION_SLACK * spacing
                        || region_notch(&after.notch, flip)
                            .exceeds(region_notch(&before.notch, flip))
                        || corner_cut(before, &after, &flip.region, &corners, spacing)
                })
                .collect();
            let outcome = after.outcome;
            if outcome.clipped && outcome.culprits.is_empty() && !raised.contains(&true) {
                return (Some(flipped), outcome.mesh);
            }
            let mut any = false;
            for (flip, &raised) in flips.iter().zip(&raised) {
                if raised
                    || flip
                        .region
                        .iter()
                        .any(|x| outcome.culprits.binary_search(&(*x as usize)).is_ok())
                    || (outcome.culprits.is_empty() && !outcome.clipped)
                {
                    for &x in &flip.quad {
                        if (x as usize) < n && !blocked[x as usize] {
                            blocked[x as usize] = true;
                            any = true;
                        }
                    }
                }
            }
            if !any {
                break;
            }
        }
        let outcome = match unflipped {
            Some(measured) => measured.outcome,
            None => self.clip(
                tri,
                &vec![false; n],
                None,
                if reported { &unreported } else { stages },
            ),
        };
        (None, outcome.mesh)
    }

    /// Measures, where not yet measured, every facet f `marked` of `m`'s mesh: its deviation,
    /// the largest distance of its vertices from the surface, each projected by Newton from
    /// f's seed ([`crate::projection::distance_foot`], as the report's deviation), and the
    /// notch of its edges that no other facet holds ([`Notch`]). A facet of the same seed,
    /// polygon and edges held once as one measured before (in `measures`, by
    /// [`measure_key`]) takes that one's measure: it depends on nothing else.
    fn measure(
        &self,
        m: &mut Measured,
        marked: &[bool],
        measures: &mut IndexMap<Vec<u64>, (f64, Notch)>,
    ) {
        let wrap = crate::projection::Wrap {
            domain: self.surface.domain(),
            periodic: self.boundary.periodic(),
            poles: self.boundary.poles(),
        };
        let mesh = &m.outcome.mesh;
        let facets = mesh.offsets.len().saturating_sub(1);
        for (f, _) in marked.iter().enumerate().take(facets).filter(|x| *x.1) {
            if m.notch[f].is_some() {
                continue;
            }
            let key = measure_key(mesh, &m.held, f);
            if let Some(&(deviation, notch)) = measures.get(&key) {
                m.deviation[f] = deviation;
                m.notch[f] = Some(notch);
                continue;
            }
            let seed = self.samples.uv[f];
            m.deviation[f] = mesh
                .polygon(f)
                .into_iter()
                .map(|x| {
                    let foot = crate::projection::distance_foot(self.surface, &wrap, x, seed);
                    crate::projection::deviation_at(self.surface, &wrap.domain, x, foot).0
                })
                .fold(0.0, f64::max);
            let mut total = Notch::default();
            let mut guess = seed;
            for (p, q) in edge_segments(mesh, &m.held, f) {
                let mut previous: Option<([f64; 2], f64)> = None;
                for j in 0..=WALL_FLIP_NOTCH_SAMPLES {
                    let x = p.lerp(q, j as f64 / WALL_FLIP_NOTCH_SAMPLES as f64);
                    let foot = periodic_foot(
                        self.surface,
                        &wrap.domain,
                        x,
                        guess,
                        wrap.periodic,
                        wrap.poles,
                    );
                    guess = foot;
                    let depth = self.boundary.inside_measure(foot).max(0.0);
                    let st = wrap.domain.to_normalised(foot);
                    if let Some((prev_st, prev_depth)) = previous {
                        let step = (st[0] - prev_st[0]).hypot(st[1] - prev_st[1]);
                        total.area += 0.5 * (prev_depth + depth) * step;
                    }
                    total.depth = total.depth.max(depth);
                    previous = Some((st, depth));
                }
            }
            m.notch[f] = Some(total);
            measures.insert(key, (m.deviation[f], total));
        }
    }

    /// [`WallMoves::own_steps`]: exact planes only. With adjusted ones the farther moves
    /// raised the largest deviation on samples/saddle.json with `random:3000` from 0.0041 to
    /// 0.0052, and the clip of the flips' tries and of the result must move alike (the
    /// extensions are cached by triangle).
    fn own_steps(&self) -> usize {
        if self.samples.tangent_planes.is_none() {
            WALL_EXTENSION_OWN_STEPS
        } else {
            WALL_EXTENSION_STEPS
        }
    }

    /// The ghost seeds of every clip and flips' try, with their points' parameters and
    /// tangents made once ([`ghost_arrays`]).
    fn ghost_seeds(&self) -> GhostSeeds<'_> {
        let mut seeds = GhostSeeds {
            uv: &self.samples.uv,
            tangents: &self.samples.tangents,
            planes: &self.seeds.planes,
            source: &self.seeds.source,
            all: None,
        };
        seeds.all = Some(self.ghost_arrays.get_or_init(|| ghost_arrays(&seeds)));
        seeds
    }

    /// The facets of `tri` clipped on the wall (module doc, the clip's retries included), or
    /// the closed facets where the clipped ones do not keep their shape; the culprits among
    /// the facets `marked`. A clip that does not keep the shape is retried with the enclosed
    /// outside vertices kept ([`enclosed_outside`]), and that one is kept where it keeps the
    /// shape with no more invalid facets ([`invalid_marked_facets`], all facets) than the
    /// closed facets. The shape checks take a facet's simplicity from `reference` (an
    /// earlier clip) where it has the facet's polygon.
    fn clip(
        &self,
        tri: &DualTriangulation,
        marked: &[bool],
        reference: Option<Judged<'_>>,
        stages: &Stages<'_>,
    ) -> WallOutcome {
        let (samples, seeds, params) = (self.samples, self.seeds, self.params);
        let n = samples.uv.len();
        let unreported = Stages::new(&NoProgress);
        let closed = build_closed_facets(
            tri,
            &seeds.planes,
            n,
            &seeds.source,
            false,
            params,
            &unreported,
        );
        // Only the first clip reports progress: the retries redo the same stage.
        let clip = |blocked: &[bool],
                    keep_enclosed: bool,
                    keep_closed: Option<&[bool]>,
                    stages: &Stages<'_>| {
            build_ghost_clipped_facets(
                self.surface,
                self.boundary,
                &self.ghost_seeds(),
                tri,
                params,
                Some(blocked),
                WallMoves {
                    keep_enclosed,
                    own_steps: self.own_steps(),
                },
                keep_closed,
                Some(&mut self.vertices.borrow_mut()),
                stages,
            )
        };
        let spacing = samples.diagonal / (2.0 * n as f64).sqrt();
        // The closed facets' edges and shape, counted once for every clip compared with them.
        let closed_edges = std::cell::OnceCell::new();
        let closed_shape = std::cell::OnceCell::new();
        let planes = &seeds.planes[..n];
        // The clipped facets in their final form with their edges, if they keep the closed
        // ones' shape; else, where `blame`, the facets to keep closed in a hybrid clip
        // ([`clip_suspects`]; only the first clip's are used).
        let finish = |mut clipped: FacetMesh, blame: bool| {
            weld_coincident_crossings(&mut clipped, params.weld_distance);
            drop_coincident_crossings(&mut clipped, WALL_CLIP_SHORT_EDGE * spacing);
            start_loops_at_lowest_triangle(&mut clipped);
            // One edge count serves all three: marking changes kinds, not loops.
            let clipped_edges = crate::sanity::edges(&clipped.offsets, &clipped.loops).ok();
            if let Some((_, boundary)) = &clipped_edges {
                mark_boundary_vertices(&mut clipped, boundary);
            }
            let before: &Option<(MeshShape, Vec<Verdict>)> = closed_shape.get_or_init(|| {
                let edges = closed_edges
                    .get_or_init(|| crate::sanity::edges(&closed.offsets, &closed.loops).ok());
                mesh_shape(&closed, edges, planes, reference.as_slice())
            });
            let mut known: Vec<Judged<'_>> = Vec::with_capacity(2);
            if let Some((_, verdicts)) = before {
                known.push((&closed, verdicts));
            }
            known.extend(reference);
            let after = mesh_shape(&clipped, &clipped_edges, planes, &known);
            let (after, simple) =
                after.map_or((None, None), |(shape, simple)| (Some(shape), Some(simple)));
            match (before, &after) {
                (_, None) => Err(Vec::new()),
                (Some((before, closed_simple)), after)
                    if !wall_clip_keeps_shape(Some(before), after.as_ref()) =>
                {
                    Err(if blame {
                        let simple = simple.as_deref();
                        let reach = before.reach;
                        clip_suspects(
                            &clipped,
                            &clipped_edges,
                            simple,
                            closed_simple,
                            planes,
                            reach,
                        )
                    } else {
                        Vec::new()
                    })
                }
                _ => Ok((clipped, clipped_edges, simple)),
            }
        };
        // One clip with its retries: the clipped facets if kept (else the suspects of the
        // first clip), and the culprits.
        let attempt = |keep_enclosed: bool, keep_closed: Option<&[bool]>, stages: &Stages<'_>| {
            let mut blocked = vec![false; n];
            let (mut clipped, mut extended) = clip(&blocked, keep_enclosed, keep_closed, stages);
            let mut culprits = Vec::new();
            // Facets extended to the wall that came out invalid keep their ghost's end.
            for _ in 0..WALL_EXTENSION_ROUNDS {
                let invalid = invalid_extended_facets(&clipped, &seeds.planes[..n], tri, &extended);
                if invalid.is_empty() {
                    break;
                }
                culprits.extend(invalid.iter().copied().filter(|&f| marked[f]));
                for f in invalid {
                    blocked[f] = true;
                }
                (clipped, extended) = clip(&blocked, keep_enclosed, keep_closed, &unreported);
            }
            if marked.contains(&true) {
                culprits.extend(invalid_marked_facets(
                    &clipped,
                    &seeds.planes[..n],
                    marked,
                    WALL_FLIP_MIN_AREA * spacing * spacing,
                ));
                // A marked facet the wall cuts into parts loses all but one: a gap beside the
                // wall, which the flips are to close, not open.
                culprits.extend(clipped.diagnostics.iter().filter_map(|d| match *d {
                    Diagnostic::FacetPartsLeftOut { point, .. } if marked[point as usize] => {
                        Some(point as usize)
                    }
                    _ => None,
                }));
            }
            culprits.sort_unstable();
            culprits.dedup();
            let blame = !keep_enclosed && keep_closed.is_none();
            let kept = finish(clipped, blame).or_else(|suspects| {
                if extended.contains(&true) {
                    finish(
                        clip(&vec![true; n], keep_enclosed, keep_closed, &unreported).0,
                        false,
                    )
                    .map_err(|_| suspects)
                } else {
                    Err(suspects)
                }
            });
            (kept, culprits)
        };
        let (first, mut culprits) = attempt(false, None, stages);
        let (mut kept, suspects) = match first {
            Ok(mesh) => (Some(mesh), Vec::new()),
            Err(suspects) => (None, suspects),
        };
        // Where an earlier clip of this wall needed the hybrid below, that one is tried
        // next: the retry with enclosed vertices kept failed there.
        let hybrid_before = self.hybrid_keep.borrow().contains(&true);
        if kept.is_none() && !hybrid_before {
            // Vertices that ran away from their points near a parabolic line and whose
            // feet fell beyond the wall cut holes in the clip (on seeded mixed surfaces,
            // holes in 8 of 8 hex and Poisson runs checked, and the whole boundary then
            // kept its closed facets): they are kept, as the closed facets keep them, where
            // that leaves no more invalid facets than the closed facets have.
            let all = vec![true; n];
            let invalid =
                |mesh: &FacetMesh| invalid_marked_facets(mesh, &seeds.planes[..n], &all, 0.0).len();
            let (retry, retry_culprits) = attempt(true, None, &unreported);
            if let Some(mesh) = retry
                .ok()
                .filter(|(mesh, _, _)| invalid(mesh) <= invalid(&closed))
            {
                kept = Some(mesh);
                culprits = retry_culprits;
            }
        }
        if kept.is_none() && suspects.contains(&true) {
            // Where the clip fails only in places (a facet left beyond the wall, a facet the
            // clip turns non-simple), those facets keep their closed fans and the rest of the
            // mesh's edge stays on the wall: a ring of neighbours more each round, up to the
            // closed facets everywhere. The facets an earlier clip of this wall kept closed
            // join the first round: the unflipped and flipped triangulations of the wall
            // flips mostly fail alike.
            let mut keep = suspects;
            for (k, &earlier) in keep.iter_mut().zip(self.hybrid_keep.borrow().iter()) {
                *k |= earlier;
            }
            for _ in 0..WALL_CLIP_HYBRID_ROUNDS {
                let (retry, retry_culprits) = attempt(false, Some(&keep), &unreported);
                // Away from the kept facets and their neighbours the clip is the first one,
                // which failed only on its shape: overlaps are counted near them.
                let near = with_neighbours(tri, &keep);
                let local = |mesh: &FacetMesh| {
                    invalid_marked_facets(mesh, &seeds.planes[..n], &near, 0.0).len()
                };
                if let Some(mesh) = retry
                    .ok()
                    .filter(|(mesh, _, _)| local(mesh) <= local(&closed))
                {
                    kept = Some(mesh);
                    culprits = retry_culprits;
                    *self.hybrid_keep.borrow_mut() = keep;
                    break;
                }
                keep = near;
            }
        }
        match kept {
            Some((mut clipped, edges, simple)) => {
                // The count of coincident neighbour planes is the structure's, not the
                // clip's: it is kept.
                clipped.diagnostics.extend(
                    closed
                        .diagnostics
                        .into_iter()
                        .filter(|d| matches!(d, Diagnostic::CoincidentPlanes { .. })),
                );
                WallOutcome {
                    mesh: clipped,
                    clipped: true,
                    culprits,
                    edges,
                    simple,
                }
            }
            None => {
                let edges = closed_edges
                    .into_inner()
                    .unwrap_or_else(|| crate::sanity::edges(&closed.offsets, &closed.loops).ok());
                let simple = closed_shape.into_inner().flatten().map(|x| x.1);
                WallOutcome {
                    mesh: closed,
                    clipped: false,
                    culprits,
                    edges,
                    simple,
                }
            }
        }
    }
}

/// A clip on the wall with its marked facets measured ([`WallClip::measure`]).
struct Measured {
    outcome: WallOutcome,
    /// The mesh's edges held by one facet ([`held_once`]).
    held: HashSet<(u32, u32)>,
    /// Per facet, the largest distance of its vertices from the surface (0 until measured).
    deviation: Vec<f64>,
    /// Per facet, the notch of its part of the mesh's edge (None until measured).
    notch: Vec<Option<Notch>>,
}

impl Measured {
    /// The clip `outcome`, no facet measured yet.
    fn new(mut outcome: WallOutcome) -> Measured {
        let n = outcome.mesh.offsets.len().saturating_sub(1);
        Measured {
            held: held_once(outcome.edges.take()),
            deviation: vec![0.0; n],
            notch: vec![None; n],
            outcome,
        }
    }
}

/// Whether a corner of the boundary (`corners`, on the surface) within
/// [`WALL_FLIP_CORNER_REACH`] spacings of the mesh's edge along the facets `region` lies
/// farther from that edge in `after`'s mesh than in `before`'s: the wall flips' notch scores,
/// measured along the chain or the mesh's edge by the depth inside the region, see little
/// of a corner cut off (a square hypar with hex patterns lost a corner to a flip that
/// closed a notch beside it). As the rest of the mesh's edge is the same in both, a
/// corner farther from the mesh's edge is farther from this part of it.
fn corner_cut(
    before: &Measured,
    after: &Measured,
    region: &[u32],
    corners: &[DVec3],
    spacing: f64,
) -> bool {
    if corners.is_empty() {
        return false;
    }
    let edges = |m: &Measured| -> Vec<(DVec3, DVec3)> {
        let (mesh, held) = (&m.outcome.mesh, &m.held);
        region
            .iter()
            .filter(|&&f| (f as usize) + 1 < mesh.offsets.len())
            .flat_map(|&f| edge_segments(mesh, held, f as usize))
            .collect()
    };
    let distance = |edges: &[(DVec3, DVec3)], c: DVec3| {
        edges
            .iter()
            .map(|&(a, b)| {
                let ab = b - a;
                let t =
                    ((c - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
                (a + ab * t).distance(c)
            })
            .fold(f64::INFINITY, f64::min)
    };
    let (old, new) = (edges(before), edges(after));
    corners.iter().any(|&c| {
        let (d_old, d_new) = (distance(&old, c), distance(&new, c));
        d_old.min(d_new) <= WALL_FLIP_CORNER_REACH * spacing
            && d_new > d_old + WALL_FLIP_DEVIATION_SLACK * spacing
    })
}

/// The edges of a mesh that one facet holds (the mesh's edge), each as (lower, higher) vertex,
/// from its [`crate::sanity::edges`]; none where an edge is held wrongly (`edges` None).
fn held_once(edges: Option<(usize, Vec<(u32, u32)>)>) -> HashSet<(u32, u32)> {
    edges
        .map(|(_, edges)| {
            edges
                .into_iter()
                .map(|(a, b)| (a.min(b), a.max(b)))
                .collect()
        })
        .unwrap_or_default()
}

/// What [`WallClip::measure`] of facet f reads of the mesh: f, the bits of its polygon's
/// vertices in loop order, and which of its edges `held` holds (one bit per edge after the
/// vertices).
fn measure_key(mesh: &FacetMesh, held: &HashSet<(u32, u32)>, f: usize) -> Vec<u64> {
    let facet = mesh.facet_loop(f);
    let mut key = Vec::with_capacity(2 + 4 * facet.len());
    key.push(f as u64);
    key.push(facet.len() as u64);
    for &a in facet {
        key.extend(mesh.vertices[a as usize].to_array().map(f64::to_bits));
    }
    for k in 0..facet.len() {
        let (a, b) = (facet[k], facet[(k + 1) % facet.len()]);
        key.push(u64::from(held.contains(&(a.min(b), a.max(b)))));
    }
    key
}

/// The edges of facet f of `mesh` in `held` ([`held_once`]), as their ends' positions.
fn edge_segments<'m>(
    mesh: &'m FacetMesh,
    held: &'m HashSet<(u32, u32)>,
    f: usize,
) -> impl Iterator<Item = (DVec3, DVec3)> + 'm {
    let facet = mesh.facet_loop(f);
    (0..facet.len())
        .map(move |k| (facet[k], facet[(k + 1) % facet.len()]))
        .filter(move |&(a, b)| held.contains(&(a.min(b), a.max(b))))
        .map(move |(a, b)| (mesh.vertices[a as usize], mesh.vertices[b as usize]))
}

/// Whether the facets clipped on the wall keep the shape of the facets closed by the ghosts'
/// planes, given the two meshes' [`mesh_shape`]s (`closed`, `clipped`; None where an edge is
/// held wrongly), both over the real seeds' planes: the same Euler
/// characteristic and boundary loops, every edge held once or twice in opposite directions,
/// no more facets open or non-simple, and no vertex farther from its facet's seed than the
/// closed facets reach (a clipped facet is a part of its closed one; a corner's normal line
/// that meets a non-convex facet's plane far away must not add a spike). On a saddle a boundary facet's edges can run past
/// the wall all around it (its polygon, not its seed, beyond the boundary) and its neighbours'
/// cuts then leave it apart: that facet and a ring of neighbours then keep their closed fans,
/// which the validity flips judged ([`clip_suspects`], the hybrid clip of [`WallClip::clip`]).
fn wall_clip_keeps_shape(closed: Option<&MeshShape>, clipped: Option<&MeshShape>) -> bool {
    match (closed, clipped) {
        (Some(before), Some(after)) => {
            after.euler == before.euler
                && after.boundary_loops == before.boundary_loops
                && after.bad_facets <= before.bad_facets
                && after.reach <= before.reach
        }
        (None, Some(_)) => true,
        (_, None) => false,
    }
}

/// The facets to blame where a clip does not keep the closed facets' shape, to be kept closed
/// in a hybrid clip ([`WallClip::clip`]), per facet of `clipped`: those apart from the largest
/// group of facets joined by shared edges (a facet the wall leaves nothing of keeps its
/// closed fan beyond the wall, alone), those holding a vertex where the mesh's edge pinches
/// (four or more boundary edges), those not simple in their plane that are simple closed
/// (`closed_simple`), and those with a vertex farther than `reach` (the closed facets'
/// largest) from their seed (a facet whose edges cross the wall far from its seed and that
/// follows the wall round several corners). None where `edges` is (an edge held wrongly).
fn clip_suspects(
    clipped: &FacetMesh,
    edges: &Option<(usize, Vec<(u32, u32)>)>,
    simple: Option<&[Verdict]>,
    closed_simple: &[Verdict],
    planes: &[Plane],
    reach: f64,
) -> Vec<bool> {
    let Some((_, boundary)) = edges else {
        return Vec::new();
    };
    let facets = clipped.offsets.len().saturating_sub(1);
    let mut suspect = vec![false; facets];
    // Groups of facets joined by shared edges (union-find over the sorted edge list).
    let mut held: Vec<(u32, u32, u32)> = Vec::with_capacity(clipped.loops.len());
    for f in 0..facets {
        let lp = clipped.facet_loop(f);
        for k in 0..lp.len() {
            let (a, b) = (lp[k], lp[(k + 1) % lp.len()]);
            held.push((a.min(b), a.max(b), f as u32));
        }
    }
    held.sort_unstable();
    let mut parent: Vec<u32> = (0..facets as u32).collect();
    for w in held.windows(2) {
        if (w[0].0, w[0].1) == (w[1].0, w[1].1) {
            let (a, b) = (find(&mut parent, w[0].2), find(&mut parent, w[1].2));
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let roots: Vec<u32> = (0..facets as u32).map(|f| find(&mut parent, f)).collect();
    let mut size = vec![0usize; facets];
    for &r in &roots {
        size[r as usize] += 1;
    }
    // The largest group, the lowest root on a tie.
    let main = (0..facets).max_by_key(|&r| (size[r], std::cmp::Reverse(r)));
    let mut boundary_edges = vec![0u32; clipped.vertices.len()];
    for &(a, b) in boundary {
        boundary_edges[a as usize] += 1;
        boundary_edges[b as usize] += 1;
    }
    for f in 0..facets {
        let lp = clipped.facet_loop(f);
        let apart = main.is_some_and(|m| roots[f] as usize != m);
        let pinched = lp.iter().any(|&v| boundary_edges[v as usize] >= 4);
        let turned = simple.is_some_and(|after| {
            !after[f].simple && closed_simple.get(f).is_some_and(|x| x.simple)
        });
        let far = lp
            .iter()
            .any(|&v| clipped.vertices[v as usize].distance(planes[f].point) > reach);
        suspect[f] = apart || pinched || turned || far;
    }
    suspect
}

/// `marked` with every real neighbour of a marked point in `tri` marked too.
fn with_neighbours(tri: &DualTriangulation, marked: &[bool]) -> Vec<bool> {
    let mut grown = marked.to_vec();
    let real = marked.len();
    for t in &tri.triangles {
        if t.iter().any(|&p| (p as usize) < real && marked[p as usize]) {
            for &p in t {
                if (p as usize) < real {
                    grown[p as usize] = true;
                }
            }
        }
    }
    grown
}

/// Gives every vertex on an edge held by one facet, other than a corner, the kind
/// [`VertexKind::Boundary`]: on the wall-clipped path a triangle vertex with a ghost can end the
/// mesh short of the wall, or a crossing be merged into a triangle vertex, and the mesh's edge
/// is what fabrication and the report read the kind for (as on the closed path, where every
/// vertex of a triangle with a ghost is a boundary vertex).
/// `boundary` holds the mesh's edges held by one facet ([`crate::sanity::edges`]).
fn mark_boundary_vertices(mesh: &mut FacetMesh, boundary: &[(u32, u32)]) {
    for &(a, b) in boundary {
        for v in [a, b] {
            let kind = &mut mesh.vertex_kinds[v as usize];
            if *kind == VertexKind::Interior {
                *kind = VertexKind::Boundary;
            }
        }
    }
}

/// Starts each facet's loop at its vertex of the lowest-numbered dual triangle (loops without
/// one keep their start). The clip's walk starts a loop wherever the facet's first inside item
/// falls, and a vertex lying on the wall is inside or not by rounding: the same structure
/// (one face, or the same face split into a polysurface) must give the same loops.
fn start_loops_at_lowest_triangle(mesh: &mut FacetMesh) {
    for f in 0..mesh.offsets.len().saturating_sub(1) {
        let lp = &mut mesh.loops[mesh.offsets[f] as usize..mesh.offsets[f + 1] as usize];
        let first = (0..lp.len())
            .filter(|&k| mesh.vertex_source[lp[k] as usize] != u32::MAX)
            .min_by_key(|&k| mesh.vertex_source[lp[k] as usize]);
        if let Some(k) = first {
            lp.rotate_left(k);
        }
    }
}

/// The facets marked in `extended` (those [`extend_to_wall`] changed) that are not simple in
/// their plane or overlap a real neighbour's facet in `tri` seen along their mean normal (the
/// report's tests, [`crate::quality`]); ascending. A neighbour that overlaps one is not
/// named: blocking the extended facet undoes the move that made the overlap.
fn invalid_extended_facets(
    mesh: &FacetMesh,
    planes: &[Plane],
    tri: &DualTriangulation,
    extended: &[bool],
) -> Vec<usize> {
    let n = planes.len();
    let mut buffer = Vec::new();
    let mut simple = |f: usize| {
        crate::quality::facet_shape_into(&planes[f], mesh.polygon(f).into_iter(), &mut buffer)
            .simple
    };
    let mut pairs = Vec::new();
    for ids in &tri.triangles {
        for k in 0..3 {
            let (a, b) = (ids[k] as usize, ids[(k + 1) % 3] as usize);
            if a < n && b < n && (extended[a] || extended[b]) {
                pairs.push((a.min(b), a.max(b)));
            }
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    let mut invalid: Vec<bool> = (0..n).map(|f| extended[f] && !simple(f)).collect();
    let mut shape = vec![None; n];
    for (f, g) in pairs {
        let mut is_simple = |x: usize| *shape[x].get_or_insert_with(|| simple(x));
        if invalid[f] && invalid[g] || !(is_simple(f) && is_simple(g)) {
            continue;
        }
        let normal = planes[f].normal + planes[g].normal;
        if crate::validity_flips::polygons_overlap(&mesh.polygon(f), &mesh.polygon(g), normal) {
            invalid[f] |= extended[f];
            invalid[g] |= extended[g];
        }
    }
    (0..n).filter(|&f| invalid[f]).collect()
}

/// The facets marked in `marked` that are not simple in their plane, have an area below
/// `least_area` (a facet collapsed onto a line, as where the planes along a hypar's ruling
/// meet in it), or overlap a facet sharing a vertex with them, seen along their mean normal
/// (the report's tests, [`crate::quality`]); ascending. Unlike [`invalid_extended_facets`]
/// the pairs are those of the mesh, not of the triangulation: a flip can bring two facets to
/// one vertex.
fn invalid_marked_facets(
    mesh: &FacetMesh,
    planes: &[Plane],
    marked: &[bool],
    least_area: f64,
) -> Vec<usize> {
    let n = planes.len();
    // Each vertex's facets, ascending and each once, by a counting sort into one flat array
    // (`holders[start[v]..start[v + 1]]`), not a list per vertex.
    let vertex_count = mesh.vertices.len();
    let mut start = vec![0u32; vertex_count + 1];
    let mut last = vec![u32::MAX; vertex_count];
    for f in 0..n {
        for &v in mesh.facet_loop(f) {
            if last[v as usize] != f as u32 {
                last[v as usize] = f as u32;
                start[v as usize + 1] += 1;
            }
        }
    }
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    let mut holders = vec![0u32; start[vertex_count] as usize];
    let mut fill = start.clone();
    last.fill(u32::MAX);
    for f in 0..n {
        for &v in mesh.facet_loop(f) {
            if last[v as usize] != f as u32 {
                last[v as usize] = f as u32;
                holders[fill[v as usize] as usize] = f as u32;
                fill[v as usize] += 1;
            }
        }
    }
    let holders_of = |v: u32| &holders[start[v as usize] as usize..start[v as usize + 1] as usize];
    let mut buffer = Vec::new();
    let mut simple = vec![None; n];
    let mut is_simple = |f: usize| {
        *simple[f].get_or_insert_with(|| {
            crate::quality::facet_shape_into(&planes[f], mesh.polygon(f).into_iter(), &mut buffer)
                .simple
        })
    };
    let mut invalid = Vec::new();
    for f in (0..n).filter(|&f| marked[f]) {
        let own = mesh.polygon(f);
        // Newell's vector area.
        let area = (0..own.len())
            .map(|k| own[k].cross(own[(k + 1) % own.len()]))
            .sum::<DVec3>()
            .length()
            / 2.0;
        if !is_simple(f) || !(area >= least_area) {
            invalid.push(f);
            continue;
        }
        let mut others: Vec<u32> = mesh.loops
            [mesh.offsets[f] as usize..mesh.offsets[f + 1] as usize]
            .iter()
            .flat_map(|&v| holders_of(v).iter().copied())
            .filter(|&g| g as usize != f)
            .collect();
        others.sort_unstable();
        others.dedup();
        if others.into_iter().any(|g| {
            let g = g as usize;
            is_simple(g)
                && crate::validity_flips::polygons_overlap(
                    &own,
                    &mesh.polygon(g),
                    planes[f].normal + planes[g].normal,
                )
        }) {
            invalid.push(f);
        }
    }
    invalid
}

/// What [`wall_clip_keeps_shape`] compares.
struct MeshShape {
    euler: i64,
    boundary_loops: usize,
    /// Facets with fewer than three vertices or a loop that is not simple in its plane.
    bad_facets: usize,
    /// The largest distance of a vertex from its facet's seed point.
    reach: f64,
}

/// The shape of a facet mesh with its [`crate::sanity::edges`], or `None` where an edge is held
/// by more than two facets or twice in one direction (`edges` None); also, per facet, whether
/// it is simple in its plane. Facet f's verdict depends only on its plane (`planes[f]`, the
/// same in every mesh compared) and its polygon's points, so where a mesh in `known` has
/// f's polygon bit for bit it takes that mesh's verdict (most facets of the closed and
/// clipped meshes, of the unflipped and flipped triangulations, are one polygon). Where it
/// has the polygon started at another vertex (a clipped loop starts at its lowest
/// triangle's vertex, a closed one where its fan starts), the crossing test's verdict holds
/// ([`crate::quality::loop_crosses`]) and only the area, whose sum depends on the start, is
/// taken again.
fn mesh_shape(
    mesh: &FacetMesh,
    edges: &Option<(usize, Vec<(u32, u32)>)>,
    planes: &[Plane],
    known: &[Judged<'_>],
) -> Option<(MeshShape, Vec<Verdict>)> {
    let (edges, boundary) = edges.as_ref()?;
    let edges = *edges;
    let mut used = vec![false; mesh.vertices.len()];
    let mut buffer = Vec::new();
    let mut simple = Vec::with_capacity(mesh.offsets.len().saturating_sub(1));
    let mut bad_facets = 0;
    let mut reach = 0.0f64;
    let same = |x: DVec3, y: DVec3| {
        x.x.to_bits() == y.x.to_bits()
            && x.y.to_bits() == y.y.to_bits()
            && x.z.to_bits() == y.z.to_bits()
    };
    for (f, w) in mesh.offsets.windows(2).enumerate() {
        let lp = &mesh.loops[w[0] as usize..w[1] as usize];
        for &v in lp {
            used[v as usize] = true;
            reach = reach.max(mesh.vertices[v as usize].distance(planes[f].point));
        }
        let n = lp.len();
        // A mesh in `known` with f's polygon started `shift` vertices on, and its verdict.
        let found = known.iter().find_map(|&(other, verdicts)| {
            let theirs = (f < verdicts.len()).then(|| other.facet_loop(f))?;
            if theirs.len() != n || n == 0 {
                return None;
            }
            let at = |k: usize| other.vertices[theirs[k] as usize];
            let first = mesh.vertices[lp[0] as usize];
            (0..n)
                .find(|&shift| {
                    same(at(shift), first)
                        && (1..n).all(|k| same(at((shift + k) % n), mesh.vertices[lp[k] as usize]))
                })
                .map(|shift| (shift, verdicts[f]))
        });
        let verdict = match found {
            Some((0, verdict)) => verdict,
            Some((_, theirs)) => {
                let points = lp.iter().map(|&v| mesh.vertices[v as usize]);
                crate::quality::project_loop_into(&planes[f], points, &mut buffer);
                Verdict {
                    simple: n >= 3 && crate::quality::loop_area(&buffer) > 0.0 && !theirs.crossing,
                    crossing: theirs.crossing,
                }
            }
            None => {
                let points = lp.iter().map(|&v| mesh.vertices[v as usize]);
                crate::quality::project_loop_into(&planes[f], points, &mut buffer);
                let crossing = n >= 3 && crate::quality::loop_crosses(&buffer);
                Verdict {
                    simple: n >= 3 && crate::quality::loop_area(&buffer) > 0.0 && !crossing,
                    crossing,
                }
            }
        };
        if !verdict.simple {
            bad_facets += 1;
        }
        simple.push(verdict);
    }
    let vertices = used.iter().filter(|&&u| u).count() as i64;
    let facets = mesh.offsets.len().saturating_sub(1) as i64;
    let shape = MeshShape {
        euler: vertices - edges as i64 + facets,
        boundary_loops: crate::sanity::boundary_loops(mesh.vertices.len(), boundary),
        bad_facets,
        reach,
    };
    Some((shape, simple))
}

/// Builds the facets of all pattern points from the dual triangulation, ending them on
/// `boundary` (the domain rectangle, or a trim's loops). With `release_tangents` the samples'
/// tangents, which only the walk reads, are let go before the assembly.
fn build_facets(
    surface: &dyn Surface,
    boundary: &Boundary,
    samples: &mut Samples,
    tri: &DualTriangulation,
    params: &FacetParams,
    release_tangents: bool,
    stages: &Stages<'_>,
) -> FacetMesh {
    let regular = samples.slopes.is_some() && samples.frame.is_some();
    let ctx = Context {
        surface,
        domain: surface.domain(),
        boundary,
        planes: &samples.planes,
        uv: &samples.uv,
        tangents: &samples.tangents,
        convex_side: &samples.convex_side,
        regular: regular || params.exact_dual,
        long_edges: false,
        extend_to_wall: None,
        wall: WallMoves::PLAIN,
        keep_closed: None,
    };
    let walk = walk_facets(&ctx, samples.uv.len(), tri, params, None, stages);
    if release_tangents {
        samples.tangents = Vec::new();
    }
    let slopes = samples
        .slopes
        .as_ref()
        .zip(samples.frame)
        .map(|(slopes, normal)| SlopeView {
            axes: SlopeFrame::new(normal, samples.convex_side[0]).axes,
            slopes,
        });
    assemble_walk(walk, tri, &samples.planes, params, slopes, stages)
}

/// The facets of the real seeds `0..seeds.uv.len()` of a triangulation closed by ghosts beyond
/// the domain (the strips of a trimmed developable surface, [`crate::rulings`]), each its
/// closed fan clipped on `boundary` as in [`build_facets`]. `seeds.planes` and `seeds.source`
/// (the real seed of every point) cover the ghosts too. Every vertex is a crossing of a bisector with the line
/// of two planes, exact however far from its points, so none is replaced by a stand-in.
#[allow(clippy::too_many_arguments)]
fn build_ghost_clipped_facets(
    surface: &dyn Surface,
    boundary: &Boundary,
    seeds: &GhostSeeds<'_>,
    tri: &DualTriangulation,
    params: &FacetParams,
    extend_to_wall: Option<&[bool]>,
    wall: WallMoves,
    keep_closed: Option<&[bool]>,
    vertices: Option<&mut VertexCache>,
    stages: &Stages<'_>,
) -> (FacetMesh, Vec<bool>) {
    let (real_count, source) = (seeds.uv.len(), seeds.source);
    with_ghost_context(
        surface,
        boundary,
        seeds,
        extend_to_wall,
        wall,
        keep_closed,
        |ctx| {
            let (mut mesh, extended) = clip_facets(ctx, real_count, tri, params, vertices, stages);
            // Diagnostics name pattern points: a ghost stands for its seed.
            for diagnostic in &mut mesh.diagnostics {
                diagnostic.map_points(|p| source[p as usize]);
            }
            (mesh, extended)
        },
    )
}

/// The real seeds (`uv`, `tangents`) and the planes and sources of all points, ghosts
/// included, of a triangulation closed by ghosts.
struct GhostSeeds<'a> {
    uv: &'a [[f64; 2]],
    tangents: &'a [[DVec3; 2]],
    planes: &'a [Plane],
    source: &'a [u32],
    /// All points' parameters and tangents as [`ghost_arrays`] gives them, where already
    /// made (they depend only on the fields above).
    all: Option<&'a GhostArrays>,
}

/// Every point's parameters and tangents in the clip's [`Context`] of a triangulation closed
/// by ghosts ([`ghost_arrays`]).
type GhostArrays = (Vec<[f64; 2]>, Vec<[DVec3; 2]>);

/// The parameters and tangents of all points of `seeds`: the real seeds' own, and for a
/// ghost the first-order foot of its point seen from its seed (only a start for the
/// projections of the vertices around it) and its seed's tangents.
fn ghost_arrays(seeds: &GhostSeeds<'_>) -> GhostArrays {
    let GhostSeeds {
        uv,
        tangents,
        planes,
        source,
        ..
    } = *seeds;
    let mut all_uv = uv.to_vec();
    let mut all_tangents = tangents.to_vec();
    for (g, plane) in planes.iter().enumerate().skip(uv.len()) {
        let seed = source[g] as usize;
        all_uv.push(first_order_foot(
            uv[seed],
            tangents[seed],
            planes[seed].point,
            plane.point,
        ));
        all_tangents.push(tangents[seed]);
    }
    (all_uv, all_tangents)
}

/// First-order foot of x seen from a point p with parameters `uv` and tangents S_u, S_v
/// (J = [S_u S_v]): uv + (J^T J)^-1 J^T (x - p), or `uv` where J^T J is singular.
fn first_order_foot(uv: [f64; 2], [su, sv]: [DVec3; 2], p: DVec3, x: DVec3) -> [f64; 2] {
    let r = x - p;
    let (e, f, g) = (su.dot(su), su.dot(sv), sv.dot(sv));
    let (a, b) = (su.dot(r), sv.dot(r));
    let det = e * g - f * f;
    if !(det > 0.0) {
        return uv;
    }
    [uv[0] + (g * a - f * b) / det, uv[1] + (e * b - f * a) / det]
}

/// Runs `f` with the clip's [`Context`] of a triangulation closed by ghosts: a ghost's
/// parameters are the first-order foot of its point seen from its seed, its tangents its
/// seed's.
fn with_ghost_context<R>(
    surface: &dyn Surface,
    boundary: &Boundary,
    seeds: &GhostSeeds<'_>,
    extend_to_wall: Option<&[bool]>,
    wall: WallMoves,
    keep_closed: Option<&[bool]>,
    f: impl FnOnce(&Context<'_>) -> R,
) -> R {
    let made;
    let (all_uv, all_tangents) = match seeds.all {
        Some(all) => all,
        None => {
            made = ghost_arrays(seeds);
            &made
        }
    };
    let convex_side = vec![0i8; seeds.planes.len()];
    let ctx = Context {
        surface,
        domain: surface.domain(),
        boundary,
        planes: seeds.planes,
        uv: all_uv,
        tangents: all_tangents,
        convex_side: &convex_side,
        regular: true,
        long_edges: true,
        extend_to_wall,
        wall,
        keep_closed,
    };
    f(&ctx)
}

/// The facets of the points `0..real_count` of `tri`, ending on `ctx.boundary` (module doc);
/// points from `real_count` on are ghosts, which get no facet and no crossings of their own.
/// Also, per real seed, whether its facet was extended to the wall (empty without
/// `ctx.extend_to_wall`). Triangle vertices found in `vertices` are taken from it, and those
/// computed are added to it.
fn clip_facets(
    ctx: &Context<'_>,
    real_count: usize,
    tri: &DualTriangulation,
    params: &FacetParams,
    vertices: Option<&mut VertexCache>,
    stages: &Stages<'_>,
) -> (FacetMesh, Vec<bool>) {
    let mut walk = walk_facets(ctx, real_count, tri, params, vertices, stages);
    let extended = std::mem::take(&mut walk.extended);
    (
        assemble_walk(walk, tri, ctx.planes, params, None, stages),
        extended,
    )
}

/// What the walk of [`clip_facets`] hands to the assembly.
struct Walk {
    triangle_vertices: Vec<TriangleVertex>,
    chunks: Vec<FacetChunk>,
    crossings: Vec<Crossing>,
    corners: Vec<(DVec3, DVec3)>,
    diagnostics: Vec<Diagnostic>,
    /// Per trim corner, whether a crossing sits on it (empty without a trim).
    absorbed: Vec<bool>,
    /// Per real seed, whether [`extend_to_wall`] moved a vertex of its facet (empty without
    /// the extension).
    extended: Vec<bool>,
}

/// Steps 1 to 3 of [`clip_facets`]: triangle vertices (taken from `vertices` where there,
/// the others added to it), boundary crossings, facet loops as items.
fn walk_facets(
    ctx: &Context<'_>,
    real_count: usize,
    tri: &DualTriangulation,
    params: &FacetParams,
    vertices: Option<&mut VertexCache>,
    stages: &Stages<'_>,
) -> Walk {
    let (surface, boundary) = (ctx.surface, ctx.boundary);
    let observer = stages.observer();
    let mut diagnostics = Vec::new();

    // 1. Triangle vertices, their conditioning and whether they lie inside.
    let known = vertices.as_deref();
    // Each vertex, and whether it was computed now (not found in the cache).
    let (mut triangle_vertices, computed): (Vec<TriangleVertex>, Vec<bool>) = tri
        .triangles
        .par_iter()
        .map_init(
            || Tally::new(observer, Stage::Facets),
            |tally, &ids| {
                tally.add(1);
                let mut key = ids;
                key.sort_unstable();
                match known.and_then(|known| known.vertices.get(&key)) {
                    Some(&vertex) => (vertex, false),
                    None => (
                        triangle_vertex_ordered(ctx, key, params.far_vertex_factor),
                        true,
                    ),
                }
            },
        )
        .unzip();
    let mut vertices = vertices;
    if let Some(cache) = vertices.as_deref_mut() {
        for ((&vertex, &ids), _) in triangle_vertices
            .iter()
            .zip(&tri.triangles)
            .zip(&computed)
            .filter(|x| *x.1)
        {
            let mut key = ids;
            key.sort_unstable();
            cache.vertices.entry(key).or_insert(vertex);
        }
    }
    diagnostics.extend(
        triangle_vertices
            .iter()
            .zip(&tri.triangles)
            .filter(|(v, _)| !v.exact)
            .map(|(v, &ids)| ill_conditioned(ctx, ids, v)),
    );
    let extended = match ctx.extend_to_wall {
        Some(blocked) => extend_to_wall(
            ctx,
            real_count,
            tri,
            blocked,
            &mut triangle_vertices,
            vertices.as_deref_mut(),
        ),
        None => Vec::new(),
    };

    let enclosed = if ctx.wall.keep_enclosed {
        enclosed_outside(tri, real_count, &mut triangle_vertices)
    } else {
        Vec::new()
    };

    // 2. Boundary crossings, only on the edges where they can be: a hull edge, or an edge
    // with an outside vertex at either end (in the order of `DualTriangulation::edges`).
    let mut edges: Vec<Edge> = crossing_edges(tri, &triangle_vertices, ctx.long_edges);
    edges.retain(|e| (e.lo as usize) < real_count);
    if !enclosed.is_empty() {
        // An edge of an enclosed vertex stays whole, as in the closed facets.
        let held = |t: u32| t != NO_TRIANGLE && enclosed[t as usize];
        edges.retain(|e| !(held(e.left) || held(e.right)));
    }
    // Crossings found in the cache are taken from it; those computed (flagged: a key per
    // edge would hold 128 bytes an edge through the walk) are added to it.
    let known = vertices.as_deref();
    let per_edge: Vec<(Vec<Crossing>, Option<Diagnostic>, bool)> = edges
        .par_iter()
        .map(|edge| {
            if ctx.long_edges {
                let (list, computed) = long_edge_crossings(ctx, edge, &triangle_vertices, known);
                (list, None, computed)
            } else {
                let (list, diagnostic) = edge_crossings(ctx, tri, edge, &triangle_vertices);
                (list, diagnostic, false)
            }
        })
        .collect();
    if let Some(cache) = vertices.filter(|_| ctx.long_edges) {
        for (edge, (list, _, computed)) in edges.iter().zip(&per_edge) {
            if !*computed {
                continue;
            }
            if let Some(key) = long_edge_key(ctx, edge, &triangle_vertices) {
                cache.crossings.entry(key).or_insert_with(|| list.clone());
            }
        }
    }
    let mut crossing_ranges: IndexMap<(u32, u32), (u32, u32)> =
        IndexMap::with_capacity_and_hasher(edges.len(), Default::default());
    let mut crossings = Vec::new();
    for (edge, (list, diagnostic, _)) in edges.iter().zip(per_edge) {
        let first = crossings.len() as u32;
        crossings.extend(list);
        if crossings.len() as u32 > first {
            crossing_ranges.insert((edge.lo, edge.hi), (first, crossings.len() as u32));
        }
        diagnostics.extend(diagnostic);
    }
    let corner_list = boundary.corners();
    let mut corner_owner = corner_owners(boundary, &corner_list, &crossings);
    // A trim corner that a crossing sits on (a facet edge through a polyline point, common
    // with symmetric patterns) is that crossing: as a vertex of its own it would give a
    // zero-length edge.
    let absorbed: Vec<bool> = if boundary.is_trim() {
        corner_list
            .iter()
            .map(|&(_, corner)| {
                crossings.iter().any(|x| {
                    boundary
                        .ahead(x.wall, corner)
                        .zip(boundary.ahead(corner, x.wall))
                        .is_some_and(|(a, b)| a.min(b) <= CORNER_ON_CROSSING)
                })
            })
            .collect()
    } else {
        Vec::new()
    };
    for (owner, &gone) in corner_owner.iter_mut().zip(&absorbed) {
        if gone {
            *owner = None;
        }
    }

    // 3. Facet loops as items, in chunks of facets (one buffer per chunk, none per facet).
    let corners = corner_samples(surface, &corner_list);
    let incident = tri.incident_triangles(ctx.uv.len());
    let lookup = ItemContext {
        keep_closed: ctx.keep_closed,
        tri,
        incident: &incident,
        crossing_ranges: &crossing_ranges,
        crossings: &crossings,
        corner_owner: &corner_owner,
        corners: &corner_list,
        boundary,
        triangle_vertices: &triangle_vertices,
        long_edges: ctx.long_edges.then_some(ctx.uv),
    };
    let chunks: Vec<FacetChunk> = (0..real_count.div_ceil(FACET_CHUNK))
        .into_par_iter()
        .map_init(
            || Tally::new(observer, Stage::Facets),
            |tally, c| {
                let mut chunk = FacetChunk::default();
                let mut fan = Vec::new();
                let facets = c * FACET_CHUNK..((c + 1) * FACET_CHUNK).min(real_count);
                let count = facets.len();
                for i in facets {
                    let simple = facet_items(
                        i as u32,
                        &lookup,
                        &mut fan,
                        &mut chunk.items,
                        &mut chunk.diagnostics,
                    );
                    chunk.ends.push(chunk.items.len() as u32);
                    chunk.simple.push(simple);
                }
                tally.add(count);
                chunk
            },
        )
        .collect();
    Walk {
        triangle_vertices,
        chunks,
        crossings,
        corners,
        diagnostics,
        absorbed,
        extended,
    }
}

/// Per triangle of `tri` (points from `real_count` on are ghosts), whether its vertex lies
/// outside the region yet no chain of triangles with outside vertices, neighbour to
/// neighbour, joins it to a triangle with a ghost: a vertex that ran away from its points
/// (nearly parallel planes near a parabolic line) with its foot beyond the wall, not a part
/// of the mesh's edge. Clipped, such vertices cut holes in the mesh; they are given a tiny
/// positive inside measure (the walk keeps them, as the closed facets do) and their edges
/// get no crossings. Empty where there are none.
fn enclosed_outside(
    tri: &DualTriangulation,
    real_count: usize,
    triangle_vertices: &mut [TriangleVertex],
) -> Vec<bool> {
    let count = tri.len();
    let outside: Vec<bool> = triangle_vertices
        .iter()
        .map(|v| !(v.inside > 0.0))
        .collect();
    let with_ghost = |t: usize| tri.triangles[t].iter().any(|&p| p as usize >= real_count);
    let mut reached = vec![false; count];
    let mut stack: Vec<usize> = (0..count).filter(|&t| with_ghost(t)).collect();
    for &t in &stack {
        reached[t] = true;
    }
    while let Some(t) = stack.pop() {
        for &o in &tri.neighbours[t] {
            if o != NO_TRIANGLE && !reached[o as usize] && outside[o as usize] {
                reached[o as usize] = true;
                stack.push(o as usize);
            }
        }
    }
    let enclosed: Vec<bool> = (0..count).map(|t| outside[t] && !reached[t]).collect();
    if !enclosed.contains(&true) {
        return Vec::new();
    }
    for (v, _) in triangle_vertices.iter_mut().zip(&enclosed).filter(|x| *x.1) {
        v.inside = f64::MIN_POSITIVE;
    }
    enclosed
}

/// Moves the vertices of triangles with a ghost that lie inside the region out past the wall.
///
/// Such a vertex V = T_i ∩ T_j ∩ T_g (g a ghost) would end facets i and j on the ghost's
/// plane T_g, short of the wall: the part of the ghost's facet inside the region is a notch
/// in the mesh's edge (the saw-tooth along a saddle's sides), the wedge at V between i's edge
/// on T_i ∩ T_g and j's edge on T_j ∩ T_g. Where the line T_i ∩ T_j runs on into that wedge
/// (direction w = ±(n_i × n_j) strictly between the two edges, seen along n_g, and away from
/// the edge's other end A unless A lies within a quarter side of V), V moves along w to the
/// first V' = V + k (h/4) w (k = 1..=[`WALL_EXTENSION_STEPS`], h the triangle's longest side)
/// whose foot lies outside. V' is in both T_i and T_j: the two facets meet along their common
/// line out to the wall, where the clip cuts them and follows the wall, and both stay exactly
/// planar. Where the line misses the wedge (one facet reflex at V, or four planes through
/// nearly one point) the notch stays: i and j cannot share an edge through it.
///
/// With two ghosts, V is a vertex of one real facet i only; it moves within T_i along the
/// bisector of the ghosts' wedge (the outside of i's corner at V), by at most
/// [`WALL_EXTENSION_OWN_STEPS`] quarter sides. A vertex within
/// [`WALL_EXTENSION_MIN_DEPTH`] of the wall, one the steps do not bring outside, and every
/// vertex of a triangle holding a seed marked in `blocked` (the caller's retry for facets that
/// came out invalid) stay where they are. Extensions found in `cache` are taken from it, and
/// those computed are added to it.
fn extend_to_wall(
    ctx: &Context<'_>,
    real_count: usize,
    tri: &DualTriangulation,
    blocked: &[bool],
    triangle_vertices: &mut [TriangleVertex],
    mut cache: Option<&mut VertexCache>,
) -> Vec<bool> {
    let known = cache.as_deref();
    let vertices = &*triangle_vertices;
    // Per triangle that may move: its extension, and its key where computed now.
    let found: Vec<(usize, Option<TriangleVertex>, Option<ExtensionKey>)> = tri
        .triangles
        .par_iter()
        .enumerate()
        .filter_map(|(t, &ids)| {
            if ids
                .iter()
                .any(|&p| (p as usize) < real_count && blocked[p as usize])
            {
                return None;
            }
            // Without one or two ghosts the vertex stays ([`extension`]).
            let ghosts = ids.iter().filter(|&&p| p as usize >= real_count).count();
            if !(1..=2).contains(&ghosts) {
                return None;
            }
            // The vertex across the edge opposite position k, as the walk left it.
            let across: [Option<DVec3>; 3] = std::array::from_fn(|k| {
                let other = tri.neighbours[t][k];
                (other != NO_TRIANGLE).then(|| vertices[other as usize].point)
            });
            let key = extension_key(ids, across);
            if let Some(&moved) = known.and_then(|known| known.extensions.get(&key)) {
                return Some((t, moved, None));
            }
            let moved = extension(ctx, real_count, ids, &vertices[t], |k| across[k]);
            Some((t, moved, Some(key)))
        })
        .collect();
    let mut extended = vec![false; real_count];
    for (t, moved, key) in found {
        if let (Some(cache), Some(key)) = (cache.as_deref_mut(), key) {
            cache.extensions.insert(key, moved);
        }
        let Some(vertex) = moved else {
            continue;
        };
        triangle_vertices[t] = vertex;
        for p in tri.triangles[t] {
            if (p as usize) < real_count {
                extended[p as usize] = true;
            }
        }
    }
    extended
}

/// Where [`extend_to_wall`] moves the vertex `v` of the triangle `ids` (points from
/// `real_count` on are ghosts): the first point past the wall along its real facets' common
/// line, or along the bisector of the ghosts' wedge (that function's doc); None where it
/// stays. `across(k)` is the vertex of the triangle across the edge opposite position k.
fn extension(
    ctx: &Context<'_>,
    real_count: usize,
    ids: [u32; 3],
    v: &TriangleVertex,
    across: impl Fn(usize) -> Option<DVec3>,
) -> Option<TriangleVertex> {
    let ghosts = ids.iter().filter(|&&p| p as usize >= real_count).count();
    // A vertex on the wall (a grid on a hypar) or within rounding of it leaves no notch
    // worth a move, and its side would be decided by rounding.
    if !(1..=2).contains(&ghosts) || !v.exact || v.inside <= WALL_EXTENSION_MIN_DEPTH * v.reach {
        return None;
    }
    let plane = |p: u32| &ctx.planes[p as usize];
    let [a, b, c] = ids.map(|p| plane(p).point);
    let step = 0.25 * a.distance(b).max(b.distance(c)).max(c.distance(a));
    let direction = if ghosts == 1 {
        // ids[k] = g, ids[k + 1] = i, ids[k + 2] = j (counter-clockwise).
        let k = ids.iter().position(|&p| p as usize >= real_count)?;
        let (i, j) = (ids[(k + 1) % 3], ids[(k + 2) % 3]);
        let u = plane(i).normal.cross(plane(j).normal).try_normalize()?;
        let apart = v.point - across(k)?;
        // Facet i's edge on T_g runs to the vertex across (g, i), j's to that across
        // (j, g): the ghost's wedge at V lies between them.
        let [ri, rj] = [
            across((k + 2) % 3)? - v.point,
            across((k + 1) % 3)? - v.point,
        ];
        let normal = plane(ids[k]).normal;
        [u, -u].into_iter().find(|&w| {
            within_wedge(normal, ri, rj, w) && (w.dot(apart) > 0.0 || apart.length() < step)
        })?
    } else {
        // ids[k] = the real seed, its facet's only vertex here: V goes out through the
        // wedge of the ghosts, along its bisector in T_k.
        let k = ids.iter().position(|&p| (p as usize) < real_count)?;
        let previous = across((k + 2) % 3)?;
        let next = across((k + 1) % 3)?;
        let n = plane(ids[k]).normal;
        let convex = n.dot((v.point - previous).cross(next - v.point)) > 0.0;
        let sum = (previous - v.point).try_normalize()? + (next - v.point).try_normalize()?;
        let outward = if convex { -sum } else { sum };
        (outward - n * n.dot(outward)).try_normalize()?
    };
    let mut guess = v.foot;
    // A vertex of one real facet moves within that facet's own plane alone.
    let steps = if ghosts == 2 {
        ctx.wall.own_steps
    } else {
        WALL_EXTENSION_STEPS
    };
    for k in 1..=steps {
        let point = v.point + direction * (step * k as f64);
        let (foot, inside) = ctx.measure(point, guess);
        if inside <= 0.0 {
            return Some(TriangleVertex {
                point,
                foot,
                inside,
                reach: v.reach,
                exact: true,
                measured: true,
                newton_foot: true,
            });
        }
        guess = foot;
    }
    None
}

/// Whether the direction w lies strictly inside the wedge between the rays a and b (under
/// 180 degrees), seen along `normal`: w = alpha a + beta b with alpha, beta > 0.
fn within_wedge(normal: DVec3, a: DVec3, b: DVec3, w: DVec3) -> bool {
    let turn = |x: DVec3, y: DVec3| normal.dot(x.cross(y));
    let (ab, aw, wb) = (turn(a, b), turn(a, w), turn(w, b));
    ab != 0.0 && aw * ab > 0.0 && wb * ab > 0.0
}

/// Step 4 of [`clip_facets`]: the walk's items assembled into the mesh.
fn assemble_walk(
    walk: Walk,
    tri: &DualTriangulation,
    planes: &[Plane],
    params: &FacetParams,
    slopes: Option<SlopeView<'_>>,
    stages: &Stages<'_>,
) -> FacetMesh {
    let Walk {
        triangle_vertices,
        chunks,
        crossings,
        corners,
        diagnostics,
        absorbed,
        extended: _,
    } = walk;
    let mut mesh = assemble(Assembly {
        tri,
        triangle_vertices,
        chunks,
        crossings: &crossings,
        corners: Some(&corners),
        planes,
        params,
        ghosts_from: None,
        slopes,
        diagnostics,
        stages,
    });
    if absorbed.contains(&true) {
        mesh.diagnostics.retain(|d| {
            !matches!(d, Diagnostic::CornerClaims { corner, claims: 0 } if absorbed[*corner as usize])
        });
    }
    mesh
}

/// Whether the meeting point `x` of three planes lies within [`UNREACHABLE_VERTEX_FACTOR`]
/// triangle sides of their points' centroid (false for a point that is not finite).
pub(crate) fn reachable(x: DVec3, [a, b, c]: [&Plane; 3]) -> bool {
    let centroid = (a.point + b.point + c.point) / 3.0;
    let longest = a
        .point
        .distance(b.point)
        .max(b.point.distance(c.point))
        .max(c.point.distance(a.point));
    x.distance(centroid) <= UNREACHABLE_VERTEX_FACTOR * longest
}

/// Facets per parallel work item of the loop stage.
const FACET_CHUNK: usize = 512;

/// The items of a run of consecutive facets: `ends[k]` closes facet k's items.
#[derive(Default)]
pub(crate) struct FacetChunk {
    /// Packed items (see [`PackedItems`]).
    pub(crate) items: PackedItems,
    /// Per facet, the end of its items.
    pub(crate) ends: Vec<u32>,
    /// Walk diagnostics with their facet, in facet order.
    pub(crate) diagnostics: Vec<(u32, Diagnostic)>,
    /// Per facet, whether its loop is its closed fan (`facet_items`' fast path).
    pub(crate) simple: Vec<bool>,
}

/// Facet loop items packed into 4 bytes each: the top two bits tell the kind (triangle,
/// crossing, corner, edge point), the rest its index; edge points index a side table.
#[derive(Default)]
pub(crate) struct PackedItems {
    codes: Vec<u32>,
    edge_points: Vec<(u32, u32, u32)>,
}

pub(crate) const ITEM_INDEX: u32 = (1 << 30) - 1;
const ITEM_CROSSING: u32 = 1 << 30;
const ITEM_CORNER: u32 = 2 << 30;
const ITEM_EDGE_POINT: u32 = 3 << 30;

impl PackedItems {
    pub(crate) fn len(&self) -> usize {
        self.codes.len()
    }

    fn push(&mut self, item: Item) {
        let code = match item {
            Item::Triangle(t) => t,
            Item::Crossing(c) => ITEM_CROSSING | c,
            Item::Corner(c) => ITEM_CORNER | c,
            Item::EdgePoint { triangle, lo, hi } => {
                self.edge_points.push((triangle, lo, hi));
                ITEM_EDGE_POINT | (self.edge_points.len() - 1) as u32
            }
        };
        self.codes.push(code);
    }

    pub(crate) fn get(&self, k: usize) -> Item {
        let code = self.codes[k];
        let index = code & ITEM_INDEX;
        match code & !ITEM_INDEX {
            0 => Item::Triangle(index),
            ITEM_CROSSING => Item::Crossing(index),
            ITEM_CORNER => Item::Corner(index),
            _ => {
                let (triangle, lo, hi) = self.edge_points[index as usize];
                Item::EdgePoint { triangle, lo, hi }
            }
        }
    }
}

/// What `facet_items` reads.
struct ItemContext<'a> {
    tri: &'a DualTriangulation,
    incident: &'a [u32],
    crossing_ranges: &'a IndexMap<(u32, u32), (u32, u32)>,
    crossings: &'a [Crossing],
    corner_owner: &'a [Option<u32>],
    corners: &'a [([f64; 2], Position)],
    boundary: &'a Boundary,
    triangle_vertices: &'a [TriangleVertex],
    /// With long edges ([`Context::long_edges`]): the seeds' parameters (each facet is
    /// clipped by itself, and one cut in several parts keeps the part around its seed).
    long_edges: Option<&'a [[f64; 2]]>,
    /// [`Context::keep_closed`].
    keep_closed: Option<&'a [bool]>,
}

/// The edges that can hold boundary crossings, in triangle order (each edge once, from its lower triangle):
/// hull edges, and edges with an outside (or stand-in) vertex at either end; with `all`,
/// every edge.
fn crossing_edges(tri: &DualTriangulation, tv: &[TriangleVertex], all: bool) -> Vec<Edge> {
    let mut edges = Vec::new();
    for t in 0..tri.len() {
        for k in 0..3 {
            let other = tri.neighbours[t][k];
            if other != NO_TRIANGLE && (other as usize) < t {
                continue;
            }
            let inside = |x: usize| tv[x].inside > 0.0;
            if !all && other != NO_TRIANGLE && inside(t) && inside(other as usize) {
                continue;
            }
            let vertices = tri.triangles[t];
            let (from, to) = (vertices[(k + 1) % 3], vertices[(k + 2) % 3]);
            let (lo, hi, left, right) = if from < to {
                (from, to, t as u32, other)
            } else {
                (to, from, other, t as u32)
            };
            edges.push(Edge {
                lo,
                hi,
                left,
                right,
            });
        }
    }
    edges
}

/// Whether a triangle lies within twice its own size (in normalised parameters) of the
/// domain boundary.
fn near_boundary(ctx: &Context<'_>, ids: [u32; 3]) -> bool {
    let uv = ids.map(|i| ctx.uv[i as usize]);
    let size = (0..3)
        .map(|k| normalised_distance(&ctx.domain, uv[k], uv[(k + 1) % 3]))
        .fold(0.0, f64::max);
    uv.iter()
        .any(|&p| ctx.boundary.inside_measure(p) <= 2.0 * size)
}

/// Distance of two parameter pairs in normalised coordinates.
fn normalised_distance(domain: &Domain, a: [f64; 2], b: [f64; 2]) -> f64 {
    let [s0, t0] = domain.to_normalised(a);
    let [s1, t1] = domain.to_normalised(b);
    // sqrt of the sum of squares, not hypot: the distances here are of order 1, far from
    // overflow, and hypot costs several times as much.
    ((s1 - s0) * (s1 - s0) + (t1 - t0) * (t1 - t0)).sqrt()
}

/// A triangle's facet vertex and where it lies.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleVertex {
    /// The meeting point of the three planes, or the stand-in when not `exact`.
    pub(crate) point: DVec3,
    /// The foot: Newton's (`newton_foot`), or the first-order estimate.
    pub(crate) foot: [f64; 2],
    /// Inside measure of the foot (positive inside the domain).
    pub(crate) inside: f64,
    /// Largest normalised distance of the triangle's points from the first-order foot.
    pub(crate) reach: f64,
    /// Whether `point` is the exact meeting point.
    pub(crate) exact: bool,
    /// Whether the foot was measured (Newton tried); a vertex deep inside the domain is
    /// decided from its first-order foot alone (see `surely_inside`).
    pub(crate) measured: bool,
    /// Whether `foot` is Newton's projection.
    pub(crate) newton_foot: bool,
}

impl TriangleVertex {
    /// The foot hint of this vertex for the report (see [`FootHint`]).
    pub(crate) fn hint(&self) -> FootHint {
        if self.newton_foot {
            FootHint::Known(self.foot)
        } else if self.measured {
            FootHint::FromSeed
        } else {
            FootHint::Guess {
                linear: self.foot,
                reach: self.reach,
            }
        }
    }
}

impl TriangleVertex {
    /// The foot and inside measure exactly as measuring would give them (Newton from the
    /// first-order foot), computed now if the vertex was decided without.
    fn measured_foot(&self, ctx: &Context<'_>) -> ([f64; 2], f64) {
        if self.measured {
            (self.foot, self.inside)
        } else {
            let (foot, inside, _) = ctx.measure_from(self.point, self.foot, self.reach);
            (foot, inside)
        }
    }
}

/// The meeting point of a triangle's three planes. An inside vertex that ran away from its
/// points (nearly parallel planes) is replaced by a finite stand-in near the points and
/// reported; facets never use the stand-in itself but its closest points on their edge lines
/// ([`edge_point`]), so they stay exactly planar. Outside vertices are only used to steer the
/// boundary clipping, so they may lie far away.
fn triangle_vertex(ctx: &Context<'_>, mut ids: [u32; 3], far_factor: f64) -> TriangleVertex {
    ids.sort_unstable();
    triangle_vertex_ordered(ctx, ids, far_factor)
}

/// [`triangle_vertex`] of the points `ids` taken in the given (canonical) order.
fn triangle_vertex_ordered(ctx: &Context<'_>, ids: [u32; 3], far_factor: f64) -> TriangleVertex {
    let [a, b, c] = ids.map(|i| &ctx.planes[i as usize]);
    // Coincident planes (a flat surface) meet on their seeds' bisectors.
    let meeting = meeting_point(a, b, c);
    let centroid = (a.point + b.point + c.point) / 3.0;
    let longest = a
        .point
        .distance(b.point)
        .max(b.point.distance(c.point))
        .max(c.point.distance(a.point));
    let distance = meeting.point.distance(centroid);
    if meeting.point.is_finite() {
        let (linear, reach) = ctx.linear_estimate(ids, meeting.point);
        let near = distance <= far_factor * longest
            || (ctx.regular && distance <= UNREACHABLE_VERTEX_FACTOR * longest);
        if near && surely_inside(ctx.boundary, linear, reach) {
            let inside = ctx.boundary.inside_measure(linear);
            return TriangleVertex {
                point: meeting.point,
                foot: linear,
                inside,
                reach,
                exact: true,
                measured: false,
                newton_foot: false,
            };
        }
        let (foot, inside, newton_foot) = ctx.measure_from(meeting.point, linear, reach);
        // A far vertex is only believable as an outside vertex of a triangle at the boundary
        // (a sliver along the hull); deep inside it means nearly parallel planes.
        if near || (inside <= 0.0 && near_boundary(ctx, ids)) {
            return TriangleVertex {
                point: meeting.point,
                foot,
                inside,
                reach,
                exact: true,
                measured: true,
                newton_foot,
            };
        }
    }
    let point = regularised_meeting_point([a, b, c], centroid, 1e-6);
    let (linear, reach) = ctx.linear_estimate(ids, point);
    let (foot, inside, newton_foot) = ctx.measure_from(point, linear, reach);
    TriangleVertex {
        point,
        foot,
        inside,
        reach,
        exact: false,
        measured: true,
        newton_foot,
    }
}

/// The vertex of one triangle, as [`build_facets`] computes it (for live editing), with the
/// points in `ids` already in the order of their pattern indices.
#[allow(clippy::too_many_arguments)]
pub(crate) fn single_triangle_vertex(
    surface: &dyn Surface,
    uv: &[[f64; 2]],
    tangents: &[[DVec3; 2]],
    planes: &[Plane],
    convex_side: &[i8],
    ids: [u32; 3],
    far_factor: f64,
) -> TriangleVertex {
    // Live editing runs on the convex path only, untrimmed.
    let boundary = Boundary::Rectangle(surface.domain());
    let ctx = Context {
        surface,
        domain: surface.domain(),
        boundary: &boundary,
        planes,
        uv,
        tangents,
        convex_side,
        regular: true,
        long_edges: false,
        extend_to_wall: None,
        wall: WallMoves::PLAIN,
        keep_closed: None,
    };
    triangle_vertex_ordered(&ctx, ids, far_factor)
}

/// The diagnostic of a triangle whose vertex is a stand-in.
fn ill_conditioned(ctx: &Context<'_>, mut ids: [u32; 3], _vertex: &TriangleVertex) -> Diagnostic {
    ids.sort_unstable();
    let [a, b, c] = ids.map(|i| &ctx.planes[i as usize]);
    let meeting = meeting_point(a, b, c);
    let centroid = (a.point + b.point + c.point) / 3.0;
    let distance = meeting.point.distance(centroid);
    let distance = if distance.is_finite() {
        distance
    } else {
        f64::INFINITY
    };
    Diagnostic::IllConditionedVertex {
        points: ids,
        determinant: meeting.determinant,
        distance,
    }
}

/// The point of the line T_a ∩ T_b closest to `x`: x - A^T (A A^T)^-1 (A x - b) with
/// A = [n_a; n_b]. When the planes coincide, the projection of x onto them. None when the
/// planes are parallel but distinct, or the line lies farther than `far_factor` times the
/// points' distance from x.
pub(crate) fn edge_point(a: &Plane, b: &Plane, x: DVec3, far_factor: f64) -> Option<DVec3> {
    let (ra, rb) = (a.signed_distance(x), b.signed_distance(x));
    let c = a.normal.dot(b.normal);
    let det = 1.0 - c * c;
    let reach = far_factor * a.point.distance(b.point);
    if det <= 1e-12 {
        // (Nearly) parallel: usable only if the planes coincide at x.
        let projected = x - a.normal * ra;
        return (b.signed_distance(projected).abs() <= 1e-12 * reach.max(f64::MIN_POSITIVE))
            .then_some(projected);
    }
    // (A A^T)^-1 (r_a, r_b) with A A^T = [[1, c], [c, 1]].
    let la = (ra - c * rb) / det;
    let lb = (rb - c * ra) / det;
    let point = x - a.normal * la - b.normal * lb;
    (point.is_finite() && point.distance(x) <= reach).then_some(point)
}

/// Where a point of the edge's segment comes from.
#[derive(Clone, Copy)]
struct SegmentEnd {
    point: DVec3,
    guess: [f64; 2],
    inside: f64,
}

/// Boundary crossings of one edge, ordered from its right triangle to its left one.
///
/// Where one end is inside, the crossing is searched on the line itself, x = x_in + lambda D
/// with D = n_lo x n_hi, so that it lies in both tangent planes to rounding, whatever the
/// other end's conditioning. Where both ends are outside, the segment is sampled for a part
/// that dips into the domain.
fn edge_crossings(
    ctx: &Context<'_>,
    tri: &DualTriangulation,
    edge: &Edge,
    triangle_vertices: &[TriangleVertex],
) -> (Vec<Crossing>, Option<Diagnostic>) {
    let (lo, hi) = (&ctx.planes[edge.lo as usize], &ctx.planes[edge.hi as usize]);
    // An ill-conditioned triangle contributes its stand-in's closest point on this edge's
    // line (the same point the facets use), or nothing usable.
    let end_of = |t: u32| {
        let v = &triangle_vertices[t as usize];
        let point = if v.exact {
            Some(v.point)
        } else {
            edge_point(lo, hi, v.point, DEFAULT_FAR_VERTEX_FACTOR)
        };
        let (guess, inside) = v.measured_foot(ctx);
        SegmentEnd {
            point: point.unwrap_or(DVec3::NAN),
            guess,
            inside,
        }
    };
    // (start, end) in canonical order right -> left; None marks a hull side (a ray).
    let start = (edge.right != NO_TRIANGLE).then(|| end_of(edge.right));
    let end = (edge.left != NO_TRIANGLE).then(|| end_of(edge.left));
    let inside = |e: &Option<SegmentEnd>| e.is_some_and(|e| e.inside > 0.0);
    if inside(&start) && inside(&end) {
        return (Vec::new(), None);
    }
    // The edge of two coincident facets is their seeds' bisector in their plane.
    let along = if coincident(lo, hi) {
        lo.normal.cross(hi.point - lo.point)
    } else {
        lo.normal.cross(hi.normal)
    };
    let Some(line) = along.try_normalize() else {
        return (
            Vec::new(),
            Some(Diagnostic::ParallelPlanes {
                points: [edge.lo, edge.hi],
            }),
        );
    };
    let spacing = lo.point.distance(hi.point).max(f64::MIN_POSITIVE);
    let outward = |t: u32| {
        // Direction along the line away from triangle t's third point k. Where all three are
        // convex on one side, the envelope decides: the ray stays in H_k, sigma n_k . d > 0.
        let third = tri.triangles[t as usize]
            .into_iter()
            .find(|&v| v != edge.lo && v != edge.hi)
            .unwrap_or(edge.lo);
        let side = ctx.convex_side[third as usize];
        if side != 0
            && ctx.convex_side[edge.lo as usize] == side
            && ctx.convex_side[edge.hi as usize] == side
        {
            let along = f64::from(side) * ctx.planes[third as usize].normal.dot(line);
            if along != 0.0 {
                return if along > 0.0 { line } else { -line };
            }
        }
        let chord = hi.point - lo.point;
        let mut away = (lo.point + hi.point) * 0.5 - ctx.planes[third as usize].point;
        away -= chord * (away.dot(chord) / chord.length_squared().max(f64::MIN_POSITIVE));
        if line.dot(away) < 0.0 {
            -line
        } else {
            line
        }
    };
    match (inside(&start), inside(&end)) {
        (true, true) => (Vec::new(), None),
        (true, false) | (false, true) => {
            let forward = inside(&start);
            let (from, to) = if forward { (start, end) } else { (end, start) };
            let Some(from) = from else {
                return (Vec::new(), None);
            };
            if !from.point.is_finite() {
                return (
                    Vec::new(),
                    Some(Diagnostic::BoundaryNotReached {
                        points: [edge.lo, edge.hi],
                    }),
                );
            }
            let (direction, target) = match to {
                Some(to)
                    if to.point.is_finite()
                        && to.point.distance(from.point) <= RAY_FAR_FACTOR * spacing =>
                {
                    let chord = to.point - from.point;
                    (
                        if line.dot(chord) < 0.0 { -line } else { line },
                        Some(chord.length()),
                    )
                }
                Some(to) => {
                    let t = if forward { edge.left } else { edge.right };
                    let towards = if to.point.is_finite() {
                        to.point - from.point
                    } else {
                        outward(t)
                    };
                    let _ = t;
                    (if line.dot(towards) < 0.0 { -line } else { line }, None)
                }
                None => {
                    let t = if forward { edge.right } else { edge.left };
                    (outward(t), None)
                }
            };
            let outside = match target {
                Some(length) => {
                    let point = from.point + direction * length;
                    let (foot_uv, inside) = ctx.measure_side(point, from.guess);
                    if inside > 0.0 {
                        march_out(ctx, &from, direction, spacing)
                    } else {
                        Some((
                            length,
                            SegmentEnd {
                                point,
                                guess: foot_uv,
                                inside,
                            },
                        ))
                    }
                }
                None => march_out(ctx, &from, direction, spacing),
            };
            let Some((length, outside)) = outside else {
                return (
                    Vec::new(),
                    Some(Diagnostic::BoundaryNotReached {
                        points: [edge.lo, edge.hi],
                    }),
                );
            };
            let crossing =
                refine_crossing(ctx, (0.0, from), (length, outside), from.point, direction);
            // `refine_crossing` walks from inside to outside: an exit in that direction.
            (
                vec![Crossing {
                    exit: forward,
                    ..crossing
                }],
                None,
            )
        }
        (false, false) => {
            // A facet edge can dip into the domain between two outside ends (a corner cut,
            // or a tiny facet of a point right at the boundary). A hull ray becomes a segment
            // reaching well past both points.
            let (a, b) = match (start, end) {
                (Some(s), Some(e)) => (s, e),
                (Some(v), None) | (None, Some(v)) => {
                    let t = if edge.left == NO_TRIANGLE {
                        edge.right
                    } else {
                        edge.left
                    };
                    let reach =
                        2.0 * (v.point.distance(lo.point) + v.point.distance(hi.point)) + spacing;
                    let point = v.point + outward(t) * reach;
                    (
                        v,
                        SegmentEnd {
                            point,
                            guess: v.guess,
                            inside: -1.0,
                        },
                    )
                }
                (None, None) => return (Vec::new(), None),
            };
            let reversed = start.is_none();
            let (first, last) = if reversed { (b, a) } else { (a, b) };
            (
                outside_segment_crossings(ctx, first, last, lo.point, hi.point),
                None,
            )
        }
    }
}

/// Crossings of an edge of a closed structure whose segment may cross the boundary several
/// times (a strip over a hole or a notch of a trim), in canonical order (right to left):
/// the segment is sampled once between each two consecutive points where the segment of its
/// ends' feet crosses a boundary loop in parameter space, and each change of side between
/// samples is refined on the segment itself.
/// With `known`, the crossings are taken from its cache where there ([`long_edge_key`]).
/// Also whether they were computed here with a key (not found in the cache), for the
/// caller to add them to it.
fn long_edge_crossings(
    ctx: &Context<'_>,
    edge: &Edge,
    triangle_vertices: &[TriangleVertex],
    known: Option<&VertexCache>,
) -> (Vec<Crossing>, bool) {
    let Some(key) = long_edge_key(ctx, edge, triangle_vertices) else {
        return (Vec::new(), false);
    };
    if let Some(found) = known.and_then(|known| known.crossings.get(&key)) {
        return (found.clone(), false);
    }
    (long_edge_crossings_of(ctx, edge, triangle_vertices), true)
}

/// [`long_edge_crossings`] computed.
fn long_edge_crossings_of(
    ctx: &Context<'_>,
    edge: &Edge,
    triangle_vertices: &[TriangleVertex],
) -> Vec<Crossing> {
    let end_of = |t: u32| {
        let v = &triangle_vertices[t as usize];
        let (guess, inside) = v.measured_foot(ctx);
        SegmentEnd {
            point: v.point,
            guess,
            inside,
        }
    };
    let (start, end) = (end_of(edge.right), end_of(edge.left));
    if !(start.point.is_finite() && end.point.is_finite()) {
        return Vec::new();
    }
    let chord = end.point - start.point;
    let length = chord.length();
    let Some(direction) = chord.try_normalize() else {
        return Vec::new();
    };
    let mut cuts = vec![0.0];
    cuts.extend(ctx.boundary.segment_crossings(start.guess, end.guess));
    cuts.push(1.0);
    let mut samples = vec![(0.0, start)];
    for k in 1..cuts.len().saturating_sub(2) {
        let tau = 0.5 * (cuts[k] + cuts[k + 1]);
        let point = start.point + chord * tau;
        let (guess, inside) = ctx.measure(point, lerp2(start.guess, end.guess, tau));
        samples.push((
            length * tau,
            SegmentEnd {
                point,
                guess,
                inside,
            },
        ));
    }
    samples.push((length, end));
    let mut found = Vec::new();
    for pair in samples.windows(2) {
        let (previous, current) = (pair[0], pair[1]);
        if (previous.1.inside > 0.0) != (current.1.inside > 0.0) {
            let crossing = refine_crossing(ctx, previous, current, start.point, direction);
            found.push(Crossing {
                exit: previous.1.inside > 0.0,
                ..crossing
            });
        }
    }
    found
}

/// The cache key of [`long_edge_crossings`] of `edge` ([`crossing_key`]), or None where the
/// edge has no crossings without a projection: on the hull, or, on a convex region, both
/// ends decided inside from their first-order feet (`surely_inside`: their measured feet
/// would lie inside too, within the margin, and so does the segment between them).
fn long_edge_key(
    ctx: &Context<'_>,
    edge: &Edge,
    triangle_vertices: &[TriangleVertex],
) -> Option<Bits<16>> {
    if edge.right == NO_TRIANGLE || edge.left == NO_TRIANGLE {
        return None;
    }
    let unmeasured = |t: u32| !triangle_vertices[t as usize].measured;
    if ctx.boundary.is_convex() && unmeasured(edge.right) && unmeasured(edge.left) {
        return None;
    }
    Some(crossing_key(
        &triangle_vertices[edge.right as usize],
        &triangle_vertices[edge.left as usize],
    ))
}

/// Crossings of a segment whose two ends are outside the domain, in order from `start`.
/// The segment is sampled uniformly and at the feet of the two points' perpendiculars (where
/// their facets are), and a stretch counts as inside only where it runs close to the surface
/// (within [`NEAR_SURFACE_RATIO`] of its distance to the points): far from them a segment
/// may pass high over the surface, where a foot inside the domain means nothing.
fn outside_segment_crossings(
    ctx: &Context<'_>,
    start: SegmentEnd,
    end: SegmentEnd,
    p: DVec3,
    q: DVec3,
) -> Vec<Crossing> {
    if !(start.point.is_finite() && end.point.is_finite()) {
        return Vec::new();
    }
    let chord = end.point - start.point;
    let length = chord.length();
    let Some(direction) = chord.try_normalize() else {
        return Vec::new();
    };
    let mut lambdas: Vec<f64> = (1..=OUTSIDE_SEGMENT_SAMPLES)
        .map(|k| length * k as f64 / (OUTSIDE_SEGMENT_SAMPLES + 1) as f64)
        .collect();
    for x in [p, q] {
        let t = (x - start.point).dot(direction);
        if t > 0.0 && t < length {
            lambdas.push(t);
        }
    }
    lambdas.sort_by(f64::total_cmp);
    let mut samples = vec![(0.0, start)];
    for &lambda in &lambdas {
        let point = start.point + direction * lambda;
        let guess = lerp2(start.guess, end.guess, lambda / length);
        let (foot_uv, inside) = ctx.measure_side(point, guess);
        if inside > 0.0 {
            let (u, v) = ctx.domain.clamp(foot_uv[0], foot_uv[1]);
            let off_surface = ctx.surface.point_at(u, v).distance(point);
            if off_surface > NEAR_SURFACE_RATIO * point.distance(p).min(point.distance(q)) {
                return Vec::new();
            }
        }
        samples.push((
            lambda,
            SegmentEnd {
                point,
                guess: foot_uv,
                inside,
            },
        ));
    }
    samples.push((length, end));
    let mut found = Vec::new();
    for pair in samples.windows(2) {
        let (previous, current) = (pair[0], pair[1]);
        if (previous.1.inside > 0.0) != (current.1.inside > 0.0) {
            let exit = previous.1.inside > 0.0;
            let crossing = refine_crossing(ctx, previous, current, start.point, direction);
            // Where the foot jumps (the segment passes a fold of the projection) the bracket
            // holds no boundary point: such a "crossing" is no crossing.
            if !crossing.converged {
                return Vec::new();
            }
            found.push(Crossing { exit, ..crossing });
        }
    }
    found
}

/// Steps along `direction` from an inside point, doubling, until outside the domain.
fn march_out(
    ctx: &Context<'_>,
    from: &SegmentEnd,
    direction: DVec3,
    spacing: f64,
) -> Option<(f64, SegmentEnd)> {
    let mut step = spacing;
    let mut guess = from.guess;
    for _ in 0..RAY_DOUBLINGS {
        let point = from.point + direction * step;
        let (foot_uv, inside) = ctx.measure_side(point, guess);
        if inside <= 0.0 {
            return Some((
                step,
                SegmentEnd {
                    point,
                    guess: foot_uv,
                    inside,
                },
            ));
        }
        guess = foot_uv;
        step *= 2.0;
    }
    None
}

fn lerp2(a: [f64; 2], b: [f64; 2], t: f64) -> [f64; 2] {
    [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]
}

/// Regula falsi (Illinois variant) on the inside measure along origin + lambda direction,
/// between two bracketing samples. The crossing's `exit` is set by the caller.
fn refine_crossing(
    ctx: &Context<'_>,
    low: (f64, SegmentEnd),
    high: (f64, SegmentEnd),
    origin: DVec3,
    direction: DVec3,
) -> Crossing {
    let (mut a, mut b) = (low, high);
    let (mut fa, mut fb) = (a.1.inside, b.1.inside);
    let mut best = if fa.abs() < fb.abs() { a } else { b };
    // Whether `best` is a point this search projected (its guess is then its Newton foot).
    let mut projected = false;
    let mut side = 0i8;
    for _ in 0..CROSSING_ITERATIONS {
        let mut lambda = (a.0 * fb - b.0 * fa) / (fb - fa);
        if !lambda.is_finite() || lambda <= a.0.min(b.0) || lambda >= a.0.max(b.0) {
            lambda = 0.5 * (a.0 + b.0);
        }
        let point = origin + direction * lambda;
        let guess = if (lambda - a.0).abs() < (lambda - b.0).abs() {
            a.1.guess
        } else {
            b.1.guess
        };
        let (foot_uv, inside) = ctx.measure(point, guess);
        let current = (
            lambda,
            SegmentEnd {
                point,
                guess: foot_uv,
                inside,
            },
        );
        if inside.abs() < best.1.inside.abs() {
            best = current;
            projected = true;
        }
        if inside.abs() < CROSSING_TOLERANCE
            || (b.0 - a.0).abs() <= 1e-15 * b.0.abs().max(a.0.abs())
        {
            break;
        }
        if (inside > 0.0) == (fa > 0.0) {
            a = current;
            fa = inside;
            if side == -1 {
                fb *= 0.5;
            }
            side = -1;
        } else {
            b = current;
            fb = inside;
            if side == 1 {
                fa *= 0.5;
            }
            side = 1;
        }
    }
    let converged = best.1.inside.abs() <= CROSSING_ACCEPTANCE;
    Crossing {
        point: best.1.point,
        wall: ctx.boundary.position(best.1.guess),
        exit: false,
        converged,
        foot: projected.then_some(best.1.guess),
        uv: best.1.guess,
    }
}

/// For each boundary corner, the crossing that owns it: the last crossing before the corner
/// along its boundary loop (in the loop's direction, the region on the left). The facet that
/// leaves the region there follows the boundary past the corner, so it is the one that holds
/// it. A corner on a loop that no edge crosses has no owner.
fn corner_owners(
    boundary: &Boundary,
    corners: &[([f64; 2], Position)],
    crossings: &[Crossing],
) -> Vec<Option<u32>> {
    corners
        .iter()
        .map(|&(_, corner)| {
            let mut best: Option<(f64, u32)> = None;
            for (index, crossing) in crossings.iter().enumerate() {
                let Some(behind) = boundary.ahead(crossing.wall, corner) else {
                    continue;
                };
                if best.map_or(true, |(b, _)| behind < b) {
                    best = Some((behind, index as u32));
                }
            }
            best.map(|b| b.1)
        })
        .collect()
}

/// Point and normal over each boundary corner.
fn corner_samples(surface: &dyn Surface, corners: &[([f64; 2], Position)]) -> Vec<(DVec3, DVec3)> {
    corners
        .iter()
        .map(|&([u, v], _)| {
            let d = surface.evaluate(u, v);
            let geometry = crate::diffgeo::LocalGeometry::from_derivatives(&d);
            (d.point, geometry.normal)
        })
        .collect()
}

/// The loop of facet i as items appended to `items`, with corners inserted along the
/// boundary; walk diagnostics go to `diagnostics` with the facet's index.
/// Returns whether the loop is just the closed fan (the fast path).
fn facet_items(
    i: u32,
    cx: &ItemContext<'_>,
    fan: &mut Vec<u32>,
    items: &mut PackedItems,
    diagnostics: &mut Vec<(u32, Diagnostic)>,
) -> bool {
    let tri = cx.tri;
    let kind = tri.fan(i, cx.incident[i as usize], fan);
    if kind == Fan::Broken || fan.is_empty() {
        diagnostics.push((
            i,
            Diagnostic::OpenFacet {
                point: i,
                reason: "no triangles around the point".into(),
            },
        ));
        return false;
    }
    if kind == Fan::Closed && cx.keep_closed.is_some_and(|keep| keep[i as usize]) {
        closed_fan_items(i, cx, fan, items);
        return false;
    }
    // Fast path: an interior point whose fan vertices are all exact and inside has no
    // boundary crossing on any of its edges (crossings need an outside end): its loop is its fan.
    if kind == Fan::Closed
        && fan.iter().all(|&t| {
            let v = &cx.triangle_vertices[t as usize];
            v.exact && v.inside > 0.0
        })
    {
        items.codes.extend_from_slice(fan);
        return true;
    }
    // Raw walk: crossings of each incoming edge, then the triangle's vertex if inside.
    let mut raw: Vec<(Item, Option<(bool, Position)>)> = Vec::with_capacity(fan.len() * 2 + 4);
    let push_edge = |j: u32, raw: &mut Vec<(Item, Option<(bool, Position)>)>| {
        for c in crossings_along(cx, i, j) {
            let crossing = cx.crossings[c as usize];
            let exit = crossing.exit == (i < j);
            raw.push((Item::Crossing(c), Some((exit, crossing.wall))));
        }
    };
    for &t in fan.iter() {
        let vertices = tri.triangles[t as usize];
        let p = vertices.iter().position(|&v| v == i).unwrap_or(0);
        let incoming = vertices[(p + 1) % 3];
        push_edge(incoming, &mut raw);
        let vertex = &cx.triangle_vertices[t as usize];
        if vertex.inside > 0.0 {
            let outgoing = vertices[(p + 2) % 3];
            push_vertex_items(t, i, [incoming, outgoing], vertex.exact, |item| {
                raw.push((item, None));
            });
        }
    }
    if kind == Fan::Open {
        let last = tri.triangles[fan[fan.len() - 1] as usize];
        let p = last.iter().position(|&v| v == i).unwrap_or(0);
        push_edge(last[(p + 2) % 3], &mut raw);
    }
    // Corners follow the exit crossing that owns them; leaving and entering must alternate.
    let boundary: Vec<bool> = raw
        .iter()
        .filter_map(|r| r.1.map(|(exit, _)| exit))
        .collect();
    if (0..boundary.len()).any(|k| boundary[k] == boundary[(k + 1) % boundary.len()]) {
        diagnostics.push((
            i,
            Diagnostic::OpenFacet {
                point: i,
                reason: "boundary crossings do not alternate between leaving and entering".into(),
            },
        ));
    }
    if let Some(seed_uv) = cx.long_edges {
        let (mut loop_items, parts) = if raw.iter().any(|r| r.1.is_some()) {
            seed_part(cx, &raw, seed_uv[i as usize])
        } else {
            (raw.iter().map(|r| r.0).collect(), 1)
        };
        // A facet that the wall leaves without area (all of it beyond the wall) keeps its
        // closed fan: every seed keeps a facet.
        if loop_items.len() < 3 && kind == Fan::Closed {
            loop_items = fan.iter().map(|&t| Item::Triangle(t)).collect();
        }
        for item in loop_items {
            items.push(item);
        }
        if parts > 1 {
            diagnostics.push((
                i,
                Diagnostic::FacetPartsLeftOut {
                    point: i,
                    parts: parts as u32,
                },
            ));
        }
        return false;
    }
    for (item, crossing) in raw {
        items.push(item);
        if let (Item::Crossing(c), Some((true, wall))) = (item, crossing) {
            let mut owned: Vec<(f64, u32)> = (0..cx.corners.len() as u32)
                .filter(|&k| cx.corner_owner[k as usize] == Some(c))
                .filter_map(|k| {
                    let ahead = cx.boundary.ahead(wall, cx.corners[k as usize].1)?;
                    Some((ahead, k))
                })
                .collect();
            owned.sort_by(|x, y| x.0.total_cmp(&y.0));
            for x in owned {
                items.push(Item::Corner(x.1));
            }
        }
    }
    false
}

/// The loop of facet i kept closed in a hybrid clip ([`WallClip::clip`]): every vertex of its
/// closed fan, inside or out, with the crossings of its edges with other real seeds between
/// them. Its clipped neighbours end their shared edge at those crossings, so the two facets
/// still share the edge's part inside the region, and the part beyond is the closed facet's
/// own edge on the mesh's edge; the crossings lie on the edge, so the loop stays in its plane.
/// An ill-conditioned vertex gives the edge points the walk gives it.
fn closed_fan_items(i: u32, cx: &ItemContext<'_>, fan: &[u32], items: &mut PackedItems) {
    let real = cx.keep_closed.map_or(0, <[bool]>::len) as u32;
    for &t in fan {
        let vertices = cx.tri.triangles[t as usize];
        let p = vertices.iter().position(|&v| v == i).unwrap_or(0);
        let [incoming, outgoing] = [vertices[(p + 1) % 3], vertices[(p + 2) % 3]];
        if incoming < real {
            for c in crossings_along(cx, i, incoming) {
                items.push(Item::Crossing(c));
            }
        }
        let exact = cx.triangle_vertices[t as usize].exact;
        push_vertex_items(t, i, [incoming, outgoing], exact, |item| items.push(item));
    }
}

/// The crossings of the edge between points i and j, in the order facet i's loop meets them
/// (they are stored from the edge's lower point to its higher one).
fn crossings_along(cx: &ItemContext<'_>, i: u32, j: u32) -> impl Iterator<Item = u32> {
    let (first, last) = cx
        .crossing_ranges
        .get(&(i.min(j), i.max(j)))
        .copied()
        .unwrap_or((0, 0));
    let forward = i < j;
    (0..last - first).map(move |k| if forward { first + k } else { last - 1 - k })
}

/// Triangle t's vertex on facet i's loop, which reaches it along the edge with point
/// `incoming` and leaves along the edge with `outgoing`: the vertex itself, or where it is a
/// stand-in (not `exact`) the points on the lines of those two edges, each shared with the
/// facet across it.
fn push_vertex_items(
    t: u32,
    i: u32,
    [incoming, outgoing]: [u32; 2],
    exact: bool,
    mut push: impl FnMut(Item),
) {
    if exact {
        push(Item::Triangle(t));
        return;
    }
    for j in [incoming, outgoing] {
        push(Item::EdgePoint {
            triangle: t,
            lo: i.min(j),
            hi: i.max(j),
        });
    }
}

/// The part of a facet's loop (`raw`, its walk with the crossings of its edges) around its
/// seed, clipped by itself on the boundary, and the number of parts the boundary cuts it into
/// (a long strip across a hole of a trim). The parts are traced as in Weiler and Atherton's
/// clipping: from an exit crossing the loop follows the boundary, picking up the corners it
/// passes, to the facet's own nearest entry ahead on that loop, and goes on along the facet
/// from there.
fn seed_part(
    cx: &ItemContext<'_>,
    raw: &[(Item, Option<(bool, Position)>)],
    seed: [f64; 2],
) -> (Vec<Item>, usize) {
    let uv_of = |item: Item| match item {
        Item::Triangle(t) | Item::EdgePoint { triangle: t, .. } => {
            cx.triangle_vertices[t as usize].foot
        }
        Item::Crossing(c) => cx.crossings[c as usize].uv,
        Item::Corner(c) => cx.corners[c as usize].0,
    };
    let mut visited = vec![false; raw.len()];
    let mut parts: Vec<Vec<Item>> = Vec::new();
    // Every part holds an inside vertex or an entry crossing: start from those.
    for start in 0..raw.len() {
        if visited[start] || matches!(raw[start].1, Some((true, _))) {
            continue;
        }
        let mut part = Vec::new();
        let mut k = start;
        while !visited[k] {
            visited[k] = true;
            let (item, crossing) = raw[k];
            part.push(item);
            let Some((true, wall)) = crossing else {
                k = (k + 1) % raw.len();
                continue;
            };
            // Each facet is clipped by itself: from an exit, the boundary is followed to the
            // facet's own nearest entry ahead on the same loop, picking up the corners between.
            let entry = raw
                .iter()
                .enumerate()
                .filter_map(|(e, r)| match r.1 {
                    Some((false, at)) => Some((
                        cx.boundary
                            .ahead_or_just_behind(wall, at, GRAZING_CROSSING_SLACK)?,
                        e,
                    )),
                    _ => None,
                })
                .min_by(|x, y| x.0.total_cmp(&y.0));
            k = match entry {
                Some((length, e)) => {
                    // A corner a crossing sits on is that crossing (no owner then).
                    let mut passed: Vec<(f64, u32)> = (0..cx.corners.len() as u32)
                        .filter(|&q| cx.corner_owner[q as usize].is_some())
                        .filter_map(|q| {
                            let ahead = cx.boundary.ahead(wall, cx.corners[q as usize].1)?;
                            (ahead < length).then_some((ahead, q))
                        })
                        .collect();
                    passed.sort_by(|x, y| x.0.total_cmp(&y.0));
                    part.extend(passed.into_iter().map(|x| Item::Corner(x.1)));
                    e
                }
                None => (k + 1) % raw.len(),
            };
        }
        parts.push(part);
    }
    let count = parts.len();
    if count == 0 {
        return (raw.iter().map(|r| r.0).collect(), 1);
    }
    let around_seed = parts.iter().position(|part| {
        let polygon: Vec<[f64; 2]> = part.iter().map(|&item| uv_of(item)).collect();
        crate::trim::in_polygon(&polygon, seed)
    });
    let chosen = around_seed.unwrap_or(0);
    (parts.swap_remove(chosen), count)
}

/// The facets of the points `0..real_count` of a triangulation whose points from
/// `real_count` on are ghosts ([`crate::ghosts`]), mirrored beyond the boundary so that every
/// real fan closes: each facet's loop is the vertices T_i ∩ T_j ∩ T_k of its fan, exactly the
/// polygon the validity flips judged ([`crate::validity_flips`]). Vertices of triangles with a
/// ghost are boundary vertices: they lie on the mirror plane of the ghost's wall, the tangent
/// plane of the wall at the boundary point nearest to the ghost's seed. `source` maps every
/// point to its real seed (for diagnostics). Ill-conditioned vertices are replaced by their
/// closest points on the facets' edge lines, as in [`build_facets`].
///
/// `envelope`: `tri` is the envelope's own structure (the convex hull of a closed convex
/// surface's dual points), whose vertices are exact however far from their triangle's
/// points; as on the open convex path, only a vertex beyond [`UNREACHABLE_VERTEX_FACTOR`]
/// times the triangle's longest side is then diagnosed (three seeds a few nanometres apart
/// in a random pattern of millions have a vertex many times their distance away, and it is
/// right).
pub(crate) fn build_closed_facets(
    tri: &DualTriangulation,
    planes: &[Plane],
    real_count: usize,
    source: &[u32],
    envelope: bool,
    params: &FacetParams,
    stages: &Stages<'_>,
) -> FacetMesh {
    let observer = stages.observer();
    let real = |t: &[u32; 3]| t.iter().any(|&v| (v as usize) < real_count);
    // Each triangle's vertex with its meeting point (kept for the diagnostics below, so that
    // the three planes are solved once).
    let (triangle_vertices, meetings): (Vec<TriangleVertex>, Vec<ThreePlanePoint>) = tri
        .triangles
        .par_iter()
        .map_init(
            || Tally::new(observer, Stage::Facets),
            |tally, ids| {
                tally.add(1);
                let mut ids = *ids;
                ids.sort_unstable();
                let [a, b, c] = ids.map(|i| &planes[i as usize]);
                let meeting = meeting_point(a, b, c);
                let centroid = (a.point + b.point + c.point) / 3.0;
                // Far vertices (nearly parallel planes, at parabolic lines) are kept exact: a
                // stand-in per edge would leave a hole, and the mesh must stay a disc. They are
                // named in a diagnostic below; only a vertex at infinity gets stand-ins.
                let exact = !real(&ids) || reachable(meeting.point, [a, b, c]);
                let point = if exact {
                    meeting.point
                } else {
                    regularised_meeting_point([a, b, c], centroid, 1e-6)
                };
                let vertex = TriangleVertex {
                    point,
                    foot: [0.0; 2],
                    inside: 1.0,
                    reach: 0.0,
                    exact,
                    measured: true,
                    newton_foot: false,
                };
                (vertex, meeting)
            },
        )
        .unzip();
    let mut diagnostics: Vec<Diagnostic> = tri
        .triangles
        .iter()
        .zip(&triangle_vertices)
        .zip(meetings)
        .filter_map(|((ids, v), meeting)| {
            let mut sorted = *ids;
            sorted.sort_unstable();
            let [a, b, c] = sorted.map(|i| &planes[i as usize]);
            let centroid = (a.point + b.point + c.point) / 3.0;
            let distance = meeting.point.distance(centroid);
            let longest = a
                .point
                .distance(b.point)
                .max(b.point.distance(c.point))
                .max(c.point.distance(a.point));
            let factor = if envelope {
                UNREACHABLE_VERTEX_FACTOR
            } else {
                params.far_vertex_factor
            };
            let far = !v.exact || !(distance <= factor * longest);
            (far && real(ids)).then_some((sorted, meeting, distance))
        })
        .map(|(sorted, meeting, distance)| {
            let mut points = sorted.map(|i| source[i as usize]);
            points.sort_unstable();
            Diagnostic::IllConditionedVertex {
                points,
                determinant: meeting.determinant,
                distance: if distance.is_finite() {
                    distance
                } else {
                    f64::INFINITY
                },
            }
        })
        .collect();
    let coincident_pairs = triangle_edges(&tri.triangles)
        .filter(|&[a, b]| a < b && (b as usize) < real_count)
        .filter(|&[a, b]| coincident(&planes[a as usize], &planes[b as usize]))
        .count();
    if coincident_pairs > 0 {
        diagnostics.push(Diagnostic::CoincidentPlanes {
            pairs: coincident_pairs as u32,
        });
    }
    let incident = tri.incident_triangles(source.len());
    let chunks: Vec<FacetChunk> = (0..real_count.div_ceil(FACET_CHUNK))
        .into_par_iter()
        .map_init(
            || Tally::new(observer, Stage::Facets),
            |tally, c| {
                let mut chunk = FacetChunk::default();
                let mut fan = Vec::new();
                let facets = c * FACET_CHUNK..((c + 1) * FACET_CHUNK).min(real_count);
                let count = facets.len();
                for i in facets {
                    let i = i as u32;
                    let kind = tri.fan(i, incident[i as usize], &mut fan);
                    if kind != Fan::Closed {
                        let reason =
                            "the fan of dual triangles around the point does not close".into();
                        chunk
                            .diagnostics
                            .push((i, Diagnostic::OpenFacet { point: i, reason }));
                    }
                    if kind != Fan::Broken {
                        for &t in &fan {
                            if triangle_vertices[t as usize].exact {
                                chunk.items.push(Item::Triangle(t));
                            } else {
                                let vertices = tri.triangles[t as usize];
                                let p = vertices.iter().position(|&v| v == i).unwrap_or(0);
                                for j in [vertices[(p + 1) % 3], vertices[(p + 2) % 3]] {
                                    chunk.items.push(Item::EdgePoint {
                                        triangle: t,
                                        lo: i.min(j),
                                        hi: i.max(j),
                                    });
                                }
                            }
                        }
                    }
                    chunk.ends.push(chunk.items.len() as u32);
                    chunk.simple.push(false);
                }
                tally.add(count);
                chunk
            },
        )
        .collect();
    let mut mesh = assemble(Assembly {
        tri,
        triangle_vertices,
        chunks,
        crossings: &[],
        corners: None,
        planes,
        params,
        ghosts_from: Some(real_count as u32),
        slopes: None,
        diagnostics: std::mem::take(&mut diagnostics),
        stages,
    });
    // Live editing never runs on this path: what only it reads is let go (every vertex's foot
    // hint is FootHint::FromSeed, as FootHints::Mesh reads an empty list).
    mesh.triangle_vertices = Vec::new();
    mesh
}
