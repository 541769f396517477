//! Mirror seeds beyond the domain boundary, so that the neighbour decision on surfaces that
//! are not convex everywhere sees every real facet as a closed polygon.
//!
//! A facet at the boundary is closed by the boundary itself: the mesh ends where its edges
//! meet the wall W, the ruled surface of the surface normals along the boundary curve
//! (DESIGN.md, item 6). Near a boundary point b with normal n_b and boundary tangent t_b, W is
//! the plane through b with unit normal w = (t_b x n_b) / |t_b x n_b|. Reflecting a seed's
//! tangent plane T_i = {x : n_i . (x - p_i) = 0} in that plane,
//!
//! ```text
//! p_i' = p_i - 2 ((p_i - b) . w) w,    n_i' = n_i - 2 (n_i . w) w,
//! ```
//!
//! gives a plane T_i' whose intersection with T_i lies in W (the two are mirror images), so a
//! ghost seed i' makes the facet of i end on the wall, up to the wall's curvature. Ghosts of
//! the seeds within [`GHOST_BAND`] spacings of a side are added across that side (and across
//! both sides near a corner), with their points mirrored in the triangulation's plane as well.
//! They take part in every flip and let the validity flips judge boundary facets as closed
//! polygons; then every triangle with a ghost is dropped, and the real triangles that remain
//! are the dual triangulation, whose open hull the facet stage closes on the true wall.

use glam::DVec3;

use crate::diffgeo::LocalGeometry;
use crate::planes::Plane;
use crate::surface::Surface;

/// Width of the band of seeds mirrored across each side, in mean pattern spacings
/// sqrt(area / n) of the triangulation's plane.
pub const GHOST_BAND: f64 = 3.0;

/// Seeds closer to a side than this fraction of the mean spacing get no ghost across it (it
/// would nearly coincide with them).
pub const GHOST_MIN_OFFSET: f64 = 1e-6;

/// The real seeds followed by their mirror images.
pub(crate) struct Augmented {
    /// Triangulation-plane coordinates.
    pub(crate) plane_uv: Vec<[f64; 2]>,
    /// Local geometry (ghosts: reflected point, normal and principal directions).
    pub(crate) geometry: Vec<LocalGeometry>,
    /// Tangent planes.
    pub(crate) planes: Vec<Plane>,
    /// Convex side per seed (a reflection keeps it).
    pub(crate) convex_side: Vec<i8>,
    /// The real seed of every point (itself for real seeds).
    pub(crate) source: Vec<u32>,
}

/// A reflection in the plane through `origin` with unit normal `normal`.
#[derive(Clone, Copy)]
struct Mirror {
    origin: DVec3,
    normal: DVec3,
}

impl Mirror {
    fn point(&self, x: DVec3) -> DVec3 {
        x - self.normal * (2.0 * (x - self.origin).dot(self.normal))
    }

    fn vector(&self, v: DVec3) -> DVec3 {
        v - self.normal * (2.0 * v.dot(self.normal))
    }

    fn geometry(&self, g: &LocalGeometry) -> LocalGeometry {
        LocalGeometry { point: self.point(g.point), normal: self.vector(g.normal), d1: self.vector(g.d1), d2: self.vector(g.d2), ..*g }
    }
}

/// The wall plane at the boundary point of `side` (0: u min, 1: u max, 2: v min, 3: v max)
/// nearest to the seed at domain parameters `uv`.
fn wall(surface: &dyn Surface, side: usize, uv: [f64; 2]) -> Option<Mirror> {
    let domain = surface.domain();
    let at = match side {
        0 => [domain.u.min, uv[1]],
        1 => [domain.u.max, uv[1]],
        2 => [uv[0], domain.v.min],
        _ => [uv[0], domain.v.max],
    };
    let d = surface.evaluate(at[0], at[1]);
    let normal = d.su.cross(d.sv).try_normalize()?;
    let tangent = if side < 2 { d.sv } else { d.su };
    let w = tangent.cross(normal).try_normalize()?;
    d.point.is_finite().then_some(Mirror { origin: d.point, normal: w })
}

/// The seeds with their ghosts appended (module doc). `extent` is the size of the
/// triangulation's plane rectangle [0, extent[0]] x [0, extent[1]]; `uv` the seeds' domain
/// parameters. Ghosts whose wall cannot be built (a degenerate boundary) are left out.
pub(crate) fn augment(
    surface: &dyn Surface,
    uv: &[[f64; 2]],
    plane_uv: &[[f64; 2]],
    extent: [f64; 2],
    geometry: &[LocalGeometry],
    planes: &[Plane],
    convex_side: &[i8],
) -> Augmented {
    let n = plane_uv.len();
    let spacing = (extent[0] * extent[1] / n as f64).sqrt();
    let band = GHOST_BAND * spacing;
    let min_offset = GHOST_MIN_OFFSET * spacing;
    let mut out = Augmented {
        plane_uv: plane_uv.to_vec(),
        geometry: geometry.to_vec(),
        planes: planes.to_vec(),
        convex_side: convex_side.to_vec(),
        source: (0..n as u32).collect(),
    };
    for i in 0..n {
        let [x, y] = plane_uv[i];
        // Distance to each side and the mirrored coordinate across it.
        let sides = [(x, [-x, y]), (extent[0] - x, [2.0 * extent[0] - x, y]), (y, [x, -y]), (extent[1] - y, [x, 2.0 * extent[1] - y])];
        let near: Vec<usize> = (0..4).filter(|&s| sides[s].0 < band && sides[s].0 > min_offset).collect();
        let mirrors: Vec<Option<Mirror>> = near.iter().map(|&s| wall(surface, s, uv[i])).collect();
        let mut push = |position: [f64; 2], g: LocalGeometry| {
            out.plane_uv.push(position);
            out.planes.push(Plane { point: g.point, normal: g.normal });
            out.geometry.push(g);
            out.convex_side.push(convex_side[i]);
            out.source.push(i as u32);
        };
        for (k, &s) in near.iter().enumerate() {
            if let Some(m) = mirrors[k] {
                push(sides[s].1, m.geometry(&geometry[i]));
            }
        }
        // Corners: across a u side and a v side in turn.
        for (a, &su) in near.iter().enumerate().filter(|(_, &s)| s < 2) {
            for (b, &sv) in near.iter().enumerate().filter(|(_, &s)| s >= 2) {
                if let (Some(mu), Some(mv)) = (mirrors[a], mirrors[b]) {
                    let position = [sides[su].1[0], sides[sv].1[1]];
                    push(position, mv.geometry(&mu.geometry(&geometry[i])));
                }
            }
        }
    }
    out
}
