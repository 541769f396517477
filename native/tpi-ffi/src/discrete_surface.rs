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

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use tpi_core::Pattern;
use tpi_core::SurfaceModel;
use tpi_core::{Discretisation, DiscretiseOptions, LiveSurface, TpiError};

use crate::boundary::{
    copy_out, ffi_boundary, finite, index_error, try_handle, FfiResult, OutPtr, TpiStatus,
};
use crate::discretisation::TpiDiscretisation;
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
