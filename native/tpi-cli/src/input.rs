//! Reading a surface file and a pattern (file, generator or surface-aware pattern spec).

use std::path::Path;

use tpi_core::{
    DiscretiseOptions, Pattern, SurfaceModel, SurfacePatternSpec, SurfaceSpec, TpiError,
};

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

/// `arg` is an existing file (read as a pattern file) or else a pattern spec: a generator
/// or a surface-aware form (`fit:D`, `relax:N:SPEC`, `align:LATTICE:FIELD`, `density:DATA`;
/// tpi_core::SurfacePatternSpec), made on `surface` with `options`. `@FILE` in a spec is read
/// here. A string that is neither gets an error naming both possibilities; a `fit:D` that
/// does not meet D is refused as `tpi pattern --max-deviation` refuses it.
pub(crate) fn load_pattern(
    arg: &str,
    surface: &SurfaceModel,
    options: &DiscretiseOptions,
    progress: &dyn tpi_core::Progress,
) -> Result<PatternSource, CliError> {
    let path = Path::new(arg);
    if path.exists() {
        let text = read_text(path)?;
        let pattern = Pattern::from_json(&text, arg).map_err(|e| CliError::core(arg, &e))?;
        return Ok(PatternSource {
            pattern,
            label: arg.to_string(),
        });
    }
    let shown = tpi_core::bounded(arg, tpi_core::QUOTE_LIMIT).to_string();
    let spec = SurfacePatternSpec::parse_with(arg, &mut read_spec_file).map_err(|e| {
        let reason = match &e {
            TpiError::InvalidGenerator { reason, .. } => {
                format!("invalid pattern generator: {reason}")
            }
            TpiError::Parse {
                context,
                line,
                column,
                message,
            } => format!("{context}: line {line}, column {column}: {message}"),
            other => other.to_string(),
        };
        if looks_like_spec(arg) {
            CliError::input(
                &shown,
                format!("{reason} (and no pattern file of this name exists)"),
            )
        } else {
            CliError::input(
                &shown,
                format!(
                    "no such pattern file, and not a pattern generator or pattern spec either \
                     ({reason})"
                ),
            )
        }
    })?;
    // Cheap checks first: too few or collinear points are found by arithmetic on the
    // generator, before any point is made.
    if let SurfacePatternSpec::Generator(generator) = &spec {
        generator
            .check_discretisable()
            .map_err(|e| CliError::input(generator.to_string(), e.to_string()))?;
    }
    let label = spec.to_string();
    let made = spec
        .generate_with_progress(surface, options, progress)
        .map_err(|e| CliError::core(&label, &e))?;
    if let Some(fit) = made.fit.filter(|f| !f.met) {
        return Err(CliError::input(
            &label,
            crate::cmd_pattern::unmet_fit(
                fit.tolerance,
                made.uv.len(),
                fit.max_deviation,
                options.planes,
                "fit:D:seed=S",
            ),
        ));
    }
    Ok(PatternSource {
        pattern: Pattern::new(made.uv),
        label,
    })
}

/// Reads a file a pattern spec names (`@FILE`, a density's image).
fn read_spec_file(name: &str) -> Result<Vec<u8>, TpiError> {
    std::fs::read(name).map_err(|e| TpiError::InvalidPatternSpec {
        part: format!("@{name}"),
        reason: format!("cannot read: {}", crate::error::describe_io(&e)),
    })
}

/// Whether a string reads more like a pattern spec than a file path.
fn looks_like_spec(arg: &str) -> bool {
    let kind = arg.split(':').next().unwrap_or("");
    arg.contains(':')
        && [
            "grid", "hex", "jitter", "random", "poisson", "fit", "relax", "align", "density",
        ]
        .contains(&kind)
}
