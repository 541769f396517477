//! `tpi fabricate`: surface + pattern + thickness -> panel solids, joints, nested sheets and
//! toolpaths.

use std::path::{Path, PathBuf};
use std::time::Instant;

use tpi_core::{
    discretise, fabricate, DiscretiseOptions, FabricateOptions, Fabrication, FabricationDiagnostic,
    FabricationError, PanelSide, PlaneMode, SlotPlan, ToolpathOptions, Units,
};

use crate::cmd_discretise::{output_formats, plane_mode, thread_count};
use crate::error::CliError;
use crate::input::{load_pattern, load_surface};
use crate::output::{check_not_an_input, check_output_path, read_text, write_all};

/// The text after the options in `tpi fabricate --help`.
pub(crate) const AFTER_HELP: &str = "\
Every facet becomes a panel of thickness T: its bottom face is the facet's plane offset by T,
neighbouring panels are cut on the bisector plane of their facets (a mitre with no gap), and
boundary sides are square. Lengths are in the surface's model units. docs/fabrication.md.
Outputs are written as for `tpi discretise` (checked, through temporary files renamed
together; an output that is also an input is refused).

EXAMPLES:
    tpi fabricate --surface samples/nurbs-dome.json --pattern samples/poisson-0.03.json \\
        --thickness 0.04 --slots 2 --out panels.json --out sheets.svg --out cut.nc
";

/// The arguments of `tpi fabricate`, as given (checked in [`run`]).
#[derive(clap::Args, Debug)]
pub(crate) struct FabricateArgs {
    /// Surface file (docs/formats.md) [required]
    #[arg(long, value_name = "FILE")]
    surface: Option<String>,
    /// Pattern file or pattern spec, also one made on the surface such as relax:20:random:500
    /// or fit:0.01 (as for `tpi discretise`) [required]
    #[arg(long, value_name = "P")]
    pattern: Option<String>,
    /// Panel thickness (> 0, below the limit the mesh allows) [required]
    #[arg(long, short = 't', value_name = "T", allow_hyphen_values = true)]
    thickness: Option<String>,
    /// inside (towards the centres of curvature) or outside [default: inside]
    #[arg(long, value_name = "SIDE")]
    side: Option<String>,
    /// N cleat slots evenly along every interior edge, or a JSON file
    /// {"slots": [{"edge": [i, j], "at": [t, ...]}]}
    #[arg(long, value_name = "N|FILE")]
    slots: Option<String>,
    /// Slot length along the edge x depth into each panel [default: 4T x 2T]
    #[arg(long, value_name = "LxD")]
    slot_size: Option<String>,
    /// Sheet size [default: 2.5x1.25]
    #[arg(long, value_name = "WxH")]
    sheet: Option<String>,
    /// Least distance between parts and from the sheet edge [default: 0.02]
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    gap: Option<String>,
    /// Router tool diameter for cut.nc, at most the gap [default: 0.006]
    #[arg(long, value_name = "D", allow_hyphen_values = true)]
    tool_diameter: Option<String>,
    /// um, mm, cm, m, km, in, ft, yd or mi (or Rhino's names): DXF $INSUNITS and G20/G21
    /// [default: the surface file's "units", else m]
    #[arg(long, value_name = "U")]
    units: Option<String>,
    /// Material density, for the mass in the summary
    #[arg(long, value_name = "RHO", allow_hyphen_values = true)]
    density: Option<String>,
    /// Facet planes: `exact` or `adjusted` (tilted where exact planes cannot give a valid
    /// facet; see `tpi discretise --help`) [default: exact]
    #[arg(long, value_name = "MODE")]
    planes: Option<String>,
    /// Run the core on N threads [default: one per core]
    #[arg(long, short = 'j', value_name = "N")]
    threads: Option<String>,
    /// Output, repeatable; the extension picks the format: .json (panels, sides, angles,
    /// flat outlines, placements, slots), .obj (one closed polyhedron per panel and cleat),
    /// .svg (the nested sheets), .dxf (ASCII DXF R2000: CUT, SLOT, ENGRAVE), .nc (G-code for a
    /// 3-axis router, one program per sheet), .csv (bevels)
    #[arg(long, short = 'o', value_name = "FILE")]
    out: Vec<String>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Json,
    Obj,
    Svg,
    Dxf,
    Nc,
    Csv,
}

