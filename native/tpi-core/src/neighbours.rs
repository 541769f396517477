//! Deciding the true neighbours: which tangent planes are intersected (paper, section 3.2).
//!
//! The candidates are the Delaunay triangulation of the pattern points in parameter space.
//! Two criteria then decide every edge (a, b) of the quadrilateral (c, a, d, b) formed by its
//! two triangles, and Lawson flips replace the diagonal (a, b) by (c, d) where it fails. The
//! flips keep the structure a valid triangulation, which is how the per-point answers are
//! reconciled into one consistent dual (a symmetric neighbour relation whose triangles close
//! up around every interior point).
//!
//! 1. **Curvature compensation** (the paper's method). Locally the surface is its osculating
//!    paraboloid z = (k1 x^2 + k2 y^2) / 2 in the principal frame, and for an elliptic
//!    paraboloid z = a x^2 + b y^2 the tangent planes of p and q meet above the line
//!    a dx (2x - px - qx) + b dy (2y - py - qy) = 0: the perpendicular bisector of p and q
//!    after the substitution x' = sqrt(a) x, y' = sqrt(b) y. So the true neighbours are the
//!    Delaunay neighbours in the metric |II| = |k1| dx1^2 + |k2| dx2^2, i.e. the candidates
//!    scaled by sqrt(kmin/kmax) along the minimum-curvature direction relative to the maximum
//!    one (the paper states the ratio applied along the maximum direction; the closed form
//!    above fixes which way it goes). The edge test is the in-circle test in that metric,
//!    with the metric averaged over the quadrilateral's four points and the points projected
//!    orthogonally into the plane of their mean normal. |k| makes the same test usable on
//!    saddles, where the paper's method is only a heuristic; a small isotropic term keeps the
//!    metric definite where a curvature vanishes.
//!
//! 2. **Envelope** (the definition of right where K > 0). With every normal oriented towards
//!    the centres of curvature (sigma_i n_i, sigma_i = sign of the curvatures), the half-spaces
//!    H_i = {x : sigma_i n_i.(x - p_i) >= 0} intersect in a convex body whose face in T_i is the
//!    exact facet of point i. The edge (a, b) is right iff the vertex T_a ∩ T_b ∩ T_c lies in
//!    H_d (equivalently T_a ∩ T_b ∩ T_d in H_c); otherwise T_d cuts the edge off and (c, d) are
//!    the neighbours. This local test is applied after the first criterion to every quad whose
//!    four points are strictly convex, and it wins: the flips it makes are counted as
//!    "envelope repairs" in the report.

use std::sync::atomic::AtomicBool;

use glam::DVec3;

use crate::diffgeo::{flat_curvatures, LocalGeometry};
use crate::planes::{intersect_three, Plane};
use crate::predicates::{orient2d, power_illegal};
use crate::progress::{NoProgress, Stage, Stages, Tally, PROGRESS_CHUNK};
use crate::tolerance::{
    COMPENSATION_TIE_TOLERANCE, CONVEX_METRIC_REGULARISATION, DEGENERATE_SLIVER_FACTOR,
    DEVELOPABLE_METRIC_REGULARISATION, ENVELOPE_FLIP_TOLERANCE, GRADIENT_MIN_COS, REAL_LINK_SEARCH,
    SLOPE_FRAME_SAMPLES,
};

use crate::triangulation::{orient, DualTriangulation, IndexMap, NO_TRIANGLE};
use crate::validity_flips::{gaussian_signs, validity_flips};

/// Counts of what the neighbour decision did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct NeighbourStats {
    /// Flips made by the curvature-compensated in-circle test.
    pub compensation_flips: usize,
    /// Where the envelope overruled the candidates: on mixed surfaces the flips made by the
    /// envelope test after curvature compensation (disagreements with the paper's method);
    /// on convex surfaces, whose structure is the envelope's own, the interior edges that
    /// are not locally Delaunay in slope space (a count of the result, whatever the order of
    /// the flips that reached it).
    pub envelope_repairs: usize,
    /// Edges the envelope rejects but that could not be flipped (non-convex quadrilateral
    /// in parameter space) or flip budget exhausted.
    pub envelope_unresolved: usize,
    /// Triangles on the convex hull of the pattern (in parameter space) that the envelope
    /// rejects, removed so that the hull follows the envelope's.
    pub hull_trims: usize,
    /// Flips kept by the validity repair of interior facets ([`crate::validity_flips`]).
    #[serde(default)]
    pub validity_flips: usize,
    /// Interior facets the validity repair could not make valid (with adjusted planes: after
    /// the plane adjustment).
    #[serde(default)]
    pub validity_unresolved: usize,
    /// Plane tilts kept by the plane adjustment ([`crate::PlaneMode::Adjusted`]).
    #[serde(default)]
    pub plane_tilts: usize,
}

