//! Tolerance-driven patterns: few pattern points whose TPI mesh keeps every vertex within a
//! distance D of the surface (issue 15, item 1).
//!
//! The geometry (DESIGN.md, items 3, 4, 7): near a seed the surface is z = 1/2 x^T II x over
//! its tangent plane, and three tangent planes meet above the circumcentre of their seeds in
//! the metric II, at 1/2 R^2 from the surface (R the circumradius in that metric; for a facet
//! of circumradius r on normal curvature k that is about k r^2 / 2). A hexagonal lattice of
//! spacing a in the metric |II| has R = a / sqrt(3), so the deviation D is met with
//! a = sqrt(6 D): the curvature sizing field M = |II| / (6 D) of `sizing.rs`, anisotropic
//! (cells long along the weakly curved direction) and with its curvatures floored so flat
//! places keep a finite spacing.
//!
//! Where a facet edge meets the boundary wall, its vertex stands off more than the interior
//! ones: two seeds a apart along a side, half a row (sqrt(3) a / 4) inside it, put the
//! vertex at R^2 = a^2 / 4 + 3 a^2 / 16 = 0.44 a^2 from both, against a^2 / 3 inside, and a
//! domain corner half a column beyond the last seed of a row at 0.75 a^2. So uniform hex
//! patterns, whose rows keep half a row from the sides, are set by their boundary and corners
//! (samples/nurbs-dome.json at D = 0.01: the largest deviation at a boundary vertex). Seeds
//! on the sides (points at s or t = 0 or 1) put the boundary vertices halfway between two
//! seeds of the side, at R^2 = a^2 / 4, and a seed on each corner puts the corner vertex on
//! it.
//!
//! [`fit_pattern`] first tries hexagonal lattices with rows on the sides t = 0, 1 and points
//! on the sides s = 0, 1 ([`wall_lattice`]), their steps in s and t graded by the field (even
//! in the largest metric length across each line) or uniform, each with every row closed on
//! s = 0, 1 or only the even ones (sparser sides, [`wall_hex`]): the size the field predicts,
//! then sizes predicted from the measured deviation, which goes as the square of the
//! spacing, and the lattices one row or one column off the one found (the rows follow the
//! columns by a rounded aspect). On surfaces without saddle points one more lattice grades
//! each row along itself ([`Grading::rowwise`]: rows near a dome's walls carry fewer
//! points than its middle row), cut by the walls s = 0, 1 and scanned over real column
//! counts (below the best pattern found so far), and one more lays the steeper grading's
//! rows so ([`Grading::cut`]); three more there have only their outer rows
//! [`FIT_WALL_INSET`] columns inside the walls t = 0, 1 ([`Grading::inset_rows`]: the
//! envelope's and the steeper grading with sparser sides, and the rowwise one). While the
//! best pattern is small ([`FIT_NEIGHBOUR_POINTS`]), two more lattices are graded by the envelope to the power [`FIT_STEEP_GRADING`], and on
//! saddles uniform ones have the row densities [`FIT_SADDLE_EXTRA_ROW_DENSITIES`]. Two
//! more graded lattices have their outer rows and columns [`FIT_WALL_INSET`] columns inside
//! the walls (a dome's wall vertex between two seeds a apart at e from the
//! wall is at R^2 = a^2 / 4 + e^2, the interior's a^2 / 3 at e = a / sqrt(12)); where the
//! surface has negative Gaussian curvature, six more have [`FIT_SADDLE_ROW_DENSITY`] times
//! the rows, the last two uniform with the sparser sides and inset from the walls (all four,
//! or only t = 0, 1: a saddle's wall of positive normal curvature puts the vertex between two
//! wall seeds a apart at a^2 / 4, three times the interior's a^2 / 12 below; samples/hypar.json
//! at D = 0.01 110 -> 71 points, samples/saddle.json at 0.01 and 0.03 149, 57 -> 132, 48).
//! On a saddle the vertex of three seeds is their circumcentre c in the indefinite
//! II and stands off |II(c)| / 2: in the metric |II| along the principal directions
//! (II = diag(1, -1)) the triangle 0, (a, 0), (a / 2, h) gives |II(c)| = (h^2 - a^2 / 4)^2 /
//! (4 h^2), a^2 / 12 for the regular hexagon (h = sqrt(3) a / 2, a quarter of a dome's a^2 / 3)
//! and 0 when its edges run along the asymptotic directions (h = a / 2, four planes in a
//! point): rows closer than the regular ones give cells longer along the asymptotic
//! directions for the same deviation. Up to [`FIT_ADAPTIVE_POINTS`] points, each lattice
//! found is also tried coarser, at the size where all but as many vertices as lie on the
//! boundary meet D, refined at its offending vertices as the rounds below are: a lattice is
//! often set by a few vertices along the walls or at the corners (on samples/hypar.json the
//! walls t = 0, 1, where seeds a apart on a wall of positive normal curvature put the vertex
//! between them at a^2 / 4, three times the saddle's interior a^2 / 12). Lattices of regular cells pay: the irregular cells of a Poisson-disk sampling
//! relaxed by Lloyd's iteration have larger circumcircles than a lattice of the same count
//! (samples/nurbs-dome.json at D = 0.0099: 512 points from the rounds below against 390 for
//! the uniform lattice). Unless the lattice already has more than [`FIT_ADAPTIVE_POINTS`]
//! points, it then runs for a bounded number of rounds (which serve saddles, whose
//! deviation the metric |II| overestimates):
//!
//! 1. a Poisson-disk sampling in the field's metric at radius [`FIT_POISSON_RADIUS`] (a
//!    maximal Poisson-disk set of radius 0.78 a has about as many points as a hexagonal
//!    lattice of spacing a), then [`FIT_LLOYD_ITERATIONS`] Lloyd iterations on the surface
//!    weighted by the field's density, which even the cells towards hexagons;
//! 2. the real discretisation (the caller's options, exact planes by default) and the
//!    deviation of every mesh vertex as the quality report measures it ([`vertex_deviations`]);
//! 3. the field's spacing scaled at every node by sqrt(tau / phi), phi the largest deviation
//!    of the nearby facets' vertices over D and tau = [`FIT_TARGET_RATIO`]: finer where D is
//!    exceeded, coarser where the deviation is far below it (bounded per round by
//!    [`FIT_MAX_STEP`]);
//!
//! and keeps the pattern of each round finished by local refinement: while some vertex
//! deviates more than D, a pattern point is added at the foot of each offending vertex
//! (worst first, one per neighbourhood), which splits the circle that vertex is the centre of.
//! The answer is the smallest finished pattern or lattice that meets D (with no invalid facet
//! when one was found without); when none meets D within [`FIT_REFINE_PASSES`] refinements,
//! the result says so ([`FittedPattern::met`]) and carries the closest attempt.
//!
//! Last, the lattices of the search that missed D narrowly ([`FIT_NEAR_MISS`]) with fewer
//! points than the best are relaxed towards a minimax covering ([`relax_near_misses`]). The
//! vertices of a facet are the centres of the circles through its seed and two neighbours,
//! so D is a covering condition: every vertex within its circumradius of the seeds, the
//! deviation c R^2 with c about k / 2. A lattice's cells are the thinnest covering, but
//! graded lattices cut by the walls leave their largest vertex deviation some per cent
//! above their mean (samples/paraboloid.json at D = 0.01: 0.993 D against a mean 0.943 D).
//! Lloyd's iteration evens the cells' areas, not their circumradii (the earlier sessions'
//! Lloyd steps from the lattices raised the largest deviation); the relaxation here moves
//! each seed towards the weighted 1-centre of its facet's vertices ([`minimax_step`]), the
//! place where the largest of its vertices' modelled deviations c_v |x - x_v|_M^2 is least,
//! which lowers the largest deviation towards the mean. Only near misses of mean deviation
//! at most [`FIT_NEAR_MEAN`] D are relaxed (the mean does not fall), fewest points first,
//! and a relaxation stops when its largest deviation falls too slowly to reach D. Besides
//! the near misses the search measured, each lattice search offers the smaller lattices of
//! its grading whose mean deviation, going as the inverse of the count, would be at most
//! [`FIT_NEAR_MEAN`] D ([`FIT_SMALLER_STEPS`]; not on saddles), relaxed after the measured
//! ones.
//!
//! How far this is from the best any pattern can do, on the two samples closest to uniform
//! (docs/performance.md, branch fit22). A hexagonal covering sized everywhere by its own
//! curvature puts a point on every (3 sqrt(3) / 2) R^2 of area, R^2 = D / (c w): on
//! samples/paraboloid.json (z = -0.08 r^2: every vertex exactly 0.08 R^2 above or below the
//! surface, R the circumradius of its seeds in the plane, about 0.08 R^2 / sqrt(1 + k^2 r^2)
//! off it along the normal, k = 0.16) that is 871 points at
//! D = 0.003, on samples/rational-dome.json (a sphere of radius 10, 179.5 of area,
//! R^2 = 2 rho D) 1,151; the strip the wall cells waste (0.144 a wide, the walls' rows inset
//! by a / sqrt(12)) adds 17 and 19. Against the smallest hex:NxN meeting D (1,521 and 2,025)
//! those bounds are 0.584 and 0.578: 0.60 with room is out of reach there for any pattern
//! (the fits, 937 and 1,268 points, are 5.5 % and 8.3 % above them). With regular cells the
//! mean vertex deviation is set by the count wherever the points go (a point of area A_p
//! carries two vertices of deviation c w A_p / (3 sqrt(3) / 2), so the mean is the integral
//! of c w over the area divided by 3 sqrt(3) N / 2): a relaxation only evens the largest
//! towards the mean (0.967 D and 0.965 D on these two fits), and the rest is the cells'
//! irregularity where the rows cannot follow the curvature.

use glam::DVec3;
use rayon::prelude::*;

use crate::discretise::{discretise, discretise_with_progress, Discretisation, DiscretiseOptions};
use crate::error::TpiError;
use crate::pattern::Generator;
use crate::progress::{NoProgress, Progress};
use crate::projection::{deviation_at, distance_foot, Wrap};
use crate::relax::{relax_weighted, seam_margins};
use crate::sizing::{metric_poisson, CurvatureFloors, SizingField};
use crate::surface::Surface;
use crate::tolerance::DUPLICATE_UV_TOLERANCE;

