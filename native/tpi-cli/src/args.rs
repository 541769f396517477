//! A small command-line scanner: `--name value`, `--name=value`, boolean flags and
//! positional arguments. Hand-written to keep the binary's dependencies few and every
//! message in the CLI's own one-line format.

use std::collections::VecDeque;

use crate::error::CliError;

/// One scanned argument.
#[derive(Debug, PartialEq)]
pub(crate) enum Arg {
    /// `--name` or `--name=value` (the inline value, if any). `-h` reads as `--help`.
    Option(String, Option<String>),
    /// Anything else (including `-` alone, and everything after `--`).
    Positional(String),
}

/// The arguments of one subcommand.
pub(crate) struct Args {
    rest: VecDeque<String>,
    command: &'static str,
    positional_only: bool,
    /// Options that may be given more than once (`out` of `tpi discretise`).
    repeatable: &'static [&'static str],
    /// Options seen so far.
    seen: Vec<String>,
}

impl Args {
    /// Scans `rest` (the arguments after the subcommand name).
    pub(crate) fn new(command: &'static str, rest: Vec<String>) -> Self {
        Self {
            rest: rest.into(),
            command,
            positional_only: false,
            repeatable: &[],
            seen: Vec::new(),
        }
    }

    /// Allows these options (by long name) to be given more than once.
    pub(crate) fn repeatable(mut self, names: &'static [&'static str]) -> Self {
        self.repeatable = names;
        self
    }

    /// Records option `name`; a second use of an option that is not repeatable is a usage
    /// error (a repeated `--surface` used to be taken silently, the last one winning).
    fn once(&mut self, name: &str) -> Result<(), CliError> {
        if self.repeatable.contains(&name) {
            return Ok(());
        }
        if self.seen.iter().any(|s| s == name) {
            return Err(self.usage(format!("--{name} is given more than once; give it once")));
        }
        self.seen.push(name.to_string());
        Ok(())
    }

    /// The next argument, or `None` at the end.
    #[allow(clippy::should_implement_trait)]
    pub(crate) fn next(&mut self) -> Option<Arg> {
        let arg = self.rest.pop_front()?;
        if self.positional_only {
            return Some(Arg::Positional(arg));
        }
        if arg == "--" {
            self.positional_only = true;
            return self.next();
        }
        if arg == "-h" {
            return Some(Arg::Option("help".into(), None));
        }
        if let Some(body) = arg.strip_prefix("--") {
            return Some(match body.split_once('=') {
                Some((name, value)) => Arg::Option(name.to_string(), Some(value.to_string())),
                None => Arg::Option(body.to_string(), None),
            });
        }
        if arg.len() > 1
            && arg.starts_with('-')
            && !arg[1..].starts_with(|c: char| c.is_ascii_digit() || c == '.')
        {
            return Some(Arg::Option(arg.trim_start_matches('-').to_string(), None));
        }
        Some(Arg::Positional(arg))
    }

    /// The value of option `name`: its inline `=value` or the next argument.
    pub(crate) fn value(&mut self, name: &str, inline: Option<String>) -> Result<String, CliError> {
        self.once(name)?;
        if let Some(v) = inline {
            return Ok(v);
        }
        match self.rest.pop_front() {
            Some(v) if !(v.starts_with("--") && v.len() > 2) => Ok(v),
            _ => Err(self.usage(format!("--{name} needs a value"))),
        }
    }

    /// Rejects an inline value given to a flag that takes none.
    pub(crate) fn flag(&mut self, name: &str, inline: Option<String>) -> Result<(), CliError> {
        self.once(name)?;
        match inline {
            None => Ok(()),
            Some(v) => Err(self.usage(format!("--{name} takes no value (got `{v}`)"))),
        }
    }

    /// A usage error of this subcommand.
    pub(crate) fn usage(&self, message: impl Into<String>) -> CliError {
        CliError::usage(Some(self.command), message)
    }

    /// The error for an option this subcommand does not know.
    pub(crate) fn unknown(&self, name: &str) -> CliError {
        self.usage(format!("unknown option `--{name}`"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(v: &[&str]) -> Vec<Arg> {
        let mut a = Args::new("x", v.iter().map(|s| s.to_string()).collect());
        std::iter::from_fn(|| a.next()).collect()
    }

    #[test]
    fn scans_options_and_positionals() {
        assert_eq!(
            scan(&[
                "--out",
                "a.json",
                "--size=10x20",
                "-h",
                "hex:3x3",
                "--",
                "--x"
            ]),
            vec![
                Arg::Option("out".into(), None),
                Arg::Positional("a.json".into()),
                Arg::Option("size".into(), Some("10x20".into())),
                Arg::Option("help".into(), None),
                Arg::Positional("hex:3x3".into()),
                Arg::Positional("--x".into()),
            ]
        );
    }
}
