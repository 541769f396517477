//! Discretisation results: the mesh, the adjacency, the quality report, the diagnostics.

use std::ffi::{c_char, c_void};
use std::mem::size_of;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use tpi_core::{
    discretise, discretise_with_progress, Diagnostic, Discretisation, Progress, QualityReport,
    Stage,
};

use crate::boundary::{
    check_copy_out, copy_out, copy_out_str, ffi_boundary, flag, try_handle, FfiError, FfiResult,
    OutPtr, TpiStatus,
};
use crate::options::{read_options, TpiOptions};
use crate::pattern::TpiPattern;
use crate::surface::TpiSurface;

/// Per-facet flag: the facet is not convex where the envelope of tangent planes makes facets
/// convex (its seed and the seeds of the facets sharing an edge with it strictly convex, K > 0,
/// on one side, and none of their planes adjusted); on saddle-shaped regions, next to
/// parabolic lines and beside adjusted planes non-convex facets are expected and not flagged.
pub const TPI_FACET_NON_CONVEX: u8 = 1;
/// Per-facet flag: the facet is not a simple polygon (self-intersecting, clockwise seen from
/// its normal, or degenerate). Invalid.
pub const TPI_FACET_NON_SIMPLE: u8 = 2;
/// Per-facet flag: the facet overlaps a facet it shares a vertex with, seen along their mean
/// normal. Invalid.
pub const TPI_FACET_OVERLAP: u8 = 4;
/// Per-facet flag: a diagnostic names this facet's pattern point.
pub const TPI_FACET_DIAGNOSTIC: u8 = 8;
/// Per-facet flag: fewer than three distinct vertices. Invalid.
pub const TPI_FACET_OPEN: u8 = 16;
/// Per-facet flag: a vertex of the facet stands farther from the surface than 3 times the
/// facet's local spacing (the mean distance from its seed to the seeds of the facets it
/// shares an edge with): exact tangent planes nearly parallel (at a parabolic line, or at
/// seeds close together) met far from it. Not invalid by itself.
pub const TPI_FACET_FAR_VERTEX: u8 = 32;

/// The `point` of a diagnostic entry that concerns no single pattern point (a domain corner
/// claimed by no facet or by several).
pub const TPI_NO_POINT: u32 = 0xFFFF_FFFF;

/// Size in bytes of the first version of `TpiQualityReport`: the smallest `struct_size`
/// accepted.
pub const TPI_QUALITY_REPORT_SIZE_V1: u32 = 200;

/// Size in bytes of the second version of `TpiQualityReport` (V1 plus `invalid_facets`,
/// `open_facets`, `validity_flips` and `validity_unresolved`).
pub const TPI_QUALITY_REPORT_SIZE_V2: u32 = 232;

/// Size in bytes of the third version of `TpiQualityReport` (V2 plus `far_vertex_facets` and
/// `max_deviation_spacings`).
pub const TPI_QUALITY_REPORT_SIZE_V3: u32 = 248;

/// The result of a discretisation: an indexed polygon mesh with one planar facet per pattern
/// point (facet i belongs to pattern point i), the dual triangulation, the quality report and
/// the diagnostics. Immutable.
///
/// Created by `tpi_discretise` or `tpi_discrete_surface_mesh`, freed by
/// `tpi_discretisation_free`. May be used from several threads at once.
pub struct TpiDiscretisation {
    result: Arc<Discretisation>,
    pairs: OnceLock<Vec<u32>>,
    entries: OnceLock<Vec<TpiDiagnosticEntry>>,
    json: OnceLock<String>,
    json_with_timings: OnceLock<String>,
    quality_json: OnceLock<String>,
    diagnostics_json: OnceLock<String>,
}

impl crate::boundary::Handle for TpiDiscretisation {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:disc");
    const C_NAME: &'static str = "TpiDiscretisation";
}

impl TpiDiscretisation {
    /// The core's result (for the fabrication entry points).
    pub(crate) fn result(&self) -> &Discretisation {
        &self.result
    }

    pub(crate) fn new(result: Arc<Discretisation>) -> Self {
        Self {
            result,
            pairs: OnceLock::new(),
            entries: OnceLock::new(),
            json: OnceLock::new(),
            json_with_timings: OnceLock::new(),
            quality_json: OnceLock::new(),
            diagnostics_json: OnceLock::new(),
        }
    }

