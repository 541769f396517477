//! Surface handles: NURBS from RhinoCommon's arrays, the analytic surfaces, sampling.

use glam::DVec3;
use tpi_core::SurfaceModel;
use tpi_core::{
    AnalyticSurface, LocalGeometry, NurbsSurface, Polysurface, Surface, TpiError, Trim, Units,
};

use crate::boundary::{
    check_copy_out, copy_out, ffi_boundary, finite, try_handle, try_pairs, try_slice, FfiError,
    OutPtr, TpiStatus,
};

/// A surface: a NURBS surface or an analytic one. Immutable once created.
///
/// Created by the `tpi_surface_new_*` calls, freed by `tpi_surface_free`. May be used from
/// several threads at once.
pub struct TpiSurface {
    pub(crate) model: SurfaceModel,
}

impl crate::boundary::Handle for TpiSurface {
    const TAG: u64 = u64::from_le_bytes(*b"tpi:surf");
    const C_NAME: &'static str = "TpiSurface";
}

/// The parameter domain [u_min, u_max] x [v_min, v_max] of a surface.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TpiDomain {
    /// Start of the u interval.
    pub u_min: f64,
    /// End of the u interval.
    pub u_max: f64,
    /// Start of the v interval.
    pub v_min: f64,
    /// End of the v interval.
    pub v_max: f64,
}

/// Point, normal, principal curvatures and principal directions at one (u, v).
///
/// The normal is Su x Sv normalised (as RhinoCommon's `NormalAt`). Curvatures are signed
/// relative to the normal: k > 0 where the surface bends towards it; k1 <= k2. (d1, d2,
/// normal) is a right-handed orthonormal frame. Where Su x Sv vanishes (a pole, a collapsed
/// edge) `regular` is 0, the normal is a fallback and the curvatures are 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TpiSample {
    /// Surface point (x, y, z).
    pub point: [f64; 3],
    /// Unit normal.
    pub normal: [f64; 3],
    /// Principal curvatures k1 <= k2.
    pub curvatures: [f64; 2],
    /// Unit principal direction of k1.
    pub d1: [f64; 3],
    /// Unit principal direction of k2.
    pub d2: [f64; 3],
    /// 1 where the surface is regular at this point, 0 where Su x Sv vanishes.
    pub regular: u32,
    /// Always 0 (padding, kept explicit for other languages).
    pub reserved: u32,
}

impl TpiSample {
    fn from_geometry(g: &LocalGeometry) -> Self {
        Self {
            point: g.point.to_array(),
            normal: g.normal.to_array(),
            curvatures: [g.k1, g.k2],
            d1: g.d1.to_array(),
            d2: g.d2.to_array(),
            regular: u32::from(g.regular),
            reserved: 0,
        }
    }
}

/// Stores a new surface handle through `out`, or the error.
fn create(
    out: *mut *mut TpiSurface,
    build: impl FnOnce() -> Result<SurfaceModel, FfiError>,
) -> Result<(), FfiError> {
    // SAFETY: `out` is NULL or valid for writes (the contract of every create call).
    let out = unsafe { OutPtr::handle(out, "out") }?;
    let model = build()?;
    out.set_boxed(TpiSurface { model });
    Ok(())
}

fn analytic(result: Result<AnalyticSurface, TpiError>) -> Result<SurfaceModel, FfiError> {
    Ok(SurfaceModel::from(result?))
}

