//! The boundary between C and Rust: the status enum, the thread-local last error, the panic
//! boundary every entry point runs behind, and the checked conversions of raw pointers.
//!
//! Every `extern "C"` function body is written as `ffi_boundary! { ... }`: the body returns
//! [`FfiResult`], `?` works inside it, and the macro turns the result into a [`TpiStatus`],
//! recording the message of a failure for `tpi_last_error_message`. A panic anywhere below is
//! caught here and becomes [`TpiStatus::Panic`]; it never unwinds into the host.
//!
//! Pointers are only ever read through the helpers of this module ([`try_ref`], [`try_slice`],
//! [`OutPtr`], [`copy_out`], [`copy_out_str`]), so NULL, alignment and length checks happen the
//! same way everywhere.

use std::any::Any;
use std::cell::RefCell;
use std::ffi::c_char;
use std::mem::{align_of, size_of};
use std::panic::{catch_unwind, AssertUnwindSafe};

use tpi_core::TpiError;

/// The result of every fallible call. The numbers are part of the ABI: they are never changed
/// and never reused, and new codes are only ever appended.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TpiStatus {
    /// Success.
    Ok = 0,
    /// A required pointer argument was NULL (a handle, an output pointer, or an input array
    /// whose length is not 0).
    NullPointer = 1,
    /// An argument is invalid: a length that does not fit (an odd number of doubles for
    /// (u, v) pairs), a misaligned pointer, an option out of range, a surface parameter out of
    /// its range, a string that is not UTF-8.
    InvalidArgument = 2,
    /// An output buffer's capacity is smaller than the data; the needed size was stored
    /// through `needed` (when not NULL) and nothing was written to the buffer.
    BufferTooSmall = 3,
    /// A pattern point index is not smaller than the number of pattern points.
    IndexOutOfRange = 4,
    /// A number that must be finite is NaN or infinite.
    NonFinite = 5,
    /// The NURBS data is inconsistent: a degree, a count, a knot vector (length, order,
    /// multiplicity, empty domain), the number of points or weights, or a weight <= 0.
    InvalidNurbs = 6,
    /// The pattern is invalid: a point outside [0, 1]^2, two coincident points, fewer than
    /// three points, all points collinear, or a malformed generator or pattern spec.
    InvalidPattern = 7,
    /// The surface cannot be discretised by tangent plane intersection (flat or developable
    /// at every pattern point).
    Degenerate = 8,
    /// An internal error (a panic) was caught at the boundary. The handles passed to the call
    /// are still valid and may be freed; please report the message.
    Panic = 9,
    /// A (u, v) parameter pair lies outside the surface's domain.
    OutOfDomain = 10,
    /// The requested data was not computed (the quality report was switched off in the
    /// options).
    Unavailable = 11,
    /// A handle argument is not a live handle of the kind the call takes: a handle of
    /// another kind (a TpiDiscretisation passed where a TpiDiscreteSurface is expected), or
    /// one that was already freed and still reads as freed. Nothing was read through it.
    InvalidHandle = 12,
    /// The caller's progress callback asked the call to stop (`tpi_discretise_with_progress`).
    /// Nothing was created.
    Cancelled = 13,
}

impl TpiStatus {
    /// The enumerator's name as it appears in the header.
    pub fn name(self) -> &'static str {
        match self {
            TpiStatus::Ok => "TPI_STATUS_OK",
            TpiStatus::NullPointer => "TPI_STATUS_NULL_POINTER",
            TpiStatus::InvalidArgument => "TPI_STATUS_INVALID_ARGUMENT",
            TpiStatus::BufferTooSmall => "TPI_STATUS_BUFFER_TOO_SMALL",
            TpiStatus::IndexOutOfRange => "TPI_STATUS_INDEX_OUT_OF_RANGE",
            TpiStatus::NonFinite => "TPI_STATUS_NON_FINITE",
            TpiStatus::InvalidNurbs => "TPI_STATUS_INVALID_NURBS",
            TpiStatus::InvalidPattern => "TPI_STATUS_INVALID_PATTERN",
            TpiStatus::Degenerate => "TPI_STATUS_DEGENERATE",
            TpiStatus::Panic => "TPI_STATUS_PANIC",
            TpiStatus::OutOfDomain => "TPI_STATUS_OUT_OF_DOMAIN",
            TpiStatus::Unavailable => "TPI_STATUS_UNAVAILABLE",
            TpiStatus::InvalidHandle => "TPI_STATUS_INVALID_HANDLE",
            TpiStatus::Cancelled => "TPI_STATUS_CANCELLED",
        }
    }

    /// Every status, in numeric order.
    ///
    /// cbindgen:ignore
    pub const ALL: [TpiStatus; 14] = [
        TpiStatus::Ok,
        TpiStatus::NullPointer,
        TpiStatus::InvalidArgument,
        TpiStatus::BufferTooSmall,
        TpiStatus::IndexOutOfRange,
        TpiStatus::NonFinite,
        TpiStatus::InvalidNurbs,
        TpiStatus::InvalidPattern,
        TpiStatus::Degenerate,
        TpiStatus::Panic,
        TpiStatus::OutOfDomain,
        TpiStatus::Unavailable,
        TpiStatus::InvalidHandle,
        TpiStatus::Cancelled,
    ];

    /// The status with this number, if any.
    pub fn from_u32(code: u32) -> Option<TpiStatus> {
        TpiStatus::ALL.iter().copied().find(|s| *s as u32 == code)
    }
}

