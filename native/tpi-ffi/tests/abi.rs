//! The conventions of the C ABI, from Rust: fixed numbers, struct layouts, the copy-out and
//! last-error conventions, options growth, and that every call forwards to the core unchanged.

#![allow(clippy::type_complexity)]

mod common;

use std::ffi::{c_char, CStr};
use std::mem::{align_of, offset_of, size_of};

use common::*;
use tpi::*;
use tpi_core::Generator;
use tpi_core::{discretise, DiscretiseOptions, LocalGeometry, NurbsSurface, Surface};

#[test]
fn status_numbers_are_fixed() {
    let expected = [
        (TpiStatus::Ok, 0, "TPI_STATUS_OK"),
        (TpiStatus::NullPointer, 1, "TPI_STATUS_NULL_POINTER"),
        (TpiStatus::InvalidArgument, 2, "TPI_STATUS_INVALID_ARGUMENT"),
        (TpiStatus::BufferTooSmall, 3, "TPI_STATUS_BUFFER_TOO_SMALL"),
        (
            TpiStatus::IndexOutOfRange,
            4,
            "TPI_STATUS_INDEX_OUT_OF_RANGE",
        ),
        (TpiStatus::NonFinite, 5, "TPI_STATUS_NON_FINITE"),
        (TpiStatus::InvalidNurbs, 6, "TPI_STATUS_INVALID_NURBS"),
        (TpiStatus::InvalidPattern, 7, "TPI_STATUS_INVALID_PATTERN"),
        (TpiStatus::Degenerate, 8, "TPI_STATUS_DEGENERATE"),
        (TpiStatus::Panic, 9, "TPI_STATUS_PANIC"),
        (TpiStatus::OutOfDomain, 10, "TPI_STATUS_OUT_OF_DOMAIN"),
        (TpiStatus::Unavailable, 11, "TPI_STATUS_UNAVAILABLE"),
        (TpiStatus::InvalidHandle, 12, "TPI_STATUS_INVALID_HANDLE"),
        (TpiStatus::Cancelled, 13, "TPI_STATUS_CANCELLED"),
    ];
    assert_eq!(
        TpiStatus::ALL.len(),
        expected.len(),
        "a new status needs a line here, with a new number"
    );
    let header =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../include/tpi.h"))
            .expect("header");
    for (status, number, name) in expected {
        assert_eq!(status as u32, number);
        assert_eq!(status.name(), name);
        // SAFETY: static NUL-terminated strings.
        assert_eq!(
            unsafe { CStr::from_ptr(tpi_status_name(number)) }.to_str(),
            Ok(name)
        );
        assert!(
            header.contains(&format!("{name} = {number},")),
            "{name} = {number} in the header"
        );
    }
    // SAFETY: as above.
    assert_eq!(
        unsafe { CStr::from_ptr(tpi_status_name(14)) }.to_str(),
        Ok("TPI_STATUS_UNKNOWN")
    );
    // SAFETY: as above.
    assert_eq!(
        unsafe { CStr::from_ptr(tpi_status_name(u32::MAX)) }.to_str(),
        Ok("TPI_STATUS_UNKNOWN")
    );
}

#[test]
fn flag_and_kind_numbers_match_the_core() {
    use tpi_core::{
        FLAG_DIAGNOSTIC, FLAG_FAR_VERTEX, FLAG_NON_CONVEX, FLAG_NON_SIMPLE, FLAG_OPEN, FLAG_OVERLAP,
    };
    assert_eq!(TPI_FACET_OPEN, FLAG_OPEN);
    assert_eq!(TPI_FACET_FAR_VERTEX, FLAG_FAR_VERTEX);
    assert_eq!(TPI_FACET_NON_CONVEX, FLAG_NON_CONVEX);
    assert_eq!(TPI_FACET_NON_SIMPLE, FLAG_NON_SIMPLE);
    assert_eq!(TPI_FACET_OVERLAP, FLAG_OVERLAP);
    assert_eq!(TPI_FACET_DIAGNOSTIC, FLAG_DIAGNOSTIC);
    assert_eq!(TpiDiagnosticKind::IllConditionedVertex as u32, 1);
    assert_eq!(TpiDiagnosticKind::ParallelPlanes as u32, 2);
    assert_eq!(TpiDiagnosticKind::BoundaryNotReached as u32, 3);
    assert_eq!(TpiDiagnosticKind::OpenFacet as u32, 4);
    assert_eq!(TpiDiagnosticKind::CornerUnreachable as u32, 5);
    assert_eq!(TpiDiagnosticKind::CornerClaims as u32, 6);
    assert_eq!(TpiDiagnosticKind::FlatPoint as u32, 7);
    assert_eq!(TpiDiagnosticKind::CoincidentPlanes as u32, 8);
    assert_eq!(TpiDiagnosticKind::SeamLeftOpen as u32, 9);
    assert_eq!(TpiDiagnosticKind::UnexpectedTopology as u32, 10);
    assert_eq!(TpiDiagnosticKind::RulingStrips as u32, 11);
    assert_eq!(TpiDiagnosticKind::FacetPartsLeftOut as u32, 12);
}

