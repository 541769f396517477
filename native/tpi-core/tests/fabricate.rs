//! Fabrication checked against geometry computed here, independently of `fabricate`: the
//! facet planes come from the discretisation's seeds, planes of faces from Newell's method,
//! volumes by the divergence theorem against the prismatoid formula and closed forms, flat
//! parts by pairwise distances, and the nesting by the `geo` crate.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;
use std::path::Path;

use geo::{Contains, Distance, Euclidean, Intersects};
use glam::{DVec2, DVec3};
use tpi_core::{
    discretise, fabricate, Discretisation, DiscretiseOptions, FabricateOptions, Fabrication,
    FabricationDiagnostic, FabricationError, Generator, PanelSide, Polyhedron, Seed, SlotPlan,
    SurfaceSpec, ToolpathOptions, Units, VertexKind,
};

const TOL: f64 = 1e-9;

fn sample_mesh(surface: &str, pattern: &str) -> Discretisation {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../samples")
        .join(surface);
    let text = std::fs::read_to_string(&path).unwrap();
    let model = SurfaceSpec::from_json(&text, surface)
        .unwrap()
        .build()
        .unwrap();
    let pattern = Generator::parse(pattern).unwrap().generate();
    discretise(&model, &pattern.uv, &DiscretiseOptions::default()).unwrap()
}

fn diagonal(mesh: &Discretisation) -> f64 {
    let (lo, hi) = mesh.vertices.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    );
    (hi - lo).length()
}

/// Newell's normal (area vector) of a 3D polygon.
fn area_vector(p: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for k in 0..p.len() {
        n += p[k].cross(p[(k + 1) % p.len()]);
    }
    n / 2.0
}

fn volume_by_divergence(s: &Polyhedron) -> f64 {
    // Each face: (area vector . any face point) / 3.
    s.faces
        .iter()
        .map(|f| {
            let pts: Vec<DVec3> = f.iter().map(|&q| s.vertices[q as usize]).collect();
            area_vector(&pts).dot(pts[0]) / 3.0
        })
        .sum()
}

