//! # tpi-ffi: the C ABI of tpi-core
//!
//! The one door through which Rhino, Grasshopper and any other host reach the core: opaque
//! handles with create/free pairs, sampling, adjacency and facet calls, copy-out buffers, one
//! status enum, a thread-local last error message, and a panic boundary around every entry
//! point. The header `include/tpi.h` is generated from this crate by cbindgen (configuration
//! in `cbindgen.toml`; the conventions every call follows are written out there, at the top of
//! the header) and checked against a fresh generation by `tests/header.rs`.
//!
//! This crate converts and forwards; the geometry lives in tpi-core.
//!
//! Rules kept here:
//! - every `extern "C"` body runs inside [`boundary::run`] (through `ffi_boundary!`) or
//!   [`boundary::run_infallible`], so no panic unwinds into the host;
//! - every pointer goes through the checked helpers of [`boundary`];
//! - nothing reachable from an entry point unwraps, expects or asserts (the lints below).

#![deny(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic,
    clippy::todo,
    clippy::unimplemented,
    clippy::unreachable,
    clippy::indexing_slicing
)]
#![deny(unsafe_op_in_unsafe_fn)]
#![warn(missing_docs)]

// catch_unwind is useless when panics abort: refuse to build such a library at all.
#[cfg(panic = "abort")]
compile_error!("tpi-ffi must be built with panic = \"unwind\": its panic boundary depends on it (DESIGN.md, pitfalls)");

// In this order in the header.
pub mod boundary;
pub mod discrete_surface;
pub mod discretisation;
pub mod fabrication;
pub mod options;
pub mod pattern;
pub mod surface;

use std::ffi::c_char;

// Everything exported, flat at the crate root (as in the header).
pub use boundary::{FfiError, FfiResult, TpiStatus};
pub use discrete_surface::*;
pub use discretisation::*;
pub use fabrication::*;
pub use options::*;
pub use pattern::*;
pub use surface::*;

use boundary::{copy_out_str, ffi_boundary, last_error, run_infallible};

/// Major version of the library this header belongs to (semantic versioning: the ABI only
/// breaks with a new major version, or before 1.0 with a new minor version).
pub const TPI_VERSION_MAJOR: u32 = 0;
/// Minor version of the library this header belongs to.
pub const TPI_VERSION_MINOR: u32 = 1;
/// Patch version of the library this header belongs to.
pub const TPI_VERSION_PATCH: u32 = 0;

/// The library's version, "MAJOR.MINOR.PATCH", as a static NUL-terminated string (never
/// freed). Compare it with the TPI_VERSION_* macros to detect a header/library mismatch.
#[no_mangle]
pub extern "C" fn tpi_version() -> *const c_char {
    const VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "\0");
    run_infallible(VERSION.as_ptr().cast(), || VERSION.as_ptr().cast())
}

/// The name of a status code as a static NUL-terminated string (e.g. "TPI_STATUS_OK"), or
/// "TPI_STATUS_UNKNOWN" for a number that is not a status. Never NULL, never freed.
#[no_mangle]
pub extern "C" fn tpi_status_name(status: u32) -> *const c_char {
    const UNKNOWN: &str = "TPI_STATUS_UNKNOWN\0";
    run_infallible(UNKNOWN.as_ptr().cast(), || {
        let name = match TpiStatus::from_u32(status) {
            Some(TpiStatus::Ok) => "TPI_STATUS_OK\0",
            Some(TpiStatus::NullPointer) => "TPI_STATUS_NULL_POINTER\0",
            Some(TpiStatus::InvalidArgument) => "TPI_STATUS_INVALID_ARGUMENT\0",
            Some(TpiStatus::BufferTooSmall) => "TPI_STATUS_BUFFER_TOO_SMALL\0",
            Some(TpiStatus::IndexOutOfRange) => "TPI_STATUS_INDEX_OUT_OF_RANGE\0",
            Some(TpiStatus::NonFinite) => "TPI_STATUS_NON_FINITE\0",
            Some(TpiStatus::InvalidNurbs) => "TPI_STATUS_INVALID_NURBS\0",
            Some(TpiStatus::InvalidPattern) => "TPI_STATUS_INVALID_PATTERN\0",
            Some(TpiStatus::Degenerate) => "TPI_STATUS_DEGENERATE\0",
            Some(TpiStatus::Panic) => "TPI_STATUS_PANIC\0",
            Some(TpiStatus::OutOfDomain) => "TPI_STATUS_OUT_OF_DOMAIN\0",
            Some(TpiStatus::Unavailable) => "TPI_STATUS_UNAVAILABLE\0",
            Some(TpiStatus::InvalidHandle) => "TPI_STATUS_INVALID_HANDLE\0",
            Some(TpiStatus::Cancelled) => "TPI_STATUS_CANCELLED\0",
            None => UNKNOWN,
        };
        name.as_ptr().cast()
    })
}

/// Copies the message of the last failed call on the calling thread, NUL terminated, UTF-8.
///
/// Every call except this one and the `*_free` calls replaces the message: a call that fails
/// stores what went wrong (naming the argument, index or field), a call that succeeds stores
/// "". The message is per thread: a call on another thread never changes it. Copy-out
/// convention; `*needed` counts the NUL (1 for an empty message). This call leaves the
/// message as it is, also when it fails itself, so a too-small buffer can be retried.
///
/// Errors: TPI_STATUS_NULL_POINTER (`buf` NULL with `capacity` > 0),
/// TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `buf` is NULL or valid for writing `capacity` chars; `needed` is NULL or valid for
/// writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_last_error_message(
    buf: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    let message = last_error();
    let reported = message.as_str();
    let status = ffi_boundary! {
        // SAFETY: the caller's contract.
        unsafe { copy_out_str(reported, buf, capacity, needed, "buf") }
    };
    // The boundary recorded this call's own outcome; put the reported message back.
    boundary::set_last_error(&message);
    status
}

/// Panics on purpose inside the panic boundary, so that tests can prove that a panic becomes
/// TPI_STATUS_PANIC instead of aborting the host. Only in builds with the `debug-panic`
/// feature (the tests'); never in the released library or its header.
#[cfg(feature = "debug-panic")]
#[doc(hidden)]
#[no_mangle]
pub extern "C" fn tpi_debug_panic() -> TpiStatus {
    ffi_boundary! {
        #[allow(clippy::panic)]
        {
            panic!("tpi_debug_panic: injected panic")
        }
    }
}
