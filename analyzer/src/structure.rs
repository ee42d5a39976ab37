//! Fitting a structured model's colour to a photo: given a pattern (from
//! retrieval, or chosen by hand), the colour ramp along its structure value and the residual
//! stochastic detail.
//!
//! The two-tone paper (§3) colours a model with two tones: the photo's extremal colours on its
//! first principal axis. Going past two tones, without knowing where the pattern's bricks lie
//! in the photo:
//! 1. **Rank matching.** The photo's structure map `t` (its projection on the tone line,
//!    [`crate::two_tone`]) and the pattern's structure value `s` over an image of the same size
//!    are both sorted; the photo pixel of rank `r` is paired with the pattern value `ŝ` of the
//!    same rank. Where the pattern is flat (a brick face at `s = 1`), many photo pixels pair
//!    with one `s`: their mean colour is the brick's colour, their spread is grain.
//! 2. **Ramp.** Stops at the pattern's `s` quantiles 0, 1/7, …, 1 (merged where equal); the stop
//!    colours minimise `Σ |ramp(ŝ_x) − photo_x|²` over all pixels (the ramp is linear in them:
//!    hat functions, a tridiagonal system). This is the least-squares best ramp under the rank
//!    pairing, and it reproduces the two-tone model when the pattern has two values.
//! 3. **Residual.** `photo_x − ramp(ŝ_x)` is what the structure does not explain (grain, stains,
//!    colour off the tone line). Lagae's analysis models it as noise
//!    ([`crate::analyze::analyze_prepared_in`] on the residual plus the photo's mean, so that it
//!    is a valid colour image): its histogram knots and band weights in three channels, the
//!    first along the photo's tone line and the other two the colour across it (not the
//!    residual's own principal axes: [`crate::colour::pca_with_first_axis`]).
//!
//! 4. **Spectrum.** The residual's band weights make up for the rendered pattern's spectrum
//!    ([`compensate_spectrum`]).
//! 5. **Tone curve.** A per-channel monotone curve maps the synthesis's colour distribution onto
//!    the photo's ([`fit_tone`]).
//! 6. **Residual amplitude.** Steps 4–5 are run with the residual's amplitude grown by `g^α`
//!    for a few `α`, `g` the factor that gives the residual the power step 4 asks of it, and
//!    the ramp's contrast lowered by as much variance as the residual gains; the candidate
//!    whose render of the user's seed is nearest the photo is kept ([`fit_structured`]).
//! 7. **Grain.** The kept candidate's finest band along the tone line is raised until its
//!    render's typical pixel is as grainy as the photo's ([`grain`]).
//!
//! Tone swap: with `swapped`, the photo's `t` is reversed before the pairing (the pattern's
//! `s = 0` then meets the photo's lighter tone). Which orientation fits is the retrieval's
//! decision (it matches both `s` and `1 − s`).

use crate::analyze::{Analysis, Options, analyze_prepared_in};
use crate::input::Photo;
use crate::noise::Tile;
use crate::params::{Colour, Model, NoiseModel, StructuredModel};
use crate::pattern::{Pattern, PatternKind, RampStop};
use crate::render::pattern::{ramp_rows, structure_image};
use crate::two_tone::two_tone;

mod final_fit;
pub mod grain;
pub(crate) mod tone;
pub use final_fit::{FinalFit, Finished, FirstRound, Scored, fit_structured, tone_render};
pub use tone::{TONE_KNOTS, TONE_SEEDS, fit_tone};

/// Stops of a fitted ramp (before merging equal ones).
pub const FIT_STOPS: usize = 8;

/// Renders pooled by the tone curve with which step 6 scores each of its candidates: the
/// user's seed alone. The chosen candidate's curve is fitted again on [`TONE_SEEDS`].
///
/// Ours, for speed: the four renders of each candidate's tone fit were four fifths of step
/// 6's renders (10 candidates on a 256² photo: 3.0 s of the analysis' 4.5 s natively).
const SELECTION_TONE_SEEDS: u32 = 1;

/// Steps above the refined roughness that step 6 also tries ([`rougher_variants`]).
const ROUGHNESS_STEPS: [f32; 2] = [0.06, 0.12];

