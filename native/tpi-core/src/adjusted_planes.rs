//! Adjusted planes (`--planes adjusted`): where exact tangent planes cannot give a valid mesh,
//! the planes of a few facets are tilted by the least amount that makes every facet valid.
//!
//! After the validity flips ([`crate::validity_flips`]) the dual structure is fixed, and some
//! facets may still be invalid with exact tangent planes: at parabolic lines (K = 0) and with
//! uniform random patterns, neighbouring planes are nearly parallel, so the vertex
//! T_i ∩ T_j ∩ T_k = [n_i; n_j; n_k]^-1 [n_i.p_i; n_j.p_j; n_k.p_k] runs away (its condition is
//! det = n_i . (n_j x n_k) ~ 0). That ill-conditioning is also the remedy: a small tilt of one
//! of the three planes moves the vertex a long way, so a few degrees suffice to bring it back
//! between its seeds. (Zimmer, Campen, Herkrath and Kobbelt, *Variational Tangent Plane
//! Intersection for Planar Polygonal Meshing*, AAG 2012, optimise all planes at once; this is
//! a local, greedy version of the same idea that touches only the facets involved.)
//!
//! A plane keeps its seed point p_j and gets the normal
//!
//! ```text
//! n'_j = cos(theta) n_j + sin(theta) (cos(phi) e1_j + sin(phi) e2_j)
//! ```
//!
//! with (e1_j, e2_j, n_j) a right-handed frame of the exact tangent plane: theta is the tilt
//! (the angle between the facet's plane and the surface's tangent plane at its seed), at most
//! [`MAX_PLANE_TILT_DEGREES`]; the plane still passes through p_j, so the facet touches the
//! surface at its seed. Only where no tilt helps is an exact plane offset along its normal
//! instead, by a few per cent of the local spacing ([`PLANE_OFFSET_STEPS`]).
//!
//! The moves, each judged by the local validity test of the flips on the facets it can
//! change (the points of the triangles around the plane and their neighbours):
//! - for each invalid facet i, tilts of the planes of i and its neighbours (ghosts included,
//!   which shape the boundary facets) of increasing size ([`PLANE_TILT_STEPS_DEGREES`]) in
//!   [`PLANE_TILT_DIRECTIONS`] directions, each measured from the exact plane, then offsets;
//! - a flip of i's star or link edges together with a tilt of one of its quad's planes
//!   ([`RESCUE_TILT_STEPS_DEGREES`]), where the flip alone does not pay;
//! - a move is kept when it leaves fewer invalid facets around it, or as many but less
//!   tangled (crossing edge pairs), or as tangled with their runaway vertices pulled back
//!   ([`REACH_GAIN`]); rounds until nothing is kept, at most [`MAX_PLANE_ADJUST_ROUNDS`];
//! - then, around each facet still invalid, random restarts ([`PLANE_KICKS`]): random tilts
//!   followed by greedy tilts and flips, kept only when they leave fewer invalid facets,
//!   undone otherwise (seeded by the facet's index, so the result is deterministic); passes
//!   over the facets still invalid while one is kept, at most [`KICK_ROUNDS`];
//! - where only a few facets are left invalid ([`ESCALATION_MAX_INVALID`]), longer series of
//!   restarts around each ([`escalate`]), drawn afresh per round and every other round
//!   tilting up to four planes of two rings at once, within [`ESCALATION_BUDGET_PER_INVALID`]
//!   plane changes per facet left (a mesh the kick rounds made valid is not touched); each
//!   round first tries [`restructure`]: flips of the facet's star and link edges towards the
//!   isotropic Delaunay triangulation of the seeds (near a parabolic line the |II| metric
//!   degenerates and gives neighbours several spacings away, which no tilt repairs), then
//!   greedy tilts and flips, kept only when fewer facets are left invalid.
//!
//! With adjusted planes a facet whose vertices lie farther than
//! [`MAX_REACH`](crate::tolerance::MAX_REACH) local spacings
//! from its seed also counts as invalid, so that runaway vertices at parabolic lines are
//! pulled in, not only folds repaired. Where facets are still invalid after the second
//! decisions, the whole adjustment runs again with
//! [`FALLBACK_REACH`](crate::tolerance::FALLBACK_REACH) and is kept only if it leaves none
//! (`structure.rs`; one weight after another, up to one that leaves more than
//! [`FALLBACK_GIVE_UP`](crate::tolerance::FALLBACK_GIVE_UP)): on a nearly developable band the facets run along the rulings by
//! several spacings, and the shorter reach forbids the simple, long facet that is there.
//!
//! Facets stay exactly planar: every vertex is the meeting point of three (adjusted) planes,
//! computed once and shared by the three facets.

