//! The finest band drawn after the histogram (`NoiseModel::fine`), bounded
//! (`render::fine_value`): the split keeps a channel's spread, keeps the sum where the histogram
//! is off but for the finest band's tails, and leaves the histogram's tails to the coarse bands,
//! where they are not isolated pixels.
mod common;

use common::{grey_basis, noise_params};
use proctex::params::{Model, NoiseModel, Params};
use proctex::render::{View, render};
use proctex::specks::speck_fraction;

const SIDE: u32 = 256;

fn noise_mut(p: &mut Params) -> &mut NoiseModel {
    match &mut p.model {
        Model::Noise(n) => n,
        Model::Structured(s) => &mut s.residual,
    }
}

/// A noise model with a strong finest band and a heavy-tailed histogram (a few dark and
/// bright outliers around a narrow core, as a photo of speckled stone has).
fn heavy_tailed() -> Params {
    let w = vec![0.6, 0.5, 0.4, 0.3, 0.2, 0.1];
    let mut p = noise_params([w.clone(), w.clone(), w], grey_basis(), 3);
    let n = noise_mut(&mut p);
    n.histogram.enabled = true;
    let knots: Vec<f32> = (0..=10)
        .map(|j| {
            let z = -2.5 + 0.5 * j as f32;
            0.04 * z + 0.05 * z * z * z / 2.5
        })
        .collect();
    n.histogram.knots = [knots.clone(), knots.clone(), knots];
    p
}

fn pixels(p: &Params) -> Vec<[f32; 3]> {
    render(p, SIDE, SIDE, &View::default()).pixels
}

fn variance(px: &[[f32; 3]], c: usize) -> f64 {
    let n = px.len() as f64;
    let m = px.iter().map(|p| p[c] as f64).sum::<f64>() / n;
    px.iter().map(|p| (p[c] as f64 - m).powi(2)).sum::<f64>() / n
}

#[test]
fn the_split_keeps_each_channels_spread_and_drops_the_specks() {
    let lagae = heavy_tailed();
    let mut split = lagae.clone();
    noise_mut(&mut split).finest_band_gaussian();
    split.validate().expect("the split model is valid");
    let n = noise_mut(&mut split);
    assert!(
        n.weights.iter().all(|w| w[0] == 0.0),
        "the finest band left the histogram"
    );
    assert!(n.fine.iter().all(|&f| f > 0.0), "and went after it");
    let (a, b) = (pixels(&lagae), pixels(&split));
    for c in 0..3 {
        let ratio = variance(&b, c) / variance(&a, c);
        assert!(
            (0.8..1.25).contains(&ratio),
            "channel {c}: variance ratio {ratio}"
        );
    }
    let photo = |px: Vec<[f32; 3]>| proctex::input::Photo {
        width: SIDE,
        height: SIDE,
        pixels: px
            .into_iter()
            .map(|p| p.map(|v| v.clamp(0.0, 1.0)))
            .collect(),
    };
    let (before, after) = (speck_fraction(&photo(a)), speck_fraction(&photo(b)));
    assert!(
        after < 0.5 * before,
        "specks {before} with the finest band through the histogram, {after} after it"
    );
}

#[test]
fn without_the_histogram_the_split_renders_the_same_sum_but_for_the_finest_bands_tails() {
    let mut lagae = heavy_tailed();
    noise_mut(&mut lagae).histogram.enabled = false;
    let mut split = lagae.clone();
    noise_mut(&mut split).finest_band_gaussian();
    assert_eq!(noise_mut(&mut split).fine, [0.6; 3]);
    // The coarse bands alone, to take out of both renders.
    let mut coarse = lagae.clone();
    noise_mut(&mut coarse)
        .weights
        .iter_mut()
        .for_each(|w| w[0] = 0.0);
    let (a, b, k) = (pixels(&lagae), pixels(&split), pixels(&coarse));
    for c in 0..3 {
        // Each render's finest band: the Gaussian band, and its bounded part.
        let (mut ab, mut aa, mut bb, mut most) = (0.0f64, 0.0f64, 0.0f64, 0.0f32);
        for ((p, q), r) in a.iter().zip(&b).zip(&k) {
            let (g, f) = ((p[c] - r[c]) as f64, (q[c] - r[c]) as f64);
            ab += g * f;
            aa += g * g;
            bb += f * f;
            most = most.max((q[c] - r[c]).abs());
        }
        let ratio = bb / aa;
        assert!(
            (0.9..1.1).contains(&ratio),
            "channel {c}: the finest band's variance ratio {ratio}"
        );
        let correlation = ab / (aa * bb).sqrt();
        assert!(correlation > 0.9, "channel {c}: correlation {correlation}");
        // Each decorrelated channel's part at most 0.6 · FINE_GAIN, rotated into RGB.
        let basis = lagae.colour.basis;
        let spread: f32 = (0..3).map(|d| basis[d][c].abs()).sum();
        let bound = 0.6 * proctex::render::FINE_GAIN * lagae.colour.contrast * spread * 1.0001;
        assert!(
            most <= bound,
            "channel {c}: an excursion {most} past the bound {bound}"
        );
    }
}

/// The part is bounded by `FINE_GAIN` band deviations and keeps the band's unit variance: the
/// gain is `1 / sd(tanh X)` for a standard normal `X` (Simpson's rule over ±12 deviations).
#[test]
fn the_bounded_part_keeps_the_bands_unit_variance() {
    use proctex::render::{FINE_GAIN, fine_value};
    let n = 24_000;
    let h = 24.0 / n as f64;
    let mut second = 0.0f64;
    for i in 0..=n {
        let x = -12.0 + h * i as f64;
        let weight = if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let density = (-0.5 * x * x).exp() / (2.0 * std::f64::consts::PI).sqrt();
        second += weight * density * (fine_value(x as f32) as f64).powi(2);
    }
    let variance = second * h / 3.0;
    assert!((variance - 1.0).abs() < 1e-5, "variance {variance}");
    assert!(fine_value(40.0) <= FINE_GAIN && fine_value(-40.0) >= -FINE_GAIN);
}

#[test]
fn a_document_without_the_part_loads_as_lagaes_model_and_saves_without_it() {
    let p = heavy_tailed();
    let text = p.to_json();
    assert!(!text.contains("\"fine\""), "a zero part is not written");
    assert_eq!(Params::from_json(&text).unwrap(), p);
    let mut split = p.clone();
    noise_mut(&mut split).finest_band_gaussian();
    let text = split.to_json();
    assert!(text.contains("\"fine\""));
    assert_eq!(Params::from_json(&text).unwrap(), split);
}
