//! The analysis phase (Lagae §7): photo → parameters.
//!
//! 1. mean RGB and PCA rotation (§6, [`crate::colour`]);
//! 2. project onto the principal axes (decorrelated channels);
//! 3. optionally Gaussianize each channel and keep its inverse CDF knots (§5);
//! 4. band powers of each channel from one FFT per *two* channels (§4, [`crate::spectrum`]),
//!    then band weights.
//!
//! Step 4 packs two real channels into one complex FFT, so three channels cost two FFTs.

use crate::colour::pca;
use crate::error::{Error, Result};
use rustfft::num_complex::Complex32;

use crate::histogram::{ChannelStats, RANK_BINS, RankMap};
use crate::input::{Crop, Photo};
use crate::lighting::flatten_lighting;
use crate::noise_tone::{HISTOGRAM_INTERVALS, HistogramCandidate, allocate};
use crate::orientation;
use crate::params::{
    Colour, FORMAT, Histogram, MAX_KNOTS, Model, NoiseModel, Params, Source, Transform,
};
use crate::spectrum::{Estimator, Extras, band_spectra_packed, estimate_weights, num_bands};

/// Analysis options (the CLI flags of `proctex analyze`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Options {
    /// The photo is area-averaged until its longer side is at most this (256, 512, 1024, 2048).
    pub size: u32,
    /// Region of the photo to analyse.
    pub crop: Option<Crop>,
    /// Histogram matching (Lagae §5).
    pub histogram: bool,
    /// Knot intervals K of the inverse CDF (the paper uses 10).
    pub knots: usize,
    /// Seed stored in the params (tiles and band offsets).
    pub seed: u32,
    /// Band-weight estimator.
    pub estimator: Estimator,
    /// Periodic + smooth decomposition before the FFT.
    pub periodic: bool,
    /// Fit each band's orientation ([`crate::orientation`]); off: every band isotropic, as in
    /// Lagae et al.
    pub orientation: bool,
    /// Fit the noise model's output tone curve ([`crate::noise_tone`]; only with the
    /// histogram on); off: Lagae's independent channels alone.
    pub tone: bool,
    /// Draw the finest band after the histogram, apart from it (bounded:
    /// [`crate::params::NoiseModel::finest_band_gaussian`]); off: Lagae's histogram on the sum
    /// of every band.
    pub fine_gaussian: bool,
    /// Divide out the photo's lighting gradient before anything else
    /// ([`crate::lighting::flatten_lighting`]); off (the default): the pixels as they are.
    pub flatten_lighting: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            size: 512,
            crop: None,
            histogram: true,
            knots: 10,
            seed: 1,
            estimator: Estimator::Rings,
            periodic: true,
            orientation: true,
            tone: true,
            fine_gaussian: true,
            flatten_lighting: false,
        }
    }
}

/// Allowed analysis sizes.
pub const SIZES: [u32; 4] = [256, 512, 1024, 2048];

/// What an analysis found, beyond the params: for plots and tests.
#[derive(Clone, Debug, PartialEq)]
pub struct Analysis {
    /// The texture.
    pub params: Params,
    /// Measured band powers per decorrelated channel (after Gaussianization when on).
    pub band_powers: [Vec<f64>; 3],
    /// Variance of each decorrelated channel.
    pub channel_variance: [f64; 3],
}

impl Options {
    /// Checks the option values.
    pub fn validate(&self) -> Result<()> {
        if !SIZES.contains(&self.size) {
            return Err(Error::Option(format!(
                "analysis size {} is not one of 256, 512, 1024, 2048",
                self.size
            )));
        }
        if self.knots < 1 || self.knots + 1 > MAX_KNOTS {
            return Err(Error::Option(format!(
                "knot count {} is not in 1..={}",
                self.knots,
                MAX_KNOTS - 1
            )));
        }
        Ok(())
    }
}

/// Decodes, crops, reduces and analyses a photo file's bytes.
#[cfg(feature = "decode")]
pub fn analyze_bytes(bytes: &[u8], opts: &Options) -> Result<Analysis> {
    opts.validate()?;
    let photo = Photo::decode(bytes)?;
    analyze_photo(&photo, opts)
}