/// Creates a NURBS surface from the arrays RhinoCommon hands over.
///
/// - `degree_u`, `degree_v`: degrees (1 to 11, Rhino's limit).
/// - `count_u`, `count_v`: control point counts (count > degree).
/// - `knots_u` (`knots_u_len` doubles) and `knots_v`: knot vectors in **Rhino's convention**,
///   count + degree - 1 knots each, as `NurbsSurface.KnotsU`/`KnotsV` give them; the domain is
///   [knots[degree - 1], knots[count - 1]]. (The textbook convention with two more knots,
///   count + degree + 1, is recognised by its length and accepted too.)
/// - `points` (`points_len` doubles): the Euclidean control points, u-major: point (i, j) is
///   `points[3 * (i * count_v + j) + 0..3]`, i.e. `Points.GetControlPoint(i, j).Location`;
///   `points_len` must be 3 * count_u * count_v.
/// - `weights` (`weights_len` doubles): the weights in the same order, all > 0, or NULL (with
///   `weights_len` 0) for a non-rational surface. The points are **not** premultiplied.
///
/// On success stores a new handle in `*out`, which the caller frees with `tpi_surface_free`;
/// on failure `*out` is NULL. Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT
/// (a length not a multiple of 3, weights_len without weights), TPI_STATUS_NON_FINITE (a NaN
/// or infinite knot, coordinate or weight), TPI_STATUS_INVALID_NURBS (everything else wrong
/// with the data, e.g. a wrong number of knots).
///
/// # Safety
/// Each array pointer is NULL or valid for reading its length in doubles; `out` is NULL or
/// valid for writing a pointer.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpi_surface_new_nurbs(
    degree_u: usize,
    degree_v: usize,
    count_u: usize,
    count_v: usize,
    knots_u: *const f64,
    knots_u_len: usize,
    knots_v: *const f64,
    knots_v_len: usize,
    points: *const f64,
    points_len: usize,
    weights: *const f64,
    weights_len: usize,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! {
        create(out, || {
            // SAFETY: the caller's contract for each array.
            let knots_u = unsafe { try_slice(knots_u, knots_u_len, "knots_u") }?;
            let knots_v = unsafe { try_slice(knots_v, knots_v_len, "knots_v") }?;
            let flat = unsafe { try_slice(points, points_len, "points") }?;
            if flat.len() % 3 != 0 {
                return Err(FfiError::invalid(format!(
                    "points has {points_len} doubles, which is not a multiple of 3 (x, y, z per control point)"
                )));
            }
            let points: Vec<DVec3> = flat.chunks_exact(3).map(DVec3::from_slice).collect();
            let weights = if weights.is_null() {
                if weights_len != 0 {
                    return Err(FfiError::invalid(format!(
                        "weights is NULL but weights_len is {weights_len}; pass 0 for a non-rational surface"
                    )));
                }
                None
            } else {
                // SAFETY: the caller's contract.
                Some(unsafe { try_slice(weights, weights_len, "weights") }?)
            };
            let surface = NurbsSurface::new([degree_u, degree_v], [count_u, count_v], knots_u, knots_v, &points, weights)
                .map_err(|e| FfiError::nurbs(&e))?;
            Ok(SurfaceModel::from(surface))
        })
    }
}

/// Creates the elliptic paraboloid z = a x^2 + b y^2 over [x0, x1] x [y0, y1] (u = x,
/// v = y); a and b non-zero with the same sign.
///
/// On success `*out` is a new handle (free with `tpi_surface_free`), else NULL. Errors:
/// TPI_STATUS_NULL_POINTER, TPI_STATUS_NON_FINITE, TPI_STATUS_INVALID_ARGUMENT.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_elliptic_paraboloid(
    a: f64,
    b: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::elliptic_paraboloid(a, b, [x0, x1], [y0, y1]))) }
}

/// Creates the hyperbolic paraboloid z = a x^2 - b y^2 over [x0, x1] x [y0, y1]; a and b
/// non-zero with the same sign.
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_hyperbolic_paraboloid(
    a: f64,
    b: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::hyperbolic_paraboloid(a, b, [x0, x1], [y0, y1]))) }
}

/// Creates the sphere cap z = sqrt(r^2 - x^2 - y^2) over [x0, x1] x [y0, y1], which must lie
/// strictly inside the disc of radius r.
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_sphere_cap(
    radius: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::sphere_cap(radius, [x0, x1], [y0, y1]))) }
}

