//! Surface-aware pattern specs: one line of text that says how a pattern is made for a
//! surface, parsed once here and run by the command line (`tpi discretise --pattern SPEC`),
//! the C ABI (`tpi_pattern_new_for_surface`) and the Grasshopper component alike (issue 15).
//!
//! The plain generators ([`Generator`], the [`crate::pattern`] module's table) make points in
//! the unit square without looking at the surface. The forms below look at it: they measure
//! areas, curvature and deviation on the surface given to [`SurfacePatternSpec::generate`],
//! with the discretisation options given there (plane mode, envelope repair).
//!
//! ## Grammar
//!
//! ```text
//! SPEC     = BASE | relax:N:BASE
//! BASE     = GENERATOR | fit:D[:seed=S] | align:LATTICE:FIELD | density:DATA
//! LATTICE  = hex:NUxNV | hex:spacing=A | grid:NUxNV | grid:spacing=A
//! FIELD    = principal | asymptotic | uv:ANGLE | DATA
//! DATA     = {JSON...} | @FILE
//! ```
//!
//! | spec | points |
//! |------|--------|
//! | `GENERATOR` | the generator's points (`hex:24x20`, `random:500:seed=7`, ...), blind to the surface |
//! | `fit:D[:seed=S]` | [`crate::fit_pattern`]: few points whose TPI mesh keeps every vertex within D model units of the surface; S seeds its sampling (default 0). Whether D was met comes back in [`SurfacePattern::fit`] |
//! | `relax:N:BASE` | BASE's points after N Lloyd iterations on the surface ([`crate::relax()`], areas measured on the surface), N from 0 to [`crate::MAX_RELAX_ITERATIONS`]; for `density:` the iterations follow the density ([`crate::density_pattern`]). Not of `fit:` (the fit already relaxes, and a relaxed fit would no longer be checked against D) and not of `relax:` (give the sum) |
//! | `align:LATTICE:FIELD` | [`crate::aligned_pattern`]: the hex or grid lattice of about as many points as LATTICE makes, laid along FIELD: `principal` (curvature directions), `asymptotic` (where K < 0), `uv:ANGLE` (degrees from the u axis, in parameters), or a direction field ([`DirectionField`] JSON) |
//! | `density:DATA` | [`crate::density_pattern`]: a Poisson-disk sampling following the density field DATA ([`DensitySpec`] JSON) |
//!
//! The field and the density come last in their form, so their data runs to the end of the
//! spec: inline JSON (`density:{"spacing": 0.1, "terms": [...]}`, colons and all), or
//! `@FILE`, the name of a JSON file. Files are never read here: [`SurfacePatternSpec::parse`]
//! refuses `@FILE` (the C ABI and the plugin take inline JSON), and
//! [`SurfacePatternSpec::parse_with`] asks its caller (the command line) for each file's
//! bytes, and for the grey-level images a density's `image` terms name (relative to the
//! density file's folder when the density came from a file; as written when inline).
//!
//! ## Examples
//!
//! ```text
//! hex:24x20                                  generator, unchanged on any surface
//! relax:20:random:500                        500 random points made even on the surface
//! fit:0.01                                   tolerance-driven, 0.01 model units
//! fit:0.01:seed=3
//! align:hex:spacing=0.04:principal           hexagons along the curvature directions
//! align:grid:30x30:uv:30                     squares turned 30 degrees in parameters
//! relax:5:align:hex:24x20:asymptotic
//! align:hex:24x20:@grain.json                a direction field from a file (command line)
//! density:{"spacing": 0.08, "ratio": 4, "terms": [{"type": "curvature", "exponent": 1}]}
//! relax:5:density:@graded.json
//! ```
//!
//! Errors are [`TpiError::InvalidPatternSpec`] naming the offending piece (`relax:abc`,
//! `fit:-1`, `align:poisson`, `@grain.json`), or the error of the part's own parser (a
//! generator's [`TpiError::InvalidGenerator`], the JSON's [`TpiError::Parse`] with line and
//! column, a field's [`TpiError::InvalidParameter`]); never a panic.

use std::fmt;

