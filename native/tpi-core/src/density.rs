//! Density fields: patterns whose points crowd where the designer wants them (issue 15,
//! item 4), as a Poisson-disk sampling of varying radius measured on the surface, optionally
//! relaxed by Lloyd's iteration following the same density.
//!
//! A density field is a product of terms, each a function rho_k(s, t) >= 0 of the place on the
//! surface; the local spacing is h = spacing / sqrt(rho), rho = prod_k rho_k, so the number of
//! points per unit surface area goes as rho. With `ratio` R the density is clamped to
//! [rho_max / R^2, rho_max] (rho_max its largest value on the field's nodes), so the spacing
//! varies at most by the factor R. The terms (JSON, `docs/formats.md`):
//!
//! | term | rho |
//! |------|-----|
//! | `{"type": "attractor", "uv": [s, t], "radius": r, "peak": p}` | 1 + (p - 1) f(d / r), d the distance in the normalised square |
//! | `{"type": "attractor", "point": [x, y, z], "radius": r, "peak": p}` | the same, d the distance in space from the surface point (model units) |
//! | `{"type": "curve", "uv": [[s, t], ...], ...}` / `"points": [[x, y, z], ...]` | the same, d the distance to the polyline |
//! | `{"type": "curvature", "exponent": e}` | (kappa / kappa_max)^e, kappa = max(abs(k1), abs(k2)) (e = 1: spacing as 1 / sqrt(kappa), the tolerance rule), floored at 1e-3 |
//! | `{"type": "image", "file": "F.pgm", "low": a, "high": b}` | a + (b - a) g, g in [0, 1] the grey level (white 1) of a binary or ASCII PGM (P5 / P2) stretched over the square, s to the right, t upwards, bilinear |
//!
//! The falloff is f(x) = 1 - 3 x^2 + 2 x^3 for x < 1, 0 beyond (smooth, 1 at the attractor).
//! The field is tabulated on [`DENSITY_NODES`]^2 nodes as an isotropic sizing field
//! (`sizing.rs`): M = G rho / spacing^2.

use serde::Deserialize;

use crate::diffgeo::LocalGeometry;
use crate::error::TpiError;
use crate::progress::{NoProgress, Progress};
use crate::relax::relax_weighted;
use crate::sizing::{largest_regular_curvature, metric_poisson, node_geometry, SizingField};
use crate::surface::Surface;
use crate::DiscretiseOptions;

/// Nodes per side of a density field's table.
pub const DENSITY_NODES: usize = 129;
/// Smallest relative curvature a curvature term keeps (so flat places keep some density).
const CURVATURE_TERM_FLOOR: f64 = 1e-3;

/// A density field (module doc): the JSON record of `tpi pattern --density FILE`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DensitySpec {
    /// Poisson-disk spacing where the density is 1 (model units, > 0).
    pub spacing: f64,
    /// Largest ratio of spacings over the surface (>= 1); none: unbounded.
    #[serde(default)]
    pub ratio: Option<f64>,
    /// Random seed of the sampling. Default 0.
    #[serde(default)]
    pub seed: u64,
    /// The terms, multiplied.
    pub terms: Vec<DensityTerm>,
}

/// One factor of a density field (module doc).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum DensityTerm {
    /// Density raised near a point (uv or 3D).
    Attractor {
        /// The point in the normalised square.
        #[serde(default)]
        uv: Option<[f64; 2]>,
        /// The point in space (model units).
        #[serde(default)]
        point: Option<[f64; 3]>,
        /// Distance at which the effect ends (normalised for uv, model units for 3D).
        radius: f64,
        /// Density at the point (> 0; below 1 repels).
        peak: f64,
    },
    /// Density raised near a polyline (uv or 3D).
    Curve {
        /// The polyline in the normalised square.
        #[serde(default)]
        uv: Option<Vec<[f64; 2]>>,
        /// The polyline in space (model units).
        #[serde(default)]
        points: Option<Vec<[f64; 3]>>,
        /// Distance at which the effect ends.
        radius: f64,
        /// Density on the curve (> 0).
        peak: f64,
    },
    /// Density following curvature.
    Curvature {
        /// The power of the relative curvature (>= 0).
        exponent: f64,
    },
    /// Density from a grey-level image.
    Image {
        /// The PGM file (relative to the density file).
        file: String,
        /// Density where the image is black (> 0).
        low: f64,
        /// Density where the image is white (> 0).
        high: f64,
        /// The decoded image, attached by [`DensitySpec::attach_image`].
        #[serde(skip)]
        pixels: Option<GreyImage>,
    },
}

/// A grey-level image, values in [0, 1], row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct GreyImage {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Row-major values in [0, 1].
    pub values: Vec<f64>,
}