#[test]
fn struct_layouts_are_fixed() {
    assert_eq!(size_of::<TpiOptions>(), TPI_OPTIONS_SIZE_V2 as usize);
    assert_eq!(
        offset_of!(TpiOptions, plane_mode),
        TPI_OPTIONS_SIZE_V1 as usize
    );
    assert_eq!(
        size_of::<TpiQualityReport>(),
        TPI_QUALITY_REPORT_SIZE_V3 as usize
    );
    assert_eq!(
        offset_of!(TpiQualityReport, invalid_facets),
        TPI_QUALITY_REPORT_SIZE_V1 as usize
    );
    assert_eq!(
        offset_of!(TpiQualityReport, far_vertex_facets),
        TPI_QUALITY_REPORT_SIZE_V2 as usize
    );
    assert_eq!(align_of::<TpiOptions>(), 8);
    assert_eq!(offset_of!(TpiOptions, far_vertex_factor), 16);
    assert_eq!(offset_of!(TpiQualityReport, facet_count), 8);
    assert_eq!(offset_of!(TpiQualityReport, diagnostic_count), 192);
    assert_eq!(size_of::<TpiDomain>(), 32);
    assert_eq!(size_of::<TpiSample>(), 120);
    assert_eq!(offset_of!(TpiSample, regular), 112);
    assert_eq!(size_of::<TpiSeed>(), 80);
    assert_eq!(size_of::<TpiPlane>(), 48);
    assert_eq!(size_of::<TpiDiagnosticEntry>(), 12);
    assert_eq!(size_of::<TpiStatus>(), 4);
}

#[test]
fn options_default_round_trips_and_respects_struct_size() {
    let mut options = TpiOptions::defaults();
    options.far_vertex_factor = -1.0;
    options.struct_size = size_of::<TpiOptions>() as u32;
    // SAFETY: a full TpiOptions.
    ok(unsafe { tpi_options_default(&mut options) });
    assert_eq!(options, TpiOptions::defaults());
    assert_eq!(
        options.to_core().map_err(|e| e.message),
        Ok(DiscretiseOptions::default())
    );

    // Not set: rejected, nothing written.
    let mut zeroed = TpiOptions {
        struct_size: 0,
        ..TpiOptions::defaults()
    };
    zeroed.weld_tolerance = 123.0;
    // SAFETY: a full TpiOptions.
    assert_eq!(
        unsafe { tpi_options_default(&mut zeroed) },
        TpiStatus::InvalidArgument
    );
    assert!(last_error().contains("struct_size"));
    assert_eq!(zeroed.weld_tolerance, 123.0);
    // SAFETY: NULL.
    assert_eq!(
        unsafe { tpi_options_default(std::ptr::null_mut()) },
        TpiStatus::NullPointer
    );

    // A caller with a bigger (newer) struct: only this library's bytes are written.
    #[repr(C)]
    struct Newer {
        options: TpiOptions,
        future: [u8; 16],
    }
    let mut newer = Newer {
        options: TpiOptions {
            struct_size: size_of::<Newer>() as u32,
            ..TpiOptions::defaults()
        },
        future: [0xAB; 16],
    };
    newer.options.flat_tolerance = 5.0;
    // SAFETY: `newer` holds struct_size bytes.
    ok(unsafe { tpi_options_default(&mut newer.options) });
    assert_eq!(
        newer.options.struct_size,
        size_of::<Newer>() as u32,
        "struct_size is left as the caller set it"
    );
    assert_eq!(
        newer.options.flat_tolerance,
        TpiOptions::defaults().flat_tolerance
    );
    assert_eq!(newer.future, [0xAB; 16]);
}