    fn pairs(&self) -> &[u32] {
        self.pairs
            .get_or_init(|| self.result.neighbour_pairs().as_flattened().to_vec())
    }

    fn entries(&self) -> &[TpiDiagnosticEntry] {
        self.entries.get_or_init(|| {
            let mut entries = Vec::new();
            for (index, d) in self.result.diagnostics.iter().enumerate() {
                let kind = TpiDiagnosticKind::of(d) as u32;
                let diagnostic = u32::try_from(index).unwrap_or(u32::MAX);
                let points = d.points();
                if points.is_empty() {
                    entries.push(TpiDiagnosticEntry {
                        point: TPI_NO_POINT,
                        kind,
                        diagnostic,
                    });
                }
                entries.extend(points.into_iter().map(|point| TpiDiagnosticEntry {
                    point,
                    kind,
                    diagnostic,
                }));
            }
            entries
        })
    }

    fn quality(&self) -> FfiResult<&QualityReport> {
        self.result.quality.as_ref().ok_or_else(|| {
            FfiError::new(
                TpiStatus::Unavailable,
                "the quality report was switched off (options.quality_report = 0)",
            )
        })
    }
}

fn json_error(e: serde_json::Error) -> FfiError {
    FfiError::new(
        TpiStatus::Panic,
        format!("internal error: JSON serialisation failed: {e}"),
    )
}

/// Gets or fills a cached string.
fn cached(cell: &OnceLock<String>, make: impl FnOnce() -> FfiResult<String>) -> FfiResult<&str> {
    if let Some(text) = cell.get() {
        return Ok(text);
    }
    let text = make()?;
    Ok(cell.get_or_init(|| text))
}

/// The pattern point behind a facet: its parameters in the surface's own domain, surface
/// point, unit normal (Su x Sv) and principal curvatures k1 <= k2.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TpiSeed {
    /// (u, v) in the surface's domain.
    pub uv: [f64; 2],
    /// Surface point.
    pub point: [f64; 3],
    /// Unit normal.
    pub normal: [f64; 3],
    /// Principal curvatures k1 <= k2 (signed relative to the normal).
    pub curvatures: [f64; 2],
}

/// A facet's plane: the plane through `point` with unit normal `normal`. Every vertex of the
/// facet lies in it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TpiPlane {
    /// A point of the plane (the seed's surface point, unless the adjusted plane is offset).
    pub point: [f64; 3],
    /// Unit normal (the surface normal at the seed, unless the plane is adjusted).
    pub normal: [f64; 3],
}

/// What a diagnostic is about. The numbers are never changed nor reused.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TpiDiagnosticKind {
    /// Three tangent planes are nearly parallel: their meeting point ran away and a stand-in
    /// was used, so the facets of the three points are not exact.
    IllConditionedVertex = 1,
    /// Two neighbouring tangent planes at the boundary are parallel.
    ParallelPlanes = 2,
    /// The common edge of two facets never reaches the surface's boundary.
    BoundaryNotReached = 3,
    /// A facet could not be closed consistently along the boundary.
    OpenFacet = 4,
    /// The tangent plane of a facet holding a domain corner is parallel to the corner's normal.
    CornerUnreachable = 5,
    /// A domain corner was claimed by no facet or by several (point is TPI_NO_POINT).
    CornerClaims = 6,
    /// The point has (nearly) zero Gaussian curvature.
    FlatPoint = 7,
    /// Neighbouring facets with coincident tangent planes (flat or developable) were separated
    /// by the bisector of their seeds (point is TPI_NO_POINT).
    CoincidentPlanes = 8,
    /// The surface is closed in a direction but was discretised as an open patch: its seam
    /// stays open (point is TPI_NO_POINT).
    SeamLeftOpen = 9,
    /// The mesh's Euler characteristic or boundary loops are not those expected (a gap or a
    /// double cover between facets; point is TPI_NO_POINT).
    UnexpectedTopology = 10,
    /// The surface is developable with its rulings along parameter lines (a cylinder, a cone,
    /// an extrusion): its facets are strips between the lines where the tangent planes of
    /// neighbouring rulings meet (point is TPI_NO_POINT).
    RulingStrips = 11,
    /// The boundary or trim cuts the point's facet into several parts: it keeps the part
    /// around its seed, the others are left out as gaps beside the boundary.
    FacetPartsLeftOut = 12,
}

