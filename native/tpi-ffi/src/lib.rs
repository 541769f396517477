//! C ABI over tpi-core. Every entry point runs behind a panic boundary.

/// Library version as a NUL-terminated string.
#[no_mangle]
pub extern "C" fn tpi_version() -> *const std::ffi::c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}
