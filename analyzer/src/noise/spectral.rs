//! The 2D tile drawn in the frequency domain: complex white noise times a fixed magnitude `M`,
//! inverse-transformed. `M` keeps the wavelet band's radial profile (Cook & DeRose's
//! construction sets it) but drops two things the construction adds:
//! - **the square lattice's four-fold bias.** The band is built with separable filters and
//!   evaluated with a separable B-spline, so a rendered band held about 0.15 less log energy
//!   along the diagonals than along the axes (`examples/band_anisotropy.rs`). Inside the disk of
//!   ½ cycle per coefficient, `M²·|B|²` (the rendered power, `B` the quadratic B-spline's
//!   transfer) is the ring average of the wavelet band's `E·|B|²`; the corners outside it,
//!   which only diagonals reach, keep the wavelet band's own power.
//! - **the even/odd fix's comb.** Adding a copy shifted by an odd offset multiplies the power by
//!   `2 + 2 cos(2π·o·(ux + uy))`, near-zero lines a few bins apart. A tile drawn from white
//!   noise is stationary, so it needs no fix.
//!
//! Measured (docs/measurements.md, "The plane tile drawn in the frequency domain, in the
//! product"): the noise model on the 27 stochastic dev photos at 6 seeds, −0.057 ± 0.019
//! overall (1.444 → 1.387; structure −0.141, colour −0.018, spectrum −0.013); on the 8 shipped
//! stochastic samples −0.006 ± 0.012 (neutral). The synthetic round trip finds the right family
//! in 335 of 432 cases with either tile.
//!
//! `E(u)`, the wavelet band's expected power, is exact: the construction is linear and
//! shift-covariant by 2 along each axis, so for unit white input
//! `E(u) = (n²/4) Σ_p |Ĥ_p(u)|²` over the responses `H_p` to unit impulses at the four
//! positions `p ∈ {0,1}²`.

use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

use super::wavelet_band;

/// [`expected_power`] in closed form at bin `(kx, ky)`, what a shader can evaluate per bin.
/// With `Â(u) = Σ_j a_j e^{−2πiuj}` and `P̂(u) = Σ_m p_m e^{−2πium}`, one axis' down- then
/// up-sampling maps `r̂(u)` to `½ P̂(u) [Â*(u) r̂(u) + Â*(u+½) r̂(u+½)]`, so the band
/// `R − R↓↑` at `u` is `r̂(u) (1 − ¼ P̂P̂ Â*Â*)` minus the three aliases `¼ P̂P̂ Â*(ux+sx)
/// Â*(uy+sy) r̂(u+s)`, and for unit white input (`E|r̂|² = n²`, aliases uncorrelated)
/// `E(u) = n² (|1 − ¼ P̂(ux) P̂(uy) Â*(ux) Â*(uy)|² + |P̂(ux) P̂(uy)|²/16 ·
/// Σ_{s≠0} |Â(ux+sx)|² |Â(uy+sy)|²)`.
pub fn expected_power_at(n: usize, kx: usize, ky: usize) -> f64 {
    let (ux, uy) = (kx as f64 / n as f64, ky as f64 / n as f64);
    let x = AxisTransfers::at(ux);
    let y = AxisTransfers::at(uy);
    x.power_with(&y, n)
}

/// [`expected_power_at`] at every bin `kx + n·ky`: the transfers are evaluated once per axis
/// position (`3n` sums of at most 32 taps) and combined per bin. [`expected_power`] gets the
/// same from four impulse responses and eight `n×n` FFTs, 20 times as long at `n` = 512.
pub fn expected_power_grid(n: usize) -> Vec<f64> {
    let axis: Vec<AxisTransfers> = (0..n)
        .map(|k| AxisTransfers::at(k as f64 / n as f64))
        .collect();
    (0..n * n)
        .map(|i| axis[i % n].power_with(&axis[i / n], n))
        .collect()
}

/// One axis' transfers at frequency `u`: `Â(u)`, `Â(u + ½)` and `P̂(u)` (see
/// [`expected_power_at`]).
struct AxisTransfers {
    a: Complex64,
    a_half: Complex64,
    p: Complex64,
}

impl AxisTransfers {
    fn at(u: f64) -> Self {
        let transfer = |taps: &mut dyn Iterator<Item = (i64, f64)>, u: f64| {
            taps.fold(Complex64::default(), |acc, (j, c)| {
                acc + Complex64::from_polar(c, -2.0 * std::f64::consts::PI * u * j as f64)
            })
        };
        let a = |u: f64| transfer(&mut (-16..16i64).map(|j| (j, super::a_coeff(j))), u);
        let p = transfer(
            &mut (-2..2i64).map(|m| (m, super::P_COEFFS[(m + 2) as usize])),
            u,
        );
        AxisTransfers {
            a: a(u),
            a_half: a(u + 0.5),
            p,
        }
    }

    /// The band's expected power at the bin whose x transfers are `self` and y transfers `y`.
    fn power_with(&self, y: &AxisTransfers, n: usize) -> f64 {
        let pp = self.p * y.p;
        let own = Complex64::new(1.0, 0.0) - 0.25 * pp * self.a.conj() * y.a.conj();
        let aliases = self.a_half.norm_sqr() * y.a.norm_sqr()
            + self.a.norm_sqr() * y.a_half.norm_sqr()
            + self.a_half.norm_sqr() * y.a_half.norm_sqr();
        (n * n) as f64 * (own.norm_sqr() + pp.norm_sqr() / 16.0 * aliases)
    }
}

/// Signed frequency of bin `k` of `n`, cycles per coefficient.
fn frequency(k: usize, n: usize) -> f64 {
    let signed = if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    };
    signed / n as f64
}

