//! Power spectrum matching (Lagae §4): 2D FFT (rustfft, any size), band power per octave
//! (eq. 10), and band weights (eq. 9), plus two improvements over the paper, both measured in the
//! round-trip tests and docs/measurements.md:
//!
//! 1. **Periodic + smooth decomposition** (Moisan 2011). The FFT treats the photo as periodic;
//!    its non-matching borders add a cross of spurious energy along the frequency axes that the
//!    paper counts as texture. We subtract the spectrum of the smooth component, obtained in
//!    closed form from the border differences with two 1D FFTs, so it costs next to nothing.
//! 2. **Deconvolved weights.** Eq. 9 assumes each noise band puts all its power in its own
//!    octave (operator `S_b`, eq. 4). Real wavelet-noise bands overlap (Lagae Fig. 3), so eq. 9
//!    over-estimates weak bands next to strong ones. We measured, for our own bands, the fraction
//!    of band `i`'s power that lands in octave `j` (the *leakage matrix* `L`, see
//!    [`measure_leakage`]) and solve `P = L·w²` for `w² ≥ 0` instead. [`Estimator::Lagae`] keeps
//!    the paper's estimator for comparison.
//! 3. **Weights fitted on fine rings** ([`crate::ring_fit`], the default): from the deconvolved
//!    solve, the weights are refined to the photo's radial spectrum on quarter-octave circular
//!    rings in the log domain, which is what the octaves cannot see.
//!
//! Band numbering: index 0 is the finest band, `[1/4, 1/2]` cycles per pixel of the analysed
//! image; band `j` is `(2^−(j+2), 2^−(j+1)]`; frequencies below the coarsest band fold into it.
//! A bin's frequency is `max(|f_x|, |f_y|)` as in eq. 10, in cycles per pixel, so non-square and
//! non-power-of-two images work.

use std::cell::RefCell;

use rustfft::FftPlanner;
use rustfft::num_complex::Complex32;

use crate::params::MAX_BANDS;

mod leakage;
pub use leakage::{LEAKAGE_512, LEAKAGE_SEEDS, leakage_matrix, measure_leakage, render_unit_band};

/// How band weights are obtained from band powers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Estimator {
    /// Lagae eq. 9: `w_b = sqrt(P_b / σ²_N)` (with our measured `σ²_N = 1`).
    Lagae,
    /// Solve `P = L·w²`, `w² ≥ 0`, with our measured leakage matrix `L`.
    Deconvolved,
    /// Fit the radial spectrum on quarter-octave rings in the log domain
    /// ([`crate::ring_fit`]), starting from the deconvolved solve.
    #[default]
    Rings,
}

impl Estimator {
    /// Name used in JSON and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Estimator::Lagae => "lagae",
            Estimator::Deconvolved => "deconvolved",
            Estimator::Rings => "rings",
        }
    }
}

/// Number of noise bands an analysed image of `w × h` supports: `log2(min side) − 1`, as in the
/// paper (8 for 512²), within `1..=MAX_BANDS`.
pub fn num_bands(w: usize, h: usize) -> usize {
    let m = w.min(h).max(1);
    let log2 = usize::BITS - 1 - m.leading_zeros();
    (log2 as usize).saturating_sub(1).clamp(1, MAX_BANDS)
}

/// Band of each frequency index of an axis of length `n` (`usize::MAX` for DC).
fn axis_bands(n: usize, nb: usize) -> Vec<usize> {
    (0..n)
        .map(|k| {
            let kk = k.min(n - k);
            if kk == 0 {
                return usize::MAX;
            }
            // Frequency kk/n is in band j when kk/n ≤ 2^−(j+1) and > 2^−(j+2).
            let mut j = 0;
            while j + 1 < nb && kk * (4usize << j) <= n {
                j += 1;
            }
            j
        })
        .collect()
}

thread_local! {
    static PLANNER: RefCell<FftPlanner<f32>> = RefCell::new(FftPlanner::new());
}

fn fft_rows(data: &mut [Complex32], len: usize) {
    let fft = PLANNER.with(|p| p.borrow_mut().plan_fft_forward(len));
    let mut scratch = vec![Complex32::default(); fft.get_inplace_scratch_len()];
    fft.process_with_scratch(data, &mut scratch);
}

