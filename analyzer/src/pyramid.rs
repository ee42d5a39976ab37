//! The steerable pyramid (Simoncelli & Freeman 1995) built in the Fourier domain, as Heeger &
//! Bergen (1995, §3) use it for texture synthesis: a high-pass residual, `S` scales of `K`
//! oriented band-pass subbands, and a low-pass residual. Circular boundaries (everything is a
//! product of spectra), so a synthesis from it tiles.
//!
//! **Masks** (ω in radians per sample of the level's own grid, `r = |ω|`, `θ = arg ω`):
//! - radial: `L(r) = cos(π/2 · log₂(4r/π))` on `π/4 < r < π/2` (1 below, 0 above) and
//!   `H(r) = cos(π/2 · log₂(2r/π))` on the same interval (0 below, 1 above), so that
//!   `H² + L² = 1` everywhere;
//! - first stage: `H₀(r) = H(r/2)`, `L₀(r) = L(r/2)` (transition on `π/2 … π`);
//! - angular: `G_k(θ) = α_K |cos(θ − πk/K)|^(K−1)` with
//!   `α_K = 2^(K−1) (K−1)! / √(K (2(K−1))!)`, so that `Σ_k G_k² = 1`;
//! - level `s` (the image low-passed by `L₀` and then `s` times by `L` and halved): the bands
//!   `H·G_k`, and `L` before the next halving.
//!
//! Analysis multiplies by the masks, synthesis multiplies each subband's spectrum by its mask
//! again and sums: with `H₀² + L₀² = 1` and `L² + H² Σ G_k² = 1` that is the identity, to float
//! precision (the tests check ≤ 10⁻⁵ relative).
//!
//! **Phase convention.** The masks are real and even (`|cos|`, not `cos`), the zero-phase
//! convention of the IPOL implementation (Briand, Vacher, Galerne & Rabin 2014), not the odd
//! filters times `(−i)^(K−1)` of matlabPyrTools. Why: with real even masks every subband of a
//! real image is real, so its histogram (what Heeger–Bergen match) is the histogram of a real
//! image, and two subbands share one complex FFT (one as its real part, one as its imaginary
//! part; [`fft2`] of `a + ib` holds both spectra), which halves the transforms. The odd filters
//! give the same energies per band; their subbands would need the same real-part treatment.
//!
//! **Halving.** A level is low-passed by `L`, which is 0 at and beyond `π/2`, so its spectrum
//! fits in the central half of the frequencies and the next level is that half: the spectrum
//! cropped to `⌈w/2⌉ × ⌈h/2⌉` (exact, no aliasing). Odd sides work the same way: the crop is
//! `⌈w/2⌉` frequencies, so a level of an odd side is a little more than half (65 → 33) and its
//! masks, defined on its own grid, sit a hair (≤ 1.5 %) below the dyadic frequencies; the
//! reconstruction stays exact. Each crop is scaled by the ratio of the pixel counts, so that a
//! subband's values are the band-passed image's values at the level's sample positions, the
//! same whatever the image's size: what lets a synthesis of another size match the sample's
//! subband histograms.

use rustfft::num_complex::Complex32;

use crate::spectrum::{fft2, ifft2};

/// Smallest side of the low-pass residual: below it a pyramid has fewer scales.
pub const MIN_LOWPASS_SIDE: usize = 8;

/// Most orientations a pyramid may have.
pub const MAX_ORIENTATIONS: usize = 16;

/// The scales a `w × h` image supports: halvings while the low-pass residual keeps at least
/// [`MIN_LOWPASS_SIDE`] on its shorter side.
pub fn max_scales(w: usize, h: usize) -> usize {
    let mut side = w.min(h);
    let mut scales = 0;
    while side.div_ceil(2) >= MIN_LOWPASS_SIDE {
        side = side.div_ceil(2);
        scales += 1;
    }
    scales
}

/// The subbands of one image.
#[derive(Clone, Debug, PartialEq)]
pub struct Pyramid {
    /// The high-pass residual, the image's size.
    pub highpass: Vec<f32>,
    /// `bands[s][k]`: scale `s` (0 finest), orientation `k` (angle `πk/K`), the level's size.
    pub bands: Vec<Vec<Vec<f32>>>,
    /// The low-pass residual, the coarsest level's size.
    pub lowpass: Vec<f32>,
}