/// Steps above the refined planks' `widths` that step 6 also tries ([`rougher_variants`]).
///
/// Ours: rows whose edges move up to ±¼ (`widths` 0.5, the searched range) still put the
/// pattern's power into the harmonics of one period; up to ±½ (`widths` 1) the fundamental's
/// peak falls by 7.6 dB (planks at 17.5 px, bare pattern, four seeds: the ring at 17.4 px from
/// −11.3 dB to −18.9 dB, flat from 4.4 to 25 px). Measured on the fidelity protocol (seeds 1–6):
/// wood planks' spectrum ratio 1.66 → 1.62, old wood's 1.49 → 1.47, colour and structure within
/// ±0.02; steps of 0.15 and 0.3 within 0.5 gave 1.62 and 1.49. A smooth warp of the rows
/// (their edges where `y + A·noise(y/4)` is whole) was tried instead of the jitter: at the
/// same amplitude it spread the harmonics less (17.4 px: −12.6 dB) and, with the database
/// rebuilt, moved wood planks' ratios to 1.67 / 1.07 / 1.69: not kept.
const WIDTHS_STEPS: [f32; 2] = [0.25, 0.5];

/// The value that [`rougher_variants`] raises, per family (the first that the family
/// has), and its steps.
const IRREGULARITY_STEPS: [(&str, [f32; 2]); 2] =
    [("roughness", ROUGHNESS_STEPS), ("widths", WIDTHS_STEPS)];

/// Factors of a lattice family's scale (grid, brick, cells, planks) that step 6 also tries
/// ([`rougher_variants`]).
///
/// Ours: the descriptor's frequencies are an octave apart, so refinement leaves the scale of a
/// near-regular lattice uncertain by about ±10 %, while its spectrum is peaks (reptile skin's
/// scales: ~10 dB above the rings a quarter-octave away); step 6's spectrum distance has
/// quarter-octave rings. Measured on the fidelity protocol (seeds 1–6, spectrum difference to
/// the noise model): reptile skin `--model cells` −0.14 ± 0.16 → −0.19 ± 0.18, wood planks
/// +0.06 ± 0.14 → −0.03 ± 0.15, brick −0.36 → −0.35; colour and structure within ±0.04. Tried
/// on cells and not kept: jitter lowered by 0.15 and 0.3 (with the cells' variation halved and
/// quartered), warp raised by 0.1 and 0.2: within ±0.04.
const LATTICE_SCALE_STEPS: [f32; 2] = [0.9, 1.1];

/// The patterns step 6 of [`fit_structured`] tries: `pattern` itself and, for a family with a
/// `roughness`, the same with the roughness raised by [`ROUGHNESS_STEPS`] (within its range);
/// for planks, with their `widths` raised by [`WIDTHS_STEPS`] (within its range, past the
/// searched one); for the lattice families, at their scale times [`LATTICE_SCALE_STEPS`].
///
/// Ours: refinement minimises the descriptor's structure distance, which hardly sees the
/// finest octaves, while the ramp of a crack pattern whose coarse octaves are too strong puts
/// more power in the coarse rings than the photo has (hacienda's ridged ramp: +3.9 and +5.5 dB
/// at 41 and 59 px) and the residual can only add power. A rougher pattern shifts its power
/// towards the fine octaves; step 6's score (spectrum, colour and structure of the render)
/// decides whether that pays. Measured on the fidelity protocol (seeds 1–6), with all six
/// amplitude choices tried on each candidate: hacienda's spectrum ratio 1.13 → 1.07 (the noise
/// model's 1.09), colour 1.02 → 1.03, structure 1.73 → 1.69; wood planks' spectrum 1.78 →
/// 1.75. Reusing the refined pattern's choice (as here), at a third of the extra work, moved
/// the spectrum ratios by 0.01 or less on hacienda, planks, old wood, black rock and gravel,
/// and rock wall's 1.14 → 1.09 (colour 1.20 → 1.26; docs/measurements.md). Hacienda's refined fits sit at 0.87–0.9, hence ridged's
/// range up to 1 ([`crate::pattern::ValueSpec::search_max`]).
fn rougher_variants(pattern: &Pattern) -> Vec<Pattern> {
    let mut out = vec![pattern.clone()];
    if matches!(
        pattern.kind,
        PatternKind::Grid | PatternKind::Brick | PatternKind::Cells | PatternKind::Planks
    ) {
        out.extend(LATTICE_SCALE_STEPS.map(|f| Pattern {
            scale: pattern.scale * f,
            ..pattern.clone()
        }));
    }
    let Some((spec, steps)) = IRREGULARITY_STEPS.iter().find_map(|&(name, steps)| {
        let spec = pattern.kind.specs().iter().find(|s| s.name == name)?;
        Some((spec, steps))
    }) else {
        return out;
    };
    let r = pattern
        .values
        .get(spec.name)
        .copied()
        .unwrap_or(spec.default);
    let mut last = r;
    for step in steps {
        let v = (r + step).min(spec.max);
        if v - last > 0.02 {
            let mut p = pattern.clone();
            p.values.insert(spec.name.into(), v);
            out.push(p);
            last = v;
        }
    }
    out
}

