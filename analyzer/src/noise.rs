//! Wavelet noise (Cook & DeRose 2005), the band-limited noise that Lagae et al. build on.
//!
//! A *tile* is an `n×n` (2D) or `n×n×n` (3D) array of coefficients made from Gaussian values by
//! removing what half resolution can represent (`N = R − R↓↑`); it is evaluated as a periodic
//! quadratic B-spline surface. One octave of noise ("a band") is `N(p)`, with its energy in
//! `[1/4, 1/2]` cycles per coefficient.
//!
//! Departures from the original, all deliberate:
//! - The 2D tile is drawn in the frequency domain ([`spectral`]): white noise times the
//!   wavelet band's expected magnitude, made a function of radius inside the disk of ½ cycle
//!   per coefficient, with no even/odd fix. Cook & DeRose's separable construction biased the
//!   band towards the axes and its fix combed the spectrum. The 3D tile keeps the construction.
//! - Random values come from the counter-based hash in [`crate::rng`] (seedable, order-free,
//!   reproducible in a shader), not from a sequential generator.
//! - The "odd offset" of the 3D tile's even/odd variance fix is made odd, as the construction
//!   intends (the original code's `offset&1==0` test never fires, a C precedence slip).
//! - Each tile is normalised to zero mean and *unit* variance of the evaluated B-spline field
//!   over one period, computed exactly from the coefficients. So `σ²_N = 1` holds for our own
//!   band by construction instead of the paper's approximate 0.265, and a band weight is the
//!   standard deviation that band contributes. [`TileStats::raw_variance`] keeps the value before
//!   normalisation for comparison with the paper.
//! - Each evaluated band is divided by its deviation at the point's sub-texel phase
//!   ([`phase_variance2`], [`phase_variance3`]), so that every phase has unit variance, not only
//!   their average: without it, a band rendered one texel per pixel is sampled at a few fixed
//!   phases and its variance is off by up to ±35 %, which the histogram spline then distorts.
//!
//! The evaluation functions at the bottom ([`bspline_weights`], [`noise2`], [`noise3`],
//! [`band_fade`]) are the per-pixel code: each has a WGSL twin of the same name in `shaders/`.

use crate::rng;

/// Side of the 2D tile. Cook & DeRose and Lagae use 128; then the finest band repeats every 128
/// pixels, four times across a 256² crop and 8 × 15 times across a 1080p view. At 512 the noise
/// model alone gains 0.032 ± 0.011 in overall fidelity on the 15 dev photos whose 256² crops
/// held the repeat, 0.063 on the 4 such shipped samples, and nothing (+0.007 ± 0.013) on the
/// 128² crops that never held it (6 seeds, paired per photo). Chosen among 128, 256 and 512 by
/// 4-fold cross-validation over the dev photos: every fold picks 512, held out −0.015 ± 0.009
/// (docs/measurements.md, "The 2D tile 512 coefficients wide, in the product"). 512² is 4 MB
/// as rgba32float.
pub const TILE_2D: usize = 512;
/// Side of the 3D tile used for solid textures (64³ coefficients, 1 MiB as `f32`).
pub const TILE_3D: usize = 64;

/// Analysis filter `a_j` for `j = −16..−1`; `a_j = a_{−1−j}` gives `j = 0..15`.
const A_COEFFS_NEG: [f64; 16] = [
    0.000334, -0.001528, 0.000410, 0.003545, -0.000938, -0.008233, 0.002172, 0.019120, -0.005040,
    -0.044412, 0.011655, 0.103311, -0.025936, -0.243780, 0.033979, 0.655340,
];
/// Refinement filter `p_{−2..1}`.
const P_COEFFS: [f64; 4] = [0.25, 0.75, 0.75, 0.25];

fn a_coeff(j: i64) -> f64 {
    // j in −16..=15
    if j < 0 {
        A_COEFFS_NEG[(j + 16) as usize]
    } else {
        A_COEFFS_NEG[(15 - j) as usize]
    }
}

