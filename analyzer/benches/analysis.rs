//! Speed benchmark (not a test): prints ratios measured in one run, so a noisy shared machine
//! moves numerator and denominator together.
//!
//! - analysis of a 512² and a 2048² photo (decoded pixels in, params out, single thread — the
//!   same code path as in the browser) vs three plain rustfft 2D FFTs of the same size (the cost
//!   floor of any per-channel spectral analysis). Target: ratio ≤ 2.
//! - render throughput of the CPU reference renderer at 1024², Mpixel/s, one thread and all.
//!
//! Run: `cargo bench -p proctex-analyzer --bench analysis`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use proctex::analyze::{Options, analyze_photo};
use proctex::input::Photo;
use proctex::render::{Prepared, View, render, render_prepared, tile_for};
use proctex::spectrum::fft2_real;

fn median_time(reps: usize, mut f: impl FnMut()) -> Duration {
    f(); // warm-up: FFT plans, caches
    let mut t: Vec<Duration> = (0..reps)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed()
        })
        .collect();
    t.sort();
    t[reps / 2]
}

fn photo_of_size(size: u32) -> Photo {
    // A real texture at the requested size: the sample photo itself at 512, and its analysed
    // texture rendered at 2048 (a 2048² photo of the same material).
    let path = format!(
        "{}/../www/samples/stk_rock_mountain_512.png",
        env!("CARGO_MANIFEST_DIR")
    );
    let photo = Photo::decode(&std::fs::read(path).expect("sample")).expect("decodes");
    if size == 512 {
        return photo;
    }
    let p = analyze_photo(&photo, &Options::default()).unwrap().params;
    render(&p, size, size, &View::default()).to_photo()
}

fn main() {
    println!("proctex analysis benchmark (median of repeated runs; ratios within one run)");
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    for (size, reps) in [(512u32, 21usize), (2048, 5)] {
        let photo = photo_of_size(size);
        let opts = Options {
            size,
            ..Options::default()
        };
        let n = (size * size) as usize;
        let plane: Vec<f32> = photo.pixels.iter().map(|p| p[0]).collect();
        let fft3 = median_time(reps, || {
            for _ in 0..3 {
                black_box(fft2_real(black_box(&plane), size as usize, size as usize));
            }
        });
        let analysis = single.install(|| {
            median_time(reps, || {
                black_box(analyze_photo(black_box(&photo), &opts).unwrap());
            })
        });
        println!(
            "analysis {size}²: {:8.2} ms   three 2D FFTs: {:8.2} ms   ratio {:.2} (target ≤ 2)   [{n} px]",
            analysis.as_secs_f64() * 1e3,
            fft3.as_secs_f64() * 1e3,
            analysis.as_secs_f64() / fft3.as_secs_f64()
        );
    }

    let photo = photo_of_size(512);
    let params = analyze_photo(&photo, &Options::default()).unwrap().params;
    let prep = Prepared::new(&params);
    let tile = tile_for(&params);
    let view = View::default();
    let mpix = 1024.0 * 1024.0 / 1e6;
    let one = single.install(|| {
        median_time(3, || {
            black_box(render_prepared(&prep, &tile, 1024, 1024, &view));
        })
    });
    let all = median_time(3, || {
        black_box(render_prepared(&prep, &tile, 1024, 1024, &view));
    });
    println!(
        "render 1024² ({} bands × 3 channels, 2D): {:.2} Mpixel/s on 1 thread, {:.2} Mpixel/s on {} threads",
        prep.bands,
        mpix / one.as_secs_f64(),
        mpix / all.as_secs_f64(),
        rayon::current_num_threads()
    );
}
