//! What half-octave bands could buy the noise model, built from its own wavelet-noise bands:
//! between octave bands `j` and `j + 1` a band evaluated on the lattice turned by 45° and
//! scaled by `2^−(j+½)` (coordinates `((x + y), (y − x)) / 2^(j+1)`: an integer matrix, so a
//! periodic tile stays periodic with the period of band `j + 1`).
//!
//! Every rung: the model's decorrelated channels (PCA of the source patch), isotropic bands,
//! weights fitted by the ring fit (`ring_fit::fit_weights_by`: quarter-octave rings, log domain)
//! to each channel's radial spectrum, random offsets per seed, exact histograms (each channel
//! rank-matched to the patch's values), judged by the fidelity protocol (quadrant pairs, seeds
//! 1..S) on the stochastic photos of a manifest:
//! 1. `octave bands`: the model's bands `0..nb` (one per octave, as the product);
//! 2. `octave + half-octave bands`: the same and the `nb − 1` bands between them;
//! 3. the same for the first decorrelated channel only, the other two with octave bands (what a
//!    fourth tile component, read by the same fetch, could carry).
//!
//! ```text
//! cargo run --release -p proctex-analyzer --example half_octave_lab -- \
//!     ../shared/photos/dev/manifest.tsv [SEEDS]
//! ```

#[path = "lab_common/ladder.rs"]
mod ladder;
use ladder::{decorrelated, print_ladder, rank_match, run_ladder, stochastic_photos, to_rgb};
use proctex::analyze::{Options, analyze_photo};
use proctex::histogram::phi_inv;
use proctex::input::Photo;
use proctex::noise::{Tile, noise2};
use proctex::render::{Prepared, View, offset_coeffs, render, texture_noise, tile_for};
use proctex::ring_fit::{RING_DENSITY, density, fit_weights_by, ring_powers};
use proctex::rng;
use proctex::spectrum::{FINE_PER_OCTAVE, num_bands};

const RUNGS: [&str; 7] = [
    "octave bands",
    "octave bands fitted to the Gaussianised channels",
    "octave + half-octave bands",
    "the model's isotropic noise, exact histograms",
    "the model's (oriented) noise, exact histograms",
    "the model as it renders (its knots, its tone curve)",
    "octave + half-octave bands for the first channel only",
];

/// Band `k` of the half-octave set: even `k` is octave band `k/2`, odd `k` the band between
/// `(k−1)/2` and `(k+1)/2`, whose density is octave band `(k−1)/2`'s stretched by `√2`
/// (`2·S(√2 ρ)`: half an octave, `FINE_PER_OCTAVE / 2` fine bins, finer).
fn half_density(k: usize, t: usize) -> f64 {
    if k.is_multiple_of(2) {
        density(&RING_DENSITY, k / 2, t)
    } else {
        let shifted = t.saturating_sub(FINE_PER_OCTAVE / 2);
        2.0 * density(&RING_DENSITY, (k - 1) / 2, shifted)
    }
}

/// The product's own model of `src` (orientation as `oriented`): rendered as it is (`exact`
/// false) or its channel noise rank-matched to the patch's decorrelated values.
fn product(src: &Photo, seed: u32, oriented: bool, exact: bool) -> Photo {
    // Lagae's model: every band through the histogram (the lab rank-matches their sum).
    let opts = Options {
        seed,
        orientation: oriented,
        fine_gaussian: false,
        ..Options::default()
    };
    let params = analyze_photo(src, &opts).expect("analysis").params;
    if !exact {
        return render(&params, src.width, src.height, &View::default()).to_photo();
    }
    let prep = Prepared::new(&params);
    let tile = tile_for(&params);
    let log2_fp = prep.inv_scale.log2();
    let (w, h) = (src.width as usize, src.height as usize);
    let mut noise: [Vec<f32>; 3] = std::array::from_fn(|_| Vec::with_capacity(w * h));
    for y in 0..h {
        for x in 0..w {
            let u = prep.texel([x as f32 + 0.5, y as f32 + 0.5, 0.0]);
            let g = texture_noise(&prep, &tile, u, log2_fp);
            for (o, v) in noise.iter_mut().zip(g.sum) {
                o.push(v);
            }
        }
    }
    let channels = decorrelated(src, &prep);
    let v: [Vec<f32>; 3] = std::array::from_fn(|c| rank_match(&noise[c], &channels[c]));
    to_rgb(&prep, &v, src.width, src.height)
}

