//! The pipeline: surface + pattern -> samples -> dual structure -> facets -> mesh -> report.
//!
//! [`discretise`] validates the pattern (normalised uv in [0, 1]^2, finite, no duplicates
//! closer than [`crate::tolerance::DUPLICATE_UV_TOLERANCE`], at least three points, not all
//! collinear), leaves out the points outside a trim, and chains the stages, each a typed
//! result of the one before (`run_within`):
//!
//! 1. [`crate::samples::sample`] -> `Samples`: point, normal, principal curvatures and tangent
//!    plane at every pattern point;
//! 2. [`crate::structure::decide_structure`] -> `DualStructure`: the true neighbours (the
//!    dual triangulation) and how the facets are built, by the path the surface takes
//!    (convex envelope, closed hull, strips, flat Voronoi, any curvature);
//! 3. [`crate::facets::build_stage`] -> `Facets`: one planar facet per pattern point, the
//!    vertices three-plane intersections, ending on the boundary, assembled into a mesh
//!    ([`crate::mesh`]: welding, numbering, loops);
//! 4. `measure` -> [`QualityReport`] and the facet flags ([`crate::quality`]).
//!
//! Facet i always belongs to pattern point i (on a trimmed surface, to the i-th point inside
//! the trim): none is dropped or reordered.
//!
//! The result is bit-identical for any number of threads: parallel stages are order-preserving
//! maps, and every shared vertex is computed by one canonical expression.

use std::borrow::Cow;
use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;
use serde::ser::{SerializeMap, SerializeStruct};
use serde::{Serialize, Serializer};

use crate::adjusted_planes::tilt_and_offset;
use crate::boundary::Boundary;
use crate::closed::SurfaceLayout;
use crate::diagnostics::{diagnosed_points, Diagnostic};
use crate::diffgeo::flat_curvatures;
use crate::error::TpiError;
use crate::facets::{
    build_stage, FacetParams, Facets, FootHint, FootHints, TriangleVertex, VertexKind,
};
use crate::mesh::FacetMesh;
use crate::neighbours::{NeighbourStats, SlopeFrame};
use crate::pattern::validate_uv;
use crate::planes::Plane;
use crate::progress::{NoProgress, Progress, Stage, Stages};
use crate::projection::Wrap;
use crate::quality::{report, resolve_feet, QualityReport, ReportInput};
use crate::samples::{bounding_box, sample, Samples};
use crate::structure::{decide_structure, FacetPlan, StructureInput};
use crate::surface::Surface;
use crate::tolerance::{
    COLLINEAR_TOLERANCE, DEFAULT_FAR_VERTEX_FACTOR, DEFAULT_FLAT_TOLERANCE, DEFAULT_WELD_TOLERANCE,
    REVERSAL_CHECK_TOLERANCE,
};
use crate::triangulation::{orient, sorted_pairs, triangle_edges, DualTriangulation};

/// Options of [`discretise`]. `Default` gives the documented defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscretiseOptions {
    /// Verify and repair the neighbours against the envelope of tangent planes where K > 0.
    /// Default value: true.
    pub envelope_repair: bool,
    /// Compute the quality report (planarity, deviation, validity flags). Default value: true.
    pub quality_report: bool,
    /// See [`DEFAULT_FAR_VERTEX_FACTOR`]. Default value: 8.
    pub far_vertex_factor: f64,
    /// See [`DEFAULT_WELD_TOLERANCE`]. Default value: 1e-10.
    pub weld_tolerance: f64,
    /// See [`DEFAULT_FLAT_TOLERANCE`]. Default value: 1e-6.
    pub flat_tolerance: f64,
    /// Which planes the facets lie in. Default value: [`PlaneMode::Exact`].
    pub planes: PlaneMode,
}

/// Which planes the facets lie in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PlaneMode {
    /// Every facet in the exact tangent plane at its seed.
    #[default]
    Exact,
    /// Exact tangent planes, except where they cannot give a valid facet on a surface that is
    /// not convex everywhere: there a few planes are tilted, by at most
    /// [`crate::tolerance::MAX_PLANE_TILT_DEGREES`], through their seeds
    /// (`adjusted_planes.rs`). Convex surfaces are unaffected (their exact planes are
    /// always valid).
    Adjusted,
}

/// How a facet's plane differs from the exact tangent plane at its seed
/// ([`PlaneMode::Adjusted`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlaneAdjustment {
    /// Unit normal of the facet's plane (the seed's normal where it was not tilted).
    pub normal: DVec3,
    /// Angle between the facet's plane and the tangent plane at its seed, in degrees.
    pub tilt_degrees: f64,
    /// Signed distance of the facet's plane from its seed along `normal` (model units).
    pub offset: f64,
}

