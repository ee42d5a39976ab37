//! Oriented bands: a band mixed with its own directional derivative, so that its power follows
//! the angular profile `1 + s·cos 2(θ − θ₀)` about the derivative's direction `θ₀` (features
//! stretched across it, along `θ₀ + 90°`), with `s ∈ [0, 1]` the strength.
//!
//! Departure from Lagae et al. and Cook & DeRose, whose bands are isotropic. Why this form:
//! - The derivative of a quadratic B-spline surface is exact and local: the same 3×3 (3×3×3)
//!   coefficients and one fetch per tap give the band and its gradient, so an oriented band
//!   costs arithmetic, not texture loads; periodic (seamless) and solid bands stay what they
//!   were.
//! - A stationary field and its derivative are uncorrelated and the derivative's spectrum is the
//!   band's times `(f·d)²`, so `α·N + β·d·∇N` has the band's spectrum times
//!   `α² + β²(f·d)²`: with `α² = 1 − s` and `β² = s / σ²_∇` (the derivative's mean variance),
//!   the profile above at unit variance.
//! - Measured before building it (`noise_ideal_lab --orient`, ideal Gaussian fields with exact
//!   histograms, 27 stochastic dev photos, 2 seeds): one such profile per octave, shared by the
//!   three channels, takes the structure ratio of octave boxes 1.79 → 1.32 (free 45° wedges,
//!   4 numbers per octave and channel: 1.25; a narrow von Mises profile: 1.21) and the overall
//!   1.51 → 1.35; on the shipped photos 1.20 → 1.16.
//!
//! As for the plain band ([`super::phase_variance2`]), the mixture's variance depends on the
//! sub-texel phase and is divided out exactly: the coefficients' covariance is the tile's
//! [`TILE2_LAGS`] / [`TILE3_LAGS`], so the variance of any linear combination of the 3×3 taps
//! is a sum over pairs of separable weight products ([`pair_covariance2`]); the mixture is two
//! separable terms ([`mixed_weights`]), so three pairs.
//!
//! Every function has a WGSL twin of the same name in `shaders/noise.wgsl` (and GLSL in
//! `shaders/glsl/noise.glsl`). Same operation order, f32.

use super::{
    COMPONENTS, TILE2_LAGS, TILE3_LAGS, bspline_weights, wrap_coord, wrap_index, wrap_period,
};

/// The derivatives (per coefficient) of the quadratic B-spline weights of [`bspline_weights`]
/// at `p`, for the same three coefficients.
#[inline]
pub fn bspline_derivative(p: f32) -> [f32; 3] {
    let mid = (p - 0.5).ceil();
    let t = mid - (p - 0.5);
    [-t, 2.0 * t - 1.0, 1.0 - t]
}

/// The cross-correlation of two weight triples at lag 0 and at lags ±1 together:
/// `[Σ aᵢbᵢ, Σ (aᵢbᵢ₊₁ + aᵢ₊₁bᵢ)]` (for `a = b`: `Σ aᵢ²` and twice [`super::weight_lags`]'s
/// second entry).
#[inline]
pub fn cross_lags(a: [f32; 3], b: [f32; 3]) -> [f32; 2] {
    [
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
        a[0] * b[1] + a[1] * b[0] + a[1] * b[2] + a[2] * b[1],
    ]
}

/// The covariance of two separable 3×3 tap weightings whose per-axis cross-lags are `x` and
/// `y` ([`cross_lags`]), under the 2D tile's coefficient autocorrelation.
#[inline]
pub fn pair_covariance2(x: [f32; 2], y: [f32; 2]) -> f32 {
    TILE2_LAGS[0] * x[0] * y[0]
        + TILE2_LAGS[1] * (x[1] * y[0] + x[0] * y[1])
        + TILE2_LAGS[2] * x[1] * y[1]
}

/// As [`pair_covariance2`] for 3×3×3 taps under the 3D tile's autocorrelation.
#[inline]
pub fn pair_covariance3(x: [f32; 2], y: [f32; 2], z: [f32; 2]) -> f32 {
    TILE3_LAGS[0] * x[0] * y[0] * z[0]
        + TILE3_LAGS[1] * (x[1] * y[0] * z[0] + x[0] * y[1] * z[0] + x[0] * y[0] * z[1])
        + TILE3_LAGS[2] * (x[1] * y[1] * z[0] + x[1] * y[0] * z[1] + x[0] * y[1] * z[1])
        + TILE3_LAGS[3] * x[1] * y[1] * z[1]
}

