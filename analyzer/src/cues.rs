//! Structure cues of a photo patch: a few numbers, each with a plain meaning, that tell a
//! lattice (brick, grid) from lines (planks, strata, grain), sparse edges (cracks, joints) from
//! Gaussian-like noise. They are measured on the photo itself, so they carry none of the gap
//! between the retrieval database's clean renders and real photos.
//!
//! All cues are measured on the luminance of the patch's centre square, area-averaged to
//! [`SIZE`]² ([`descriptor_image`]), after removing its slow shading (a Gaussian of σ =
//! [`SHADING_SIGMA`] px subtracted) and scaling to unit deviation. The shading removal is what
//! lets a lit wall show its lattice: without it the autocorrelation's central lobe floods the
//! whole map on shaded photos.

use crate::gabor::{SIZE, descriptor_image};
use crate::input::Photo;
use crate::spectrum::{ifft2, spectrum_real};
use crate::straight_lines::straight_lines;
use rustfft::num_complex::Complex32;

/// σ in pixels (of the [`SIZE`]² map) of the Gaussian whose blur is taken as shading.
pub const SHADING_SIGMA: f32 = 12.0;

/// The cues' names, in the order of [`cues`]'s values.
pub const CUE_NAMES: [&str; CUES] = [
    "lattice",
    "lattice2",
    "lobe_elongation",
    "coherence",
    "axis_alignment",
    "kurtosis",
    "kurtosis_fine",
    "skewness",
    "bimodality",
    "edge_sparsity",
    "straight_lines",
    "crossing_lines",
];

/// The index of `skewness` in [`CUE_NAMES`].
pub const SKEWNESS: usize = 7;

/// How many cues [`cues`] returns.
pub const CUES: usize = 12;

/// The cues of `photo` (see the module docs), in the order of [`CUE_NAMES`]:
/// - `lattice`: the highest local maximum of the detrended map's autocorrelation outside its
///   central lobe (1: a perfect repeat; near 0: no repeat);
/// - `lattice2`: the highest such maximum whose offset is at least 30° from the first's, above
///   the mean of its line across the first offset (a second period vector: a 2D lattice such
///   as brick or grid, not stripes);
/// - `lobe_elongation`: 1 − the ratio of the central lobe's second moments (0: round; near 1:
///   a line-like lobe, as stripes and grain make);
/// - `coherence`: how much the gradients share one orientation (0: isotropic, 1: all one);
/// - `axis_alignment`: the gradient energy's 4-fold harmonic, positive where edges follow
///   the image axes (walls and floors are photographed square);
/// - `kurtosis`, `kurtosis_fine`: excess kurtosis of the detrended map and of its finest
///   detail (Gaussian noise: 0; sparse joints and cracks: large);
/// - `skewness`: of the detrended map (thin dark joints: negative);
/// - `bimodality`: Otsu's between-class share of the variance (two tones: near 1);
/// - `edge_sparsity`: the share of gradient energy in the strongest tenth of the pixels;
/// - `straight_lines`, `crossing_lines`: the strongest long straight line, in robust deviations
///   of all lines, and the strongest line across it as a share of it
///   ([`crate::straight_lines::straight_lines`]: joints, boards and panel edges).
pub fn cues(photo: &Photo) -> [f32; CUES] {
    let map = luminance_map(photo);
    let detrended = detrended(&map);
    let fine = standardised(
        &detrended
            .iter()
            .zip(&blur(&detrended, SIZE, 1.5))
            .map(|(a, b)| a - b)
            .collect::<Vec<_>>(),
    );
    let acf = autocorrelation(&detrended);
    let (lobe, elongation) = central_lobe(&acf);
    let peaks = lattice_peaks(&acf, &lobe);
    let (coherence, axis_alignment, edge_sparsity) = gradient_cues(&blur(&detrended, SIZE, 0.7));
    let (lines, crossing) = straight_lines(&detrended);
    [
        peaks.0,
        peaks.1,
        elongation,
        coherence,
        axis_alignment,
        moment(&detrended, 4) - 3.0,
        moment(&fine, 4) - 3.0,
        moment(&detrended, 3),
        bimodality(&map),
        edge_sparsity,
        lines,
        crossing,
    ]
}