impl Default for DiscretiseOptions {
    fn default() -> Self {
        Self {
            envelope_repair: true,
            quality_report: true,
            far_vertex_factor: DEFAULT_FAR_VERTEX_FACTOR,
            weld_tolerance: DEFAULT_WELD_TOLERANCE,
            flat_tolerance: DEFAULT_FLAT_TOLERANCE,
            planes: PlaneMode::Exact,
        }
    }
}

/// Wall-clock time of each stage in milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, serde::Deserialize)]
pub struct Timings {
    /// Evaluation and curvature at every pattern point.
    pub samples: f64,
    /// Global Delaunay triangulation in parameter space.
    pub delaunay: f64,
    /// Curvature compensation and envelope repair; on surfaces not convex everywhere also
    /// the validity flips and, with adjusted planes, the plane adjustment.
    pub neighbours: f64,
    /// Facet vertices (three-plane intersections, inside tests) and boundary crossings.
    pub facets: f64,
    /// Mesh assembly: welding, shared vertex numbering, facet loops.
    #[serde(default)]
    pub mesh: f64,
    /// Quality report.
    pub report: f64,
    /// Everything.
    pub total: f64,
}

/// Pattern point data attached to each facet.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seed {
    /// Parameters in the surface's own domain.
    pub uv: [f64; 2],
    /// Surface point.
    pub point: DVec3,
    /// Unit normal Su x Sv.
    pub normal: DVec3,
    /// Principal curvatures k1 <= k2.
    pub curvatures: [f64; 2],
}

/// A discretised surface: an indexed polygon mesh with one planar facet per pattern point.
#[derive(Clone, Debug, Default)]
pub struct Discretisation {
    /// Mesh vertices.
    pub vertices: Vec<DVec3>,
    /// What each vertex is.
    pub vertex_kinds: Vec<VertexKind>,
    /// Facet i's loop is `facet_loops[facet_offsets[i]..facet_offsets[i + 1]]`.
    pub facet_offsets: Vec<u32>,
    /// Flat facet loops (counter-clockwise seen from the normal).
    pub facet_loops: Vec<u32>,
    /// The pattern point of each facet (facet i belongs to pattern point i, or on a trimmed
    /// surface to pattern point `pattern_indices[i]`).
    pub seeds: Vec<Seed>,
    /// On a trimmed surface, the pattern index of each facet's point (the points inside the
    /// trim, in pattern order); empty otherwise (facet i belongs to pattern point i).
    pub pattern_indices: Vec<u32>,
    /// On a trimmed surface, how many pattern points lie outside the trim and were left out
    /// (no facet); 0 otherwise.
    pub outside_trim: usize,
    /// Triangles of the final dual structure (counter-clockwise in parameter space).
    pub dual_triangles: Vec<[u32; 3]>,
    /// On the strips of a developable surface ([`Diagnostic::RulingStrips`]), whose dual
    /// triangles nearly all have a ghost, every neighbour pair (i < j, sorted), so that
    /// [`Discretisation::neighbour_pairs`] holds them all; empty on the other paths.
    pub ghost_neighbours: Vec<[u32; 2]>,
    /// The quality report (None when switched off).
    pub quality: Option<QualityReport>,
    /// Per-facet flags (see `quality::FLAG_*`), empty when the report is off.
    pub facet_flags: Vec<u8>,
    /// Local problems, each naming its pattern points.
    pub diagnostics: Vec<Diagnostic>,
    /// Per facet, its plane against the exact tangent plane ([`PlaneMode::Adjusted`]; empty
    /// with exact planes).
    pub plane_adjustments: Vec<PlaneAdjustment>,
    /// Stage timings.
    pub timings: Timings,
    /// Length units of the surface ([`Surface::units`]), `None` when unitless.
    pub units: Option<crate::units::Units>,
    /// The topology the mesh must have: a disc, or a closed sphere on a closed surface.
    pub topology: MeshTopology,
}

/// The topology a mesh must have ([`Discretisation::sanity_check`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct MeshTopology {
    /// V - E + F.
    pub euler: i64,
    /// Loops of boundary edges.
    pub boundary_loops: usize,
}

impl MeshTopology {
    /// A disc: Euler characteristic 1, one boundary loop.
    pub const DISC: MeshTopology = MeshTopology {
        euler: 1,
        boundary_loops: 1,
    };
    /// A closed sphere: Euler characteristic 2, no boundary.
    pub const SPHERE: MeshTopology = MeshTopology {
        euler: 2,
        boundary_loops: 0,
    };
}

impl Default for MeshTopology {
    fn default() -> Self {
        MeshTopology::DISC
    }
}

impl Discretisation {
    /// Number of facets.
    pub fn facet_count(&self) -> usize {
        self.seeds.len()
    }

