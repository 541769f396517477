//! `tpi discretise`: surface + pattern -> planar-facet mesh in JSON, OBJ, SVG and PNG.

use std::path::{Path, PathBuf};
use std::time::Instant;

use tpi_core::{
    discretise_with_progress, Diagnostic, Discretisation, DiscretiseOptions, PlaneMode,
    SurfaceModel, TpiError,
};

use crate::error::CliError;
use crate::input::{load_pattern, load_surface, PatternSource};
use crate::output::{check_not_an_input, check_output_path, write_all};
use crate::progress::Progress;
use crate::render::{self, DEFAULT_SIZE, MAX_SIDE};
use crate::{obj, summary, svg};

/// The text after the options in `tpi discretise --help`.
pub(crate) const AFTER_HELP: &str = "\
All outputs are computed in memory first, checked (every number finite, every OBJ face with
at least 3 distinct vertices) and then written through temporary files renamed together, so
a failing or interrupted run leaves no output file (and no half-written one); an output that
is also an input is refused. A summary of the quality report goes to stderr; progress bars
too (one per stage that runs, with count, percentage and time left) when stderr is a terminal
and the run takes more than a second. When the report finds invalid facets, an unexpected
topology or facets with a vertex more than 3 local pattern spacings off the surface, the
surface intersects itself (sampled) or a seam stays open, a `warning:` line goes to stderr.
Exit code 0 on success, 1 for bad input or output, 2 for usage, 3 for invalid facets or an
unexpected topology with --strict.

PATTERN SPECS made on the surface (the same grammar as the C ABI's
tpi_pattern_new_for_surface and the Grasshopper component; tpi_core::SurfacePatternSpec):
    fit:D[:seed=S]          few points whose mesh keeps every vertex within D model units of
                            the surface (as tpi pattern --max-deviation D; refused when D is
                            not met)
    relax:N:SPEC            SPEC's points after N Lloyd iterations on the surface (as
                            tpi pattern SPEC --relax N); SPEC is anything here but fit: or
                            relax:; of a density, the iterations follow the density
    align:LATTICE:FIELD     LATTICE hex:NUxNV, hex:spacing=A, grid:NUxNV or grid:spacing=A
                            laid along FIELD: principal, asymptotic, uv:ANGLE, a direction
                            field as inline JSON {...} or @FILE.json (as tpi pattern LATTICE
                            --align FIELD)
    density:DATA            a Poisson-disk sampling following a density field: inline JSON
                            {...} or @FILE.json (as tpi pattern --density FILE); its image
                            files are read beside the density file
The field and the density run to the end of the spec, so inline JSON may hold colons.
The surface-aware patterns use the plane mode of --planes.

EXAMPLES:
    tpi discretise --surface samples/nurbs-dome.json --pattern samples/random-1000.json \\
        --out dome.json --out dome.obj --out dome.svg --out dome.png
    tpi discretise --surface samples/paraboloid.json --pattern hex:24x20 --out mesh.obj
    tpi discretise --surface samples/hypar.json --pattern poisson:0.03:seed=7 \\
        --out hypar.png --size 800x600 --threads 2
    tpi discretise --surface samples/nurbs-dome.json --pattern relax:20:random:500 --out even.obj
    tpi discretise --surface samples/saddle.json --pattern fit:0.01 --out fit.png \\
        --colour deviation:0.01
    tpi discretise --surface samples/saddle.json --pattern align:hex:spacing=0.04:asymptotic \\
        --out aligned.obj
    tpi discretise --surface samples/nurbs-dome.json \\
        --pattern relax:5:density:@samples/attractor-density.json --out graded.png
";