/// The luminance of `photo`'s centre square at [`SIZE`]² (see the module docs).
fn luminance_map(photo: &Photo) -> Vec<f32> {
    let lum: Vec<f32> = photo
        .pixels
        .iter()
        .map(|c| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2])
        .collect();
    descriptor_image(&lum, photo.width as usize, photo.height as usize)
}

/// A [`SIZE`]² map without its shading, standardised.
fn detrended(map: &[f32]) -> Vec<f32> {
    let shading = blur(map, SIZE, SHADING_SIGMA);
    standardised(
        &map.iter()
            .zip(&shading)
            .map(|(a, b)| a - b)
            .collect::<Vec<_>>(),
    )
}

/// The first period vector of `photo`'s lattice, in pixels of the photo's centre square, and its
/// autocorrelation there (the `lattice` cue): the shortest offset among the detrended map's
/// autocorrelation maxima within 10 % of the highest outside the central lobe; `None` where
/// there is no such maximum.
pub fn lattice_period(photo: &Photo) -> Option<((f32, f32), f32)> {
    let acf = autocorrelation(&detrended(&luminance_map(photo)));
    let (lobe, _) = central_lobe(&acf);
    let (height, (x, y)) = first_period(&acf, &lobe)?;
    // The map is the centre square (the shorter side) resampled to SIZE².
    let per_px = photo.width.min(photo.height) as f32 / SIZE as f32;
    Some(((x as f32 * per_px, y as f32 * per_px), height))
}

/// The `skewness` cue of [`cues`] alone (the same value, at a fraction of the cost): negative
/// where thin dark features (joints, cracks, gaps between stones) stand out of a lighter
/// surface.
pub fn dark_skewness(photo: &Photo) -> f32 {
    moment(&detrended(&luminance_map(photo)), 3)
}

/// `photo`'s luminance map ([`SIZE`]², its centre square) without its shading, standardised:
/// the map the `skewness` cue is the third moment of.
pub fn detrended_luminance(photo: &Photo) -> Vec<f32> {
    detrended(&luminance_map(photo))
}

/// `v` with zero mean and unit deviation (zeros when flat).
fn standardised(v: &[f32]) -> Vec<f32> {
    let n = v.len() as f64;
    let m = v.iter().map(|&x| x as f64).sum::<f64>() / n;
    let var = v.iter().map(|&x| (x as f64 - m).powi(2)).sum::<f64>() / n;
    let inv = if var > 1e-12 { 1.0 / var.sqrt() } else { 0.0 };
    v.iter().map(|&x| ((x as f64 - m) * inv) as f32).collect()
}

/// The `k`-th moment of a standardised map.
fn moment(v: &[f32], k: i32) -> f32 {
    (v.iter().map(|&x| (x as f64).powi(k)).sum::<f64>() / v.len() as f64) as f32
}

/// Separable Gaussian blur of an `n × n` map, circular (the kernel cut at 3σ).
/// Below σ = 0.05 px, the map itself.
pub fn blur(v: &[f32], n: usize, sigma: f32) -> Vec<f32> {
    if sigma < 0.05 {
        return v.to_vec();
    }
    let r = (3.0 * sigma).ceil() as i64;
    let kernel: Vec<f32> = (-r..=r)
        .map(|i| (-(i * i) as f32 / (2.0 * sigma * sigma)).exp())
        .collect();
    let total: f32 = kernel.iter().sum();
    let pass = |src: &[f32], index: &dyn Fn(usize, usize) -> usize| {
        let mut out = vec![0.0f32; n * n];
        for line in 0..n {
            for x in 0..n {
                let mut s = 0.0f32;
                for (j, w) in kernel.iter().enumerate() {
                    let xx = (x as i64 + j as i64 - r).rem_euclid(n as i64) as usize;
                    s += w * src[index(line, xx)];
                }
                out[index(line, x)] = s / total;
            }
        }
        out
    };
    let rows = pass(v, &|y, x| y * n + x);
    pass(&rows, &|x, y| y * n + x)
}

