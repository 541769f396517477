//! Issue 13, item 4: `tpi_discretise_with_progress` reports each stage's progress to a C
//! callback and stops when the callback returns nonzero. Checked here: the reports are well
//! formed (stages in pipeline order, done never above total and at total when a stage ends),
//! the result is byte for byte `tpi_discretise`'s, and a cancel from the callback gives
//! TPI_STATUS_CANCELLED, no handle, a message naming the stage, and no later stage started.

mod common;

use std::ffi::c_void;
use std::sync::Mutex;

use common::*;
use tpi::*;

/// What the callback saw, and when it asks to cancel.
struct Log {
    calls: Mutex<Vec<(u32, u64, u64)>>,
    /// Cancel at the first call of this stage.
    cancel_at: Option<u32>,
}

unsafe extern "C" fn record(user_data: *mut c_void, stage: u32, done: u64, total: u64) -> i32 {
    // SAFETY: the tests pass a &Log that outlives the call.
    let log = unsafe { &*(user_data as *const Log) };
    log.calls.lock().unwrap().push((stage, done, total));
    i32::from(log.cancel_at == Some(stage))
}

fn run(
    surface: *const TpiSurface,
    pattern: *const TpiPattern,
    log: &Log,
) -> (TpiStatus, *mut TpiDiscretisation) {
    let mut out = std::ptr::null_mut();
    // SAFETY: live handles, a callback that only reads its Log, valid out pointer.
    let status = unsafe {
        tpi_discretise_with_progress(
            surface,
            pattern,
            std::ptr::null(),
            Some(record),
            log as *const Log as *mut c_void,
            &mut out,
        )
    };
    (status, out)
}

#[test]
fn progress_is_reported_stage_by_stage_and_the_result_is_unchanged() {
    let surface = dome(2.0);
    let points = jittered_grid(60);
    let p = pattern(&points);
    let log = Log {
        calls: Mutex::default(),
        cancel_at: None,
    };
    let (status, d) = run(surface, p, &log);
    ok(status);
    assert_eq!(read_mesh(d), discretise_from_scratch(surface, &points));
    let calls = log.calls.into_inner().unwrap();
    let stages: Vec<u32> = {
        let mut s: Vec<u32> = calls.iter().map(|c| c.0).collect();
        s.dedup();
        s
    };
    assert_eq!(
        stages,
        [
            TPI_STAGE_SAMPLES,
            TPI_STAGE_DELAUNAY,
            TPI_STAGE_NEIGHBOURS,
            TPI_STAGE_FACETS,
            TPI_STAGE_MESH,
            TPI_STAGE_REPORT
        ]
    );
    for stage in stages {
        let of: Vec<_> = calls.iter().filter(|c| c.0 == stage).collect();
        // Starts at 0, never goes back, never above the total, ends at the total.
        assert_eq!(of[0].1, 0, "{of:?}");
        assert!(of.windows(2).all(|w| w[0].1 <= w[1].1), "{of:?}");
        assert!(of.iter().all(|c| c.2 == of[0].2 && c.1 <= c.2), "{of:?}");
        assert_eq!(of.last().unwrap().1, of[0].2, "{of:?}");
        // At most about one report per percent, plus the start and the end.
        assert!(of.len() <= 103, "{} reports", of.len());
    }
    // The samples' total is the pattern's size.
    assert_eq!(calls[0], (TPI_STAGE_SAMPLES, 0, points.len() as u64));
    // SAFETY: our handles, freed once.
    unsafe {
        tpi_discretisation_free(d);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn a_nonzero_return_cancels_in_that_stage() {
    let surface = dome(2.0);
    let p = pattern(&jittered_grid(40));
    for stage in [
        TPI_STAGE_SAMPLES,
        TPI_STAGE_DELAUNAY,
        TPI_STAGE_NEIGHBOURS,
        TPI_STAGE_FACETS,
        TPI_STAGE_MESH,
        TPI_STAGE_REPORT,
    ] {
        let log = Log {
            calls: Mutex::default(),
            cancel_at: Some(stage),
        };
        let (status, d) = run(surface, p, &log);
        assert_eq!(status, TpiStatus::Cancelled, "stage {stage}");
        assert!(d.is_null());
        let message = last_error();
        let names = [
            "samples",
            "delaunay",
            "neighbours",
            "facets",
            "mesh",
            "report",
        ];
        // The facets and the mesh assembly are one step: asked in the facets, the call
        // stops after the mesh.
        let stops = if stage == TPI_STAGE_FACETS {
            TPI_STAGE_MESH
        } else {
            stage
        };
        assert!(
            message.contains("cancelled") && message.contains(names[stops as usize]),
            "{message}"
        );
        // No stage after the one it stopped in was started.
        let calls = log.calls.into_inner().unwrap();
        assert!(calls.iter().all(|c| c.0 <= stops), "{calls:?}");
        assert_eq!(calls.last().unwrap().0, stops);
    }
    // The handles are untouched: a run without a callback still succeeds, and equals one
    // with a callback that never cancels.
    let mut d = std::ptr::null_mut();
    // SAFETY: live handles, no callback, valid out pointer.
    ok(unsafe {
        tpi_discretise_with_progress(
            surface,
            p,
            std::ptr::null(),
            None,
            std::ptr::null_mut(),
            &mut d,
        )
    });
    let log = Log {
        calls: Mutex::default(),
        cancel_at: None,
    };
    let (status, watched) = run(surface, p, &log);
    ok(status);
    assert_eq!(read_mesh(d), read_mesh(watched));
    // SAFETY: our handles, freed once.
    unsafe {
        tpi_discretisation_free(d);
        tpi_discretisation_free(watched);
        tpi_pattern_free(p);
        tpi_surface_free(surface);
    }
}

#[test]
fn null_arguments_are_refused_before_any_report() {
    let p = pattern(&jittered_grid(5));
    let log = Log {
        calls: Mutex::default(),
        cancel_at: None,
    };
    let (status, d) = run(std::ptr::null(), p, &log);
    assert_eq!(status, TpiStatus::NullPointer);
    assert!(d.is_null());
    assert!(last_error().contains("surface"));
    assert!(log.calls.lock().unwrap().is_empty());
    // SAFETY: our handle, freed once.
    unsafe { tpi_pattern_free(p) };
}
