//! Stage 2 of the pipeline: samples -> the dual structure.
//!
//! Which seeds are neighbours (the triangles of the dual triangulation, each the meeting point
//! of three tangent planes) and how the facets are then built ([`FacetPlan`]). One path is
//! chosen per surface, in this order:
//!
//! 1. **Closed and convex** (closed one way or both, every seed on one convex side, not
//!    trimmed): the envelope of the tangent planes is the convex hull of the dual points
//!    (n_i, n_i . p_i) ([`crate::closed`]), with ghost seeds beyond the open sides
//!    ([`crate::ghosts`]). Facets: [`FacetPlan::Ghosts`].
//! 2. **Developable** with rulings along parameter lines, every seed flat (K ~ 0): strips
//!    between the rulings ([`crate::rulings`]), an annulus when closed across them. Facets:
//!    [`FacetPlan::Ghosts`] (clipped on a trim).
//! 3. **Convex, within the slope frame**: the regular triangulation of the slopes
//!    s_i = (n_i . e1, n_i . e2) / (n_i . N) lifted to heights h_i = -sigma (n_i . p_i) /
//!    (n_i . N), built directly ([`crate::regular`]; on degenerate input Delaunay, then
//!    exact power flips), then oriented, ordered and trimmed
//!    ([`crate::neighbours::decide_convex`]).
//!    This is the envelope's structure exactly. Facets: [`FacetPlan::Clipped`].
//! 4. **Convex but too steep** for the slope frame: parameter-space Delaunay candidates,
//!    repaired against the envelope ([`crate::neighbours::decide`]). [`FacetPlan::Clipped`].
//!    A closed surface whose seeds are all convex but whose tangent planes have no envelope
//!    (path 1 failed: creases, as on a pinched sphere) goes to path 6 instead.
//! 5. **Flat**: every plane the same; the Voronoi diagram of the seeds in it
//!    ([`crate::flat`]), on a band boundary where the plane is closed one way.
//!    [`FacetPlan::Clipped`].
//! 6. **Any curvature** (saddles, mixed): the seeds and their ghosts mirrored beyond the
//!    boundary or trim, Delaunay in the |II| metric and validity flips
//!    ([`crate::neighbours::decide`]); on a surface closed one way the structure folded
//!    across the seam ([`crate::periodic`]). With [`PlaneMode::Adjusted`] a few planes are
//!    then tilted ([`crate::adjusted_planes`]). Facets: [`FacetPlan::Augmented`].
//!
//! A trimmed developable surface whose strips cannot be built, and live editing of a trim,
//! are refused ([`TpiError::TrimUnsupported`]).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::adjusted_planes::{adjust_planes, PlaneAdjustStats};
use crate::boundary::Boundary;
use crate::closed::{self, SurfaceLayout};
use crate::diagnostics::Diagnostic;
use crate::diffgeo::{flat_curvatures, LocalGeometry};
use crate::discretise::{
    check_closed_seeds, check_not_collinear, ms, plane_extent, DiscretiseOptions, MeshTopology,
    PlaneMode, Timings,
};
use crate::error::TpiError;
use crate::flat;
use crate::ghosts::{augment, augment_within_trim, Augmented};
use crate::neighbours::{decide, decide_convex, NeighbourInput, NeighbourStats};
use crate::periodic;
use crate::planes::{coincident, Plane};
use crate::progress::{Stage, Stages};
use crate::regular::regular_triangulation;
use crate::rulings;
use crate::samples::Samples;
use crate::surface::Surface;
use crate::tolerance::{
    FALLBACK_GIVE_UP, FALLBACK_REACH, MAX_REACH, METRIC_REGULARISATION,
    METRIC_REGULARISATION_RETRIES, RETRY_MAX_INVALID, SPECULATION_DELAY_MS, STRIP_TRIM_MARGIN,
};
use crate::triangulation::{real_pairs, DualTriangulation};

