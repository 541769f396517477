//! Validity flips: the last step of the neighbour decision on surfaces that are not convex
//! everywhere (saddles, mixed curvature).
//!
//! Where K < 0 there is no envelope to define the right neighbours. The curvature-compensated
//! Delaunay triangulation ([`crate::neighbours`]) is the right start: on a locally quadratic
//! surface z = x^T II x / 2 the top view of the vertex T_i ∩ T_j ∩ T_k is the circumcentre of
//! (p_i, p_j, p_k) in the metric II, so Delaunay triangles in |II| keep those centres near their
//! triangles. But II is indefinite, its "circles" are hyperbolas, and a few triangles still give
//! centres far from their seeds: the facets around them turn non-simple or fold over a
//! neighbour. Those facets are repaired here by edge flips chosen by the facets themselves.
//!
//! For an interior facet i (its fan of dual triangles closes), its polygon is the sequence of
//! the vertices T_i ∩ T_j ∩ T_k of the triangles around i, counter-clockwise. It is *valid*
//! when (DESIGN.md, item 8)
//! - it is simple and counter-clockwise in its own plane T_i (frame (e1, e2, n_i)), and
//! - it does not overlap a facet that shares an edge with it: projected along the mean of the
//!   two normals, no edge of one crosses a non-shared edge of the other properly and no
//!   vertex of one lies strictly inside the other.
//!
//! A round visits the invalid facets in index order. For each, the edges of its star (i, j)
//! and of its link (j, k) are tried one by one: the edge is flipped (a topological move: the
//! structure stays a triangulated disc whatever the quad's shape in the plane, since facet
//! loops follow adjacency; only a flip whose new diagonal exists already is refused), the
//! invalid facets among those the flip can change (the quad's four points and their
//! neighbours) are counted before and after, and the flip is kept only if the count drops.
//! Every kept flip lowers the number of invalid facets, so the loop ends; it is bounded by
//! [`MAX_VALIDITY_ROUNDS`] rounds in any case.
//!
//! Single flips that must each pay get stuck where a facet needs two: on saddles with
//! irregular patterns (Poisson-disk, jittered) most of the facets they leave are of that
//! kind. So then, for each facet i still invalid, a *detour*: one star or link edge of i is
//! flipped although that alone does not pay, the invalid facets around it get
//! [`DETOUR_REPAIR_PASSES`] passes of single-flip repairs, and the whole sequence is kept if
//! it leaves fewer invalid facets than before, or undone (a journal of the flips and
//! verdicts). Rounds until no detour is kept; the detours tried are counted against
//! [`DETOUR_BUDGET`] per point plus [`DETOUR_BUDGET_FLOOR`], so uniform random points (many
//! facets no flip sequence repairs with exact planes) cost a bounded amount. A detour's cost
//! grows with the square of the fans it touches, and around runaway vertices of nearly
//! parallel planes (parabolic lines) fans of a hundred triangles occur: so the work of
//! judging facets is counted too (edges of the polygons built, products of the edge counts
//! of the pairs tested for overlap), and the detours also stop at [`DETOUR_WORK_BUDGET`] per
//! point plus [`DETOUR_WORK_BUDGET_FLOOR`].
//!
//! Where the single detours leave at most [`PAIR_DETOUR_MAX_INVALID`] facets, *pair
//! detours* flip two star or link edges of a facet together before the repairs. A facet
//! whose ring holds seeds of both signs of Gaussian curvature (a parabolic line runs through
//! it: neighbouring planes nearly parallel, often beyond repair with exact planes) gets at
//! most [`PAIR_DETOUR_PARABOLIC_TRIES`] of them, so that the budget goes to the facets that
//! can be repaired. On a surface of one sign of K (a saddle) no facet is limited.
//!
//! Last, a triangle whose vertex is *unreachable* (the planes of two of its points parallel,
//! or all three parallel to one line: on a parabolic line of a symmetric surface, seeds
//! mirrored about it have exactly parallel planes) is flipped away whatever the verdicts
//! ([`State::flip_unreachable`]): the facet stage would replace its vertex by a stand-in per
//! facet edge, which cuts a hole, and the mesh must stay a disc with its invalid facets
//! flagged. Of its three edges the flip kept is the one that leaves the fewest unreachable
//! triangles in its quad (fewer than before), then the fewest invalid facets around it.
//!
//! With exact planes a search ends with a pass over the triangles whose vertex has run away
//! (beyond [`RUNAWAY_SPACINGS`] local spacings from one of its seeds): an edge of such a
//! triangle is flipped where the summed excess over that limit drops and no more facets are
//! invalid around it ([`bring_in_runaways`]).
//!
//! Facets on the hull (open fans) are built with the boundary later ([`crate::facets`]);
//! they are not judged here.

// NaN-safe negated comparisons are intended: a NaN area or length must fail the test.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use std::borrow::Cow;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::{DVec2, DVec3};

use crate::diffgeo::LocalGeometry;
use crate::facets::reachable;
use crate::planes::{meeting_point, Plane};
use crate::tolerance::{
    DETOUR_BUDGET, DETOUR_BUDGET_FLOOR, DETOUR_REPAIR_PASSES, DETOUR_WORK_BUDGET,
    DETOUR_WORK_BUDGET_FLOOR, ISOTROPIC_FLIP_TIE, MAX_VALIDITY_ROUNDS, PAIR_DETOUR_BUDGET,
    PAIR_DETOUR_BUDGET_FLOOR, PAIR_DETOUR_MAX_INVALID, PAIR_DETOUR_PARABOLIC_TRIES,
    RUNAWAY_EXCESS_MARGIN, RUNAWAY_REACH, RUNAWAY_SPACINGS, UNREACHABLE_RUNAWAY_SPACINGS,
    VALIDITY_TOLERANCE,
};
use crate::triangulation::{DualTriangulation, Fan, NO_TRIANGLE};

/// A score of a flip's neighbourhood ([`State::try_flip_scored`]): of the triangulation, its
/// incident triangle per point and the flip's quad points.
pub(crate) type FlipScore<'s> = dyn FnMut(&DualTriangulation, &[u32], &[u32; 4]) -> f64 + 's;

/// What the validity flips did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct ValidityFlipStats {
    /// Flips kept.
    pub flips: usize,
    /// Interior facets still invalid by the local test afterwards.
    pub unresolved: usize,
}

/// Repairs invalid interior facets of the points `0..judged` by flips (module doc).
/// `embedding` holds the triangulation's points (ghosts included); `planes` the tangent
/// planes of all of them; `gaussian_signs` the sign of the Gaussian curvature at each of
/// them ([`gaussian_signs`]; empty: unknown, no facet's pair detours limited). Once `stop`
/// is set the search ends at its next step.
///
/// With `runaway_limit` (exact planes), where the repairs leave facets reaching farther from
/// their seeds than [`RUNAWAY_REACH`] times the seeds' diagonal or [`RUNAWAY_SPACINGS`] local
/// spacings (runaway vertices of nearly parallel planes, which the repairs make as often as
/// they meet them), the search runs again from the same triangulation with such facets
/// counted as invalid, and that outcome is kept if it leaves fewer runaways and no more
/// facets invalid (judged without the limit), or fewer facets flawed (invalid or runaway or
/// both), and in either case no facet reaching farther: a facet reaching beyond the whole
/// patch (up to 2e4 times its diagonal was seen) is no more use to a builder than a
/// self-intersecting one, both are flagged, and trading one for the other is no loss. Each
/// search then ends with [`bring_in_runaways`].
pub(crate) fn validity_flips(
    tri: &mut DualTriangulation,
    embedding: &[[f64; 2]],
    planes: &[Plane],
    judged: usize,
    gaussian_signs: &[i8],
    stop: Option<&AtomicBool>,
    runaway_limit: bool,
) -> ValidityFlipStats {
    let input = SearchInput {
        embedding,
        planes,
        gaussian_signs,
        judged,
        stop,
    };
    if !runaway_limit || judged == 0 {
        return search(tri, &input, None, false).stats;
    }
    let runaways = Runaways::of(tri, planes, judged, embedding.len());
    let original = tri.clone();
    let plain = search(tri, &input, Some(&runaways), false);
    if plain.runaways == 0 || is_set(stop) {
        return plain.stats;
    }
    let mut limited_tri = original;
    let limited = search(&mut limited_tri, &input, Some(&runaways), true);
    let fewer_runaways =
        limited.stats.unresolved <= plain.stats.unresolved && limited.runaways < plain.runaways;
    // Fewer facets flawed, but not at the price of one reaching farther (a count does not see
    // a facet traded for one a hundred times as far).
    let no_farther = limited.farthest <= plain.farthest.max(1.0);
    if (fewer_runaways || limited.flawed < plain.flawed) && no_farther {
        *tri = limited_tri;
        limited.stats
    } else {
        plain.stats
    }
}

/// The sign of the Gaussian curvature k1 k2 at each point (1, -1, or 0 where it vanishes).
pub(crate) fn gaussian_signs(geometry: &[LocalGeometry]) -> Vec<i8> {
    geometry
        .iter()
        .map(|g| match g.gaussian() {
            k if k > 0.0 => 1,
            k if k < 0.0 => -1,
            _ => 0,
        })
        .collect()
}

/// What a validity search reads ([`validity_flips`]'s arguments).
struct SearchInput<'a> {
    embedding: &'a [[f64; 2]],
    planes: &'a [Plane],
    gaussian_signs: &'a [i8],
    judged: usize,
    stop: Option<&'a AtomicBool>,
}

/// Whether `stop` is given and set.
fn is_set(stop: Option<&AtomicBool>) -> bool {
    stop.is_some_and(|stop| stop.load(Ordering::Relaxed))
}

/// What makes a facet a runaway ([`validity_flips`]): per point the reach beyond which it has
/// run away, the points whose facets are exempt, those closed by a ghost in the triangulation
/// the search starts from (they reach beyond the wall, where the facet stage clips them), and
/// the local spacing of every point.
struct Runaways {
    limits: Vec<f64>,
    walled: Vec<bool>,
    spacing: Vec<f64>,
}

impl Runaways {
    /// Per point the lesser of [`RUNAWAY_REACH`] times the diagonal of the seeds `0..judged`
    /// and [`RUNAWAY_SPACINGS`] local spacings, and the points of triangles with a ghost among
    /// the `points` of `tri`.
    fn of(tri: &DualTriangulation, planes: &[Plane], judged: usize, points: usize) -> Self {
        let (lo, hi) = crate::samples::bounding_box(planes[..judged].iter().map(|p| p.point));
        let mut walled = vec![false; points];
        for t in tri
            .triangles
            .iter()
            .filter(|t| t.iter().any(|&x| x as usize >= judged))
        {
            for &x in t {
                walled[x as usize] = true;
            }
        }
        let global = RUNAWAY_REACH * (hi - lo).length();
        let spacing = local_spacing(tri, planes, points);
        let limits = spacing
            .iter()
            .map(|&h| global.min(RUNAWAY_SPACINGS * h))
            .collect();
        Runaways {
            limits,
            walled,
            spacing,
        }
    }
}

/// What a validity search leaves: its statistics (with runaways measured, the facets
/// invalid judged without a reach limit), the runaways and the facets that are either (0
/// where none were measured).
struct Outcome {
    stats: ValidityFlipStats,
    runaways: usize,
    flawed: usize,
    /// The largest reach of a facet not exempt, over its limit.
    farthest: f64,
}

