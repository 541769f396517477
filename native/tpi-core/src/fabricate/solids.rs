//! Panel solids: offset vertices, side planes, angles, slots and the closed polyhedra
//! (geometry in the parent module's doc).

use std::collections::HashMap;

use glam::{DVec2, DVec3};

use super::clip;
use super::layout::Placement;
use super::{
    Cleat, FabricationDiagnostic, FabricationError, Panel, PanelSide, Polyhedron, Side, Slot,
    SlotPlan,
};
use crate::tolerance::{
    FABRICATION_MAX_VALENCE, FABRICATION_OUTLINE_MERGE, FABRICATION_PARALLEL_TOLERANCE,
    FABRICATION_SHORT_EDGE, FABRICATION_SINGULAR_TOLERANCE,
};
use crate::Discretisation;

/// Panels before slotting and nesting.
pub(super) struct Built {
    pub(super) panels: Vec<Panel>,
    pub(super) diagnostics: Vec<FabricationDiagnostic>,
    /// Bounding-box diagonal of the mesh.
    pub(super) diagonal: f64,
    /// Notches per panel: (side, s0, s1, depth), s along the side from `top[side]`.
    notches: Vec<Vec<(usize, f64, f64, f64)>>,
    /// Panels clipped where a bottom edge collapsed: their solid is already built (no slots).
    clipped: Vec<bool>,
}

/// `w` with `m_i . w = m_j . w = m_k . w = t` for the sorted triple (so every panel gets the
/// same bits), or None when the three normals are (nearly) coplanar.
fn triple_offset(m: &[DVec3], mut tri: [u32; 3], t: f64) -> Option<DVec3> {
    tri.sort_unstable();
    let [a, b, c] = tri.map(|q| m[q as usize]);
    let det = a.dot(b.cross(c));
    if det.abs() < FABRICATION_SINGULAR_TOLERANCE {
        return None;
    }
    Some((b.cross(c) + c.cross(a) + a.cross(b)) * (t / det))
}

/// `w` with `m . w = t`, `s1 . w = 0`, `s2 . w = 0`; with dependent side planes, the
/// least-norm `w` on the first one.
fn own_offset(m: DVec3, s1: DVec3, s2: DVec3, t: f64) -> DVec3 {
    let det = m.dot(s1.cross(s2));
    if det.abs() >= FABRICATION_SINGULAR_TOLERANCE {
        return s1.cross(s2) * (t / det);
    }
    let c = m.dot(s1);
    let q = 1.0 - c * c;
    if q <= FABRICATION_SINGULAR_TOLERANCE {
        return m * t;
    }
    (m - s1 * c) * (t / q)
}