/// How the facet stage builds the facets of a [`DualStructure`].
pub(crate) enum FacetPlan {
    /// The real seeds alone; facets ending where their edges cross the boundary's wall (the
    /// convex and flat paths). `band`: a flat surface closed one way, ending only on its open
    /// sides.
    Clipped {
        /// The band boundary replacing the stage's boundary, when there is one.
        band: Option<Boundary>,
    },
    /// Every facet closed by the planes of its neighbours, ghosts included (closed convex
    /// surfaces, strips): `planes` of every point of the triangulation, `source` the real
    /// seed of each (itself for the first `uv.len()`).
    Ghosts {
        /// Planes of the seeds followed by the ghosts'.
        planes: Vec<Plane>,
        /// The real seed of every point.
        source: Vec<u32>,
        /// The strips of a developable surface (path 2).
        strips: bool,
    },
    /// The any-curvature path's seeds and ghosts, every real facet closed by them; `on_wall`:
    /// the ghosts are mirrored across the boundary or trim (not a structure folded across a
    /// seam), and the facets are clipped on its wall where that keeps the mesh's shape.
    Augmented {
        /// Seeds and ghosts.
        seeds: Augmented,
        /// Clip on the boundary's wall.
        on_wall: bool,
    },
}

/// The result of the dual-structure stage.
pub(crate) struct DualStructure {
    /// The dual triangulation over the seeds (and the plan's ghosts).
    pub(crate) triangulation: DualTriangulation,
    /// How the facets are built.
    pub(crate) plan: FacetPlan,
    /// What the decision did.
    pub(crate) neighbours: NeighbourStats,
    /// The topology the mesh must have.
    pub(crate) topology: MeshTopology,
}

impl DualStructure {
    /// Whether these are the strips of a developable surface (path 2).
    pub(crate) fn is_strips(&self) -> bool {
        matches!(self.plan, FacetPlan::Ghosts { strips: true, .. })
    }
}

/// The stage's inputs besides the samples.
pub(crate) struct StructureInput<'a> {
    /// The surface.
    pub(crate) surface: &'a dyn Surface,
    /// The validated pattern (normalised).
    pub(crate) pattern: &'a [[f64; 2]],
    /// The pipeline's options.
    pub(crate) options: &'a DiscretiseOptions,
    /// Where the facets end: the domain rectangle or a trim.
    pub(crate) boundary: &'a Boundary,
    /// Whether a developable surface may take the strips.
    pub(crate) allow_strips: bool,
    /// Which sides of the domain meet or collapse ([`closed::surface_layout`]).
    pub(crate) layout: &'a SurfaceLayout,
}