    /// The pattern index of facet i's point (i itself unless the surface is trimmed).
    pub fn pattern_index(&self, i: usize) -> usize {
        self.pattern_indices.get(i).map_or(i, |&p| p as usize)
    }

    /// The plane of facet i as (a point of it, unit normal): the seed's tangent plane, or its
    /// adjusted plane ([`PlaneMode::Adjusted`]).
    pub fn facet_plane(&self, i: usize) -> (DVec3, DVec3) {
        let seed = &self.seeds[i];
        match self.plane_adjustments.get(i) {
            Some(a) => (seed.point + a.normal * a.offset, a.normal),
            None => (seed.point, seed.normal),
        }
    }

    /// The vertex loop of facet i.
    pub fn facet(&self, i: usize) -> &[u32] {
        &self.facet_loops[self.facet_offsets[i] as usize..self.facet_offsets[i + 1] as usize]
    }

    /// The symmetric neighbour pairs (i < j) of the dual structure, sorted.
    pub fn neighbour_pairs(&self) -> Vec<[u32; 2]> {
        sorted_pairs(
            triangle_edges(&self.dual_triangles).chain(self.ghost_neighbours.iter().copied()),
        )
    }

    /// The result in the output contract as JSON text; `timings` false leaves out
    /// `timings_ms` (the only part that differs between runs).
    pub fn to_json(&self, timings: bool) -> String {
        let view = ContractView {
            result: self,
            timings,
        };
        serde_json::to_string(&view).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
    }
}

struct ContractView<'a> {
    result: &'a Discretisation,
    timings: bool,
}

struct FacetView<'a> {
    result: &'a Discretisation,
    index: usize,
}

impl Serialize for FacetView<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let seed = &self.result.seeds[self.index];
        let mut s = serializer.serialize_struct("Facet", 6)?;
        s.serialize_field("seed", &self.result.pattern_index(self.index))?;
        s.serialize_field("uv", &seed.uv)?;
        s.serialize_field("point", &seed.point.to_array())?;
        s.serialize_field("normal", &seed.normal.to_array())?;
        s.serialize_field("vertices", self.result.facet(self.index))?;
        if let Some(a) = self.result.plane_adjustments.get(self.index) {
            s.serialize_field("plane_normal", &a.normal.to_array())?;
            s.serialize_field("plane_tilt_deg", &a.tilt_degrees)?;
            s.serialize_field("plane_offset", &a.offset)?;
        }
        s.serialize_field(
            "flags",
            &self
                .result
                .facet_flags
                .get(self.index)
                .copied()
                .unwrap_or(0),
        )?;
        s.end()
    }
}

impl Serialize for ContractView<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let r = self.result;
        let mut map = serializer.serialize_map(None)?;
        let vertices: Vec<[f64; 3]> = r.vertices.iter().map(|v| v.to_array()).collect();
        map.serialize_entry("units", &r.units)?;
        map.serialize_entry("vertices", &vertices)?;
        let facets: Vec<FacetView<'_>> = (0..r.facet_count())
            .map(|index| FacetView { result: r, index })
            .collect();
        map.serialize_entry("facets", &facets)?;
        map.serialize_entry("dual_triangles", &r.dual_triangles)?;
        map.serialize_entry("quality", &r.quality)?;
        map.serialize_entry("diagnostics", &r.diagnostics)?;
        if !r.pattern_indices.is_empty() {
            map.serialize_entry("pattern_points_outside_trim", &r.outside_trim)?;
        }
        if self.timings {
            map.serialize_entry("timings_ms", &r.timings)?;
        }
        map.end()
    }
}

/// Checks normalised pattern points: finite, inside [0, 1]^2, no duplicates
/// (`validate_uv` in the pattern module), and at least three of them.
pub fn validate_pattern(points: &[[f64; 2]]) -> Result<(), TpiError> {
    if points.len() < 4096 {
        validate_uv(points)?;
    } else {
        validate_large(points)?;
    }
    if points.len() < 3 {
        return Err(TpiError::TooFewPatternPoints {
            found: points.len(),
            needed: 3,
        });
    }
    Ok(())
}