/// Builds every panel (without slots; [`cut_slots`] adds them and the solids).
pub(super) fn build(
    mesh: &Discretisation,
    t: f64,
    side: PanelSide,
) -> Result<Built, FabricationError> {
    let n = mesh.facet_count();
    if n == 0 {
        return Err(FabricationError::BadMesh {
            reason: "it has no facets".into(),
        });
    }
    if mesh.facet_offsets.len() != n + 1 {
        return Err(FabricationError::BadMesh {
            reason: format!(
                "{} facet offsets for {} facets (expected {})",
                mesh.facet_offsets.len(),
                n,
                n + 1
            ),
        });
    }
    if mesh.facet_offsets.windows(2).any(|w| w[0] > w[1])
        || mesh.facet_offsets.last().map(|&l| l as usize) != Some(mesh.facet_loops.len())
    {
        return Err(FabricationError::BadMesh {
            reason: "the facet offsets do not describe the facet loops (decreasing, or not ending at the loops' length)".into(),
        });
    }
    for (q, v) in mesh.vertices.iter().enumerate() {
        if !v.is_finite() {
            return Err(FabricationError::BadMesh {
                reason: format!("vertex {q} is not finite ({v})"),
            });
        }
    }
    for i in 0..n {
        let f = mesh.facet(i);
        if f.len() < 3 {
            return Err(FabricationError::BadMesh {
                reason: format!("facet {i} has {} vertices (at least 3 needed)", f.len()),
            });
        }
        if let Some(&bad) = f.iter().find(|&&q| q as usize >= mesh.vertices.len()) {
            return Err(FabricationError::BadMesh {
                reason: format!("facet {i} names vertex {bad}, which does not exist"),
            });
        }
        let s = &mesh.seeds[i];
        if !s.normal.is_finite() || !s.point.is_finite() || s.normal.length() < 0.5 {
            return Err(FabricationError::BadMesh {
                reason: format!("facet {i} has no finite unit normal"),
            });
        }
    }
    let (lo, hi) = mesh.vertices.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    );
    let diagonal = (hi - lo).length().max(f64::MIN_POSITIVE);
    let short = FABRICATION_SHORT_EDGE * diagonal;

    // Directed edges -> (facet, side); neighbour of each side.
    let mut edges: HashMap<(u32, u32), u32> = HashMap::with_capacity(mesh.facet_loops.len());
    for i in 0..n {
        let f = mesh.facet(i);
        for k in 0..f.len() {
            edges.insert((f[k], f[(k + 1) % f.len()]), i as u32);
        }
    }
    let neighbours: Vec<Vec<Option<u32>>> = (0..n)
        .map(|i| {
            let f = mesh.facet(i);
            (0..f.len())
                .map(|k| {
                    edges
                        .get(&(f[(k + 1) % f.len()], f[k]))
                        .copied()
                        .filter(|&j| j as usize != i)
                })
                .collect()
        })
        .collect();

    // The concave side: where the neighbours' seeds lie.
    let mut lean = 0.0;
    for (i, around) in neighbours.iter().enumerate() {
        for j in around.iter().flatten() {
            let (si, sj) = (&mesh.seeds[i], &mesh.seeds[*j as usize]);
            lean += si.normal.normalize().dot(sj.point - si.point);
        }
    }
    let mut sigma = if lean >= 0.0 { 1.0 } else { -1.0 };
    if side == PanelSide::Outside {
        sigma = -sigma;
    }
    // Each panel's top plane is its facet's plane: the seed's tangent plane, or the adjusted
    // plane of `PlaneMode::Adjusted`.
    let planes: Vec<(DVec3, DVec3)> = (0..n).map(|i| mesh.facet_plane(i)).collect();
    let m: Vec<DVec3> = planes
        .iter()
        .map(|(_, normal)| normal.normalize() * sigma)
        .collect();
    let e: Vec<f64> = (0..n).map(|i| m[i].dot(planes[i].0)).collect();
    let centroid: Vec<DVec3> = (0..n)
        .map(|i| {
            let f = mesh.facet(i);
            f.iter().map(|&q| mesh.vertices[q as usize]).sum::<DVec3>() / f.len() as f64
        })
        .collect();

    let mut diagnostics = Vec::new();
    let mut parallel_seen = Vec::new();

    // Side plane (outward unit normal, offset) of side k of facet i, towards neighbour nb.
    let side_plane = |i: usize, a: DVec3, b: DVec3, nb: Option<u32>| -> (DVec3, f64, bool) {
        let mi = m[i];
        let dir = b - a;
        let outward = (dir.cross(mi) * sigma).normalize_or_zero();
        if let Some(j) = nb {
            let j = j as usize;
            let diff = mi - m[j];
            let len = diff.length();
            if len >= FABRICATION_PARALLEL_TOLERANCE {
                let s = diff / len;
                let d = (e[i] - e[j]) / len;
                // Orient outwards: by the edge's outward direction, or (zero-length edge)
                // away from the panel's centroid.
                let probe = if outward != DVec3::ZERO {
                    s.dot(outward)
                } else {
                    s.dot(a - centroid[i])
                };
                return if probe >= 0.0 {
                    (s, d, false)
                } else {
                    (-s, -d, false)
                };
            }
        }
        let s = if outward != DVec3::ZERO {
            outward
        } else {
            let away = a - centroid[i];
            (away - mi * mi.dot(away)).normalize_or(mi.any_orthonormal_vector())
        };
        (s, s.dot(a), nb.is_some())
    };

    let mut panels = Vec::with_capacity(n);
    let mut ring_ids: Vec<Vec<u32>> = Vec::with_capacity(n);
    for i in 0..n {
        let f = mesh.facet(i);
        let len = f.len();
        let pos = |q: usize| mesh.vertices[f[q % len] as usize];
        // Ring: (top, bottom, neighbour of the side that starts here).
        let mut top: Vec<DVec3> = Vec::with_capacity(len + 2);
        let mut bottom: Vec<DVec3> = Vec::with_capacity(len + 2);
        let mut side_nb: Vec<Option<u32>> = Vec::with_capacity(len + 2);
        let mut ids: Vec<u32> = Vec::with_capacity(len + 2);
        for k in 0..len {
            let v = pos(k);
            let prev_nb = neighbours[i][(k + len - 1) % len];
            let next_nb = neighbours[i][k];
            let fan = walk_fan(mesh, &neighbours, i, k);
            match fan {
                Some(fan) if fan.len() >= 3 => {
                    let mf = fan.len();
                    let root_at = (0..mf).min_by_key(|&q| fan[q]).unwrap_or(0);
                    let g: Vec<u32> = (0..mf).map(|q| fan[(root_at + q) % mf]).collect();
                    let r = g[0];
                    let j = (mf - root_at) % mf; // index of panel i in g
                    let seq: Vec<u32> = if j == 0 {
                        g[1..].iter().rev().copied().collect()
                    } else {
                        let mut s = vec![g[j - 1], r, g[(j + 1) % mf]];
                        s.dedup();
                        s
                    };
                    if mf > 3 && j == 0 {
                        diagnostics.push(FabricationDiagnostic::SplitVertex {
                            vertex: f[k],
                            panels: g.clone(),
                        });
                    }
                    for q in 0..seq.len() - 1 {
                        let w = triple_offset(&m, [i as u32, seq[q], seq[q + 1]], t)
                            .unwrap_or_else(|| {
                                let (s1, _, _) = side_plane(i, pos(k + len - 1), v, prev_nb);
                                let (s2, _, _) = side_plane(i, v, pos(k + 1), next_nb);
                                own_offset(m[i], s1, s2, t)
                            });
                        top.push(v);
                        ids.push(f[k]);
                        bottom.push(v + w);
                        side_nb.push(if q + 1 < seq.len() - 1 {
                            Some(seq[q + 1])
                        } else {
                            next_nb
                        });
                    }
                }
                _ => {
                    let (s1, _, _) = side_plane(i, pos(k + len - 1), v, prev_nb);
                    let (s2, _, _) = side_plane(i, v, pos(k + 1), next_nb);
                    top.push(v);
                    ids.push(f[k]);
                    bottom.push(v + own_offset(m[i], s1, s2, t));
                    side_nb.push(next_nb);
                }
            }
        }
        // Sides.
        let ring = top.len();
        let mut sides = Vec::with_capacity(ring);
        for k in 0..ring {
            let (a, b) = (top[k], top[(k + 1) % ring]);
            let nb = side_nb[k];
            let (s, d, parallel) = side_plane(i, a, b, nb);
            if parallel {
                if let Some(j) = nb {
                    let pair = [(i as u32).min(j), (i as u32).max(j)];
                    if !parallel_seen.contains(&pair) {
                        parallel_seen.push(pair);
                        diagnostics
                            .push(FabricationDiagnostic::ParallelNeighbours { panels: pair });
                    }
                }
            }
            let dihedral_deg = nb.map(|j| {
                let mj = m[j as usize];
                let theta = m[i].cross(mj).length().atan2(m[i].dot(mj)).to_degrees();
                if m[i].dot(centroid[j as usize] - a) >= 0.0 {
                    180.0 - theta
                } else {
                    180.0 + theta
                }
            });
            sides.push(Side {
                neighbour: nb,
                plane: [s.x, s.y, s.z, d],
                dihedral_deg,
                bevel_deg: s.dot(m[i]).clamp(-1.0, 1.0).asin().to_degrees(),
                length: (b - a).length(),
            });
        }
        let tol = FABRICATION_OUTLINE_MERGE * diagonal;
        let part = flat_part(i, &top, &bottom, m[i] * sigma, short, tol)?;
        if part.widened {
            diagnostics.push(FabricationDiagnostic::BottomOutsideTop { panel: i as u32 });
        }
        if let Some(&flags) = mesh.facet_flags.get(i) {
            if flags & crate::INVALID_FLAGS != 0 {
                diagnostics.push(FabricationDiagnostic::InvalidFacet {
                    panel: i as u32,
                    flags,
                });
            }
        }
        panels.push(Panel {
            seed: i as u32,
            normal: m[i],
            top,
            bottom,
            sides,
            frame: part.frame,
            flat: part.flat,
            flat_bottom: part.flat_bottom,
            cut_outline: part.cut_outline,
            slots: Vec::new(),
            placement: Placement::default(),
            solid: Polyhedron::default(),
        });
        ring_ids.push(ids);
    }

    // Thickness limit: where a bottom edge collapses (its offset vertices meet at T_max <= T),
    // the panels around it are clipped instead (clip.rs).
    let mut worst: Option<(f64, u32, Option<u32>)> = None;
    let mut collapsed: Vec<(usize, usize, f64)> = Vec::new();
    for (i, p) in panels.iter().enumerate() {
        let ring = p.top.len();
        for k in 0..ring {
            let k1 = (k + 1) % ring;
            let top_edge = p.top[k1] - p.top[k];
            let l = top_edge.length();
            if l <= short {
                continue;
            }
            let d = top_edge / l;
            let shrink = -((p.bottom[k1] - p.top[k1]) - (p.bottom[k] - p.top[k])).dot(d) / t;
            if shrink > 0.0 {
                let max = l / shrink;
                if worst.map_or(true, |(w, _, _)| max < w) {
                    worst = Some((max, p.seed, p.sides[k].neighbour));
                }
                if t >= max {
                    collapsed.push((i, k, max));
                }
            }
        }
    }
    let mut clipped = vec![false; panels.len()];
    if let (false, Some(worst)) = (collapsed.is_empty(), worst) {
        let frame = clip::Frame {
            mesh,
            neighbours: &neighbours,
            m: &m,
            e: &e,
            centroid: &centroid,
            sigma,
            t,
            diagonal,
            worst,
        };
        clipped = clip::resolve(
            &frame,
            &mut panels,
            &mut ring_ids,
            &collapsed,
            &mut diagnostics,
        )?;
    }
    let notches = vec![Vec::new(); panels.len()];
    Ok(Built {
        panels,
        diagnostics,
        diagonal,
        notches,
        clipped,
    })
}

