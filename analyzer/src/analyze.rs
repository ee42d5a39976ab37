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
use crate::histogram::gaussianize;
use crate::input::{Crop, Photo};
use crate::params::{
    Colour, FORMAT, Histogram, MAX_KNOTS, Model, NoiseModel, Params, Source, Transform,
};
use crate::spectrum::{Estimator, band_powers_pair, estimate_weights, num_bands};

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
}

impl Default for Options {
    fn default() -> Self {
        Options {
            size: 512,
            crop: None,
            histogram: true,
            knots: 10,
            seed: 1,
            estimator: Estimator::Deconvolved,
            periodic: true,
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
pub fn analyze_bytes(bytes: &[u8], opts: &Options) -> Result<Analysis> {
    opts.validate()?;
    let photo = Photo::decode(bytes)?;
    analyze_photo(&photo, opts)
}

/// Crops, reduces and analyses a decoded photo.
pub fn analyze_photo(photo: &Photo, opts: &Options) -> Result<Analysis> {
    opts.validate()?;
    let region = match opts.crop {
        Some(c) => photo.crop(c)?,
        None => photo.clone(),
    };
    region.check_min_size()?;
    let reduced = region.reduce_to(opts.size);
    let mut analysis = analyze_prepared(&reduced, opts);
    // One texel is one analysed pixel; in world units (photo pixels) that is this many.
    analysis.params.transform.scale = region.width as f32 / reduced.width as f32;
    analysis.params.source = Some(Source {
        width: photo.width,
        height: photo.height,
        crop: opts.crop.map(|c| [c.x, c.y, c.w, c.h]),
        analysis_width: reduced.width,
        analysis_height: reduced.height,
        estimator: opts.estimator.name().into(),
    });
    Ok(analysis)
}

/// The analysis proper, on an image already at analysis size (at least 32×32).
pub fn analyze_prepared(photo: &Photo, opts: &Options) -> Analysis {
    let (w, h) = (photo.width as usize, photo.height as usize);
    let n = w * h;
    let p = pca(&photo.pixels);
    let mean = p.mean.map(|m| m as f32);
    let basis = p.basis.map(|r| r.map(|v| v as f32));

    // Decorrelated channels (computed with the f32 basis actually stored, so that synthesis
    // inverts exactly what analysis measured).
    let mut channels = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    for (i, px) in photo.pixels.iter().enumerate() {
        let d = [px[0] - mean[0], px[1] - mean[1], px[2] - mean[2]];
        for c in 0..3 {
            channels[c][i] = basis[c][0] * d[0] + basis[c][1] * d[1] + basis[c][2] * d[2];
        }
    }
    let channel_variance = [0, 1, 2].map(|c| {
        let m = channels[c].iter().map(|&v| v as f64).sum::<f64>() / n as f64;
        channels[c]
            .iter()
            .map(|&v| (v as f64 - m).powi(2))
            .sum::<f64>()
            / n as f64
    });

    // Knots are kept even with the histogram off, so that the UI can toggle it later.
    let mut knots: [Vec<f32>; 3] = Default::default();
    let mut signal: [Vec<f32>; 3] = Default::default();
    for c in 0..3 {
        let g = gaussianize(&channels[c], opts.knots);
        knots[c] = g.knots;
        signal[c] = if opts.histogram {
            g.values
        } else {
            std::mem::take(&mut channels[c])
        };
    }

    let nb = num_bands(w, h);
    let [p0, p1] = band_powers_pair(&signal[0], Some(&signal[1]), w, h, nb, opts.periodic);
    let [p2, _] = band_powers_pair(&signal[2], None, w, h, nb, opts.periodic);
    let band_powers = [p0, p1, p2];
    let weights = [0, 1, 2].map(|c| estimate_weights(&band_powers[c], opts.estimator));

    let params = Params {
        format: FORMAT.into(),
        seed: opts.seed,
        solid: false,
        transform: Transform {
            scale: 1.0,
            rotation_deg: 0.0,
        },
        colour: Colour { mean, basis },
        model: Model::Noise(NoiseModel {
            weights,
            histogram: Histogram {
                enabled: opts.histogram,
                knots,
            },
        }),
        source: None,
    };
    Analysis {
        params,
        band_powers,
        channel_variance,
    }
}
