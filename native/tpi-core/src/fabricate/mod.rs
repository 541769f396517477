//! Fabrication: from the planar facets of a [`Discretisation`] to panel solids with mitred
//! joints, cleat slots, flat parts nested on sheets, and the files a workshop reads.
//!
//! The paper's prototype (Manahl and Stavric, section 4.3) built the shell from
//! cross-laminated timber panels made from an offset mesh, joined by wedge-shaped cleats in
//! slots, and milled from toolpaths. This module is that chain.
//!
//! # Geometry
//!
//! Facet i lies in the plane `m_i . x = e_i` with the unit normal `m_i = s n_i` turned to the
//! chosen side (`s = +1` or `-1`; by default the concave side, the side the seeds of the
//! neighbours lie on: `sum over neighbour pairs of n_i . (p_j - p_i) > 0` means `+n_i`).
//! The panel of facet i is the solid between its **top** face (the facet) and its **bottom**
//! face in the offset plane `m_i . x = e_i + T`.
//!
//! * **Mitre.** Two neighbouring panels i and j are cut on their bisector plane
//!   `(m_i - m_j) . x = e_i - e_j`: it holds the common top edge (both sides 0) and the common
//!   bottom edge (both sides T), so both panels are cut on one plane, with no gap and no
//!   overlap (DESIGN.md, item 10).
//! * **Offset vertex.** Where three panels i, j, k meet at a top vertex v, the bottom vertex is
//!   `v + w` with `m_i . w = m_j . w = m_k . w = T`, in closed form
//!   `w = T (m_j x m_k + m_k x m_i + m_i x m_j) / (m_i . (m_j x m_k))`; it lies on all three
//!   offset planes and all three bisectors, and every panel computes it from the same sorted
//!   triple, so the panels agree bit for bit.
//! * **More than three panels at a vertex.** The fan of panels around the vertex
//!   `P_0, ..., P_{m-1}` (cyclic, from the panel of lowest seed `r = P_0`) is split into the
//!   triangles `(r, P_q, P_{q+1})`: each gives one offset vertex, and a panel in several of
//!   these triangles gets its top vertex repeated (a zero-length top edge with the diagonal
//!   partner as neighbour) with one bottom vertex per triangle. The side face on such an edge
//!   is a triangle in the bisector plane of the two panels; every panel sees the same split.
//!   Named by [`FabricationDiagnostic::SplitVertex`].
//! * **Boundary.** A boundary side is square to the panel: the plane through the top edge that
//!   contains `m_i`. At a vertex on the boundary the bottom vertex solves
//!   `m_i . w = T, s_prev . w = 0, s_next . w = 0` with the panel's own two side planes; two
//!   panels meeting there share the side plane and the bottom edge line, and each ends it at its
//!   own boundary plane.
//! * **Thickness limit.** The bottom edge of side k is `b_{k+1} - b_k = (v_{k+1} - v_k) +
//!   T (u_{k+1} - u_k)` with `u = w / T` fixed by the planes, so it shortens linearly with T and
//!   collapses at `T_max = |v_{k+1} - v_k| / (-(u_{k+1} - u_k) . d)` (`d` the unit top edge).
//!   For a thickness at or above an edge's `T_max`, the panels around the edge are clipped
//!   to the intersection of their half-spaces and the edge flips (module `clip`, named by
//!   [`FabricationDiagnostic::EdgeCollapsed`]); what clipping cannot resolve (no solid left, a
//!   non-convex facet, a cascade) is rejected with [`FabricationError::ThicknessTooLarge`],
//!   naming the panel and the reason.
//! * **Angles.** `dihedral_deg` is the angle between the two top faces measured through the
//!   material: `180 - theta` when the neighbour bends towards the offset side, `180 + theta`
//!   otherwise (`theta` the angle between the normals). `bevel_deg` is the angle between the side
//!   face and the panel normal, `asin(o . m_i)` with `o` the side's outward unit normal:
//!   positive when the panel narrows towards its bottom face, `theta / 2` for a mitre, 0 for a
//!   square side.
//! * **Volume.** Every section of a panel between its two faces is the polygon
//!   `top[k] + t (bottom[k] - top[k])`, so its area is quadratic in t and the volume is the
//!   prismatoid formula `T (A_top + 4 A_mid + A_bottom) / 6` (not for a clipped panel).
//! * **Slots.** A slot at parameter t of an interior edge (from `top[k]` to `top[k+1]` of the
//!   panel of the lower seed) is a notch of length L along the edge, centred there, and depth D
//!   into each panel, measured in the panel's plane square to the edge, through the full
//!   thickness: its back wall is the bisector plane moved by D into the panel. The cleat that
//!   fills both notches is the prism of length L over the hexagon `top_i + D u_i, top, top_j +
//!   D u_j, bottom_j + D u_j, bottom, bottom_i + D u_i` (`u` the in-plane inward normal of the
//!   edge): a wedge in section.
//! * **Flat parts.** Each panel is mapped into its plane by the rigid map
//!   `x -> ((x - top[0]) . e1, (x - top[0]) . e2)` with `e1` along its first edge and
//!   `e2 = n_i x e1`, so outlines keep their lengths and angles and stay counter-clockwise.

