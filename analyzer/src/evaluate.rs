//! The fidelity protocol ([`fidelity`]): synthesise from one patch of a photo and compare with
//! another patch, relative to the distance between the two patches themselves (the distances:
//! [`crate::distance`]); the syntheses it judges, and the floor that a random-phase Gaussian
//! model reaches.

use crate::analyze::{Analysis, Options};
use crate::colour::pca;
use crate::distance::{Distances, distances};
use crate::error::Result;
use crate::heeger_bergen::RasterOptions;
use crate::input::{Crop, Photo};
use crate::render::{View, render};
use crate::retrieve::{ModelChoice, Refinement, Suggestion, analyze_photo_model_progress};
use crate::rng;
use crate::spectrum::{fft2_real, ifft2, spectrum_real};

/// The best a stationary Gaussian model with histogram matching can do with `photo`: each
/// decorrelated channel keeps its own power spectrum exactly (of its periodic component, so no
/// border cross) with independent random phases, and is then rank-matched to the channel's
/// exact distribution. Any model of Lagae's family (any band structure, any spectrum shape)
/// is at best this; the fidelity table reports its ratio as the floor.
pub fn random_phase(photo: &Photo, seed: u32) -> Photo {
    let (w, h) = (photo.width as usize, photo.height as usize);
    let n = w * h;
    let p = pca(&photo.pixels);
    let mut out = vec![[0.0f32; 3]; n];
    for c in 0..3 {
        let axis = p.basis[c];
        let chan: Vec<f32> = photo
            .pixels
            .iter()
            .map(|px| {
                (0..3)
                    .map(|k| axis[k] * (px[k] as f64 - p.mean[k]))
                    .sum::<f64>() as f32
            })
            .collect();
        let spec = spectrum_real(&chan, w, h, true);
        // Unit-modulus Hermitian phases: the normalised spectrum of real white noise.
        let noise: Vec<f32> = (0..n)
            .map(|i| rng::gaussian(seed, 0x7068_6173 + c as u32, i as u32) as f32)
            .collect();
        let phases = fft2_real(&noise, w, h);
        let shuffled: Vec<_> = spec
            .iter()
            .zip(&phases)
            .map(|(s, ph)| {
                let m = ph.norm();
                if m > 0.0 { s * (ph / m) } else { *s }
            })
            .collect();
        let field = ifft2(shuffled, w, h);
        // Exact rank matching to the channel's own values.
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| field[a].re.total_cmp(&field[b].re));
        let mut sorted = chan.clone();
        sorted.sort_unstable_by(f32::total_cmp);
        for (rank, &i) in order.iter().enumerate() {
            let v = sorted[rank] as f64;
            for k in 0..3 {
                out[i][k] += (v * axis[k]) as f32;
            }
        }
    }
    for px in &mut out {
        for k in 0..3 {
            px[k] = (px[k] + p.mean[k] as f32).clamp(0.0, 1.0);
        }
    }
    Photo {
        width: photo.width,
        height: photo.height,
        pixels: out,
    }
}

/// Result of the fidelity protocol on one photo.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Fidelity {
    /// Distance between the two halves of the photo.
    pub halves: Distances,
    /// Mean distance between a synthesis from one half and the other half.
    pub synthesis: Distances,
    /// `synthesis.spectrum_db / halves.spectrum_db`.
    pub spectrum_ratio: f64,
    /// `synthesis.colour / halves.colour`.
    pub colour_ratio: f64,
    /// `synthesis.structure / halves.structure`.
    pub structure_ratio: f64,
    /// Mean distance between the random-phase floor ([`random_phase`]) of one patch and the
    /// other patch.
    pub floor: Distances,
    /// `floor.spectrum_db / halves.spectrum_db`: the best ratio a Gaussian model can reach.
    pub floor_spectrum_ratio: f64,
    /// `floor.colour / halves.colour`.
    pub floor_colour_ratio: f64,
    /// `floor.structure / halves.structure`.
    pub floor_structure_ratio: f64,
    /// The mean distance of the syntheses from each of the four source patches (top-left,
    /// bottom-left, top-right, bottom-right) to the other patch of its pair: what
    /// [`ratio_difference`] pairs.
    pub per_patch: [Distances; 4],
    /// Whether the photo's quadrants repeat ([`quadrants_repeat`]): then top-left and
    /// bottom-right are one patch, bottom-left and top-right another.
    pub repeat: bool,
}

