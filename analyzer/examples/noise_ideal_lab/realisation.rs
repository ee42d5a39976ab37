//! The `--expected` and `--rounds` ladders of `noise_ideal_lab`: the model's realisation against
//! its own expected spectrum, and further rounds of distribution transfer after the product's
//! output curve.

use super::ladder::rank_match;
use super::{
    Model, frequency, model_noise, model_of, random_phase_field, round_rotation, synthesise,
    synthesise_orient, to_rgb,
};
use proctex::analyze::{Options, analyze_photo};
use proctex::evaluate::random_phase;
use proctex::input::Photo;
use proctex::render::Prepared;
use proctex::rng;
use proctex::spectrum::{fft2_real, ifft2, spectrum_real};

/// The `--expected` ladder: where the model's structure goes against the oriented octave
/// boxes, its own ideal. Every rung has exact histograms; the model's expected 2D power
/// spectrum is the mean periodogram of its channel noise over [`EXPECTED_SEEDS`] realisations
/// (seeds apart from the protocol's).
pub const EXPECTED_RUNGS: [&str; 7] = [
    "floor (full spectrum, exact)",
    "octave boxes, shared profile 1 + s·cos 2(θ−θ0)",
    "the model's noise (its realisation), exact histograms",
    "the model's expected 2D spectrum, random phases, exact histograms",
    "the photo's octave powers × the model's expected shape within each octave",
    "the model's expected 2D spectrum, Gaussian (Rayleigh) amplitudes, exact histograms",
    "the model's realisation, its amplitudes set to the expected spectrum's, exact histograms",
];
const EXPECTED_SEEDS: u32 = 16;

/// The `--rounds` ladder: the product as it renders (its histogram and its RGB tone curve, the
/// first round of distribution transfer), then further rounds along fixed rotations of the RGB
/// axes ([`round_rotation`]), each a curve per rotated axis fitted as the product fits its own
/// curve (quantile matching the model's samples at seeds apart from the protocol's onto the
/// photo's values along the axis). Ignores the parameter budget: what the rounds could buy.
pub const ROUNDS_RUNGS: [&str; 5] = [
    "the product as it renders (one round: its RGB curve)",
    "+ 1 round, 9 knots per axis",
    "+ 1 round, 17 knots per axis",
    "+ 2 rounds, 9 knots",
    "+ 4 rounds, 9 knots",
];
const ROUNDS: [(usize, usize); 4] = [(1, 9), (1, 17), (2, 9), (4, 9)];

/// Rung `rung` of the `--rounds` ladder ([`ROUNDS_RUNGS`]).
pub fn synthesise_rounds(rung: usize, src: &Photo, seed: u32) -> Photo {
    use proctex::evaluate::render_params_at_photo_size;
    use proctex::noise_tone::{FIT_SEED, NOISE_TONE_SEEDS, quantile_match};
    let opts = Options {
        seed,
        ..Options::default()
    };
    let params = analyze_photo(src, &opts).expect("analysis").params;
    let mut out = render_params_at_photo_size(&params, src);
    if rung == 0 {
        return out;
    }
    let (rounds, knots) = ROUNDS[rung - 1];
    let mut samples: Vec<[f32; 3]> = (0..NOISE_TONE_SEEDS)
        .flat_map(|k| {
            let p = proctex::params::Params {
                seed: FIT_SEED + k,
                ..params.clone()
            };
            render_params_at_photo_size(&p, src).pixels
        })
        .collect();
    let rotate = |rot: &[[f32; 3]; 3], px: &[f32; 3]| -> [f32; 3] {
        std::array::from_fn(|a| (0..3).map(|c| rot[a][c] * px[c]).sum())
    };
    let back = |rot: &[[f32; 3]; 3], v: &[f32; 3]| -> [f32; 3] {
        std::array::from_fn(|c| (0..3).map(|a| rot[a][c] * v[a]).sum())
    };
    for r in 0..rounds {
        let rot = round_rotation(r + 1);
        let projected: Vec<[f32; 3]> = samples.iter().map(|p| rotate(&rot, p)).collect();
        let target: [Vec<f32>; 3] = std::array::from_fn(|a| {
            let mut t: Vec<f32> = src.pixels.iter().map(|p| rotate(&rot, p)[a]).collect();
            t.sort_unstable_by(f32::total_cmp);
            t
        });
        let tone = quantile_match(std::slice::from_ref(&projected), &target, knots);
        let curve = tone.curve();
        let apply = |p: &[f32; 3]| {
            let v = rotate(&rot, p);
            back(&rot, &[0, 1, 2].map(|a| curve(a, v[a])))
        };
        samples = samples.iter().map(apply).collect();
        out.pixels = out.pixels.iter().map(apply).collect();
    }
    for p in &mut out.pixels {
        *p = p.map(|v| v.clamp(0.0, 1.0));
    }
    out
}

