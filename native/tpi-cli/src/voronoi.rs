//! Voronoi cells of pattern points, clipped to the unit square, for the pattern preview.
//!
//! Each cell is the unit square cut by the perpendicular bisectors between the point and
//! its Delaunay neighbours (spade): the Voronoi cell of a point is exactly the intersection
//! of those half-planes, so nothing else needs to be tested.

use spade::{DelaunayTriangulation, HasPosition, Point2, Triangulation};

struct Site {
    position: Point2<f64>,
    index: usize,
}

impl HasPosition for Site {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.position
    }
}

/// The cell of every point (counter-clockwise polygons, in point order). Points must be
/// finite and distinct (a validated pattern).
pub(crate) fn cells(points: &[[f64; 2]]) -> Vec<Vec<[f64; 2]>> {
    let square = vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut neighbours: Vec<Vec<usize>> = vec![Vec::new(); points.len()];
    let sites: Vec<Site> = points
        .iter()
        .enumerate()
        .map(|(index, p)| Site {
            position: Point2::new(p[0], p[1]),
            index,
        })
        .collect();
    match DelaunayTriangulation::<Site>::bulk_load(sites) {
        Ok(t) => {
            for edge in t.undirected_edges() {
                let [a, b] = edge.vertices();
                let (a, b) = (a.data().index, b.data().index);
                neighbours[a].push(b);
                neighbours[b].push(a);
            }
        }
        Err(_) => {
            // Not reachable for validated points; fall back to all pairs for tiny inputs.
            if points.len() <= 200 {
                for (a, list) in neighbours.iter_mut().enumerate() {
                    list.extend((0..points.len()).filter(|&b| b != a));
                }
            }
        }
    }
    points
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            let mut cell = square.clone();
            for &j in &neighbours[i] {
                let q = points[j];
                // Keep x with (x - m) . (q - p) <= 0, m the midpoint.
                let n = [q[0] - p[0], q[1] - p[1]];
                let m = [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
                cell = clip(&cell, n, n[0] * m[0] + n[1] * m[1]);
                if cell.is_empty() {
                    break;
                }
            }
            cell
        })
        .collect()
}

/// Sutherland-Hodgman: the part of `polygon` with n . x <= c.
fn clip(polygon: &[[f64; 2]], n: [f64; 2], c: f64) -> Vec<[f64; 2]> {
    let side = |x: [f64; 2]| n[0] * x[0] + n[1] * x[1] - c;
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for k in 0..polygon.len() {
        let a = polygon[k];
        let b = polygon[(k + 1) % polygon.len()];
        let (sa, sb) = (side(a), side(b));
        if sa <= 0.0 {
            out.push(a);
        }
        if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
            let t = sa / (sa - sb);
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn area(p: &[[f64; 2]]) -> f64 {
        (0..p.len())
            .map(|k| {
                let (a, b) = (p[k], p[(k + 1) % p.len()]);
                a[0] * b[1] - a[1] * b[0]
            })
            .sum::<f64>()
            / 2.0
    }

    #[test]
    fn cells_tile_the_square() {
        let points: Vec<[f64; 2]> = (0..50)
            .map(|i| {
                let x = ((i * 37) % 50) as f64 / 50.0 + 0.01;
                let y = ((i * 11) % 50) as f64 / 50.0 + 0.005;
                [x, y]
            })
            .collect();
        let cells = cells(&points);
        let total: f64 = cells.iter().map(|c| area(c)).sum();
        assert!((total - 1.0).abs() < 1e-9, "{total}");
        // A 2 x 2 grid: four quarters.
        let quarters = super::cells(&[[0.25, 0.25], [0.75, 0.25], [0.25, 0.75], [0.75, 0.75]]);
        for c in &quarters {
            assert!((area(c) - 0.25).abs() < 1e-12);
        }
    }
}