/// Independent noise fields per tile, one per decorrelated colour channel. They are stored side
/// by side (planes on the CPU, the RGB of one RGBA texel on the GPU), so that one texture fetch
/// at a point serves all three channels: the channels used to read one field at three offsets,
/// three fetches where one now does.
pub const COMPONENTS: usize = 3;

/// What tile generation measured, for reports and tests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TileStats {
    /// Variance of the evaluated band before normalisation (Lagae quote ≈ 0.265 for theirs).
    pub raw_variance: f64,
    /// Mean of the coefficients before it was removed.
    pub raw_mean: f64,
}

/// A wavelet-noise tile: [`COMPONENTS`] independent fields of `n^dims` coefficients each.
#[derive(Clone, Debug, PartialEq)]
pub struct Tile {
    /// Number of dimensions, 2 or 3.
    pub dims: usize,
    /// Side length (even).
    pub n: usize,
    /// Coefficients, component `k`'s at `k·n^dims + x + n·y (+ n²·z)`: the planes one after
    /// another, so that component 0 alone is the first `n^dims` values.
    pub data: Vec<f32>,
    /// Measurements taken while generating, per component.
    pub stats: [TileStats; COMPONENTS],
}

impl Tile {
    /// The 2D tile of `seed` (from [`recent_2d`] when it was made lately).
    pub fn new_2d(seed: u32) -> Self {
        recent_2d(seed)
    }

    /// The 3D tile of `seed`.
    pub fn new_3d(seed: u32) -> Self {
        Self::generate(seed, 3, TILE_3D, rng::stream::TILE_3D)
    }

    /// Component `k`'s coefficients.
    pub fn plane(&self, k: usize) -> &[f32] {
        let len = self.n.pow(self.dims as u32);
        &self.data[k * len..(k + 1) * len]
    }

    /// The 2D tile from [`spectral`] (components 0 and 1 from one complex draw, 2 from the
    /// next), the 3D one by Cook & DeRose's construction (component `k` draws the Gaussian
    /// values `k·n³ …` of `stream`); then normalisation (see the module docs).
    pub fn generate(seed: u32, dims: usize, n: usize, stream: u32) -> Self {
        assert!(dims == 2 || dims == 3, "tiles are 2D or 3D");
        assert!(
            n >= 4 && n.is_power_of_two(),
            "tile side must be a power of two, at least 4"
        );
        let mut data = Vec::with_capacity(COMPONENTS * n.pow(dims as u32));
        let planes: [(Vec<f32>, TileStats); COMPONENTS] = if dims == 2 {
            spectral_components(seed, n, stream)
        } else {
            std::array::from_fn(|k| component(seed, dims, n, stream, k))
        };
        let stats = planes.map(|(plane, stats)| {
            data.extend(plane);
            stats
        });
        Tile {
            dims,
            n,
            data,
            stats,
        }
    }
}

/// The 2D tile of `seed`, kept for the next caller among the [`RECENT_2D`] used last. One
/// analysis renders the same few seeds many times (the noise model's tone curve at its fit
/// seeds, every family's fit and ranking at the analysis seed), and a 512² tile takes tens of
/// milliseconds to make (about 45 ms in the browser's worker) where a copy takes a fraction of
/// one. Same seed, same tile: what it returns does not depend on what was asked before.
fn recent_2d(seed: u32) -> Tile {
    use std::sync::{Arc, Mutex};
    static RECENT: Mutex<Vec<(u32, Arc<Tile>)>> = Mutex::new(Vec::new());
    // Least recently used last out: a hit moves to the back.
    let found = RECENT.lock().ok().and_then(|mut r| {
        let i = r.iter().position(|(s, _)| *s == seed)?;
        let entry = r.remove(i);
        let tile = entry.1.clone();
        r.push(entry);
        Some(tile)
    });
    let tile = found.unwrap_or_else(|| {
        let tile = Arc::new(Tile::generate(seed, 2, TILE_2D, rng::stream::TILE_2D));
        if let Ok(mut r) = RECENT.lock() {
            if r.len() == RECENT_2D {
                r.remove(0);
            }
            r.push((seed, tile.clone()));
        }
        tile
    });
    Tile::clone(&tile)
}

