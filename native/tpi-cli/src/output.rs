//! Reading inputs and writing outputs without ever leaving a partial file.
//!
//! All outputs of a run are computed in memory first. [`write_all`] then writes each to a
//! temporary file in its target's directory, and only when every one of them is written
//! completely (and synced) renames them into place. On any failure every temporary file is
//! removed (and any output already renamed by this run is put back as it was: an existing
//! file is moved aside to a backup before it is replaced, and restored when a later rename
//! fails), so a failing run leaves no output behind and an existing file of the same name is
//! untouched unless the whole run succeeds. SIGINT and SIGTERM remove the temporaries
//! ([`clean_up_on_signals`]); concurrent runs commit one after the other (a lock on each
//! output directory during the renames); an output that is also an input is refused
//! ([`check_not_an_input`]).

use std::fs::{self, File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

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

/// Environment variable (for tests only): milliseconds to wait after every temporary file
/// is written and before the renames, so that a test can signal the process while the
/// temporaries exist.
pub(crate) const PAUSE_VARIABLE: &str = "TPI_TEST_PAUSE_BEFORE_COMMIT_MS";

/// A fresh path beside `path`: `.NAME.tpi-KIND-PID-N`.
fn sibling(path: &Path, kind: &str) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    parent_dir(path).join(format!(".{name}.tpi-{kind}-{}-{n}", std::process::id()))
}

/// The temporary files of the run that exist right now. The signal handler removes them;
/// the commit holds the lock from its first rename to its last, so the handler sees the
/// temporaries either all before the commit or none after it.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Removes every temporary file of the run (on a signal, or on a failure).
fn remove_pending(pending: &mut Vec<PathBuf>) {
    for t in pending.drain(..) {
        let _ = fs::remove_file(t);
    }
}

/// On SIGINT or SIGTERM: remove the temporary files and exit with 128 + the signal number,
/// as the default action's status reads in a shell. Outputs already in place stay (a commit
/// in progress finishes first). Called once, before anything is written.
pub(crate) fn clean_up_on_signals() {
    #[cfg(unix)]
    {
        use signal_hook::consts::{SIGINT, SIGTERM};
        if let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) {
            let _ = std::thread::Builder::new()
                .name("tpi-signals".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        let mut pending = pending();
                        remove_pending(&mut pending);
                        std::process::exit(128 + signal);
                    }
                });
        }
    }
}

/// Creates the temporary file for `path` (registered for the signal handler before it
/// exists on disk, under the lock) and writes and syncs it.
fn write_temp(path: &Path, bytes: &[u8]) -> Result<PathBuf, CliError> {
    let temp = sibling(path, "tmp");
    let created = {
        let mut pending = pending();
        let file = OpenOptions::new().write(true).create_new(true).open(&temp);
        if file.is_ok() {
            pending.push(temp.clone());
        }
        file
    };
    let result = created.and_then(|mut file: File| {
        file.write_all(bytes)?;
        file.sync_all()
    });
    match result {
        Ok(()) => Ok(temp),
        Err(e) => {
            let _ = fs::remove_file(&temp);
            pending().retain(|t| *t != temp);
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
                let mut pending = pending();
                for t in &temps {
                    let _ = fs::remove_file(t);
                }
                pending.retain(|t| !temps.contains(t));
                return Err(e);
            }
        }
    }
    if let Some(ms) = std::env::var(PAUSE_VARIABLE)
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
    {
        std::thread::sleep(std::time::Duration::from_millis(ms));
    }
    let _locks = lock_directories(outputs.iter().map(|(p, _)| p.as_path()));
    let mut pending = pending();
    let pairs: Vec<(PathBuf, PathBuf)> = outputs
        .iter()
        .map(|(p, _)| p.clone())
        .zip(temps.iter().cloned())
        .collect();
    let result = commit(&pairs);
    // Renamed or removed by the commit, either way: none of them is pending any more.
    pending.retain(|t| !temps.contains(t));
    result
}

/// Renames every temporary file onto its target: an existing target is first moved aside to
/// a backup (`.NAME.tpi-bak-PID-N`); when a rename fails, every target renamed so far gets
/// its backup back (or is removed if it did not exist before) and the temporaries are
/// removed. On success the backups are removed.
fn commit(pairs: &[(PathBuf, PathBuf)]) -> Result<(), CliError> {
    // (target, its backup if it existed) for every target already replaced.
    let mut done: Vec<(&Path, Option<PathBuf>)> = Vec::with_capacity(pairs.len());
    let mut failure = None;
    for (path, temp) in pairs {
        let backup = if fs::symlink_metadata(path).is_ok() {
            let backup = sibling(path, "bak");
            if let Err(e) = fs::rename(path, &backup) {
                failure = Some(CliError::io(path, "cannot replace", &e));
                break;
            }
            Some(backup)
        } else {
            None
        };
        match fs::rename(temp, path) {
            Ok(()) => done.push((path, backup)),
            Err(e) => {
                if let Some(b) = &backup {
                    let _ = fs::rename(b, path);
                }
                failure = Some(CliError::io(path, "cannot write", &e));
                break;
            }
        }
    }
    match failure {
        None => {
            for (_, backup) in done {
                if let Some(b) = backup {
                    let _ = fs::remove_file(b);
                }
            }
            Ok(())
        }
        Some(e) => {
            for (path, backup) in done.into_iter().rev() {
                match backup {
                    Some(b) => {
                        let _ = fs::rename(b, path);
                    }
                    None => {
                        let _ = fs::remove_file(path);
                    }
                }
            }
            for (_, temp) in pairs {
                let _ = fs::remove_file(temp);
            }
            Err(e)
        }
    }
}

