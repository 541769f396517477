//! Fabrication through the C ABI gives what the core gives, and bad arguments come back as
//! status codes with a message naming them.

mod common;

use common::*;
use tpi::*;

fn discretised() -> (*mut TpiSurface, *mut TpiPattern, *mut TpiDiscretisation) {
    let surface = dome(2.0);
    let p = pattern(&jittered_grid(8));
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, NULL options, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, std::ptr::null(), &mut d) });
    (surface, p, d)
}

#[test]
fn files_match_the_core_and_errors_name_the_culprit() {
    let (surface, p, d) = discretised();
    let mut fab = std::ptr::null_mut();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_fabricate(d, 0.05, TPI_SIDE_INSIDE, 1, 4.0, 3.0, 0.03, &mut fab) });
    let (mut panels, mut sheets) = (0usize, 0usize);
    // SAFETY: live handle, valid out pointers.
    ok(unsafe { tpi_fabrication_counts(fab, &mut panels, &mut sheets) });
    assert_eq!(panels, 64);
    assert!(sheets >= 1);
    // The same as the core's own result on the same mesh.
    let points: Vec<glam::DVec3> = dome_points(2.0)
        .chunks_exact(3)
        .map(|c| glam::DVec3::new(c[0], c[1], c[2]))
        .collect();
    let s = tpi_core::NurbsSurface::new(
        [DOME_DEGREE, DOME_DEGREE],
        [DOME_COUNT, DOME_COUNT],
        &DOME_KNOTS,
        &DOME_KNOTS,
        &points,
        None,
    )
    .unwrap();
    let mesh = tpi_core::discretise(
        &s,
        &jittered_grid(8),
        &tpi_core::DiscretiseOptions::default(),
    )
    .unwrap();
    let core = tpi_core::fabricate(
        &mesh,
        &tpi_core::FabricateOptions {
            thickness: 0.05,
            slots: tpi_core::SlotPlan::Even(1),
            sheet: [4.0, 3.0],
            gap: 0.03,
            ..tpi_core::FabricateOptions::default()
        },
    )
    .unwrap();
    // SAFETY: live handle; read_string passes valid buffers.
    let json =
        read_string(|o, c, n| unsafe { tpi_fabrication_file(fab, TPI_FILE_PANELS_JSON, o, c, n) });
    assert_eq!(json, core.to_json());
    for file in [
        TPI_FILE_PANELS_OBJ,
        TPI_FILE_SHEETS_SVG,
        TPI_FILE_SHEETS_DXF,
        TPI_FILE_BEVELS_CSV,
    ] {
        // SAFETY: as above.
        let text = read_string(|o, c, n| unsafe { tpi_fabrication_file(fab, file, o, c, n) });
        assert!(text.len() > 100, "file {file}");
    }
    // SAFETY: as above.
    let gcode = read_string(|o, c, n| unsafe { tpi_fabrication_gcode(fab, 0.006, o, c, n) });
    assert!(gcode.ends_with("M30\n"));
    let mut needed = 0usize;
    // SAFETY: NULL buffer with capacity 0 is the size query.
    let status = unsafe { tpi_fabrication_file(fab, 9, std::ptr::null_mut(), 0, &mut needed) };
    assert_eq!(status, TpiStatus::InvalidArgument);
    assert!(last_error().contains("file = 9"), "{}", last_error());
    // SAFETY: as above.
    let status = unsafe { tpi_fabrication_gcode(fab, 0.5, std::ptr::null_mut(), 0, &mut needed) };
    assert_eq!(status, TpiStatus::InvalidArgument);
    assert!(last_error().contains("gap"), "{}", last_error());

    // Bad thickness: NaN, negative, beyond the limit; bad side; NULL handle.
    let mut none = std::ptr::null_mut();
    for (t, status, needle) in [
        (f64::NAN, TpiStatus::NonFinite, "thickness = NaN"),
        (-1.0, TpiStatus::InvalidArgument, "thickness = -1"),
        (50.0, TpiStatus::InvalidArgument, "collapses"),
    ] {
        // SAFETY: live handle, valid out pointer.
        let s = unsafe { tpi_fabricate(d, t, TPI_SIDE_INSIDE, 0, 300.0, 300.0, 0.03, &mut none) };
        assert_eq!(s, status, "{t}");
        assert!(last_error().contains(needle), "{t}: {}", last_error());
        assert!(none.is_null());
    }
    // SAFETY: as above.
    let s = unsafe { tpi_fabricate(d, 0.05, 7, 0, 3.0, 1.5, 0.03, &mut none) };
    assert_eq!(s, TpiStatus::InvalidArgument);
    // SAFETY: NULL handle is reported, not dereferenced.
    let s = unsafe { tpi_fabricate(std::ptr::null(), 0.05, 0, 0, 3.0, 1.5, 0.03, &mut none) };
    assert_eq!(s, TpiStatus::NullPointer);
    // SAFETY: handles from this test, each freed once.
    unsafe {
        tpi_fabrication_free(fab);
        tpi_fabrication_free(std::ptr::null_mut());
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}
