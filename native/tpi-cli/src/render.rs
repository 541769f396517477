//! The PNG picture: a shaded 3D view of the mesh, rendered in-process.
//!
//! A small software rasteriser: orthographic view from above at an angle (azimuth -60 deg,
//! elevation 40 deg), each facet triangulated (ear clipping in its own plane, so that
//! non-convex facets of saddle regions fill correctly), z-buffered, Lambert-shaded with a
//! fixed light relative to the view and lit from both sides, coloured by side count or by
//! deviation from the surface ([`Colouring`]). Edges are drawn dark (flagged facets' edges
//! red) with a depth bias, seeds optionally as dots on the surface, and the image is rendered
//! at twice the resolution and averaged down for anti-aliasing. A legend of the colours sits
//! in the lower left corner.

use std::collections::HashMap;

use glam::{DVec2, DVec3};
use tpi_core::Discretisation;

use crate::font::{self, Image};
use crate::palette::{deviation_colour, side_class, side_colour, EDGE_COLOUR, FLAG_COLOUR};

/// Default picture size.
pub(crate) const DEFAULT_SIZE: (u32, u32) = (1200, 900);

/// Largest accepted picture side.
pub(crate) const MAX_SIDE: u32 = 16_384;

/// How the facets are coloured.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Colouring<'a> {
    /// By side count (the palette's classes).
    Sides,
    /// By each facet's deviation (model units, one per facet) over `scale`: the ramp of
    /// [`deviation_colour`], red at `scale` and beyond.
    Deviation {
        /// Per facet, the largest distance of its vertices from the surface.
        per_facet: &'a [f64],
        /// The deviation drawn red (a tolerance, or the largest deviation).
        scale: f64,
    },
}

/// Per facet, the largest distance of its vertices from the surface (model units), as the
/// quality report measures it ([`tpi_core::vertex_deviations`]).
pub(crate) fn facet_deviations(
    surface: &dyn tpi_core::Surface,
    result: &Discretisation,
) -> Vec<f64> {
    let per_vertex = tpi_core::vertex_deviations(surface, result);
    (0..result.facet_count())
        .map(|i| {
            result
                .facet(i)
                .iter()
                .map(|&v| per_vertex.get(v as usize).copied().unwrap_or(f64::NAN))
                .fold(0.0, f64::max)
        })
        .collect()
}

/// What to draw besides the facets.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Picture<'a> {
    /// The facets' colours.
    pub colouring: Colouring<'a>,
    /// Whether each facet's seed is drawn as a dot on the surface.
    pub seeds: bool,
}

/// Renders the mesh into an RGB image of `width` x `height` (row-major, 3 bytes a pixel),
/// with the colours and seeds of `picture`.
pub(crate) fn render_picture(
    result: &Discretisation,
    width: u32,
    height: u32,
    picture: Picture<'_>,
) -> Vec<u8> {
    let ss: usize = if (width as usize) * (height as usize) <= 16_000_000 {
        2
    } else {
        1
    };
    let (w, h) = (width as usize * ss, height as usize * ss);
    let mut canvas = Canvas::new(w, h);
    // Background: a soft vertical gradient.
    for y in 0..h {
        let t = y as f32 / h.max(1) as f32;
        let c = [
            lerp(238.0, 212.0, t),
            lerp(242.0, 220.0, t),
            lerp(246.0, 228.0, t),
        ];
        for x in 0..w {
            canvas.colour[y * w + x] = c;
        }
    }

    let finite: Vec<DVec3> = crate::palette::framing_points(result);
    if !finite.is_empty() && result.facet_count() > 0 {
        let camera = Camera::fit(&finite, w as f64, h as f64, ss as f64 * 40.0);
        draw_mesh(&mut canvas, result, &camera, ss, picture.colouring);
        if picture.seeds {
            draw_seeds(&mut canvas, result, &camera, ss);
        }
    }
    let mut rgb = canvas.downsample(ss, width as usize, height as usize);
    let mut image = Image {
        rgb: &mut rgb,
        w: width as usize,
        h: height as usize,
    };
    match picture.colouring {
        Colouring::Sides => legend(&mut image, result),
        Colouring::Deviation { scale, .. } => deviation_legend(&mut image, scale),
    }
    rgb
}

