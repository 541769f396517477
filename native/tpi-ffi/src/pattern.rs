//! Pattern handles: points in the normalised square, given or generated.

use std::ffi::{c_char, c_void};

use std::mem::size_of;

use tpi_core::{FitOutcome, Generator, GridSize, Pattern, SurfacePatternSpec};

use crate::boundary::{
    copy_out, ffi_boundary, finite, try_handle, try_pairs, try_str, FfiError, FfiResult, OutPtr,
    TpiStatus,
};
use crate::discretisation::{CallbackObserver, TpiProgressCallback};
use crate::options::{read_options, TpiOptions};
use crate::surface::TpiSurface;

/// A set of pattern points (s, t) in the normalised square [0, 1]^2, mapped linearly onto a
/// surface's domain: u = u_min + s (u_max - u_min), v = v_min + t (v_max - v_min). Immutable
/// once created.
///
/// Created by the `tpi_pattern_new*` calls, freed by `tpi_pattern_free`. May be used from
/// several threads at once.
pub struct TpiPattern {
    pub(crate) pattern: Pattern,
    /// How the fit went, for a pattern made by a `fit:D` spec.
    pub(crate) fit: Option<FitOutcome>,
}

impl crate::boundary::Handle for TpiPattern {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:patt");
    const C_NAME: &'static str = "TpiPattern";
}

fn create(out: *mut *mut TpiPattern, build: impl FnOnce() -> FfiResult<Pattern>) -> FfiResult {
    // SAFETY: `out` is NULL or valid for writes (the contract of every create call).
    let out = unsafe { OutPtr::handle(out, "out") }?;
    let pattern = build()?;
    out.set_boxed(TpiPattern { pattern, fit: None });
    Ok(())
}

fn generate(generator: Generator) -> FfiResult<Pattern> {
    generator.validate()?;
    Ok(generator.generate())
}

/// Creates a pattern from `uv_len / 2` points: `uv` holds s0, t0, s1, t1, ... in [0, 1].
///
/// The points are validated: each finite and inside [0, 1]^2, no two closer than 1e-9.
/// Fewer than three points make a valid pattern, but discretising it fails.
///
/// On success `*out` is a new handle (free with `tpi_pattern_free`), else NULL. Errors:
/// TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (odd `uv_len`),
/// TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_PATTERN (a point outside the square, a
/// duplicate; the message names the point).
///
/// # Safety
/// `uv` is NULL or valid for reading `uv_len` doubles; `out` is NULL or valid for writing a
/// pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new(
    uv: *const f64,
    uv_len: usize,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! {
        create(out, || {
            // SAFETY: the caller's contract.
            let pairs = unsafe { try_pairs(uv, uv_len, "uv") }?;
            let pattern = Pattern::new(pairs.to_vec());
            pattern.validate()?;
            Ok(pattern)
        })
    }
}

/// Creates the square grid of `nu` x `nv` cell centres ((i + 1/2)/nu, (j + 1/2)/nv), point
/// (i, j) at index i * nv + j (generator `grid:NUxNV`).
///
/// On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
/// TPI_STATUS_INVALID_PATTERN (a count of 0, more than 10^7 points).
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_grid(
    nu: usize,
    nv: usize,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! { create(out, || generate(Generator::Grid(GridSize::Counts { nu, nv }))) }
}

/// Creates the hexagonal grid of `nu` x `nv` points: rows at t = (j + 1/2)/nv, points at
/// s = (i + 1/4)/nu in even rows and (i + 3/4)/nu in odd rows (generator `hex:NUxNV`).
///
/// On success `*out` is a new handle, else NULL. Errors as `tpi_pattern_new_grid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_hex(
    nu: usize,
    nv: usize,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! { create(out, || generate(Generator::Hex(GridSize::Counts { nu, nv }))) }
}

/// Creates the `nu` x `nv` grid with each cell centre moved by uniform random offsets in
/// [-amount/2, amount/2) of the cell's size; `amount` in [0, 1] (generator
/// `jitter:NUxNV:amount=A:seed=S`). Deterministic for a given seed.
///
/// On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
/// TPI_STATUS_INVALID_PATTERN.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_jitter(
    nu: usize,
    nv: usize,
    amount: f64,
    seed: u64,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! { create(out, || generate(Generator::Jitter { size: GridSize::Counts { nu, nv }, amount, seed })) }
}

