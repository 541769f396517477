//! The NURBS dome shared by the Rust tests of the C ABI and the C test's fixture generator
//! (examples/c_fixture.rs), and small safe wrappers over the C ABI for tests.
//!
//! The dome is the bicubic Bezier patch (4 x 4 control points, Rhino knots 0 0 0 1 1 1) that
//! is exactly the elliptic paraboloid z = h (1 - x'^2 - y'^2), x' = x / 5, y' = y / 5, over
//! [-5, 5]^2: x' = 2u - 1 has cubic Bernstein coefficients (-1, -1/3, 1/3, 1) and x'^2 has
//! (1, -1/3, -1/3, 1), so control point (i, j) is (5 a_i, 5 a_j, h (1 - q_i - q_j)).
// Test helpers: `pub` is how the test files that include this module reach them.
#![allow(unreachable_pub)]
#![allow(dead_code)]

use std::ffi::c_char;

use tpi::*;

/// Degrees of the dome.
pub const DOME_DEGREE: usize = 3;
/// Control points per direction.
pub const DOME_COUNT: usize = 4;
/// Rhino-convention knots (count + degree - 1 = 6), in u and in v.
pub const DOME_KNOTS: [f64; 6] = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
/// Half-width of the dome's square.
pub const DOME_HALF_WIDTH: f64 = 5.0;

const A: [f64; 4] = [-1.0, -1.0 / 3.0, 1.0 / 3.0, 1.0];
const Q: [f64; 4] = [1.0, -1.0 / 3.0, -1.0 / 3.0, 1.0];

/// The control points, u-major, flat (x, y, z per point), for the dome of height `height`.
pub fn dome_points(height: f64) -> Vec<f64> {
    let mut points = Vec::with_capacity(3 * DOME_COUNT * DOME_COUNT);
    for i in 0..DOME_COUNT {
        for j in 0..DOME_COUNT {
            points.extend([
                DOME_HALF_WIDTH * A[i],
                DOME_HALF_WIDTH * A[j],
                height * (1.0 - Q[i] - Q[j]),
            ]);
        }
    }
    points
}

/// Panics with the library's last error message when `status` is not OK.
pub fn ok(status: TpiStatus) {
    assert_eq!(status, TpiStatus::Ok, "{}", last_error());
}

/// The calling thread's last error message.
pub fn last_error() -> String {
    let mut needed = 0usize;
    // SAFETY: size query with a valid `needed`.
    unsafe { tpi_last_error_message(std::ptr::null_mut(), 0, &mut needed) };
    let mut buf = vec![0 as c_char; needed.max(1)];
    // SAFETY: buf holds `needed` chars.
    unsafe { tpi_last_error_message(buf.as_mut_ptr(), buf.len(), &mut needed) };
    let bytes: Vec<u8> = buf
        .iter()
        .take_while(|&&c| c != 0)
        .map(|&c| c as u8)
        .collect();
    String::from_utf8_lossy(&bytes).into_owned()
}

/// A NURBS dome of the given height through the C ABI.
pub fn dome(height: f64) -> *mut TpiSurface {
    let points = dome_points(height);
    let mut surface = std::ptr::null_mut();
    // SAFETY: every array is valid for its length; `surface` is a valid out pointer.
    ok(unsafe {
        tpi_surface_new_nurbs(
            DOME_DEGREE,
            DOME_DEGREE,
            DOME_COUNT,
            DOME_COUNT,
            DOME_KNOTS.as_ptr(),
            DOME_KNOTS.len(),
            DOME_KNOTS.as_ptr(),
            DOME_KNOTS.len(),
            points.as_ptr(),
            points.len(),
            std::ptr::null(),
            0,
            &mut surface,
        )
    });
    surface
}

/// A pattern from (s, t) pairs through the C ABI.
pub fn pattern(points: &[[f64; 2]]) -> *mut TpiPattern {
    let flat = points.as_flattened();
    let mut pattern = std::ptr::null_mut();
    // SAFETY: valid array and out pointer.
    ok(unsafe { tpi_pattern_new(flat.as_ptr(), flat.len(), &mut pattern) });
    pattern
}

/// Reads a copy-out array: size query, then copy.
pub fn read_array<T: Copy + Default>(
    call: impl Fn(*mut T, usize, *mut usize) -> TpiStatus,
) -> Vec<T> {
    let mut needed = 0usize;
    let status = call(std::ptr::null_mut(), 0, &mut needed);
    assert!(
        status == TpiStatus::Ok || status == TpiStatus::BufferTooSmall,
        "{status:?}: {}",
        last_error()
    );
    let mut data = vec![T::default(); needed];
    let mut again = 0usize;
    ok(call(data.as_mut_ptr(), data.len(), &mut again));
    assert_eq!(again, needed);
    data
}