/// Encodes an RGB image as PNG.
pub(crate) fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(rgb).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())?;
    }
    Ok(bytes)
}

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + (b - a) * t
}

struct Canvas {
    w: usize,
    h: usize,
    colour: Vec<[f32; 3]>,
    depth: Vec<f32>,
    /// 0: no edge, 1: dark edge, 2: flagged edge.
    edge: Vec<u8>,
}

impl Canvas {
    fn new(w: usize, h: usize) -> Self {
        Self {
            w,
            h,
            colour: vec![[0.0; 3]; w * h],
            depth: vec![f32::INFINITY; w * h],
            edge: vec![0; w * h],
        }
    }

    fn downsample(&self, ss: usize, width: usize, height: usize) -> Vec<u8> {
        let mut out = vec![0u8; width * height * 3];
        let n = (ss * ss) as f32;
        for y in 0..height {
            for x in 0..width {
                let mut acc = [0.0f32; 3];
                for dy in 0..ss {
                    for dx in 0..ss {
                        let i = (y * ss + dy) * self.w + x * ss + dx;
                        let c = match self.edge[i] {
                            1 => mix(self.colour[i], EDGE_COLOUR, 0.85),
                            2 => mix(self.colour[i], FLAG_COLOUR, 0.95),
                            _ => self.colour[i],
                        };
                        for k in 0..3 {
                            acc[k] += c[k];
                        }
                    }
                }
                for k in 0..3 {
                    out[(y * width + x) * 3 + k] = (acc[k] / n).round().clamp(0.0, 255.0) as u8;
                }
            }
        }
        out
    }
}

fn mix(a: [f32; 3], b: [u8; 3], t: f32) -> [f32; 3] {
    [
        lerp(a[0], b[0] as f32, t),
        lerp(a[1], b[1] as f32, t),
        lerp(a[2], b[2] as f32, t),
    ]
}

/// A projected point: pixel x (right), pixel y (down), depth (larger is farther).
type Screen = (f64, f64, f64);

/// Orthographic camera: world -> (pixel x, pixel y, depth).
struct Camera {
    centre: DVec3,
    right: DVec3,
    up: DVec3,
    forward: DVec3,
    scale: f64,
    offset: DVec2,
    light: DVec3,
    extent: f64,
}

impl Camera {
    fn fit(points: &[DVec3], w: f64, h: f64, legend_space: f64) -> Self {
        let (az, el) = ((-60.0f64).to_radians(), 40.0f64.to_radians());
        let eye = DVec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let forward = -eye;
        let right = forward.cross(DVec3::Z).normalize();
        let up = right.cross(forward);
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        for &p in points {
            lo = lo.min(p);
            hi = hi.max(p);
        }
        let centre = (lo + hi) / 2.0;
        let (mut smin, mut smax) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
        for &p in points {
            let d = p - centre;
            let s = DVec2::new(d.dot(right), d.dot(up));
            smin = smin.min(s);
            smax = smax.max(s);
        }
        let span = (smax - smin).max(DVec2::splat(1e-300));
        let margin = 0.06;
        let avail = DVec2::new(
            w * (1.0 - 2.0 * margin),
            h * (1.0 - 2.0 * margin) - legend_space,
        );
        let scale = (avail.x / span.x).min(avail.y / span.y);
        let mid = (smin + smax) / 2.0;
        let offset = DVec2::new(
            w / 2.0 - mid.x * scale,
            (h - legend_space) / 2.0 + mid.y * scale,
        );
        let light = (-0.45 * right + 0.6 * up - 0.65 * forward).normalize();
        Self {
            centre,
            right,
            up,
            forward,
            scale,
            offset,
            light,
            extent: (hi - lo).length().max(1e-300),
        }
    }

    /// Pixel x (right), pixel y (down), depth (larger is farther).
    fn project(&self, p: DVec3) -> Screen {
        let d = p - self.centre;
        (
            self.offset.x + d.dot(self.right) * self.scale,
            self.offset.y - d.dot(self.up) * self.scale,
            d.dot(self.forward),
        )
    }
}