impl GreyImage {
    /// Reads a binary (P5, 8 or 16 bits) or ASCII (P2) PGM.
    ///
    /// Errors: [`TpiError::Parse`] naming `context` and what is wrong.
    pub fn from_pgm(bytes: &[u8], context: &str) -> Result<GreyImage, TpiError> {
        let fail = |message: &str| TpiError::Parse {
            context: context.to_string(),
            message: format!("not a readable PGM image: {message}"),
            line: 0,
            column: 0,
        };
        let mut pos = 0usize;
        // Whitespace-separated header tokens, skipping # comments.
        let mut token = |bytes: &[u8]| -> Option<String> {
            loop {
                while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
                    pos += 1;
                }
                if pos < bytes.len() && bytes[pos] == b'#' {
                    while pos < bytes.len() && bytes[pos] != b'\n' {
                        pos += 1;
                    }
                    continue;
                }
                break;
            }
            let start = pos;
            while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
                pos += 1;
            }
            (pos > start).then(|| String::from_utf8_lossy(&bytes[start..pos]).into_owned())
        };
        let magic = token(bytes).ok_or_else(|| fail("empty file"))?;
        let number = |t: Option<String>, what: &str| -> Result<usize, TpiError> {
            t.and_then(|t| t.parse::<usize>().ok())
                .ok_or_else(|| fail(&format!("no {what} in the header")))
        };
        let width = number(token(bytes), "width")?;
        let height = number(token(bytes), "height")?;
        let max = number(token(bytes), "maximum value")?;
        if width == 0 || height == 0 || width > 1 << 14 || height > 1 << 14 {
            return Err(fail("width and height must be 1 to 16384"));
        }
        if max == 0 || max > 65535 {
            return Err(fail("the maximum value must be 1 to 65535"));
        }
        let count = width * height;
        let mut values = Vec::with_capacity(count);
        match magic.as_str() {
            "P5" => {
                pos += 1; // the single whitespace after the header
                let wide = max > 255;
                let need = count * if wide { 2 } else { 1 };
                let data = bytes
                    .get(pos..pos + need)
                    .ok_or_else(|| fail("the pixel data is shorter than width x height"))?;
                for k in 0..count {
                    let v = if wide {
                        u16::from_be_bytes([data[2 * k], data[2 * k + 1]]) as usize
                    } else {
                        data[k] as usize
                    };
                    values.push((v.min(max)) as f64 / max as f64);
                }
            }
            "P2" => {
                for _ in 0..count {
                    let v = number(token(bytes), "pixel value")?;
                    values.push(v.min(max) as f64 / max as f64);
                }
            }
            _ => return Err(fail("expected the magic number P5 or P2")),
        }
        Ok(GreyImage {
            width,
            height,
            values,
        })
    }

    /// The grey level at (s, t) of the unit square (s to the right, t upwards), bilinear
    /// between pixel centres.
    pub fn sample(&self, st: [f64; 2]) -> f64 {
        let x =
            (st[0].clamp(0.0, 1.0) * self.width as f64 - 0.5).clamp(0.0, (self.width - 1) as f64);
        let y = ((1.0 - st[1].clamp(0.0, 1.0)) * self.height as f64 - 0.5)
            .clamp(0.0, (self.height - 1) as f64);
        let (i, j) = (x.floor() as usize, y.floor() as usize);
        let (i1, j1) = ((i + 1).min(self.width - 1), (j + 1).min(self.height - 1));
        let (fx, fy) = (x - i as f64, y - j as f64);
        let at = |a: usize, b: usize| self.values[b * self.width + a];
        (1.0 - fy) * ((1.0 - fx) * at(i, j) + fx * at(i1, j))
            + fy * ((1.0 - fx) * at(i, j1) + fx * at(i1, j1))
    }
}

/// The smooth falloff of attractors: 1 - 3 x^2 + 2 x^3 below 1, 0 beyond.
fn falloff(x: f64) -> f64 {
    if x >= 1.0 {
        0.0
    } else {
        let x = x.max(0.0);
        1.0 - x * x * (3.0 - 2.0 * x)
    }
}