/// A failed call: the status to return and the message for `tpi_last_error_message`.
#[derive(Clone, Debug, PartialEq)]
pub struct FfiError {
    /// The status code.
    pub status: TpiStatus,
    /// What went wrong, naming the argument.
    pub message: String,
}

impl FfiError {
    /// A new error.
    pub fn new(status: TpiStatus, message: impl Into<String>) -> Self {
        Self {
            status,
            message: message.into(),
        }
    }

    /// A NULL pointer passed as `name`.
    pub fn null(name: &str) -> Self {
        Self::new(TpiStatus::NullPointer, format!("{name} is NULL"))
    }

    /// An invalid argument.
    pub fn invalid(message: impl Into<String>) -> Self {
        Self::new(TpiStatus::InvalidArgument, message)
    }

    /// A core error mapped to its status by [`status_of`].
    pub fn core(error: &TpiError) -> Self {
        Self::new(status_of(error), error.to_string())
    }

    /// A core error from NURBS construction: everything but non-finite numbers is
    /// [`TpiStatus::InvalidNurbs`].
    pub fn nurbs(error: &TpiError) -> Self {
        let status = match status_of(error) {
            TpiStatus::NonFinite => TpiStatus::NonFinite,
            _ => TpiStatus::InvalidNurbs,
        };
        Self::new(status, error.to_string())
    }
}

impl From<TpiError> for FfiError {
    fn from(error: TpiError) -> Self {
        FfiError::core(&error)
    }
}

/// The result type of every entry point's body.
pub type FfiResult<T = ()> = Result<T, FfiError>;

/// The status a core error maps to.
pub fn status_of(error: &TpiError) -> TpiStatus {
    match error {
        TpiError::NonFinite { .. } => TpiStatus::NonFinite,
        TpiError::InvalidParameter { .. }
        | TpiError::OutOfBounds { .. }
        | TpiError::EmptyDomain { .. }
        | TpiError::Parse { .. } => TpiStatus::InvalidArgument,
        TpiError::InvalidDegree { .. }
        | TpiError::KnotCount { .. }
        | TpiError::KnotsDecreasing { .. }
        | TpiError::KnotMultiplicity { .. }
        | TpiError::PointCount { .. }
        | TpiError::WeightCount { .. }
        | TpiError::NonPositiveWeight { .. } => TpiStatus::InvalidNurbs,
        TpiError::OutOfDomain { .. } => TpiStatus::OutOfDomain,
        TpiError::PatternPointOutOfRange { s, t, .. } => {
            if s.is_finite() && t.is_finite() {
                TpiStatus::InvalidPattern
            } else {
                TpiStatus::NonFinite
            }
        }
        TpiError::DuplicatePatternPoint { .. }
        | TpiError::SameSurfacePoint { .. }
        | TpiError::TooFewPatternPoints { .. }
        | TpiError::CollinearPattern { .. }
        | TpiError::InvalidGenerator { .. }
        | TpiError::InvalidPatternSpec { .. } => TpiStatus::InvalidPattern,
        TpiError::DegenerateSurface { .. } => TpiStatus::Degenerate,
        // A malformed trim is invalid input; a trim that a path (live editing, a non-convex
        // surface) cannot honour is refused as such, never ignored.
        TpiError::InvalidTrim { .. } | TpiError::TrimUnsupported { .. } => {
            TpiStatus::InvalidArgument
        }
        // Faces that cannot be joined (trimmed, nested, apart, not a rectangle) are invalid
        // input, the message naming the face.
        TpiError::InvalidPolysurface { .. } => TpiStatus::InvalidArgument,
        TpiError::Cancelled { .. } => TpiStatus::Cancelled,
        // The core's error is non-exhaustive; a variant added later is reported as invalid
        // input until it gets its own code.
        _ => TpiStatus::InvalidArgument,
    }
}

