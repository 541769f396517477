//! Wavefront OBJ: one `v` line per mesh vertex, one `f` n-gon per facet with 1-based indices
//! into the shared vertices (Rhino's OBJ import reads n-gons as mesh n-gons).
//!
//! A face needs at least 3 distinct vertices: an open facet with fewer (flag 16 in the JSON)
//! gets no `f` line but a comment `# facet I open: K vertices` in its place, so the `f` lines
//! and comments together follow the facets in order (issue 14: `f 7 8` made the file invalid).
//! Non-simple and overlapping facets are written as they are (they are valid OBJ faces) and
//! flagged in the JSON output.

use std::fmt::Write;

use tpi_core::{Discretisation, Units};

/// The units as every output names them: `mm`, ..., or `unitless` with the reason.
pub(crate) fn units_text(units: Option<Units>) -> String {
    match units {
        Some(u) => u.short_name().to_string(),
        None => "unitless (the surface file has no \"units\")".to_string(),
    }
}

/// The mesh as OBJ text. `source` goes into the header comment.
pub(crate) fn to_obj(result: &Discretisation, source: &str) -> String {
    let mut out = String::with_capacity(result.vertices.len() * 48 + result.facet_loops.len() * 8);
    let _ = writeln!(
        out,
        "# tpi {}: tangent plane intersection mesh",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(out, "# {source}");
    let _ = writeln!(out, "# units: {}", units_text(result.units));
    let _ = writeln!(
        out,
        "# {} vertices, {} facets (facet i belongs to pattern point i)",
        result.vertices.len(),
        result.facet_count()
    );
    let _ = writeln!(out, "o tpi_mesh");
    let mut floats = zmij::Buffer::new();
    let mut integers = itoa::Buffer::new();
    for v in &result.vertices {
        out.push('v');
        for x in [v.x, v.y, v.z] {
            out.push(' ');
            push_num(&mut out, &mut floats, x);
        }
        out.push('\n');
    }
    // One buffer for every facet's distinct vertices (a vector per facet was a third of the
    // writer's instructions).
    let mut distinct = Vec::new();
    for i in 0..result.facet_count() {
        let facet = result.facet(i);
        distinct.clear();
        distinct.extend_from_slice(facet);
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() < 3 {
            let n = distinct.len();
            let noun = if n == 1 { "vertex" } else { "vertices" };
            let _ = writeln!(out, "# facet {i} open: {n} {noun}");
            continue;
        }
        out.push('f');
        for &k in facet {
            out.push(' ');
            out.push_str(integers.format(u64::from(k) + 1));
        }
        out.push('\n');
    }
    out
}

/// Appends the shortest round-trip text of a coordinate: decimal for 1e-5 <= |x| < 1e15
/// (no trailing ".0"), exponent form otherwise, "0" for zero; as `{}` / `{:e}` print it,
/// without their cost (zmij's shortest round-trip digits; where the shortest length leaves a
/// choice its last digit may differ from the standard library's, reading back the same).
fn push_num(out: &mut String, buffer: &mut zmij::Buffer, x: f64) {
    let a = x.abs();
    if x == 0.0 {
        out.push('0');
    } else if !x.is_finite() {
        let _ = write!(out, "{x}");
    } else if (1e-5..1e15).contains(&a) {
        let text = buffer.format_finite(x);
        out.push_str(text.strip_suffix(".0").unwrap_or(text));
    } else {
        let _ = write!(out, "{x:e}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue 14: an open facet (fewer than 3 distinct vertices) was written as `f 7 8`, which
    /// is not a face. Facets 0 and 2 are triangles, facet 1 has two vertices and facet 3 one
    /// vertex twice: only two `f` lines, each with 3 indices, and a comment for each open one.
    #[test]
    fn open_facets_get_no_face() {
        let seed = tpi_core::Seed {
            uv: [0.5, 0.5],
            point: glam::DVec3::ZERO,
            normal: glam::DVec3::Z,
            curvatures: [1.0, 1.0],
        };
        let result = Discretisation {
            vertices: vec![
                glam::DVec3::X,
                glam::DVec3::Y,
                glam::DVec3::Z,
                glam::DVec3::ONE,
            ],
            facet_offsets: vec![0, 3, 5, 8, 10],
            facet_loops: vec![0, 1, 2, 2, 3, 1, 2, 3, 3, 3],
            seeds: vec![seed; 4],
            ..Discretisation::default()
        };
        let text = to_obj(&result, "test");
        let faces: Vec<&str> = text.lines().filter(|l| l.starts_with("f ")).collect();
        assert_eq!(faces, ["f 1 2 3", "f 2 3 4"]);
        assert!(text.contains("# facet 1 open: 2 vertices\n"), "{text}");
        assert!(text.contains("# facet 3 open: 1 vertex\n"), "{text}");
    }

    /// The text is what the standard library's shortest round-trip formatting prints.
    #[test]
    fn coordinates_round_trip_as_short_as_std_prints_them() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut buffer = zmij::Buffer::new();
        let mut samples = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.1,
            1e-5,
            9.99e-6,
            1e15,
            999999999999999.9,
            123456.0,
            2.5e-3,
        ];
        for _ in 0..100_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let bits = state >> 12 | 0x3FF0_0000_0000_0000;
            let unit = f64::from_bits(bits) - 1.0;
            let exponent = ((state >> 3) % 40) as i32 - 20;
            samples.push((unit - 0.5) * 10f64.powi(exponent));
        }
        let count = samples.len();
        let mut same = 0usize;
        for x in samples {
            let mut text = String::new();
            push_num(&mut text, &mut buffer, x);
            let a = x.abs();
            let std_text = if x == 0.0 {
                "0".to_string()
            } else if (1e-5..1e15).contains(&a) {
                format!("{x}")
            } else {
                format!("{x:e}")
            };
            // Round trip exactly, as short as the standard library's, the same form; where the
            // shortest length leaves a choice of last digit the two may pick differently.
            let back: f64 = text.parse().unwrap_or(f64::NAN);
            assert!(back == x, "{x:?} printed {text}");
            assert!(
                text.len() <= std_text.len(),
                "{x:?}: {text} against {std_text}"
            );
            assert_eq!(text.contains('e'), std_text.contains('e'), "{x:?}");
            same += usize::from(text == std_text);
        }
        // The choice is rare: nearly every coordinate prints exactly as before.
        assert!(same * 100 >= count * 99, "{same} of {count} the same");
    }
}
