//! The noise model's output tone curve: one round of iterative distribution transfer (Pitié,
//! Kokaram & Dahyot 2005) after Lagae's histogram spline.
//!
//! Lagae's model matches the photo's distribution along each decorrelated (PCA) axis and
//! synthesises the axes independently. PCA makes the channels uncorrelated, not independent:
//! where the colours are multi-modal (green leaves on brown soil, stones of several colours)
//! independent channels mix the modes and make colours the photo does not have. One round of
//! distribution transfer along other axes recovers part of the joint distribution: the
//! synthesis is projected on a second set of axes, each projection is mapped onto the photo's
//! distribution along it, and the result rotated back. We take the RGB axes as that second set:
//! they are a well-spread rotation of the PCA axes for any photo (the luminance axis lies at
//! 55° from each), and the per-channel output tone curve of [`crate::params::Tone`] already
//! renders, morphs and exports them (a pointwise map: random access, any resolution).
//!
//! Measured on ideal fields (`noise_ideal_lab --colour`, docs/measurements.md): rounds of
//! distribution transfer take the dev set's colour ratio from 1.57 to 1.40 (one round) and 1.23
//! (two); see "Output tone curve of the noise model" there for what this one round does in the
//! product.

use crate::colour::ColourQuantiles;
use crate::input::Photo;
use crate::params::{Params, Tone};
use crate::render::{ChannelNoise, Prepared, colour, texture_noise, tile_for};

/// Seed of the first realisation sampled by [`fit_noise_tone`] and [`allocate`]: fixed, not the params' own, so that
/// analyses differing only in their seed share the curve (it is a property of the model), and
/// apart from the seeds a user or the fidelity protocol (seeds 1, 2, …) renders, so that the
/// curve is measured on realisations it was not fitted to.
pub const FIT_SEED: u32 = 0x5eed_0000;

/// Realisations (seeds [`FIT_SEED`], `FIT_SEED + 1`, …) pooled by [`fit_noise_tone`] and
/// [`allocate`]: the low-frequency bands hold few independent features in a photo-sized patch,
/// so one seed's distribution is not the model's.
pub const NOISE_TONE_SEEDS: u32 = 4;

/// Sample points per seed (a regular grid over the photo's extent).
/// Measured: 4096 per seed (and the halves subsampled to 16k pixels) made the analysis 2× faster
/// and the dev set's colour ratio worse by 0.038 ± 0.019 (paired).
const SAMPLES_PER_SEED: usize = 16_384;

/// Numbers a noise-model texture may hold: its band weights, histogram knots, band
/// orientations, output tone curve and colour block (mean, basis, contrast); a few dozen
/// numbers is what keeps the model editable with sliders and small in a shader. [`allocate`]
/// spends what the weights, orientations and colour leave on knots.
pub const PARAMETER_BUDGET: usize = 100;

/// Knot intervals `K` of the histogram spline that [`allocate`] tries (up to the analysis's
/// own `K`, which it always tries).
pub const HISTOGRAM_INTERVALS: [usize; 4] = [4, 6, 8, 10];

/// Most knots per channel of the noise model's curve.
pub const MAX_NOISE_TONE_KNOTS: usize = 33;

/// The numbers in a noise model's document that are not knots: 3 weights and, where any band
/// is oriented, 2 orientation numbers per band, the finest band's 3 parts after the histogram
/// where it has them, plus the colour block (3 mean, 9 basis, 1 contrast).
pub fn fixed_numbers(model: &crate::params::NoiseModel) -> usize {
    let fine = if model.fine == [0.0; 3] { 0 } else { 3 };
    model.bands() * 3 + model.orientation.len() * 2 + fine + 13
}

/// All the numbers of a noise model's document counted against [`PARAMETER_BUDGET`].
pub fn numbers(model: &crate::params::NoiseModel) -> usize {
    fixed_numbers(model)
        + 3 * model.histogram.knots[0].len()
        + tone_numbers(model.tone.as_ref().map_or(0, |t| t.knots[0].len()))
}

/// The numbers of a tone curve of `knots` knots per channel (its knots and ranges).
pub fn tone_numbers(knots: usize) -> usize {
    if knots == 0 { 0 } else { 3 * knots + 6 }
}