fn transpose(src: &[Complex32], w: usize, h: usize) -> Vec<Complex32> {
    let mut out = vec![Complex32::default(); w * h];
    const B: usize = 32;
    for y0 in (0..h).step_by(B) {
        for x0 in (0..w).step_by(B) {
            for y in y0..(y0 + B).min(h) {
                for x in x0..(x0 + B).min(w) {
                    out[x * h + y] = src[y * w + x];
                }
            }
        }
    }
    out
}

/// 2D FFT of a `w × h` complex image (row-major). The result is *transposed*: index `q·h + r`
/// holds horizontal frequency `q` and vertical frequency `r`.
pub fn fft2(mut data: Vec<Complex32>, w: usize, h: usize) -> Vec<Complex32> {
    fft_rows(&mut data, w);
    let mut t = transpose(&data, w, h);
    fft_rows(&mut t, h);
    t
}

/// Inverse of [`fft2`]: from the transposed layout back to a row-major `w × h` image, scaled by
/// `1/(w·h)`.
pub fn ifft2(mut spec: Vec<Complex32>, w: usize, h: usize) -> Vec<Complex32> {
    let inverse = |data: &mut [Complex32], len: usize| {
        let fft = PLANNER.with(|p| p.borrow_mut().plan_fft_inverse(len));
        let mut scratch = vec![Complex32::default(); fft.get_inplace_scratch_len()];
        fft.process_with_scratch(data, &mut scratch);
    };
    inverse(&mut spec, h);
    let mut t = transpose(&spec, h, w);
    inverse(&mut t, w);
    let k = 1.0 / (w * h) as f32;
    t.iter_mut().for_each(|v| *v *= k);
    t
}

/// [`ifft2`] without its `1/(w·h)` scale, for a spectrum whose nonzero entries all lie in the
/// given `columns` (horizontal frequencies `q`, the transposed layout's chunks of length `h`;
/// sorted, distinct): the inverse FFTs of the other columns, all zeros, are skipped, and only
/// the kept columns are transposed. The result is bit for bit `ifft2(spec) · w·h` wherever it
/// is not zero (the skipped transforms would be zeros of either sign, and adding a zero of
/// either sign to a number leaves it unchanged). What the Gabor descriptor's band-pass filters
/// need: the lowest frequencies touch 18 of 128 columns, a filter's orientation half of them.
pub fn ifft2_columns_unscaled(
    mut spec: Vec<Complex32>,
    w: usize,
    h: usize,
    columns: &[usize],
) -> Vec<Complex32> {
    let mut t = vec![Complex32::default(); w * h];
    ifft2_columns_unscaled_into(&mut spec, w, h, columns, &mut t, &mut Vec::new());
    t
}

/// [`ifft2_columns_unscaled`] into caller-owned buffers, for a loop over many spectra of one
/// size (the descriptor's filter bank): `spec` (transposed layout) is transformed in place in
/// its `columns` only, which must hold the only nonzero entries; `out` receives the row-major
/// result and must be all zeros on entry (the caller clears it as it reads the result: one
/// pass over it instead of two).
pub fn ifft2_columns_unscaled_into(
    spec: &mut [Complex32],
    w: usize,
    h: usize,
    columns: &[usize],
    out: &mut [Complex32],
    scratch: &mut Vec<Complex32>,
) {
    let (col_fft, row_fft) = PLANNER.with(|p| {
        let mut p = p.borrow_mut();
        (p.plan_fft_inverse(h), p.plan_fft_inverse(w))
    });
    let need = col_fft
        .get_inplace_scratch_len()
        .max(row_fft.get_inplace_scratch_len());
    if scratch.len() < need {
        scratch.resize(need, Complex32::default());
    }
    for &q in columns {
        let column = &mut spec[q * h..(q + 1) * h];
        col_fft.process_with_scratch(column, &mut scratch[..col_fft.get_inplace_scratch_len()]);
        for (r, v) in column.iter().enumerate() {
            out[r * w + q] = *v;
        }
    }
    row_fft.process_with_scratch(out, &mut scratch[..row_fft.get_inplace_scratch_len()]);
}