/// Circular autocorrelation of a standardised `SIZE²` map, normalised to 1 at the origin
/// (row-major, origin at index 0).
fn autocorrelation(map: &[f32]) -> Vec<f32> {
    let spec = spectrum_real(map, SIZE, SIZE, true);
    let power: Vec<Complex32> = spec
        .iter()
        .map(|c| Complex32::new(c.norm_sqr(), 0.0))
        .collect();
    let a = ifft2(power, SIZE, SIZE);
    let a0 = a[0].re.max(1e-20);
    a.iter().map(|c| c.re / a0).collect()
}

/// Offset of index `j` from the origin, in (−SIZE/2, SIZE/2].
fn offset(j: usize) -> (i32, i32) {
    let s = |v: usize| {
        if v > SIZE / 2 {
            v as i32 - SIZE as i32
        } else {
            v as i32
        }
    };
    (s(j % SIZE), s(j / SIZE))
}

/// The autocorrelation's central lobe (the positive region connected to the origin) and its
/// elongation, 1 − the ratio of its second moments' eigenvalues.
fn central_lobe(acf: &[f32]) -> (Vec<bool>, f32) {
    let n = SIZE;
    let mut lobe = vec![false; n * n];
    let mut stack = vec![0usize];
    lobe[0] = true;
    let (mut sxx, mut syy, mut sxy, mut sw) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    while let Some(j) = stack.pop() {
        let (dx, dy) = offset(j);
        let w = acf[j] as f64;
        sxx += w * (dx * dx) as f64;
        syy += w * (dy * dy) as f64;
        sxy += w * (dx * dy) as f64;
        sw += w;
        let (x, y) = (j % n, j / n);
        for (nx, ny) in [(x + n - 1, y), (x + 1, y), (x, y + n - 1), (x, y + 1)] {
            let k = (ny % n) * n + nx % n;
            if !lobe[k] && acf[k] > 0.0 {
                lobe[k] = true;
                stack.push(k);
            }
        }
    }
    let (a, b, c) = (sxx / sw, syy / sw, sxy / sw);
    let mid = 0.5 * (a + b);
    let half = (0.25 * (a - b) * (a - b) + c * c).sqrt();
    let (big, small) = (mid + half, (mid - half).max(0.0));
    let elongation = if big > 1e-12 { 1.0 - small / big } else { 0.0 };
    (lobe, elongation as f32)
}

/// The autocorrelation's local maxima outside the central lobe with a positive value, highest
/// first, with their offsets.
fn acf_peaks(acf: &[f32], lobe: &[bool]) -> Vec<(f32, (i32, i32))> {
    let n = SIZE;
    let mut peaks: Vec<(f32, (i32, i32))> = Vec::new();
    for j in 0..n * n {
        if lobe[j] {
            continue;
        }
        let v = acf[j];
        let (x, y) = (j % n, j / n);
        let is_peak = [n - 1, 0, 1].iter().all(|&dy| {
            [n - 1, 0, 1]
                .iter()
                .all(|&dx| (dx, dy) == (0, 0) || acf[((y + dy) % n) * n + (x + dx) % n] <= v)
        });
        if is_peak && v > 0.0 {
            peaks.push((v, offset(j)));
        }
    }
    peaks.sort_by(|a, b| b.0.total_cmp(&a.0));
    peaks
}

/// The first period: the shortest offset among the peaks within 10 % of the highest (on
/// stripes every point of a ridge is as high as any other; the period is the shortest), with
/// its value.
fn first_period(acf: &[f32], lobe: &[bool]) -> Option<(f32, (i32, i32))> {
    first_of(&acf_peaks(acf, lobe))
}

fn first_of(peaks: &[(f32, (i32, i32))]) -> Option<(f32, (i32, i32))> {
    let &(top, _) = peaks.first()?;
    let length2 = |(x, y): (i32, i32)| x * x + y * y;
    peaks
        .iter()
        .filter(|p| p.0 >= 0.9 * top)
        .copied()
        .min_by_key(|p| length2(p.1))
}

