//! Speed benchmark of the Heeger–Bergen synthesis (not a test): prints ratios measured in one
//! run, so a noisy shared machine moves numerator and denominator together.
//!
//! A 512² RGB synthesis from the 512² rock sample, the paper's 5 iterations, 4 scales and 4
//! orientations, on every thread and on one, against the FFTs it needs (those of the sample's
//! analysis and of every round's analysis and reconstruction, three channels, as plain rustfft
//! 2D transforms timed one after another) and against the 1.5 s target; then the share of the
//! steerable pyramid alone (one analysis and reconstruction of a 512² channel); then solid
//! textures of 64³ and 128³ (one run each) against the 2D synthesis' time.
//!
//! Run: `cargo bench -p proctex-analyzer --bench pyramid` (add `-- --quick` for fewer
//! repetitions, as CI does).

mod common;

use std::hint::black_box;

use common::{median_time, ms};

use proctex::heeger_bergen::solid::{SolidOptions, synthesize_solid};
use proctex::heeger_bergen::{RasterOptions, synthesize, transforms};
use proctex::input::Photo;
use proctex::pyramid::Plan;
use proctex::spectrum::fft2_real;

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let reps = if quick { 3 } else { 7 };
    let path = format!(
        "{}/../www/samples/stk_rock_mountain_512.png",
        env!("CARGO_MANIFEST_DIR")
    );
    let photo = Photo::decode(&std::fs::read(path).expect("sample")).expect("decodes");
    let opts = RasterOptions::new(512, 512);
    println!("proctex pyramid benchmark (median of {reps} runs; ratios within one run)");

    let plan = Plan::new(512, 512, 4, 4);
    let sizes = transforms((512, 512), &opts);
    let images: Vec<Vec<f32>> = [
        (512usize, 512usize),
        (256, 256),
        (128, 128),
        (64, 64),
        (32, 32),
    ]
    .iter()
    .map(|&(w, h)| (0..w * h).map(|i| (i % 7) as f32).collect())
    .collect();
    let ffts = median_time(reps, || {
        for &(w, h) in &sizes {
            let k = images.iter().position(|v| v.len() == w * h).unwrap_or(0);
            black_box(fft2_real(&images[k], w, h));
        }
    });

    let all = median_time(reps, || {
        black_box(synthesize(&photo, &opts).unwrap());
    });
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let one = median_time(reps, || {
        single.install(|| black_box(synthesize(&photo, &opts).unwrap()));
    });
    let channel: Vec<f32> = photo.pixels.iter().map(|p| p[0]).collect();
    let pyramid = median_time(reps, || {
        black_box(plan.synthesise(&plan.analyse(&channel)));
    });
    println!(
        "  the FFTs it needs ({} 2D transforms, one thread): {:.0} ms",
        sizes.len(),
        ms(ffts)
    );
    println!(
        "  512² RGB, 5 iterations, every thread: {:.0} ms = {:.2}× its FFTs, {:.2}× the 1.5 s target",
        ms(all),
        ms(all) / ms(ffts),
        ms(all) / 1500.0
    );
    println!(
        "  512² RGB, 5 iterations, one thread (as in the worker): {:.0} ms = {:.2}× its FFTs",
        ms(one),
        ms(one) / ms(ffts)
    );
    println!(
        "  one 512² channel's pyramid, analysis + reconstruction: {:.1} ms ({} transforms)",
        ms(pyramid),
        plan.analysis_transforms().len() + plan.synthesis_transforms().len()
    );
    // Solid textures (HB §4) from the sample's top-left 256² (one run each: seconds).
    let crop = photo
        .crop(proctex::input::Crop {
            x: 0,
            y: 0,
            w: 256,
            h: 256,
        })
        .expect("crop");
    for n in [64u32, 128] {
        let opts = SolidOptions {
            n,
            ..SolidOptions::default()
        };
        let start = std::time::Instant::now();
        black_box(synthesize_solid(&crop, &opts, &|_, _| true).unwrap());
        let t = start.elapsed();
        println!(
            "  solid {n}³ from a 256² crop, 5 iterations, every thread: {:.0} ms ({:.2}× the 2D synthesis of 512²)",
            ms(t),
            ms(t) / ms(all)
        );
    }
}