/// The plain baseline the speed target is stated against: one 2D FFT of a real image.
pub fn fft2_real(img: &[f32], w: usize, h: usize) -> Vec<Complex32> {
    fft2(img.iter().map(|&v| Complex32::new(v, 0.0)).collect(), w, h)
}

/// Border differences of a spatial image, all Moisan's decomposition needs from it:
/// `a(x) = u(x, h−1) − u(x, 0)` and `b(y) = u(w−1, y) − u(0, y)`.
fn border_differences(u: &[Complex32], w: usize, h: usize) -> (Vec<Complex32>, Vec<Complex32>) {
    let a = (0..w).map(|x| u[(h - 1) * w + x] - u[x]).collect();
    let b = (0..h).map(|y| u[y * w + w - 1] - u[y * w]).collect();
    (a, b)
}

/// The spectrum of the smooth component (Moisan's periodic + smooth decomposition), from the
/// border differences of the image: `ŝ(q, r) = v̂(q, r) / λ(q, r)` with
/// `v̂ = Â(q)·(1 − e^{2πi r/h}) + B̂(r)·(1 − e^{2πi q/w})` and
/// `λ = 2cos(2πq/w) + 2cos(2πr/h) − 4`; `ŝ(0, 0) = 0`.
struct SmoothComponent {
    a: Vec<Complex32>,
    b: Vec<Complex32>,
    eq: Vec<Complex32>,
    cq: Vec<f32>,
    er: Vec<Complex32>,
    cr: Vec<f32>,
}

impl SmoothComponent {
    fn new((mut a, mut b): (Vec<Complex32>, Vec<Complex32>), w: usize, h: usize) -> Self {
        fft_rows(&mut a, w);
        fft_rows(&mut b, h);
        // Per axis: 1 − e^{2πik/n} and 2cos(2πk/n) − 2.
        let factors = |n: usize| -> (Vec<Complex32>, Vec<f32>) {
            (0..n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    (
                        Complex32::new((1.0 - t.cos()) as f32, (-t.sin()) as f32),
                        (2.0 * t.cos() - 2.0) as f32,
                    )
                })
                .unzip()
        };
        let (eq, cq) = factors(w);
        let (er, cr) = factors(h);
        SmoothComponent {
            a,
            b,
            eq,
            cq,
            er,
            cr,
        }
    }

    /// Subtracts `ŝ` from a spectrum in transposed layout. Written as plain `f32` arithmetic
    /// over contiguous rows so that it vectorises; `λ` is 0 only at DC, where `ŝ = 0`.
    fn subtract_from(&self, spec: &mut [Complex32], h: usize) {
        for (q, row) in spec.chunks_exact_mut(h).enumerate() {
            let (aq, eq, cq) = (self.a[q], self.eq[q], self.cq[q]);
            for (((z, er), br), cr) in row.iter_mut().zip(&self.er).zip(&self.b).zip(&self.cr) {
                let lambda = cq + cr;
                let inv = if lambda == 0.0 { 0.0 } else { 1.0 / lambda };
                let re = (aq.re * er.re - aq.im * er.im) + (br.re * eq.re - br.im * eq.im);
                let im = (aq.re * er.im + aq.im * er.re) + (br.re * eq.im + br.im * eq.re);
                z.re -= re * inv;
                z.im -= im * inv;
            }
        }
    }
}

/// Spectrum (transposed layout) of a real image, optionally with the smooth component removed.
pub fn spectrum_real(img: &[f32], w: usize, h: usize, periodic: bool) -> Vec<Complex32> {
    let data: Vec<Complex32> = img.iter().map(|&v| Complex32::new(v, 0.0)).collect();
    spectrum(data, w, h, periodic)
}

fn spectrum(data: Vec<Complex32>, w: usize, h: usize, periodic: bool) -> Vec<Complex32> {
    let smooth = periodic.then(|| border_differences(&data, w, h));
    let mut spec = fft2(data, w, h);
    if let Some(borders) = smooth {
        SmoothComponent::new(borders, w, h).subtract_from(&mut spec, h);
    }
    spec
}

