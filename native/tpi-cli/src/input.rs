//! Reading a surface file and a pattern (file or generator spec).

use std::path::Path;

use tpi_core::{Generator, Pattern, SurfaceModel, SurfaceSpec, TpiError};

use crate::error::CliError;
use crate::output::read_text;

/// Reads and validates a surface file.
pub(crate) fn load_surface(path: &Path) -> Result<SurfaceModel, CliError> {
    let (_, model) = load_surface_spec(path)?;
    Ok(model)
}

/// Reads a surface file: the record as written and the validated surface.
pub(crate) fn load_surface_spec(path: &Path) -> Result<(SurfaceSpec, SurfaceModel), CliError> {
    let name = path.display().to_string();
    let text = read_text(path)?;
    let spec = SurfaceSpec::from_json(&text, &name).map_err(|e| CliError::core(&name, &e))?;
    let model = spec.build().map_err(|e| CliError::core(&name, &e))?;
    Ok((spec, model))
}

/// A pattern and where it came from.
pub(crate) struct PatternSource {
    /// The points.
    pub pattern: Pattern,
    /// The file name, or the canonical generator spec.
    pub label: String,
}

/// `arg` is an existing file (read as a pattern file) or else a generator spec. A string
/// that is neither gets an error naming both possibilities.
pub(crate) fn load_pattern(arg: &str) -> Result<PatternSource, CliError> {
    let path = Path::new(arg);
    if path.exists() {
        let text = read_text(path)?;
        let pattern = Pattern::from_json(&text, arg).map_err(|e| CliError::core(arg, &e))?;
        return Ok(PatternSource {
            pattern,
            label: arg.to_string(),
        });
    }
    match Generator::parse(arg) {
        // Cheap checks first: too few or collinear points are found by arithmetic on the
        // spec, before any point is made.
        Ok(generator) => match generator.check_discretisable() {
            Ok(()) => Ok(PatternSource {
                pattern: generator.generate(),
                label: generator.to_string(),
            }),
            Err(e) => Err(CliError::input(generator.to_string(), e.to_string())),
        },
        Err(e) => {
            let reason = match &e {
                TpiError::InvalidGenerator { reason, .. } => reason.clone(),
                other => other.to_string(),
            };
            Err(if looks_like_spec(arg) {
                CliError::input(arg, format!("invalid pattern generator: {reason} (and no pattern file of this name exists)"))
            } else {
                CliError::input(
                    arg,
                    format!(
                        "no such pattern file, and not a pattern generator spec either ({reason})"
                    ),
                )
            })
        }
    }
}

/// Whether a string reads more like a generator spec than a file path.
fn looks_like_spec(arg: &str) -> bool {
    let kind = arg.split(':').next().unwrap_or("");
    arg.contains(':') && ["grid", "hex", "jitter", "random", "poisson"].contains(&kind)
}
