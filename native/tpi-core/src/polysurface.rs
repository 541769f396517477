//! Polysurfaces: several four-sided faces that share whole sides, discretised as one shell.
//!
//! **Layout.** The faces are laid out as a grid of `columns x rows` cells, one face per cell,
//! so that two faces in neighbouring cells share the side between them. A face sits in its
//! cell by one of the eight symmetries of the square: with cell coordinates (a, b) in
//! [0, 1]^2,
//!
//! ```text
//! a' = flip_a ? 1 - a : a,   b' = flip_b ? 1 - b : b,   (s, t) = swap ? (b', a') : (a', b'),
//! (u, v) = (u0 + s (u1 - u0), v0 + t (v1 - v0))   in the face's own domain,
//! ```
//!
//! chosen so that the face continues its neighbour: at every parameter tau along a shared cell
//! side, the two faces give the same point (to [`EDGE_MATCH_TOLERANCE`] of the bounding-box
//! diagonal). The first face sits in the first cell as it is; the others are placed by a
//! breadth-first walk over shared sides (found from the geometry, so faces may come in any
//! order and any orientation), and the cells must fill a rectangle.
//!
//! **The polysurface as one surface.** Column i has width w_i and row j height h_j (the mean
//! length of the faces' mid-lines across them, so that a uniform pattern spreads by area), and
//! the polysurface is the surface over [0, sum w] x [0, sum h] whose cell (i, j) is its face
//! composed with the affine map above:
//!
//! ```text
//! P(A, B) = F(u, v),  (u, v) = M (A, B) + c,  M = [[u_A, u_B], [v_A, v_B]] constant per cell,
//! P_A = u_A F_u + v_A F_v,  P_AA = u_A^2 F_uu + 2 u_A v_A F_uv + v_A^2 F_vv,  and so on.
//! ```
//!
//! It is continuous across the faces' shared sides and smooth inside each cell; its tangent
//! planes are the faces' own, so the whole pipeline (patterns, neighbours, the envelope,
//! boundaries, seams, the report) runs on it unchanged and the facets of neighbouring faces
//! meet along common edges and vertices. A point on a shared side belongs to the cell after
//! it (to the right or above). Faces whose grid wraps around (a ring of faces) close the
//! polysurface in that direction, found by [`crate::surface_layout`] as for one face.

use glam::DVec3;

use crate::error::TpiError;
use crate::samples::bounding_diagonal;
use crate::spec::SurfaceModel;
use crate::surface::{Domain, Interval, Surface, SurfaceDerivatives};
use crate::tolerance::{EDGE_MATCH_SAMPLES, EDGE_MATCH_TOLERANCE};
use crate::units::Units;

/// Faces accepted in one polysurface: the layout compares every placed face with every face
/// not yet placed, so this bounds the work at about a million side comparisons.
pub const MAX_POLYSURFACE_FACES: usize = 1000;

/// One of the eight placements of a face in its cell (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Orientation {
    swap: bool,
    flip_a: bool,
    flip_b: bool,
}

impl Orientation {
    const IDENTITY: Orientation = Orientation {
        swap: false,
        flip_a: false,
        flip_b: false,
    };

    fn all() -> impl Iterator<Item = Orientation> {
        (0..8u8).map(|k| Orientation {
            swap: k & 1 != 0,
            flip_a: k & 2 != 0,
            flip_b: k & 4 != 0,
        })
    }

    /// Normalised face parameters (s, t) of cell coordinates (a, b).
    fn face_st(self, a: f64, b: f64) -> (f64, f64) {
        let a = if self.flip_a { 1.0 - a } else { a };
        let b = if self.flip_b { 1.0 - b } else { b };
        if self.swap {
            (b, a)
        } else {
            (a, b)
        }
    }

