//! `tpi`: the command line front door to tpi-core.
//!
//! - `tpi discretise`: surface + pattern -> planar-facet mesh (JSON, OBJ, SVG, PNG) and a
//!   quality summary
//! - `tpi pattern`: pattern files and their Voronoi preview
//! - `tpi info`: a surface's parameters, domain and curvature regions
//! - `tpi bench`: stage timings, facets per second and peak memory on benchmark surfaces
//!
//! Exit codes: 0 success, 1 bad input or output (one line on stderr, `tpi: error: FILE:
//! PROBLEM`), 2 usage, 3 invalid facets under `tpi discretise --strict`. See docs/cli.md.

mod args;
mod bench;
mod cmd_discretise;
mod cmd_info;
mod cmd_pattern;
mod error;
mod font;
mod input;
mod obj;
mod output;
mod palette;
mod progress;
mod render;
mod selfx;
mod summary;
mod svg;
mod voronoi;

use error::CliError;

const HELP: &str = "\
tpi: planar-facet discretisation of free-form surfaces by tangent plane intersection

Every pattern point in the unit square becomes one exactly planar facet: its tangent plane
on the surface, cut by the tangent planes of its true neighbours.

USAGE:
    tpi <COMMAND> [ARGS]

COMMANDS:
    discretise   surface + pattern -> mesh of planar facets (JSON, OBJ, SVG, PNG) + report
    pattern      generate pattern points (grid, hex, jitter, random, Poisson-disk) + preview
    info         a surface's parameters, domain and curvature regions
    bench        time the discretisation stage by stage (docs/performance.md)
    help         this help, or `tpi help COMMAND` for a command's help

OPTIONS:
    -h, --help       this help
    -V, --version    the version

EXAMPLES:
    tpi discretise --surface samples/nurbs-dome.json --pattern samples/random-1000.json \\
        --out dome.json --out dome.obj --out dome.svg --out dome.png
    tpi discretise --surface samples/paraboloid.json --pattern hex:24x20 --out mesh.obj
    tpi pattern poisson:0.03:seed=7 --out poisson.json --preview poisson.svg
    tpi info samples/mixed-roof.json

Exit codes: 0 success, 1 bad input or output, 2 usage, 3 invalid facets (--strict).
Formats: docs/formats.md.
";

fn main() {
    // Before anything is written: SIGINT/SIGTERM remove the temporary output files.
    output::clean_up_on_signals();
    let mut argv = std::env::args().skip(1);
    let command = argv.next();
    let rest: Vec<String> = argv.collect();
    let result = match command.as_deref() {
        None => {
            eprint!("{HELP}");
            Err(CliError::usage(None, "a command is required"))
        }
        Some("-h" | "--help") => {
            print!("{HELP}");
            Ok(())
        }
        Some("help") => match rest.first().map(String::as_str) {
            None => {
                print!("{HELP}");
                Ok(())
            }
            Some("discretise" | "discretize") => {
                print!("{}", cmd_discretise::HELP);
                Ok(())
            }
            Some("pattern") => {
                print!("{}", cmd_pattern::HELP);
                Ok(())
            }
            Some("info") => {
                print!("{}", cmd_info::HELP);
                Ok(())
            }
            Some("bench") => {
                print!("{}", bench::HELP);
                Ok(())
            }
            Some(other) => Err(CliError::usage(None, format!("unknown command `{other}`"))),
        },
        Some("-V" | "--version") => {
            println!("tpi {}", env!("CARGO_PKG_VERSION"));
            Ok(())
        }
        Some("discretise" | "discretize") => cmd_discretise::run(rest),
        Some("pattern") => cmd_pattern::run(rest),
        Some("info") => cmd_info::run(rest),
        Some("bench") => bench::run(rest),
        Some(other) => Err(CliError::usage(
            None,
            format!(
                "unknown command `{other}`; the commands are discretise, pattern, info and bench"
            ),
        )),
    };
    if let Err(e) = result {
        eprintln!("{e}");
        std::process::exit(e.exit_code());
    }
}
