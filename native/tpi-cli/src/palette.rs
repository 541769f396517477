//! Colours shared by the SVG and PNG pictures: facets by side count, flagged outlines.

/// Fill colour of a facet with `sides` sides (RGB).
pub(crate) fn side_colour(sides: usize) -> [u8; 3] {
    match sides {
        0..=2 => [0xba, 0xb0, 0xac],
        3 => [0xff, 0x9d, 0xa7],
        4 => [0xf2, 0x8e, 0x2b],
        5 => [0xed, 0xc9, 0x48],
        6 => [0x59, 0xa1, 0x4f],
        7 => [0x4e, 0x79, 0xa7],
        8 => [0xb0, 0x7a, 0xa1],
        _ => [0x9c, 0x75, 0x5f],
    }
}

/// Legend label of a side count class ("9+" collects everything above 8).
pub(crate) fn side_label(sides: usize) -> String {
    match sides {
        0..=2 => "<3".to_string(),
        9.. => "9+".to_string(),
        n => n.to_string(),
    }
}

/// The class a side count is shown in (counts above 8 share one colour).
pub(crate) fn side_class(sides: usize) -> usize {
    match sides {
        0..=2 => 2,
        9.. => 9,
        n => n,
    }
}

/// The colour of a deviation `t` in units of the scale: a ramp through blue (0), teal,
/// green, yellow (0.75) to red (1 and beyond), so that what meets a tolerance reads cool and
/// what reaches it warm.
pub(crate) fn deviation_colour(t: f64) -> [u8; 3] {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [0x2c as f64, 0x4f as f64, 0xa0 as f64]),
        (0.25, [0x2a as f64, 0x9d as f64, 0xa8 as f64]),
        (0.5, [0x6a as f64, 0xbf as f64, 0x4b as f64]),
        (0.75, [0xf0 as f64, 0xc8 as f64, 0x3c as f64]),
        (1.0, [0xd7 as f64, 0x30 as f64, 0x27 as f64]),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        1.0
    };
    let k = STOPS
        .iter()
        .rposition(|&(at, _)| at <= t)
        .unwrap_or(0)
        .min(3);
    let ((a, ca), (b, cb)) = (STOPS[k], STOPS[k + 1]);
    let f = ((t - a) / (b - a)).clamp(0.0, 1.0);
    let mix = |i: usize| (ca[i] + (cb[i] - ca[i]) * f).round() as u8;
    [mix(0), mix(1), mix(2)]
}

/// Outline colour of flagged facets.
pub(crate) const FLAG_COLOUR: [u8; 3] = [0xe0, 0x00, 0x00];

/// Edge colour.
pub(crate) const EDGE_COLOUR: [u8; 3] = [0x22, 0x22, 0x22];

/// `#rrggbb`.
pub(crate) fn hex(c: [u8; 3]) -> String {
    let mut text = String::with_capacity(7);
    push_hex(&mut text, c);
    text
}

/// Appends `#rrggbb` to `out` ([`hex`] without its own string, for writers of many facets).
pub(crate) fn push_hex(out: &mut String, c: [u8; 3]) {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    out.push('#');
    for byte in c {
        out.push(char::from(DIGITS[usize::from(byte >> 4)]));
        out.push(char::from(DIGITS[usize::from(byte & 15)]));
    }
}

/// The vertices the pictures are framed on: every finite vertex within a quarter of the
/// seeds' bounding-box diagonal of that box. A vertex that ran far away (an ill-conditioned
/// meeting point of nearly parallel planes) would otherwise shrink the whole picture; its
/// facets are still drawn, clipped by the frame.
pub(crate) fn framing_points(result: &tpi_core::Discretisation) -> Vec<glam::DVec3> {
    use glam::DVec3;
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for s in result.seeds.iter().filter(|s| s.point.is_finite()) {
        lo = lo.min(s.point);
        hi = hi.max(s.point);
    }
    let finite = result.vertices.iter().copied().filter(|v| v.is_finite());
    if !lo.is_finite() || !hi.is_finite() {
        return finite.collect();
    }
    let pad = DVec3::splat(0.25 * (hi - lo).length());
    let (lo, hi) = (lo - pad, hi + pad);
    let kept: Vec<DVec3> = finite
        .clone()
        .filter(|v| v.cmpge(lo).all() && v.cmple(hi).all())
        .collect();
    if kept.is_empty() {
        finite.collect()
    } else {
        kept
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_read_as_the_standard_formatter_writes_them() {
        for c in [
            [0, 0, 0],
            [255, 255, 255],
            [0x59, 0xa1, 0x4f],
            [0x0a, 0xb0, 0x0c],
        ] {
            let expected = format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
            assert_eq!(hex(c), expected);
            let mut appended = String::from("x");
            push_hex(&mut appended, c);
            assert_eq!(appended, format!("x{expected}"));
        }
    }
}
