//! Panels clipped where a bottom edge collapses (a thickness beyond the edge's limit).
//!
//! The bottom edge of side k of panel i collapses at `T_max` (parent module doc): there its
//! two offset vertices meet in the *apex*, the point of the bisector plane of i and its
//! neighbour j that lies at depth `T_max` below all four facets i, j, a and b, where a and b
//! are the third panels at the edge's two ends. Below the apex the edge is gone: the bottom
//! of i no longer touches j, and a and b meet instead, on their own bisector plane (the edge
//! flips, as in a straight skeleton). So, for T >= T_max:
//!
//! * Panels i and j (and a and b) are each the intersection of their half-spaces: the top
//!   plane `m . x >= e`, the bottom plane `m . x <= e + T` and every side plane (outward
//!   normal `o`, `o . x <= d`); a and b also get the half-space of their new bisector plane
//!   `(m_a - m_b) . x = e_a - e_b`, as a side of zero top length at the vertex where the edge
//!   ended (a repeated top vertex, as at a split vertex). A side that no longer reaches the
//!   bottom face drops out of it: the side face of i over the collapsed edge is the triangle
//!   `top[k], top[k+1], apex`, and the same triangle is j's face on the same plane.
//! * With the cell as the solid, its bottom face is a convex polygon on the offset plane;
//!   `bottom[k]` is where side k's bottom edge begins, and a side that does not reach the
//!   bottom face has `bottom[k] = bottom[k + 1]` (a repeated bottom vertex).
//! * The cell is computed by enumerating the points where three of its planes meet and keeping
//!   those inside every half-space; each plane's face is the loop of the kept points on it,
//!   ordered by angle (counter-clockwise seen from outside).
//!
//! This is exact for convex facets (a K > 0 surface's, or any convex facet on a saddle) and
//! one flip per edge. What it cannot resolve is refused, naming the panel
//! ([`FabricationError::ThicknessTooLarge`] with its reason): a non-convex facet, a bottom face
//! that vanishes (no solid at all), a clip that would cut the top face, and a cascade (a side
//! that leaves the bottom face without being a collapsed edge, or a new side that collapses in
//! turn).

use std::collections::{BTreeSet, HashSet};

use glam::DVec3;

use super::solids::{flat_part, walk_fan};
use super::{FabricationDiagnostic, FabricationError, Panel, Polyhedron, Side};
use crate::tolerance::{
    FABRICATION_CLIP_TOLERANCE, FABRICATION_OUTLINE_MERGE, FABRICATION_PARALLEL_TOLERANCE,
    FABRICATION_SHORT_EDGE, FABRICATION_SINGULAR_TOLERANCE,
};
use crate::Discretisation;

/// What the clipping reads from the panel build.
pub(super) struct Frame<'a> {
    pub(super) mesh: &'a Discretisation,
    /// Neighbour of each side of each facet (facet order, not ring order).
    pub(super) neighbours: &'a [Vec<Option<u32>>],
    /// Unit normal of each facet plane, pointing into the panel.
    pub(super) m: &'a [DVec3],
    /// `m_i . x = e_i` is facet i's plane.
    pub(super) e: &'a [f64],
    /// Facet centroids.
    pub(super) centroid: &'a [DVec3],
    /// The side: `m_i = sigma n_i`.
    pub(super) sigma: f64,
    /// The thickness.
    pub(super) t: f64,
    /// Bounding-box diagonal of the mesh.
    pub(super) diagonal: f64,
    /// The smallest collapse thickness of the mesh: (T_max, panel, neighbour).
    pub(super) worst: (f64, u32, Option<u32>),
}

impl Frame<'_> {
    /// The refusal; `reason` names the panel that cannot be resolved, `panel` and `neighbour`
    /// of the error are the first edge to collapse.
    fn refuse(&self, reason: String) -> FabricationError {
        FabricationError::ThicknessTooLarge {
            thickness: self.t,
            max: self.worst.0,
            panel: self.worst.1,
            neighbour: self.worst.2,
            reason,
        }
    }
}