use std::borrow::Cow;
use std::sync::atomic::AtomicBool;

use glam::DVec3;

use crate::pattern::SplitMix64;
use crate::planes::Plane;
use crate::tolerance::{
    ESCALATION_BUDGET_PER_INVALID, ESCALATION_KICKS, ESCALATION_MAX_INVALID, ESCALATION_ROUNDS,
    KICK_REPAIR_PASSES, KICK_ROUNDS, MAX_PLANE_ADJUST_ROUNDS, MAX_PLANE_TILT_DEGREES,
    PLANE_ADJUST_BUDGET, PLANE_ADJUST_BUDGET_PER_INVALID, PLANE_KICKS, PLANE_OFFSET_STEPS,
    PLANE_TILT_DIRECTIONS, PLANE_TILT_STEPS_DEGREES, REACH_GAIN, RESCUE_TILT_STEPS_DEGREES,
    RESTRUCTURE_FLIPS,
};
use crate::triangulation::DualTriangulation;
use crate::validity_flips::{affected_points, local_spacing, Journal, State};

/// What the plane adjustment did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PlaneAdjustStats {
    /// Tilts kept (a plane may be tilted more than once).
    pub tilts: usize,
    /// Facets still invalid by the local test afterwards.
    pub unresolved: usize,
}

/// Tilts the planes of points around invalid facets of the points `0..judged` (module doc).
/// `planes` holds the planes of every point of the triangulation (ghosts from `judged` on)
/// and is replaced by the adjusted planes. A facet with a vertex farther than `reach` local
/// spacings from its seed counts as invalid ([`crate::tolerance::MAX_REACH`], or
/// [`crate::tolerance::FALLBACK_REACH`] on a second try). Once `stop` is set the search ends
/// at its next step (a speculative adjustment whose result will be dropped).
pub(crate) fn adjust_planes(
    tri: &mut DualTriangulation,
    planes: &mut Vec<Plane>,
    judged: usize,
    reach: f64,
    stop: Option<&AtomicBool>,
) -> PlaneAdjustStats {
    let exact = planes.clone();
    let points = planes.len();
    let mut state = State::new(tri, points, Cow::Owned(std::mem::take(planes)), judged);
    state.stop = stop;
    let spacing = local_spacing(state.tri, &state.planes, points);
    state.impose_reach_limit(spacing.iter().map(|&h| reach * h).collect());
    let mut stats = PlaneAdjustStats::default();
    // A facet whose repair failed is tried again only after a kept move changed its
    // neighbourhood.
    let mut retry = vec![true; judged];
    // A bound on the work, counted (so the result stays deterministic), not timed, per
    // judged facet and per facet invalid now, whichever is lower: where tilts cannot help (a
    // nearly developable surface) the search stops there.
    let budget = (PLANE_ADJUST_BUDGET * judged)
        .min(PLANE_ADJUST_BUDGET_PER_INVALID * state.invalid.iter().filter(|&&x| x).count());
    'rounds: for _ in 0..MAX_PLANE_ADJUST_ROUNDS {
        let queue: Vec<u32> = (0..judged as u32)
            .filter(|&i| state.invalid[i as usize] && retry[i as usize])
            .collect();
        if queue.is_empty() {
            break;
        }
        retry.iter_mut().for_each(|r| *r = false);
        let mut kept = 0;
        for i in queue {
            if state.spent(budget) {
                stats.tilts += kept;
                break 'rounds;
            }
            if state.invalid[i as usize] && try_move(&mut state, &exact, &spacing, i) {
                kept += 1;
                // A move on a plane of i's ring renews verdicts up to three rings from i.
                let near = polygons_of_plane(&state, i);
                let near = affected_points(state.tri, &state.incident, &near);
                for x in judged_around(&state, &near) {
                    retry[x as usize] = true;
                }
            }
        }
        stats.tilts += kept;
        if kept == 0 {
            break;
        }
    }
    // What the greedy moves cannot repair, random restarts around it may; a kept restart
    // changes the neighbourhood of others, so the pass repeats while one is kept.
    'kicks: for _ in 0..KICK_ROUNDS {
        let mut kept = false;
        for i in 0..judged as u32 {
            if state.spent(budget) {
                break 'kicks;
            }
            if state.invalid[i as usize] && kick(&mut state, &exact, &spacing, i, budget, &KICK) {
                stats.tilts += 1;
                kept = true;
            }
        }
        if !kept {
            break;
        }
    }
    escalate(&mut state, &exact, &spacing, &mut stats);
    stats.unresolved = state.invalid.iter().filter(|&&x| x).count();
    *planes = state.planes.into_owned();
    stats
}