/// Rounds of field adaptation in [`fit_pattern`].
pub const FIT_ROUNDS: usize = 6;
/// Lloyd iterations after each round's Poisson-disk sampling.
pub const FIT_LLOYD_ITERATIONS: usize = 4;
/// Poisson-disk radius in units of the field's hexagonal spacing (0.78: a maximal Poisson-disk
/// set has about 0.7 / r^2 points per unit area, a hexagonal lattice 2 / (sqrt(3) a^2)).
pub const FIT_POISSON_RADIUS: f64 = 0.78;
/// Deviation over D that the field adaptation aims at, below 1 to leave room for the
/// irregularity of the points.
pub const FIT_TARGET_RATIO: f64 = 0.8;
/// Largest change of the spacing at one node in one round (factor, and its inverse).
pub const FIT_MAX_STEP: f64 = 1.5;
/// Column spacing of the first lattice [`fit_pattern`] tries, in the field's metric (the
/// hexagonal spacing is 1).
pub const FIT_WALL_SPACING: f64 = 1.0;
/// Refinement passes (points added at offending vertices) that finish each round.
pub const FIT_REFINE_PASSES: usize = 12;
/// Refinement passes in a row that may lower neither the largest deviation nor the number
/// of vertices beyond the tolerance before the refinement of a round gives up (the passes
/// of a converging refinement are noisy: on a saddle two such passes in a row occur on the
/// way to a fit).
pub const FIT_STALLED_PASSES: usize = 3;
/// Most points a fitted pattern may have.
pub const MAX_FIT_POINTS: usize = 2_000_000;
/// Fewest points a fitted pattern starts from.
pub const MIN_FIT_POINTS: usize = 12;
/// Nodes per side of the sizing field.
const FIELD_NODES: usize = 65;
/// Curvature floors of the field: anisotropy at most 1 : 20 in curvature, and the spacing at
/// most 1 / sqrt(0.01) = 10 times the finest.
const FIT_FLOORS: CurvatureFloors = CurvatureFloors {
    relative: 0.05,
    global: 0.01,
};

/// What [`fit_pattern`] found.
#[derive(Clone, Debug, PartialEq)]
pub struct FittedPattern {
    /// The pattern points (normalised, [0, 1]^2).
    pub uv: Vec<[f64; 2]>,
    /// Whether every mesh vertex lies within the tolerance.
    pub met: bool,
    /// The largest vertex deviation of its mesh (model units): the larger of the quality
    /// report's and [`vertex_deviations`]'s.
    pub max_deviation: f64,
    /// Invalid facets of its mesh (the quality report's count).
    pub invalid_facets: usize,
    /// Discretisations run to find it.
    pub discretisations: usize,
}

/// The deviation of every mesh vertex from the surface (model units), as the quality report
/// measures it: the distance to the foot found by Newton's method from the parameters of the
/// first facet holding the vertex (`crate::projection`); 0 for vertices no facet uses.
pub fn vertex_deviations(surface: &dyn Surface, d: &Discretisation) -> Vec<f64> {
    vertex_feet(surface, d)
        .into_iter()
        .map(|f| f.map_or(0.0, |(dev, _)| dev))
        .collect()
}

/// The largest of [`vertex_deviations`] (0 for a mesh without vertices).
fn largest_vertex_deviation(surface: &dyn Surface, d: &Discretisation) -> f64 {
    largest_foot_deviation(&vertex_feet(surface, d))
}

/// How a mesh whose vertices stand at most `own` off the surface ([`vertex_feet`]) is judged:
/// the larger of that and the report's largest deviation, and the report's invalid facets
/// (0 and 0 without a report).
fn judged(own: f64, d: &Discretisation) -> (f64, usize) {
    let q = d.quality.as_ref();
    (
        own.max(q.map_or(0.0, |q| q.max_deviation)),
        q.map_or(0, |q| q.invalid_facets),
    )
}

/// The largest deviation among the feet of [`vertex_feet`] (0 where there is none).
fn largest_foot_deviation(feet: &[Option<(f64, [f64; 2])>]) -> f64 {
    feet.iter()
        .filter_map(|f| f.map(|(dev, _)| dev))
        .fold(0.0, f64::max)
}

/// Per vertex, its deviation and its foot's parameters (the surface's own), None if unused.
fn vertex_feet(surface: &dyn Surface, d: &Discretisation) -> Vec<Option<(f64, [f64; 2])>> {
    let mut first = vec![u32::MAX; d.vertices.len()];
    for i in 0..d.facet_count() {
        for &v in d.facet(i) {
            if first[v as usize] == u32::MAX {
                first[v as usize] = i as u32;
            }
        }
    }
    let wrap = Wrap::of(surface);
    let domain = wrap.domain;
    (0..d.vertices.len())
        .into_par_iter()
        .map(|v| {
            let i = *first.get(v).filter(|&&i| i != u32::MAX)?;
            let x = d.vertices[v];
            let foot = distance_foot(surface, &wrap, x, d.seeds[i as usize].uv);
            let (dev, foot) = deviation_at(surface, &domain, x, foot);
            Some((if dev.is_finite() { dev } else { f64::INFINITY }, foot))
        })
        .collect()
}

/// A tolerance-driven pattern for `surface` (module doc): few points whose TPI mesh, built
/// with `options`, keeps every vertex within `max_deviation` of the surface. `seed` drives
/// the Poisson-disk sampling.
///
/// Errors: [`TpiError::InvalidParameter`] for a tolerance that is not a positive finite
/// number, or one so small that the pattern would need more than [`MAX_FIT_POINTS`] points;
/// those of [`crate::discretise()`].
pub fn fit_pattern(
    surface: &dyn Surface,
    max_deviation: f64,
    seed: u64,
    options: &DiscretiseOptions,
) -> Result<FittedPattern, TpiError> {
    fit_pattern_with_progress(surface, max_deviation, seed, options, &NoProgress)
}

/// [`fit_pattern`], reporting the stages of every discretisation it runs to `progress`
/// ([`crate::Progress`]; a fit runs tens of them), which can cancel it between stages
/// ([`TpiError::Cancelled`]: nothing of the fit is kept). The result is the same as without
/// an observer.
pub fn fit_pattern_with_progress(
    surface: &dyn Surface,
    max_deviation: f64,
    seed: u64,
    options: &DiscretiseOptions,
    progress: &dyn Progress,
) -> Result<FittedPattern, TpiError> {
    if !(max_deviation.is_finite() && max_deviation > 0.0) {
        return Err(TpiError::InvalidParameter {
            field: "max_deviation".into(),
            value: max_deviation,
            reason: "the tolerance must be a positive number (model units)".into(),
        });
    }
    let options = DiscretiseOptions {
        quality_report: true,
        ..*options
    };
    let base = SizingField::curvature(surface, FIELD_NODES, max_deviation, FIT_FLOORS);
    let nodes = base.nodes();
    let mut multiplier = vec![1.0f64; nodes * nodes];
    let mut best: Option<FittedPattern> = None;
    let mut closest: Option<FittedPattern> = None;
    let mut runs = 0usize;
    let mut near: Vec<NearMiss> = Vec::new();
    let margins = seam_margins(surface);
    // A lattice far larger than the field predicts is not worth discretising: across a
    // parabolic line a vertex runs away whatever the spacing (samples/mixed-roof.json).
    let lattice_limit = (FIT_LATTICE_FACTOR * base.expected_poisson_count(FIT_POISSON_RADIUS))
        .min(MAX_FIT_POINTS as f64) as usize;
    if margins == [0.0, 0.0] {
        // Every row closed first: above FIT_ADAPTIVE_POINTS only the first is tried, and on
        // samples/saddle.json at D = 1.56e-5 the sparser sides need 117,527 points against
        // 101,061 (on the domes they save a few per cent at the counts of the tests).
        let mut variants = vec![
            Grading::of(&base),
            Grading::of(&base).sparse(),
            Grading::uniform(&base),
            Grading::uniform(&base).sparse(),
            Grading::of(&base).inset(),
            Grading::of(&base).sparse().inset(),
        ];
        let saddle = has_saddle_points(surface);
        if !saddle {
            // On saddles the rows graded along themselves gained nothing
            // (samples/hypar.json, samples/saddle.json at D = 0.003, 0.01, 0.03). The
            // steeper grading's rows cut by the walls: samples/paraboloid.json at D = 0.03
            // 109 -> 108 points, samples/anisotropic-dome.json at 0.003 672 -> 655 (the
            // envelope's grading cut so gained nothing).
            variants.push(Grading::of(&base).rowwise(&base));
            variants.push(Grading::steep(&base).cut(&base));
            // Rows (only) inset from the walls t = 0, 1 (Grading::inset_rows):
            // samples/paraboloid.json at D = 0.003, 0.01, 0.03 971, 299, 108 -> 941, 295,
            // 105 points, samples/rational-dome.json at 0.03 149 -> 140,
            // samples/nurbs-dome.json at 0.01, 0.03 339, 124 -> 331, 116 (on the saddles
            // nothing).
            variants.push(Grading::of(&base).sparse().inset_rows());
            variants.push(Grading::steep(&base).sparse().inset_rows());
            variants.push(Grading::of(&base).inset_rows().rowwise(&base));
        }
        if saddle {
            variants.push(Grading::of(&base).saddle_rows());
            variants.push(Grading::of(&base).sparse().saddle_rows());
            variants.push(Grading::uniform(&base).saddle_rows());
            variants.push(Grading::uniform(&base).sparse().saddle_rows());
            // The sparser sides with the saddle rows inset from the walls (all four, or
            // only t = 0, 1): a saddle's walls of positive normal curvature put the vertex
            // between two wall seeds a apart at a^2 / 4, three times its interior's
            // a^2 / 12, and the inset moves those seeds off the walls (Grading::inset).
            // samples/hypar.json at D = 0.01 110 -> 71 points, samples/saddle.json at 0.01
            // and 0.03 149, 57 -> 132, 48 (the same with every row closed, or uniform
            // lattices inset without the saddle rows, gained less: at best 142 and 56 on
            // the saddle, nothing on the hypar).
            variants.push(Grading::uniform(&base).sparse().saddle_rows().inset());
            variants.push(Grading::uniform(&base).sparse().saddle_rows().inset_rows());
        }
        // Lattices from here on only while the best is small (FIT_NEIGHBOUR_POINTS).
        let small_only = variants.len();
        variants.push(Grading::steep(&base));
        variants.push(Grading::steep(&base).sparse());
        if has_saddle_points(surface) {
            for density in FIT_SADDLE_EXTRA_ROW_DENSITIES {
                let g = [Grading::uniform(&base), Grading::uniform(&base).sparse()];
                for grading in g {
                    variants.push(grading.rows(density));
                }
            }
        }
        for (k, grading) in variants.into_iter().enumerate() {
            if best
                .as_ref()
                .is_some_and(|b| b.uv.len() > FIT_ADAPTIVE_POINTS)
            {
                break;
            }
            if k >= small_only
                && best
                    .as_ref()
                    .is_some_and(|b| b.uv.len() > FIT_NEIGHBOUR_POINTS)
            {
                break;
            }
            let beat = best.as_ref().map_or(usize::MAX, |b| b.uv.len());
            let lattice = wall_lattice(
                surface,
                &grading,
                max_deviation,
                lattice_limit,
                beat,
                &options,
                &mut runs,
                progress,
                &mut near,
            )?;
            if let Some(lattice) = lattice {
                consider(&mut best, &mut closest, lattice);
            }
        }
        if saddle {
            // On saddles the smaller lattices not yet measured relaxed to nothing
            // (samples/hypar.json, samples/saddle.json at D = 0.003, 0.01, 0.03) and
            // doubled the fit's time; their lattices are set by a few wall vertices.
            near.retain(|n| n.1.is_finite());
        }
    }
    // Above FIT_ADAPTIVE_POINTS the rounds (each tens of discretisations) would take far
    // longer than the lattice's few.
    let rounds = match &best {
        Some(b) if b.uv.len() > FIT_ADAPTIVE_POINTS => 0,
        _ => FIT_ROUNDS,
    };
    for _round in 0..rounds {
        let mut field = base.clone();
        field.scale_spacing(&multiplier);
        let expected = field.expected_poisson_count(FIT_POISSON_RADIUS);
        if expected > MAX_FIT_POINTS as f64 {
            return Err(TpiError::InvalidParameter {
                field: "max_deviation".into(),
                value: max_deviation,
                reason: format!(
                    "the tolerance needs about {expected:.0} pattern points, more than \
                     {MAX_FIT_POINTS}"
                ),
            });
        }
        if expected < MIN_FIT_POINTS as f64 {
            // A nearly flat surface or a loose tolerance: start from a few points anyway.
            let f = (expected.max(1e-12) / MIN_FIT_POINTS as f64).sqrt();
            for m in &mut multiplier {
                *m *= f;
            }
            field = base.clone();
            field.scale_spacing(&multiplier);
        }
        let mut points = metric_poisson(&field, FIT_POISSON_RADIUS, seed, MAX_FIT_POINTS);
        if points.len() < 3 {
            points = Generator::parse("hex:3x3")?.generate().uv;
        }
        let density = |st: [f64; 2]| field.lloyd_density(st);
        points = relax_weighted(
            surface,
            &points,
            FIT_LLOYD_ITERATIONS,
            &options,
            Some(&density),
            progress,
        )?;
        runs += FIT_LLOYD_ITERATIONS;
        let d = discretise_with_progress(surface, &points, &options, progress)?;
        runs += 1;
        let feet = vertex_feet(surface, &d);
        let ratios = facet_ratios(&d, &feet, max_deviation);
        update_multiplier(&mut multiplier, nodes, &surface.domain(), &d, &ratios);
        // A finished pattern larger than the best valid one found cannot replace it.
        let limit = best
            .as_ref()
            .filter(|b| b.invalid_facets == 0)
            .map_or(usize::MAX, |b| b.uv.len());
        let finished = refine(
            surface,
            points,
            d,
            feet,
            max_deviation,
            limit,
            &options,
            &mut runs,
            progress,
        )?;
        consider(&mut best, &mut closest, finished);
    }
    if margins == [0.0, 0.0] {
        if let Some(b) = best.take() {
            best = Some(relax_near_misses(
                surface,
                &base,
                b,
                near,
                max_deviation,
                &options,
                &mut runs,
                progress,
            )?);
        }
    }
    let mut result = best.or(closest).unwrap_or(FittedPattern {
        uv: Vec::new(),
        met: false,
        max_deviation: f64::INFINITY,
        invalid_facets: 0,
        discretisations: 0,
    });
    result.discretisations = runs;
    Ok(result)
}