/// Clips the panels around every collapsed side (`(panel, ring side, T_max)`), names each
/// collapsed edge in `diagnostics`, and returns which panels were clipped (their `solid` is
/// set; the others get theirs later).
pub(super) fn resolve(
    frame: &Frame<'_>,
    panels: &mut [Panel],
    ring_ids: &mut [Vec<u32>],
    collapsed: &[(usize, usize, f64)],
    diagnostics: &mut Vec<FabricationDiagnostic>,
) -> Result<Vec<bool>, FabricationError> {
    let mesh = frame.mesh;
    let mut clipped = vec![false; panels.len()];
    let mut edges_done: HashSet<(u32, u32)> = HashSet::new();
    let mut resolved: BTreeSet<usize> = BTreeSet::new();
    // New sides: (panel, top vertex, partner).
    let mut extras: Vec<(usize, u32, u32)> = Vec::new();
    for &(i, k, max) in collapsed {
        let ring = ring_ids[i].len();
        let (v, w) = (ring_ids[i][k], ring_ids[i][(k + 1) % ring]);
        resolved.insert(i);
        let neighbour = panels[i].sides[k].neighbour;
        if !edges_done.insert((v.min(w), v.max(w))) {
            continue;
        }
        let mut joined = None;
        if let Some(j) = neighbour {
            resolved.insert(j as usize);
            let third = |vertex: u32| -> Option<u32> {
                let at = mesh.facet(i).iter().position(|&q| q == vertex)?;
                let fan = walk_fan(mesh, frame.neighbours, i, at)?;
                if fan.len() != 3 {
                    return None;
                }
                fan.into_iter().find(|&q| q as usize != i && q != j)
            };
            if let (Some(a), Some(b)) = (third(v), third(w)) {
                let already = panels[a as usize]
                    .sides
                    .iter()
                    .any(|s| s.neighbour == Some(b));
                if a != b && !already {
                    extras.push((a as usize, v, b));
                    extras.push((b as usize, w, a));
                    resolved.insert(a as usize);
                    resolved.insert(b as usize);
                    joined = Some([a.min(b), a.max(b)]);
                }
            }
        }
        diagnostics.push(FabricationDiagnostic::EdgeCollapsed {
            panel: i as u32,
            neighbour,
            vertices: [v, w],
            at_thickness: max,
            joined,
        });
    }
    let collapsed_edges = edges_done;
    let eps = FABRICATION_CLIP_TOLERANCE * frame.diagonal;
    for &p in &resolved {
        for &(q, vertex, partner) in extras.iter().filter(|x| x.0 == p) {
            add_side(frame, &mut panels[p], &mut ring_ids[p], q, vertex, partner)?;
        }
        clip_panel(
            frame,
            p,
            &mut panels[p],
            &ring_ids[p],
            &collapsed_edges,
            eps,
        )?;
        let part = flat_part(
            p,
            &panels[p].top,
            &panels[p].bottom,
            frame.m[p] * frame.sigma,
            FABRICATION_SHORT_EDGE * frame.diagonal,
            FABRICATION_OUTLINE_MERGE * frame.diagonal,
        )?;
        let widened = FabricationDiagnostic::BottomOutsideTop { panel: p as u32 };
        diagnostics.retain(|d| *d != widened);
        if part.widened {
            diagnostics.push(widened);
        }
        let panel = &mut panels[p];
        panel.frame = part.frame;
        panel.flat = part.flat;
        panel.flat_bottom = part.flat_bottom;
        panel.cut_outline = part.cut_outline;
        clipped[p] = true;
    }
    Ok(clipped)
}