/// Distance from p to the segment ab (any dimension, as slices).
fn segment_distance(p: &[f64], a: &[f64], b: &[f64]) -> f64 {
    let ab: Vec<f64> = a.iter().zip(b).map(|(x, y)| y - x).collect();
    let ap: Vec<f64> = a.iter().zip(p).map(|(x, y)| y - x).collect();
    let len2: f64 = ab.iter().map(|x| x * x).sum();
    let t = if len2 > 0.0 {
        (ab.iter().zip(&ap).map(|(x, y)| x * y).sum::<f64>() / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ap.iter()
        .zip(&ab)
        .map(|(x, y)| (x - t * y).powi(2))
        .sum::<f64>()
        .sqrt()
}

impl DensitySpec {
    /// Reads a density file (module doc) and checks it ([`DensitySpec::validate`]); image
    /// terms still need their pixels ([`DensitySpec::attach_image`]).
    ///
    /// Errors: [`TpiError::Parse`] for malformed JSON or unknown fields, then those of
    /// [`DensitySpec::validate`].
    pub fn from_json(text: &str, context: &str) -> Result<DensitySpec, TpiError> {
        let spec: DensitySpec = crate::spec::read(text, context)?;
        spec.validate()?;
        Ok(spec)
    }

    /// Checks the numbers: spacing positive, ratio at least 1, radii and peaks positive,
    /// exponents non-negative, exactly one of uv or 3D per attractor and curve, curves of
    /// at least one point.
    ///
    /// Errors: [`TpiError::InvalidParameter`] naming the field.
    pub fn validate(&self) -> Result<(), TpiError> {
        let bad = |field: String, value: f64, reason: &str| {
            Err(TpiError::InvalidParameter {
                field,
                value,
                reason: reason.into(),
            })
        };
        let positive = |x: f64| x.is_finite() && x > 0.0;
        if !positive(self.spacing) {
            return bad("spacing".into(), self.spacing, "must be a positive number");
        }
        if let Some(r) = self.ratio {
            if !(r.is_finite() && r >= 1.0) {
                return bad("ratio".into(), r, "must be a number >= 1");
            }
        }
        // An attractor's or a curve's falloff: its radius and its peak, both positive.
        let falloff = |name: &dyn Fn(&str) -> String, radius: f64, peak: f64| {
            if !positive(radius) {
                return bad(name("radius"), radius, "must be a positive number");
            }
            if !positive(peak) {
                return bad(name("peak"), peak, "must be a positive number");
            }
            Ok(())
        };
        for (k, term) in self.terms.iter().enumerate() {
            let name = |f: &str| format!("terms[{k}].{f}");
            match term {
                DensityTerm::Attractor {
                    uv,
                    point,
                    radius,
                    peak,
                } => {
                    if uv.is_some() == point.is_some() {
                        return bad(name("uv"), f64::NAN, "give exactly one of uv and point");
                    }
                    let finite = uv
                        .iter()
                        .flatten()
                        .chain(point.iter().flatten())
                        .all(|x| x.is_finite());
                    if !finite {
                        return bad(name("uv"), f64::NAN, "coordinates must be finite");
                    }
                    falloff(&name, *radius, *peak)?;
                }
                DensityTerm::Curve {
                    uv,
                    points,
                    radius,
                    peak,
                } => {
                    let count = uv.as_ref().map(Vec::len).or(points.as_ref().map(Vec::len));
                    if uv.is_some() == points.is_some() || count == Some(0) {
                        return bad(
                            name("uv"),
                            f64::NAN,
                            "give exactly one of uv and points, with at least one point",
                        );
                    }
                    let finite = uv
                        .iter()
                        .flatten()
                        .flatten()
                        .chain(points.iter().flatten().flatten())
                        .all(|x| x.is_finite());
                    if !finite {
                        return bad(name("uv"), f64::NAN, "coordinates must be finite");
                    }
                    falloff(&name, *radius, *peak)?;
                }
                DensityTerm::Curvature { exponent } => {
                    if !(exponent.is_finite() && *exponent >= 0.0 && *exponent <= 8.0) {
                        return bad(name("exponent"), *exponent, "must be a number in [0, 8]");
                    }
                }
                DensityTerm::Image { low, high, .. } => {
                    if !positive(*low) {
                        return bad(name("low"), *low, "must be a positive number");
                    }
                    if !positive(*high) {
                        return bad(name("high"), *high, "must be a positive number");
                    }
                }
            }
        }
        Ok(())
    }

    /// The image files the terms name, with their term indices.
    pub fn image_files(&self) -> Vec<(usize, String)> {
        self.terms
            .iter()
            .enumerate()
            .filter_map(|(k, t)| match t {
                DensityTerm::Image { file, .. } => Some((k, file.clone())),
                _ => None,
            })
            .collect()
    }

    /// Gives image term `index` its decoded pixels.
    pub fn attach_image(&mut self, index: usize, image: GreyImage) {
        if let Some(DensityTerm::Image { pixels, .. }) = self.terms.get_mut(index) {
            *pixels = Some(image);
        }
    }

    /// The density (before the ratio bound) at normalised `st` with the local geometry
    /// there; `kappa_max` the surface's largest curvature.
    fn density(&self, st: [f64; 2], geometry: &LocalGeometry, kappa_max: f64) -> f64 {
        let p = geometry.point.to_array();
        self.terms
            .iter()
            .map(|term| match term {
                DensityTerm::Attractor {
                    uv,
                    point,
                    radius,
                    peak,
                } => {
                    let d = match (uv, point) {
                        (Some(a), _) => (st[0] - a[0]).hypot(st[1] - a[1]),
                        (_, Some(a)) => segment_distance(&p, a, a),
                        _ => f64::INFINITY,
                    };
                    1.0 + (peak - 1.0) * falloff(d / radius)
                }
                DensityTerm::Curve {
                    uv,
                    points,
                    radius,
                    peak,
                } => {
                    let d = match (uv, points) {
                        (Some(line), _) => polyline_distance(&st, line),
                        (_, Some(line)) => polyline_distance(&p, line),
                        _ => f64::INFINITY,
                    };
                    1.0 + (peak - 1.0) * falloff(d / radius)
                }
                DensityTerm::Curvature { exponent } => {
                    let k = geometry.k1.abs().max(geometry.k2.abs());
                    // At most 1: a singular node ([`largest_regular_curvature`]) is not
                    // denser than the most curved regular place.
                    let relative = if kappa_max > 0.0 {
                        (k / kappa_max).min(1.0)
                    } else {
                        1.0
                    };
                    relative.max(CURVATURE_TERM_FLOOR).powf(*exponent)
                }
                DensityTerm::Image {
                    low, high, pixels, ..
                } => {
                    let g = pixels.as_ref().map_or(1.0, |img| img.sample(st));
                    low + (high - low) * g
                }
            })
            .product()
    }

    /// The isotropic sizing field of this density on `surface` (module doc).
    ///
    /// Errors: [`TpiError::InvalidParameter`] when an image term has no pixels attached.
    pub(crate) fn field(&self, surface: &dyn Surface) -> Result<SizingField, TpiError> {
        if let Some((k, file)) = self.terms.iter().enumerate().find_map(|(k, t)| match t {
            DensityTerm::Image {
                file, pixels: None, ..
            } => Some((k, file.clone())),
            _ => None,
        }) {
            return Err(TpiError::InvalidParameter {
                field: format!("terms[{k}].file"),
                value: f64::NAN,
                reason: format!("the image {file} was not read"),
            });
        }
        let largest = |values: Vec<Option<f64>>| {
            values
                .into_iter()
                .flatten()
                .filter(|x| x.is_finite())
                .fold(0.0, f64::max)
        };
        let kappa_max = largest_regular_curvature(surface, DENSITY_NODES);
        let top = largest(node_geometry(surface, DENSITY_NODES, |_, g, _, st| {
            self.density(st, g, kappa_max)
        }));
        let floor = match self.ratio {
            Some(r) => top / (r * r),
            None => top * 1e-12,
        };
        let spacing = self.spacing;
        Ok(SizingField::isotropic(
            surface,
            DENSITY_NODES,
            move |st, g| {
                let rho = self.density(st, g, kappa_max).clamp(floor, top.max(floor));
                spacing / rho.sqrt()
            },
        ))
    }
}

/// Distance from p to a polyline (a single point: the distance to it).
fn polyline_distance<const N: usize>(p: &[f64; N], line: &[[f64; N]]) -> f64 {
    if line.len() == 1 {
        return segment_distance(p, &line[0], &line[0]);
    }
    line.windows(2)
        .map(|w| segment_distance(p, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}

/// Points following a density field on a surface: the Poisson-disk sampling of the field's
/// spacing (at most `max_points`), then `relax` Lloyd iterations weighted by the same
/// density (0: none).
///
/// Errors: those of `DensitySpec::field` and of the discretisations of the relaxation.
pub fn density_pattern(
    surface: &dyn Surface,
    spec: &DensitySpec,
    relax: usize,
    max_points: usize,
    options: &DiscretiseOptions,
) -> Result<Vec<[f64; 2]>, TpiError> {
    density_pattern_with_progress(surface, spec, relax, max_points, options, &NoProgress)
}

/// [`density_pattern`], reporting the stages of the relaxation's discretisations to
/// `progress`, which can cancel them ([`TpiError::Cancelled`]).
pub(crate) fn density_pattern_with_progress(
    surface: &dyn Surface,
    spec: &DensitySpec,
    relax: usize,
    max_points: usize,
    options: &DiscretiseOptions,
    progress: &dyn Progress,
) -> Result<Vec<[f64; 2]>, TpiError> {
    spec.validate()?;
    let field = spec.field(surface)?;
    let points = metric_poisson(&field, 1.0, spec.seed, max_points);
    if relax == 0 {
        return Ok(points);
    }
    let density = |st: [f64; 2]| field.lloyd_density(st);
    relax_weighted(surface, &points, relax, options, Some(&density), progress)
}