    /// d(s, t)/d(a, b) as [[s_a, s_b], [t_a, t_b]].
    fn jacobian(self) -> [[f64; 2]; 2] {
        let da = if self.flip_a { -1.0 } else { 1.0 };
        let db = if self.flip_b { -1.0 } else { 1.0 };
        if self.swap {
            [[0.0, db], [da, 0.0]]
        } else {
            [[da, 0.0], [0.0, db]]
        }
    }
}

/// A side of a cell, in cell coordinates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum CellSide {
    /// a = 0.
    Left,
    /// a = 1.
    Right,
    /// b = 0.
    Bottom,
    /// b = 1.
    Top,
}

impl CellSide {
    const ALL: [CellSide; 4] = [
        CellSide::Left,
        CellSide::Right,
        CellSide::Bottom,
        CellSide::Top,
    ];

    fn opposite(self) -> CellSide {
        match self {
            CellSide::Left => CellSide::Right,
            CellSide::Right => CellSide::Left,
            CellSide::Bottom => CellSide::Top,
            CellSide::Top => CellSide::Bottom,
        }
    }

    /// The neighbouring cell's offset.
    fn step(self) -> (i64, i64) {
        match self {
            CellSide::Left => (-1, 0),
            CellSide::Right => (1, 0),
            CellSide::Bottom => (0, -1),
            CellSide::Top => (0, 1),
        }
    }

    /// Cell coordinates of the point at `tau` in [0, 1] along this side (a for the bottom and
    /// top, b for the left and right, both increasing), so that two cells sharing a side
    /// meet at equal tau.
    fn at(self, tau: f64) -> (f64, f64) {
        match self {
            CellSide::Left => (0.0, tau),
            CellSide::Right => (1.0, tau),
            CellSide::Bottom => (tau, 0.0),
            CellSide::Top => (tau, 1.0),
        }
    }
}

/// A face placed in the grid.
#[derive(Clone, Debug, PartialEq)]
struct Cell {
    face: usize,
    orientation: Orientation,
    /// d(u, v)/d(A, B) for this cell, [[u_A, u_B], [v_A, v_B]].
    jacobian: [[f64; 2]; 2],
}

/// Several faces laid out as one surface (see the module doc).
#[derive(Clone, Debug, PartialEq)]
pub struct Polysurface {
    faces: Vec<SurfaceModel>,
    columns: usize,
    rows: usize,
    /// Column boundaries in A, `columns + 1` increasing values from 0.
    column_edges: Vec<f64>,
    /// Row boundaries in B, `rows + 1` increasing values from 0.
    row_edges: Vec<f64>,
    /// Cell (i, j) at `cells[j * columns + i]`.
    cells: Vec<Cell>,
    units: Option<Units>,
}

impl Polysurface {
    /// Lays out `faces` as one surface.
    ///
    /// Errors ([`TpiError::InvalidPolysurface`], naming the face): no faces or more than
    /// [`MAX_POLYSURFACE_FACES`]; a trimmed face or a face that is itself a polysurface; faces
    /// whose units differ; a face that shares no whole side with the others; faces that do not
    /// fill a rectangle of rows and columns; two faces laid side by side whose sides differ.
    pub fn new(faces: Vec<SurfaceModel>) -> Result<Polysurface, TpiError> {
        let invalid = |item: String, reason: String| TpiError::InvalidPolysurface { item, reason };
        if faces.is_empty() || faces.len() > MAX_POLYSURFACE_FACES {
            return Err(invalid(
                "faces".to_string(),
                format!(
                    "a polysurface needs 1 to {MAX_POLYSURFACE_FACES} faces, found {}",
                    faces.len()
                ),
            ));
        }
        for (k, face) in faces.iter().enumerate() {
            if face.trim().is_some() {
                return Err(invalid(
                    format!("faces[{k}]"),
                    "trimmed faces are not supported in a polysurface yet; give the untrimmed face"
                        .to_string(),
                ));
            }
            if matches!(face, SurfaceModel::Polysurface(_)) {
                return Err(invalid(
                    format!("faces[{k}]"),
                    "a face may not itself be a polysurface; list its faces".to_string(),
                ));
            }
            if face.units() != faces[0].units() {
                return Err(invalid(
                    format!("faces[{k}]"),
                    format!(
                        "its units ({}) differ from faces[0]'s ({})",
                        crate::units::units_label(face.units()),
                        crate::units::units_label(faces[0].units())
                    ),
                ));
            }
        }
        let units = faces[0].units();
        let geometry = FaceGeometry::new(faces);
        let placed = lay_out(&geometry)?;
        Ok(Polysurface::from_placement(geometry, placed, units))
    }

