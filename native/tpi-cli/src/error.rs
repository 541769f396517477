//! The CLI's error: a usage mistake (exit code 2), a problem with an input or output file
//! (exit code 1), or invalid facets under `--strict` (exit code 3). Both print as one line on stderr, `tpi: error: ...`.

use std::fmt;
use std::io;
use std::path::Path;

use tpi_core::TpiError;

/// Everything that ends a run with a non-zero exit code.
#[derive(Debug)]
pub(crate) enum CliError {
    /// Wrong command line: unknown option, missing value, bad extension. Exit code 2.
    Usage {
        /// What is wrong.
        message: String,
        /// The subcommand whose `--help` explains the syntax.
        command: Option<&'static str>,
    },
    /// A file (or generator spec, or option value) that cannot be used. Exit code 1.
    Input {
        /// The file or value concerned, named first in the message.
        subject: String,
        /// What is wrong with it.
        problem: String,
    },
    /// `--strict` and the mesh has invalid facets (the outputs were written). Exit code 3.
    InvalidFacets {
        /// How many facets are open, non-simple or overlapping.
        count: usize,
    },
    /// `--strict` and the mesh is not the disc, annulus or sphere expected (the outputs were
    /// written). Exit code 3.
    UnexpectedTopology {
        /// Euler characteristic found.
        euler: i64,
        /// Boundary loops found.
        loops: u32,
    },
}

impl CliError {
    /// A usage error of `command`.
    pub(crate) fn usage(command: Option<&'static str>, message: impl Into<String>) -> Self {
        CliError::Usage {
            message: message.into(),
            command,
        }
    }

    /// A problem with `subject` (a file name, a generator spec, an option).
    pub(crate) fn input(subject: impl fmt::Display, problem: impl Into<String>) -> Self {
        CliError::Input {
            subject: subject.to_string(),
            problem: problem.into(),
        }
    }

    /// A core error about `subject`. Parse errors carry their own source name (the context
    /// passed to the core), which is the same file name: it is not repeated.
    pub(crate) fn core(subject: impl fmt::Display, error: &TpiError) -> Self {
        match error {
            TpiError::Parse {
                line,
                column,
                message,
                ..
            } => CliError::input(subject, format!("line {line}, column {column}: {message}")),
            other => CliError::input(subject, other.to_string()),
        }
    }

    /// An I/O error while doing `action` (e.g. "cannot read") on `path`.
    pub(crate) fn io(path: &Path, action: &str, error: &io::Error) -> Self {
        CliError::input(path.display(), format!("{action}: {}", describe_io(error)))
    }

    /// The process exit code.
    pub(crate) fn exit_code(&self) -> i32 {
        match self {
            CliError::Usage { .. } => 2,
            CliError::Input { .. } => 1,
            CliError::InvalidFacets { .. } | CliError::UnexpectedTopology { .. } => 3,
        }
    }
}

impl fmt::Display for CliError {
    /// One line, bounded: every quoted value at most [`tpi_core::QUOTE_LIMIT`] characters,
    /// the subject (a file name or spec) too, the whole at most [`tpi_core::MESSAGE_LIMIT`].
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let line = self.unbounded_line();
        f.write_str(&tpi_core::bound_message(&line))
    }
}

impl CliError {
    fn unbounded_line(&self) -> String {
        let mut s = String::new();
        let _ = self.write_line(&mut s);
        s
    }

    fn write_line(&self, f: &mut String) -> fmt::Result {
        use std::fmt::Write;
        match self {
            CliError::Usage {
                message,
                command: Some(command),
            } => {
                write!(f, "tpi: error: {message} (see `tpi {command} --help`)")
            }
            CliError::Usage {
                message,
                command: None,
            } => write!(f, "tpi: error: {message} (see `tpi --help`)"),
            CliError::Input { subject, problem } => write!(
                f,
                "tpi: error: {}: {problem}",
                elide_middle(subject, tpi_core::QUOTE_LIMIT)
            ),
            CliError::UnexpectedTopology { euler, loops } => write!(
                f,
                "tpi: error: the mesh has Euler characteristic {euler} and {loops} boundary loop(s), not those expected (--strict)"
            ),
            CliError::InvalidFacets { count } => {
                write!(
                    f,
                    "tpi: error: {count} invalid facet{} (--strict)",
                    if *count == 1 { "" } else { "s" }
                )
            }
        }
    }
}

/// A subject (a file path, a spec, an option) of at most `limit` characters: when longer, its
/// start and its end with `...` between and the whole length after, so that a long path still
/// shows its file name (`/very/long/...dir/r.svg (96 characters)`).
fn elide_middle(text: &str, limit: usize) -> std::borrow::Cow<'_, str> {
    let count = text.chars().count();
    if count <= limit {
        return std::borrow::Cow::Borrowed(text);
    }
    let suffix = format!(" ({count} characters)");
    let keep = limit.saturating_sub(suffix.len() + 3);
    let head_len = keep / 3;
    let head: String = text.chars().take(head_len).collect();
    let tail: String = text.chars().skip(count - (keep - head_len)).collect();
    std::borrow::Cow::Owned(format!("{head}...{tail}{suffix}"))
}

/// An I/O error as a short lower-case phrase without the "(os error N)" suffix.
pub(crate) fn describe_io(error: &io::Error) -> String {
    let text = match error.kind() {
        io::ErrorKind::NotFound => "no such file or directory".to_string(),
        io::ErrorKind::PermissionDenied => "permission denied".to_string(),
        io::ErrorKind::InvalidData => "the file is not valid UTF-8 text".to_string(),
        _ => {
            let s = error.to_string();
            let s = match s.find(" (os error") {
                Some(i) => s[..i].to_string(),
                None => s,
            };
            let mut chars = s.chars();
            match chars.next() {
                Some(c) => c.to_lowercase().collect::<String>() + chars.as_str(),
                None => s,
            }
        }
    };
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_subject_keeps_its_start_and_its_file_name() {
        let path = format!("/tmp/{}/unwritable/ok-surface.json/r.svg", "d".repeat(120));
        let e = CliError::input(&path, "cannot write: not a directory");
        let line = e.to_string();
        assert!(line.starts_with("tpi: error: /tmp/ddd"), "{line}");
        assert!(line.contains("ok-surface.json/r.svg ("), "{line}");
        assert!(
            line.contains(&format!("({} characters)", path.len())),
            "{line}"
        );
        let subject = line
            .strip_prefix("tpi: error: ")
            .and_then(|l| l.split(": cannot write").next())
            .unwrap();
        assert!(
            subject.chars().count() <= tpi_core::QUOTE_LIMIT,
            "{subject}"
        );
        // Short subjects are left as they are.
        assert_eq!(
            CliError::input("a.json", "bad").to_string(),
            "tpi: error: a.json: bad"
        );
    }
}