impl Pyramid {
    /// Every subband in a fixed order: high-pass, the bands scale by scale, low-pass.
    pub fn subbands(&self) -> impl Iterator<Item = &Vec<f32>> {
        std::iter::once(&self.highpass)
            .chain(self.bands.iter().flatten())
            .chain(std::iter::once(&self.lowpass))
    }

    /// [`Pyramid::subbands`], mutable.
    pub fn subbands_mut(&mut self) -> impl Iterator<Item = &mut Vec<f32>> {
        std::iter::once(&mut self.highpass)
            .chain(self.bands.iter_mut().flatten())
            .chain(std::iter::once(&mut self.lowpass))
    }
}

/// One level's grid and masks (transposed spectrum layout of [`fft2`]: index `q·h + r`).
#[derive(Clone, Debug)]
struct Level {
    w: usize,
    h: usize,
    /// `H·G_k` per orientation.
    bands: Vec<Vec<f32>>,
    /// `L`.
    low: Vec<f32>,
}

/// The masks of a pyramid of one size, computed once and used for any number of images.
#[derive(Clone, Debug)]
pub struct Plan {
    width: usize,
    height: usize,
    high0: Vec<f32>,
    low0: Vec<f32>,
    levels: Vec<Level>,
    /// The coarsest grid (the low-pass residual's).
    bottom: (usize, usize),
}

/// Signed frequency index of bin `k` of an axis of length `n`: `0, 1, …, −1`; for even `n` the
/// Nyquist bin `n/2` counts as `−n/2`.
fn signed(k: usize, n: usize) -> i64 {
    if k < n.div_ceil(2) {
        k as i64
    } else {
        k as i64 - n as i64
    }
}

/// Radial low-pass `L(r)`.
pub fn radial_low(r: f64) -> f64 {
    use std::f64::consts::PI;
    let t = (4.0 * r / PI).log2();
    if t <= 0.0 {
        1.0
    } else if t >= 1.0 - 1e-12 {
        0.0
    } else {
        (PI / 2.0 * t).cos()
    }
}

/// Radial high-pass `H(r)`, `H² + L² = 1`.
pub fn radial_high(r: f64) -> f64 {
    use std::f64::consts::PI;
    let t = (4.0 * r / PI).log2();
    if t <= 0.0 {
        0.0
    } else if t >= 1.0 - 1e-12 {
        1.0
    } else {
        (PI / 2.0 * t).sin()
    }
}

/// `α_K` of the angular masks.
fn alpha(k: usize) -> f64 {
    let n = k - 1;
    let factorial = |m: usize| (1..=m).map(|i| i as f64).product::<f64>();
    2f64.powi(n as i32) * factorial(n) / (k as f64 * factorial(2 * n)).sqrt()
}

/// `f(r, θ)` on every bin of a `w × h` grid, in the transposed layout.
fn mask(w: usize, h: usize, f: impl Fn(f64, f64) -> f64) -> Vec<f32> {
    let mut out = Vec::with_capacity(w * h);
    for q in 0..w {
        let wx = std::f64::consts::TAU * signed(q, w) as f64 / w as f64;
        for r in 0..h {
            let wy = std::f64::consts::TAU * signed(r, h) as f64 / h as f64;
            out.push(f(wx.hypot(wy), wy.atan2(wx)) as f32);
        }
    }
    out
}

/// The bins of a `w × h` spectrum (transposed layout) that a `w2 × h2` crop keeps, as
/// (index in the crop, index in the full grid).
fn crop_pairs(w: usize, h: usize, w2: usize, h2: usize) -> impl Iterator<Item = (usize, usize)> {
    (0..w2).flat_map(move |q2| {
        let q = signed(q2, w2).rem_euclid(w as i64) as usize;
        (0..h2).map(move |r2| {
            let r = signed(r2, h2).rem_euclid(h as i64) as usize;
            (q2 * h2 + r2, q * h + r)
        })
    })
}

/// Inverse FFTs of two Hermitian spectra at once: the real images are the real and imaginary
/// parts of the inverse of `a + ib`.
fn ifft2_pair(
    a: &[Complex32],
    b: Option<&[Complex32]>,
    w: usize,
    h: usize,
) -> (Vec<f32>, Vec<f32>) {
    let packed: Vec<Complex32> = match b {
        Some(b) => a
            .iter()
            .zip(b)
            .map(|(x, y)| Complex32::new(x.re - y.im, x.im + y.re))
            .collect(),
        None => a.to_vec(),
    };
    let z = ifft2(packed, w, h);
    (
        z.iter().map(|v| v.re).collect(),
        if b.is_some() {
            z.iter().map(|v| v.im).collect()
        } else {
            Vec::new()
        },
    )
}