/// Every face planar within `tol`; every edge used once in each direction.
fn check_closed_planar(s: &Polyhedron, tol: f64, what: &str) {
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    for (q, f) in s.faces.iter().enumerate() {
        let pts: Vec<DVec3> = f.iter().map(|&x| s.vertices[x as usize]).collect();
        let a = area_vector(&pts);
        assert!(a.length() > 0.0, "{what}: face {q} has zero area");
        let n = a.normalize();
        let c = pts.iter().sum::<DVec3>() / pts.len() as f64;
        for p in &pts {
            let off = n.dot(*p - c).abs();
            assert!(off <= tol, "{what}: face {q} not planar ({off})");
        }
        for k in 0..f.len() {
            *edges.entry((f[k], f[(k + 1) % f.len()])).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &edges {
        assert_eq!(count, 1, "{what}: edge {a}->{b} used {count} times");
        assert_eq!(
            edges.get(&(b, a)),
            Some(&1),
            "{what}: edge {a}->{b} has no opposite (solid not closed)"
        );
    }
    assert!(s.volume() > 0.0, "{what}: faces not outward");
}

/// All the solid checks of one fabrication of `mesh`.
fn check_panels(mesh: &Discretisation, fab: &Fabrication, t: f64, expect_side: f64) {
    // Panels clipped where a bottom edge collapsed (named by the diagnostics): their volume is
    // checked against an independent cell in `clipped_panels_are_the_cells_of_the_nearest_plane`,
    // not the prismatoid formula.
    let mut clipped = std::collections::HashSet::new();
    let mut joined_pairs = std::collections::HashSet::new();
    for d in &fab.diagnostics {
        if let FabricationDiagnostic::EdgeCollapsed {
            panel,
            neighbour,
            joined,
            ..
        } = d
        {
            clipped.insert(*panel);
            clipped.extend(neighbour.iter().copied());
            clipped.extend(joined.iter().flatten().copied());
            joined_pairs.extend(joined.iter().copied());
        }
    }
    let diag = diagonal(mesh);
    let tol = TOL * diag;
    let mut shared_interior_sides = 0;
    // Each facet's plane, measured from its vertices (Newell's normal, oriented like the
    // seed's): the tangent plane, or the adjusted one.
    let planes: Vec<(DVec3, DVec3)> = (0..mesh.facet_count())
        .map(|i| {
            let corners: Vec<DVec3> = mesh
                .facet(i)
                .iter()
                .map(|&q| mesh.vertices[q as usize])
                .collect();
            let mut n = area_vector(&corners).normalize();
            if n.dot(mesh.seeds[i].normal) < 0.0 {
                n = -n;
            }
            let origin = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
            (origin, n)
        })
        .collect();
    for (i, p) in fab.panels.iter().enumerate() {
        let (origin, n) = planes[i];
        // Bottom at distance T from the top plane, on the expected side.
        assert_eq!(p.top.len(), p.bottom.len());
        for b in &p.bottom {
            let dist = n.dot(*b - origin) * expect_side;
            assert!(
                (dist - t).abs() <= tol,
                "panel {i}: bottom at {dist}, not {t}"
            );
        }
        for v in &p.top {
            assert!(
                n.dot(*v - origin).abs() <= tol,
                "panel {i}: top off its plane"
            );
        }
        // Each top vertex is a vertex of the facet, in order.
        let facet: Vec<DVec3> = mesh
            .facet(i)
            .iter()
            .map(|&q| mesh.vertices[q as usize])
            .collect();
        let mut dedup = p.top.clone();
        dedup.dedup();
        if dedup.len() > 1 && dedup.first() == dedup.last() {
            dedup.pop();
        }
        assert_eq!(dedup.len(), facet.len(), "panel {i}: top is not the facet");
        let start = facet.iter().position(|v| *v == dedup[0]).unwrap();
        for k in 0..facet.len() {
            assert_eq!(dedup[k], facet[(start + k) % facet.len()], "panel {i}");
        }
        check_closed_planar(&p.solid, tol, &format!("panel {i}"));
        // Prismatoid volume against the divergence theorem.
        let a_top = area_vector(&p.top).length();
        let a_bot = area_vector(&p.bottom).length();
        let mid: Vec<DVec3> = p
            .top
            .iter()
            .zip(&p.bottom)
            .map(|(a, b)| (*a + *b) / 2.0)
            .collect();
        let a_mid = area_vector(&mid).length();
        let prismatoid = t * (a_top + 4.0 * a_mid + a_bot) / 6.0;
        let div = volume_by_divergence(&p.solid);
        assert!(
            clipped.contains(&(i as u32))
                || (div - prismatoid).abs() <= 1e-9 * prismatoid.max(t * a_top),
            "panel {i}: volume {div} vs prismatoid {prismatoid}"
        );
        // Side planes: the side face's four points lie on the reported plane; interior
        // sides lie on the bisector of the two seeds' tangent planes.
        let ring = p.top.len();
        for k in 0..ring {
            let k1 = (k + 1) % ring;
            let s = &p.sides[k];
            let sn = DVec3::new(s.plane[0], s.plane[1], s.plane[2]);
            assert!((sn.length() - 1.0).abs() < 1e-12);
            // A side whose bottom edge collapsed (clipped panels) has bottom[k] = bottom[k+1],
            // not on its plane: its face is the triangle of the top edge and the apex.
            let collapsed = (p.bottom[k] - p.bottom[k1]).length() <= tol && p.top[k] != p.top[k1];
            // A side of zero top length where two panels meet below a collapsed edge lies
            // below the top: its face is the triangle of its bottom edge and the apex.
            let below = p.top[k] == p.top[k1]
                && s.neighbour
                    .is_some_and(|j| joined_pairs.contains(&[j.min(i as u32), j.max(i as u32)]));
            let corners = if below {
                vec![p.bottom[k], p.bottom[k1]]
            } else if collapsed {
                assert!(
                    clipped.contains(&(i as u32)),
                    "panel {i}: side {k} collapsed"
                );
                vec![p.top[k], p.top[k1]]
            } else {
                vec![p.top[k], p.top[k1], p.bottom[k], p.bottom[k1]]
            };
            for &q in &corners {
                assert!(
                    (sn.dot(q) - s.plane[3]).abs() <= tol,
                    "panel {i} side {k} off its plane"
                );
            }
            let Some(j) = s.neighbour else {
                // Square: contains the normal.
                assert!(sn.dot(n).abs() <= 1e-9, "panel {i} side {k} not square");
                continue;
            };
            let (oj, nj) = planes[j as usize];
            // Independent bisector: points x with n.(x - p_i) = nj.(x - p_j).
            for &q in &corners {
                let r = n.dot(q - origin) - nj.dot(q - oj);
                assert!(
                    r.abs() <= 2.0 * tol,
                    "panel {i} side {k}: not on the bisector ({r})"
                );
            }
            // The neighbour's side over the same edge: the same plane, opposite normal.
            let pj = &fab.panels[j as usize];
            let rj = pj.top.len();
            // (A side of zero top length where two panels meet below a collapsed edge starts at
            // another vertex in each panel.)
            let Some(kj) = (0..rj)
                .find(|&l| {
                    pj.sides[l].neighbour == Some(i as u32)
                        && pj.top[l] == p.top[k1]
                        && pj.top[(l + 1) % rj] == p.top[k]
                })
                .or_else(|| {
                    (0..rj).find(|&l| {
                        clipped.contains(&(i as u32))
                            && p.top[k] == p.top[k1]
                            && pj.sides[l].neighbour == Some(i as u32)
                            && pj.top[l] == pj.top[(l + 1) % rj]
                    })
                })
            else {
                panic!("panel {i} side {k}: panel {j} has no side over the same edge");
            };
            let o = &pj.sides[kj].plane;
            for c in 0..4 {
                assert!(
                    (o[c] + s.plane[c]).abs() <= tol.max(1e-12),
                    "panel {i}/{j}: planes differ"
                );
            }
            // No gap, no overlap: where both ends are interior vertices, the two side faces
            // have the same corners.
            let ends_interior = [k, k1].iter().all(|&e| {
                let v = p.top[e];
                mesh.vertices
                    .iter()
                    .position(|w| *w == v)
                    .map(|q| mesh.vertex_kinds[q] == VertexKind::Interior)
                    .unwrap_or(false)
            });
            let kj1 = (kj + 1) % rj;
            let collapsed_j =
                (pj.bottom[kj] - pj.bottom[kj1]).length() <= tol && pj.top[kj] != pj.top[kj1];
            assert_eq!(collapsed, collapsed_j, "panel {i}/{j}: one side collapsed");
            if ends_interior && !collapsed {
                assert!(
                    (pj.bottom[kj1] - p.bottom[k]).length() <= tol,
                    "panel {i}/{j}: bottom corner differs"
                );
                assert!(
                    (pj.bottom[kj] - p.bottom[k1]).length() <= tol,
                    "panel {i}/{j}: bottom corner differs"
                );
                shared_interior_sides += 1;
            }
        }
        // The flat part is congruent to the top face.
        for a in 0..ring {
            for b in a + 1..ring {
                let d3 = (p.top[a] - p.top[b]).length();
                let d2 = (p.flat[a] - p.flat[b]).length();
                assert!(
                    (d3 - d2).abs() <= tol,
                    "panel {i}: flat distance {d2} vs {d3}"
                );
            }
        }
        // The cut outline holds the top and the bottom seen along the normal, and is no
        // larger than the top widened by the outward reach of the bottom along its perimeter
        // (so a non-convex facet keeps its shape: no convex hull).
        let cut = geo_polygon(&p.cut_outline);
        let mut reach: f64 = 0.0;
        for (a, b) in p.flat.iter().zip(&p.flat_bottom) {
            let q = geo::Point::new(a.x, a.y);
            assert!(
                Euclidean::distance(&q, &cut) <= tol,
                "panel {i}: top outside the cut"
            );
            let q = geo::Point::new(b.x, b.y);
            assert!(
                Euclidean::distance(&q, &cut) <= tol,
                "panel {i}: bottom outside the cut"
            );
            reach = reach.max((*b - *a).length());
        }
        let perimeter: f64 = (0..ring)
            .map(|k| (p.flat[(k + 1) % ring] - p.flat[k]).length())
            .sum();
        let grown = signed_area(&p.cut_outline) - signed_area(&p.flat);
        assert!(
            grown >= -tol && grown <= perimeter * reach + reach * reach * ring as f64 + tol,
            "panel {i}: cut outline grows the top by {grown}"
        );
        assert!(
            signed_area(&p.flat) > 0.0,
            "panel {i}: flat outline not counter-clockwise"
        );
    }
    assert!(shared_interior_sides > 0, "no interior side was compared");
}

fn signed_area(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|k| p[k].perp_dot(p[(k + 1) % p.len()]))
        .sum::<f64>()
        / 2.0
}

fn geo_polygon(points: &[DVec2]) -> geo::Polygon<f64> {
    geo::Polygon::new(
        geo::LineString::from(points.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>()),
        vec![],
    )
}

fn check_nesting(fab: &Fabrication) {
    let mut on_sheet: Vec<Vec<(usize, geo::Polygon<f64>)>> = vec![Vec::new(); fab.sheets.len()];
    for (i, p) in fab.panels.iter().enumerate() {
        let pl = p.placement;
        let placed: Vec<DVec2> = p.cut_outline.iter().map(|&q| pl.apply(q)).collect();
        // Rotation and translation as documented: sheet = R(angle) flat + (x, y).
        let (s, c) = pl.angle_deg.to_radians().sin_cos();
        let q0 = p.cut_outline[0];
        let by_hand = DVec2::new(c * q0.x - s * q0.y + pl.x, s * q0.x + c * q0.y + pl.y);
        assert!((by_hand - placed[0]).length() < 1e-12);
        let size = fab.sheets[pl.sheet].size;
        let inner = geo::Rect::new(
            (fab.gap - 1e-9, fab.gap - 1e-9),
            (size[0] - fab.gap + 1e-9, size[1] - fab.gap + 1e-9),
        )
        .to_polygon();
        let poly = geo_polygon(&placed);
        assert!(inner.contains(&poly), "panel {i} leaves its sheet's margin");
        on_sheet[pl.sheet].push((i, poly));
    }
    for parts in &on_sheet {
        for a in 0..parts.len() {
            for b in a + 1..parts.len() {
                let (pa, pb) = (&parts[a].1, &parts[b].1);
                assert!(
                    !pa.intersects(pb),
                    "parts {} and {} overlap",
                    parts[a].0,
                    parts[b].0
                );
                let d = Euclidean::distance(pa, pb);
                assert!(
                    d >= fab.gap - 1e-9,
                    "parts {} and {} are {d} apart, less than the gap {}",
                    parts[a].0,
                    parts[b].0,
                    fab.gap
                );
            }
        }
    }
    for s in &fab.sheets {
        assert!(s.utilisation > 0.0 && s.utilisation <= 1.0);
    }
}

#[test]
fn paraboloid_dome_panels_are_exact_offsets_with_mitres() {
    let mesh = sample_mesh("paraboloid.json", "hex:12x10");
    let t = 0.05;
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            sheet: [3.0, 1.5],
            gap: 0.03,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    assert_eq!(fab.panels.len(), mesh.facet_count());
    // The dome z = -0.08 (x^2 + y^2) bends downwards: its concave side is -z, so the normal
    // (+z here) side is the outside; the default goes inside.
    let up = mesh.seeds[0].normal.z.signum();
    check_panels(&mesh, &fab, t, -up);
    check_nesting(&fab);
    // Concave side: every mitre narrows the panel (positive bevel), dihedral below 180.
    for p in &fab.panels {
        for s in &p.sides {
            if let Some(d) = s.dihedral_deg {
                assert!(d < 180.0 && s.bevel_deg > 0.0, "{d} {}", s.bevel_deg);
                assert!((180.0 - d - 2.0 * s.bevel_deg).abs() < 1e-9);
            }
        }
    }
    // Outside: the other side, still exact.
    let out = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            side: PanelSide::Outside,
            sheet: [3.0, 1.5],
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    check_panels(&mesh, &out, t, up);
}

#[test]
fn saddle_panels_are_exact_too() {
    let mesh = sample_mesh("hypar.json", "hex:10x10");
    let diag = diagonal(&mesh);
    let t = 0.005 * diag;
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            sheet: [diag, diag / 2.0],
            gap: t,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    let side = fab.panels[0].normal.dot(mesh.seeds[0].normal).signum();
    check_panels(&mesh, &fab, t, side);
    check_nesting(&fab);
}

/// With adjusted planes (a mixed roof, where a few planes are tilted) each panel is the
/// exact offset of its facet's own plane, with the same mitres.
#[test]
fn panels_follow_adjusted_planes() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../samples/mixed-roof.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let model = SurfaceSpec::from_json(&text, "mixed-roof.json")
        .unwrap()
        .build()
        .unwrap();
    let pattern = Generator::parse("hex:30x24").unwrap().generate();
    let options = DiscretiseOptions {
        planes: tpi_core::PlaneMode::Adjusted,
        ..DiscretiseOptions::default()
    };
    let mesh = discretise(&model, &pattern.uv, &options).unwrap();
    let tilted = mesh
        .plane_adjustments
        .iter()
        .filter(|a| a.tilt_degrees > 0.0)
        .count();
    assert!(tilted > 0, "the case needs adjusted planes");
    let diag = diagonal(&mesh);
    let t = 2e-5 * diag;
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            sheet: [diag, diag / 2.0],
            gap: t,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    let side = fab.panels[0].normal.dot(mesh.seeds[0].normal).signum();
    check_panels(&mesh, &fab, t, side);
}