/// Rung `rung` of the `--expected` ladder ([`EXPECTED_RUNGS`]).
pub fn synthesise_expected(rung: usize, src: &Photo, seed: u32) -> Photo {
    match rung {
        0 => random_phase(src, seed),
        1 => synthesise_orient(3, src, seed),
        2 => synthesise(3, src, seed),
        _ => {
            let (w, h) = (src.width, src.height);
            let (wu, hu) = (w as usize, h as usize);
            let m = model_of(src, seed);
            let mut expected: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; wu * hu]);
            for k in 0..EXPECTED_SEEDS {
                // Seeds apart from the protocol's (1, 2, …) and the tone curve's fit seeds.
                let params = proctex::params::Params {
                    seed: 0x7000_0000 + k,
                    ..m.params.clone()
                };
                let one = Model {
                    prep: Prepared::new(&params),
                    params,
                    channels: Default::default(),
                };
                let g = model_noise(&one, w, h);
                for c in 0..3 {
                    for (e, s) in expected[c]
                        .iter_mut()
                        .zip(spectrum_real(&g[c], wu, hu, true))
                    {
                        *e += s.norm_sqr() as f64 / EXPECTED_SEEDS as f64;
                    }
                }
            }
            let lowest = (w.max(h) as f64).log2().floor() as usize;
            let octave = |i: usize| {
                let (fx, fy) = frequency(i, wu, hu);
                let r = (fx * fx + fy * fy).sqrt();
                (r > 0.0).then(|| ((-r.log2()).floor().max(0.0) as usize).min(lowest))
            };
            if rung >= 5 {
                let g = model_noise(&m, w, h);
                let v = std::array::from_fn(|c| {
                    let spec = if rung == 5 {
                        let white: Vec<f32> = (0..wu * hu)
                            .map(|i| rng::gaussian(seed, 0x6f63_7462 + c as u32, i as u32) as f32)
                            .collect();
                        fft2_real(&white, wu, hu)
                            .iter()
                            .enumerate()
                            .map(|(i, z)| z * (expected[c][i] / (wu * hu) as f64).sqrt() as f32)
                            .collect()
                    } else {
                        fft2_real(&g[c], wu, hu)
                            .iter()
                            .enumerate()
                            .map(|(i, z)| {
                                let n = z.norm();
                                if n > 0.0 {
                                    z * (expected[c][i].sqrt() as f32 / n)
                                } else {
                                    *z
                                }
                            })
                            .collect()
                    };
                    let field: Vec<f32> = ifft2(spec, wu, hu).iter().map(|v| v.re).collect();
                    rank_match(&field, &m.channels[c])
                });
                return to_rgb(&m, &v, w, h);
            }
            let v = std::array::from_fn(|c| {
                let gain: Vec<f64> = if rung == 3 {
                    vec![1.0; lowest + 1]
                } else {
                    // Per octave: the photo channel's power over the model's expected power.
                    let spec = spectrum_real(&m.channels[c], wu, hu, true);
                    let (mut photo, mut model) =
                        (vec![0.0f64; lowest + 1], vec![0.0f64; lowest + 1]);
                    for i in 0..wu * hu {
                        if let Some(j) = octave(i) {
                            photo[j] += spec[i].norm_sqr() as f64;
                            model[j] += expected[c][i];
                        }
                    }
                    photo
                        .iter()
                        .zip(&model)
                        .map(|(p, m)| if *m > 0.0 { p / m } else { 0.0 })
                        .collect()
                };
                let field = random_phase_field(wu, hu, seed, c, |i| {
                    octave(i).map(|j| (expected[c][i] * gain[j]).sqrt() as f32)
                });
                rank_match(&field, &m.channels[c])
            });
            to_rgb(&m, &v, w, h)
        }
    }
}