/// The exact plane of a point tilted by `degrees` towards direction `phi` (radians) of its
/// tangent frame, through the same seed point.
pub(crate) fn tilted(exact: &Plane, degrees: f64, phi: f64) -> Plane {
    let (e1, e2) = exact.normal.any_orthonormal_pair();
    let (s, c) = degrees.to_radians().sin_cos();
    let direction = e1 * phi.cos() + e2 * phi.sin();
    Plane {
        point: exact.point,
        normal: (exact.normal * c + direction * s).normalize(),
    }
}

/// One greedy move for invalid facet i: a tilt ([`try_tilts`]), else a flip of its star or
/// link edges with rescue tilts ([`rescue_flip`]); a tilt can make a flip worth while and
/// the other way round, so both are tried. Whether one was kept.
fn try_move(state: &mut State<'_>, exact: &[Plane], spacing: &[f64], i: u32) -> bool {
    let judged = state.invalid.len();
    try_tilts(state, exact, spacing, i)
        || state
            .try_repair_with(i, judged, &mut |state, quad| {
                rescue_flip(state, exact, spacing, quad)
            })
            .is_some()
}

/// Tries tilts of the planes of facet i and its neighbours, smallest first; keeps the first
/// that lowers the number of invalid facets around the tilted plane.
fn try_tilts(state: &mut State<'_>, exact: &[Plane], spacing: &[f64], i: u32) -> bool {
    let mut fan = Vec::new();
    state.tri.fan(i, state.incident[i as usize], &mut fan);
    let mut ring: Vec<u32> = fan
        .iter()
        .flat_map(|&t| state.tri.triangles[t as usize])
        .collect();
    ring.sort_unstable();
    ring.dedup();
    // The facet's own plane first: its tilt is the one the user asked about.
    ring.sort_by_key(|&j| j != i);
    for &degrees in PLANE_TILT_STEPS_DEGREES {
        debug_assert!(degrees <= MAX_PLANE_TILT_DEGREES);
        for &j in &ring {
            for d in 0..PLANE_TILT_DIRECTIONS {
                let phi = std::f64::consts::TAU * d as f64 / PLANE_TILT_DIRECTIONS as f64;
                let candidate = tilted(&exact[j as usize], degrees, phi);
                if try_plane(state, spacing, j, candidate) {
                    return true;
                }
            }
        }
    }
    // Then offsets along the exact normal (the facet leaves its seed: last resort).
    for &fraction in PLANE_OFFSET_STEPS {
        for &j in &ring {
            for sign in [1.0, -1.0] {
                let e = &exact[j as usize];
                let candidate = Plane {
                    point: e.point + e.normal * (sign * fraction * spacing[j as usize]),
                    normal: e.normal,
                };
                if try_plane(state, spacing, j, candidate) {
                    return true;
                }
            }
        }
    }
    false
}

/// Sets the plane of point j to `candidate` and keeps it if the number of invalid facets it
/// can change drops, or stays while their runaway vertices come back ([`REACH_GAIN`]);
/// otherwise restores the old plane.
fn try_plane(state: &mut State<'_>, spacing: &[f64], j: u32, candidate: Plane) -> bool {
    let old = state.planes[j as usize];
    if old == candidate {
        return false;
    }
    let points = judged_around(state, &polygons_of_plane(state, j));
    let before = current(state, spacing, &points);
    if before.count == 0 {
        return false;
    }
    state.set_plane(j, candidate);
    if let Some(verdicts) = judge(state, spacing, &points, &before) {
        commit(state, verdicts);
        return true;
    }
    state.set_plane(j, old);
    false
}

