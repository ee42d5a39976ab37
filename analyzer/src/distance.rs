//! Texture distances, to judge a synthesis against a photo of the same material.
//!
//! Two distances, both independent of image size so that crops of different sizes compare:
//! - **spectrum**: RMS difference, in dB, of the radially averaged power spectra of luminance,
//!   in 24 rings of a quarter octave from 1/128 to 1/2 cycle per pixel. A ring's value is the
//!   variance it holds (sum of `|F|²/N²`), so it does not scale with the number of pixels.
//! - **colour**: sliced Wasserstein-1 distance between the two RGB distributions, averaged over
//!   13 fixed directions (the axes, face and body diagonals of the RGB cube), in colour units.
//!
//! Below the fidelity protocol ([`crate::evaluate`]) and the structured fit
//! ([`crate::structure`]), which both measure with them.

use crate::db::Db;
use crate::gabor::{describe, descriptor_image};
use crate::input::Photo;
use crate::spectrum::spectrum_real;

/// Distances between two textures.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Distances {
    /// Radially averaged power spectrum distance, RMS dB.
    pub spectrum_db: f64,
    /// Sliced Wasserstein-1 colour distance.
    pub colour: f64,
    /// Structure distance: the retrieval descriptor's weighted distance ([`structure_distance`]).
    pub structure: f64,
}

impl Distances {
    /// Each distance combined with `o`'s by `f`.
    pub fn zip(self, o: Distances, f: impl Fn(f64, f64) -> f64) -> Distances {
        Distances {
            spectrum_db: f(self.spectrum_db, o.spectrum_db),
            colour: f(self.colour, o.colour),
            structure: f(self.structure, o.structure),
        }
    }

    /// All three distances 0.
    pub const ZERO: Distances = Distances {
        spectrum_db: 0.0,
        colour: 0.0,
        structure: 0.0,
    };
}

const RINGS_PER_OCTAVE: usize = 4;
const OCTAVES: usize = 6;

/// Power per ring (quarter-octave rings from 2^−7 to 2^−1 cycles per pixel) of the luminance.
pub fn radial_spectrum(p: &Photo) -> Vec<f64> {
    let (w, h) = (p.width as usize, p.height as usize);
    let lum: Vec<f32> = p
        .pixels
        .iter()
        .map(|c| 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2])
        .collect();
    let mean = lum.iter().map(|&v| v as f64).sum::<f64>() / lum.len() as f64;
    let centred: Vec<f32> = lum.iter().map(|&v| v - mean as f32).collect();
    let spec = spectrum_real(&centred, w, h, true);
    let rings = RINGS_PER_OCTAVE * OCTAVES;
    let mut out = vec![0.0f64; rings];
    let norm = (w as f64 * h as f64).powi(2);
    for q in 0..w {
        let fx = q.min(w - q) as f64 / w as f64;
        for r in 0..h {
            let fy = r.min(h - r) as f64 / h as f64;
            let rho = (fx * fx + fy * fy).sqrt();
            if rho <= 0.0 || rho > 0.5 {
                continue;
            }
            // Ring 0 is the finest: (2^−1.25, 2^−1].
            let k = (-(rho.log2()) - 1.0) * RINGS_PER_OCTAVE as f64;
            let k = k.floor() as i64;
            if k < 0 || k as usize >= rings {
                continue;
            }
            out[k as usize] += spec[q * h + r].norm_sqr() as f64 / norm;
        }
    }
    out
}

pub use crate::colour::{ColourQuantiles, colour_distance};

/// The structure distance: the weighted distance ([`Db::distance`] of the shipped database)
/// between the Gabor descriptors ([`crate::gabor`]) of the two images' luminance, centre
/// squares. Unlike the radially averaged spectrum it sees orientation (lines, rows, a running
/// bond) and the shape of the distribution (thin dark joints), which is what structured models
/// are for; it is not rotation invariant (two patches of one photo share their orientation).
pub fn structure_distance(a: &Photo, b: &Photo) -> f64 {
    structure_distance_with(Db::shipped(), a, b)
}

/// [`structure_distance`] with the weights of `db` (the browser loads the database file
/// rather than embedding it in the wasm).
pub fn structure_distance_with(db: &Db, a: &Photo, b: &Photo) -> f64 {
    db.distance(&describe_luminance(a), &describe_luminance(b)) as f64
}

/// The descriptor [`structure_distance`] compares: of the luminance's centre square.
pub fn describe_luminance(p: &Photo) -> crate::gabor::Descriptor {
    let lum: Vec<f32> = p
        .pixels
        .iter()
        .map(|c| 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2])
        .collect();
    describe(&descriptor_image(&lum, p.width as usize, p.height as usize))
}

/// What [`distances`] needs of an image that many others are compared with (a photo that
/// candidate renders are scored against): its radial spectrum, colour quantiles and
/// descriptor, computed once. [`Reference::distances`] gives bit for bit what
/// [`distances_with`] does.
#[derive(Clone, Debug)]
pub struct Reference {
    spectrum: Vec<f64>,
    colour: ColourQuantiles,
    descriptor: crate::gabor::Descriptor,
}

impl Reference {
    /// The reference of `p`.
    pub fn of(p: &Photo) -> Reference {
        Reference {
            spectrum: radial_spectrum(p),
            colour: ColourQuantiles::of(p),
            descriptor: describe_luminance(p),
        }
    }

    /// `distances_with(db, a, reference's image)`.
    pub fn distances(&self, db: &Db, a: &Photo) -> Distances {
        Distances {
            spectrum_db: spectrum_distance(&radial_spectrum(a), &self.spectrum),
            colour: ColourQuantiles::of(a).distance(&self.colour),
            structure: db.distance(&describe_luminance(a), &self.descriptor) as f64,
        }
    }
}

/// RMS difference in dB of two radial spectra, over the rings where either has power.
fn spectrum_distance(sa: &[f64], sb: &[f64]) -> f64 {
    let mut sum = 0.0;
    let mut count = 0;
    for (x, y) in sa.iter().zip(sb) {
        if *x > 0.0 || *y > 0.0 {
            let d = 10.0 * ((x + 1e-12).log10() - (y + 1e-12).log10());
            sum += d * d;
            count += 1;
        }
    }
    if count > 0 {
        (sum / count as f64).sqrt()
    } else {
        0.0
    }
}

/// The three distances.
pub fn distances(a: &Photo, b: &Photo) -> Distances {
    distances_with(Db::shipped(), a, b)
}

/// [`distances`] with the structure distance weighted by `db`.
pub fn distances_with(db: &Db, a: &Photo, b: &Photo) -> Distances {
    Distances {
        spectrum_db: spectrum_distance(&radial_spectrum(a), &radial_spectrum(b)),
        colour: colour_distance(a, b),
        structure: structure_distance_with(db, a, b),
    }
}