/// Crops, reduces and analyses a decoded photo.
pub fn analyze_photo(photo: &Photo, opts: &Options) -> Result<Analysis> {
    analyze_photo_with(photo, opts, analyze_prepared)
}

/// The photo the analysis sees: `opts.crop` of `photo`, checked, reduced to `opts.size`, its
/// lighting gradient divided out where `opts.flatten_lighting` says (what
/// [`analyze_photo_with`] hands its analysis).
pub fn prepare_photo(photo: &Photo, opts: &Options) -> Result<Photo> {
    let (region, reduced) = prepare_regions(photo, opts)?;
    Ok(reduced.or(region).unwrap_or_else(|| photo.clone()))
}

/// The crop (`None`: the photo itself) and its reduction, lighting flattened when the options
/// say (`None`: neither needed).
fn prepare_regions(photo: &Photo, opts: &Options) -> Result<(Option<Photo>, Option<Photo>)> {
    opts.validate()?;
    let cropped = match opts.crop {
        Some(c) => Some(photo.crop(c)?),
        None => None,
    };
    let region = cropped.as_ref().unwrap_or(photo);
    region.check_min_size()?;
    let reduced = region.reduced(opts.size);
    let reduced = if opts.flatten_lighting {
        Some(flatten_lighting(reduced.as_ref().unwrap_or(region)))
    } else {
        reduced
    };
    Ok((cropped, reduced))
}

/// Crops and reduces `photo` as `opts` say, runs `analysis` on the result, and stamps the
/// params with the world scale (one texel is one analysed pixel) and their provenance.
pub fn analyze_photo_with(
    photo: &Photo,
    opts: &Options,
    analysis: impl FnOnce(&Photo, &Options) -> Analysis,
) -> Result<Analysis> {
    let (region, reduced) = prepare_regions(photo, opts)?;
    let region = region.as_ref().unwrap_or(photo);
    let reduced: &Photo = reduced.as_ref().unwrap_or(region);
    let mut analysis = analysis(reduced, opts);
    // One texel is one analysed pixel; in world units (photo pixels) that is this many.
    analysis.params.transform.scale = region.width as f32 / reduced.width as f32;
    analysis.params.source = Some(Source {
        width: photo.width,
        height: photo.height,
        crop: opts.crop.map(|c| [c.x, c.y, c.w, c.h]),
        analysis_width: reduced.width,
        analysis_height: reduced.height,
        estimator: opts.estimator.name().into(),
        flattened_lighting: opts.flatten_lighting,
    });
    Ok(analysis)
}

/// The analysis proper, on an image already at analysis size (at least 32×32).
pub fn analyze_prepared(photo: &Photo, opts: &Options) -> Analysis {
    analyze_prepared_in(photo, opts, pca(&photo.pixels))
}

