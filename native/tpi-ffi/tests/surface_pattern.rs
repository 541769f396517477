//! `tpi_pattern_new_for_surface`, `tpi_pattern_fit_report`, `tpi_pattern_hex_baseline`: the
//! conventions (NULL, UTF-8, options, struct sizes, `*out` NULL after a failure) and that the
//! options reach the core: the points equal the Rust API's (`SurfacePatternSpec` run on the
//! same analytic surface with the same options). The fit's tolerance itself is checked from C
//! against the sphere's closed form (tests/c/test_tpi.c).

mod common;

use std::mem::size_of;

use common::*;
use tpi::*;
use tpi_core::{AnalyticSurface, DiscretiseOptions, PlaneMode, SurfacePatternSpec};

fn saddle() -> *mut TpiSurface {
    let mut s = std::ptr::null_mut();
    // SAFETY: valid out pointer.
    ok(unsafe { tpi_surface_new_hyperbolic_paraboloid(0.3, 0.2, -2.0, 2.0, -2.0, 2.0, &mut s) });
    s
}

fn points(p: *const TpiPattern) -> Vec<f64> {
    // SAFETY: live handle.
    read_array(|o, c, n| unsafe { tpi_pattern_points(p, o, c, n) })
}

#[test]
fn the_points_are_the_rust_apis_with_the_options_given() {
    let surface = saddle();
    let core = AnalyticSurface::hyperbolic_paraboloid(0.3, 0.2, [-2.0, 2.0], [-2.0, 2.0]).unwrap();
    let spec = "relax:3:align:hex:8x8:asymptotic";
    let mut options = TpiOptions::defaults();
    options.plane_mode = TPI_PLANES_ADJUSTED;
    for (given, core_options) in [
        (std::ptr::null(), DiscretiseOptions::default()),
        (
            &options as *const TpiOptions,
            DiscretiseOptions {
                planes: PlaneMode::Adjusted,
                ..Default::default()
            },
        ),
    ] {
        let text = std::ffi::CString::new(spec).unwrap();
        let mut p = std::ptr::null_mut();
        // SAFETY: live handle, NUL-terminated spec, options NULL or a full TpiOptions.
        ok(unsafe { tpi_pattern_new_for_surface(surface, text.as_ptr(), given, &mut p) });
        let expected = SurfacePatternSpec::parse(spec)
            .unwrap()
            .generate(&core, &core_options)
            .unwrap()
            .uv;
        assert_eq!(points(p), expected.as_flattened());
        let mut report = TpiFitReport {
            struct_size: size_of::<TpiFitReport>() as u32,
            ..Default::default()
        };
        // SAFETY: live handle, valid report.
        assert_eq!(
            unsafe { tpi_pattern_fit_report(p, &mut report) },
            TpiStatus::Unavailable
        );
        // SAFETY: our handle.
        unsafe { tpi_pattern_free(p) };
    }
    // SAFETY: our handle.
    unsafe { tpi_surface_free(surface) };
}

