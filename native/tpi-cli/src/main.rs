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

// The doc comments of the argument structs are clap's help text, where `[required]` and
// `[:seed=S]` are what the user reads, not rustdoc links.
#![allow(rustdoc::broken_intra_doc_links)]

mod bench;
mod cmd_discretise;
mod cmd_fabricate;
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

use std::ffi::OsString;

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{CommandFactory, Parser, Subcommand};

use error::CliError;

/// The help layout of every command: USAGE, the options, then the command's notes and
/// EXAMPLES.
const TEMPLATE: &str = "\
{about-with-newline}
USAGE:
    {usage}

OPTIONS:
{options}{after-help}";

const TOP_TEMPLATE: &str = "\
{about-with-newline}
USAGE:
    {usage}

COMMANDS:
{subcommands}

OPTIONS:
{options}{after-help}";

const TOP_AFTER_HELP: &str = "\
EXAMPLES:
    tpi discretise --surface samples/nurbs-dome.json --pattern samples/random-1000.json \\
        --out dome.json --out dome.obj --out dome.svg --out dome.png
    tpi discretise --surface samples/paraboloid.json --pattern hex:24x20 --out mesh.obj
    tpi pattern poisson:0.03:seed=7 --out poisson.json --preview poisson.svg
    tpi info samples/mixed-roof.json
    tpi completions bash > tpi.bash; tpi man > tpi.1

Exit codes: 0 success, 1 bad input or output, 2 usage, 3 invalid facets (--strict).
Formats: docs/formats.md; the command line: docs/cli.md.
";

/// Planar-facet discretisation of free-form surfaces by tangent plane intersection.
///
/// Every pattern point in the unit square becomes one exactly planar facet: its tangent
/// plane on the surface, cut by the tangent planes of its true neighbours.
#[derive(Parser, Debug)]
#[command(
    name = "tpi",
    version,
    help_template = TOP_TEMPLATE,
    after_help = TOP_AFTER_HELP,
    arg_required_else_help = true,
    max_term_width = 100
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Surface + pattern -> mesh of planar facets (JSON, OBJ, SVG, PNG) + quality report
    #[command(visible_alias = "discretize", help_template = TEMPLATE, after_help = cmd_discretise::AFTER_HELP)]
    Discretise(cmd_discretise::DiscretiseArgs),
    /// Surface + pattern + thickness -> panel solids, mitred joints, cleat slots, nested
    /// sheets, G-code (docs/fabrication.md)
    #[command(help_template = TEMPLATE, after_help = cmd_fabricate::AFTER_HELP)]
    Fabricate(cmd_fabricate::FabricateArgs),
    /// Generate pattern points (grid, hex, jitter, random, Poisson-disk) + Voronoi preview
    #[command(help_template = TEMPLATE, after_help = cmd_pattern::AFTER_HELP)]
    Pattern(cmd_pattern::PatternArgs),
    /// A surface's parameters, domain, curvature regions and self-intersection
    #[command(help_template = TEMPLATE, after_help = cmd_info::AFTER_HELP)]
    Info(cmd_info::InfoArgs),
    /// Time the discretisation stage by stage (docs/performance.md)
    #[command(help_template = TEMPLATE, after_help = bench::AFTER_HELP)]
    Bench(bench::BenchArgs),
    /// Print a shell completion script (bash, zsh, fish, powershell, elvish) to stdout
    #[command(help_template = TEMPLATE, after_help = "EXAMPLES:\n    tpi completions bash > ~/.local/share/bash-completion/completions/tpi\n    tpi completions zsh > ~/.zfunc/_tpi\n    tpi completions fish > ~/.config/fish/completions/tpi.fish\n    tpi completions powershell > tpi.ps1\n")]
    Completions {
        /// The shell
        #[arg(value_name = "SHELL")]
        shell: clap_complete::Shell,
    },
    /// Print the man page (roff) to stdout
    #[command(help_template = TEMPLATE, after_help = "EXAMPLES:\n    tpi man > tpi.1 && man ./tpi.1\n")]
    Man,
}

/// The commands, for naming the one an argument error belongs to.
const COMMANDS: [&str; 8] = [
    "discretise",
    "discretize",
    "fabricate",
    "pattern",
    "info",
    "bench",
    "completions",
    "man",
];

