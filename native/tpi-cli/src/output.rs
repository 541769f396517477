//! Reading inputs and writing outputs without ever leaving a partial file.
//!
//! All outputs of a run are computed in memory first. [`write_all`] then writes each to a
//! temporary file in its target's directory, and only when every one of them is written
//! completely (and synced) renames them into place. On any failure every temporary file is
//! removed (and any output already renamed by this run), so a failing run leaves no output
//! behind and an existing file of the same name is untouched unless the whole run succeeds.

use std::fs::{self, File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::error::CliError;

/// Reads a text input file, naming it in the error.
pub(crate) fn read_text(path: &Path) -> Result<String, CliError> {
    if path.is_dir() {
        return Err(CliError::input(
            path.display(),
            "cannot read: is a directory",
        ));
    }
    fs::read_to_string(path).map_err(|e| CliError::io(path, "cannot read", &e))
}

/// The directory a path's file lives in ("." for a bare file name).
fn parent_dir(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Cheap early check of an output path, before any work is done: its directory exists and
/// it is not itself a directory. (Permissions are found out when writing.)
pub(crate) fn check_output_path(path: &Path) -> Result<(), CliError> {
    let dir = parent_dir(path);
    if path.file_name().is_none() {
        return Err(CliError::input(
            path.display(),
            "cannot write: not a file name",
        ));
    }
    if !dir.exists() {
        return Err(CliError::input(
            path.display(),
            format!("cannot write: directory {} does not exist", dir.display()),
        ));
    }
    if !dir.is_dir() {
        return Err(CliError::input(
            path.display(),
            format!("cannot write: {} is not a directory", dir.display()),
        ));
    }
    if path.is_dir() {
        return Err(CliError::input(
            path.display(),
            "cannot write: is a directory",
        ));
    }
    Ok(())
}

static TEMP_COUNTER: AtomicUsize = AtomicUsize::new(0);

/// A fresh temporary path beside `path`: `.NAME.tpi-tmp-PID-N`.
fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    parent_dir(path).join(format!(".{name}.tpi-tmp-{}-{n}", std::process::id()))
}

fn write_temp(path: &Path, bytes: &[u8]) -> Result<PathBuf, CliError> {
    let temp = temp_path(path);
    let result = (|| {
        let mut file: File = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)?;
        file.write_all(bytes)?;
        file.sync_all()
    })();
    match result {
        Ok(()) => Ok(temp),
        Err(e) => {
            let _ = fs::remove_file(&temp);
            Err(CliError::io(path, "cannot write", &e))
        }
    }
}

/// Writes every `(path, bytes)` pair, all or nothing (see the module doc).
pub(crate) fn write_all(outputs: &[(PathBuf, Vec<u8>)]) -> Result<(), CliError> {
    let mut temps: Vec<PathBuf> = Vec::with_capacity(outputs.len());
    for (path, bytes) in outputs {
        match check_output_path(path).and_then(|()| write_temp(path, bytes)) {
            Ok(temp) => temps.push(temp),
            Err(e) => {
                for t in &temps {
                    let _ = fs::remove_file(t);
                }
                return Err(e);
            }
        }
    }
    for (k, ((path, _), temp)) in outputs.iter().zip(&temps).enumerate() {
        if let Err(e) = fs::rename(temp, path) {
            for t in &temps[k..] {
                let _ = fs::remove_file(t);
            }
            for (done, _) in &outputs[..k] {
                let _ = fs::remove_file(done);
            }
            return Err(CliError::io(path, "cannot write", &e));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_or_nothing() {
        let dir = std::env::temp_dir().join(format!("tpi-output-test-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let good = dir.join("a.txt");
        let bad = dir.join("missing").join("b.txt");
        let err = write_all(&[(good.clone(), b"a".to_vec()), (bad, b"b".to_vec())]).unwrap_err();
        assert!(err.to_string().contains("b.txt"), "{err}");
        assert!(!good.exists());
        assert_eq!(
            fs::read_dir(&dir).unwrap().count(),
            0,
            "temporary files left"
        );
        write_all(&[(good.clone(), b"a".to_vec())]).unwrap();
        assert_eq!(fs::read(&good).unwrap(), b"a");
        fs::remove_dir_all(&dir).unwrap();
    }
}