/// The distance to another patch of the photo that a render at distance `d` from the analysed
/// patch is expected to have, in units of the photo's own patch-to-patch distance `unit`:
/// `√(1 + (d / unit)²)`, the render's error and the photo's own variation adding in
/// quadrature as independent errors do. Step 6 sums it over the three distances.
fn predicted_ratio(d: f64, unit: f64) -> f64 {
    (1.0 + (d / unit).powi(2)).sqrt()
}

/// Strengths `α` of the residual gain `g` that [`fit_structured`] tries (the residual's
/// amplitude times `g^α`).
const RESIDUAL_GAIN_STRENGTHS: [f64; 3] = [0.0, 0.5, 1.0];

/// Step 6 (ours): each residual channel that grows (`grow > 1`) is drawn Gaussian, with the
/// mean and spread its histogram gives it ([`crate::histogram::gaussian_knots`]), before it is
/// scaled.
///
/// Why: a residual grows to supply fine grain that the rendered ramp lacks and the analysed
/// residual does not hold (the rank pairing gave the photo's grain along its tone line to the
/// ramp), so the analysed residual's histogram does not describe what is added. That histogram
/// is the photo's colour off the tone line, whose tails are structure the ramp misses (mortar
/// of another hue than the bricks' lighter pixels): coherent lines and patches in the photo,
/// isolated pixels once drawn as noise and multiplied by the gain. Measured on the development
/// set (`proctex fidelity --set`, every quadrant, the chosen model's synthesis within 1.5× the
/// photo's specks): 143 → 154 of 208 patches (grid 2 → 9 of 10, turbulence 17 → 19 of 27,
/// cells 3 → 4 of 9, none fewer), the same 208 choices but one, structured fidelity
/// ln(auto/noise) −0.249 ± 0.046 → −0.263 ± 0.050, stochastic −0.131 → −0.133; the red brick
/// wall's planks 1.7 → 0.67 % specks (its photo 0.28 %). A channel that does not grow keeps
/// its histogram (Lagae's model), and step 6's score chooses between the two as between every
/// amplitude.
fn gaussian_where_grown(noise: &mut NoiseModel, grow: [f64; 3]) {
    if !noise.histogram.enabled {
        return;
    }
    for (c, &g) in grow.iter().enumerate() {
        if g > 1.0 {
            noise.histogram.knots[c] = crate::histogram::gaussian_knots(&noise.histogram.knots[c]);
        }
    }
}

/// Largest factor by which [`fit_structured`] may grow the residual's amplitude.
const MAX_RESIDUAL_GAIN: f64 = 100.0;

/// The residual's amplitude times `gain` per decorrelated channel: its histogram's knots (kept
/// in their valid range) when histogram matching is on, else its band weights; and the finest
/// band's part after the histogram.
fn scale_residual(noise: &mut NoiseModel, gain: [f64; 3]) {
    for (c, &g) in gain.iter().enumerate() {
        let g = g.min(MAX_RESIDUAL_GAIN) as f32;
        if noise.histogram.enabled {
            noise.histogram.knots[c]
                .iter_mut()
                .for_each(|v| *v = (*v * g).clamp(-2.0, 2.0));
        } else {
            noise.weights[c].iter_mut().for_each(|v| *v *= g);
        }
        noise.fine[c] = (noise.fine[c] * g).min(4.0);
    }
}