/// A clap error in the CLI's own one-line form (`tpi: error: ... (see `tpi X --help`)`),
/// exit code 2; help and version requests print as clap renders them, exit code 0.
fn from_clap(e: clap::Error, argv: &[OsString]) -> Result<(), CliError> {
    let command = argv.iter().skip(1).find_map(|a| {
        let a = a.to_str()?;
        COMMANDS.iter().find(|c| **c == a).map(|c| match *c {
            "discretize" => "discretise",
            other => other,
        })
    });
    let arg_name = |kind: ContextKind| match e.get(kind) {
        Some(ContextValue::String(s)) => s.split_whitespace().next().unwrap_or("").to_string(),
        _ => String::new(),
    };
    let value = |kind: ContextKind| match e.get(kind) {
        Some(ContextValue::String(s)) => s.clone(),
        _ => String::new(),
    };
    let message = match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            return Ok(());
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            return Err(CliError::usage(None, "a command is required"));
        }
        ErrorKind::InvalidSubcommand => format!(
            "unknown command `{}`; the commands are discretise, fabricate, pattern, info, bench, completions and man",
            value(ContextKind::InvalidSubcommand)
        ),
        ErrorKind::UnknownArgument => {
            let arg = value(ContextKind::InvalidArg);
            if arg.starts_with('-') {
                format!("unknown option `{arg}`")
            } else {
                format!("unexpected argument `{arg}`")
            }
        }
        ErrorKind::InvalidValue if value(ContextKind::InvalidValue).is_empty() => {
            format!("{} needs a value", arg_name(ContextKind::InvalidArg))
        }
        ErrorKind::ArgumentConflict
            if arg_name(ContextKind::InvalidArg) == arg_name(ContextKind::PriorArg) =>
        {
            format!(
                "{} is given more than once; give it once",
                arg_name(ContextKind::InvalidArg)
            )
        }
        _ => {
            let text = e.to_string();
            let first = text.lines().next().unwrap_or("").trim();
            first.strip_prefix("error: ").unwrap_or(first).to_string()
        }
    };
    Err(CliError::usage(command, message))
}

/// The man page: clap_mangen's sections for `tpi` itself, then one section per command
/// (`TPI DISCRETISE`, ...) with its synopsis, description, options, notes and examples, so
/// that the one page documents every option (clap_mangen alone lists the commands as
/// tpi-discretise(1) and so on, pages that are not installed anywhere).
fn man_page() -> std::io::Result<Vec<u8>> {
    let mut top = Cli::command();
    top.build();
    let man = clap_mangen::Man::new(top.clone());
    let mut page = Vec::new();
    man.render_title(&mut page)?;
    man.render_name_section(&mut page)?;
    man.render_synopsis_section(&mut page)?;
    man.render_description_section(&mut page)?;
    man.render_options_section(&mut page)?;
    page.extend_from_slice(b".SH NOTES\n");
    let mut notes = Vec::new();
    man.render_extra_section(&mut notes)?;
    page.extend(strip_heading(&notes));
    for sub in top.get_subcommands().filter(|c| c.get_name() != "help") {
        let name = format!("tpi {}", sub.get_name());
        page.extend_from_slice(format!(".SH \"{}\"\n", name.to_uppercase()).as_bytes());
        let man = clap_mangen::Man::new(sub.clone().bin_name(&name));
        let mut section = Vec::new();
        man.render_description_section(&mut section)?;
        page.extend(strip_heading(&section));
        for (render, title) in [
            (
                clap_mangen::Man::render_synopsis_section as Render,
                "Synopsis",
            ),
            (clap_mangen::Man::render_options_section, "Options"),
            (clap_mangen::Man::render_extra_section, "Notes and examples"),
        ] {
            let mut section = Vec::new();
            render(&man, &mut section)?;
            if section.is_empty() {
                continue;
            }
            page.extend_from_slice(format!(".SS \"{title}\"\n").as_bytes());
            page.extend(strip_heading(&section));
        }
    }
    man.render_version_section(&mut page)?;
    Ok(page)
}

/// One of clap_mangen's section renderers.
type Render = fn(&clap_mangen::Man, &mut dyn std::io::Write) -> std::io::Result<()>;

/// A rendered section without what comes before its body: the preamble roff puts at the
/// start of every rendering (`.ie \n(.g .ds Aq ...`) and the `.SH` heading line.
fn strip_heading(section: &[u8]) -> &[u8] {
    let heading = if section.starts_with(b".SH ") {
        Some(0)
    } else {
        section
            .windows(5)
            .position(|w| w == b"\n.SH ")
            .map(|at| at + 1)
    };
    match heading {
        Some(at) => section[at..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(&[][..], |end| &section[at + end + 1..]),
        None => section,
    }
}

fn main() {
    // Before anything is written: SIGINT/SIGTERM remove the temporary output files.
    output::clean_up_on_signals();
    let argv: Vec<OsString> = std::env::args_os().collect();
    let result = match Cli::try_parse_from(&argv) {
        Err(e) => from_clap(e, &argv),
        Ok(cli) => match cli.command {
            Command::Discretise(args) => cmd_discretise::run(args),
            Command::Fabricate(args) => cmd_fabricate::run(args),
            Command::Pattern(args) => cmd_pattern::run(args),
            Command::Info(args) => cmd_info::run(args),
            Command::Bench(args) => bench::run(args),
            Command::Completions { shell } => {
                clap_complete::generate(shell, &mut Cli::command(), "tpi", &mut std::io::stdout());
                Ok(())
            }
            Command::Man => {
                use std::io::Write;
                man_page()
                    .and_then(|page| std::io::stdout().write_all(&page))
                    .map_err(|e| CliError::input("stdout", e.to_string()))
            }
        },
    };
    if let Err(e) = result {
        eprintln!("{e}");
        std::process::exit(e.exit_code());
    }
}