/// Inserts into panel p's ring a side of zero top length at `vertex`, on the bisector plane
/// of p and `partner`, oriented so that the facet lies inside.
fn add_side(
    frame: &Frame<'_>,
    panel: &mut Panel,
    ids: &mut Vec<u32>,
    p: usize,
    vertex: u32,
    partner: u32,
) -> Result<(), FabricationError> {
    let Some(q) = ids.iter().position(|&x| x == vertex) else {
        return Err(frame.refuse(format!("vertex {vertex} is not on panel {p}")));
    };
    let (mi, mj) = (frame.m[p], frame.m[partner as usize]);
    let diff = mi - mj;
    let len = diff.length();
    if len < FABRICATION_PARALLEL_TOLERANCE {
        return Err(frame.refuse(format!(
            "panel {p} and panel {partner} meet below a collapsed edge and are coplanar"
        )));
    }
    let (mut s, mut d) = (diff / len, (frame.e[p] - frame.e[partner as usize]) / len);
    if s.dot(frame.centroid[p]) > d {
        s = -s;
        d = -d;
    }
    let a = panel.top[q];
    let theta = mi.cross(mj).length().atan2(mi.dot(mj)).to_degrees();
    let dihedral = if mi.dot(frame.centroid[partner as usize] - a) >= 0.0 {
        180.0 - theta
    } else {
        180.0 + theta
    };
    panel.top.insert(q, a);
    panel.bottom.insert(q, panel.bottom[q]);
    ids.insert(q, vertex);
    panel.sides.insert(
        q,
        Side {
            neighbour: Some(partner),
            plane: [s.x, s.y, s.z, d],
            dihedral_deg: Some(dihedral),
            bevel_deg: s.dot(mi).clamp(-1.0, 1.0).asin().to_degrees(),
            length: 0.0,
        },
    );
    Ok(())
}

/// Replaces panel p's bottom and solid by those of the intersection of its half-spaces.
fn clip_panel(
    frame: &Frame<'_>,
    p: usize,
    panel: &mut Panel,
    ids: &[u32],
    collapsed_edges: &HashSet<(u32, u32)>,
    eps: f64,
) -> Result<(), FabricationError> {
    let ring = panel.top.len();
    let mi = frame.m[p];
    let nrm = mi * frame.sigma;
    // A convex facet: every corner turns the same way (zero-length edges skipped).
    let short = FABRICATION_SHORT_EDGE * frame.diagonal;
    let corners: Vec<DVec3> = {
        let mut c: Vec<DVec3> = Vec::with_capacity(ring);
        for &x in &panel.top {
            if c.last().map_or(true, |l: &DVec3| (*l - x).length() > short) {
                c.push(x);
            }
        }
        while c.len() > 1 && (c[0] - c[c.len() - 1]).length() <= short {
            c.pop();
        }
        c
    };
    let nc = corners.len();
    for q in 0..nc {
        let (a, b, c) = (corners[q], corners[(q + 1) % nc], corners[(q + 2) % nc]);
        let turn = (b - a).cross(c - b).dot(nrm);
        if turn < -eps * frame.diagonal {
            return Err(frame.refuse(
                format!("panel {p}'s facet is not convex, so a collapsed bottom edge there cannot be resolved by clipping"),
            ));
        }
    }
    // Planes: 0 top, 1 bottom, 2 + k side k (identical planes share one index).
    let mut planes: Vec<(DVec3, f64)> = vec![(-mi, -frame.e[p]), (mi, frame.e[p] + frame.t)];
    let mut side_plane = Vec::with_capacity(ring);
    for s in &panel.sides {
        let (n, d) = (DVec3::new(s.plane[0], s.plane[1], s.plane[2]), s.plane[3]);
        let same = planes
            .iter()
            .position(|&(m, f)| (m - n).length() <= 1e-12 && (f - d).abs() <= eps);
        side_plane.push(same.unwrap_or_else(|| {
            planes.push((n, d));
            planes.len() - 1
        }));
    }
    let (mut vertices, faces) = convex_cell(&planes, eps);
    // Top face: exactly the facet (snap to the top vertices; every one must be a corner).
    for v in vertices.iter_mut() {
        if let Some(x) = panel.top.iter().find(|x| (**x - *v).length() <= eps) {
            *v = *x;
        }
    }
    let top_face = faces.iter().find(|f| f.0 == 0);
    let top_ok = top_face.is_some_and(|f| {
        f.1.len() == nc
            && corners
                .iter()
                .all(|c| f.1.iter().any(|&q| vertices[q as usize] == *c))
    });
    if !top_ok {
        return Err(frame.refuse(format!(
            "clipping panel {p} where a bottom edge collapsed would cut its top face"
        )));
    }
    let Some(bottom_face) = faces.iter().find(|f| f.0 == 1) else {
        return Err(frame.refuse(format!(
            "panel {p} has no bottom face left at this thickness: no solid exists"
        )));
    };
    // bottom[k]: the start of side k's bottom edge (along the top edge's direction).
    let on_bottom: Vec<u32> = bottom_face.1.clone();
    let mut start: Vec<Option<DVec3>> = vec![None; ring];
    for k in 0..ring {
        let (n, d) = planes[side_plane[k]];
        let along = (mi.cross(n) * frame.sigma).normalize_or_zero();
        let mut on: Vec<DVec3> = on_bottom
            .iter()
            .map(|&q| vertices[q as usize])
            .filter(|x| (n.dot(*x) - d).abs() <= eps)
            .collect();
        on.sort_by(|x, y| x.dot(along).total_cmp(&y.dot(along)));
        if on.len() >= 2 && (on[on.len() - 1] - on[0]).length() > eps {
            start[k] = Some(on[0]);
        }
    }
    let Some(first) = (0..ring).find(|&k| start[k].is_some()) else {
        return Err(frame.refuse(format!(
            "panel {p} has no bottom face left at this thickness: no solid exists"
        )));
    };
    let mut bottom = vec![DVec3::ZERO; ring];
    let mut next = start[first].unwrap_or_default();
    for step in 0..ring {
        let k = (first + ring - step) % ring;
        if let Some(x) = start[k] {
            next = x;
        } else {
            let k1 = (k + 1) % ring;
            let edge = (ids[k].min(ids[k1]), ids[k].max(ids[k1]));
            if ids[k] == ids[k1] || !collapsed_edges.contains(&edge) {
                return Err(frame.refuse(
                    format!(
                        "side {k} of panel {p} (neighbour {}) leaves the bottom face too: the collapse cascades, which clipping does not resolve",
                        panel.sides[k].neighbour.map_or("none".to_string(), |j| j.to_string())
                    ),
                ));
            }
        }
        bottom[k] = next;
    }
    panel.bottom = bottom;
    panel.solid = Polyhedron {
        vertices,
        faces: faces.into_iter().map(|f| f.1).collect(),
    };
    Ok(())
}