/// The highest local maximum of the autocorrelation outside the central lobe, and the highest
/// one whose offset is at least 30° away from the first's direction (0 where none).
fn lattice_peaks(acf: &[f32], lobe: &[bool]) -> (f32, f32) {
    let n = SIZE;
    let peaks = acf_peaks(acf, lobe);
    let Some((first, (ax, ay))) = first_of(&peaks) else {
        return (0.0, 0.0);
    };
    let norm_a = ((ax * ax + ay * ay) as f32).sqrt();
    // Stripes have no second period, but their autocorrelation is a ridge through every
    // multiple of the first: any point of it is a peak at any angle. So a second peak counts
    // by its height above the mean of the line through it across the first vector (the ridge
    // itself for stripes, a line through peaks and troughs for a 2D lattice).
    let across = [-ay as f32 / norm_a, ax as f32 / norm_a];
    // Over ± the first period's length: far enough to cross a 2D lattice's troughs, near
    // enough that a slightly tilted first offset (a ridge's shortest peak one pixel aside)
    // stays on a ridge.
    let ridge_mean = |(bx, by): (i32, i32)| {
        let reach = (norm_a.round() as i32).max(8);
        let sum: f32 = (-reach..=reach)
            .map(|t| {
                let x = (bx as f32 + t as f32 * across[0]).round() as i64;
                let y = (by as f32 + t as f32 * across[1]).round() as i64;
                let (x, y) = (
                    x.rem_euclid(n as i64) as usize,
                    y.rem_euclid(n as i64) as usize,
                );
                acf[y * n + x]
            })
            .sum();
        sum / (2 * reach + 1) as f32
    };
    let second = peaks
        .iter()
        .filter(|(_, (bx, by))| {
            let norm_b = ((bx * bx + by * by) as f32).sqrt();
            let cross = (ax * by - ay * bx) as f32;
            cross.abs() >= 0.5 * norm_a * norm_b
        })
        .map(|&(v, at)| (v - ridge_mean(at)).max(0.0))
        .fold(0.0f32, f32::max);
    (first, second)
}

/// Orientation coherence, 4-fold axis alignment and edge sparsity of a map's gradients
/// (central differences, circular).
fn gradient_cues(map: &[f32]) -> (f32, f32, f32) {
    let n = SIZE;
    let (mut c2, mut s2, mut e, mut c4) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut energies = Vec::with_capacity(n * n);
    for y in 0..n {
        for x in 0..n {
            let gx = 0.5 * (map[y * n + (x + 1) % n] - map[y * n + (x + n - 1) % n]) as f64;
            let gy = 0.5 * (map[((y + 1) % n) * n + x] - map[((y + n - 1) % n) * n + x]) as f64;
            let q = gx * gx + gy * gy;
            c2 += gx * gx - gy * gy;
            s2 += 2.0 * gx * gy;
            e += q;
            if q > 1e-20 {
                // |g|² cos 4θ = ((gx² − gy²)² − (2 gx gy)²) / |g|²
                c4 += ((gx * gx - gy * gy).powi(2) - (2.0 * gx * gy).powi(2)) / q;
            }
            energies.push(q);
        }
    }
    if e <= 1e-20 {
        return (0.0, 0.0, 0.0);
    }
    energies.sort_by(|a, b| b.total_cmp(a));
    let top: f64 = energies[..energies.len() / 10].iter().sum();
    (
        ((c2 * c2 + s2 * s2).sqrt() / e) as f32,
        (c4 / e) as f32,
        (top / e) as f32,
    )
}

