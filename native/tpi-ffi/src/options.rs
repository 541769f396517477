//! Discretisation options as a C struct that can grow.

use std::mem::size_of;

use tpi_core::{DiscretiseOptions, PlaneMode};

use crate::boundary::{ffi_boundary, finite, flag, FfiError, FfiResult, TpiStatus};

/// Size in bytes of the first version of `TpiOptions`: the smallest `struct_size` accepted.
pub const TPI_OPTIONS_SIZE_V1: u32 = 40;

/// Size in bytes of the second version of `TpiOptions` (adds `plane_mode`).
pub const TPI_OPTIONS_SIZE_V2: u32 = 48;

/// `plane_mode`: every facet in the exact tangent plane at its seed.
pub const TPI_PLANES_EXACT: u32 = 0;

/// `plane_mode`: exact tangent planes, except where they cannot give a valid facet on a
/// surface that is not convex everywhere: there a few planes are tilted by at most 5
/// degrees (`tpi_discretisation_planes` gives each facet's plane).
pub const TPI_PLANES_ADJUSTED: u32 = 1;

/// Options of a discretisation.
///
/// Growth: fields are only ever appended. `struct_size` must hold `sizeof(TpiOptions)` as the
/// caller compiled it; the library reads (and `tpi_options_default` writes) only that many
/// bytes, and gives fields beyond them their defaults. So a program compiled against an
/// older header keeps working with a newer library. Always start from `tpi_options_default`:
///
/// ```c
/// TpiOptions options;
/// options.struct_size = sizeof options;
/// tpi_options_default(&options);
/// options.envelope_repair = 0;
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TpiOptions {
    /// sizeof(TpiOptions) as compiled by the caller; at least TPI_OPTIONS_SIZE_V1.
    pub struct_size: u32,
    /// 1: verify and repair the neighbours against the envelope of tangent planes where the
    /// Gaussian curvature is positive; 0: the paper's method alone. Default value: 1.
    pub envelope_repair: u32,
    /// 1: compute the quality report and the per-facet flags; 0: skip them
    /// (`tpi_discretisation_quality` then gives TPI_STATUS_UNAVAILABLE). Default value: 1.
    pub quality_report: u32,
    /// Always 0 (padding, kept explicit for other languages).
    pub reserved: u32,
    /// A facet vertex farther than this many times its dual triangle's longest side from the
    /// triangle's centroid is ill-conditioned (nearly parallel planes) and replaced by a
    /// stand-in, with a diagnostic. Finite, > 0. Default value: 8.
    pub far_vertex_factor: f64,
    /// Vertices closer than this times the bounding-box diagonal are welded. Finite, >= 0.
    /// Default value: 1e-10.
    pub weld_tolerance: f64,
    /// A point is flat when |K| <= flat_tolerance * max(k1^2, k2^2). Finite, >= 0.
    /// Default value: 1e-6.
    pub flat_tolerance: f64,
    /// TPI_PLANES_EXACT or TPI_PLANES_ADJUSTED (since TPI_OPTIONS_SIZE_V2). Default value:
    /// TPI_PLANES_EXACT.
    pub plane_mode: u32,
    /// Always 0 (padding, kept explicit for other languages).
    pub reserved2: u32,
}

impl TpiOptions {
    /// The defaults, with `struct_size` set to this library's size.
    pub fn defaults() -> Self {
        let d = DiscretiseOptions::default();
        Self {
            struct_size: size_of::<TpiOptions>() as u32,
            envelope_repair: u32::from(d.envelope_repair),
            quality_report: u32::from(d.quality_report),
            reserved: 0,
            far_vertex_factor: d.far_vertex_factor,
            weld_tolerance: d.weld_tolerance,
            flat_tolerance: d.flat_tolerance,
            plane_mode: match d.planes {
                PlaneMode::Exact => TPI_PLANES_EXACT,
                PlaneMode::Adjusted => TPI_PLANES_ADJUSTED,
            },
            reserved2: 0,
        }
    }

