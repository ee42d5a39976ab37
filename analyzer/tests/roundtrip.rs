//! Lagae Fig. 5: random weights → render → analyse recovers the weights.
//!
//! Tolerance per band, from the number of samples the estimate rests on. A band's power is a
//! sum of `|F|²` over its FFT bins; for Gaussian noise each independent complex bin is an
//! exponential variable, so with `m` independent bins the relative standard deviation of the
//! power is `1/sqrt(m)` and of the weight (its square root) `1/(2·sqrt(m))`. Two things bound
//! `m`: the band's FFT bins in the image (`n_bins/2` independent, Hermitian symmetry), and the
//! noise coefficients the image actually shows — `min(512/2^j, 128)²` for band `j` with a 128²
//! tile: the fine bands repeat the same tile, so more pixels bring no new randomness. We allow
//! 4 standard deviations of that, plus 3 % for the calibration of the leakage matrix, and also
//! account for the deconvolution coupling each band to its neighbours (`+ 0.5·` the neighbours'
//! allowance, since ~10 % of their power is subtracted).

mod common;

use common::{grey_basis, lcg, noise_params};
use proctex::analyze::{Options, analyze_prepared};
use proctex::render::{View, render};
use proctex::spectrum::{Estimator, num_bands};

const SIZE: u32 = 512;

fn band_bins(nb: usize) -> Vec<f64> {
    // Count FFT bins per band exactly as the analysis assigns them.
    let n = SIZE as usize;
    let band_of = |k: usize| -> Option<usize> {
        let kk = k.min(n - k);
        if kk == 0 {
            return None;
        }
        let mut j = 0;
        while j + 1 < nb && kk * (4usize << j) <= n {
            j += 1;
        }
        Some(j)
    };
    let mut bins = vec![0.0; nb];
    for x in 0..n {
        for y in 0..n {
            let b = match (band_of(x), band_of(y)) {
                (None, None) => continue,
                (Some(a), None) | (None, Some(a)) => a,
                (Some(a), Some(b)) => a.min(b),
            };
            bins[b] += 1.0;
        }
    }
    bins
}

fn tolerances(nb: usize) -> Vec<f64> {
    let bins = band_bins(nb);
    let sd: Vec<f64> = (0..nb)
        .map(|j| {
            let coeffs = ((SIZE as f64 / (1u64 << j) as f64).min(128.0)).powi(2);
            let m = (bins[j] / 2.0).min(coeffs * 0.75 / 2.0).max(1.0);
            1.0 / (2.0 * m.sqrt())
        })
        .collect();
    (0..nb)
        .map(|j| {
            let neighbours = [j.wrapping_sub(1), j + 1]
                .iter()
                .filter(|&&k| k < nb)
                .map(|&k| sd[k])
                .fold(0.0, f64::max);
            4.0 * sd[j] + 0.5 * 4.0 * neighbours + 0.03
        })
        .collect()
}

/// Renders random weights, analyses with `estimator`, returns relative errors per band
/// (channel 0, the only one with power).
fn trial(seed: u32, estimator: Estimator) -> (Vec<f64>, Vec<f32>) {
    let nb = num_bands(SIZE as usize, SIZE as usize);
    let mut s = seed as u64 * 7919 + 1;
    // Weights between 0.25 and 1 (relative), scaled so the texture stays inside [0, 1].
    let w: Vec<f32> = (0..nb)
        .map(|_| (0.25 + 0.75 * lcg(&mut s)) as f32)
        .collect();
    let norm = (w.iter().map(|v| v * v).sum::<f32>()).sqrt();
    let w: Vec<f32> = w.iter().map(|v| v / norm * 0.08).collect();
    let params = noise_params(
        [w.clone(), vec![0.0; nb], vec![0.0; nb]],
        grey_basis(),
        seed,
    );
    let img = render(&params, SIZE, SIZE, &View::default()).to_photo();
    let opts = Options {
        histogram: false,
        estimator,
        ..Options::default()
    };
    let a = analyze_prepared(&img, &opts);
    let got = &a.params.noise().unwrap().weights[0];
    let err = (0..nb)
        .map(|j| ((got[j] - w[j]) / w[j]).abs() as f64)
        .collect();
    (err, w)
}