use crate::align::{aligned_pattern, AlignField, DirectionField, Lattice};
use crate::density::{density_pattern_with_progress, DensitySpec, GreyImage};
use crate::discretise::DiscretiseOptions;
use crate::error::TpiError;
use crate::fit::fit_pattern_with_progress;
use crate::pattern::{Generator, MAX_GENERATED_POINTS};
use crate::progress::{NoProgress, Progress};
use crate::relax::{relax_with_progress, MAX_RELAX_ITERATIONS};
use crate::surface::Surface;

/// A parsed surface-aware pattern spec (module doc). Made by [`SurfacePatternSpec::parse`] or
/// [`SurfacePatternSpec::parse_with`]; data named by `@FILE` is already read and checked.
#[derive(Clone, Debug, PartialEq)]
pub enum SurfacePatternSpec {
    /// A plain generator (blind to the surface).
    Generator(Generator),
    /// `fit:D[:seed=S]`: a tolerance-driven pattern.
    Fit {
        /// The largest vertex deviation allowed (model units, finite, > 0).
        max_deviation: f64,
        /// Seed of the sampling.
        seed: u64,
    },
    /// `relax:N:BASE`: BASE's points after N Lloyd iterations on the surface.
    Relax {
        /// Lloyd iterations (at most [`MAX_RELAX_ITERATIONS`]).
        iterations: usize,
        /// The pattern relaxed: never `Relax` or `Fit`.
        base: Box<SurfacePatternSpec>,
    },
    /// `align:LATTICE:FIELD`: an aligned hex or grid lattice.
    Align {
        /// The `hex:...` or `grid:...` generator giving the lattice and the point count.
        generator: Generator,
        /// The direction field.
        field: AlignField,
    },
    /// `density:DATA`: a density-graded Poisson-disk sampling.
    Density(Box<DensitySpec>),
}

/// What [`SurfacePatternSpec::generate`] made.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfacePattern {
    /// The pattern points, normalised to [0, 1]^2.
    pub uv: Vec<[f64; 2]>,
    /// For `fit:`, how the fit went; None for the other forms.
    pub fit: Option<FitOutcome>,
}

/// How a `fit:D` spec went (the numbers of [`crate::FittedPattern`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOutcome {
    /// The tolerance asked for (D, model units).
    pub tolerance: f64,
    /// Whether every mesh vertex lies within D. When false, the points are the closest
    /// attempt and a caller that needs the tolerance must refuse them.
    pub met: bool,
    /// The largest vertex deviation of the pattern's mesh (model units).
    pub max_deviation: f64,
    /// Invalid facets of the pattern's mesh.
    pub invalid_facets: usize,
    /// Discretisations run to find it.
    pub discretisations: usize,
}

/// The keywords that start a surface-aware form, for messages.
const FORMS: &str = "a generator (grid, hex, jitter, random, poisson), fit:D, relax:N:SPEC, \
                     align:LATTICE:FIELD or density:JSON";

fn invalid(part: &str, reason: impl Into<String>) -> TpiError {
    TpiError::InvalidPatternSpec {
        part: part.to_string(),
        reason: reason.into(),
    }
}

/// The reader of [`SurfacePatternSpec::parse`]: refuses every file.
fn no_files(name: &str) -> Result<Vec<u8>, TpiError> {
    Err(invalid(
        &format!("@{name}"),
        "files are not read here: give the JSON text inline in the spec (read the file and \
         put its text in place of @FILE)",
    ))
}

impl SurfacePatternSpec {
    /// Parses a spec (module doc) whose data is all inline: `@FILE` and density images are
    /// refused with [`TpiError::InvalidPatternSpec`].
    ///
    /// Errors: see the module doc.
    pub fn parse(text: &str) -> Result<SurfacePatternSpec, TpiError> {
        Self::parse_with(text, &mut no_files)
    }