/// The difference of two models' fidelity ratios on one photo (`a` − `b`, both measured with
/// the same seeds), and its standard error: the per-patch differences of mean distance over
/// `halves`, averaged over the distinct source patches, the error their spread over `√n`:
/// four patches, or two where the quadrants repeat (each the mean of its two copies). The
/// patches, not the syntheses, are the independent samples: the syntheses from one patch
/// share its pixels, and the seeds only vary the render (a model that fits one patch's
/// peculiarities is as wrong with every seed). Four samples make a rough error, but an honest
/// one: a difference within it is not evidence that either model is better on that photo.
pub fn ratio_difference(a: &Fidelity, b: &Fidelity) -> (Distances, Distances) {
    let mut diffs: Vec<Distances> = a
        .per_patch
        .iter()
        .zip(&b.per_patch)
        .map(|(x, y)| {
            x.zip(*y, |p, q| p - q)
                .zip(a.halves, |d, h| d / h.max(1e-9))
        })
        .collect();
    if a.repeat {
        // Top-left with bottom-right, bottom-left with top-right: one patch each.
        let mean2 = |i: usize, j: usize| diffs[i].zip(diffs[j], |x, y| (x + y) / 2.0);
        diffs = vec![mean2(0, 3), mean2(1, 2)];
    }
    let n = diffs.len() as f64;
    let mean = diffs
        .iter()
        .fold(Distances::ZERO, |acc, d| acc.zip(*d, |x, y| x + y / n));
    let var = diffs.iter().fold(Distances::ZERO, |acc, d| {
        let dev = d.zip(mean, |x, m| x - m);
        acc.zip(dev, |x, v| x + v * v / (n - 1.0))
    });
    (mean, var.zip(Distances::ZERO, |v, _| (v / n).sqrt()))
}

/// Analyses with the noise model and renders a texture of exactly the photo's pixel size.
pub fn synthesize(photo: &Photo, opts: &Options) -> Result<Photo> {
    Ok(synthesize_model(photo, opts, ModelChoice::Noise, Refinement::NONE)?.0)
}

/// Analyses with the chosen model and renders a texture of exactly the photo's pixel size
/// (what `proctex synth` does); also returns the analysis and the ranked suggestions.
pub fn synthesize_model(
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
) -> Result<(Photo, Analysis, Vec<Suggestion>)> {
    synthesize_model_progress(photo, opts, choice, refinement, &|_, _| true)
}

/// [`synthesize_model`] with the refinement's `progress`
/// ([`crate::retrieve::analyze_with_model_progress`]).
pub fn synthesize_model_progress(
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Result<(Photo, Analysis, Vec<Suggestion>)> {
    let (a, suggestions) = analyze_photo_model_progress(photo, opts, choice, refinement, progress)?;
    Ok((
        render_params_at_photo_size(&a.params, photo),
        a,
        suggestions,
    ))
}

/// The realisations of the analysis' texture that `render` says (at least one), each at
/// exactly the photo's pixel size.
fn renders_at_photo_size(a: &Analysis, photo: &Photo, render: RenderSeed) -> Vec<Photo> {
    match render {
        RenderSeed::Fitted => vec![render_params_at_photo_size(&a.params, photo)],
        RenderSeed::Unseen(k) => (0..k.max(1))
            .map(|j| {
                let p = crate::params::Params {
                    seed: a
                        .params
                        .seed
                        .wrapping_add(UNSEEN_SEED_OFFSET)
                        .wrapping_add(j),
                    ..a.params.clone()
                };
                render_params_at_photo_size(&p, photo)
            })
            .collect(),
    }
}

/// Which realisation of an analysed model the fidelity protocol scores.
///
/// The analysis fits some of its numbers on renders at its own seed (the structured fit scores
/// its amplitudes and variants on the seed's render, and its output tone curve pools that
/// render with the next three seeds'), so the seed's render is partly fitted to the photo's
/// realisation: what a user sees at the texture's origin, not what a tile or any other part of
/// the infinite texture shows. On the development set the automatic choice's overall ratio on
/// the structured photos was 7 % worse on an unseen realisation (paired ln +0.070 ± 0.022; the
/// noise model alone, whose tone curve is fitted on other seeds, +0.002 ± 0.010;
/// docs/devset.md).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RenderSeed {
    /// The analysis seed's render (the view the app opens on).
    #[default]
    Fitted,
    /// The renders at the analysis seed + [`UNSEEN_SEED_OFFSET`] + 0, 1, … (this many, at
    /// least one; their distances averaged): no step of the fit drew them. One realisation is
    /// one draw of the pieces a patch holds (a few bricks or planks, each with its own shade),
    /// so a paired comparison of two builds scatters less with several.
    Unseen(u32),
}