/// Adds `ma · FFT(a) + mb · FFT(b)` to `acc` for two real images with one complex FFT: with
/// `Z = FFT(a + ib)` and `Z*₋ = conj(Z(−ω))`, `FFT(a) = (Z + Z*₋)/2`, `FFT(b) = (Z − Z*₋)/2i`.
fn add_filtered_pair(
    acc: &mut [Complex32],
    (a, ma): (&[f32], &[f32]),
    b: Option<(&[f32], &[f32])>,
    w: usize,
    h: usize,
) {
    let packed: Vec<Complex32> = match b {
        Some((b, _)) => a
            .iter()
            .zip(b)
            .map(|(&x, &y)| Complex32::new(x, y))
            .collect(),
        None => a.iter().map(|&x| Complex32::new(x, 0.0)).collect(),
    };
    let z = fft2(packed, w, h);
    let Some((_, mb)) = b else {
        for ((acc, z), m) in acc.iter_mut().zip(&z).zip(ma) {
            *acc += z * m;
        }
        return;
    };
    for q in 0..w {
        let qm = (w - q) % w;
        for r in 0..h {
            let rm = (h - r) % h;
            let (i, j) = (q * h + r, qm * h + rm);
            let (zi, zj) = (z[i], z[j].conj());
            let fa = (zi + zj) * 0.5;
            let d = (zi - zj) * 0.5;
            let fb = Complex32::new(d.im, -d.re);
            acc[i] += fa * ma[i] + fb * mb[i];
        }
    }
}

impl Plan {
    /// The masks of a `w × h` pyramid with `scales` scales (at most [`max_scales`]) and
    /// `orientations` orientations (1 to [`MAX_ORIENTATIONS`]).
    pub fn new(w: usize, h: usize, scales: usize, orientations: usize) -> Plan {
        assert!(scales <= max_scales(w, h), "{scales} scales for {w}×{h}");
        assert!((1..=MAX_ORIENTATIONS).contains(&orientations));
        let a = alpha(orientations);
        let kk = orientations as f64;
        let (mut lw, mut lh) = (w, h);
        let mut levels = Vec::with_capacity(scales);
        for _ in 0..scales {
            let bands = (0..orientations)
                .map(|k| {
                    let phi = std::f64::consts::PI * k as f64 / kk;
                    mask(lw, lh, |r, t| {
                        radial_high(r) * a * (t - phi).cos().abs().powi(orientations as i32 - 1)
                    })
                })
                .collect();
            levels.push(Level {
                w: lw,
                h: lh,
                bands,
                low: mask(lw, lh, |r, _| radial_low(r)),
            });
            (lw, lh) = (lw.div_ceil(2), lh.div_ceil(2));
        }
        Plan {
            width: w,
            height: h,
            high0: mask(w, h, |r, _| radial_high(r / 2.0)),
            low0: mask(w, h, |r, _| radial_low(r / 2.0)),
            levels,
            bottom: (lw, lh),
        }
    }

    /// The image size.
    pub fn size(&self) -> (usize, usize) {
        (self.width, self.height)
    }

    /// Number of scales.
    pub fn scales(&self) -> usize {
        self.levels.len()
    }

    /// Number of orientations.
    pub fn orientations(&self) -> usize {
        self.levels.first().map_or(0, |l| l.bands.len())
    }

    /// The size of scale `s`'s subbands (`s == scales()` is the low-pass residual's).
    pub fn level_size(&self, s: usize) -> (usize, usize) {
        self.levels.get(s).map_or(self.bottom, |l| (l.w, l.h))
    }

    /// The sizes of the 2D FFTs that one [`Plan::analyse`] runs, in order (two real subbands
    /// share one transform): with [`Plan::synthesis_transforms`], the cost floor a benchmark
    /// states the synthesis' time against.
    pub fn analysis_transforms(&self) -> Vec<(usize, usize)> {
        let full = (self.width, self.height);
        let mut out = vec![full, full];
        for level in &self.levels {
            out.extend(std::iter::repeat_n(
                (level.w, level.h),
                level.bands.len().div_ceil(2),
            ));
        }
        out.push(self.bottom);
        out
    }