/// How many 2D tiles [`recent_2d`] keeps (3 MB each). An automatic analysis asks for nine
/// seeds: the database's (1), the analysis seed and the three after it (the structured fit's
/// tone curve pools four renders), and the noise model's four tone-fit seeds; eight at the
/// default seed, which is the database's. With eight kept first in, first out, every analysis
/// at another seed made all nine again; twelve keep one analysis's seeds and a few of the
/// previous one's.
const RECENT_2D: usize = 12;

/// The 2D tile's components drawn in the frequency domain ([`spectral`]): components 0 and 1
/// are the real and imaginary parts of one draw (the Gaussian values `0 … 2n²`), component 2 the
/// real part of the next (`2n² … 4n²`).
fn spectral_components(seed: u32, n: usize, stream: u32) -> [(Vec<f32>, TileStats); COMPONENTS] {
    let computed;
    let magnitude = if n == TILE_2D {
        spectral::tile2_magnitude()
    } else {
        computed = spectral::magnitude(n);
        &computed
    };
    let values = (2 * n * n) as u32;
    let draw = |d: u32| {
        spectral::field_pair(n, magnitude, |i| {
            rng::gaussian(seed, stream, d * values + i)
        })
    };
    let mut draws = crate::parallel::map_in_order(&[0u32, 1], |&d| draw(d)).into_iter();
    let (Some([c0, c1]), Some([c2, _])) = (draws.next(), draws.next()) else {
        unreachable!("two draws");
    };
    let mut planes =
        crate::parallel::map_in_order(&[c0, c1, c2], |c| normalised(c.clone(), n, 2)).into_iter();
    std::array::from_fn(|_| planes.next().expect("three components"))
}

/// One component of a (3D) tile by Cook & DeRose's construction: its normalised coefficients
/// and what generating it measured.
fn component(seed: u32, dims: usize, n: usize, stream: u32, k: usize) -> (Vec<f32>, TileStats) {
    let total = n.pow(dims as u32);
    let first = (k * total) as u32;
    let r: Vec<f64> = (0..total)
        .map(|i| rng::gaussian(seed, stream, first + i as u32))
        .collect();

    let band = wavelet_band(&r, n, dims);

    // Even/odd variance fix: add a copy shifted by an odd offset along every axis.
    let mut offset = n / 2;
    if offset.is_multiple_of(2) {
        offset += 1;
    }
    let data: Vec<f64> = (0..total)
        .map(|i| band[i] + band[shift_index(i, n, dims, offset)])
        .collect();
    normalised(data, n, dims)
}

/// Cook & DeRose's band `R − R↓↑` of the coefficients `r`: down- then up-sample along every
/// axis in turn (separable), and subtract.
fn wavelet_band(r: &[f64], n: usize, dims: usize) -> Vec<f64> {
    let mut low = r.to_vec();
    let mut line = vec![0.0; n];
    let mut half = vec![0.0; n / 2];
    for axis in 0..dims {
        for_each_line(n, dims, axis, |start, stride| {
            for i in 0..n {
                line[i] = low[start + i * stride];
            }
            downsample(&line, &mut half);
            upsample(&half, &mut line);
            for i in 0..n {
                low[start + i * stride] = line[i];
            }
        });
    }
    r.iter().zip(&low).map(|(a, b)| a - b).collect()
}