mod clip;
mod layout;
mod solids;
mod toolpath;
mod writers;

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::Discretisation;

pub use layout::Placement;
pub use toolpath::ToolpathOptions;
pub use writers::Units;

/// Most slots [`SlotPlan::Even`] may put on one edge.
pub const MAX_SLOTS_PER_EDGE: u32 = 1000;

/// Which side of the facets the panels are thickened to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PanelSide {
    /// Towards the centres of curvature (the concave side) where K > 0. Default value.
    #[default]
    Inside,
    /// Away from the centres of curvature.
    Outside,
}

/// Where the cleat slots go.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum SlotPlan {
    /// No slots. Default value.
    #[default]
    None,
    /// N slots evenly along every interior edge, at t = q / (N + 1), q = 1..=N.
    Even(u32),
    /// Slots at given parameters of given edges: `(seed a, seed b, [t, ...])`, t in (0, 1)
    /// measured from the start of the edge as it runs in seed a's facet.
    Explicit(Vec<([u32; 2], Vec<f64>)>),
}

impl SlotPlan {
    /// Reads `{"slots": [{"edge": [i, j], "at": [t0, t1, ...]}]}`; `source` names the file in
    /// errors.
    pub fn from_json(text: &str, source: &str) -> Result<SlotPlan, FabricationError> {
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Entry {
            edge: [u32; 2],
            at: Vec<f64>,
        }
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct File {
            slots: Vec<Entry>,
        }
        let file: File = serde_json::from_str(text).map_err(|e| FabricationError::SlotFile {
            file: source.to_string(),
            reason: e.to_string(),
        })?;
        Ok(SlotPlan::Explicit(
            file.slots.into_iter().map(|e| (e.edge, e.at)).collect(),
        ))
    }
}

/// Parameters of [`fabricate`].
#[derive(Clone, Debug, PartialEq)]
pub struct FabricateOptions {
    /// Panel thickness T in model units (finite, > 0). Default value: 0.04.
    pub thickness: f64,
    /// Side the panels are thickened to. Default value: [`PanelSide::Inside`].
    pub side: PanelSide,
    /// Cleat slots. Default value: none.
    pub slots: SlotPlan,
    /// Slot length L along the edge; `None` takes
    /// [`crate::tolerance::DEFAULT_SLOT_LENGTH_FACTOR`] times T. Default value: None.
    pub slot_length: Option<f64>,
    /// Slot depth D into each panel; `None` takes
    /// [`crate::tolerance::DEFAULT_SLOT_DEPTH_FACTOR`] times T. Default value: None.
    pub slot_depth: Option<f64>,
    /// Sheet size W x H in model units. Default value: [2.5, 1.25].
    pub sheet: [f64; 2],
    /// Least distance between two parts, and between a part and the sheet's edge.
    /// Default value: 0.02.
    pub gap: f64,
}

impl Default for FabricateOptions {
    fn default() -> Self {
        Self {
            thickness: 0.04,
            side: PanelSide::Inside,
            slots: SlotPlan::None,
            slot_length: None,
            slot_depth: None,
            sheet: [2.5, 1.25],
            gap: 0.02,
        }
    }
}

