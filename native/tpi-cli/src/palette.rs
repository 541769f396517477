//! Colours shared by the SVG and PNG pictures: facets by side count, flagged outlines.

/// Fill colour of a facet with `sides` sides (RGB).
pub fn side_colour(sides: usize) -> [u8; 3] {
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
pub fn side_label(sides: usize) -> String {
    match sides {
        0..=2 => "<3".to_string(),
        9.. => "9+".to_string(),
        n => n.to_string(),
    }
}

/// The class a side count is shown in (counts above 8 share one colour).
pub fn side_class(sides: usize) -> usize {
    match sides {
        0..=2 => 2,
        9.. => 9,
        n => n,
    }
}

/// Outline colour of flagged facets.
pub const FLAG_COLOUR: [u8; 3] = [0xe0, 0x00, 0x00];

/// Edge colour.
pub const EDGE_COLOUR: [u8; 3] = [0x22, 0x22, 0x22];

/// `#rrggbb`.
pub fn hex(c: [u8; 3]) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}