    fn from_placement(
        geometry: FaceGeometry,
        placed: Placement,
        units: Option<Units>,
    ) -> Polysurface {
        let Placement {
            columns,
            rows,
            cells,
        } = placed;
        // Mean mid-line lengths: a uniform pattern then spreads over the faces by area.
        let mid_length = |cell: &Cell, across_a: bool| {
            let n = EDGE_MATCH_SAMPLES;
            let mut length = 0.0;
            let mut previous: Option<DVec3> = None;
            for k in 0..n {
                let tau = k as f64 / (n - 1) as f64;
                let (a, b) = if across_a { (tau, 0.5) } else { (0.5, tau) };
                let p = geometry.point(cell.face, cell.orientation, a, b);
                if let Some(q) = previous {
                    length += p.distance(q);
                }
                previous = Some(p);
            }
            length
        };
        let edges = |count: usize, other: usize, across_a: bool| {
            let mut edges = vec![0.0];
            for i in 0..count {
                let mean = (0..other)
                    .map(|j| {
                        let cell = if across_a {
                            &cells[j * columns + i]
                        } else {
                            &cells[i * columns + j]
                        };
                        mid_length(cell, across_a)
                    })
                    .sum::<f64>()
                    / other as f64;
                // A face of no length across (a pole strip) still gets a column.
                let width = if mean.is_finite() && mean > 0.0 {
                    mean
                } else {
                    1.0
                };
                edges.push(edges[i] + width);
            }
            edges
        };
        let column_edges = edges(columns, rows, true);
        let row_edges = edges(rows, columns, false);
        let cells = cells
            .into_iter()
            .enumerate()
            .map(|(index, cell)| {
                let (i, j) = (index % columns, index / columns);
                let width = column_edges[i + 1] - column_edges[i];
                let height = row_edges[j + 1] - row_edges[j];
                let domain = geometry.faces[cell.face].domain();
                let st = cell.orientation.jacobian();
                let (lu, lv) = (domain.u.length(), domain.v.length());
                Cell {
                    jacobian: [
                        [lu * st[0][0] / width, lu * st[0][1] / height],
                        [lv * st[1][0] / width, lv * st[1][1] / height],
                    ],
                    ..cell
                }
            })
            .collect();
        Polysurface {
            faces: geometry.faces,
            columns,
            rows,
            column_edges,
            row_edges,
            cells,
            units,
        }
    }

    /// The faces, in the order given.
    pub fn faces(&self) -> &[SurfaceModel] {
        &self.faces
    }

    /// The grid: (columns, rows).
    pub fn grid(&self) -> (usize, usize) {
        (self.columns, self.rows)
    }

    /// Column boundaries in u: `columns + 1` increasing values from 0 (a column is as wide as
    /// its faces' mean length across it).
    pub fn column_edges(&self) -> &[f64] {
        &self.column_edges
    }

    /// Row boundaries in v: `rows + 1` increasing values from 0.
    pub fn row_edges(&self) -> &[f64] {
        &self.row_edges
    }

    /// Which face covers (A, B) (clamped into the domain), and its own parameters there.
    pub fn face_at(&self, a: f64, b: f64) -> (usize, [f64; 2]) {
        let (cell, (u, v)) = self.locate(a, b);
        (cell.face, [u, v])
    }

    /// The face of cell (column, row), for `tpi info`.
    pub fn face_of_cell(&self, column: usize, row: usize) -> Option<usize> {
        (column < self.columns && row < self.rows)
            .then(|| self.cells[row * self.columns + column].face)
    }

