//! The discrete surface: the live object a host keeps, holding a surface, its pattern points
//! and its current mesh.
//!
//! Edits (move, add, remove a point; replace the surface) only change the inputs and count
//! as pending; `tpi_discrete_surface_recompute` brings the mesh up to date. One pending point
//! edit is applied by the core's live editing (`tpi_core::LiveSurface`), which updates only
//! the dual structure and facets around the point where it can (a convex surface away from
//! the boundary) and runs the whole pipeline elsewhere; a batch of several pending edits is
//! discretised from scratch. Either way the mesh is exactly that of a discretisation of the
//! edited inputs from scratch. The mesh is assembled when it is asked for
//! (`tpi_discrete_surface_mesh`) after a recompute.
//!
//! A host that redraws after every edit takes only what changed instead
//! (`tpi_discrete_surface_changes`, a `TpiMeshChanges` snapshot of
//! `tpi_core::LiveChanges`): the changed facets with their loops and planes, and the vertices
//! whose positions are new, in the live structure's own vertex numbering.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use tpi_core::Pattern;
use tpi_core::SurfaceModel;
use tpi_core::{Discretisation, DiscretiseOptions, LiveChanges, LiveSurface, TpiError};

use crate::boundary::{
    copy_out, ffi_boundary, finite, index_error, try_handle, FfiResult, OutPtr, TpiStatus,
};
use crate::discretisation::{TpiDiscretisation, TpiPlane};
use crate::options::{read_options, TpiOptions};
use crate::pattern::TpiPattern;
use crate::surface::TpiSurface;

/// A live discrete surface: a surface, its pattern points (normalised, in [0, 1]^2) and the
/// mesh of the last successful recompute.
///
/// Created by `tpi_discrete_surface_new`, freed by `tpi_discrete_surface_free`. May be used
/// from several threads at once: calls on one discrete surface are serialised by a lock
/// inside it (a recompute blocks the other calls on the same object until it is done).
pub struct TpiDiscreteSurface {
    state: Mutex<State>,
}

impl crate::boundary::Handle for TpiDiscreteSurface {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:live");
    const C_NAME: &'static str = "TpiDiscreteSurface";
}

struct State {
    /// The inputs with every edit applied (pending ones included).
    surface: SurfaceModel,
    points: Vec<[f64; 2]>,
    options: DiscretiseOptions,
    /// The live surface of the last successful recompute.
    live: LiveSurface,
    /// Its mesh, once assembled (None: assemble from `live` when asked for).
    mesh: Option<Arc<Discretisation>>,
    /// Edits since the last successful recompute, in order.
    pending: Vec<Edit>,
}

/// One pending edit.
enum Edit {
    Move(usize, [f64; 2]),
    Add([f64; 2]),
    Remove(usize),
    Surface,
}

impl State {
    /// The current mesh, assembled if needed.
    fn mesh(&mut self) -> Arc<Discretisation> {
        let live = &mut self.live;
        Arc::clone(
            self.mesh
                .get_or_insert_with(|| Arc::new(live.take_discretisation())),
        )
    }

    /// Applies the pending edits: one point edit through live editing, anything else (a
    /// batch, a new surface) by discretising the edited inputs from scratch. On an error the
    /// live surface is as before.
    fn apply_pending(&mut self) -> Result<(), TpiError> {
        match self.pending.as_slice() {
            [] => return Ok(()),
            [Edit::Move(i, st)] => self.live.move_point(*i, *st)?,
            [Edit::Add(st)] => {
                self.live.add_point(*st)?;
            }
            [Edit::Remove(i)] => self.live.remove_point(*i)?,
            [Edit::Surface] => self.live.set_surface(Box::new(self.surface.clone()))?,
            _ => {
                self.live = LiveSurface::new(
                    Box::new(self.surface.clone()),
                    self.points.clone(),
                    self.options,
                )?;
            }
        }
        self.pending.clear();
        self.mesh = None;
        Ok(())
    }
}