/// Creates the sphere cap over the centred square [-h, h]^2 (needs h > 0 and
/// h * sqrt(2) < radius).
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_sphere_cap_square(
    radius: f64,
    half_width: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::sphere_cap_square(radius, half_width))) }
}

/// Creates the ellipsoid cap z = c sqrt(1 - x^2/a^2 - y^2/b^2) over [x0, x1] x [y0, y1],
/// strictly inside the ellipse; a, b, c > 0.
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpi_surface_new_ellipsoid_cap(
    a: f64,
    b: f64,
    c: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::ellipsoid_cap(a, b, c, [x0, x1], [y0, y1]))) }
}

/// Creates the egg-crate z = A sin(x) sin(y) over [x0, x1] x [y0, y1]; A non-zero.
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_egg_crate(
    amplitude: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::egg_crate(amplitude, [x0, x1], [y0, y1]))) }
}

/// Creates the cylinder z = sqrt(r^2 - x^2) over [x0, x1] x [y0, y1] with |x| < r. Its
/// Gaussian curvature is 0 everywhere and its rulings run along y: it is discretised as
/// strips between the lines where the tangent planes of neighbouring rulings meet
/// (TPI_DIAGNOSTIC_KIND_RULING_STRIPS).
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_cylinder(
    radius: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::cylinder(radius, [x0, x1], [y0, y1]))) }
}

/// Creates the plane z = p x + q y + c0 over [x0, x1] x [y0, y1]. Its tangent planes all
/// coincide, so its facets are the Voronoi cells of their seeds in the plane
/// (TPI_DIAGNOSTIC_KIND_COINCIDENT_PLANES).
///
/// On success `*out` is a new handle, else NULL. Errors as
/// `tpi_surface_new_elliptic_paraboloid`.
///
/// # Safety
/// `out` is NULL or valid for writing a pointer.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpi_surface_new_plane(
    p: f64,
    q: f64,
    c0: f64,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! { create(out, || analytic(AnalyticSurface::plane(p, q, c0, [x0, x1], [y0, y1]))) }
}

/// Frees a surface. NULL is allowed and does nothing. Handles created from this surface
/// (patterns do not depend on it; discretisations and discrete surfaces hold their own copy)
/// stay valid.
///
/// # Safety
/// `surface` is NULL or a handle from a `tpi_surface_new_*` call that was not freed yet, and
/// no other call is using it.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_free(surface: *mut TpiSurface) {
    crate::boundary::run_infallible((), || {
        // SAFETY: the caller hands back ownership of a handle from this library.
        unsafe { crate::boundary::free_handle(surface) }
    })
}

/// Stores the surface's parameter domain in `*out`.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `surface` is NULL or a live handle; `out` is NULL or valid for writing a `TpiDomain`.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_domain(
    surface: *const TpiSurface,
    out: *mut TpiDomain,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let surface = unsafe { try_handle(surface, "surface") }?;
        let out = unsafe { OutPtr::new(out, "out") }?;
        let d = surface.model.domain();
        out.set(TpiDomain { u_min: d.u.min, u_max: d.u.max, v_min: d.v.min, v_max: d.v.max });
        Ok(())
    }
}