/// Decides the dual structure of the samples (module doc). Adjusted planes replace the
/// samples' planes where they are tilted; diagnostics of the decision are appended to the
/// samples'. Times the triangulation and the decision into `timings`.
pub(crate) fn decide_structure(
    input: &StructureInput<'_>,
    samples: &mut Samples,
    timings: &mut Timings,
    stages: &Stages<'_>,
) -> Result<DualStructure, TpiError> {
    let StructureInput {
        surface,
        pattern,
        options,
        boundary,
        allow_strips,
        layout,
    } = *input;
    let layout = *layout;
    let weld = options.weld_tolerance * samples.diagonal;
    let convex = samples
        .convex_side
        .iter()
        .all(|&s| s != 0 && s == samples.convex_side[0]);
    let closable = layout.open_sides().is_some() && convex && !boundary.is_trim();
    // Seeds on a pole are refused everywhere, and seeds on one surface point across the seam
    // where the seam is to be closed.
    if layout.poles.contains(&true) || closable {
        let regular: Vec<bool> = if samples.geometry.len() == samples.uv.len() {
            samples.geometry.iter().map(|g| g.regular).collect()
        } else {
            vec![true; samples.uv.len()]
        };
        check_closed_seeds(
            surface,
            &layout,
            &samples.uv,
            &samples.planes,
            &regular,
            closable,
            weld,
        )?;
    }

    // Path 1: closed and convex.
    let hull_stage = Instant::now();
    let mut topology = None;
    let mut ghosts: Option<(Vec<Plane>, Vec<u32>)> = None;
    let mut envelope = None;
    if let Some(open) = layout.open_sides().filter(|_| closable) {
        // Timed as the triangulation when the hull succeeds.
        stages.enter(Stage::Delaunay, None);
        let holes = open.iter().filter(|&&o| o).count();
        if holes == 0 {
            envelope = closed::envelope_triangulation(&samples.planes, samples.planes.len()).ok();
        } else {
            let augmented = augment_open_sides(surface, samples, pattern, open);
            envelope = closed::envelope_triangulation(&augmented.planes, samples.uv.len()).ok();
            ghosts = Some((augmented.planes, augmented.source));
        }
        if envelope.is_some() {
            topology = Some(MeshTopology {
                euler: 2 - holes as i64,
                boundary_loops: holes,
            });
        }
    }
    if let Some(triangulation) = envelope {
        check_not_collinear(&samples.plane_uv)?;
        timings.delaunay = ms(hull_stage);
        let (planes, source) = ghosts.unwrap_or_else(|| identity_ghosts(&samples.planes));
        return Ok(DualStructure {
            triangulation,
            plan: FacetPlan::Ghosts {
                planes,
                source,
                strips: false,
            },
            neighbours: NeighbourStats::default(),
            topology: topology.unwrap_or(MeshTopology::DISC),
        });
    }

    // Path 2: strips of a developable surface. Rulings are sampled only where every seed is
    // flat (K ~ 0): elsewhere they cannot be.
    let flat_seeds = samples
        .curvatures
        .iter()
        .all(|&[k1, k2]| flat_curvatures(k1, k2));
    let rulings = flat_seeds.then(|| rulings::find_rulings(surface)).flatten();
    let trimmed = boundary.is_trim();
    if let Some(r) = rulings.filter(|_| allow_strips) {
        let closed = layout.closed[1 - r.along];
        if closed && !trimmed {
            check_seam(surface, &layout, samples, weld)?;
        }
        stages.enter(Stage::Delaunay, None);
        // Trimmed: walls beyond the domain, the strips clipped on the trim by the facet stage.
        let margin = if trimmed {
            STRIP_TRIM_MARGIN * samples.diagonal
        } else {
            0.0
        };
        let strips =
            rulings::strip_structure(surface, r, &samples.uv, &samples.planes, closed, margin);
        if let Some((triangulation, planes, source)) = strips {
            check_not_collinear(&samples.plane_uv)?;
            timings.delaunay = ms(hull_stage);
            // Their zero curvature is what the strips are built for, not a defect to flag.
            samples
                .diagnostics
                .retain(|d| !matches!(d, Diagnostic::FlatPoint { .. }));
            samples.diagnostics.push(Diagnostic::RulingStrips {
                direction: r.along as u8,
                closed,
            });
            if !closed {
                note_open_seam(samples, &layout);
            }
            return Ok(DualStructure {
                triangulation,
                plan: FacetPlan::Ghosts {
                    planes,
                    source,
                    strips: true,
                },
                neighbours: NeighbourStats::default(),
                topology: if closed && !trimmed {
                    MeshTopology {
                        euler: 0,
                        boundary_loops: 2,
                    }
                } else {
                    MeshTopology::DISC
                },
            });
        }
    }

    let stage = Instant::now();
    let flat = samples
        .planes
        .iter()
        .all(|p| coincident(&samples.planes[0], p));
    check_not_collinear(&samples.plane_uv)?;
    let neighbour_input = NeighbourInput {
        plane_uv: &samples.plane_uv,
        geometry: &samples.geometry,
        planes: &samples.planes,
        convex_side: &samples.convex_side,
        any_curvature: false,
        metric_regularisation: METRIC_REGULARISATION,
        stop: None,
        runaway_limit: false,
    };
    // Each path with whether it closed the seam of a closed surface.
    let (structure, seam_closed) = match (&samples.slopes, &samples.lifted) {
        // Path 3: convex everywhere, the envelope's own structure in slope space.
        (Some(slopes), Some(lifted)) => {
            stages.enter(Stage::Delaunay, None);
            // The regular triangulation directly; on degenerate input Delaunay, then flips.
            let direct = regular_triangulation(lifted);
            let regular = direct.is_some();
            let mut triangulation = match direct {
                Some(triangulation) => triangulation,
                None => DualTriangulation::delaunay(slopes)?,
            };
            stages.check()?;
            timings.delaunay = ms(stage);
            let stage = Instant::now();
            let neighbours = decide_convex(
                &mut triangulation,
                slopes,
                lifted,
                regular,
                &neighbour_input,
                stages,
            );
            timings.neighbours = ms(stage);
            (
                clipped(triangulation, neighbours, None, MeshTopology::DISC),
                false,
            )
        }
        // Path 4: strictly convex everywhere but too steep for the slope embedding. Not for
        // a closed surface that path 1 refused: its seeds look convex, but its tangent planes
        // have no envelope (a sphere pinched into concave creases), and as an open patch it
        // would leave its seam and poles open; the any-curvature path closes them.
        _ if convex && !closable => {
            stages.enter(Stage::Delaunay, None);
            let mut triangulation = DualTriangulation::delaunay(&samples.plane_uv)?;
            stages.check()?;
            timings.delaunay = ms(stage);
            let stage = Instant::now();
            stages.enter(Stage::Neighbours, None);
            let neighbours = decide(
                &mut triangulation,
                &neighbour_input,
                options.envelope_repair,
                samples.plane_uv.len(),
            );
            timings.neighbours = ms(stage);
            (
                clipped(triangulation, neighbours, None, MeshTopology::DISC),
                false,
            )
        }
        // Path 5: a flat surface, the Voronoi cells of the seeds in its plane.
        _ if flat => {
            let mut band = None;
            let mut topology = MeshTopology::DISC;
            if let Some(walls) = layout.open_sides().filter(|_| !trimmed) {
                check_seam(surface, &layout, samples, weld)?;
                let open = walls.iter().filter(|&&w| w).count();
                topology = MeshTopology {
                    euler: 2 - open as i64,
                    boundary_loops: open,
                };
                band = Some(Boundary::Band {
                    domain: surface.domain(),
                    walls,
                    closed: layout.closed,
                });
            }
            stages.enter(Stage::Delaunay, None);
            let triangulation = flat::voronoi_dual(&samples.planes)?;
            timings.delaunay = ms(stage);
            // Zero curvature is what this path is for, not a defect to flag; every neighbour
            // pair is separated by its bisector.
            samples
                .diagnostics
                .retain(|d| !matches!(d, Diagnostic::FlatPoint { .. }));
            samples.diagnostics.push(Diagnostic::CoincidentPlanes {
                pairs: real_pairs(&triangulation, samples.planes.len()).len() as u32,
            });
            let seam_closed = band.is_some();
            let structure = clipped(triangulation, NeighbourStats::default(), band, topology);
            (structure, seam_closed)
        }
        // A trimmed cylinder, cone or extrusion whose strips could not be built (seeds of
        // several rulings on one plane): the ghosts' triangulation would give no valid mesh.
        _ if trimmed && rulings.is_some() => {
            return Err(TpiError::TrimUnsupported {
                reason: "the surface is developable (a cylinder, cone or extrusion: its facets are strips along its rulings), and these seeds give no strips (several rulings share one tangent plane)".into(),
            });
        }
        // Path 6: saddles and mixed curvature.
        _ => any_curvature(input, samples, &layout, timings, stages, stage)?,
    };
    if !seam_closed {
        note_open_seam(samples, &layout);
    }
    Ok(structure)
}

