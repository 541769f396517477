//! include/tpi.h is exactly what the pinned cbindgen generates from this crate.
//!
//! The check needs no network: cbindgen is a dev-dependency (from crates.io, pinned in
//! Cargo.toml and Cargo.lock) and reads the sources directly, without `cargo metadata`.
//! To update the committed header after changing the ABI:
//!
//! ```text
//! TPI_BLESS=1 cargo test -p tpi-ffi --test header
//! ```

use std::path::{Path, PathBuf};

fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn header_path() -> PathBuf {
    crate_dir().join("../../include/tpi.h")
}

/// The header as cbindgen generates it now.
pub fn generate() -> String {
    let dir = crate_dir();
    let config =
        cbindgen::Config::from_file(dir.join("cbindgen.toml")).expect("cbindgen.toml must parse");
    let bindings = cbindgen::Builder::new()
        .with_config(config)
        .with_src(dir.join("src/lib.rs"))
        .generate()
        .expect("cbindgen must generate the header");
    let mut bytes = Vec::new();
    bindings.write(&mut bytes);
    String::from_utf8(bytes).expect("the header is UTF-8")
}

fn first_difference(a: &str, b: &str) -> String {
    for (n, (x, y)) in a.lines().zip(b.lines()).enumerate() {
        if x != y {
            return format!("line {}:\n  committed: {x}\n  generated: {y}", n + 1);
        }
    }
    format!(
        "lengths differ: committed {} lines, generated {} lines",
        a.lines().count(),
        b.lines().count()
    )
}

#[test]
fn committed_header_matches_a_fresh_generation() {
    let fresh = generate();
    let path = header_path();
    if std::env::var_os("TPI_BLESS").is_some_and(|v| v == "1") {
        std::fs::write(&path, &fresh).expect("write include/tpi.h");
        return;
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == fresh,
        "include/tpi.h is stale ({}); regenerate it with `TPI_BLESS=1 cargo test -p tpi-ffi --test header`\n{}",
        Path::new("include/tpi.h").display(),
        first_difference(&committed, &fresh)
    );
}

#[test]
fn header_declares_no_test_only_entry_points() {
    let fresh = generate();
    assert!(
        !fresh.contains("tpi_debug_panic"),
        "the panic-injection entry point must stay out of the header"
    );
}