/// The validity search of [`validity_flips`]. With `runaways` the outcome counts them, and
/// with `limited` they also count as invalid during the search.
fn search(
    tri: &mut DualTriangulation,
    input: &SearchInput<'_>,
    runaways: Option<&Runaways>,
    limited: bool,
) -> Outcome {
    let n = input.judged;
    let mut state = State::new(tri, input.embedding.len(), Cow::Borrowed(input.planes), n);
    state.stop = input.stop;
    if let Some(r) = runaways.filter(|_| limited) {
        let limits = r
            .walled
            .iter()
            .zip(&r.limits)
            .map(|(&w, &l)| if w { f64::INFINITY } else { l })
            .collect();
        state.impose_reach_limit(limits);
    }
    let mut stats = ValidityFlipStats::default();
    // A facet whose repair failed is tried again only after a kept flip changed its
    // neighbourhood.
    let mut changed = vec![true; n];
    for _ in 0..MAX_VALIDITY_ROUNDS {
        let queue: Vec<u32> = (0..n as u32)
            .filter(|&i| state.invalid[i as usize] && changed[i as usize])
            .collect();
        if queue.is_empty() {
            break;
        }
        changed.iter_mut().for_each(|c| *c = false);
        let mut kept = 0;
        for i in queue {
            if state.stopped() {
                break;
            }
            if !state.invalid[i as usize] {
                continue;
            }
            if let Some(affected) = state.try_repair(i, n) {
                kept += 1;
                for x in affected {
                    changed[x as usize] = true;
                }
            }
        }
        stats.flips += kept;
        if kept == 0 {
            break;
        }
    }
    // What single flips cannot repair, a detour through a flip that does not pay may.
    // Counted, not timed (the result stays deterministic): uniform random points leave many
    // facets no flip sequence repairs, and the search stops there.
    let budget = (DETOUR_BUDGET * n as f64).ceil() as usize + DETOUR_BUDGET_FLOOR;
    state.work_budget = state
        .work
        .saturating_add(DETOUR_WORK_BUDGET.saturating_mul(n as u64))
        .saturating_add(DETOUR_WORK_BUDGET_FLOOR);
    'detours: for _ in 0..MAX_VALIDITY_ROUNDS {
        let mut kept = 0;
        for i in 0..n as u32 {
            if state.detours >= budget || state.work >= state.work_budget || state.stopped() {
                stats.flips += kept;
                break 'detours;
            }
            if state.invalid[i as usize] && state.try_detour(i, n) {
                kept += 1;
            }
        }
        stats.flips += kept;
        if kept == 0 {
            break;
        }
    }
    // What one detour cannot repair, two flips together may (pair detours: bounded apart),
    // where only a few facets are left (hex, grid and Poisson-disk patterns; not the many of
    // uniform random points, whose pair detours would trade invalid facets for runaway ones).
    let pairs = (PAIR_DETOUR_BUDGET * n as f64).ceil() as usize + PAIR_DETOUR_BUDGET_FLOOR;
    let left = state.invalid.iter().filter(|&&x| x).count();
    let rounds = if left <= PAIR_DETOUR_MAX_INVALID {
        MAX_VALIDITY_ROUNDS
    } else {
        0
    };
    let mut tried = 0;
    'pairs: for _ in 0..rounds {
        let mut kept = 0;
        for i in 0..n as u32 {
            if tried >= pairs || state.work >= state.work_budget || state.stopped() {
                stats.flips += kept;
                break 'pairs;
            }
            if !state.invalid[i as usize] {
                continue;
            }
            let most = if state.straddles_parabolic_line(i, input.gaussian_signs) {
                PAIR_DETOUR_PARABOLIC_TRIES
            } else {
                usize::MAX
            };
            if state.try_pair_detour(i, n, [pairs, most], &mut tried) {
                kept += 1;
            }
        }
        stats.flips += kept;
        if kept == 0 {
            break;
        }
    }
    stats.flips += state.flip_unreachable();
    if let Some(r) = runaways {
        // With a limit the verdicts count runaways as invalid: the last pass and the
        // search's outcome are judged without it.
        state.reach_limit = None;
        stats.flips += bring_in_runaways(&mut state, input.planes, &r.spacing);
    }
    stats.unresolved = state.invalid.iter().filter(|&&x| x).count();
    let mut outcome = Outcome {
        stats,
        runaways: 0,
        flawed: stats.unresolved,
        farthest: 0.0,
    };
    if let Some(r) = runaways {
        let (mut invalid, mut runaway, mut flawed) = (0, 0, 0);
        for i in 0..n as u32 {
            let bad = state.facet_invalid(i);
            let reach = if r.walled[i as usize] {
                0.0
            } else {
                state.reach(i, r.limits[i as usize])
            };
            let far = reach > 1.0;
            outcome.farthest = outcome.farthest.max(reach);
            invalid += usize::from(bad);
            runaway += usize::from(far);
            flawed += usize::from(bad || far);
        }
        outcome.stats.unresolved = invalid;
        outcome.runaways = runaway;
        outcome.flawed = flawed;
    }
    outcome
}

/// The triangulation being repaired with what the tests read: an incident triangle per point,
/// the vertex T_i ∩ T_j ∩ T_k of every triangle, and the verdict of every judged facet.
pub(crate) struct State<'a> {
    pub(crate) tri: &'a mut DualTriangulation,
    /// One incident triangle per point.
    pub(crate) incident: Vec<u32>,
    /// The planes of all points (borrowed by the flips, owned and edited by the plane
    /// adjustment, [`crate::adjusted_planes`]).
    pub(crate) planes: Cow<'a, [Plane]>,
    vertex: Vec<DVec3>,
    /// The verdict of every judged facet.
    pub(crate) invalid: Vec<bool>,
    /// Per judged facet, whether `invalid` holds its verdict (all but with
    /// [`State::unjudged`]).
    known: Vec<bool>,
    /// Vertices closer than this become one, as in the facet stage's welding.
    weld: f64,
    /// Points from this index on are ghosts: not judged, and not part of the mesh.
    judged: usize,
    /// Per point, its facet as last built (None: to build), renewed when a flip changes it.
    facets: Vec<Option<Facet>>,
    /// Per point, the overlap verdicts with neighbours computed so far.
    overlaps: Vec<Vec<(u32, bool)>>,
    /// Where Some, every plane replaced and every verdict set is logged here (old values)
    /// so that a tentative sequence of changes can be undone ([`State::undo`]).
    pub(crate) journal: Option<Journal>,
    /// Where Some, per point the farthest its facet's vertices may lie from its seed; a
    /// facet reaching farther counts as invalid (the plane adjustment pulls runaway vertices
    /// in; exact planes leave them, and the report names them).
    reach_limit: Option<Vec<f64>>,
    /// How many planes [`State::set_plane`] replaced (tried or kept): the plane adjustment's
    /// measure of work.
    pub(crate) plane_changes: usize,
    /// Where Some and set, the search ends at its next step ([`State::stopped`]): a
    /// speculative decision whose result is no longer wanted.
    pub(crate) stop: Option<&'a AtomicBool>,
    /// Detour flips tried ([`State::try_detour`]): the measure of their work.
    detours: usize,
    /// Work spent judging facets: the edges of every polygon built and the products of the
    /// edge counts of every pair tested for overlap ([`DETOUR_WORK_BUDGET`]).
    work: u64,
    /// The work at which detours stop, even within one facet's candidates.
    work_budget: u64,
    /// A fan buffer for the walks around points (taken and put back: no allocation per flip
    /// tried).
    fan: Vec<u32>,
    /// Buffers of forgotten facets, reused by the next facets built.
    polygon_pool: Vec<Vec<DVec3>>,
    neighbour_pool: Vec<Vec<(u32, [DVec3; 2])>>,
    /// Per point, the last `stamp` that collected it ([`State::affected_into`]).
    seen: Vec<u32>,
    stamp: u32,
}

/// The old values of what a tentative sequence of changes replaced, in order.
#[derive(Default)]
pub(crate) struct Journal {
    /// Planes replaced and flips made, in order (undone in reverse).
    changes: Vec<Change>,
    verdicts: Vec<(u32, bool)>,
}

/// One logged change of the triangulation or the planes.
enum Change {
    /// Point j's plane was replaced; this is the old one.
    Plane(u32, Plane),
    /// A flip made this edge (its points): undone by flipping it back.
    Flip(u32, u32),
}

impl Journal {
    /// How many more invalid facets there are now than before the journal began.
    pub(crate) fn invalid_gain(&self, state_invalid: &[bool]) -> isize {
        let mut seen = std::collections::HashMap::new();
        for &(x, old) in &self.verdicts {
            seen.entry(x).or_insert(old);
        }
        seen.iter()
            .map(|(&x, &old)| isize::from(state_invalid[x as usize]) - isize::from(old))
            .sum()
    }
}

/// A facet as the local test sees it.
struct Facet {
    /// Welded polygon, None where the fan does not close.
    polygon: Option<Vec<DVec3>>,
    /// Finite, simple and counter-clockwise in the seed's plane.
    simple: bool,
    /// The polygon's [`tangle`] (0 where simple, or where the fan does not close).
    tangle: usize,
    /// Real edge neighbours with the ends of the polygon edge shared with each.
    neighbours: Vec<(u32, [DVec3; 2])>,
}

impl<'a> State<'a> {
    /// The state of a triangulation of `points` points (ghosts from `judged` on) with every
    /// vertex computed and every judged facet's verdict.
    pub(crate) fn new(
        tri: &'a mut DualTriangulation,
        points: usize,
        planes: Cow<'a, [Plane]>,
        judged: usize,
    ) -> Self {
        let mut state = Self::new_with(tri, points, planes, judged);
        state.invalid = state.initial_verdicts(judged);
        state.known = vec![true; judged];
        state
    }

    /// The state with every vertex computed and no verdict.
    fn new_with(
        tri: &'a mut DualTriangulation,
        points: usize,
        planes: Cow<'a, [Plane]>,
        judged: usize,
    ) -> Self {
        use rayon::prelude::*;
        let (lo, hi) = crate::samples::bounding_box(planes[..judged].iter().map(|p| p.point));
        let weld = crate::tolerance::DEFAULT_WELD_TOLERANCE * (hi - lo).length();
        let vertex: Vec<DVec3> = tri
            .triangles
            .par_iter()
            .map(|&t| triangle_vertex(&planes, t))
            .collect();
        let incident = tri.incident_triangles(points);
        State {
            tri,
            incident,
            planes,
            vertex,
            invalid: Vec::new(),
            known: Vec::new(),
            weld,
            judged,
            facets: (0..points).map(|_| None).collect(),
            overlaps: vec![Vec::new(); points],
            journal: None,
            reach_limit: None,
            plane_changes: 0,
            stop: None,
            detours: 0,
            work: 0,
            work_budget: u64::MAX,
            fan: Vec::new(),
            polygon_pool: Vec::new(),
            neighbour_pool: Vec::new(),
            seen: vec![0; points],
            stamp: 0,
        }
    }

    /// As [`State::new`], but no facet judged yet: a verdict is made where a move first
    /// needs it ([`State::try_flip_scored`]), so that a few moves cost only their regions.
    pub(crate) fn unjudged(
        tri: &'a mut DualTriangulation,
        points: usize,
        planes: Cow<'a, [Plane]>,
        judged: usize,
    ) -> Self {
        let mut state = Self::new_with(tri, points, planes, judged);
        state.invalid = vec![false; judged];
        state.known = vec![false; judged];
        state
    }