    /// The sizes of the 2D FFTs that one [`Plan::synthesise`] runs, in order.
    pub fn synthesis_transforms(&self) -> Vec<(usize, usize)> {
        let full = (self.width, self.height);
        let mut out = vec![self.bottom];
        for level in self.levels.iter().rev() {
            out.extend(std::iter::repeat_n(
                (level.w, level.h),
                level.bands.len().div_ceil(2),
            ));
        }
        out.extend([full, full]);
        out
    }

    /// The subbands of a `w × h` image.
    pub fn analyse(&self, image: &[f32]) -> Pyramid {
        let (w, h) = (self.width, self.height);
        assert_eq!(image.len(), w * h);
        let x = fft2(
            image.iter().map(|&v| Complex32::new(v, 0.0)).collect(),
            w,
            h,
        );
        let highpass_spec: Vec<Complex32> = x.iter().zip(&self.high0).map(|(v, m)| v * m).collect();
        let (highpass, _) = ifft2_pair(&highpass_spec, None, w, h);
        let mut y: Vec<Complex32> = x.iter().zip(&self.low0).map(|(v, m)| v * m).collect();
        let mut bands = Vec::with_capacity(self.levels.len());
        for (s, level) in self.levels.iter().enumerate() {
            let filtered: Vec<Vec<Complex32>> = level
                .bands
                .iter()
                .map(|m| y.iter().zip(m).map(|(v, m)| v * m).collect())
                .collect();
            let mut out = Vec::with_capacity(filtered.len());
            for pair in filtered.chunks(2) {
                let (a, b) = ifft2_pair(&pair[0], pair.get(1).map(|v| &v[..]), level.w, level.h);
                out.push(a);
                if pair.len() == 2 {
                    out.push(b);
                }
            }
            bands.push(out);
            let (w2, h2) = self.level_size(s + 1);
            let scale = (w2 * h2) as f32 / (level.w * level.h) as f32;
            let mut next = vec![Complex32::default(); w2 * h2];
            for (i2, i) in crop_pairs(level.w, level.h, w2, h2) {
                next[i2] = y[i] * (level.low[i] * scale);
            }
            y = next;
        }
        let (bw, bh) = self.bottom;
        let (lowpass, _) = ifft2_pair(&y, None, bw, bh);
        Pyramid {
            highpass,
            bands,
            lowpass,
        }
    }

