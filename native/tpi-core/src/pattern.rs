//! Pattern points: 2D points (s, t) in the normalised square [0, 1]^2, mapped linearly onto a
//! surface's parameter domain (u = u0 + s (u1 - u0), v = v0 + t (v1 - v0)).
//!
//! The pattern file is `{"uv": [[s, t], ...]}` (docs/formats.md). [`Pattern::validate`]
//! rejects non-finite or out-of-range points ([`TpiError::PatternPointOutOfRange`]) and points
//! closer than [`DUPLICATE_UV_TOLERANCE`] to an earlier one
//! ([`TpiError::DuplicatePatternPoint`]); the duplicate search hashes the points into cells of
//! the tolerance's size, so it runs in expected O(n).
//!
//! ## Generators
//!
//! Each generator is deterministic: the same parameters and seed give the same points on
//! every platform and with every version of every dependency, because the random numbers come
//! from the project's own [`SplitMix64`] and the generators use only the correctly rounded
//! IEEE operations (+, -, *, /, sqrt; no trigonometry).
//!
//! | syntax | points |
//! |--------|--------|
//! | `grid:NUxNV` | exactly NU * NV cell centres ((i + 1/2)/NU, (j + 1/2)/NV) |
//! | `grid:spacing=D` | `grid:NxN` with N = max(1, round(1/D)) |
//! | `hex:NUxNV` | exactly NU * NV: NV rows at t = (j + 1/2)/NV, NU points per row at s = (i + 1/4)/NU in even rows j and (i + 3/4)/NU in odd rows (half a step apart) |
//! | `hex:spacing=D` | `hex:NUxNV` with NU = max(1, round(1/D)), NV = max(1, round(2/(sqrt(3) D))): rows sqrt(3)/2 of the column step apart |
//! | `jitter:NUxNV[:amount=A][:seed=S]` | exactly NU * NV: each cell centre moved by independent uniform offsets in [-A/2, A/2) of the cell's width and height; A in [0, 1], default 0.5 (A = 1 spreads each point over its whole cell); also `jitter:spacing=D:...` |
//! | `random:N[:seed=S]` | exactly N uniform points in [0, 1)^2 (a draw that would duplicate an earlier point is drawn again) |
//! | `poisson:R[:seed=S]` | Bridson's Poisson-disk sampling of [0, 1)^2 with minimum distance R and k = 30 candidates per active point; the count depends on R (about 0.7 / R^2) |
//!
//! Seeds are unsigned 64-bit integers, default 0. Grid points are cell centres, so no grid
//! point lies on the boundary of the square. Points are ordered u-major: for grids, point
//! (i, j) is at index i * NV + j (the control-point order of the NURBS record). At most
//! [`MAX_GENERATED_POINTS`] points are generated, and a Poisson radius must be at least
//! [`MIN_POISSON_RADIUS`].

use std::collections::HashMap;
use std::fmt;
use std::hash::{BuildHasherDefault, Hasher};
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::TpiError;
use crate::surface::Domain;
use crate::tolerance::DUPLICATE_UV_TOLERANCE;
use crate::tolerance::MIN_POISSON_RADIUS;

/// Largest number of points a generator produces (grids: NU * NV; random: N).
pub const MAX_GENERATED_POINTS: usize = 10_000_000;

/// Candidates tried around each active point in Bridson's algorithm.
pub(crate) const POISSON_CANDIDATES: usize = 30;

/// Default jitter amount when the generator spec leaves it out.
pub const DEFAULT_JITTER_AMOUNT: f64 = 0.5;

/// A set of pattern points in normalised [0, 1]^2.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pattern {
    /// The points (s, t), each coordinate in [0, 1].
    pub uv: Vec<[f64; 2]>,
}

impl Pattern {
    /// A pattern from its points (not validated; see [`Pattern::validate`]).
    pub fn new(uv: Vec<[f64; 2]>) -> Self {
        Self { uv }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.uv.len()
    }