/// Inputs of the neighbour decision for every pattern point.
pub(crate) struct NeighbourInput<'a> {
    /// Coordinates the triangulation lives in (scaled parameter space).
    pub plane_uv: &'a [[f64; 2]],
    /// Local geometry per point.
    pub geometry: &'a [LocalGeometry],
    /// Tangent planes per point.
    pub planes: &'a [Plane],
    /// +1 or -1 where the point is strictly convex (K > 0): the side of the centres of
    /// curvature relative to the normal; 0 elsewhere.
    pub convex_side: &'a [i8],
    /// The any-curvature path (saddles, mixed surfaces): the compensation metric gets the
    /// isotropic term `metric_regularisation` and the tie tolerance, and the validity flips
    /// run. False on strictly convex surfaces, where the envelope test decides anyway.
    pub any_curvature: bool,
    /// The weight of the isotropic term on the any-curvature path:
    /// [`crate::tolerance::METRIC_REGULARISATION`], or one of
    /// [`crate::tolerance::METRIC_REGULARISATION_RETRIES`] when a first decision left a few
    /// facets invalid (`structure::decide_again`).
    pub metric_regularisation: f64,
    /// Where Some and set, the validity flips end at their next step: a speculative
    /// decision whose result will be dropped (`structure::decide_again`).
    pub stop: Option<&'a AtomicBool>,
    /// Exact planes: where the validity flips leave facets reaching beyond
    /// [`crate::tolerance::RUNAWAY_REACH`] times the seeds' diagonal, they run again counting
    /// those invalid, kept if that leaves fewer runaways and no more facets invalid, or fewer
    /// facets invalid or runaway ([`validity_flips`]).
    pub runaway_limit: bool,
}

/// Runs both criteria to convergence, then the validity flips of the facets of points
/// `0..real_count` ([`crate::validity_flips`]); points from `real_count` on are ghosts
/// ([`crate::ghosts`]), whose facets are not judged. Deterministic (a stack in edge order).
pub(crate) fn decide(
    tri: &mut DualTriangulation,
    input: &NeighbourInput<'_>,
    envelope: bool,
    real_count: usize,
) -> NeighbourStats {
    let mut stats = NeighbourStats::default();
    let uv = input.plane_uv;
    stats.compensation_flips = flip_until_stable(
        tri,
        uv,
        |tri, t, k| {
            compensation_illegal(tri, input, t, k) && !isolates_real_points(tri, t, k, real_count)
        },
        None,
    )
    .0;
    if envelope {
        let (flips, unresolved) = flip_until_stable(
            tri,
            uv,
            |tri, t, k| {
                envelope_illegal(tri, input, t, k) && !isolates_real_points(tri, t, k, real_count)
            },
            None,
        );
        stats.envelope_repairs = flips;
        stats.envelope_unresolved = unresolved;
    }
    if input.any_curvature {
        let validity = validity_flips(
            tri,
            uv,
            input.planes,
            real_count,
            &gaussian_signs(input.geometry),
            input.stop,
            input.runaway_limit,
        );
        stats.validity_flips = validity.flips;
        stats.validity_unresolved = validity.unresolved;
    }
    tri.canonicalise(input.plane_uv.len());
    // With ghosts the hull lies beyond the boundary: nothing to trim.
    if envelope && real_count == input.plane_uv.len() {
        stats.hull_trims = trim_hull(tri, input);
    }
    stats
}

/// Where every point is strictly convex with the same side and all normals lie within
/// acos([`GRADIENT_MIN_COS`]) of the surface's mean normal N ([`slope_frame`]), the surface is
/// a graph over the plane perpendicular to N, each tangent plane is z = a_i x + b_i y + c_i in
/// a frame (e1, e2, N), with (a_i, b_i) = -(n_i.e1, n_i.e2) / n_i.N, and the envelope is the
/// upper (sigma = +1) or lower (sigma = -1) envelope of these planes. Its dual is the regular
/// triangulation of the slopes sigma (a_i, b_i) lifted to -sigma c_i (the lower convex hull of
/// the lifted points, by Legendre duality): a planar triangulation in slope space whose hull
/// is exactly the envelope's. Returns the lifted points ([`SlopeFrame::lift`]), or None where
/// the conditions fail.
///
/// N depends on the surface alone, not on the pattern, so each point's slopes are its own
/// (which is what lets a live surface update them one point at a time).
pub(crate) fn gradient_embedding(
    planes: &[Plane],
    convex_side: &[i8],
    frame: Option<DVec3>,
) -> Option<Vec<[f64; 3]>> {
    let side = *convex_side.first()?;
    if side == 0 || convex_side.iter().any(|&s| s != side) {
        return None;
    }
    let frame = SlopeFrame::new(frame?, side);
    planes.iter().map(|p| frame.lift(p)).collect()
}

/// The frame of the slope embedding: N, (e1, e2) and the convex side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SlopeFrame {
    /// The unit mean normal of the surface.
    pub normal: DVec3,
    /// Tangent axes: (e1, e2, N) right-handed.
    pub axes: (DVec3, DVec3),
    /// +1 or -1: the side of the centres of curvature.
    pub side: f64,
}

