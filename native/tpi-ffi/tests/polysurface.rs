//! `tpi_surface_new_polysurface`: two halves of a saddle joined through the C ABI give the
//! single face's mesh; the faces are borrowed; every malformed input is a typed status naming
//! the argument or the face.

mod common;

use common::*;
use tpi::*;

fn hypar(x0: f64, x1: f64) -> *mut TpiSurface {
    let mut s = std::ptr::null_mut();
    // SAFETY: valid out pointer.
    ok(unsafe { tpi_surface_new_hyperbolic_paraboloid(0.4, 0.4, x0, x1, -1.0, 1.0, &mut s) });
    s
}

fn join(faces: &[*const TpiSurface]) -> (TpiStatus, *mut TpiSurface) {
    let mut out = 1usize as *mut TpiSurface;
    // SAFETY: `faces` is valid for its length; `out` is a valid out pointer.
    let status = unsafe { tpi_surface_new_polysurface(faces.as_ptr(), faces.len(), &mut out) };
    (status, out)
}

fn free(surfaces: &[*mut TpiSurface]) {
    for &s in surfaces {
        // SAFETY: our handles, each freed once.
        unsafe { tpi_surface_free(s) };
    }
}

/// The points of facet `i`'s loop.
fn facet_points(mesh: &Mesh, i: usize) -> Vec<[f64; 3]> {
    let start: usize = mesh.facet_sizes[..i].iter().map(|&n| n as usize).sum();
    mesh.facet_indices[start..start + mesh.facet_sizes[i] as usize]
        .iter()
        .map(|&v| {
            let v = v as usize;
            [
                mesh.vertices[3 * v],
                mesh.vertices[3 * v + 1],
                mesh.vertices[3 * v + 2],
            ]
        })
        .collect()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[test]
fn two_saddle_halves_give_the_single_face_mesh() {
    let single = hypar(-1.0, 1.0);
    // Given right half first: the layout comes from the geometry, not the order.
    let (right, left) = (hypar(0.0, 1.0), hypar(-1.0, 0.0));
    let (status, joined) = join(&[right, left]);
    ok(status);
    // Borrowed: freeing the faces leaves the polysurface intact.
    free(&[right, left]);

    let mut domain = TpiDomain::default();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_surface_domain(joined, &mut domain) });
    assert_eq!((domain.u_min, domain.v_min), (0.0, 0.0));
    assert!(domain.u_max > 0.0 && domain.v_max > 0.0);

    // Evaluation: the point at a fraction of the domain is the saddle's at that fraction.
    let uv = [0.3 * domain.u_max, 0.8 * domain.v_max];
    let mut sample = TpiSample::default();
    // SAFETY: two doubles in, room for one sample.
    ok(unsafe { tpi_surface_evaluate(joined, uv.as_ptr(), 2, &mut sample, 1) });
    let (x, y) = (-1.0 + 2.0 * 0.3, -1.0 + 2.0 * 0.8);
    let expected = [x, y, 0.4 * x * x - 0.4 * y * y];
    assert!(
        distance(sample.point, expected) < 1e-12,
        "{:?}",
        sample.point
    );

    let points = jittered_grid(12);
    let a = discretise_from_scratch(single, &points);
    let b = discretise_from_scratch(joined, &points);
    assert_eq!(a.facet_sizes.len(), points.len());
    assert_eq!(a.facet_sizes, b.facet_sizes);
    for i in 0..points.len() {
        let far = facet_points(&a, i)
            .into_iter()
            .zip(facet_points(&b, i))
            .map(|(p, q)| distance(p, q))
            .fold(0.0, f64::max);
        assert!(far < 1e-9, "facet {i} moved by {far:e}");
    }

    // Live editing takes the polysurface too, and its mesh is the one from scratch.
    let p = pattern(&points);
    let mut ds = std::ptr::null_mut();
    // SAFETY: live handles, default options, valid out pointer.
    ok(unsafe { tpi_discrete_surface_new(joined, p, std::ptr::null(), &mut ds) });
    assert_eq!(current_mesh(ds).facet_indices, b.facet_indices);
    // SAFETY: our handles, freed once.
    unsafe {
        tpi_discrete_surface_free(ds);
        tpi_pattern_free(p);
    }
    free(&[single, joined]);
}

