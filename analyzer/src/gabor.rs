//! The texture descriptor of retrieval (two-tone paper §4): a Gabor filter bank applied to a
//! structure map through the FFT.
//!
//! The map is standardised (zero mean, unit variance: the descriptor describes shape, the ramp
//! fit takes care of colour), its spectrum taken once (Moisan's periodic component, so that the
//! photo's borders add no cross), and multiplied by each filter of the bank; one inverse FFT per
//! filter gives the complex response, whose magnitude is the local energy at that orientation
//! and frequency. Entries: the mean and the standard deviation of every response magnitude
//! ([`ORIENTATIONS`] × [`FREQUENCIES`] each), then [`QUANTILES`] quantiles of the standardised
//! map (its shape of distribution: two flat tones, a skew towards thin dark joints, …).
//!
//! Departures from the paper, each for a reason:
//! - Log-Gabor filters (Field 1987) on the polar frequency grid instead of Gabor kernels: no DC
//!   response at any bandwidth, one octave per frequency exactly, and cheap to build in the
//!   frequency domain where they are applied anyway. One-sided (analytic), so the magnitude of
//!   the response is the envelope.
//! - Orientations cover 180° (a real image's spectrum is symmetric), so rotating a texture by
//!   `180°/ORIENTATIONS` shifts the orientation index cyclically ([`Descriptor::rotated`]).
//! - The tone swap (`s → 1 − s`) leaves the magnitudes alone and mirrors the quantiles
//!   ([`Descriptor::swapped`]); the paper's global mean is folded into the quantiles.
//! - The four coarser frequencies' responses are evaluated on every 2nd to 16th pixel
//!   ([`DECIMATION`]: the spectrum folded onto the coarser grid gives the response's exact
//!   values there), their statistics taken over those samples: for speed.
//! - Contrast-sensitivity weights: Mannos & Sakrison's CSF at each filter's frequency, for a
//!   descriptor image seen at 40 pixels per degree (a 128² image about 3° wide).

use rustfft::num_complex::Complex32;

use crate::spectrum::{ifft2_columns_unscaled, ifft2_columns_unscaled_into, spectrum_real};

/// Side of the square image the descriptor is computed on.
pub const SIZE: usize = 128;
/// Orientations of the filter bank over 180°.
pub const ORIENTATIONS: usize = 8;
/// Centre frequencies of the filter bank: `0.35·2^−k` cycles per pixel.
pub const FREQUENCIES: usize = 6;
/// Quantiles of the standardised map: at these probabilities.
pub const QUANTILE_AT: [f32; 5] = [0.05, 0.25, 0.5, 0.75, 0.95];
/// Number of quantile entries.
pub const QUANTILES: usize = QUANTILE_AT.len();
/// Entries of a descriptor.
pub const LEN: usize = 2 * ORIENTATIONS * FREQUENCIES + QUANTILES;

/// The highest centre frequency, cycles per pixel.
const F0: f32 = 0.35;

/// A descriptor: `[mean (o, k)…, std (o, k)…, quantiles…]`, entry `(o, k)` at `o·FREQUENCIES + k`.
#[derive(Clone, Debug, PartialEq)]
pub struct Descriptor(pub Vec<f32>);

impl Descriptor {
    /// The descriptor of the same texture turned by `shift · 180°/ORIENTATIONS`.
    pub fn rotated(&self, shift: usize) -> Descriptor {
        let mut out = self.0.clone();
        let block = ORIENTATIONS * FREQUENCIES;
        for part in 0..2 {
            for o in 0..ORIENTATIONS {
                let to = (o + shift) % ORIENTATIONS;
                for k in 0..FREQUENCIES {
                    out[part * block + to * FREQUENCIES + k] =
                        self.0[part * block + o * FREQUENCIES + k];
                }
            }
        }
        Descriptor(out)
    }