/// Evaluates the surface at `uv_len / 2` parameter pairs: `uv` holds u0, v0, u1, v1, ... in
/// the surface's own domain (not normalised). Writes one `TpiSample` per pair to `out`, which
/// has room for `out_capacity` samples.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (odd `uv_len`),
/// TPI_STATUS_BUFFER_TOO_SMALL (`out_capacity < uv_len / 2`; nothing written),
/// TPI_STATUS_NON_FINITE (a NaN or infinite parameter), TPI_STATUS_OUT_OF_DOMAIN (a pair
/// outside the domain). On an error nothing is written to `out`; the message names the first
/// offending pair.
///
/// # Safety
/// `surface` is NULL or a live handle; `uv` is NULL or valid for reading `uv_len` doubles;
/// `out` is NULL or valid for writing `out_capacity` samples.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_evaluate(
    surface: *const TpiSurface,
    uv: *const f64,
    uv_len: usize,
    out: *mut TpiSample,
    out_capacity: usize,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let surface = unsafe { try_handle(surface, "surface") }?;
        let pairs = unsafe { try_pairs(uv, uv_len, "uv") }?;
        // Capacity first, so that a too-small buffer costs no evaluation.
        unsafe { check_copy_out(pairs.len(), out, out_capacity, std::ptr::null_mut(), "out") }?;
        let domain = surface.model.domain();
        for (index, &[u, v]) in pairs.iter().enumerate() {
            finite(&format!("uv[{}]", 2 * index), u)?;
            finite(&format!("uv[{}]", 2 * index + 1), v)?;
            domain.check(u, v).map_err(|e| FfiError::new(TpiStatus::OutOfDomain, format!("pair {index}: {e}")))?;
        }
        let samples: Vec<TpiSample> = pairs
            .iter()
            .map(|&[u, v]| TpiSample::from_geometry(&LocalGeometry::from_derivatives(&surface.model.evaluate(u, v))))
            .collect();
        // SAFETY: the caller's contract.
        unsafe { copy_out(&samples, out, out_capacity, std::ptr::null_mut(), "out") }
    }
}

/// Units of `tpi_surface_with_units` and `tpi_surface_units`: unitless (the default of every
/// new surface). The values are those of Rhino's `UnitSystem` (RhinoCommon and rhino3dm), so
/// that `(int)doc.ModelUnitSystem` passes through.
pub const TPI_UNITS_NONE: i32 = 0;
/// Microns (Rhino's `UnitSystem.Microns`).
pub const TPI_UNITS_MICRONS: i32 = 1;
/// Millimetres (`UnitSystem.Millimeters`).
pub const TPI_UNITS_MILLIMETERS: i32 = 2;
/// Centimetres (`UnitSystem.Centimeters`).
pub const TPI_UNITS_CENTIMETERS: i32 = 3;
/// Metres (`UnitSystem.Meters`).
pub const TPI_UNITS_METERS: i32 = 4;
/// Kilometres (`UnitSystem.Kilometers`).
pub const TPI_UNITS_KILOMETERS: i32 = 5;
/// Inches (`UnitSystem.Inches`).
pub const TPI_UNITS_INCHES: i32 = 8;
/// Feet (`UnitSystem.Feet`).
pub const TPI_UNITS_FEET: i32 = 9;
/// Miles (`UnitSystem.Miles`).
pub const TPI_UNITS_MILES: i32 = 10;
/// Yards (`UnitSystem.Yards`).
pub const TPI_UNITS_YARDS: i32 = 19;

const UNIT_CODES: [(i32, Units); 9] = [
    (TPI_UNITS_MICRONS, Units::Microns),
    (TPI_UNITS_MILLIMETERS, Units::Millimetres),
    (TPI_UNITS_CENTIMETERS, Units::Centimetres),
    (TPI_UNITS_METERS, Units::Metres),
    (TPI_UNITS_KILOMETERS, Units::Kilometres),
    (TPI_UNITS_INCHES, Units::Inches),
    (TPI_UNITS_FEET, Units::Feet),
    (TPI_UNITS_MILES, Units::Miles),
    (TPI_UNITS_YARDS, Units::Yards),
];

