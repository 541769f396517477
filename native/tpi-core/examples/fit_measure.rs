//! Measures tolerance-driven patterns against the smallest uniform hexagonal pattern meeting
//! the same tolerance (issue 15, item 1):
//!
//! `cargo run --release -p tpi-core --example fit_measure -- SAMPLE FRACTION...`
//!
//! For each fraction f of the surface's bounding diagonal, D = f * diagonal: the fit's count,
//! its time and where its largest deviation sits (interior, boundary or corner vertex), and
//! the smallest `hex:spacing=1/N` and `hex:NxN` meeting D (doubling, then bisection on N),
//! with the same facts, and where the domain is not square on the surface `hex:NxM` with
//! M = round(N 2 / sqrt(3) L_t / L_s), L_s and L_t the lengths of the middle parameter lines
//! (cells regular on the surface). Deviations are the crate's projection
//! ([`tpi_core::vertex_deviations`]).
//! Environment: FIT_ONLY=1 skips the hex search, FIT_NO_CHECK=1 also the check of the fit
//! (only the fit runs: for timing the process), FIT_TIMINGS=1 prints the check's stage
//! timings, FIT_SCAN=1 looks below the bisection's hex, FIT_DEBUG=1 prints the mean
//! deviation of the interior, boundary and corner vertices of every mesh checked (how much
//! slack a pattern leaves below D, and where), FIT_WORST=1 its eight worst vertices.

use std::time::Instant;

use tpi_core::{
    discretise, fit_pattern, vertex_deviations, DiscretiseOptions, Generator, Surface, SurfaceSpec,
    VertexKind,
};

/// The largest deviation of the mesh of `uv` and the kind of vertex where it sits.
fn worst(surface: &dyn Surface, uv: &[[f64; 2]]) -> (f64, &'static str, usize) {
    let d = discretise(surface, uv, &DiscretiseOptions::default()).expect("discretise");
    let feet_start = Instant::now();
    let dev = vertex_deviations(surface, &d);
    if std::env::var("FIT_TIMINGS").is_ok() {
        println!(
            "    {} points: {:?}; vertex deviations {:.1} ms",
            uv.len(),
            d.timings,
            feet_start.elapsed().as_secs_f64() * 1e3
        );
    }
    if std::env::var("FIT_DEBUG").is_ok() {
        let mut by_kind = [(0.0, 0usize); 3];
        for (v, &x) in dev.iter().enumerate() {
            let k = match d.vertex_kinds[v] {
                VertexKind::Interior => 0,
                VertexKind::Boundary => 1,
                VertexKind::Corner => 2,
            };
            by_kind[k].0 += x;
            by_kind[k].1 += 1;
        }
        let mean = |k: usize| by_kind[k].0 / by_kind[k].1.max(1) as f64;
        println!(
            "    mean deviation: interior {:.3e} ({}), boundary {:.3e} ({}), corner {:.3e}",
            mean(0),
            by_kind[0].1,
            mean(1),
            by_kind[1].1,
            mean(2)
        );
    }
    if std::env::var("FIT_WORST").is_ok() {
        let mut order: Vec<usize> = (0..dev.len()).collect();
        order.sort_by(|&a, &b| dev[b].total_cmp(&dev[a]));
        for &v in order.iter().take(8) {
            println!(
                "    {:.4e} at {:?} {:?}",
                dev[v], d.vertices[v], d.vertex_kinds[v]
            );
        }
    }
    let (mut best, mut at) = (0.0, 0usize);
    for (v, &x) in dev.iter().enumerate() {
        if x > best {
            best = x;
            at = v;
        }
    }
    let kind = match d.vertex_kinds[at] {
        VertexKind::Interior => "interior",
        VertexKind::Boundary => "boundary",
        VertexKind::Corner => "corner",
    };
    let invalid = d.quality.map_or(0, |q| q.invalid_facets);
    (best, kind, invalid)
}