    /// The descriptor of the tone-swapped map `1 − s`: the same magnitudes, the quantiles
    /// mirrored (`q_p(−z) = −q_{1−p}(z)`).
    pub fn swapped(&self) -> Descriptor {
        let mut out = self.0.clone();
        let q0 = 2 * ORIENTATIONS * FREQUENCIES;
        for i in 0..QUANTILES {
            out[q0 + i] = -self.0[q0 + QUANTILES - 1 - i];
        }
        Descriptor(out)
    }
}

/// The contrast-sensitivity weight of frequency index `k` (Mannos & Sakrison 1974, at 40
/// pixels per degree), normalised to a maximum of 1 over the bank.
pub fn csf_weights() -> [f32; FREQUENCIES] {
    let csf = |f: f32| {
        let c = 0.114 * f * 40.0;
        2.6 * (0.0192 + c) * (-c.powf(1.1)).exp()
    };
    let w: Vec<f32> = (0..FREQUENCIES)
        .map(|k| csf(F0 * 0.5f32.powi(k as i32)))
        .collect();
    let max = w.iter().cloned().fold(0.0, f32::max);
    std::array::from_fn(|k| w[k] / max)
}

/// The filter bank's frequency responses on the `SIZE²` grid (transposed layout, as
/// [`spectrum_real`]): `[o·FREQUENCIES + k]`, each sparse as (index, gain) where the gain is
/// above 1e-4.
pub fn bank() -> &'static [Vec<(u32, f32)>] {
    use std::sync::OnceLock;
    static BANK: OnceLock<Vec<Vec<(u32, f32)>>> = OnceLock::new();
    BANK.get_or_init(|| {
        let n = SIZE;
        // One octave per frequency: σ of ln(ρ/f) = 0.55·ln 2 ... a common log-Gabor choice
        // (σ/f ≈ 0.65). Angular σ: half the spacing of the orientations.
        let sigma_r = 0.65f32.ln().abs();
        let sigma_t = std::f32::consts::PI / ORIENTATIONS as f32 * 0.6;
        let mut out = Vec::with_capacity(ORIENTATIONS * FREQUENCIES);
        for o in 0..ORIENTATIONS {
            let theta = o as f32 * std::f32::consts::PI / ORIENTATIONS as f32;
            for k in 0..FREQUENCIES {
                let f = F0 * 0.5f32.powi(k as i32);
                let mut taps = Vec::new();
                for q in 0..n {
                    let fx = if q <= n / 2 {
                        q as f32
                    } else {
                        q as f32 - n as f32
                    } / n as f32;
                    for r in 0..n {
                        let fy = if r <= n / 2 {
                            r as f32
                        } else {
                            r as f32 - n as f32
                        } / n as f32;
                        let rho = (fx * fx + fy * fy).sqrt();
                        if rho == 0.0 {
                            continue;
                        }
                        let radial = (-(rho / f).ln().powi(2) / (2.0 * sigma_r * sigma_r)).exp();
                        let mut d = fy.atan2(fx) - theta;
                        d = (d + std::f32::consts::PI).rem_euclid(2.0 * std::f32::consts::PI)
                            - std::f32::consts::PI;
                        let angular = (-(d * d) / (2.0 * sigma_t * sigma_t)).exp();
                        let g = radial * angular;
                        if g > 1e-4 {
                            taps.push(((q * n + r) as u32, g));
                        }
                    }
                }
                out.push(taps);
            }
        }
        out
    })
}

/// The sampling step of the responses of frequency index `k`: [`describe`] evaluates each
/// response on every `DECIMATION[k]`-th pixel along both axes (its spectrum folded onto the
/// coarser grid, [`Plan`]), and takes the magnitude's mean and deviation over those samples.
///
/// Ours, for speed: the samples are exactly the full response's values at those pixels
/// (folding is exact for any spectrum); only the statistics are taken over fewer, strongly
/// correlated samples. A response's magnitude varies on the scale of its filter's wavelength
/// `1/f_k` (one octave of bandwidth), and the step keeps `D·f_k` at 0.175 for `k ≥ 2` (about six
/// samples per wavelength; the two finest frequencies keep every pixel). The inverse FFTs of the
/// four coarse frequencies, two thirds of the bank, shrink to 64², 32², 16² and 8².
pub const DECIMATION: [usize; FREQUENCIES] = [1, 1, 2, 4, 8, 16];