/// Reads a copy-out string.
pub fn read_string(call: impl Fn(*mut c_char, usize, *mut usize) -> TpiStatus) -> String {
    let chars = read_array::<c_char>(call);
    assert_eq!(chars.last(), Some(&0), "NUL terminated");
    let bytes: Vec<u8> = chars[..chars.len() - 1].iter().map(|&c| c as u8).collect();
    String::from_utf8(bytes).expect("UTF-8")
}

/// Everything a host reads from a discretisation, through the C ABI.
#[derive(Debug, PartialEq)]
pub struct Mesh {
    pub json: String,
    pub vertices: Vec<f64>,
    pub facet_sizes: Vec<u32>,
    pub facet_indices: Vec<u32>,
    pub facet_flags: Vec<u8>,
    pub seeds: Vec<TpiSeed>,
    pub planes: Vec<TpiPlane>,
    pub neighbour_pairs: Vec<u32>,
    pub dual_triangles: Vec<u32>,
    pub quality_json: String,
    pub diagnostics_json: String,
    pub diagnostic_entries: Vec<TpiDiagnosticEntry>,
}

/// Reads every array of a discretisation.
pub fn read_mesh(d: *const TpiDiscretisation) -> Mesh {
    // SAFETY (all calls): `d` is a live handle; the closures pass buffers from read_array.
    unsafe {
        Mesh {
            json: read_string(|o, c, n| tpi_discretisation_json(d, 0, o, c, n)),
            vertices: read_array(|o, c, n| tpi_discretisation_vertices(d, o, c, n)),
            facet_sizes: read_array(|o, c, n| tpi_discretisation_facet_sizes(d, o, c, n)),
            facet_indices: read_array(|o, c, n| tpi_discretisation_facet_indices(d, o, c, n)),
            facet_flags: read_array(|o, c, n| tpi_discretisation_facet_flags(d, o, c, n)),
            seeds: read_array(|o, c, n| tpi_discretisation_seeds(d, o, c, n)),
            planes: read_array(|o, c, n| tpi_discretisation_planes(d, o, c, n)),
            neighbour_pairs: read_array(|o, c, n| tpi_discretisation_neighbour_pairs(d, o, c, n)),
            dual_triangles: read_array(|o, c, n| tpi_discretisation_dual_triangles(d, o, c, n)),
            quality_json: read_string(|o, c, n| tpi_discretisation_quality_json(d, o, c, n)),
            diagnostics_json: read_string(|o, c, n| {
                tpi_discretisation_diagnostics_json(d, o, c, n)
            }),
            diagnostic_entries: read_array(|o, c, n| {
                tpi_discretisation_diagnostic_entries(d, o, c, n)
            }),
        }
    }
}

/// Discretises from scratch through the C ABI and reads the mesh.
pub fn discretise_from_scratch(surface: *const TpiSurface, points: &[[f64; 2]]) -> Mesh {
    let p = pattern(points);
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, default options, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, std::ptr::null(), &mut d) });
    let mesh = read_mesh(d);
    // SAFETY: our handles, freed once.
    unsafe {
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
    }
    mesh
}

/// The current mesh of a discrete surface.
pub fn current_mesh(ds: *const TpiDiscreteSurface) -> Mesh {
    let mut d = std::ptr::null_mut();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_discrete_surface_mesh(ds, &mut d) });
    let mesh = read_mesh(d);
    // SAFETY: our handle, freed once.
    unsafe { tpi_discretisation_free(d) };
    mesh
}

/// The current points of a discrete surface.
pub fn current_points(ds: *const TpiDiscreteSurface) -> Vec<[f64; 2]> {
    // SAFETY: live handle; buffers from read_array.
    let flat = read_array(|o, c, n| unsafe { tpi_discrete_surface_points(ds, o, c, n) });
    flat.chunks_exact(2).map(|c| [c[0], c[1]]).collect()
}

/// A jittered grid of n x n points (normalised), deterministic.
pub fn jittered_grid(n: usize) -> Vec<[f64; 2]> {
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let wobble = ((i * 7 + j * 3) % 5) as f64 / 5.0 - 0.4;
            points.push([
                (i as f64 + 0.5 + 0.3 * wobble) / n as f64,
                (j as f64 + 0.5 - 0.2 * wobble) / n as f64,
            ]);
        }
    }
    points
}