/// A hexagonal lattice with rows on the sides t = 0 and t = 1 and points on the sides s = 0
/// and s = 1: `rows + 1` rows t = j / rows, even rows s = i / columns (i = 0..=columns),
/// odd rows s = (i + 1/2) / columns and both ends (with [`Grading::sparse`], only the last
/// row's ends, the corners).
/// The lattice is laid in graded coordinates: s = grade_s(i / columns), t = grade_t(j / rows);
/// with an inset e ([`Grading::inset`]), the walls' rows and columns e columns inside:
/// s = grade_s((i + e) / (columns + 2 e)), and likewise in t with e in rows.
///
/// The ends of the odd rows put a seed on the sides s = 0, 1 every row, sqrt(3) a / 2 apart,
/// and the boundary vertices between them at R^2 = 3 a^2 / 16, far below the interior's
/// a^2 / 3. Without them the side seeds are sqrt(3) a apart (even rows), the odd row's first
/// seed half a column inside: the edge between it and a side seed meets the side a / sqrt(3)
/// from that seed, at R^2 = a^2 / 3, as in the interior; two points fewer per odd row.
fn wall_hex(columns: usize, rows: usize, grading: &Grading) -> Vec<[f64; 2]> {
    let mut points = Vec::with_capacity((columns + 2) * (rows + 1));
    // With an inset, lattice coordinate x (0 on one wall, 1 on the other) is taken as
    // x + inset steps inside the span of columns + 2 insets.
    let (inset_s, inset_t) = (grading.inset, grading.row_inset());
    let ts: Vec<f64> = (0..=rows)
        .map(|j| {
            let n = rows as f64;
            grading.t.at((j as f64 + inset_t) / (n + 2.0 * inset_t))
        })
        .collect();
    for (j, &t) in ts.iter().enumerate() {
        let ends = j % 2 == 0 || !grading.sparse_sides || j == rows;
        if let Some(field) = &grading.row_field {
            let row = rowwise_positions(field, grading, columns as f64, &ts, j, ends);
            points.extend(row.into_iter().map(|s| [s, t]));
            continue;
        }
        let s_at = |x: f64| {
            let n = columns as f64;
            grading.s.at((x * n + inset_s) / (n + 2.0 * inset_s))
        };
        if j % 2 == 0 {
            points.extend((0..=columns).map(|i| [s_at(i as f64 / columns as f64), t]));
        } else {
            if ends {
                points.push([s_at(0.0), t]);
            }
            points.extend((0..columns).map(|i| [s_at((i as f64 + 0.5) / columns as f64), t]));
            if ends {
                points.push([s_at(1.0), t]);
            }
        }
    }
    points
}

/// A [`Grading::rowwise`] lattice of `rows + 1` rows graded by `grading.t` and a real
/// number of `columns` (the column step is the envelope's length over it: rows cut by the
/// walls need no whole number of steps).
fn rowwise_hex(columns: f64, rows: usize, grading: &Grading) -> Vec<[f64; 2]> {
    let Some(field) = &grading.row_field else {
        return Vec::new();
    };
    let ts: Vec<f64> = (0..=rows)
        .map(|j| {
            let (n, inset_t) = (rows as f64, grading.row_inset());
            grading.t.at((j as f64 + inset_t) / (n + 2.0 * inset_t))
        })
        .collect();
    let mut points = Vec::new();
    for (j, &t) in ts.iter().enumerate() {
        let row = rowwise_positions(field, grading, columns, &ts, j, true);
        points.extend(row.into_iter().map(|s| [s, t]));
    }
    points
}

/// The s of the points of row `j` (at t = `ts[j]`) of a [`Grading::rowwise`] lattice of
/// `columns` columns (real). The row is laid by its own metric length y along it (the
/// integral of sqrt(M_ss(s, t)) ds from the middle s = 1/2), in steps of the lattice's
/// column step: even rows at y = 0, +-1, +-2, ..., odd rows at +-1/2, +-3/2,
/// ..., so that neighbouring rows are offset by half a step in the middle and drift apart
/// only as much as their metric profiles differ. Rows laid end to end by their own rounded
/// counts drift by a whole step across the row where the counts differ and pass through an
/// alignment of seeds, whose triangles stand off 1.3 times the regular lattice's (measured:
/// samples/paraboloid.json at D = 0.01, 16 columns, 1.23 to 1.29 D against 0.98 D for the
/// separable lattice); shrinking or stretching the last three steps of each half row to a
/// whole count moves that alignment next to the walls (1.18 to 1.25 D). Here the lattice
/// is cut by the walls instead: a row ends on a wall when its last point is at least
/// [`ROWWISE_WALL_GAP`] steps from it (always on the rows t = 0, 1, which keep their
/// corners); with `ends` false only the even rows do.
fn rowwise_positions(
    field: &SizingField,
    grading: &Grading,
    columns: f64,
    ts: &[f64],
    j: usize,
    ends: bool,
) -> Vec<f64> {
    let t = ts[j];
    // The lattice's column step in the metric (the envelope's).
    let step = grading.s.total / columns;
    let own;
    let grade = if grading.row_own {
        own = Grade::new(|s| field.metric_at([s, t])[0].max(0.0).sqrt());
        &own
    } else {
        &grading.s
    };
    if !(grade.total > 0.0 && grade.total.is_finite()) {
        return Vec::new();
    }
    let total = grade.total / step;
    let middle = grade.cumulative_at(0.5) * total;
    let odd = j % 2 == 1;
    let wall_row = j == 0 || j + 1 == ts.len();
    // One half row of metric length `length` (steps): the offsets of its points from the
    // middle (none at the middle), the lattice cut by the wall.
    let half = |length: f64| -> Vec<f64> {
        let first = if odd { 0.5 } else { 1.0 };
        let mut xs: Vec<f64> = (0..)
            .map(|i| first + i as f64)
            .take_while(|&x| x < length)
            .collect();
        let gap = length - xs.last().copied().unwrap_or(0.0);
        if wall_row {
            // The rows on the walls t = 0, 1 keep their corners.
            if gap < ROWWISE_CORNER_GAP && !xs.is_empty() {
                xs.pop();
            }
            xs.push(length);
        } else if gap >= ROWWISE_WALL_GAP && ends {
            xs.push(length);
        }
        xs
    };
    let to_s = |y: f64| grade.at((middle + y) / total);
    let mut row: Vec<f64> = half(middle).into_iter().rev().map(|x| to_s(-x)).collect();
    if !odd {
        row.push(to_s(0.0));
    }
    row.extend(half(total - middle).into_iter().map(to_s));
    row
}

/// Real column counts, evenly spaced from the one found down to [`ROWWISE_SCAN_SPAN`] less,
/// that [`wall_lattice`] tries for a [`Grading::rowwise`] lattice (each with the row
/// counts from two less to one more than the one found), and only those lattices with at
/// least [`ROWWISE_SCAN_FLOOR`] of its points.
const ROWWISE_SCAN_STEPS: usize = 8;

/// Fewest points of a lattice in the scan of [`ROWWISE_SCAN_STEPS`], as a fraction of the
/// lattice found (the scan's tries go to the lattices likeliest to meet the tolerance).
const ROWWISE_SCAN_FLOOR: f64 = 0.93;

/// How far below the columns found (in columns) the scan of [`ROWWISE_SCAN_STEPS`] reaches.
const ROWWISE_SCAN_SPAN: f64 = 2.0;

/// Most lattices of the scan discretised (fewest points first; the first meeting the
/// tolerance with no invalid facet is kept).
const ROWWISE_SCAN_TRIES: usize = 10;

/// A [`Grading::rowwise`] row, the lattice cut by a wall s = 0 or 1, ends on the wall when
/// its last point is at least this far (column steps) from it: just above half a step, so
/// that where the rows' lengths are whole steps the odd rows end half a step from the walls
/// without a point on them, as the separable lattices' sparser sides do ([`wall_hex`]).
/// Covering radii of a hexagonal lattice of unit steps cut by a straight wall at any offset
/// with a row on the wall t = 0, each row closed by this rule (the largest distance from a
/// point of the domain to its nearest seed, squared, over the regular lattice's 1 / 3; a
/// grid search in a Python model, the wall at 41 offsets): 1.014 with a straight wall,
/// 1.061 with a wall slanted by 0.1 step per row (neighbouring rows of different metric
/// lengths); a gap of 0.4 gives 1.014 and 1.016 but closes the odd rows of whole-step
/// lengths too, and as a second lattice gained nothing on the domes of `fit_measure`
/// (samples/nurbs-dome, paraboloid, rational-dome, anisotropic-dome at D = 0.003, 0.01,
/// 0.03, FIT_ABSOLUTE=1). Closing no row leaves gaps of almost a step.
const ROWWISE_WALL_GAP: f64 = 0.52;