/// One filter of the bank as [`describe`] applies it: its taps with their index on the
/// folded grid, the folded grid's side, and the folded columns that hold taps (the only ones
/// whose inverse FFTs are computed).
struct Plan {
    /// (index on the `SIZE²` spectrum, index on the folded `side²` grid, gain).
    taps: Vec<(u32, u32, f32)>,
    side: usize,
    columns: Vec<usize>,
}

/// [`bank`]'s filters as [`describe`] applies them ([`DECIMATION`]).
fn plans() -> &'static [Plan] {
    use std::sync::OnceLock;
    static PLANS: OnceLock<Vec<Plan>> = OnceLock::new();
    PLANS.get_or_init(|| {
        bank()
            .iter()
            .enumerate()
            .map(|(i, taps)| {
                let side = SIZE / DECIMATION[i % FREQUENCIES];
                let taps: Vec<(u32, u32, f32)> = taps
                    .iter()
                    .map(|&(idx, g)| {
                        let (q, r) = (idx as usize / SIZE, idx as usize % SIZE);
                        (idx, ((q % side) * side + r % side) as u32, g)
                    })
                    .collect();
                let mut columns: Vec<usize> =
                    taps.iter().map(|&(_, f, _)| f as usize / side).collect();
                columns.sort_unstable();
                columns.dedup();
                Plan {
                    taps,
                    side,
                    columns,
                }
            })
            .collect()
    })
}

/// The `SIZE × SIZE` centre square of a `w × h` map, area-averaged to `SIZE²` (or the map
/// itself when it is that size). Maps smaller than `SIZE` are repeated (mirror-free tiling) to
/// fill it.
pub fn descriptor_image(map: &[f32], w: usize, h: usize) -> Vec<f32> {
    let side = w.min(h);
    let (x0, y0) = ((w - side) / 2, (h - side) / 2);
    let mut out = vec![0.0f32; SIZE * SIZE];
    if side >= SIZE {
        // Box average over the square's cells (fractional edges by coverage).
        let step = side as f64 / SIZE as f64;
        for oy in 0..SIZE {
            let (ya, yb) = (oy as f64 * step, (oy + 1) as f64 * step);
            for ox in 0..SIZE {
                let (xa, xb) = (ox as f64 * step, (ox + 1) as f64 * step);
                let (mut sum, mut area) = (0.0f64, 0.0f64);
                for y in ya.floor() as usize..(yb.ceil() as usize).min(side) {
                    let cy = (yb.min(y as f64 + 1.0) - ya.max(y as f64)).max(0.0);
                    for x in xa.floor() as usize..(xb.ceil() as usize).min(side) {
                        let cx = (xb.min(x as f64 + 1.0) - xa.max(x as f64)).max(0.0);
                        sum += cx * cy * map[(y0 + y) * w + x0 + x] as f64;
                        area += cx * cy;
                    }
                }
                out[oy * SIZE + ox] = (sum / area.max(1e-12)) as f32;
            }
        }
    } else {
        for y in 0..SIZE {
            for x in 0..SIZE {
                out[y * SIZE + x] = map[(y0 + y % side) * w + x0 + x % side];
            }
        }
    }
    out
}