/// The convex cell `{x : n . x <= d for every plane}`: its vertices (points where three planes
/// meet, inside every half-space within `eps`, merged within `eps`) and, per plane with at
/// least three vertices on it, the face loop, counter-clockwise seen from outside.
pub(super) fn convex_cell(
    planes: &[(DVec3, f64)],
    eps: f64,
) -> (Vec<DVec3>, Vec<(usize, Vec<u32>)>) {
    let n = planes.len();
    let mut vertices: Vec<DVec3> = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            for c in b + 1..n {
                let ((na, da), (nb, db), (nc, dc)) = (planes[a], planes[b], planes[c]);
                let det = na.dot(nb.cross(nc));
                if det.abs() < FABRICATION_SINGULAR_TOLERANCE {
                    continue;
                }
                let x = (nb.cross(nc) * da + nc.cross(na) * db + na.cross(nb) * dc) / det;
                if !x.is_finite() || planes.iter().any(|&(m, f)| m.dot(x) > f + eps) {
                    continue;
                }
                if !vertices.iter().any(|v| (*v - x).length() <= eps) {
                    vertices.push(x);
                }
            }
        }
    }
    let mut faces = Vec::new();
    for (f, &(m, d)) in planes.iter().enumerate() {
        let on: Vec<u32> = (0..vertices.len() as u32)
            .filter(|&q| (m.dot(vertices[q as usize]) - d).abs() <= eps)
            .collect();
        if on.len() < 3 {
            continue;
        }
        let c = on.iter().map(|&q| vertices[q as usize]).sum::<DVec3>() / on.len() as f64;
        let u = m.any_orthonormal_vector();
        let w = m.cross(u);
        let angle = |q: u32| {
            let r = vertices[q as usize] - c;
            r.dot(w).atan2(r.dot(u))
        };
        let mut loop_ = on;
        loop_.sort_by(|&x, &y| angle(x).total_cmp(&angle(y)));
        faces.push((f, loop_));
    }
    (vertices, faces)
}