/// Coefficients normalised to zero mean and unit evaluated variance, with what that measured.
fn normalised(mut data: Vec<f64>, n: usize, dims: usize) -> (Vec<f32>, TileStats) {
    let total = data.len();
    let raw_mean = data.iter().sum::<f64>() / total as f64;
    data.iter_mut().for_each(|v| *v -= raw_mean);
    let raw_variance = evaluated_variance(&data, n, dims);
    let inv_sd = if raw_variance > 0.0 {
        1.0 / raw_variance.sqrt()
    } else {
        0.0
    };
    (
        data.iter().map(|v| (v * inv_sd) as f32).collect(),
        TileStats {
            raw_variance,
            raw_mean,
        },
    )
}

/// Calls `f(start, stride)` for every line of the tile along `axis`.
fn for_each_line(n: usize, dims: usize, axis: usize, mut f: impl FnMut(usize, usize)) {
    let stride = n.pow(axis as u32);
    let total = n.pow(dims as u32);
    for start in 0..total {
        // `start` is a line start when its coordinate along `axis` is 0.
        if (start / stride).is_multiple_of(n) {
            f(start, stride);
        }
    }
}

fn shift_index(i: usize, n: usize, dims: usize, offset: usize) -> usize {
    let mut out = 0;
    let mut rest = i;
    let mut mul = 1;
    for _ in 0..dims {
        let c = rest % n;
        rest /= n;
        out += ((c + offset) % n) * mul;
        mul *= n;
    }
    out
}

/// `r↓[i] = Σ_j a_j · r[(2i + j) mod n]`, `j = −16..15`.
fn downsample(from: &[f64], to: &mut [f64]) {
    let n = from.len() as i64;
    for (i, out) in to.iter_mut().enumerate() {
        let mut s = 0.0;
        for j in -16..16i64 {
            s += a_coeff(j) * from[(2 * i as i64 + j).rem_euclid(n) as usize];
        }
        *out = s;
    }
}

/// `r↑[i] = Σ_{k=⌊i/2⌋}^{⌊i/2⌋+1} p_{i−2k} · r↓[k mod n/2]`.
fn upsample(from: &[f64], to: &mut [f64]) {
    let half = from.len() as i64;
    for (i, out) in to.iter_mut().enumerate() {
        let i = i as i64;
        let mut s = 0.0;
        for k in (i / 2)..=(i / 2 + 1) {
            s += P_COEFFS[(i - 2 * k + 2) as usize] * from[k.rem_euclid(half) as usize];
        }
        *out = s;
    }
}

/// Exact variance over one period of the periodic quadratic B-spline field with zero-mean
/// coefficients `c`: `mean(c · (A ⊛ c))`, where `A` is the B-spline's autocorrelation at integer
/// lags (the quintic B-spline at −2..2: 1, 26, 66, 26, 1 over 120), applied along every axis.
fn evaluated_variance(c: &[f64], n: usize, dims: usize) -> f64 {
    const AUTO: [f64; 5] = [
        1.0 / 120.0,
        26.0 / 120.0,
        66.0 / 120.0,
        26.0 / 120.0,
        1.0 / 120.0,
    ];
    // Along every axis in turn, each output the five taps' sum in tap order (what convolving
    // one line at a time gives, bit for bit), with whole rows of the axes below moving together
    // so that no pass walks the tile with a stride of a row or a plane (a 512² tile's variance
    // took a fifth of its generation that way).
    let mut f = c.to_vec();
    let mut g = vec![0.0; c.len()];
    for axis in 0..dims {
        let stride = n.pow(axis as u32);
        for (from, to) in f
            .chunks_exact(stride * n)
            .zip(g.chunks_exact_mut(stride * n))
        {
            for (i, out) in to.chunks_exact_mut(stride).enumerate() {
                let taps: [&[f64]; 5] = std::array::from_fn(|d| {
                    let k = (i + n + d - 2) % n;
                    &from[k * stride..(k + 1) * stride]
                });
                for (j, o) in out.iter_mut().enumerate() {
                    let mut s = 0.0;
                    for (a, t) in AUTO.iter().zip(&taps) {
                        s += a * t[j];
                    }
                    *o = s;
                }
            }
        }
        std::mem::swap(&mut f, &mut g);
    }
    c.iter().zip(&f).map(|(a, b)| a * b).sum::<f64>() / c.len() as f64
}

