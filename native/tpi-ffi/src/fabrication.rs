//! Fabrication: panel solids with mitred joints, cleat slots, flat parts nested on sheets,
//! and the workshop's files as text (docs/fabrication.md). Converts and forwards to
//! `tpi_core::fabricate`.

use std::ffi::c_char;
use std::sync::OnceLock;

use tpi_core::{
    fabricate, FabricateOptions, Fabrication, FabricationError, PanelSide, SlotPlan,
    ToolpathOptions, Units,
};

use crate::boundary::{
    copy_out_str, ffi_boundary, try_handle, FfiError, FfiResult, Handle, OutPtr, TpiStatus,
};
use crate::discretisation::TpiDiscretisation;

/// `side` of `tpi_fabricate`: thicken towards the centres of curvature (the concave side).
pub const TPI_SIDE_INSIDE: u32 = 0;
/// `side` of `tpi_fabricate`: thicken away from the centres of curvature.
pub const TPI_SIDE_OUTSIDE: u32 = 1;

/// File of `tpi_fabrication_file`: panels.json (the contract in docs/fabrication.md).
pub const TPI_FILE_PANELS_JSON: u32 = 0;
/// File of `tpi_fabrication_file`: panels.obj, one closed polyhedron per panel and cleat.
pub const TPI_FILE_PANELS_OBJ: u32 = 1;
/// File of `tpi_fabrication_file`: sheets.svg.
pub const TPI_FILE_SHEETS_SVG: u32 = 2;
/// File of `tpi_fabrication_file`: sheets.dxf (ASCII DXF R2000, `$INSUNITS` from the surface's
/// units, `tpi_surface_with_units`; metres for a unitless surface).
pub const TPI_FILE_SHEETS_DXF: u32 = 3;
/// File of `tpi_fabrication_file`: bevels.csv.
pub const TPI_FILE_BEVELS_CSV: u32 = 4;

/// Fabricated panels, cleats and sheets. Immutable.
pub struct TpiFabrication {
    fab: Fabrication,
    files: [OnceLock<String>; 5],
}

impl Handle for TpiFabrication {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:fabr");
    const C_NAME: &'static str = "TpiFabrication";
}

fn fabrication_error(e: &FabricationError) -> FfiError {
    let status = match e {
        FabricationError::InvalidOption { value, .. } if !value.is_finite() => TpiStatus::NonFinite,
        FabricationError::BadMesh { .. } => TpiStatus::Degenerate,
        _ => TpiStatus::InvalidArgument,
    };
    FfiError::new(status, e.to_string())
}

/// A fabrication handle argument.
///
/// # Safety
/// `ptr` is NULL or a live handle.
unsafe fn handle<'a>(ptr: *const TpiFabrication) -> FfiResult<&'a TpiFabrication> {
    // SAFETY: forwarded contract.
    unsafe { try_handle(ptr, "fabrication") }
}

/// Builds the panels of `discretisation`: thickness `thickness` (> 0, below the limit the
/// mesh allows), `side` TPI_SIDE_INSIDE or TPI_SIDE_OUTSIDE, `slots_per_edge` cleat slots
/// evenly along every interior edge (0 for none; default slot size 4T x 2T; slots that do
/// not fit are left out), parts nested on sheets of `sheet_width` x `sheet_height` kept `gap`
/// apart. Lengths in model units.
///
/// On success `*out` is a new handle (free with `tpi_fabrication_free`), else NULL.
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE (a NaN or infinite length),
/// TPI_STATUS_INVALID_ARGUMENT (a length <= 0, a thickness for which no panel solid exists, a part
/// larger than the sheet, `side` not 0 or 1), TPI_STATUS_DEGENERATE (a facet that cannot be
/// a panel). The message names the option, or the panel.
///
/// # Safety
/// `discretisation` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpi_fabricate(
    discretisation: *const TpiDiscretisation,
    thickness: f64,
    side: u32,
    slots_per_edge: u32,
    sheet_width: f64,
    sheet_height: f64,
    gap: f64,
    out: *mut *mut TpiFabrication,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let d = unsafe { try_handle(discretisation, "discretisation") }?;
        let side = match side {
            TPI_SIDE_INSIDE => PanelSide::Inside,
            TPI_SIDE_OUTSIDE => PanelSide::Outside,
            other => return Err(FfiError::invalid(format!("side = {other}: expected 0 (inside) or 1 (outside)"))),
        };
        let options = FabricateOptions {
            thickness,
            side,
            slots: if slots_per_edge == 0 { SlotPlan::None } else { SlotPlan::Even(slots_per_edge) },
            sheet: [sheet_width, sheet_height],
            gap,
            ..FabricateOptions::default()
        };
        let fab = fabricate(d.result(), &options).map_err(|e| fabrication_error(&e))?;
        out.set_boxed(TpiFabrication { fab, files: Default::default() });
        Ok(())
    }
}

