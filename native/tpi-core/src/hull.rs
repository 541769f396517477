//! The convex hull of points in space, by randomised incremental insertion with a conflict
//! list, decided by exact orientation tests (Shewchuk's orient3d, the `robust` crate).
//!
//! Faces are kept counter-clockwise seen from outside: for a face (a, b, c), orient3d(a, b, c,
//! x) > 0 for every x strictly inside the hull. A point x sees the face when
//! orient3d(a, b, c, x) <= 0. Counting a point on a face's plane as seeing it is the
//! symbolic perturbation that pushes every point outwards, each later point (in insertion order)
//! further than all earlier ones: coplanar points (cocircular seeds on a sphere, a symmetric grid) all become
//! vertices, and every decision agrees with every other, so the hull is a closed triangulated
//! sphere whose vertices are every input point in convex position.
//!
//! Insertion of x (in Morton order of the points, so that consecutive points are near): a
//! walk from the last new face towards the face through which the ray from a fixed interior
//! point to x leaves the hull (orient3d against the planes through that point and each edge);
//! x sees that face unless it is inside. The faces it sees form a connected cap; the cap's
//! boundary, the horizon, is joined to x by new faces.

/// Points needed for a hull in space (a tetrahedron).
const HULL_MIN_POINTS: usize = 4;

/// A face of the hull: vertices counter-clockwise seen from outside, the face across each
/// edge (edge k runs from `v[k]` to `v[(k + 1) % 3]`).
#[derive(Clone, Debug)]
struct Face {
    v: [u32; 3],
    adjacent: [u32; 3],
    alive: bool,
}

/// Why no hull could be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum HullError {
    /// Fewer than four points, or all of them on one plane.
    Flat,
    /// The faces seen from a point did not form a disc (never for exact tests; kept so that
    /// a broken invariant is an error, not a panic).
    Inconsistent,
}

/// The hull's faces (counter-clockwise seen from outside), per face the face across the edge
/// opposite each of its vertices (as [`crate::triangulation::DualTriangulation`] keeps its
/// neighbours), and, per point, whether it is a vertex of the hull. Deterministic: after the
/// first four independent points, the points are inserted along a Morton curve of their
/// coordinates (so that each walk is short).
pub(crate) type Hull = (Vec<[u32; 3]>, Vec<[u32; 3]>, Vec<bool>);