    /// The image whose subbands are `p` (the inverse of [`Plan::analyse`] when `p` came from
    /// it; for any other subbands, the image whose analysis is nearest to them).
    pub fn synthesise(&self, p: &Pyramid) -> Vec<f32> {
        let (bw, bh) = self.bottom;
        let mut y = fft2(
            p.lowpass.iter().map(|&v| Complex32::new(v, 0.0)).collect(),
            bw,
            bh,
        );
        for (s, level) in self.levels.iter().enumerate().rev() {
            let (w2, h2) = self.level_size(s + 1);
            let scale = (level.w * level.h) as f32 / (w2 * h2) as f32;
            let mut up = vec![Complex32::default(); level.w * level.h];
            for (i2, i) in crop_pairs(level.w, level.h, w2, h2) {
                up[i] = y[i2] * (level.low[i] * scale);
            }
            let bands = &p.bands[s];
            for (pair, masks) in bands.chunks(2).zip(level.bands.chunks(2)) {
                let second = (pair.len() == 2).then(|| (&pair[1][..], &masks[1][..]));
                add_filtered_pair(&mut up, (&pair[0], &masks[0]), second, level.w, level.h);
            }
            y = up;
        }
        let (w, h) = (self.width, self.height);
        for (v, m) in y.iter_mut().zip(&self.low0) {
            *v *= m;
        }
        add_filtered_pair(&mut y, (&p.highpass, &self.high0), None, w, h);
        ifft2_pair(&y, None, w, h).0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng;

    fn noise(w: usize, h: usize, seed: u32) -> Vec<f32> {
        (0..w * h)
            .map(|i| rng::gaussian(seed, 11, i as u32) as f32 + 0.3 * ((i % w) as f32 * 0.2).sin())
            .collect()
    }

    fn relative_error(a: &[f32], b: &[f32]) -> f64 {
        let num: f64 = a.iter().zip(b).map(|(x, y)| ((x - y) as f64).powi(2)).sum();
        let den: f64 = a.iter().map(|x| (*x as f64).powi(2)).sum();
        (num / den).sqrt()
    }

    /// Analysis then synthesis gives the image back to float precision, for square, oblong,
    /// odd and non-power-of-two sizes and any number of orientations.
    #[test]
    fn reconstruction_is_perfect() {
        for (w, h, k) in [
            (64, 64, 4),
            (128, 96, 4),
            (65, 63, 4),
            (100, 36, 3),
            (48, 48, 1),
            (64, 64, 6),
            (33, 40, 2),
        ] {
            let img = noise(w, h, (w * h + k) as u32);
            for s in 0..=max_scales(w, h) {
                let plan = Plan::new(w, h, s, k);
                let p = plan.analyse(&img);
                let back = plan.synthesise(&p);
                let e = relative_error(&img, &back);
                assert!(e <= 1e-5, "{w}×{h}, {s} scales, {k} orientations: {e:e}");
            }
        }
    }

    /// The masks partition unity: `H₀² + L₀² = 1`, and per level `L² + Σ_k (H G_k)² = 1`
    /// wherever the level's content can be (inside the previous low-pass).
    #[test]
    fn masks_partition_unity() {
        let plan = Plan::new(64, 48, 2, 4);
        for (h, l) in plan.high0.iter().zip(&plan.low0) {
            assert!((h * h + l * l - 1.0).abs() < 1e-6);
        }
        for level in &plan.levels {
            for i in 0..level.w * level.h {
                let sum: f32 =
                    level.low[i].powi(2) + level.bands.iter().map(|m| m[i].powi(2)).sum::<f32>();
                assert!((sum - 1.0).abs() < 1e-5, "{sum}");
            }
        }
        assert!((alpha(4) - (8.0 * 6.0 / (4.0f64 * 720.0).sqrt())).abs() < 1e-12);
    }

    /// Every subband of a real image is real and has the level's size, and a subband's energy
    /// is where its mask is: a pattern of vertical stripes (horizontal frequency) puts its
    /// energy in orientation 0, not in orientation 2 (the perpendicular one).
    #[test]
    fn subbands_are_oriented() {
        let (w, h) = (64usize, 64usize);
        let img: Vec<f32> = (0..w * h)
            .map(|i| (std::f32::consts::TAU * (i % w) as f32 * 12.0 / w as f32).cos())
            .collect();
        let plan = Plan::new(w, h, 3, 4);
        let p = plan.analyse(&img);
        assert_eq!(p.bands.len(), 3);
        assert_eq!(p.bands[1][0].len(), 32 * 32);
        assert_eq!(p.lowpass.len(), 8 * 8);
        let energy = |v: &[f32]| v.iter().map(|x| x * x).sum::<f32>();
        // 12 cycles in 64 px: ω = 2π·12/64 ≈ 1.18 rad, inside level 0's band (π/4 … π/2 ×2).
        let e: Vec<f32> = p.bands.iter().flatten().map(|b| energy(b)).collect();
        let strongest = e.iter().cloned().fold(0.0, f32::max);
        assert!(energy(&p.bands[0][0]) > 0.5 * strongest, "{e:?}");
        assert!(energy(&p.bands[0][2]) < 1e-6 * strongest, "{e:?}");
    }

    /// A subband's values do not depend on the image's size: the same periodic pattern on a
    /// grid twice as large has the same band values (at matching positions).
    #[test]
    fn subband_values_do_not_depend_on_size() {
        let pattern = |w: usize| -> Vec<f32> {
            (0..w * w)
                .map(|i| {
                    let (x, y) = ((i % w) as f32, (i / w) as f32);
                    let t = std::f32::consts::TAU / 32.0;
                    (t * x * 3.0).cos() + 0.5 * (t * (x + 2.0 * y)).sin()
                })
                .collect()
        };
        let (small, large) = (pattern(32), pattern(64));
        let a = Plan::new(32, 32, 2, 4).analyse(&small);
        let b = Plan::new(64, 64, 2, 4).analyse(&large);
        for s in 0..2 {
            for k in 0..4 {
                let (sa, sb) = (&a.bands[s][k], &b.bands[s][k]);
                let wa = 32 >> s;
                let wb = 64 >> s;
                for y in 0..wa {
                    for x in 0..wa {
                        let d = (sa[y * wa + x] - sb[y * wb + x]).abs();
                        assert!(d < 1e-4, "scale {s} orientation {k}: {d}");
                    }
                }
            }
        }
    }
}