/// Frees a fabrication. NULL is allowed and does nothing.
///
/// # Safety
/// `fabrication` is NULL or a handle that was not freed yet, and no other call is using it.
#[no_mangle]
pub unsafe extern "C" fn tpi_fabrication_free(fabrication: *mut TpiFabrication) {
    crate::boundary::run_infallible((), || {
        // SAFETY: the caller hands back ownership of a handle from this library.
        unsafe { crate::boundary::free_handle(fabrication) }
    })
}

/// Stores the number of panels (one per facet) in `*panels` and of sheets in `*sheets`.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `fabrication` is NULL or a live handle; `panels` and `sheets` are NULL or valid for
/// writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_fabrication_counts(
    fabrication: *const TpiFabrication,
    panels: *mut usize,
    sheets: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let f = unsafe { handle(fabrication) }?;
        let panels = unsafe { OutPtr::new(panels, "panels") }?;
        let sheets = unsafe { OutPtr::new(sheets, "sheets") }?;
        panels.set(f.fab.panels.len());
        sheets.set(f.fab.sheets.len());
        Ok(())
    }
}

/// Copies one of the files (`file`: a TPI_FILE_* number) as text, NUL terminated.
/// Copy-out convention; `*needed` counts the NUL.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (an unknown `file`),
/// TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `fabrication` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// chars; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_fabrication_file(
    fabrication: *const TpiFabrication,
    file: u32,
    out: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let f = unsafe { handle(fabrication) }?;
        let Some(cell) = f.files.get(file as usize) else {
            return Err(FfiError::invalid(format!("file = {file}: expected 0 to 4 (TPI_FILE_*)")));
        };
        let text = match cell.get() {
            Some(text) => text,
            None => {
                let text = match file {
                    TPI_FILE_PANELS_JSON => f.fab.to_json(),
                    TPI_FILE_PANELS_OBJ => f.fab.to_obj(),
                    TPI_FILE_SHEETS_SVG => f.fab.sheets_svg(),
                    TPI_FILE_SHEETS_DXF => f
                        .fab
                        .sheets_dxf(f.fab.units.unwrap_or(Units::Metres))
                        .map_err(|e| fabrication_error(&e))?,
                    _ => f.fab.bevels_csv(),
                };
                cell.get_or_init(|| text)
            }
        };
        unsafe { copy_out_str(text, out, capacity, needed, "out") }
    }
}

/// Copies the G-code for a 3-axis router with a tool of `tool_diameter` (model units; at
/// most the gap), NUL terminated: one program per sheet (docs/fabrication.md). Copy-out
/// convention; `*needed` counts the NUL. Not cached: a call that only asks for the size
/// computes the text too.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_ARGUMENT (a
/// diameter <= 0 or larger than the gap), TPI_STATUS_BUFFER_TOO_SMALL.
///
/// # Safety
/// `fabrication` is NULL or a live handle; `out` is NULL or valid for writing `capacity`
/// chars; `needed` is NULL or valid for writing a `size_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_fabrication_gcode(
    fabrication: *const TpiFabrication,
    tool_diameter: f64,
    out: *mut c_char,
    capacity: usize,
    needed: *mut usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let f = unsafe { handle(fabrication) }?;
        let text = f
            .fab
            .gcode(&ToolpathOptions { tool_diameter, ..ToolpathOptions::default() })
            .map_err(|e| fabrication_error(&e))?;
        unsafe { copy_out_str(&text, out, capacity, needed, "out") }
    }
}