/// [`fit_structured`] without the output tone curve, with the noise tile of `opts.seed`
/// supplied (to share it across fits): what retrieval ranks, many times per photo.
pub fn fit_structured_with(
    photo: &Photo,
    pattern: &Pattern,
    opts: &Options,
    swapped: bool,
    tile: &Tile,
) -> Analysis {
    let mut a = fit_structured_gains(photo, pattern, opts, swapped, tile).0;
    if opts.fine_gaussian
        && let Model::Structured(m) = &mut a.params.model
    {
        m.residual.finest_band_gaussian();
    }
    a
}

/// [`fit_structured_with`] with step 6's residual amplitude `g^alpha` applied
/// ([`grow_residual`]), without the output tone curve: one candidate of step 6 as the ranking
/// would see it (for laboratories that compare the ranking's fits across amplitudes).
pub fn fit_structured_grown(
    photo: &Photo,
    pattern: &Pattern,
    opts: &Options,
    swapped: bool,
    tile: &Tile,
    alpha: f64,
) -> Analysis {
    let (mut a, gains, balance) = fit_structured_gains(photo, pattern, opts, swapped, tile);
    if let Model::Structured(m) = &mut a.params.model {
        grow_residual(m, gains, &balance, alpha, opts.fine_gaussian);
    }
    a
}

/// Step 6's residual amplitude `alpha` applied to a fitted model: the residual grown by
/// `g^alpha` per channel (`gains`: [`compensate_spectrum`]'s `g`), drawn Gaussian where it grows,
/// the ramp contracted by as much variance ([`Balance::contract_ramp`]), and the finest band
/// drawn Gaussian when `fine_gaussian`.
fn grow_residual(
    m: &mut StructuredModel,
    gains: [f64; 3],
    balance: &Balance,
    alpha: f64,
    fine_gaussian: bool,
) {
    let grow = gains.map(|g| g.max(1.0).powf(alpha));
    gaussian_where_grown(&mut m.residual, grow);
    scale_residual(&mut m.residual, grow);
    balance.contract_ramp(&mut m.ramp, grow);
    if fine_gaussian {
        m.residual.finest_band_gaussian();
    }
}

/// The variances that [`fit_structured`]'s step 6 keeps in balance: a residual grown by `g`
/// adds variance that the rank pairing had given to the ramp, so the ramp gives it back.
#[derive(Clone, Copy, Debug)]
struct Balance {
    /// Mean RGB of the rendered ramp (`ramp(s)` over the pattern's structure image).
    ramp_mean: [f32; 3],
    /// Variance of the residual in each of its decorrelated channels.
    residual_var: [f64; 3],
    /// Total (RGB) variance of the photo.
    photo_var: f64,
}

impl Balance {
    /// Ours (step 6): with the residual grown by `grow` per channel, the ramp's stops are
    /// pulled towards the rendered ramp's mean by `β = √((V_photo − V_grown) / (V_photo −
    /// V_residual))` (at least ½; `V` total variances), so that ramp and residual together
    /// keep the photo's variance: least squares leaves the residual uncorrelated with the
    /// ramp, so `V_photo − V_residual` is the ramp's share, and `β = 1` when nothing grows.
    /// Why: the rank pairing gives the ramp all of the photo's variance along the tone line,
    /// fine grain included (the structure map is the photo's own projection), while the grain
    /// that the rendered pattern lacks is the residual's to draw. Growing the residual without
    /// taking that variance back from the ramp widened the render's distribution, the colour
    /// distance then outweighed the spectrum's gain in step 6's score, and the residual stayed
    /// weak (hacienda: its render 2–3 dB short in the quarter-octave rings of 3–10 px).
    fn contract_ramp(&self, ramp: &mut [RampStop], grow: [f64; 3]) {
        let base: f64 = self.residual_var.iter().sum();
        let share = self.photo_var - base;
        if share <= 1e-12 {
            return;
        }
        let grown: f64 = (0..3)
            .map(|c| grow[c].min(MAX_RESIDUAL_GAIN).powi(2) * self.residual_var[c])
            .sum();
        let beta = ((self.photo_var - grown).max(0.0) / share)
            .sqrt()
            .clamp(0.5, 1.0) as f32;
        for stop in ramp {
            for c in 0..3 {
                let m = self.ramp_mean[c];
                stop.rgb[c] = (m + beta * (stop.rgb[c] - m)).clamp(0.0, 1.0);
            }
        }
    }
}