/// A row on the walls t = 0, 1 of a [`Grading::rowwise`] lattice always ends on the corner;
/// its last point before the corner goes when it is nearer than this (column steps).
const ROWWISE_CORNER_GAP: f64 = 0.05;

/// A monotone map of [0, 1] onto itself: the inverse of the normalised cumulative of a
/// positive weight, tabulated; the lattice's steps in s (or t) are then even in the weight.
struct Grade {
    /// The cumulative of the weight at k / (n - 1), normalised to end at 1.
    cumulative: Vec<f64>,
    /// The weight's integral over [0, 1].
    total: f64,
}

impl Grade {
    fn new(weight: impl Fn(f64) -> f64) -> Grade {
        const STEPS: usize = 512;
        let mut cumulative = vec![0.0f64; STEPS + 1];
        for k in 0..STEPS {
            let w = weight((k as f64 + 0.5) / STEPS as f64);
            let w = if w.is_finite() && w > 0.0 { w } else { 0.0 };
            cumulative[k + 1] = cumulative[k] + w / STEPS as f64;
        }
        let total = cumulative[STEPS];
        if !(total > 0.0 && total.is_finite()) {
            // No usable weight: the identity.
            let cumulative = (0..=STEPS).map(|k| k as f64 / STEPS as f64).collect();
            return Grade {
                cumulative,
                total: 0.0,
            };
        }
        for c in &mut cumulative {
            *c /= total;
        }
        Grade { cumulative, total }
    }

    /// The normalised cumulative at x (linear between the tabulated values).
    fn cumulative_at(&self, x: f64) -> f64 {
        let n = self.cumulative.len() - 1;
        let f = (x.clamp(0.0, 1.0) * n as f64).min(n as f64);
        let k = (f.floor() as usize).min(n - 1);
        let w = f - k as f64;
        self.cumulative[k] * (1.0 - w) + self.cumulative[k + 1] * w
    }

    /// The x whose cumulative is q (ends exact).
    fn at(&self, q: f64) -> f64 {
        let n = self.cumulative.len() - 1;
        if q <= 0.0 {
            return 0.0;
        }
        if q >= 1.0 {
            return 1.0;
        }
        let k = self.cumulative.partition_point(|&c| c < q).clamp(1, n);
        let (a, b) = (self.cumulative[k - 1], self.cumulative[k]);
        let f = if b > a { (q - a) / (b - a) } else { 0.5 };
        ((k - 1) as f64 + f) / n as f64
    }
}

/// The largest of sqrt(M_ss) over the line s = x (`component` 0), or of sqrt(M_tt) over the
/// line t = x (`component` 2), sampled at 65 points.
fn envelope(field: &SizingField, component: usize, x: f64) -> f64 {
    const ACROSS: usize = 65;
    (0..ACROSS)
        .map(|k| {
            let y = k as f64 / (ACROSS - 1) as f64;
            let st = if component == 0 { [x, y] } else { [y, x] };
            field.metric_at(st)[component].max(0.0).sqrt()
        })
        .fold(0.0, f64::max)
}

/// The grading of [`wall_hex`] in s and in t.
struct Grading {
    s: Grade,
    t: Grade,
    /// Whether the odd rows but the last go without their ends on s = 0, 1 ([`wall_hex`]).
    sparse_sides: bool,
    /// Rows per row of a lattice regular in the metric (1; [`FIT_SADDLE_ROW_DENSITY`]).
    row_density: f64,
    /// Distance of the outer rows and columns from the walls, in columns (0 or
    /// [`FIT_WALL_INSET`]).
    inset: f64,
    /// Distance of the outer rows (not the columns) from the walls t = 0, 1, in columns (0
    /// or [`FIT_WALL_INSET`]; [`Grading::inset_rows`]).
    inset_rows: f64,
    /// The field by which each row is graded along itself ([`Grading::rowwise`]), or None
    /// (every row graded by `s`).
    row_field: Option<SizingField>,
    /// With `row_field`, whether each row is graded by its own metric length (else by `s`,
    /// the rows only cut by the walls).
    row_own: bool,
}

impl Grading {
    /// Steps even in the largest metric length across each line: in s by
    /// w(s) = max over t of sqrt(M_ss(s, t)), in t likewise (so every place gets at least
    /// the spacing the most demanding place on its lines asks for).
    fn of(field: &SizingField) -> Grading {
        Grading {
            s: Grade::new(|x| envelope(field, 0, x)),
            t: Grade::new(|x| envelope(field, 2, x)),
            sparse_sides: false,
            row_density: 1.0,
            inset: 0.0,
            inset_rows: 0.0,
            row_field: None,
            row_own: false,
        }
    }

    /// Steps even in the envelope of [`Grading::of`] raised to [`FIT_STEEP_GRADING`] (finer
    /// where the metric is large, coarser where it is small than [`Grading::of`]), with the
    /// rows and columns of [`Grading::of`] (its metric lengths).
    fn steep(field: &SizingField) -> Grading {
        let of = Grading::of(field);
        let steep = |component: usize, total: f64| {
            let mut g = Grade::new(|x| envelope(field, component, x).powf(FIT_STEEP_GRADING));
            g.total = total;
            g
        };
        Grading {
            s: steep(0, of.s.total),
            t: steep(2, of.t.total),
            ..of
        }
    }

    /// Even steps, as long in the metric as the largest of [`Grading::of`]'s.
    fn uniform(field: &SizingField) -> Grading {
        let top = |component: usize| {
            (0..=64)
                .map(|k| envelope(field, component, k as f64 / 64.0))
                .fold(0.0, f64::max)
        };
        let (s, t) = (top(0), top(2));
        Grading {
            s: Grade::new(|_| s),
            t: Grade::new(|_| t),
            sparse_sides: false,
            row_density: 1.0,
            inset: 0.0,
            inset_rows: 0.0,
            row_field: None,
            row_own: false,
        }
    }

    /// Distance of the outer rows from the walls t = 0, 1 in rows (the inset in columns over
    /// the rows' sqrt(3) / 2 columns).
    fn row_inset(&self) -> f64 {
        (self.inset + self.inset_rows) / (3f64.sqrt() / 2.0)
    }

    /// The same grading, the odd rows without their ends on the sides ([`wall_hex`]).
    fn sparse(self) -> Grading {
        Grading {
            sparse_sides: true,
            ..self
        }
    }

    /// The same grading with the outer rows and columns [`FIT_WALL_INSET`] inside the walls.
    fn inset(self) -> Grading {
        Grading {
            inset: FIT_WALL_INSET,
            ..self
        }
    }

    /// The same grading with the outer rows (only) [`FIT_WALL_INSET`] inside the walls
    /// t = 0, 1. The rows run along those walls, so their seeds a apart at e from a wall put
    /// the wall vertex between them at R^2 = a^2 / 4 + e^2, a^2 / 3 as inside at
    /// e = [`FIT_WALL_INSET`], and the lattice spans 0.67 rows more than one with rows on
    /// the walls; across the rows the walls s = 0, 1 keep their seeds (a lattice inset there
    /// leaves the odd rows' ends half a column further out, [`Grading::inset`] with sparser
    /// sides).
    fn inset_rows(self) -> Grading {
        Grading {
            inset_rows: FIT_WALL_INSET,
            ..self
        }
    }

    /// The same rows, each row graded along itself by `field` ([`rowwise_positions`]):
    /// steps even in the row's own metric length sqrt(M_ss(s, t)) instead of the envelope
    /// over all rows, the lattice cut by the walls s = 0, 1 ([`ROWWISE_WALL_GAP`]). Where
    /// the curvature falls in both s and t (a dome's corners) the separable grading spaces
    /// every row as its most demanding place; graded along itself a row near a wall carries
    /// fewer points than the middle row.
    fn rowwise(self, field: &SizingField) -> Grading {
        Grading {
            row_field: Some(field.clone()),
            row_own: true,
            ..self
        }
    }

    /// The same grading, its rows laid as [`Grading::rowwise`]'s (from the middle, cut by
    /// the walls, scanned over real column counts) but by this grading's steps in s: the
    /// separable lattice without a whole number of columns.
    fn cut(self, field: &SizingField) -> Grading {
        Grading {
            row_own: false,
            ..self.rowwise(field)
        }
    }

    /// The same grading with [`FIT_SADDLE_ROW_DENSITY`] times the rows.
    fn saddle_rows(self) -> Grading {
        self.rows(FIT_SADDLE_ROW_DENSITY)
    }

    /// The same grading with `density` times the rows.
    fn rows(self, density: f64) -> Grading {
        Grading {
            row_density: density,
            ..self
        }
    }
}

/// Rows per row of the metric-regular lattice in the lattices [`fit_pattern`] adds where the
/// surface has negative Gaussian curvature. In the metric |II| laid along the principal
/// directions of a saddle, II = diag(1, -1), and the triangle of seeds 0, (a, 0),
/// (a / 2, h) of a lattice of columns a and rows h has its vertex (the circumcentre in II)
/// at |II(c)| = (h^2 - a^2 / 4)^2 / (4 h^2): a^2 / 12 for the regular h = sqrt(3) a / 2, and
/// 0 at h = a / 2, where the edges run along the asymptotic directions (and four planes meet
/// in a point). Between them the cells get longer along the asymptotic directions for the
/// same deviation: per point, |II(c)| / (a h) is 0.096 at h = 0.866 a, 0.034 at 0.72 a
/// (1.2 times the rows). Measured on samples/hypar.json (`fit_measure`, FIT_ABSOLUTE=1):
/// 1.2 times the rows 135 points at D = 0.01 and 316 at 0.003, against 151 and 454 with only
/// the regular lattices; 1.35 and more lose to the walls and corners.
pub const FIT_SADDLE_ROW_DENSITY: f64 = 1.2;

/// Power of the envelope in the steeper grading of the further lattices [`fit_pattern`]
/// tries while its best pattern has at most [`FIT_NEIGHBOUR_POINTS`] points
/// ([`Grading::steep`]). The envelope of a line is its largest metric length, so where the
/// curvature falls away in both s and t (a paraboloid's corners) the separable grading keeps
/// cells finer than the curvature asks for; a steeper grading moves points from there to the
/// middle. Measured on samples/paraboloid.json (`fit_measure`, FIT_ABSOLUTE=1, D = 0.003,
/// 0.01, 0.03): 998, 312, 114 points -> 971, 299, 109 with 1.75 (971, 299, 111 with 1.5;
/// 0.5, 2 and 3 gain nothing); the NURBS dome and the rational dome unchanged.
const FIT_STEEP_GRADING: f64 = 1.75;