/// What is wrong with a fabrication request. Every variant names the culprit.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FabricationError {
    /// An option that must be a finite positive number is not.
    #[error("{field} = {value} is invalid: {reason}")]
    InvalidOption {
        /// The option (`thickness`, `gap`, `sheet width`, ...).
        field: &'static str,
        /// The value found.
        value: f64,
        /// The valid range.
        reason: &'static str,
    },
    /// The thickness collapses bottom edges in a way clipping cannot resolve (see
    /// [`FabricationDiagnostic::EdgeCollapsed`] for the ones it does): no solid is left, a
    /// non-convex facet, or a cascade of collapses. `max` is the thickness below which no
    /// bottom edge collapses at all.
    #[error("thickness {thickness} is too large for this mesh: {reason}; the first bottom edge (panel {panel} {}) collapses at thickness {max}, and up to that thickness no panel is clipped; use a thinner panel (or a coarser pattern there)", across(.neighbour))]
    ThicknessTooLarge {
        /// The thickness asked for.
        thickness: f64,
        /// The largest thickness the geometry allows (exclusive).
        max: f64,
        /// The panel (seed) whose bottom edge collapses first.
        panel: u32,
        /// Its neighbour along that edge (None: a boundary side, or not an edge).
        neighbour: Option<u32>,
        /// Why the collapse is not resolved, naming the panel.
        reason: String,
    },
    /// The discretisation cannot be fabricated (empty, a facet with fewer than three vertices,
    /// a vertex that is not finite).
    #[error("the mesh cannot be fabricated: {reason}")]
    BadMesh {
        /// What is wrong, naming the facet or vertex.
        reason: String,
    },
    /// A slot file that cannot be read.
    #[error("{file}: {reason}")]
    SlotFile {
        /// The file.
        file: String,
        /// What is wrong.
        reason: String,
    },
    /// A slot names an edge that is not an interior edge, or a parameter outside (0, 1), or it
    /// does not fit on its edge.
    #[error("slot on edge [{a}, {b}] at t = {t}: {reason}")]
    BadSlot {
        /// First seed of the edge.
        a: u32,
        /// Second seed of the edge.
        b: u32,
        /// The slot's parameter.
        t: f64,
        /// What is wrong.
        reason: String,
    },
    /// An output file could not be written (the DXF crate refused the drawing).
    #[error("{file}: {reason}")]
    Output {
        /// The file (`sheets.dxf`).
        file: &'static str,
        /// The writer's message.
        reason: String,
    },
    /// A flat part does not fit on a sheet in any orientation tried.
    #[error("panel {panel} needs {width} x {height} (with the gap on every side) and does not fit on a {sheet_width} x {sheet_height} sheet; use a larger --sheet")]
    PartTooLarge {
        /// The panel (seed).
        panel: u32,
        /// Its smallest bounding rectangle's width, plus twice the gap.
        width: f64,
        /// Its height, plus twice the gap.
        height: f64,
        /// Sheet width.
        sheet_width: f64,
        /// Sheet height.
        sheet_height: f64,
    },
}

/// Something local worth knowing about the fabricated panels; the result is still usable.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
#[non_exhaustive]
pub enum FabricationDiagnostic {
    /// More than three panels meet at a top vertex: it was split into offset vertices by
    /// triangles of the fan from the lowest seed (see the module doc).
    SplitVertex {
        /// The mesh vertex.
        vertex: u32,
        /// The panels around it, in fan order from the lowest seed.
        panels: Vec<u32>,
    },
    /// The thickness is beyond the limit of this edge: the offset vertices at its two ends
    /// met at `at_thickness`, the bottom edge vanished, and the panels around it were clipped
    /// (each the intersection of its half-spaces; the side faces over the edge are
    /// triangles). Below the edge the third panels at its two ends now meet (`joined`), on
    /// their bisector plane, as a side of zero top length at each of them.
    EdgeCollapsed {
        /// A panel of the edge.
        panel: u32,
        /// The other (None: a boundary edge).
        neighbour: Option<u32>,
        /// The edge's two mesh vertices.
        vertices: [u32; 2],
        /// The thickness at which the bottom edge vanished.
        at_thickness: f64,
        /// The two panels that meet below it instead (None on the boundary, or where a vertex
        /// of the edge is not where exactly three panels meet).
        joined: Option<[u32; 2]>,
    },
    /// Two neighbouring facets are coplanar: the side between them is cut square.
    ParallelNeighbours {
        /// The two panels.
        panels: [u32; 2],
    },
    /// The bottom outline of a panel reaches outside its top outline (seen along the normal):
    /// the part's cut outline is the convex hull of both.
    BottomOutsideTop {
        /// The panel.
        panel: u32,
    },
    /// `--slots N` put a slot where it does not fit (the edge is too short for its length,
    /// or the bottom edge is): the slot was left out.
    SlotSkipped {
        /// The two panels of the edge.
        panels: [u32; 2],
        /// The slot's parameter along the edge.
        t: f64,
    },
    /// The discretisation flagged this facet invalid (open, non-simple or overlapping): its
    /// panel is built but should be checked before cutting.
    InvalidFacet {
        /// The panel.
        panel: u32,
        /// The facet's flags.
        flags: u8,
    },
}