/// The descriptor of a `SIZE × SIZE` structure map.
pub fn describe(map: &[f32]) -> Descriptor {
    assert_eq!(map.len(), SIZE * SIZE, "descriptor maps are SIZE²");
    let n = map.len() as f64;
    let mean = map.iter().map(|&v| v as f64).sum::<f64>() / n;
    let var = map.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / n;
    let inv = if var > 1e-12 { 1.0 / var.sqrt() } else { 0.0 };
    let z: Vec<f32> = map
        .iter()
        .map(|&v| ((v as f64 - mean) * inv) as f32)
        .collect();
    let spec = spectrum_real(&z, SIZE, SIZE, true);
    let block = ORIENTATIONS * FREQUENCIES;
    let mut out = vec![0.0f32; LEN];
    // The inverse FFT's 1/SIZE² is a power of two: applied to the sums instead of to every
    // response, it gives the same bits (scaling by a power of two commutes with rounding).
    let k = 1.0 / n;
    // One filtered spectrum, response and scratch buffer for the whole bank: each filter
    // zeroes and fills only the columns it touches (the only ones transformed) of its
    // (folded) grid.
    let mut filtered = vec![Complex32::default(); SIZE * SIZE];
    let mut resp = vec![Complex32::default(); SIZE * SIZE];
    let mut scratch = Vec::new();
    for (i, plan) in plans().iter().enumerate() {
        let side = plan.side;
        let cells = side * side;
        for &q in &plan.columns {
            filtered[q * side..(q + 1) * side].fill(Complex32::default());
        }
        for &(idx, folded, g) in &plan.taps {
            filtered[folded as usize] += spec[idx as usize] * g;
        }
        ifft2_columns_unscaled_into(
            &mut filtered[..cells],
            side,
            side,
            &plan.columns,
            &mut resp[..cells],
            &mut scratch,
        );
        let (s1, s2) = magnitude_sums_and_clear(&mut resp[..cells]);
        // The unscaled inverse of the folded spectrum is the full one's at the sampled pixels.
        let samples = cells as f64;
        let m = s1 * k / samples;
        out[i] = m as f32;
        out[block + i] = (s2 * (k * k) / samples - m * m).max(0.0).sqrt() as f32;
    }
    let ranks = QUANTILE_AT.map(|p| ((z.len() - 1) as f32 * p).round() as usize);
    let stats = crate::radix::order_statistics(&z, &ranks);
    out[2 * block..2 * block + QUANTILES].copy_from_slice(&stats);
    Descriptor(out)
}

/// `Σ|v|` and `Σ|v|²` over a response, summed in f64 (`Complex::norm` calls libm's hypotf,
/// which took 9 % of a native suggestion's time). Leaves the response all zeros, as
/// [`ifft2_columns_unscaled_into`] wants its output buffer, in the same pass over it.
fn magnitude_sums_and_clear(resp: &mut [Complex32]) -> (f64, f64) {
    // |v|² and its square root in f32 (four at a time; the f64 square root's latency was half
    // of the descriptor's time), four partial sums each in f64 (independent additions
    // pipeline). The descriptor moves by a few units in the last place of f32: the database
    // file built with it is byte for byte the one built with f64 square roots and one sum.
    const LANES: usize = 4;
    debug_assert_eq!(resp.len() % LANES, 0, "SIZE² is a multiple of the lanes");
    let (mut s1, mut s2) = ([0.0f64; LANES], [0.0f64; LANES]);
    for c in resp.chunks_exact_mut(LANES) {
        let mut q = [0.0f32; LANES];
        for l in 0..LANES {
            q[l] = c[l].re * c[l].re + c[l].im * c[l].im;
            c[l] = Complex32::default();
        }
        for l in 0..LANES {
            s1[l] += q[l].sqrt() as f64;
            s2[l] += q[l] as f64;
        }
    }
    (s1.iter().sum(), s2.iter().sum())
}