impl TpiDiagnosticKind {
    /// The kind of a core diagnostic.
    pub fn of(d: &Diagnostic) -> Self {
        match d {
            Diagnostic::IllConditionedVertex { .. } => TpiDiagnosticKind::IllConditionedVertex,
            Diagnostic::ParallelPlanes { .. } => TpiDiagnosticKind::ParallelPlanes,
            Diagnostic::BoundaryNotReached { .. } => TpiDiagnosticKind::BoundaryNotReached,
            Diagnostic::OpenFacet { .. } => TpiDiagnosticKind::OpenFacet,
            Diagnostic::CornerUnreachable { .. } => TpiDiagnosticKind::CornerUnreachable,
            Diagnostic::CornerClaims { .. } => TpiDiagnosticKind::CornerClaims,
            Diagnostic::FlatPoint { .. } => TpiDiagnosticKind::FlatPoint,
            Diagnostic::CoincidentPlanes { .. } => TpiDiagnosticKind::CoincidentPlanes,
            Diagnostic::SeamLeftOpen { .. } => TpiDiagnosticKind::SeamLeftOpen,
            Diagnostic::UnexpectedTopology { .. } => TpiDiagnosticKind::UnexpectedTopology,
            Diagnostic::RulingStrips { .. } => TpiDiagnosticKind::RulingStrips,
            Diagnostic::FacetPartsLeftOut { .. } => TpiDiagnosticKind::FacetPartsLeftOut,
        }
    }
}

/// One (pattern point, diagnostic) pair: a diagnostic naming three points gives three
/// entries, one naming none gives one entry with `point` = TPI_NO_POINT.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TpiDiagnosticEntry {
    /// The pattern point (= facet) index, or TPI_NO_POINT.
    pub point: u32,
    /// A TpiDiagnosticKind value.
    pub kind: u32,
    /// Index of the diagnostic in the array of `tpi_discretisation_diagnostics_json`.
    pub diagnostic: u32,
}

/// The quality report as numbers; `tpi_discretisation_quality_json` has the same and the
/// histogram of facet sizes.
///
/// Growth: fields are only ever appended; set `struct_size` to sizeof(TpiQualityReport)
/// before the call, and the library writes only that many bytes (and stores in
/// `struct_size` how many it filled in).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TpiQualityReport {
    /// sizeof(TpiQualityReport) as compiled by the caller; at least
    /// TPI_QUALITY_REPORT_SIZE_V1.
    pub struct_size: u32,
    /// 1 if every vertex coordinate is finite.
    pub all_finite: u32,
    /// Number of facets (= pattern points).
    pub facet_count: u64,
    /// Number of mesh vertices.
    pub vertex_count: u64,
    /// Number of mesh edges.
    pub edge_count: u64,
    /// Vertices not on the boundary.
    pub interior_vertex_count: u64,
    /// Fraction of interior vertices where exactly three facets meet.
    pub trivalent_fraction: f64,
    /// Largest distance of a facet vertex from its facet's tangent plane, relative to the
    /// bounding-box diagonal (0 up to rounding).
    pub max_planarity_error: f64,
    /// Largest distance of a mesh vertex from the surface (model units).
    pub max_deviation: f64,
    /// Mean distance of mesh vertices from the surface (model units).
    pub mean_deviation: f64,
    /// Facets that are not convex.
    pub non_convex_facets: u64,
    /// Facets that are not simple polygons.
    pub non_simple_facets: u64,
    /// Pairs of neighbouring facets that overlap.
    pub overlapping_pairs: u64,
    /// Facets with any flag.
    pub flagged_facets: u64,
    /// V - E + F (1 for a disc).
    pub euler_characteristic: i64,
    /// Number of boundary loops (1 for a disc).
    pub boundary_loops: u64,
    /// Edges shared by more than two facets.
    pub non_manifold_edges: u64,
    /// Smallest facet area.
    pub min_facet_area: f64,
    /// Largest facet area.
    pub max_facet_area: f64,
    /// Shortest mesh edge.
    pub min_edge_length: f64,
    /// Longest mesh edge.
    pub max_edge_length: f64,
    /// Bounding-box diagonal used for relative measures.
    pub bounding_box_diagonal: f64,
    /// Flips made by the curvature-compensated in-circle test.
    pub compensation_flips: u64,
    /// Flips made by the envelope repair.
    pub envelope_repairs: u64,
    /// Edges the envelope rejects that could not be flipped.
    pub envelope_unresolved: u64,
    /// Number of diagnostics.
    pub diagnostic_count: u64,
    /// Open, non-simple or overlapping facets (each once): 0 for a valid mesh. Since V2.
    pub invalid_facets: u64,
    /// Facets with fewer than three distinct vertices. Since V2.
    pub open_facets: u64,
    /// Flips kept by the validity repair (saddles, mixed curvature). Since V2.
    pub validity_flips: u64,
    /// Facets the validity repair could not make valid. Since V2.
    pub validity_unresolved: u64,
    /// Facets with a vertex farther from the surface than 3 local spacings
    /// (`TPI_FACET_FAR_VERTEX`). Since V3.
    pub far_vertex_facets: u64,
    /// The largest, over the facets, of the deviation of a facet's farthest vertex over the
    /// facet's local spacing: below 1 on a mesh that hugs its surface. Since V3.
    pub max_deviation_spacings: f64,
}