impl SlopeFrame {
    /// The frame of unit normal `normal` for convex side `side`.
    pub(crate) fn new(normal: DVec3, side: i8) -> Self {
        Self {
            normal,
            axes: normal.any_orthonormal_pair(),
            side: f64::from(side),
        }
    }

    /// The lifted point (s, h) of one tangent plane, whose lower convex hull is dual to the
    /// envelope ([`crate::predicates`]): its slopes and the height h = -sigma c of the plane
    /// z = a x + b y + c in the frame, c = n.p / n.N. None where [`Self::slopes`] is.
    pub(crate) fn lift(&self, p: &Plane) -> Option<[f64; 3]> {
        let [a, b] = self.slopes(p)?;
        Some([a, b, self.height(p)])
    }

    /// The height -sigma n.p / n.N of [`Self::lift`].
    pub(crate) fn height(&self, p: &Plane) -> f64 {
        -self.side * (p.normal.dot(p.point) / p.normal.dot(self.normal))
    }

    /// The slopes of one tangent plane, or None where its normal is too far from N.
    pub(crate) fn slopes(&self, p: &Plane) -> Option<[f64; 2]> {
        let nz = p.normal.dot(self.normal);
        let (e1, e2) = self.axes;
        (nz >= GRADIENT_MIN_COS).then(|| {
            [
                -self.side * p.normal.dot(e1) / nz,
                -self.side * p.normal.dot(e2) / nz,
            ]
        })
    }
}

/// The unit mean of the surface's normals on a [`SLOPE_FRAME_SAMPLES`]^2 grid over its domain
/// (corners included), or None where it vanishes or is not finite.
pub(crate) fn slope_frame(surface: &dyn crate::surface::Surface) -> Option<DVec3> {
    let domain = surface.domain();
    let last = (SLOPE_FRAME_SAMPLES - 1) as f64;
    let mut sum = DVec3::ZERO;
    for i in 0..SLOPE_FRAME_SAMPLES {
        for j in 0..SLOPE_FRAME_SAMPLES {
            let [u, v] = domain.from_normalised([i as f64 / last, j as f64 / last]);
            sum += LocalGeometry::from_derivatives(&surface.evaluate(u, v)).normal;
        }
    }
    sum.try_normalize()
}

/// The envelope's dual structure for a convex surface, from the Delaunay triangulation of
/// the slopes ([`gradient_embedding`]) flipped to the regular triangulation of the `lifted`
/// points ([`SlopeFrame::lift`], whose first two coordinates are `slopes`) by the exact power test ([`crate::predicates`]), with
/// convexity judged exactly in slope space where the result is embedded; then oriented
/// counter-clockwise in parameter space (`plane_uv`), put in canonical order and trimmed.
///
/// `envelope_repairs` counts the interior edges of the result that are not locally Delaunay
/// in slope space ([`slope_repairs`]): where the envelope departs from the plain Delaunay
/// candidates. It depends on the result alone, not on the order of the flips.
///
/// `regular` says that `tri` is that regular triangulation already
/// ([`crate::regular::regular_triangulation`]): no edge is tested.
pub(crate) fn decide_convex(
    tri: &mut DualTriangulation,
    slopes: &[[f64; 2]],
    lifted: &[[f64; 3]],
    regular: bool,
    input: &NeighbourInput<'_>,
    stages: &Stages<'_>,
) -> NeighbourStats {
    let unresolved = if regular {
        // Nothing to flip: the stage's items (the interior edges the flips would test) are
        // done at once.
        let edges = (3 * tri.len()
            - tri
                .neighbours
                .iter()
                .flatten()
                .filter(|&&n| n == NO_TRIANGLE)
                .count())
            / 2;
        stages.enter(Stage::Neighbours, Some(edges));
        let mut tally = Tally::new(stages.observer(), Stage::Neighbours);
        for done in (0..edges).step_by(PROGRESS_CHUNK) {
            tally.add((edges - done).min(PROGRESS_CHUNK));
        }
        0
    } else {
        flip_to_regular(tri, slopes, lifted, Some(stages))
    };
    orient_like(tri, input.plane_uv);
    tri.canonicalise(input.plane_uv.len());
    // Rounding can leave slivers along a straight stretch of the hull.
    let hull_trims = trim_hull(tri, input);
    let envelope_repairs = slope_repairs(tri, slopes);
    NeighbourStats {
        compensation_flips: 0,
        envelope_repairs,
        envelope_unresolved: unresolved,
        hull_trims,
        ..NeighbourStats::default()
    }
}

/// Flips `tri` (a triangulation of `slopes`) towards the regular triangulation of the
/// `lifted` points by the exact power test, each flip only where its quadrilateral is strictly
/// convex in slope space; returns the illegal edges left unflipped (0 where the result is the
/// regular triangulation).
pub(crate) fn flip_to_regular(
    tri: &mut DualTriangulation,
    slopes: &[[f64; 2]],
    lifted: &[[f64; 3]],
    stages: Option<&Stages<'_>>,
) -> usize {
    let (_flips, unresolved) = flip_until_stable(
        tri,
        slopes,
        |tri, t, k| {
            let ids = quad(tri, t, k);
            power_illegal(ids.map(|i| lifted[i as usize]), ids)
        },
        stages,
    );
    unresolved
}

