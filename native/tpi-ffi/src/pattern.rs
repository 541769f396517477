//! Pattern handles: points in the normalised square, given or generated.

use std::ffi::c_char;

use tpi_core::{Generator, GridSize, Pattern};

use crate::boundary::{
    copy_out, ffi_boundary, try_handle, try_pairs, try_str, FfiResult, OutPtr, TpiStatus,
};

/// A set of pattern points (s, t) in the normalised square [0, 1]^2, mapped linearly onto a
/// surface's domain: u = u_min + s (u_max - u_min), v = v_min + t (v_max - v_min). Immutable
/// once created.
///
/// Created by the `tpi_pattern_new*` calls, freed by `tpi_pattern_free`. May be used from
/// several threads at once.
pub struct TpiPattern {
    pub(crate) pattern: Pattern,
}

impl crate::boundary::Handle for TpiPattern {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:patt");
    const C_NAME: &'static str = "TpiPattern";
}

fn create(out: *mut *mut TpiPattern, build: impl FnOnce() -> FfiResult<Pattern>) -> FfiResult {
    // SAFETY: `out` is NULL or valid for writes (the contract of every create call).
    let out = unsafe { OutPtr::handle(out, "out") }?;
    let pattern = build()?;
    out.set_boxed(TpiPattern { pattern });
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
