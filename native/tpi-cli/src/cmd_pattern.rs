//! `tpi pattern`: generate a pattern file and preview it with its Voronoi diagram.

use std::fmt::Write;
use std::path::PathBuf;

use tpi_core::Generator;

use crate::error::CliError;
use crate::output::{check_output_path, write_all};
use crate::{svg, voronoi};

/// The text after the options in `tpi pattern --help`.
pub(crate) const AFTER_HELP: &str = "\
GENERATOR (deterministic: the same spec gives the same points everywhere):
    grid:NUxNV                        NU x NV cell centres
    grid:spacing=D                    square grid with spacing about D
    hex:NUxNV                         NU x NV points, rows shifted by half a step
    hex:spacing=D                     hexagonal grid with spacing about D
    jitter:NUxNV[:amount=A][:seed=S]  grid points moved randomly within their cells (A in [0, 1])
    random:N[:seed=S]                 N uniform random points
    poisson:R[:seed=S]                Poisson-disk points at least R apart (about 0.7/R^2 points)
At most 10000000 points (tpi_core::MAX_GENERATED_POINTS); a Poisson radius at least
tpi_core::MIN_POISSON_RADIUS.

EXAMPLES:
    tpi pattern hex:24x20 --out hex.json --preview hex.svg
    tpi pattern random:1000:seed=7 --out random.json
    tpi pattern poisson:0.03:seed=7 --out poisson.json --preview poisson.svg
    tpi pattern random:1000 --surface samples/nurbs-dome.json --relax 20 --out even.json
";

/// The arguments of `tpi pattern`, as given (checked in [`run`]).
#[derive(clap::Args, Debug)]
pub(crate) struct PatternArgs {
    /// The generator spec, e.g. hex:24x20 (see GENERATOR below) [required]
    #[arg(value_name = "GENERATOR")]
    spec: Option<String>,
    /// The pattern file ({"uv": [[s, t], ...]}, docs/formats.md)
    #[arg(long, short = 'o', value_name = "FILE")]
    out: Option<PathBuf>,
    /// An SVG of the points and their Voronoi diagram in the unit square
    #[arg(long, value_name = "FILE")]
    preview: Option<PathBuf>,
    /// The surface the pattern is for (with --relax)
    #[arg(long, value_name = "FILE")]
    surface: Option<PathBuf>,
    /// Relax the points by N Lloyd iterations on the surface (areas measured on the surface,
    /// not in parameters), so that the panels come out even in size [requires --surface]
    #[arg(long, value_name = "N")]
    relax: Option<String>,
}

/// Runs `tpi pattern`.
pub(crate) fn run(args: PatternArgs) -> Result<(), CliError> {
    let usage = |message: String| CliError::usage(Some("pattern"), message);
    let PatternArgs {
        spec,
        out,
        preview,
        surface,
        relax,
    } = args;
    let relax = match (&relax, &surface) {
        (None, None) => None,
        (Some(_), None) => return Err(usage("--relax needs --surface FILE".into())),
        (None, Some(_)) => return Err(usage("--surface is for --relax N".into())),
        (Some(n), Some(path)) => {
            let iterations = n
                .parse::<usize>()
                .ok()
                .filter(|&k| k <= tpi_core::MAX_RELAX_ITERATIONS)
                .ok_or_else(|| {
                    usage(format!(
                        "--relax {}: expected a whole number from 0 to {}",
                        tpi_core::bounded(n, tpi_core::QUOTE_LIMIT),
                        tpi_core::MAX_RELAX_ITERATIONS
                    ))
                })?;
            Some((iterations, path.clone()))
        }
    };
    let spec = spec.ok_or_else(|| usage("a GENERATOR is required, e.g. hex:24x20".into()))?;
    if out.is_none() && preview.is_none() {
        return Err(usage("--out (and/or --preview) is required".into()));
    }
    for (path, ext) in [(&out, "json"), (&preview, "svg")] {
        if let Some(p) = path {
            if p.extension()
                .and_then(|e| e.to_str())
                .map(|e| e.to_ascii_lowercase())
                != Some(ext.to_string())
            {
                return Err(usage(format!("{} must end in .{ext}", p.display())));
            }
            check_output_path(p)?;
        }
    }
    let generator = Generator::parse(&spec).map_err(|e| match e {
        tpi_core::TpiError::InvalidGenerator { reason, .. } => {
            CliError::input(&spec, format!("invalid pattern generator: {reason}"))
        }
        other => CliError::input(&spec, other.to_string()),
    })?;
    let mut pattern = generator.generate();
    pattern
        .validate()
        .map_err(|e| CliError::input(&spec, e.to_string()))?;
    let mut described = generator.to_string();
    if let Some((iterations, path)) = relax {
        let surface = crate::input::load_surface(&path)?;
        pattern.uv = tpi_core::relax(
            &surface,
            &pattern.uv,
            iterations,
            &tpi_core::DiscretiseOptions::default(),
        )
        .map_err(|e| CliError::input(path.display(), e.to_string()))?;
        described = format!(
            "{described} relaxed {iterations} times on {}",
            path.display()
        );
    }

    let mut files = Vec::new();
    if let Some(p) = &out {
        files.push((p.clone(), pattern_json(&pattern.uv).into_bytes()));
    }
    if let Some(p) = &preview {
        let cells = voronoi::cells(&pattern.uv);
        files.push((
            p.clone(),
            svg::pattern_preview(&pattern.uv, &cells, &format!("tpi pattern {described}"))
                .into_bytes(),
        ));
    }
    write_all(&files)?;
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    eprintln!(
        "tpi: {described}: {} points -> {}",
        pattern.len(),
        names.join(", ")
    );
    Ok(())
}

/// The pattern file, one point per line, numbers in shortest round-trip form.
pub(crate) fn pattern_json(uv: &[[f64; 2]]) -> String {
    let mut s = String::with_capacity(uv.len() * 44 + 16);
    s.push_str("{\"uv\": [");
    for (i, p) in uv.iter().enumerate() {
        s.push_str(if i == 0 { "\n  [" } else { ",\n  [" });
        let _ = write!(s, "{}, {}]", num(p[0]), num(p[1]));
    }
    s.push_str(if uv.is_empty() { "]}\n" } else { "\n]}\n" });
    s
}

fn num(x: f64) -> String {
    serde_json::to_string(&x).unwrap_or_else(|_| "0".into())
}
