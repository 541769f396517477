//! `tpi bench`: the discretisation's speed on the benchmark surfaces of
//! `tpi_core::benchmark`, stage by stage, with facets per second and peak memory
//! (docs/performance.md).

use std::fmt::Write;
use std::path::PathBuf;
use std::time::Instant;

use serde::Serialize;
use tpi_core::benchmark::{
    floor, nurbs_dome, paraboloid, poisson_pattern, random_pattern, saddle, FloorTimings,
};
use tpi_core::SplitMix64;
use tpi_core::{
    discretise, fabricate, DiscretiseOptions, FabricateOptions, LiveSurface, SlotPlan, Surface,
    Timings, ToolpathOptions,
};

use crate::error::CliError;
use crate::output::{check_output_path, write_all};

pub(crate) const AFTER_HELP: &str = "\
Discretises N uniform random pattern points (SplitMix64, seed 7 + N; with --pattern poisson
about N Poisson-disk points) on (a) the paraboloid of revolution z = -0.08 (x^2 + y^2) over
[-5, 5]^2, (b) a bicubic NURBS dome with 12 x 12 control points and non-uniform knots and
(c) a bicubic NURBS saddle (K < 0 everywhere), R times each, and prints the median time of
every stage in milliseconds: samples (evaluation and curvature, pattern validation),
Delaunay, neighbours (curvature compensation / envelope), facets (vertices and boundary),
mesh (assembly), report (quality report) and total, with facets per second, the threads
used and the process's peak resident memory while that size ran (VmHWM).

With --edits E it then times live editing (tpi_core::LiveSurface) on the same surface: E
drags of random pattern points inside [0.1, 0.9]^2, each by up to half a point spacing,
and prints the median time of one edit (the local update of structure, facets and report
data), the share that took the incremental path, and the median time to assemble the
edited mesh (numbering, loops, the report's aggregates) after an edit (5 samples, timed
apart from the edits).

EXAMPLES:
    tpi bench
    tpi bench --sizes 1000 --threads 1 --repeat 101
    tpi bench --sizes 10000 --surfaces paraboloid,saddle --pattern poisson
    tpi bench --sizes 1000,1000000 --repeat 1 --edits 1001 --surfaces nurbs
    tpi bench --sizes 1000,10000,100000,1000000 --json --plot docs/performance-scaling.svg
    tpi bench --sizes 10000 --surfaces nurbs --fabricate --repeat 1
";

/// The arguments of `tpi bench`, as given (checked in [`parse`]).
#[derive(clap::Args, Debug)]
pub(crate) struct BenchArgs {
    /// Pattern sizes, comma-separated [default: 1000,10000,100000,1000000]
    #[arg(long, value_name = "LIST")]
    sizes: Option<String>,
    /// paraboloid, nurbs, saddle, comma-separated (saddle: K < 0 everywhere, the
    /// any-curvature path) [default: all three]
    #[arg(long, value_name = "LIST")]
    surfaces: Option<String>,
    /// random (uniform, SplitMix64, seed 7 + N) or poisson (Poisson-disk, radius
    /// sqrt(0.7 / N): about N points, evenly spaced) [default: random]
    #[arg(long, value_name = "KIND")]
    pattern: Option<String>,
    /// Rayon threads [default: all cores]
    #[arg(long, value_name = "T")]
    threads: Option<String>,
    /// Runs per size, the median is reported (odd is best) [default: 3]
    #[arg(long, value_name = "R")]
    repeat: Option<String>,
    /// Switch the quality report off (DiscretiseOptions::quality_report)
    #[arg(long)]
    no_report: bool,
    /// Also time E live edits per size [default: 0]
    #[arg(long, value_name = "E")]
    edits: Option<String>,
    /// Also time the floor (tpi_core::benchmark::floor: evaluation with curvature, one
    /// Delaunay triangulation of the slopes, one three-plane solve per triangle; and apart,
    /// one text write of the result) in the same process and print the pipeline's ratio to it
    #[arg(long)]
    floor: bool,
    /// Also time fabrication (tpi_core::fabricate: panel solids with 2 cleat slots per edge,
    /// flat parts, nesting on 2.5 x 1.25 sheets, and every output: JSON, OBJ, SVG, DXF,
    /// G-code, bevels) of each size's mesh
    #[arg(long)]
    fabricate: bool,
    /// Print JSON instead of the table
    #[arg(long)]
    json: bool,
    /// Also write a log-log plot of total time against the pattern size
    #[arg(long, value_name = "FILE.svg")]
    plot: Option<PathBuf>,
}