    /// Whether the pattern has no points.
    pub fn is_empty(&self) -> bool {
        self.uv.is_empty()
    }

    /// Checks every point: finite and inside [0, 1]^2 (else
    /// [`TpiError::PatternPointOutOfRange`] with the first offending index), and no point
    /// closer than [`DUPLICATE_UV_TOLERANCE`] to an earlier one (else
    /// [`TpiError::DuplicatePatternPoint`] for the first such point, naming the nearest earlier
    /// point it duplicates). Range errors are reported before duplicates. An empty pattern is
    /// valid here; the mesh stage asks for enough points.
    pub fn validate(&self) -> Result<(), TpiError> {
        validate_uv(&self.uv)
    }

    /// Reads a pattern file (`{"uv": [[s, t], ...]}`) and validates it.
    ///
    /// Errors: [`TpiError::Parse`] (with line and column; `context` names the source) for
    /// malformed JSON or unknown fields, then the errors of [`Pattern::validate`].
    pub fn from_json(text: &str, context: &str) -> Result<Pattern, TpiError> {
        let pattern: Pattern = crate::spec::read(text, context)?;
        pattern.validate()?;
        Ok(pattern)
    }

    /// The points mapped linearly onto `domain`: (s, t) -> (u0 + s (u1 - u0), v0 + t (v1 - v0)).
    pub fn to_domain(&self, domain: &Domain) -> Vec<[f64; 2]> {
        self.uv
            .iter()
            .map(|&st| domain.from_normalised(st))
            .collect()
    }
}

/// The checks of [`Pattern::validate`] on a plain slice of normalised points.
pub(crate) fn validate_uv(uv: &[[f64; 2]]) -> Result<(), TpiError> {
    for (index, &[s, t]) in uv.iter().enumerate() {
        if !in_unit_square(s, t) {
            return Err(TpiError::PatternPointOutOfRange { index, s, t });
        }
    }
    let mut hash = UvHash::new(DUPLICATE_UV_TOLERANCE, uv.len());
    for (index, &p) in uv.iter().enumerate() {
        if let Some((duplicate_of, distance)) = hash.nearest_within(uv, p) {
            return Err(TpiError::DuplicatePatternPoint {
                index,
                duplicate_of,
                distance,
            });
        }
        hash.insert(p, index);
    }
    Ok(())
}

fn in_unit_square(s: f64, t: f64) -> bool {
    (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t)
}

/// A hash of points into square cells of side `tolerance`: every point closer than the
/// tolerance to a query lies in the query's cell or one of its 8 neighbours. Each cell holds
/// a chain of point indices (`head` per cell, `next` per point).
struct UvHash {
    cell: f64,
    head: HashMap<(i64, i64), usize, BuildHasherDefault<CellHasher>>,
    next: Vec<usize>,
}

const NO_POINT: usize = usize::MAX;