/// Band powers of two real images at once (packed as real and imaginary part of one complex FFT).
/// Powers are variances: `Σ_{bins in band} |F|² / (w·h)²`, so that they sum to the image
/// variance. `second` may be `None`.
pub fn band_powers_pair(
    first: &[f32],
    second: Option<&[f32]>,
    w: usize,
    h: usize,
    nb: usize,
    periodic: bool,
) -> [Vec<f64>; 2] {
    let packed: Vec<Complex32> = match second {
        Some(s) => first
            .iter()
            .zip(s)
            .map(|(&a, &b)| Complex32::new(a, b))
            .collect(),
        None => first.iter().map(|&a| Complex32::new(a, 0.0)).collect(),
    };
    band_powers_packed(packed, w, h, nb, periodic)
}

/// [`band_powers_pair`] on an already packed `w × h` complex image (real part: first image,
/// imaginary part: second).
///
/// The two real spectra are `F₁(k) = (Z(k) + Z̄(−k))/2` and `F₂(k) = (Z(k) − Z̄(−k))/2i`, so each
/// conjugate pair of bins is visited once (and counted twice).
pub fn band_powers_packed(
    packed: Vec<Complex32>,
    w: usize,
    h: usize,
    nb: usize,
    periodic: bool,
) -> [Vec<f64>; 2] {
    band_spectra_packed(packed, w, h, nb, periodic, Extras::default()).map(|b| b.powers)
}

/// Per band, the angular moment of one image's power: `cos` and `sin` are `Σ P·cos 2θ` and
/// `Σ P·sin 2θ` over the band's frequencies (`θ` the frequency's direction in texel
/// coordinates, each conjugate pair once with its multiplicity, as the powers), `square`
/// `Σ P²` likewise: what the orientation fit needs ([`crate::orientation`]). Same units as
/// the powers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BandMoments {
    pub cos: Vec<f64>,
    pub sin: Vec<f64>,
    pub square: Vec<f64>,
}

/// Fine radial bins per octave of the density table and of the photo's ring powers.
pub const FINE_PER_OCTAVE: usize = 8;
/// The fine bin of squared radial frequency `f2 = ρ²` (cycles per pixel, `0 < ρ ≤ 2^−½`):
/// bin `t` holds `ρ ∈ (2^−½−(t+1)/8, 2^−½−t/8]`. In `f32`, as [`band_spectra_packed`] computes `ρ²`,
/// so that every caller bins a frequency alike.
#[inline]
pub fn fine_bin_sq(f2: f32) -> usize {
    // −4·log2(f2) − 4, floored, from the float's exponent and a comparison of its mantissa
    // with 2^¼, 2^½ and 2^¾: exact, and a few times cheaper than `log2` in the spectrum loop.
    const QUARTERS: [f32; 3] = [1.189_207_1, std::f32::consts::SQRT_2, 1.681_792_8];
    debug_assert!(FINE_PER_OCTAVE == 8 && f2 > 0.0 && f2.is_normal());
    let bits = f2.to_bits();
    let exponent = ((bits >> 23) & 0xff) as i32 - 127;
    let mantissa = f32::from_bits((bits & 0x007f_ffff) | 0x3f80_0000);
    let t = if mantissa == 1.0 {
        -4 * exponent - 4
    } else {
        let k = QUARTERS.iter().filter(|&&q| mantissa >= q).count() as i32;
        -4 * exponent - k - 5
    };
    t.max(0) as usize
}

/// A photo channel's power and bin count per fine radial bin (see [`fine_bin_sq`]), from its
/// spectrum: what [`crate::ring_fit::fit_weights`] needs. Power in variance units (`Σ |F|² / (w·h)²`), counts in
/// FFT bins (both of a conjugate pair).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RingPowers {
    pub power: Vec<f64>,
    pub count: Vec<f64>,
}

/// What [`band_spectra_packed`] measures of each of the two images beyond the band powers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Extras {
    /// The bands' angular moments ([`BandMoments`], for the orientation fit).
    pub moments: bool,
    /// The power per fine radial bin ([`RingPowers`], for the ring fit of the weights).
    pub rings: bool,
}