    /// Parses a spec, calling `read` for the bytes of each file it names: each `@FILE`, and
    /// each image a density's `image` terms name (joined to the density file's folder when
    /// the density came from `@FILE`). `read`'s errors are returned as they are.
    ///
    /// Errors: see the module doc.
    pub fn parse_with(
        text: &str,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, TpiError>,
    ) -> Result<SurfacePatternSpec, TpiError> {
        let text = text.trim();
        if let Some(rest) = text.strip_prefix("relax:") {
            let (n, base) = rest.split_once(':').unwrap_or((rest, ""));
            let part = format!("relax:{n}");
            let iterations = n
                .parse::<usize>()
                .ok()
                .filter(|&k| k <= MAX_RELAX_ITERATIONS)
                .ok_or_else(|| {
                    invalid(
                        &part,
                        format!("expected a whole number of iterations from 0 to {MAX_RELAX_ITERATIONS}"),
                    )
                })?;
            if base.trim().is_empty() {
                return Err(invalid(
                    &part,
                    "relax:N needs the pattern to relax after it, e.g. relax:20:random:500",
                ));
            }
            let base = Self::parse_base(base.trim(), read)?;
            return match base {
                SurfacePatternSpec::Fit { .. } => Err(invalid(
                    &format!("{part}:fit"),
                    "a fit is not relaxed: it relaxes its own points, and relaxed they would \
                     no longer be checked against its tolerance",
                )),
                base => Ok(SurfacePatternSpec::Relax {
                    iterations,
                    base: Box::new(base),
                }),
            };
        }
        Self::parse_base(text, read)
    }

    fn parse_base(
        text: &str,
        read: &mut dyn FnMut(&str) -> Result<Vec<u8>, TpiError>,
    ) -> Result<SurfacePatternSpec, TpiError> {
        let (kind, rest) = text.split_once(':').unwrap_or((text, ""));
        match kind {
            "relax" => Err(invalid(
                "relax:...:relax",
                "relax once, with the sum of the iterations",
            )),
            "fit" => parse_fit(rest),
            "align" => parse_align(rest, read),
            "density" => parse_density(rest, read),
            "grid" | "hex" | "jitter" | "random" | "poisson" => {
                Ok(SurfacePatternSpec::Generator(Generator::parse(text)?))
            }
            "" => Err(invalid(
                text,
                format!("empty pattern spec; expected {FORMS}"),
            )),
            other => Err(invalid(
                other,
                format!("unknown pattern kind; expected {FORMS}"),
            )),
        }
    }

    /// Makes the points on `surface`; `options` are those of every discretisation the form
    /// runs (relaxation, fit). Deterministic: the same spec, surface and options give the
    /// same points.
    ///
    /// Errors: those of the form's function ([`crate::fit_pattern`], [`crate::relax()`],
    /// [`crate::aligned_pattern`], [`crate::density_pattern`]). A fit that does not meet its
    /// tolerance is not an error: see [`FitOutcome::met`].
    pub fn generate(
        &self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
    ) -> Result<SurfacePattern, TpiError> {
        self.generate_with_progress(surface, options, &NoProgress)
    }

    /// [`SurfacePatternSpec::generate`], reporting the stages of every discretisation the
    /// form runs (a fit's, a relaxation's) to `progress` ([`crate::Progress`]), which can
    /// cancel it between stages ([`TpiError::Cancelled`]). The points are the same as
    /// without an observer; a form that runs no discretisation reports nothing.
    pub fn generate_with_progress(
        &self,
        surface: &dyn Surface,
        options: &DiscretiseOptions,
        progress: &dyn Progress,
    ) -> Result<SurfacePattern, TpiError> {
        let plain = |uv| SurfacePattern { uv, fit: None };
        match self {
            SurfacePatternSpec::Generator(g) => {
                g.validate()?;
                Ok(plain(g.generate().uv))
            }
            SurfacePatternSpec::Fit {
                max_deviation,
                seed,
            } => {
                let f =
                    fit_pattern_with_progress(surface, *max_deviation, *seed, options, progress)?;
                Ok(SurfacePattern {
                    fit: Some(FitOutcome {
                        tolerance: *max_deviation,
                        met: f.met,
                        max_deviation: f.max_deviation,
                        invalid_facets: f.invalid_facets,
                        discretisations: f.discretisations,
                    }),
                    uv: f.uv,
                })
            }
            SurfacePatternSpec::Align { generator, field } => {
                let (lattice, count) = aligned_lattice(generator)?;
                Ok(plain(aligned_pattern(surface, lattice, count, field)?))
            }
            SurfacePatternSpec::Density(spec) => Ok(plain(density_pattern_with_progress(
                surface,
                spec,
                0,
                MAX_GENERATED_POINTS,
                options,
                progress,
            )?)),
            SurfacePatternSpec::Relax { iterations, base } => match base.as_ref() {
                SurfacePatternSpec::Density(spec) => Ok(plain(density_pattern_with_progress(
                    surface,
                    spec,
                    *iterations,
                    MAX_GENERATED_POINTS,
                    options,
                    progress,
                )?)),
                base => {
                    let start = base.generate_with_progress(surface, options, progress)?;
                    Ok(plain(relax_with_progress(
                        surface,
                        &start.uv,
                        *iterations,
                        options,
                        progress,
                    )?))
                }
            },
        }
    }
}