/// A multiply-rotate hasher (as rustc's FxHasher) for integer cell keys: the keys come from
/// the user's points, but a collision costs only time, and the chains stay short because a
/// cell of the duplicate tolerance's size holds few distinct points.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x517C_C1B7_2722_0A95);
    }

    fn write_i64(&mut self, x: i64) {
        self.write_u64(x as u64);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

impl UvHash {
    fn new(cell: f64, capacity: usize) -> Self {
        Self {
            cell,
            head: HashMap::with_capacity_and_hasher(capacity, BuildHasherDefault::default()),
            next: Vec::with_capacity(capacity),
        }
    }

    fn key(&self, p: [f64; 2]) -> (i64, i64) {
        // Points are finite and inside [0, 1]^2 here, so the keys fit easily.
        (
            (p[0] / self.cell).floor() as i64,
            (p[1] / self.cell).floor() as i64,
        )
    }

    /// The nearest stored point strictly closer than the cell size (ties: smaller index).
    fn nearest_within(&self, points: &[[f64; 2]], p: [f64; 2]) -> Option<(usize, f64)> {
        let (ci, cj) = self.key(p);
        let mut best: Option<(usize, f64)> = None;
        for di in -1..=1 {
            for dj in -1..=1 {
                let mut k = self
                    .head
                    .get(&(ci + di, cj + dj))
                    .copied()
                    .unwrap_or(NO_POINT);
                while let Some(q) = points.get(k) {
                    let d = (p[0] - q[0]).hypot(p[1] - q[1]);
                    if d < self.cell {
                        let better = match best {
                            None => true,
                            Some((bk, bd)) => d < bd || (d == bd && k < bk),
                        };
                        if better {
                            best = Some((k, d));
                        }
                    }
                    k = self.next.get(k).copied().unwrap_or(NO_POINT);
                }
            }
        }
        best
    }

    /// Stores point `index` (indices are inserted in increasing order).
    fn insert(&mut self, p: [f64; 2], index: usize) {
        let key = self.key(p);
        let previous = self.head.insert(key, index).unwrap_or(NO_POINT);
        if self.next.len() <= index {
            self.next.resize(index + 1, NO_POINT);
        }
        self.next[index] = previous;
    }
}

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, fast 64-bit generator, written out here so
/// that generated patterns never change with a dependency's version.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator started from `seed`.
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in [0, 1) with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform integer in [0, n) (0 when n = 0), by the multiply-shift reduction.
    pub fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.next_u64()) * n as u128) >> 64) as usize
    }
}

/// The size of a grid: explicit counts or a target spacing in normalised units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum GridSize {
    /// NU columns (along s) by NV rows (along t).
    Counts {
        /// Points along s.
        nu: usize,
        /// Points along t.
        nv: usize,
    },
    /// A target distance between neighbouring points, in (0, 1].
    Spacing(f64),
}

impl fmt::Display for GridSize {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GridSize::Counts { nu, nv } => write!(f, "{nu}x{nv}"),
            GridSize::Spacing(d) => write!(f, "spacing={d}"),
        }
    }
}

/// max(1, round(x)) as a count, saturating (x is finite and positive after validation).
fn round_count(x: f64) -> usize {
    if x.is_finite() && x >= 1.0 {
        x.round().min(usize::MAX as f64) as usize
    } else {
        1
    }
}

impl GridSize {
    /// (NU, NV) of a square or jittered grid: counts as given, spacing D -> N = max(1, round(1/D)).
    pub fn square_counts(&self) -> (usize, usize) {
        match *self {
            GridSize::Counts { nu, nv } => (nu, nv),
            GridSize::Spacing(d) => {
                let n = round_count(1.0 / d);
                (n, n)
            }
        }
    }

    /// (NU, NV) of a hexagonal grid: counts as given, spacing D -> NU = max(1, round(1/D)),
    /// NV = max(1, round(2 / (sqrt(3) D))).
    pub fn hex_counts(&self) -> (usize, usize) {
        match *self {
            GridSize::Counts { nu, nv } => (nu, nv),
            GridSize::Spacing(d) => (round_count(1.0 / d), round_count(2.0 / (3f64.sqrt() * d))),
        }
    }

    fn validate(&self, counts: (usize, usize)) -> Result<(), String> {
        match *self {
            GridSize::Counts { nu, nv } => {
                if nu == 0 || nv == 0 {
                    return Err(format!("grid counts {nu}x{nv} must both be at least 1"));
                }
            }
            GridSize::Spacing(d) => {
                if !(d.is_finite() && d > 0.0 && d <= 1.0) {
                    return Err(format!("spacing {d} must be a number in (0, 1]"));
                }
            }
        }
        let (nu, nv) = counts;
        match nu.checked_mul(nv) {
            Some(n) if n <= MAX_GENERATED_POINTS => Ok(()),
            _ => Err(format!(
                "{nu}x{nv} points exceed the maximum of {MAX_GENERATED_POINTS}"
            )),
        }
    }
}

