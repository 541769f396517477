//! Discretises a surface file with a generated pattern and runs the structural check and the
//! quality report's validity counts: the tool behind the scale figures of
//! docs/performance.md ("Exact combinatorics").
//!
//! ```sh
//! cargo run --release -p tpi-core --example scale_check -- samples/nurbs-dome.json random:3000000
//! ```
//!
//! Prints one line per run and exits 1 when the check fails or a facet is flagged invalid.

use std::process::ExitCode;

use tpi_core::{discretise, DiscretiseOptions, Generator, SurfaceSpec};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [surface, pattern] = args.as_slice() else {
        eprintln!("usage: scale_check SURFACE.json SPEC (e.g. random:1000000)");
        return ExitCode::from(2);
    };
    let run = || -> Result<bool, String> {
        let text = std::fs::read_to_string(surface).map_err(|e| format!("{surface}: {e}"))?;
        let model = SurfaceSpec::from_json(&text, surface)
            .and_then(|spec| spec.build())
            .map_err(|e| e.to_string())?;
        let points = Generator::parse(pattern)
            .map_err(|e| e.to_string())?
            .generate()
            .uv;
        let d = discretise(&model, &points, &DiscretiseOptions::default())
            .map_err(|e| e.to_string())?;
        let sanity = d.sanity_check();
        let q = d.quality.as_ref();
        let flagged = q.map_or(0, |q| q.flagged_facets);
        let invalid = q.map_or(0, |q| q.invalid_facets);
        println!(
            "{surface} {pattern}: {} facets, sanity_check {}, flagged {flagged}, invalid {invalid}",
            d.facet_count(),
            match &sanity {
                Ok(()) => "ok".to_string(),
                Err(e) => format!("FAILED ({e})"),
            }
        );
        Ok(sanity.is_ok() && invalid == 0)
    };
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("scale_check: {e}");
            ExitCode::from(2)
        }
    }
}