/// After a flip of the quad's diagonal that did not pay by itself: tilts of the quad's
/// planes, smallest first, until one makes the flip and the tilt together lower the number
/// of invalid facets around them. Restores the planes when none does.
fn rescue_flip(state: &mut State<'_>, exact: &[Plane], spacing: &[f64], quad: [u32; 4]) -> bool {
    for &degrees in RESCUE_TILT_STEPS_DEGREES {
        for j in quad {
            let old = state.planes[j as usize];
            let mut changed = polygons_of_plane(state, j);
            changed.extend_from_slice(&quad);
            let points = judged_around(state, &changed);
            // The verdicts still describe the mesh before the flip (the reach is measured
            // after it, which only makes the test stricter for polygons the flip stretched).
            let before = current(state, spacing, &points);
            for d in 0..PLANE_TILT_DIRECTIONS {
                let phi = std::f64::consts::TAU * d as f64 / PLANE_TILT_DIRECTIONS as f64;
                state.set_plane(j, tilted(&exact[j as usize], degrees, phi));
                if let Some(verdicts) = judge(state, spacing, &points, &before) {
                    commit(state, verdicts);
                    return true;
                }
            }
            state.set_plane(j, old);
        }
    }
    false
}

/// The points whose polygons a new plane of point j changes: j and its neighbours.
fn polygons_of_plane(state: &State<'_>, j: u32) -> Vec<u32> {
    affected_points(state.tri, &state.incident, &[j])
}

/// The judged points whose verdict can change when the polygons of `changed` change: them
/// and their neighbours (overlap is judged between neighbours).
fn judged_around(state: &State<'_>, changed: &[u32]) -> Vec<u32> {
    let mut points = affected_points(state.tri, &state.incident, changed);
    points.retain(|&x| (x as usize) < state.invalid.len());
    points
}

/// How bad the invalid facets among some points are, compared lexicographically: how many,
/// then their summed [`State::tangle`] (crossing edge pairs), then their summed reach.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Badness {
    count: usize,
    tangle: usize,
    reach: f64,
}

impl Badness {
    fn of(state: &mut State<'_>, spacing: &[f64], invalid: &[u32]) -> Self {
        let mut tangle = 0usize;
        let mut reach = 0.0;
        for &x in invalid {
            tangle = tangle.saturating_add(state.tangle(x));
            reach += state.reach(x, spacing[x as usize]);
        }
        Badness {
            count: invalid.len(),
            tangle,
            reach,
        }
    }

    /// Fewer invalid facets; or as many, less tangled; or as tangled, with their runaway
    /// vertices come back towards their seeds by [`REACH_GAIN`] (a runaway vertex is what
    /// usually makes a facet invalid, and it returns step by step).
    fn better_than(&self, before: &Badness) -> bool {
        self.count < before.count
            || (self.count == before.count
                && (self.tangle < before.tangle
                    || (self.tangle == before.tangle && self.reach < REACH_GAIN * before.reach)))
    }
}

/// The badness of `points` by their current verdicts.
fn current(state: &mut State<'_>, spacing: &[f64], points: &[u32]) -> Badness {
    let invalid: Vec<u32> = points
        .iter()
        .copied()
        .filter(|&x| state.invalid[x as usize])
        .collect();
    Badness::of(state, spacing, &invalid)
}

/// Fresh verdicts of `points` if they are better than `before`, None otherwise (known as soon
/// as more facets are invalid than before).
fn judge(
    state: &mut State<'_>,
    spacing: &[f64],
    points: &[u32],
    before: &Badness,
) -> Option<Vec<(u32, bool)>> {
    let mut verdicts = Vec::with_capacity(points.len());
    let mut invalid = Vec::new();
    // Those invalid before first: when they are all still invalid and no less bad, the move
    // cannot pay (every other facet can only add to the badness), and that is known after
    // judging only them, which is what most futile moves come to.
    let (was_invalid, was_valid): (Vec<u32>, Vec<u32>) =
        points.iter().partition(|&&x| state.invalid[x as usize]);
    for &x in &was_invalid {
        let v = state.facet_invalid(x);
        verdicts.push((x, v));
        if v {
            invalid.push(x);
        }
    }
    if invalid.len() == before.count && !Badness::of(state, spacing, &invalid).better_than(before) {
        return None;
    }
    for x in was_valid {
        let v = state.facet_invalid(x);
        verdicts.push((x, v));
        if v {
            invalid.push(x);
            if invalid.len() > before.count {
                return None;
            }
        }
    }
    Badness::of(state, spacing, &invalid)
        .better_than(before)
        .then_some(verdicts)
}