/// Phase averages of the cross-lags over a uniform sub-texel phase: of the weights
/// (`[11/20, 13/30]`) and of their derivatives (`[1, −2/3]`), by integrating the polynomials of
/// [`bspline_weights`] and [`bspline_derivative`].
const WEIGHT_LAGS_MEAN: [f32; 2] = [11.0 / 20.0, 13.0 / 30.0];
const DERIVATIVE_LAGS_MEAN: [f32; 2] = [1.0, -2.0 / 3.0];

/// `σ²_∇`: the variance of a 2D band's derivative along an axis (per coefficient), averaged
/// over phases (the band itself averages to 1). About 3.20.
pub fn gradient_variance2() -> f32 {
    pair_covariance2(DERIVATIVE_LAGS_MEAN, WEIGHT_LAGS_MEAN)
}

/// As [`gradient_variance2`] for a 3D band's derivative along x or y.
pub fn gradient_variance3() -> f32 {
    pair_covariance3(DERIVATIVE_LAGS_MEAN, WEIGHT_LAGS_MEAN, WEIGHT_LAGS_MEAN)
}

/// A band's mixing coefficients `[α, β·dx, β·dy]` for streaks along `angle_deg` (texel
/// coordinates, the sense of [`crate::params::Transform::rotation_deg`]) at strength `s`: the
/// derivative runs across the streaks, `d = (−sin a, cos a)`. `grad_var` is
/// [`gradient_variance2`] or [`gradient_variance3`].
pub fn mixing(angle_deg: f32, strength: f32, grad_var: f32) -> [f32; 3] {
    let s = strength.clamp(0.0, 1.0);
    let a = angle_deg.to_radians();
    let beta = (s / grad_var).sqrt();
    [(1.0 - s).sqrt(), -a.sin() * beta, a.cos() * beta]
}

/// The x weights of the mixture's first separable term: `α·wx + gx·dwx`. The mixture
/// `α·N + gx·∂N/∂x + gy·∂N/∂y` weighs the taps by `ax ⊗ wy + gy·(wx ⊗ dwy)`: two separable
/// terms, so its value takes two row sums and its variance three pair covariances.
#[inline]
pub fn mixed_weights(wx: [f32; 3], dwx: [f32; 3], m: [f32; 3]) -> [f32; 3] {
    [
        m[0] * wx[0] + m[1] * dwx[0],
        m[0] * wx[1] + m[1] * dwx[1],
        m[0] * wx[2] + m[1] * dwx[2],
    ]
}

/// The variance of a 2D mixture at one phase: `ax` from [`mixed_weights`], `wx`, `wy` the
/// B-spline weights, `dwy` their derivative along y, `gy` the mixture's y derivative weight.
#[inline]
pub fn oriented_variance2(ax: [f32; 3], wx: [f32; 3], wy: [f32; 3], dwy: [f32; 3], gy: f32) -> f32 {
    pair_covariance2(cross_lags(ax, ax), cross_lags(wy, wy))
        + 2.0 * gy * pair_covariance2(cross_lags(ax, wx), cross_lags(wy, dwy))
        + gy * gy * pair_covariance2(cross_lags(wx, wx), cross_lags(dwy, dwy))
}

/// As [`oriented_variance2`] for a 3D band whose derivative lies in the xy plane (`wz` the
/// z weights).
#[inline]
pub fn oriented_variance3(
    ax: [f32; 3],
    wx: [f32; 3],
    wy: [f32; 3],
    wz: [f32; 3],
    dwy: [f32; 3],
    gy: f32,
) -> f32 {
    let zz = cross_lags(wz, wz);
    pair_covariance3(cross_lags(ax, ax), cross_lags(wy, wy), zz)
        + 2.0 * gy * pair_covariance3(cross_lags(ax, wx), cross_lags(wy, dwy), zz)
        + gy * gy * pair_covariance3(cross_lags(wx, wx), cross_lags(dwy, dwy), zz)
}

/// One oriented 2D band of every component at `p` (coefficient units), periodic with period
/// `n`, mixed by `m` ([`mixing`]).
#[inline]
pub fn noise2_oriented(tile: &[f32], n: usize, p: [f32; 2], m: [f32; 3]) -> [f32; COMPONENTS] {
    let nf = n as f32;
    let ni = n as i32;
    let (px, py) = (wrap_coord(p[0], nf), wrap_coord(p[1], nf));
    let (mx, wx) = bspline_weights(px);
    let (my, wy) = bspline_weights(py);
    let rows = [0, 1, 2].map(|d| wrap_index(my + d - 1, ni) * n);
    let cols = [0, 1, 2].map(|d| wrap_index(mx + d - 1, ni));
    let ax = mixed_weights(wx, bspline_derivative(px), m);
    let dwy = bspline_derivative(py);
    oriented_3x3(tile, n * n, rows, cols, [ax, wx, wy, dwy], m[2])
}