/// A pattern generator; see the module doc for the syntax and the exact point counts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Generator {
    /// Square grid of cell centres.
    Grid(GridSize),
    /// Hexagonal (triangular-lattice) grid: rows offset by half a step.
    Hex(GridSize),
    /// Square grid with each point moved randomly inside its cell.
    Jitter {
        /// The underlying grid.
        size: GridSize,
        /// Offset range as a fraction of the cell, in [0, 1].
        amount: f64,
        /// Random seed.
        seed: u64,
    },
    /// Uniform random points.
    Random {
        /// Number of points, >= 1.
        count: usize,
        /// Random seed.
        seed: u64,
    },
    /// Bridson's Poisson-disk sampling.
    Poisson {
        /// Minimum distance between points in normalised units, >= [`MIN_POISSON_RADIUS`].
        radius: f64,
        /// Random seed.
        seed: u64,
    },
}

const SYNTAX: &str = "expected grid:NUxNV, grid:spacing=D, hex:NUxNV, hex:spacing=D, \
jitter:NUxNV[:amount=A][:seed=S], random:N[:seed=S] or poisson:R[:seed=S]";

fn parse_grid_size(token: &str) -> Result<GridSize, String> {
    if let Some(value) = token.strip_prefix("spacing=") {
        let d: f64 = value
            .parse()
            .map_err(|_| format!("spacing `{value}` is not a number"))?;
        return Ok(GridSize::Spacing(d));
    }
    let Some((a, b)) = token.split_once('x') else {
        return Err(format!(
            "grid size `{token}` is neither NUxNV (e.g. 20x15) nor spacing=D"
        ));
    };
    let nu: usize = a
        .parse()
        .map_err(|_| format!("count `{a}` in `{token}` is not a non-negative integer"))?;
    let nv: usize = b
        .parse()
        .map_err(|_| format!("count `{b}` in `{token}` is not a non-negative integer"))?;
    Ok(GridSize::Counts { nu, nv })
}

/// Parses `key=value` options, allowing only `allowed` keys, each at most once.
fn parse_options<'a>(
    tokens: &[&'a str],
    allowed: &[&str],
) -> Result<Vec<(&'a str, &'a str)>, String> {
    let mut out: Vec<(&str, &str)> = Vec::new();
    for token in tokens {
        let Some((key, value)) = token.split_once('=') else {
            return Err(format!(
                "option `{token}` is not of the form key=value (accepted keys: {})",
                allowed.join(", ")
            ));
        };
        if !allowed.contains(&key) {
            return Err(format!(
                "unknown option `{key}` (accepted: {})",
                allowed.join(", ")
            ));
        }
        if out.iter().any(|(k, _)| *k == key) {
            return Err(format!("option `{key}` is given twice"));
        }
        out.push((key, value));
    }
    Ok(out)
}

fn option<'a>(options: &[(&str, &'a str)], key: &str) -> Option<&'a str> {
    options.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
}

fn parse_seed(options: &[(&str, &str)]) -> Result<u64, String> {
    match option(options, "seed") {
        None => Ok(0),
        Some(v) => v
            .parse()
            .map_err(|_| format!("seed `{v}` is not an unsigned 64-bit integer")),
    }
}