    /// Validates and converts to the core's options.
    pub fn to_core(&self) -> FfiResult<DiscretiseOptions> {
        let far_vertex_factor = finite("options.far_vertex_factor", self.far_vertex_factor)?;
        if far_vertex_factor <= 0.0 {
            return Err(FfiError::invalid(format!(
                "options.far_vertex_factor is {far_vertex_factor}; it must be > 0"
            )));
        }
        let weld_tolerance = finite("options.weld_tolerance", self.weld_tolerance)?;
        let flat_tolerance = finite("options.flat_tolerance", self.flat_tolerance)?;
        for (name, value) in [
            ("options.weld_tolerance", weld_tolerance),
            ("options.flat_tolerance", flat_tolerance),
        ] {
            if value < 0.0 {
                return Err(FfiError::invalid(format!(
                    "{name} is {value}; it must be >= 0"
                )));
            }
        }
        for (name, value) in [
            ("options.reserved", self.reserved),
            ("options.reserved2", self.reserved2),
        ] {
            if value != 0 {
                return Err(FfiError::invalid(format!(
                    "{name} is {value}; it must be 0"
                )));
            }
        }
        let planes = match self.plane_mode {
            TPI_PLANES_EXACT => PlaneMode::Exact,
            TPI_PLANES_ADJUSTED => PlaneMode::Adjusted,
            other => {
                return Err(FfiError::invalid(format!(
                    "options.plane_mode is {other}; it must be TPI_PLANES_EXACT (0) or TPI_PLANES_ADJUSTED (1)"
                )))
            }
        };
        Ok(DiscretiseOptions {
            envelope_repair: flag("options.envelope_repair", self.envelope_repair)?,
            quality_report: flag("options.quality_report", self.quality_report)?,
            far_vertex_factor,
            weld_tolerance,
            flat_tolerance,
            planes,
        })
    }
}

/// Reads the caller's `struct_size` and checks it.
///
/// # Safety
/// `ptr` is non-NULL, aligned, and points to at least 4 readable bytes.
unsafe fn struct_size(ptr: *const TpiOptions) -> FfiResult<usize> {
    // SAFETY: struct_size is the first field, at offset 0 (repr(C)).
    let size = unsafe { ptr.cast::<u32>().read() };
    if size < TPI_OPTIONS_SIZE_V1 {
        return Err(FfiError::invalid(format!(
            "options.struct_size is {size}; set it to sizeof(TpiOptions) (at least {TPI_OPTIONS_SIZE_V1})"
        )));
    }
    Ok((size as usize).min(size_of::<TpiOptions>()))
}

fn check_pointer(ptr: *const TpiOptions) -> FfiResult {
    if ptr.is_null() {
        return Err(FfiError::null("options"));
    }
    if (ptr as usize) % std::mem::align_of::<TpiOptions>() != 0 {
        return Err(FfiError::invalid("options is not aligned to 8 bytes"));
    }
    Ok(())
}

/// Reads options given by a caller: NULL means the defaults; otherwise `struct_size` bytes
/// are read and later fields keep their defaults.
///
/// # Safety
/// `ptr` is NULL or points to `struct_size` readable bytes starting with a `TpiOptions`.
pub unsafe fn read_options(ptr: *const TpiOptions) -> FfiResult<DiscretiseOptions> {
    if ptr.is_null() {
        return Ok(DiscretiseOptions::default());
    }
    check_pointer(ptr)?;
    // SAFETY: the caller's contract.
    let size = unsafe { struct_size(ptr) }?;
    let mut options = TpiOptions::defaults();
    // SAFETY: `size` bytes are readable (contract) and fit in `options` (clamped); the
    // fields are plain numbers, valid for any bytes.
    unsafe {
        std::ptr::copy_nonoverlapping(
            ptr.cast::<u8>(),
            (&mut options as *mut TpiOptions).cast::<u8>(),
            size,
        )
    };
    options.to_core()
}

/// Fills `*options` with the defaults (see each field). `options->struct_size` must be set
/// to sizeof(TpiOptions) first; only that many bytes are written, and `struct_size` is left
/// as it is.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (`struct_size` smaller than
/// TPI_OPTIONS_SIZE_V1, e.g. not set).
///
/// # Safety
/// `options` is NULL or valid for reading and writing `options->struct_size` bytes.
#[no_mangle]
pub unsafe extern "C" fn tpi_options_default(options: *mut TpiOptions) -> TpiStatus {
    ffi_boundary! {
        check_pointer(options)?;
        // SAFETY: the caller's contract.
        let size = unsafe { struct_size(options) }?;
        let mut defaults = TpiOptions::defaults();
        // SAFETY: struct_size is the first field; `options` holds at least 4 bytes.
        defaults.struct_size = unsafe { options.cast::<u32>().read() };
        // SAFETY: `size` bytes are writable (contract) and readable from `defaults`.
        unsafe { std::ptr::copy_nonoverlapping((&defaults as *const TpiOptions).cast::<u8>(), options.cast::<u8>(), size) };
        Ok(())
    }
}