/// See [`Hull`].
pub(crate) fn convex_hull(points: &[[f64; 3]]) -> Result<Hull, HullError> {
    if points.len() < HULL_MIN_POINTS {
        return Err(HullError::Flat);
    }
    let coord = |i: u32| {
        let [x, y, z] = points[i as usize];
        robust::Coord3D { x, y, z }
    };
    let orient =
        |a: u32, b: u32, c: u32, x: u32| robust::orient3d(coord(a), coord(b), coord(c), coord(x));
    let start = initial_tetrahedron(points, &orient).ok_or(HullError::Flat)?;
    // Orient the tetrahedron: (a, b, c) counter-clockwise from outside when d is inside.
    let [a, b, c, d] = start;
    let (b, c) = if orient(a, b, c, d) > 0.0 {
        (b, c)
    } else {
        (c, b)
    };
    // A point strictly inside every later hull: the walk's centre of projection.
    let centre = {
        let p = [a, b, c, d].map(|i| glam::DVec3::from_array(points[i as usize]));
        let m = (p[0] + p[1] + p[2] + p[3]) * 0.25;
        robust::Coord3D {
            x: m.x,
            y: m.y,
            z: m.z,
        }
    };
    // Whether the ray from the centre towards x passes on the inner side of the plane through
    // the centre and the directed edge (u, w) of a face counter-clockwise from outside.
    let inside_edge =
        |u: u32, w: u32, x: u32| robust::orient3d(centre, coord(u), coord(w), coord(x)) <= 0.0;
    let mut faces: Vec<Face> = Vec::new();
    // Faces opposite d, a, b, c; adjacency fixed up below.
    for v in [[a, b, c], [b, d, c], [c, d, a], [a, d, b]] {
        faces.push(Face {
            v,
            adjacent: [u32::MAX; 3],
            alive: true,
        });
    }
    link_all(&mut faces, &[0, 1, 2, 3]);
    let mut on_hull = vec![false; points.len()];
    for v in start {
        on_hull[v as usize] = true;
    }
    let mut order: Vec<u32> = (0..points.len() as u32)
        .filter(|&i| !on_hull[i as usize])
        .collect();
    let keys = morton_keys(points);
    order.sort_by_key(|&i| (keys[i as usize], i));
    let mut visible = Vec::new();
    let mut stack = Vec::new();
    let mut mark = vec![false; faces.len()];
    let mut last = 0u32;
    for x in order {
        // Walk towards the face the ray from the centre through x leaves the hull by.
        let mut f = last;
        let mut steps = 0usize;
        let exit = loop {
            let face = &faces[f as usize];
            let v = face.v;
            // Cross the first edge (from a rotating start, so the walk cannot cycle) whose
            // plane has x on its outer side.
            let rotate = steps % 3;
            let crossing = (0..3)
                .map(|k| (k + rotate) % 3)
                .find(|&k| !inside_edge(v[k], v[(k + 1) % 3], x));
            match crossing {
                None => break Some(f),
                Some(k) => f = face.adjacent[k],
            }
            steps += 1;
            if f as usize >= faces.len() || steps > faces.len() {
                break None;
            }
        };
        let Some(first) = exit else {
            return Err(HullError::Inconsistent);
        };
        if !sees(&faces[first as usize], x, &orient) {
            // Inside the hull: not a vertex.
            last = first;
            continue;
        }
        // The cap of faces x sees.
        visible.clear();
        stack.clear();
        mark.resize(faces.len(), false);
        stack.push(first);
        mark[first as usize] = true;
        while let Some(f) = stack.pop() {
            visible.push(f);
            for &g in &faces[f as usize].adjacent {
                if g as usize >= faces.len() {
                    return Err(HullError::Inconsistent);
                }
                if !mark[g as usize] && sees(&faces[g as usize], x, &orient) {
                    mark[g as usize] = true;
                    stack.push(g);
                }
            }
        }
        // Horizon edges (u, w) of visible faces whose neighbour is not visible, each with the
        // neighbour across it; a new face (u, w, x) per edge.
        let mut new_faces: Vec<u32> = Vec::new();
        for &f in &visible {
            for k in 0..3 {
                let g = faces[f as usize].adjacent[k];
                if mark[g as usize] {
                    continue;
                }
                let u = faces[f as usize].v[k];
                let w = faces[f as usize].v[(k + 1) % 3];
                let id = faces.len() as u32;
                faces.push(Face {
                    v: [u, w, x],
                    adjacent: [g, u32::MAX, u32::MAX],
                    alive: true,
                });
                // The neighbour now looks across (w, u) at the new face.
                let across = &mut faces[g as usize];
                let back = (0..3)
                    .find(|&j| across.v[j] == w && across.v[(j + 1) % 3] == u)
                    .ok_or(HullError::Inconsistent)?;
                across.adjacent[back] = id;
                new_faces.push(id);
            }
        }
        // New faces meet each other along (w, x) and (x, u).
        link_new(&mut faces, &new_faces)?;
        on_hull[x as usize] = true;
        for &f in &visible {
            faces[f as usize].alive = false;
            mark[f as usize] = false;
        }
        mark.resize(faces.len(), false);
        last = *new_faces.first().ok_or(HullError::Inconsistent)?;
    }
    // The live faces renumbered; a face's edge (k + 1, k + 2) is the one opposite vertex k.
    let mut index = vec![u32::MAX; faces.len()];
    let mut next = 0u32;
    for (f, face) in faces.iter().enumerate() {
        if face.alive {
            index[f] = next;
            next += 1;
        }
    }
    let live = faces.iter().filter(|f| f.alive);
    let triangles = live.clone().map(|f| f.v).collect();
    let neighbours = live
        .map(|f| {
            let across = |k: usize| index.get(f.adjacent[k] as usize).copied();
            match (across(1), across(2), across(0)) {
                (Some(a), Some(b), Some(c)) if [a, b, c].iter().all(|&x| x != u32::MAX) => {
                    Ok([a, b, c])
                }
                _ => Err(HullError::Inconsistent),
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok((triangles, neighbours, on_hull))
}

/// Morton (Z-order) keys of the points' coordinates quantised to 2^21 steps of their box.
fn morton_keys(points: &[[f64; 3]]) -> Vec<u64> {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let spread = |v: u64| {
        let mut x = v & 0x1f_ffff;
        x = (x | x << 32) & 0x1f_0000_0000_ffff;
        x = (x | x << 16) & 0x1f_0000_ff00_00ff;
        x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
        x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
        (x | x << 2) & 0x1249_2492_4924_9249
    };
    points
        .iter()
        .map(|p| {
            let q = |k: usize| {
                let t = if hi[k] > lo[k] {
                    (p[k] - lo[k]) / (hi[k] - lo[k])
                } else {
                    0.0
                };
                (t * ((1u64 << 21) - 1) as f64) as u64
            };
            spread(q(0)) | spread(q(1)) << 1 | spread(q(2)) << 2
        })
        .collect()
}

fn sees(face: &Face, x: u32, orient: &impl Fn(u32, u32, u32, u32) -> f64) -> bool {
    face.alive && orient(face.v[0], face.v[1], face.v[2], x) <= 0.0
}

/// Four points not on one plane: the first point, the next distinct one, the next not on
/// their line, the first other one not on their plane.
fn initial_tetrahedron(
    points: &[[f64; 3]],
    orient: &impl Fn(u32, u32, u32, u32) -> f64,
) -> Option<[u32; 4]> {
    let n = points.len() as u32;
    let a = 0u32;
    let b = (1..n).find(|&i| points[i as usize] != points[a as usize])?;
    let collinear = |c: u32| {
        let [p, q, r] = [a, b, c].map(|i| glam::DVec3::from_array(points[i as usize]));
        (q - p).cross(r - p) == glam::DVec3::ZERO
    };
    let c = (b + 1..n).find(|&c| !collinear(c))?;
    let d = (b + 1..n).find(|&d| d != c && orient(a, b, c, d) != 0.0)?;
    Some([a, b, c, d])
}

/// Sets the adjacency among the given faces by their shared edges.
fn link_all(faces: &mut [Face], ids: &[u32]) {
    for &f in ids {
        for k in 0..3 {
            let (u, w) = (faces[f as usize].v[k], faces[f as usize].v[(k + 1) % 3]);
            if let Some(&g) = ids.iter().find(|&&g| {
                let v = faces[g as usize].v;
                (0..3).any(|j| v[j] == w && v[(j + 1) % 3] == u)
            }) {
                faces[f as usize].adjacent[k] = g;
            }
        }
    }
}

/// Links the new faces (u, w, x) of one insertion around x: face (u, w, x)'s edge (w, x)
/// meets the face whose edge (x, w) is (x, u') with u' = w.
fn link_new(faces: &mut [Face], new_faces: &[u32]) -> Result<(), HullError> {
    let mut by_first: std::collections::HashMap<u32, u32> =
        std::collections::HashMap::with_capacity(new_faces.len());
    for &f in new_faces {
        if by_first.insert(faces[f as usize].v[0], f).is_some() {
            return Err(HullError::Inconsistent);
        }
    }
    for &f in new_faces {
        let w = faces[f as usize].v[1];
        let &g = by_first.get(&w).ok_or(HullError::Inconsistent)?;
        // f's edge 1 is (w, x); g = (w, w', x) has edge 2 (x, w).
        faces[f as usize].adjacent[1] = g;
        faces[g as usize].adjacent[2] = f;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute force: every hull face has all points on its inner side or on its plane.
    fn check(points: &[[f64; 3]]) -> (usize, usize) {
        let (faces, neighbours, on_hull) = convex_hull(points).unwrap();
        // Each neighbour holds the edge opposite vertex k, the other way round.
        for (f, face) in faces.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (face[(k + 1) % 3], face[(k + 2) % 3]);
                let g = faces[neighbours[f][k] as usize];
                assert!(
                    (0..3).any(|j| g[j] == b && g[(j + 1) % 3] == a),
                    "face {f} edge {k}"
                );
            }
        }
        let p = |i: u32| {
            let [x, y, z] = points[i as usize];
            robust::Coord3D { x, y, z }
        };
        for f in &faces {
            for x in 0..points.len() as u32 {
                assert!(robust::orient3d(p(f[0]), p(f[1]), p(f[2]), p(x)) >= 0.0);
            }
        }
        // Closed: V - E + F = 2 with E = 3F / 2.
        let vertices = on_hull.iter().filter(|&&h| h).count();
        assert_eq!(
            vertices as i64 - (3 * faces.len() / 2) as i64 + faces.len() as i64,
            2
        );
        (vertices, faces.len())
    }

    #[test]
    fn random_points_on_a_sphere_are_all_vertices() {
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let points: Vec<[f64; 3]> = (0..400)
            .map(|_| {
                let (z, t): (f64, f64) = (2.0 * next() - 1.0, std::f64::consts::TAU * next());
                let r = (1.0 - z * z).sqrt();
                [r * t.cos(), r * t.sin(), z]
            })
            .collect();
        assert_eq!(check(&points).0, 400);
    }

    #[test]
    fn coplanar_rings_keep_every_point() {
        // Latitude rings of a sphere: every four points of two rings are coplanar.
        let mut points = vec![[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]];
        for ring in 1..8 {
            let phi = std::f64::consts::PI * ring as f64 / 8.0;
            for k in 0..12 {
                let t = std::f64::consts::TAU * k as f64 / 12.0;
                points.push([phi.sin() * t.cos(), phi.sin() * t.sin(), phi.cos()]);
            }
        }
        assert_eq!(check(&points).0, points.len());
        // A cube's corners: faces of four coplanar points.
        let cube: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        assert_eq!(check(&cube), (8, 12));
    }

    #[test]
    fn interior_and_flat_inputs() {
        let mut points = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.1, 0.1, 0.1],
        ];
        let (_, _, on_hull) = convex_hull(&points).unwrap();
        assert_eq!(on_hull, vec![true, true, true, true, false]);
        points.truncate(3);
        points.push([1.0, 1.0, 0.0]);
        assert_eq!(convex_hull(&points), Err(HullError::Flat));
    }
}