/// Names the first closed direction of a surface whose seam the structure left open.
fn note_open_seam(samples: &mut Samples, layout: &SurfaceLayout) {
    if let Some(k) = (0..2).find(|&k| layout.closed[k]) {
        samples
            .diagnostics
            .push(Diagnostic::SeamLeftOpen { direction: k as u8 });
    }
}

/// No two seeds on one surface point across the seam of a surface about to be closed
/// (`weld`: the weld distance).
fn check_seam(
    surface: &dyn Surface,
    layout: &SurfaceLayout,
    samples: &Samples,
    weld: f64,
) -> Result<(), TpiError> {
    let regular = vec![true; samples.uv.len()];
    check_closed_seeds(
        surface,
        layout,
        &samples.uv,
        &samples.planes,
        &regular,
        true,
        weld,
    )
}

/// A structure whose facets are clipped on the boundary.
fn clipped(
    triangulation: DualTriangulation,
    neighbours: NeighbourStats,
    band: Option<Boundary>,
    topology: MeshTopology,
) -> DualStructure {
    DualStructure {
        triangulation,
        plan: FacetPlan::Clipped { band },
        neighbours,
        topology,
    }
}

/// One decision of the neighbours (and with adjusted planes, of the planes).
struct Attempt {
    triangulation: DualTriangulation,
    planes: Vec<Plane>,
    neighbours: NeighbourStats,
    adjusted: Option<PlaneAdjustStats>,
}

