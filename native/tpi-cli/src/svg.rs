//! SVG pictures: the mesh's top view (x, y) and a pattern's points with their Voronoi diagram.

use std::collections::BTreeMap;
use std::fmt::Write;

use tpi_core::Discretisation;

use crate::palette::{
    hex, push_hex, side_class, side_colour, side_label, EDGE_COLOUR, FLAG_COLOUR,
};

/// Longest side of the drawing area, in SVG user units (pixels).
const DRAWING: f64 = 1000.0;
const MARGIN: f64 = 20.0;
const LEGEND_WIDTH: f64 = 150.0;

/// Escapes text for XML content and attributes.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Top view of the mesh: one `<polygon>` per facet (in facet order, `data-facet` = index),
/// filled by side count, flagged facets outlined red; a legend on the right.
pub(crate) fn mesh_top_view(result: &Discretisation, title: &str) -> String {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for v in crate::palette::framing_points(result) {
        lo = [lo[0].min(v.x), lo[1].min(v.y)];
        hi = [hi[0].max(v.x), hi[1].max(v.y)];
    }
    if !(lo[0] <= hi[0] && lo[1] <= hi[1]) {
        lo = [0.0, 0.0];
        hi = [1.0, 1.0];
    }
    let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
    let scale = DRAWING / span[0].max(span[1]);
    let (w, h) = (span[0] * scale, span[1] * scale);
    let width = w + 2.0 * MARGIN + LEGEND_WIDTH;
    let height = (h + 2.0 * MARGIN).max(300.0);
    let map = |x: f64, y: f64| {
        let far = 1e6;
        (
            (MARGIN + (x - lo[0]) * scale).clamp(-far, far),
            (MARGIN + (hi[1] - y) * scale).clamp(-far, far),
        )
    };

    let mut out = String::new();
    header(&mut out, width, height, title);
    let _ = writeln!(out, "<clipPath id=\"frame\"><rect x=\"0\" y=\"0\" width=\"{:.1}\" height=\"{height:.1}\"/></clipPath>", w + 2.0 * MARGIN);
    let _ = writeln!(out, "<g id=\"facets\" clip-path=\"url(#frame)\" stroke=\"{}\" stroke-width=\"0.7\" stroke-linejoin=\"round\">", hex(EDGE_COLOUR));
    let mut counts: BTreeMap<usize, usize> = BTreeMap::new();
    let flagged = |i: usize| result.facet_flags.get(i).copied().unwrap_or(0) != 0;
    // Flagged facets last, so that their red outlines lie on top.
    let order = (0..result.facet_count())
        .filter(|&i| !flagged(i))
        .chain((0..result.facet_count()).filter(|&i| flagged(i)));
    let mut any_flagged = false;
    // Written piece by piece, without `write!`: at 100k facets the formatting machinery was
    // most of the writer's time (about 40 MB/s).
    out.reserve(result.facet_loops.len() * 16 + result.facet_count() * 72);
    let mut integers = itoa::Buffer::new();
    let flag_colour = hex(FLAG_COLOUR);
    for i in order {
        let facet = result.facet(i);
        *counts.entry(side_class(facet.len())).or_default() += 1;
        out.push_str("<polygon data-facet=\"");
        out.push_str(integers.format(i));
        out.push_str("\" data-sides=\"");
        out.push_str(integers.format(facet.len()));
        out.push_str("\" fill=\"");
        push_hex(&mut out, side_colour(facet.len()));
        out.push('"');
        if flagged(i) {
            any_flagged = true;
            out.push_str(" data-flags=\"");
            out.push_str(integers.format(result.facet_flags[i]));
            out.push_str("\" stroke=\"");
            out.push_str(&flag_colour);
            out.push_str("\" stroke-width=\"1.6\"");
        }
        out.push_str(" points=\"");
        push_points(
            &mut out,
            facet.iter().map(|&vi| {
                let v = result.vertices[vi as usize];
                map(v.x, v.y)
            }),
        );
        out.push_str("\"/>\n");
    }
    out.push_str("</g>\n");

    // Legend.
    let lx = w + 2.0 * MARGIN;
    let _ = writeln!(
        out,
        "<g id=\"legend\" font-family=\"sans-serif\" font-size=\"13\" fill=\"#222\">"
    );
    let _ = writeln!(
        out,
        "<text x=\"{lx:.1}\" y=\"{:.1}\" font-weight=\"bold\">sides</text>",
        MARGIN + 12.0
    );
    let mut y = MARGIN + 24.0;
    for (&class, &n) in &counts {
        let _ = writeln!(
            out,
            "<rect x=\"{lx:.1}\" y=\"{y:.1}\" width=\"16\" height=\"16\" fill=\"{}\" stroke=\"{}\" stroke-width=\"0.7\"/><text x=\"{:.1}\" y=\"{:.1}\">{}: {n}</text>",
            hex(side_colour(class)),
            hex(EDGE_COLOUR),
            lx + 22.0,
            y + 13.0,
            side_label(class)
        );
        y += 22.0;
    }
    if any_flagged {
        let n = (0..result.facet_count()).filter(|&i| flagged(i)).count();
        let _ = writeln!(
            out,
            "<rect x=\"{lx:.1}\" y=\"{y:.1}\" width=\"16\" height=\"16\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.6\"/><text x=\"{:.1}\" y=\"{:.1}\">flagged: {n}</text>",
            hex(FLAG_COLOUR),
            lx + 22.0,
            y + 13.0
        );
        y += 22.0;
    }
    let _ = writeln!(out, "<text x=\"{lx:.1}\" y=\"{:.1}\" font-size=\"11\" fill=\"#666\">top view (x right, y up; units: {})</text>", y + 14.0, tpi_core::units_label(result.units));
    out.push_str("</g>\n</svg>\n");
    out
}

