//! `tpi pattern`: generate a pattern file and preview it with its Voronoi diagram.

use std::fmt::Write;
use std::path::PathBuf;

use tpi_core::{Generator, Surface};

use crate::error::CliError;
use crate::output::{check_output_path, write_all};
use crate::render;
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
    tpi pattern --surface samples/saddle.json --max-deviation 0.01 --out fit.json
    tpi pattern --surface samples/nurbs-dome.json --density density.json --relax 5 --out graded.json
    tpi pattern hex:spacing=0.04 --surface samples/saddle.json --align principal --out aligned.json
    tpi pattern grid:30x30 --surface samples/torus-band.json --align uv:30 --out grid.json
    tpi pattern hex:24x20 --surface samples/saddle.json --align field:grain.json --out grain.json
";

/// The arguments of `tpi pattern`, as given (checked in [`run`]).
#[derive(clap::Args, Debug)]
pub(crate) struct PatternArgs {
    /// The generator spec, e.g. hex:24x20 (see GENERATOR below) [required unless
    /// --max-deviation]
    #[arg(value_name = "GENERATOR")]
    spec: Option<String>,
    /// The pattern file ({"uv": [[s, t], ...]}, docs/formats.md)
    #[arg(long, short = 'o', value_name = "FILE")]
    out: Option<PathBuf>,
    /// An SVG of the points and their Voronoi diagram in the unit square
    #[arg(long, value_name = "FILE")]
    preview: Option<PathBuf>,
    /// The surface the pattern is for (with --relax or --max-deviation)
    #[arg(long, value_name = "FILE")]
    surface: Option<PathBuf>,
    /// Tolerance-driven pattern: few points whose mesh keeps every vertex within D model
    /// units of the surface; prints its count and the count of the smallest uniform hex
    /// pattern that meets D [requires --surface, no GENERATOR]
    #[arg(long, value_name = "D")]
    max_deviation: Option<String>,
    /// The facet planes of the meshes --max-deviation measures: `exact` (the default) or
    /// `adjusted` (as `tpi discretise --planes`; across parabolic lines, where exact
    /// vertices run away, only adjusted planes can meet a tolerance)
    #[arg(long, value_name = "MODE")]
    planes: Option<String>,
    /// Density-graded pattern: a Poisson-disk sampling whose spacing follows the density
    /// field in FILE (attractors, curves, curvature, a PGM image; docs/formats.md), relaxed
    /// with --relax N following the same density [requires --surface, no GENERATOR]
    #[arg(long, value_name = "FILE")]
    density: Option<PathBuf>,
    /// Random seed of the tolerance-driven pattern's sampling (default 0)
    #[arg(long, value_name = "S")]
    seed: Option<String>,
    /// Lay a hex or grid GENERATOR's lattice along a direction field on the surface, about
    /// as many points as the generator makes, so that the facet edges follow the field:
    /// principal (curvature directions), asymptotic (where K < 0), uv:ANGLE (degrees from the
    /// u axis in parameters) or field:FILE.json (docs/formats.md) [requires --surface]
    #[arg(long, value_name = "FIELD")]
    align: Option<String>,
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
        max_deviation,
        density,
        seed,
        planes,
        align,
    } = args;
    if planes.is_some() && max_deviation.is_none() {
        return Err(usage("--planes is for --max-deviation".into()));
    }
    if let Some(field) = align {
        if max_deviation.is_some() || density.is_some() || relax.is_some() || seed.is_some() {
            return Err(usage(
                "--align lays a hex or grid GENERATOR's lattice: give no --max-deviation, \
                 --density, --relax or --seed"
                    .into(),
            ));
        }
        let Some(path) = surface else {
            return Err(usage("--align needs --surface FILE".into()));
        };
        let spec =
            spec.ok_or_else(|| usage("--align needs a GENERATOR, hex:... or grid:...".into()))?;
        check_outputs(&out, &preview)?;
        return run_align(&spec, &field, &path, &out, &preview);
    }
    if let Some(file) = density {
        if spec.is_some() || max_deviation.is_some() {
            return Err(usage(
                "--density makes its own pattern: give no GENERATOR and no --max-deviation".into(),
            ));
        }
        let Some(path) = surface else {
            return Err(usage("--density needs --surface FILE".into()));
        };
        if seed.is_some() {
            return Err(usage(
                "--seed is for --max-deviation (a density file has \"seed\")".into(),
            ));
        }
        check_outputs(&out, &preview)?;
        let iterations = parse_relax(relax.as_deref())?;
        return run_density(&file, iterations, &path, &out, &preview);
    }
    if let Some(tolerance) = max_deviation {
        if spec.is_some() || relax.is_some() {
            return Err(usage(
                "--max-deviation makes its own pattern: give no GENERATOR and no --relax".into(),
            ));
        }
        let Some(path) = surface else {
            return Err(usage("--max-deviation needs --surface FILE".into()));
        };
        let planes = crate::cmd_discretise::plane_mode(planes.as_deref(), "pattern")?;
        check_outputs(&out, &preview)?;
        return run_fit(&tolerance, seed.as_deref(), planes, &path, &out, &preview);
    }
    if seed.is_some() {
        return Err(usage(
            "--seed is for --max-deviation (generators take :seed=S)".into(),
        ));
    }
    let iterations = match (&relax, &surface) {
        (None, None) => None,
        (Some(_), None) => return Err(usage("--relax needs --surface FILE".into())),
        (None, Some(_)) if !on_surface(&preview) => {
            return Err(usage(
                "--surface is for --relax N or a .png --preview".into(),
            ))
        }
        (None, Some(_)) => None,
        (Some(n), Some(_)) => Some(parse_relax(Some(n))?),
    };
    let spec = spec.ok_or_else(|| usage("a GENERATOR is required, e.g. hex:24x20".into()))?;
    check_outputs(&out, &preview)?;
    let generator = parse_generator(&spec)?;
    let mut pattern = generator.generate();
    pattern
        .validate()
        .map_err(|e| CliError::input(&spec, e.to_string()))?;
    let mut described = generator.to_string();
    let loaded = match &surface {
        Some(path) => Some((
            crate::input::load_surface(path)?,
            path.display().to_string(),
        )),
        None => None,
    };
    if let (Some(iterations), Some((surface, _)), Some(path)) = (iterations, &loaded, &surface) {
        pattern.uv = tpi_core::relax(
            surface,
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

    let names = write_pattern(
        &pattern.uv,
        &described,
        &out,
        &preview,
        loaded.as_ref().map(|(s, n)| (s, n.as_str())),
        None,
        &tpi_core::DiscretiseOptions::default(),
    )?;
    eprintln!("tpi: {described}: {} points -> {}", pattern.len(), names);
    Ok(())
}

/// A failed fit whose closest pattern stayed within this factor of the tolerance missed it
/// narrowly (the refinement stalled), rather than through a vertex that runs away.
const NEAR_MISS_FACTOR: f64 = 1.5;

/// Why a fit to `tolerance` is refused: its closest attempt (`points`, `max_deviation`), and
/// what may help (`reseed`: how this command sets the fit's seed; `planes`: the plane mode).
pub(crate) fn unmet_fit(
    tolerance: f64,
    points: usize,
    max_deviation: f64,
    planes: tpi_core::PlaneMode,
    reseed: &str,
) -> String {
    let hint = if max_deviation <= NEAR_MISS_FACTOR * tolerance {
        format!(" (a near miss: another {reseed}, or a slightly larger tolerance, may meet it)")
    } else if planes == tpi_core::PlaneMode::Exact {
        " (where exact tangent planes are nearly parallel, vertices run away: try --planes \
         adjusted)"
            .to_string()
    } else {
        String::new()
    };
    format!(
        "no pattern found whose mesh stays within {tolerance}: the closest had {points} points \
         and a vertex {max_deviation} off the surface{hint}"
    )
}

/// `tpi pattern hex:...|grid:... --surface S --align FIELD`.
fn run_align(
    spec: &str,
    field: &str,
    path: &std::path::Path,
    out: &Option<PathBuf>,
    preview: &Option<PathBuf>,
) -> Result<(), CliError> {
    let generator = parse_generator(spec)?;
    let (lattice, count) = match generator {
        Generator::Hex(size) => {
            let (nu, nv) = size.hex_counts();
            (tpi_core::Lattice::Hex, nu * nv)
        }
        Generator::Grid(size) => {
            let (nu, nv) = size.square_counts();
            (tpi_core::Lattice::Grid, nu * nv)
        }
        _ => {
            return Err(CliError::usage(
                Some("pattern"),
                format!(
                    "--align lays a hex or grid lattice: {} is neither",
                    tpi_core::bounded(spec, tpi_core::QUOTE_LIMIT)
                ),
            ))
        }
    };
    let align = match field.strip_prefix("field:") {
        Some(file) => {
            let file = std::path::Path::new(file);
            let text = crate::output::read_text(file)?;
            let name = file.display().to_string();
            tpi_core::AlignField::File(
                tpi_core::DirectionField::from_json(&text, &name)
                    .map_err(|e| CliError::core(&name, &e))?,
            )
        }
        None => tpi_core::AlignField::parse(field).map_err(|e| match e {
            tpi_core::TpiError::InvalidParameter { reason, .. } => CliError::usage(
                Some("pattern"),
                format!(
                    "--align {}: {reason}",
                    tpi_core::bounded(field, tpi_core::QUOTE_LIMIT)
                ),
            ),
            other => CliError::usage(Some("pattern"), other.to_string()),
        })?,
    };
    let surface = crate::input::load_surface(path)?;
    let name = path.display().to_string();
    let uv = tpi_core::aligned_pattern(&surface, lattice, count, &align)
        .map_err(|e| CliError::core(&name, &e))?;
    let described = format!("{generator} aligned with {field} on {name}");
    let names = write_pattern(
        &uv,
        &described,
        out,
        preview,
        Some((&surface, &name)),
        None,
        &tpi_core::DiscretiseOptions::default(),
    )?;
    eprintln!("tpi: {described}: {} points -> {}", uv.len(), names);
    Ok(())
}

/// A generator spec parsed, its errors naming the spec.
fn parse_generator(spec: &str) -> Result<Generator, CliError> {
    Generator::parse(spec).map_err(|e| match e {
        tpi_core::TpiError::InvalidGenerator { reason, .. } => {
            CliError::input(spec, format!("invalid pattern generator: {reason}"))
        }
        other => CliError::input(spec, other.to_string()),
    })
}

/// Writes the pattern file (`out`) and the preview (`preview_bytes`), all or nothing, and
/// returns their names for the summary line.
fn write_pattern(
    uv: &[[f64; 2]],
    described: &str,
    out: &Option<PathBuf>,
    preview: &Option<PathBuf>,
    surface: Option<(&tpi_core::SurfaceModel, &str)>,
    tolerance: Option<f64>,
    options: &tpi_core::DiscretiseOptions,
) -> Result<String, CliError> {
    let mut files = Vec::new();
    if let Some(p) = out {
        files.push((p.clone(), pattern_json(uv).into_bytes()));
    }
    if let Some(p) = preview {
        let bytes = preview_bytes(p, uv, described, surface, tolerance, options)?;
        files.push((p.clone(), bytes));
    }
    write_all(&files)?;
    let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    Ok(names.join(", "))
}

/// The --relax count (0 when absent).
fn parse_relax(n: Option<&str>) -> Result<usize, CliError> {
    let Some(n) = n else { return Ok(0) };
    n.parse::<usize>()
        .ok()
        .filter(|&k| k <= tpi_core::MAX_RELAX_ITERATIONS)
        .ok_or_else(|| {
            CliError::usage(
                Some("pattern"),
                format!(
                    "--relax {}: expected a whole number from 0 to {}",
                    tpi_core::bounded(n, tpi_core::QUOTE_LIMIT),
                    tpi_core::MAX_RELAX_ITERATIONS
                ),
            )
        })
}

/// `tpi pattern --surface S --density FILE [--relax N]`.
fn run_density(
    file: &std::path::Path,
    iterations: usize,
    path: &std::path::Path,
    out: &Option<PathBuf>,
    preview: &Option<PathBuf>,
) -> Result<(), CliError> {
    let file_name = file.display().to_string();
    let text = crate::output::read_text(file)?;
    let mut spec = tpi_core::DensitySpec::from_json(&text, &file_name)
        .map_err(|e| CliError::core(&file_name, &e))?;
    let dir = file.parent().unwrap_or(std::path::Path::new("."));
    for (index, image) in spec.image_files() {
        let image_path = dir.join(&image);
        let bytes =
            std::fs::read(&image_path).map_err(|e| CliError::io(&image_path, "read", &e))?;
        let name = image_path.display().to_string();
        let grey =
            tpi_core::GreyImage::from_pgm(&bytes, &name).map_err(|e| CliError::core(&name, &e))?;
        spec.attach_image(index, grey);
    }
    let surface = crate::input::load_surface(path)?;
    let name = path.display().to_string();
    let uv = tpi_core::density_pattern(
        &surface,
        &spec,
        iterations,
        tpi_core::MAX_GENERATED_POINTS,
        &tpi_core::DiscretiseOptions::default(),
    )
    .map_err(|e| CliError::core(&name, &e))?;
    let described = if iterations > 0 {
        format!("density {file_name} on {name}, relaxed {iterations} times")
    } else {
        format!("density {file_name} on {name}")
    };
    let names = write_pattern(
        &uv,
        &described,
        out,
        preview,
        Some((&surface, &name)),
        None,
        &tpi_core::DiscretiseOptions::default(),
    )?;
    eprintln!("tpi: {described}: {} points -> {}", uv.len(), names);
    Ok(())
}

/// Checks --out and --preview: at least one, each with its extension, writable.
fn check_outputs(out: &Option<PathBuf>, preview: &Option<PathBuf>) -> Result<(), CliError> {
    let usage = |message: String| CliError::usage(Some("pattern"), message);
    if out.is_none() && preview.is_none() {
        return Err(usage("--out (and/or --preview) is required".into()));
    }
    for (path, exts) in [(out, &["json"][..]), (preview, &["svg", "png"][..])] {
        if let Some(p) = path {
            let ext = p
                .extension()
                .and_then(|e| e.to_str())
                .map(|e| e.to_ascii_lowercase());
            if !exts.iter().any(|&e| ext.as_deref() == Some(e)) {
                return Err(usage(format!(
                    "{} must end in .{}",
                    p.display(),
                    exts.join(" or .")
                )));
            }
            check_output_path(p)?;
        }
    }
    Ok(())
}

/// Whether the preview is a picture on the surface (.png) rather than the unit square.
fn on_surface(preview: &Option<PathBuf>) -> bool {
    preview.as_ref().is_some_and(|p| {
        p.extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("png"))
    })
}