/// The benchmark's surfaces by name.
const SURFACES: [&str; 3] = ["paraboloid", "nurbs", "saddle"];

/// The benchmark's pattern kinds by name (the first is the default).
const PATTERNS: [&str; 2] = ["random", "poisson"];

struct Config {
    sizes: Vec<usize>,
    surfaces: Vec<&'static str>,
    pattern: &'static str,
    threads: Option<usize>,
    repeat: usize,
    report: bool,
    json: bool,
    plot: Option<PathBuf>,
    edits: usize,
    floor: bool,
    fabricate: bool,
}

/// One surface and size: the medians.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct Row {
    /// Surface name.
    pub surface: &'static str,
    /// Pattern points.
    pub points: usize,
    /// Facets (one per pattern point).
    pub facets: usize,
    /// Median of each stage and the total, milliseconds.
    pub median_ms: Timings,
    /// Facets per second at the median total.
    pub facets_per_second: f64,
    /// Peak resident memory of the process while this size ran, in MB (10^6 bytes); 0 where
    /// the system does not say.
    pub peak_memory_mb: f64,
    /// Live editing, with --edits.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub edits: Option<EditRow>,
    /// The floor's medians, with --floor.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub floor_ms: Option<FloorTimings>,
    /// The pipeline's median total over the floor's median compute, with --floor.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub floor_ratio: Option<f64>,
    /// Fabrication of the mesh, with --fabricate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fabrication: Option<FabricationRow>,
}

/// Fabrication of one surface and size (see `--fabricate`).
#[derive(Clone, Debug, Serialize)]
pub(crate) struct FabricationRow {
    /// Panel thickness used: 1e-3 of the mesh's diagonal, or half the largest the mesh
    /// allows where that is less.
    pub thickness: f64,
    /// Sheets the parts were nested on.
    pub sheets: usize,
    /// Median time of the fabrication (solids, flat parts, nesting), milliseconds.
    pub median_fabricate_ms: f64,
    /// Median time of writing every output to memory, milliseconds.
    pub median_outputs_ms: f64,
}

/// Live editing on one surface and size.
#[derive(Clone, Debug, Serialize)]
pub(crate) struct EditRow {
    /// Edits timed.
    pub count: usize,
    /// Median time of one edit, microseconds.
    pub median_edit_us: f64,
    /// Share of the edits that took the incremental path.
    pub incremental_share: f64,
    /// Median time to assemble the mesh after an edit, milliseconds.
    pub median_assembly_ms: f64,
}

/// The whole run.
#[derive(Debug, Serialize)]
pub(crate) struct Report {
    /// tpi's version.
    pub version: &'static str,
    /// rayon threads used.
    pub threads: usize,
    /// Runs per size.
    pub repeat: usize,
    /// Whether the quality report was on.
    pub quality_report: bool,
    /// The pattern kind: "random" or "poisson".
    pub pattern: &'static str,
    /// One row per surface and size.
    pub results: Vec<Row>,
}