/// The arguments of `tpi discretise`, as given (checked in [`run`]).
#[derive(clap::Args, Debug)]
pub(crate) struct DiscretiseArgs {
    /// Surface file (docs/formats.md): NURBS or analytic [required]
    #[arg(long, value_name = "FILE")]
    surface: Option<String>,
    /// A pattern file ({"uv": [[s, t], ...]}) or a pattern spec: a generator (grid:NUxNV,
    /// grid:spacing=D, hex:NUxNV, hex:spacing=D, jitter:NUxNV[:amount=A][:seed=S],
    /// random:N[:seed=S], poisson:R[:seed=S]) or a pattern made on the surface (fit:D,
    /// relax:N:SPEC, align:LATTICE:FIELD, density:JSON; see PATTERN SPECS below); an
    /// existing file wins over a spec of the same name [required]
    #[arg(long, value_name = "P")]
    pattern: Option<String>,
    /// Output, repeatable; the extension picks the format: .json (the output contract),
    /// .obj (Wavefront OBJ, one n-gon per facet), .svg (top view, facets coloured by side
    /// count, flagged facets outlined red), .png (shaded 3D view)
    #[arg(long, short = 'o', value_name = "FILE")]
    out: Vec<String>,
    /// PNG colours: `sides` (the default, by side count) or `deviation[:D]` (each facet by
    /// the largest distance of its vertices from the surface, red at D; without D at the
    /// largest deviation)
    #[arg(long, value_name = "MODE")]
    colour: Option<String>,
    /// PNG size in pixels [default: 1200x900]
    #[arg(long, value_name = "WxH")]
    size: Option<String>,
    /// Run the core on N threads (the result is identical for any N) [default: one per core]
    #[arg(long, short = 'j', value_name = "N")]
    threads: Option<String>,
    /// Skip the quality report (faster; no facet flags)
    #[arg(long)]
    no_report: bool,
    /// Facet planes: `exact` (the default) puts every facet in the exact tangent plane at its
    /// seed; `adjusted` tilts the planes of the few facets that exact planes cannot make
    /// valid (saddles, parabolic lines, random patterns) by at most 5 degrees through their
    /// seeds
    #[arg(long, value_name = "MODE")]
    planes: Option<String>,
    /// Exit with code 3 when the mesh has invalid facets (open, non-simple or overlapping) or
    /// is not the disc, annulus or sphere expected; the outputs are still written
    #[arg(long)]
    strict: bool,
}

/// Output formats, by file extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Json,
    Obj,
    Svg,
    Png,
}

impl Format {
    fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "json" => Format::Json,
            "obj" => Format::Obj,
            "svg" => Format::Svg,
            "png" => Format::Png,
            _ => return None,
        })
    }
}

/// How the PNG colours its facets (`--colour`).
#[derive(Clone, Copy, Debug, PartialEq)]
enum PngColour {
    Sides,
    /// By deviation, red at the given tolerance or (None) at the largest deviation.
    Deviation(Option<f64>),
}

/// `--colour MODE`.
fn png_colour(arg: Option<&str>) -> Result<PngColour, CliError> {
    let refuse = |v: &str| {
        CliError::usage(
            Some("discretise"),
            format!(
                "--colour {}: expected `sides`, `deviation` or `deviation:D` with D a positive \
                 number (model units)",
                tpi_core::bounded(v, tpi_core::QUOTE_LIMIT)
            ),
        )
    };
    match arg {
        None | Some("sides") => Ok(PngColour::Sides),
        Some("deviation") => Ok(PngColour::Deviation(None)),
        Some(v) => {
            let d = v
                .strip_prefix("deviation:")
                .and_then(|d| d.parse::<f64>().ok())
                .filter(|d| d.is_finite() && *d > 0.0)
                .ok_or_else(|| refuse(v))?;
            Ok(PngColour::Deviation(Some(d)))
        }
    }
}

struct Options {
    colour: PngColour,
    surface: String,
    pattern: String,
    outs: Vec<(PathBuf, Format)>,
    size: (u32, u32),
    threads: Option<usize>,
    report: bool,
    strict: bool,
    planes: PlaneMode,
}

fn parse(args: DiscretiseArgs) -> Result<Options, CliError> {
    let usage = |message: String| CliError::usage(Some("discretise"), message);
    let outs = output_formats(
        &args.out,
        Format::of,
        ".json, .obj, .svg or .png",
        "discretise",
    )?;
    let size = match &args.size {
        None => None,
        Some(v) => Some(parse_size(v).ok_or_else(|| {
            usage(format!(
                "--size {v}: expected WIDTHxHEIGHT in pixels, each 16..={MAX_SIDE}, e.g. 1200x900"
            ))
        })?),
    };
    let threads = thread_count(args.threads.as_deref(), "discretise")?;
    let planes = plane_mode(args.planes.as_deref(), "discretise")?;
    let surface = args
        .surface
        .ok_or_else(|| usage("--surface is required".into()))?;
    let pattern = args
        .pattern
        .ok_or_else(|| usage("--pattern is required".into()))?;
    let colour = png_colour(args.colour.as_deref())?;
    if args.colour.is_some() && !outs.iter().any(|(_, f)| *f == Format::Png) {
        return Err(usage(
            "--colour applies to a .png output, and none is given".into(),
        ));
    }
    if size.is_some() && !outs.iter().any(|(_, f)| *f == Format::Png) {
        return Err(usage(
            "--size applies to a .png output, and none is given".into(),
        ));
    }
    let report = !args.no_report;
    if args.strict && !report {
        return Err(usage(
            "--strict needs the quality report; drop --no-report".into(),
        ));
    }
    Ok(Options {
        colour,
        surface,
        pattern,
        outs,
        size: size.unwrap_or(DEFAULT_SIZE),
        threads,
        report,
        strict: args.strict,
        planes,
    })
}