fn units_from_code(code: i32) -> Result<Option<Units>, FfiError> {
    if code == TPI_UNITS_NONE {
        return Ok(None);
    }
    UNIT_CODES
        .iter()
        .find(|(c, _)| *c == code)
        .map(|&(_, u)| Some(u))
        .ok_or_else(|| {
            FfiError::new(
                TpiStatus::InvalidArgument,
                format!(
                    "units {code}: expected one of TPI_UNITS_NONE (0), {} (Rhino's UnitSystem values)",
                    UNIT_CODES
                        .iter()
                        .map(|(c, u)| format!("{c} ({})", u.short_name()))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })
}

/// Creates a copy of `surface` with the model's length units `units` (a `TPI_UNITS_*` value,
/// Rhino's `UnitSystem` numbering; `TPI_UNITS_NONE` for unitless). Nothing is rescaled: the
/// units are carried to the outputs (the discretisation JSON's `"units"`, the fabrication's
/// panels.json and DXF `$INSUNITS`). Surfaces are immutable, hence a new handle; free both.
///
/// Errors: TPI_STATUS_NULL_POINTER, TPI_STATUS_INVALID_ARGUMENT (a value that is no
/// `TPI_UNITS_*`, the message lists them). On an error `*out` is set to NULL.
///
/// # Safety
/// `surface` is NULL or a live handle; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_with_units(
    surface: *const TpiSurface,
    units: i32,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let units = units_from_code(units)?;
        let model = surface.model.clone().with_units(units);
        out.set_boxed(TpiSurface { model });
        Ok(())
    }
}

/// Creates a copy of `surface` trimmed to the region bounded by closed polylines in the
/// surface's own (u, v) parameters (not normalised): the outer loop `outer_uv`
/// (`outer_len` doubles, u then v per point, counter-clockwise) and `hole_count` holes,
/// clockwise, whose points follow one another in `holes_uv` (`holes_len` doubles), hole `k`
/// having `hole_point_counts[k]` points. The closing segment of a loop is implied; a last
/// point equal to the first is accepted and ignored. A trimmed surface's trim is replaced.
/// Surfaces are immutable, hence a new handle; free both.
///
/// Discretising a trimmed surface leaves the pattern points outside the trim out and ends
/// the facets on it (convex surfaces; elsewhere TPI_STATUS_INVALID_ARGUMENT, the trim is
/// never ignored). `tpi_discrete_surface_new` refuses a trimmed surface with
/// TPI_STATUS_INVALID_ARGUMENT. Evaluation and the domain are those of the untrimmed surface.
///
/// Errors: TPI_STATUS_NULL_POINTER (`surface`, `out`, or an array whose length is not 0);
/// TPI_STATUS_INVALID_ARGUMENT (an odd number of doubles, hole point counts that do not add
/// up to `holes_len / 2`, and the trim's validation: a loop with fewer than 3 points, two
/// consecutive equal points, a point outside the domain, an outer loop that is not
/// counter-clockwise or a hole that is not clockwise, segments that touch or cross, a hole
/// outside the outer loop or inside another; the message names the loop and point, e.g.
/// `trim.holes[1][4]`); TPI_STATUS_NON_FINITE (a NaN or infinite coordinate). On an error
/// `*out` is set to NULL.
///
/// # Safety
/// `surface` is NULL or a live handle; `outer_uv` and `holes_uv` are NULL or valid for
/// reading `outer_len` and `holes_len` doubles; `hole_point_counts` is NULL or valid for
/// reading `hole_count` values; `out` is NULL or valid for writing a pointer.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tpi_surface_with_trim(
    surface: *const TpiSurface,
    outer_uv: *const f64,
    outer_len: usize,
    holes_uv: *const f64,
    holes_len: usize,
    hole_point_counts: *const usize,
    hole_count: usize,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract for every argument.
        let out = unsafe { OutPtr::handle(out, "out") }?;
        let surface = unsafe { try_handle(surface, "surface") }?;
        let outer = unsafe { try_pairs(outer_uv, outer_len, "outer_uv") }?;
        let hole_points = unsafe { try_pairs(holes_uv, holes_len, "holes_uv") }?;
        let counts = unsafe { try_slice(hole_point_counts, hole_count, "hole_point_counts") }?;
        let total = counts.iter().try_fold(0usize, |sum, &c| sum.checked_add(c));
        if total != Some(hole_points.len()) {
            return Err(FfiError::invalid(format!(
                "hole_point_counts add up to {}, but holes_uv holds {} points ({holes_len} doubles)",
                total.map_or_else(|| "more than SIZE_MAX".to_string(), |t| t.to_string()),
                hole_points.len()
            )));
        }
        let mut holes = Vec::with_capacity(counts.len());
        let mut rest = hole_points;
        for &count in counts {
            // The counts add up to the number of points, so every split succeeds.
            let (hole, tail) = rest
                .split_at_checked(count)
                .ok_or_else(|| FfiError::invalid("hole_point_counts overrun holes_uv"))?;
            holes.push(hole.to_vec());
            rest = tail;
        }
        let trim = Trim { outer: outer.to_vec(), holes };
        let model = SurfaceModel::trimmed(surface.model.clone(), trim)?;
        out.set_boxed(TpiSurface { model });
        Ok(())
    }
}

