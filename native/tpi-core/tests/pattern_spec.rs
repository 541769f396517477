//! Issue 15: the surface-aware pattern specs (`SurfacePatternSpec`) that the command line,
//! the C ABI and the plugin share. Each form must give exactly the points of the function
//! it names, called here directly with the parameters written out by hand; a fit must meet
//! its tolerance at every vertex by this suite's own projection (`common::closest_parameters`),
//! not by the fit's own number; malformed specs must give an error naming the bad piece.

mod common;

use common::*;
use tpi_core::{
    aligned_pattern, density_pattern, discretise, relax, AlignField, DensitySpec,
    DiscretiseOptions, Generator, GridSize, Lattice, Surface, SurfacePatternSpec, TpiError,
    MAX_GENERATED_POINTS,
};

fn generate(spec: &str, surface: &dyn Surface) -> Vec<[f64; 2]> {
    SurfacePatternSpec::parse(spec)
        .unwrap_or_else(|e| panic!("{spec}: {e}"))
        .generate(surface, &DiscretiseOptions::default())
        .unwrap_or_else(|e| panic!("{spec}: {e}"))
        .uv
}

#[test]
fn each_form_parses_to_the_parameters_written_in_it() {
    let cases: Vec<(&str, SurfacePatternSpec)> = vec![
        (
            "hex:6x5",
            SurfacePatternSpec::Generator(Generator::Hex(GridSize::Counts { nu: 6, nv: 5 })),
        ),
        (
            " fit:0.25:seed=9 ",
            SurfacePatternSpec::Fit {
                max_deviation: 0.25,
                seed: 9,
            },
        ),
        (
            "fit:1e-2",
            SurfacePatternSpec::Fit {
                max_deviation: 0.01,
                seed: 0,
            },
        ),
        (
            "relax:20:random:500",
            SurfacePatternSpec::Relax {
                iterations: 20,
                base: Box::new(SurfacePatternSpec::Generator(Generator::Random {
                    count: 500,
                    seed: 0,
                })),
            },
        ),
        (
            "align:grid:30x20:uv:-30.5",
            SurfacePatternSpec::Align {
                generator: Generator::Grid(GridSize::Counts { nu: 30, nv: 20 }),
                field: AlignField::Uv(-30.5),
            },
        ),
        (
            "relax:2:align:hex:spacing=0.1:asymptotic",
            SurfacePatternSpec::Relax {
                iterations: 2,
                base: Box::new(SurfacePatternSpec::Align {
                    generator: Generator::Hex(GridSize::Spacing(0.1)),
                    field: AlignField::Asymptotic,
                }),
            },
        ),
    ];
    for (text, expected) in cases {
        assert_eq!(SurfacePatternSpec::parse(text).unwrap(), expected, "{text}");
    }
    // Inline JSON, colons and all, runs to the end of the spec.
    let field = r#"align:hex:8x8:{"size": [2, 2], "directions": [[1, 0], [1, 0], [0, 1], [0, 1]]}"#;
    match SurfacePatternSpec::parse(field).unwrap() {
        SurfacePatternSpec::Align {
            field: AlignField::File(d),
            ..
        } => {
            assert_eq!(d.size, [2, 2]);
            assert_eq!(d.directions[2], [0.0, 1.0]);
        }
        other => panic!("{other:?}"),
    }
    let density = r#"density:{"spacing": 0.5, "ratio": 3, "seed": 4, "terms": [{"type": "curvature", "exponent": 1}]}"#;
    match SurfacePatternSpec::parse(density).unwrap() {
        SurfacePatternSpec::Density(d) => {
            assert_eq!((d.spacing, d.ratio, d.seed), (0.5, Some(3.0), 4));
            assert_eq!(d.terms.len(), 1);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn each_form_gives_the_points_of_the_function_it_names() {
    let surface = sample_surface("paraboloid.json");
    let options = DiscretiseOptions::default();
    let hex = Generator::Hex(GridSize::Counts { nu: 7, nv: 6 })
        .generate()
        .uv;
    assert_eq!(generate("hex:7x6", &surface), hex);
    assert_eq!(
        generate("relax:3:hex:7x6", &surface),
        relax(&surface, &hex, 3, &options).unwrap()
    );
    assert_eq!(generate("relax:0:hex:7x6", &surface), hex);
    assert_eq!(
        generate("align:hex:7x6:principal", &surface),
        aligned_pattern(&surface, Lattice::Hex, 42, &AlignField::Principal).unwrap()
    );
    assert_eq!(
        generate("align:grid:spacing=0.125:uv:30", &surface),
        aligned_pattern(&surface, Lattice::Grid, 64, &AlignField::Uv(30.0)).unwrap()
    );
    let text = std::fs::read_to_string(format!(
        "{}/../../samples/attractor-density.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let density = DensitySpec::from_json(&text, "attractor-density.json").unwrap();
    let dome = sample_surface("nurbs-dome.json");
    assert_eq!(
        generate(&format!("density:{text}"), &dome),
        density_pattern(&dome, &density, 0, MAX_GENERATED_POINTS, &options).unwrap()
    );
    // relax:N of a density follows the density, as `tpi pattern --density F --relax N`.
    assert_eq!(
        generate(&format!("relax:2:density:{text}"), &dome),
        density_pattern(&dome, &density, 2, MAX_GENERATED_POINTS, &options).unwrap()
    );
}

#[test]
fn a_fit_spec_meets_its_tolerance_at_every_vertex_by_an_independent_projection() {
    let surface = sample_surface("paraboloid.json");
    let d = 0.02;
    let made = SurfacePatternSpec::parse(&format!("fit:{d}:seed=1"))
        .unwrap()
        .generate(&surface, &DiscretiseOptions::default())
        .unwrap();
    let fit = made.fit.expect("a fit reports its outcome");
    assert!(fit.met, "{fit:?}");
    assert_eq!(fit.tolerance, d);
    let mesh = discretise(&surface, &made.uv, &DiscretiseOptions::default()).unwrap();
    let worst = max_over_used_vertices(&mesh, |x| {
        let [u, v] = closest_parameters(&surface, x, 12);
        surface.point_at(u, v).distance(x)
    });
    println!(
        "fit:{d}: {} points, own max deviation {worst:.5e}, reported {:.5e}",
        made.uv.len(),
        fit.max_deviation
    );
    assert!(worst <= d * (1.0 + 1e-9), "{worst} > {d}");
    assert!(worst > 0.0);
    // The other forms carry no fit outcome.
    let plain = SurfacePatternSpec::parse("hex:5x5")
        .unwrap()
        .generate(&surface, &DiscretiseOptions::default())
        .unwrap();
    assert!(plain.fit.is_none());
}

/// (spec, a piece the message must quote, a word of the reason).
const BAD: &[(&str, &str, &str)] = &[
    ("", "", "empty"),
    ("spiral:7", "spiral", "unknown pattern kind"),
    ("relax:abc:random:50", "relax:abc", "whole number"),
    ("relax:1001:random:50", "relax:1001", "1000"),
    ("relax:5", "relax:5", "needs the pattern"),
    ("relax:5:", "relax:5", "needs the pattern"),
    ("relax:5:fit:0.1", "relax:5:fit", "not relaxed"),
    ("relax:5:relax:3:hex:4x4", "relax", "sum"),
    ("fit:-1", "fit:-1", "positive"),
    ("fit:nan", "fit:nan", "positive"),
    ("fit:inf", "fit:inf", "positive"),
    ("fit:", "fit:", "positive"),
    ("fit:0.1:seed=-3", "seed=-3", "unsigned"),
    ("fit:0.1:planes=adjusted", "planes=adjusted", "fit:D[:seed=S]"),
    ("fit:0.1:seed=1:seed=2", "seed=2", "fit:D[:seed=S]"),
    ("align:poisson:0.1:principal", "align:poisson", "hex or grid"),
    ("align:hex:24x20", "align:hex:24x20", "direction field is missing"),
    ("align:hex:24x20:sideways", "sideways", "principal"),
    ("align:grid:4x4:uv:400", "uv:400", "degrees"),
    ("align:hex:0x4:principal", "hex:0x4", ""),
    ("align:hex:4x4:{\"size\": [1, 1]}", "align field", "directions"),
    ("align:hex:4x4:@grain.json", "@grain.json", "inline"),
    ("align:hex:4x4:@", "@", "file name"),
    ("density:", "density:", "JSON"),
    ("density:spacing=3", "density:spacing=3", "JSON"),
    ("density:@graded.json", "@graded.json", "inline"),
    ("density:{\"spacing\": 0.1}", "density", "terms"),
    ("density:{\"spacing\": -1, \"terms\": []}", "spacing", ""),
    (
        "density:{\"spacing\": 0.1, \"terms\": [{\"type\": \"image\", \"file\": \"g.pgm\", \"low\": 1, \"high\": 2}]}",
        "g.pgm",
        "inline",
    ),
    ("hex:axb", "hex:axb", ""),
];

#[test]
fn malformed_specs_are_refused_naming_the_piece_that_is_wrong() {
    for &(spec, piece, word) in BAD {
        let e = SurfacePatternSpec::parse(spec).expect_err(spec);
        let message = e.to_string();
        assert!(
            message.contains(piece) && message.contains(word),
            "{spec}: {message}"
        );
        assert!(
            matches!(
                e,
                TpiError::InvalidPatternSpec { .. }
                    | TpiError::InvalidGenerator { .. }
                    | TpiError::Parse { .. }
                    | TpiError::InvalidParameter { .. }
            ),
            "{spec}: {e:?}"
        );
    }
}

#[test]
fn junk_never_panics() {
    let long = "relax:1:".repeat(2000) + "hex:4x4";
    let junk = [
        ":",
        "::::",
        "relax:",
        "relax::",
        "align:",
        "align::",
        "align:::",
        "fit:::",
        "density:{",
        "density:{}",
        "density:[]",
        "align:hex:4x4:{",
        "align:hex:4x4:{}",
        "hex:",
        "héx:4x4",
        "relax:١:hex:4x4",
        "\u{0}",
        "@",
        "density:@",
        long.as_str(),
    ];
    for text in junk {
        assert!(SurfacePatternSpec::parse(text).is_err(), "{text:?}");
    }
}

#[test]
fn files_are_read_through_the_callers_reader_images_beside_their_density_file() {
    let pgm = b"P2\n2 2\n255\n0 255\n255 0\n".to_vec();
    let density = br#"{"spacing": 0.8, "seed": 2, "terms": [{"type": "image", "file": "grey.pgm", "low": 1, "high": 4}]}"#.to_vec();
    let field = br#"{"size": [2, 2], "directions": [[1, 0], [1, 0], [1, 0], [1, 0]]}"#.to_vec();
    let mut asked = Vec::new();
    let mut read = |name: &str| -> Result<Vec<u8>, TpiError> {
        asked.push(name.to_string());
        match name {
            "in/graded.json" => Ok(density.clone()),
            "in/grey.pgm" => Ok(pgm.clone()),
            "grain.json" => Ok(field.clone()),
            other => Err(TpiError::InvalidPatternSpec {
                part: other.into(),
                reason: "no such file".into(),
            }),
        }
    };
    let spec =
        SurfacePatternSpec::parse_with("relax:1:density:@in/graded.json", &mut read).unwrap();
    let aligned = SurfacePatternSpec::parse_with("align:hex:6x6:@grain.json", &mut read).unwrap();
    let missing = SurfacePatternSpec::parse_with("density:@nowhere.json", &mut read).unwrap_err();
    assert_eq!(
        asked,
        [
            "in/graded.json",
            "in/grey.pgm",
            "grain.json",
            "nowhere.json"
        ]
    );
    assert!(missing.to_string().contains("nowhere.json"), "{missing}");
    let surface = sample_surface("paraboloid.json");
    match &spec {
        SurfacePatternSpec::Relax {
            iterations: 1,
            base,
        } => match base.as_ref() {
            SurfacePatternSpec::Density(d) => {
                let uv = spec
                    .generate(&surface, &DiscretiseOptions::default())
                    .unwrap()
                    .uv;
                let direct = density_pattern(
                    &surface,
                    d,
                    1,
                    MAX_GENERATED_POINTS,
                    &DiscretiseOptions::default(),
                )
                .unwrap();
                assert_eq!(uv, direct);
            }
            other => panic!("{other:?}"),
        },
        other => panic!("{other:?}"),
    }
    match aligned {
        SurfacePatternSpec::Align {
            field: AlignField::File(d),
            ..
        } => assert_eq!(d.size, [2, 2]),
        other => panic!("{other:?}"),
    }
}