fn commit(state: &mut State<'_>, verdicts: Vec<(u32, bool)>) {
    for (x, v) in verdicts {
        state.set_verdict(x, v);
    }
}

/// Iterated local search around facet i, which the greedy moves left invalid: up to
/// [`PLANE_KICKS`] times, tilt one to three planes of i and its neighbours at random (within
/// [`MAX_PLANE_TILT_DEGREES`]), let the greedy moves (tilts, then flips with rescue tilts)
/// repair what that broke, and keep the whole when it leaves fewer invalid facets than
/// before; otherwise undo it (the journal logs flips as well as planes).
fn kick(
    state: &mut State<'_>,
    exact: &[Plane],
    spacing: &[f64],
    i: u32,
    budget: usize,
    plan: &KickPlan,
) -> bool {
    let mut rng = SplitMix64::new(0x7469_6c74 ^ u64::from(i) ^ plan.salt);
    for _ in 0..plan.kicks {
        if state.spent(budget) {
            return false;
        }
        let ring = polygons_of_plane(state, i);
        // The planes a restart may tilt: i's ring, or (wide) the ring of that ring.
        let pool = if plan.wide {
            affected_points(state.tri, &state.incident, &ring)
        } else {
            ring
        };
        state.journal = Some(Journal::default());
        for _ in 0..1 + rng.below(plan.most_planes) {
            let j = pool[rng.below(pool.len())];
            let degrees = MAX_PLANE_TILT_DEGREES * (0.2 + 0.8 * rng.next_f64());
            let phi = std::f64::consts::TAU * rng.next_f64();
            state.set_plane(j, tilted(&exact[j as usize], degrees, phi));
        }
        // The tilted planes are in the pool: their polygons reach one ring beyond it, the
        // verdicts that can change two (three rings from i, four when wide).
        let changed = affected_points(state.tri, &state.incident, &pool);
        let gain = judge_and_repair(state, exact, spacing, &changed, budget);
        if gain < 0 {
            state.journal = None;
            return true;
        }
        state.undo();
    }
    false
}

/// After a journalled change (a restart's tilts, a restructure's flips) whose polygons lie
/// among `changed`: the verdicts around them renewed, then [`KICK_REPAIR_PASSES`] greedy
/// passes ([`try_move`]) over the facets there still invalid, stopping once `budget` plane
/// changes are spent (past it the change is judged as it stands). Returns the change in the
/// number of invalid facets since the journal began (negative: fewer).
fn judge_and_repair(
    state: &mut State<'_>,
    exact: &[Plane],
    spacing: &[f64],
    changed: &[u32],
    budget: usize,
) -> isize {
    let points = judged_around(state, changed);
    let verdicts: Vec<(u32, bool)> = points
        .iter()
        .map(|&x| (x, state.facet_invalid(x)))
        .collect();
    commit(state, verdicts);
    for _ in 0..KICK_REPAIR_PASSES {
        if state.spent(budget) {
            break;
        }
        let mut any = false;
        for &x in &points {
            if state.invalid[x as usize] {
                any |= try_move(state, exact, spacing, x);
            }
        }
        if !any {
            break;
        }
    }
    state
        .journal
        .as_ref()
        .map_or(0, |journal| journal.invalid_gain(&state.invalid))
}

/// How a series of random restarts around one facet is drawn ([`kick`]).
struct KickPlan {
    /// Restarts tried.
    kicks: usize,
    /// Mixed into the seed of the restarts, so that another series draws other tilts.
    salt: u64,
    /// Planes tilted at random per restart: 1 to this many.
    most_planes: usize,
    /// Whether the tilted planes are drawn from two rings around the facet, not one.
    wide: bool,
}