/// Creates a polysurface: several untrimmed four-sided faces that share whole sides, joined
/// as one surface. The faces are laid out as rows and columns of a rectangle, found from the
/// geometry (two faces share a side when their points along it agree to a small fraction of
/// the size), so they may come in any order and orientation; a ring of faces closes the
/// surface in that direction. The polysurface's domain is [0, sum of column widths] x
/// [0, sum of row heights] (widths and heights are the faces' mid-line lengths), so a pattern
/// in [0, 1]^2 spreads over the faces by length; its tangent planes are the faces' own, and
/// the facets of neighbouring faces meet along common edges.
///
/// `faces` is an array of `count` surface handles, which are **borrowed**: the new handle
/// holds its own copy of each, so the caller still frees every face (and may do so right
/// away). The faces' units must agree; the polysurface carries them.
///
/// Errors: TPI_STATUS_NULL_POINTER (`faces` with `count > 0`, a NULL element, named as
/// `faces[k]`, or `out`); TPI_STATUS_INVALID_HANDLE (an element that is not a live
/// surface handle); TPI_STATUS_INVALID_ARGUMENT (`count` 0 or more than 1000; a face that is
/// trimmed or itself a polysurface; faces whose units differ; a face that shares no whole side
/// with the others; faces that do not fill a rectangle of rows and columns; the message names
/// the face, e.g. `faces[1]: shares no whole side ...`, or `faces` for the layout as a whole).
/// On an error `*out` is set to NULL.
///
/// # Safety
/// `faces` is NULL or valid for reading `count` pointers, each NULL or a surface handle from
/// this library that stays alive during the call; `out` is NULL or valid for writing a pointer.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_new_polysurface(
    faces: *const *const TpiSurface,
    count: usize,
    out: *mut *mut TpiSurface,
) -> TpiStatus {
    ffi_boundary! {
        create(out, || {
            // SAFETY: the caller's contract for the array.
            let handles = unsafe { try_slice(faces, count, "faces") }?;
            let mut models = Vec::with_capacity(handles.len());
            for (k, &face) in handles.iter().enumerate() {
                // SAFETY: the caller's contract for each element.
                let face = unsafe { try_handle(face, &format!("faces[{k}]")) }?;
                models.push(face.model.clone());
            }
            Ok(SurfaceModel::Polysurface(Box::new(Polysurface::new(models)?)))
        })
    }
}

/// Stores the surface's units in `*out`: a `TPI_UNITS_*` value, `TPI_UNITS_NONE` when unitless.
///
/// Errors: TPI_STATUS_NULL_POINTER.
///
/// # Safety
/// `surface` is NULL or a live handle; `out` is NULL or valid for writing an `int32_t`.
#[no_mangle]
pub unsafe extern "C" fn tpi_surface_units(surface: *const TpiSurface, out: *mut i32) -> TpiStatus {
    ffi_boundary! {
        // SAFETY: the caller's contract.
        let surface = unsafe { try_handle(surface, "surface") }?;
        let out = unsafe { OutPtr::new(out, "out") }?;
        let code = surface
            .model
            .units()
            .and_then(|u| UNIT_CODES.iter().find(|(_, v)| *v == u).map(|&(c, _)| c))
            .unwrap_or(TPI_UNITS_NONE);
        out.set(code);
        Ok(())
    }
}