#[test]
fn a_fit_report_is_written_up_to_the_callers_size() {
    let surface = saddle();
    let mut p = std::ptr::null_mut();
    // SAFETY: live handle, static spec, valid out pointer.
    ok(unsafe {
        tpi_pattern_new_for_surface(surface, c"fit:0.05".as_ptr(), std::ptr::null(), &mut p)
    });
    // A caller with a bigger (future) struct: only 40 bytes are written, and it is told so.
    #[repr(C)]
    struct Bigger {
        report: TpiFitReport,
        extra: [u64; 3],
    }
    let mut big = Bigger {
        report: TpiFitReport {
            struct_size: size_of::<Bigger>() as u32,
            ..Default::default()
        },
        extra: [7; 3],
    };
    // SAFETY: `big` holds struct_size bytes.
    ok(unsafe { tpi_pattern_fit_report(p, &mut big.report) });
    assert_eq!(big.report.struct_size, TPI_FIT_REPORT_SIZE_V1);
    assert_eq!(big.extra, [7; 3]);
    assert_eq!(big.report.tolerance, 0.05);
    assert_eq!(big.report.met, 1);
    assert!(big.report.max_deviation <= 0.05 && big.report.discretisations >= 1);
    let mut small = TpiFitReport {
        struct_size: 8,
        ..Default::default()
    };
    // SAFETY: live handle, valid report.
    assert_eq!(
        unsafe { tpi_pattern_fit_report(p, &mut small) },
        TpiStatus::InvalidArgument
    );
    assert!(last_error().contains("struct_size"));
    assert_eq!(small.met, 0); // nothing written
                              // SAFETY: our handles.
    unsafe {
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn failures_create_nothing_and_name_the_argument() {
    let surface = saddle();
    let dangling = std::ptr::NonNull::<TpiPattern>::dangling().as_ptr();
    let cases: [(&std::ffi::CStr, TpiStatus, &str); 4] = [
        (c"relax:x:hex:4x4", TpiStatus::InvalidPattern, "relax:x"),
        (c"grid:\xff", TpiStatus::InvalidArgument, "UTF-8"),
        (c"align:hex:4x4:@grain.json", TpiStatus::InvalidPattern, "inline"),
        (
            c"density:{\"spacing\": 0.5, \"terms\": [{\"type\": \"image\", \"file\": \"g.pgm\", \"low\": 1, \"high\": 2}]}",
            TpiStatus::InvalidPattern,
            "g.pgm",
        ),
    ];
    for (spec, status, needle) in cases {
        let mut p = dangling;
        // SAFETY: live handle, NUL-terminated spec, valid out pointer.
        let got = unsafe {
            tpi_pattern_new_for_surface(surface, spec.as_ptr(), std::ptr::null(), &mut p)
        };
        assert_eq!(got, status, "{spec:?}");
        assert!(p.is_null(), "{spec:?}: *out not reset");
        assert!(last_error().contains(needle), "{spec:?}: {}", last_error());
    }
    let mut bad = TpiOptions::defaults();
    bad.struct_size = 4;
    let mut p = std::ptr::null_mut();
    // SAFETY: as above; `bad` is a full struct.
    unsafe {
        assert_eq!(
            tpi_pattern_new_for_surface(surface, c"hex:4x4".as_ptr(), &bad, &mut p),
            TpiStatus::InvalidArgument
        );
        assert_eq!(
            tpi_pattern_new_for_surface(
                std::ptr::null(),
                c"hex:4x4".as_ptr(),
                std::ptr::null(),
                &mut p
            ),
            TpiStatus::NullPointer
        );
        let (mut count, mut deviation) = (5usize, 0.0);
        for d in [0.0, -1.0, f64::NAN] {
            let status = tpi_pattern_hex_baseline(
                surface,
                d,
                100,
                std::ptr::null(),
                &mut count,
                &mut deviation,
            );
            assert_ne!(status, TpiStatus::Ok, "{d}");
            assert!(last_error().contains("max_deviation"), "{}", last_error());
        }
        assert_eq!(count, 5); // nothing written
        assert_eq!(
            tpi_pattern_hex_baseline(
                surface,
                0.1,
                100,
                std::ptr::null(),
                std::ptr::null_mut(),
                &mut deviation
            ),
            TpiStatus::NullPointer
        );
        tpi_surface_free(surface);
    }
    assert!(p.is_null());
}

/// Counts the discretisations a pattern runs (a call for the samples stage with `done` 0
/// starts one) and asks to cancel once `cancel_at` of them have started (0: never).
struct Runs {
    started: std::sync::atomic::AtomicU64,
    cancel_at: u64,
}

unsafe extern "C" fn count_runs(
    user_data: *mut std::ffi::c_void,
    stage: u32,
    done: u64,
    _total: u64,
) -> i32 {
    // SAFETY: the test passes a &Runs that outlives the call.
    let runs = unsafe { &*(user_data as *const Runs) };
    let ordering = std::sync::atomic::Ordering::SeqCst;
    if stage == TPI_STAGE_SAMPLES && done == 0 {
        runs.started.fetch_add(1, ordering);
    }
    i32::from(runs.cancel_at != 0 && runs.started.load(ordering) >= runs.cancel_at)
}

fn with_progress(
    surface: *const TpiSurface,
    spec: &std::ffi::CStr,
    runs: Option<&Runs>,
) -> (TpiStatus, *mut TpiPattern) {
    let mut p = std::ptr::null_mut();
    let (callback, user_data): (TpiProgressCallback, *mut std::ffi::c_void) = match runs {
        Some(r) => (Some(count_runs), r as *const Runs as *mut std::ffi::c_void),
        None => (None, std::ptr::null_mut()),
    };
    // SAFETY: live handle, NUL-terminated spec, a callback that only counts, valid out.
    let status = unsafe {
        tpi_pattern_new_for_surface_with_progress(
            surface,
            spec.as_ptr(),
            std::ptr::null(),
            callback,
            user_data,
            &mut p,
        )
    };
    (status, p)
}

fn fit_report(p: *const TpiPattern) -> Option<TpiFitReport> {
    let mut report = TpiFitReport {
        struct_size: size_of::<TpiFitReport>() as u32,
        ..Default::default()
    };
    // SAFETY: live handle, valid report.
    (unsafe { tpi_pattern_fit_report(p, &mut report) } == TpiStatus::Ok).then_some(report)
}

/// `tpi_pattern_new_for_surface_with_progress`: the same points and fit report as without a
/// callback; one samples-stage start per discretisation the form runs (the fit's own count;
/// one per Lloyd iteration); a nonzero return gives TPI_STATUS_CANCELLED, no handle, a
/// message saying so, and no further discretisation started.
#[test]
fn a_fit_and_a_relaxation_report_each_discretisation_and_can_be_cancelled() {
    let surface = saddle();
    for (spec, lloyd) in [(c"fit:0.05", None), (c"relax:3:random:150", Some(3u64))] {
        let mut plain = std::ptr::null_mut();
        // SAFETY: live handle, NUL-terminated spec, valid out pointer.
        ok(unsafe {
            tpi_pattern_new_for_surface(surface, spec.as_ptr(), std::ptr::null(), &mut plain)
        });
        let (status, silent) = with_progress(surface, spec, None);
        ok(status);
        let counter = Runs {
            started: Default::default(),
            cancel_at: 0,
        };
        let (status, watched) = with_progress(surface, spec, Some(&counter));
        ok(status);
        assert_eq!(points(plain), points(silent), "{spec:?}");
        assert_eq!(points(plain), points(watched), "{spec:?}");
        assert_eq!(fit_report(plain), fit_report(watched), "{spec:?}");
        let expected = lloyd.unwrap_or_else(|| fit_report(plain).unwrap().discretisations);
        assert!(expected >= 3, "{spec:?}: {expected}");
        assert_eq!(counter.started.into_inner(), expected, "{spec:?}");

        let stopper = Runs {
            started: Default::default(),
            cancel_at: 2,
        };
        let (status, cancelled) = with_progress(surface, spec, Some(&stopper));
        assert_eq!(status, TpiStatus::Cancelled, "{spec:?}");
        assert!(cancelled.is_null());
        assert!(last_error().contains("cancelled"), "{}", last_error());
        assert_eq!(stopper.started.into_inner(), 2, "{spec:?}");
        // SAFETY: our handles.
        unsafe {
            tpi_pattern_free(plain);
            tpi_pattern_free(silent);
            tpi_pattern_free(watched);
        }
    }
    // SAFETY: our handle.
    unsafe { tpi_surface_free(surface) };
}