impl TpiQualityReport {
    fn from_core(q: &QualityReport) -> Self {
        let n = |x: usize| x as u64;
        Self {
            struct_size: size_of::<TpiQualityReport>() as u32,
            all_finite: u32::from(q.all_finite),
            facet_count: n(q.facet_count),
            vertex_count: n(q.vertex_count),
            edge_count: n(q.edge_count),
            interior_vertex_count: n(q.interior_vertex_count),
            trivalent_fraction: q.trivalent_fraction,
            max_planarity_error: q.max_planarity_error,
            max_deviation: q.max_deviation,
            mean_deviation: q.mean_deviation,
            non_convex_facets: n(q.non_convex_facets),
            non_simple_facets: n(q.non_simple_facets),
            overlapping_pairs: n(q.overlapping_pairs),
            flagged_facets: n(q.flagged_facets),
            euler_characteristic: q.euler_characteristic,
            boundary_loops: n(q.boundary_loops),
            non_manifold_edges: n(q.non_manifold_edges),
            min_facet_area: q.min_facet_area,
            max_facet_area: q.max_facet_area,
            min_edge_length: q.min_edge_length,
            max_edge_length: q.max_edge_length,
            bounding_box_diagonal: q.bounding_box_diagonal,
            compensation_flips: n(q.neighbours.compensation_flips),
            envelope_repairs: n(q.neighbours.envelope_repairs),
            envelope_unresolved: n(q.neighbours.envelope_unresolved),
            diagnostic_count: n(q.diagnostic_count),
            invalid_facets: n(q.invalid_facets),
            open_facets: n(q.open_facets),
            validity_flips: n(q.neighbours.validity_flips),
            validity_unresolved: n(q.neighbours.validity_unresolved),
            far_vertex_facets: n(q.far_vertex_facets),
            max_deviation_spacings: q.max_deviation_spacings,
        }
    }
}

/// A handle argument.
///
/// # Safety
/// `ptr` is NULL or a live handle.
unsafe fn handle<'a>(ptr: *const TpiDiscretisation) -> FfiResult<&'a TpiDiscretisation> {
    // SAFETY: forwarded contract.
    unsafe { try_handle(ptr, "discretisation") }
}

/// Copy-out of `len` elements made by `make`, which only runs when the buffer is big enough.
///
/// # Safety
/// As [`copy_out`].
unsafe fn copy_out_lazy<T: Copy>(
    len: usize,
    make: impl FnOnce() -> Vec<T>,
    out: *mut T,
    capacity: usize,
    needed: *mut usize,
) -> FfiResult {
    // SAFETY: forwarded contract.
    unsafe { check_copy_out(len, out, capacity, needed, "out") }?;
    // SAFETY: forwarded contract.
    unsafe { copy_out(&make(), out, capacity, needed, "out") }
}