/// Appends an SVG point list, `x,y` pairs apart by spaces, each coordinate as `{:.2}`
/// writes it ([`push_fixed2`]).
fn push_points(out: &mut String, points: impl Iterator<Item = (f64, f64)>) {
    for (k, (x, y)) in points.enumerate() {
        if k > 0 {
            out.push(' ');
        }
        push_fixed2(out, x);
        out.push(',');
        push_fixed2(out, y);
    }
}

/// Above this |100 x| the rounding of 100 x in binary can reach [`FIXED2_TIE_MARGIN`]
/// (its error is at most |100 x| 2^-52, 2.2e-7 here).
const FIXED2_DIRECT_LIMIT: f64 = 1e9;

/// How close to a half 100 x may come before the standard formatter decides its rounding.
const FIXED2_TIE_MARGIN: f64 = 1e-6;

/// Appends x with two decimals, the text `{x:.2}` writes: where 100 x lies farther than
/// [`FIXED2_TIE_MARGIN`] from a half, the product's rounding error cannot move it across
/// one, so rounding the product gives the correctly rounded decimal; the standard formatter
/// writes the rest (ties, large or non-finite values, and results of zero, whose sign it
/// keeps: `-0.00`).
fn push_fixed2(out: &mut String, x: f64) {
    let scaled = x * 100.0;
    let near_half = ((scaled - scaled.trunc()).abs() - 0.5).abs() < FIXED2_TIE_MARGIN;
    let rounded = scaled.round();
    if !(scaled.abs() < FIXED2_DIRECT_LIMIT) || near_half || rounded == 0.0 {
        let _ = write!(out, "{x:.2}");
        return;
    }
    // |rounded| < 1e9: exact in i64.
    let hundredths = rounded as i64;
    if hundredths < 0 {
        out.push('-');
    }
    let magnitude = hundredths.unsigned_abs();
    out.push_str(itoa::Buffer::new().format(magnitude / 100));
    out.push('.');
    let fraction = (magnitude % 100) as u8;
    out.push(char::from(b'0' + fraction / 10));
    out.push(char::from(b'0' + fraction % 10));
}

