//! Whether the noise model's isotropic bands are isotropic as the structure descriptor sees
//! them: the mean log-Gabor energy per orientation (over its mean over orientations, ln), per
//! frequency, of the noise model's render with every band isotropic, averaged over seeds,
//! against the same for white Gaussian noise (the descriptor's own bias on the pixel grid).
//!
//! ```text
//! cargo run --release -p proctex-analyzer --example band_anisotropy -- PHOTO [SEEDS]
//! ```

use proctex::analyze::{Options, analyze_photo};
use proctex::distance::describe_luminance;
use proctex::evaluate::render_params_at_photo_size;
use proctex::gabor::{FREQUENCIES, ORIENTATIONS};
use proctex::input::{Crop, Photo};
use proctex::rng;

fn energies(p: &Photo) -> Vec<f64> {
    let d = describe_luminance(p).0;
    d[..ORIENTATIONS * FREQUENCIES]
        .iter()
        .map(|&v| v as f64)
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let photo = Photo::decode(&std::fs::read(&args[0]).unwrap()).unwrap();
    let seeds = args.get(1).map_or(16, |s| s.parse().unwrap());
    let side = 128u32;
    let src = photo
        .crop(Crop {
            x: 0,
            y: 0,
            w: side.min(photo.width),
            h: side.min(photo.height),
        })
        .unwrap();
    let mut acc = [
        vec![0.0f64; ORIENTATIONS * FREQUENCIES],
        vec![0.0; ORIENTATIONS * FREQUENCIES],
    ];
    // One analysis (isotropic, no tone curve: nothing in it depends on the seed); each seed
    // renders it with its own tile and band offsets.
    let opts = Options {
        orientation: false,
        tone: false,
        ..Options::default()
    };
    let mut params = analyze_photo(&src, &opts).unwrap().params;
    for seed in 1..=seeds {
        params.seed = seed;
        let model = render_params_at_photo_size(&params, &src);
        let white = Photo {
            width: side,
            height: side,
            pixels: (0..side * side)
                .map(|i| {
                    let g = 0.5 + 0.1 * rng::gaussian(seed, 0x77, i) as f32;
                    [g, g, g]
                })
                .collect(),
        };
        for (a, p) in acc.iter_mut().zip([&model, &white]) {
            let e = energies(p);
            for (x, v) in a.iter_mut().zip(e) {
                *x += v.max(1e-12).ln() / seeds as f64;
            }
        }
    }
    for (name, a) in ["noise model, isotropic", "white noise"].iter().zip(&acc) {
        println!("{name}: ln(energy / its mean over orientations)");
        for k in 0..FREQUENCIES {
            let row: Vec<f64> = (0..ORIENTATIONS).map(|o| a[o * FREQUENCIES + k]).collect();
            let m = row.iter().sum::<f64>() / ORIENTATIONS as f64;
            let cells: Vec<String> = row.iter().map(|v| format!("{:+.3}", v - m)).collect();
            println!("f{k}: {}", cells.join(" "));
        }
    }
}