impl Generator {
    /// Parses the CLI syntax (module doc), e.g. `grid:20x15`, `hex:spacing=0.05`,
    /// `jitter:20x20:amount=0.3:seed=7`, `random:1000:seed=7`, `poisson:0.03:seed=7`, and
    /// validates the parameters.
    ///
    /// Errors: [`TpiError::InvalidGenerator`] with the spec and what is wrong.
    pub fn parse(spec: &str) -> Result<Generator, TpiError> {
        let fail = |reason: String| TpiError::InvalidGenerator {
            spec: spec.to_string(),
            reason,
        };
        let tokens: Vec<&str> = spec.trim().split(':').collect();
        let kind = tokens.first().copied().unwrap_or("");
        let rest = tokens.get(1..).unwrap_or(&[]);
        let generator = match kind {
            "grid" | "hex" => {
                let [size] = rest else {
                    return Err(fail(format!(
                        "{kind} takes exactly one argument, NUxNV or spacing=D"
                    )));
                };
                let size = parse_grid_size(size).map_err(fail)?;
                if kind == "grid" {
                    Generator::Grid(size)
                } else {
                    Generator::Hex(size)
                }
            }
            "jitter" => {
                let Some((size, opts)) = rest.split_first() else {
                    return Err(fail("jitter needs a grid size, NUxNV or spacing=D".into()));
                };
                let size = parse_grid_size(size).map_err(fail)?;
                let opts = parse_options(opts, &["amount", "seed"]).map_err(fail)?;
                let amount = match option(&opts, "amount") {
                    None => DEFAULT_JITTER_AMOUNT,
                    Some(v) => v
                        .parse()
                        .map_err(|_| fail(format!("amount `{v}` is not a number")))?,
                };
                Generator::Jitter {
                    size,
                    amount,
                    seed: parse_seed(&opts).map_err(fail)?,
                }
            }
            "random" => {
                let Some((n, opts)) = rest.split_first() else {
                    return Err(fail("random needs a point count, e.g. random:1000".into()));
                };
                let count: usize = n.parse().map_err(|_| {
                    fail(format!("point count `{n}` is not a non-negative integer"))
                })?;
                let opts = parse_options(opts, &["seed"]).map_err(fail)?;
                Generator::Random {
                    count,
                    seed: parse_seed(&opts).map_err(fail)?,
                }
            }
            "poisson" => {
                let Some((r, opts)) = rest.split_first() else {
                    return Err(fail("poisson needs a radius, e.g. poisson:0.03".into()));
                };
                let radius: f64 = r
                    .parse()
                    .map_err(|_| fail(format!("radius `{r}` is not a number")))?;
                let opts = parse_options(opts, &["seed"]).map_err(fail)?;
                Generator::Poisson {
                    radius,
                    seed: parse_seed(&opts).map_err(fail)?,
                }
            }
            "" => return Err(fail(format!("empty generator; {SYNTAX}"))),
            other => return Err(fail(format!("unknown generator kind `{other}`; {SYNTAX}"))),
        };
        generator.check().map_err(fail)?;
        Ok(generator)
    }

    /// Checks the parameters (counts >= 1, spacing in (0, 1], amount in [0, 1], radius >=
    /// [`MIN_POISSON_RADIUS`], at most [`MAX_GENERATED_POINTS`] points).
    ///
    /// Errors: [`TpiError::InvalidGenerator`] with the canonical spec and what is wrong.
    pub fn validate(&self) -> Result<(), TpiError> {
        self.check().map_err(|reason| TpiError::InvalidGenerator {
            spec: self.to_string(),
            reason,
        })
    }

    fn check(&self) -> Result<(), String> {
        match *self {
            Generator::Grid(size) => size.validate(size.square_counts()),
            Generator::Hex(size) => size.validate(size.hex_counts()),
            Generator::Jitter { size, amount, .. } => {
                size.validate(size.square_counts())?;
                if !(0.0..=1.0).contains(&amount) {
                    return Err(format!("amount {amount} must be in [0, 1]"));
                }
                Ok(())
            }
            Generator::Random { count, .. } => {
                if count == 0 {
                    Err("the point count must be at least 1".into())
                } else if count > MAX_GENERATED_POINTS {
                    Err(format!(
                        "{count} points exceed the maximum of {MAX_GENERATED_POINTS}"
                    ))
                } else {
                    Ok(())
                }
            }
            Generator::Poisson { radius, .. } => {
                if !(radius.is_finite() && radius >= MIN_POISSON_RADIUS) {
                    Err(format!(
                        "radius {radius} must be a number >= {MIN_POISSON_RADIUS}"
                    ))
                } else {
                    Ok(())
                }
            }
        }
    }