/// The descriptor's FFTs alone, on a `SIZE²` map: its spectrum and, per filter of the bank,
/// the inverse FFT of the columns it touches on its folded grid (as [`describe`] does),
/// nothing else. The cost floor that the benchmarks (native and WASM) print [`describe`] and
/// retrieval against; returns a checksum so none of it is optimised away.
pub fn fft_floor(map: &[f32]) -> f32 {
    assert_eq!(map.len(), SIZE * SIZE, "descriptor maps are SIZE²");
    let spec = spectrum_real(map, SIZE, SIZE, true);
    let mut sum = 0.0f32;
    for plan in plans() {
        let mut folded = vec![Complex32::default(); plan.side * plan.side];
        for &(idx, f, _) in &plan.taps {
            folded[f as usize] += spec[idx as usize];
        }
        sum += ifft2_columns_unscaled(folded, plan.side, plan.side, &plan.columns)[1].re;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stripes(angle_deg: f32, period: f32) -> Vec<f32> {
        let (c, s) = (angle_deg.to_radians().cos(), angle_deg.to_radians().sin());
        (0..SIZE * SIZE)
            .map(|i| {
                let (x, y) = ((i % SIZE) as f32, (i / SIZE) as f32);
                (0.5 + 0.5 * ((c * x + s * y) / period * std::f32::consts::TAU).sin()).round()
            })
            .collect()
    }

    #[test]
    fn rotation_shifts_the_orientation_entries() {
        let step = 180.0 / ORIENTATIONS as f32;
        let a = describe(&stripes(0.0, 8.0));
        let b = describe(&stripes(2.0 * step, 8.0));
        let dist = |x: &Descriptor, y: &Descriptor| {
            x.0.iter()
                .zip(&y.0)
                .map(|(p, q)| (p - q).powi(2))
                .sum::<f32>()
        };
        let best = (0..ORIENTATIONS)
            .min_by(|&i, &j| dist(&a.rotated(i), &b).total_cmp(&dist(&a.rotated(j), &b)))
            .unwrap();
        assert_eq!(best, 2, "stripes turned by two steps match the shift by 2");
    }

    #[test]
    fn a_folded_response_is_the_full_one_at_the_sampled_pixels() {
        let map = stripes(30.0, 23.0);
        let spec = spectrum_real(&map, SIZE, SIZE, true);
        for i in [2, 3 * FREQUENCIES + 4, 7 * FREQUENCIES + 5] {
            let plan = &plans()[i];
            let d = SIZE / plan.side;
            assert_eq!(d, DECIMATION[i % FREQUENCIES]);
            let mut full = vec![Complex32::default(); SIZE * SIZE];
            let mut folded = vec![Complex32::default(); plan.side * plan.side];
            for &(idx, f, g) in &plan.taps {
                full[idx as usize] = spec[idx as usize] * g;
                folded[f as usize] += spec[idx as usize] * g;
            }
            let all: Vec<usize> = (0..SIZE).collect();
            let full = ifft2_columns_unscaled(full, SIZE, SIZE, &all);
            let coarse = ifft2_columns_unscaled(folded, plan.side, plan.side, &plan.columns);
            let scale = full.iter().map(|v| v.norm()).fold(0.0f32, f32::max);
            assert!(scale > 1.0, "filter {i} responds to the stripes");
            for y in 0..plan.side {
                for x in 0..plan.side {
                    let (a, b) = (coarse[y * plan.side + x], full[(d * y) * SIZE + d * x]);
                    assert!(
                        (a - b).norm() <= 1e-4 * scale,
                        "filter {i} at ({x}, {y}): {a} vs {b}"
                    );
                }
            }
        }
    }

    #[test]
    fn swap_mirrors_the_quantiles() {
        let map: Vec<f32> = (0..SIZE * SIZE)
            .map(|i| ((i * 7919) % 101) as f32 / 100.0)
            .collect();
        let inv: Vec<f32> = map.iter().map(|v| 1.0 - v).collect();
        let (a, b) = (describe(&map), describe(&inv));
        let s = a.swapped();
        for i in 0..LEN {
            assert!(
                (s.0[i] - b.0[i]).abs() < 1e-3,
                "entry {i}: {} vs {}",
                s.0[i],
                b.0[i]
            );
        }
    }
}