/// How far [`RenderSeed::Unseen`] moves the seed: past every seed the fit renders (the tone
/// curves pool at most four after the analysis seed; the noise model's own fit seeds are
/// `noise_tone::FIT_SEED` on).
pub const UNSEEN_SEED_OFFSET: u32 = 1000;

/// `params` rendered over `photo`'s pixels, one world unit per pixel (as the fidelity
/// protocol's syntheses are).
pub fn render_params_at_photo_size(params: &crate::params::Params, photo: &Photo) -> Photo {
    let world_per_pixel = 1.0; // world units are photo pixels
    render(
        params,
        photo.width,
        photo.height,
        &View {
            pixel_size: world_per_pixel,
            ..View::default()
        },
    )
    .to_photo()
}

/// The photo's quadrants, each half its size: top-left, top-right, bottom-left, bottom-right.
pub fn quadrants(photo: &Photo) -> Result<[Photo; 4]> {
    let (hw, hh) = (photo.width / 2, photo.height / 2);
    let quad = |x: u32, y: u32| photo.crop(Crop { x, y, w: hw, h: hh });
    let (right, bottom) = (photo.width - hw, photo.height - hh);
    Ok([
        quad(0, 0)?,
        quad(right, 0)?,
        quad(0, bottom)?,
        quad(right, bottom)?,
    ])
}

/// Mean absolute difference per colour value (0–1) below which [`quadrants_repeat`] counts
/// two quadrants as one patch (copies on the samples: 0.0003; distinct patches of one
/// material: 0.07 and more).
pub const REPEAT_TOLERANCE: f64 = 0.01;

/// Whether the photo's top-right quadrant repeats its bottom-left and its bottom-right its
/// top-left (within [`REPEAT_TOLERANCE`]), as in several game textures that are a tile laid
/// 2×2 with an offset: then the fidelity protocol's second pair (top-right, bottom-right) is
/// its first (top-left, bottom-left) with the roles swapped, its syntheses the same (the
/// analysis sees nearly the same pixels), and only two of the four source patches are
/// distinct. The copies' syntheses still differ (a difference of 0.0003 can tip the refinement
/// to another family), so the protocol keeps all four and averages each patch's two copies.
/// Measured (2026-11-25): black rock, hacienda, mountain rock and rock wall (256² and 512²)
/// repeat (0.0003); old wood's copies differ by 0.015 and count as distinct (its two pairs
/// are 2.35 and 1.67 dB apart in spectrum, not alike); the other samples differ by 0.07–0.1.
pub fn quadrants_repeat(photo: &Photo) -> Result<bool> {
    let [tl, tr, bl, br] = quadrants(photo)?;
    let mad = |a: &Photo, b: &Photo| {
        let sum: f64 = a
            .pixels
            .iter()
            .zip(&b.pixels)
            .map(|(p, q)| (0..3).map(|c| (p[c] - q[c]).abs() as f64).sum::<f64>())
            .sum();
        sum / (3 * a.pixels.len().max(1)) as f64
    };
    Ok(mad(&tr, &bl) < REPEAT_TOLERANCE && mad(&br, &tl) < REPEAT_TOLERANCE)
}

/// The fidelity protocol: quadrants top-left/bottom-left and top-right/bottom-right of the
/// photo are pairs (A, B) of different patches of one material; synthesise from A (at A's pixel
/// size) and compare with B, and from B against A, for each seed; divide the mean distance by
/// the mean `d(A, B)`. (Quadrants stacked vertically, not the left and right halves: several
/// game textures are 2×2 tilings with a half-tile offset whose right half is the left half
/// shifted, which would make `d(A, B)` zero.) Where the quadrants repeat
/// ([`quadrants_repeat`]), the second pair is the first swapped: [`ratio_difference`] then
/// counts two independent patches, not four.
pub fn fidelity(
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
    seeds: &[u32],
) -> Result<Fidelity> {
    fidelity_by(
        photo,
        opts,
        Synthesiser::Model(choice, refinement, RenderSeed::Fitted),
        seeds,
        &mut |_| {},
    )
}