/// Advisory locks (flock) on the directories of the outputs, in a fixed order, held during
/// the renames: two runs writing the same outputs commit one after the other, so the outputs
/// always come from one run. Best effort: a directory that cannot be opened or locked is
/// not locked (and on other systems than Unix nothing is).
fn lock_directories<'a>(paths: impl Iterator<Item = &'a Path>) -> Vec<File> {
    let mut dirs: Vec<PathBuf> = paths
        .map(|p| fs::canonicalize(parent_dir(p)).unwrap_or_else(|_| parent_dir(p)))
        .collect();
    dirs.sort();
    dirs.dedup();
    let mut locks = Vec::with_capacity(dirs.len());
    #[cfg(unix)]
    for dir in dirs {
        use std::os::fd::AsRawFd;
        if let Ok(file) = File::open(&dir) {
            // SAFETY: flock on a file descriptor this function owns; it blocks until the
            // lock is free and is released when the File is dropped (closed).
            if unsafe { libc::flock(file.as_raw_fd(), libc::LOCK_EX) } == 0 {
                locks.push(file);
            }
        }
    }
    #[cfg(not(unix))]
    drop(dirs);
    locks
}

/// Refuses an output that is one of the inputs (the same path, or the same file by another
/// name): writing it would destroy the input. A usage error (exit code 2).
pub(crate) fn check_not_an_input(
    output: &Path,
    inputs: &[&Path],
    command: &'static str,
) -> Result<(), CliError> {
    for input in inputs {
        if same_file(output, input) {
            return Err(CliError::usage(
                Some(command),
                format!(
                    "--out {} is also an input ({}): it would be overwritten; choose another output name",
                    output.display(),
                    input.display()
                ),
            ));
        }
    }
    Ok(())
}

/// Whether two paths name the same file (compared by device and inode where both exist,
/// else by their canonical directories and file names).
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (fs::metadata(a), fs::metadata(b)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    let canonical = |p: &Path| {
        fs::canonicalize(p).ok().or_else(|| {
            let dir = fs::canonicalize(parent_dir(p)).ok()?;
            Some(dir.join(p.file_name()?))
        })
    };
    match (canonical(a), canonical(b)) {
        (Some(x), Some(y)) => x == y,
        _ => a == b,
    }
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

    /// Issue 14: when a later rename failed, an earlier output was deleted rather than
    /// restored. Targets a.txt and b.txt exist with old content, c.txt does not; the third
    /// rename fails (its temporary file vanished): a.txt and b.txt keep their old content,
    /// c.txt is gone again, and no temporary or backup file is left.
    #[test]
    fn a_failed_rename_restores_the_earlier_outputs() {
        let dir = std::env::temp_dir().join(format!("tpi-commit-test-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let (a, b, c) = (dir.join("a.txt"), dir.join("b.txt"), dir.join("c.txt"));
        fs::write(&a, b"old a").unwrap();
        fs::write(&b, b"old b").unwrap();
        let temps: Vec<PathBuf> = [&a, &c, &b]
            .iter()
            .map(|p| write_temp(p, b"new").unwrap())
            .collect();
        fs::remove_file(&temps[2]).unwrap();
        let pairs = vec![
            (a.clone(), temps[0].clone()),
            (c.clone(), temps[1].clone()),
            (b.clone(), temps[2].clone()),
        ];
        let err = commit(&pairs).unwrap_err();
        pending().retain(|t| !temps.contains(t));
        assert!(err.to_string().contains("b.txt"), "{err}");
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        assert_eq!(fs::read(&b).unwrap(), b"old b");
        assert!(!c.exists());
        let mut left: Vec<String> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(left, ["a.txt", "b.txt"]);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_same_file_by_another_name_is_an_input() {
        let dir = std::env::temp_dir().join(format!("tpi-same-test-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(dir.join("sub")).unwrap();
        let a = dir.join("a.json");
        fs::write(&a, b"{}").unwrap();
        assert!(same_file(&a, &dir.join("sub").join("..").join("a.json")));
        assert!(!same_file(&a, &dir.join("b.json")));
        assert!(check_not_an_input(&a, &[&dir.join("b.json"), &a], "discretise").is_err());
        fs::remove_dir_all(&dir).unwrap();
    }
}