/// Row densities of the further lattices [`fit_pattern`] tries on surfaces with negative
/// Gaussian curvature while its best pattern has at most [`FIT_NEIGHBOUR_POINTS`] points (each
/// uniform, with every row closed on the sides or the sparser sides: the graded ones gained
/// nothing on samples/hypar.json and cost as many discretisations). Which lattice
/// the walls and corners of a saddle let through is not smooth in the row density: on
/// samples/hypar.json (`fit_measure`, FIT_ABSOLUTE=1) 1.05 gives 110 points at D = 0.01
/// (135 with 1 and 1.2 only; 1.25 and 1.3 give 135 too), 1.1 gives 306 at D = 0.003 (316).
const FIT_SADDLE_EXTRA_ROW_DENSITIES: [f64; 3] = [1.05, 1.1, 1.15];

/// Distance of the outer seeds from the walls in the lattices with an inset, in columns:
/// on a dome (metric |II| isotropic), two seeds a apart at a distance e from a wall put the
/// vertex on the wall between them at R^2 = a^2 / 4 + e^2, at most the interior's a^2 / 3
/// for e = a / sqrt(12) = 0.29 a; the lattice then spans 0.58 columns and rows less than one
/// with seeds on the walls.
pub const FIT_WALL_INSET: f64 = 0.29;

/// Whether the surface has negative Gaussian curvature at some point of a 9 x 9 grid over
/// its domain (LN - M^2 < 0 with the unnormalised normal su x sv, whose sign does not matter).
fn has_saddle_points(surface: &dyn Surface) -> bool {
    let domain = surface.domain();
    (0..9).any(|i| {
        (0..9).any(|j| {
            let [u, v] = domain.from_normalised([i as f64 / 8.0, j as f64 / 8.0]);
            let d = surface.evaluate(u, v);
            let n = d.su.cross(d.sv);
            let (l, m, nn) = (d.suu.dot(n), d.suv.dot(n), d.svv.dot(n));
            let k = l * nn - m * m;
            k < -1e-12 * (l * l + 2.0 * m * m + nn * nn)
        })
    })
}

/// What a candidate lattice of the search is discretised with and measured against.
struct Trial<'a> {
    surface: &'a dyn Surface,
    options: &'a DiscretiseOptions,
    progress: &'a dyn Progress,
    tolerance: f64,
    /// Patterns that missed the tolerance by at most [`FIT_NEAR_MISS`] with no invalid facet.
    near: std::cell::RefCell<Vec<NearMiss>>,
}

impl Trial<'_> {
    /// The pattern `uv` as a fit, when its mesh meets the tolerance with no invalid facet
    /// (or with some, where `invalid_allowed`: the lattice it would replace has some too);
    /// counts the discretisation in `runs`.
    fn meets(
        &self,
        uv: Vec<[f64; 2]>,
        invalid_allowed: bool,
        runs: &mut usize,
    ) -> Result<Option<FittedPattern>, TpiError> {
        let d = discretise_with_progress(self.surface, &uv, self.options, self.progress)?;
        *runs += 1;
        let feet = vertex_feet(self.surface, &d);
        let (deviation, invalid) = judged(largest_foot_deviation(&feet), &d);
        let met = deviation <= self.tolerance && (invalid == 0 || invalid_allowed);
        if !met && invalid == 0 && deviation <= FIT_NEAR_MISS * self.tolerance {
            self.near
                .borrow_mut()
                .push((deviation, mean_foot_deviation(&feet), uv.clone()));
        }
        Ok(met.then_some(FittedPattern {
            uv,
            met: true,
            max_deviation: deviation,
            invalid_facets: invalid,
            discretisations: 0,
        }))
    }
}

/// The smallest [`wall_hex`] lattice graded by `grading` meeting the tolerance (module
/// doc), its rows and columns in the ratio of the grading's metric lengths (cells regular in
/// the metric |II| where it is largest): the first size predicted by the field, the next ones
/// from the measured deviation (it goes as the square of the spacing), down to a size next to
/// one that fails or until the prediction saves less than [`FIT_LATTICE_SLACK`]. A lattice
/// of more than [`FIT_CALIBRATION_POINTS`] points is first aimed by a lattice of about that
/// many (the same grading), so that the large one is discretised once in most cases (at
/// 100k points a discretisation with its report takes most of a second): the search then
/// stops at the first large lattice that meets the tolerance unless the prediction saves
/// more than twice [`FIT_CALIBRATION_MARGIN`]. None when no lattice of at most `limit`
/// points was found that meets it within [`FIT_LATTICE_TRIES`] discretisations.
#[allow(clippy::too_many_arguments)]
fn wall_lattice(
    surface: &dyn Surface,
    grading: &Grading,
    tolerance: f64,
    limit: usize,
    beat: usize,
    options: &DiscretiseOptions,
    runs: &mut usize,
    progress: &dyn Progress,
    near: &mut Vec<NearMiss>,
) -> Result<Option<FittedPattern>, TpiError> {
    let (l_s, l_t) = (grading.s.total, grading.t.total);
    if !(l_s > 0.0 && l_t > 0.0 && l_s.is_finite() && l_t.is_finite()) {
        return Ok(None);
    }
    // Columns of spacing 1 in the metric, rows sqrt(3) / 2 of it apart.
    let aspect = 2.0 / 3f64.sqrt() * (l_t / l_s) * grading.row_density;
    // Rows inset from the walls t = 0, 1 alone span 2 insets more.
    let rows_inset = 2.0 * grading.inset_rows / (3f64.sqrt() / 2.0);
    let rows_of = |columns: usize| ((columns as f64 * aspect - rows_inset).round() as usize).max(1);
    // Rows graded along themselves have fewer points than the separable lattice's bound
    // (counted when that bound is within the limit: a lattice beyond it is never built).
    let size = |columns: usize| {
        let bound = (columns + 2) * (rows_of(columns) + 1);
        match grading.row_field {
            Some(_) if bound <= limit => wall_hex(columns, rows_of(columns), grading).len(),
            _ => bound,
        }
    };
    let mut columns = (l_s / FIT_WALL_SPACING).ceil().clamp(2.0, 1e7) as usize;
    let mut met: Option<FittedPattern> = None;
    let mut failed_below = 1usize; // the most columns known to fail
    let mut met_columns = 0usize;
    // The mean vertex deviation and the count of the lattice found by the search.
    let (mut met_mean, mut met_count) = (f64::NAN, 0usize);
    // The columns at which all but the boundary's share of the vertices meet the tolerance
    // (from the last lattice discretised): see the refinement after the search.
    let mut bulk_columns: Option<usize> = None;

    // A large lattice is first calibrated on a small one of the same grading: the deviation
    // goes as the square of the spacing (interior, boundary and corner vertices alike), so
    // the small lattice's deviation predicts the columns that meet the tolerance, and the
    // large one is discretised once or twice instead of at every step of the search.
    let mut slack = FIT_LATTICE_SLACK;
    if size(columns) > FIT_CALIBRATION_POINTS && size(columns) <= limit {
        let scale = (FIT_CALIBRATION_POINTS as f64 / size(columns) as f64).sqrt();
        let small = ((columns as f64 * scale).round() as usize).max(8);
        let uv = wall_hex(small, rows_of(small), grading);
        let quick = DiscretiseOptions {
            quality_report: false,
            ..*options
        };
        let d = discretise_with_progress(surface, &uv, &quick, progress)?;
        *runs += 1;
        let deviation = largest_vertex_deviation(surface, &d);
        if deviation > 0.0 && deviation.is_finite() {
            let aimed =
                small as f64 * (deviation / tolerance).sqrt() * (1.0 + FIT_CALIBRATION_MARGIN);
            columns = (aimed.ceil() as usize).clamp(2, 2 * columns);
            // Below the aim by less than twice the margin is not worth another discretisation
            // of the large lattice.
            slack = 2.0 * FIT_CALIBRATION_MARGIN;
        }
    }
    for _ in 0..FIT_LATTICE_TRIES {
        if size(columns) > limit {
            break;
        }
        let uv = wall_hex(columns, rows_of(columns), grading);
        let d = discretise_with_progress(surface, &uv, options, progress)?;
        *runs += 1;
        let feet = vertex_feet(surface, &d);
        let own = largest_foot_deviation(&feet);
        let bulk = bulk_deviation(&d, &feet);
        if bulk > 0.0 && bulk.is_finite() {
            bulk_columns = Some(
                ((columns as f64 * (bulk / tolerance).sqrt()) * (1.0 + FIT_CALIBRATION_MARGIN))
                    .ceil() as usize,
            );
        }
        let (deviation, invalid) = judged(own, &d);
        let ok = deviation <= tolerance;
        if !ok && invalid == 0 && deviation <= FIT_NEAR_MISS * tolerance {
            near.push((deviation, mean_foot_deviation(&feet), uv.clone()));
        }
        let predicted = if deviation > 0.0 && deviation.is_finite() {
            (columns as f64 * (deviation / tolerance).sqrt()).ceil() as usize
        } else {
            columns + 1
        };
        if ok {
            met_columns = columns;
            met_mean = mean_foot_deviation(&feet);
            met_count = uv.len();
            met = Some(FittedPattern {
                uv,
                met: true,
                max_deviation: deviation,
                invalid_facets: invalid,
                discretisations: 0,
            });
            // Done next to a size known to fail, or when the prediction saves less than
            // FIT_LATTICE_SLACK of the columns (a large lattice is not worth a
            // discretisation per column).
            if columns <= failed_below + 1 || predicted as f64 >= columns as f64 * (1.0 - slack) {
                break;
            }
            // Fewer columns, but never back to a size known to fail.
            columns = predicted.clamp(failed_below + 1, columns - 1);
        } else {
            failed_below = failed_below.max(columns);
            // Aim a little finer than predicted, so a large lattice does not creep up on the
            // tolerance a column at a time.
            let aimed = (predicted as f64 * (1.0 + 0.5 * FIT_LATTICE_SLACK)).ceil() as usize;
            // At most twice the columns: a runaway vertex predicts any size.
            let next = aimed.clamp(columns + 1, 2 * columns);
            columns = match &met {
                Some(m) if size(next) >= m.uv.len() => break,
                _ => next,
            };
        }
    }
    // A lattice is set by its worst vertices, often a few along the walls or at the corners
    // (on samples/hypar.json the walls t = 0, 1, where the seeds a apart along a wall of
    // positive normal curvature put the vertex between them at a^2 / 4 in the metric, three
    // times the interior's a^2 / 12 of a hexagonal lattice along the principal directions of
    // a saddle). The lattice at which all but as many vertices as lie on the boundary meet
    // the tolerance, refined at its offending vertices, may then have fewer points.
    let Some(mut m) = met else {
        return Ok(None);
    };
    let trial = Trial {
        surface,
        options,
        progress,
        tolerance,
        near: std::cell::RefCell::new(Vec::new()),
    };
    // The rows follow the columns by a rounded aspect, so a lattice one row or one column
    // smaller than the one found may meet the tolerance too: on samples/rational-dome.json at
    // D = 0.01 a lattice of one row less (409 points against 429).
    if m.uv.len() <= FIT_NEIGHBOUR_POINTS {
        let (c, r) = (met_columns, rows_of(met_columns));
        let neighbours = [
            (c, r - 1),
            (c - 1, r),
            (c - 1, r + 1),
            (c + 1, r.saturating_sub(2)),
        ];
        for (c, r) in neighbours {
            if c < 2 || r < 1 {
                continue;
            }
            let uv = wall_hex(c, r, grading);
            if uv.len() >= m.uv.len() {
                continue;
            }
            if let Some(met) = trial.meets(uv, m.invalid_facets > 0, runs)? {
                m = met;
            }
        }
    }
    // Rows cut by the walls take any column step: a window of real column counts and of
    // row counts around the one found, fewest points first.
    if grading.row_field.is_some() && m.uv.len() <= FIT_NEIGHBOUR_POINTS {
        let (c, r) = (met_columns as f64, rows_of(met_columns));
        let mut window: Vec<(f64, usize, Vec<[f64; 2]>)> = Vec::new();
        // Below this lattice and the best pattern found before it.
        let target = m.uv.len().min(beat);
        for rows in r.saturating_sub(2).max(1)..=r + 1 {
            for k in 0..ROWWISE_SCAN_STEPS {
                let columns = c - ROWWISE_SCAN_SPAN * k as f64 / ROWWISE_SCAN_STEPS as f64;
                if columns < 1.0 {
                    break;
                }
                let uv = rowwise_hex(columns, rows, grading);
                if uv.len() < target && uv.len() as f64 >= ROWWISE_SCAN_FLOOR * target as f64 {
                    window.push((columns, rows, uv));
                }
            }
        }
        window.sort_by_key(|w| w.2.len());
        window.dedup_by(|a, b| a.2 == b.2);
        for (_, _, uv) in window.into_iter().take(ROWWISE_SCAN_TRIES) {
            if let Some(met) = trial.meets(uv, false, runs)? {
                m = met;
                break;
            }
        }
    }
    near.append(&mut trial.near.into_inner());
    // Smaller lattices of this grading for the relaxation (relax_near_misses), not yet
    // measured: those whose mean deviation, going as the inverse of the count from the
    // lattice found, would be at most FIT_NEAR_MEAN D.
    if m.uv.len() <= FIT_NEIGHBOUR_POINTS && met_mean > 0.0 && met_mean.is_finite() {
        let floor = (met_count as f64 * met_mean / (FIT_NEAR_MEAN * tolerance)).ceil() as usize;
        let top = m.uv.len().min(beat);
        let (c, r) = (met_columns, rows_of(met_columns));
        let rows = r.saturating_sub(3).max(1)..=r + 1;
        let mut extra = Vec::new();
        if grading.row_field.is_some() {
            for rows in rows {
                for k in 1..=FIT_SMALLER_STEPS {
                    let columns = c as f64 - k as f64 / FIT_SMALLER_STEPS as f64 * FIT_SMALLER_SPAN;
                    if columns >= 1.0 {
                        extra.push(rowwise_hex(columns, rows, grading));
                    }
                }
            }
        } else {
            for columns in c.saturating_sub(2).max(2)..=c {
                for rows in rows.clone() {
                    extra.push(wall_hex(columns, rows, grading));
                }
            }
        }
        near.extend(
            extra
                .into_iter()
                .filter(|uv| uv.len() >= floor && uv.len() < top)
                .map(|uv| (f64::NAN, f64::NAN, uv)),
        );
    }
    let Some(bulk) = bulk_columns else {
        return Ok(Some(m));
    };
    // Above FIT_ADAPTIVE_POINTS the refinement's passes (each a discretisation of the whole
    // lattice) would take far longer than the search (samples/saddle.json at 100k points:
    // 10.5 s against 1.2 s).
    if m.uv.len() > FIT_ADAPTIVE_POINTS
        || bulk as f64 > met_columns as f64 * (1.0 - FIT_BULK_SAVING)
        || bulk < 2
    {
        return Ok(Some(m));
    }
    let uv = wall_hex(bulk, rows_of(bulk), grading);
    let d = discretise_with_progress(surface, &uv, options, progress)?;
    *runs += 1;
    let feet = vertex_feet(surface, &d);
    let refined = refine(
        surface,
        uv,
        d,
        feet,
        tolerance,
        m.uv.len() - 1,
        options,
        runs,
        progress,
    )?;
    let better = refined.met
        && refined.uv.len() < m.uv.len()
        && (refined.invalid_facets == 0 || m.invalid_facets > 0);
    Ok(Some(if better { refined } else { m }))
}

