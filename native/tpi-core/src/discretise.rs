//! The pipeline: surface + pattern -> samples -> neighbours -> facets -> mesh -> report.
//!
//! [`discretise`] validates the pattern (normalised uv in [0, 1]^2, finite, no duplicates
//! closer than [`crate::tolerance::DUPLICATE_UV_TOLERANCE`], at least three points, not all
//! collinear), evaluates point, normal and principal curvatures at every pattern point,
//! decides the true neighbours ([`crate::neighbours`]), builds one planar facet per pattern
//! point ([`crate::facets`]) and measures the result ([`crate::quality`]). Facet i always
//! belongs to pattern point i: none is dropped or reordered.
//!
//! The result is bit-identical for any number of threads: parallel stages are order-preserving
//! maps, and every shared vertex is computed by one canonical expression.

use std::time::Instant;

use glam::DVec3;
use rayon::prelude::*;
use serde::ser::{SerializeMap, SerializeStruct};
use serde::{Serialize, Serializer};

use crate::adjusted_planes::{adjust_planes, tilt_and_offset};
use crate::boundary::Boundary;
use crate::closed;
use crate::diagnostics::Diagnostic;
use crate::diffgeo::{flat_curvatures, LocalGeometry};
use crate::error::TpiError;
use crate::facets::{
    build_closed_facets, build_facets, build_ghost_clipped_facets, FacetParams, FootHint,
    TriangleVertex, VertexKind,
};
use crate::flat;
use crate::ghosts::{augment, augment_within_trim};
use crate::mesh::{FacetMesh, SlopeView};
use crate::neighbours::{decide, decide_convex, NeighbourInput, NeighbourStats, SlopeFrame};
use crate::pattern::validate_uv;
use crate::periodic;
use crate::planes::{coincident, Plane};
use crate::progress::{NoProgress, Progress, Stage, Stages};
use crate::quality::{report, resolve_feet, QualityReport, ReportInput};
use crate::rulings;
use crate::samples::{bounding_box, sample, Samples};
use crate::surface::Surface;
use crate::tolerance::{
    COLLINEAR_TOLERANCE, DEFAULT_FAR_VERTEX_FACTOR, DEFAULT_FLAT_TOLERANCE, DEFAULT_WELD_TOLERANCE,
    REVERSAL_CHECK_TOLERANCE, STRIP_TRIM_MARGIN,
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
/// ([`crate::progress`]); the result is the same as without an observer.
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
    let observer = stages.observer();
    stages.enter(Stage::Samples, Some(pattern.len()));

    let Samples {
        uv,
        geometry,
        tangents,
        mut planes,
        diagonal,
        convex_side,
        plane_uv,
        seeds,
        frame,
        lifted,
        slopes,
        mut diagnostics,
    } = sample(surface, pattern, options, observer)?;
    timings.samples = ms(start);
    stages.leave();

    // Closed surfaces and poles (crate::closed): seeds on a pole are refused everywhere, and
    // seeds on one surface point across the seam where the seam is to be closed.
    let layout = closed::surface_layout(surface);
    let convex = convex_side.iter().all(|&s| s != 0 && s == convex_side[0]);
    let closable = layout.open_sides().is_some() && convex && !boundary.is_trim();
    if layout.poles.contains(&true) || closable {
        let regular: Vec<bool> = if geometry.len() == uv.len() {
            geometry.iter().map(|g| g.regular).collect()
        } else {
            vec![true; uv.len()]
        };
        let weld = options.weld_tolerance * diagonal;
        check_closed_seeds(surface, &layout, &uv, &seeds, &regular, closable, weld)?;
    }
    // A convex surface closed in one direction: the envelope is the hull of the dual points,
    // with ghost seeds beyond its open sides (not at its poles or its seam) that end the mesh
    // there as on the any-curvature path. Where the closed surface is not convex at every
    // seed, or its tangent planes do not bound one convex body (a dented sphere), it is
    // discretised as an open patch (the CLI warns that the seam stays open). A trimmed one is
    // left to the clipping of the convex paths, which ends it on its trim.
    let hull_stage = Instant::now();
    let mut closed_ghosts: Option<(Vec<Plane>, Vec<u32>)> = None;
    let mut closed_topology = MeshTopology::DISC;
    let envelope = match layout.open_sides() {
        Some(open) if closable => {
            // Timed as the triangulation when the hull succeeds (below).
            stages.enter(Stage::Delaunay, None);
            let holes = open.iter().filter(|&&o| o).count();
            closed_topology = MeshTopology {
                euler: 2 - holes as i64,
                boundary_loops: holes,
            };
            if holes == 0 {
                closed::envelope_triangulation(&planes, planes.len()).ok()
            } else {
                // The slope path lets the local geometry go: the ghosts need it.
                let recomputed: Vec<LocalGeometry>;
                let full: &[LocalGeometry] = if geometry.len() == uv.len() {
                    &geometry
                } else {
                    recomputed = uv
                        .iter()
                        .map(|&[u, v]| LocalGeometry::from_derivatives(&surface.evaluate(u, v)))
                        .collect();
                    &recomputed
                };
                let extent = plane_extent(&plane_uv, pattern);
                let ghosts = augment(surface, &uv, &plane_uv, extent, full, &convex_side, open);
                let envelope = closed::envelope_triangulation(&ghosts.planes, uv.len()).ok();
                closed_ghosts = Some((ghosts.planes, ghosts.source));
                envelope
            }
        }
        _ => None,
    };
    let closed_convex = envelope.is_some();
    // Seeds of a seam about to be closed: no two on one surface point across it.
    let check_seam = |uv: &[[f64; 2]], seeds: &[Seed]| {
        let weld = options.weld_tolerance * diagonal;
        let regular = vec![true; uv.len()];
        check_closed_seeds(surface, &layout, uv, seeds, &regular, true, weld)
    };
    // A developable surface with rulings along parameter lines (crate::rulings): strips, and
    // an annulus where it is closed across its rulings.
    // Rulings are sampled only where every seed is flat (K ~ 0): elsewhere they cannot be.
    let flat_seeds = seeds
        .iter()
        .all(|s| flat_curvatures(s.curvatures[0], s.curvatures[1]));
    let rulings = flat_seeds.then(|| rulings::find_rulings(surface)).flatten();
    // Trimmed, they are the strips of the seeds inside, with walls beyond the domain, clipped
    // on the trim by the facet stage.
    let trimmed = boundary.is_trim();
    let strips = match rulings.filter(|_| allow_strips) {
        Some(r) if !closed_convex => {
            let closed = layout.closed[1 - r.along];
            if closed && !trimmed {
                check_seam(&uv, &seeds)?;
            }
            stages.enter(Stage::Delaunay, None);
            let margin = if trimmed {
                STRIP_TRIM_MARGIN * diagonal
            } else {
                0.0
            };
            rulings::strip_structure(surface, r, &uv, &planes, closed, margin)
                .map(|(triangulation, planes, source)| (r, closed, triangulation, planes, source))
        }
        _ => None,
    };
    let strips_closed = strips.as_ref().is_some_and(|s| s.1);
    let strip_dual = strips.is_some();
    let ghost_dual = closed_convex || strip_dual;
    let mut ghost_neighbours = Vec::new();
    let strip_triangulation = strips.map(|(r, closed, triangulation, all_planes, source)| {
        if closed && !trimmed {
            closed_topology = MeshTopology {
                euler: 0,
                boundary_loops: 2,
            };
        }
        // Their zero curvature is what the strips are built for, not a defect to flag.
        diagnostics.retain(|d| !matches!(d, Diagnostic::FlatPoint { .. }));
        diagnostics.push(Diagnostic::RulingStrips {
            direction: r.along as u8,
            closed,
        });
        closed_ghosts = Some((all_planes, source));
        triangulation
    });
    let mut seam_closed = false;
    // A flat surface closed one way (a ring, a disc around a pole): its facets end only on its
    // open sides, and cells run across its seam (crate::boundary, a band).
    let mut flat_band: Option<Boundary> = None;

    // Candidates and true neighbours.
    let stage = Instant::now();
    let flat = planes.iter().all(|p| coincident(&planes[0], p));
    check_not_collinear(&plane_uv)?;
    let input = NeighbourInput {
        plane_uv: &plane_uv,
        geometry: &geometry,
        planes: &planes,
        convex_side: &convex_side,
        any_curvature: false,
    };
    let (mut triangulation, mut augmented, mut neighbours) = match (&slopes, &lifted) {
        _ if ghost_dual => {
            timings.delaunay = ms(hull_stage);
            stages.enter(Stage::Delaunay, None);
            (
                strip_triangulation.or(envelope).unwrap_or_default(),
                None,
                NeighbourStats::default(),
            )
        }
        // Convex everywhere: the envelope's own structure, computed in slope space.
        (Some(slopes), Some(lifted)) => {
            stages.enter(Stage::Delaunay, None);
            let mut triangulation = DualTriangulation::delaunay(slopes)?;
            timings.delaunay = ms(stage);
            let stage = Instant::now();
            let stats = decide_convex(&mut triangulation, slopes, lifted, &input, stages);
            timings.neighbours = ms(stage);
            (triangulation, None, stats)
        }
        // Strictly convex everywhere but too steep for the slope embedding: the envelope tests
        // on parameter-space candidates, with the boundary clipped on the wall.
        _ if convex_side.iter().all(|&s| s != 0 && s == convex_side[0]) => {
            stages.enter(Stage::Delaunay, None);
            let mut triangulation = DualTriangulation::delaunay(&plane_uv)?;
            timings.delaunay = ms(stage);
            let stage = Instant::now();
            stages.enter(Stage::Neighbours, None);
            let stats = decide(
                &mut triangulation,
                &input,
                options.envelope_repair,
                plane_uv.len(),
            );
            timings.neighbours = ms(stage);
            (triangulation, None, stats)
        }
        // A flat surface: the Voronoi cells of the seeds in its plane (crate::flat), clipped
        // on the boundary (or the trim) as on the convex paths.
        _ if flat => {
            if let Some(walls) = layout.open_sides().filter(|_| !boundary.is_trim()) {
                check_seam(&uv, &seeds)?;
                let open = walls.iter().filter(|&&w| w).count();
                closed_topology = MeshTopology {
                    euler: 2 - open as i64,
                    boundary_loops: open,
                };
                seam_closed = true;
                flat_band = Some(Boundary::Band {
                    domain: surface.domain(),
                    walls,
                    closed: layout.closed,
                });
            }
            stages.enter(Stage::Delaunay, None);
            let triangulation = flat::voronoi_dual(&planes)?;
            timings.delaunay = ms(stage);
            // Zero curvature is what this path is for, not a defect to flag; every neighbour
            // pair is separated by its bisector.
            diagnostics.retain(|d| !matches!(d, Diagnostic::FlatPoint { .. }));
            diagnostics.push(Diagnostic::CoincidentPlanes {
                pairs: real_pairs(&triangulation, planes.len()).len() as u32,
            });
            (triangulation, None, NeighbourStats::default())
        }
        // A trimmed cylinder, cone or extrusion whose strips could not be built (seeds of
        // several rulings on one plane): the ghosts' triangulation would give no valid mesh.
        _ if boundary.is_trim() && rulings.is_some() => {
            return Err(TpiError::TrimUnsupported {
                reason: "the surface is developable (a cylinder, cone or extrusion: its facets are strips along its rulings), and these seeds give no strips (several rulings share one tangent plane)".into(),
            });
        }
        // Saddles and mixed curvature: ghost seeds beyond the boundary (or the trim) close
        // every real facet for the validity flips.
        _ => {
            let extent = plane_extent(&plane_uv, pattern);
            // Closed one way with open sides across it (crate::periodic): the seam closed
            // where the structure folds into an annulus, else left open as on an open patch.
            let seam = layout.open_sides().filter(|_| !boundary.is_trim());
            if seam.is_some() {
                check_seam(&uv, &seeds)?;
                stages.enter(Stage::Neighbours, None);
            }
            let folded = match seam {
                // Triangulation, decision and fold are one step, timed as the neighbours.
                Some(open) => periodic::decide_folded(
                    surface,
                    &periodic::Points {
                        uv: &uv,
                        plane_uv: &plane_uv,
                        geometry: &geometry,
                        convex_side: &convex_side,
                    },
                    extent,
                    open,
                    usize::from(layout.closed[1]),
                    options.envelope_repair,
                )?,
                None => None,
            };
            if let Some((triangulation, points, stats)) = folded {
                // Every open side is a boundary loop; poles are closed over.
                let open = seam.map_or(0, |o| o.iter().filter(|&&o| o).count());
                closed_topology = MeshTopology {
                    euler: 2 - open as i64,
                    boundary_loops: open,
                };
                seam_closed = true;
                // Triangulation, decision and fold are one step here.
                timings.neighbours = ms(stage);
                (triangulation, Some(points), stats)
            } else {
                stages.enter(Stage::Delaunay, None);
                let augmented = if boundary.is_trim() {
                    augment_within_trim(
                        surface,
                        &plane_uv,
                        extent,
                        &geometry,
                        &convex_side,
                        boundary,
                    )
                } else {
                    augment(
                        surface,
                        &uv,
                        &plane_uv,
                        extent,
                        &geometry,
                        &convex_side,
                        [true; 4],
                    )
                };
                let mut triangulation = DualTriangulation::delaunay(&augmented.plane_uv)?;
                timings.delaunay = ms(stage);
                let stage = Instant::now();
                stages.enter(Stage::Neighbours, None);
                let augmented_input = NeighbourInput {
                    plane_uv: &augmented.plane_uv,
                    geometry: &augmented.geometry,
                    planes: &augmented.planes,
                    convex_side: &augmented.convex_side,
                    any_curvature: true,
                };
                let stats = decide(
                    &mut triangulation,
                    &augmented_input,
                    options.envelope_repair,
                    plane_uv.len(),
                );
                timings.neighbours = ms(stage);
                (triangulation, Some(augmented), stats)
            }
        }
    };
    if let Some(k) = (0..2)
        .find(|&k| layout.closed[k])
        .filter(|_| !closed_convex && !strips_closed && !seam_closed)
    {
        diagnostics.push(Diagnostic::SeamLeftOpen { direction: k as u8 });
    }

    // Facets and mesh.
    let stage = Instant::now();
    let params = FacetParams {
        far_vertex_factor: options.far_vertex_factor,
        weld_distance: options.weld_tolerance * diagonal,
        reversal_distance: REVERSAL_CHECK_TOLERANCE * diagonal,
        exact_dual: flat_band.is_some(),
    };
    let mut adjustment = None;
    // The plane adjustment decides planes and flips edges: its time counts as neighbours'.
    let mut adjust_ms = 0.0;
    let (mesh, triangulation) = match &mut augmented {
        None if ghost_dual => {
            let (all_planes, source) = closed_ghosts
                .take()
                .unwrap_or_else(|| (planes.clone(), (0..uv.len() as u32).collect()));
            stages.enter(Stage::Facets, Some(triangulation.len() + uv.len()));
            let mesh = if trimmed {
                build_ghost_clipped_facets(
                    surface,
                    boundary,
                    &uv,
                    &tangents,
                    &all_planes,
                    &source,
                    &triangulation,
                    &params,
                    stages,
                )
            } else {
                build_closed_facets(
                    &triangulation,
                    &all_planes,
                    uv.len(),
                    &source,
                    &params,
                    stages,
                )
            };
            if strip_dual {
                ghost_neighbours = real_pairs(&triangulation, uv.len());
            }
            // The dual structure reported is the real seeds' part.
            let mut real = triangulation;
            if all_planes.len() > uv.len() {
                real.retain_points(uv.len());
                real.canonicalise(uv.len());
            }
            (mesh, real)
        }
        None => {
            stages.enter(Stage::Facets, Some(triangulation.len() + uv.len()));
            let mesh = build_facets(
                surface,
                flat_band.as_ref().unwrap_or(boundary),
                &uv,
                &tangents,
                &planes,
                &convex_side,
                &triangulation,
                &params,
                slopes.as_ref().zip(frame).map(|(slopes, n)| SlopeView {
                    axes: SlopeFrame::new(n, convex_side[0]).axes,
                    slopes,
                }),
                stages,
            );
            (mesh, triangulation)
        }
        Some(augmented) => {
            if options.planes == PlaneMode::Adjusted {
                let adjust = Instant::now();
                let stats = adjust_planes(&mut triangulation, &mut augmented.planes, uv.len());
                adjust_ms = ms(adjust);
                adjustment = Some(stats);
                planes.copy_from_slice(&augmented.planes[..uv.len()]);
            }
            stages.enter(Stage::Facets, Some(triangulation.len() + uv.len()));
            let mesh = build_closed_facets(
                &triangulation,
                &augmented.planes,
                uv.len(),
                &augmented.source,
                &params,
                stages,
            );
            // The dual structure reported is the real seeds' part.
            let mut real = triangulation;
            real.retain_points(uv.len());
            real.canonicalise(uv.len());
            (mesh, real)
        }
    };
    drop(augmented);
    diagnostics.extend(mesh.diagnostics.iter().cloned());
    if !mesh.vertices.is_empty()
        && !strip_dual
        && mesh
            .diagnostics
            .iter()
            .filter(|d| matches!(d, Diagnostic::IllConditionedVertex { .. }))
            .count()
            == triangulation.len()
    {
        // Curved at the seeds, the planes fail to meet because of the pattern (issue 14: four
        // random points nearly on one line on a saddle were said to make it developable).
        let reason = if flat_seeds {
            "every triple of neighbouring tangent planes is (nearly) parallel: the surface is developable".to_string()
        } else {
            format!(
                "every triple of neighbouring tangent planes is (nearly) parallel, though the surface is curved at the pattern points: the {} points are too few or too close to one line for their tangent planes to meet; use more points, spread in both directions",
                uv.len()
            )
        };
        return Err(TpiError::DegenerateSurface { reason });
    }
    timings.facets = ms(stage) - mesh.assembly_ms - adjust_ms;
    timings.neighbours += adjust_ms;
    timings.mesh = mesh.assembly_ms;

    let FacetMesh {
        vertices,
        vertex_kinds,
        offsets,
        loops,
        feet,
        mut triangle_vertices,
        mut vertex_source,
        mut facet_simple,
        welded,
        ..
    } = mesh;
    // What only live editing reads is let go now (the report's peak is the pipeline's).
    if !keep {
        triangle_vertices = Vec::new();
        vertex_source = Vec::new();
        facet_simple = Vec::new();
    }
    let kept_triangulation = keep.then(|| triangulation.clone());
    let dual_triangles = triangulation.triangles;
    drop(triangulation.neighbours);
    let (plane_uv, slopes) = if keep {
        (plane_uv, slopes)
    } else {
        (Vec::new(), None)
    };
    let _ = plane_uv;
    let mut result = Discretisation {
        vertices,
        vertex_kinds,
        facet_offsets: offsets,
        facet_loops: loops,
        seeds,
        pattern_indices: Vec::new(),
        outside_trim: 0,
        dual_triangles,
        ghost_neighbours,
        quality: None,
        facet_flags: Vec::new(),
        diagnostics,
        plane_adjustments: Vec::new(),
        timings,
        units: surface.units(),
        topology: if ghost_dual || seam_closed {
            closed_topology
        } else {
            MeshTopology::DISC
        },
    };
    if let Some(stats) = adjustment {
        neighbours.plane_tilts = stats.tilts;
        neighbours.validity_unresolved = stats.unresolved;
    }
    if options.planes == PlaneMode::Adjusted {
        // Every facet says how its plane differs (0 where it is the exact tangent plane, as
        // everywhere on convex surfaces).
        result.plane_adjustments = plane_adjustments(&result.seeds, &planes);
    }
    let mut resolved = Vec::new();
    let mut feet = feet;
    if options.quality_report {
        let stage = Instant::now();
        stages.enter(
            Stage::Report,
            Some(result.facet_count() + result.vertices.len()),
        );
        let mut diagnosed = vec![false; pattern.len()];
        for d in &result.diagnostics {
            for p in d.points() {
                diagnosed[p as usize] = true;
            }
        }
        if keep {
            resolved = resolve_feet(
                surface,
                &uv,
                &result.vertices,
                &result.facet_offsets,
                &result.facet_loops,
                &feet,
            );
            feet = resolved
                .iter()
                .map(|f| f.map_or(FootHint::FromSeed, FootHint::Known))
                .collect();
        }
        let (quality, flags) = report(
            &ReportInput {
                surface,
                uv: &uv,
                planes: &planes,
                vertices: &result.vertices,
                offsets: &result.facet_offsets,
                loops: &result.facet_loops,
                diagonal,
                diagnosed: &diagnosed,
                neighbours,
                diagnostic_count: result.diagnostics.len(),
                feet: &feet,
                convex_side: &convex_side,
            },
            observer,
        );
        result.quality = Some(quality);
        result.facet_flags = flags;
        note_topology(&mut result, boundary.is_trim());
        result.timings.report = ms(stage);
    }
    stages.leave();
    result.timings.total = ms(start);
    let state = keep.then(|| {
        let (lo, hi) = bounding_box(planes.iter().map(|p| p.point));
        let side = convex_side.first().copied().unwrap_or(0);
        PipelineState {
            uv,
            seeds: result.seeds.clone(),
            tangents,
            planes,
            convex_side,
            slopes: frame
                .zip(slopes)
                .map(|(n, s)| (SlopeFrame::new(n, side), s)),
            triangulation: kept_triangulation.unwrap_or_default(),
            triangle_vertices,
            vertex_source,
            facet_simple,
            feet: resolved,
            neighbours,
            welded,
            diagonal,
            bbox: (lo, hi),
        }
    });
    Ok((result, state))
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
fn check_not_collinear(points: &[[f64; 2]]) -> Result<(), TpiError> {
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

fn ms(since: Instant) -> f64 {
    since.elapsed().as_secs_f64() * 1e3
}

/// The size of the triangulation plane's rectangle: the scale factors that
/// [`scaled_parameters`] applied to the normalised pattern coordinates.
fn plane_extent(plane_uv: &[[f64; 2]], pattern: &[[f64; 2]]) -> [f64; 2] {
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

/// The edges of `tri` between two real points (`< real_count`), as sorted pairs i < j
/// (every edge where all points are real).
fn real_pairs(tri: &DualTriangulation, real_count: usize) -> Vec<[u32; 2]> {
    sorted_pairs(
        triangle_edges(&tri.triangles)
            .filter(|&[a, b]| (a as usize) < real_count && (b as usize) < real_count),
    )
}

/// No seed on a pole (its tangent plane is not defined by the parametrisation); on a closed
/// surface about to be discretised as one (`closing`: convex, untrimmed) also no seed where
/// the surface is singular and no two seeds on one surface point (across the seam).
fn check_closed_seeds(
    surface: &dyn Surface,
    layout: &closed::SurfaceLayout,
    uv: &[[f64; 2]],
    seeds: &[Seed],
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
    let mut order: Vec<usize> = (0..seeds.len()).collect();
    let key = |i: usize| seeds[i].point.to_array();
    order.sort_unstable_by(|&a, &b| {
        key(a)
            .partial_cmp(&key(b))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if seeds[j].point.x - seeds[i].point.x > tolerance {
                break;
            }
            if seeds[i].point.distance(seeds[j].point) <= tolerance {
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