#[test]
fn units_must_agree_and_are_carried() {
    let (left, right) = (hypar(-1.0, 0.0), hypar(0.0, 1.0));
    let (mut left_mm, mut right_mm, mut right_m) = (
        std::ptr::null_mut(),
        std::ptr::null_mut(),
        std::ptr::null_mut(),
    );
    // SAFETY: live handles, valid out pointers.
    unsafe {
        ok(tpi_surface_with_units(
            left,
            TPI_UNITS_MILLIMETERS,
            &mut left_mm,
        ));
        ok(tpi_surface_with_units(
            right,
            TPI_UNITS_MILLIMETERS,
            &mut right_mm,
        ));
        ok(tpi_surface_with_units(
            right,
            TPI_UNITS_METERS,
            &mut right_m,
        ));
    }
    let (status, joined) = join(&[left_mm, right_mm]);
    ok(status);
    let mut units = -1;
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_surface_units(joined, &mut units) });
    assert_eq!(units, TPI_UNITS_MILLIMETERS);
    let (status, none) = join(&[left_mm, right_m]);
    assert_eq!(status, TpiStatus::InvalidArgument);
    assert!(none.is_null());
    let message = last_error();
    assert!(
        message.starts_with("faces[1]: ") && message.contains("units"),
        "{message}"
    );
    free(&[left, right, left_mm, right_mm, right_m, joined]);
}

#[test]
fn bad_faces_are_refused_naming_the_argument() {
    let (left, right) = (hypar(-1.0, 0.0), hypar(0.0, 1.0));
    let apart = hypar(2.0, 3.0);

    // NULL array with a count, NULL element, NULL out.
    let mut out = 1usize as *mut TpiSurface;
    // SAFETY: NULL with count 2 is refused before any read.
    let status = unsafe { tpi_surface_new_polysurface(std::ptr::null(), 2, &mut out) };
    assert_eq!(status, TpiStatus::NullPointer);
    assert!(out.is_null());
    assert_eq!(last_error(), "faces is NULL");
    let (status, out) = join(&[left, std::ptr::null()]);
    assert_eq!((status, out.is_null()), (TpiStatus::NullPointer, true));
    assert_eq!(last_error(), "faces[1] is NULL");
    let faces = [left as *const TpiSurface, right];
    // SAFETY: valid array; NULL out is refused.
    let status = unsafe { tpi_surface_new_polysurface(faces.as_ptr(), 2, std::ptr::null_mut()) };
    assert_eq!(status, TpiStatus::NullPointer);
    assert_eq!(last_error(), "out is NULL");

    // No faces.
    let (status, out) = join(&[]);
    assert_eq!((status, out.is_null()), (TpiStatus::InvalidArgument, true));
    assert!(last_error().starts_with("faces: "), "{}", last_error());

    // A handle of another kind.
    let p = pattern(&jittered_grid(3));
    let (status, out) = join(&[left, p.cast()]);
    assert_eq!((status, out.is_null()), (TpiStatus::InvalidHandle, true));
    assert!(
        last_error().contains("faces[1] is a TpiPattern"),
        "{}",
        last_error()
    );

    // Faces that share no side.
    let (status, out) = join(&[left, apart]);
    assert_eq!((status, out.is_null()), (TpiStatus::InvalidArgument, true));
    assert!(
        last_error().starts_with("faces[1]: shares no whole side"),
        "{}",
        last_error()
    );

    // A trimmed face, and a face that is itself a polysurface.
    let outer = [0.1, -0.9, 0.9, -0.9, 0.9, 0.9, 0.1, 0.9];
    let mut trimmed = std::ptr::null_mut();
    // SAFETY: valid arrays and out pointer.
    ok(unsafe {
        tpi_surface_with_trim(
            right,
            outer.as_ptr(),
            outer.len(),
            std::ptr::null(),
            0,
            std::ptr::null(),
            0,
            &mut trimmed,
        )
    });
    let (status, out) = join(&[left, trimmed]);
    assert_eq!((status, out.is_null()), (TpiStatus::InvalidArgument, true));
    assert!(
        last_error().starts_with("faces[1]: ") && last_error().contains("trimmed"),
        "{}",
        last_error()
    );
    let (status, joined) = join(&[left, right]);
    ok(status);
    let (status, out) = join(&[joined, apart]);
    assert_eq!((status, out.is_null()), (TpiStatus::InvalidArgument, true));
    assert!(
        last_error().starts_with("faces[0]: ") && last_error().contains("polysurface"),
        "{}",
        last_error()
    );

    // SAFETY: our pattern, freed once.
    unsafe { tpi_pattern_free(p) };
    free(&[left, right, apart, trimmed, joined]);
}