/// [`validate_uv`] for large patterns, with the same errors: the range check, then for
/// every point in parallel its nearest earlier point closer than the duplicate tolerance
/// (ties: the smaller index; the same distance formula), found in a grid of about one point
/// per cell (a duplicate lies in the point's cell or a neighbour, the cells being larger than
/// the tolerance), and the first point that has one.
fn validate_large(points: &[[f64; 2]]) -> Result<(), TpiError> {
    use crate::tolerance::DUPLICATE_UV_TOLERANCE;
    for (index, &[s, t]) in points.iter().enumerate() {
        if !((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)) {
            return Err(TpiError::PatternPointOutOfRange { index, s, t });
        }
    }
    let n = points.len();
    let size = ((n as f64).sqrt() as usize).clamp(1, (1.0 / DUPLICATE_UV_TOLERANCE) as usize / 4);
    let cell_of = |x: f64| ((x * size as f64) as usize).min(size - 1);
    let index = |p: [f64; 2]| cell_of(p[1]) * size + cell_of(p[0]);
    let mut start = vec![0u32; size * size + 1];
    for &p in points {
        start[index(p) + 1] += 1;
    }
    for c in 0..size * size {
        start[c + 1] += start[c];
    }
    // The points sorted by cell, with their coordinates (scanned in memory order below).
    let mut fill = start.clone();
    let mut members = vec![([0.0f64; 2], 0u32); n];
    for (i, &p) in points.iter().enumerate() {
        let c = index(p);
        members[fill[c] as usize] = (p, i as u32);
        fill[c] += 1;
    }
    drop(fill);
    // For the points of cell row y, the earlier points closer than the tolerance in the rows
    // y - 1 ..= y + 1: the smallest later index that has one.
    let first = (0..size)
        .into_par_iter()
        .filter_map(|y| {
            let mut first: Option<usize> = None;
            for x in 0..size {
                let c = y * size + x;
                for &(p, i) in &members[start[c] as usize..start[c + 1] as usize] {
                    let i = i as usize;
                    if first.is_some_and(|f| f <= i) {
                        continue;
                    }
                    let lo_x = x.saturating_sub(1);
                    let hi_x = (x + 1).min(size - 1);
                    let has = (y.saturating_sub(1)..=(y + 1).min(size - 1)).any(|row| {
                        let run = &members[start[row * size + lo_x] as usize
                            ..start[row * size + hi_x + 1] as usize];
                        run.iter().any(|&(q, k)| {
                            let (dx, dy) = (p[0] - q[0], p[1] - q[1]);
                            // A cheap bound first; the exact test is the one of Pattern::validate.
                            (k as usize) < i
                                && dx * dx + dy * dy
                                    < 4.0 * DUPLICATE_UV_TOLERANCE * DUPLICATE_UV_TOLERANCE
                                && dx.hypot(dy) < DUPLICATE_UV_TOLERANCE
                        })
                    });
                    if has {
                        first = Some(i);
                    }
                }
            }
            first
        })
        .min();
    if let Some(i) = first {
        // Its nearest earlier point (ties: the smaller index).
        let p = points[i];
        let mut best: Option<(usize, f64)> = None;
        for (k, q) in points[..i].iter().enumerate() {
            let d = (p[0] - q[0]).hypot(p[1] - q[1]);
            if d < DUPLICATE_UV_TOLERANCE
                && best.map_or(true, |(bk, bd)| d < bd || (d == bd && k < bk))
            {
                best = Some((k, d));
            }
        }
        if let Some((duplicate_of, distance)) = best {
            return Err(TpiError::DuplicatePatternPoint {
                index: i,
                duplicate_of,
                distance,
            });
        }
    }
    Ok(())
}

/// Discretises `surface` with pattern points given in normalised [0, 1]^2 coordinates.
pub fn discretise(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
) -> Result<Discretisation, TpiError> {
    discretise_with_progress(surface, pattern, options, &NoProgress)
}

/// [`discretise`], reporting each stage's start, work items done and end to `progress`
/// ([`crate::Progress`]); the result is the same as without an observer.
pub fn discretise_with_progress(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
    progress: &dyn Progress,
) -> Result<Discretisation, TpiError> {
    run(surface, pattern, options, false, progress).map(|(result, _)| result)
}

/// What the pipeline computed on the way, kept for live editing ([`crate::live`]).
pub(crate) struct PipelineState {
    pub(crate) uv: Vec<[f64; 2]>,
    pub(crate) seeds: Vec<Seed>,
    pub(crate) tangents: Vec<[DVec3; 2]>,
    pub(crate) planes: Vec<Plane>,
    pub(crate) convex_side: Vec<i8>,
    /// The slope frame and slopes where the convex path ran.
    pub(crate) slopes: Option<(SlopeFrame, Vec<[f64; 2]>)>,
    pub(crate) triangulation: DualTriangulation,
    pub(crate) triangle_vertices: Vec<TriangleVertex>,
    pub(crate) vertex_source: Vec<u32>,
    pub(crate) facet_simple: Vec<bool>,
    /// The report's foot of every vertex (None: unused, or the report is off).
    pub(crate) feet: Vec<Option<[f64; 2]>>,
    pub(crate) neighbours: NeighbourStats,
    /// Triangles whose vertices were welded (their facets are not simple for live editing).
    pub(crate) welded: Vec<u32>,
    pub(crate) diagonal: f64,
    /// Bounding box of the surface points.
    pub(crate) bbox: (DVec3, DVec3),
    /// How the report's projections continue past the domain's sides.
    pub(crate) wrap: Wrap,
}