/// Creates `count` uniform random points (generator `random:N:seed=S`). Deterministic for a
/// given seed.
///
/// On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
/// TPI_STATUS_INVALID_PATTERN.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_random(
    count: usize,
    seed: u64,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! { create(out, || generate(Generator::Random { count, seed })) }
}

/// Creates a Poisson-disk sampling with minimum distance `radius` (>= 0.001) in normalised
/// units (generator `poisson:R:seed=S`). Deterministic for a given seed; the number of points
/// depends on the radius (about 0.7 / radius^2).
///
/// On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
/// TPI_STATUS_INVALID_PATTERN.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_poisson(
    radius: f64,
    seed: u64,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! { create(out, || generate(Generator::Poisson { radius, seed })) }
}

/// Creates a pattern from a generator spec, the command line's syntax: `grid:NUxNV`,
/// `grid:spacing=D`, `hex:NUxNV`, `hex:spacing=D`, `jitter:NUxNV[:amount=A][:seed=S]`,
/// `jitter:spacing=D[...]`, `random:N[:seed=S]`, `poisson:R[:seed=S]`.
///
/// On success `*out` is a new handle, else NULL. Errors: TPI_STATUS_NULL_POINTER,
/// TPI_STATUS_INVALID_ARGUMENT (not UTF-8), TPI_STATUS_INVALID_PATTERN (malformed spec, with
/// the accepted syntax in the message).
///
/// # Safety
/// `spec` is NULL or a NUL-terminated string; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_from_spec(
    spec: *const c_char,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! {
        create(out, || {
            // SAFETY: the caller's contract.
            let spec = unsafe { try_str(spec, "spec") }?;
            generate(Generator::parse(spec)?)
        })
    }
}

/// Creates a pattern made on `surface` from a pattern spec: a generator (as
/// `tpi_pattern_new_from_spec`) or one of the forms that look at the surface (the grammar of
/// the command line's `tpi discretise --pattern`, tpi_core::SurfacePatternSpec):
///
/// - `fit:D[:seed=S]`: few points whose TPI mesh keeps every vertex within D model units of
///   the surface (D > 0); `tpi_pattern_fit_report` tells whether D was met. A fit that does
///   not meet D still creates the pattern (the closest attempt): check `met`.
/// - `relax:N:SPEC`: SPEC's points after N (0 to 1000) Lloyd iterations on the surface,
///   areas measured on the surface; SPEC is any form but `fit:` and `relax:` (of a density,
///   the iterations follow the density).
/// - `align:LATTICE:FIELD`: LATTICE `hex:NUxNV`, `hex:spacing=A`, `grid:NUxNV` or
///   `grid:spacing=A` (about that many points) laid along FIELD: `principal`, `asymptotic`,
///   `uv:ANGLE` (degrees) or a direction field as inline JSON
///   `{"size": [NS, NT], "directions": [[ds, dt], ...]}`.
/// - `density:{JSON}`: a Poisson-disk sampling following a density field (the JSON of a
///   density file, docs/formats.md, inline).
///
/// The field and the density run to the end of the spec, so their JSON may hold colons. The
/// library reads no files: `@FILE` and density `image` terms (which name a file) are refused
/// with TPI_STATUS_INVALID_PATTERN; read the file and put its JSON text in the spec.
/// `options` (NULL for the defaults) are those of the discretisations the form runs (the
/// plane mode decides what a fit measures). Deterministic for a given spec, surface and
/// options. A fit or a relaxation runs many discretisations and may take seconds.
///
/// On success `*out` is a new handle (free with `tpi_pattern_free`), else NULL. Errors:
/// TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (not UTF-8, bad options, a bad
/// number in the JSON), TPI_STATUS_INVALID_PATTERN (a malformed spec: the message quotes the
/// piece that is wrong), TPI_STATUS_NON_FINITE, TPI_STATUS_DEGENERATE (a surface the form
/// cannot work on).
///
/// # Safety
/// `surface` is NULL or a live handle; `spec` is NULL or a NUL-terminated string; `options`
/// is NULL or a `TpiOptions` with `struct_size` readable bytes; `out` is NULL or valid for
/// writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_for_surface(
    surface: *const TpiSurface,
    spec: *const c_char,
    options: *const TpiOptions,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    // SAFETY: the caller's contract, and no callback.
    unsafe {
        tpi_pattern_new_for_surface_with_progress(
            surface,
            spec,
            options,
            None,
            std::ptr::null_mut(),
            out,
        )
    }
}