/// Discretises `surface` with `pattern`: one planar facet per pattern point.
///
/// `options` may be NULL for the defaults. The surface and the pattern are only read; the
/// result does not refer to them, so they may be freed afterwards.
///
/// On success `*out` is a new handle (free with `tpi_discretisation_free`), else NULL.
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (bad options),
/// TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_PATTERN (fewer than three points, duplicates,
/// all collinear), TPI_STATUS_DEGENERATE (a flat or developable surface).
///
/// # Safety
/// `surface` and `pattern` are NULL or live handles; `options` is NULL or a `TpiOptions`
/// with `struct_size` readable bytes; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretise(
    surface: *const TpiSurface,
    pattern: *const TpiPattern,
    options: *const TpiOptions,
    out: *mut *mut TpiDiscretisation,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let pattern = unsafe { try_handle(pattern, "pattern") }?;
        let options = unsafe { read_options(options) }?;
        let result = discretise(&surface.model, &pattern.pattern.uv, &options)?;
        out.set_boxed(TpiDiscretisation::new(Arc::new(result)));
        Ok(())
    }
}

/// Stage of a discretisation reported to a `TpiProgressCallback`: evaluation and curvature at
/// every pattern point.
pub const TPI_STAGE_SAMPLES: u32 = 0;
/// Stage: the candidate triangulation (Delaunay, the hull of a closed convex surface, strips).
pub const TPI_STAGE_DELAUNAY: u32 = 1;
/// Stage: the neighbour decision (flips, envelope repair, plane adjustment).
pub const TPI_STAGE_NEIGHBOURS: u32 = 2;
/// Stage: facet vertices and loops.
pub const TPI_STAGE_FACETS: u32 = 3;
/// Stage: mesh assembly (welding, vertex numbering).
pub const TPI_STAGE_MESH: u32 = 4;
/// Stage: the quality report.
pub const TPI_STAGE_REPORT: u32 = 5;

/// A progress callback for `tpi_discretise_with_progress`: `stage` is a TPI_STAGE_* number,
/// `done` the work items of that stage done so far, `total` its number of items (0 when the
/// stage cannot know it beforehand: then `done` stays 0). Returns 0 to go on, anything else to
/// cancel the call.
///
/// It is called when a stage starts (`done` 0), as its items get done where the calling
/// thread does them (at most about once per percent of `total`; the items the library's
/// worker threads do are only seen in the next call), and when it ends (`done` == `total`).
/// Calls come only from the thread that called `tpi_discretise_with_progress` (a runtime
/// such as Mono waits at exit for every foreign thread that ever called into it); the
/// callback must return quickly, must not unwind (no C++ exception, no .NET exception
/// crossing it), and must not call the library.
pub type TpiProgressCallback =
    Option<unsafe extern "C" fn(user_data: *mut c_void, stage: u32, done: u64, total: u64) -> i32>;

/// The TPI_STAGE_* number of a stage.
fn stage_number(stage: Stage) -> u32 {
    match stage {
        Stage::Samples => TPI_STAGE_SAMPLES,
        Stage::Delaunay => TPI_STAGE_DELAUNAY,
        Stage::Neighbours => TPI_STAGE_NEIGHBOURS,
        Stage::Facets => TPI_STAGE_FACETS,
        Stage::Mesh => TPI_STAGE_MESH,
        // Stage is non-exhaustive; a later stage counts as the report's (the last).
        _ => TPI_STAGE_REPORT,
    }
}

/// The current stage as the callback last heard of it.
struct Reported {
    stage: u32,
    total: u64,
    /// `done` at the last call.
    sent: u64,
}

/// The core's progress observer calling a C callback: one call at a time (under `reported`),
/// the workers' counts summed in `done`; a nonzero return sets `cancel`, which the core asks
/// between stages.
pub(crate) struct CallbackObserver {
    callback: unsafe extern "C" fn(*mut c_void, u32, u64, u64) -> i32,
    user_data: *mut c_void,
    reported: Mutex<Reported>,
    done: AtomicU64,
    cancel: AtomicBool,
    /// The thread that called `tpi_discretise_with_progress`: the only one that calls back.
    caller: std::thread::ThreadId,
}

// SAFETY: `user_data` is only handed back to the callback, never dereferenced here, and the
// callback is only called on the thread that passed them (checked against `caller`).
unsafe impl Sync for CallbackObserver {}

impl CallbackObserver {
    /// The observer of a call made on this thread (the only one that will call back).
    pub(crate) fn new(
        callback: unsafe extern "C" fn(*mut c_void, u32, u64, u64) -> i32,
        user_data: *mut c_void,
    ) -> Self {
        CallbackObserver {
            callback,
            user_data,
            reported: Mutex::new(Reported {
                stage: TPI_STAGE_SAMPLES,
                total: 0,
                sent: 0,
            }),
            done: AtomicU64::new(0),
            cancel: AtomicBool::new(false),
            caller: std::thread::current().id(),
        }
    }