/// Makes the triangles counter-clockwise in `uv` (the orientation the facet loops inherit),
/// judged by the majority so that a few slivers cannot decide.
pub(crate) fn orient_like(tri: &mut DualTriangulation, uv: &[[f64; 2]]) {
    let reversed = tri
        .triangles
        .iter()
        .filter(|t| orient(uv[t[0] as usize], uv[t[1] as usize], uv[t[2] as usize]) < 0.0)
        .count();
    if 2 * reversed > tri.len() {
        tri.reverse();
    }
}

/// Interior edges (each once) whose quad is not locally Delaunay in slope space: the fourth
/// point strictly inside the circle through the other three.
pub(crate) fn slope_repairs(tri: &DualTriangulation, slopes: &[[f64; 2]]) -> usize {
    use rayon::prelude::*;
    (0..tri.len())
        .into_par_iter()
        .map(|t| {
            (0..3)
                .filter(|&k| {
                    let other = tri.neighbours[t][k];
                    other != NO_TRIANGLE
                        && (other as usize) > t
                        && slope_edge_repaired(tri, slopes, t, k)
                })
                .count()
        })
        .sum()
}

/// Whether the interior edge opposite vertex k of triangle t is not locally Delaunay in slope
/// space (see [`slope_repairs`]).
pub(crate) fn slope_edge_repaired(
    tri: &DualTriangulation,
    slopes: &[[f64; 2]],
    t: usize,
    k: usize,
) -> bool {
    let [c, a, b, d] = quad(tri, t, k).map(|i| slopes[i as usize]);
    // (c, a, b) in either orientation: the in-circle sign flips with it.
    let o = orient(c, a, b);
    o != 0.0 && in_circle(c, a, b, d) * o.signum() > 0.0
}

/// Removes hull triangles the envelope rejects, until none is left.
///
/// Two tests, both exact consequences of the envelope on a convex surface, where every
/// half-space H_m = {x : sigma n_m.(x - p_m) >= 0} bounds the convex body:
/// - the triangle's vertex T_i ∩ T_j ∩ T_k must lie in H_m for every point m nearby (its
///   points' neighbours and their neighbours); a vertex cut off by another plane is not on
///   the envelope at all;
/// - for a hull edge (i, j) of triangle (i, j, k), the facet edge T_i ∩ T_j runs from the
///   vertex outwards, away from k; on the envelope that ray must stay in H_k, i.e.
///   sigma n_k . d > 0 for its direction d.
///
/// Either failure means parameter space and the envelope disagree about the hull (typically
/// for slivers along the boundary): the triangle is dropped, so that its other edges become
/// hull edges, and the triangles behind them are tested in turn. A triangle is kept if
/// dropping it would leave a point without triangles.
fn trim_hull(tri: &mut DualTriangulation, input: &NeighbourInput<'_>) -> usize {
    let mut removed: Vec<bool> = Vec::new();
    let mut triangle_count: Vec<u32> = Vec::new();
    let mut rings = Rings::default();
    let mut queue: Vec<u32> = (0..tri.len() as u32)
        .filter(|&t| tri.neighbours[t as usize].contains(&NO_TRIANGLE))
        .collect();
    queue.reverse();
    let mut trims = 0;
    while let Some(t) = queue.pop() {
        if removed.get(t as usize).copied().unwrap_or(false)
            || !hull_rejected(tri, input, &mut rings, t as usize)
        {
            continue;
        }
        if triangle_count.is_empty() {
            // First trim: the per-point counts (never needed when nothing is trimmed).
            triangle_count = vec![0u32; input.plane_uv.len()];
            for tv in &tri.triangles {
                for &v in tv {
                    triangle_count[v as usize] += 1;
                }
            }
            removed = vec![false; tri.len()];
        }
        let vertices = tri.triangles[t as usize];
        if vertices.iter().any(|&v| triangle_count[v as usize] <= 1) {
            continue;
        }
        removed[t as usize] = true;
        trims += 1;
        for &v in &vertices {
            triangle_count[v as usize] -= 1;
        }
        for k in 0..3 {
            let other = tri.neighbours[t as usize][k];
            if other == NO_TRIANGLE {
                continue;
            }
            rings.remember(tri, other);
            rings.remember(tri, t);
            for n in tri.neighbours[other as usize].iter_mut() {
                if *n == t {
                    *n = NO_TRIANGLE;
                }
            }
            tri.neighbours[t as usize][k] = NO_TRIANGLE;
            queue.push(other);
        }
    }
    if trims > 0 {
        tri.remove_triangles(&removed);
    }
    trims
}