/// Adds [`Diagnostic::UnexpectedTopology`] when the report's Euler characteristic and
/// boundary loops are not those of `result.topology` (on a trimmed surface: a disc with as
/// many holes as extra loops, Euler characteristic 2 - loops), as
/// [`Discretisation::sanity_check`] judges them.
pub(crate) fn note_topology(result: &mut Discretisation, trimmed: bool) {
    let Some(q) = result.quality.as_mut() else {
        return;
    };
    let expected = result.topology;
    let (euler, loops) = (q.euler_characteristic, q.boundary_loops);
    let as_expected = (euler == expected.euler && loops == expected.boundary_loops)
        || (trimmed && loops >= 1 && euler == 2 - loops as i64);
    if !as_expected {
        result.diagnostics.push(Diagnostic::UnexpectedTopology {
            euler,
            boundary_loops: loops as u32,
            expected_euler: expected.euler,
            expected_loops: expected.boundary_loops as u32,
        });
        q.diagnostic_count += 1;
    }
}

/// The pipeline; with `keep` also its state.
///
/// On a trimmed surface ([`Surface::trim`]) the pattern points outside the trim are left out
/// before sampling; the facets of the others end on the trim ([`crate::boundary`]), and the
/// result names each facet's pattern index. Trims are not taken with `keep` (live editing),
/// nor on a developable surface whose strips cannot be built: there
/// [`TpiError::TrimUnsupported`], never a result that ignores the trim.
pub(crate) fn run(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
    keep: bool,
    progress: &dyn Progress,
) -> Result<(Discretisation, Option<PipelineState>), TpiError> {
    let start = Instant::now();
    let stages = Stages::new(progress);
    validate_pattern(pattern)?;
    let Some(trim) = surface.trim() else {
        let rectangle = Boundary::Rectangle(surface.domain());
        let strips = run_within(
            surface, pattern, options, keep, &rectangle, start, true, &stages,
        )?;
        // With adjusted planes, strips left invalid (next to an inflection of a developable
        // surface's cross-section, crate::rulings) are weighed against the general path,
        // which tilts the planes there; the one with fewer invalid facets is kept.
        let invalid = |r: &Discretisation| r.quality.as_ref().map_or(0, |q| q.invalid_facets);
        let ruled = strips
            .0
            .diagnostics
            .iter()
            .any(|d| matches!(d, Diagnostic::RulingStrips { .. }));
        if options.planes == PlaneMode::Adjusted && ruled && invalid(&strips.0) > 0 {
            let general = run_within(
                surface, pattern, options, keep, &rectangle, start, false, &stages,
            )?;
            if invalid(&general.0) < invalid(&strips.0) {
                return Ok(general);
            }
        }
        return Ok(strips);
    };
    if keep {
        return Err(TpiError::TrimUnsupported {
            reason: "live editing does not take trimmed surfaces yet; discretise instead".into(),
        });
    }
    let domain = surface.domain();
    let boundary = Boundary::new(domain, Some(trim));
    // Points on a loop are decided by the crossing rule of `Trim::contains`.
    let kept: Vec<u32> = (0..pattern.len() as u32)
        .filter(|&i| trim.contains(domain.from_normalised(pattern[i as usize])))
        .collect();
    if kept.len() < 3 {
        return Err(TpiError::InvalidTrim {
            item: "trim".into(),
            reason: format!(
                "only {} of the {} pattern points lie inside the trim; at least 3 are needed",
                kept.len(),
                pattern.len()
            ),
        });
    }
    let inside: Vec<[f64; 2]> = kept.iter().map(|&i| pattern[i as usize]).collect();
    let (mut result, state) = run_within(
        surface, &inside, options, keep, &boundary, start, true, &stages,
    )?;
    for d in &mut result.diagnostics {
        d.map_points(|p| kept[p as usize]);
    }
    result.outside_trim = pattern.len() - kept.len();
    result.pattern_indices = kept;
    Ok((result, state))
}