/// The preview's bytes: an .svg of the points and their Voronoi cells in the unit square,
/// or a .png of the pattern on `surface`: its TPI mesh (the cells the points make on the
/// surface) rendered in 3D with the points as dots, coloured by deviation from the surface
/// (red at `tolerance`) when a tolerance is given, else by side count.
fn preview_bytes(
    path: &std::path::Path,
    uv: &[[f64; 2]],
    described: &str,
    surface: Option<(&tpi_core::SurfaceModel, &str)>,
    tolerance: Option<f64>,
    options: &tpi_core::DiscretiseOptions,
) -> Result<Vec<u8>, CliError> {
    let title = format!("tpi pattern {described}");
    if !on_surface(&Some(path.to_path_buf())) {
        let cells = voronoi::cells(uv);
        return Ok(svg::pattern_preview(uv, &cells, &title).into_bytes());
    }
    let Some((surface, name)) = surface else {
        return Err(CliError::usage(
            Some("pattern"),
            "a .png preview draws the pattern on a surface: give --surface FILE".to_string(),
        ));
    };
    let mesh = tpi_core::discretise(surface, uv, options).map_err(|e| CliError::core(name, &e))?;
    let deviations = render::facet_deviations(surface, &mesh);
    let colouring = match tolerance {
        Some(scale) => render::Colouring::Deviation {
            per_facet: &deviations,
            scale,
        },
        None => render::Colouring::Sides,
    };
    let picture = render::Picture {
        colouring,
        seeds: true,
    };
    let (w, h) = render::DEFAULT_SIZE;
    let rgb = render::render_picture(&mesh, w, h, picture);
    render::encode_png(&rgb, w, h)
        .map_err(|problem| CliError::input(path.display(), format!("cannot encode: {problem}")))
}