/// One side face of a panel: the face over `top[k] -> top[k + 1]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Side {
    /// The neighbour across it (None on the boundary).
    pub neighbour: Option<u32>,
    /// Its plane `[nx, ny, nz, d]`, `n . x = d`, n the unit outward normal.
    pub plane: [f64; 4],
    /// Angle between the two top faces through the material, degrees (None on the boundary).
    pub dihedral_deg: Option<f64>,
    /// Angle of the side face against the panel normal, degrees; positive when the panel
    /// narrows towards its bottom face.
    pub bevel_deg: f64,
    /// Length of the top edge.
    pub length: f64,
}

/// A cleat slot in one panel.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Slot {
    /// The side it is cut into.
    pub side: usize,
    /// The neighbour across that side.
    pub neighbour: u32,
    /// Distance of the slot's centre from `top[side]` along the top edge.
    pub at: f64,
    /// Length along the edge.
    pub length: f64,
    /// Depth into the panel.
    pub depth: f64,
    /// The notch's outline on the top face in flat coordinates (4 points: on the edge, then
    /// into the panel).
    pub flat: [[f64; 2]; 4],
}

/// A closed polyhedron with outward (counter-clockwise seen from outside) planar faces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polyhedron {
    /// Vertex positions.
    pub vertices: Vec<DVec3>,
    /// Faces as loops of vertex indices.
    pub faces: Vec<Vec<u32>>,
}

impl Polyhedron {
    /// The enclosed volume by the divergence theorem (faces fanned from their first vertex).
    pub fn volume(&self) -> f64 {
        let mut v = 0.0;
        for f in &self.faces {
            let a = self.vertices[f[0] as usize];
            for q in 1..f.len().saturating_sub(1) {
                let b = self.vertices[f[q] as usize];
                let c = self.vertices[f[q + 1] as usize];
                v += a.dot(b.cross(c));
            }
        }
        v / 6.0
    }
}

/// One panel: the solid of one facet.
#[derive(Clone, Debug, PartialEq)]
pub struct Panel {
    /// The seed (pattern point, facet index).
    pub seed: u32,
    /// Unit normal pointing from the top face into the panel (towards the bottom face).
    pub normal: DVec3,
    /// Top outline (the facet; a vertex repeated where the vertex was split).
    pub top: Vec<DVec3>,
    /// Bottom outline: `bottom[k]` is the offset of `top[k]`; in a panel clipped where a bottom
    /// edge collapsed, the corner where side k's bottom edge begins (`bottom[k] = bottom[k+1]`
    /// when side k does not reach the bottom face).
    pub bottom: Vec<DVec3>,
    /// Side k joins `top[k]` and `top[k + 1]`.
    pub sides: Vec<Side>,
    /// Origin and axes of the flat frame: flat = ((x - origin) . e1, (x - origin) . e2).
    pub frame: (DVec3, DVec3, DVec3),
    /// Top outline in the flat frame, same order as `top`.
    pub flat: Vec<DVec2>,
    /// Bottom outline in the flat frame (projected along the normal).
    pub flat_bottom: Vec<DVec2>,
    /// The outline a 3-axis router cuts around (counter-clockwise, no repeated vertices).
    pub cut_outline: Vec<DVec2>,
    /// Slots cut into this panel.
    pub slots: Vec<Slot>,
    /// Where the part lies on its sheet.
    pub placement: Placement,
    /// The closed solid, notches included.
    pub solid: Polyhedron,
}