// ---------------------------------------------------------------------------------------------
// Per-pixel evaluation: twins of the WGSL functions of the same names in `shaders/noise.wgsl`.
// Keep them in f32 and in the same operation order as the shader.
// ---------------------------------------------------------------------------------------------

/// Quadratic B-spline weights along one axis at `p ∈ [0, n)`: the index of the middle
/// coefficient and the weights of coefficients `mid − 1`, `mid`, `mid + 1`.
#[inline]
pub fn bspline_weights(p: f32) -> (i32, [f32; 3]) {
    let mid = (p - 0.5).ceil();
    let t = mid - (p - 0.5);
    let w0 = 0.5 * t * t;
    let w2 = 0.5 * (1.0 - t) * (1.0 - t);
    (mid as i32, [w0, 1.0 - w0 - w2, w2])
}

/// The tile's expected coefficient autocorrelation at lags 0 and ±1 along each axis, by how
/// many axes the lag moves along: `[R(0,0), R(±1,0), R(±1,±1)]`, each the mean over the axes
/// (or both diagonals). Measured over 6 seeds' tiles (`tile_lags_match_the_constants`
/// re-measures them). The 2D tile's lags of 2 (−0.08 along an axis, up to +0.2 diagonally: its
/// isotropic spectrum is not separable) are left out: with them the phase variance moves by
/// under 0.2 % at any phase.
pub const TILE2_LAGS: [f32; 3] = [5.5698, -1.1486, -0.7269];
/// As [`TILE2_LAGS`] for the 3D tile: lags moving along 0, 1, 2 and 3 axes.
pub const TILE3_LAGS: [f32; 4] = [8.964, -0.7905, -0.4997, -0.3143];

/// The B-spline weights' autocorrelation at lags 0 and ±1: `[Σ wᵢ², w₀w₁ + w₁w₂]`.
#[inline]
pub fn weight_lags(w: [f32; 3]) -> [f32; 2] {
    [
        w[0] * w[0] + w[1] * w[1] + w[2] * w[2],
        w[0] * w[1] + w[1] * w[2],
    ]
}

/// The variance of a 2D band at the sub-texel phase whose B-spline weights are `wx`, `wy`:
/// `V = Σ R(dx, dy) Cx(dx) Cy(dy)` over lags −1…1, `R` the tile's coefficient
/// autocorrelation ([`TILE2_LAGS`]) and `C` the weights' ([`weight_lags`]).
///
/// Departure from Cook & DeRose: a wavelet-noise band's variance depends on where a point lies
/// between coefficients (1.35 on them, 0.64 midway, 1 on average), a grid-aligned
/// modulation that the histogram spline cannot undo. Dividing by `√V` makes every phase unit
/// variance. Measured (docs/measurements.md, "The noise model against its ideal"): on the 27
/// stochastic dev photos the colour ratio went 2.07 → 1.66 and the overall 1.85 → 1.73.
#[inline]
pub fn phase_variance2(wx: [f32; 3], wy: [f32; 3]) -> f32 {
    let cx = weight_lags(wx);
    let cy = weight_lags(wy);
    TILE2_LAGS[0] * cx[0] * cy[0]
        + 2.0 * TILE2_LAGS[1] * (cx[0] * cy[1] + cx[1] * cy[0])
        + 4.0 * TILE2_LAGS[2] * cx[1] * cy[1]
}