/// The pipeline on validated pattern points, the facets ending on `boundary`; `allow_strips`
/// lets a developable surface with rulings along parameter lines take the strips
/// (crate::rulings). Each stage is reported to `stages` where it is timed.
// The pipeline's inputs and the two switches of `run`; a struct would only rename them.
#[allow(clippy::too_many_arguments)]
fn run_within(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
    keep: bool,
    boundary: &Boundary,
    start: Instant,
    allow_strips: bool,
    stages: &Stages<'_>,
) -> Result<(Discretisation, Option<PipelineState>), TpiError> {
    let mut timings = Timings::default();
    stages.check()?;
    stages.enter(Stage::Samples, Some(pattern.len()));
    let mut samples = sample(surface, pattern, options, stages.observer())?;
    timings.samples = ms(start);
    stages.check()?;
    stages.leave();

    // Sampled once: the structure decides by it, the report projects by it.
    let layout = crate::closed::surface_layout(surface);
    let wrap = Wrap::from_layout(surface.domain(), &layout);
    let input = StructureInput {
        surface,
        pattern,
        options,
        boundary,
        allow_strips,
        layout: &layout,
    };
    let structure = decide_structure(&input, &mut samples, &mut timings, stages)?;
    // Only the structure reads these: let go before the facets, the pipeline's peak.
    samples.plane_uv = Vec::new();
    samples.lifted = None;
    samples.geometry = Vec::new();
    let (topology, strips, neighbours) = (
        structure.topology,
        structure.is_strips(),
        structure.neighbours,
    );

    stages.check()?;
    let stage = Instant::now();
    let params = FacetParams {
        far_vertex_factor: options.far_vertex_factor,
        weld_distance: options.weld_tolerance * samples.diagonal,
        reversal_distance: REVERSAL_CHECK_TOLERANCE * samples.diagonal,
        exact_dual: matches!(structure.plan, FacetPlan::Clipped { band: Some(_) }),
    };
    let facets = build_stage(
        surface,
        boundary,
        &mut samples,
        structure,
        &params,
        !keep,
        stages,
    );
    check_not_developable(&facets, &samples, strips)?;
    timings.facets = ms(stage) - facets.mesh.assembly_ms;
    timings.mesh = facets.mesh.assembly_ms;

    let Facets {
        mesh,
        triangulation,
        ghost_neighbours,
    } = facets;
    let FacetMesh {
        vertices,
        vertex_kinds,
        offsets,
        loops,
        known_feet,
        triangle_vertices,
        vertex_source,
        facet_simple,
        welded,
        diagnostics,
        ..
    } = mesh;
    samples.diagnostics.extend(diagnostics);
    let mut result = Discretisation {
        vertices,
        vertex_kinds,
        facet_offsets: offsets,
        facet_loops: loops,
        // Built at the end from the samples (Samples::seeds).
        seeds: Vec::new(),
        pattern_indices: Vec::new(),
        outside_trim: 0,
        dual_triangles: Vec::new(),
        ghost_neighbours,
        quality: None,
        facet_flags: Vec::new(),
        diagnostics: std::mem::take(&mut samples.diagnostics),
        plane_adjustments: Vec::new(),
        timings,
        units: surface.units(),
        topology,
    };
    let live_triangulation = keep.then(|| triangulation.clone());
    result.dual_triangles = triangulation.triangles;
    drop(triangulation.neighbours);
    // The tangents and slopes are let go before the hints are listed and the report runs,
    // unless live editing keeps them.
    if !keep {
        samples.tangents = Vec::new();
        samples.slopes = None;
    }
    // What the report knows of each vertex's foot. Without live editing the triangle
    // vertices' hints are listed per vertex and the triangle vertices let go (they are twice
    // the list); with it they are kept and read where they are.
    let (live, mut listed): (Option<LiveParts>, Vec<FootHint>) = match live_triangulation {
        Some(triangulation) => {
            let live = LiveParts {
                triangulation,
                triangle_vertices,
                vertex_source,
                facet_simple,
                welded,
            };
            (Some(live), Vec::new())
        }
        None if options.quality_report => {
            // The triangle vertices' hints in the triangle vertices' buffer (collected in
            // place, then shrunk to their size), so that the triangle vertices and the list
            // are not held at once.
            let mut by_triangle: Vec<FootHint> =
                triangle_vertices.into_iter().map(|t| t.hint()).collect();
            by_triangle.shrink_to_fit();
            let hints = FootHints::ByTriangle {
                hints: &by_triangle,
                vertex_source: &vertex_source,
                known: &known_feet,
            };
            let listed = (0..result.vertices.len()).map(|v| hints.get(v)).collect();
            drop((by_triangle, vertex_source, facet_simple, welded));
            (None, listed)
        }
        None => {
            drop((triangle_vertices, vertex_source, facet_simple, welded));
            (None, Vec::new())
        }
    };
    stages.check()?;
    let mut resolved = Vec::new();
    if options.quality_report {
        let stage = Instant::now();
        stages.enter(
            Stage::Report,
            Some(samples.uv.len() + result.vertices.len()),
        );
        if let Some(live) = &live {
            resolved = resolve_feet(
                surface,
                &wrap,
                &samples.uv,
                &result.vertices,
                &result.facet_offsets,
                &result.facet_loops,
                FootHints::Mesh {
                    triangle_vertices: &live.triangle_vertices,
                    vertex_source: &live.vertex_source,
                    known: &known_feet,
                },
            );
            let known = |f: &Option<[f64; 2]>| f.map_or(FootHint::FromSeed, FootHint::Known);
            listed = resolved.iter().map(known).collect();
        }
        measure(
            surface,
            &wrap,
            &samples,
            &mut result,
            neighbours,
            std::mem::take(&mut listed),
            stages,
        );
        note_topology(&mut result, boundary.is_trim());
        result.timings.report = ms(stage);
    }
    stages.check()?;
    stages.leave();
    drop((listed, known_feet));
    // The seeds last, when the facet stage's and the report's temporaries are gone.
    result.seeds = samples.seeds();
    if options.planes == PlaneMode::Adjusted {
        // Every facet says how its plane differs (0 where it is the exact tangent plane, as
        // everywhere on convex surfaces).
        result.plane_adjustments = plane_adjustments(&result.seeds, &samples.planes);
    }
    result.timings.total = ms(start);
    let state = live.map(|live| pipeline_state(samples, &result, live, neighbours, resolved, wrap));
    Ok((result, state))
}

