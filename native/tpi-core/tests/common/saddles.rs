//! Saddle surfaces (K < 0 everywhere) written independently of the crate's samples, with
//! their own closed-form derivatives (issue 10): hyperbolic paraboloids z = x y / c and
//! z = x^2/a^2 - y^2/b^2 turned by any angle, seeded random skewed saddles with cubic terms
//! (K < 0 checked on a grid), the inner band of a torus, sectors of a catenoid and of a
//! hyperboloid of one sheet, and a helicoid. Used by the example `saddle_sweep` and the
//! any-curvature tests.
// Test helpers: `pub` is how the test files that include this module reach them.
#![allow(unreachable_pub, dead_code)]

use glam::DVec3;
use tpi_core::{Domain, Interval, Surface, SurfaceDerivatives};

use super::{gaussian_and_mean, Rng};

/// A surface given by a closure returning the point and its derivatives up to second order.
pub struct Analytic {
    domain: Domain,
    eval: Box<dyn Fn(f64, f64) -> SurfaceDerivatives + Send + Sync>,
}

impl Surface for Analytic {
    fn domain(&self) -> Domain {
        self.domain
    }

    fn evaluate(&self, u: f64, v: f64) -> SurfaceDerivatives {
        let (u, v) = self.domain.clamp(u, v);
        (self.eval)(u, v)
    }
}

pub fn analytic(
    u: [f64; 2],
    v: [f64; 2],
    eval: impl Fn(f64, f64) -> SurfaceDerivatives + Send + Sync + 'static,
) -> Analytic {
    Analytic {
        domain: Domain::new(Interval::new(u[0], u[1]), Interval::new(v[0], v[1])),
        eval: Box::new(eval),
    }
}

/// A height field z = f(x', y') over [-hx, hx] x [-hy, hy], where (x', y') is (x, y) turned
/// by `degrees`; `f` returns [f, f_x', f_y', f_x'x', f_x'y', f_y'y'].
pub fn height_field(
    hx: f64,
    hy: f64,
    degrees: f64,
    f: impl Fn(f64, f64) -> [f64; 6] + Send + Sync + 'static,
) -> Analytic {
    let (s, c) = degrees.to_radians().sin_cos();
    analytic([-hx, hx], [-hy, hy], move |x, y| {
        let (xr, yr) = (c * x + s * y, -s * x + c * y);
        let [z, a, b, aa, ab, bb] = f(xr, yr);
        // Chain rule: d/dx = c d/dx' - s d/dy', d/dy = s d/dx' + c d/dy'.
        let zx = c * a - s * b;
        let zy = s * a + c * b;
        let zxx = c * c * aa - 2.0 * c * s * ab + s * s * bb;
        let zxy = c * s * aa + (c * c - s * s) * ab - c * s * bb;
        let zyy = s * s * aa + 2.0 * c * s * ab + c * c * bb;
        SurfaceDerivatives {
            point: DVec3::new(x, y, z),
            su: DVec3::new(1.0, 0.0, zx),
            sv: DVec3::new(0.0, 1.0, zy),
            suu: DVec3::new(0.0, 0.0, zxx),
            suv: DVec3::new(0.0, 0.0, zxy),
            svv: DVec3::new(0.0, 0.0, zyy),
        }
    })
}

/// z = x' y' / c.
pub fn hypar_xy(c: f64, hx: f64, hy: f64, degrees: f64) -> Analytic {
    height_field(hx, hy, degrees, move |x, y| {
        [x * y / c, y / c, x / c, 0.0, 1.0 / c, 0.0]
    })
}

/// z = x'^2 / a^2 - y'^2 / b^2.
pub fn hypar_ab(a: f64, b: f64, hx: f64, hy: f64, degrees: f64) -> Analytic {
    let (p, q) = (1.0 / (a * a), 1.0 / (b * b));
    height_field(hx, hy, degrees, move |x, y| {
        [
            p * x * x - q * y * y,
            2.0 * p * x,
            -2.0 * q * y,
            2.0 * p,
            0.0,
            -2.0 * q,
        ]
    })
}