/// Point neighbourhoods of the triangulation as it was before trimming, computed on demand
/// (only around the hull) by walking fans; trimming changes adjacency, so the neighbours of
/// a triangle are saved before its first change.
#[derive(Default)]
struct Rings {
    /// Sorted neighbour lists of the points asked for.
    lists: IndexMap<u32, Vec<u32>>,
    /// A triangle holding each point met so far.
    holder: IndexMap<u32, u32>,
    /// Neighbours of changed triangles before their first change.
    original: IndexMap<u32, [u32; 3]>,
}

impl Rings {
    fn remember(&mut self, tri: &DualTriangulation, t: u32) {
        self.original.entry(t).or_insert(tri.neighbours[t as usize]);
    }

    fn neighbours_of(&self, tri: &DualTriangulation, t: u32) -> [u32; 3] {
        self.original
            .get(&t)
            .copied()
            .unwrap_or(tri.neighbours[t as usize])
    }

    /// The sorted neighbours of point v, which triangle `start` holds.
    fn ring(&mut self, tri: &DualTriangulation, v: u32, start: u32) -> &[u32] {
        if !self.lists.contains_key(&v) {
            let mut list = Vec::new();
            for direction in [1usize, 2] {
                let mut t = start;
                for _ in 0..=tri.len() {
                    let vertices = tri.triangles[t as usize];
                    let Some(k) = vertices.iter().position(|&x| x == v) else {
                        break;
                    };
                    for &other in &[vertices[(k + 1) % 3], vertices[(k + 2) % 3]] {
                        list.push(other);
                        self.holder.entry(other).or_insert(t);
                    }
                    let next = self.neighbours_of(tri, t)[(k + direction) % 3];
                    if next == NO_TRIANGLE || next == start {
                        break;
                    }
                    t = next;
                }
            }
            list.sort_unstable();
            list.dedup();
            self.lists.insert(v, list);
        }
        &self.lists[&v]
    }

    /// The neighbours of the neighbours of `vertices` (of one triangle t), and those
    /// neighbours themselves, as in the adjacency lists of the whole structure.
    fn second_ring(&mut self, tri: &DualTriangulation, t: u32, vertices: [u32; 3]) -> Vec<u32> {
        let mut out = Vec::new();
        for &v in &vertices {
            let first: Vec<u32> = self.ring(tri, v, t).to_vec();
            for m in first {
                let start = self.holder.get(&m).copied().unwrap_or(t);
                out.push(m);
                out.extend_from_slice(self.ring(tri, m, start));
            }
        }
        out
    }
}

/// Whether the envelope rejects hull triangle t (see [`trim_hull`]).
fn hull_rejected(
    tri: &DualTriangulation,
    input: &NeighbourInput<'_>,
    rings: &mut Rings,
    t: usize,
) -> bool {
    let vertices = tri.triangles[t];
    let side = input.convex_side[vertices[0] as usize];
    if side == 0
        || vertices
            .iter()
            .any(|&v| input.convex_side[v as usize] != side)
    {
        return false;
    }
    let s = f64::from(side);
    let planes = input.planes;
    let vertex = three_plane_vertex(planes, vertices);
    let size = (0..3)
        .map(|k| {
            planes[vertices[k] as usize]
                .point
                .distance(planes[vertices[(k + 1) % 3] as usize].point)
        })
        .fold(0.0, f64::max);
    let tolerance = ENVELOPE_FLIP_TOLERANCE * size;
    // Three (numerically) collinear planes along a straight stretch of the hull meet at
    // infinity: such a sliver holds no vertex of the envelope.
    let centroid = vertices
        .iter()
        .fold(DVec3::ZERO, |acc, &v| acc + planes[v as usize].point)
        / 3.0;
    if !vertex.is_finite() || vertex.distance(centroid) > DEGENERATE_SLIVER_FACTOR * size {
        return true;
    }
    let cut_off = rings
        .second_ring(tri, t as u32, vertices)
        .into_iter()
        .any(|x| {
            input.convex_side[x as usize] == side
                && s * planes[x as usize].signed_distance(vertex) < -tolerance
        });
    if cut_off {
        return true;
    }
    (0..3).any(|k| {
        if tri.neighbours[t][k] != NO_TRIANGLE {
            return false;
        }
        let [c, a, b] = rotated(vertices, k);
        let (pa, pb, pc) = (
            &input.planes[a as usize],
            &input.planes[b as usize],
            &input.planes[c as usize],
        );
        let Some(line) = pa.normal.cross(pb.normal).try_normalize() else {
            return false;
        };
        let chord = pb.point - pa.point;
        let mut away = (pa.point + pb.point) * 0.5 - pc.point;
        away -= chord * (away.dot(chord) / chord.length_squared().max(f64::MIN_POSITIVE));
        let outward = if line.dot(away) < 0.0 { -line } else { line };
        s * pc.normal.dot(outward) < 0.0
    })
}