impl TpiDiscreteSurface {
    /// The state. A panic while the lock was held (caught at the boundary) leaves the state
    /// as the interrupted call left it; every edit changes it in one step, so it stays
    /// consistent, and the object stays usable.
    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

/// A handle argument.
///
/// # Safety
/// `ptr` is NULL or a live handle.
unsafe fn handle<'a>(ptr: *const TpiDiscreteSurface) -> FfiResult<&'a TpiDiscreteSurface> {
    // SAFETY: forwarded contract.
    unsafe { try_handle(ptr, "discrete_surface") }
}

/// Checks a new pattern point (s, t): finite and inside [0, 1]^2.
fn check_point(s: f64, t: f64) -> FfiResult<[f64; 2]> {
    finite("s", s)?;
    finite("t", t)?;
    Pattern::new(vec![[s, t]]).validate()?;
    Ok([s, t])
}

/// Creates a discrete surface from copies of `surface` and `pattern` (the caller keeps its
/// handles and may free them at once) and computes its first mesh. `options` may be NULL for
/// the defaults; they hold for the object's life.
///
/// On success `*out` is a new handle (free with `tpi_discrete_surface_free`), else NULL.
/// Errors: as `tpi_discretise`.
///
/// # Safety
/// `surface` and `pattern` are NULL or live handles; `options` is NULL or a `TpiOptions`
/// with `struct_size` readable bytes; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_new(
    surface: *const TpiSurface,
    pattern: *const TpiPattern,
    options: *const TpiOptions,
    out: *mut *mut TpiDiscreteSurface,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let pattern = unsafe { try_handle(pattern, "pattern") }?;
        let options = unsafe { read_options(options) }?;
        let points = pattern.pattern.uv.clone();
        let mut live = LiveSurface::new(Box::new(surface.model.clone()), points.clone(), options)?;
        let mesh = Some(Arc::new(live.take_discretisation()));
        let state = State { surface: surface.model.clone(), points, options, live, mesh, pending: Vec::new() };
        out.set_boxed(TpiDiscreteSurface { state: Mutex::new(state) });
        Ok(())
    }
}

/// Frees a discrete surface. NULL is allowed and does nothing. Meshes taken from it with
/// `tpi_discrete_surface_mesh` stay valid.
///
/// # Safety
/// `discrete_surface` is NULL or a handle that was not freed yet, and no other call is using
/// it.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_free(discrete_surface: *mut TpiDiscreteSurface) {
    crate::boundary::run_infallible((), || {
        // SAFETY: the caller hands back ownership of a handle from this library.
        unsafe { crate::boundary::free_handle(discrete_surface) }
    })
}

/// Stores the current number of pattern points in `*out` (edits included, recomputed or not).
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_point_count(
    discrete_surface: *const TpiDiscreteSurface,
    out: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface) }?;
        let out = unsafe { OutPtr::new(out, "out") }?;
        out.set(ds.lock().points.len());
        Ok(())
    }
}

/// Copies the current pattern points s0, t0, s1, t1, ... (edits included). Copy-out
/// convention; `*needed` = 2 * point count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing
/// `capacity` doubles; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_points(
    discrete_surface: *const TpiDiscreteSurface,
    out: *mut f64,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface) }?;
        let state = ds.lock();
        unsafe { copy_out(state.points.as_flattened(), out, capacity, needed, "out") }
    }
}

/// Moves pattern point `index` to (s, t) in [0, 1]^2. A pending edit: the mesh changes at
/// the next `tpi_discrete_surface_recompute`.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INDEX_OUT_OF_RANGE, TPI_STATUS_NON_FINITE,
/// TPI_STATUS_INVALID_PATTERN (outside the square). On an error nothing changes.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_move_point(
    discrete_surface: *mut TpiDiscreteSurface,
    index: usize,
    s: f64,
    t: f64,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface.cast_const()) }?;
        let mut state = ds.lock();
        let len = state.points.len();
        let slot = state.points.get_mut(index).ok_or_else(|| index_error("pattern point", index, len))?;
        let point = check_point(s, t)?;
        *slot = point;
        state.pending.push(Edit::Move(index, point));
        Ok(())
    }
}

/// Appends the pattern point (s, t) in [0, 1]^2; its index (the previous point count) is
/// stored in `*index` unless `index` is NULL. A pending edit.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_PATTERN. On
/// an error nothing changes.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle; `index` is NULL or valid for writing a
/// `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_add_point(
    discrete_surface: *mut TpiDiscreteSurface,
    s: f64,
    t: f64,
    index: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface.cast_const()) }?;
        let index = if index.is_null() { None } else { Some(unsafe { OutPtr::new(index, "index") }?) };
        let point = check_point(s, t)?;
        let mut state = ds.lock();
        state.points.push(point);
        state.pending.push(Edit::Add(point));
        if let Some(index) = index {
            index.set(state.points.len() - 1);
        }
        Ok(())
    }
}

/// Removes pattern point `index`; the points after it move down by one index (as the facets
/// of the next mesh do). A pending edit.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INDEX_OUT_OF_RANGE. On an error nothing
/// changes.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_remove_point(
    discrete_surface: *mut TpiDiscreteSurface,
    index: usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface.cast_const()) }?;
        let mut state = ds.lock();
        let len = state.points.len();
        if index >= len {
            return Err(index_error("pattern point", index, len));
        }
        state.points.remove(index);
        state.pending.push(Edit::Remove(index));
        Ok(())
    }
}