/// The flat frame, outlines and cut outline of a panel.
pub(super) struct FlatPart {
    pub(super) frame: (DVec3, DVec3, DVec3),
    pub(super) flat: Vec<DVec2>,
    pub(super) flat_bottom: Vec<DVec2>,
    pub(super) cut_outline: Vec<DVec2>,
    /// The cut outline reaches outside the top outline (a negative bevel).
    pub(super) widened: bool,
}

/// Lays panel `i` flat (see the module doc): `nrm` is the facet's normal (`m_i s`), `short`
/// the zero edge length, `tol` the outline merge distance.
pub(super) fn flat_part(
    i: usize,
    top: &[DVec3],
    bottom: &[DVec3],
    nrm: DVec3,
    short: f64,
    tol: f64,
) -> Result<FlatPart, FabricationError> {
    let ring = top.len();
    let origin = top[0];
    let e1 = (1..=ring)
        .map(|q| top[q % ring] - top[q - 1])
        .find(|d| d.length() > short)
        .map(|d| d.normalize())
        .unwrap_or_else(|| nrm.any_orthonormal_vector());
    let e2 = nrm.cross(e1).normalize();
    let to_flat = |x: DVec3| DVec2::new((x - origin).dot(e1), (x - origin).dot(e2));
    let flat: Vec<DVec2> = top.iter().map(|&x| to_flat(x)).collect();
    let flat_bottom: Vec<DVec2> = bottom.iter().map(|&x| to_flat(x)).collect();
    let mut outline: Vec<DVec2> = Vec::with_capacity(ring);
    for &p in &flat {
        if outline.last().map_or(true, |q| (*q - p).length() > tol) {
            outline.push(p);
        }
    }
    while outline.len() > 1 && (outline[0] - outline[outline.len() - 1]).length() <= tol {
        outline.pop();
    }
    if outline.len() < 3 {
        return Err(FabricationError::BadMesh {
            reason: format!(
                "facet {i} is degenerate: fewer than 3 of its vertices are apart by more than {tol}"
            ),
        });
    }
    // The outline a vertical cut must follow: each side's top edge line, moved out to the
    // side's bottom edge where that lies outside (a negative bevel); consecutive lines
    // meet at the corners. Without negative bevels this is the top outline itself.
    let mut lines: Vec<(DVec2, DVec2)> = Vec::with_capacity(ring); // (point, direction)
    let mut widened = false;
    for k in 0..ring {
        let k1 = (k + 1) % ring;
        let e = flat[k1] - flat[k];
        if e.length() <= tol {
            continue;
        }
        let d = e.normalize();
        let out = DVec2::new(d.y, -d.x);
        // The bottom points of this side and of every side of zero length at its two ends
        // (a split vertex, or two panels meeting below a collapsed edge).
        let push = (0..ring)
            .filter(|&q| {
                q == k
                    || q == k1
                    || (flat[q] - flat[k]).length() <= tol
                    || (flat[q] - flat[k1]).length() <= tol
            })
            .map(|q| (flat_bottom[q] - flat[k]).dot(out))
            .fold(0.0, f64::max);
        if push > tol {
            widened = true;
        }
        lines.push((flat[k] + out * push, d));
    }
    let cut_outline = if widened {
        let n_lines = lines.len();
        let mut corners: Vec<DVec2> = Vec::with_capacity(n_lines);
        for q in 0..n_lines {
            let (p0, d0) = lines[(q + n_lines - 1) % n_lines];
            let (p1, d1) = lines[q];
            let cross = d0.perp_dot(d1);
            let corner = if cross.abs() <= 1e-12 {
                p1
            } else {
                // p0 + a d0 = p1 + b d1
                p0 + d0 * ((p1 - p0).perp_dot(d1) / cross)
            };
            if corners
                .last()
                .map_or(true, |c| (*c - corner).length() > tol)
            {
                corners.push(corner);
            }
        }
        while corners.len() > 1 && (corners[0] - corners[corners.len() - 1]).length() <= tol {
            corners.pop();
        }
        corners
    } else {
        outline
    };
    Ok(FlatPart {
        frame: (origin, e1, e2),
        flat,
        flat_bottom,
        cut_outline,
        widened,
    })
}