/// [`fit_structured_with`], also returning [`compensate_spectrum`]'s residual gains and the
/// variances of step 6.
fn fit_structured_gains(
    photo: &Photo,
    pattern: &Pattern,
    opts: &Options,
    swapped: bool,
    tile: &Tile,
) -> (Analysis, [f64; 3], Balance) {
    let (w, h) = (photo.width, photo.height);
    let n = photo.pixels.len();
    let tt = two_tone(photo);
    let s_img = structure_image(pattern, opts.seed, tile, w, h);

    // Rank pairing: photo pixel of rank r ↔ pattern value of rank r.
    let mut s_sorted = s_img.clone();
    crate::radix::sort(&mut s_sorted);
    let keys: Vec<f32> = tt
        .structure
        .iter()
        .map(|&t| if swapped { 1.0 - t } else { t })
        .collect();
    // Ties (flat photo regions) in index order: deterministic.
    let order = crate::radix::argsort(&keys);
    let mut paired = vec![0.0f32; n];
    for (r, &i) in order.iter().enumerate() {
        paired[i as usize] = s_sorted[r];
    }

    // Stops at the pattern's quantiles, merged where (nearly) equal.
    let mut at: Vec<f32> = (0..FIT_STOPS)
        .map(|k| s_sorted[((n - 1) * k) / (FIT_STOPS - 1)].clamp(0.0, 1.0))
        .collect();
    at.dedup_by(|b, a| *b - *a < 1e-4);
    if at.len() < 2 {
        at = vec![0.0, 1.0];
    }

    // Least squares over hat functions: tridiagonal normal equations, ridge towards the mean.
    let k = at.len();
    let mean = {
        let mut m = [0.0f64; 3];
        for p in &photo.pixels {
            for c in 0..3 {
                m[c] += p[c] as f64;
            }
        }
        m.map(|v| v / n as f64)
    };
    let mut diag = vec![0.0f64; k];
    let mut off = vec![0.0f64; k]; // off[i]: entry (i, i+1)
    let mut rhs = vec![[0.0f64; 3]; k];
    for (x, &sv) in paired.iter().enumerate() {
        let (i, f) = hat(&at, sv);
        let px = photo.pixels[x];
        let (wa, wb) = (1.0 - f as f64, f as f64);
        diag[i] += wa * wa;
        for c in 0..3 {
            rhs[i][c] += wa * px[c] as f64;
        }
        if wb > 0.0 {
            diag[i + 1] += wb * wb;
            off[i] += wa * wb;
            for c in 0..3 {
                rhs[i + 1][c] += wb * px[c] as f64;
            }
        }
    }
    let ridge = 1e-6 * n as f64 + 1e-9;
    for i in 0..k {
        diag[i] += ridge;
        for c in 0..3 {
            rhs[i][c] += ridge * mean[c];
        }
    }
    let colours = solve_tridiagonal(&diag, &off, &rhs);
    let ramp: Vec<RampStop> = at
        .iter()
        .zip(&colours)
        .map(|(&a, c)| RampStop {
            at: a,
            rgb: c.map(|v| (v as f32).clamp(0.0, 1.0)),
        })
        .collect();

    // The residual, around the photo's mean so that it is a colour image to analyse.
    let rows: Vec<[f32; 4]> = ramp
        .iter()
        .map(|s| [s.rgb[0], s.rgb[1], s.rgb[2], s.at])
        .collect();
    let mean32 = mean.map(|v| v as f32);
    let residual = Photo {
        width: w,
        height: h,
        pixels: photo
            .pixels
            .iter()
            .zip(&paired)
            .map(|(p, &sv)| {
                let r = ramp_rows(&rows, sv);
                [0, 1, 2].map(|c| p[c] - r[c] + mean32[c])
            })
            .collect(),
    };
    // The residual has no tone curve of its own (the structured model's applies last).
    // Nor is its finest band split from its histogram yet: step 4 sets the band weights.
    let residual_opts = Options {
        tone: false,
        fine_gaussian: false,
        ..*opts
    };
    // Its channels: the photo's tone line, then the colour across it (see
    // `colour::pca_with_first_axis`).
    let tone_line = [0, 1, 2].map(|c| (tt.tones[1][c] - tt.tones[0][c]) as f64);
    let mut analysis = analyze_prepared_in(
        &residual,
        &residual_opts,
        crate::colour::pca_with_first_axis(&residual.pixels, tone_line),
    );
    let mut noise = match &analysis.params.model {
        Model::Noise(nm) => nm.clone(),
        Model::Structured(s) => s.residual.clone(),
    };
    let gains = compensate_spectrum(
        photo,
        &residual,
        &s_img,
        &rows,
        &analysis.params.colour,
        opts,
        &mut noise.weights,
    );
    let balance = {
        let variance = |px: &mut dyn Iterator<Item = [f32; 3]>| -> ([f64; 3], [f64; 3]) {
            let (mut s1, mut s2) = ([0.0f64; 3], [0.0f64; 3]);
            for p in px {
                for c in 0..3 {
                    s1[c] += p[c] as f64;
                    s2[c] += (p[c] as f64).powi(2);
                }
            }
            let m = s1.map(|v| v / n as f64);
            (
                m,
                [0, 1, 2].map(|c| (s2[c] / n as f64 - m[c] * m[c]).max(0.0)),
            )
        };
        let (ramp_mean, _) = variance(&mut s_img.iter().map(|&sv| ramp_rows(&rows, sv)));
        let (_, photo_var) = variance(&mut photo.pixels.iter().copied());
        let basis = analysis.params.colour.basis;
        let (_, residual_var) = variance(&mut residual.pixels.iter().map(|p| {
            let d = [0, 1, 2].map(|k| p[k] - mean32[k]);
            basis.map(|b| b[0] * d[0] + b[1] * d[1] + b[2] * d[2])
        }));
        Balance {
            ramp_mean: ramp_mean.map(|v| v as f32),
            residual_var,
            photo_var: photo_var.iter().sum(),
        }
    };
    analysis.params.colour.mean = analysis.params.colour.mean.map(|v| v.clamp(0.0, 1.0));
    analysis.params.model = Model::Structured(StructuredModel {
        pattern: pattern.clone(),
        ramp,
        residual: noise,
        tone: None,
    });
    (analysis, gains, balance)
}