impl Panel {
    /// Area of the top outline.
    pub fn top_area(&self) -> f64 {
        polygon_area(&self.flat)
    }
}

/// A sheet of the nesting.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Sheet {
    /// Width and height.
    pub size: [f64; 2],
    /// Area of the parts' cut outlines over the sheet's area.
    pub utilisation: f64,
}

/// A cleat: the solid filling the two notches of one slot.
#[derive(Clone, Debug, PartialEq)]
pub struct Cleat {
    /// The two panels it joins (lower seed first).
    pub panels: [u32; 2],
    /// The slot's parameter along the edge.
    pub t: f64,
    /// The solid.
    pub solid: Polyhedron,
}

/// The fabricated panels, cleats, sheets and diagnostics.
#[derive(Clone, Debug, PartialEq)]
pub struct Fabrication {
    /// Panel thickness.
    pub thickness: f64,
    /// The panels, one per facet, in seed order.
    pub panels: Vec<Panel>,
    /// The cleats.
    pub cleats: Vec<Cleat>,
    /// The sheets.
    pub sheets: Vec<Sheet>,
    /// The gap kept between parts.
    pub gap: f64,
    /// Local findings.
    pub diagnostics: Vec<FabricationDiagnostic>,
    /// Length units of the model (the surface file's `"units"`, through the discretisation),
    /// `None` when unitless.
    pub units: Option<Units>,
}

/// Builds panel solids, joints, flat parts and their nesting from a discretisation.
pub fn fabricate(
    mesh: &Discretisation,
    options: &FabricateOptions,
) -> Result<Fabrication, FabricationError> {
    check_positive("thickness", options.thickness)?;
    check_positive("sheet width", options.sheet[0])?;
    check_positive("sheet height", options.sheet[1])?;
    if !(options.gap >= 0.0) || !options.gap.is_finite() {
        return Err(FabricationError::InvalidOption {
            field: "gap",
            value: options.gap,
            reason: "must be a finite number >= 0",
        });
    }
    if let SlotPlan::Even(count) = options.slots {
        if count > MAX_SLOTS_PER_EDGE {
            return Err(FabricationError::InvalidOption {
                field: "slots per edge",
                value: f64::from(count),
                reason: "at most 1000 slots per edge",
            });
        }
    }
    let t = options.thickness;
    let slot_length = options
        .slot_length
        .unwrap_or(crate::tolerance::DEFAULT_SLOT_LENGTH_FACTOR * t);
    let slot_depth = options
        .slot_depth
        .unwrap_or(crate::tolerance::DEFAULT_SLOT_DEPTH_FACTOR * t);
    check_positive("slot length", slot_length)?;
    check_positive("slot depth", slot_depth)?;
    let mut built = solids::build(mesh, t, options.side)?;
    let cleats = solids::cut_slots(&mut built, &options.slots, slot_length, slot_depth)?;
    let mut diagnostics = std::mem::take(&mut built.diagnostics);
    let mut panels = built.panels;
    let sheets = layout::nest(&mut panels, options.sheet, options.gap, &mut diagnostics)?;
    Ok(Fabrication {
        thickness: t,
        panels,
        cleats,
        sheets,
        gap: options.gap,
        diagnostics,
        units: mesh.units,
    })
}

fn across(neighbour: &Option<u32>) -> String {
    match neighbour {
        Some(j) => format!("along neighbour {j}"),
        None => "along the boundary".to_string(),
    }
}

fn check_positive(field: &'static str, value: f64) -> Result<(), FabricationError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(FabricationError::InvalidOption {
            field,
            value,
            reason: "must be a finite number > 0",
        })
    }
}

/// Signed area of a polygon (positive counter-clockwise).
pub(crate) fn polygon_area(p: &[DVec2]) -> f64 {
    let n = p.len();
    let mut a = 0.0;
    for k in 0..n {
        a += p[k].perp_dot(p[(k + 1) % n]);
    }
    a / 2.0
}