/// Largest lattice (points) whose neighbours one row or one column smaller [`wall_lattice`]
/// tries: a row is then at least about 1.5 % of the points, and the four discretisations per
/// lattice stay cheap (on samples/nurbs-dome.json at D = 2e-4, 15,916 points, trying them
/// for every lattice added 12 discretisations and about a third to the fit's time).
const FIT_NEIGHBOUR_POINTS: usize = 4_000;

/// Least saving (fraction of the columns) for which [`wall_lattice`] tries a coarser lattice
/// refined at its offending vertices.
const FIT_BULK_SAVING: f64 = 0.05;

/// The deviation that all but the worst vertices meet, as many of them left out as the mesh
/// has boundary and corner vertices (unused vertices count as meeting any tolerance).
fn bulk_deviation(d: &Discretisation, feet: &[Option<(f64, [f64; 2])>]) -> f64 {
    let on_boundary = d
        .vertex_kinds
        .iter()
        .zip(feet)
        .filter(|(k, f)| f.is_some() && **k != crate::facets::VertexKind::Interior)
        .count();
    let mut devs: Vec<f64> = feet.iter().filter_map(|f| f.map(|(dev, _)| dev)).collect();
    if devs.is_empty() {
        return 0.0;
    }
    let k = on_boundary.min(devs.len() - 1);
    let (_, kth, _) = devs.select_nth_unstable_by(k, |a, b| b.total_cmp(a));
    *kth
}

/// Largest lattice (points) that the adaptive rounds try to improve on.
pub const FIT_ADAPTIVE_POINTS: usize = 30_000;

/// Most points of a lattice [`fit_pattern`] tries, in multiples of the count the curvature
/// field predicts.
const FIT_LATTICE_FACTOR: f64 = 4.0;

/// Fraction of its columns by which [`wall_lattice`] stops trying smaller lattices.
const FIT_LATTICE_SLACK: f64 = 0.01;

/// Lattices of more points than this are first calibrated on one of about this many
/// ([`wall_lattice`]).
const FIT_CALIBRATION_POINTS: usize = 12_000;

/// Fraction of its columns by which a calibrated lattice aims finer than the calibration
/// predicts (the small lattice's deviation over the square of its spacing is not quite the
/// large one's).
const FIT_CALIBRATION_MARGIN: f64 = 0.005;

/// Discretisations [`wall_lattice`] may run.
const FIT_LATTICE_TRIES: usize = 8;

/// Keeps the better pattern: among those that meet the tolerance the one with no invalid
/// facet, then the fewest points; else the one closest to the tolerance.
fn consider(
    best: &mut Option<FittedPattern>,
    closest: &mut Option<FittedPattern>,
    candidate: FittedPattern,
) {
    if candidate.met {
        let better = match best {
            None => true,
            Some(b) => {
                (candidate.invalid_facets == 0 && b.invalid_facets > 0)
                    || ((candidate.invalid_facets == 0) == (b.invalid_facets == 0)
                        && candidate.uv.len() < b.uv.len())
            }
        };
        if better {
            *best = Some(candidate);
        }
    } else if closest
        .as_ref()
        .map_or(true, |c| candidate.max_deviation < c.max_deviation)
    {
        *closest = Some(candidate);
    }
}

/// Per facet, the largest deviation of its vertices over `tolerance`.
fn facet_ratios(d: &Discretisation, feet: &[Option<(f64, [f64; 2])>], tolerance: f64) -> Vec<f64> {
    (0..d.facet_count())
        .map(|i| {
            d.facet(i)
                .iter()
                .filter_map(|&v| feet[v as usize].map(|(dev, _)| dev))
                .fold(0.0, f64::max)
                / tolerance
        })
        .collect()
}

/// Scales the spacing multiplier at every node by sqrt(tau / phi) (module doc), phi the
/// largest ratio of the facets whose seeds are nearest that node, spread to nodes with no
/// seed from their neighbours and smoothed over 3 x 3 nodes (geometric mean).
fn update_multiplier(
    multiplier: &mut [f64],
    nodes: usize,
    domain: &crate::surface::Domain,
    d: &Discretisation,
    ratios: &[f64],
) {
    let m = (nodes - 1) as f64;
    let mut phi = vec![f64::NAN; nodes * nodes];
    for (i, &r) in ratios.iter().enumerate() {
        let st = domain.to_normalised(d.seeds[i].uv);
        let a = ((st[0] * m).round() as usize).min(nodes - 1);
        let b = ((st[1] * m).round() as usize).min(nodes - 1);
        let k = a * nodes + b;
        let r = if r.is_finite() { r } else { 4.0 };
        phi[k] = if phi[k].is_nan() { r } else { phi[k].max(r) };
    }
    // Nodes without a seed take the largest of their filled neighbours, ring by ring.
    loop {
        let empty = phi.iter().filter(|x| x.is_nan()).count();
        if empty == 0 || empty == phi.len() {
            break;
        }
        let before = phi.clone();
        for a in 0..nodes {
            for b in 0..nodes {
                if !before[a * nodes + b].is_nan() {
                    continue;
                }
                let mut v = f64::NAN;
                for (da, db) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                    let (x, y) = (a as i64 + da, b as i64 + db);
                    if x >= 0 && y >= 0 && (x as usize) < nodes && (y as usize) < nodes {
                        let w = before[x as usize * nodes + y as usize];
                        if !w.is_nan() {
                            v = if v.is_nan() { w } else { v.max(w) };
                        }
                    }
                }
                phi[a * nodes + b] = v;
            }
        }
    }
    let step: Vec<f64> = phi
        .iter()
        .map(|&p| {
            let p = if p.is_nan() { FIT_TARGET_RATIO } else { p };
            (FIT_TARGET_RATIO / p.max(1e-6))
                .sqrt()
                .clamp(1.0 / FIT_MAX_STEP, FIT_MAX_STEP)
                .ln()
        })
        .collect();
    for a in 0..nodes {
        for b in 0..nodes {
            let (mut sum, mut count) = (0.0, 0.0);
            for x in a.saturating_sub(1)..=(a + 1).min(nodes - 1) {
                for y in b.saturating_sub(1)..=(b + 1).min(nodes - 1) {
                    sum += step[x * nodes + y];
                    count += 1.0;
                }
            }
            // The smoothed step, but never coarser than the node's own.
            let own = step[a * nodes + b];
            multiplier[a * nodes + b] *= (sum / count).min(own).exp();
        }
    }
}