    /// The same polysurface with its faces' units replaced.
    pub fn with_units(self, units: Option<Units>) -> Polysurface {
        Polysurface {
            faces: self
                .faces
                .into_iter()
                .map(|f| f.with_units(units))
                .collect(),
            units,
            ..self
        }
    }

    fn locate(&self, a: f64, b: f64) -> (&Cell, (f64, f64)) {
        let index = |edges: &[f64], x: f64| {
            // The cell after a boundary owns it; the last cell owns the domain's end.
            let count = edges.len() - 1;
            edges[1..count].partition_point(|&e| e <= x)
        };
        let a = a.clamp(0.0, self.column_edges[self.columns]);
        let b = b.clamp(0.0, self.row_edges[self.rows]);
        let i = index(&self.column_edges, a);
        let j = index(&self.row_edges, b);
        let cell = &self.cells[j * self.columns + i];
        let local_a =
            (a - self.column_edges[i]) / (self.column_edges[i + 1] - self.column_edges[i]);
        let local_b = (b - self.row_edges[j]) / (self.row_edges[j + 1] - self.row_edges[j]);
        let (s, t) = cell
            .orientation
            .face_st(local_a.clamp(0.0, 1.0), local_b.clamp(0.0, 1.0));
        let domain = self.faces[cell.face].domain();
        (cell, (domain.u.lerp(s), domain.v.lerp(t)))
    }
}

impl Surface for Polysurface {
    fn domain(&self) -> Domain {
        Domain::new(
            Interval::new(0.0, self.column_edges[self.columns]),
            Interval::new(0.0, self.row_edges[self.rows]),
        )
    }

    fn evaluate(&self, a: f64, b: f64) -> SurfaceDerivatives {
        let (cell, (u, v)) = self.locate(a, b);
        let f = self.faces[cell.face].evaluate(u, v);
        let [[ua, ub], [va, vb]] = cell.jacobian;
        SurfaceDerivatives {
            point: f.point,
            su: ua * f.su + va * f.sv,
            sv: ub * f.su + vb * f.sv,
            suu: ua * ua * f.suu + 2.0 * ua * va * f.suv + va * va * f.svv,
            suv: ua * ub * f.suu + (ua * vb + ub * va) * f.suv + va * vb * f.svv,
            svv: ub * ub * f.suu + 2.0 * ub * vb * f.suv + vb * vb * f.svv,
        }
    }

    fn point_at(&self, a: f64, b: f64) -> DVec3 {
        let (cell, (u, v)) = self.locate(a, b);
        self.faces[cell.face].point_at(u, v)
    }

    fn units(&self) -> Option<Units> {
        self.units
    }
}

/// The faces with the scale their sides are compared at.
struct FaceGeometry {
    faces: Vec<SurfaceModel>,
    tolerance: f64,
    /// Per face, its four sides sampled once, each along its own parameter increasing:
    /// s = 0 and s = 1 (along t), t = 0 and t = 1 (along s). Every placement reads them.
    sides: Vec<[Vec<DVec3>; 4]>,
}

impl FaceGeometry {
    fn new(faces: Vec<SurfaceModel>) -> FaceGeometry {
        let n = EDGE_MATCH_SAMPLES;
        let diagonal = bounding_diagonal(faces.iter().flat_map(|face| {
            (0..n * n).map(move |k| {
                let d = face.domain();
                let (s, t) = (
                    (k % n) as f64 / (n - 1) as f64,
                    (k / n) as f64 / (n - 1) as f64,
                );
                face.point_at(d.u.lerp(s), d.v.lerp(t))
            })
        }));
        let at = |k: usize| k as f64 / (n - 1) as f64;
        let sides = faces
            .iter()
            .map(|face| {
                let d = face.domain();
                let side = |st: &dyn Fn(f64) -> (f64, f64)| -> Vec<DVec3> {
                    (0..n)
                        .map(|k| {
                            let (s, t) = st(at(k));
                            face.point_at(d.u.lerp(s), d.v.lerp(t))
                        })
                        .collect()
                };
                [
                    side(&|x| (0.0, x)),
                    side(&|x| (1.0, x)),
                    side(&|x| (x, 0.0)),
                    side(&|x| (x, 1.0)),
                ]
            })
            .collect();
        FaceGeometry {
            faces,
            tolerance: EDGE_MATCH_TOLERANCE * diagonal,
            sides,
        }
    }