/// What live editing keeps of the facet stage beyond the output.
struct LiveParts {
    triangulation: DualTriangulation,
    triangle_vertices: Vec<TriangleVertex>,
    vertex_source: Vec<u32>,
    facet_simple: Vec<bool>,
    welded: Vec<u32>,
}

/// Refuses a surface none of whose dual triangles gave a well-conditioned vertex (every
/// triple of neighbouring planes nearly parallel), except on strips, which are built for it.
/// Where the seeds are curved, the pattern is to blame, not the surface.
fn check_not_developable(facets: &Facets, samples: &Samples, strips: bool) -> Result<(), TpiError> {
    let mesh = &facets.mesh;
    let ill_conditioned = mesh
        .diagnostics
        .iter()
        .filter(|d| matches!(d, Diagnostic::IllConditionedVertex { .. }))
        .count();
    if !mesh.vertices.is_empty() && !strips && ill_conditioned == facets.triangulation.len() {
        // Curved at the seeds, the planes fail to meet because of the pattern (issue 14: four
        // random points nearly on one line on a saddle were said to make it developable).
        let flat_seeds = samples
            .curvatures
            .iter()
            .all(|&[k1, k2]| flat_curvatures(k1, k2));
        let reason = if flat_seeds {
            "every triple of neighbouring tangent planes is (nearly) parallel: the surface is developable".to_string()
        } else {
            format!(
                "every triple of neighbouring tangent planes is (nearly) parallel, though the surface is curved at the pattern points: the {} points are too few or too close to one line for their tangent planes to meet; use more points, spread in both directions",
                samples.uv.len()
            )
        };
        return Err(TpiError::DegenerateSurface { reason });
    }
    Ok(())
}

/// Stage 5 of the pipeline: the quality report of `result` and its facet flags, the feet of
/// its vertices as the facet stage (or live editing) knows them.
fn measure(
    surface: &dyn Surface,
    wrap: &Wrap,
    samples: &Samples,
    result: &mut Discretisation,
    neighbours: NeighbourStats,
    feet: Vec<FootHint>,
    stages: &Stages<'_>,
) {
    let diagnosed = diagnosed_points(&result.diagnostics, samples.uv.len());
    // The envelope of tangent planes decides a facet's shape only where its plane is the
    // tangent plane: a seed whose plane was adjusted counts as not strictly convex.
    let convex_side: Cow<'_, [i8]> = match &samples.tangent_planes {
        Some(tangent) => samples
            .convex_side
            .iter()
            .zip(samples.planes.iter().zip(tangent))
            .map(|(&side, (plane, tangent))| if plane == tangent { side } else { 0 })
            .collect(),
        None => Cow::Borrowed(&samples.convex_side),
    };
    let (quality, flags) = report(
        &ReportInput {
            surface,
            uv: &samples.uv,
            planes: &samples.planes,
            vertices: &result.vertices,
            offsets: &result.facet_offsets,
            loops: &result.facet_loops,
            diagonal: samples.diagonal,
            diagnosed: &diagnosed,
            neighbours,
            diagnostic_count: result.diagnostics.len(),
            convex_side: &convex_side,
            wrap,
        },
        feet,
        stages.observer(),
    );
    result.quality = Some(quality);
    result.facet_flags = flags;
}