/// What [`band_spectra_packed`] returns for each of the two packed images: band powers, and
/// the [`Extras`] asked for (empty otherwise).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BandSpectra {
    pub powers: Vec<f64>,
    pub moments: BandMoments,
    pub rings: RingPowers,
}

/// [`band_powers_packed`] with both images' [`Extras`] (the spectrum fits of structured models
/// need only the powers).
pub fn band_spectra_packed(
    packed: Vec<Complex32>,
    w: usize,
    h: usize,
    nb: usize,
    periodic: bool,
    extras: Extras,
) -> [BandSpectra; 2] {
    let with_moments = extras.moments;
    let spec = spectrum(packed, w, h, periodic);
    let signed_sq = |k: usize, n: usize| {
        let f = k.min(n - k) as f32 / n as f32;
        f * f
    };
    let fy2: Vec<f32> = (0..h).map(|r| signed_sq(r, h)).collect();
    let fy: Vec<f32> = (0..h)
        .map(|r| if r <= h / 2 { r as f32 } else { r as f32 - h as f32 } / h as f32)
        .collect();
    let mut moments: [BandMoments; 2] = std::array::from_fn(|_| BandMoments {
        cos: vec![0.0; nb],
        sin: vec![0.0; nb],
        square: vec![0.0; nb],
    });
    let bx = axis_bands(w, nb);
    let by = axis_bands(h, nb);
    let mut p = [vec![0.0f64; nb], vec![0.0f64; nb]];
    let mut rings: [RingPowers; 2] = Default::default();
    if extras.rings {
        let fine = fine_bin_sq(1.0 / (w.max(h) as f32).powi(2)) + 1;
        for r in &mut rings {
            r.power = vec![0.0; fine];
            r.count = vec![0.0; fine];
        }
    }
    for q in 0..=w / 2 {
        let qm = if q == 0 { 0 } else { w - q };
        let self_row = qm == q;
        let (row, mirror) = (&spec[q * h..(q + 1) * h], &spec[qm * h..(qm + 1) * h]);
        let bq = bx[q];
        let fx = q as f32 / w as f32;
        let fx2 = signed_sq(q, w);
        // Accumulate a row in f32 per band, then add to the f64 totals.
        let mut acc = [[0.0f32; MAX_BANDS]; 2];
        let mut mom = [[[0.0f32; MAX_BANDS]; 3]; 2];
        for r in 0..h {
            let rm = if r == 0 { 0 } else { h - r };
            // Each unordered pair {(q, r), (−q, −r)} once, with its multiplicity.
            let mult = if !self_row || r < rm {
                2.0
            } else if r == rm {
                1.0
            } else {
                continue;
            };
            let band = bq.min(by[r]);
            if band == usize::MAX {
                continue;
            }
            let z = row[r];
            let zm = mirror[rm].conj();
            let pa = (z + zm).norm_sqr();
            let pb = (z - zm).norm_sqr();
            acc[0][band] += mult * pa;
            acc[1][band] += mult * pb;
            let f2 = fx2 + fy2[r];
            if extras.rings {
                let t = fine_bin_sq(f2);
                for (ring, pw) in rings.iter_mut().zip([pa, pb]) {
                    ring.power[t] += (mult * pw) as f64;
                    ring.count[t] += mult as f64;
                }
            }
            if !with_moments {
                continue;
            }
            // cos 2θ and sin 2θ of frequency (fx, fy), the same for its conjugate.
            let (c2, s2) = ((fx2 - fy2[r]) / f2, 2.0 * fx * fy[r] / f2);
            for (m, pw) in mom.iter_mut().zip([pa, pb]) {
                m[0][band] += mult * pw * c2;
                m[1][band] += mult * pw * s2;
                m[2][band] += mult * pw * pw;
            }
        }
        for c in 0..2 {
            for j in 0..nb {
                p[c][j] += acc[c][j] as f64;
                moments[c].cos[j] += mom[c][0][j] as f64;
                moments[c].sin[j] += mom[c][1][j] as f64;
                moments[c].square[j] += mom[c][2][j] as f64;
            }
        }
    }
    let norm = 4.0 * (w as f64 * h as f64).powi(2);
    for v in p.iter_mut().flatten() {
        *v /= norm;
    }
    for m in &mut moments {
        for j in 0..nb {
            m.cos[j] /= norm;
            m.sin[j] /= norm;
            m.square[j] /= norm * norm;
        }
    }
    for ring in &mut rings {
        ring.power.iter_mut().for_each(|v| *v /= norm);
    }
    let [p0, p1] = p;
    let [m0, m1] = moments;
    let [r0, r1] = rings;
    [
        BandSpectra {
            powers: p0,
            moments: m0,
            rings: r0,
        },
        BandSpectra {
            powers: p1,
            moments: m1,
            rings: r1,
        },
    ]
}