/// `tpi_pattern_new_for_surface`, reporting progress to `callback` (see
/// `TpiProgressCallback`), which can cancel it by returning nonzero. A fit or a relaxation
/// runs many discretisations (a fit tens of them, seconds on a large surface): each one's
/// stages are reported as `tpi_discretise_with_progress` reports them, from TPI_STAGE_SAMPLES
/// again for the next; a form that runs none (a generator, an aligned lattice, a density
/// without relaxation) reports nothing.
///
/// `callback` may be NULL (the same as `tpi_pattern_new_for_surface`); `user_data` is handed
/// to every call of `callback` and never read by the library. The points are the same as
/// `tpi_pattern_new_for_surface`'s. Once the callback has returned nonzero, the call stops
/// where the running stage of the running discretisation ends and returns
/// TPI_STATUS_CANCELLED with `*out` NULL and nothing created.
///
/// Errors: those of `tpi_pattern_new_for_surface`, and TPI_STATUS_CANCELLED.
///
/// # Safety
/// As `tpi_pattern_new_for_surface`; `callback` is NULL or a function that may be called with
/// `user_data` on the calling thread until this call returns.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_new_for_surface_with_progress(
    surface: *const TpiSurface,
    spec: *const c_char,
    options: *const TpiOptions,
    callback: TpiProgressCallback,
    user_data: *mut c_void,
    out: *mut *mut TpiPattern,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let spec = unsafe { try_str(spec, "spec") }?;
        let options = unsafe { read_options(options) }?;
        let spec = SurfacePatternSpec::parse(spec)?;
        let made = match callback {
            None => spec.generate(&surface.model, &options)?,
            Some(callback) => {
                let observer = CallbackObserver::new(callback, user_data);
                spec.generate_with_progress(&surface.model, &options, &observer)?
            }
        };
        let pattern = Pattern::new(made.uv);
        pattern.validate()?;
        out.set_boxed(TpiPattern { pattern, fit: made.fit });
        Ok(())
    }
}

/// Size in bytes of the first version of `TpiFitReport`: the smallest `struct_size`
/// accepted.
pub const TPI_FIT_REPORT_SIZE_V1: u32 = 40;

/// How a `fit:D` pattern went (`tpi_pattern_fit_report`).
///
/// Growth: fields are only ever appended; set `struct_size` to sizeof(TpiFitReport) before
/// the call, and the library writes only that many bytes (and stores in `struct_size` how
/// many it filled in).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TpiFitReport {
    /// sizeof(TpiFitReport) as compiled by the caller; at least TPI_FIT_REPORT_SIZE_V1.
    pub struct_size: u32,
    /// 1 if every vertex of the pattern's mesh lies within `tolerance` of the surface, else
    /// 0 (the pattern is then the closest attempt).
    pub met: u32,
    /// The tolerance asked for, D (model units).
    pub tolerance: f64,
    /// The largest vertex deviation of the pattern's mesh (model units).
    pub max_deviation: f64,
    /// Invalid facets of the pattern's mesh.
    pub invalid_facets: u64,
    /// Discretisations run to find the pattern.
    pub discretisations: u64,
}

