//! `tpi`: the command line front door to tpi-core (see README.md).

fn main() {
    eprintln!("tpi {}: subcommands are not implemented yet", env!("CARGO_PKG_VERSION"));
    std::process::exit(2);
}