impl Format {
    fn of(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "json" => Format::Json,
            "obj" => Format::Obj,
            "svg" => Format::Svg,
            "dxf" => Format::Dxf,
            "nc" | "gcode" | "ngc" => Format::Nc,
            "csv" => Format::Csv,
            _ => return None,
        })
    }
}

struct Options {
    surface: String,
    pattern: String,
    outs: Vec<(PathBuf, Format)>,
    fab: FabricateOptions,
    slots_arg: Option<String>,
    tool: ToolpathOptions,
    /// `--units`, if given (else the surface file's, else metres).
    units: Option<Units>,
    density: Option<f64>,
    threads: Option<usize>,
    planes: PlaneMode,
}

fn usage(message: String) -> CliError {
    CliError::usage(Some("fabricate"), message)
}

/// A number; NaN and infinities pass, for the core to name what they break.
fn number(name: &str, v: &str) -> Result<f64, CliError> {
    v.trim()
        .parse::<f64>()
        .map_err(|_| usage(format!("--{name} {v}: expected a number")))
}

fn pair(name: &str, v: &str, example: &str) -> Result<[f64; 2], CliError> {
    let bad = || {
        usage(format!(
            "--{name} {v}: expected two numbers AxB, e.g. {example}"
        ))
    };
    let (x, y) = v.split_once(['x', 'X']).ok_or_else(bad)?;
    match (x.trim().parse::<f64>(), y.trim().parse::<f64>()) {
        (Ok(x), Ok(y)) => Ok([x, y]),
        _ => Err(bad()),
    }
}

fn parse(args: FabricateArgs) -> Result<Options, CliError> {
    let mut fab = FabricateOptions::default();
    let mut tool = ToolpathOptions::default();
    if let Some(v) = &args.side {
        fab.side = match v.as_str() {
            "inside" => PanelSide::Inside,
            "outside" => PanelSide::Outside,
            _ => return Err(usage(format!("--side {v}: expected inside or outside"))),
        };
    }
    if let Some(v) = &args.slot_size {
        let [l, d] = pair("slot-size", v, "0.16x0.08")?;
        fab.slot_length = Some(l);
        fab.slot_depth = Some(d);
    }
    if let Some(v) = &args.sheet {
        fab.sheet = pair("sheet", v, "2.5x1.25")?;
    }
    if let Some(v) = &args.gap {
        fab.gap = number("gap", v)?;
    }
    if let Some(v) = &args.tool_diameter {
        tool.tool_diameter = number("tool-diameter", v)?;
    }
    let units = match &args.units {
        None => None,
        Some(v) => Some(Units::from_name(v).map_err(|e| usage(format!("--units {v}: {e}")))?),
    };
    let density = match &args.density {
        None => None,
        Some(v) => {
            let x = number("density", v)?;
            if !(x > 0.0 && x.is_finite()) {
                return Err(usage(format!("--density {v}: must be > 0")));
            }
            Some(x)
        }
    };
    let planes = plane_mode(args.planes.as_deref(), "fabricate")?;
    let threads = thread_count(args.threads.as_deref(), "fabricate")?;
    let outs = output_formats(
        &args.out,
        Format::of,
        ".json, .obj, .svg, .dxf, .nc or .csv",
        "fabricate",
    )?;
    let surface = args
        .surface
        .ok_or_else(|| usage("--surface is required".into()))?;
    let pattern = args
        .pattern
        .ok_or_else(|| usage("--pattern is required".into()))?;
    let thickness = args
        .thickness
        .ok_or_else(|| usage("--thickness is required".into()))?;
    fab.thickness = number("thickness", &thickness)?;
    Ok(Options {
        surface,
        pattern,
        outs,
        fab,
        slots_arg: args.slots,
        tool,
        units,
        density,
        threads,
        planes,
    })
}

/// The option a core error is about, named first in the message.
fn fabrication_error(e: &FabricationError) -> CliError {
    let subject = match e {
        FabricationError::InvalidOption { field, .. } => match *field {
            "thickness" => "--thickness",
            "gap" => "--gap",
            "tool diameter" => "--tool-diameter",
            "slot length" | "slot depth" | "slot size" => "--slot-size",
            "slots per edge" => "--slots",
            "step down" => "--tool-diameter",
            _ => "--sheet",
        },
        FabricationError::ThicknessTooLarge { .. } => "--thickness",
        FabricationError::BadSlot { .. } | FabricationError::SlotFile { .. } => "--slots",
        FabricationError::PartTooLarge { .. } => "--sheet",
        _ => "the mesh",
    };
    CliError::input(subject, e.to_string())
}