fn header(out: &mut String, width: f64, height: f64, title: &str) {
    let _ = writeln!(out, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width:.0}\" height=\"{height:.0}\" viewBox=\"0 0 {width:.1} {height:.1}\">"
    );
    let _ = writeln!(out, "<title>{}</title>", escape(title));
    let _ = writeln!(
        out,
        "<rect x=\"0\" y=\"0\" width=\"{width:.1}\" height=\"{height:.1}\" fill=\"#ffffff\"/>"
    );
}

/// The pattern in the unit square (s right, t up): its Voronoi cells clipped to the square
/// as `<polygon>`s (one per point, in point order) and the points as `<circle>`s.
pub(crate) fn pattern_preview(points: &[[f64; 2]], cells: &[Vec<[f64; 2]>], title: &str) -> String {
    let size = 800.0;
    let m = MARGIN;
    let map = |p: [f64; 2]| (m + p[0] * size, m + (1.0 - p[1]) * size);
    let total = size + 2.0 * m;
    let mut out = String::new();
    header(&mut out, total, total + 20.0, title);
    let _ = writeln!(out, "<rect x=\"{m}\" y=\"{m}\" width=\"{size}\" height=\"{size}\" fill=\"#f7f7f2\" stroke=\"#222\" stroke-width=\"1\"/>");
    let _ = writeln!(out, "<g id=\"voronoi\" fill=\"none\" stroke=\"#4e79a7\" stroke-width=\"0.8\" stroke-linejoin=\"round\">");
    for (i, cell) in cells.iter().enumerate() {
        let _ = write!(out, "<polygon data-point=\"{i}\" points=\"");
        push_points(&mut out, cell.iter().map(|&p| map(p)));
        out.push_str("\"/>\n");
    }
    out.push_str("</g>\n");
    let r = (0.35 * size / (points.len().max(1) as f64).sqrt()).clamp(0.6, 4.0);
    let _ = writeln!(out, "<g id=\"points\" fill=\"#e15759\">");
    for &p in points {
        let (x, y) = map(p);
        let _ = writeln!(out, "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"{r:.2}\"/>");
    }
    out.push_str("</g>\n");
    let _ = writeln!(
        out,
        "<text x=\"{m}\" y=\"{:.1}\" font-family=\"sans-serif\" font-size=\"13\" fill=\"#222\">{} points, Voronoi cells in the unit square (s right, t up)</text>",
        total + 8.0,
        points.len()
    );
    out.push_str("</svg>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fast writer's text against the standard formatter's `{:.2}`, on values drawn
    /// across the drawing's range, exact ties (x.xx5 in binary: 0.125, 2.675...), values a
    /// rounding step from a tie, negatives, zeros of both signs, and out-of-range values.
    #[test]
    fn two_decimals_read_as_the_standard_formatter_writes_them() {
        let mut values = vec![
            0.0,
            -0.0,
            0.004,
            -0.004,
            0.005,
            -0.005,
            0.125,
            -0.125,
            2.675,
            1.005,
            0.015,
            999_999.995,
            -999_999.995,
            1e6,
            -1e6,
            1e7,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            5e-324,
            0.994_999_999_999_999_9,
            0.995,
        ];
        // SplitMix64: reproducible values without a dependency.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        };
        for _ in 0..200_000 {
            let unit = (next() >> 11) as f64 / (1u64 << 53) as f64;
            values.push((unit - 0.5) * 2400.0);
            // Exact hundredths and half-hundredths, and their neighbours in binary.
            let k = (next() % 2_000_000) as f64 - 1_000_000.0;
            for base in [k / 100.0, (k + 0.5) / 100.0] {
                values.extend([base, base.next_up(), base.next_down()]);
            }
        }
        for x in values {
            let mut fast = String::new();
            push_fixed2(&mut fast, x);
            assert_eq!(fast, format!("{x:.2}"), "{x:e}");
        }
    }
}