/// Two rectangles w x L folded along the y axis, each rising at angle alpha: a V.
fn v_fold(w: f64, l: f64, alpha: f64) -> Discretisation {
    let (c, s) = (alpha.cos(), alpha.sin());
    let vertices = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(0.0, l, 0.0),
        DVec3::new(-w * c, l, w * s),
        DVec3::new(-w * c, 0.0, w * s),
        DVec3::new(w * c, 0.0, w * s),
        DVec3::new(w * c, l, w * s),
    ];
    let seed = |normal: DVec3, point: DVec3| Seed {
        uv: [0.0, 0.0],
        point,
        normal,
        curvatures: [0.0, 0.0],
    };
    Discretisation {
        vertex_kinds: vec![VertexKind::Boundary; vertices.len()],
        facet_offsets: vec![0, 4, 8],
        facet_loops: vec![0, 1, 2, 3, 0, 4, 5, 1],
        seeds: vec![
            seed(DVec3::new(s, 0.0, c), (vertices[0] + vertices[2]) / 2.0),
            seed(DVec3::new(-s, 0.0, c), (vertices[0] + vertices[5]) / 2.0),
        ],
        vertices,
        ..Discretisation::default()
    }
}

#[test]
fn v_fold_volumes_and_angles_match_the_closed_form() {
    let (w, l, alpha, t) = (0.7, 1.3, 0.3f64, 0.05);
    let mesh = v_fold(w, l, alpha);
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    for p in &fab.panels {
        check_closed_planar(&p.solid, 1e-12, "v fold");
        // Section: top w, bottom w - T tan(alpha) (mitre at the fold, square at the far end).
        let closed = l * (t * w - t * t * alpha.tan() / 2.0);
        assert!(
            (p.solid.volume() - closed).abs() < 1e-14,
            "{} vs {closed}",
            p.solid.volume()
        );
        assert!((volume_by_divergence(&p.solid) - closed).abs() < 1e-14);
        let fold = p.sides.iter().find(|s| s.neighbour.is_some()).unwrap();
        assert!((fold.bevel_deg - alpha.to_degrees()).abs() < 1e-12);
        assert!((fold.dihedral_deg.unwrap() - (180.0 - 2.0 * alpha.to_degrees())).abs() < 1e-12);
        // The mitre is the plane x = 0.
        assert!(fold.plane[0].abs() > 1.0 - 1e-15 && fold.plane[3].abs() < 1e-15);
        for s in p.sides.iter().filter(|s| s.neighbour.is_none()) {
            assert_eq!(s.bevel_deg, 0.0);
        }
    }
    // Outside (convex side): the section widens, w + T tan(alpha) at the bottom.
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            side: PanelSide::Outside,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    for p in &fab.panels {
        let closed = l * (t * w + t * t * alpha.tan() / 2.0);
        assert!((p.solid.volume() - closed).abs() < 1e-14);
        let fold = p.sides.iter().find(|s| s.neighbour.is_some()).unwrap();
        assert!((fold.bevel_deg + alpha.to_degrees()).abs() < 1e-12);
        assert!((fold.dihedral_deg.unwrap() - (180.0 + 2.0 * alpha.to_degrees())).abs() < 1e-12);
    }
}