    fn point(&self, face: usize, orientation: Orientation, a: f64, b: f64) -> DVec3 {
        let (s, t) = orientation.face_st(a, b);
        let d = self.faces[face].domain();
        self.faces[face].point_at(d.u.lerp(s), d.v.lerp(t))
    }

    /// The samples of one cell side of a placed face, in the cell side's direction: the face
    /// side it maps to (the face coordinate that stays 0 or 1 along it), forwards or reversed.
    fn side(&self, face: usize, orientation: Orientation, side: CellSide) -> Vec<DVec3> {
        let (a0, b0) = side.at(0.0);
        let (a1, b1) = side.at(1.0);
        let (s0, t0) = orientation.face_st(a0, b0);
        let (s1, t1) = orientation.face_st(a1, b1);
        let (index, forward) = if s0 == s1 {
            (usize::from(s0 != 0.0), t1 > t0)
        } else {
            (2 + usize::from(t0 != 0.0), s1 > s0)
        };
        let samples = &self.sides[face][index];
        if forward {
            samples.clone()
        } else {
            samples.iter().rev().copied().collect()
        }
    }

    fn same(&self, p: &[DVec3], q: &[DVec3]) -> bool {
        p.iter()
            .zip(q)
            .all(|(x, y)| x.distance(*y) <= self.tolerance)
    }

    /// A side that is one point (a pole) joins nothing.
    fn is_point(&self, p: &[DVec3]) -> bool {
        p.iter().all(|x| x.distance(p[0]) <= self.tolerance)
    }
}

struct Placement {
    columns: usize,
    rows: usize,
    cells: Vec<Cell>,
}

