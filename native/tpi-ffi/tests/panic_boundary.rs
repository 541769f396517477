//! The panic boundary: a panic inside an entry point returns TPI_STATUS_PANIC, records a
//! message, and leaves the library usable; it never unwinds into (and aborts) the host.
//!
//! `tpi_debug_panic` exists only with the `debug-panic` feature, which this crate enables for
//! its own tests through a dev-dependency on itself; the released library and the header do
//! not have it (tests/header.rs and tests/run_c_tests.sh check that).

use std::ffi::CStr;

use tpi::boundary::{run, run_infallible, FfiError};
use tpi::TpiStatus;

fn last_error() -> String {
    let mut buf = vec![0 as std::ffi::c_char; 1024];
    let mut needed = 0usize;
    // SAFETY: buf holds 1024 chars; needed is a valid usize.
    let status = unsafe { tpi::tpi_last_error_message(buf.as_mut_ptr(), buf.len(), &mut needed) };
    assert_eq!(status, TpiStatus::Ok);
    // SAFETY: the call wrote a NUL-terminated string.
    unsafe { CStr::from_ptr(buf.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn an_injected_panic_in_an_exported_call_returns_the_panic_status() {
    let status = tpi::tpi_debug_panic();
    assert_eq!(status, TpiStatus::Panic);
    assert_eq!(status as u32, 9);
    let message = last_error();
    assert!(message.contains("caught panic"), "{message}");
    assert!(
        message.contains("tpi_debug_panic: injected panic"),
        "{message}"
    );
}

#[test]
fn the_library_stays_usable_after_a_panic() {
    assert_eq!(tpi::tpi_debug_panic(), TpiStatus::Panic);
    let mut pattern: *mut tpi::TpiPattern = std::ptr::null_mut();
    // SAFETY: `pattern` is a valid out pointer.
    assert_eq!(
        unsafe { tpi::tpi_pattern_new_grid(3, 3, &mut pattern) },
        TpiStatus::Ok
    );
    assert!(!pattern.is_null());
    assert_eq!(last_error(), "", "a successful call clears the message");
    let mut count = 0usize;
    // SAFETY: live handle, valid out pointer.
    assert_eq!(
        unsafe { tpi::tpi_pattern_point_count(pattern, &mut count) },
        TpiStatus::Ok
    );
    assert_eq!(count, 9);
    // SAFETY: the handle is ours and freed once.
    unsafe { tpi::tpi_pattern_free(pattern) };
}

#[test]
fn panics_on_several_threads_are_caught_on_each() {
    let handles: Vec<_> = (0..4)
        .map(|_| std::thread::spawn(|| (tpi::tpi_debug_panic(), last_error())))
        .collect();
    for h in handles {
        let (status, message) = h.join().expect("the thread must not die");
        assert_eq!(status, TpiStatus::Panic);
        assert!(message.contains("injected panic"), "{message}");
    }
}

#[test]
fn the_boundary_function_every_entry_point_uses_catches_string_and_other_payloads() {
    let status = run(|| std::panic::panic_any(format!("formatted {}", 42)));
    assert_eq!(status, TpiStatus::Panic);
    assert!(last_error().contains("formatted 42"));

    let status = run(|| std::panic::panic_any(17u8));
    assert_eq!(status, TpiStatus::Panic);
    assert!(last_error().contains("(no message)"));

    let status = run(|| Err(FfiError::invalid("not a panic")));
    assert_eq!(status, TpiStatus::InvalidArgument);
    assert_eq!(last_error(), "not a panic");

    assert_eq!(run(|| Ok(())), TpiStatus::Ok);
    assert_eq!(last_error(), "");

    let value = run_infallible(7, || -> i32 { std::panic::panic_any("in a free") });
    assert_eq!(value, 7);
}

#[test]
fn unwinding_is_on() {
    // With panic = "abort" the crate refuses to compile; this documents the requirement for
    // the test profile too.
    const { assert!(cfg!(panic = "unwind")) };
}