    /// Whether the search was told to stop (`stop` set): its result will be dropped, so it
    /// may end wherever it is.
    pub(crate) fn stopped(&self) -> bool {
        is_set(self.stop)
    }

    /// Whether the plane changes passed `budget` or the search was told to stop.
    pub(crate) fn spent(&self, budget: usize) -> bool {
        self.plane_changes > budget || self.stopped()
    }

    /// Facet x's verdict, judged now if it is not known.
    fn verdict(&mut self, x: u32) -> bool {
        if !self.known[x as usize] {
            let v = self.facet_invalid(x);
            self.invalid[x as usize] = v;
            self.known[x as usize] = true;
        }
        self.invalid[x as usize]
    }

    /// From now on a facet whose vertices lie farther from its seed than `limits[i]` counts as
    /// invalid; the verdicts are renewed accordingly.
    pub(crate) fn impose_reach_limit(&mut self, limits: Vec<f64>) {
        self.reach_limit = Some(limits);
        for i in 0..self.judged as u32 {
            if !self.invalid[i as usize] && self.beyond_reach(i) {
                self.invalid[i as usize] = true;
            }
        }
    }

    /// Whether facet i reaches beyond its limit ([`State::impose_reach_limit`]).
    fn beyond_reach(&mut self, i: u32) -> bool {
        let Some(limit) = self.reach_limit.as_ref().map(|l| l[i as usize]) else {
            return false;
        };
        self.reach(i, limit) > 1.0
    }

    /// Sets the verdict of facet x (logged in the journal).
    pub(crate) fn set_verdict(&mut self, x: u32, invalid: bool) {
        if let Some(journal) = &mut self.journal {
            journal.verdicts.push((x, self.invalid[x as usize]));
        }
        self.invalid[x as usize] = invalid;
    }

    /// Undoes everything the journal logged and ends it.
    pub(crate) fn undo(&mut self) {
        let Some(journal) = self.journal.take() else {
            return;
        };
        for &(x, old) in journal.verdicts.iter().rev() {
            self.invalid[x as usize] = old;
        }
        for change in journal.changes.iter().rev() {
            match *change {
                Change::Plane(j, old) => self.set_plane(j, old),
                Change::Flip(c, d) => {
                    // Flipped back by its points: triangle labels and rotations need not be
                    // those the flip left once later flips were undone.
                    let mut fan = std::mem::take(&mut self.fan);
                    let edge = find_edge(self.tri, &self.incident, c, d, &mut fan);
                    self.fan = fan;
                    if let Some((t, k)) = edge {
                        self.flip(t as u32, k);
                    }
                }
            }
        }
    }

    /// How far facet i's polygon reaches from its seed: its farthest vertex's distance over
    /// `spacing`; infinite where a vertex is unreachable, 0 where the fan does not close.
    pub(crate) fn reach(&mut self, i: u32, spacing: f64) -> f64 {
        let seed = self.planes[i as usize].point;
        let facet = self.facet(i);
        facet.polygon.as_ref().map_or(0.0, |p| {
            p.iter()
                .map(|x| x.distance(seed) / spacing)
                .map(|r| if r.is_finite() { r } else { f64::INFINITY })
                .fold(0.0, f64::max)
        })
    }

    /// Facet i's [`tangle`] in its own plane (0 where its fan does not close).
    pub(crate) fn tangle(&mut self, i: u32) -> usize {
        self.facet(i).tangle
    }

    /// Replaces the plane of point j and renews the vertices of the triangles around it.
    pub(crate) fn set_plane(&mut self, j: u32, plane: Plane) {
        if let Some(journal) = &mut self.journal {
            journal
                .changes
                .push(Change::Plane(j, self.planes[j as usize]));
        }
        self.planes.to_mut()[j as usize] = plane;
        self.plane_changes += 1;
        let mut fan = std::mem::take(&mut self.fan);
        self.tri.fan(j, self.incident[j as usize], &mut fan);
        for &t in &fan {
            self.vertex[t as usize] = triangle_vertex(&self.planes, self.tri.triangles[t as usize]);
            for v in self.tri.triangles[t as usize] {
                self.forget(v);
            }
        }
        self.fan = fan;
    }

    /// Whether a flip just made among `points` touches a ghost (an index from `judged` on)
    /// and leaves one of them without its ghost neighbours in one run ([`Self::one_ghost_arc`]):
    /// such a flip would open a hole in the mesh and is undone.
    fn breaks_ghost_run(&self, points: &[u32], judged: usize) -> bool {
        points.iter().any(|&x| x as usize >= judged)
            && !points.iter().all(|&x| self.one_ghost_arc(x))
    }

    /// Whether point x keeps the mesh a disc around it: a real point has a real neighbour
    /// and its ghost neighbours in one run around it; a ghost's real neighbours are in one run.
    fn one_ghost_arc(&self, x: u32) -> bool {
        let mut fan = Vec::new();
        let kind = self.tri.fan(x, self.incident[x as usize], &mut fan);
        if kind == Fan::Broken {
            return false;
        }
        // Neighbours in order: the second point of each triangle, then the last one's third.
        let real: Vec<bool> = {
            let mut out: Vec<bool> = fan
                .iter()
                .map(|&t| {
                    let v = self.tri.triangles[t as usize];
                    (v[(v.iter().position(|&y| y == x).unwrap_or(0) + 1) % 3] as usize)
                        < self.judged
                })
                .collect();
            if kind == Fan::Open {
                if let Some(&last) = fan.last() {
                    let v = self.tri.triangles[last as usize];
                    out.push(
                        (v[(v.iter().position(|&y| y == x).unwrap_or(0) + 2) % 3] as usize)
                            < self.judged,
                    );
                }
            }
            out
        };
        let n = real.len();
        let closed = kind == Fan::Closed;
        // Runs of real neighbours (cyclic where the fan closes).
        let previous_real = |k: usize| {
            if k == 0 {
                closed && real[n - 1]
            } else {
                real[k - 1]
            }
        };
        let starts = (0..n).filter(|&k| real[k] && !previous_real(k)).count();
        let runs = if closed && real.iter().all(|&r| r) {
            1
        } else {
            starts
        };
        if (x as usize) < self.judged {
            runs == 1
        } else {
            runs <= 1
        }
    }

    /// Flips triangle t's edge opposite k and brings the caches up to date; returns the two
    /// triangles holding the new diagonal (the first at position 1 of the second).
    fn flip(&mut self, t: u32, k: usize) -> (u32, u32) {
        let (t1, t2) = self.tri.flip(t, k);
        if let Some(journal) = &mut self.journal {
            // The new diagonal is the edge opposite position 1 of t1 = [c, a, d].
            let [c, _, d] = self.tri.triangles[t1 as usize];
            journal.changes.push(Change::Flip(c, d));
        }
        for t in [t1, t2] {
            self.vertex[t as usize] = triangle_vertex(&self.planes, self.tri.triangles[t as usize]);
            for v in self.tri.triangles[t as usize] {
                self.incident[v as usize] = t;
                self.forget(v);
            }
        }
        (t1, t2)
    }

    /// Flips away the triangles whose vertex is unreachable (module doc: the planes of two of
    /// their points are parallel, or all three nearly meet in a line), whatever that does to
    /// the verdicts: the facet stage replaces such a vertex by a stand-in per edge, which
    /// leaves a hole in the mesh, and a disc with invalid facets flagged is better than a
    /// hole. For each such triangle with a judged point, its three edges are flipped in turn
    /// and the flip kept that leaves the fewest unreachable triangles in its quad (fewer than
    /// before), then the fewest invalid facets among those it can change; each kept flip
    /// lowers the number of unreachable triangles, so the pass ends. Returns the flips kept.
    pub(crate) fn flip_unreachable(&mut self) -> usize {
        let mut kept = 0;
        // Passes over the triangles until one keeps no flip: a flip reuses the numbers of
        // its two triangles, so a triangle it made may be one this pass has passed.
        loop {
            let before = kept;
            for t in 0..self.tri.len() as u32 {
                if self.flip_unreachable_at(t) {
                    kept += 1;
                }
            }
            if kept == before {
                return kept;
            }
        }
    }

    /// [`State::flip_unreachable`] for triangle t: whether a flip was kept.
    fn flip_unreachable_at(&mut self, t: u32) -> bool {
        let judged = self.judged;
        let unreachable = |state: &Self, t: u32| state.vertex[t as usize].is_nan();
        // The triangle's points: the slots of its edges' triangles change with each flip
        // tried and undone, the points do not.
        let v = self.tri.triangles[t as usize];
        if !unreachable(self, t) || v.iter().all(|&x| x as usize >= judged) {
            return false;
        }
        // (unreachable in the quad after, invalid facets around it after, the edge).
        let mut best: Option<(usize, usize, (u32, u32))> = None;
        for k in 0..3 {
            let (a, b) = (v[(k + 1) % 3], v[(k + 2) % 3]);
            let Some((t0, k0, quad)) = self.flippable(a, b) else {
                continue;
            };
            let other = self.tri.neighbours[t0][k0];
            let before =
                usize::from(unreachable(self, t0 as u32)) + usize::from(unreachable(self, other));
            let (t1, t2) = self.flip(t0 as u32, k0);
            let after = usize::from(unreachable(self, t1)) + usize::from(unreachable(self, t2));
            if after < before && !self.breaks_ghost_run(&quad, judged) {
                let mut region = Vec::with_capacity(AFFECTED_CAPACITY);
                self.affected_into(&quad, &mut region);
                let invalid = region
                    .iter()
                    .filter(|&&x| (x as usize) < judged && self.facet_invalid(x))
                    .count();
                if best.map_or(true, |(u, i, _)| (after, invalid) < (u, i)) {
                    best = Some((after, invalid, (a, b)));
                }
            }
            // Undo: the new diagonal is the edge opposite position 1 of t1.
            self.flip(t1, 1);
        }
        let Some((_, _, (a, b))) = best else {
            return false;
        };
        let Some((t0, k0, quad)) = self.flippable(a, b) else {
            return false;
        };
        self.flip(t0 as u32, k0);
        let mut region = Vec::with_capacity(AFFECTED_CAPACITY);
        self.affected_into(&quad, &mut region);
        for x in region {
            if (x as usize) < judged {
                let v = self.facet_invalid(x);
                self.set_verdict(x, v);
                self.known[x as usize] = true;
            }
        }
        true
    }

    /// Drops the cached facet of point v and every overlap verdict involving it.
    fn forget(&mut self, v: u32) {
        if let Some(facet) = self.facets[v as usize].take() {
            self.polygon_pool.extend(facet.polygon);
            self.neighbour_pool.push(facet.neighbours);
        }
        let mut list = std::mem::take(&mut self.overlaps[v as usize]);
        for &(other, _) in &list {
            self.overlaps[other as usize].retain(|&(x, _)| x != v);
        }
        list.clear();
        self.overlaps[v as usize] = list;
    }

    /// [`affected_points`] of `quad` into `out` (cleared first): sorted, each once, collected
    /// by marks so that only the distinct points are sorted.
    fn affected_into(&mut self, quad: &[u32], out: &mut Vec<u32>) {
        self.stamp = self.stamp.wrapping_add(1);
        if self.stamp == 0 {
            self.seen.iter_mut().for_each(|s| *s = 0);
            self.stamp = 1;
        }
        let stamp = self.stamp;
        out.clear();
        let mut fan = std::mem::take(&mut self.fan);
        for &p in quad {
            if self.seen[p as usize] != stamp {
                self.seen[p as usize] = stamp;
                out.push(p);
            }
        }
        // With the points of the triangles around the quad's points.
        for &p in quad {
            self.tri.fan(p, self.incident[p as usize], &mut fan);
            for &t in &fan {
                for x in self.tri.triangles[t as usize] {
                    if self.seen[x as usize] != stamp {
                        self.seen[x as usize] = stamp;
                        out.push(x);
                    }
                }
            }
        }
        self.fan = fan;
        out.sort_unstable();
    }