/// Step 4 (ours, not in the two-tone paper): the residual's spectrum made up for the pattern's.
///
/// The render is `ramp(s) + residual` with the two independent, so their power spectra add.
/// The residual measured under the rank pairing has the spectrum of `photo − ramp(ŝ)`, where
/// `ŝ` is the photo's own structure; the rendered pattern's `ramp(s)` has its own spectrum,
/// which differs (sharper joints, another scale). So in the residual's channel along the
/// photo's tone line (its first), band by band, the residual gets the power the photo has and
/// the rendered ramp lacks:
/// `target_k = max(P_photo,k − P_ramp,k, P_photo,k / 20)` (band powers deconvolved as in the
/// analysis, linear values: spectra of sums add only before any histogram map), and each weight
/// is scaled by `√(target_k / P_residual,k)`. The weights are then rescaled to their former
/// sum of squares: with histogram matching on, that sum is what the inverse CDF expects, and the
/// residual's total variance is the histogram's. Gains: spectrum ratios of the fidelity table
/// (docs/measurements.md).
///
/// The two colour channels are left as measured: the structure the pattern lacks varies along
/// the tone line, and giving each channel of the residual's own principal axes its share of the
/// missing power (as before) drew it as independent noise on axes that mix luminance and
/// colour: saturated blue and yellow blotches on a grey-blue rubble wall, whose render's
/// blue-minus-yellow deviation was 27 of 255 against the photo's 5.7 (5.7 with this). The
/// measurement over the development set: docs/devset.md, "The residual's colour".
///
/// Returns, per channel, the factor `√(Σ_k target_k / Σ_k P_residual,k)` by which the
/// residual's amplitude would have to grow to carry the target power (step 6 of
/// [`fit_structured`]); 1 for a channel left alone.
fn compensate_spectrum(
    photo: &Photo,
    residual: &Photo,
    s_img: &[f32],
    rows: &[[f32; 4]],
    colour: &Colour,
    opts: &Options,
    weights: &mut [Vec<f32>; 3],
) -> [f64; 3] {
    // Only the first channel, the tone line's: the structure the pattern lacks is a
    // variation along it; the colour channels keep the residual's own spectra.
    let mut gains = [1.0f64; 3];
    let (w, h) = (photo.width as usize, photo.height as usize);
    let nb = crate::spectrum::num_bands(w, h);
    let wc = &mut weights[0];
    if wc.len() != nb {
        return gains;
    }
    let power = |px: &mut dyn Iterator<Item = [f32; 3]>| channel_powers(colour, 0, px, w, h, opts);
    let p_photo = power(&mut photo.pixels.iter().copied());
    let p_ramp = power(&mut s_img.iter().map(|&sv| {
        let r = ramp_rows(rows, sv);
        [r[0], r[1], r[2]]
    }));
    let p_res = power(&mut residual.pixels.iter().copied());
    let before: f64 = wc.iter().map(|&v| (v as f64).powi(2)).sum();
    for k in 0..nb {
        let target = (p_photo[k] - p_ramp[k]).max(p_photo[k] / 20.0);
        if p_res[k] > 1e-12 {
            wc[k] = (wc[k] as f64 * (target / p_res[k]).sqrt()) as f32;
        }
    }
    let after: f64 = wc.iter().map(|&v| (v as f64).powi(2)).sum();
    if after > 1e-20 {
        let g = (before / after).sqrt();
        gains[0] = 1.0 / g;
        for v in wc.iter_mut() {
            *v = (*v as f64 * g) as f32;
        }
    }
    gains
}