/// Runs `tpi bench`.
pub(crate) fn run(args: BenchArgs) -> Result<(), CliError> {
    let config = parse(args)?;
    if let Some(plot) = &config.plot {
        check_output_path(plot)?;
    }
    let pool = match config.threads {
        Some(t) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .map_err(|e| CliError::input("--threads", e.to_string()))?,
        ),
        None => None,
    };
    let body = || measure(&config);
    let report = match &pool {
        Some(pool) => pool.install(body),
        None => body(),
    }?;
    if config.json {
        let text = serde_json::to_string_pretty(&report)
            .map_err(|e| CliError::input("JSON", e.to_string()))?;
        println!("{text}");
    } else {
        print!("{}", table(&report));
    }
    if let Some(plot) = &config.plot {
        write_all(&[(plot.clone(), scaling_plot(&report).into_bytes())])?;
    }
    Ok(())
}

fn parse(args: BenchArgs) -> Result<Config, CliError> {
    let usage = |message: String| CliError::usage(Some("bench"), message);
    let mut config = Config {
        sizes: vec![1_000, 10_000, 100_000, 1_000_000],
        surfaces: SURFACES.to_vec(),
        pattern: PATTERNS[0],
        threads: None,
        repeat: 3,
        report: !args.no_report,
        json: args.json,
        plot: None,
        edits: 0,
        floor: args.floor,
        fabricate: args.fabricate,
    };
    if let Some(v) = &args.sizes {
        config.sizes = v
            .split(',')
            .map(|s| match s.trim().replace('_', "").parse::<usize>() {
                Ok(n) if (3..=10_000_000).contains(&n) => Ok(n),
                _ => Err(usage(format!(
                    "--sizes {v}: expected whole numbers from 3 to 10000000, comma-separated"
                ))),
            })
            .collect::<Result<_, _>>()?;
    }
    if let Some(v) = &args.surfaces {
        config.surfaces = v
            .split(',')
            .map(|s| {
                SURFACES
                    .iter()
                    .find(|&&known| known == s.trim())
                    .copied()
                    .ok_or_else(|| {
                        usage(format!(
                            "--surfaces {v}: the surfaces are paraboloid, nurbs and saddle"
                        ))
                    })
            })
            .collect::<Result<_, _>>()?;
    }
    if let Some(v) = &args.pattern {
        config.pattern = PATTERNS
            .iter()
            .find(|&&known| known == v.trim())
            .copied()
            .ok_or_else(|| {
                usage(format!(
                    "--pattern {v}: the patterns are random and poisson"
                ))
            })?;
    }
    if let Some(v) = &args.threads {
        config.threads = match v.parse::<usize>() {
            Ok(n) if (1..=1024).contains(&n) => Some(n),
            _ => {
                return Err(usage(format!(
                    "--threads {v}: expected a whole number from 1 to 1024"
                )))
            }
        };
    }
    if let Some(v) = &args.repeat {
        config.repeat = match v.parse::<usize>() {
            Ok(n) if (1..=100_000).contains(&n) => n,
            _ => {
                return Err(usage(format!(
                    "--repeat {v}: expected a whole number from 1 to 100000"
                )))
            }
        };
    }
    if let Some(v) = &args.edits {
        config.edits = match v.parse::<usize>() {
            Ok(n) if n <= 1_000_000 => n,
            _ => {
                return Err(usage(format!(
                    "--edits {v}: expected a whole number up to 1000000"
                )))
            }
        };
    }
    if let Some(v) = args.plot {
        if v.extension().and_then(|e| e.to_str()) != Some("svg") {
            return Err(usage(format!(
                "--plot {}: the plot is an .svg file",
                v.display()
            )));
        }
        config.plot = Some(v);
    }
    Ok(config)
}