    /// Whether the pattern this generator would give can be discretised at all, decided by
    /// arithmetic on the parameters before any point is made (issue 14: `grid:1x10000000`
    /// used to generate ten million points before they were found collinear).
    ///
    /// Errors: [`TpiError::TooFewPatternPoints`] when it gives fewer than 3 points,
    /// [`TpiError::CollinearPattern`] when every point lies on one line (a square grid or an
    /// unjittered jitter grid with one row or column, a hexagonal grid with one row), the
    /// generator's own [`TpiError::InvalidGenerator`] when it is invalid.
    pub fn check_discretisable(&self) -> Result<(), TpiError> {
        self.check().map_err(|reason| TpiError::InvalidGenerator {
            spec: self.to_string(),
            reason,
        })?;
        if let Some(count) = self.expected_count() {
            if count < 3 {
                return Err(TpiError::TooFewPatternPoints {
                    found: count,
                    needed: 3,
                });
            }
        }
        let collinear = match *self {
            Generator::Grid(size) => {
                let (nu, nv) = size.square_counts();
                nu == 1 || nv == 1
            }
            Generator::Jitter { size, amount, .. } => {
                let (nu, nv) = size.square_counts();
                amount == 0.0 && (nu == 1 || nv == 1)
            }
            Generator::Hex(size) => size.hex_counts().1 == 1,
            Generator::Random { .. } | Generator::Poisson { .. } => false,
        };
        match (collinear, self.expected_count()) {
            (true, Some(count)) => Err(TpiError::CollinearPattern { count }),
            _ => Ok(()),
        }
    }

    /// The number of points [`Generator::generate`] gives, where it is fixed by the
    /// parameters (all but Poisson-disk). `None` for Poisson-disk or an invalid generator.
    pub fn expected_count(&self) -> Option<usize> {
        if self.check().is_err() {
            return None;
        }
        match *self {
            Generator::Grid(size) | Generator::Jitter { size, .. } => {
                let (nu, nv) = size.square_counts();
                Some(nu * nv)
            }
            Generator::Hex(size) => {
                let (nu, nv) = size.hex_counts();
                Some(nu * nv)
            }
            Generator::Random { count, .. } => Some(count),
            Generator::Poisson { .. } => None,
        }
    }

    /// Generates the points. Deterministic: the same generator gives the same pattern.
    /// A generator that fails [`Generator::validate`] (only possible when built by hand, since
    /// [`Generator::parse`] validates) gives an empty pattern.
    pub fn generate(&self) -> Pattern {
        if self.check().is_err() {
            return Pattern::default();
        }
        let uv = match *self {
            Generator::Grid(size) => {
                let (nu, nv) = size.square_counts();
                lattice(nu, nv, |_| 0.5)
            }
            Generator::Hex(size) => {
                let (nu, nv) = size.hex_counts();
                lattice(nu, nv, |j| if j % 2 == 0 { 0.25 } else { 0.75 })
            }
            Generator::Jitter { size, amount, seed } => {
                let (nu, nv) = size.square_counts();
                let mut rng = SplitMix64::new(seed);
                let mut uv = lattice(nu, nv, |_| 0.5);
                for p in &mut uv {
                    let ds = (rng.next_f64() - 0.5) * amount / nu as f64;
                    let dt = (rng.next_f64() - 0.5) * amount / nv as f64;
                    p[0] = (p[0] + ds).clamp(0.0, 1.0);
                    p[1] = (p[1] + dt).clamp(0.0, 1.0);
                }
                uv
            }
            Generator::Random { count, seed } => random(count, seed),
            Generator::Poisson { radius, seed } => poisson(radius, seed),
        };
        Pattern { uv }
    }
}

/// NU x NV lattice, u-major: point (i, j) = ((i + offset(j)) / NU, (j + 1/2) / NV).
fn lattice(nu: usize, nv: usize, offset: impl Fn(usize) -> f64) -> Vec<[f64; 2]> {
    let mut uv = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            uv.push([
                (i as f64 + offset(j)) / nu as f64,
                (j as f64 + 0.5) / nv as f64,
            ]);
        }
    }
    uv
}

