//! Speed benchmark (not a test): prints ratios measured in one run, so a noisy shared machine
//! moves numerator and denominator together.
//!
//! - analysis of a 512² and a 2048² photo (decoded pixels in, params out, single thread — the
//!   same code path as in the browser) vs three plain rustfft 2D FFTs of the same size (the cost
//!   floor of any per-channel spectral analysis). Target: ratio ≤ 2, for Lagae's analysis;
//!   the time with the noise model's output tone curve (its per-photo allocation) is printed
//!   beside it.
//! - render throughput of the CPU reference renderer at 1024², Mpixel/s, one thread and all.
//! - model retrieval for a 256² query, single thread: the descriptor (two-tone map
//!   and Gabor bank) vs its own FFTs alone, and descriptor + search of every family (target
//!   ≤ 250 ms in WASM; e2e/bench times the same in the browser); the refinement's time and how
//!   much it lowers the structure distance; the database's build time (target ≤ 3 min on this
//!   2-core machine) and size (budget 8 MB).
//! - the full automatic analysis of a 256² crop (retrieval, refinement, ranking and the chosen
//!   model's final fit, what `proctex analyze --crop 0,0,256,256` does) on every thread, against
//!   the 1.5 s target and against the noise model's analysis of the same crop in the same run.
//!
//! Run: `cargo bench -p proctex-analyzer --bench analysis` (the full run), or with `-- --quick`
//! (what `scripts/test.sh` runs in CI): fewer repetitions, and the database build timed on one
//! entry in 8 and projected to all of them (the unit test `shipped_database_is_fresh_and_small`
//! rebuilds the whole database already), the size that of the shipped file (which that test
//! checks is the build's). Every line and ratio is printed in both modes.

mod common;

use std::hint::black_box;
use std::time::Instant;

use common::{median_time, ms};

use proctex::analyze::{Options, analyze_photo};
use proctex::db::{DB_SEED, Db, describe_pattern, query, sample as db_sample, samples};
use proctex::gabor::{descriptor_image, fft_floor};
use proctex::input::Photo;
use proctex::noise::Tile;
use proctex::pattern::PatternKind;
use proctex::render::{Prepared, View, render, render_prepared, tile_for};
use proctex::retrieve::{Refinement, Suggester, suggest_with};
use proctex::spectrum::fft2_real;
use proctex::two_tone::two_tone;

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