/// As [`phase_variance2`] for a 3D band ([`TILE3_LAGS`]).
#[inline]
pub fn phase_variance3(wx: [f32; 3], wy: [f32; 3], wz: [f32; 3]) -> f32 {
    let cx = weight_lags(wx);
    let cy = weight_lags(wy);
    let cz = weight_lags(wz);
    TILE3_LAGS[0] * cx[0] * cy[0] * cz[0]
        + 2.0
            * TILE3_LAGS[1]
            * (cx[1] * cy[0] * cz[0] + cx[0] * cy[1] * cz[0] + cx[0] * cy[0] * cz[1])
        + 4.0
            * TILE3_LAGS[2]
            * (cx[1] * cy[1] * cz[0] + cx[1] * cy[0] * cz[1] + cx[0] * cy[1] * cz[1])
        + 8.0 * TILE3_LAGS[3] * cx[1] * cy[1] * cz[1]
}

#[inline]
pub(crate) fn wrap_coord(p: f32, n: f32) -> f32 {
    p - n * (p / n).floor()
}

/// `i mod n` for a power-of-two tile side `n` (the 2D tile is 512², the 3D one 64³): a mask,
/// which the GPU twin also uses because integer division is slow on software rasterisers (it
/// made `%` the costliest operation of the plane shader on SwiftShader).
#[inline]
fn wrap_index(i: i32, n: i32) -> usize {
    debug_assert!(
        n > 0 && (n & (n - 1)) == 0,
        "tile side {n} is not a power of two"
    );
    (i & (n - 1)) as usize
}

/// One 2D wavelet-noise band of every component at `p` (coefficient units), periodic with
/// period `n`: `tile` holds the [`COMPONENTS`] planes ([`Tile::data`]).
#[inline]
pub fn noise2(tile: &[f32], n: usize, p: [f32; 2]) -> [f32; COMPONENTS] {
    noise2_components(tile, n, p)
}

/// Component 0 of [`noise2`], the same operations on the first plane alone (the structured
/// models' pattern noise reads only it; the GPU takes `.x` of the one fetch).
#[inline]
pub fn noise2_first(tile: &[f32], n: usize, p: [f32; 2]) -> f32 {
    noise2_components::<1>(tile, n, p)[0]
}

#[inline]
fn noise2_components<const K: usize>(tile: &[f32], n: usize, p: [f32; 2]) -> [f32; K] {
    let nf = n as f32;
    let ni = n as i32;
    let plane = n * n;
    let (mx, wx) = bspline_weights(wrap_coord(p[0], nf));
    let (my, wy) = bspline_weights(wrap_coord(p[1], nf));
    let rows = [0, 1, 2].map(|d| wrap_index(my + d - 1, ni) * n);
    let cols = [0, 1, 2].map(|d| wrap_index(mx + d - 1, ni));
    band_3x3(tile, plane, rows, cols, wx, wy)
}

/// The B-spline sum over the 3×3 coefficients at `rows` (offsets of their rows) and `cols`
/// of every component (planes `plane` apart), divided by the band's deviation at the phase.
#[inline]
fn band_3x3<const K: usize>(
    tile: &[f32],
    plane: usize,
    rows: [usize; 3],
    cols: [usize; 3],
    wx: [f32; 3],
    wy: [f32; 3],
) -> [f32; K] {
    let mut sum = [0.0f32; K];
    for dy in 0..3 {
        let mut line = [0.0f32; K];
        for dx in 0..3 {
            let i = rows[dy] + cols[dx];
            for k in 0..K {
                line[k] += wx[dx] * tile[i + k * plane];
            }
        }
        for k in 0..K {
            sum[k] += wy[dy] * line[k];
        }
    }
    let sd = phase_variance2(wx, wy).sqrt();
    sum.map(|v| v / sd)
}

/// `i mod m` for any `m ≥ 1` (a wrapped period need not be a power of two).
#[inline]
pub fn wrap_period(i: i32, m: i32) -> usize {
    i.rem_euclid(m) as usize
}