/// The `--out` files with their formats (by extension, `format_of`): each once, each of a
/// known format (`extensions` names them in the message).
pub(crate) fn output_formats<F>(
    outs: &[String],
    format_of: impl Fn(&Path) -> Option<F>,
    extensions: &str,
    command: &'static str,
) -> Result<Vec<(PathBuf, F)>, CliError> {
    let usage = |message: String| CliError::usage(Some(command), message);
    let mut checked: Vec<(PathBuf, F)> = Vec::new();
    for v in outs {
        let path = PathBuf::from(v);
        let Some(format) = format_of(&path) else {
            return Err(usage(format!(
                "--out {v}: unknown output format; the extension must be {extensions}"
            )));
        };
        if checked.iter().any(|(p, _)| *p == path) {
            return Err(usage(format!("--out {v} is given twice")));
        }
        checked.push((path, format));
    }
    Ok(checked)
}

/// `--threads N`: a whole number from 1 to 1024 (None: one thread per core).
pub(crate) fn thread_count(
    arg: Option<&str>,
    command: &'static str,
) -> Result<Option<usize>, CliError> {
    match arg {
        None => Ok(None),
        Some(v) => match v.parse::<usize>() {
            Ok(n) if (1..=1024).contains(&n) => Ok(Some(n)),
            _ => Err(CliError::usage(
                Some(command),
                format!("--threads {v}: expected a whole number from 1 to 1024"),
            )),
        },
    }
}

/// `--planes MODE`: `exact` (the default) or `adjusted`.
pub(crate) fn plane_mode(arg: Option<&str>, command: &'static str) -> Result<PlaneMode, CliError> {
    match arg {
        None | Some("exact") => Ok(PlaneMode::Exact),
        Some("adjusted") => Ok(PlaneMode::Adjusted),
        Some(v) => Err(CliError::usage(
            Some(command),
            format!("--planes {v}: expected `exact` or `adjusted`"),
        )),
    }
}

fn parse_size(s: &str) -> Option<(u32, u32)> {
    let (w, h) = s.split_once(['x', 'X'])?;
    let (w, h): (u32, u32) = (w.trim().parse().ok()?, h.trim().parse().ok()?);
    ((16..=MAX_SIDE).contains(&w) && (16..=MAX_SIDE).contains(&h)).then_some((w, h))
}