    /// Calls the callback (the caller holds `reported`).
    fn call(&self, reported: &mut Reported, done: u64) {
        reported.sent = done;
        // SAFETY: the caller's contract for `callback` and `user_data`
        // (tpi_discretise_with_progress).
        let answer =
            unsafe { (self.callback)(self.user_data, reported.stage, done, reported.total) };
        if answer != 0 {
            self.cancel.store(true, Ordering::SeqCst);
        }
    }
}

impl Progress for CallbackObserver {
    fn stage_started(&self, stage: Stage, total: Option<usize>) {
        if let Ok(mut reported) = self.reported.lock() {
            reported.stage = stage_number(stage);
            reported.total = total.map_or(0, |t| t as u64);
            self.done.store(0, Ordering::SeqCst);
            if std::thread::current().id() == self.caller {
                self.call(&mut reported, 0);
            }
        }
    }

    fn advanced(&self, _stage: Stage, items: usize) {
        let done = self.done.fetch_add(items as u64, Ordering::SeqCst) + items as u64;
        // Only the calling thread calls back: a host runtime (Mono) that attaches a foreign
        // worker thread on its first callback waits for it at exit, and the workers never end.
        if std::thread::current().id() != self.caller {
            return;
        }
        if let Ok(mut reported) = self.reported.try_lock() {
            let step = (reported.total / 100).max(1);
            if reported.total > 0 && done.saturating_sub(reported.sent) >= step {
                let done = done.min(reported.total);
                self.call(&mut reported, done);
            }
        }
    }

    fn stage_finished(&self, _stage: Stage) {
        if let Ok(mut reported) = self.reported.lock() {
            let done = self.done.load(Ordering::SeqCst).min(reported.total);
            if std::thread::current().id() == self.caller {
                self.call(&mut reported, done);
            }
        }
    }

    fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }
}

/// `tpi_discretise`, reporting progress to `callback` (see `TpiProgressCallback`), which can
/// cancel it by returning nonzero.
///
/// `callback` may be NULL (no reports, no cancelling: the same as `tpi_discretise`);
/// `user_data` is handed to every call of `callback` and never read by the library. The
/// result is the same as `tpi_discretise`'s. Once the callback has returned nonzero, the call
/// stops where the running stage ends (the facets and the mesh assembly count as one; every
/// stage is under a second at a million points on two cores) and returns
/// TPI_STATUS_CANCELLED with `*out` NULL and nothing created; the last error message names
/// the stage it stopped in.
///
/// Errors: those of `tpi_discretise`, and TPI_STATUS_CANCELLED.
///
/// # Safety
/// As `tpi_discretise`; `callback` is NULL or a function that may be called with `user_data`
/// on the calling thread until this call returns.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretise_with_progress(
    surface: *const TpiSurface,
    pattern: *const TpiPattern,
    options: *const TpiOptions,
    callback: TpiProgressCallback,
    user_data: *mut c_void,
    out: *mut *mut TpiDiscretisation,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let pattern = unsafe { try_handle(pattern, "pattern") }?;
        let options = unsafe { read_options(options) }?;
        let result = match callback {
            None => discretise(&surface.model, &pattern.pattern.uv, &options)?,
            Some(callback) => {
                let observer = CallbackObserver::new(callback, user_data);
                discretise_with_progress(&surface.model, &pattern.pattern.uv, &options, &observer)?
            }
        };
        out.set_boxed(TpiDiscretisation::new(Arc::new(result)));
        Ok(())
    }
}

/// Frees a discretisation. NULL is allowed and does nothing.
///
/// # Safety
/// `discretisation` is NULL or a handle that was not freed yet, and no other call is using
/// it.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_free(discretisation: *mut TpiDiscretisation) {
    crate::boundary::run_infallible((), || {
        // SAFETY: the caller hands back ownership of a handle from this library.
        unsafe { crate::boundary::free_handle(discretisation) }
    })
}

/// Stores the number of facets (= pattern points) in `*out`.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_facet_count(
    discretisation: *const TpiDiscretisation,
    out: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { OutPtr::new(out, "out") }?.set(d.result.facet_count());
        Ok(())
    }
}