/// The band powers (as the analysis estimates them: weights squared) of decorrelated channel
/// `c` of `colour` over a `w × h` image's pixels `px`: what [`compensate_spectrum`] predicts.
fn channel_powers(
    colour: &Colour,
    c: usize,
    px: &mut dyn Iterator<Item = [f32; 3]>,
    w: usize,
    h: usize,
    opts: &Options,
) -> Vec<f64> {
    let (b, m) = (colour.basis[c], colour.mean);
    let ch: Vec<f32> = px
        .map(|p| b[0] * (p[0] - m[0]) + b[1] * (p[1] - m[1]) + b[2] * (p[2] - m[2]))
        .collect();
    let nb = crate::spectrum::num_bands(w, h);
    let p = crate::spectrum::band_powers(&ch, w, h, nb, opts.periodic);
    crate::spectrum::estimate_weights(&p, opts.estimator)
        .iter()
        .map(|&v| (v as f64).powi(2))
        .collect()
}

/// The stop segment `i` and the fraction `f` towards stop `i + 1` of structure value `s`, as
/// [`ramp_rows`] interpolates (`f = 0` at and beyond the ends).
fn hat(at: &[f32], s: f32) -> (usize, f32) {
    let k = at.len();
    if s <= at[0] {
        return (0, 0.0);
    }
    for i in 1..k {
        if s < at[i] {
            return (i - 1, (s - at[i - 1]) / (at[i] - at[i - 1]));
        }
    }
    (k - 1, 0.0)
}

/// Solves the symmetric tridiagonal system (Thomas algorithm; the ridge keeps it positive
/// definite) for three right-hand sides.
fn solve_tridiagonal(diag: &[f64], off: &[f64], rhs: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let k = diag.len();
    let mut c = vec![0.0f64; k];
    let mut d = vec![[0.0f64; 3]; k];
    let mut denom = diag[0];
    c[0] = if k > 1 { off[0] / denom } else { 0.0 };
    d[0] = rhs[0].map(|v| v / denom);
    for i in 1..k {
        denom = diag[i] - off[i - 1] * c[i - 1];
        c[i] = if i + 1 < k { off[i] / denom } else { 0.0 };
        for ch in 0..3 {
            d[i][ch] = (rhs[i][ch] - off[i - 1] * d[i - 1][ch]) / denom;
        }
    }
    let mut x = d.clone();
    for i in (0..k - 1).rev() {
        for ch in 0..3 {
            x[i][ch] = d[i][ch] - c[i] * x[i + 1][ch];
        }
    }
    x
}

#[cfg(test)]
mod tests;