/// Runs `tpi discretise`.
pub(crate) fn run(args: DiscretiseArgs) -> Result<(), CliError> {
    let opts = parse(args)?;
    // Cheap checks first: an output that can never be written, or that would overwrite an
    // input, fails before any work.
    let pattern_path = Path::new(&opts.pattern);
    let mut inputs = vec![Path::new(&opts.surface)];
    if pattern_path.exists() {
        inputs.push(pattern_path);
    }
    for (path, _) in &opts.outs {
        check_not_an_input(path, &inputs, "discretise")?;
        check_output_path(path)?;
    }
    let started = Instant::now();
    let progress = Progress::start();

    progress.stage("surface", None, opts.surface.clone());
    let surface: SurfaceModel = load_surface(Path::new(&opts.surface))?;

    // Sampled, a few milliseconds: a folded surface gets a warning, not silence.
    let self_intersection = crate::selfx::find(&surface, crate::selfx::DEFAULT_SAMPLES);

    let options = DiscretiseOptions {
        quality_report: opts.report,
        planes: opts.planes,
        ..DiscretiseOptions::default()
    };
    // A surface-aware spec (relax:, fit:, align:, density:) is made on the surface with the
    // same plane mode.
    progress.stage("pattern", None, opts.pattern.clone());
    // A fit or a relaxation runs many discretisations: the spinner's message follows them.
    let runs = crate::progress::PatternRuns::new(&progress, opts.pattern.clone());
    let pattern = load_pattern(&opts.pattern, &surface, &options, &runs)?;
    progress.end_stage();

    // The core's stages, each reported as it runs.
    let run_core = || discretise_with_progress(&surface, &pattern.pattern.uv, &options, &progress);
    let (result, threads) = match opts.threads {
        Some(n) => {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .thread_name(|i| format!("tpi-core-{i}"))
                .build()
                .map_err(|e| {
                    CliError::input("--threads", format!("cannot start {n} threads: {e}"))
                })?;
            (pool.install(run_core), n)
        }
        None => (run_core(), rayon::current_num_threads()),
    };
    let result = result.map_err(|e| core_error(&e, &opts.surface, &pattern))?;
    // Never a file with a non-finite number in it (issue 14: exit 0 with `null` vertices).
    check_finite(&result).map_err(|problem| {
        CliError::input(
            &opts.surface,
            format!("{problem}; no output written (the surface's evaluation does not stay finite at this pattern)"),
        )
    })?;

    let title = format!("{} with {}", opts.surface, pattern.label);
    let deviations = match opts.colour {
        PngColour::Sides => Vec::new(),
        PngColour::Deviation(_) => render::facet_deviations(&surface, &result),
    };
    let colouring = match opts.colour {
        PngColour::Sides => render::Colouring::Sides,
        PngColour::Deviation(scale) => render::Colouring::Deviation {
            per_facet: &deviations,
            scale: scale.unwrap_or_else(|| {
                let largest = deviations
                    .iter()
                    .copied()
                    .filter(|d| d.is_finite())
                    .fold(0.0, f64::max);
                if largest > 0.0 {
                    largest
                } else {
                    1.0
                }
            }),
        },
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::with_capacity(opts.outs.len());
    if !opts.outs.is_empty() {
        progress.stage("outputs", Some(opts.outs.len() as u64), "");
    }
    for (path, format) in &opts.outs {
        // Only the PNG is rendered; the other formats are written out as text.
        let verb = if matches!(format, Format::Png) {
            "rendering"
        } else {
            "encoding"
        };
        progress.message(format!("{verb} {}", path.display()));
        let bytes =
            render_output(&result, *format, &title, opts.size, colouring).map_err(|problem| {
                CliError::input(path.display(), format!("cannot encode: {problem}"))
            })?;
        files.push((path.clone(), bytes));
        progress.advance(1);
    }

    if !files.is_empty() {
        progress.stage("write", None, format!("{} files", files.len()));
    }
    write_all(&files)?;
    progress.finish();

    eprint!(
        "{}",
        summary::summary(&result, &opts.surface, &pattern.label, threads)
    );
    if !files.is_empty() {
        let names: Vec<String> = files
            .iter()
            .map(|(p, b)| format!("{} ({})", p.display(), human_size(b.len())))
            .collect();
        eprintln!("  wrote {}", names.join(", "));
    }
    eprintln!("  done in {:.0} ms", started.elapsed().as_secs_f64() * 1e3);
    if let Some(c) = &self_intersection {
        eprintln!("{}", crate::selfx::warning(c));
    }
    let mut topology = None;
    let cut = result
        .diagnostics
        .iter()
        .filter(|d| matches!(d, Diagnostic::FacetPartsLeftOut { .. }))
        .count();
    if cut > 0 {
        eprintln!("warning: the boundary cuts {cut} facet(s) into several parts (a strip across a hole or notch of a trim, or a saddle's facet whose edge dips beyond the wall): each keeps the part around its seed, and the other parts are left out as gaps beside the boundary (facet_parts_left_out in the JSON)");
    }
    for d in &result.diagnostics {
        match *d {
            Diagnostic::SeamLeftOpen { direction } => {
                let direction = if direction == 0 { "u" } else { "v" };
                eprintln!("warning: the surface is closed in {direction}, and it was discretised as an open patch: the mesh leaves its seam open (a trimmed surface, one closed both ways, or a structure that did not close across its seam)");
            }
            Diagnostic::UnexpectedTopology {
                euler,
                boundary_loops,
                expected_euler,
                expected_loops,
            } => {
                let invalid = result.quality.as_ref().map_or(0, |q| q.invalid_facets);
                eprintln!(
                    "{}",
                    summary::topology_warning(
                        (euler, boundary_loops),
                        (expected_euler, expected_loops),
                        invalid
                    )
                );
                topology = Some((euler, boundary_loops));
            }
            _ => {}
        }
    }
    if let Some(far) = result
        .quality
        .as_ref()
        .and_then(summary::far_vertex_warning)
    {
        eprintln!("{far}");
    }
    if let Some(q) = result.quality.as_ref().filter(|q| q.invalid_facets > 0) {
        eprintln!("{}", summary::invalid_warning(q));
        if opts.strict {
            return Err(CliError::InvalidFacets {
                count: q.invalid_facets,
            });
        }
    }
    if let (Some((euler, loops)), true) = (topology, opts.strict) {
        return Err(CliError::UnexpectedTopology { euler, loops });
    }
    Ok(())
}

fn render_output(
    result: &Discretisation,
    format: Format,
    title: &str,
    size: (u32, u32),
    colouring: render::Colouring<'_>,
) -> Result<Vec<u8>, String> {
    Ok(match format {
        Format::Json => result.to_json(true).into_bytes(),
        Format::Obj => obj::to_obj(result, title).into_bytes(),
        Format::Svg => svg::mesh_top_view(result, &format!("tpi: {title}")).into_bytes(),
        Format::Png => {
            let picture = render::Picture {
                colouring,
                seeds: false,
            };
            let rgb = render::render_picture(result, size.0, size.1, picture);
            render::encode_png(&rgb, size.0, size.1)?
        }
    })
}

/// A core error names the pattern when it is about the pattern, else the surface file.
fn core_error(e: &TpiError, surface: &str, pattern: &PatternSource) -> CliError {
    match e {
        TpiError::PatternPointOutOfRange { .. }
        | TpiError::DuplicatePatternPoint { .. }
        | TpiError::SameSurfacePoint { .. }
        | TpiError::TooFewPatternPoints { .. }
        | TpiError::CollinearPattern { .. } => CliError::core(&pattern.label, e),
        _ => CliError::core(surface, e),
    }
}

/// The first non-finite number of a result that an output would carry: a vertex, a seed's
/// point, normal or curvatures, a number of the quality report.
fn check_finite(result: &Discretisation) -> Result<(), String> {
    if let Some((i, v)) = result
        .vertices
        .iter()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
    {
        return Err(format!(
            "vertex {i} is not finite ({}, {}, {})",
            v.x, v.y, v.z
        ));
    }
    for (i, s) in result.seeds.iter().enumerate() {
        let numbers = [s.point.to_array(), s.normal.to_array()].concat();
        if numbers
            .iter()
            .chain(&s.uv)
            .chain(&s.curvatures)
            .any(|x| !x.is_finite())
        {
            return Err(format!(
                "pattern point {i}: surface point, normal or curvature not finite"
            ));
        }
    }
    if let Some(q) = &result.quality {
        let numbers = [
            ("trivalent fraction", q.trivalent_fraction),
            ("planarity", q.max_planarity_error),
            ("deviation", q.max_deviation),
            ("mean deviation", q.mean_deviation),
            ("facet area", q.min_facet_area),
            ("facet area", q.max_facet_area),
            ("edge length", q.min_edge_length),
            ("edge length", q.max_edge_length),
            ("bounding box diagonal", q.bounding_box_diagonal),
        ];
        if let Some((name, x)) = numbers.iter().find(|(_, x)| !x.is_finite()) {
            return Err(format!("the quality report's {name} is not finite ({x})"));
        }
        if !q.all_finite {
            return Err("the quality report found non-finite vertices".to_string());
        }
    }
    Ok(())
}

fn human_size(n: usize) -> String {
    if n >= 1 << 20 {
        format!("{:.1} MB", n as f64 / (1 << 20) as f64)
    } else if n >= 1 << 10 {
        format!("{:.0} kB", n as f64 / 1024.0)
    } else {
        format!("{n} B")
    }
}

#[cfg(test)]
mod tests {
    use super::check_finite;
    use glam::DVec3;
    use tpi_core::{Discretisation, QualityReport, Seed};

    fn finite() -> Discretisation {
        Discretisation {
            vertices: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
            seeds: vec![Seed {
                uv: [0.5, 0.5],
                point: DVec3::ZERO,
                normal: DVec3::Z,
                curvatures: [0.1, 0.2],
            }],
            quality: Some(QualityReport {
                all_finite: true,
                ..QualityReport::default()
            }),
            ..Discretisation::default()
        }
    }

    #[test]
    fn every_non_finite_number_is_refused_before_writing() {
        // Issue 14: an overflowing surface gave `null` vertices in the JSON and exit 0.
        assert_eq!(check_finite(&finite()), Ok(()));
        let mut vertex = finite();
        vertex.vertices[2].y = f64::NAN;
        let message = check_finite(&vertex).unwrap_err();
        assert!(message.starts_with("vertex 2 is not finite"), "{message}");
        let mut seed = finite();
        seed.seeds[0].curvatures[1] = f64::INFINITY;
        let message = check_finite(&seed).unwrap_err();
        assert!(message.starts_with("pattern point 0:"), "{message}");
        let mut report = finite();
        if let Some(q) = report.quality.as_mut() {
            q.max_deviation = f64::INFINITY;
        }
        let message = check_finite(&report).unwrap_err();
        assert!(message.contains("deviation is not finite"), "{message}");
        let mut flagged = finite();
        if let Some(q) = flagged.quality.as_mut() {
            q.all_finite = false;
        }
        assert!(check_finite(&flagged).is_err());
    }
}