/// One synthesis of the fidelity protocol, as [`fidelity_by`] reports it.
#[derive(Debug)]
pub struct SynthesisRun<'a> {
    /// The source patch: 0 top-left, 1 bottom-left, 2 top-right, 3 bottom-right (the order of
    /// [`Fidelity::per_patch`]).
    pub patch: usize,
    /// The seed of this synthesis.
    pub seed: u32,
    /// The candidates ranked for the patch, nearest first (empty for the noise model alone).
    pub ranking: &'a [Suggestion],
    /// Wall time of the patch's analysis (model choice included, the render not), milliseconds.
    pub analysis_ms: f64,
    /// The synthesis' distances to the other patch of its pair (its realisations' mean).
    pub distances: Distances,
    /// The source patch and the synthesis (rendered at the patch's size; its first
    /// realisation).
    pub source: &'a Photo,
    pub synthesis: &'a Photo,
}

/// What makes the syntheses of the fidelity protocol.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Synthesiser {
    /// A procedural model: analysed with this choice and refinement, rendered at the patch's
    /// pixel size with the realisation that the [`RenderSeed`] says.
    Model(ModelChoice, Refinement, RenderSeed),
    /// The Heeger–Bergen raster synthesis from the patch itself, of the patch's size (the
    /// options' size and seed are set per synthesis).
    Pyramid(RasterOptions),
}

/// The fidelity protocol with any [`Synthesiser`], reporting every synthesis to `observe` as it
/// is made (which model each source patch got, how long its analysis took): what the
/// development-set yardstick tabulates.
pub fn fidelity_by(
    photo: &Photo,
    opts: &Options,
    synthesiser: Synthesiser,
    seeds: &[u32],
    observe: &mut dyn FnMut(SynthesisRun),
) -> Result<Fidelity> {
    let mut make = |src: &Photo, seed: u32| -> Result<Made> {
        let start = std::time::Instant::now();
        match synthesiser {
            Synthesiser::Model(choice, refinement, render) => {
                let o = Options { seed, ..*opts };
                let (analysis, ranking) =
                    analyze_photo_model_progress(src, &o, choice, refinement, &|_, _| true)?;
                let ms = start.elapsed().as_secs_f64() * 1000.0;
                Ok((renders_at_photo_size(&analysis, src, render), ranking, ms))
            }
            Synthesiser::Pyramid(raster) => {
                let raster = RasterOptions {
                    width: src.width,
                    height: src.height,
                    seed,
                    ..raster
                };
                let syn = crate::heeger_bergen::synthesize(src, &raster)?;
                Ok((
                    vec![syn],
                    Vec::new(),
                    start.elapsed().as_secs_f64() * 1000.0,
                ))
            }
        }
    };
    fidelity_core(photo, seeds, &mut make, observe)
}

/// The fidelity protocol with syntheses made by `synthesise(source patch, seed)` (of the
/// patch's size): for experiments with models that are not the product's (the labs).
pub fn fidelity_with(
    photo: &Photo,
    seeds: &[u32],
    synthesise: &mut dyn FnMut(&Photo, u32) -> Result<Photo>,
) -> Result<Fidelity> {
    let mut make = |src: &Photo, seed: u32| Ok((vec![synthesise(src, seed)?], Vec::new(), 0.0));
    fidelity_core(photo, seeds, &mut make, &mut |_| {})
}

/// What a synthesis of the protocol returns: the texture's realisations (at least one; the
/// protocol averages their distances), the ranking, the analysis' time (ms).
type Made = (Vec<Photo>, Vec<Suggestion>, f64);