fn draw_mesh(
    canvas: &mut Canvas,
    result: &Discretisation,
    cam: &Camera,
    ss: usize,
    colouring: Colouring<'_>,
) {
    let projected: Vec<Screen> = result.vertices.iter().map(|&v| cam.project(v)).collect();
    let mut edges: HashMap<(u32, u32), bool> = HashMap::new();
    let mut lengths: Vec<f64> = Vec::new();
    for i in 0..result.facet_count() {
        let facet = result.facet(i);
        if facet.len() < 3
            || facet
                .iter()
                .any(|&k| !result.vertices[k as usize].is_finite())
        {
            continue;
        }
        let points: Vec<DVec3> = facet.iter().map(|&k| result.vertices[k as usize]).collect();
        let mut normal = newell_normal(&points);
        if normal == DVec3::ZERO {
            normal = result.seeds[i].normal;
        }
        if normal.dot(cam.forward) > 0.0 {
            normal = -normal;
        }
        let lambert = normal.dot(cam.light).max(0.0) as f32;
        let intensity = 0.32 + 0.68 * lambert;
        let base = match colouring {
            Colouring::Sides => side_colour(side_class(facet.len())),
            Colouring::Deviation { per_facet, scale } => {
                deviation_colour(per_facet.get(i).copied().unwrap_or(f64::NAN) / scale)
            }
        };
        let colour = [
            base[0] as f32 * intensity,
            base[1] as f32 * intensity,
            base[2] as f32 * intensity,
        ];
        for [a, b, c] in triangulate(&points, normal) {
            fill_triangle(
                canvas,
                projected[facet[a] as usize],
                projected[facet[b] as usize],
                projected[facet[c] as usize],
                colour,
            );
        }
        let flagged = result.facet_flags.get(i).copied().unwrap_or(0) != 0;
        for k in 0..facet.len() {
            let (a, b) = (facet[k], facet[(k + 1) % facet.len()]);
            let key = (a.min(b), a.max(b));
            let entry = edges.entry(key).or_insert(false);
            *entry |= flagged;
            let (pa, pb) = (projected[a as usize], projected[b as usize]);
            lengths.push(((pa.0 - pb.0).powi(2) + (pa.1 - pb.1).powi(2)).sqrt());
        }
    }
    // Edge width follows the mesh density (median edge length on screen): thin lines for dense meshes.
    lengths.sort_by(f64::total_cmp);
    let median = lengths.get(lengths.len() / 2).copied().unwrap_or(0.0) / ss as f64;
    let radius = ss as f64 * if median > 12.0 { 0.75 } else { 0.5 };
    let bias = (cam.extent * 2e-3) as f32;
    let mut ordered: Vec<(&(u32, u32), &bool)> = edges.iter().collect();
    ordered.sort_by_key(|(k, f)| (**f, **k));
    for (&(a, b), &flagged) in ordered {
        let r = if flagged { radius * 1.25 } else { radius };
        draw_line(
            canvas,
            projected[a as usize],
            projected[b as usize],
            r,
            bias,
            if flagged { 2 } else { 1 },
        );
    }
}

/// Newell's normal of a planar polygon (zero for a degenerate one).
fn newell_normal(points: &[DVec3]) -> DVec3 {
    let mut n = DVec3::ZERO;
    for k in 0..points.len() {
        let (a, b) = (points[k], points[(k + 1) % points.len()]);
        n += DVec3::new(
            (a.y - b.y) * (a.z + b.z),
            (a.z - b.z) * (a.x + b.x),
            (a.x - b.x) * (a.y + b.y),
        );
    }
    n.try_normalize().unwrap_or(DVec3::ZERO)
}