/// The whole number of coefficients nearest `m` that a band of a tile of side `n` can repeat
/// with: at least 1, and a multiple of `n` when `m ≥ n` (the band already repeats every `n`
/// coefficients). Halves round up (`floor(x + 0.5)`: WGSL's `round` rounds them to even).
#[inline]
pub fn whole_period(m: f32, n: f32) -> f32 {
    if m < n {
        (m + 0.5).floor().max(1.0)
    } else {
        n * (m / n + 0.5).floor()
    }
}

/// One 2D band of every component at `p` (coefficient units) with its coefficient indices
/// wrapped at `min(period, n)` per axis: periodic with `period` (per axis) when each is a whole
/// number (see [`whole_period`]). The quadratic B-spline of a wrapped coefficient sequence is
/// periodic and C¹, so a seamless tile's edges continue each other like interior pixels.
#[inline]
pub fn noise2_periodic(tile: &[f32], n: usize, p: [f32; 2], period: [f32; 2]) -> [f32; COMPONENTS] {
    noise2_periodic_components(tile, n, p, period)
}

/// Component 0 of [`noise2_periodic`] (see [`noise2_first`]).
#[inline]
pub fn noise2_periodic_first(tile: &[f32], n: usize, p: [f32; 2], period: [f32; 2]) -> f32 {
    noise2_periodic_components::<1>(tile, n, p, period)[0]
}

#[inline]
fn noise2_periodic_components<const K: usize>(
    tile: &[f32],
    n: usize,
    p: [f32; 2],
    period: [f32; 2],
) -> [f32; K] {
    let plane = n * n;
    let pw = [period[0].min(n as f32), period[1].min(n as f32)];
    let (px, py) = (pw[0] as i32, pw[1] as i32);
    let (mx, wx) = bspline_weights(wrap_coord(p[0], pw[0]));
    let (my, wy) = bspline_weights(wrap_coord(p[1], pw[1]));
    let rows = [0, 1, 2].map(|d| wrap_period(my + d - 1, py) * n);
    let cols = [0, 1, 2].map(|d| wrap_period(mx + d - 1, px));
    band_3x3(tile, plane, rows, cols, wx, wy)
}

/// One 3D wavelet-noise band of every component at `p` (coefficient units), periodic with
/// period `n`.
#[inline]
pub fn noise3(tile: &[f32], n: usize, p: [f32; 3]) -> [f32; COMPONENTS] {
    noise3_components(tile, n, p)
}

/// Component 0 of [`noise3`] (see [`noise2_first`]).
#[inline]
pub fn noise3_first(tile: &[f32], n: usize, p: [f32; 3]) -> f32 {
    noise3_components::<1>(tile, n, p)[0]
}

#[inline]
fn noise3_components<const K: usize>(tile: &[f32], n: usize, p: [f32; 3]) -> [f32; K] {
    let nf = n as f32;
    let ni = n as i32;
    let volume = n * n * n;
    let (mx, wx) = bspline_weights(wrap_coord(p[0], nf));
    let (my, wy) = bspline_weights(wrap_coord(p[1], nf));
    let (mz, wz) = bspline_weights(wrap_coord(p[2], nf));
    let mut sum = [0.0f32; K];
    for dz in 0..3 {
        let slab = wrap_index(mz + dz as i32 - 1, ni) * n * n;
        let mut plane = [0.0f32; K];
        for dy in 0..3 {
            let row = slab + wrap_index(my + dy as i32 - 1, ni) * n;
            let mut line = [0.0f32; K];
            for dx in 0..3 {
                let i = row + wrap_index(mx + dx as i32 - 1, ni);
                for k in 0..K {
                    line[k] += wx[dx] * tile[i + k * volume];
                }
            }
            for k in 0..K {
                plane[k] += wy[dy] * line[k];
            }
        }
        for k in 0..K {
            sum[k] += wz[dz] * plane[k];
        }
    }
    let sd = phase_variance3(wx, wy, wz).sqrt();
    sum.map(|v| v / sd)
}