/// `tpi pattern --surface S --max-deviation D`: the fitted pattern, its count and the
/// uniform hex count for the same tolerance. Fails (writing nothing) when D cannot be met.
fn run_fit(
    tolerance: &str,
    seed: Option<&str>,
    planes: tpi_core::PlaneMode,
    path: &std::path::Path,
    out: &Option<PathBuf>,
    preview: &Option<PathBuf>,
) -> Result<(), CliError> {
    let usage = |message: String| CliError::usage(Some("pattern"), message);
    let d = tolerance
        .parse::<f64>()
        .ok()
        .filter(|d| d.is_finite() && *d > 0.0)
        .ok_or_else(|| {
            usage(format!(
                "--max-deviation {}: expected a positive number (model units)",
                tpi_core::bounded(tolerance, tpi_core::QUOTE_LIMIT)
            ))
        })?;
    let seed = match seed {
        None => 0,
        Some(s) => s.parse::<u64>().map_err(|_| {
            usage(format!(
                "--seed {}: expected an unsigned 64-bit integer",
                tpi_core::bounded(s, tpi_core::QUOTE_LIMIT)
            ))
        })?,
    };
    let surface = crate::input::load_surface(path)?;
    let name = path.display().to_string();
    let options = tpi_core::DiscretiseOptions {
        planes,
        ..Default::default()
    };
    // Tens of discretisations, then the uniform baseline's: a spinner says how far they are.
    let progress = crate::progress::Progress::start();
    progress.stage("fit", None, format!("max deviation {d}"));
    let runs = crate::progress::PatternRuns::new(&progress, format!("fit:{d}"));
    let fitted = tpi_core::fit_pattern_with_progress(&surface, d, seed, &options, &runs)
        .map_err(|e| CliError::core(&name, &e))?;
    if !fitted.met {
        return Err(CliError::input(
            &name,
            unmet_fit(d, fitted.uv.len(), fitted.max_deviation, planes, "--seed"),
        ));
    }
    let search_limit = fitted.uv.len() * tpi_core::HEX_BASELINE_SEARCH_FACTOR;
    progress.stage("baseline", None, format!("uniform hex for {d}"));
    let hex = tpi_core::hex_baseline(&surface, d, search_limit, &options)
        .map_err(|e| CliError::core(&name, &e))?;
    progress.finish();
    let described = format!("max deviation {d} on {name}");
    let names = write_pattern(
        &fitted.uv,
        &described,
        out,
        preview,
        Some((&surface, &name)),
        Some(d),
        &options,
    )?;
    let units = surface.units().map_or(String::new(), |u| {
        format!(" {}", tpi_core::units_label(Some(u)))
    });
    eprintln!(
        "tpi: {described}: {} points (mesh max deviation {:.4e}{units}, {} invalid facets, {} \
         discretisations) -> {}",
        fitted.uv.len(),
        fitted.max_deviation,
        fitted.invalid_facets,
        fitted.discretisations,
        names
    );
    match hex {
        Some(h) => eprintln!(
            "tpi: uniform hex for the same tolerance: {} points ({}, max deviation {:.4e}, {} \
             invalid facets); the fitted pattern has {:.1}% of them",
            h.count,
            h.generator,
            h.max_deviation,
            h.invalid_facets,
            100.0 * fitted.uv.len() as f64 / h.count as f64
        ),
        None => eprintln!(
            "tpi: no uniform hex pattern of up to {search_limit} points ({}x the fitted \
             pattern) meets the same tolerance",
            tpi_core::HEX_BASELINE_SEARCH_FACTOR
        ),
    }
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