/// A seeded random skewed saddle over [-5, 5] x [-4, 4]: z = a x^2 - b y^2 + e x y plus the
/// cubic terms c1 x^3 + c2 x^2 y + c3 x y^2 + c4 y^3, turned by a random angle; drawn again
/// until K < 0 on a 40 x 40 grid with the ratio of largest to smallest |K| at least 4.
pub fn skewed_saddle(seed: u64) -> Analytic {
    let mut rng = Rng::new(0x736b_6577 ^ seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    loop {
        let a = rng.range(0.03, 0.12);
        let b = rng.range(0.03, 0.12);
        let e = rng.range(-0.05, 0.05);
        let cs = [
            rng.range(-0.012, 0.012),
            rng.range(-0.012, 0.012),
            rng.range(-0.012, 0.012),
            rng.range(-0.012, 0.012),
        ];
        let degrees = rng.range(0.0, 180.0);
        let f = move |x: f64, y: f64| {
            let [c1, c2, c3, c4] = cs;
            [
                a * x * x - b * y * y
                    + e * x * y
                    + c1 * x * x * x
                    + c2 * x * x * y
                    + c3 * x * y * y
                    + c4 * y * y * y,
                2.0 * a * x + e * y + 3.0 * c1 * x * x + 2.0 * c2 * x * y + c3 * y * y,
                -2.0 * b * y + e * x + c2 * x * x + 2.0 * c3 * x * y + 3.0 * c4 * y * y,
                2.0 * a + 6.0 * c1 * x + 2.0 * c2 * y,
                e + 2.0 * c2 * x + 2.0 * c3 * y,
                -2.0 * b + 2.0 * c3 * x + 6.0 * c4 * y,
            ]
        };
        let surface = height_field(5.0, 4.0, degrees, f);
        let (lo, hi) = gaussian_range(&surface, 40);
        if hi < 0.0 && lo / hi >= 4.0 {
            return surface;
        }
    }
}

/// Asserts that the derivatives agree with central differences of the points and of the
/// first derivatives on a grid (the surfaces' own formulas checked against their points).
pub fn check_derivatives(name: &str, surface: &dyn Surface) {
    let dom = surface.domain();
    let h = 1e-5;
    for i in 1..10 {
        for j in 1..10 {
            let [u, v] = dom.from_normalised([i as f64 / 10.0, j as f64 / 10.0]);
            let d = surface.evaluate(u, v);
            let du = |f: &dyn Fn(SurfaceDerivatives) -> DVec3| {
                (f(surface.evaluate(u + h, v)) - f(surface.evaluate(u - h, v))) / (2.0 * h)
            };
            let dv = |f: &dyn Fn(SurfaceDerivatives) -> DVec3| {
                (f(surface.evaluate(u, v + h)) - f(surface.evaluate(u, v - h))) / (2.0 * h)
            };
            let pairs = [
                (d.su, du(&|e| e.point)),
                (d.sv, dv(&|e| e.point)),
                (d.suu, du(&|e| e.su)),
                (d.suv, dv(&|e| e.su)),
                (d.suv, du(&|e| e.sv)),
                (d.svv, dv(&|e| e.sv)),
            ];
            for (k, (exact, numeric)) in pairs.iter().enumerate() {
                let scale = 1.0 + exact.length();
                assert!(
                    (*exact - *numeric).length() < 1e-6 * scale,
                    "{name}: derivative {k} at ({u}, {v}): {exact} vs {numeric}"
                );
            }
        }
    }
}

/// The smallest and largest Gaussian curvature over an (n+1) x (n+1) grid.
pub fn gaussian_range(surface: &dyn Surface, n: usize) -> (f64, f64) {
    let dom = surface.domain();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=n {
        for j in 0..=n {
            let [u, v] = dom.from_normalised([i as f64 / n as f64, j as f64 / n as f64]);
            let k = gaussian_and_mean(surface, u, v).0;
            lo = lo.min(k);
            hi = hi.max(k);
        }
    }
    (lo, hi)
}

/// The torus with major radius `big` and tube radius `small`: u the revolution angle, v the
/// tube angle (pi = the inner equator), both in degrees.
pub fn torus(big: f64, small: f64, u: [f64; 2], v: [f64; 2]) -> Analytic {
    analytic(
        [u[0].to_radians(), u[1].to_radians()],
        [v[0].to_radians(), v[1].to_radians()],
        move |t, p| {
            let (st, ct) = t.sin_cos();
            let (sp, cp) = p.sin_cos();
            let r = big + small * cp;
            SurfaceDerivatives {
                point: DVec3::new(r * ct, r * st, small * sp),
                su: DVec3::new(-r * st, r * ct, 0.0),
                sv: DVec3::new(-small * sp * ct, -small * sp * st, small * cp),
                suu: DVec3::new(-r * ct, -r * st, 0.0),
                suv: DVec3::new(small * sp * st, -small * sp * ct, 0.0),
                svv: DVec3::new(-small * cp * ct, -small * cp * st, -small * sp),
            }
        },
    )
}

/// A surface of revolution about z: (r(v) cos u, r(v) sin u, h(v)) with `profile` returning
/// [r, r', r'', h, h', h''], u in degrees.
pub fn revolution(
    u: [f64; 2],
    v: [f64; 2],
    profile: impl Fn(f64) -> [f64; 6] + Send + Sync + 'static,
) -> Analytic {
    analytic([u[0].to_radians(), u[1].to_radians()], v, move |t, s| {
        let (st, ct) = t.sin_cos();
        let [r, r1, r2, h, h1, h2] = profile(s);
        SurfaceDerivatives {
            point: DVec3::new(r * ct, r * st, h),
            su: DVec3::new(-r * st, r * ct, 0.0),
            sv: DVec3::new(r1 * ct, r1 * st, h1),
            suu: DVec3::new(-r * ct, -r * st, 0.0),
            suv: DVec3::new(-r1 * st, r1 * ct, 0.0),
            svv: DVec3::new(r2 * ct, r2 * st, h2),
        }
    })
}

/// A catenoid r = c cosh(v / c), h = v.
pub fn catenoid(c: f64, u: [f64; 2], v: [f64; 2]) -> Analytic {
    revolution(u, v, move |s| {
        let (ch, sh) = ((s / c).cosh(), (s / c).sinh());
        [c * ch, sh, ch / c, s, 1.0, 0.0]
    })
}

/// A hyperboloid of one sheet r = a cosh v, h = c sinh v.
pub fn hyperboloid(a: f64, c: f64, u: [f64; 2], v: [f64; 2]) -> Analytic {
    revolution(u, v, move |s| {
        let (ch, sh) = (s.cosh(), s.sinh());
        [a * ch, a * sh, a * ch, c * sh, c * ch, c * sh]
    })
}

/// A helicoid (v cos u, v sin u, c u), u in degrees.
pub fn helicoid(c: f64, u: [f64; 2], v: [f64; 2]) -> Analytic {
    analytic([u[0].to_radians(), u[1].to_radians()], v, move |t, s| {
        let (st, ct) = t.sin_cos();
        SurfaceDerivatives {
            point: DVec3::new(s * ct, s * st, c * t),
            su: DVec3::new(-s * st, s * ct, c),
            sv: DVec3::new(ct, st, 0.0),
            suu: DVec3::new(-s * ct, -s * st, 0.0),
            suv: DVec3::new(-st, ct, 0.0),
            svv: DVec3::ZERO,
        }
    })
}

/// The saddles of the sweep, by name.
pub fn saddles() -> Vec<(String, Box<dyn Surface>)> {
    let mut out: Vec<(String, Box<dyn Surface>)> = vec![
        ("hp-xy-sq".into(), Box::new(hypar_xy(12.0, 5.0, 5.0, 0.0))),
        ("hp-xy-wide".into(), Box::new(hypar_xy(6.0, 8.0, 3.0, 20.0))),
        (
            "hp-xy-steep".into(),
            Box::new(hypar_xy(2.5, 4.0, 4.0, 37.0)),
        ),
        (
            "hp-ab-round".into(),
            Box::new(hypar_ab(4.0, 4.0, 5.0, 5.0, 0.0)),
        ),
        (
            "hp-ab-aniso".into(),
            Box::new(hypar_ab(3.0, 9.0, 6.0, 4.0, 25.0)),
        ),
        (
            "hp-ab-steep".into(),
            Box::new(hypar_ab(2.0, 3.0, 4.0, 4.0, 60.0)),
        ),
        (
            "hp-ab-long".into(),
            Box::new(hypar_ab(5.0, 2.5, 10.0, 2.5, 70.0)),
        ),
    ];
    for seed in 1..=5 {
        out.push((format!("skew{seed}"), Box::new(skewed_saddle(seed))));
    }
    out.push((
        "torus-in".into(),
        Box::new(torus(10.0, 3.0, [-50.0, 50.0], [105.0, 255.0])),
    ));
    out.push((
        "torus-fat".into(),
        Box::new(torus(5.0, 3.0, [-80.0, 80.0], [110.0, 250.0])),
    ));
    out.push((
        "catenoid".into(),
        Box::new(catenoid(2.0, [0.0, 200.0], [-2.5, 2.5])),
    ));
    out.push((
        "hyperboloid".into(),
        Box::new(hyperboloid(2.0, 3.0, [-60.0, 160.0], [-0.9, 0.9])),
    ));
    out.push((
        "helicoid".into(),
        Box::new(helicoid(1.5, [0.0, 240.0], [-3.0, 3.0])),
    ));
    out
}
