//! The orientation of each band, fitted to the photo's power spectrum: the analysis side of
//! [`crate::noise::oriented`].
//!
//! A band of strength `s` and streak angle `a` has power `∝ 1 + s·cos 2(θ − θ₀)` with
//! `θ₀ = a + 90°`, so the angular moment of its power, `Z = Σ P·e^{2iθ} / Σ P` over the band's
//! frequencies, is `s·m₁·e^{2iθ₀}`, where `m₁` ([`PURE_MOMENT`]) is the moment of a band of full
//! strength as our band powers measure it (octave rings of the FFT grid, the derivative's
//! radial tilt). The three decorrelated channels share one orientation per band: their moments
//! are pooled, each channel's power weighted by its variance (the principal channel leads, as
//! it does in what one sees).
//!
//! Isotropic photos keep the isotropic model. An isotropic band's measured moment is not 0 but
//! noise, of expected `|Z|²` = `null` (below; large in the coarse bands, which hold few
//! frequency pairs). A band is oriented only where `|Z|²` is significantly above it (a test at
//! a family-wise 5 % over the bands), and its strength comes from `|Z|² − null`, the unbiased
//! estimate of the true `|Z|²`. No constant here was chosen by looking at photos.

use crate::params::BandOrientation;
use crate::spectrum::BandMoments;

/// The angular moment `|Z|` of a band of full strength measured by
/// [`crate::spectrum::band_spectra_packed`] in its own octave: `cos²` has 1/2; the derivative's
/// radial tilt and the square octave rings move it. Measured at half strength (the moment is
/// not quite linear in the strength: 0.50 at full strength) as the mean over 8 angles and 3
/// seeds, bands 1–4 (0.45–0.48); re-measured by the test `pure_moments_are_current` in
/// `tests/orientation.rs`.
pub const PURE_MOMENT: f64 = 0.47;
/// As [`PURE_MOMENT`] for the finest band, which meets the Nyquist limit: there the derivative's
/// power runs past the limit and the moment depends on the angle (0.27 at 0°, 0.52 at 30° at
/// full strength), so this is a mean and band 0's strength is known only roughly.
pub const PURE_MOMENT_FINEST: f64 = 0.25;

/// One orientation per band (none at all when every band is isotropic) from the channels' band powers and moments, each channel's power
/// weighted by `weight[c]`.
pub fn fit(powers: &[&[f64]], moments: &[&BandMoments], weight: &[f64]) -> Vec<BandOrientation> {
    let nb = powers[0].len();
    // |Z|² / null is exponential under isotropy: P(> k) = e^−k. A 5 % chance that any band of
    // an isotropic photo comes out oriented (Bonferroni over the bands).
    let significance = (20.0 * nb as f64).ln();
    let bands: Vec<BandOrientation> = (0..nb)
        .map(|j| {
            let (mut zc, mut zs, mut total, mut square) = (0.0, 0.0, 0.0, 0.0);
            for ((p, m), &wc) in powers.iter().zip(moments).zip(weight) {
                zc += wc * m.cos[j];
                zs += wc * m.sin[j];
                total += wc * p[j];
                square += wc * wc * m.square[j];
            }
            if total.is_nan() || total <= 0.0 {
                return isotropic();
            }
            let z2 = (zc * zc + zs * zs) / (total * total);
            // Under isotropy each independent frequency pair's power is exponential, of
            // variance E[P]² = E[P²]/2, so E|Z|² = Σ_pairs P²/2 / (Σ_pairs P)²; the sums count
            // each pair twice (its multiplicity), which makes that square / total².
            let null = square / (total * total);
            if z2.is_nan() || z2 <= significance * null {
                return isotropic();
            }
            let pure = if j == 0 {
                PURE_MOMENT_FINEST
            } else {
                PURE_MOMENT
            };
            let strength = ((z2 - null).sqrt() / pure).min(1.0);
            let across = zs.atan2(zc).to_degrees() / 2.0;
            BandOrientation {
                angle_deg: (across - 90.0).rem_euclid(180.0) as f32,
                strength: strength as f32,
            }
        })
        .collect();
    if bands.iter().all(|o| o.strength == 0.0) {
        Vec::new()
    } else {
        bands
    }
}

fn isotropic() -> BandOrientation {
    BandOrientation {
        angle_deg: 0.0,
        strength: 0.0,
    }
}