/// The panels around the vertex at position k of facet i, walking across each panel's side
/// that starts at the vertex; None when the walk reaches the boundary (or breaks).
pub(super) fn walk_fan(
    mesh: &Discretisation,
    neighbours: &[Vec<Option<u32>>],
    i: usize,
    k: usize,
) -> Option<Vec<u32>> {
    let v = mesh.facet(i)[k];
    let mut fan = vec![i as u32];
    let (mut cur, mut pos) = (i, k);
    loop {
        let next = neighbours[cur][pos]?;
        if next as usize == i {
            return Some(fan);
        }
        if fan.len() >= FABRICATION_MAX_VALENCE || fan.contains(&next) {
            return None;
        }
        pos = mesh.facet(next as usize).iter().position(|&q| q == v)?;
        fan.push(next);
        cur = next as usize;
    }
}

/// Adds the slots of `plan` to the panels, builds every panel's solid and returns the cleats.
pub(super) fn cut_slots(
    built: &mut Built,
    plan: &SlotPlan,
    length: f64,
    depth: f64,
) -> Result<Vec<Cleat>, FabricationError> {
    let short = FABRICATION_SHORT_EDGE * built.diagonal;
    // Requests: (a, b, t).
    let mut requests: Vec<(u32, u32, f64)> = Vec::new();
    match plan {
        SlotPlan::None => {}
        SlotPlan::Even(count) => {
            for p in &built.panels {
                for s in &p.sides {
                    if let Some(j) = s.neighbour {
                        if p.seed < j && s.length > short {
                            for q in 1..=*count {
                                requests.push((p.seed, j, f64::from(q) / f64::from(count + 1)));
                            }
                        }
                    }
                }
            }
        }
        SlotPlan::Explicit(list) => {
            for ([a, b], ts) in list {
                for &t in ts {
                    requests.push((*a, *b, t));
                }
            }
        }
    }
    let mut cleats = Vec::with_capacity(requests.len());
    for (a, b, t) in requests {
        let bad = |reason: String| FabricationError::BadSlot { a, b, t, reason };
        if !(t > 0.0 && t < 1.0) {
            return Err(bad("t must lie strictly between 0 and 1".into()));
        }
        let find = |x: u32, y: u32| -> Option<usize> {
            let p = built.panels.get(x as usize)?;
            (0..p.sides.len())
                .filter(|&k| p.sides[k].neighbour == Some(y))
                .max_by(|&k, &l| p.sides[k].length.total_cmp(&p.sides[l].length))
        };
        let (Some(ka), Some(kb)) = (find(a, b), find(b, a)) else {
            return Err(bad(format!("panels {a} and {b} are not neighbours")));
        };
        if built.clipped[a as usize] || built.clipped[b as usize] {
            if matches!(plan, SlotPlan::Even(_)) {
                built
                    .diagnostics
                    .push(FabricationDiagnostic::SlotSkipped { panels: [a, b], t });
                continue;
            }
            let c = if built.clipped[a as usize] { a } else { b };
            return Err(bad(format!(
                "panel {c} is clipped where a bottom edge collapsed (edge_collapsed diagnostic), and clipped panels take no slots"
            )));
        }
        let pa = &built.panels[a as usize];
        let pb = &built.panels[b as usize];
        let ring_a = pa.top.len();
        let (p0, p1) = (pa.top[ka], pa.top[(ka + 1) % ring_a]);
        let edge_len = (p1 - p0).length();
        if edge_len <= short {
            return Err(bad("the edge has zero length".into()));
        }
        let d = (p1 - p0) / edge_len;
        let centre = t * edge_len;
        let (s0, s1) = (centre - length / 2.0, centre + length / 2.0);
        // The span both faces of both panels offer, along d from p0.
        let ba0 = (pa.bottom[ka] - p0).dot(d);
        let ba1 = (pa.bottom[(ka + 1) % ring_a] - p0).dot(d);
        let ring_b = pb.top.len();
        let bb0 = (pb.bottom[kb] - p0).dot(d);
        let bb1 = (pb.bottom[(kb + 1) % ring_b] - p0).dot(d);
        let lo = 0f64.max(ba0).max(bb1);
        let hi = edge_len.min(ba1).min(bb0);
        if s0 < lo || s1 > hi {
            if matches!(plan, SlotPlan::Even(_)) {
                built
                    .diagnostics
                    .push(FabricationDiagnostic::SlotSkipped { panels: [a, b], t });
                continue;
            }
            return Err(bad(format!(
                "a slot of length {length} at {centre} needs [{s0}, {s1}] along the edge, and the edge offers [{lo}, {hi}] on both faces of both panels"
            )));
        }
        // Inward directions in each panel's plane, and the bottom line of the joint.
        let ua = -(d.cross(pa.normal)).normalize() * outward_sign(pa, ka);
        let ub = -((-d).cross(pb.normal)).normalize() * outward_sign(pb, kb);
        let bottom_at = |s: f64| pa.bottom[ka] + d * (s - ba0);
        let section = |s: f64| {
            let (top, bot) = (p0 + d * s, bottom_at(s));
            [
                top + ua * depth,
                top,
                top + ub * depth,
                bot + ub * depth,
                bot,
                bot + ua * depth,
            ]
        };
        let (c0, c1) = (section(s0), section(s1));
        let mut solid = Polyhedron {
            vertices: c0.iter().chain(c1.iter()).copied().collect(),
            faces: vec![(0..6).rev().collect(), (6..12).collect()],
        };
        for q in 0..6u32 {
            let q1 = (q + 1) % 6;
            solid.faces.push(vec![q, q1, q1 + 6, q + 6]);
        }
        orient_outward(&mut solid);
        // The notches, in each panel's own coordinates along its side.
        let pa_flat = |x: DVec3| flat_of(pa, x);
        let pb_flat = |x: DVec3| flat_of(pb, x);
        let slot_a = Slot {
            side: ka,
            neighbour: b,
            at: centre,
            length,
            depth,
            flat: [
                pa_flat(p0 + d * s0),
                pa_flat(p0 + d * s0 + ua * depth),
                pa_flat(p0 + d * s1 + ua * depth),
                pa_flat(p0 + d * s1),
            ]
            .map(|p| [p.x, p.y]),
        };
        let q0 = pb.top[kb];
        let r = (q0 - p0).dot(d);
        let (sb0, sb1) = (r - s1, r - s0);
        let slot_b = Slot {
            side: kb,
            neighbour: a,
            at: (sb0 + sb1) / 2.0,
            length,
            depth,
            flat: [
                pb_flat(q0 - d * sb0),
                pb_flat(q0 - d * sb0 + ub * depth),
                pb_flat(q0 - d * sb1 + ub * depth),
                pb_flat(q0 - d * sb1),
            ]
            .map(|p| [p.x, p.y]),
        };
        let notches = [(a, (ka, s0, s1)), (b, (kb, sb0, sb1))];
        let overlaps = notches.iter().any(|&(panel, (k, n0, n1))| {
            built.notches[panel as usize]
                .iter()
                .any(|&(k2, x0, x1, _)| k2 == k && x0 < n1 && n0 < x1)
        });
        if overlaps {
            if matches!(plan, SlotPlan::Even(_)) {
                built
                    .diagnostics
                    .push(FabricationDiagnostic::SlotSkipped { panels: [a, b], t });
                continue;
            }
            return Err(bad("it overlaps another slot on the same edge".into()));
        }
        for (panel, (k, n0, n1)) in notches {
            built.notches[panel as usize].push((k, n0, n1, depth));
        }
        built.panels[a as usize].slots.push(slot_a);
        built.panels[b as usize].slots.push(slot_b);
        cleats.push(Cleat {
            panels: [a.min(b), a.max(b)],
            t,
            solid,
        });
    }
    for ((p, notches), &clipped) in built
        .panels
        .iter_mut()
        .zip(&built.notches)
        .zip(&built.clipped)
    {
        if !clipped {
            p.solid = panel_solid(p, notches);
        }
    }
    Ok(cleats)
}