/// The restarts of the kick rounds.
const KICK: KickPlan = KickPlan {
    kicks: PLANE_KICKS,
    salt: 0,
    most_planes: 3,
    wide: false,
};

/// The last resort for the few facets the kick rounds leave invalid (at most
/// [`ESCALATION_MAX_INVALID`]; more means a surface where tilts cannot help): further series
/// of restarts around each, drawn afresh in each round (a new salt), every other round from
/// two rings around the facet with up to four planes tilted at once (a cluster at a
/// parabolic line whose facets need several planes moved together), until none is left,
/// [`ESCALATION_ROUNDS`] rounds have run or [`ESCALATION_BUDGET_PER_INVALID`] plane changes
/// per facet left have been spent. Where the kick rounds left nothing, nothing changes.
fn escalate(state: &mut State<'_>, exact: &[Plane], spacing: &[f64], stats: &mut PlaneAdjustStats) {
    let left = state.invalid.iter().filter(|&&x| x).count();
    if left == 0 || left > ESCALATION_MAX_INVALID {
        return;
    }
    let budget = state.plane_changes + ESCALATION_BUDGET_PER_INVALID * left;
    for round in 0..ESCALATION_ROUNDS {
        let wide = round % 2 == 1;
        let plan = KickPlan {
            kicks: ESCALATION_KICKS,
            salt: 0x6573_6361_6c61_7465_u64.wrapping_mul(round as u64 + 1),
            most_planes: if wide { 4 } else { 3 },
            wide,
        };
        let queue: Vec<u32> = (0..state.invalid.len() as u32)
            .filter(|&i| state.invalid[i as usize])
            .collect();
        if queue.is_empty() {
            return;
        }
        for i in queue {
            if state.spent(budget) {
                return;
            }
            if state.invalid[i as usize] && restructure(state, exact, spacing, i) {
                stats.tilts += 1;
            }
            if state.invalid[i as usize] && kick(state, exact, spacing, i, budget, &plan) {
                stats.tilts += 1;
            }
        }
    }
}

/// A targeted move for facet i where its neighbours are wrong, not its planes: near a
/// parabolic line the |II| metric degenerates and the neighbours of a facet may include
/// seeds several spacings away (a hex facet of 12 to 18 sides), which no tilt within
/// [`MAX_PLANE_TILT_DEGREES`] can make valid. The star and link edges of i are flipped
/// towards the isotropic Delaunay triangulation of the seeds seen along i's normal
/// ([`State::isotropic_flips_around`], at most [`RESTRUCTURE_FLIPS`]), the region's
/// verdicts renewed, and the greedy moves (tilts, flips with rescue tilts) given
/// [`KICK_REPAIR_PASSES`] passes over its invalid facets; the whole is kept when it leaves
/// no more invalid facets than before (whether fewer is returned), undone otherwise.
fn restructure(state: &mut State<'_>, exact: &[Plane], spacing: &[f64], i: u32) -> bool {
    let seeds: Vec<DVec3> = exact.iter().map(|p| p.point).collect();
    state.journal = Some(Journal::default());
    let flips =
        state.isotropic_flips_around(i, &seeds, exact[i as usize].normal, RESTRUCTURE_FLIPS);
    if flips == 0 {
        state.undo();
        return false;
    }
    // The flipped quads lie within two rings of i (as it stands now); the verdicts that can
    // change, one ring further.
    let ring = polygons_of_plane(state, i);
    let changed = affected_points(state.tri, &state.incident, &ring);
    let gain = judge_and_repair(state, exact, spacing, &changed, usize::MAX);
    // As many invalid facets with neighbours closer to the isotropic ones is kept too: the
    // restarts that follow then start from the better structure.
    if gain <= 0 {
        state.journal = None;
        return gain < 0;
    }
    state.undo();
    false
}

/// The tilt of `plane` against the exact tangent plane with unit normal `normal` at `seed`,
/// in degrees, and the plane's signed offset from the seed along its normal.
pub(crate) fn tilt_and_offset(plane: &Plane, seed: DVec3, normal: DVec3) -> (f64, f64) {
    let cos = plane.normal.dot(normal).clamp(-1.0, 1.0);
    let sin = plane.normal.cross(normal).length();
    (
        sin.atan2(cos).to_degrees(),
        plane.normal.dot(plane.point - seed),
    )
}