/// Entries of the database described in the quick mode's build: one in this many.
const QUICK_DB_STRIDE: usize = 8;

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    println!(
        "proctex analysis benchmark (median of repeated runs; ratios within one run){}",
        if quick {
            "; quick mode (fewer repetitions; the database build projected from 1 entry in 8)"
        } else {
            ""
        }
    );
    let single = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let reps_of = |full: usize| if quick { full.div_ceil(3) } else { full };
    for (size, reps) in [(512u32, reps_of(21)), (2048, reps_of(5))] {
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
        // Lagae's analysis (what the target is for), then with the output tone curve's
        // per-photo allocation (`noise_tone`), which renders samples of the model.
        let lagae = Options {
            tone: false,
            ..opts
        };
        let analysis = single.install(|| {
            median_time(reps, || {
                black_box(analyze_photo(black_box(&photo), &lagae).unwrap());
            })
        });
        let toned = single.install(|| {
            median_time(reps, || {
                black_box(analyze_photo(black_box(&photo), &opts).unwrap());
            })
        });
        println!(
            "analysis {size}²: {:8.2} ms   three 2D FFTs: {:8.2} ms   ratio {:.2} (target ≤ 2)   [{n} px]; \
             with the output tone curve {:8.2} ms (ratio {:.2})",
            analysis.as_secs_f64() * 1e3,
            fft3.as_secs_f64() * 1e3,
            analysis.as_secs_f64() / fft3.as_secs_f64(),
            toned.as_secs_f64() * 1e3,
            toned.as_secs_f64() / fft3.as_secs_f64()
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

    retrieval(&single, reps_of(11));
    full_analysis(reps_of(5));
    database_build(quick);
}

/// The automatic analysis of each sample's top-left 256² crop, every thread, against the
/// target (1.5 s natively) and against the noise model alone on the same crop.
fn full_analysis(reps: usize) {
    use proctex::input::Crop;
    use proctex::retrieve::{ModelChoice, analyze_with_model};
    let db = Db::shipped();
    let opts = Options::default();
    for name in ["skimage_brick_512.png", "skimage_gravel_512.png"] {
        let crop = sample(name)
            .crop(Crop {
                x: 0,
                y: 0,
                w: 256,
                h: 256,
            })
            .expect("512² sample");
        let mut chosen = "";
        let auto = median_time(reps, || {
            let (a, s) = analyze_with_model(
                db,
                black_box(&crop),
                &opts,
                ModelChoice::Auto,
                Refinement::default(),
            );
            chosen = s.first().map_or("noise", |s| s.name);
            black_box(a);
        });
        let noise = median_time(reps, || {
            black_box(proctex::analyze::analyze_prepared(black_box(&crop), &opts));
        });
        println!(
            "full automatic analysis, {name} top-left 256² crop: {:.0} ms on {} threads (target ≤ \
             1500 ms natively: ratio {:.2}); the noise model alone {:.0} ms ({:.1}× it); chosen: \
             {chosen}",
            ms(auto),
            rayon::current_num_threads(),
            auto.as_secs_f64() / 1.5,
            ms(noise),
            auto.as_secs_f64() / noise.as_secs_f64()
        );
    }
}

fn sample(name: &str) -> Photo {
    let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
    Photo::decode(&std::fs::read(path).expect("sample")).expect("decodes")
}

fn retrieval(single: &rayon::ThreadPool, reps: usize) {
    let db = Db::shipped();
    let opts = Options::default();
    for name in ["skimage_brick_512.png", "skimage_gravel_512.png"] {
        let photo = sample(name).reduced(256).expect("512² sample");
        let (w, h) = (photo.width as usize, photo.height as usize);
        let (ffts, descriptor, retrieve) = single.install(|| {
            let map = descriptor_image(&two_tone(&photo).structure, w, h);
            (
                median_time(reps, || {
                    black_box(fft_floor(black_box(&map)));
                }),
                median_time(reps, || {
                    black_box(query(&two_tone(black_box(&photo)).structure, w, h));
                }),
                median_time(reps, || {
                    black_box(Suggester::new(db, &photo, &opts, Refinement::default()));
                }),
            )
        });
        println!(
            "retrieval, {name} as a 256² query (1 thread): descriptor {:.1} ms, its FFTs alone {:.1} ms \
             (ratio {:.2}); descriptor + search of {} entries {:.1} ms (target ≤ 250 in WASM; \
             {:.2}× the FFTs)",
            ms(descriptor),
            ms(ffts),
            descriptor.as_secs_f64() / ffts.as_secs_f64(),
            db.entries.len(),
            ms(retrieve),
            retrieve.as_secs_f64() / ffts.as_secs_f64()
        );
        let t = Instant::now();
        let ranked = suggest_with(db, &photo, &opts, Refinement::default(), &|_, _| true);
        let all = t.elapsed();
        let fams: Vec<_> = ranked.iter().filter(|s| s.pattern.is_some()).collect();
        let gains: Vec<f32> = fams
            .iter()
            .map(|s| s.retrieval_distance - s.refined_distance.unwrap_or(s.retrieval_distance))
            .collect();
        let best = fams
            .iter()
            .min_by(|a, b| {
                let d = |s: &proctex::retrieve::Suggestion| {
                    s.refined_distance.unwrap_or(s.retrieval_distance)
                };
                d(a).total_cmp(&d(b))
            })
            .expect("families");
        let r = Refinement::default();
        println!(
            "refinement, {name}: {} of {} families refined (the others skipped by the bound) × {} \
             evaluations ({} starts) + ranking {:.0} ms on {} threads ({:.0}× retrieval); \
             structure distance lowered by {:.2} on average, {:.2} at most; nearest family {} \
             {:.2} → {:.2}; first: {}",
            fams.iter().filter(|s| s.refined_distance.is_some()).count(),
            fams.len(),
            r.evaluations,
            r.starts,
            ms(all),
            rayon::current_num_threads(),
            all.as_secs_f64() / retrieve.as_secs_f64(),
            gains.iter().sum::<f32>() / gains.len() as f32,
            gains.iter().cloned().fold(0.0, f32::max),
            best.name,
            best.retrieval_distance,
            best.refined_distance.unwrap_or(best.retrieval_distance),
            ranked[0].name
        );
    }
}

/// The database's build time and size: built whole, or (quick) one entry in
/// [`QUICK_DB_STRIDE`] described as `Db::build` describes each, the time projected to all.
fn database_build(quick: bool) {
    let t = Instant::now();
    let (entries, build, bytes, how) = if quick {
        use rayon::prelude::*;
        let jobs: Vec<(PatternKind, usize)> = PatternKind::ALL
            .into_iter()
            .flat_map(|k| (0..samples(k)).map(move |i| (k, i)))
            .collect();
        let tile = Tile::new_2d(DB_SEED);
        let described: Vec<_> = jobs
            .par_iter()
            .step_by(QUICK_DB_STRIDE)
            .map(|&(kind, i)| describe_pattern(&db_sample(kind, i), DB_SEED, &tile))
            .collect();
        let part = t.elapsed();
        let projected = part.mul_f64(jobs.len() as f64 / described.len() as f64);
        let how = format!(
            "projected from {} entries described in {:.1} s; size of the shipped file",
            described.len(),
            part.as_secs_f64()
        );
        (jobs.len(), projected, Db::shipped().to_bytes().len(), how)
    } else {
        let built = Db::build(&|_, _| {});
        let build = t.elapsed();
        let bytes = built.to_bytes().len();
        (built.entries.len(), build, bytes, "built whole".to_string())
    };
    println!(
        "database build: {} entries in {:.1} s on {} threads (target ≤ 180 s: ratio {:.2}); \
         {} bytes ({:.2} MB, budget 8 MB: ratio {:.2}) [{how}]",
        entries,
        build.as_secs_f64(),
        rayon::current_num_threads(),
        build.as_secs_f64() / 180.0,
        bytes,
        bytes as f64 / 1e6,
        bytes as f64 / 8e6
    );
}