fn fidelity_core(
    photo: &Photo,
    seeds: &[u32],
    make: &mut dyn FnMut(&Photo, u32) -> Result<Made>,
    observe: &mut dyn FnMut(SynthesisRun),
) -> Result<Fidelity> {
    let [tl, tr, bl, br] = quadrants(photo)?;
    let repeat = quadrants_repeat(photo)?;
    let pairs = [(tl, bl), (tr, br)];
    let (mut halves, mut synthesis, mut floor) =
        (Distances::ZERO, Distances::ZERO, Distances::ZERO);
    let mut n = 0.0;
    let mut per_patch = [Distances::ZERO; 4];
    for (pi, (a, b)) in pairs.iter().enumerate() {
        let d = distances(a, b);
        halves = halves.zip(d, |x, y| x + y / pairs.len() as f64);
        for &seed in seeds {
            for (di, (src, other)) in [(a, b), (b, a)].into_iter().enumerate() {
                let (syns, ranking, analysis_ms) = make(src, seed)?;
                let k = syns.len().max(1) as f64;
                let d = syns.iter().fold(Distances::ZERO, |acc, syn| {
                    acc.zip(distances(syn, other), |x, y| x + y / k)
                });
                let syn = &syns[0];
                observe(SynthesisRun {
                    patch: 2 * pi + di,
                    seed,
                    ranking: &ranking,
                    analysis_ms,
                    distances: d,
                    source: src,
                    synthesis: syn,
                });
                synthesis = synthesis.zip(d, |x, y| x + y);
                per_patch[2 * pi + di] =
                    per_patch[2 * pi + di].zip(d, |x, y| x + y / seeds.len() as f64);
                floor = floor.zip(distances(&random_phase(src, seed), other), |x, y| x + y);
                n += 1.0;
            }
        }
    }
    synthesis = synthesis.zip(Distances::ZERO, |x, _| x / n);
    floor = floor.zip(Distances::ZERO, |x, _| x / n);
    let ratio = |d: Distances| d.zip(halves, |x, y| x / y.max(1e-9));
    let (r, fr) = (ratio(synthesis), ratio(floor));
    Ok(Fidelity {
        halves,
        synthesis,
        spectrum_ratio: r.spectrum_db,
        colour_ratio: r.colour,
        structure_ratio: r.structure,
        floor,
        floor_spectrum_ratio: fr.spectrum_db,
        floor_colour_ratio: fr.colour,
        floor_structure_ratio: fr.structure,
        per_patch,
        repeat,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fidelity_with(halves: f64, per_patch: [f64; 4]) -> Fidelity {
        let d = |v: f64| Distances {
            spectrum_db: v,
            colour: v / 100.0,
            structure: 2.0 * v,
        };
        Fidelity {
            halves: d(halves),
            synthesis: d(per_patch.iter().sum::<f64>() / 4.0),
            spectrum_ratio: 0.0,
            colour_ratio: 0.0,
            structure_ratio: 0.0,
            floor: Distances::ZERO,
            floor_spectrum_ratio: 0.0,
            floor_colour_ratio: 0.0,
            floor_structure_ratio: 0.0,
            per_patch: per_patch.map(d),
            repeat: false,
        }
    }

    #[test]
    fn unseen_renders_are_the_seeds_past_the_offset_in_order() {
        let photo = random_patch(5, 32, 32);
        let a = Analysis {
            params: crate::analyze::hash_noise_params(32, 9),
            band_powers: Default::default(),
            channel_variance: [0.0; 3],
        };
        let at = |seed: u32| {
            let p = crate::params::Params {
                seed,
                ..a.params.clone()
            };
            render_params_at_photo_size(&p, &photo).pixels
        };
        let fitted = renders_at_photo_size(&a, &photo, RenderSeed::Fitted);
        assert_eq!(fitted.len(), 1);
        assert_eq!(fitted[0].pixels, at(a.params.seed));
        let unseen = renders_at_photo_size(&a, &photo, RenderSeed::Unseen(3));
        assert_eq!(unseen.len(), 3);
        for (j, r) in unseen.iter().enumerate() {
            assert_eq!(
                r.pixels,
                at(a.params.seed + UNSEEN_SEED_OFFSET + j as u32),
                "{j}"
            );
        }
        assert_ne!(unseen[0].pixels, unseen[1].pixels);
        // At least one realisation, whatever the count says.
        assert_eq!(
            renders_at_photo_size(&a, &photo, RenderSeed::Unseen(0)).len(),
            1
        );
    }

    #[test]
    fn ratio_difference_is_the_mean_over_patches_with_its_standard_error() {
        let a = fidelity_with(2.0, [3.0, 4.0, 5.0, 6.0]);
        let b = fidelity_with(2.0, [2.0; 4]);
        let (mean, se) = ratio_difference(&a, &b);
        // Per patch (a − b) / halves: 0.5, 1, 1.5, 2 (in every distance, each in its own units).
        let want_se = ((0.75f64.powi(2) + 0.25f64.powi(2)) * 2.0 / 3.0 / 4.0).sqrt();
        for (m, s) in [
            (mean.spectrum_db, se.spectrum_db),
            (mean.colour, se.colour),
            (mean.structure, se.structure),
        ] {
            assert!((m - 1.25).abs() < 1e-12, "{m}");
            assert!((s - want_se).abs() < 1e-12, "{s}");
        }
        // The mean is the difference of the two ratios the table prints.
        let (r, _) = ratio_difference(&a, &a);
        assert_eq!((r.spectrum_db, r.colour, r.structure), (0.0, 0.0, 0.0));
    }

    /// A `2w × 2h` photo whose quadrants are `tl`, `tr`, `bl`, `br`.
    fn laid(q: [&Photo; 4]) -> Photo {
        let (w, h) = (q[0].width, q[0].height);
        let mut pixels = Vec::with_capacity((4 * w * h) as usize);
        for y in 0..2 * h {
            for x in 0..2 * w {
                let k = (2 * (y / h) + x / w) as usize;
                pixels.push(q[k].get(x % w, y % h));
            }
        }
        Photo {
            width: 2 * w,
            height: 2 * h,
            pixels,
        }
    }

    fn random_patch(seed: u32, w: u32, h: u32) -> Photo {
        Photo {
            width: w,
            height: h,
            pixels: (0..w * h)
                .map(|i| {
                    let v = rng::uniform(seed, 0, i) as f32;
                    [v, 0.5 * v, 1.0 - v]
                })
                .collect(),
        }
    }

    #[test]
    fn quadrants_repeat_only_where_the_second_pair_is_the_first_swapped() {
        let (a, b, c, d) = (
            random_patch(1, 24, 16),
            random_patch(2, 24, 16),
            random_patch(3, 24, 16),
            random_patch(4, 24, 16),
        );
        // A tile laid 2×2 with an offset: top-right = bottom-left, bottom-right = top-left.
        assert!(quadrants_repeat(&laid([&a, &b, &b, &a])).unwrap());
        // JPEG-like noise between the copies still repeats.
        let mut b2 = b.clone();
        for p in &mut b2.pixels {
            p[0] = (p[0] + 0.003).min(1.0);
        }
        assert!(quadrants_repeat(&laid([&a, &b2, &b, &a])).unwrap());
        // Four different patches, or only one of the two copies: not a repeat.
        assert!(!quadrants_repeat(&laid([&a, &b, &c, &d])).unwrap());
        assert!(!quadrants_repeat(&laid([&a, &b, &b, &c])).unwrap());
        assert!(!quadrants_repeat(&laid([&a, &a, &a, &b])).unwrap());
    }

    #[test]
    fn ratio_difference_over_two_patches_counts_two_samples() {
        // A repeating photo: top-left = bottom-right (3, 3.2), bottom-left = top-right (4, 3.8).
        // Per patch (a − b) / halves: 0.55 and 0.95, the error |0.95 − 0.55| / 2. Counted as
        // four samples (0.5, 1, 0.9, 0.6) it would read about √3 too small.
        let mut a = fidelity_with(2.0, [3.0, 4.0, 3.8, 3.2]);
        let b = fidelity_with(2.0, [2.0; 4]);
        let four = ratio_difference(&a, &b);
        a.repeat = true;
        let (mean, se) = ratio_difference(&a, &b);
        assert!((mean.spectrum_db - 0.75).abs() < 1e-12);
        assert!((four.0.spectrum_db - 0.75).abs() < 1e-12);
        assert!((se.spectrum_db - 0.2).abs() < 1e-12, "{}", se.spectrum_db);
        assert!(four.1.spectrum_db < 0.7 * se.spectrum_db, "{:?}", four.1);
    }
}
