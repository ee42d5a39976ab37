//! The `--marginals` ladder: what each band's own marginal distribution could buy a model of
//! Gaussian bands. Heeger & Bergen (1995) match the histogram of every subband, not only the
//! image's; a procedural noise could map each band through its own monotone curve before the
//! bands are summed (random access kept). Every rung works in the model's decorrelated channels
//! with exact histograms of the sum (rank matching), on boxes of the 2D spectrum (one octave of
//! radius, `wedges` orientations):
//! 1. the floor (as the other ladders: `PROCTEX_LAB_GAUSSIAN` chooses its amplitudes);
//! 2. the boxes' Gaussian fields summed (the `--bands` ladder's rung);
//! 3. each box's field first rank-matched to the patch's own content in that box (the channel
//!    filtered to the box: its band signal, heavy tails and skew included), then summed.

use super::ladder::rank_match;
use super::{box_amplitudes, box_bins, floor, model_of, random_phase_field, to_rgb};
use proctex::input::Photo;
use proctex::spectrum::{ifft2, spectrum_real};
use rustfft::num_complex::Complex32;

pub const MARGINAL_RUNGS: [&str; 5] = [
    "floor (full spectrum)",
    "octave boxes, Gaussian bands",
    "octave boxes, each band's marginal the patch's",
    "octave boxes, 4 orientations, Gaussian bands",
    "octave boxes, 4 orientations, each band's marginal the patch's",
];

/// Rung `rung` of [`MARGINAL_RUNGS`].
pub fn synthesise_marginals(rung: usize, src: &Photo, seed: u32) -> Photo {
    if rung == 0 {
        return floor(src, seed);
    }
    let (w, h) = (src.width as usize, src.height as usize);
    let m = model_of(src, seed);
    let wedges = if rung <= 2 { 1 } else { 4 };
    let matched = rung.is_multiple_of(2);
    // Rank matching also gives a band the patch's own energy in this window, which no
    // procedural noise has (its energy over a window scatters as the Gaussian field's does);
    // `PROCTEX_LAB_SHAPE_ONLY` keeps the field's own deviation, so that only the marginal's
    // shape is the patch's.
    let shape_only = std::env::var_os("PROCTEX_LAB_SHAPE_ONLY").is_some();
    let (bins_of, count) = box_bins(w, h, 1.0, wedges);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); count];
    for (i, b) in bins_of.iter().enumerate() {
        if let Some(j) = b {
            members[*j].push(i);
        }
    }
    let v = std::array::from_fn(|c| {
        let spec = spectrum_real(&m.channels[c], w, h, true);
        let amplitude = box_amplitudes(&spec, &bins_of, count);
        let mut sum = vec![0.0f32; w * h];
        for (j, box_members) in members.iter().enumerate() {
            if box_members.is_empty() {
                continue;
            }
            // Each box its own draw: the seed's channel stream offset by the box.
            let field = random_phase_field(w, h, seed, c + 3 * (j + 1), |i| {
                (bins_of[i] == Some(j)).then_some(amplitude[j])
            });
            let band = if matched {
                let mut own = vec![Complex32::default(); w * h];
                for &i in box_members {
                    own[i] = spec[i];
                }
                let signal: Vec<f32> = ifft2(own, w, h).iter().map(|z| z.re).collect();
                let shaped = rank_match(&field, &signal);
                if shape_only {
                    let gain = (deviation(&field) / deviation(&shaped).max(1e-30)) as f32;
                    shaped.iter().map(|v| v * gain).collect()
                } else {
                    shaped
                }
            } else {
                field
            };
            for (s, b) in sum.iter_mut().zip(band) {
                *s += b;
            }
        }
        rank_match(&sum, &m.channels[c])
    });
    to_rgb(&m, &v, src.width, src.height)
}

/// The deviation of `v` about its mean.
fn deviation(v: &[f32]) -> f64 {
    let n = v.len().max(1) as f64;
    let mean = v.iter().map(|&x| x as f64).sum::<f64>() / n;
    (v.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / n).sqrt()
}