/// Replaces the surface with a copy of `surface` (e.g. after its control points were
/// edited); the pattern points stay where they are in the normalised square. The caller
/// keeps its handle. A pending edit.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discrete_surface` and `surface` are NULL or live handles.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_set_surface(
    discrete_surface: *mut TpiDiscreteSurface,
    surface: *const TpiSurface,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface.cast_const()) }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let model = surface.model.clone();
        let mut state = ds.lock();
        state.surface = model;
        state.pending.push(Edit::Surface);
        Ok(())
    }
}

/// Stores the number of edits since the last successful recompute in `*out`; 0 means the
/// mesh is up to date.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_pending_edits(
    discrete_surface: *const TpiDiscreteSurface,
    out: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface) }?;
        let out = unsafe { OutPtr::new(out, "out") }?;
        out.set(ds.lock().pending.len());
        Ok(())
    }
}

/// Brings the mesh up to date with the pending edits. With no pending edits this does
/// nothing and succeeds.
///
/// On an error the edits stay (still pending), the previous mesh stays current, and the
/// message says what is wrong with the edited input (e.g. a moved point duplicating
/// another), so the host can undo or fix an edit and recompute again.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_PATTERN, TPI_STATUS_DEGENERATE,
/// TPI_STATUS_NON_FINITE.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_recompute(
    discrete_surface: *mut TpiDiscreteSurface,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let ds = unsafe { handle(discrete_surface.cast_const()) }?;
        let mut state = ds.lock();
        state.apply_pending()?;
        Ok(())
    }
}

/// Stores in `*out` a new discretisation handle for the current mesh (that of the last
/// successful recompute), to be read with the `tpi_discretisation_*` calls and freed with
/// `tpi_discretisation_free`. The mesh is shared, not copied, and it is immutable: later
/// edits and recomputes make new meshes and leave this one as it is, and it outlives the
/// discrete surface.
///
/// Errors: TPI_STATUS_NULL_POINTER. On an error `*out` is NULL.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_mesh(
    discrete_surface: *const TpiDiscreteSurface,
    out: *mut *mut TpiDiscretisation,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let ds = unsafe { handle(discrete_surface) }?;
        let mesh = ds.lock().mesh();
        out.set_boxed(TpiDiscretisation::new(mesh));
        Ok(())
    }
}

/// What changed in a discrete surface's mesh between two `tpi_discrete_surface_changes`
/// calls: an immutable snapshot, read with the `tpi_mesh_changes_*` calls and freed with
/// `tpi_mesh_changes_free`.
///
/// Vertices are named by ids of the discrete surface's live structure, not by the vertex
/// numbers of `tpi_discrete_surface_mesh`: an id keeps its position until a later snapshot
/// lists it with a new one. When `everything` is set (the first snapshot, and after a
/// recompute that ran the whole pipeline: a batch of edits, a new surface, an edit near the
/// boundary or on a surface without live editing) the numbering started over and every
/// facet and every vertex is listed.
pub struct TpiMeshChanges {
    changes: LiveChanges,
    /// Vertex count of each listed facet.
    sizes: Vec<u32>,
    planes: Vec<TpiPlane>,
    /// Positions of the listed vertices, x y z each.
    vertices: Vec<f64>,
}

impl crate::boundary::Handle for TpiMeshChanges {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:chng");
    const C_NAME: &'static str = "TpiMeshChanges";
}

impl TpiMeshChanges {
    fn new(changes: LiveChanges) -> Self {
        let offsets = &changes.facet_offsets;
        let sizes = offsets
            .iter()
            .zip(offsets.iter().skip(1))
            .map(|(start, end)| end - start)
            .collect();
        let planes = changes
            .planes
            .iter()
            .map(|(point, normal)| TpiPlane {
                point: point.to_array(),
                normal: normal.to_array(),
            })
            .collect();
        let vertices = changes.vertices.iter().flat_map(|x| x.to_array()).collect();
        Self {
            changes,
            sizes,
            planes,
            vertices,
        }
    }
}

/// A changes handle argument.
///
/// # Safety
/// `ptr` is NULL or a live handle.
unsafe fn changes<'a>(ptr: *const TpiMeshChanges) -> FfiResult<&'a TpiMeshChanges> {
    // SAFETY: forwarded contract.
    unsafe { try_handle(ptr, "changes") }
}