fn synthesise(rung: usize, src: &Photo, seed: u32) -> Photo {
    match rung {
        3 => return product(src, seed, false, true),
        4 => return product(src, seed, true, true),
        5 => return product(src, seed, true, false),
        _ => {}
    }
    // The last rung: half-octave bands for channel 0, octave bands for the others.
    let first_only = rung == 6;
    let rung = if first_only { 2 } else { rung };
    let (w, h) = (src.width as usize, src.height as usize);
    let opts = Options {
        seed,
        tone: false,
        orientation: false,
        fine_gaussian: false,
        ..Options::default()
    };
    let params = analyze_photo(src, &opts).expect("analysis").params;
    let prep = Prepared::new(&params);
    let channels = decorrelated(src, &prep);
    let nb = num_bands(w, h);
    let half = rung == 2;
    // Rung 1 fits the spectra of the channels' ranks mapped to a standard normal (as the
    // product's analysis measures them), the others the channels' own spectra.
    let gaussianised = |v: &[f32]| -> Vec<f32> {
        let mut order: Vec<usize> = (0..v.len()).collect();
        order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
        let mut out = vec![0.0f32; v.len()];
        for (rank, &i) in order.iter().enumerate() {
            out[i] = phi_inv((rank as f64 + 0.5) / v.len() as f64) as f32;
        }
        out
    };
    let count = if half { 2 * nb - 1 } else { nb };
    let dens = |k: usize, t: usize| {
        if half {
            half_density(k, t)
        } else {
            density(&RING_DENSITY, k, t)
        }
    };
    let weights: [Vec<f32>; 3] = std::array::from_fn(|c| {
        let measured = if rung == 1 {
            gaussianised(&channels[c])
        } else {
            channels[c].clone()
        };
        let rings = ring_powers(&measured, w, h, true);
        let total: f64 = rings.power.iter().sum();
        if first_only && c > 0 {
            // Octave bands alone: the half-octave slots left at zero.
            let octave = fit_weights_by(
                &|k: usize, t: usize| density(&RING_DENSITY, k, t),
                &rings,
                w,
                h,
                nb,
                &vec![total / nb as f64; nb],
            );
            return (0..count)
                .map(|k| if k % 2 == 0 { octave[k / 2] } else { 0.0 })
                .collect();
        }
        fit_weights_by(
            &dens,
            &rings,
            w,
            h,
            count,
            &vec![total / count as f64; count],
        )
    });
    let tile = Tile::new_2d(seed);
    let n = tile.n as f32;
    let offsets: Vec<[f32; 2]> = (0..count)
        .map(|k| {
            // Octave band j draws the same offsets in every rung, so that the rungs differ by
            // the bands they add, not by the tile regions they read.
            let index = match (half, k % 2) {
                (true, 0) => k / 2,
                (true, _) => 100 + k / 2,
                (false, _) => k,
            };
            [0u32, 1].map(|a| {
                offset_coeffs(
                    rng::uniform(seed, 0x6861_6c66, (index * 2) as u32 + a) as f32,
                    n,
                )
            })
        })
        .collect();
    let mut fields: [Vec<f32>; 3] = std::array::from_fn(|_| vec![0.0; w * h]);
    for y in 0..h {
        for x in 0..w {
            let (ux, uy) = (x as f32 + 0.5, y as f32 + 0.5);
            let mut sum = [0.0f32; 3];
            for (k, o) in offsets.iter().enumerate() {
                let (j, turned) = if half {
                    (k / 2, k % 2 == 1)
                } else {
                    (k, false)
                };
                let p = if turned {
                    let f = 1.0 / (1u32 << (j + 1)) as f32;
                    [(ux + uy) * f + o[0], (uy - ux) * f + o[1]]
                } else {
                    let f = 1.0 / (1u32 << j) as f32;
                    [ux * f + o[0], uy * f + o[1]]
                };
                let g = noise2(&tile.data, tile.n, p);
                for c in 0..3 {
                    sum[c] += weights[c][k] * g[c];
                }
            }
            for c in 0..3 {
                fields[c][y * w + x] = sum[c];
            }
        }
    }
    let v: [Vec<f32>; 3] = std::array::from_fn(|c| rank_match(&fields[c], &channels[c]));
    to_rgb(&prep, &v, src.width, src.height)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let manifest = args.first().expect("MANIFEST.tsv");
    let seeds: Vec<u32> = (1..=args.get(1).map_or(2, |s| s.parse().unwrap())).collect();
    let photos = stochastic_photos(manifest);
    let table = run_ladder(&photos, &seeds, RUNGS.len(), &synthesise);
    println!(
        "{} stochastic photos of {manifest}, seeds {seeds:?}: fidelity ratios, mean ± standard error over photos",
        photos.len()
    );
    print_ladder(&RUNGS, &table);
}