/// [`analyze_prepared`] with the colour statistics `p` of the photo's pixels given (its basis
/// the channels the noise is analysed in; a structured model's residual is analysed in a basis
/// whose first axis is the photo's tone line: [`crate::colour::pca_with_first_axis`]).
pub fn analyze_prepared_in(photo: &Photo, opts: &Options, p: crate::colour::Pca) -> Analysis {
    let (w, h) = (photo.width as usize, photo.height as usize);
    let n = w * h;
    let mean = p.mean.map(|m| m as f32);
    let basis = p.basis.map(|r| r.map(|v| v as f32));

    // Decorrelated channels, computed with the f32 basis actually stored (so that synthesis
    // inverts exactly what analysis measured). They are recomputed from the pixels in each pass
    // (nine multiply-adds) rather than stored: pass 1 takes their range, pass 2 their rank bins
    // (u16), pass 3 packs the Gaussianized values for the FFTs.
    let project = |px: &[f32; 3], c: usize| -> f32 {
        let b = basis[c];
        b[0] * (px[0] - mean[0]) + b[1] * (px[1] - mean[1]) + b[2] * (px[2] - mean[2])
    };
    // Range of each channel: four independent lanes of min/max so the chains do not serialise.
    let mut lo = [[f32::INFINITY; 3]; 4];
    let mut hi = [[f32::NEG_INFINITY; 3]; 4];
    let mut quads = photo.pixels.chunks_exact(4);
    for quad in &mut quads {
        for (l, px) in quad.iter().enumerate() {
            for c in 0..3 {
                let v = project(px, c);
                lo[l][c] = if v < lo[l][c] { v } else { lo[l][c] };
                hi[l][c] = if v > hi[l][c] { v } else { hi[l][c] };
            }
        }
    }
    for px in quads.remainder() {
        for c in 0..3 {
            let v = project(px, c);
            lo[0][c] = lo[0][c].min(v);
            hi[0][c] = hi[0][c].max(v);
        }
    }
    // Mean and variance of each channel are known exactly from the covariance: the mean is 0
    // and the variance `bᵀ C b` for the stored (f32) axis b.
    let stats = [0, 1, 2].map(|c| {
        let b = basis[c].map(|v| v as f64);
        let cb = [0, 1, 2].map(|i| (0..3).map(|k| p.covariance[i][k] * b[k]).sum::<f64>());
        let var: f64 = (0..3).map(|i| b[i] * cb[i]).sum();
        ChannelStats {
            lo: lo.iter().map(|l| l[c]).fold(f32::INFINITY, f32::min),
            hi: hi.iter().map(|h| h[c]).fold(f32::NEG_INFINITY, f32::max),
            n,
            mean: 0.0,
            sigma: var.max(0.0).sqrt(),
        }
    });
    let channel_variance = stats.map(|s| s.sigma * s.sigma);

    // Rank bins of all three channels in one pass, then maps and knots (knots are kept even
    // with the histogram off, so that the UI can toggle it later).
    let binning = stats.map(|s| RankMap::binning(&s));
    let mut counts = [
        vec![0u32; RANK_BINS],
        vec![0u32; RANK_BINS],
        vec![0u32; RANK_BINS],
    ];
    let mut bins = vec![[0u16; 3]; n];
    for (px, b) in photo.pixels.iter().zip(bins.iter_mut()) {
        for c in 0..3 {
            let k = RankMap::bin_of(project(px, c), binning[c]);
            counts[c][k as usize] += 1;
            b[c] = k;
        }
    }
    let mut knots: [Vec<f32>; 3] = Default::default();
    let mut maps: [Option<RankMap>; 3] = Default::default();
    for c in 0..3 {
        let (map, k) = RankMap::from_counts(&counts[c], &stats[c], opts.knots);
        knots[c] = k;
        maps[c] = opts.histogram.then_some(map);
    }
    // The knot sets the output tone curve's allocation tries: `opts.knots` and fewer, each of
    // the whole image and of its top and bottom halves (the allocation's two folds).
    let candidates: Vec<HistogramCandidate> = if opts.tone && opts.histogram {
        let half_counts = half_rank_counts(&bins, w, h);
        let mut ks: Vec<usize> = vec![opts.knots];
        ks.extend(HISTOGRAM_INTERVALS.iter().filter(|&&k| k < opts.knots));
        ks.into_iter()
            .map(|k| {
                let of = |counts: &[Vec<u32>; 3], n: usize| {
                    [0, 1, 2].map(|c| {
                        let st = ChannelStats { n, ..stats[c] };
                        RankMap::from_counts(&counts[c], &st, k).1
                    })
                };
                HistogramCandidate {
                    whole: of(&counts, n),
                    halves: [
                        of(&half_counts[0], (h / 2) * w),
                        of(&half_counts[1], (h - h / 2) * w),
                    ],
                }
            })
            .collect()
    } else {
        Vec::new()
    };
    // Channels 0 and 1 as real and imaginary part of one complex image, channel 2 alone.
    let (pair, single): (Vec<Complex32>, Vec<Complex32>) = match &maps {
        [Some(m0), Some(m1), Some(m2)] => bins
            .iter()
            .map(|b| {
                (
                    Complex32::new(m0.z(b[0]), m1.z(b[1])),
                    Complex32::new(m2.z(b[2]), 0.0),
                )
            })
            .unzip(),
        _ => photo
            .pixels
            .iter()
            .map(|px| {
                (
                    Complex32::new(project(px, 0), project(px, 1)),
                    Complex32::new(project(px, 2), 0.0),
                )
            })
            .unzip(),
    };
    drop(bins);

    let nb = num_bands(w, h);
    let extras = Extras {
        moments: opts.orientation,
        rings: opts.estimator == Estimator::Rings,
    };
    let [s0, s1] = band_spectra_packed(pair, w, h, nb, opts.periodic, extras);
    let [s2, _] = band_spectra_packed(single, w, h, nb, opts.periodic, extras);
    let spectra = [s0, s1, s2];
    let band_powers = spectra.each_ref().map(|s| s.powers.clone());
    let weights = [0, 1, 2].map(|c| {
        let octaves = estimate_weights(&band_powers[c], opts.estimator);
        if !extras.rings {
            return octaves;
        }
        // The ring fit starts from the octave solve's variances.
        let start: Vec<f64> = octaves.iter().map(|&v| (v as f64).powi(2)).collect();
        crate::ring_fit::fit_weights(&spectra[c].rings, w, h, nb, &start)
    });
    // The channels' powers weighted by their variances (Gaussianised channels have unit
    // variance; raw ones carry theirs already).
    let variance_weight = if opts.histogram {
        channel_variance
    } else {
        [1.0; 3]
    };
    let orientation = if opts.orientation {
        orientation::fit(
            &[&band_powers[0], &band_powers[1], &band_powers[2]],
            &[
                &spectra[0].moments,
                &spectra[1].moments,
                &spectra[2].moments,
            ],
            &variance_weight,
        )
    } else {
        Vec::new()
    };

    let mut params = Params {
        format: FORMAT.into(),
        seed: opts.seed,
        solid: false,
        transform: Transform {
            scale: 1.0,
            rotation_deg: 0.0,
        },
        colour: Colour {
            mean,
            basis,
            contrast: 1.0,
        },
        model: Model::Noise(NoiseModel {
            weights,
            histogram: Histogram {
                enabled: opts.histogram,
                knots,
            },
            orientation,
            tone: None,
            fine: [0.0; 3],
        }),
        source: None,
    };
    // The curve is a second round of Lagae's histogram matching: off with it.
    if opts.tone
        && opts.histogram
        && let (Some(a), Model::Noise(n)) = (
            allocate(photo, &params, &candidates, opts.fine_gaussian),
            &mut params.model,
        )
    {
        n.histogram.knots = a.knots;
        n.tone = a.tone;
        if let Some((fine, weights)) = a.fine {
            n.fine = fine;
            n.weights = weights;
        }
    } else if opts.fine_gaussian
        && let Model::Noise(n) = &mut params.model
    {
        n.finest_band_gaussian();
    }
    Analysis {
        params,
        band_powers,
        channel_variance,
    }
}

/// The noise model of a `side²` synthetic photo of hash noise (`seed`), for tests.
/// The rank-bin counts of the three channels over the image's top rows (`h / 2`) and over the
/// rest, from each pixel's bins.
fn half_rank_counts(bins: &[[u16; 3]], w: usize, h: usize) -> [[Vec<u32>; 3]; 2] {
    let mut out: [[Vec<u32>; 3]; 2] =
        std::array::from_fn(|_| std::array::from_fn(|_| vec![0u32; RANK_BINS]));
    for (i, b) in bins.iter().enumerate() {
        let half = usize::from(i / w >= h / 2);
        for c in 0..3 {
            out[half][c][b[c] as usize] += 1;
        }
    }
    out
}

#[cfg(test)]
pub(crate) fn hash_noise_params(side: u32, seed: u32) -> Params {
    let pixels = (0..side * side)
        .map(|i| [0, 1, 2].map(|c| crate::rng::uniform(seed, c, i) as f32 * 0.5 + 0.25))
        .collect();
    let photo = Photo {
        width: side,
        height: side,
        pixels,
    };
    analyze_photo(&photo, &Options::default()).unwrap().params
}