thread_local! {
    /// The message of the last failed call on this thread (empty after a success).
    static LAST_ERROR: RefCell<String> = const { RefCell::new(String::new()) };
}

/// Replaces this thread's last error message. Never panics: if the thread-local is being
/// torn down or is borrowed (impossible in practice), the message is dropped.
pub fn set_last_error(message: &str) {
    let _ = LAST_ERROR.try_with(|cell| {
        if let Ok(mut slot) = cell.try_borrow_mut() {
            slot.clear();
            slot.push_str(message);
        }
    });
}

/// A copy of this thread's last error message ("" if there is none or it is unavailable).
pub fn last_error() -> String {
    LAST_ERROR
        .try_with(|cell| {
            cell.try_borrow()
                .map(|message| message.clone())
                .unwrap_or_default()
        })
        .unwrap_or_default()
}

/// The message carried by a panic payload.
fn panic_message(payload: &(dyn Any + Send)) -> String {
    if let Some(s) = payload.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = payload.downcast_ref::<String>() {
        s.clone()
    } else {
        "(no message)".to_string()
    }
}

/// The panic boundary: runs `body`, catching any panic, and turns the outcome into a status.
/// The thread's last error is cleared before `body` runs and set when it fails.
///
/// Every fallible entry point is `run(|| { ... })` through the [`ffi_boundary!`] macro; this
/// function is public (hidden) so that the tests can drive the very same code with a
/// panicking closure.
#[doc(hidden)]
pub fn run(body: impl FnOnce() -> FfiResult) -> TpiStatus {
    set_last_error("");
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => TpiStatus::Ok,
        Ok(Err(error)) => {
            // Bounded: an offending value is quoted with at most QUOTE_LIMIT characters.
            set_last_error(&tpi_core::bound_message(&error.message));
            error.status
        }
        Err(payload) => {
            let message = panic_message(payload.as_ref());
            // Dropping the payload runs foreign code (its Drop); keep that inside a boundary too.
            let _ = catch_unwind(AssertUnwindSafe(move || drop(payload)));
            set_last_error(&tpi_core::bound_message(&format!(
                "internal error (caught panic): {message}"
            )));
            TpiStatus::Panic
        }
    }
}

/// The panic boundary for calls that return no status (the `*_free` functions and the static
/// string getters): a panic gives `fallback`. The last error is left untouched.
#[doc(hidden)]
pub fn run_infallible<T>(fallback: T, body: impl FnOnce() -> T) -> T {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(value) => value,
        Err(payload) => {
            let _ = catch_unwind(AssertUnwindSafe(move || drop(payload)));
            fallback
        }
    }
}

/// Wraps an entry point's body (which returns [`FfiResult`]) in the panic boundary.
macro_rules! ffi_boundary {
    ($($body:tt)*) => {
        $crate::boundary::run(move || -> $crate::boundary::FfiResult { $($body)* })
    };
}
pub(crate) use ffi_boundary;

/// A shared reference from a pointer argument, or [`TpiStatus::NullPointer`] naming it.
///
/// # Safety
/// `ptr` is NULL or points to a live `T` that nothing mutates during the returned lifetime.
pub unsafe fn try_ref<'a, T>(ptr: *const T, name: &str) -> FfiResult<&'a T> {
    check_pointer(ptr, name)?;
    // SAFETY: non-NULL and aligned (checked); the caller guarantees it points to a live T.
    unsafe { ptr.as_ref() }.ok_or_else(|| FfiError::null(name))
}

/// Checks a pointer for NULL and alignment.
fn check_pointer<T>(ptr: *const T, name: &str) -> FfiResult {
    if ptr.is_null() {
        return Err(FfiError::null(name));
    }
    if (ptr as usize) % align_of::<T>() != 0 {
        return Err(FfiError::invalid(format!(
            "{name} ({ptr:p}) is not aligned to {} bytes",
            align_of::<T>()
        )));
    }
    Ok(())
}