/// The pattern finished by local refinement (module doc), starting from `points` and their
/// discretisation `d` with its vertices' `feet`. The refinement gives up, returning the
/// pattern as it stands, when the next pass would have more than `limit` points or when
/// [`FIT_STALLED_PASSES`] passes in a row have lowered neither the largest deviation below
/// its lowest so far nor the number of vertices beyond the tolerance: where
/// exact tangent planes are nearly parallel (parabolic lines) a vertex runs away whatever
/// points are added, and each pass would only make the pattern denser and the mesh slower.
#[allow(clippy::too_many_arguments)]
fn refine(
    surface: &dyn Surface,
    mut points: Vec<[f64; 2]>,
    mut d: Discretisation,
    mut feet: Vec<Option<(f64, [f64; 2])>>,
    tolerance: f64,
    limit: usize,
    options: &DiscretiseOptions,
    runs: &mut usize,
    progress: &dyn Progress,
) -> Result<FittedPattern, TpiError> {
    let domain = surface.domain();
    let [margin_s, margin_t] = seam_margins(surface);
    let mut lowest = f64::INFINITY;
    let mut last_offending = usize::MAX;
    let mut stalled = 0usize;
    for pass in 0..=FIT_REFINE_PASSES {
        let (max_deviation, invalid) = judged(largest_foot_deviation(&feet), &d);
        let offending_count = feet
            .iter()
            .filter(|f| f.is_some_and(|(dev, _)| dev > tolerance))
            .count();
        if max_deviation < lowest || offending_count < last_offending {
            stalled = 0;
        } else {
            stalled += 1;
        }
        lowest = lowest.min(max_deviation);
        last_offending = offending_count;
        if max_deviation <= tolerance || pass == FIT_REFINE_PASSES || stalled >= FIT_STALLED_PASSES
        {
            return Ok(FittedPattern {
                uv: points,
                met: max_deviation <= tolerance,
                max_deviation,
                invalid_facets: invalid,
                discretisations: 0,
            });
        }
        // Offending vertices, worst first; one new point per neighbourhood: no two new
        // points closer than half the distance from their vertex to its first facet's seed.
        // Each: (deviation, foot in normalised parameters and on the surface,
        // distance from the foot to its first facet's seed in parameters and on the surface).
        let on_surface = |st: [f64; 2]| {
            let [u, v] = domain.from_normalised(st);
            surface.point_at(u, v)
        };
        let mut offending: Vec<(f64, [f64; 2], DVec3, f64, f64)> = Vec::new();
        let mut first = vec![u32::MAX; d.vertices.len()];
        for i in 0..d.facet_count() {
            for &v in d.facet(i) {
                if first[v as usize] == u32::MAX {
                    first[v as usize] = i as u32;
                }
            }
        }
        for (v, f) in feet.iter().enumerate() {
            if let Some((dev, foot)) = *f {
                if dev > tolerance && first[v] != u32::MAX {
                    let seed = &d.seeds[first[v] as usize];
                    let seed_st = domain.to_normalised(seed.uv);
                    let st = domain.to_normalised(foot);
                    let st = [
                        st[0].clamp(margin_s, 1.0 - margin_s),
                        st[1].clamp(margin_t, 1.0 - margin_t),
                    ];
                    let x = on_surface(st);
                    let reach = (st[0] - seed_st[0]).hypot(st[1] - seed_st[1]);
                    offending.push((dev, st, x, reach, x.distance(seed.point)));
                }
            }
        }
        if offending.is_empty() {
            // The report's projection sees a deviation this one does not: refine the
            // facets around the report's worst by their own vertices' means.
            return Ok(FittedPattern {
                uv: points,
                met: false,
                max_deviation,
                invalid_facets: invalid,
                discretisations: 0,
            });
        }
        offending.sort_by(|a, b| b.0.total_cmp(&a.0));
        // Near in parameters or on the surface: across a seam or around a pole, points far
        // apart in (s, t) are near, or one.
        let existing: Vec<DVec3> = points.iter().map(|&p| on_surface(p)).collect();
        let mut added: Vec<([f64; 2], DVec3, f64, f64)> = Vec::new();
        for (_, st, x, reach, reach_3d) in offending {
            let near = |p: [f64; 2], q: DVec3, r: f64, r_3d: f64| {
                (p[0] - st[0]).hypot(p[1] - st[1]) < r || q.distance(x) < r_3d
            };
            if added
                .iter()
                .any(|&(p, q, r, r_3d)| near(p, q, 0.5 * r.max(reach), 0.5 * r_3d.max(reach_3d)))
            {
                continue;
            }
            let (r, r_3d) = (
                (0.25 * reach).max(10.0 * DUPLICATE_UV_TOLERANCE),
                0.25 * reach_3d,
            );
            if points
                .iter()
                .zip(&existing)
                .any(|(&p, &q)| near(p, q, r, r_3d))
            {
                continue;
            }
            added.push((st, x, reach, reach_3d));
        }
        if added.is_empty() || points.len() + added.len() > limit {
            return Ok(FittedPattern {
                uv: points,
                met: false,
                max_deviation,
                invalid_facets: invalid,
                discretisations: 0,
            });
        }
        points.extend(added.into_iter().map(|(p, ..)| p));
        d = discretise_with_progress(surface, &points, options, progress)?;
        *runs += 1;
        feet = vertex_feet(surface, &d);
    }
    unreachable_result()
}

/// Never reached: the refinement loop returns on its last pass.
fn unreachable_result() -> Result<FittedPattern, TpiError> {
    Err(TpiError::InvalidParameter {
        field: "refinement".into(),
        value: FIT_REFINE_PASSES as f64,
        reason: "the refinement loop ended without a result".into(),
    })
}

/// The smallest uniform hexagonal pattern `hex:NxM` (`hex:spacing=1/N`) whose mesh keeps
/// every vertex within the tolerance, by doubling N (before it reaches large patterns, a
/// bracket aimed by the last one's deviation, which goes as 1 / N^2), bisection on it, and
/// every N down to 0.85 of the bisection's (the deviation is not monotone in N).
#[derive(Clone, Debug, PartialEq)]
pub struct HexBaseline {
    /// The generator found.
    pub generator: Generator,
    /// Its number of points.
    pub count: usize,
    /// Its mesh's largest vertex deviation (as [`FittedPattern::max_deviation`]).
    pub max_deviation: f64,
    /// Its mesh's invalid facets.
    pub invalid_facets: usize,
}

/// The uniform hexagonal baseline of a tolerance ([`HexBaseline`]); None when no
/// `hex:spacing=1/N` with at most `max_points` points (and N at most [`MAX_HEX_COLUMNS`])
/// meets it. The bound keeps the search finite in time where no uniform pattern meets the
/// tolerance (exact planes across a parabolic line): a caller comparing with a fitted
/// pattern of n points needs to look no further than a few times n.
///
/// Errors: those of [`crate::discretise()`].
pub fn hex_baseline(
    surface: &dyn Surface,
    max_deviation: f64,
    max_points: usize,
    options: &DiscretiseOptions,
) -> Result<Option<HexBaseline>, TpiError> {
    let options = DiscretiseOptions {
        quality_report: true,
        ..*options
    };
    let quick = DiscretiseOptions {
        quality_report: false,
        ..options
    };
    // A pattern whose vertices deviate more than the tolerance by this crate's projection
    // fails whatever the report says (the measure is the larger of the two): most of the
    // search's patterns fail, and are judged without the report (a third of the time of a
    // large discretisation). Its result then carries that deviation and no invalid count;
    // only patterns that pass are kept.
    let try_columns = |n: usize| -> Result<HexBaseline, TpiError> {
        let generator = Generator::Hex(crate::pattern::GridSize::Spacing(1.0 / n as f64));
        let uv = generator.generate().uv;
        let first = discretise(surface, &uv, &quick)?;
        let own = largest_vertex_deviation(surface, &first);
        if own > max_deviation || own.is_nan() {
            return Ok(HexBaseline {
                generator,
                count: uv.len(),
                max_deviation: own,
                invalid_facets: 0,
            });
        }
        drop(first);
        let d = discretise(surface, &uv, &options)?;
        let (max_deviation, invalid_facets) = judged(own, &d);
        Ok(HexBaseline {
            generator,
            count: uv.len(),
            max_deviation,
            invalid_facets,
        })
    };
    let points_of = |n: usize| {
        Generator::Hex(crate::pattern::GridSize::Spacing(1.0 / n as f64))
            .generate()
            .uv
            .len()
    };
    let mut lo = 2usize; // fails (or is too few)
    let mut hi = 4usize;
    let mut aimed = false;
    let mut found = loop {
        if points_of(hi) > max_points {
            return Ok(None);
        }
        let h = try_columns(hi)?;
        if h.max_deviation <= max_deviation {
            break h;
        }
        lo = hi;
        hi *= 2;
        // Before the doubling reaches large patterns, the deviation of this one (it goes as
        // 1 / N^2) aims a bracket around the N that meets the tolerance: its foot, if it
        // fails, is where the bisection starts, and its top is tried next.
        let aim = h.max_deviation / max_deviation;
        if !aimed && points_of(hi) > FIT_CALIBRATION_POINTS && aim.is_finite() {
            aimed = true;
            let predicted = lo as f64 * aim.sqrt();
            let foot = (predicted * HEX_BRACKET).floor() as usize;
            if foot > lo && foot <= MAX_HEX_COLUMNS && points_of(foot) <= max_points {
                let f = try_columns(foot)?;
                if f.max_deviation <= max_deviation {
                    hi = foot;
                    break f;
                }
                lo = foot;
            }
            hi = ((predicted / HEX_BRACKET).ceil() as usize).max(lo + 1);
        }
        if hi > MAX_HEX_COLUMNS {
            return Ok(None);
        }
    };
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let h = try_columns(mid)?;
        if h.max_deviation <= max_deviation {
            hi = mid;
            found = h;
        } else {
            lo = mid;
        }
    }
    // The deviation is not monotone in N (where the rows meet the sides and corners changes
    // with N: on samples/nurbs-dome.json at D = 0.01, 1/25 meets D, 1/26 does not, 1/27
    // does): a few sizes below the bisection's are tried too.
    let floor = (hi as f64 * HEX_BASELINE_SCAN).ceil() as usize;
    for n in (floor.max(3)..hi).rev() {
        let h = try_columns(n)?;
        if h.max_deviation <= max_deviation {
            found = h;
        }
    }
    Ok(Some(found))
}

/// Fraction of the predicted N where [`hex_baseline`] puts the foot of its bracket (and its
/// inverse its top).
const HEX_BRACKET: f64 = 0.95;

/// Fraction of the bisection's N down to which [`hex_baseline`] tries every N.
const HEX_BASELINE_SCAN: f64 = 0.85;

/// How many times a fitted pattern's count the CLI lets [`hex_baseline`] search: a ratio
/// below 1 / 8 is reported as such rather than measured.
pub const HEX_BASELINE_SEARCH_FACTOR: usize = 8;

/// Most columns [`hex_baseline`] tries (about 1.3 million points).
pub const MAX_HEX_COLUMNS: usize = 1024;