/// Stores the number of mesh vertices in `*out`.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_vertex_count(
    discretisation: *const TpiDiscretisation,
    out: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { OutPtr::new(out, "out") }?.set(d.result.vertices.len());
        Ok(())
    }
}

/// Copies the vertex coordinates x0, y0, z0, x1, ... (3 doubles per vertex). Copy-out
/// convention; `*needed` = 3 * vertex count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// doubles; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_vertices(
    discretisation: *const TpiDiscretisation,
    out: *mut f64,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let v = &d.result.vertices;
        unsafe { copy_out_lazy(3 * v.len(), || v.iter().flat_map(|p| p.to_array()).collect(), out, capacity, needed) }
    }
}

/// Copies the number of vertices of each facet (one uint32_t per facet, in facet order).
/// Copy-out convention; `*needed` = facet count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_facet_sizes(
    discretisation: *const TpiDiscretisation,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let offsets = &d.result.facet_offsets;
        let sizes = || offsets.windows(2).map(|w| match w { [a, b] => b.saturating_sub(*a), _ => 0 }).collect();
        unsafe { copy_out_lazy(d.result.facet_count(), sizes, out, capacity, needed) }
    }
}

/// Copies the facets' vertex indices, facet after facet, each loop counter-clockwise seen
/// from the facet's normal; facet i's loop starts after the sizes of facets 0..i-1.
/// Copy-out convention; `*needed` = sum of the facet sizes.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_facet_indices(
    discretisation: *const TpiDiscretisation,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { copy_out(&d.result.facet_loops, out, capacity, needed, "out") }
    }
}

/// Copies the per-facet flags (TPI_FACET_* bits; one uint8_t per facet). Copy-out
/// convention; `*needed` = facet count, or 0 when the quality report was switched off.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint8_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_facet_flags(
    discretisation: *const TpiDiscretisation,
    out: *mut u8,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { copy_out(&d.result.facet_flags, out, capacity, needed, "out") }
    }
}

/// Copies the seed of each facet (one TpiSeed per facet; facet i belongs to pattern point
/// i). Copy-out convention; `*needed` = facet count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// TpiSeed; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_seeds(
    discretisation: *const TpiDiscretisation,
    out: *mut TpiSeed,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let seeds = &d.result.seeds;
        let make = || {
            seeds
                .iter()
                .map(|s| TpiSeed { uv: s.uv, point: s.point.to_array(), normal: s.normal.to_array(), curvatures: s.curvatures })
                .collect()
        };
        unsafe { copy_out_lazy(seeds.len(), make, out, capacity, needed) }
    }
}

/// Copies the plane of each facet (one TpiPlane per facet): the tangent plane at its seed,
/// or with `plane_mode` TPI_PLANES_ADJUSTED the facet's adjusted plane (its tilt is the angle
/// between its normal and the seed's, from `tpi_discretisation_seeds`). Copy-out convention;
/// `*needed` = facet count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// TpiPlane; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_planes(
    discretisation: *const TpiDiscretisation,
    out: *mut TpiPlane,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let result = &d.result;
        let make = || {
            (0..result.facet_count())
                .map(|i| {
                    let (point, normal) = result.facet_plane(i);
                    TpiPlane { point: point.to_array(), normal: normal.to_array() }
                })
                .collect()
        };
        unsafe { copy_out_lazy(result.facet_count(), make, out, capacity, needed) }
    }
}

/// Copies the neighbour pairs of the final dual structure: i0, j0, i1, j1, ... (2 uint32_t
/// per pair, i < j, sorted). Two facets are neighbours when they share an edge. Copy-out
/// convention; `*needed` = 2 * pair count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_neighbour_pairs(
    discretisation: *const TpiDiscretisation,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { copy_out(d.pairs(), out, capacity, needed, "out") }
    }
}

/// Copies the triangles of the final dual structure (3 uint32_t pattern point indices per
/// triangle, counter-clockwise in parameter space); each triangle is one interior mesh
/// vertex, where its three tangent planes meet. Copy-out convention; `*needed` =
/// 3 * triangle count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_dual_triangles(
    discretisation: *const TpiDiscretisation,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { copy_out(d.result.dual_triangles.as_flattened(), out, capacity, needed, "out") }
    }
}