/// Lawson's flip loop with the given illegality test. Returns (flips, unresolved).
///
/// Every interior edge is tested once in triangle order; after each flip the four outer edges
/// of the flipped quad are tested (last in, first out) before the next edge in order. The
/// first tests of all edges are done in parallel up front: an edge whose two triangles no
/// flip has touched yet reads nothing a flip changes, so its result stands. An edge whose
/// triangles changed is found again by its two points (kept for the few changed triangles).
///
/// With `stages`, the neighbour stage starts with the interior edges as its total, and each
/// edge of the loop counts as one item when its turn comes.
fn flip_until_stable(
    tri: &mut DualTriangulation,
    embedding: &[[f64; 2]],
    illegal: impl Fn(&DualTriangulation, usize, usize) -> bool + Sync,
    stages: Option<&Stages<'_>>,
) -> (usize, usize) {
    use rayon::prelude::*;
    // Interior edges in triangle order, as (triangle << 2 | side).
    let initial: Vec<u32> = {
        let mut v = Vec::with_capacity(tri.len() * 3 / 2 + 1);
        for t in 0..tri.len() {
            for k in 0..3 {
                let other = tri.neighbours[t][k];
                if other != NO_TRIANGLE && (other as usize) > t {
                    v.push(((t as u32) << 2) | k as u32);
                }
            }
        }
        v
    };
    if let Some(stages) = stages {
        stages.enter(Stage::Neighbours, Some(initial.len()));
    }
    let mut tally = Tally::new(
        stages.map_or(&NoProgress, Stages::observer),
        Stage::Neighbours,
    );
    let first_tests: Vec<bool> = {
        let tri_ref: &DualTriangulation = tri;
        initial
            .par_iter()
            .map(|&e| illegal(tri_ref, (e >> 2) as usize, (e & 3) as usize))
            .collect()
    };
    let mut dirty = vec![false; tri.len()];
    // The vertices of changed triangles before their first change.
    let mut original: IndexMap<u32, [u32; 3]> = IndexMap::default();
    let budget = 20 * tri.len() + 100;
    let mut flips = 0;
    let mut unresolved = 0;
    let mut incident: Vec<u32> = Vec::new();
    let mut stack: Vec<(u32, u32)> = Vec::new();
    for (n, &e) in initial.iter().enumerate() {
        tally.add(1);
        let (t0, k0) = ((e >> 2) as usize, (e & 3) as usize);
        let mut next: Option<(u32, u32, Option<bool>)> = {
            let other = tri.neighbours[t0][k0];
            if !dirty[t0] && other != NO_TRIANGLE && !dirty[other as usize] {
                let tv = tri.triangles[t0];
                Some((tv[(k0 + 1) % 3], tv[(k0 + 2) % 3], Some(first_tests[n])))
            } else {
                let tv = original
                    .get(&(t0 as u32))
                    .copied()
                    .unwrap_or(tri.triangles[t0]);
                Some((tv[(k0 + 1) % 3], tv[(k0 + 2) % 3], None))
            }
        };
        while let Some((a, b, known)) = next
            .take()
            .or_else(|| stack.pop().map(|(a, b)| (a, b, None)))
        {
            let (t, k, verdict) = match known {
                Some(verdict) => (t0, k0, verdict),
                None => {
                    if incident.is_empty() {
                        incident = tri.incident_triangles(embedding.len());
                    }
                    let Some((t, k)) = find_edge(tri, &incident, a, b) else {
                        continue;
                    };
                    (t, k, illegal(tri, t, k))
                }
            };
            if !verdict {
                continue;
            }
            let t2 = tri.neighbours[t][k];
            let [c, a, b] = rotated(tri.triangles[t], k);
            let k2 = tri.neighbours[t2 as usize]
                .iter()
                .position(|&x| x as usize == t)
                .unwrap_or(0);
            let d = tri.triangles[t2 as usize][k2];
            let e = embedding;
            let convex = orient2d(e[c as usize], e[a as usize], e[d as usize]) > 0.0
                && orient2d(e[d as usize], e[b as usize], e[c as usize]) > 0.0;
            if !convex || flips >= budget {
                unresolved += 1;
                continue;
            }
            original.entry(t as u32).or_insert(tri.triangles[t]);
            original.entry(t2).or_insert(tri.triangles[t2 as usize]);
            if incident.is_empty() {
                incident = tri.incident_triangles(embedding.len());
            }
            let (t1, t2) = tri.flip(t as u32, k);
            dirty[t1 as usize] = true;
            dirty[t2 as usize] = true;
            flips += 1;
            for v in [c, a, d] {
                incident[v as usize] = t1;
            }
            incident[b as usize] = t2;
            stack.extend_from_slice(&[(a, c), (c, b), (b, d), (d, a)]);
        }
    }
    (flips, unresolved)
}