#[test]
fn invalid_options_are_rejected_by_name() {
    let surface = dome(3.0);
    let p = pattern(&jittered_grid(5));
    let cases: [(fn(&mut TpiOptions), TpiStatus, &str); 8] = [
        (
            |o| o.plane_mode = 2,
            TpiStatus::InvalidArgument,
            "plane_mode",
        ),
        (|o| o.reserved2 = 3, TpiStatus::InvalidArgument, "reserved2"),
        (
            |o| o.far_vertex_factor = f64::NAN,
            TpiStatus::NonFinite,
            "far_vertex_factor",
        ),
        (
            |o| o.far_vertex_factor = 0.0,
            TpiStatus::InvalidArgument,
            "far_vertex_factor",
        ),
        (
            |o| o.weld_tolerance = -1.0,
            TpiStatus::InvalidArgument,
            "weld_tolerance",
        ),
        (
            |o| o.envelope_repair = 2,
            TpiStatus::InvalidArgument,
            "envelope_repair",
        ),
        (|o| o.reserved = 1, TpiStatus::InvalidArgument, "reserved"),
        (
            |o| o.struct_size = 8,
            TpiStatus::InvalidArgument,
            "struct_size",
        ),
    ];
    for (edit, status, field) in cases {
        let mut options = TpiOptions::defaults();
        edit(&mut options);
        let mut d = std::ptr::null_mut();
        // SAFETY: live handles, a full options struct, valid out pointer.
        assert_eq!(
            unsafe { tpi_discretise(surface, p, &options, &mut d) },
            status,
            "{field}"
        );
        assert!(d.is_null());
        assert!(last_error().contains(field), "{}", last_error());
    }
    // SAFETY: our handles.
    unsafe {
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn copy_out_follows_the_convention() {
    let p = pattern(&[[0.1, 0.2], [0.3, 0.4], [0.5, 0.6]]);
    let mut needed = 0usize;
    let mut buf = [-1.0f64; 6];
    // SAFETY (all calls): live handle; buffers as described.
    unsafe {
        // Size query.
        assert_eq!(
            tpi_pattern_points(p, std::ptr::null_mut(), 0, &mut needed),
            TpiStatus::BufferTooSmall
        );
        assert_eq!(needed, 6);
        // Too small: needed set, nothing written.
        needed = 0;
        assert_eq!(
            tpi_pattern_points(p, buf.as_mut_ptr(), 5, &mut needed),
            TpiStatus::BufferTooSmall
        );
        assert_eq!(needed, 6);
        assert_eq!(buf, [-1.0; 6]);
        assert!(last_error().contains("capacity 5"), "{}", last_error());
        // NULL out with a capacity.
        assert_eq!(
            tpi_pattern_points(p, std::ptr::null_mut(), 6, &mut needed),
            TpiStatus::NullPointer
        );
        // Enough, with and without `needed`.
        ok(tpi_pattern_points(
            p,
            buf.as_mut_ptr(),
            6,
            std::ptr::null_mut(),
        ));
        assert_eq!(buf, [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]);
        // Misaligned.
        let mut bytes = [0u8; 64];
        let misaligned = bytes.as_mut_ptr().add(1).cast::<f64>();
        assert_eq!(
            tpi_pattern_points(p, misaligned, 6, &mut needed),
            TpiStatus::InvalidArgument
        );
        assert!(last_error().contains("aligned"));
        tpi_pattern_free(p);
    }
}

#[test]
fn the_last_error_is_per_thread_and_cleared_by_success() {
    let mut out = std::ptr::null_mut();
    // SAFETY: NULL spec is checked.
    assert_eq!(
        unsafe { tpi_pattern_new_from_spec(std::ptr::null(), &mut out) },
        TpiStatus::NullPointer
    );
    assert_eq!(last_error(), "spec is NULL");
    let other = std::thread::spawn(last_error).join().expect("thread");
    assert_eq!(other, "");
    // Reading the message does not change it, even with a too-small buffer.
    let mut tiny = [0 as c_char; 2];
    let mut needed = 0;
    // SAFETY: tiny holds 2 chars.
    assert_eq!(
        unsafe { tpi_last_error_message(tiny.as_mut_ptr(), 2, &mut needed) },
        TpiStatus::BufferTooSmall
    );
    assert_eq!(needed, "spec is NULL".len() + 1);
    assert_eq!(last_error(), "spec is NULL");
    // SAFETY: valid out pointer.
    ok(unsafe { tpi_pattern_new_grid(2, 2, &mut out) });
    assert_eq!(last_error(), "");
    // SAFETY: our handle.
    unsafe { tpi_pattern_free(out) };
}

#[test]
fn sampling_forwards_to_the_core() {
    let surface = dome(3.0);
    let points: Vec<glam::DVec3> = dome_points(3.0)
        .chunks_exact(3)
        .map(glam::DVec3::from_slice)
        .collect();
    let core =
        NurbsSurface::new([3, 3], [4, 4], &DOME_KNOTS, &DOME_KNOTS, &points, None).expect("dome");
    let uv = [0.0, 0.0, 0.25, 0.75, 0.5, 0.5, 1.0, 0.3];
    let mut samples = [TpiSample::default(); 4];
    // SAFETY: live handle, arrays of the given lengths.
    ok(unsafe {
        tpi_surface_evaluate(
            surface,
            uv.as_ptr(),
            uv.len(),
            samples.as_mut_ptr(),
            samples.len(),
        )
    });
    for (k, sample) in samples.iter().enumerate() {
        let g = LocalGeometry::from_derivatives(&core.evaluate(uv[2 * k], uv[2 * k + 1]));
        assert_eq!(sample.point, g.point.to_array());
        assert_eq!(sample.normal, g.normal.to_array());
        assert_eq!(sample.curvatures, [g.k1, g.k2]);
        assert_eq!(sample.d1, g.d1.to_array());
        assert_eq!(sample.d2, g.d2.to_array());
        assert_eq!(sample.regular, 1);
    }
    let mut domain = TpiDomain::default();
    // SAFETY: live handle, valid out pointer.
    ok(unsafe { tpi_surface_domain(surface, &mut domain) });
    assert_eq!(
        domain,
        TpiDomain {
            u_min: 0.0,
            u_max: 1.0,
            v_min: 0.0,
            v_max: 1.0
        }
    );
    // SAFETY: our handle.
    unsafe { tpi_surface_free(surface) };
}

#[test]
fn discretising_forwards_to_the_core() {
    let surface = dome(3.0);
    let points = jittered_grid(6);
    let mesh = discretise_from_scratch(surface, &points);
    let control: Vec<glam::DVec3> = dome_points(3.0)
        .chunks_exact(3)
        .map(glam::DVec3::from_slice)
        .collect();
    let core =
        NurbsSurface::new([3, 3], [4, 4], &DOME_KNOTS, &DOME_KNOTS, &control, None).expect("dome");
    let expected = discretise(&core, &points, &DiscretiseOptions::default()).expect("discretise");
    assert_eq!(mesh.json, expected.to_json(false));
    assert_eq!(
        mesh.vertices,
        expected
            .vertices
            .iter()
            .flat_map(|v| v.to_array())
            .collect::<Vec<_>>()
    );
    assert_eq!(mesh.facet_indices, expected.facet_loops);
    assert_eq!(
        mesh.neighbour_pairs,
        expected.neighbour_pairs().as_flattened()
    );
    assert_eq!(mesh.dual_triangles, expected.dual_triangles.as_flattened());
    assert_eq!(mesh.facet_flags, expected.facet_flags);
    let quality = expected.quality.as_ref().expect("quality");
    assert_eq!(
        mesh.quality_json,
        serde_json::to_string(quality).expect("json")
    );
    assert_eq!(
        mesh.diagnostics_json,
        serde_json::to_string(&expected.diagnostics).expect("json")
    );
    let entries: usize = expected
        .diagnostics
        .iter()
        .map(|d| d.points().len().max(1))
        .sum();
    assert_eq!(mesh.diagnostic_entries.len(), entries);
    // SAFETY: our handle.
    unsafe { tpi_surface_free(surface) };
}

#[test]
fn the_quality_struct_carries_the_json_numbers() {
    let surface = dome(3.0);
    let p = pattern(&jittered_grid(6));
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, std::ptr::null(), &mut d) });
    let mut q = TpiQualityReport {
        struct_size: size_of::<TpiQualityReport>() as u32,
        ..Default::default()
    };
    // SAFETY: live handle, a full struct.
    ok(unsafe { tpi_discretisation_quality(d, &mut q) });
    // SAFETY: live handle; buffers from read_string.
    let json: serde_json::Value = serde_json::from_str(&read_string(|o, c, n| unsafe {
        tpi_discretisation_quality_json(d, o, c, n)
    }))
    .expect("json");
    assert_eq!(json["facet_count"].as_u64(), Some(q.facet_count));
    assert_eq!(json["vertex_count"].as_u64(), Some(q.vertex_count));
    assert_eq!(json["edge_count"].as_u64(), Some(q.edge_count));
    assert_eq!(
        json["euler_characteristic"].as_i64(),
        Some(q.euler_characteristic)
    );
    assert_eq!(json["max_deviation"].as_f64(), Some(q.max_deviation));
    assert_eq!(
        json["neighbours"]["envelope_repairs"].as_u64(),
        Some(q.envelope_repairs)
    );
    assert_eq!(json["diagnostic_count"].as_u64(), Some(q.diagnostic_count));
    assert_eq!(json["all_finite"].as_bool(), Some(q.all_finite == 1));
    assert_eq!(json["invalid_facets"].as_u64(), Some(q.invalid_facets));
    assert_eq!(json["open_facets"].as_u64(), Some(q.open_facets));
    assert_eq!(
        json["neighbours"]["validity_flips"].as_u64(),
        Some(q.validity_flips)
    );
    assert_eq!(q.facet_count, 36);
    assert_eq!(q.struct_size, size_of::<TpiQualityReport>() as u32);

    let mut small = TpiQualityReport {
        struct_size: 16,
        ..Default::default()
    };
    // SAFETY: live handle, a full struct.
    assert_eq!(
        unsafe { tpi_discretisation_quality(d, &mut small) },
        TpiStatus::InvalidArgument
    );
    // SAFETY: our handles.
    unsafe {
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn without_the_report_quality_is_unavailable_and_flags_are_empty() {
    let surface = dome(3.0);
    let p = pattern(&jittered_grid(5));
    let options = TpiOptions {
        quality_report: 0,
        ..TpiOptions::defaults()
    };
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, full options, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, &options, &mut d) });
    let mut q = TpiQualityReport {
        struct_size: size_of::<TpiQualityReport>() as u32,
        ..Default::default()
    };
    let mut needed = 99;
    // SAFETY: live handle; buffers as given.
    unsafe {
        assert_eq!(
            tpi_discretisation_quality(d, &mut q),
            TpiStatus::Unavailable
        );
        assert_eq!(
            tpi_discretisation_quality_json(d, std::ptr::null_mut(), 0, &mut needed),
            TpiStatus::Unavailable
        );
        ok(tpi_discretisation_facet_flags(
            d,
            std::ptr::null_mut(),
            0,
            &mut needed,
        ));
        assert_eq!(needed, 0);
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn generators_forward_to_the_core() {
    let cases: Vec<(&str, Box<dyn Fn(*mut *mut TpiPattern) -> TpiStatus>)> = vec![
        // SAFETY (all): valid out pointers.
        (
            "grid:4x3",
            Box::new(|o| unsafe { tpi_pattern_new_grid(4, 3, o) }),
        ),
        (
            "hex:5x4",
            Box::new(|o| unsafe { tpi_pattern_new_hex(5, 4, o) }),
        ),
        (
            "jitter:4x4:amount=0.3:seed=7",
            Box::new(|o| unsafe { tpi_pattern_new_jitter(4, 4, 0.3, 7, o) }),
        ),
        (
            "random:25:seed=3",
            Box::new(|o| unsafe { tpi_pattern_new_random(25, 3, o) }),
        ),
        (
            "poisson:0.2:seed=5",
            Box::new(|o| unsafe { tpi_pattern_new_poisson(0.2, 5, o) }),
        ),
    ];
    for (spec, make) in cases {
        let expected = Generator::parse(spec).expect("spec").generate().uv;
        let mut p = std::ptr::null_mut();
        ok(make(&mut p));
        // SAFETY: live handle.
        let got = read_array(|o, c, n| unsafe { tpi_pattern_points(p, o, c, n) });
        assert_eq!(got, expected.as_flattened(), "{spec}");
        let c_spec = std::ffi::CString::new(spec).expect("no NUL");
        let mut q = std::ptr::null_mut();
        // SAFETY: NUL-terminated spec, valid out pointer.
        ok(unsafe { tpi_pattern_new_from_spec(c_spec.as_ptr(), &mut q) });
        // SAFETY: live handle.
        let from_spec = read_array(|o, c, n| unsafe { tpi_pattern_points(q, o, c, n) });
        assert_eq!(from_spec, got, "{spec}");
        // SAFETY: our handles.
        unsafe {
            tpi_pattern_free(p);
            tpi_pattern_free(q);
        }
    }
    let mut p = std::ptr::null_mut();
    // SAFETY: valid out pointers.
    unsafe {
        assert_eq!(
            tpi_pattern_new_grid(0, 3, &mut p),
            TpiStatus::InvalidPattern
        );
        assert_eq!(
            tpi_pattern_new_jitter(3, 3, 1.5, 0, &mut p),
            TpiStatus::InvalidPattern
        );
        assert_eq!(
            tpi_pattern_new_random(0, 0, &mut p),
            TpiStatus::InvalidPattern
        );
        assert_eq!(
            tpi_pattern_new_poisson(f64::NAN, 0, &mut p),
            TpiStatus::InvalidPattern
        );
        let bad = c"grid:3";
        assert_eq!(
            tpi_pattern_new_from_spec(bad.as_ptr(), &mut p),
            TpiStatus::InvalidPattern
        );
        assert!(last_error().contains("grid:3"));
        let not_utf8 = c"grid:\xff";
        assert_eq!(
            tpi_pattern_new_from_spec(not_utf8.as_ptr(), &mut p),
            TpiStatus::InvalidArgument
        );
    }
    assert!(p.is_null());
}

#[test]
fn analytic_surfaces_forward_to_the_core() {
    let mut s = std::ptr::null_mut();
    let p = pattern(&jittered_grid(5));
    // SAFETY: valid out pointers, live handles; each surface freed once.
    unsafe {
        // Build and discretise each, one at a time.
        type Make = unsafe fn(*mut *mut TpiSurface) -> TpiStatus;
        let cases: [(Make, TpiStatus); 8] = [
            (
                |o| tpi_surface_new_elliptic_paraboloid(0.1, 0.2, -3.0, 3.0, -2.0, 2.0, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_hyperbolic_paraboloid(0.1, 0.2, -3.0, 3.0, -2.0, 2.0, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_sphere_cap(10.0, -3.0, 3.0, -3.0, 3.0, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_sphere_cap_square(10.0, 4.0, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_ellipsoid_cap(10.0, 8.0, 5.0, -3.0, 3.0, -3.0, 3.0, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_egg_crate(1.0, 0.3, 2.8, 0.3, 2.8, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_cylinder(5.0, -3.0, 3.0, 0.0, 10.0, o),
                TpiStatus::Ok,
            ),
            (
                |o| tpi_surface_new_plane(0.1, 0.2, 1.0, 0.0, 1.0, 0.0, 1.0, o),
                TpiStatus::Ok,
            ),
        ];
        for (k, (make, expected)) in cases.iter().enumerate() {
            let mut surface = std::ptr::null_mut();
            ok(make(&mut surface));
            let mut d = std::ptr::null_mut();
            assert_eq!(
                tpi_discretise(surface, p, std::ptr::null(), &mut d),
                *expected,
                "case {k}: {}",
                last_error()
            );
            tpi_discretisation_free(d);
            tpi_surface_free(surface);
        }
        assert_eq!(
            tpi_surface_new_sphere_cap(1.0, -3.0, 3.0, -3.0, 3.0, &mut s),
            TpiStatus::InvalidArgument
        );
        assert!(s.is_null());
        assert_eq!(
            tpi_surface_new_elliptic_paraboloid(1.0, -1.0, 0.0, 1.0, 0.0, 1.0, &mut s),
            TpiStatus::InvalidArgument
        );
        assert_eq!(
            tpi_surface_new_egg_crate(f64::NAN, 0.0, 1.0, 0.0, 1.0, &mut s),
            TpiStatus::NonFinite
        );
        assert_eq!(
            tpi_surface_new_plane(0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, &mut s),
            TpiStatus::InvalidArgument
        );
        assert!(s.is_null());
        tpi_pattern_free(p);
    }
}

#[test]
fn a_bigger_quality_struct_gets_this_librarys_fields_and_their_size() {
    #[repr(C)]
    struct Newer {
        report: TpiQualityReport,
        future: [u64; 2],
    }
    let surface = dome(3.0);
    let p = pattern(&jittered_grid(7));
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, std::ptr::null(), &mut d) });
    let mut newer = Newer {
        report: TpiQualityReport {
            struct_size: size_of::<Newer>() as u32,
            ..Default::default()
        },
        future: [7, 7],
    };
    // SAFETY: `newer` holds struct_size bytes.
    ok(unsafe { tpi_discretisation_quality(d, &mut newer.report) });
    assert_eq!(newer.report.struct_size, TPI_QUALITY_REPORT_SIZE_V3);
    assert_eq!(newer.report.facet_count, 49);
    assert_eq!(newer.future, [7, 7]);
    // SAFETY: our handles.
    unsafe {
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn a_first_version_quality_struct_gets_only_its_bytes() {
    let surface = dome(3.0);
    let p = pattern(&jittered_grid(6));
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, std::ptr::null(), &mut d) });
    // A caller compiled against the first header: the V2 fields must stay untouched.
    let sentinel = u64::MAX - 1;
    let mut q = TpiQualityReport {
        struct_size: TPI_QUALITY_REPORT_SIZE_V1,
        invalid_facets: sentinel,
        open_facets: sentinel,
        validity_flips: sentinel,
        validity_unresolved: sentinel,
        ..Default::default()
    };
    // SAFETY: live handle; the struct holds more than struct_size bytes.
    ok(unsafe { tpi_discretisation_quality(d, &mut q) });
    assert_eq!(q.struct_size, TPI_QUALITY_REPORT_SIZE_V1);
    assert_eq!(q.facet_count, 36);
    assert_eq!(
        [
            q.invalid_facets,
            q.open_facets,
            q.validity_flips,
            q.validity_unresolved
        ],
        [sentinel; 4]
    );
    // SAFETY: our handles.
    unsafe {
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn a_second_version_quality_struct_gets_only_its_bytes() {
    let surface = dome(3.0);
    let p = pattern(&jittered_grid(6));
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, valid out pointer.
    ok(unsafe { tpi_discretise(surface, p, std::ptr::null(), &mut d) });
    // A caller compiled against the second header: the V3 fields must stay untouched.
    let mut q = TpiQualityReport {
        struct_size: TPI_QUALITY_REPORT_SIZE_V2,
        far_vertex_facets: 77,
        max_deviation_spacings: -1.0,
        ..Default::default()
    };
    // SAFETY: live handle; the struct holds more than struct_size bytes.
    ok(unsafe { tpi_discretisation_quality(d, &mut q) });
    assert_eq!(q.struct_size, TPI_QUALITY_REPORT_SIZE_V2);
    assert_eq!(q.facet_count, 36);
    assert_eq!(q.invalid_facets, 0);
    assert_eq!((q.far_vertex_facets, q.max_deviation_spacings), (77, -1.0));
    // The full struct: a dome's vertices stay well within a spacing of the surface.
    let mut full = TpiQualityReport {
        struct_size: TPI_QUALITY_REPORT_SIZE_V3,
        far_vertex_facets: 77,
        ..Default::default()
    };
    // SAFETY: as above.
    ok(unsafe { tpi_discretisation_quality(d, &mut full) });
    assert_eq!(full.far_vertex_facets, 0);
    assert!(
        full.max_deviation_spacings > 0.0 && full.max_deviation_spacings < 1.0,
        "{}",
        full.max_deviation_spacings
    );
    // SAFETY: our handles.
    unsafe {
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

/// `plane_mode` TPI_PLANES_ADJUSTED reaches the core (the same mesh as the Rust API), and
/// `tpi_discretisation_planes` then gives each facet's own plane: every vertex of the facet
/// lies in it, some are tilted against the seed's normal (by at most 5 degrees), and with
/// TPI_PLANES_EXACT every plane is the seed's tangent plane. A first-version options struct
/// (40 bytes) keeps the default, exact planes.
#[test]
fn adjusted_planes_reach_the_core_and_the_planes_copy_out() {
    let mut s = std::ptr::null_mut();
    // SAFETY: valid out pointer.
    ok(unsafe { tpi_surface_new_hyperbolic_paraboloid(0.1, 0.1, -3.0, 3.0, -3.0, 3.0, &mut s) });
    let core = tpi_core::AnalyticSurface::new(
        tpi_core::AnalyticKind::HyperbolicParaboloid { a: 0.1, b: 0.1 },
        [-3.0, 3.0],
        [-3.0, 3.0],
    )
    .expect("hypar");
    let points = tpi_core::Generator::Random {
        count: 1500,
        seed: 11,
    }
    .generate()
    .uv;
    let p = pattern(&points);
    for (mode, struct_size) in [
        (TPI_PLANES_EXACT, TPI_OPTIONS_SIZE_V2),
        (TPI_PLANES_ADJUSTED, TPI_OPTIONS_SIZE_V2),
        (TPI_PLANES_ADJUSTED, TPI_OPTIONS_SIZE_V1),
    ] {
        let options = TpiOptions {
            plane_mode: mode,
            struct_size,
            ..TpiOptions::defaults()
        };
        let adjusted = mode == TPI_PLANES_ADJUSTED && struct_size == TPI_OPTIONS_SIZE_V2;
        let mut d = std::ptr::null_mut();
        // SAFETY: live handles, a full options struct, valid out pointer.
        ok(unsafe { tpi_discretise(s, p, &options, &mut d) });
        let expected = discretise(
            &core,
            &points,
            &DiscretiseOptions {
                planes: if adjusted {
                    tpi_core::PlaneMode::Adjusted
                } else {
                    tpi_core::PlaneMode::Exact
                },
                ..DiscretiseOptions::default()
            },
        )
        .expect("discretise");
        let mesh = read_mesh(d);
        assert_eq!(mesh.json, expected.to_json(false));
        // SAFETY: live handle; the copy-out convention.
        let planes: Vec<TpiPlane> =
            read_array(|o, c, n| unsafe { tpi_discretisation_planes(d, o, c, n) });
        let seeds: Vec<TpiSeed> =
            read_array(|o, c, n| unsafe { tpi_discretisation_seeds(d, o, c, n) });
        let mut tilted = 0;
        let mut offset = 0;
        for (f, (plane, seed)) in planes.iter().zip(&seeds).enumerate() {
            let normal = glam::DVec3::from_array(plane.normal);
            let point = glam::DVec3::from_array(plane.point);
            let tilt = normal
                .angle_between(glam::DVec3::from_array(seed.normal))
                .to_degrees();
            assert!(tilt <= 5.0 + 1e-9, "facet {f} tilted {tilt} degrees");
            tilted += usize::from(tilt > 1e-9);
            let corner = expected.facet(f);
            for &v in corner {
                let x = expected.vertices[v as usize];
                assert!(
                    normal.dot(x - point).abs() <= 1e-9,
                    "facet {f}: vertex {v} off its plane"
                );
            }
            offset += usize::from(point != glam::DVec3::from_array(seed.point));
        }
        if adjusted {
            assert!(tilted > 0, "no plane was adjusted");
            assert_eq!(expected.quality.as_ref().map(|q| q.invalid_facets), Some(0));
        } else {
            assert_eq!((tilted, offset), (0, 0));
        }
        // SAFETY: our handle.
        unsafe { tpi_discretisation_free(d) };
    }
    // SAFETY: our handles.
    unsafe {
        tpi_pattern_free(p);
        tpi_surface_free(s);
    }
}

/// The dome's NURBS call with the control points and weights given.
fn nurbs_with(points: &[f64], weights: &[f64]) -> (TpiStatus, String) {
    let mut surface = std::ptr::null_mut();
    // SAFETY: every array is valid for its length; `surface` is a valid out pointer.
    let status = unsafe {
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
            if weights.is_empty() {
                std::ptr::null()
            } else {
                weights.as_ptr()
            },
            weights.len(),
            &mut surface,
        )
    };
    let message = last_error();
    // SAFETY: NULL or our handle.
    unsafe { tpi_surface_free(surface) };
    (status, message)
}

/// Issue 14: a control point at 1e308 (or a weight of 5e-324 beside weights of 1) was
/// accepted and evaluated to infinities; both are refused by name, with the bound, and the
/// numbers print in shortest round-trip form.
#[test]
fn unrepresentable_nurbs_are_refused_with_the_bound() {
    let mut points = dome_points(3.0);
    points[3 * 5] = 1e308;
    let (status, message) = nurbs_with(&points, &[]);
    assert_eq!(status, TpiStatus::InvalidNurbs, "{message}");
    assert!(
        message.contains("points[5][0] (control point u 1, v 1) = 1e308")
            && message.contains("1e15"),
        "{message}"
    );
    let mut weights = vec![1.0; 16];
    weights[0] = 5e-324;
    let (status, message) = nurbs_with(&dome_points(3.0), &weights);
    assert_eq!(status, TpiStatus::InvalidNurbs, "{message}");
    assert!(
        message.contains("weights[0] (control point u 0, v 0) = 5e-324"),
        "{message}"
    );
    weights[0] = 1e-7;
    let (status, message) = nurbs_with(&dome_points(3.0), &weights);
    assert_eq!(status, TpiStatus::InvalidNurbs, "{message}");
    assert!(message.contains("<= 1000000"), "{message}");
}

/// Issue 14: the C ABI's messages had no length limit (a long spec was quoted whole).
#[test]
fn messages_are_bounded() {
    let spec = format!("grid:{}x3\0", "9".repeat(100_000));
    let mut out = std::ptr::null_mut();
    // SAFETY: NUL-terminated string, valid out pointer.
    let status = unsafe { tpi_pattern_new_from_spec(spec.as_ptr().cast(), &mut out) };
    assert_eq!(status, TpiStatus::InvalidPattern);
    let message = last_error();
    assert!(message.len() < 1024, "{} bytes", message.len());
    assert!(message.contains("grid:999"), "{message}");
}