/// A slice from an array argument of `len` elements. A length of 0 gives an empty slice
/// whatever the pointer (NULL is fine then).
///
/// # Safety
/// When `len > 0`, `ptr` is NULL or points to `len` initialised `T`s that nothing mutates
/// during the returned lifetime.
pub unsafe fn try_slice<'a, T>(ptr: *const T, len: usize, name: &str) -> FfiResult<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    check_pointer(ptr, name)?;
    if len
        .checked_mul(size_of::<T>())
        .map_or(true, |bytes| bytes > isize::MAX as usize)
    {
        return Err(FfiError::invalid(format!(
            "the length {len} of {name} is impossibly large"
        )));
    }
    // SAFETY: non-NULL, aligned, size fits isize (checked); the caller guarantees `len`
    // initialised elements.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// A NUL-terminated UTF-8 string argument.
///
/// # Safety
/// `ptr` is NULL or points to a NUL-terminated string.
pub unsafe fn try_str<'a>(ptr: *const c_char, name: &str) -> FfiResult<&'a str> {
    check_pointer(ptr, name)?;
    // SAFETY: non-NULL; the caller guarantees NUL termination.
    let c = unsafe { std::ffi::CStr::from_ptr(ptr) };
    c.to_str()
        .map_err(|e| FfiError::invalid(format!("{name} is not UTF-8: {e}")))
}

/// An output pointer argument, checked for NULL and alignment, written without reading.
pub struct OutPtr<T> {
    ptr: *mut T,
}

impl<T> OutPtr<T> {
    /// Checks `ptr`.
    ///
    /// # Safety
    /// `ptr` is NULL or valid for writing one `T` until [`OutPtr::set`] is called.
    pub unsafe fn new(ptr: *mut T, name: &str) -> FfiResult<Self> {
        check_pointer(ptr.cast_const(), name)?;
        Ok(Self { ptr })
    }

    /// The checked pointer (non-NULL, aligned).
    pub fn as_ptr(&self) -> *mut T {
        self.ptr
    }

    /// Writes the value (the previous contents are not read nor dropped).
    pub fn set(&self, value: T) {
        // SAFETY: checked non-NULL and aligned in `new`; validity for writes is the contract
        // of `new`.
        unsafe { self.ptr.write(value) }
    }
}

impl<T> OutPtr<*mut T> {
    /// For the `out` argument of a create call: checks it and stores NULL right away, so the
    /// caller's handle stays NULL whatever happens next.
    ///
    /// # Safety
    /// As [`OutPtr::new`].
    pub unsafe fn handle(ptr: *mut *mut T, name: &str) -> FfiResult<Self> {
        // SAFETY: forwarded contract.
        let out = unsafe { OutPtr::new(ptr, name) }?;
        out.set(std::ptr::null_mut());
        Ok(out)
    }
}

impl<T: Handle> OutPtr<*mut T> {
    /// Moves `value` to the heap behind its type tag and hands the pointer to the caller, who
    /// owns it (and frees it with [`free_handle`]).
    pub fn set_boxed(&self, value: T) {
        let tagged = Box::new(Tagged { tag: T::TAG, value });
        self.set(Box::into_raw(tagged).cast::<T>());
    }
}

/// The opaque handle types. Every handle the library hands out points to a `Tagged` value:
/// its first 8 bytes are the tag of its kind while it is alive and [`FREED_TAG`] after its
/// `*_free` call, so that a handle of the wrong kind (or a freed one whose memory still
/// reads as freed) is refused with [`TpiStatus::InvalidHandle`] instead of being read as
/// something else. (A pointer that never came from this library cannot be detected.)
pub trait Handle: Sized {
    /// The live tag of this kind: 8 ASCII bytes, distinct per kind.
    const TAG: u64;
    /// The C type name, for messages.
    const C_NAME: &'static str;
}

/// The tag a handle's memory carries after its `*_free` call ("tpi:free").
pub const FREED_TAG: u64 = u64::from_le_bytes(*b"tpi:free");

/// The live tags of every kind, for naming a wrong kind in a message.
const KINDS: [(u64, &str); 6] = [
    (
        crate::surface::TpiSurface::TAG,
        crate::surface::TpiSurface::C_NAME,
    ),
    (
        crate::pattern::TpiPattern::TAG,
        crate::pattern::TpiPattern::C_NAME,
    ),
    (
        crate::discretisation::TpiDiscretisation::TAG,
        crate::discretisation::TpiDiscretisation::C_NAME,
    ),
    (
        crate::discrete_surface::TpiDiscreteSurface::TAG,
        crate::discrete_surface::TpiDiscreteSurface::C_NAME,
    ),
    (
        crate::fabrication::TpiFabrication::TAG,
        crate::fabrication::TpiFabrication::C_NAME,
    ),
    (
        crate::discrete_surface::TpiMeshChanges::TAG,
        crate::discrete_surface::TpiMeshChanges::C_NAME,
    ),
];