    /// Builds (or reuses) the facet of point i.
    fn facet(&mut self, i: u32) -> &Facet {
        if self.facets[i as usize].is_none() {
            let mut fan = std::mem::take(&mut self.fan);
            let mut buffer = self.polygon_pool.pop().unwrap_or_default();
            let polygon = if self.closed_polygon_into(i, &mut fan, &mut buffer) {
                Some(buffer)
            } else {
                self.polygon_pool.push(buffer);
                None
            };
            let tangle = polygon
                .as_ref()
                .map_or(0, |p| tangle(p, self.planes[i as usize].normal));
            self.work += polygon.as_ref().map_or(0, |p| p.len() as u64);
            let simple = polygon.is_some() && tangle == 0;
            let mut neighbours = self.neighbour_pool.pop().unwrap_or_default();
            neighbours.clear();
            if polygon.is_some() {
                neighbours.extend((0..fan.len()).filter_map(|k| {
                    let v = self.tri.triangles[fan[k] as usize];
                    let j = v[(v.iter().position(|&x| x == i).unwrap_or(0) + 1) % 3];
                    let ends = [
                        self.vertex[fan[(k + fan.len() - 1) % fan.len()] as usize],
                        self.vertex[fan[k] as usize],
                    ];
                    ((j as usize) < self.judged).then_some((j, ends))
                }));
            }
            self.fan = fan;
            self.facets[i as usize] = Some(Facet {
                polygon,
                simple,
                tangle,
                neighbours,
            });
        }
        self.facets[i as usize].as_ref().expect("built above")
    }

    /// Facet i's polygon (welded), None where its fan does not close.
    fn polygon(&self, i: u32, fan: &mut Vec<u32>) -> Option<Vec<DVec3>> {
        let mut polygon = Vec::new();
        self.closed_polygon_into(i, fan, &mut polygon)
            .then_some(polygon)
    }

    /// Facet i's polygon (welded) into `polygon` (cleared first); false where its fan does
    /// not close.
    fn closed_polygon_into(&self, i: u32, fan: &mut Vec<u32>, polygon: &mut Vec<DVec3>) -> bool {
        polygon.clear();
        if self.tri.fan(i, self.incident[i as usize], fan) != Fan::Closed {
            return false;
        }
        polygon.extend(fan.iter().map(|&t| self.vertex[t as usize]));
        weld_loop(polygon, self.weld);
        true
    }

    /// The verdicts of facets 0..n: every polygon built and tested for simplicity once, then
    /// every edge (i, j) of two simple closed facets tested for overlap once.
    fn initial_verdicts(&self, n: usize) -> Vec<bool> {
        use rayon::prelude::*;
        let polygons: Vec<Option<Vec<DVec3>>> = (0..n as u32)
            .into_par_iter()
            .map_init(Vec::new, |fan, i| self.polygon(i, fan))
            .collect();
        let simple: Vec<bool> = polygons
            .par_iter()
            .enumerate()
            .map(|(i, p)| {
                p.as_ref()
                    .map_or(true, |p| simple_in_plane(p, self.planes[i].normal))
            })
            .collect();
        let (polygons_ref, simple_ref) = (&polygons, &simple);
        let overlapping: Vec<(u32, u32)> = (0..self.tri.len())
            .into_par_iter()
            .flat_map_iter(|t| {
                let (polygons, simple) = (polygons_ref, simple_ref);
                let v = self.tri.triangles[t];
                (0..3).filter_map(move |k| {
                    let (i, j) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                    // Each undirected edge once: from its triangle with i < j.
                    if i > j || j as usize >= n {
                        return None;
                    }
                    let (pi, pj) = (
                        polygons[i as usize].as_ref()?,
                        polygons[j as usize].as_ref()?,
                    );
                    if !simple[i as usize] || !simple[j as usize] {
                        return None;
                    }
                    let normal = self.planes[i as usize].normal + self.planes[j as usize].normal;
                    let other = self.tri.neighbours[t][k];
                    let ends = [
                        self.vertex[t],
                        if other == NO_TRIANGLE {
                            self.vertex[t]
                        } else {
                            self.vertex[other as usize]
                        },
                    ];
                    (!separated(pi, pj, ends, normal) && polygons_overlap(pi, pj, normal))
                        .then_some((i, j))
                })
            })
            .collect();
        let mut invalid: Vec<bool> = simple.iter().map(|&s| !s).collect();
        for (i, j) in overlapping {
            invalid[i as usize] = true;
            invalid[j as usize] = true;
        }
        invalid
    }

    /// Whether interior facet i is invalid (module doc); hull facets are never judged.
    pub(crate) fn facet_invalid(&mut self, i: u32) -> bool {
        if self.beyond_reach(i) {
            return true;
        }
        let facet = self.facet(i);
        if facet.polygon.is_none() {
            return false;
        }
        if !facet.simple {
            return true;
        }
        // By index: judging a neighbour may build its facet, which needs `self` mutably.
        for n in 0..facet.neighbours.len() {
            let Some((j, ends)) = self.facets[i as usize].as_ref().map(|f| f.neighbours[n]) else {
                return false;
            };
            if let Some(&(_, verdict)) = self.overlaps[i as usize].iter().find(|&&(x, _)| x == j) {
                if verdict {
                    return true;
                }
                continue;
            }
            let other_simple = {
                let other = self.facet(j);
                other.polygon.is_some() && other.simple
            };
            let verdict = other_simple && {
                let normal = self.planes[i as usize].normal + self.planes[j as usize].normal;
                let (a, b) = (
                    self.facets[i as usize].as_ref(),
                    self.facets[j as usize].as_ref(),
                );
                let (a, b) = (
                    a.and_then(|f| f.polygon.as_ref()),
                    b.and_then(|f| f.polygon.as_ref()),
                );
                match (a, b) {
                    (Some(a), Some(b)) => {
                        self.work += (a.len() * b.len()) as u64;
                        !separated(a, b, ends, normal) && polygons_overlap(a, b, normal)
                    }
                    _ => false,
                }
            };
            self.overlaps[i as usize].push((j, verdict));
            self.overlaps[j as usize].push((i, verdict));
            if verdict {
                return true;
            }
        }
        false
    }

    /// Whether the ring of point i (the points of its triangles) holds a point whose Gaussian
    /// curvature has another sign than i's (`signs`; false where empty).
    fn straddles_parabolic_line(&mut self, i: u32, signs: &[i8]) -> bool {
        let Some(&own) = signs.get(i as usize) else {
            return false;
        };
        let mut fan = std::mem::take(&mut self.fan);
        self.tri.fan(i, self.incident[i as usize], &mut fan);
        let straddles = fan.iter().any(|&t| {
            self.tri.triangles[t as usize]
                .iter()
                .any(|&x| signs.get(x as usize).is_some_and(|&s| s != own))
        });
        self.fan = fan;
        straddles
    }

    /// The edges a repair of interior facet i tries, as point pairs: its star edges, then its
    /// link edges; None where its fan does not close.
    fn repair_candidates(&mut self, i: u32) -> Option<Vec<(u32, u32)>> {
        let mut fan = std::mem::take(&mut self.fan);
        let closed = self.tri.fan(i, self.incident[i as usize], &mut fan) == Fan::Closed;
        let candidates = closed.then(|| {
            let mut candidates: Vec<(u32, u32)> = Vec::with_capacity(2 * fan.len());
            for &t in &fan {
                let v = self.tri.triangles[t as usize];
                let k = v.iter().position(|&x| x == i).unwrap_or(0);
                let (j, m) = (v[(k + 1) % 3], v[(k + 2) % 3]);
                candidates.push((i, j));
                candidates.push((j, m));
            }
            candidates
        });
        self.fan = fan;
        candidates
    }

    /// The interior edge (a, b) as (triangle, opposite position, quad points (c, a, b, d))
    /// where it can be flipped. A flip is a topological move: the structure stays a
    /// triangulated disc whatever the quad's shape in the plane (facet loops follow
    /// adjacency, not positions), unless the new diagonal (c, d) exists already.
    fn flippable(&mut self, a: u32, b: u32) -> Option<(usize, usize, [u32; 4])> {
        let mut fan = std::mem::take(&mut self.fan);
        let flippable = find_edge(self.tri, &self.incident, a, b, &mut fan).and_then(|(t, k)| {
            let quad = quad_points(self.tri, t, k);
            let [c, _, _, d] = quad;
            (c != d && !has_edge(self.tri, &self.incident, c, d, &mut fan)).then_some((t, k, quad))
        });
        self.fan = fan;
        flippable
    }

    /// Where no single flip repairs facet i: a star or link edge of i flipped although it
    /// does not pay by itself, then single-flip repairs of the invalid facets around it
    /// ([`DETOUR_REPAIR_PASSES`] passes); the whole is kept when it leaves fewer invalid
    /// facets than before, and undone otherwise.
    fn try_detour(&mut self, i: u32, judged: usize) -> bool {
        let Some(candidates) = self.repair_candidates(i) else {
            return false;
        };
        for (a, b) in candidates {
            if self.work >= self.work_budget {
                return false;
            }
            let Some((t, k, quad)) = self.flippable(a, b) else {
                continue;
            };
            self.detours += 1;
            self.journal = Some(Journal::default());
            self.flip(t as u32, k);
            if self.breaks_ghost_run(&quad, judged) {
                self.undo();
                continue;
            }
            let mut region = Vec::with_capacity(AFFECTED_CAPACITY);
            self.affected_into(&quad, &mut region);
            region.retain(|&x| (x as usize) < judged);
            if self.settle_detour(&region, judged) {
                return true;
            }
        }
        false
    }

    /// The end of a detour whose flips are made (in the journal): the facets of `region` are
    /// judged again, the invalid ones get [`DETOUR_REPAIR_PASSES`] passes of single-flip
    /// repairs, and the whole is kept (true) when it leaves fewer invalid facets than before,
    /// undone (false) otherwise.
    fn settle_detour(&mut self, region: &[u32], judged: usize) -> bool {
        let mut targets = Vec::new();
        for &x in region {
            let v = self.facet_invalid(x);
            if v != self.invalid[x as usize] {
                self.set_verdict(x, v);
            }
            if v {
                targets.push(x);
            }
        }
        for _ in 0..DETOUR_REPAIR_PASSES {
            let mut any = false;
            for &x in &targets {
                if self.invalid[x as usize] && self.try_repair(x, judged).is_some() {
                    any = true;
                }
            }
            if !any {
                break;
            }
        }
        let gain = self
            .journal
            .as_ref()
            .map_or(0, |journal| journal.invalid_gain(&self.invalid));
        if gain < 0 {
            self.journal = None;
            return true;
        }
        self.undo();
        false
    }