impl Attempt {
    /// Facets left invalid by the local test: after the plane adjustment, or after the
    /// validity flips with exact planes.
    fn left(&self) -> usize {
        self.adjusted
            .map_or(self.neighbours.validity_unresolved, |a| a.unresolved)
    }
}

/// The neighbours decided (and with `adjust`, a reach, the planes adjusted with that reach)
/// again from the Delaunay triangulation of the seeds and ghosts `augmented` with their exact
/// planes `exact`, with each of the isotropic terms' `weights` in turn: for a structure whose
/// decision with [`METRIC_REGULARISATION`] left 1 to [`RETRY_MAX_INVALID`] facets invalid,
/// the weights of [`METRIC_REGULARISATION_RETRIES`]; for adjusted planes still invalid after
/// that, every weight with [`FALLBACK_REACH`]. Near a parabolic line, and where the saddle's
/// metric is strongly anisotropic, the isotropic term decides how far the facets run along
/// the flat direction, and a facet that neither flips nor tilts within 5 degrees repair with
/// one weight is often valid with another. Returns the attempt that left the fewest facets
/// invalid (the first of equals; it stops at none, and after an attempt that left more than
/// `give_up` where given), or None without weights. A cancellation seen by `stages` is
/// answered between attempts.
///
/// `first`, where given, is the attempt with `weights[0]`, already made. The attempts are
/// independent searches, so each is made beside the one before it (`rayon::join`; on two
/// cores the wall time of a chain of attempts about halves): the later one is told to stop
/// as soon as the earlier ends the search, and is dropped then. The result is the
/// sequential one's, attempt for attempt.
#[allow(clippy::too_many_arguments)]
fn decide_again(
    augmented: &Augmented,
    exact: Vec<Plane>,
    envelope_repair: bool,
    n: usize,
    adjust: Option<f64>,
    weights: &[f64],
    give_up: Option<usize>,
    first: Option<Result<Attempt, TpiError>>,
    stages: &Stages<'_>,
) -> Result<Option<Attempt>, TpiError> {
    let run = |weight: f64, stop: Option<&AtomicBool>| {
        attempt(
            &Reseed {
                plane_uv: &augmented.plane_uv,
                geometry: &augmented.geometry,
                convex_side: &augmented.convex_side,
                exact: &exact,
            },
            envelope_repair,
            n,
            adjust,
            weight,
            stop,
        )
    };
    // Whether the search ends after this attempt, whatever came before: none left (then it
    // is the best), or more than `give_up`.
    let ends = |attempt: &Attempt| {
        attempt.left() == 0 || give_up.is_some_and(|most| attempt.left() > most)
    };
    let mut best: Option<Attempt> = None;
    // The attempt with weights[k], where made beside the one before it.
    let mut known = first;
    for (k, &weight) in weights.iter().enumerate() {
        stages.check()?;
        let (current, next) = match (known.take(), weights.get(k + 1)) {
            (Some(current), _) => (current, None),
            (None, Some(&later)) => {
                let stop = AtomicBool::new(false);
                rayon::join(
                    || {
                        let current = run(weight, None);
                        if current.as_ref().map_or(true, ends) {
                            stop.store(true, Ordering::Relaxed);
                        }
                        current
                    },
                    || speculate(&stop, || run(later, Some(&stop))),
                )
            }
            (None, None) => (run(weight, None), None),
        };
        let attempt = current?;
        let done = ends(&attempt);
        if best.as_ref().map_or(true, |b| attempt.left() < b.left()) {
            best = Some(attempt);
        }
        if done {
            break;
        }
        // Made beside this one, which did not end the search: never stopped.
        known = next;
    }
    Ok(best)
}

