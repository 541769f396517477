//! Wavefront OBJ: one `v` line per mesh vertex, one `f` n-gon per facet with 1-based indices
//! into the shared vertices (Rhino's OBJ import reads n-gons as mesh n-gons).

use std::fmt::Write;

use tpi_core::Discretisation;

/// The mesh as OBJ text. `source` goes into the header comment.
pub(crate) fn to_obj(result: &Discretisation, source: &str) -> String {
    let mut out = String::with_capacity(result.vertices.len() * 48 + result.facet_loops.len() * 8);
    let _ = writeln!(
        out,
        "# tpi {}: tangent plane intersection mesh",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(out, "# {source}");
    let _ = writeln!(
        out,
        "# {} vertices, {} facets (facet i belongs to pattern point i)",
        result.vertices.len(),
        result.facet_count()
    );
    let _ = writeln!(out, "o tpi_mesh");
    for v in &result.vertices {
        let _ = writeln!(out, "v {} {} {}", num(v.x), num(v.y), num(v.z));
    }
    for i in 0..result.facet_count() {
        out.push('f');
        for &k in result.facet(i) {
            let _ = write!(out, " {}", k + 1);
        }
        out.push('\n');
    }
    out
}

/// Shortest round-trip text of a coordinate.
fn num(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 {
        "0".to_string()
    } else if (1e-5..1e15).contains(&a) || !x.is_finite() {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