/// Band powers of one real image.
pub fn band_powers(img: &[f32], w: usize, h: usize, nb: usize, periodic: bool) -> Vec<f64> {
    let [p, _] = band_powers_pair(img, None, w, h, nb, periodic);
    p
}

/// Band weights from band powers.
pub fn estimate_weights(powers: &[f64], estimator: Estimator) -> Vec<f32> {
    match estimator {
        Estimator::Lagae => powers.iter().map(|&p| p.max(0.0).sqrt() as f32).collect(),
        // Without the rings' powers the ring fit has only the octaves: the deconvolved solve.
        Estimator::Deconvolved | Estimator::Rings => {
            let l = leakage_matrix(powers.len());
            nonneg_solve(&l, powers)
                .into_iter()
                .map(|v| v.sqrt() as f32)
                .collect()
        }
    }
}

/// Solves `L v = p` with `v ≥ 0` by projected Gauss–Seidel. `L` is column-stochastic-like and
/// diagonally dominant (each band keeps most of its power), so this converges quickly; the
/// iteration count is fixed for determinism.
pub fn nonneg_solve(l: &[Vec<f64>], p: &[f64]) -> Vec<f64> {
    let n = p.len();
    let mut v: Vec<f64> = (0..n).map(|i| (p[i] / l[i][i]).max(0.0)).collect();
    for _ in 0..200 {
        for i in 0..n {
            let mut r = p[i];
            for k in 0..n {
                if k != i {
                    r -= l[i][k] * v[k];
                }
            }
            v[i] = (r / l[i][i]).max(0.0);
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_counts_and_axis_bands() {
        assert_eq!(num_bands(512, 512), 8);
        assert_eq!(num_bands(2048, 1000), 8);
        assert_eq!(num_bands(32, 32), 4);
        assert_eq!(num_bands(1 << 20, 1 << 20), MAX_BANDS);
        let b = axis_bands(512, 8);
        assert_eq!(b[0], usize::MAX);
        assert_eq!(b[256], 0); // Nyquist folds into the finest band
        assert_eq!(b[129], 0);
        assert_eq!(b[128], 1);
        assert_eq!(b[1], 7);
        assert_eq!(b[2], 7);
        assert_eq!(b[3], 6);
        assert_eq!(b[511], 7);
    }

    #[test]
    fn parseval_and_pair_packing() {
        let (w, h) = (48, 30);
        let a: Vec<f32> = (0..w * h).map(|i| ((i * 37 % 101) as f32).sin()).collect();
        let b: Vec<f32> = (0..w * h).map(|i| ((i * 13 % 7) as f32).cos()).collect();
        let var = |v: &[f32]| {
            let m = v.iter().map(|&x| x as f64).sum::<f64>() / v.len() as f64;
            v.iter().map(|&x| (x as f64 - m).powi(2)).sum::<f64>() / v.len() as f64
        };
        let nb = num_bands(w, h);
        let [pa, pb] = band_powers_pair(&a, Some(&b), w, h, nb, false);
        assert!((pa.iter().sum::<f64>() - var(&a)).abs() < 1e-5);
        assert!((pb.iter().sum::<f64>() - var(&b)).abs() < 1e-5);
        let pa1 = band_powers(&a, w, h, nb, false);
        for j in 0..nb {
            assert!((pa[j] - pa1[j]).abs() < 1e-6);
        }
    }

    #[test]
    fn inverse_fft_round_trips() {
        let (w, h) = (40, 24);
        let img: Vec<Complex32> = (0..w * h)
            .map(|i| Complex32::new((i as f32 * 0.37).sin(), (i as f32 * 0.11).cos()))
            .collect();
        let back = ifft2(fft2(img.clone(), w, h), w, h);
        for (a, b) in img.iter().zip(&back) {
            assert!((a - b).norm() < 1e-4);
        }
    }

    #[test]
    fn the_column_inverse_equals_the_full_one_bit_for_bit() {
        // A spectrum nonzero in columns 1, 2 and 6 only (w = 8 columns of h = 16).
        let (w, h) = (8, 16);
        let columns = [1, 2, 6];
        let spec: Vec<Complex32> = (0..w * h)
            .map(|i| {
                if columns.contains(&(i / h)) {
                    Complex32::new((i as f32 * 0.37).sin(), (i as f32 * 0.11).cos())
                } else {
                    Complex32::default()
                }
            })
            .collect();
        let full = ifft2(spec.clone(), w, h);
        let sparse = ifft2_columns_unscaled(spec, w, h, &columns);
        let k = 1.0 / (w * h) as f32;
        for (a, b) in full.iter().zip(&sparse) {
            assert!(a.re == b.re * k && a.im == b.im * k, "{a} vs {b}·k");
        }
    }

    #[test]
    fn smooth_component_removal_kills_the_border_cross() {
        // A linear ramp is smooth but not periodic: its FFT has energy in every band along the
        // axes. Its periodic component is (nearly) constant.
        let (w, h) = (64, 64);
        let ramp: Vec<f32> = (0..w * h)
            .map(|i| (i % w) as f32 / w as f32 + (i / w) as f32 / (2 * h) as f32)
            .collect();
        let nb = num_bands(w, h);
        let raw = band_powers(&ramp, w, h, nb, false);
        let per = band_powers(&ramp, w, h, nb, true);
        assert!(raw[0] > 1e-5, "{raw:?}");
        assert!(
            per.iter().sum::<f64>() < 1e-3 * raw.iter().sum::<f64>(),
            "{per:?}"
        );
    }

    #[test]
    fn leakage_table_is_current() {
        let l = measure_leakage(512, &LEAKAGE_SEEDS);
        for j in 0..8 {
            for i in 0..8 {
                assert!(
                    (l[j][i] - LEAKAGE_512[j][i]).abs() < 1e-6,
                    "LEAKAGE_512[{j}][{i}] is stale: run `cargo run --example leakage`"
                );
            }
        }
        assert_eq!(
            leakage_matrix(8),
            LEAKAGE_512.iter().map(|r| r.to_vec()).collect::<Vec<_>>()
        );
    }

    #[test]
    fn leakage_transfers_to_other_sizes() {
        // The matrix built for 256² (7 bands) from the 512² measurement matches a direct
        // measurement at 256² to 0.02 for the fine and interior bands. Towards the coarse end
        // it is an approximation (band 4 at 256² has 16×16 coefficients in view, the two
        // coarsest 8×8 and 4×4, whose split between octaves is uncertain by several percent
        // even over 24 seeds).
        let direct = measure_leakage(256, &LEAKAGE_SEEDS);
        let built = leakage_matrix(7);
        for j in 0..7 {
            for i in 0..7 {
                let tol = [0.02, 0.02, 0.02, 0.02, 0.04, 0.1, 0.1][i];
                assert!(
                    (direct[j][i] - built[j][i]).abs() < tol,
                    "[{j}][{i}] {} vs {}",
                    direct[j][i],
                    built[j][i]
                );
            }
        }
    }

    #[test]
    fn nonneg_solver_inverts_and_clamps() {
        let l = leakage_matrix(6);
        let v = [0.5, 0.0, 0.2, 0.1, 0.0, 0.3];
        let p: Vec<f64> = (0..6)
            .map(|j| (0..6).map(|i| l[j][i] * v[i]).sum())
            .collect();
        let got = nonneg_solve(&l, &p);
        for i in 0..6 {
            assert!((got[i] - v[i]).abs() < 1e-9, "{got:?}");
        }
    }
}
