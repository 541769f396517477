//! Shared helpers of the end-to-end tests: the built `tpi` binary, the sample files, scratch
//! directories. Each test file uses what it needs.
#![allow(unreachable_pub, dead_code)]

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The `tpi` binary Cargo built for these tests.
pub const TPI: &str = env!("CARGO_BIN_EXE_tpi");

/// The repository's `samples/` folder.
pub fn samples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples")
}

/// The path of one sample file.
pub fn sample(name: &str) -> String {
    samples().join(name).to_string_lossy().into_owned()
}

/// A fresh empty scratch directory for one test (named after the test file, the process and
/// a counter, so tests running at once never share one).
pub fn scratch(name: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "tpi-{}-{}-{}-{name}",
        env!("CARGO_CRATE_NAME"),
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `tpi` with `args`.
pub fn tpi(args: &[&str]) -> Output {
    Command::new(TPI).args(args).output().expect("run tpi")
}

/// Bytes of a child's output as text.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// A run's stderr as text.
pub fn stderr(o: &Output) -> String {
    text(&o.stderr)
}