/// Otsu's between-class variance over the total, 64 bins.
fn bimodality(v: &[f32]) -> f32 {
    let (lo, hi) = v
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    if hi - lo <= 1e-9 {
        return 0.0;
    }
    let mut hist = [0f64; 64];
    let mut sums = [0f64; 64];
    for &x in v {
        let b = (((x - lo) / (hi - lo)) * 63.999) as usize;
        hist[b] += 1.0;
        sums[b] += x as f64;
    }
    let n: f64 = hist.iter().sum();
    let mean = sums.iter().sum::<f64>() / n;
    let var = v.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / n;
    let (mut w0, mut s0, mut best) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..63 {
        w0 += hist[i];
        s0 += sums[i];
        let w1 = n - w0;
        if w0 == 0.0 || w1 == 0.0 {
            continue;
        }
        let (m0, m1) = (s0 / w0, (mean * n - s0) / w1);
        best = best.max(w0 * w1 * (m0 - m1) * (m0 - m1) / (n * n));
    }
    if var > 1e-20 {
        (best / var) as f32
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn photo(n: usize, f: impl Fn(usize, usize) -> f32) -> Photo {
        Photo {
            width: n as u32,
            height: n as u32,
            pixels: (0..n * n)
                .map(|i| {
                    let v = f(i % n, i / n);
                    [v, v, v]
                })
                .collect(),
        }
    }

    fn cue(c: &[f32; CUES], name: &str) -> f32 {
        c[CUE_NAMES.iter().position(|n| *n == name).unwrap()]
    }

    /// Gaussian white noise, deviation 0.1 about 0.5.
    fn white(x: usize, y: usize) -> f32 {
        0.5 + 0.1 * crate::rng::gaussian(7, 0, (y * 4096 + x) as u32) as f32
    }

    #[test]
    fn a_brick_lattice_repeats_in_two_directions_and_white_noise_does_not() {
        // Courses 16 px high, bricks 32 px long, rows offset by half a brick, 2 px dark joints.
        let brick = photo(SIZE, |x, y| {
            let row = y / 16;
            let xs = (x + row % 2 * 16) % 32;
            if y % 16 < 2 || xs < 2 {
                0.2
            } else {
                0.7 + 0.05 * white(x, y)
            }
        });
        let c = cues(&brick);
        assert!(cue(&c, "lattice") > 0.4, "{c:?}");
        assert!(cue(&c, "lattice2") > 0.1, "{c:?}");
        assert!(cue(&c, "axis_alignment") > 0.5, "{c:?}");
        assert!(cue(&c, "skewness") < -1.0, "thin dark joints: {c:?}");
        let noise = cues(&photo(SIZE, white));
        assert!(cue(&noise, "lattice") < 0.15, "{noise:?}");
        assert!(cue(&noise, "coherence") < 0.1, "{noise:?}");
        assert!(cue(&noise, "kurtosis").abs() < 0.5, "{noise:?}");
    }

    #[test]
    fn stripes_are_coherent_and_elongate_the_central_lobe_but_have_no_second_period() {
        let stripes = photo(SIZE, |x, y| {
            0.5 + 0.4 * (std::f32::consts::TAU * y as f32 / 16.0).sin() + 0.02 * white(x, y)
        });
        let c = cues(&stripes);
        assert!(cue(&c, "coherence") > 0.9, "{c:?}");
        assert!(cue(&c, "lobe_elongation") > 0.8, "{c:?}");
        assert!(cue(&c, "lattice") > 0.8, "{c:?}");
        assert!(cue(&c, "lattice2") < 0.05, "{c:?}");
    }

    #[test]
    fn dark_skewness_is_the_skewness_cue_and_tells_dark_joints_from_noise() {
        let joints = photo(SIZE, |x, y| {
            if y % 16 < 2 || x % 24 < 2 {
                0.2
            } else {
                0.7 + 0.3 * (white(x, y) - 0.5)
            }
        });
        let noise = photo(SIZE, white);
        assert_eq!(CUE_NAMES[SKEWNESS], "skewness");
        for p in [&joints, &noise] {
            assert_eq!(dark_skewness(p), cue(&cues(p), "skewness"));
        }
        // The ranking's threshold (retrieve::DARK_NETWORK_SKEWNESS, about −0.7) lies between.
        assert!(dark_skewness(&joints) < -1.0, "{}", dark_skewness(&joints));
        assert!(
            dark_skewness(&noise).abs() < 0.3,
            "{}",
            dark_skewness(&noise)
        );
    }

    #[test]
    fn two_tones_are_bimodal_and_a_flat_patch_gives_zeros_not_nan() {
        let checks = photo(64, |x, y| if (x / 8 + y / 8) % 2 == 0 { 0.1 } else { 0.9 });
        assert!(cue(&cues(&checks), "bimodality") > 0.95);
        let flat = cues(&photo(64, |_, _| 0.5));
        assert!(flat.iter().all(|v| v.is_finite()), "{flat:?}");
    }
}