/// Fills `*out` with the quality report. Set `out->struct_size` = sizeof(TpiQualityReport)
/// first; only that many bytes are written, and on return `struct_size` holds the number of
/// bytes filled in (smaller than the caller's size when the library is older than the
/// caller's header).
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`struct_size` below
/// TPI_QUALITY_REPORT_SIZE_V1), TPI_STATUS_UNAVAILABLE (the report was switched off).
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for reading and writing
/// `out->struct_size` bytes.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_quality(
    discretisation: *const TpiDiscretisation,
    out: *mut TpiQualityReport,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let out = unsafe { OutPtr::new(out, "out") }?;
        // SAFETY: checked non-NULL and aligned; struct_size is the first field.
        let size = unsafe { out.as_ptr().cast::<u32>().read() };
        if size < TPI_QUALITY_REPORT_SIZE_V1 {
            return Err(FfiError::invalid(format!(
                "out->struct_size is {size}; set it to sizeof(TpiQualityReport) (at least {TPI_QUALITY_REPORT_SIZE_V1})"
            )));
        }
        let mut report = TpiQualityReport::from_core(d.quality()?);
        let bytes = (size as usize).min(size_of::<TpiQualityReport>());
        // Tells a caller built against a newer header how much was filled in.
        report.struct_size = bytes as u32;
        // SAFETY: `bytes` bytes are writable (contract) and readable from `report`.
        unsafe { std::ptr::copy_nonoverlapping((&report as *const TpiQualityReport).cast::<u8>(), out.as_ptr().cast::<u8>(), bytes) };
        Ok(())
    }
}

/// Copies the quality report as JSON text (an object with the fields of TpiQualityReport,
/// `neighbours` nested, and `side_histogram`: facet count per number of sides), NUL
/// terminated. Copy-out convention; `*needed` counts the NUL.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL, TPI_STATUS_UNAVAILABLE.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// chars; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_quality_json(
    discretisation: *const TpiDiscretisation,
    out: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let quality = d.quality()?;
        let text = cached(&d.quality_json, || serde_json::to_string(quality).map_err(json_error))?;
        unsafe { copy_out_str(text, out, capacity, needed, "out") }
    }
}

/// Stores the number of diagnostics (local problems, each naming its pattern points) in
/// `*out`; the entries of `tpi_discretisation_diagnostic_entries` may be more.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_diagnostic_count(
    discretisation: *const TpiDiscretisation,
    out: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { OutPtr::new(out, "out") }?.set(d.result.diagnostics.len());
        Ok(())
    }
}

/// Copies the per-point diagnostics as (point, kind, diagnostic) entries, in diagnostic
/// order. Copy-out convention; `*needed` = number of entries.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// entries; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_diagnostic_entries(
    discretisation: *const TpiDiscretisation,
    out: *mut TpiDiagnosticEntry,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        unsafe { copy_out(d.entries(), out, capacity, needed, "out") }
    }
}

/// Copies the diagnostics as a JSON array, NUL terminated: each element has a `kind`
/// (snake_case of the TpiDiagnosticKind name, e.g. "flat_point") and its fields (`point` or
/// `points`, and numbers such as `gaussian_curvature`). Copy-out convention; `*needed`
/// counts the NUL.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// chars; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_diagnostics_json(
    discretisation: *const TpiDiscretisation,
    out: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let text = cached(&d.diagnostics_json, || serde_json::to_string(&d.result.diagnostics).map_err(json_error))?;
        unsafe { copy_out_str(text, out, capacity, needed, "out") }
    }
}

/// Copies the whole result as JSON text in the project's output contract (the command
/// line's output: vertices, facets with seed, uv, point, normal, vertices and flags,
/// dual_triangles, quality, diagnostics), NUL terminated. `include_timings` 1 adds
/// `timings_ms` (which differ between runs); 0 leaves it out. Copy-out convention;
/// `*needed` counts the NUL.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`include_timings` not 0 or
/// 1), TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// chars; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discretisation_json(
    discretisation: *const TpiDiscretisation,
    include_timings: u32,
    out: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let d = unsafe { handle(discretisation) }?;
        let timings = flag("include_timings", include_timings)?;
        let cell = if timings { &d.json_with_timings } else { &d.json };
        let text = cached(cell, || Ok(d.result.to_json(timings)))?;
        unsafe { copy_out_str(text, out, capacity, needed, "out") }
    }
}