/// The model's channel noise at sample points: [`NOISE_TONE_SEEDS`] realisations (seeds
/// [`FIT_SEED`], …) on a regular grid over `width × height` texels, about [`SAMPLES_PER_SEED`]
/// points each; the finest band's part after the histogram unweighted (a part of 1 in every
/// channel), which [`coloured`] scales by the model's own. The noise does not depend on the
/// knots or that part, so every candidate colours the same samples.
fn channel_samples(params: &Params, width: u32, height: u32) -> Vec<ChannelNoise> {
    let n = width as usize * height as usize;
    let stride = ((n as f64 / SAMPLES_PER_SEED as f64).sqrt().floor() as usize).max(1);
    let seeds: Vec<u32> = (0..NOISE_TONE_SEEDS).collect();
    crate::parallel::map_in_order(&seeds, |&k| {
        let mut p = Params {
            seed: FIT_SEED + k,
            ..params.clone()
        };
        p.model.noise_layer_mut().fine = [1.0; 3];
        let (prep, tile) = (Prepared::new(&p), tile_for(&p));
        let scale = params.transform.scale;
        let mut out = Vec::with_capacity(n / (stride * stride) + 1);
        for y in (0..height).step_by(stride) {
            for x in (0..width).step_by(stride) {
                // One texel per photo pixel; world units are texels times the scale.
                let world = [(x as f32 + 0.5) * scale, (y as f32 + 0.5) * scale, 0.0];
                out.push(texture_noise(&prep, &tile, prep.texel(world), 0.0));
            }
        }
        out
    })
    .concat()
}

/// The colours of `params` (its histogram, no tone curve) at channel noise `samples`.
fn coloured(params: &Params, samples: &[ChannelNoise]) -> Vec<[f32; 3]> {
    let prep = Prepared::new(params);
    samples
        .iter()
        .map(|&g| {
            let n = ChannelNoise {
                sum: g.sum,
                fine: [0, 1, 2].map(|c| g.fine[c] * prep.fine[c]),
            };
            colour(&prep, n, prep.mean)
        })
        .collect()
}

/// The output tone curve of noise-model `params` (without a curve) for `photo`, the image it
/// was analysed on, with `knots` knots per channel: the model sampled over the photo's extent
/// ([`channel_samples`]) and each RGB channel quantile-matched onto the photo's
/// ([`quantile_match`]). `None` for a photo of fewer than 64 pixels or `params` with a curve.
pub fn fit_noise_tone(photo: &Photo, params: &Params, knots: usize) -> Option<Tone> {
    if photo.pixels.len() < 64 || params.model.tone().is_some() {
        return None;
    }
    let samples = channel_samples(params, photo.width, photo.height);
    Some(quantile_match(
        &[coloured(params, &samples)],
        &sorted_channels(photo),
        knots,
    ))
}

/// One histogram knot count that [`allocate`] tries: each channel's inverse-CDF knots of the
/// whole analysed image, and of its top (`height / 2` rows) and bottom halves alone.
#[derive(Clone, Debug, PartialEq)]
pub struct HistogramCandidate {
    /// Knots of the whole image.
    pub whole: [Vec<f32>; 3],
    /// Knots of the top and of the bottom half.
    pub halves: [[Vec<f32>; 3]; 2],
}

/// How a noise model spends its knots ([`allocate`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Allocation {
    /// The histogram's knots per channel.
    pub knots: [Vec<f32>; 3],
    /// The finest band's part after the histogram ([`crate::params::NoiseModel::fine`]) and
    /// the band weights that go with it (the finest band's moved there), when the allocation
    /// split it; `None` otherwise.
    pub fine: Option<([f32; 3], [Vec<f32>; 3])>,
    /// The output tone curve, if one was worth its numbers.
    pub tone: Option<Tone>,
    /// The colour distance it leaves on the half of the photo its curve was not fitted to
    /// (the mean of the two folds).
    pub distance: f64,
}