#[test]
fn slots_are_notches_of_volume_l_d_t_and_cleats_fill_both() {
    let (w, l, alpha, t) = (0.7, 1.3, 0.3f64, 0.05);
    let mesh = v_fold(w, l, alpha);
    let plain = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    let (sl, sd) = (0.12, 0.08);
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            slots: SlotPlan::Even(3),
            slot_length: Some(sl),
            slot_depth: Some(sd),
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    assert_eq!(fab.cleats.len(), 3);
    for (p, q) in fab.panels.iter().zip(&plain.panels) {
        assert_eq!(p.slots.len(), 3);
        check_closed_planar(&p.solid, 1e-12, "notched panel");
        let removed = q.solid.volume() - volume_by_divergence(&p.solid);
        assert!(
            (removed - 3.0 * sl * sd * t).abs() < 1e-14,
            "removed {removed}"
        );
    }
    let mut centres = Vec::new();
    for c in &fab.cleats {
        check_closed_planar(&c.solid, 1e-12, "cleat");
        assert!((volume_by_divergence(&c.solid) - 2.0 * sl * sd * t).abs() < 1e-14);
        let centre = c.solid.vertices.iter().sum::<DVec3>() / 12.0;
        centres.push(centre.y);
        // The cleat fills the two notches: each of its vertices is a vertex of a notched panel.
        for v in &c.solid.vertices {
            assert!(fab.panels.iter().any(|p| p
                .solid
                .vertices
                .iter()
                .any(|u| (*u - *v).length() < 1e-12)));
        }
    }
    centres.sort_by(f64::total_cmp);
    for (q, y) in centres.iter().enumerate() {
        // Evenly spaced at t = 1/4, 1/2, 3/4 of the edge (its direction either way).
        let expected = l * (q as f64 + 1.0) / 4.0;
        assert!((y - expected).abs() < 1e-12, "{y} vs {expected}");
    }
    // An explicit plan names its edges; a wrong one is refused with its name.
    let err = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            slots: SlotPlan::from_json(r#"{"slots": [{"edge": [0, 1], "at": [1.5]}]}"#, "s.json")
                .unwrap(),
            ..FabricateOptions::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(err, FabricationError::BadSlot { a: 0, b: 1, .. }),
        "{err}"
    );
    assert!(SlotPlan::from_json(r#"{"slot": []}"#, "s.json").is_err());
}

#[test]
fn bad_thickness_is_refused_with_a_reason() {
    let mesh = v_fold(0.7, 1.3, 0.3);
    for bad in [f64::NAN, -0.1, 0.0, f64::INFINITY] {
        let err = fabricate(
            &mesh,
            &FabricateOptions {
                thickness: bad,
                ..FabricateOptions::default()
            },
        )
        .unwrap_err();
        assert!(
            matches!(
                err,
                FabricationError::InvalidOption {
                    field: "thickness",
                    ..
                }
            ),
            "{bad}: {err}"
        );
    }
    // The fold's bottom edge from the mitre to the far end has length w - T tan(alpha): it
    // collapses at T = w / tan(alpha).
    let max = 0.7 / 0.3f64.tan();
    let err = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: max * 1.01,
            sheet: [100.0, 100.0],
            ..FabricateOptions::default()
        },
    )
    .unwrap_err();
    match err {
        FabricationError::ThicknessTooLarge { max: m, .. } => {
            assert!((m - max).abs() < 1e-12, "{m} vs {max}")
        }
        other => panic!("{other}"),
    }
    assert!(fabricate(
        &mesh,
        &FabricateOptions {
            thickness: max * 0.99,
            sheet: [100.0, 100.0],
            ..FabricateOptions::default()
        }
    )
    .is_ok());
    // A part larger than the sheet is named.
    let err = fabricate(
        &mesh,
        &FabricateOptions {
            sheet: [0.5, 0.5],
            ..FabricateOptions::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(err, FabricationError::PartTooLarge { .. }),
        "{err}"
    );
}

#[test]
fn poisson_patterns_on_the_nurbs_dome_and_the_saddle() {
    for (surface, pattern, relative) in [
        ("nurbs-dome.json", "poisson:0.03:seed=7", 0.004),
        ("saddle.json", "poisson:0.03:seed=7", 0.002),
    ] {
        let mesh = sample_mesh(surface, pattern);
        let diag = diagonal(&mesh);
        let t = relative * diag;
        let fab = fabricate(
            &mesh,
            &FabricateOptions {
                thickness: t,
                sheet: [diag, diag / 2.0],
                gap: 0.002 * diag,
                ..FabricateOptions::default()
            },
        )
        .unwrap();
        let side = fab.panels[0].normal.dot(mesh.seeds[0].normal).signum();
        check_panels(&mesh, &fab, t, side);
        check_nesting(&fab);
    }
}

#[test]
fn a_thickness_beyond_a_short_edge_is_named() {
    // Random patterns leave short edges; their bottom edges collapse early.
    let mesh = sample_mesh("hypar.json", "random:400:seed=1");
    let err = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: 0.5,
            sheet: [100.0, 100.0],
            ..FabricateOptions::default()
        },
    )
    .unwrap_err();
    let FabricationError::ThicknessTooLarge { max, panel, .. } = err else {
        panic!("{err}");
    };
    assert!(max < 0.5 && (panel as usize) < mesh.facet_count());
    // Just below the limit, every bottom edge keeps its direction.
    let t = max * 0.999;
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            sheet: [100.0, 100.0],
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    for p in &fab.panels {
        let r = p.top.len();
        for k in 0..r {
            let top = p.top[(k + 1) % r] - p.top[k];
            let bottom = p.bottom[(k + 1) % r] - p.bottom[k];
            if top.length() > 1e-9 {
                assert!(
                    top.dot(bottom) > 0.0,
                    "panel {}: bottom edge {k} reversed",
                    p.seed
                );
            }
        }
    }
}

fn workshop() -> (Discretisation, Fabrication) {
    let mesh = sample_mesh("paraboloid.json", "hex:12x10");
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: 0.05,
            slots: SlotPlan::Even(1),
            slot_length: Some(0.1),
            slot_depth: Some(0.06),
            sheet: [3.0, 1.5],
            gap: 0.03,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    (mesh, fab)
}

#[test]
fn toolpath_runs_one_tool_radius_outside_every_outline() {
    let (_, fab) = workshop();
    assert!(fab.cleats.len() > 10);
    check_toolpath(&fab, 0.008);
    // A saddle: non-convex outlines, so reflex corners too.
    let mesh = sample_mesh("hypar.json", "hex:10x10");
    let diag = diagonal(&mesh);
    let saddle = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: 0.005 * diag,
            sheet: [diag, diag / 2.0],
            gap: 0.01 * diag,
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    let reflex = saddle
        .panels
        .iter()
        .filter(|p| {
            let c = &p.cut_outline;
            let n = c.len();
            (0..n).any(|k| (c[k] - c[(k + n - 1) % n]).perp_dot(c[(k + 1) % n] - c[k]) < 0.0)
        })
        .count();
    assert!(reflex > 0, "no non-convex outline to test");
    check_toolpath(&saddle, 0.004 * diag);
}