/// [`noise2_oriented`] with its coefficient indices wrapped at `min(period, n)` per axis, as
/// [`super::noise2_periodic`].
#[inline]
pub fn noise2_periodic_oriented(
    tile: &[f32],
    n: usize,
    p: [f32; 2],
    period: [f32; 2],
    m: [f32; 3],
) -> [f32; COMPONENTS] {
    let pw = [period[0].min(n as f32), period[1].min(n as f32)];
    let (px, py) = (wrap_coord(p[0], pw[0]), wrap_coord(p[1], pw[1]));
    let (mx, wx) = bspline_weights(px);
    let (my, wy) = bspline_weights(py);
    let rows = [0, 1, 2].map(|d| wrap_period(my + d - 1, pw[1] as i32) * n);
    let cols = [0, 1, 2].map(|d| wrap_period(mx + d - 1, pw[0] as i32));
    let ax = mixed_weights(wx, bspline_derivative(px), m);
    let dwy = bspline_derivative(py);
    oriented_3x3(tile, n * n, rows, cols, [ax, wx, wy, dwy], m[2])
}

/// The mixture over the 3×3 coefficients at `rows` and `cols` of every component, weighted
/// `ax ⊗ wy + gy·(wx ⊗ dwy)` (`w = [ax, wx, wy, dwy]`), divided by its deviation at the phase.
#[inline]
fn oriented_3x3(
    tile: &[f32],
    plane: usize,
    rows: [usize; 3],
    cols: [usize; 3],
    w: [[f32; 3]; 4],
    gy: f32,
) -> [f32; COMPONENTS] {
    let [ax, wx, wy, dwy] = w;
    let mut sum = [0.0f32; COMPONENTS];
    for dy in 0..3 {
        let mut line_a = [0.0f32; COMPONENTS];
        let mut line = [0.0f32; COMPONENTS];
        for dx in 0..3 {
            let i = rows[dy] + cols[dx];
            for k in 0..COMPONENTS {
                let c = tile[i + k * plane];
                line_a[k] += ax[dx] * c;
                line[k] += wx[dx] * c;
            }
        }
        for k in 0..COMPONENTS {
            sum[k] += wy[dy] * line_a[k] + gy * dwy[dy] * line[k];
        }
    }
    let sd = oriented_variance2(ax, wx, wy, dwy, gy).sqrt();
    sum.map(|v| v / sd)
}

/// One oriented 3D band of every component at `p` (coefficient units), periodic with period
/// `n`, its derivative in the xy plane, mixed by `m` ([`mixing`] with [`gradient_variance3`]).
#[inline]
pub fn noise3_oriented(tile: &[f32], n: usize, p: [f32; 3], m: [f32; 3]) -> [f32; COMPONENTS] {
    let nf = n as f32;
    let ni = n as i32;
    let volume = n * n * n;
    let q = p.map(|v| wrap_coord(v, nf));
    let (mx, wx) = bspline_weights(q[0]);
    let (my, wy) = bspline_weights(q[1]);
    let (mz, wz) = bspline_weights(q[2]);
    let ax = mixed_weights(wx, bspline_derivative(q[0]), m);
    let dwy = bspline_derivative(q[1]);
    let gy = m[2];
    let mut sum = [0.0f32; COMPONENTS];
    for dz in 0..3 {
        let slab = wrap_index(mz + dz as i32 - 1, ni) * n * n;
        let mut plane = [0.0f32; COMPONENTS];
        for dy in 0..3 {
            let row = slab + wrap_index(my + dy as i32 - 1, ni) * n;
            let mut line_a = [0.0f32; COMPONENTS];
            let mut line = [0.0f32; COMPONENTS];
            for dx in 0..3 {
                let i = row + wrap_index(mx + dx as i32 - 1, ni);
                for k in 0..COMPONENTS {
                    let c = tile[i + k * volume];
                    line_a[k] += ax[dx] * c;
                    line[k] += wx[dx] * c;
                }
            }
            for k in 0..COMPONENTS {
                plane[k] += wy[dy] * line_a[k] + gy * dwy[dy] * line[k];
            }
        }
        for k in 0..COMPONENTS {
            sum[k] += wz[dz] * plane[k];
        }
    }
    let sd = oriented_variance3(ax, wx, wy, wz, dwy, gy).sqrt();
    sum.map(|v| v / sd)
}
