//! The measured spectral response of our own noise bands: the leakage matrix of the
//! deconvolved estimator ([`super::Estimator::Deconvolved`]) and the unit-band renders that it
//! and the ring fit's densities ([`crate::ring_fit`]) are measured on.

use super::{band_powers, num_bands};

/// Seeds averaged by [`measure_leakage`] for [`LEAKAGE_512`].
pub const LEAKAGE_SEEDS: [u32; 24] = [
    1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24,
];

/// The measured leakage matrix at 512² (8 bands, averaged over 24 seeds): `LEAKAGE_512[j][i]` is the power in octave `j`
/// of a unit-variance noise band `i`. Printed by `cargo run --example leakage`; the test
/// `leakage_table_is_current` re-measures it. Column 0 (the finest band) meets the Nyquist limit;
/// the last columns meet the coarse end, where an octave holds only a few FFT bins (band 7:
/// |k| ≤ 2, band 6: |k| ∈ {3, 4}); columns 1–2 are the scale-free interior.
#[rustfmt::skip]
pub const LEAKAGE_512: [[f64; 8]; 8] = [
    [0.919389, 0.075303, 0.007085, 0.000224, 0.000015, 0.000003, 0.000001, 0.000000],
    [0.077251, 0.823648, 0.057306, 0.006404, 0.000216, 0.000016, 0.000003, 0.000001],
    [0.000672, 0.097397, 0.830057, 0.054311, 0.006253, 0.000241, 0.000026, 0.000006],
    [0.000629, 0.000810, 0.100864, 0.799305, 0.048109, 0.006110, 0.000320, 0.000044],
    [0.000627, 0.000757, 0.000598, 0.128526, 0.747388, 0.037702, 0.006182, 0.000399],
    [0.000650, 0.000744, 0.000554, 0.004950, 0.162151, 0.651313, 0.026900, 0.004752],
    [0.000741, 0.000649, 0.000530, 0.003095, 0.010464, 0.246765, 0.490419, 0.012368],
    [0.004050, 0.002212, 0.001355, 0.006932, 0.015824, 0.045549, 0.446753, 0.738370],
];

/// The leakage matrix for `nb` bands, from [`LEAKAGE_512`]. For power-of-two square images a
/// band's leakage depends only on its distance from the finest band (Nyquist) and from the
/// coarsest (discrete bins), so column `i` is taken from the measured column at the same distance
/// from the end it is closer to (interior columns from column 1), shifted along the diagonal.
/// Power that would land finer than band 0 or coarser than the last band folds into them, as the
/// analysis folds those frequencies. Other sizes use the same matrix as an approximation.
pub fn leakage_matrix(nb: usize) -> Vec<Vec<f64>> {
    let m = LEAKAGE_512.len();
    let mut l = vec![vec![0.0; nb]; nb];
    for i in 0..nb {
        let from_coarse = nb - 1 - i;
        let mi = if i == 0 {
            0
        } else {
            (m as i64 - 1 - from_coarse as i64).max(1) as usize
        };
        for (mj, row) in LEAKAGE_512.iter().enumerate() {
            let j = (mj as i64 + i as i64 - mi as i64).clamp(0, nb as i64 - 1) as usize;
            l[j][i] += row[mi];
        }
    }
    l
}

/// Measures the leakage matrix of our own noise bands: renders each band alone (unit weight,
/// channel 0) on a `size × size` grid with the CPU renderer's own per-pixel code at one texel
/// per pixel, and averages its band powers over `seeds`. Returns `L[j][i]`.
pub fn measure_leakage(size: usize, seeds: &[u32]) -> Vec<Vec<f64>> {
    let nb = num_bands(size, size);
    let mut l = vec![vec![0.0; nb]; nb];
    for &seed in seeds {
        for i in 0..nb {
            let img = render_unit_band(size, seed, i);
            let p = band_powers(&img, size, size, nb, true);
            for j in 0..nb {
                l[j][i] += p[j] / seeds.len() as f64;
            }
        }
    }
    l
}

/// Band `band` of the noise alone (unit weight, channel 0, isotropic) on a `size × size` grid,
/// rendered with the CPU renderer's own per-pixel code at one texel per pixel: what the bands'
/// spectral measurements ([`measure_leakage`], [`crate::ring_fit::measure_ring_density`]) use.
pub fn render_unit_band(size: usize, seed: u32, band: usize) -> Vec<f32> {
    use crate::params::{Colour, FORMAT, Histogram, Model, NoiseModel, Params, Transform};
    use crate::render::{Prepared, texture_noise, tile_for};
    let nb = band + 1;
    let mut unit = vec![0.0f32; nb];
    unit[band] = 1.0;
    let params = Params {
        format: FORMAT.into(),
        seed,
        solid: false,
        transform: Transform {
            scale: 1.0,
            rotation_deg: 0.0,
        },
        colour: Colour {
            mean: [0.5; 3],
            basis: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            contrast: 1.0,
        },
        model: Model::Noise(NoiseModel {
            weights: [unit, vec![0.0; nb], vec![0.0; nb]],
            histogram: Histogram {
                enabled: false,
                knots: [vec![0.0, 1.0], vec![0.0, 1.0], vec![0.0, 1.0]],
            },
            orientation: Vec::new(),
            tone: None,
        }),
        source: None,
    };
    let prep = Prepared::new(&params);
    let tile = tile_for(&params);
    (0..size * size)
        .map(|k| {
            let (x, y) = ((k % size) as f32 + 0.5, (k / size) as f32 + 0.5);
            texture_noise(&prep, &tile, prep.texel([x, y, 0.0]), 0.0)[0]
        })
        .collect()
}