/// Places every face (see the module doc).
fn lay_out(geometry: &FaceGeometry) -> Result<Placement, TpiError> {
    let count = geometry.faces.len();
    let mut at: Vec<Option<((i64, i64), Orientation)>> = vec![None; count];
    let mut occupied = std::collections::HashMap::new();
    at[0] = Some(((0, 0), Orientation::IDENTITY));
    occupied.insert((0i64, 0i64), 0usize);
    let mut queue = std::collections::VecDeque::from([0usize]);
    while let Some(f) = queue.pop_front() {
        let Some((cell, orientation)) = at[f] else {
            continue;
        };
        for side in CellSide::ALL {
            let (di, dj) = side.step();
            let next = (cell.0 + di, cell.1 + dj);
            if occupied.contains_key(&next) {
                continue;
            }
            let ours = geometry.side(f, orientation, side);
            if geometry.is_point(&ours) {
                continue;
            }
            let found = (0..count).filter(|&g| at[g].is_none()).find_map(|g| {
                Orientation::all()
                    .find(|&o| geometry.same(&ours, &geometry.side(g, o, side.opposite())))
                    .map(|o| (g, o))
            });
            if let Some((g, o)) = found {
                at[g] = Some((next, o));
                occupied.insert(next, g);
                queue.push_back(g);
            }
        }
    }
    let invalid = |item: String, reason: String| TpiError::InvalidPolysurface { item, reason };
    if let Some(lost) = at.iter().position(Option::is_none) {
        return Err(invalid(
            format!("faces[{lost}]"),
            "shares no whole side with the faces laid out from faces[0] (faces join along \
             whole sides, end to end, as rows and columns of four-sided faces)"
                .to_string(),
        ));
    }
    let cells_of: Vec<((i64, i64), Orientation)> = at.into_iter().flatten().collect();
    let min_i = cells_of.iter().map(|c| c.0 .0).min().unwrap_or(0);
    let max_i = cells_of.iter().map(|c| c.0 .0).max().unwrap_or(0);
    let min_j = cells_of.iter().map(|c| c.0 .1).min().unwrap_or(0);
    let max_j = cells_of.iter().map(|c| c.0 .1).max().unwrap_or(0);
    let columns = (max_i - min_i + 1) as usize;
    let rows = (max_j - min_j + 1) as usize;
    let mut grid: Vec<Option<Cell>> = vec![None; columns * rows];
    for (face, &((i, j), orientation)) in cells_of.iter().enumerate() {
        grid[(j - min_j) as usize * columns + (i - min_i) as usize] = Some(Cell {
            face,
            orientation,
            jacobian: [[0.0; 2]; 2],
        });
    }
    if let Some(hole) = grid.iter().position(Option::is_none) {
        return Err(invalid(
            "faces".to_string(),
            format!(
                "the faces do not fill a rectangle of rows and columns ({columns} x {rows} \
                 cells, none at column {}, row {}); only such layouts are supported so far",
                hole % columns,
                hole / columns
            ),
        ));
    }
    let cells: Vec<Cell> = grid.into_iter().flatten().collect();
    // Faces placed by one neighbour must also continue the others they sit beside.
    for j in 0..rows {
        for i in 0..columns {
            let here = &cells[j * columns + i];
            let mut beside = Vec::new();
            if i + 1 < columns {
                beside.push((&cells[j * columns + i + 1], CellSide::Right));
            }
            if j + 1 < rows {
                beside.push((&cells[(j + 1) * columns + i], CellSide::Top));
            }
            for (there, side) in beside {
                let ours = geometry.side(here.face, here.orientation, side);
                let theirs = geometry.side(there.face, there.orientation, side.opposite());
                if !geometry.same(&ours, &theirs) {
                    return Err(invalid(
                        format!("faces[{}]", there.face),
                        format!(
                            "laid beside faces[{}] but their sides differ (more than {:e} of \
                             the size apart)",
                            here.face, EDGE_MATCH_TOLERANCE
                        ),
                    ));
                }
            }
        }
    }
    Ok(Placement {
        columns,
        rows,
        cells,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precomputed_sides_match_the_face_evaluated_along_each_cell_side() {
        let face = crate::analytic::AnalyticSurface::new(
            crate::analytic::AnalyticKind::EllipticParaboloid { a: 0.3, b: 0.7 },
            [-1.0, 2.0],
            [0.5, 1.5],
        )
        .unwrap();
        let geometry = FaceGeometry::new(vec![SurfaceModel::Analytic(face)]);
        let n = EDGE_MATCH_SAMPLES;
        for o in Orientation::all() {
            for side in CellSide::ALL {
                let samples = geometry.side(0, o, side);
                for (k, x) in samples.iter().enumerate() {
                    let (a, b) = side.at(k as f64 / (n - 1) as f64);
                    let direct = geometry.point(0, o, a, b);
                    assert!(x.distance(direct) < 1e-12, "{o:?} {side:?} sample {k}");
                }
            }
        }
    }

    #[test]
    fn orientation_jacobian_matches_its_map() {
        for o in Orientation::all() {
            let (s0, t0) = o.face_st(0.3, 0.6);
            let (s1, t1) = o.face_st(0.4, 0.6);
            let (s2, t2) = o.face_st(0.3, 0.7);
            let j = o.jacobian();
            assert!(((s1 - s0) / 0.1 - j[0][0]).abs() < 1e-12);
            assert!(((t1 - t0) / 0.1 - j[1][0]).abs() < 1e-12);
            assert!(((s2 - s0) / 0.1 - j[0][1]).abs() < 1e-12);
            assert!(((t2 - t0) / 0.1 - j[1][1]).abs() < 1e-12);
        }
    }
}