/// What live editing keeps of a run ([`PipelineState`]).
fn pipeline_state(
    samples: Samples,
    result: &Discretisation,
    live: LiveParts,
    neighbours: NeighbourStats,
    resolved: Vec<Option<[f64; 2]>>,
    wrap: Wrap,
) -> PipelineState {
    let (lo, hi) = bounding_box(samples.planes.iter().map(|p| p.point));
    let side = samples.convex_side.first().copied().unwrap_or(0);
    PipelineState {
        uv: samples.uv,
        seeds: result.seeds.clone(),
        tangents: samples.tangents,
        planes: samples.planes,
        convex_side: samples.convex_side,
        slopes: samples
            .frame
            .zip(samples.slopes)
            .map(|(n, s)| (SlopeFrame::new(n, side), s)),
        triangulation: live.triangulation,
        triangle_vertices: live.triangle_vertices,
        vertex_source: live.vertex_source,
        facet_simple: live.facet_simple,
        feet: resolved,
        neighbours,
        welded: live.welded,
        diagonal: samples.diagonal,
        bbox: (lo, hi),
        wrap,
    }
}

/// Each facet's plane against the exact tangent plane at its seed.
pub(crate) fn plane_adjustments(seeds: &[Seed], planes: &[Plane]) -> Vec<PlaneAdjustment> {
    seeds
        .iter()
        .zip(planes)
        .map(|(seed, plane)| {
            let (tilt_degrees, offset) = tilt_and_offset(plane, seed.point, seed.normal);
            PlaneAdjustment {
                normal: plane.normal,
                tilt_degrees,
                offset,
            }
        })
        .collect()
}

/// Rejects patterns whose points all lie on one line in parameter space (no facet could
/// close), whatever space the triangulation is then built in.
pub(crate) fn check_not_collinear(points: &[[f64; 2]]) -> Result<(), TpiError> {
    let first = points[0];
    let distance2 = |p: [f64; 2]| (p[0] - first[0]).powi(2) + (p[1] - first[1]).powi(2);
    let far = points
        .iter()
        .copied()
        .max_by(|a, b| distance2(*a).total_cmp(&distance2(*b)))
        .unwrap_or(first);
    let scale = distance2(far);
    if points
        .iter()
        .any(|&p| orient(first, far, p).abs() > COLLINEAR_TOLERANCE * scale)
    {
        Ok(())
    } else {
        Err(TpiError::CollinearPattern {
            count: points.len(),
        })
    }
}

pub(crate) fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// The size of the triangulation plane's rectangle: the scale factors that
/// `samples::scaled_parameters` applied to the normalised pattern coordinates.
pub(crate) fn plane_extent(plane_uv: &[[f64; 2]], pattern: &[[f64; 2]]) -> [f64; 2] {
    let mut extent = [1.0, 1.0];
    for axis in 0..2 {
        if let Some(k) =
            (0..pattern.len()).max_by(|&a, &b| pattern[a][axis].total_cmp(&pattern[b][axis]))
        {
            if pattern[k][axis] > 0.0 {
                extent[axis] = plane_uv[k][axis] / pattern[k][axis];
            }
        }
    }
    extent
}

/// No seed on a pole (its tangent plane is not defined by the parametrisation); on a closed
/// surface about to be discretised as one (`closing`: convex, untrimmed) also no seed where
/// the surface is singular and no two seeds on one surface point (across the seam).
pub(crate) fn check_closed_seeds(
    surface: &dyn Surface,
    layout: &SurfaceLayout,
    uv: &[[f64; 2]],
    planes: &[Plane],
    regular: &[bool],
    closing: bool,
    tolerance: f64,
) -> Result<(), TpiError> {
    let bad = |i: usize| layout.on_pole(surface, uv[i]) || (closing && !regular[i]);
    if let Some(i) = (0..uv.len()).find(|&i| bad(i)) {
        return Err(TpiError::InvalidParameter {
            field: format!("pattern point {i}"),
            value: if layout.closed[0] { uv[i][1] } else { uv[i][0] },
            reason: "it lies on a pole of the surface, where the parametrisation defines no tangent plane; move it off the pole".into(),
        });
    }
    if !closing {
        return Ok(());
    }
    // The seeds' surface points are their tangent planes'.
    let point = |i: usize| planes[i].point;
    let mut order: Vec<usize> = (0..planes.len()).collect();
    let key = |i: usize| point(i).to_array();
    order.sort_unstable_by(|&a, &b| {
        key(a)
            .partial_cmp(&key(b))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if point(j).x - point(i).x > tolerance {
                break;
            }
            if point(i).distance(point(j)) <= tolerance {
                return Err(TpiError::SameSurfacePoint {
                    index: i.max(j),
                    duplicate_of: i.min(j),
                    place: "across the seam of the closed surface".into(),
                });
            }
        }
    }
    Ok(())
}