/// Finds the triangle and opposite position of the interior edge (a, b), if it still exists,
/// by walking the triangles around a (both ways from a known incident triangle).
fn find_edge(tri: &DualTriangulation, incident: &[u32], a: u32, b: u32) -> Option<(usize, usize)> {
    let start = incident[a as usize];
    if start == NO_TRIANGLE {
        return None;
    }
    // Direction 1 steps counter-clockwise around a, direction 2 clockwise.
    for step in [1usize, 2] {
        let mut t = start;
        for _ in 0..=tri.len() {
            let vertices = tri.triangles[t as usize];
            let p = vertices.iter().position(|&v| v == a)?;
            // Directed edge a -> v(p+1) is opposite v(p+2).
            if vertices[(p + 1) % 3] == b {
                let k = (p + 2) % 3;
                return (tri.neighbours[t as usize][k] != NO_TRIANGLE).then_some((t as usize, k));
            }
            let next = tri.neighbours[t as usize][(p + step) % 3];
            if next == NO_TRIANGLE || next == start {
                break;
            }
            t = next;
        }
    }
    None
}

fn rotated(x: [u32; 3], k: usize) -> [u32; 3] {
    [x[k], x[(k + 1) % 3], x[(k + 2) % 3]]
}

/// The four points (c, a, b, d) of the quad around the edge opposite vertex k of triangle t.
// Always inlined into the flip tests (the convex path's first tests call it once per edge):
// left to the compiler, it stopped being inlined there when the progress counting came in
// (+85 instructions an edge under callgrind).
#[inline(always)]
fn quad(tri: &DualTriangulation, t: usize, k: usize) -> [u32; 4] {
    let [c, a, b] = rotated(tri.triangles[t], k);
    let t2 = tri.neighbours[t][k] as usize;
    let d = tri.opposite(t2, t as u32).unwrap_or(tri.triangles[t2][0]);
    [c, a, b, d]
}

/// In-circle test in the averaged curvature-compensation metric.
fn compensation_illegal(
    tri: &DualTriangulation,
    input: &NeighbourInput<'_>,
    t: usize,
    k: usize,
) -> bool {
    let ids = quad(tri, t, k);
    let geo = ids.map(|i| &input.geometry[i as usize]);
    let mean_normal = geo.iter().fold(DVec3::ZERO, |acc, g| acc + g.normal);
    let Some(normal) = mean_normal.try_normalize() else {
        return false;
    };
    let e1 = (geo[0].d1 - normal * geo[0].d1.dot(normal))
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    let e2 = normal.cross(e1);
    // Metric G = sum |k| (d.e)(d.e)^T over the four points, in the frame (e1, e2).
    let mut g = [0.0f64; 3];
    let mut largest = 0.0f64;
    let mut developable = true;
    for point in &geo {
        largest = largest.max(point.k1.abs()).max(point.k2.abs());
        developable &= flat_curvatures(point.k1, point.k2);
        for (kappa, dir) in [(point.k1.abs(), point.d1), (point.k2.abs(), point.d2)] {
            let (x, y) = (dir.dot(e1), dir.dot(e2));
            g[0] += kappa * x * x;
            g[1] += kappa * x * y;
            g[2] += kappa * y * y;
        }
    }
    let trace = g[0] + g[2];
    if !(trace > 0.0) || !trace.is_finite() {
        g = [1.0, 0.0, 1.0];
    } else if input.any_curvature {
        // The four points' sum of |k| d d^T plus, per point, the isotropic term; a small one
        // across a developable quad, whose planes differ only across the rulings.
        let weight = if developable {
            DEVELOPABLE_METRIC_REGULARISATION
        } else {
            input.metric_regularisation
        };
        g[0] += 4.0 * weight * largest;
        g[2] += 4.0 * weight * largest;
    } else {
        g[0] += CONVEX_METRIC_REGULARISATION * trace;
        g[2] += CONVEX_METRIC_REGULARISATION * trace;
    }
    // Cholesky G = L L^T, coordinates x' = L^T x.
    let l11 = g[0].sqrt();
    let l21 = g[1] / l11;
    let l22 = (g[2] - l21 * l21).max(0.0).sqrt();
    let origin = geo[0].point;
    let map = |p: DVec3| {
        let r = p - origin;
        let (x, y) = (r.dot(e1), r.dot(e2));
        [l11 * x + l21 * y, l22 * y]
    };
    let [c, a, b, d] = geo.map(|g| map(g.point));
    // Triangle (c, a, b) must be counter-clockwise in this frame for the test to mean anything.
    if orient(c, a, b) <= 0.0 || orient(d, b, a) <= 0.0 {
        return false;
    }
    // Ties (four points on one metric circle, e.g. a square grid where |II| is isotropic) are
    // left alone: a flip there only follows rounding.
    let scale = [a, b, d]
        .iter()
        .map(|p| (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2))
        .fold(0.0, f64::max);
    let tie = if input.any_curvature {
        COMPENSATION_TIE_TOLERANCE * scale * scale
    } else {
        0.0
    };
    in_circle(c, a, b, d) > tie
}