/// `|B(u)|²` of the quadratic B-spline the tile is evaluated with: `sinc⁶` along each axis.
fn spline_power(kx: usize, ky: usize, n: usize) -> f64 {
    let sinc = |u: f64| {
        if u == 0.0 {
            1.0
        } else {
            let x = std::f64::consts::PI * u;
            x.sin() / x
        }
    };
    (sinc(frequency(kx, n)) * sinc(frequency(ky, n))).powi(6)
}

/// Ring (of one bin, by rounded radius) of bin `(kx, ky)`.
fn ring(kx: usize, ky: usize, n: usize) -> usize {
    let (ux, uy) = (frequency(kx, n), frequency(ky, n));
    ((ux * ux + uy * uy).sqrt() * n as f64).round() as usize
}

/// The rendered power `E·|B|²` of the wavelet band averaged over each ring of one bin, rings
/// `0..=n/2` (the disk): the isotropic profile the tile's magnitude takes inside the disk, and
/// the constant `TILE_PROFILE` of the GPU bake.
pub fn ring_profile(n: usize) -> Vec<f64> {
    ring_profile_of(&expected_power_grid(n), n)
}

/// [`ring_profile`] from the band's expected power per bin ([`expected_power_grid`]).
fn ring_profile_of(expected: &[f64], n: usize) -> Vec<f64> {
    let rings = n / 2 + 1;
    let (mut sum, mut count) = (vec![0.0f64; rings], vec![0usize; rings]);
    for ky in 0..n {
        for kx in 0..n {
            let r = ring(kx, ky, n);
            if r < rings {
                sum[r] += expected[kx + n * ky] * spline_power(kx, ky, n);
                count[r] += 1;
            }
        }
    }
    sum.iter().zip(&count).map(|(s, &c)| s / c as f64).collect()
}

/// [`ring_profile`] of the 2D tile ([`super::TILE_2D`]), computed once: what the exported bake
/// passes carry as `TILE_PROFILE`.
pub fn tile2_profile() -> &'static [f64] {
    static PROFILE: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    PROFILE.get_or_init(|| ring_profile(super::TILE_2D))
}

/// [`magnitude`] of the 2D tile ([`super::TILE_2D`]), computed once: every tile of that side
/// shares it.
pub fn tile2_magnitude() -> &'static [f64] {
    static MAGNITUDE: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    MAGNITUDE.get_or_init(|| magnitude(super::TILE_2D))
}

/// `M(u)` at every frequency bin `kx + n·ky` of an `n×n` tile (bins in FFT order): inside the
/// disk the ring profile over the B-spline's transfer, outside it the wavelet band's own
/// expected power, over n². `Σ E = n⁴·σ²` for coefficients of variance σ² (Parseval) and the
/// unscaled inverse DFT of `Z·M` has variance `Σ M²` per part, so dividing by n² keeps the
/// band's raw variance.
pub fn magnitude(n: usize) -> Vec<f64> {
    let expected = expected_power_grid(n);
    let profile = ring_profile_of(&expected, n);
    let scale = 1.0 / (n * n) as f64;
    (0..n * n)
        .map(|i| {
            let (kx, ky) = (i % n, i / n);
            let r = ring(kx, ky, n);
            let power = if r < profile.len() {
                profile[r] / spline_power(kx, ky, n)
            } else {
                expected[i]
            };
            power.sqrt() * scale
        })
        .collect()
}

/// The wavelet band's expected power per bin for unit white input from the construction's
/// four polyphase impulse responses (see the module docs): the reference the closed form
/// ([`expected_power_grid`]) is tested against.
pub fn expected_power(n: usize) -> Vec<f64> {
    let mut out = vec![0.0f64; n * n];
    for p in [[0, 0], [1, 0], [0, 1], [1, 1]] {
        let mut impulse = vec![0.0f64; n * n];
        impulse[p[0] + n * p[1]] = 1.0;
        let h = fft2(
            wavelet_band(&impulse, n, 2)
                .into_iter()
                .map(Complex64::from)
                .collect(),
            n,
            false,
        );
        for (o, v) in out.iter_mut().zip(&h) {
            *o += v.norm_sqr() * (n * n) as f64 / 4.0;
        }
    }
    out
}

/// Two independent real fields `[Re X, Im X]` of `X = IFFT(Z·M)`, `Z` complex white noise of
/// unit variance per part from `gaussian(i)` (bin `b` takes values `2b` and `2b + 1`). Their
/// real and imaginary parts are independent because `M(u) = M(−u)`.
pub fn field_pair(n: usize, magnitude: &[f64], gaussian: impl Fn(u32) -> f64) -> [Vec<f64>; 2] {
    let spec: Vec<Complex64> = (0..n * n)
        .map(|b| {
            let z = Complex64::new(gaussian(2 * b as u32), gaussian(2 * b as u32 + 1));
            z * magnitude[b]
        })
        .collect();
    let x = fft2(spec, n, true);
    [
        x.iter().map(|c| c.re).collect(),
        x.iter().map(|c| c.im).collect(),
    ]
}

/// The 2D DFT of an `n×n` array (rows, then columns), inverse unscaled when `inverse`.
fn fft2(mut data: Vec<Complex64>, n: usize, inverse: bool) -> Vec<Complex64> {
    let mut planner = FftPlanner::<f64>::new();
    let fft = if inverse {
        planner.plan_fft_inverse(n)
    } else {
        planner.plan_fft_forward(n)
    };
    for row in data.chunks_exact_mut(n) {
        fft.process(row);
    }
    let mut column = vec![Complex64::default(); n];
    for x in 0..n {
        for y in 0..n {
            column[y] = data[x + n * y];
        }
        fft.process(&mut column);
        for y in 0..n {
            data[x + n * y] = column[y];
        }
    }
    data
}