/// Side of the 3D tile (twin of `tile3_side` in `shaders/tile3.wgsl` and `tile3_atlas.wgsl`).
#[inline]
pub fn tile3_side(tile: &Tile) -> usize {
    tile.n
}

/// Coefficient `c` of every component of a 3D tile of side `n` (twin of `tile3_texel` in
/// `shaders/tile3.wgsl` and `tile3_atlas.wgsl`; [`noise3`] inlines this indexing with
/// precomputed row offsets).
#[inline]
pub fn tile3_texel(tile: &[f32], n: usize, c: [usize; 3]) -> [f32; COMPONENTS] {
    let i = c[0] + n * (c[1] + n * c[2]);
    std::array::from_fn(|k| tile[i + k * n * n * n])
}

/// Slices per row of a slice atlas (`ATLAS_COLUMNS` in `shaders/atlas3.wgsl`).
pub const ATLAS_COLUMNS: usize = 8;

/// The atlas texel of voxel `c` of a volume whose slices are `size` texels (twin of
/// `atlas_texel` in `shaders/atlas3.wgsl`): slice z at column z % 8, row z / 8.
#[inline]
pub fn atlas_texel(c: [usize; 3], size: [usize; 2]) -> [usize; 2] {
    [
        c[0] + size[0] * (c[2] % ATLAS_COLUMNS),
        c[1] + size[1] * (c[2] / ATLAS_COLUMNS),
    ]
}

/// The voxel at atlas texel `t` (twin of `atlas_voxel` in `shaders/atlas3.wgsl`).
#[inline]
pub fn atlas_voxel(t: [usize; 2], size: [usize; 2]) -> [usize; 3] {
    let (col, row) = (t[0] / size[0], t[1] / size[1]);
    [
        t[0] - col * size[0],
        t[1] - row * size[1],
        col + ATLAS_COLUMNS * row,
    ]
}

impl Tile {
    /// A 3D tile as the slice atlas that exported solid textures bake (`8n × n²/8`, row-major,
    /// RGBA: the components in RGB, 0 in A): what `fs_bake3_tile` must produce.
    pub fn atlas(&self) -> (usize, usize, Vec<f32>) {
        assert_eq!(self.dims, 3, "only 3D tiles have an atlas");
        let n = self.n;
        let (w, h) = (n * ATLAS_COLUMNS, n * n / ATLAS_COLUMNS);
        let mut out = vec![0.0; 4 * w * h];
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    let [u, v] = atlas_texel([x, y, z], [n, n]);
                    let t = tile3_texel(&self.data, n, [x, y, z]);
                    out[4 * (u + w * v)..][..COMPONENTS].copy_from_slice(&t);
                }
            }
        }
        (w, h, out)
    }

    /// The coefficients as RGBA texels, x fastest (the components in RGB, 0 in A): what the GPU
    /// tile texture holds, one fetch for every component.
    pub fn rgba(&self) -> Vec<f32> {
        let len = self.n.pow(self.dims as u32);
        let mut out = vec![0.0; 4 * len];
        for k in 0..COMPONENTS {
            for (i, v) in self.plane(k).iter().enumerate() {
                out[4 * i + k] = *v;
            }
        }
        out
    }
}

/// Band clamping (Norton et al. 1982): the factor of band `j` (energy up to `2^−(j+1)` cycles per
/// texel) when one pixel covers `2^log2_footprint` texels. 1 while the band is below the pixel
/// Nyquist rate, fading linearly (in octaves) to 0 when it lies an octave above it.
#[inline]
pub fn band_fade(band: u32, log2_footprint: f32) -> f32 {
    (1.0 - (log2_footprint - band as f32)).clamp(0.0, 1.0)
}

pub mod oriented;
pub mod spectral;

#[cfg(test)]
mod tests;