/// The smallest N of `spec(N)` meeting D by doubling from 4 and bisection.
fn bisect(
    surface: &dyn Surface,
    tolerance: f64,
    spec: impl Fn(usize) -> String,
) -> Option<(String, usize, f64, &'static str, usize)> {
    let run = |n: usize| {
        let uv = Generator::parse(&spec(n)).ok()?.generate().uv;
        let (dev, kind, _) = worst(surface, &uv);
        Some((spec(n), uv.len(), dev, kind, n))
    };
    let (mut lo, mut hi) = (2usize, 4usize);
    let mut found = loop {
        let h = run(hi)?;
        if h.2 <= tolerance {
            break h;
        }
        lo = hi;
        hi *= 2;
        if hi > 1024 {
            return None;
        }
    };
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let h = run(mid)?;
        if h.2 <= tolerance {
            hi = mid;
            found = h;
        } else {
            lo = mid;
        }
    }
    // Bisection assumes that a finer hex always does as well; look below for a smaller one.
    if std::env::var("FIT_SCAN").is_ok() {
        for n in (found.4 * 3 / 4..found.4).rev() {
            let h = run(n)?;
            if h.2 <= tolerance {
                println!("    smaller hex meets D: {} {} pts", h.0, h.1);
            }
        }
    }
    Some(found)
}

/// A baseline's generator spec for N.
type SpecOf = Box<dyn Fn(usize) -> String>;

/// The length on the surface of the middle parameter line along s (`along` 0) or t (1).
fn iso_length(surface: &dyn Surface, along: usize) -> f64 {
    let domain = surface.domain();
    let at = |x: f64| {
        let st = if along == 0 { [x, 0.5] } else { [0.5, x] };
        let [u, v] = domain.from_normalised(st);
        surface.point_at(u, v)
    };
    (0..256)
        .map(|k| at(k as f64 / 256.0).distance(at((k + 1) as f64 / 256.0)))
        .sum()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = &args[0];
    let path = format!("{}/../../samples/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("sample");
    let surface = SurfaceSpec::from_json(&text, name)
        .expect("spec")
        .build()
        .expect("surface");
    let [lo, hi] = tpi_core::sampled_bounding_box(&surface, 64);
    let diagonal = lo.distance(hi);
    for fraction in &args[1..] {
        let f: f64 = fraction.parse().expect("fraction");
        // FIT_ABSOLUTE=1: the arguments are tolerances in model units.
        let tolerance = if std::env::var("FIT_ABSOLUTE").is_ok() {
            f
        } else {
            f * diagonal
        };
        let start = Instant::now();
        let fitted =
            fit_pattern(&surface, tolerance, 0, &DiscretiseOptions::default()).expect("fit");
        let seconds = start.elapsed().as_secs_f64();
        if std::env::var("FIT_NO_CHECK").is_ok() {
            // Only the fit (for timing the whole process).
            println!(
                "{name} D={tolerance:.4e} ({f}): fit {} pts met={} runs={} {seconds:.2}s",
                fitted.uv.len(),
                fitted.met,
                fitted.discretisations
            );
            continue;
        }
        let (dev, kind, invalid) = worst(&surface, &fitted.uv);
        println!(
            "{name} D={tolerance:.4e} ({f}): fit {} pts met={} dev/D={:.3} at {kind} \
             invalid={invalid} runs={} {seconds:.2}s",
            fitted.uv.len(),
            fitted.met,
            dev / tolerance,
            fitted.discretisations
        );
        if std::env::var("FIT_ONLY").is_ok() {
            continue;
        }
        // hex:NxM with M chosen for cells regular on the surface: the lengths of the middle
        // parameter lines give the aspect of the domain on the surface.
        let m_per_n = 2.0 / 3f64.sqrt() * iso_length(&surface, 1) / iso_length(&surface, 0);
        let mut rows: Vec<(&str, SpecOf)> = vec![
            (
                "hex:spacing",
                Box::new(|n: usize| format!("hex:spacing={}", 1.0 / n as f64)) as SpecOf,
            ),
            ("hex:NxN", Box::new(|n: usize| format!("hex:{n}x{n}"))),
        ];
        if (m_per_n - 2.0 / 3f64.sqrt()).abs() > 0.02 {
            rows.push((
                "hex:NxM",
                Box::new(move |n: usize| {
                    format!("hex:{n}x{}", ((n as f64 * m_per_n).round() as usize).max(1))
                }),
            ));
        }
        for (label, spec) in rows {
            match bisect(&surface, tolerance, spec) {
                Some((g, count, dev, kind, _)) => println!(
                    "  {label}: {g} {count} pts dev/D={:.3} at {kind}; ratio {:.3}",
                    dev / tolerance,
                    fitted.uv.len() as f64 / count as f64
                ),
                None => println!("  {label}: none up to 1024"),
            }
        }
    }
}