/// The lattice and point count an aligned pattern takes from a `hex:...` or `grid:...`
/// generator: NU * NV of its counts (from the spacing when given as `spacing=A`).
///
/// Errors: [`TpiError::InvalidPatternSpec`] for any other generator.
pub fn aligned_lattice(generator: &Generator) -> Result<(Lattice, usize), TpiError> {
    generator.validate()?;
    match generator {
        Generator::Hex(size) => {
            let (nu, nv) = size.hex_counts();
            Ok((Lattice::Hex, nu * nv))
        }
        Generator::Grid(size) => {
            let (nu, nv) = size.square_counts();
            Ok((Lattice::Grid, nu * nv))
        }
        other => Err(invalid(
            &other.to_string(),
            "an aligned pattern lays a hex or grid lattice: give hex:NUxNV, hex:spacing=A, \
             grid:NUxNV or grid:spacing=A",
        )),
    }
}

/// `fit:` and what follows: D, then optionally seed=S.
fn parse_fit(rest: &str) -> Result<SurfacePatternSpec, TpiError> {
    let mut tokens = rest.split(':');
    let d = tokens.next().unwrap_or("");
    let max_deviation = d
        .parse::<f64>()
        .ok()
        .filter(|x| x.is_finite() && *x > 0.0)
        .ok_or_else(|| {
            invalid(
                &format!("fit:{d}"),
                "expected the largest deviation D, a positive number (model units), e.g. fit:0.01",
            )
        })?;
    let mut seed = 0;
    for (k, token) in tokens.enumerate() {
        match token.strip_prefix("seed=") {
            Some(s) if k == 0 => {
                seed = s.parse::<u64>().map_err(|_| {
                    invalid(token, "the seed is an unsigned 64-bit integer, e.g. seed=7")
                })?;
            }
            _ => {
                return Err(invalid(
                    token,
                    "fit takes D and optionally seed=S: fit:D[:seed=S]",
                ))
            }
        }
    }
    Ok(SurfacePatternSpec::Fit {
        max_deviation,
        seed,
    })
}

/// `align:` and what follows: `hex|grid`, the size, then the field to the end.
fn parse_align(
    rest: &str,
    read: &mut dyn FnMut(&str) -> Result<Vec<u8>, TpiError>,
) -> Result<SurfacePatternSpec, TpiError> {
    let mut pieces = rest.splitn(3, ':');
    let kind = pieces.next().unwrap_or("");
    let size = pieces.next().unwrap_or("");
    let field = pieces.next().unwrap_or("").trim();
    if kind != "hex" && kind != "grid" {
        return Err(invalid(
            &format!("align:{kind}"),
            "align:LATTICE:FIELD lays a hex or grid lattice, e.g. align:hex:24x20:principal",
        ));
    }
    let generator = Generator::parse(&format!("{kind}:{size}"))?;
    aligned_lattice(&generator)?;
    if field.is_empty() {
        return Err(invalid(
            &format!("align:{kind}:{size}"),
            "the direction field is missing: principal, asymptotic, uv:ANGLE, {JSON} or @FILE",
        ));
    }
    let field = match data(field, "align field", read)? {
        Some((json, context, _)) => AlignField::File(DirectionField::from_json(&json, &context)?),
        None => AlignField::parse(field).map_err(|e| match e {
            TpiError::InvalidParameter { reason, .. } => {
                invalid(field, reason.replace("field:FILE.json", "{JSON} or @FILE"))
            }
            other => other,
        })?,
    };
    Ok(SurfacePatternSpec::Align { generator, field })
}