/// A handle's heap block: the tag first (fixed offset 0 whatever `T`), then the value.
#[repr(C)]
struct Tagged<T> {
    tag: u64,
    value: T,
}

/// Reads the tag of a non-NULL, 8-byte aligned handle pointer and checks it against `T`'s.
///
/// # Safety
/// `ptr` came from this library's `set_boxed` (of any handle kind), alive or freed.
unsafe fn check_tag<T: Handle>(ptr: *const T, name: &str) -> FfiResult {
    if ptr.is_null() {
        return Err(FfiError::null(name));
    }
    if (ptr as usize) % align_of::<Tagged<T>>() != 0 {
        return Err(FfiError::new(
            TpiStatus::InvalidHandle,
            format!("{name} ({ptr:p}) is not a {} handle: misaligned", T::C_NAME),
        ));
    }
    // SAFETY: every handle block starts with its u64 tag (repr(C) `Tagged`), aligned (checked);
    // volatile so the read is not assumed from an earlier one.
    let tag = unsafe { ptr.cast::<u64>().read_volatile() };
    if tag == T::TAG {
        return Ok(());
    }
    let message = if tag == FREED_TAG {
        format!("{name} is a {} handle that was already freed", T::C_NAME)
    } else if let Some((_, other)) = KINDS.iter().find(|(t, _)| *t == tag) {
        format!("{name} is a {other} handle, expected a {}", T::C_NAME)
    } else {
        format!("{name} is not a live {} handle", T::C_NAME)
    };
    Err(FfiError::new(TpiStatus::InvalidHandle, message))
}

/// The value behind a handle argument: [`TpiStatus::NullPointer`] for NULL,
/// [`TpiStatus::InvalidHandle`] for a handle of another kind or a freed one.
///
/// # Safety
/// `ptr` is NULL or a handle from this library (see `check_tag`); a live one of kind `T` is
/// not freed during the returned lifetime.
pub unsafe fn try_handle<'a, T: Handle>(ptr: *const T, name: &str) -> FfiResult<&'a T> {
    // SAFETY: forwarded contract.
    unsafe { check_tag(ptr, name) }?;
    // SAFETY: the tag says this is a live `Tagged<T>` made by `set_boxed`.
    Ok(unsafe { &(*ptr.cast::<Tagged<T>>()).value })
}

/// Frees a handle from `set_boxed`. NULL, a handle of another kind and a freed handle are
/// left alone (a `*_free` call returns no status); the tag is overwritten with
/// [`FREED_TAG`] before the memory is released.
///
/// # Safety
/// `ptr` is NULL or a handle from this library; the caller gives up a live one of kind `T`.
pub unsafe fn free_handle<T: Handle>(ptr: *mut T) {
    // SAFETY: forwarded contract.
    if unsafe { check_tag(ptr.cast_const(), "handle") }.is_err() {
        return;
    }
    let block = ptr.cast::<Tagged<T>>();
    // SAFETY: a live `Tagged<T>` (tag checked) owned by the caller, handed back here.
    unsafe {
        std::ptr::addr_of_mut!((*block).tag).write_volatile(FREED_TAG);
        drop(Box::from_raw(block));
    }
}

/// Stores `len` through `needed` (if not NULL) and checks `out`/`capacity` against it: the
/// common first half of every copy-out call. Returns the buffer to fill, or `None` when there
/// is nothing to copy.
///
/// # Safety
/// `needed` is NULL or valid for writing a `usize`; `out` is NULL or valid for writing
/// `capacity` elements of `T`.
unsafe fn prepare_copy<'a, T>(
    len: usize,
    out: *mut T,
    capacity: usize,
    needed: *mut usize,
    name: &str,
) -> FfiResult<Option<&'a mut [T]>> {
    if !needed.is_null() {
        // SAFETY: forwarded contract.
        unsafe { OutPtr::new(needed, "needed") }?.set(len);
    }
    if capacity > 0 || len > 0 {
        if out.is_null() && capacity > 0 {
            return Err(FfiError::null(name));
        }
        if capacity < len {
            return Err(FfiError::new(
                TpiStatus::BufferTooSmall,
                format!("{name} has capacity {capacity}; {len} elements are needed"),
            ));
        }
        check_pointer(out.cast_const(), name)?;
    }
    if len == 0 {
        return Ok(None);
    }
    // SAFETY: non-NULL and aligned (checked), capacity >= len; the caller guarantees
    // `capacity` writable elements. The elements are `Copy` plain data, so viewing possibly
    // uninitialised memory as a slice we only write to is the same as `ptr::write`.
    Ok(Some(unsafe { std::slice::from_raw_parts_mut(out, len) }))
}

