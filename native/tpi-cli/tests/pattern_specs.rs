//! `tpi discretise --pattern SPEC` with the pattern specs made on the surface (issue 15):
//! each gives the mesh that `tpi pattern ... --surface S` followed by `tpi discretise
//! --pattern FILE` gives, and `fit:D` meets D at every vertex by the sphere's closed-form
//! distance, computed here from the output file (not the fit's own number).

mod common;

use std::fs;
use std::path::Path;

use common::*;
use serde_json::Value;

fn ok(args: &[&str]) {
    let out = tpi(args);
    assert!(
        out.status.success(),
        "tpi {args:?} failed: {}",
        stderr(&out)
    );
}

/// The mesh of an output file: its vertices and facets (timings and names left out).
fn mesh(path: &Path) -> (Value, Value) {
    let v: Value = serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap();
    (v["vertices"].clone(), v["facets"].clone())
}

/// `tpi pattern PATTERN_ARGS --surface S --out p.json` + `tpi discretise --pattern p.json`
/// against `tpi discretise --pattern SPEC`: the same mesh, bit for bit.
fn same_mesh_as_pattern_file(name: &str, surface: &str, pattern_args: &[&str], spec: &str) {
    let dir = scratch(name);
    let p = dir.join("p.json");
    let a = dir.join("a.json");
    let b = dir.join("b.json");
    let mut args = pattern_args.to_vec();
    args.extend(["--surface", surface, "--out", p.to_str().unwrap()]);
    let mut full = vec!["pattern"];
    full.extend(args);
    ok(&full);
    ok(&[
        "discretise",
        "--surface",
        surface,
        "--pattern",
        p.to_str().unwrap(),
        "--out",
        a.to_str().unwrap(),
    ]);
    ok(&[
        "discretise",
        "--surface",
        surface,
        "--pattern",
        spec,
        "--out",
        b.to_str().unwrap(),
    ]);
    let (va, fa) = mesh(&a);
    let (vb, fb) = mesh(&b);
    assert!(fa.as_array().is_some_and(|f| f.len() > 10), "{name}");
    assert_eq!(fa, fb, "{name}: facets differ");
    assert_eq!(va, vb, "{name}: vertices differ");
}

#[test]
fn relax_spec_gives_the_mesh_of_tpi_pattern_relax() {
    same_mesh_as_pattern_file(
        "relax",
        &sample("nurbs-dome.json"),
        &["random:500", "--relax", "20"],
        "relax:20:random:500",
    );
}

#[test]
fn align_and_density_specs_give_the_meshes_of_tpi_pattern() {
    same_mesh_as_pattern_file(
        "align",
        &sample("saddle.json"),
        &["hex:12x10", "--align", "asymptotic"],
        "align:hex:12x10:asymptotic",
    );
    let density = sample("attractor-density.json");
    same_mesh_as_pattern_file(
        "density",
        &sample("nurbs-dome.json"),
        &["--density", &density, "--relax", "2"],
        &format!("relax:2:density:@{density}"),
    );
    // The same density inline: the spec carries the JSON itself, colons and all.
    let inline = fs::read_to_string(&density).unwrap().replace('\n', " ");
    same_mesh_as_pattern_file(
        "density-inline",
        &sample("nurbs-dome.json"),
        &["--density", &density],
        &format!("density:{inline}"),
    );
}

#[test]
fn fit_spec_meets_the_tolerance_at_every_vertex_of_the_sphere() {
    let dir = scratch("fit");
    let surface = dir.join("sphere.json");
    let radius = 10.0;
    fs::write(
        &surface,
        r#"{"type": "sphere_cap", "radius": 10, "x": [-3, 3], "y": [-3, 3]}"#,
    )
    .unwrap();
    let out = dir.join("m.json");
    let d = 0.005;
    ok(&[
        "discretise",
        "--surface",
        surface.to_str().unwrap(),
        "--pattern",
        "fit:0.005",
        "--out",
        out.to_str().unwrap(),
    ]);
    let (vertices, facets) = mesh(&out);
    let vertices: Vec<[f64; 3]> = serde_json::from_value(vertices).unwrap();
    let facets = facets.as_array().unwrap();
    assert!(facets.len() >= 12);
    let mut worst = 0.0f64;
    for f in facets {
        for k in f["vertices"].as_array().unwrap() {
            let [x, y, z] = vertices[k.as_u64().unwrap() as usize];
            // Distance to the whole sphere: a lower bound of the distance to the cap, so the
            // check is never looser than the cap's.
            worst = worst.max(((x * x + y * y + z * z).sqrt() - radius).abs());
        }
    }
    println!(
        "fit:{d}: {} points, max vertex distance {worst:.5e}",
        facets.len()
    );
    assert!(worst > 0.0 && worst <= d * (1.0 + 1e-9), "{worst} > {d}");
    // Half the tolerance needs more points.
    let finer = dir.join("finer.json");
    ok(&[
        "discretise",
        "--surface",
        surface.to_str().unwrap(),
        "--pattern",
        "fit:0.0025",
        "--out",
        finer.to_str().unwrap(),
    ]);
    let (_, finer_facets) = mesh(&finer);
    assert!(finer_facets.as_array().unwrap().len() > facets.len());
}

#[test]
fn malformed_specs_fail_naming_the_piece_and_write_nothing() {
    let dir = scratch("bad");
    let out = dir.join("m.json");
    let dome = sample("nurbs-dome.json");
    let missing = dir.join("missing.json");
    let missing_spec = format!("density:@{}", missing.display());
    for (spec, needles) in [
        ("relax:abc:random:50", vec!["relax:abc", "whole number"]),
        ("relax:5:fit:0.1", vec!["relax:5:fit", "not relaxed"]),
        ("fit:-1", vec!["fit:-1", "positive"]),
        ("align:hex:4x4", vec!["direction field is missing"]),
        (
            "align:poisson:0.1:principal",
            vec!["align:poisson", "hex or grid"],
        ),
        ("hexagon:4x4", vec!["unknown pattern kind"]),
        (missing_spec.as_str(), vec!["missing.json", "cannot read"]),
    ] {
        let o = tpi(&[
            "discretise",
            "--surface",
            &dome,
            "--pattern",
            spec,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{spec}: {}", stderr(&o));
        let e = stderr(&o);
        assert!(e.starts_with("tpi: error: "), "{spec}: {e}");
        assert_eq!(e.trim_end().lines().count(), 1, "{spec}: {e}");
        for n in needles {
            assert!(e.contains(n), "{spec}: `{n}` missing from {e}");
        }
        assert!(!out.exists());
    }
}

#[test]
fn the_help_documents_the_grammar() {
    let o = tpi(&["discretise", "--help"]);
    let help = text(&o.stdout);
    for needle in [
        "fit:D[:seed=S]",
        "relax:N:SPEC",
        "align:LATTICE:FIELD",
        "density:DATA",
        "@FILE.json",
    ] {
        assert!(help.contains(needle), "`{needle}` missing from the help");
    }
}