/// One step of the minimax relaxation (module doc): each point p moves towards the place x
/// where the largest of its facet's vertex deviations, each modelled as
/// c_v |x - x_v|_M^2 (x_v the vertex's foot, M the field's metric at p, c_v = dev_v /
/// |p - x_v|_M^2 from the measured deviation), is least: a weighted 1-centre, found by
/// steps towards the worst foot halved when they do not lower the largest; the point then
/// moves [`FIT_MINIMAX_STEP`] times the way to it. Points on a wall slide along it, corners
/// stay, the rest stay in the square.
fn minimax_step(
    field: &SizingField,
    domain: &crate::surface::Domain,
    d: &Discretisation,
    feet: &[Option<(f64, [f64; 2])>],
    points: &[[f64; 2]],
) -> Vec<[f64; 2]> {
    let damping = FIT_MINIMAX_STEP;
    (0..points.len())
        .map(|i| {
            let p = points[i];
            let m = field.metric_at(p);
            let q = |a: [f64; 2], b: [f64; 2]| {
                let (x, y) = (a[0] - b[0], a[1] - b[1]);
                m[0] * x * x + 2.0 * m[1] * x * y + m[2] * y * y
            };
            let targets: Vec<([f64; 2], f64)> = d
                .facet(i)
                .iter()
                .filter_map(|&v| feet[v as usize])
                .filter_map(|(dev, foot)| {
                    let st = domain.to_normalised(foot);
                    let r = q(p, st);
                    (r > 1e-18 && dev.is_finite()).then_some((st, dev / r))
                })
                .collect();
            if targets.len() < 2 {
                return p;
            }
            let f = |x: [f64; 2]| {
                targets
                    .iter()
                    .map(|&(st, c)| c * q(x, st))
                    .fold(0.0, f64::max)
            };
            let fixed = [p[0] <= 0.0 || p[0] >= 1.0, p[1] <= 0.0 || p[1] >= 1.0];
            let constrain = |x: [f64; 2]| {
                [
                    if fixed[0] { p[0] } else { x[0].clamp(0.0, 1.0) },
                    if fixed[1] { p[1] } else { x[1].clamp(0.0, 1.0) },
                ]
            };
            let mut x = p;
            let mut fx = f(x);
            let mut gamma = 0.25;
            for _ in 0..40 {
                let worst = targets
                    .iter()
                    .max_by(|a, b| (a.1 * q(x, a.0)).total_cmp(&(b.1 * q(x, b.0))))
                    .map(|t| t.0)
                    .unwrap_or(x);
                let y = constrain([
                    x[0] + gamma * (worst[0] - x[0]),
                    x[1] + gamma * (worst[1] - x[1]),
                ]);
                let fy = f(y);
                if fy < fx {
                    x = y;
                    fx = fy;
                } else {
                    gamma *= 0.5;
                    if gamma < 1e-4 {
                        break;
                    }
                }
            }
            constrain([
                p[0] + damping * (x[0] - p[0]),
                p[1] + damping * (x[1] - p[1]),
            ])
        })
        .collect()
}

/// A pattern of the lattice search that missed the tolerance by at most [`FIT_NEAR_MISS`]
/// with no invalid facet: its largest and mean vertex deviation, and its points.
type NearMiss = (f64, f64, Vec<[f64; 2]>);

/// Largest deviation of a [`NearMiss`], over the tolerance: the lattices one column or a few
/// points below the one found stand off 1.01 to 1.08 D on the domes of `fit_measure`.
const FIT_NEAR_MISS: f64 = 1.08;

/// Largest mean vertex deviation, over the tolerance, of a [`NearMiss`] that
/// [`relax_near_misses`] relaxes: the relaxation evens the deviations but cannot lower their
/// mean (the lattice is already the thinnest covering), and ends with the largest about 3 %
/// above the mean (samples/paraboloid.json at D = 0.01: the 295-point lattice from 0.993 D,
/// mean 0.943 D, to 0.952 D in 30 steps; a 285-point lattice of mean 0.966 D from 1.052 D
/// to 0.9997 D in 40). The near misses of mean 0.98 to 1.0 D it relaxed to no better than
/// 1.01 to 1.04 D in 80 steps.
const FIT_NEAR_MEAN: f64 = 0.975;

/// Real column counts below the one found, evenly spaced over [`FIT_SMALLER_SPAN`] columns,
/// of the smaller [`Grading::rowwise`] lattices [`wall_lattice`] offers
/// [`relax_near_misses`] unmeasured (each with the row counts from three less to one more;
/// the separable lattices offer those of up to two columns less with the same rows); only
/// those whose mean deviation, going as the inverse of the count from the lattice found,
/// would be at most [`FIT_NEAR_MEAN`] D. On samples/rational-dome.json at D = 0.01 and
/// 0.03 the search's own near misses gave 389 and 137 points, these 370 and 130.
const FIT_SMALLER_STEPS: usize = 16;

/// Columns below the one found spanned by [`FIT_SMALLER_STEPS`].
const FIT_SMALLER_SPAN: f64 = 4.0;

/// Most steps of [`minimax_step`] per near miss.
const FIT_MINIMAX_ITERATIONS: usize = 80;

/// Most discretisations [`relax_near_misses`] runs in all.
const FIT_MINIMAX_BUDGET: usize = 300;

/// Most pattern points [`relax_near_misses`] discretises in all (counted as the best
/// pattern's points per discretisation; fewer discretisations than [`FIT_MINIMAX_BUDGET`]
/// above 833 points): on samples/nurbs-dome.json at D = 0.001 (3,093 points) 300
/// discretisations found nothing and took 2.2 -> 7.1 s of CPU.
const FIT_MINIMAX_POINTS: usize = 250_000;

/// Steps of [`minimax_step`] after which [`minimax_relax`] gives up a near miss whose largest
/// deviation, falling at the rate of its last 5 steps, would not reach the tolerance within
/// [`FIT_MINIMAX_ITERATIONS`].
const FIT_MINIMAX_PATIENCE: usize = 10;

/// How far each point of [`minimax_step`] moves, as a multiple of the way to its weighted
/// 1-centre (over-relaxed: the step towards the 1-centre of a facet whose neighbours move
/// too undershoots). On samples/paraboloid.json at D = 0.01 the 285-point near miss met D
/// after 62 steps with 1.5 and 40 with 2; 0.6 and 1 fell 2 to 3 times slower.
const FIT_MINIMAX_STEP: f64 = 2.0;

/// The best pattern, or a smaller one: the near misses of the lattice search with fewer
/// points and a mean vertex deviation of at most [`FIT_NEAR_MEAN`] D, fewest points first,
/// each relaxed by [`minimax_relax`] until one meets the tolerance with no invalid facet
/// (at most [`FIT_MINIMAX_BUDGET`] discretisations and [`FIT_MINIMAX_POINTS`] points in
/// all; only while the best pattern has at most [`FIT_NEIGHBOUR_POINTS`] points).
#[allow(clippy::too_many_arguments)]
fn relax_near_misses(
    surface: &dyn Surface,
    field: &SizingField,
    best: FittedPattern,
    mut near: Vec<NearMiss>,
    tolerance: f64,
    options: &DiscretiseOptions,
    runs: &mut usize,
    progress: &dyn Progress,
) -> Result<FittedPattern, TpiError> {
    if !best.met || best.invalid_facets > 0 || best.uv.len() > FIT_NEIGHBOUR_POINTS {
        return Ok(best);
    }
    let mean_limit = FIT_NEAR_MEAN * tolerance;
    near.retain(|(_, mean, uv)| uv.len() < best.uv.len() && !(*mean > mean_limit));
    // Fewest points first, each pattern once (measured before unmeasured).
    let points_order = |a: &[[f64; 2]], b: &[[f64; 2]]| {
        a.len().cmp(&b.len()).then_with(|| {
            a.iter()
                .flatten()
                .zip(b.iter().flatten())
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        })
    };
    near.sort_by(|a, b| points_order(&a.2, &b.2).then(a.1.total_cmp(&b.1)));
    near.dedup_by(|a, b| a.2 == b.2);
    near.sort_by(|a, b| a.2.len().cmp(&b.2.len()).then(a.1.total_cmp(&b.1)));
    let iterations = FIT_MINIMAX_ITERATIONS;
    let mut budget = FIT_MINIMAX_BUDGET.min(FIT_MINIMAX_POINTS / best.uv.len().max(1));
    let mut best = best;
    let mut found = false;
    // The measured near misses first, then the smaller lattices not yet measured (each
    // pass up to its first success).
    let (measured, unmeasured): (Vec<NearMiss>, Vec<NearMiss>) =
        near.into_iter().partition(|n| n.1.is_finite());
    for (_, _, uv) in measured
        .into_iter()
        .chain([(f64::NAN, f64::NAN, Vec::new())])
        .chain(unmeasured)
    {
        if uv.is_empty() {
            // Between the passes.
            found = false;
            continue;
        }
        if budget == 0 {
            break;
        }
        if found {
            continue;
        }
        if uv.len() >= best.uv.len() {
            continue;
        }
        let before = *runs;
        let relaxed = minimax_relax(
            surface,
            field,
            uv,
            tolerance,
            iterations.min(budget),
            options,
            runs,
            progress,
        )?;
        budget = budget.saturating_sub(*runs - before);
        if let Some(f) = relaxed {
            best = f;
            found = true;
        }
    }
    Ok(best)
}

/// `points` moved by up to `iterations` steps of [`minimax_step`] until their mesh meets
/// the tolerance with no invalid facet (None when it does not, or when the largest deviation
/// falls too slowly to get there).
#[allow(clippy::too_many_arguments)]
fn minimax_relax(
    surface: &dyn Surface,
    field: &SizingField,
    mut points: Vec<[f64; 2]>,
    tolerance: f64,
    iterations: usize,
    options: &DiscretiseOptions,
    runs: &mut usize,
    progress: &dyn Progress,
) -> Result<Option<FittedPattern>, TpiError> {
    let domain = surface.domain();
    let mut history: Vec<f64> = Vec::new();
    for it in 0..=iterations {
        // A pattern the discretisation refuses (points moved onto each other, a lattice of
        // few columns with coinciding points) is no candidate; a cancellation ends the fit.
        let d = match discretise_with_progress(surface, &points, options, progress) {
            Ok(d) => d,
            Err(e @ TpiError::Cancelled { .. }) => return Err(e),
            Err(_) => {
                *runs += 1;
                return Ok(None);
            }
        };
        *runs += 1;
        if !d.pattern_indices.is_empty() || d.seeds.len() != points.len() {
            return Ok(None);
        }
        let feet = vertex_feet(surface, &d);
        let (deviation, invalid) = judged(largest_foot_deviation(&feet), &d);
        if it == 0 && mean_foot_deviation(&feet) > FIT_NEAR_MEAN * tolerance {
            return Ok(None);
        }
        if deviation <= tolerance && invalid == 0 {
            return Ok(Some(FittedPattern {
                uv: points,
                met: true,
                max_deviation: deviation,
                invalid_facets: 0,
                discretisations: 0,
            }));
        }
        history.push(deviation);
        if it == iterations || !deviation.is_finite() {
            return Ok(None);
        }
        if it >= FIT_MINIMAX_PATIENCE {
            let rate = (history[it - 5] - history[it]) / 5.0;
            if deviation - rate * (iterations - it) as f64 > tolerance {
                return Ok(None);
            }
        }
        points = minimax_step(field, &domain, &d, &feet, &points);
    }
    Ok(None)
}

/// The mean deviation of the vertices of [`vertex_feet`] (0 without any).
fn mean_foot_deviation(feet: &[Option<(f64, [f64; 2])>]) -> f64 {
    let (sum, count) = feet
        .iter()
        .filter_map(|f| f.map(|(dev, _)| dev))
        .fold((0.0, 0usize), |(s, c), d| (s + d, c + 1));
    if count == 0 {
        0.0
    } else {
        sum / count as f64
    }
}