/// Positive when d lies strictly inside the circle through the counter-clockwise a, b, c.
pub(crate) fn in_circle(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    let (adx, ady) = (a[0] - d[0], a[1] - d[1]);
    let (bdx, bdy) = (b[0] - d[0], b[1] - d[1]);
    let (cdx, cdy) = (c[0] - d[0], c[1] - d[1]);
    let ad = adx * adx + ady * ady;
    let bd = bdx * bdx + bdy * bdy;
    let cd = cdx * cdx + cdy * cdy;
    adx * (bdy * cd - bd * cdy) - ady * (bdx * cd - bd * cdx) + ad * (bdx * cdy - bdy * cdx)
}

/// The envelope test on a strictly convex quad.
fn envelope_illegal(
    tri: &DualTriangulation,
    input: &NeighbourInput<'_>,
    t: usize,
    k: usize,
) -> bool {
    envelope_quad_illegal(input.planes, input.convex_side, quad(tri, t, k))
}

/// The envelope test on the quad (c, a, b, d) around the edge (a, b): true where T_d cuts
/// off the vertex T_a ∩ T_b ∩ T_c and T_c the vertex T_a ∩ T_b ∩ T_d (beyond the tolerance).
/// The three planes of each vertex are taken in ascending index order.
pub(crate) fn envelope_quad_illegal(
    planes: &[Plane],
    convex_side: &[i8],
    [c, a, b, d]: [u32; 4],
) -> bool {
    let side = convex_side[c as usize];
    if side == 0 || [a, b, d].iter().any(|&i| convex_side[i as usize] != side) {
        return false;
    }
    let size = [a, b, d]
        .iter()
        .map(|&i| planes[i as usize].point.distance(planes[c as usize].point))
        .fold(0.0, f64::max);
    let tolerance = ENVELOPE_FLIP_TOLERANCE * size;
    let s = f64::from(side);
    let outside = |mut x: [u32; 3], other: u32| {
        x.sort_unstable();
        let vertex = intersect_three(
            &planes[x[0] as usize],
            &planes[x[1] as usize],
            &planes[x[2] as usize],
        )
        .point;
        let distance = s * planes[other as usize].signed_distance(vertex);
        vertex.is_finite() && distance < -tolerance
    };
    outside([a, b, c], d) && outside([a, b, d], c)
}

/// The meeting point of the tangent planes of three points, in canonical (ascending) order.
pub(crate) fn three_plane_vertex(planes: &[Plane], mut ids: [u32; 3]) -> DVec3 {
    ids.sort_unstable();
    intersect_three(
        &planes[ids[0] as usize],
        &planes[ids[1] as usize],
        &planes[ids[2] as usize],
    )
    .point
}

/// Whether flipping the edge opposite vertex k of triangle t would cut real points (below
/// `real_count`) off from the others: the edge joins two real points a and b, the quad's
/// other two points are ghosts (a real one would keep a and b linked through it), and a
/// search over real edges from a, not using the edge, does not reach b before it has visited
/// all the real points it can reach (a or b cut off with at most [`REAL_LINK_SEARCH`] real
/// points). Such a flip is not made, whatever the criterion says: a seed near a corner, whose
/// ghosts across both sides stand a fraction of a spacing away, is near all of them in the
/// |II| metric, and flips towards them would close its facet by ghost planes alone, a panel
/// apart from the mesh (a mixed roof with a hex pattern whose seed sits 0.0014 and 0.0054
/// from a corner in parameters); two seeds of a top row near a corner went apart together,
/// an island of two facets (an unseen mixed surface, seed 55, hex 300).
fn isolates_real_points(tri: &DualTriangulation, t: usize, k: usize, real_count: usize) -> bool {
    let [c, a, b, d] = quad(tri, t, k);
    let real = |x: u32| (x as usize) < real_count;
    if !(real(a) && real(b)) || real(c) || real(d) {
        return false;
    }
    // Each end's real component without the edge, searched up to REAL_LINK_SEARCH points:
    // Some(true) where it is exhausted without meeting the other end, Some(false) where it
    // meets it, None where the search stops first.
    let mut fan = Vec::new();
    let mut cut_off = |from: u32, to: u32| {
        let mut visited: Vec<u32> = vec![from];
        let mut queue: std::collections::VecDeque<(u32, u32)> =
            std::iter::once((from, t as u32)).collect();
        while let Some((x, start)) = queue.pop_front() {
            tri.fan(x, start, &mut fan);
            for &s in &fan {
                for &y in &tri.triangles[s as usize] {
                    let the_edge = (x, y) == (from, to);
                    if y == x || !real(y) || the_edge || visited.contains(&y) {
                        continue;
                    }
                    if y == to {
                        return Some(false);
                    }
                    if visited.len() >= REAL_LINK_SEARCH {
                        return None;
                    }
                    visited.push(y);
                    queue.push_back((y, s));
                }
            }
        }
        Some(true)
    };
    match cut_off(a, b) {
        Some(cut) => cut,
        None => cut_off(b, a) == Some(true),
    }
}