/// Runs `tpi fabricate`.
pub(crate) fn run(args: FabricateArgs) -> Result<(), CliError> {
    let mut opts = parse(args)?;
    let pattern_path = Path::new(&opts.pattern);
    let mut inputs = vec![Path::new(&opts.surface)];
    if pattern_path.exists() {
        inputs.push(pattern_path);
    }
    if let Some(slots) = &opts.slots_arg {
        if Path::new(slots).exists() {
            inputs.push(Path::new(slots));
        }
    }
    for (path, _) in &opts.outs {
        check_not_an_input(path, &inputs, "fabricate")?;
        check_output_path(path)?;
    }
    let started = Instant::now();
    if let Some(s) = &opts.slots_arg {
        opts.fab.slots = match s.parse::<u32>() {
            Ok(0) => SlotPlan::None,
            Ok(n) => SlotPlan::Even(n),
            Err(_) => {
                let text = read_text(Path::new(s))?;
                SlotPlan::from_json(&text, s).map_err(|e| CliError::input(s, e.to_string()))?
            }
        };
    }
    let surface = load_surface(Path::new(&opts.surface))?;
    // The surface file's units, unless --units says otherwise; a contradiction is an error
    // (tpi never rescales), and a unitless surface keeps the old default, metres.
    let units = match (opts.units, tpi_core::Surface::units(&surface)) {
        (Some(given), Some(file)) if given != file => {
            return Err(usage(format!(
                "--units {given}: the surface file {} says \"units\": \"{file}\" (tpi does not rescale; drop --units or convert the model)",
                opts.surface
            )))
        }
        (Some(u), _) | (None, Some(u)) => u,
        (None, None) => Units::Metres,
    };
    opts.tool.units = units;
    let options = DiscretiseOptions {
        planes: opts.planes,
        ..DiscretiseOptions::default()
    };
    let pattern = load_pattern(&opts.pattern, &surface, &options, &tpi_core::NoProgress)?;
    let run_core = || -> Result<Result<Fabrication, FabricationError>, tpi_core::TpiError> {
        let mesh = discretise(&surface, &pattern.pattern.uv, &options)?;
        Ok(fabricate(&mesh, &opts.fab))
    };
    let pool = match opts.threads {
        Some(n) => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| {
                    CliError::input("--threads", format!("cannot start {n} threads: {e}"))
                })?,
        ),
        None => None,
    };
    let result = match &pool {
        Some(pool) => pool.install(run_core),
        None => run_core(),
    };
    let fab = result
        .map_err(|e| CliError::core(&opts.surface, &e))?
        .map_err(|e| fabrication_error(&e))?;
    // The outputs are independent: written in parallel (on the same threads as the core),
    // each into memory, then committed together; the first failing one, in the order given,
    // is reported.
    let render = |format: &Format| -> Result<Vec<u8>, CliError> {
        Ok(match format {
            Format::Json => fab.to_json().into_bytes(),
            Format::Obj => fab.to_obj().into_bytes(),
            Format::Svg => fab.sheets_svg().into_bytes(),
            Format::Dxf => fab
                .sheets_dxf(units)
                .map_err(|e| fabrication_error(&e))?
                .into_bytes(),
            Format::Csv => fab.bevels_csv().into_bytes(),
            Format::Nc => fab
                .gcode(&opts.tool)
                .map_err(|e| fabrication_error(&e))?
                .into_bytes(),
        })
    };
    let render_all = || -> Vec<Result<Vec<u8>, CliError>> {
        use rayon::prelude::*;
        opts.outs
            .par_iter()
            .map(|(_, format)| render(format))
            .collect()
    };
    let rendered = match &pool {
        Some(pool) => pool.install(render_all),
        None => render_all(),
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::with_capacity(opts.outs.len());
    for ((path, _), bytes) in opts.outs.iter().zip(rendered) {
        files.push((path.clone(), bytes?));
    }
    write_all(&files)?;
    eprint!("{}", summary(&fab, opts.density));
    eprintln!(
        "  units: {units}{}",
        match (fab.units, opts.units) {
            (Some(_), _) => " (from the surface file)",
            (None, Some(_)) => " (--units; the surface file has no \"units\")",
            (None, None) => " (default: the surface file has no \"units\")",
        }
    );
    if !files.is_empty() {
        let names: Vec<String> = files.iter().map(|(p, _)| p.display().to_string()).collect();
        eprintln!("  wrote {}", names.join(", "));
    }
    eprintln!("  done in {:.0} ms", started.elapsed().as_secs_f64() * 1e3);
    Ok(())
}