    /// Where no detour repairs facet i: two of its star and link edges flipped together (the
    /// second chosen among the edges of i after the first), then single-flip repairs of the
    /// invalid facets around both quads ([`DETOUR_REPAIR_PASSES`] passes); kept when the whole
    /// leaves fewer invalid facets than before, undone otherwise. Each pair tried counts
    /// against `budget` (through `tried`), and at most `most` are tried for i.
    fn try_pair_detour(
        &mut self,
        i: u32,
        judged: usize,
        [budget, most]: [usize; 2],
        tried: &mut usize,
    ) -> bool {
        let Some(firsts) = self.repair_candidates(i) else {
            return false;
        };
        let before = *tried;
        for (a, b) in firsts {
            // The edges of i once (a, b) is flipped.
            let Some((t, k, _)) = self.flippable(a, b) else {
                continue;
            };
            self.journal = Some(Journal::default());
            self.flip(t as u32, k);
            let seconds = self.repair_candidates(i);
            self.undo();
            let Some(seconds) = seconds else {
                continue;
            };
            for (c, d) in seconds {
                if *tried >= budget || *tried - before >= most || self.work >= self.work_budget {
                    return false;
                }
                if (c, d) == (a, b) || (d, c) == (a, b) {
                    continue;
                }
                let Some((t, k, first)) = self.flippable(a, b) else {
                    break;
                };
                self.journal = Some(Journal::default());
                self.flip(t as u32, k);
                let Some((t2, k2, second)) = self.flippable(c, d) else {
                    self.undo();
                    continue;
                };
                *tried += 1;
                self.flip(t2 as u32, k2);
                let quads = [first, second];
                if self.breaks_ghost_run(quads.as_flattened(), judged) {
                    self.undo();
                    continue;
                }
                let mut region = Vec::with_capacity(2 * AFFECTED_CAPACITY);
                let mut more = Vec::with_capacity(AFFECTED_CAPACITY);
                self.affected_into(&first, &mut region);
                self.affected_into(&second, &mut more);
                region.extend(more);
                region.sort_unstable();
                region.dedup();
                region.retain(|&x| (x as usize) < judged);
                if self.settle_detour(&region, judged) {
                    return true;
                }
            }
        }
        false
    }

    /// Lawson flips of the star and link edges of point i by the Euclidean in-circle test of
    /// the points `seeds` projected on the plane perpendicular to `normal`: the isotropic
    /// Delaunay triangulation around i, which is what the neighbours tend to where the
    /// curvature vanishes (a parabolic line, where the |II| metric degenerates and its
    /// Delaunay edges run long). Only convex quads are flipped, around a ghost only where the
    /// ghosts stay in one run; at most `most` flips. Verdicts are not renewed (the caller
    /// judges the region). Returns the flips made.
    pub(crate) fn isotropic_flips_around(
        &mut self,
        i: u32,
        seeds: &[DVec3],
        normal: DVec3,
        most: usize,
    ) -> usize {
        let (e1, e2) = normal.any_orthonormal_pair();
        let origin = seeds[i as usize];
        let at = |x: u32| {
            let d = seeds[x as usize] - origin;
            DVec2::new(d.dot(e1), d.dot(e2))
        };
        let mut flips = 0;
        'passes: while flips < most {
            let Some(candidates) = self.repair_candidates(i) else {
                break;
            };
            for (a, b) in candidates {
                let Some((t, k, quad)) = self.flippable(a, b) else {
                    continue;
                };
                let [c, a, b, d] = quad;
                let (pc, pa, pb, pd) = (at(c), at(a), at(b), at(d));
                let cross = |o: DVec2, p: DVec2, q: DVec2| (p - o).perp_dot(q - o);
                // Convex quad: c and d strictly on opposite sides of ab, a and b of cd.
                let convex = cross(pa, pb, pc) * cross(pa, pb, pd) < 0.0
                    && cross(pc, pd, pa) * cross(pc, pd, pb) < 0.0;
                if !convex {
                    continue;
                }
                // d strictly inside the circle through c, a, b (orientation-corrected).
                let lift = |p: DVec2| {
                    let q = p - pd;
                    DVec3::new(q.x, q.y, q.length_squared())
                };
                let (qc, qa, qb) = (lift(pc), lift(pa), lift(pb));
                let in_circle = qc.dot(qa.cross(qb)) * cross(pc, pa, pb).signum();
                let scale = (pa - pb).length_squared().powi(2);
                if !(in_circle > ISOTROPIC_FLIP_TIE * scale) {
                    continue;
                }
                let (t1, _) = self.flip(t as u32, k);
                if self.breaks_ghost_run(&quad, self.judged) {
                    self.flip(t1, 1);
                    continue;
                }
                flips += 1;
                continue 'passes;
            }
            break;
        }
        flips
    }

    /// Flips the edge (a, b) where it can be flipped and keeps the flip when `score` (of the
    /// triangulation, the incident triangles and the quad's points (c, a, b, d)) drops by
    /// more than `margin` and no judged facet among those the flip can change turns invalid
    /// (with `trade`: no more of them are invalid than before) (verdicts renewed); otherwise
    /// the flip is undone. A flip touching a ghost must leave
    /// the ghosts in one run around every point of the quad. Returns whether it was kept.
    pub(crate) fn try_flip_scored(
        &mut self,
        a: u32,
        b: u32,
        margin: f64,
        trade: bool,
        blocked: &[bool],
        score: &mut FlipScore<'_>,
    ) -> Option<([u32; 4], Vec<u32>)> {
        let (t, k, quad) = self.flippable(a, b)?;
        if quad
            .iter()
            .any(|&x| (x as usize) < self.judged && blocked[x as usize])
        {
            return None;
        }
        let before = score(self.tri, &self.incident, &quad);
        // The facets a flip can change are the same points before and after it.
        let mut region = Vec::with_capacity(AFFECTED_CAPACITY);
        self.affected_into(&quad, &mut region);
        region.retain(|&x| (x as usize) < self.judged);
        for &x in &region {
            self.verdict(x);
        }
        self.journal = Some(Journal::default());
        self.flip(t as u32, k);
        if self.breaks_ghost_run(&quad, self.judged) {
            self.undo();
            return None;
        }
        let after = score(self.tri, &self.incident, &quad);
        if !(after < before - margin) {
            self.undo();
            return None;
        }
        let mut verdicts = Vec::with_capacity(region.len());
        for &x in &region {
            let v = self.facet_invalid(x);
            if !trade && v && !self.invalid[x as usize] {
                self.undo();
                return None;
            }
            verdicts.push(v);
        }
        if trade {
            let before = region.iter().filter(|&&x| self.invalid[x as usize]).count();
            if verdicts.iter().filter(|&&v| v).count() > before {
                self.undo();
                return None;
            }
        }
        self.journal = None;
        for (&x, v) in region.iter().zip(verdicts) {
            self.invalid[x as usize] = v;
            self.known[x as usize] = true;
        }
        Some((quad, region))
    }

    /// Tries the star and link edges of facet i; keeps the first flip that lowers the number
    /// of invalid facets around it and returns the points whose verdicts it renewed.
    fn try_repair(&mut self, i: u32, judged: usize) -> Option<Vec<u32>> {
        self.try_repair_with(i, judged, &mut |_, _| false)
    }

    /// [`State::try_repair`], where a flip that does not lower the count by itself is handed
    /// to `rescue` (with the quad's points; the verdicts still describe the mesh before the
    /// flip) before it is undone; `rescue` returns whether it lowered the count (its changes
    /// then stay, and it has set the verdicts), or undoes its own changes.
    pub(crate) fn try_repair_with(
        &mut self,
        i: u32,
        judged: usize,
        rescue: &mut dyn FnMut(&mut Self, [u32; 4]) -> bool,
    ) -> Option<Vec<u32>> {
        for (a, b) in self.repair_candidates(i)? {
            let Some((t, k, quad)) = self.flippable(a, b) else {
                continue;
            };
            let touches_ghost = quad.iter().any(|&x| x as usize >= judged);
            let mut affected = Vec::with_capacity(AFFECTED_CAPACITY);
            self.affected_into(&quad, &mut affected);
            affected.retain(|&x| (x as usize) < judged);
            let before = affected
                .iter()
                .filter(|&&x| self.invalid[x as usize])
                .count();
            if before == 0 {
                continue;
            }
            let (t1, _) = self.flip(t as u32, k);
            // Around a ghost the flip must leave every point's ghost neighbours in one run: a
            // ghost drawn into the real region would open a hole in the mesh.
            if touches_ghost && !quad.iter().all(|&x| self.one_ghost_arc(x)) {
                self.flip(t1, 1);
                continue;
            }
            // Those invalid before first (most stay so: a futile flip is known soonest), the
            // quad's points (their polygons changed) next; stop once no gain is possible.
            // (Four stable passes: the order of a stable sort by that key, without its
            // comparisons.)
            let key = |x: u32| {
                2 * usize::from(!self.invalid[x as usize]) + usize::from(!quad.contains(&x))
            };
            let mut ordered = Vec::with_capacity(affected.len());
            for k in 0..4 {
                ordered.extend(affected.iter().copied().filter(|&x| key(x) == k));
            }
            let affected = ordered;
            let mut verdicts = Vec::with_capacity(affected.len());
            let mut count = 0;
            for &x in &affected {
                let v = self.facet_invalid(x);
                count += usize::from(v);
                verdicts.push(v);
                if count >= before {
                    break;
                }
            }
            if count < before {
                for (&x, v) in affected.iter().zip(verdicts) {
                    self.set_verdict(x, v);
                }
                return Some(affected);
            }
            if rescue(self, quad) {
                return Some(affected);
            }
            // Undo: the new diagonal (c, d) is the edge opposite position 1 of t1 = [c, a, d].
            self.flip(t1, 1);
        }
        None
    }
}

/// Per point, the mean distance from its seed to its neighbours' seeds (1 for an isolated
/// point).
pub(crate) fn local_spacing(tri: &DualTriangulation, planes: &[Plane], points: usize) -> Vec<f64> {
    let mut sum = vec![0.0; points];
    let mut count = vec![0u32; points];
    for t in &tri.triangles {
        for k in 0..3 {
            let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
            let d = planes[a].point.distance(planes[b].point);
            for x in [a, b] {
                sum[x] += d;
                count[x] += 1;
            }
        }
    }
    sum.iter()
        .zip(&count)
        .map(|(&s, &c)| {
            if c > 0 && s > 0.0 {
                s / f64::from(c)
            } else {
                1.0
            }
        })
        .collect()
}

/// How far the vertex of triangle t lies beyond [`RUNAWAY_SPACINGS`] local spacings from its
/// farthest seed, in spacings (0 within, and for a triangle with a ghost: the facet stage
/// clips those at the wall; [`UNREACHABLE_RUNAWAY_SPACINGS`] where the vertex is
/// unreachable).
fn runaway_excess(planes: &[Plane], spacing: &[f64], judged: usize, t: [u32; 3]) -> f64 {
    if t.iter().any(|&x| x as usize >= judged) {
        return 0.0;
    }
    let x = triangle_vertex(planes, t);
    let reach = t
        .iter()
        .map(|&i| x.distance(planes[i as usize].point) / spacing[i as usize])
        .fold(0.0, |a: f64, r| {
            if r.is_finite() {
                a.max(r)
            } else {
                f64::INFINITY
            }
        });
    (reach.min(UNREACHABLE_RUNAWAY_SPACINGS) - RUNAWAY_SPACINGS).max(0.0)
}

