//! The one-screen summary of a discretisation printed on stderr.

use std::fmt::Write;

use tpi_core::tolerance::FAR_VERTEX_SPACINGS;
use tpi_core::Discretisation;

/// At most this many diagnostics are listed by name.
const LISTED_DIAGNOSTICS: usize = 3;

/// The warning printed on stderr when the mesh has invalid facets.
pub(crate) fn invalid_warning(q: &tpi_core::QualityReport) -> String {
    format!(
        "warning: {} invalid facets (open {}, non-simple {}, overlapping pairs {}); they are flagged in the outputs",
        q.invalid_facets, q.open_facets, q.non_simple_facets, q.overlapping_pairs
    )
}

/// The warning printed on stderr when the report flags facets with a vertex farther from the
/// surface than [`FAR_VERTEX_SPACINGS`] local spacings (`tpi_core::FLAG_FAR_VERTEX`), or None.
pub(crate) fn far_vertex_warning(q: &tpi_core::QualityReport) -> Option<String> {
    (q.far_vertex_facets > 0).then(|| {
        format!(
            "warning: {} facets have a vertex more than {} local pattern spacings off the surface (largest deviation {}; up to {:.0} local spacings): where neighbouring tangent planes are nearly parallel (at a parabolic line, K = 0, or at seeds close together) they meet far from it; the facets are flagged in the outputs, and --planes adjusted holds facets near their seeds",
            q.far_vertex_facets,
            FAR_VERTEX_SPACINGS,
            sig(q.max_deviation),
            q.max_deviation_spacings
        )
    })
}

/// The warning printed on stderr when the mesh's Euler characteristic and boundary loops
/// are not those expected; `invalid` facets flagged (an open one counts its one edge twice)
/// may account for it, and the line then says so.
pub(crate) fn topology_warning(
    (euler, loops): (i64, u32),
    (expected_euler, expected_loops): (i64, u32),
    invalid: usize,
) -> String {
    let place = match invalid {
        0 => "where no single facet shows it".to_string(),
        n => format!("at or next to the {n} invalid facets flagged"),
    };
    format!("warning: the mesh has Euler characteristic {euler} and {loops} boundary loop(s), where {expected_euler} and {expected_loops} were expected: its facets leave a gap or overlap {place}")
}

/// The summary text (several lines, each ending in a newline).
pub(crate) fn summary(
    result: &Discretisation,
    surface: &str,
    pattern: &str,
    threads: usize,
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "tpi: {surface} with {pattern}: {} facets, {} vertices",
        result.facet_count(),
        result.vertices.len()
    );
    let _ = writeln!(s, "  units: {}", crate::obj::units_text(result.units));
    if !result.pattern_indices.is_empty() {
        let _ = writeln!(
            s,
            "  trim: {} pattern points outside the trim left out (facets keep their pattern index as seed)",
            result.outside_trim
        );
    }
    match &result.quality {
        None => {
            let _ = writeln!(s, "  quality report: off (--no-report)");
        }
        Some(q) => {
            let sides: Vec<String> = q
                .side_histogram
                .iter()
                .map(|(k, n)| format!("{k}:{n}"))
                .collect();
            let _ = writeln!(s, "  edges {}   sides {}", q.edge_count, sides.join("  "));
            let _ = writeln!(
                s,
                "  interior vertices {}, trivalent {:.1}%",
                q.interior_vertex_count,
                100.0 * q.trivalent_fraction
            );
            let _ = writeln!(
                s,
                "  planarity {:.1e} (max, relative to diagonal {})   deviation max {}  mean {}  (up to {:.2} local spacings; {} facets beyond {})",
                q.max_planarity_error,
                sig(q.bounding_box_diagonal),
                sig(q.max_deviation),
                sig(q.mean_deviation),
                q.max_deviation_spacings,
                q.far_vertex_facets,
                FAR_VERTEX_SPACINGS
            );
            let _ = writeln!(
                s,
                "  facet area {} .. {}{}   edge length {} .. {}",
                sig(q.min_facet_area),
                sig(q.max_facet_area),
                if q.min_facet_area < 0.0 {
                    " (signed: negative for a facet wound the wrong way round, non-simple)"
                } else {
                    ""
                },
                sig(q.min_edge_length),
                sig(q.max_edge_length)
            );
            let flags = if q.flagged_facets == 0 {
                "none".to_string()
            } else {
                format!("{} facets", q.flagged_facets)
            };
            let _ = writeln!(
                s,
                "  validity: {} invalid facets (open {}, non-simple {}, overlapping pairs {}); non-convex {}; flagged {flags}{}",
                q.invalid_facets,
                q.open_facets,
                q.non_simple_facets,
                q.overlapping_pairs,
                q.non_convex_facets,
                if q.all_finite { "" } else { "   NON-FINITE VERTICES" }
            );
            let _ = writeln!(
                s,
                "  topology: Euler characteristic {}, boundary loops {}, non-manifold edges {}",
                q.euler_characteristic, q.boundary_loops, q.non_manifold_edges
            );
            let _ = writeln!(
                s,
                "  neighbours: {} compensation flips, {} envelope repairs, {} unresolved, {} validity flips",
                q.neighbours.compensation_flips, q.neighbours.envelope_repairs, q.neighbours.envelope_unresolved, q.neighbours.validity_flips
            );
        }
    }
    if !result.plane_adjustments.is_empty() {
        let _ = writeln!(s, "  {}", plane_summary(result));
    }
    let d = &result.diagnostics;
    if d.is_empty() {
        let _ = writeln!(s, "  diagnostics: none");
    } else {
        let _ = writeln!(s, "  diagnostics: {}", d.len());
        for diag in d.iter().take(LISTED_DIAGNOSTICS) {
            let text = serde_json::to_string(diag).unwrap_or_default();
            let _ = writeln!(s, "    {}", truncate(&text, 110));
        }
        if d.len() > LISTED_DIAGNOSTICS {
            let _ = writeln!(
                s,
                "    ... {} more in the JSON output",
                d.len() - LISTED_DIAGNOSTICS
            );
        }
    }
    let t = &result.timings;
    let _ = writeln!(
        s,
        "  timings: samples {:.1} ms, delaunay {:.1} ms, neighbours {:.1} ms, facets {:.1} ms, mesh {:.1} ms, report {:.1} ms, total {:.1} ms ({threads} thread{})",
        t.samples, t.delaunay, t.neighbours, t.facets, t.mesh, t.report, t.total, if threads == 1 { "" } else { "s" }
    );
    s
}