/// What a decision from scratch reads: the seeds' and ghosts' embedding, local geometry and
/// convex sides, and their exact planes.
struct Reseed<'a> {
    plane_uv: &'a [[f64; 2]],
    geometry: &'a [LocalGeometry],
    convex_side: &'a [i8],
    exact: &'a [Plane],
}

/// `make()` unless `stop` is set before it starts, and its result unless `stop` was set by
/// the time it ends (then it may have been cut short): a speculative computation whose
/// result is wanted only if the one beside it did not end the search.
fn speculate<T>(stop: &AtomicBool, make: impl FnOnce() -> T) -> Option<T> {
    if stop.load(Ordering::Relaxed) {
        return None;
    }
    let made = make();
    (!stop.load(Ordering::Relaxed)).then_some(made)
}

/// One attempt of [`decide_again`]: the neighbours decided from the Delaunay triangulation
/// with the isotropic term `weight`, then with `adjust` the planes adjusted with that reach.
/// Once `stop` is set the searches end early and the attempt is to be dropped.
fn attempt(
    seeds: &Reseed<'_>,
    envelope_repair: bool,
    n: usize,
    adjust: Option<f64>,
    weight: f64,
    stop: Option<&AtomicBool>,
) -> Result<Attempt, TpiError> {
    let mut triangulation = DualTriangulation::delaunay(seeds.plane_uv)?;
    let input = NeighbourInput {
        plane_uv: seeds.plane_uv,
        geometry: seeds.geometry,
        planes: seeds.exact,
        convex_side: seeds.convex_side,
        any_curvature: true,
        metric_regularisation: weight,
        stop,
        // Exact planes (no adjustment follows): runaway facets are brought in.
        runaway_limit: adjust.is_none(),
    };
    let neighbours = decide(&mut triangulation, &input, envelope_repair, n);
    let mut planes = seeds.exact.to_vec();
    let adjusted =
        adjust.map(|reach| adjust_planes(&mut triangulation, &mut planes, n, reach, stop));
    Ok(Attempt {
        triangulation,
        planes,
        neighbours,
        adjusted,
    })
}

/// The real seeds' own planes as the ghosts' plan of a structure without ghosts.
fn identity_ghosts(planes: &[Plane]) -> (Vec<Plane>, Vec<u32>) {
    (planes.to_vec(), (0..planes.len() as u32).collect())
}

/// The seeds and their ghosts beyond the `open` sides (u0, u1, v0, v1) of the domain.
fn augment_open_sides(
    surface: &dyn Surface,
    samples: &Samples,
    pattern: &[[f64; 2]],
    open: [bool; 4],
) -> Augmented {
    // The slope path lets the local geometry go: the ghosts need it.
    let recomputed: Vec<LocalGeometry>;
    let full: &[LocalGeometry] = if samples.geometry.len() == samples.uv.len() {
        &samples.geometry
    } else {
        recomputed = samples
            .uv
            .iter()
            .map(|&[u, v]| LocalGeometry::from_derivatives(&surface.evaluate(u, v)))
            .collect();
        &recomputed
    };
    let extent = plane_extent(&samples.plane_uv, pattern);
    augment(
        surface,
        &samples.uv,
        &samples.plane_uv,
        extent,
        full,
        &samples.convex_side,
        open,
    )
}