/// The last pass of a validity search with exact planes: flips an edge of a triangle whose
/// vertex has run away ([`runaway_excess`]) where that lowers the excess summed over the
/// triangles around the flip's quad (only the flip's two triangles change) and leaves no
/// more invalid facets among those the flip can change. The summed excess drops with every
/// kept flip, so the pass ends; it is bounded by [`MAX_VALIDITY_ROUNDS`] rounds in any case.
/// `spacing` holds every point's local spacing. Returns the flips kept.
fn bring_in_runaways(state: &mut State<'_>, planes: &[Plane], spacing: &[f64]) -> usize {
    let judged = state.judged;
    let blocked = vec![false; judged];
    let (mut fan, mut around) = (Vec::new(), Vec::new());
    let mut kept = 0;
    for _ in 0..MAX_VALIDITY_ROUNDS {
        let targets: Vec<[u32; 3]> = state
            .tri
            .triangles
            .iter()
            .copied()
            .filter(|&t| runaway_excess(planes, spacing, judged, t) > 0.0)
            .collect();
        let mut kept_now = 0;
        for t in targets {
            for k in 0..3 {
                let mut score = |tri: &DualTriangulation, incident: &[u32], quad: &[u32; 4]| {
                    around.clear();
                    for &v in quad {
                        tri.fan(v, incident[v as usize], &mut fan);
                        around.extend_from_slice(&fan);
                    }
                    around.sort_unstable();
                    around.dedup();
                    around
                        .iter()
                        .map(|&x| {
                            runaway_excess(planes, spacing, judged, tri.triangles[x as usize])
                        })
                        .sum::<f64>()
                };
                let (a, b) = (t[k], t[(k + 1) % 3]);
                if state
                    .try_flip_scored(a, b, RUNAWAY_EXCESS_MARGIN, true, &blocked, &mut score)
                    .is_some()
                {
                    kept_now += 1;
                    break;
                }
            }
        }
        kept += kept_now;
        if kept_now == 0 {
            break;
        }
    }
    kept
}

/// The vertex T_i ∩ T_j ∩ T_k of a triangle (coincident planes separated by bisectors:
/// [`crate::planes::meeting_point`]), NaN where it is unreachable (the facet stage
/// cannot use it: [`crate::facets::reachable`]), which makes every facet around it invalid.
fn triangle_vertex(planes: &[Plane], t: [u32; 3]) -> DVec3 {
    let mut ids = t;
    ids.sort_unstable();
    let [a, b, c] = ids.map(|i| &planes[i as usize]);
    let x = meeting_point(a, b, c).point;
    if reachable(x, t.map(|i| &planes[i as usize])) {
        x
    } else {
        DVec3::NAN
    }
}

/// Whether points a and b are joined by an edge (interior or hull); `fan` is a buffer.
fn has_edge(tri: &DualTriangulation, incident: &[u32], a: u32, b: u32, fan: &mut Vec<u32>) -> bool {
    tri.fan(a, incident[a as usize], fan);
    fan.iter().any(|&t| tri.triangles[t as usize].contains(&b))
}