/// Chooses, per photo, how noise-model `params` (no curve yet) spends the numbers
/// [`PARAMETER_BUDGET`] leaves after its weights, orientations and colour ([`fixed_numbers`]):
/// each of the histogram knot sets `histograms` (each channel's inverse-CDF knots at one `K`;
/// the analysis's own `K` first) is tried with no curve and with the largest curve the budget
/// leaves (at most [`MAX_NOISE_TONE_KNOTS`]). Each split is scored by two-fold validation
/// within the photo: the model with one half's histogram (top or bottom), and the curve fitted
/// on its samples ([`channel_samples`]) and that half, is scored by the sliced Wasserstein
/// colour distance ([`ColourQuantiles::distance`]) to the other half. The split of least
/// distance wins, and its histogram and curve are those of the whole photo. No constant is chosen on photos: the knot count
/// follows from the budget and the error each split leaves on pixels it was not fitted to.
/// `None` for a photo of fewer than 64 pixels.
///
/// Measured on the development set (docs/measurements.md, "Output tone curve of the noise
/// model"): at `K = 10`, a curve of 9, 17 and 33 knots took the stochastic photos' colour ratio
/// from 1.69 to 1.41, 1.35 and 1.33; 5 histogram knots with 17 curve knots gave 1.37 and with
/// 9 gave 1.50, so the split matters. Scored on the pixels it was fitted to, the choice went
/// wrong on small crops (colour 1.44, several 128² crops worse than without a curve: a curve
/// matches the distance's three RGB directions exactly); scored on the other half with the
/// histogram of the whole photo, it favoured no curve (the histogram had seen both halves).
///
/// With `fine_gaussian`, every candidate histogram is scored as the model renders it with its
/// finest band split off ([`crate::params::NoiseModel::finest_band_gaussian`], which depends on
/// the knots), so the curve is fitted to that render.
pub fn allocate(
    photo: &Photo,
    params: &Params,
    histograms: &[HistogramCandidate],
    fine_gaussian: bool,
) -> Option<Allocation> {
    let crate::params::Model::Noise(model) = &params.model else {
        return None;
    };
    if photo.pixels.len() < 64 || model.tone.is_some() || histograms.is_empty() {
        return None;
    }
    // The model with `knots`, split when asked (its band weights do not depend on the knots).
    let model_with = |knots: &[Vec<f32>; 3]| {
        let mut m = model.clone();
        m.histogram.knots = knots.clone();
        if fine_gaussian {
            m.finest_band_gaussian();
        }
        m
    };
    let split = model_with(&model.histogram.knots);
    let mut sampled = params.clone();
    *sampled.model.noise_layer_mut() = split.clone();
    let samples = channel_samples(&sampled, photo.width, photo.height);
    // Two folds: the photo's top and bottom halves. A split is scored by curves fitted on one
    // half and compared with the other: fitted and scored on the same pixels, a curve matches
    // the three RGB directions of the distance exactly and always looks best.
    let half = photo.height / 2;
    let halves = [(0, half), (half, photo.height)].map(|(y0, y1)| Photo {
        width: photo.width,
        height: y1 - y0,
        pixels: photo.pixels[(y0 * photo.width) as usize..(y1 * photo.width) as usize].to_vec(),
    });
    let sorted_halves = [sorted_channels(&halves[0]), sorted_channels(&halves[1])];
    let targets = [
        ColourQuantiles::of(&halves[0]),
        ColourQuantiles::of(&halves[1]),
    ];
    let clamped = |px: Vec<[f32; 3]>| Photo {
        width: px.len() as u32,
        height: 1,
        pixels: px
            .into_iter()
            .map(|p| p.map(|v| v.clamp(0.0, 1.0)))
            .collect(),
    };
    let through = |tone: &Tone, colours: &[[f32; 3]]| -> Vec<[f32; 3]> {
        let curve = tone.curve();
        colours
            .iter()
            .map(|px| [0, 1, 2].map(|c| curve(c, px[c])))
            .collect()
    };
    let fixed = fixed_numbers(&split);
    let with_knots = |knots: &[Vec<f32>; 3]| {
        let mut p = params.clone();
        p.model = crate::params::Model::Noise(model_with(knots));
        coloured(&p, &samples)
    };
    // Every candidate's options scored in parallel (native), then reduced in order.
    let indices: Vec<usize> = (0..histograms.len()).collect();
    let scored = crate::parallel::map_in_order(&indices, |&i| {
        let candidate = &histograms[i];
        let used = fixed + 3 * candidate.whole[0].len();
        let room = PARAMETER_BUDGET.saturating_sub(used);
        let tone_knots = (room.saturating_sub(6) / 3).min(MAX_NOISE_TONE_KNOTS);
        // Per fold: the model with the fold's histogram, scored against the other half.
        let folds = [0, 1].map(|fold| with_knots(&candidate.halves[fold]));
        let mut options = Vec::with_capacity(2);
        // No curve: within the budget, or the first candidate (the analysis's own K) anyway.
        if used <= PARAMETER_BUDGET || i == 0 {
            let distance: f64 = (0..2)
                .map(|fold| {
                    ColourQuantiles::of(&clamped(folds[fold].clone())).distance(&targets[1 - fold])
                })
                .sum();
            options.push((distance, 0));
        }
        if tone_knots >= 3 {
            let distance: f64 = (0..2)
                .map(|fold| {
                    let tone = quantile_match(
                        std::slice::from_ref(&folds[fold]),
                        &sorted_halves[fold],
                        tone_knots,
                    );
                    ColourQuantiles::of(&clamped(through(&tone, &folds[fold])))
                        .distance(&targets[1 - fold])
                })
                .sum();
            options.push((distance, tone_knots));
        }
        options
    });
    // (distance, histogram index, curve knots (0: none)), the best so far.
    let mut best: Option<(f64, usize, usize)> = None;
    for (i, options) in scored.into_iter().enumerate() {
        for (distance, tone_knots) in options {
            if best.is_none_or(|b| distance < b.0) {
                best = Some((distance, i, tone_knots));
            }
        }
    }
    let (distance, i, tone_knots) = best?;
    let chosen = model_with(&histograms[i].whole);
    let tone = (tone_knots > 0).then(|| {
        quantile_match(
            std::slice::from_ref(&with_knots(&histograms[i].whole)),
            &sorted_channels(photo),
            tone_knots,
        )
    });
    Some(Allocation {
        fine: fine_gaussian.then(|| (chosen.fine, chosen.weights.clone())),
        knots: chosen.histogram.knots,
        tone,
        distance: distance / 2.0,
    })
}