/// The summary on stderr.
fn summary(fab: &Fabrication, density: Option<f64>) -> String {
    let area: f64 = fab.panels.iter().map(|p| p.top_area().abs()).sum();
    let volume: f64 = fab.panels.iter().map(|p| p.solid.volume()).sum();
    let cleat_volume: f64 = fab.cleats.iter().map(|c| c.solid.volume()).sum::<f64>() + 0.0;
    let by_area = |p: &&tpi_core::Panel| p.top_area().abs();
    let smallest = fab
        .panels
        .iter()
        .min_by(|a, b| by_area(a).total_cmp(&by_area(b)));
    let largest = fab
        .panels
        .iter()
        .max_by(|a, b| by_area(a).total_cmp(&by_area(b)));
    let bevels = fab
        .panels
        .iter()
        .flat_map(|p| p.sides.iter().filter(|s| s.neighbour.is_some()))
        .map(|s| s.bevel_deg)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), b| {
            (lo.min(b), hi.max(b))
        });
    let mut s = format!(
        "tpi fabricate: {} panels of thickness {}, {} cleats, {} diagnostics\n",
        fab.panels.len(),
        fab.thickness,
        fab.cleats.len(),
        fab.diagnostics.len()
    );
    if !fab.diagnostics.is_empty() {
        let mut kinds: Vec<(&str, usize)> = Vec::new();
        for d in &fab.diagnostics {
            let kind = match d {
                FabricationDiagnostic::SplitVertex { .. } => "split vertex",
                FabricationDiagnostic::ParallelNeighbours { .. } => "coplanar neighbours",
                FabricationDiagnostic::BottomOutsideTop { .. } => "cut outline widened",
                FabricationDiagnostic::SlotSkipped { .. } => "slot left out",
                FabricationDiagnostic::InvalidFacet { .. } => "invalid facet",
                FabricationDiagnostic::EdgeCollapsed { .. } => "collapsed edge",
                _ => "other",
            };
            match kinds.iter_mut().find(|(k, _)| *k == kind) {
                Some((_, n)) => *n += 1,
                None => kinds.push((kind, 1)),
            }
        }
        let list: Vec<String> = kinds.iter().map(|(k, n)| format!("{n} {k}")).collect();
        s += &format!(
            "  diagnostics: {} (each named in the .json output)\n",
            list.join(", ")
        );
        for d in &fab.diagnostics {
            if let FabricationDiagnostic::EdgeCollapsed {
                panel,
                neighbour,
                vertices,
                at_thickness,
                joined,
            } = d
            {
                let across = neighbour.map_or("the boundary".to_string(), |j| format!("panel {j}"));
                let below = joined.map_or(String::new(), |[a, b]| {
                    format!("; panels {a} and {b} meet below it")
                });
                s += &format!(
                    "  collapsed edge: the bottom edge of panel {panel} along {across} (vertices {} and {}) vanishes at thickness {at_thickness}: panels clipped{below}\n",
                    vertices[0], vertices[1]
                );
            }
        }
    }
    let utils: Vec<f64> = fab.sheets.iter().map(|x| x.utilisation * 100.0).collect();
    let mean = utils.iter().sum::<f64>() / utils.len().max(1) as f64;
    let (lo, hi) = utils
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &u| {
            (a.min(u), b.max(u))
        });
    s += &format!(
        "  sheets: {} (utilisation mean {mean:.0} %, lowest {lo:.0} %, highest {hi:.0} %)\n",
        fab.sheets.len()
    );
    s += &format!(
        "  total area {area:.6}, panel volume {volume:.6}, cleat volume {cleat_volume:.6}\n"
    );
    if let Some(rho) = density {
        s += &format!(
            "  mass {:.3} (density {rho})\n",
            (volume + cleat_volume) * rho
        );
    }
    if let (Some(a), Some(b)) = (smallest, largest) {
        s += &format!(
            "  smallest part: panel {} ({:.6}), largest: panel {} ({:.6})\n",
            a.seed,
            a.top_area().abs(),
            b.seed,
            b.top_area().abs()
        );
    }
    if bevels.0.is_finite() {
        s += &format!("  bevels {:.3} to {:.3} degrees\n", bevels.0, bevels.1);
    }
    s
}
