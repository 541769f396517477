//! The version macros of include/tpi.h, the Rust constants behind them and `tpi_version()`
//! all match the package version in Cargo.toml.

use std::ffi::CStr;

fn header() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../include/tpi.h"))
        .expect("read include/tpi.h")
}

fn header_define(name: &str) -> u32 {
    let text = header();
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("#define {name} ")))
        .unwrap_or_else(|| panic!("include/tpi.h has no #define {name}"));
    line[format!("#define {name} ").len()..]
        .trim()
        .parse()
        .expect("a number")
}

fn cargo(part: &str) -> u32 {
    part.parse().expect("a numeric version part")
}

#[test]
fn rust_constants_match_cargo_toml() {
    assert_eq!(
        tpi::TPI_VERSION_MAJOR,
        cargo(env!("CARGO_PKG_VERSION_MAJOR"))
    );
    assert_eq!(
        tpi::TPI_VERSION_MINOR,
        cargo(env!("CARGO_PKG_VERSION_MINOR"))
    );
    assert_eq!(
        tpi::TPI_VERSION_PATCH,
        cargo(env!("CARGO_PKG_VERSION_PATCH"))
    );
}

#[test]
fn header_macros_match_cargo_toml() {
    assert_eq!(
        header_define("TPI_VERSION_MAJOR"),
        cargo(env!("CARGO_PKG_VERSION_MAJOR"))
    );
    assert_eq!(
        header_define("TPI_VERSION_MINOR"),
        cargo(env!("CARGO_PKG_VERSION_MINOR"))
    );
    assert_eq!(
        header_define("TPI_VERSION_PATCH"),
        cargo(env!("CARGO_PKG_VERSION_PATCH"))
    );
}

#[test]
fn tpi_version_returns_the_cargo_version() {
    // SAFETY: tpi_version returns a static NUL-terminated string.
    let version = unsafe { CStr::from_ptr(tpi::tpi_version()) }
        .to_str()
        .expect("UTF-8");
    assert_eq!(version, env!("CARGO_PKG_VERSION"));
    assert_eq!(
        version,
        format!(
            "{}.{}.{}",
            tpi::TPI_VERSION_MAJOR,
            tpi::TPI_VERSION_MINOR,
            tpi::TPI_VERSION_PATCH
        )
    );
}