/// Four significant digits, whatever the scale (issue 14: `{:.4}` printed `deviation max
/// 0.0000` for a fine mesh): decimal for 1e-3 <= |x| < 1e5, exponent form otherwise.
pub(crate) fn sig(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() {
        format!("{x}")
    } else if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.3e}")
    }
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        s.chars().take(n - 3).collect::<String>() + "..."
    }
}

/// The tilt distribution of adjusted planes: how many facets were tilted, the largest and
/// the median tilt among them, and the largest offset.
fn plane_summary(result: &Discretisation) -> String {
    let mut tilts: Vec<f64> = result
        .plane_adjustments
        .iter()
        .map(|a| a.tilt_degrees)
        .filter(|&t| t > 0.0)
        .collect();
    tilts.sort_by(f64::total_cmp);
    let offset = result
        .plane_adjustments
        .iter()
        .map(|a| a.offset.abs())
        .fold(0.0, f64::max);
    if tilts.is_empty() {
        return "planes: adjusted mode, every facet in its exact tangent plane".into();
    }
    format!(
        "planes: {} of {} facets tilted, tilt max {:.2} deg, median {:.2} deg; offset max {}",
        tilts.len(),
        result.plane_adjustments.len(),
        tilts[tilts.len() - 1],
        tilts[tilts.len() / 2],
        sig(offset)
    )
}

#[cfg(test)]
mod tests {
    use super::{far_vertex_warning, sig, summary, topology_warning};
    use tpi_core::{Discretisation, QualityReport};

    /// The area line of the summary of a mesh whose smallest facet area is `min`.
    fn area_line(min: f64) -> String {
        let result = Discretisation {
            quality: Some(QualityReport {
                min_facet_area: min,
                max_facet_area: 2.5,
                ..QualityReport::default()
            }),
            ..Discretisation::default()
        };
        let text = summary(&result, "s.json", "hex:4x4", 1);
        let line = text.lines().find(|l| l.contains("facet area"));
        line.unwrap_or_else(|| panic!("no area line in {text}"))
            .to_string()
    }

    #[test]
    fn a_negative_facet_area_is_said_to_be_signed() {
        // Issue 14: the summary printed negative areas with no word on what they mean.
        let negative = area_line(-0.125);
        assert!(
            negative.contains("facet area -0.1250 .. 2.500"),
            "{negative}"
        );
        assert!(
            negative
                .contains("(signed: negative for a facet wound the wrong way round, non-simple)"),
            "{negative}"
        );
        let positive = area_line(0.125);
        assert!(
            positive.contains("facet area 0.1250 .. 2.500"),
            "{positive}"
        );
        assert!(!positive.contains("signed"), "{positive}");
    }

    #[test]
    fn facets_with_a_far_vertex_are_warned_about() {
        let report = |far_vertex_facets, max_deviation_spacings| QualityReport {
            facet_count: 100,
            far_vertex_facets,
            max_deviation: 49.7,
            max_deviation_spacings,
            ..QualityReport::default()
        };
        assert_eq!(far_vertex_warning(&report(0, 2.9)), None);
        let far = far_vertex_warning(&report(4, 50.2)).expect("a warning");
        assert!(
            far.starts_with("warning: 4 facets have a vertex more than 3 local pattern spacings off the surface (largest deviation 49.70; up to 50 local spacings)"),
            "{far}"
        );
    }

    #[test]
    fn the_topology_warning_points_at_the_invalid_facets_where_there_are_some() {
        let alone = topology_warning((2, 2), (1, 1), 0);
        assert!(
            alone.starts_with("warning: the mesh has Euler characteristic 2 and 2 boundary loop(s), where 1 and 1 were expected")
                && alone.ends_with("where no single facet shows it"),
            "{alone}"
        );
        let with = topology_warning((2, 1), (1, 1), 46);
        assert!(
            with.ends_with("at or next to the 46 invalid facets flagged"),
            "{with}"
        );
    }

    #[test]
    fn four_significant_digits_at_any_scale() {
        for (x, text) in [
            (0.0256, "0.02560"),
            (16.3834, "16.38"),
            (1234.5, "1234"),
            (0.4610, "0.4610"),
            (3.2e-6, "3.200e-6"),
            (-0.0012, "-0.001200"),
            (123456.0, "1.235e5"),
            (0.0, "0"),
        ] {
            assert_eq!(sig(x), text, "{x}");
        }
    }
}