/// Ear clipping of a planar polygon in its own plane; a fan where it fails (non-simple input).
fn triangulate(points: &[DVec3], normal: DVec3) -> Vec<[usize; 3]> {
    let n = points.len();
    let fan = || (1..n - 1).map(|k| [0, k, k + 1]).collect::<Vec<_>>();
    if n == 3 {
        return vec![[0, 1, 2]];
    }
    let a = normal.any_orthonormal_vector();
    let b = normal.cross(a);
    let p: Vec<DVec2> = points
        .iter()
        .map(|&x| DVec2::new(x.dot(a), x.dot(b)))
        .collect();
    let area: f64 = (0..n).map(|k| p[k].perp_dot(p[(k + 1) % n])).sum();
    let mut idx: Vec<usize> = (0..n).collect();
    if area < 0.0 {
        idx.reverse();
    }
    let mut out = Vec::with_capacity(n - 2);
    let cross = |o: DVec2, u: DVec2, v: DVec2| (u - o).perp_dot(v - o);
    while idx.len() > 3 {
        let m = idx.len();
        let mut clipped = false;
        for k in 0..m {
            let (i0, i1, i2) = (idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]);
            let (a0, a1, a2) = (p[i0], p[i1], p[i2]);
            if cross(a0, a1, a2) <= 0.0 {
                continue;
            }
            let inside = idx.iter().any(|&j| {
                j != i0
                    && j != i1
                    && j != i2
                    && cross(a0, a1, p[j]) >= 0.0
                    && cross(a1, a2, p[j]) >= 0.0
                    && cross(a2, a0, p[j]) >= 0.0
            });
            if inside {
                continue;
            }
            out.push([i0, i1, i2]);
            idx.remove(k);
            clipped = true;
            break;
        }
        if !clipped {
            return fan();
        }
    }
    out.push([idx[0], idx[1], idx[2]]);
    out
}

fn fill_triangle(canvas: &mut Canvas, a: Screen, b: Screen, c: Screen, colour: [f32; 3]) {
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if !area.is_finite() || area.abs() < 1e-12 {
        return;
    }
    let x0 = a.0.min(b.0).min(c.0).floor().max(0.0) as usize;
    let x1 = (a.0.max(b.0).max(c.0).ceil() as isize).min(canvas.w as isize - 1);
    let y0 = a.1.min(b.1).min(c.1).floor().max(0.0) as usize;
    let y1 = (a.1.max(b.1).max(c.1).ceil() as isize).min(canvas.h as isize - 1);
    if x1 < 0 || y1 < 0 {
        return;
    }
    for y in y0..=y1 as usize {
        let py = y as f64 + 0.5;
        for x in x0..=x1 as usize {
            let px = x as f64 + 0.5;
            let w0 = ((b.0 - px) * (c.1 - py) - (b.1 - py) * (c.0 - px)) / area;
            let w1 = ((c.0 - px) * (a.1 - py) - (c.1 - py) * (a.0 - px)) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let z = (w0 * a.2 + w1 * b.2 + w2 * c.2) as f32;
            let i = y * canvas.w + x;
            if z < canvas.depth[i] {
                canvas.depth[i] = z;
                canvas.colour[i] = colour;
            }
        }
    }
}

/// The part of segment a-b inside the rectangle [lo, hi]^2 (Liang-Barsky), depth interpolated.
fn clip_segment(a: Screen, b: Screen, lo: (f64, f64), hi: (f64, f64)) -> Option<(Screen, Screen)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - lo.0),
        (dx, hi.0 - a.0),
        (-dy, a.1 - lo.1),
        (dy, hi.1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 || t0.is_nan() || t1.is_nan() {
        return None;
    }
    let at = |t: f64| (a.0 + t * dx, a.1 + t * dy, a.2 + t * (b.2 - a.2));
    Some((at(t0), at(t1)))
}