/// Stores in `*out` a new handle holding what changed in the mesh since the last call on
/// this discrete surface (the first call: since it was created, so everything), and starts
/// the next such list empty. Only successful recomputes change the mesh; pending edits do
/// not count. After one point edit recomputed by live editing the snapshot holds the few
/// facets around the point (about 7 for a move) and costs microseconds whatever the mesh's
/// size; after a recompute that ran the whole pipeline it lists everything (`everything`
/// is 1). See `TpiMeshChanges` for the vertex numbering.
///
/// On success `*out` is a new handle (free with `tpi_mesh_changes_free`), else NULL.
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `discrete_surface` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_discrete_surface_changes(
    discrete_surface: *mut TpiDiscreteSurface,
    out: *mut *mut TpiMeshChanges,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let ds = unsafe { handle(discrete_surface.cast_const()) }?;
        let changes = ds.lock().live.take_changes();
        out.set_boxed(TpiMeshChanges::new(changes));
        Ok(())
    }
}

/// Frees a changes snapshot. NULL is allowed and does nothing.
///
/// # Safety
/// `changes` is NULL or a handle that was not freed yet, and no other call is using it.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_free(changes: *mut TpiMeshChanges) {
    crate::boundary::run_infallible((), || {
        // SAFETY: the caller hands back ownership of a handle from this library.
        unsafe { crate::boundary::free_handle(changes) }
    })
}

/// Stores whether everything changed (1: the vertex numbering started over and every facet
/// and vertex is listed; 0: only what is listed changed) in `*everything`, the number of
/// facets of the mesh now in `*facet_count` (facets from it on are gone), and one more than
/// the largest vertex id in use in `*vertex_id_bound`. Any of the three may be NULL.
///
/// Errors: TPI_STATUS_NULL_POINTER (`changes`).
///
/// # Safety
/// `changes` is NULL or a live handle; `everything` is NULL or valid for writing a
/// `uint32_t`, `facet_count` and `vertex_id_bound` NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_counts(
    changes: *const TpiMeshChanges,
    everything: *mut u32,
    facet_count: *mut usize,
    vertex_id_bound: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        if !everything.is_null() {
            unsafe { OutPtr::new(everything, "everything") }?.set(u32::from(c.changes.everything));
        }
        if !facet_count.is_null() {
            unsafe { OutPtr::new(facet_count, "facet_count") }?.set(c.changes.facet_count);
        }
        if !vertex_id_bound.is_null() {
            unsafe { OutPtr::new(vertex_id_bound, "vertex_id_bound") }?.set(c.changes.vertex_id_bound);
        }
        Ok(())
    }
}

/// Copies the indices of the changed facets (= pattern point indices), ascending: every
/// facet whose loop or vertex positions changed, a new facet, and the facets renumbered by a
/// removed point. Copy-out convention; `*needed` = number of changed facets.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_facets(
    changes: *const TpiMeshChanges,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        unsafe { copy_out(&c.changes.facets, out, capacity, needed, "out") }
    }
}

/// Copies the vertex count of each changed facet, in the order of
/// `tpi_mesh_changes_facets`. Copy-out convention; `*needed` = number of changed facets.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_facet_sizes(
    changes: *const TpiMeshChanges,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        unsafe { copy_out(&c.sizes, out, capacity, needed, "out") }
    }
}

/// Copies the changed facets' loops, facet after facet in the order of
/// `tpi_mesh_changes_facets`, as vertex ids (see `TpiMeshChanges`): counter-clockwise seen
/// from the facet's normal and starting at the same vertex as the facet's loop in
/// `tpi_discrete_surface_mesh`. Copy-out convention; `*needed` = the sum of the sizes.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_facet_indices(
    changes: *const TpiMeshChanges,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        unsafe { copy_out(&c.changes.facet_loops, out, capacity, needed, "out") }
    }
}

/// Copies the changed facets' planes in the order of `tpi_mesh_changes_facets`, as
/// `tpi_discretisation_planes` gives them. Copy-out convention; `*needed` = number of
/// changed facets.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// TpiPlane; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_planes(
    changes: *const TpiMeshChanges,
    out: *mut TpiPlane,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        unsafe { copy_out(&c.planes, out, capacity, needed, "out") }
    }
}

/// Copies the ids of the vertices whose position is new, ascending (every other vertex id
/// the listed loops hold kept its position). Copy-out convention; `*needed` = number of
/// listed vertices.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// uint32_t; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_vertex_ids(
    changes: *const TpiMeshChanges,
    out: *mut u32,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        unsafe { copy_out(&c.changes.vertex_ids, out, capacity, needed, "out") }
    }
}

/// Copies the new positions of the listed vertices, x0, y0, z0, x1, ... in the order of
/// `tpi_mesh_changes_vertex_ids`. Copy-out convention; `*needed` = 3 * number of listed
/// vertices.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `changes` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// doubles; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_mesh_changes_vertices(
    changes: *const TpiMeshChanges,
    out: *mut f64,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let c = unsafe { self::changes(changes) }?;
        unsafe { copy_out(&c.vertices, out, capacity, needed, "out") }
    }
}