/// Each RGB channel of `photo`'s pixels, sorted.
pub fn sorted_channels(photo: &Photo) -> [Vec<f32>; 3] {
    std::array::from_fn(|c| {
        let mut t: Vec<f32> = photo.pixels.iter().map(|p| p[c]).collect();
        crate::radix::sort(&mut t);
        t
    })
}

/// The tone curve of `knots` knots per RGB channel that maps the pooled `renders` onto the
/// photo's sorted channels: knots evenly spaced over the pooled values' 0.2–99.8 % quantile
/// range map the fraction `F_render(x)` of rendered values below them to the photo's quantile
/// at that fraction (kept non-decreasing).
pub fn quantile_match(
    renders: &[Vec<[f32; 3]>],
    sorted_photo: &[Vec<f32>; 3],
    knots: usize,
) -> Tone {
    let mut tone = Tone::identity(knots);
    for c in 0..3 {
        let r: Vec<f32> = renders
            .iter()
            .flat_map(|px| px.iter().map(move |p| p[c]))
            .collect();
        // Two order statistics and, per knot, the count of values below it: what sorting
        // `r` gave (its nearest-rank quantiles, and `partition_point` of `v < x`), in linear
        // time.
        let rank = |f: f64| ((r.len() - 1) as f64 * f).round() as usize;
        let ends = crate::radix::order_statistics(&r, &[rank(0.002), rank(0.998)]);
        let lo = ends[0];
        let hi = ends[1].max(lo + 1e-3);
        tone.range[c] = [lo, hi];
        let at: Vec<f32> = (0..knots)
            .map(|k| lo + (hi - lo) * k as f32 / (knots - 1) as f32)
            .collect();
        let below = counts_below(&r, &at);
        let mut prev = f32::NEG_INFINITY;
        for (v, &count) in tone.knots[c].iter_mut().zip(&below) {
            let f = count as f64 / r.len() as f64;
            prev = quantile(&sorted_photo[c], f.clamp(0.002, 0.998)).max(prev);
            *v = prev;
        }
    }
    tone
}

/// For each of the ascending thresholds `at`, how many of `values` are below it (`v < x`).
fn counts_below(values: &[f32], at: &[f32]) -> Vec<usize> {
    // `first[j]`: the values below `at[j]` and no earlier threshold (`j = at.len()`: below
    // none); a value is below `at[k]` for every `k` from its `j` on.
    let mut first = vec![0usize; at.len() + 1];
    for &v in values {
        first[at.partition_point(|&x| v.partial_cmp(&x) != Some(std::cmp::Ordering::Less))] += 1;
    }
    let mut out = vec![0usize; at.len()];
    let mut sum = 0;
    for (k, o) in out.iter_mut().enumerate() {
        sum += first[k];
        *o = sum;
    }
    out
}

/// The sample quantile of sorted `v` at fraction `f` (nearest rank).
fn quantile(v: &[f32], f: f64) -> f32 {
    v[((v.len() - 1) as f64 * f).round() as usize]
}