/// The checks of [`copy_out`] for `len` elements, without copying: stores `len` through
/// `needed` and fails as `copy_out` would. Lets a call check the capacity before computing
/// the data.
///
/// # Safety
/// As [`copy_out`].
pub unsafe fn check_copy_out<T>(
    len: usize,
    out: *mut T,
    capacity: usize,
    needed: *mut usize,
    name: &str,
) -> FfiResult {
    // SAFETY: forwarded contract.
    unsafe { prepare_copy(len, out, capacity, needed, name) }.map(|_| ())
}

/// The copy-out convention: `*needed = data.len()` (if `needed` is not NULL); if `capacity`
/// is smaller, [`TpiStatus::BufferTooSmall`] and nothing is written; otherwise the data is
/// copied to `out`. `out` may be NULL only when `capacity` is 0.
///
/// # Safety
/// `needed` is NULL or valid for writing a `usize`; `out` is NULL or valid for writing
/// `capacity` elements of `T`.
pub unsafe fn copy_out<T: Copy>(
    data: &[T],
    out: *mut T,
    capacity: usize,
    needed: *mut usize,
    name: &str,
) -> FfiResult {
    // SAFETY: forwarded contract.
    if let Some(buffer) = unsafe { prepare_copy(data.len(), out, capacity, needed, name) }? {
        buffer.copy_from_slice(data);
    }
    Ok(())
}

/// [`copy_out`] for text: copies the bytes of `text` and a terminating NUL; the needed size
/// counts the NUL.
///
/// # Safety
/// As [`copy_out`].
pub unsafe fn copy_out_str(
    text: &str,
    out: *mut c_char,
    capacity: usize,
    needed: *mut usize,
    name: &str,
) -> FfiResult {
    let bytes = text.as_bytes();
    let len = bytes.len() + 1;
    // SAFETY: forwarded contract.
    if let Some(buffer) = unsafe { prepare_copy(len, out, capacity, needed, name) }? {
        let (body, nul) = buffer.split_at_mut(bytes.len());
        for (dst, &src) in body.iter_mut().zip(bytes) {
            *dst = src as c_char;
        }
        for dst in nul {
            *dst = 0;
        }
    }
    Ok(())
}

/// Checks that `value` is finite, naming the argument.
pub fn finite(name: &str, value: f64) -> FfiResult<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(FfiError::new(
            TpiStatus::NonFinite,
            format!("{name} is not a finite number ({value})"),
        ))
    }
}

/// Pairs of doubles from a flat array of `len` doubles (which must be even).
///
/// # Safety
/// As [`try_slice`].
pub unsafe fn try_pairs<'a>(ptr: *const f64, len: usize, name: &str) -> FfiResult<&'a [[f64; 2]]> {
    if len % 2 != 0 {
        return Err(FfiError::invalid(format!(
            "{name} has {len} doubles; (u, v) pairs need an even number"
        )));
    }
    // SAFETY: forwarded contract; checks NULL, alignment (that of f64, which [f64; 2] shares)
    // and the total size.
    let flat = unsafe { try_slice(ptr, len, name) }?;
    // SAFETY: [f64; 2] has the size of two f64 and the alignment of one; `flat` holds exactly
    // len / 2 pairs.
    Ok(unsafe { std::slice::from_raw_parts(flat.as_ptr().cast::<[f64; 2]>(), len / 2) })
}

/// A `u32` flag argument that must be 0 or 1.
pub fn flag(name: &str, value: u32) -> FfiResult<bool> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(FfiError::invalid(format!(
            "{name} is {value}; it must be 0 or 1"
        ))),
    }
}

/// [`TpiStatus::IndexOutOfRange`] for `index` in a collection of `len`.
pub fn index_error(what: &str, index: usize, len: usize) -> FfiError {
    FfiError::new(
        TpiStatus::IndexOutOfRange,
        format!("{what} {index} is out of range (there are {len})"),
    )
}