fn check_toolpath(fab: &Fabrication, d: f64) {
    let code = fab
        .gcode(&ToolpathOptions {
            tool_diameter: d,
            ..ToolpathOptions::default()
        })
        .unwrap();
    let r = d / 2.0;
    let mut sheet = 0usize;
    let mut part: Option<usize> = None;
    let mut pos = DVec2::ZERO;
    let mut z = 0.0;
    let mut measured = 0usize;
    let mut worst: f64 = 0.0;
    let outlines: Vec<geo::LineString<f64>> = fab
        .panels
        .iter()
        .map(|p| {
            let mut pts: Vec<(f64, f64)> = p
                .cut_outline
                .iter()
                .map(|&q| {
                    let s = p.placement.apply(q);
                    (s.x, s.y)
                })
                .collect();
            pts.push(pts[0]);
            geo::LineString::from(pts)
        })
        .collect();
    let word = |line: &str, c: char| -> Option<f64> {
        line.split_whitespace()
            .find(|w| w.starts_with(c))
            .and_then(|w| w[1..].parse().ok())
    };
    for line in code.lines() {
        if let Some(rest) = line.strip_prefix("(tpi fabricate: sheet ") {
            sheet = rest.split_whitespace().next().unwrap().parse().unwrap();
            continue;
        }
        if let Some(rest) = line.strip_prefix("(part ") {
            let mut w = rest.split_whitespace();
            let seed: usize = w.next().unwrap().parse().unwrap();
            part = (w.next() == Some("profile)")).then_some(seed);
            if let Some(q) = part {
                assert_eq!(fab.panels[q].placement.sheet, sheet);
            }
            continue;
        }
        let (x, y) = (word(line, 'X'), word(line, 'Y'));
        if let Some(nz) = word(line, 'Z') {
            z = nz;
        }
        let to = DVec2::new(x.unwrap_or(pos.x), y.unwrap_or(pos.y));
        let cutting = z < 0.0 && (line.starts_with("G1") || line.starts_with("G3"));
        if let (Some(q), true) = (part, cutting && (x.is_some() || y.is_some())) {
            let samples: Vec<DVec2> = if line.starts_with("G3") {
                let c = pos + DVec2::new(word(line, 'I').unwrap(), word(line, 'J').unwrap());
                assert!(((pos - c).length() - r).abs() < 1e-8, "arc radius");
                let a0 = (pos - c).y.atan2((pos - c).x);
                let mut a1 = (to - c).y.atan2((to - c).x);
                if a1 < a0 {
                    a1 += std::f64::consts::TAU;
                }
                (0..=16)
                    .map(|s| {
                        let a = a0 + (a1 - a0) * s as f64 / 16.0;
                        c + DVec2::new(a.cos(), a.sin()) * r
                    })
                    .collect()
            } else {
                (0..=16)
                    .map(|s| pos + (to - pos) * (s as f64 / 16.0))
                    .collect()
            };
            let poly = geo::Polygon::new(outlines[q].clone(), vec![]);
            for p in samples {
                let pt = geo::Point::new(p.x, p.y);
                assert!(
                    !poly.contains(&pt),
                    "part {q}: the tool enters the part at {p}"
                );
                let dist = Euclidean::distance(&pt, &outlines[q]);
                worst = worst.max((dist - r).abs());
                measured += 1;
            }
        }
        pos = to;
    }
    assert!(measured > 1000, "{measured} samples");
    assert!(
        worst < 1e-8,
        "the toolpath strays {worst} from one tool radius"
    );
    assert!(code.contains("G3 ") && code.ends_with("M30\n"));
    assert_eq!(
        code.matches(" slot)").count(),
        fab.panels.iter().map(|p| p.slots.len()).sum::<usize>()
    );
    // A gap the tool does not fit into is refused.
    let err = fab
        .gcode(&ToolpathOptions {
            tool_diameter: fab.gap * 1.5,
            ..ToolpathOptions::default()
        })
        .unwrap_err();
    assert!(
        matches!(err, FabricationError::InvalidOption { field: "gap", .. }),
        "{err}"
    );
}