/// +1 when `d x normal` points out of the panel across side k, else -1.
fn outward_sign(p: &Panel, k: usize) -> f64 {
    let ring = p.top.len();
    let d = p.top[(k + 1) % ring] - p.top[k];
    let o = d.cross(p.normal);
    let c = p.top.iter().sum::<DVec3>() / ring as f64;
    if o.dot(p.top[k] - c) >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

fn flat_of(p: &Panel, x: DVec3) -> DVec2 {
    let (o, e1, e2) = p.frame;
    DVec2::new((x - o).dot(e1), (x - o).dot(e2))
}

/// The closed solid of a panel with its notches: the ring of (top, bottom) pairs, with four
/// pairs inserted per notch, gives the top face, the bottom face and one quad per ring edge.
fn panel_solid(p: &Panel, notches: &[(usize, f64, f64, f64)]) -> Polyhedron {
    let ring = p.top.len();
    let mut pairs: Vec<(DVec3, DVec3)> = Vec::with_capacity(ring + 4 * notches.len());
    for k in 0..ring {
        pairs.push((p.top[k], p.bottom[k]));
        let mut here: Vec<&(usize, f64, f64, f64)> = notches.iter().filter(|n| n.0 == k).collect();
        if here.is_empty() {
            continue;
        }
        here.sort_by(|x, y| x.1.total_cmp(&y.1));
        let a = p.top[k];
        let d = (p.top[(k + 1) % ring] - a).normalize();
        let u = -(d.cross(p.normal)).normalize() * outward_sign(p, k);
        let b0 = (p.bottom[k] - a).dot(d);
        for &&(_, s0, s1, depth) in &here {
            let top = |s: f64| a + d * s;
            let bot = |s: f64| p.bottom[k] + d * (s - b0);
            pairs.push((top(s0), bot(s0)));
            pairs.push((top(s0) + u * depth, bot(s0) + u * depth));
            pairs.push((top(s1) + u * depth, bot(s1) + u * depth));
            pairs.push((top(s1), bot(s1)));
        }
    }
    let count = pairs.len();
    let mut vertices: Vec<DVec3> = Vec::with_capacity(2 * count);
    let mut top_idx = Vec::with_capacity(count);
    for (q, &(t, _)) in pairs.iter().enumerate() {
        if q > 0 && pairs[q - 1].0 == t {
            top_idx.push(top_idx[q - 1]);
        } else {
            top_idx.push(vertices.len() as u32);
            vertices.push(t);
        }
    }
    if count > 1 && pairs[count - 1].0 == pairs[0].0 {
        let (last, first) = (top_idx[count - 1], top_idx[0]);
        for x in top_idx.iter_mut() {
            if *x == last {
                *x = first;
            }
        }
    }
    let bot_idx: Vec<u32> = pairs
        .iter()
        .map(|&(_, b)| {
            vertices.push(b);
            vertices.len() as u32 - 1
        })
        .collect();
    let mut faces = Vec::with_capacity(count + 2);
    faces.push(top_idx.iter().rev().copied().collect::<Vec<u32>>());
    faces.push(bot_idx.clone());
    for q in 0..count {
        let q1 = (q + 1) % count;
        faces.push(vec![top_idx[q], top_idx[q1], bot_idx[q1], bot_idx[q]]);
    }
    let faces = faces
        .into_iter()
        .map(|f| {
            let mut g: Vec<u32> = Vec::with_capacity(f.len());
            for x in f {
                if g.last() != Some(&x) {
                    g.push(x);
                }
            }
            while g.len() > 1 && g.first() == g.last() {
                g.pop();
            }
            g
        })
        .filter(|f| f.len() >= 3)
        .collect();
    let mut solid = Polyhedron { vertices, faces };
    orient_outward(&mut solid);
    solid
}

fn orient_outward(solid: &mut Polyhedron) {
    if solid.volume() < 0.0 {
        for f in &mut solid.faces {
            f.reverse();
        }
    }
}