fn measure(config: &Config) -> Result<Report, CliError> {
    let options = DiscretiseOptions {
        quality_report: config.report,
        ..DiscretiseOptions::default()
    };
    let mut results = Vec::new();
    for &name in &config.surfaces {
        let surface: Box<dyn Surface> = match name {
            "paraboloid" => Box::new(paraboloid()),
            "saddle" => Box::new(saddle()),
            _ => Box::new(nurbs_dome()),
        };
        for &n in &config.sizes {
            let pattern = match config.pattern {
                "poisson" => poisson_pattern(n),
                _ => random_pattern(n),
            };
            reset_peak_memory();
            // One unmeasured run warms caches and the allocator on the smaller sizes.
            if n <= 100_000 {
                run_once(surface.as_ref(), &pattern, &options, name)?;
            }
            let mut runs = Vec::with_capacity(config.repeat);
            let mut facets = 0;
            for _ in 0..config.repeat {
                let (timings, count) = run_once(surface.as_ref(), &pattern, &options, name)?;
                facets = count;
                runs.push(timings);
            }
            let median_ms = median_timings(&runs);
            let floor_ms = if config.floor {
                let floors = (0..config.repeat)
                    .map(|_| {
                        floor(surface.as_ref(), &pattern).map_err(|e| CliError::core(name, &e))
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                let pick = |f: fn(&FloorTimings) -> f64| median(floors.iter().map(f).collect());
                Some(FloorTimings {
                    samples: pick(|f| f.samples),
                    triangulation: pick(|f| f.triangulation),
                    plane_solves: pick(|f| f.plane_solves),
                    write: pick(|f| f.write),
                    compute: pick(|f| f.compute),
                })
            } else {
                None
            };
            let edits = if config.edits > 0 {
                Some(edit_timings(name, &pattern, config.edits, &options)?)
            } else {
                None
            };
            let fabrication = if config.fabricate {
                Some(fabrication_timings(
                    surface.as_ref(),
                    &pattern,
                    &options,
                    name,
                    config.repeat,
                )?)
            } else {
                None
            };
            results.push(Row {
                surface: name,
                points: pattern.len(),
                facets,
                facets_per_second: if median_ms.total > 0.0 {
                    facets as f64 / (median_ms.total * 1e-3)
                } else {
                    0.0
                },
                median_ms,
                peak_memory_mb: peak_memory_bytes() as f64 / 1e6,
                edits,
                floor_ratio: floor_ms
                    .filter(|f| f.compute > 0.0)
                    .map(|f| median_ms.total / f.compute),
                floor_ms,
                fabrication,
            });
        }
    }
    Ok(Report {
        version: env!("CARGO_PKG_VERSION"),
        threads: rayon::current_num_threads(),
        repeat: config.repeat,
        quality_report: config.report,
        pattern: config.pattern,
        results,
    })
}

fn run_once(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
    name: &str,
) -> Result<(Timings, usize), CliError> {
    let start = Instant::now();
    let result = discretise(surface, pattern, options).map_err(|e| CliError::core(name, &e))?;
    let mut timings = result.timings;
    // The total as the caller sees it (validation and result construction included).
    timings.total = timings.total.max(start.elapsed().as_secs_f64() * 1e3);
    let facets = result.facet_count();
    drop(result);
    Ok((timings, facets))
}

/// Times fabrication of the mesh of `pattern` on `surface` (see `--fabricate`), `repeat`
/// times, medians.
fn fabrication_timings(
    surface: &dyn Surface,
    pattern: &[[f64; 2]],
    options: &DiscretiseOptions,
    name: &str,
    repeat: usize,
) -> Result<FabricationRow, CliError> {
    let mesh = discretise(surface, pattern, options).map_err(|e| CliError::core(name, &e))?;
    let fail = |e: &tpi_core::FabricationError| CliError::input(name, e.to_string());
    let (lo, hi) = mesh.vertices.iter().fold(
        (glam::DVec3::INFINITY, glam::DVec3::NEG_INFINITY),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    );
    let mut fab_options = FabricateOptions {
        thickness: 1e-3 * (hi - lo).length(),
        slots: SlotPlan::Even(2),
        gap: 0.01,
        ..FabricateOptions::default()
    };
    if let Err(tpi_core::FabricationError::ThicknessTooLarge { max, .. }) =
        fabricate(&mesh, &fab_options)
    {
        fab_options.thickness = 0.5 * max;
    }
    // A router bit no wider than the panel (the slots are 4 x 2 thicknesses) nor the gap.
    let tool = ToolpathOptions {
        tool_diameter: fab_options.thickness.min(0.006).min(fab_options.gap),
        ..ToolpathOptions::default()
    };
    let (mut build, mut write) = (Vec::new(), Vec::new());
    let mut sheets = 0;
    for _ in 0..repeat.max(1) {
        let start = Instant::now();
        let fab = fabricate(&mesh, &fab_options).map_err(|e| fail(&e))?;
        build.push(start.elapsed().as_secs_f64() * 1e3);
        let start = Instant::now();
        let bytes = fab.to_json().len()
            + fab.to_obj().len()
            + fab.sheets_svg().len()
            + fab
                .sheets_dxf(tpi_core::Units::Metres)
                .map_err(|e| fail(&e))?
                .len()
            + fab.bevels_csv().len()
            + fab.gcode(&tool).map_err(|e| fail(&e))?.len();
        write.push(start.elapsed().as_secs_f64() * 1e3);
        std::hint::black_box(bytes);
        sheets = fab.sheets.len();
    }
    Ok(FabricationRow {
        thickness: fab_options.thickness,
        sheets,
        median_fabricate_ms: median(build),
        median_outputs_ms: median(write),
    })
}

/// Times `count` live drags (see the help) on a live surface of `pattern`.
fn edit_timings(
    name: &str,
    pattern: &[[f64; 2]],
    count: usize,
    options: &DiscretiseOptions,
) -> Result<EditRow, CliError> {
    let surface: Box<dyn Surface> = match name {
        "paraboloid" => Box::new(paraboloid()),
        "saddle" => Box::new(saddle()),
        _ => Box::new(nurbs_dome()),
    };
    let mut live = LiveSurface::new(surface, pattern.to_vec(), *options)
        .map_err(|e| CliError::core(name, &e))?;
    let before = live.stats();
    let n = pattern.len();
    let mut rng = SplitMix64::new(97 + n as u64);
    let mut edit_us = Vec::with_capacity(count);
    let mut assembly_ms = Vec::new();
    let step = 0.5 / (n as f64).sqrt();
    let mut drag = |live: &mut LiveSurface| -> Result<f64, CliError> {
        // A point inside [0.1, 0.9]^2, dragged by up to half a spacing.
        let i = loop {
            let i = rng.below(n);
            let p = live.points()[i];
            if (0.1..=0.9).contains(&p[0]) && (0.1..=0.9).contains(&p[1]) {
                break i;
            }
        };
        let p = live.points()[i];
        let q = [
            p[0] + step * (rng.next_f64() - 0.5),
            p[1] + step * (rng.next_f64() - 0.5),
        ];
        let start = Instant::now();
        let moved = live.move_point(i, q);
        let us = start.elapsed().as_secs_f64() * 1e6;
        moved.map_err(|e| CliError::core(name, &e))?;
        Ok(us)
    };
    for _ in 0..count {
        edit_us.push(drag(&mut live)?);
    }
    let stats = live.stats();
    // Then a few edits each followed by assembling the mesh (kept apart: assembling a large
    // mesh evicts the caches the edits live in).
    for _ in 0..count.clamp(1, 5) {
        drag(&mut live)?;
        let start = Instant::now();
        let facets = live.discretisation().facet_count();
        assembly_ms.push(start.elapsed().as_secs_f64() * 1e3);
        if facets != n {
            return Err(CliError::input(name, "live editing lost a facet"));
        }
    }
    Ok(EditRow {
        count,
        median_edit_us: median(edit_us),
        incremental_share: (stats.incremental - before.incremental) as f64 / count.max(1) as f64,
        median_assembly_ms: median(assembly_ms),
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// The median of each field separately.
fn median_timings(runs: &[Timings]) -> Timings {
    let median = |f: fn(&Timings) -> f64| {
        let mut v: Vec<f64> = runs.iter().map(f).collect();
        v.sort_by(f64::total_cmp);
        match v.len() {
            0 => 0.0,
            n if n % 2 == 1 => v[n / 2],
            n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
        }
    };
    Timings {
        samples: median(|t| t.samples),
        delaunay: median(|t| t.delaunay),
        neighbours: median(|t| t.neighbours),
        facets: median(|t| t.facets),
        mesh: median(|t| t.mesh),
        report: median(|t| t.report),
        total: median(|t| t.total),
    }
}

/// Resets the kernel's peak-RSS counter of this process (Linux 4.0+); harmless elsewhere.
fn reset_peak_memory() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// VmHWM of this process in bytes, or 0 where unknown.
fn peak_memory_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find_map(|l| {
                let rest = l.strip_prefix("VmHWM:")?;
                rest.trim()
                    .trim_end_matches("kB")
                    .trim()
                    .parse::<u64>()
                    .ok()
            })
        })
        .map_or(0, |kb| kb * 1024)
}

/// The human-readable table.
pub(crate) fn table(report: &Report) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "tpi bench: {} pattern, median of {} run{}, {} thread{}, quality report {} (times in ms)",
        report.pattern,
        report.repeat,
        if report.repeat == 1 { "" } else { "s" },
        report.threads,
        if report.threads == 1 { "" } else { "s" },
        if report.quality_report { "on" } else { "off" }
    );
    let _ = writeln!(
        s,
        "{:<10} {:>8} {:>9} {:>9} {:>10} {:>9} {:>9} {:>9} {:>10} {:>12} {:>8}",
        "surface",
        "points",
        "samples",
        "delaunay",
        "neighbours",
        "facets",
        "mesh",
        "report",
        "total",
        "facets/s",
        "peak MB"
    );
    for r in &report.results {
        let t = &r.median_ms;
        let _ = writeln!(
            s,
            "{:<10} {:>8} {:>9.3} {:>9.3} {:>10.3} {:>9.3} {:>9.3} {:>9.3} {:>10.3} {:>12.0} {:>8.1}",
            r.surface, r.points, t.samples, t.delaunay, t.neighbours, t.facets, t.mesh, t.report, t.total, r.facets_per_second, r.peak_memory_mb
        );
    }
    if report.results.iter().any(|r| r.floor_ms.is_some()) {
        let _ = writeln!(
            s,
            "floor (what any TPI run must do; ratio = pipeline total / floor compute):"
        );
        let _ = writeln!(
            s,
            "{:<10} {:>8} {:>9} {:>13} {:>12} {:>9} {:>9} {:>9} {:>7}",
            "surface",
            "points",
            "samples",
            "triangulation",
            "plane solves",
            "compute",
            "total",
            "write",
            "ratio"
        );
        for r in &report.results {
            if let (Some(f), Some(ratio)) = (&r.floor_ms, r.floor_ratio) {
                let _ = writeln!(
                    s,
                    "{:<10} {:>8} {:>9.3} {:>13.3} {:>12.3} {:>9.3} {:>9.3} {:>9.3} {:>6.1}x",
                    r.surface,
                    r.points,
                    f.samples,
                    f.triangulation,
                    f.plane_solves,
                    f.compute,
                    r.median_ms.total,
                    f.write,
                    ratio
                );
            }
        }
    }
    if report.results.iter().any(|r| r.fabrication.is_some()) {
        let _ = writeln!(
            s,
            "fabrication (solids, 2 slots per edge, flat parts, nesting; then every output written to memory):"
        );
        let _ = writeln!(
            s,
            "{:<10} {:>8} {:>10} {:>7} {:>10} {:>10} {:>10}",
            "surface", "panels", "thickness", "sheets", "fabricate", "outputs", "total"
        );
        for r in &report.results {
            if let Some(f) = &r.fabrication {
                let _ = writeln!(
                    s,
                    "{:<10} {:>8} {:>10.3e} {:>7} {:>10.1} {:>10.1} {:>10.1}",
                    r.surface,
                    r.facets,
                    f.thickness,
                    f.sheets,
                    f.median_fabricate_ms,
                    f.median_outputs_ms,
                    r.median_ms.total + f.median_fabricate_ms + f.median_outputs_ms
                );
            }
        }
    }
    if report.results.iter().any(|r| r.edits.is_some()) {
        let _ = writeln!(s, "live edits (drags inside [0.1, 0.9]^2):");
        let _ = writeln!(
            s,
            "{:<10} {:>8} {:>8} {:>14} {:>12} {:>14}",
            "surface", "points", "edits", "median edit us", "incremental", "assembly ms"
        );
        for r in &report.results {
            if let Some(e) = &r.edits {
                let _ = writeln!(
                    s,
                    "{:<10} {:>8} {:>8} {:>14.1} {:>11.1}% {:>14.3}",
                    r.surface,
                    r.points,
                    e.count,
                    e.median_edit_us,
                    100.0 * e.incremental_share,
                    e.median_assembly_ms
                );
            }
        }
    }
    s
}