#[test]
fn random_weights_are_recovered() {
    let nb = num_bands(SIZE as usize, SIZE as usize);
    let tol = tolerances(nb);
    let mut worst = vec![0.0f64; nb];
    let mut worst_lagae = vec![0.0f64; nb];
    let mut mean_ours = vec![0.0f64; nb];
    let mut mean_lagae = vec![0.0f64; nb];
    let seeds = 1..=6u32;
    let count = seeds.clone().count() as f64;
    for seed in seeds {
        let (err, w) = trial(seed, Estimator::Deconvolved);
        let (err_l, _) = trial(seed, Estimator::Lagae);
        for j in 0..nb {
            assert!(
                err[j] <= tol[j],
                "seed {seed} band {j}: relative error {:.4} > tolerance {:.4} (weights {w:?})",
                err[j],
                tol[j]
            );
            worst[j] = worst[j].max(err[j]);
            worst_lagae[j] = worst_lagae[j].max(err_l[j]);
            mean_ours[j] += err[j] / count;
            mean_lagae[j] += err_l[j] / count;
        }
    }
    println!("band  tolerance  worst(deconvolved)  mean(deconvolved)  mean(lagae eq.9)");
    for j in 0..nb {
        println!(
            "{j:>4} {:>10.4} {:>19.4} {:>18.4} {:>17.4}",
            tol[j], worst[j], mean_ours[j], mean_lagae[j]
        );
    }
    // The deconvolution is the point of departing from eq. 9: it must be better overall.
    let sum = |v: &[f64]| v.iter().sum::<f64>();
    assert!(sum(&mean_ours) < sum(&mean_lagae));
}

#[test]
fn tolerances_are_tighter_on_high_bands() {
    let t = tolerances(8);
    assert!(t[0] < t[4] && t[4] < t[7], "{t:?}");
    assert!(t[0] < 0.1, "{t:?}");
}

#[test]
fn colour_round_trip_recovers_basis_and_weights() {
    // Three channels with clearly separated variances and a non-trivial rotation.
    let nb = 8;
    let basis = {
        // Rotate the grey basis about the grey axis by 40°: still a proper rotation.
        let g = grey_basis();
        let (c, s) = (40f32.to_radians().cos(), 40f32.to_radians().sin());
        let r1 = [0, 1, 2].map(|k| c * g[1][k] + s * g[2][k]);
        let r2 = [0, 1, 2].map(|k| -s * g[1][k] + c * g[2][k]);
        [g[0], r1, r2]
    };
    let w0: Vec<f32> = (0..nb).map(|j| 0.03 + 0.004 * j as f32).collect();
    let w1: Vec<f32> = (0..nb).map(|j| 0.018 - 0.001 * j as f32).collect();
    let w2: Vec<f32> = (0..nb).map(|_| 0.006).collect();
    let params = noise_params([w0.clone(), w1.clone(), w2.clone()], basis, 5);
    let img = render(&params, SIZE, SIZE, &View::default()).to_photo();
    let a = analyze_prepared(
        &img,
        &Options {
            histogram: false,
            ..Options::default()
        },
    );
    let got = &a.params;
    for r in 0..3 {
        let d: f32 = (0..3).map(|k| got.colour.basis[r][k] * basis[r][k]).sum();
        assert!(d.abs() > 0.99, "axis {r}: |cos| = {}", d.abs());
    }
    let gw = &got.noise().unwrap().weights;
    let tol = tolerances(nb);
    for (c, want) in [&w0, &w1, &w2].iter().enumerate() {
        for j in 0..nb {
            let e = ((gw[c][j] - want[j]) / want[j]).abs() as f64;
            // Channel PCA is estimated from the same image, which adds a little cross-talk.
            assert!(e <= tol[j] + 0.05, "channel {c} band {j}: {e:.4}");
        }
    }
}