#[test]
fn files_read_back() {
    let (_, fab) = workshop();
    // panels.json
    let json: serde_json::Value = serde_json::from_str(&fab.to_json()).unwrap();
    assert_eq!(json["thickness"], 0.05);
    let panels = json["panels"].as_array().unwrap();
    assert_eq!(panels.len(), fab.panels.len());
    for (p, v) in fab.panels.iter().zip(panels) {
        let top = v["top"].as_array().unwrap();
        assert_eq!(top.len(), v["bottom"].as_array().unwrap().len());
        assert_eq!(top.len(), v["sides"].as_array().unwrap().len());
        assert_eq!(top.len(), v["flat"].as_array().unwrap().len());
        assert_eq!(v["seed"], p.seed);
        let pl = &v["placement"];
        assert!(pl["sheet"].as_u64().unwrap() < fab.sheets.len() as u64);
        for s in v["sides"].as_array().unwrap() {
            assert_eq!(s["plane"].as_array().unwrap().len(), 4);
            assert_eq!(s["neighbour"].is_null(), s["dihedral_deg"].is_null());
        }
    }
    assert_eq!(json["sheets"].as_array().unwrap().len(), fab.sheets.len());
    // panels.obj: one closed object per panel and per cleat.
    let obj = fab.to_obj();
    let mut verts: Vec<DVec3> = Vec::new();
    let mut objects: Vec<(String, Vec<Vec<usize>>)> = Vec::new();
    for line in obj.lines() {
        let mut w = line.split_whitespace();
        match w.next() {
            Some("o") => objects.push((w.next().unwrap().to_string(), Vec::new())),
            Some("v") => {
                let c: Vec<f64> = w.map(|x| x.parse().unwrap()).collect();
                verts.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => objects
                .last_mut()
                .unwrap()
                .1
                .push(w.map(|x| x.parse::<usize>().unwrap() - 1).collect()),
            _ => {}
        }
    }
    assert_eq!(objects.len(), fab.panels.len() + fab.cleats.len());
    assert!(!fab.cleats.is_empty());
    for (name, faces) in &objects {
        let mut edges: HashMap<(usize, usize), i32> = HashMap::new();
        for f in faces {
            for k in 0..f.len() {
                *edges.entry((f[k], f[(k + 1) % f.len()])).or_default() += 1;
            }
        }
        for (&(a, b), &c) in &edges {
            assert!(
                c == 1 && edges.get(&(b, a)) == Some(&1),
                "{name}: open at {a}-{b}"
            );
        }
    }
    // bevels.csv: one row per side.
    let csv = fab.bevels_csv();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(
        rows[0],
        "panel,side,neighbour,length,dihedral_deg,bevel_deg"
    );
    assert_eq!(
        rows.len() - 1,
        fab.panels.iter().map(|p| p.sides.len()).sum::<usize>()
    );
    for r in &rows[1..] {
        let c: Vec<&str> = r.split(',').collect();
        assert_eq!(c.len(), 6);
        assert!(c[3].parse::<f64>().unwrap() >= 0.0);
        assert_eq!(c[2].is_empty(), c[4].is_empty());
    }
    // sheets.dxf: read back by ezdxf (tests/fabrication/read_dxf.py).
    check_dxf_with_ezdxf(&fab);
    let svg = fab.sheets_svg();
    assert_eq!(
        svg.matches("<polygon stroke=\"#c00\"").count(),
        fab.panels.len()
    );
    assert_eq!(svg.matches("<rect").count(), fab.sheets.len());
}

/// sheets.dxf read back by the `dxf` crate (an independent reader and writer; the entities
/// are written by our own code): R2000, `$INSUNITS` 4, the five layers, handles distinct and
/// below `$HANDSEED`; one closed SHEET rectangle per sheet (1.1 W apart), then per part in
/// seed order its closed CUT outline and closed BOTTOM outline placed on its sheet, its open
/// SLOT polylines, and ENGRAVE strokes inside its sheet; and the same polylines given to the
/// crate as entities (the way sheets.dxf was written before) make the very same text.
#[test]
fn dxf_reads_back_with_the_dxf_crate() {
    use dxf::entities::EntityType;
    let (_, fab) = workshop();
    let text = fab.sheets_dxf(Units::Millimetres).unwrap();
    let drawing = dxf::Drawing::load(&mut text.as_bytes()).unwrap();
    assert_eq!(drawing.header.version, dxf::enums::AcadVersion::R2000);
    assert_eq!(
        drawing.header.default_drawing_units,
        dxf::enums::Units::Millimeters
    );
    let layers: Vec<&str> = drawing.layers().map(|l| l.name.as_str()).collect();
    for layer in ["SHEET", "CUT", "BOTTOM", "SLOT", "ENGRAVE"] {
        assert!(layers.contains(&layer), "layer {layer} missing: {layers:?}");
    }
    let entities: Vec<(&str, bool, Vec<DVec2>, u64)> = drawing
        .entities()
        .map(|e| match &e.specific {
            EntityType::LwPolyline(l) => (
                e.common.layer.as_str(),
                l.is_closed(),
                l.vertices.iter().map(|v| DVec2::new(v.x, v.y)).collect(),
                e.common.handle.0,
            ),
            other => panic!("not an LWPOLYLINE: {other:?}"),
        })
        .collect();
    let mut handles: Vec<u64> = entities.iter().map(|e| e.3).collect();
    handles.extend(drawing.layers().map(|l| l.handle.0));
    handles.sort_unstable();
    let count = handles.len();
    handles.dedup();
    assert_eq!(handles.len(), count, "handles repeat");
    assert!(handles[0] > 0 && handles[count - 1] < drawing.header.next_available_handle.0);
    let mut offsets = vec![0.0];
    for s in &fab.sheets {
        offsets.push(offsets.last().unwrap() + 1.1 * s.size[0]);
    }
    let same = |a: &[DVec2], b: &[DVec2]| {
        a.len() == b.len() && a.iter().zip(b).all(|(p, q)| p.distance(*q) <= 1e-9)
    };
    let mut at = entities.iter();
    for (k, s) in fab.sheets.iter().enumerate() {
        let (x0, [w, h]) = (offsets[k], s.size);
        let (layer, closed, pts, _) = at.next().unwrap();
        let rect = [
            DVec2::new(x0, 0.0),
            DVec2::new(x0 + w, 0.0),
            DVec2::new(x0 + w, h),
            DVec2::new(x0, h),
        ];
        assert!(
            *layer == "SHEET" && *closed && same(pts, &rect),
            "sheet {k}"
        );
    }
    let mut rest = at.peekable();
    for p in &fab.panels {
        let pl = p.placement;
        let place = |q: DVec2| {
            let (sin, cos) = pl.angle_deg.to_radians().sin_cos();
            DVec2::new(
                cos * q.x - sin * q.y + pl.x + offsets[pl.sheet],
                sin * q.x + cos * q.y + pl.y,
            )
        };
        let want: Vec<DVec2> = p.cut_outline.iter().map(|&q| place(q)).collect();
        let (layer, closed, pts, _) = rest.next().unwrap();
        assert!(
            *layer == "CUT" && *closed && same(pts, &want),
            "panel {} cut",
            p.seed
        );
        let want: Vec<DVec2> = p.flat_bottom.iter().map(|&q| place(q)).collect();
        let (layer, closed, pts, _) = rest.next().unwrap();
        assert!(
            *layer == "BOTTOM" && *closed && same(pts, &want),
            "panel {} bottom",
            p.seed
        );
        for s in &p.slots {
            let want: Vec<DVec2> = s
                .flat
                .iter()
                .map(|&q| place(DVec2::from_array(q)))
                .collect();
            let (layer, closed, pts, _) = rest.next().unwrap();
            assert!(
                *layer == "SLOT" && !*closed && same(pts, &want),
                "panel {} slot",
                p.seed
            );
        }
        let mut strokes = 0;
        while let Some((_, _, pts, _)) = rest.next_if(|e| e.0 == "ENGRAVE") {
            strokes += 1;
            let (x0, [w, h]) = (offsets[pl.sheet], fab.sheets[pl.sheet].size);
            assert!(
                pts.iter()
                    .all(|q| q.x >= x0 && q.x <= x0 + w && q.y >= 0.0 && q.y <= h),
                "panel {}: a stroke off its sheet",
                p.seed
            );
        }
        assert!(strokes > 0, "panel {} has no label", p.seed);
    }
    assert!(rest.next().is_none());
    // The same polylines handed to the crate as entities (as sheets.dxf was made before its
    // entities were streamed) give the very same text.
    let mut rebuilt = dxf::Drawing::new();
    rebuilt.header.version = dxf::enums::AcadVersion::R2000;
    rebuilt.header.default_drawing_units = dxf::enums::Units::Millimeters;
    // A new drawing gets new random identifiers: the ones read are kept.
    rebuilt.header.fingerprint_guid = drawing.header.fingerprint_guid;
    rebuilt.header.version_guid = drawing.header.version_guid;
    for layer in drawing.layers().filter(|l| l.name != "0") {
        rebuilt.add_layer(dxf::tables::Layer {
            name: layer.name.clone(),
            color: layer.color.clone(),
            ..Default::default()
        });
    }
    for (layer, closed, pts, _) in &entities {
        let mut line = dxf::entities::LwPolyline::default();
        line.set_is_closed(*closed);
        line.vertices = pts
            .iter()
            .map(|p| dxf::LwPolylineVertex {
                x: p.x,
                y: p.y,
                ..Default::default()
            })
            .collect();
        let mut entity = dxf::entities::Entity::new(EntityType::LwPolyline(line));
        entity.common.layer = layer.to_string();
        rebuilt.add_entity(entity);
    }
    let mut bytes = Vec::new();
    rebuilt.save(&mut bytes).unwrap();
    let bytes = String::from_utf8(bytes).unwrap();
    // A new drawing is also stamped with the clock: the creation and update times differ
    // when a second passes between the two drawings, and only they may.
    assert!(
        text.lines().any(|l| l.trim() == "$TDUPDATE"),
        "sheets.dxf has no $TDUPDATE"
    );
    let (ours, theirs) = (without_timestamps(&bytes), without_timestamps(&text));
    if let Some(k) = ours.iter().zip(&theirs).position(|(a, b)| a != b) {
        panic!(
            "line {k}: the crate writes {:?}, sheets.dxf has {:?}",
            ours[k], theirs[k]
        );
    }
    assert_eq!(ours.len(), theirs.len());
}

/// The lines of a DXF text with the values of its date and time header variables
/// ($TDCREATE, $TDUCREATE, $TDUPDATE, $TDUUPDATE: group code, then value) left empty.
fn without_timestamps(text: &str) -> Vec<&str> {
    let mut lines: Vec<&str> = text.lines().collect();
    for k in 0..lines.len() {
        let name = lines[k].trim();
        if ["$TDCREATE", "$TDUCREATE", "$TDUPDATE", "$TDUUPDATE"].contains(&name)
            && k + 2 < lines.len()
        {
            lines[k + 2] = "";
        }
    }
    lines
}

/// sheets.dxf written in millimetres, read by ezdxf (Python, an independent reader): R2000,
/// `$INSUNITS` 4, layers CUT, SLOT and ENGRAVE, no audit error; every part's cut outline a
/// closed CUT polyline equal to its flat cut outline turned by `angle_deg` and moved by
/// `(x, y)` plus its sheet's offset (sheets 1.1 W apart), every slot an open SLOT polyline the
/// same way, every ENGRAVE stroke inside a sheet.
fn check_dxf_with_ezdxf(fab: &Fabrication) {
    let dxf = fab.sheets_dxf(Units::Millimetres).unwrap();
    let dir = std::env::temp_dir().join(format!("tpi-fabricate-dxf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("sheets.dxf");
    std::fs::write(&file, &dxf).unwrap();
    let python = std::env::var("TPI_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fabrication/read_dxf.py");
    let output = std::process::Command::new(&python)
        .arg(&script)
        .arg(&file)
        .output()
        .unwrap_or_else(|e| panic!("cannot run `{python}` ({e}); the DXF test needs Python 3 with ezdxf (`python3 -m pip install 'ezdxf==1.4.*'`) or TPI_PYTHON"));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        output.status.success(),
        "ezdxf could not read sheets.dxf (is ezdxf installed? `python3 -m pip install 'ezdxf==1.4.*'`):\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let read: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    assert_eq!(read["version"], "AC1015");
    assert_eq!(read["insunits"], 4);
    assert_eq!(read["audit_errors"], 0);
    let layers: Vec<&str> = read["layers"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap())
        .collect();
    for layer in ["CUT", "SLOT", "ENGRAVE"] {
        assert!(layers.contains(&layer), "layer {layer} missing: {layers:?}");
    }
    let polylines = read["polylines"].as_array().unwrap();
    let on = |layer: &str| -> Vec<(bool, Vec<DVec2>)> {
        polylines
            .iter()
            .filter(|p| p["layer"] == layer)
            .map(|p| {
                let pts = p["points"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|q| DVec2::new(q[0].as_f64().unwrap(), q[1].as_f64().unwrap()))
                    .collect();
                (p["closed"].as_bool().unwrap(), pts)
            })
            .collect()
    };
    let mut offsets = vec![0.0];
    for s in &fab.sheets {
        offsets.push(offsets.last().unwrap() + 1.1 * s.size[0]);
    }
    let place = |pl: &tpi_core::Placement, q: DVec2| {
        let (sin, cos) = pl.angle_deg.to_radians().sin_cos();
        DVec2::new(
            cos * q.x - sin * q.y + pl.x + offsets[pl.sheet],
            sin * q.x + cos * q.y + pl.y,
        )
    };
    let same = |a: &[DVec2], b: &[DVec2]| {
        a.len() == b.len() && a.iter().zip(b).all(|(p, q)| p.distance(*q) <= 1e-9)
    };
    let cut = on("CUT");
    assert_eq!(cut.len(), fab.panels.len());
    let slots = on("SLOT");
    assert_eq!(
        slots.len(),
        fab.panels.iter().map(|p| p.slots.len()).sum::<usize>()
    );
    assert!(!slots.is_empty());
    for p in &fab.panels {
        let want: Vec<DVec2> = p
            .cut_outline
            .iter()
            .map(|&q| place(&p.placement, q))
            .collect();
        assert!(
            cut.iter().any(|(closed, pts)| *closed && same(pts, &want)),
            "panel {}: its cut outline is not a closed CUT polyline of the DXF",
            p.seed
        );
        for s in &p.slots {
            let want: Vec<DVec2> = s
                .flat
                .iter()
                .map(|&q| place(&p.placement, DVec2::from_array(q)))
                .collect();
            assert!(
                slots
                    .iter()
                    .any(|(closed, pts)| !*closed && same(pts, &want)),
                "panel {}: slot at {} missing from SLOT",
                p.seed,
                s.at
            );
        }
    }
    let engrave = on("ENGRAVE");
    assert!(engrave.len() > fab.panels.len());
    for (_, pts) in &engrave {
        for q in pts {
            let k = offsets.iter().rposition(|&o| o <= q.x).unwrap();
            assert!(k < fab.sheets.len());
            let s = fab.sheets[k].size;
            assert!(
                q.x - offsets[k] <= s[0] && q.y >= 0.0 && q.y <= s[1],
                "stroke off its sheet: {q}"
            );
        }
    }
}

/// Four planar quads around one vertex: the 3 x 3 grid x in {-1, 0, 1.5}, y in {-0.7, 0, 1}
/// lifted to z = a x^2 + b y^2 (a sum f(x) + g(y) is planar over every grid rectangle), four
/// different planes through the centre whose offsets do not meet in a point.
fn four_quads(a: f64, b: f64) -> Discretisation {
    let z = |x: f64, y: f64| a * x * x + b * y * y;
    let mut vertices = Vec::new();
    for y in [-0.7, 0.0, 1.0] {
        for x in [-1.0, 0.0, 1.5] {
            vertices.push(DVec3::new(x, y, z(x, y)));
        }
    }
    let idx = |x: i32, y: i32| ((y + 1) * 3 + (x + 1)) as u32;
    let mut loops = Vec::new();
    let mut offsets = vec![0u32];
    let mut seeds = Vec::new();
    for (cx, cy) in [(-1, -1), (0, -1), (-1, 0), (0, 0)] {
        // Counter-clockwise seen from above.
        let quad = [
            idx(cx, cy),
            idx(cx + 1, cy),
            idx(cx + 1, cy + 1),
            idx(cx, cy + 1),
        ];
        let pts: Vec<DVec3> = quad.iter().map(|&q| vertices[q as usize]).collect();
        let normal = area_vector(&pts).normalize();
        loops.extend_from_slice(&quad);
        offsets.push(loops.len() as u32);
        seeds.push(Seed {
            uv: [0.0, 0.0],
            point: pts.iter().sum::<DVec3>() / 4.0,
            normal,
            curvatures: [0.0, 0.0],
        });
    }
    let mut kinds = vec![VertexKind::Boundary; 9];
    kinds[4] = VertexKind::Interior;
    Discretisation {
        vertices,
        vertex_kinds: kinds,
        facet_offsets: offsets,
        facet_loops: loops,
        seeds,
        ..Discretisation::default()
    }
}

#[test]
fn four_panels_at_a_vertex_are_split_the_same_way_for_all() {
    let mesh = four_quads(1.0, 0.8);
    for p in mesh.seeds.iter() {
        assert!(p.normal.z > 0.4);
    }
    let t = 0.2;
    let fab = fabricate(
        &mesh,
        &FabricateOptions {
            thickness: t,
            sheet: [5.0, 5.0],
            ..FabricateOptions::default()
        },
    )
    .unwrap();
    // The four offset planes do not meet in a point: an independent check.
    let m: Vec<DVec3> = mesh.seeds.iter().map(|s| s.normal).collect();
    let w = |i: usize, j: usize, k: usize| {
        let det = m[i].dot(m[j].cross(m[k]));
        (m[j].cross(m[k]) + m[k].cross(m[i]) + m[i].cross(m[j])) * (t / det)
    };
    assert!((w(0, 1, 2) - w(1, 2, 3)).length() > 1e-4);
    // The surface bends up (towards +z): the panels go up.
    check_panels(&mesh, &fab, t, 1.0);
    let split: Vec<_> = fab
        .diagnostics
        .iter()
        .filter_map(|d| match d {
            FabricationDiagnostic::SplitVertex { vertex, panels } => {
                Some((*vertex, panels.clone()))
            }
            _ => None,
        })
        .collect();
    assert_eq!(split.len(), 1, "{:?}", fab.diagnostics);
    assert_eq!(split[0].0, 4);
    assert_eq!(split[0].1.len(), 4);
    // Two panels (a diagonal pair) get a zero-length top edge, the other two do not.
    let zero: Vec<u32> = fab
        .panels
        .iter()
        .filter(|p| p.sides.iter().any(|s| s.length == 0.0))
        .map(|p| p.seed)
        .collect();
    assert_eq!(zero.len(), 2, "{zero:?}");
    assert!(fab
        .panels
        .iter()
        .all(|p| p.top.len() == 4 || p.top.len() == 5));
}

#[test]
fn absurd_counts_are_refused_not_attempted() {
    let mesh = v_fold(0.7, 1.3, 0.3);
    let err = fabricate(
        &mesh,
        &FabricateOptions {
            slots: SlotPlan::Even(u32::MAX),
            ..FabricateOptions::default()
        },
    )
    .unwrap_err();
    assert!(
        matches!(
            err,
            FabricationError::InvalidOption {
                field: "slots per edge",
                ..
            }
        ),
        "{err}"
    );
    let fab = fabricate(&mesh, &FabricateOptions::default()).unwrap();
    let err = fab
        .gcode(&ToolpathOptions {
            step_down: Some(1e-12),
            ..ToolpathOptions::default()
        })
        .unwrap_err();
    assert!(
        matches!(
            err,
            FabricationError::InvalidOption {
                field: "step down",
                ..
            }
        ),
        "{err}"
    );
}

/// Clips a convex polyhedron (outward face polygons) by the half-space `n . x <= d`
/// (Sutherland-Hodgman on every face, then the cap of the cut points): a different algorithm
/// from the core's enumeration of three-plane points.
fn clip_convex(faces: Vec<Vec<DVec3>>, n: DVec3, d: f64) -> Vec<Vec<DVec3>> {
    let mut out = Vec::with_capacity(faces.len() + 1);
    let mut cut: Vec<DVec3> = Vec::new();
    for f in faces {
        let mut g = Vec::with_capacity(f.len() + 1);
        for k in 0..f.len() {
            let (a, b) = (f[k], f[(k + 1) % f.len()]);
            let (sa, sb) = (n.dot(a) - d, n.dot(b) - d);
            if sa <= 0.0 {
                g.push(a);
            }
            if sa == 0.0 {
                cut.push(a);
            }
            if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
                let x = a + (b - a) * (sa / (sa - sb));
                g.push(x);
                cut.push(x);
            }
        }
        if g.len() >= 3 {
            out.push(g);
        }
    }
    if cut.len() >= 3 {
        let c = cut.iter().sum::<DVec3>() / cut.len() as f64;
        let u = n.any_orthonormal_vector();
        let w = n.cross(u);
        cut.sort_by(|x, y| {
            let (rx, ry) = (*x - c, *y - c);
            rx.dot(w)
                .atan2(rx.dot(u))
                .total_cmp(&ry.dot(w).atan2(ry.dot(u)))
        });
        out.push(cut);
    }
    out
}

/// The box `[lo, hi]` as outward face polygons.
fn box_faces(lo: DVec3, hi: DVec3) -> Vec<Vec<DVec3>> {
    let c = |x: usize, y: usize, z: usize| {
        DVec3::new(
            if x == 0 { lo.x } else { hi.x },
            if y == 0 { lo.y } else { hi.y },
            if z == 0 { lo.z } else { hi.z },
        )
    };
    vec![
        vec![c(0, 0, 0), c(0, 1, 0), c(1, 1, 0), c(1, 0, 0)],
        vec![c(0, 0, 1), c(1, 0, 1), c(1, 1, 1), c(0, 1, 1)],
        vec![c(0, 0, 0), c(1, 0, 0), c(1, 0, 1), c(0, 0, 1)],
        vec![c(0, 1, 0), c(0, 1, 1), c(1, 1, 1), c(1, 1, 0)],
        vec![c(0, 0, 0), c(0, 0, 1), c(0, 1, 1), c(0, 1, 0)],
        vec![c(1, 0, 0), c(1, 1, 0), c(1, 1, 1), c(1, 0, 1)],
    ]
}

#[test]
fn clipped_panels_are_the_cells_of_the_nearest_plane() {
    // A coarse hex pattern on the ellipsoid: at 1.5 times the thickness where its first bottom
    // edge collapses, 14 edges have collapsed; that thickness used to be refused.
    let mesh = sample_mesh("ellipsoid.json", "hex:7x6");
    let options = |t: f64| FabricateOptions {
        thickness: t,
        sheet: [100.0, 100.0],
        slots: SlotPlan::Even(1),
        ..FabricateOptions::default()
    };
    let FabricationError::ThicknessTooLarge { max, reason, .. } =
        fabricate(&mesh, &options(100.0)).unwrap_err()
    else {
        panic!("a thickness of 100 on the ellipsoid should leave no solid");
    };
    assert!(reason.contains("no solid"), "{reason}");
    let t = 1.5 * max;
    let fab = fabricate(&mesh, &options(t)).unwrap();
    let collapsed: Vec<_> = fab
        .diagnostics
        .iter()
        .filter_map(|d| match d {
            FabricationDiagnostic::EdgeCollapsed {
                panel,
                neighbour,
                at_thickness,
                joined,
                ..
            } => Some((*panel, *neighbour, *at_thickness, *joined)),
            _ => None,
        })
        .collect();
    assert!(collapsed.len() >= 5, "{collapsed:?}");
    assert!(collapsed.iter().any(|c| c.3.is_some()), "no edge flipped");
    for c in &collapsed {
        assert!(c.2 >= max * (1.0 - 1e-12) && c.2 <= t, "{c:?}");
    }
    let side = fab.panels[0].normal.dot(mesh.seeds[0].normal).signum();
    check_panels(&mesh, &fab, t, side);
    check_nesting(&fab);
    assert!(fab.to_json().contains("\"kind\":\"edge_collapsed\""));

    // Independently: on this K > 0 surface, thickened to its concave side, the panel of
    // facet p is the set of points at depth 0..T below its plane that lie no deeper below any
    // other facet's plane (the nearest plane wins; depths along each facet's normal). That
    // cell, clipped here from a box by every other facet's bisector, must be the solid: every
    // solid vertex inside it and the same volume. Checked for every panel with no boundary
    // side (a boundary side is cut square instead).
    let diag = diagonal(&mesh);
    let tol = TOL * diag;
    let planes: Vec<(DVec3, f64)> = (0..mesh.facet_count())
        .map(|i| {
            let corners: Vec<DVec3> = mesh
                .facet(i)
                .iter()
                .map(|&q| mesh.vertices[q as usize])
                .collect();
            let mut n = area_vector(&corners).normalize();
            if n.dot(mesh.seeds[i].normal) * side < 0.0 {
                n = -n;
            }
            let o = corners.iter().copied().sum::<DVec3>() / corners.len() as f64;
            (n, n.dot(o))
        })
        .collect();
    // Panels at a vertex where more than three panels meet (the poles) follow the split of
    // that vertex by the fan from the lowest seed, not the nearest plane: left out.
    let split: std::collections::HashSet<u32> = fab
        .diagnostics
        .iter()
        .filter_map(|d| match d {
            FabricationDiagnostic::SplitVertex { panels, .. } => Some(panels.clone()),
            _ => None,
        })
        .flatten()
        .collect();
    let mut checked = 0;
    let mut clipped_checked = 0;
    for (i, p) in fab.panels.iter().enumerate() {
        if p.sides.iter().any(|s| s.neighbour.is_none()) || split.contains(&(i as u32)) {
            continue;
        }
        let (n, e) = planes[i];
        let mut half: Vec<(DVec3, f64)> = vec![(-n, -e), (n, e + t)];
        for (q, &(nq, eq)) in planes.iter().enumerate() {
            if q != i && (n - nq).length() > 1e-9 {
                half.push((n - nq, e - eq));
            }
        }
        let (lo, hi) = p.top.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), v| (lo.min(*v), hi.max(*v)),
        );
        let mut cell = box_faces(lo - DVec3::splat(3.0 * t), hi + DVec3::splat(3.0 * t));
        for &(hn, hd) in &half {
            cell = clip_convex(cell, hn, hd);
        }
        let cell_volume: f64 = cell.iter().map(|f| area_vector(f).dot(f[0]) / 3.0).sum();
        let volume = volume_by_divergence(&p.solid);
        assert!(
            (volume - cell_volume).abs() <= 1e-9 * cell_volume,
            "panel {i}: volume {volume}, nearest-plane cell {cell_volume}"
        );
        for v in &p.solid.vertices {
            for &(hn, hd) in &half {
                let out = (hn.dot(*v) - hd) / hn.length();
                assert!(
                    out <= tol,
                    "panel {i}: vertex {v} outside its cell by {out}"
                );
            }
        }
        checked += 1;
        if collapsed.iter().any(|c| {
            c.0 == i as u32 || c.1 == Some(i as u32) || c.3.is_some_and(|j| j.contains(&(i as u32)))
        }) {
            clipped_checked += 1;
        }
    }
    println!("{checked} panels checked against their cell, {clipped_checked} of them clipped, {} edges collapsed", collapsed.len());
    assert!(
        checked >= 10 && clipped_checked >= 10,
        "{checked} {clipped_checked}"
    );
}
