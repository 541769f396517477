//! The pipeline: an analytic or NURBS surface from fuzzed parameters and a fuzzed pattern.
//! Never a panic; every result has finite vertices, and a result whose quality report finds
//! no invalid facet and no unexpected topology passes the core's invariant check
//! (`Discretisation::sanity_check`).
#![no_main]

use arbitrary::Arbitrary;
use glam::DVec3;
use libfuzzer_sys::fuzz_target;
use tpi_core::{
    discretise, AnalyticKind, AnalyticSurface, DiscretiseOptions, NurbsSurface, SurfaceModel,
};

#[derive(Arbitrary, Debug)]
enum Shape {
    Elliptic {
        a: i8,
        b: i8,
    },
    Hyperbolic {
        a: i8,
        b: i8,
    },
    Sphere {
        radius: u8,
    },
    Egg {
        amplitude: i8,
    },
    /// A 4 x 4 bicubic Bezier patch: heights on a 3 x 3 square grid, optional weights.
    Bezier {
        heights: [i8; 16],
        weights: Option<[u8; 16]>,
    },
}

#[derive(Arbitrary, Debug)]
struct Input {
    shape: Shape,
    /// Pattern points as 16-bit fractions of the unit square.
    points: Vec<(u16, u16)>,
}

fn surface(shape: &Shape) -> Option<SurfaceModel> {
    let x = [-1.0, 1.0];
    let analytic = |kind| {
        AnalyticSurface::new(kind, x, x)
            .ok()
            .map(SurfaceModel::from)
    };
    match *shape {
        Shape::Elliptic { a, b } => analytic(AnalyticKind::EllipticParaboloid {
            a: f64::from(a) / 16.0,
            b: f64::from(b) / 16.0,
        }),
        Shape::Hyperbolic { a, b } => analytic(AnalyticKind::HyperbolicParaboloid {
            a: f64::from(a) / 16.0,
            b: f64::from(b) / 16.0,
        }),
        Shape::Sphere { radius } => analytic(AnalyticKind::SphereCap {
            radius: 1.5 + f64::from(radius) / 16.0,
        }),
        Shape::Egg { amplitude } => analytic(AnalyticKind::EggCrate {
            amplitude: f64::from(amplitude) / 16.0,
        }),
        Shape::Bezier { heights, weights } => {
            let points: Vec<DVec3> = (0..16)
                .map(|k| DVec3::new((k / 4) as f64, (k % 4) as f64, f64::from(heights[k]) / 32.0))
                .collect();
            let weights: Option<Vec<f64>> =
                weights.map(|w| w.iter().map(|&x| 0.25 + f64::from(x) / 64.0).collect());
            let knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
            NurbsSurface::new([3, 3], [4, 4], &knots, &knots, &points, weights.as_deref())
                .ok()
                .map(SurfaceModel::from)
        }
    }
}

fuzz_target!(|input: Input| {
    if input.points.len() > 400 {
        return;
    }
    let Some(model) = surface(&input.shape) else {
        return;
    };
    let uv: Vec<[f64; 2]> = input
        .points
        .iter()
        .map(|&(s, t)| [f64::from(s) / 65535.0, f64::from(t) / 65535.0])
        .collect();
    let Ok(result) = discretise(&model, &uv, &DiscretiseOptions::default()) else {
        return;
    };
    assert!(result.vertices.iter().all(|v| v.is_finite()), "{input:?}");
    // A mesh whose topology is not the one expected is named by a diagnostic (its facets may
    // each be valid); every other result the report finds valid must pass the invariants.
    let topology_named = result
        .diagnostics
        .iter()
        .any(|d| matches!(d, tpi_core::Diagnostic::UnexpectedTopology { .. }));
    if let Some(q) = &result.quality {
        if q.invalid_facets == 0 && !topology_named {
            if let Err(e) = result.sanity_check() {
                panic!("no invalid facet reported, yet {e}: {input:?}");
            }
        }
    }
});