/// `density:` and what follows: the density field's JSON, inline or `@FILE`.
fn parse_density(
    rest: &str,
    read: &mut dyn FnMut(&str) -> Result<Vec<u8>, TpiError>,
) -> Result<SurfacePatternSpec, TpiError> {
    let rest = rest.trim();
    let Some((json, context, folder)) = data(rest, "density", read)? else {
        return Err(invalid(
            &format!("density:{rest}"),
            "expected the density field's JSON inline, density:{\"spacing\": ..., \"terms\": \
             [...]}, or a file, density:@FILE (docs/formats.md)",
        ));
    };
    let mut spec = DensitySpec::from_json(&json, &context)?;
    for (index, image) in spec.image_files() {
        let name = match &folder {
            Some(dir) if !std::path::Path::new(&image).is_absolute() => {
                std::path::Path::new(dir).join(&image).display().to_string()
            }
            _ => image.clone(),
        };
        let bytes = read(&name).map_err(|e| match e {
            TpiError::InvalidPatternSpec { reason, .. } => invalid(
                &format!("terms[{index}].file {name}"),
                format!("the density's image: {reason}"),
            ),
            other => other,
        })?;
        spec.attach_image(index, GreyImage::from_pgm(&bytes, &name)?);
    }
    Ok(SurfacePatternSpec::Density(Box::new(spec)))
}

/// JSON data: inline `{...}` (its errors' context: `label`) or `@FILE` read through `read`
/// (context: the file name; folder: the file's folder). None when `text` is neither.
fn data(
    text: &str,
    label: &str,
    read: &mut dyn FnMut(&str) -> Result<Vec<u8>, TpiError>,
) -> Result<Option<(String, String, Option<String>)>, TpiError> {
    if text.starts_with('{') {
        return Ok(Some((
            text.to_string(),
            format!("{label} (inline JSON)"),
            None,
        )));
    }
    let Some(name) = text.strip_prefix('@') else {
        return Ok(None);
    };
    if name.is_empty() {
        return Err(invalid("@", "expected a file name after @"));
    }
    let bytes = read(name)?;
    let json = String::from_utf8(bytes)
        .map_err(|_| invalid(&format!("@{name}"), "the file is not UTF-8 text"))?;
    let folder = std::path::Path::new(name)
        .parent()
        .map(|p| p.display().to_string());
    Ok(Some((json, name.to_string(), folder)))
}

impl fmt::Display for SurfacePatternSpec {
    /// A short description: the spec itself for the forms without data, with the data
    /// summarised (`density(3 terms)`, `field(33x33 nodes)`).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SurfacePatternSpec::Generator(g) => write!(f, "{g}"),
            SurfacePatternSpec::Fit {
                max_deviation,
                seed,
            } => write!(f, "fit:{max_deviation}:seed={seed}"),
            SurfacePatternSpec::Relax { iterations, base } => {
                write!(f, "relax:{iterations}:{base}")
            }
            SurfacePatternSpec::Align { generator, field } => {
                write!(f, "align:{generator}:")?;
                match field {
                    AlignField::Principal => f.write_str("principal"),
                    AlignField::Asymptotic => f.write_str("asymptotic"),
                    AlignField::Uv(a) => write!(f, "uv:{a}"),
                    AlignField::File(d) => write!(f, "field({}x{} nodes)", d.size[0], d.size[1]),
                }
            }
            SurfacePatternSpec::Density(d) => write!(
                f,
                "density({} term{}, spacing {})",
                d.terms.len(),
                if d.terms.len() == 1 { "" } else { "s" },
                d.spacing
            ),
        }
    }
}