fn draw_line(canvas: &mut Canvas, a: Screen, b: Screen, radius: f64, bias: f32, kind: u8) {
    let pad = radius + 2.0;
    let Some((a, b)) = clip_segment(
        a,
        b,
        (-pad, -pad),
        (canvas.w as f64 + pad, canvas.h as f64 + pad),
    ) else {
        return;
    };
    let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
    if !len.is_finite() {
        return;
    }
    let steps = (len / 0.5).ceil().max(1.0) as usize;
    let r = radius.ceil() as isize;
    let r2 = radius * radius;
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        let (x, y, z) = (
            a.0 + t * (b.0 - a.0),
            a.1 + t * (b.1 - a.1),
            (a.2 + t * (b.2 - a.2)) as f32,
        );
        let (cx, cy) = (x.floor() as isize, y.floor() as isize);
        for dy in -r..=r {
            for dx in -r..=r {
                let (px, py) = (cx + dx, cy + dy);
                if px < 0 || py < 0 || px >= canvas.w as isize || py >= canvas.h as isize {
                    continue;
                }
                let (fx, fy) = (px as f64 + 0.5 - x, py as f64 + 0.5 - y);
                if fx * fx + fy * fy > r2 {
                    continue;
                }
                let i = py as usize * canvas.w + px as usize;
                if z - bias <= canvas.depth[i] {
                    canvas.edge[i] = canvas.edge[i].max(kind);
                }
            }
        }
    }
}

/// Each seed as a dark dot on its surface point, hidden where the mesh lies in front.
fn draw_seeds(canvas: &mut Canvas, result: &Discretisation, cam: &Camera, ss: usize) {
    let radius = ss as f64 * 1.6;
    for seed in result.seeds.iter().filter(|s| s.point.is_finite()) {
        let p = cam.project(seed.point);
        // A dot is a line of no length, drawn with the edges' colour and depth bias.
        draw_line(canvas, p, p, radius, 0.02, 1);
    }
}

/// A colour bar from 0 to `scale` with its labels in the lower left corner (final
/// resolution).
fn deviation_legend(img: &mut Image<'_>, scale: f64) {
    let text_scale = if img.h >= 600 { 2 } else { 1 };
    let (bar_w, bar_h) = (160 * text_scale, 7 * text_scale + 4);
    let x0 = 12usize;
    let y = img.h.saturating_sub(bar_h + 12);
    let dark = [0x22, 0x22, 0x22];
    let x = font::draw_text(img, x0, y + 2, text_scale, "0", dark) + 8;
    img.fill_rect(x, y, bar_w, bar_h, dark);
    for k in 0..bar_w.saturating_sub(2) {
        let t = k as f64 / (bar_w - 3).max(1) as f64;
        img.fill_rect(x + 1 + k, y + 1, 1, bar_h - 2, deviation_colour(t));
    }
    font::draw_text(
        img,
        x + bar_w + 8,
        y + 2,
        text_scale,
        &format!("{scale:.3e}"),
        dark,
    );
}

/// Swatches with side counts in the lower left corner (final resolution).
fn legend(img: &mut Image<'_>, result: &Discretisation) {
    let mut classes: Vec<usize> = (0..result.facet_count())
        .map(|i| side_class(result.facet(i).len()))
        .collect();
    classes.sort_unstable();
    classes.dedup();
    let scale = if img.h >= 600 { 2 } else { 1 };
    let box_size = 7 * scale + 4;
    let mut x = 12usize;
    let y = img.h.saturating_sub(box_size + 12);
    for class in classes {
        let label = crate::palette::side_label(class);
        img.fill_rect(x, y, box_size, box_size, [0x22, 0x22, 0x22]);
        img.fill_rect(x + 1, y + 1, box_size - 2, box_size - 2, side_colour(class));
        x += box_size + 4;
        x = font::draw_text(img, x, y + 2, scale, &label, [0x22, 0x22, 0x22]) + 10;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ear_clipping_of_a_non_convex_polygon() {
        // An L shape: fan from vertex 0 would leave the polygon.
        let pts: Vec<DVec3> = [
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ]
        .iter()
        .map(|p| DVec3::new(p[0], p[1], 0.0))
        .collect();
        let tris = triangulate(&pts, DVec3::Z);
        assert_eq!(tris.len(), 4);
        let area: f64 = tris
            .iter()
            .map(|t| {
                let (a, b, c) = (pts[t[0]], pts[t[1]], pts[t[2]]);
                (b - a).cross(c - a).z / 2.0
            })
            .sum();
        assert!((area - 3.0).abs() < 1e-12, "{area}");
    }
}
