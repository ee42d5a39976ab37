//! The measured spectral response of our own noise bands: the leakage matrix of the
//! deconvolved estimator ([`super::Estimator::Deconvolved`]) and the unit-band renders that it
//! and the ring fit's densities ([`crate::ring_fit`]) are measured on.

use super::{band_powers, num_bands};

/// Seeds averaged by [`measure_leakage`] for [`LEAKAGE_512`]: 1 to 96. The coarsest band
/// shows only 4 × 4 tile coefficients at 512², so its column scatters between seed sets: its
/// own-octave share read 0.82, 0.84 and 1.00 over three disjoint sets of 24 seeds.
pub const LEAKAGE_SEEDS: [u32; 96] = {
    let mut seeds = [0u32; 96];
    let mut i = 0;
    while i < seeds.len() {
        seeds[i] = i as u32 + 1;
        i += 1;
    }
    seeds
};

/// The measured leakage matrix at 512² (8 bands, averaged over [`LEAKAGE_SEEDS`]): `LEAKAGE_512[j][i]` is the power in octave `j`
/// of a unit-variance noise band `i`. Printed by `cargo run --example leakage`; the test
/// `leakage_table_is_current` re-measures it. Column 0 (the finest band) meets the Nyquist limit;
/// the last columns meet the coarse end, where an octave holds only a few FFT bins (band 7:
/// |k| ≤ 2, band 6: |k| ∈ {3, 4}); columns 1–2 are the scale-free interior.
#[rustfmt::skip]
pub const LEAKAGE_512: [[f64; 8]; 8] = [
    [0.893970, 0.078289, 0.007021, 0.000224, 0.000015, 0.000003, 0.000001, 0.000000],
    [0.101956, 0.782826, 0.058880, 0.006376, 0.000216, 0.000016, 0.000004, 0.000001],
    [0.000666, 0.134172, 0.778158, 0.055311, 0.006348, 0.000255, 0.000028, 0.000006],
    [0.000587, 0.001206, 0.148322, 0.758908, 0.049425, 0.006401, 0.000325, 0.000045],
    [0.000574, 0.000780, 0.002214, 0.167024, 0.722462, 0.039611, 0.005947, 0.000423],
    [0.000539, 0.000694, 0.001346, 0.004350, 0.205035, 0.649393, 0.026373, 0.005641],
    [0.000470, 0.000615, 0.001112, 0.002437, 0.008874, 0.279786, 0.453770, 0.012675],
    [0.001095, 0.001514, 0.002773, 0.005048, 0.010058, 0.036737, 0.438141, 0.805864],
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
            fine: [0.0; 3],
            tone: None,
        }),
        source: None,
    };
    let prep = Prepared::new(&params);
    let tile = tile_for(&params);
    (0..size * size)
        .map(|k| {
            let (x, y) = ((k % size) as f32 + 0.5, (k / size) as f32 + 0.5);
            texture_noise(&prep, &tile, prep.texel([x, y, 0.0]), 0.0).sum[0]
        })
        .collect()
}