/// A log-log SVG plot of the median total time against the pattern size, one line per
/// surface, with dashed n and n log n reference slopes through each line's first point.
pub(crate) fn scaling_plot(report: &Report) -> String {
    let (width, height) = (640.0, 440.0);
    let (left, right, top, bottom) = (70.0, 170.0, 40.0, 50.0);
    let points: Vec<(f64, f64)> = report
        .results
        .iter()
        .map(|r| (r.points as f64, r.median_ms.total.max(1e-6)))
        .collect();
    let (mut x_lo, mut x_hi, mut y_lo, mut y_hi) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in &points {
        x_lo = x_lo.min(x);
        x_hi = x_hi.max(x);
        y_lo = y_lo.min(y);
        y_hi = y_hi.max(y);
    }
    if points.is_empty() {
        (x_lo, x_hi, y_lo, y_hi) = (1e3, 1e6, 1e-1, 1e3);
    }
    // Whole decades around the data (a value on a decade stays on it).
    let decade = |v: f64, up: bool| {
        let l = v.log10();
        10f64.powf(if up {
            (l - 1e-9).ceil()
        } else {
            (l + 1e-9).floor()
        })
    };
    let (x_lo, x_hi) = (
        decade(x_lo, false),
        decade(x_hi, true).max(decade(x_lo, false) * 10.0),
    );
    let (y_lo, y_hi) = (
        decade(y_lo, false),
        decade(y_hi, true).max(decade(y_lo, false) * 10.0),
    );
    let plot_w = width - left - right;
    let plot_h = height - top - bottom;
    let sx = |x: f64| left + (x.log10() - x_lo.log10()) / (x_hi.log10() - x_lo.log10()) * plot_w;
    let sy =
        |y: f64| top + plot_h - (y.log10() - y_lo.log10()) / (y_hi.log10() - y_lo.log10()) * plot_h;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="22" text-anchor="middle" font-size="14">tpi bench: median total time, {} thread{}, report {}</text>"#,
        left + plot_w / 2.0,
        report.threads,
        if report.threads == 1 { "" } else { "s" },
        if report.quality_report { "on" } else { "off" }
    );
    // Grid and axes, one line per decade.
    let mut x = x_lo;
    while x <= x_hi * 1.0001 {
        let px = sx(x);
        let _ = writeln!(
            s,
            r##"<line x1="{px:.1}" y1="{top}" x2="{px:.1}" y2="{:.1}" stroke="#ddd"/>"##,
            top + plot_h
        );
        let _ = writeln!(
            s,
            r#"<text x="{px:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
            top + plot_h + 16.0,
            si(x)
        );
        x *= 10.0;
    }
    let mut y = y_lo;
    while y <= y_hi * 1.0001 {
        let py = sy(y);
        let _ = writeln!(
            s,
            r##"<line x1="{left}" y1="{py:.1}" x2="{:.1}" y2="{py:.1}" stroke="#ddd"/>"##,
            left + plot_w
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
            left - 6.0,
            py + 4.0,
            ms_label(y)
        );
        y *= 10.0;
    }
    let _ = writeln!(
        s,
        r##"<rect x="{left}" y="{top}" width="{plot_w}" height="{plot_h}" fill="none" stroke="#333"/>"##
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" text-anchor="middle">pattern points = facets (n)</text>"#,
        left + plot_w / 2.0,
        height - 12.0
    );
    let _ = writeln!(
        s,
        r#"<text transform="translate(18 {:.1}) rotate(-90)" text-anchor="middle">median total (ms)</text>"#,
        top + plot_h / 2.0
    );
    let colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];
    let mut legend_y = top + 10.0;
    let mut names: Vec<&str> = Vec::new();
    for r in &report.results {
        if !names.contains(&r.surface) {
            names.push(r.surface);
        }
    }
    for (k, name) in names.iter().enumerate() {
        let colour = colours[k % colours.len()];
        let line: Vec<(f64, f64)> = report
            .results
            .iter()
            .filter(|r| r.surface == *name)
            .map(|r| (r.points as f64, r.median_ms.total.max(1e-6)))
            .collect();
        let path: Vec<String> = line
            .iter()
            .map(|&(x, y)| format!("{:.1},{:.1}", sx(x), sy(y)))
            .collect();
        let _ = writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="2"/>"#,
            path.join(" ")
        );
        for &(x, y) in &line {
            let _ = writeln!(
                s,
                r#"<circle cx="{:.1}" cy="{:.1}" r="3.5" fill="{colour}"/>"#,
                sx(x),
                sy(y)
            );
        }
        // n log n reference through the first point.
        if let (Some(&(x0, y0)), Some(&(x1, _))) = (line.first(), line.last()) {
            if x1 > x0 {
                let y1 = y0 * (x1 * x1.ln()) / (x0 * x0.ln());
                let _ = writeln!(
                    s,
                    r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{colour}" stroke-dasharray="5 4" stroke-width="1"/>"#,
                    sx(x0),
                    sy(y0),
                    sx(x1),
                    sy(y1.clamp(y_lo, y_hi))
                );
            }
        }
        let _ = writeln!(
            s,
            r#"<line x1="{:.1}" y1="{legend_y:.1}" x2="{:.1}" y2="{legend_y:.1}" stroke="{colour}" stroke-width="2"/>"#,
            left + plot_w + 12.0,
            left + plot_w + 36.0
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}">{name}</text>"#,
            left + plot_w + 42.0,
            legend_y + 4.0
        );
        legend_y += 18.0;
    }
    let _ = writeln!(
        s,
        r##"<line x1="{:.1}" y1="{legend_y:.1}" x2="{:.1}" y2="{legend_y:.1}" stroke="#555" stroke-dasharray="5 4"/>"##,
        left + plot_w + 12.0,
        left + plot_w + 36.0
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}">n log n</text>"#,
        left + plot_w + 42.0,
        legend_y + 4.0
    );
    let _ = writeln!(s, "</svg>");
    s
}

fn si(x: f64) -> String {
    match x {
        x if x >= 1e6 => format!("{}M", x / 1e6),
        x if x >= 1e3 => format!("{}k", x / 1e3),
        x => format!("{x}"),
    }
}

fn ms_label(y: f64) -> String {
    if y >= 1.0 {
        format!("{y:.0}")
    } else {
        format!("{y}")
    }
}