fn random(count: usize, seed: u64) -> Vec<[f64; 2]> {
    let mut rng = SplitMix64::new(seed);
    let mut uv: Vec<[f64; 2]> = Vec::with_capacity(count);
    let mut hash = UvHash::new(DUPLICATE_UV_TOLERANCE, count);
    while uv.len() < count {
        let p = [rng.next_f64(), rng.next_f64()];
        // Draw again in the (astronomically rare) case of a duplicate, so the pattern validates.
        if hash.nearest_within(&uv, p).is_none() {
            hash.insert(p, uv.len());
            uv.push(p);
        }
    }
    uv
}

/// Bridson, "Fast Poisson disk sampling in arbitrary dimensions" (2007), on [0, 1)^2.
fn poisson(radius: f64, seed: u64) -> Vec<[f64; 2]> {
    const EMPTY: u32 = u32::MAX;
    // Any radius above the square's diagonal gives the first point alone; capping it keeps
    // the arithmetic below finite for absurdly large radii without changing the result.
    let radius = radius.min(2.0);
    let r2 = radius * radius;
    let cell = radius / std::f64::consts::SQRT_2;
    let n = ((1.0 / cell).ceil() as usize).max(1);
    let cell_of = |x: f64| ((x / cell) as usize).min(n - 1);
    let mut grid = vec![EMPTY; n * n];
    let mut rng = SplitMix64::new(seed);
    let mut points: Vec<[f64; 2]> = Vec::new();
    let mut active: Vec<usize> = Vec::new();

    let first = [rng.next_f64(), rng.next_f64()];
    grid[cell_of(first[1]) * n + cell_of(first[0])] = 0;
    points.push(first);
    active.push(0);

    while !active.is_empty() {
        let slot = rng.below(active.len());
        let centre = points[active[slot]];
        let mut accepted = false;
        for _ in 0..POISSON_CANDIDATES {
            // A uniform point of the annulus r <= d < 2r, by rejection from its bounding square.
            let (dx, dy) = loop {
                let dx = (2.0 * rng.next_f64() - 1.0) * 2.0 * radius;
                let dy = (2.0 * rng.next_f64() - 1.0) * 2.0 * radius;
                let d2 = dx * dx + dy * dy;
                if d2 >= r2 && d2 < 4.0 * r2 {
                    break (dx, dy);
                }
            };
            let q = [centre[0] + dx, centre[1] + dy];
            if !(q[0] >= 0.0 && q[0] < 1.0 && q[1] >= 0.0 && q[1] < 1.0) {
                continue;
            }
            let (ci, cj) = (cell_of(q[0]), cell_of(q[1]));
            if grid[cj * n + ci] != EMPTY {
                continue;
            }
            let mut far = true;
            'search: for gj in cj.saturating_sub(2)..=(cj + 2).min(n - 1) {
                for gi in ci.saturating_sub(2)..=(ci + 2).min(n - 1) {
                    let k = grid[gj * n + gi];
                    if k != EMPTY {
                        let p = points[k as usize];
                        let (ex, ey) = (p[0] - q[0], p[1] - q[1]);
                        if ex * ex + ey * ey < r2 {
                            far = false;
                            break 'search;
                        }
                    }
                }
            }
            if far {
                grid[cj * n + ci] = points.len() as u32;
                active.push(points.len());
                points.push(q);
                accepted = true;
                break;
            }
        }
        if !accepted {
            active.swap_remove(slot);
        }
    }
    points
}

impl fmt::Display for Generator {
    /// The canonical spec, which [`Generator::parse`] reads back to an equal generator.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Generator::Grid(size) => write!(f, "grid:{size}"),
            Generator::Hex(size) => write!(f, "hex:{size}"),
            Generator::Jitter { size, amount, seed } => {
                write!(f, "jitter:{size}:amount={amount}:seed={seed}")
            }
            Generator::Random { count, seed } => write!(f, "random:{count}:seed={seed}"),
            Generator::Poisson { radius, seed } => write!(f, "poisson:{radius}:seed={seed}"),
        }
    }
}

impl FromStr for Generator {
    type Err = TpiError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Generator::parse(s)
    }
}