/// Fills `*out` with how the fit went, for a pattern made by `tpi_pattern_new_for_surface`
/// with a `fit:D` spec (the point count is `tpi_pattern_point_count`). Set
/// `out->struct_size` = sizeof(TpiFitReport) first; only that many bytes are written, and on
/// return `struct_size` holds the number of bytes filled in.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`struct_size` below
/// TPI_FIT_REPORT_SIZE_V1), TPI_STATUS_UNAVAILABLE (the pattern was not made by a fit).
///
/// # Safety
/// `pattern` is NULL or a live handle; `out` is NULL or valid for reading and writing
/// `out->struct_size` bytes.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_fit_report(
    pattern: *const TpiPattern,
    out: *mut TpiFitReport,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let pattern = unsafe { try_handle(pattern, "pattern") }?;
        let out = unsafe { OutPtr::new(out, "out") }?;
        // SAFETY: checked non-NULL and aligned; struct_size is the first field.
        let size = unsafe { out.as_ptr().cast::<u32>().read() };
        if size < TPI_FIT_REPORT_SIZE_V1 {
            return Err(FfiError::invalid(format!(
                "out->struct_size is {size}; set it to sizeof(TpiFitReport) (at least {TPI_FIT_REPORT_SIZE_V1})"
            )));
        }
        let fit = pattern.fit.ok_or_else(|| {
            FfiError::new(
                TpiStatus::Unavailable,
                "this pattern was not made by a fit:D spec (tpi_pattern_new_for_surface)",
            )
        })?;
        let bytes = (size as usize).min(size_of::<TpiFitReport>());
        let report = TpiFitReport {
            struct_size: bytes as u32,
            met: u32::from(fit.met),
            tolerance: fit.tolerance,
            max_deviation: fit.max_deviation,
            invalid_facets: fit.invalid_facets as u64,
            discretisations: fit.discretisations as u64,
        };
        // SAFETY: `bytes` bytes are writable (contract) and readable from `report`.
        unsafe { std::ptr::copy_nonoverlapping((&report as *const TpiFitReport).cast::<u8>(), out.as_ptr().cast::<u8>(), bytes) };
        Ok(())
    }
}

/// The smallest uniform hexagonal pattern `hex:spacing=1/N` whose mesh on `surface` keeps
/// every vertex within `max_deviation` (model units, > 0) of the surface, found by doubling N,
/// bisection, and every N down to 0.85 of the bisection's (the deviation is not monotone in
/// N), looking at patterns of at most `max_points` points (the baseline a fitted pattern is
/// compared with). `options`: NULL for the defaults.
///
/// On success `*count` is its number of points and `*deviation` its mesh's largest vertex
/// deviation; when no such pattern has at most `max_points` points, `*count` is 0 and
/// `*deviation` NaN. Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT
/// (`max_deviation` not > 0, bad options), TPI_STATUS_NON_FINITE, TPI_STATUS_DEGENERATE.
///
/// # Safety
/// `surface` is NULL or a live handle; `options` is NULL or a `TpiOptions` with
/// `struct_size` readable bytes; `count` and `deviation` are NULL or valid for writing.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_hex_baseline(
    surface: *const TpiSurface,
    max_deviation: f64,
    max_points: usize,
    options: *const TpiOptions,
    count: *mut usize,
    deviation: *mut f64,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let surface = unsafe { try_handle(surface, "surface") }?;
        let count = unsafe { OutPtr::new(count, "count") }?;
        let deviation = unsafe { OutPtr::new(deviation, "deviation") }?;
        let options = unsafe { read_options(options) }?;
        let d = finite("max_deviation", max_deviation)?;
        if d <= 0.0 {
            return Err(FfiError::invalid(format!("max_deviation is {d}; it must be > 0")));
        }
        let found = tpi_core::hex_baseline(&surface.model, d, max_points, &options)?;
        count.set(found.as_ref().map_or(0, |h| h.count));
        deviation.set(found.as_ref().map_or(f64::NAN, |h| h.max_deviation));
        Ok(())
    }
}

/// Frees a pattern. NULL is allowed and does nothing.
///
/// # Safety
/// `pattern` is NULL or a handle from a `tpi_pattern_new*` call that was not freed yet, and
/// no other call is using it.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_free(pattern: *mut TpiPattern) {
    crate::boundary::run_infallible((), || {
        // SAFETY: the caller hands back ownership of a handle from this library.
        unsafe { crate::boundary::free_handle(pattern) }
    })
}

/// Stores the number of points in `*out`.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `pattern` is NULL or a live handle; `out` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_point_count(
    pattern: *const TpiPattern,
    out: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let pattern = unsafe { try_handle(pattern, "pattern") }?;
        unsafe { OutPtr::new(out, "out") }?.set(pattern.pattern.len());
        Ok(())
    }
}

/// Copies the points to `out` as s0, t0, s1, t1, ... (2 doubles per point); the copy-out
/// convention (see the header's introduction): `*needed` = 2 * point count.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `pattern` is NULL or a live handle; `out` is NULL or valid for writing `capacity` doubles;
/// `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_pattern_points(
    pattern: *const TpiPattern,
    out: *mut f64,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let pattern = unsafe { try_handle(pattern, "pattern") }?;
        unsafe { copy_out(pattern.pattern.uv.as_flattened(), out, capacity, needed, "out") }
    }
}
