//! Inputs found by the cargo-fuzz targets in fuzz/ (issue 14), kept as plain tests. Findings
//! that are fixed run as ordinary tests; an open one is ignored with its reason, so that it
//! stays visible (`cargo test -- --ignored` runs it).

use tpi_core::{discretise, AnalyticKind, AnalyticSurface, DiscretiseOptions, SurfaceModel};

/// Found by `fuzz/fuzz_targets/discretise.rs`: three pattern points on the elliptic
/// paraboloid z = -4.8125 (x^2 + y^2) over [-1, 1]^2. The quality report counts 0 invalid
/// facets, yet `sanity_check` finds facet 0 (vertices 0 1 2 3 4) not simple: two of its
/// edges cross. One of the two is wrong; the geometry is not this to change.
#[test]
#[ignore = "open finding: the quality report and sanity_check disagree on facet 0"]
fn fuzz_three_points_on_a_steep_paraboloid_report_and_sanity_agree() {
    let surface: SurfaceModel = AnalyticSurface::new(
        AnalyticKind::EllipticParaboloid {
            a: -77.0 / 16.0,
            b: -77.0 / 16.0,
        },
        [-1.0, 1.0],
        [-1.0, 1.0],
    )
    .unwrap()
    .into();
    let uv = [
        [1.0, 1.0],
        [57343.0 / 65535.0, 63711.0 / 65535.0],
        [0.0, 0.0],
    ];
    let result = discretise(&surface, &uv, &DiscretiseOptions::default()).unwrap();
    let invalid = result.quality.as_ref().unwrap().invalid_facets;
    let sane = result.sanity_check();
    assert_eq!(
        invalid == 0,
        sane.is_ok(),
        "report: {invalid} invalid facets; sanity_check: {sane:?}"
    );
}