/// Points whose validity a flip of the quad's diagonal can change: the quad's four points
/// (their polygons change) and their neighbours (their overlap with those polygons).
pub(crate) fn affected_points(tri: &DualTriangulation, incident: &[u32], quad: &[u32]) -> Vec<u32> {
    let mut out: Vec<u32> = quad.to_vec();
    let mut fan = Vec::new();
    for &p in quad {
        tri.fan(p, incident[p as usize], &mut fan);
        for &t in &fan {
            out.extend_from_slice(&tri.triangles[t as usize]);
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The four points (c, a, b, d) of the quad around the edge opposite vertex k of triangle t.
fn quad_points(tri: &DualTriangulation, t: usize, k: usize) -> [u32; 4] {
    let v = tri.triangles[t];
    let (c, a, b) = (v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
    let t2 = tri.neighbours[t][k] as usize;
    let k2 = tri.neighbours[t2]
        .iter()
        .position(|&x| x as usize == t)
        .unwrap_or(0);
    [c, a, b, tri.triangles[t2][k2]]
}

/// The interior edge (a, b) as (triangle, opposite position), if it exists; `fan` is a
/// buffer.
fn find_edge(
    tri: &DualTriangulation,
    incident: &[u32],
    a: u32,
    b: u32,
    fan: &mut Vec<u32>,
) -> Option<(usize, usize)> {
    tri.fan(a, incident[a as usize], fan);
    for &t in fan.iter() {
        let v = tri.triangles[t as usize];
        let p = v.iter().position(|&x| x == a)?;
        for (next, opposite) in [((p + 1) % 3, (p + 2) % 3), ((p + 2) % 3, (p + 1) % 3)] {
            if v[next] == b && tri.neighbours[t as usize][opposite] != NO_TRIANGLE {
                return Some((t as usize, opposite));
            }
        }
    }
    None
}

/// Drops consecutive vertices (cyclically) closer than `weld` to the previous kept one.
fn weld_loop(points: &mut Vec<DVec3>, weld: f64) {
    points.dedup_by(|b, a| a.distance(*b) <= weld);
    while points.len() > 1 && points[0].distance(points[points.len() - 1]) <= weld {
        points.pop();
    }
}

/// Room for the points a flip can affect around a quad of four usual fans (no regrowth).
const AFFECTED_CAPACITY: usize = 48;

/// Polygons up to this many vertices are flattened into a buffer on the stack.
const FLAT_STACK: usize = 32;

/// Coordinates in the plane perpendicular to `normal`, frame (e1, e2, normal) right-handed,
/// relative to `origin` (so that rounding is relative to the polygons' own size): into
/// `stack` where the points fit, else into `heap` (no allocation for the usual facet).
fn flatten_into<'b>(
    points: &[DVec3],
    normal: DVec3,
    origin: DVec3,
    stack: &'b mut [DVec2; FLAT_STACK],
    heap: &'b mut Vec<DVec2>,
) -> &'b [DVec2] {
    let (e1, e2) = normal.normalize_or(DVec3::Z).any_orthonormal_pair();
    let to2 = |&x: &DVec3| DVec2::new((x - origin).dot(e1), (x - origin).dot(e2));
    if points.len() <= FLAT_STACK {
        for (p, x) in stack.iter_mut().zip(points) {
            *p = to2(x);
        }
        &stack[..points.len()]
    } else {
        heap.clear();
        heap.extend(points.iter().map(to2));
        heap
    }
}

/// Longest edge of a closed polygon. One square root, of the largest squared length: the
/// same value as the largest length (the square root is monotonic and correctly rounded).
fn size(p: &[DVec2]) -> f64 {
    // Edges as (previous, this) vertex: the largest is the same in any order.
    let mut previous = p.len().wrapping_sub(1);
    p.iter()
        .enumerate()
        .map(|(k, &x)| {
            let edge = (p[previous] - x).length_squared();
            previous = k;
            edge
        })
        .fold(0.0, f64::max)
        .sqrt()
}

/// Simple and counter-clockwise seen from `normal`, at least three distinct vertices.
pub(crate) fn simple_in_plane(points: &[DVec3], normal: DVec3) -> bool {
    tangle(points, normal) == 0
}

/// How far a polygon is from simple and counter-clockwise in the plane perpendicular to
/// `normal`: the number of properly crossing pairs of non-adjacent edges, plus the number of
/// edges if its signed area is not positive (0: simple and counter-clockwise; `usize::MAX`:
/// fewer than three points or a non-finite one).
pub(crate) fn tangle(points: &[DVec3], normal: DVec3) -> usize {
    let Some(&origin) = points.first() else {
        return usize::MAX;
    };
    if !points.iter().all(|x| x.is_finite()) {
        return usize::MAX;
    }
    let (mut stack, mut heap) = ([DVec2::ZERO; FLAT_STACK], Vec::new());
    let p = flatten_into(points, normal, origin, &mut stack, &mut heap);
    let n = p.len();
    if n < 3 {
        return usize::MAX;
    }
    let area: f64 = (0..n).map(|k| p[k].perp_dot(p[(k + 1) % n])).sum();
    let not_ccw = if area > 0.0 { 0 } else { n };
    not_ccw + crossing_edge_pairs(p)
}

/// Polygons with more edges than this count their crossing edge pairs by a sweep in x.
const SWEEP_MIN_EDGES: usize = 24;

/// The number of pairs of non-adjacent edges of the closed polygon `p` that meet
/// ([`edges_meet`]). Two edges whose x-extents are disjoint cannot meet, so beyond
/// [`SWEEP_MIN_EDGES`] edges only the pairs whose x-extents overlap are tested (edges sorted
/// by their smallest x, each against the following ones that start before it ends): the
/// same count, without the quadratic cost on the rare facets of a hundred or more edges
/// (around runaway vertices of nearly parallel planes).
fn crossing_edge_pairs(p: &[DVec2]) -> usize {
    let n = p.len();
    let adjacent = |a: usize, b: usize| b == a + 1 || (a == 0 && b == n - 1);
    let meet = |a: usize, b: usize| edges_meet(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n]);
    if n <= SWEEP_MIN_EDGES {
        // Each edge's box once, not once per pair (the same test as `edges_meet`'s).
        let mut boxes = [[0.0; 4]; SWEEP_MIN_EDGES];
        for (k, b) in boxes.iter_mut().enumerate().take(n) {
            *b = edge_box(p[k], p[(k + 1) % n]);
        }
        let mut count = 0;
        for a in 0..n {
            // The pairs (a, b > a + 1) but (0, n - 1), which are adjacent.
            let end = if a == 0 { n - 1 } else { n };
            let box_a = boxes[a];
            for b in a + 2..end {
                if !boxes_apart(box_a, boxes[b])
                    && edges_meet_near(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n])
                {
                    count += 1;
                }
            }
        }
        return count;
    }
    let extent = |k: usize| {
        let (x0, x1) = (p[k].x, p[(k + 1) % n].x);
        (x0.min(x1), x0.max(x1))
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_unstable_by(|&a, &b| extent(a).0.total_cmp(&extent(b).0).then(a.cmp(&b)));
    let mut count = 0;
    for (k, &e) in order.iter().enumerate() {
        let end = extent(e).1;
        for &f in order[k + 1..].iter().take_while(|&&f| extent(f).0 <= end) {
            let (a, b) = (e.min(f), e.max(f));
            if !adjacent(a, b) && meet(a, b) {
                count += 1;
            }
        }
    }
    count
}

/// Whether two simple polygons that may share vertices overlap in area, seen along
/// `normal`: a proper crossing of their edges, or a vertex of one strictly inside the other.
/// Vertices of one closer than the tolerance to a vertex of the other count as shared.
pub(crate) fn polygons_overlap(a: &[DVec3], b: &[DVec3], normal: DVec3) -> bool {
    let Some(&origin) = a.first() else {
        return false;
    };
    let (e1, e2) = normal.normalize_or(DVec3::Z).any_orthonormal_pair();
    let to2 = |x: &DVec3| DVec2::new((*x - origin).dot(e1), (*x - origin).dot(e2));
    // Small polygons stay on the stack.
    let mut buffer_a = [DVec2::ZERO; 16];
    let mut buffer_b = [DVec2::ZERO; 16];
    let (mut heap_a, mut heap_b) = (Vec::new(), Vec::new());
    let pa: &mut [DVec2] = if a.len() <= 16 {
        &mut buffer_a[..a.len()]
    } else {
        heap_a.resize(a.len(), DVec2::ZERO);
        &mut heap_a
    };
    let pb: &mut [DVec2] = if b.len() <= 16 {
        &mut buffer_b[..b.len()]
    } else {
        heap_b.resize(b.len(), DVec2::ZERO);
        &mut heap_b
    };
    for (p, x) in pa.iter_mut().zip(a) {
        *p = to2(x);
    }
    for (p, x) in pb.iter_mut().zip(b) {
        *p = to2(x);
    }
    let (pa, pb) = (&*pa, pb);
    let (na, nb) = (pa.len(), pb.len());
    let scale = size(pa).max(size(pb));
    let tolerance = VALIDITY_TOLERANCE * scale;
    let box_a = bounds(pa);
    // Per vertex of b, the vertex of a it was moved onto (`UNSHARED` where none), and as bits
    // (the first 64 vertices of each polygon) the vertices of b moved and those of a moved
    // onto: such a pair is one point, and the tests below skip what a shared point decides
    // without arithmetic.
    let mut stack_onto = [UNSHARED; 16];
    let mut heap_onto = Vec::new();
    let onto: &mut [usize] = if nb <= 16 {
        &mut stack_onto[..nb]
    } else {
        heap_onto.resize(nb, UNSHARED);
        &mut heap_onto
    };
    let (mut shared_a, mut shared_b) = (0u64, 0u64);
    // A vertex of b farther than twice the tolerance outside a's box is within the tolerance
    // of no vertex of a (the margin covers the rounding of the box test): it is not searched.
    let (near_lo, near_hi) = (
        box_a.0 - DVec2::splat(2.0 * tolerance),
        box_a.1 + DVec2::splat(2.0 * tolerance),
    );
    for (y, q) in pb.iter_mut().enumerate() {
        if q.x < near_lo.x || q.x > near_hi.x || q.y < near_lo.y || q.y > near_hi.y {
            continue;
        }
        if let Some(x) = pa
            .iter()
            .position(|p| (*p - *q).length_squared() <= tolerance * tolerance)
        {
            *q = pa[x];
            onto[y] = x;
            if x < 64 {
                shared_a |= 1 << x;
            }
            if y < 64 {
                shared_b |= 1 << y;
            }
        }
    }
    let (pb, onto) = (&*pb, &*onto);
    let eps = VALIDITY_TOLERANCE * scale * scale;
    // Segments (and points) whose bounding boxes miss the other polygon's cannot cross it (or
    // lie inside it): only the few near the shared part are tested pair by pair.
    let box_b = bounds(pb);
    // The boxes of b's edges, once (not once per edge of a).
    let mut stack_boxes = [(DVec2::ZERO, DVec2::ZERO); 16];
    let mut heap_boxes = Vec::new();
    let edge_boxes_b: &mut [(DVec2, DVec2)] = if nb <= 16 {
        &mut stack_boxes[..nb]
    } else {
        heap_boxes.resize(nb, (DVec2::ZERO, DVec2::ZERO));
        &mut heap_boxes
    };
    let mut previous = nb.wrapping_sub(1);
    for (y, &t) in pb.iter().enumerate() {
        let r = pb[previous];
        edge_boxes_b[previous] = (r.min(t), r.max(t));
        previous = y;
    }
    for x in 0..na {
        let x1 = next(x, na);
        let (p, q) = (pa[x], pa[x1]);
        let edge = (p.min(q), p.max(q));
        if !boxes_meet(edge, box_b) {
            continue;
        }
        for (y, &edge_b) in edge_boxes_b.iter().enumerate() {
            if !boxes_meet(edge, edge_b) {
                continue;
            }
            let y1 = next(y, nb);
            // Edges with an end in common do not cross properly: the orientation of the
            // shared point against the other edge is exactly 0 (or NaN), never beyond `eps`.
            let (s, s1) = (onto[y], onto[y1]);
            if s == x || s == x1 || s1 == x || s1 == x1 {
                continue;
            }
            if proper_crossing(p, q, pb[y], pb[y1], eps) {
                return true;
            }
        }
    }
    // No proper crossing: overlap means a vertex of one strictly inside the other. The
    // crossing number first (most vertices tested are outside), then the distances. A
    // shared vertex is at distance 0 from a vertex of the other polygon: never inside.
    let inside = |points: &[DVec2], shared: u64, poly: &[DVec2], poly_box| {
        points.iter().enumerate().any(|(k, &p)| {
            (k >= 64 || shared >> k & 1 == 0)
                && boxes_meet((p, p), poly_box)
                && odd_crossing_number(p, poly)
                && !poly
                    .iter()
                    .any(|q| (*q - p).length_squared() <= tolerance * tolerance)
                && clear_of_edges(p, poly, tolerance)
        })
    };
    inside(pb, shared_b, pa, box_a) || inside(pa, shared_a, pb, box_b)
}

/// [`polygons_overlap`]'s mark of a vertex of one polygon that is no vertex of the other.
const UNSHARED: usize = usize::MAX;

/// The index after `k` around a closed polygon of `n` vertices.
fn next(k: usize, n: usize) -> usize {
    if k + 1 == n {
        0
    } else {
        k + 1
    }
}

/// The (min, max) corners of the points' bounding box.
fn bounds(points: &[DVec2]) -> (DVec2, DVec2) {
    points.iter().fold(
        (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    )
}

/// Whether two closed boxes (min, max) share a point.
fn boxes_meet(a: (DVec2, DVec2), b: (DVec2, DVec2)) -> bool {
    a.0.x <= b.1.x && b.0.x <= a.1.x && a.0.y <= b.1.y && b.0.y <= a.1.y
}

/// Whether the line through the shared edge `ends` separates polygons a and b seen along
/// `normal`: every other vertex of one strictly on one side and of the other strictly on
/// the other (then they cannot overlap; otherwise [`polygons_overlap`] decides).
fn separated(a: &[DVec3], b: &[DVec3], ends: [DVec3; 2], normal: DVec3) -> bool {
    let (e1, e2) = normal.normalize_or(DVec3::Z).any_orthonormal_pair();
    let to2 = |x: DVec3| DVec2::new((x - ends[0]).dot(e1), (x - ends[0]).dot(e2));
    let direction = to2(ends[1]);
    let length = direction.length();
    if !(length > 0.0) {
        return false;
    }
    let margin = VALIDITY_TOLERANCE * length;
    let side = |poly: &[DVec3]| {
        let (mut positive, mut negative) = (false, false);
        for &x in poly {
            let d = direction.perp_dot(to2(x)) / length;
            positive |= d > margin;
            negative |= d < -margin;
        }
        (positive, negative)
    };
    let ((ap, an), (bp, bn)) = (side(a), side(b));
    (ap && !an && bn && !bp) || (an && !ap && bp && !bn)
}

/// Whether `p` lies strictly inside the polygon: inside by the crossing number and farther than
/// `tolerance` from every edge (a point on the boundary is not inside). The crossing number
/// comes first: most points tested are outside, and then no distance is needed.
#[cfg(test)]
fn point_strictly_inside(p: DVec2, poly: &[DVec2], tolerance: f64) -> bool {
    odd_crossing_number(p, poly) && clear_of_edges(p, poly, tolerance)
}

/// Whether a ray from `p` along +x crosses the closed polygon an odd number of times.
fn odd_crossing_number(p: DVec2, poly: &[DVec2]) -> bool {
    // Each edge (a, b) from its previous vertex: the parity is the same in any order.
    let Some(&last) = poly.last() else {
        return false;
    };
    let mut a = last;
    let mut inside = false;
    for &b in poly {
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
        a = b;
    }
    inside
}

/// Whether `p` lies farther than `tolerance` from every edge of the closed polygon.
fn clear_of_edges(p: DVec2, poly: &[DVec2], tolerance: f64) -> bool {
    // Each edge (a, b) from its previous vertex: `all` is the same in any order.
    let Some(&last) = poly.last() else {
        return true;
    };
    let mut a = last;
    poly.iter().all(|&b| {
        let a = std::mem::replace(&mut a, b);
        let ab = b - a;
        let t = ((p - a).dot(ab) / ab.length_squared().max(f64::MIN_POSITIVE)).clamp(0.0, 1.0);
        (a + ab * t - p).length_squared() > tolerance * tolerance
    })
}

/// The segments ab and cd cross properly: each strictly (beyond `eps`, an area) on both
/// sides of the other.
/// Whether segments pq and rs cross properly, or an end of one lies on the other up to
/// [`VALIDITY_TOLERANCE`] times the other's squared length (a facet whose vertex sits on a
/// non-adjacent edge, as where four planes share a ruling of the surface, is not simple:
/// rounding decides which side it falls on).
fn edges_meet(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    // Disjoint bounding boxes (most pairs of a polygon's edges) cannot meet.
    !boxes_apart(edge_box(p, q), edge_box(r, s)) && edges_meet_near(p, q, r, s)
}

/// The box (x min, x max, y min, y max) of segment pq.
fn edge_box(p: DVec2, q: DVec2) -> [f64; 4] {
    [p.x.min(q.x), p.x.max(q.x), p.y.min(q.y), p.y.max(q.y)]
}

/// Whether two boxes of [`edge_box`] are strictly apart along x or y.
fn boxes_apart(a: [f64; 4], b: [f64; 4]) -> bool {
    a[1] < b[0] || b[1] < a[0] || a[3] < b[2] || b[3] < a[2]
}

/// [`edges_meet`] for segments whose boxes are not apart.
fn edges_meet_near(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
    let (pq, rs) = (q - p, s - r);
    let (d1, d2) = (pq.perp_dot(r - p), pq.perp_dot(s - p));
    let (d3, d4) = (rs.perp_dot(p - r), rs.perp_dot(q - r));
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let within = |a: DVec2, b: DVec2, c: DVec2| {
        c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
    };
    let (t1, t2) = (
        VALIDITY_TOLERANCE * pq.length_squared(),
        VALIDITY_TOLERANCE * rs.length_squared(),
    );
    (d1.abs() <= t1 && within(p, q, r))
        || (d2.abs() <= t1 && within(p, q, s))
        || (d3.abs() <= t2 && within(r, s, p))
        || (d4.abs() <= t2 && within(r, s, q))
}

fn proper_crossing(a: DVec2, b: DVec2, c: DVec2, d: DVec2, eps: f64) -> bool {
    let d1 = (b - a).perp_dot(c - a);
    let d2 = (b - a).perp_dot(d - a);
    let d3 = (d - c).perp_dot(a - c);
    let d4 = (d - c).perp_dot(b - c);
    let opposite = |x: f64, y: f64| (x > eps && y < -eps) || (x < -eps && y > eps);
    opposite(d1, d2) && opposite(d3, d4)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A facet is limited as beside a parabolic line exactly where a point of its ring has
    /// another sign of K: on a 5 x 5 grid with K > 0 for x <= 1 and K < 0 beyond, the point
    /// (1, 2) has (2, 2) beside it, the point (3, 2) only points with K < 0; with one sign
    /// everywhere, or none known, no point is.
    #[test]
    fn only_facets_with_both_signs_of_curvature_in_their_ring_straddle_a_parabolic_line() {
        let uv: Vec<[f64; 2]> = (0..25).map(|k| [(k % 5) as f64, (k / 5) as f64]).collect();
        let planes: Vec<Plane> = uv
            .iter()
            .map(|&[x, y]| Plane {
                point: DVec3::new(x, y, 0.0),
                normal: DVec3::Z,
            })
            .collect();
        let mut tri = DualTriangulation::delaunay(&uv).expect("a grid triangulates");
        let mut state = State::new(&mut tri, uv.len(), Cow::Borrowed(&planes), uv.len());
        let mixed: Vec<i8> = uv
            .iter()
            .map(|p| if p[0] <= 1.0 { 1 } else { -1 })
            .collect();
        let at = |x: u32, y: u32| 5 * y + x;
        assert!(state.straddles_parabolic_line(at(1, 2), &mixed));
        assert!(state.straddles_parabolic_line(at(2, 2), &mixed));
        assert!(!state.straddles_parabolic_line(at(3, 2), &mixed));
        assert!(!state.straddles_parabolic_line(at(0, 2), &mixed));
        let saddle = vec![-1i8; uv.len()];
        assert!((0..25).all(|i| !state.straddles_parabolic_line(i, &saddle)));
        assert!((0..25).all(|i| !state.straddles_parabolic_line(i, &[])));
    }

    /// The sweep counts the same crossing pairs as testing every pair of non-adjacent edges:
    /// star polygons (many crossings), random walks (some) and convex polygons (none), with
    /// vertical edges and repeated x-coordinates that tie the sweep's order.
    #[test]
    fn the_sweep_counts_every_crossing_pair_of_a_large_polygon() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let every_pair = |p: &[DVec2]| {
            let n = p.len();
            let mut count = 0;
            for a in 0..n {
                for b in a + 2..n {
                    if !(a == 0 && b == n - 1)
                        && edges_meet(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n])
                    {
                        count += 1;
                    }
                }
            }
            count
        };
        let mut crossings_seen = 0;
        for n in [3, 5, 24, 25, 40, 97, 150] {
            let star: Vec<DVec2> = (0..n)
                .map(|k| {
                    let angle = std::f64::consts::TAU * (k * (n / 2 - 1).max(1)) as f64 / n as f64;
                    DVec2::new(angle.cos(), angle.sin())
                })
                .collect();
            let walk: Vec<DVec2> = (0..n)
                .map(|_| DVec2::new((next() * 8.0).round(), next()))
                .collect();
            let convex: Vec<DVec2> = (0..n)
                .map(|k| {
                    let angle = std::f64::consts::TAU * k as f64 / n as f64;
                    DVec2::new(angle.cos(), 0.5 * angle.sin())
                })
                .collect();
            for p in [star, walk, convex] {
                let expected = every_pair(&p);
                assert_eq!(crossing_edge_pairs(&p), expected, "{n} points: {p:?}");
                crossings_seen += expected;
            }
        }
        assert!(crossings_seen > 1000, "{crossings_seen}");
    }

    /// `polygons_overlap` as it was before its edge boxes were taken once per polygon: the
    /// oracle of the test below (verbatim).
    fn polygons_overlap_before(a: &[DVec3], b: &[DVec3], normal: DVec3) -> bool {
        let Some(&origin) = a.first() else {
            return false;
        };
        let (e1, e2) = normal.normalize_or(DVec3::Z).any_orthonormal_pair();
        let to2 = |x: &DVec3| DVec2::new((*x - origin).dot(e1), (*x - origin).dot(e2));
        // Small polygons stay on the stack.
        let mut buffer_a = [DVec2::ZERO; 16];
        let mut buffer_b = [DVec2::ZERO; 16];
        let (mut heap_a, mut heap_b) = (Vec::new(), Vec::new());
        let pa: &mut [DVec2] = if a.len() <= 16 {
            &mut buffer_a[..a.len()]
        } else {
            heap_a.resize(a.len(), DVec2::ZERO);
            &mut heap_a
        };
        let pb: &mut [DVec2] = if b.len() <= 16 {
            &mut buffer_b[..b.len()]
        } else {
            heap_b.resize(b.len(), DVec2::ZERO);
            &mut heap_b
        };
        for (p, x) in pa.iter_mut().zip(a) {
            *p = to2(x);
        }
        for (p, x) in pb.iter_mut().zip(b) {
            *p = to2(x);
        }
        let (pa, pb) = (&*pa, pb);
        let scale = size(pa).max(size(pb));
        let tolerance = VALIDITY_TOLERANCE * scale;
        for q in pb.iter_mut() {
            if let Some(p) = pa
                .iter()
                .find(|p| (**p - *q).length_squared() <= tolerance * tolerance)
            {
                *q = *p;
            }
        }
        let pb = &*pb;
        let eps = VALIDITY_TOLERANCE * scale * scale;
        let (na, nb) = (pa.len(), pb.len());
        // Segments (and points) whose bounding boxes miss the other polygon's cannot cross it (or
        // lie inside it): only the few near the shared part are tested pair by pair.
        let (box_a, box_b) = (bounds(pa), bounds(pb));
        for x in 0..na {
            let (p, q) = (pa[x], pa[(x + 1) % na]);
            let edge = (p.min(q), p.max(q));
            if !boxes_meet(edge, box_b) {
                continue;
            }
            for y in 0..nb {
                let (r, t) = (pb[y], pb[(y + 1) % nb]);
                if boxes_meet(edge, (r.min(t), r.max(t))) && proper_crossing(p, q, r, t, eps) {
                    return true;
                }
            }
        }
        // No proper crossing: overlap means a vertex of one strictly inside the other.
        let inside = |points: &[DVec2], poly: &[DVec2], poly_box: (DVec2, DVec2)| {
            points.iter().any(|&p| {
                boxes_meet((p, p), poly_box)
                    && !poly
                        .iter()
                        .any(|q| (*q - p).length_squared() <= tolerance * tolerance)
                    && point_strictly_inside(p, poly, tolerance)
            })
        };
        inside(pb, pa, box_a) || inside(pa, pb, box_b)
    }

    /// `edges_meet` as it was before its box test was split out: the oracle of the tests
    /// below (verbatim).
    fn edges_meet_before(p: DVec2, q: DVec2, r: DVec2, s: DVec2) -> bool {
        // Disjoint bounding boxes (most pairs of a polygon's edges) cannot meet.
        if p.x.max(q.x) < r.x.min(s.x)
            || r.x.max(s.x) < p.x.min(q.x)
            || p.y.max(q.y) < r.y.min(s.y)
            || r.y.max(s.y) < p.y.min(q.y)
        {
            return false;
        }
        let (pq, rs) = (q - p, s - r);
        let (d1, d2) = (pq.perp_dot(r - p), pq.perp_dot(s - p));
        let (d3, d4) = (rs.perp_dot(p - r), rs.perp_dot(q - r));
        if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
            && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
        {
            return true;
        }
        let within = |a: DVec2, b: DVec2, c: DVec2| {
            c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
        };
        let (t1, t2) = (
            VALIDITY_TOLERANCE * pq.length_squared(),
            VALIDITY_TOLERANCE * rs.length_squared(),
        );
        (d1.abs() <= t1 && within(p, q, r))
            || (d2.abs() <= t1 && within(p, q, s))
            || (d3.abs() <= t2 && within(r, s, p))
            || (d4.abs() <= t2 && within(r, s, q))
    }

    /// A polygon generator for the oracle tests: star-shaped polygons around a centre,
    /// optionally sharing an edge with a given one, with near-degenerate variants (vertices
    /// snapped to a coarse grid, so that many are collinear or coincide; tiny perturbations).
    struct Polygons {
        state: u64,
    }

    impl Polygons {
        fn next(&mut self) -> f64 {
            self.state ^= self.state << 13;
            self.state ^= self.state >> 7;
            self.state ^= self.state << 17;
            (self.state >> 11) as f64 / (1u64 << 53) as f64
        }

        fn star(&mut self, centre: DVec3, n: usize, radius: f64) -> Vec<DVec3> {
            let start = self.next() * std::f64::consts::TAU;
            (0..n)
                .map(|k| {
                    let angle =
                        start + std::f64::consts::TAU * (k as f64 + 0.8 * self.next()) / n as f64;
                    let r = radius * (0.2 + self.next());
                    centre + DVec3::new(r * angle.cos(), r * angle.sin(), 0.3 * r * self.next())
                })
                .collect()
        }

        /// Degrades a polygon: snapped to a grid of `step`, or moved by tiny amounts.
        fn degrade(&mut self, p: &mut [DVec3], kind: u32) {
            for x in p.iter_mut() {
                match kind {
                    1 => *x = (*x / 0.25).round() * 0.25,
                    2 => *x += DVec3::new(self.next() - 0.5, self.next() - 0.5, 0.0) * 1e-12,
                    _ => {}
                }
            }
        }
    }

    /// The overlap test gives the verdicts it gave before its edge boxes were precomputed and
    /// its shared vertices skipped, on polygon pairs of 3 to 23 vertices sharing an edge (the callers' case, in both orders, either normal), pairs
    /// sharing a vertex or nothing, and near-degenerate ones (collinear and coincident
    /// vertices on a grid, perturbations of 1e-12).
    #[test]
    fn the_overlap_test_matches_its_former_self() {
        let mut gen = Polygons {
            state: 0x2545_f491_4f6c_dd1d,
        };
        let (mut overlaps, mut apart) = (0, 0);
        for case in 0..20_000 {
            // Every tenth pair has 15 to 23 vertices (beyond the stack buffers).
            let large = if case % 10 == 9 { 12 } else { 0 };
            let n = 3 + case % 9 + large;
            let m = 3 + (case / 9) % 9 + large;
            let a = gen.star(DVec3::ZERO, n, 1.0);
            let centre = DVec3::new(gen.next() * 2.0, gen.next() * 2.0, 0.0);
            let mut b = gen.star(centre, m, 1.0);
            let mut a = a;
            match case % 4 {
                // Share the edge (a[0], a[1]), reversed in b.
                0 | 1 => {
                    b[0] = a[1];
                    b[1] = a[0];
                }
                // Share a vertex.
                2 => b[0] = a[0],
                _ => {}
            }
            gen.degrade(&mut a, (case / 4 % 3) as u32);
            gen.degrade(&mut b, (case / 12 % 3) as u32);
            let normal = DVec3::new(gen.next() - 0.5, gen.next() - 0.5, 1.0);
            for normal in [normal, normal.normalize(), DVec3::ZERO] {
                for (p, q) in [(&a, &b), (&b, &a)] {
                    let expected = polygons_overlap_before(p, q, normal);
                    assert_eq!(
                        polygons_overlap(p, q, normal),
                        expected,
                        "{p:?} {q:?} {normal}"
                    );
                    if expected {
                        overlaps += 1;
                    } else {
                        apart += 1;
                    }
                }
            }
        }
        assert!(overlaps > 10_000 && apart > 10_000, "{overlaps} {apart}");
    }

    /// The simplicity count gives the counts it gave before each edge's box was taken once:
    /// the star, random-walk and grid-snapped polygons of every size up to the sweep's.
    #[test]
    fn the_crossing_count_matches_its_former_self() {
        let mut gen = Polygons {
            state: 0x9e37_79b9_7f4a_7c15,
        };
        let before = |p: &[DVec2]| {
            let n = p.len();
            let mut count = 0;
            for a in 0..n {
                for b in a + 2..n {
                    if !(a == 0 && b == n - 1)
                        && edges_meet_before(p[a], p[(a + 1) % n], p[b], p[(b + 1) % n])
                    {
                        count += 1;
                    }
                }
            }
            count
        };
        let mut crossings = 0;
        for case in 0..20_000 {
            let n = 3 + case % (SWEEP_MIN_EDGES + 6);
            let mut p: Vec<DVec2> = (0..n)
                .map(|_| DVec2::new(gen.next() * 4.0, gen.next() * 4.0))
                .collect();
            if case % 3 == 1 {
                p.iter_mut().for_each(|x| *x = x.round());
            }
            let expected = before(&p);
            assert_eq!(crossing_edge_pairs(&p), expected, "{p:?}");
            crossings += expected;
        }
        assert!(crossings > 10_000, "{crossings}");
    }
}