/// Path 6 (module doc): ghost seeds beyond the boundary (or the trim) close every real facet
/// for the validity flips; on a surface closed one way with open sides across it the
/// structure is folded into an annulus where it folds, else left open as on an open patch.
/// `stage` is when the triangulation started. Also returns whether the seam was closed.
fn any_curvature(
    input: &StructureInput<'_>,
    samples: &mut Samples,
    layout: &SurfaceLayout,
    timings: &mut Timings,
    stages: &Stages<'_>,
    stage: Instant,
) -> Result<(DualStructure, bool), TpiError> {
    let StructureInput {
        surface,
        pattern,
        options,
        boundary,
        ..
    } = *input;
    let n = samples.uv.len();
    let extent = plane_extent(&samples.plane_uv, pattern);
    let seam = layout.open_sides().filter(|_| !boundary.is_trim());
    let mut topology = MeshTopology::DISC;
    let mut folded = None;
    if let Some(open) = seam {
        check_seam(
            surface,
            layout,
            samples,
            options.weld_tolerance * samples.diagonal,
        )?;
        stages.enter(Stage::Neighbours, None);
        // Triangulation, decision and fold are one step, timed as the neighbours.
        folded = periodic::decide_folded(
            surface,
            &periodic::Points {
                uv: &samples.uv,
                plane_uv: &samples.plane_uv,
                geometry: &samples.geometry,
                convex_side: &samples.convex_side,
            },
            extent,
            open,
            usize::from(layout.closed[1]),
            options.envelope_repair,
        )?;
        if folded.is_some() {
            // Every open side is a boundary loop; poles are closed over.
            let open = open.iter().filter(|&&o| o).count();
            topology = MeshTopology {
                euler: 2 - open as i64,
                boundary_loops: open,
            };
        }
    }
    let seam_closed = folded.is_some();
    let (mut triangulation, mut augmented, mut neighbours) = match folded {
        Some(structure) => {
            timings.neighbours = ms(stage);
            structure
        }
        None => {
            stages.enter(Stage::Delaunay, None);
            let augmented = if boundary.is_trim() {
                augment_within_trim(
                    surface,
                    &samples.plane_uv,
                    extent,
                    &samples.geometry,
                    &samples.convex_side,
                    boundary,
                )
            } else {
                augment(
                    surface,
                    &samples.uv,
                    &samples.plane_uv,
                    extent,
                    &samples.geometry,
                    &samples.convex_side,
                    [true; 4],
                )
            };
            let mut triangulation = DualTriangulation::delaunay(&augmented.plane_uv)?;
            stages.check()?;
            timings.delaunay = ms(stage);
            let stage = Instant::now();
            stages.enter(Stage::Neighbours, None);
            let augmented_input = NeighbourInput {
                plane_uv: &augmented.plane_uv,
                geometry: &augmented.geometry,
                planes: &augmented.planes,
                convex_side: &augmented.convex_side,
                any_curvature: true,
                metric_regularisation: METRIC_REGULARISATION,
                stop: None,
                runaway_limit: options.planes == PlaneMode::Exact,
            };
            let neighbours = decide(
                &mut triangulation,
                &augmented_input,
                options.envelope_repair,
                n,
            );
            timings.neighbours = ms(stage);
            (triangulation, augmented, neighbours)
        }
    };
    let adjusted = options.planes == PlaneMode::Adjusted;
    // The plane adjustment and a second decision decide planes and flip edges: their time
    // counts as the neighbours'.
    let adjust = Instant::now();
    // The exact planes, kept where the adjustment may need them again.
    let exact = (adjusted && !seam_closed).then(|| augmented.planes.clone());
    // Where a second decision may follow, its first attempt is made beside the adjustment
    // ([`decide_again`]), and dropped as soon as the adjustment leaves none or too many.
    let (mut stats, first_retry) = match (&exact, METRIC_REGULARISATION_RETRIES.first()) {
        (Some(exact), Some(&weight)) => {
            let (stop, adjusted) = (AtomicBool::new(false), AtomicBool::new(false));
            let (stats, retry) = rayon::join(
                || {
                    let stats = adjust_planes(
                        &mut triangulation,
                        &mut augmented.planes,
                        n,
                        MAX_REACH,
                        None,
                    );
                    if !(1..=RETRY_MAX_INVALID).contains(&stats.unresolved) {
                        stop.store(true, Ordering::Relaxed);
                    }
                    adjusted.store(true, Ordering::Release);
                    stats
                },
                || {
                    // Only beside an adjustment that runs long: most end sooner.
                    let start = Instant::now();
                    let delay = Duration::from_millis(SPECULATION_DELAY_MS);
                    while !adjusted.load(Ordering::Acquire) && start.elapsed() < delay {
                        std::thread::sleep(Duration::from_millis(1));
                    }
                    let seeds = Reseed {
                        plane_uv: &augmented.plane_uv,
                        geometry: &augmented.geometry,
                        convex_side: &augmented.convex_side,
                        exact,
                    };
                    let envelope_repair = options.envelope_repair;
                    speculate(&stop, || {
                        attempt(
                            &seeds,
                            envelope_repair,
                            n,
                            Some(MAX_REACH),
                            weight,
                            Some(&stop),
                        )
                    })
                },
            );
            (Some(stats), retry)
        }
        _ => (
            adjusted.then(|| {
                adjust_planes(
                    &mut triangulation,
                    &mut augmented.planes,
                    n,
                    MAX_REACH,
                    None,
                )
            }),
            None,
        ),
    };
    let mut left = stats.map_or(neighbours.validity_unresolved, |s| s.unresolved);
    // Many left (a nearly developable surface, where neither flips nor tilts help) are not
    // decided again; folded structures are decided with the fold, and not again.
    if !seam_closed && (1..=RETRY_MAX_INVALID).contains(&left) {
        let exact = exact.clone().unwrap_or_else(|| augmented.planes.clone());
        let retried = decide_again(
            &augmented,
            exact,
            options.envelope_repair,
            n,
            adjusted.then_some(MAX_REACH),
            METRIC_REGULARISATION_RETRIES,
            None,
            first_retry,
            stages,
        )?;
        if let Some(attempt) = retried.filter(|a| a.left() < left) {
            left = attempt.left();
            triangulation = attempt.triangulation;
            augmented.planes = attempt.planes;
            neighbours = attempt.neighbours;
            stats = attempt.adjusted;
        }
    }
    // Adjusted planes that still leave facets invalid: the whole adjustment again with the
    // longer reach of a nearly developable band, kept only where it leaves none (so a mesh
    // the first adjustment made valid is never touched, and one it did not is replaced only
    // by a valid one).
    if let (Some(exact), false, true) = (exact, seam_closed, left > 0) {
        let weights: Vec<f64> = std::iter::once(METRIC_REGULARISATION)
            .chain(METRIC_REGULARISATION_RETRIES.iter().copied())
            .collect();
        let retried = decide_again(
            &augmented,
            exact,
            options.envelope_repair,
            n,
            Some(FALLBACK_REACH),
            &weights,
            Some(FALLBACK_GIVE_UP),
            None,
            stages,
        )?;
        if let Some(attempt) = retried.filter(|a| a.left() == 0) {
            left = 0;
            triangulation = attempt.triangulation;
            augmented.planes = attempt.planes;
            neighbours = attempt.neighbours;
            stats = attempt.adjusted;
        }
    }
    timings.neighbours += ms(adjust);
    if let Some(stats) = stats {
        // The seeds are the tangent planes' (Samples::seeds).
        samples.tangent_planes = Some(std::mem::replace(
            &mut samples.planes,
            augmented.planes[..n].to_vec(),
        ));
        neighbours.plane_tilts = stats.tilts;
        neighbours.validity_unresolved = left;
    }
    let structure = DualStructure {
        triangulation,
        plan: FacetPlan::Augmented {
            seeds: augmented,
            on_wall: !seam_closed,
        },
        neighbours,
        topology,
    };
    Ok((structure, seam_closed))
}
