//! Criterion benchmarks of the discretisation's stages on the benchmark surfaces
//! (`tpi_core::benchmark`), swept over the pattern size.
//!
//! `cargo bench -p tpi-core` runs 1k, 10k and 100k points; `TPI_BENCH_LARGE=1` adds 1M.
//! `tpi bench` prints the same stages from one process with medians, facets/s and peak
//! memory (docs/performance.md).
// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{
    black_box, criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use tpi_core::benchmark::{delaunay_triangle_count, nurbs_dome, paraboloid, random_pattern};
use tpi_core::{discretise, DiscretiseOptions, LocalGeometry, Surface};

fn sizes() -> Vec<usize> {
    let mut sizes = vec![1_000, 10_000, 100_000];
    if std::env::var_os("TPI_BENCH_LARGE").is_some() {
        sizes.push(1_000_000);
    }
    sizes
}

fn surfaces() -> Vec<(&'static str, Box<dyn Surface>)> {
    vec![
        ("paraboloid", Box::new(paraboloid())),
        ("nurbs", Box::new(nurbs_dome())),
    ]
}

/// Evaluation to second order and curvature at every pattern point.
fn samples(c: &mut Criterion) {
    let mut group = c.benchmark_group("samples");
    for (name, surface) in surfaces() {
        for n in sizes() {
            let uv: Vec<[f64; 2]> = random_pattern(n)
                .iter()
                .map(|&st| surface.domain().from_normalised(st))
                .collect();
            group.throughput(Throughput::Elements(n as u64));
            group.bench_with_input(BenchmarkId::new(name, n), &uv, |b, uv| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for &[u, v] in uv {
                        let g = LocalGeometry::from_derivatives(&surface.evaluate(u, v));
                        acc += g.k1 + g.k2;
                    }
                    black_box(acc)
                })
            });
        }
    }
    group.finish();
}

/// One evaluation to second order (no curvature), the unit of every projection.
fn evaluate(c: &mut Criterion) {
    let mut group = c.benchmark_group("evaluate");
    for (name, surface) in surfaces() {
        let uv: Vec<[f64; 2]> = random_pattern(1000)
            .iter()
            .map(|&st| surface.domain().from_normalised(st))
            .collect();
        group.throughput(Throughput::Elements(uv.len() as u64));
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &[u, v] in &uv {
                    let d = surface.evaluate(u, v);
                    acc += d.point.x + d.suu.z;
                }
                black_box(acc)
            })
        });
    }
    group.finish();
}

/// The global Delaunay triangulation of the pattern (the candidate structure).
fn delaunay(c: &mut Criterion) {
    let mut group = c.benchmark_group("delaunay");
    for n in sizes() {
        let pattern = random_pattern(n);
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::from_parameter(n), &pattern, |b, p| {
            b.iter(|| black_box(delaunay_triangle_count(p)))
        });
    }
    group.finish();
}

/// The whole pipeline, with the quality report on (the normal path) and off.
fn full(c: &mut Criterion) {
    for (label, report) in [("discretise", true), ("discretise_no_report", false)] {
        let mut group = c.benchmark_group(label);
        group.sampling_mode(SamplingMode::Flat);
        let options = DiscretiseOptions {
            quality_report: report,
            ..DiscretiseOptions::default()
        };
        for (name, surface) in surfaces() {
            for n in sizes() {
                if n >= 100_000 {
                    group.sample_size(10);
                }
                let pattern = random_pattern(n);
                group.throughput(Throughput::Elements(n as u64));
                group.bench_with_input(BenchmarkId::new(name, n), &pattern, |b, p| {
                    b.iter(|| {
                        black_box(
                            discretise(surface.as_ref(), p, &options).map(|d| d.facet_count()),
                        )
                    })
                });
            }
        }
        group.finish();
    }
}

criterion_group!(benches, evaluate, samples, delaunay, full);
criterion_main!(benches);
