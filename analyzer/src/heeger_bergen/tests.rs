use super::*;
use crate::render::Image;
use crate::seamless::seam_stats;

/// A `w × h` photo whose pixel `i` at `(x, y)` is `f(x, y, i)`.
fn photo_of(w: u32, h: u32, f: impl Fn(f32, f32, u32) -> [f32; 3]) -> Photo {
    Photo {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|i| f((i % w) as f32, (i / w) as f32, i))
            .collect(),
    }
}

/// A colour test texture that is not periodic on its grid: oriented stripes at a scale the
/// pyramid resolves, blobs, grain and a gradient, in three correlated colours.
fn sample(w: u32, h: u32) -> Photo {
    photo_of(w, h, |x, y, i| {
        let stripes = (0.45 * x + 0.2 * y).sin();
        let blobs = (0.07 * x).sin() * (0.09 * y + 1.0).cos();
        let grain = rng::gaussian(3, 5, i) as f32;
        let v = 0.5 + 0.18 * stripes + 0.12 * blobs + 0.05 * grain + 0.001 * x;
        [v, 0.8 * v + 0.05 * blobs, 0.6 * v - 0.04 * stripes].map(|c| c.clamp(0.0, 1.0))
    })
}

#[test]
fn histogram_matching_is_exact_for_equal_lengths_and_keeps_the_order() {
    let mut v: Vec<f32> = (0..1000).map(|i| rng::gaussian(1, 2, i) as f32).collect();
    let before = v.clone();
    let target: Vec<f32> = (0..1000).map(|i| (i as f32 / 999.0).powi(3)).collect();
    match_histogram(&mut v, &target);
    assert_eq!(sorted(&v), target);
    for i in 0..1000 {
        for j in [i + 1, i + 7].into_iter().filter(|&j| j < 1000) {
            assert_eq!(before[i] < before[j], v[i] < v[j]);
        }
    }
    // Another length: the quantiles of the target, interpolated.
    let mut short: Vec<f32> = (0..10).map(|i| i as f32).collect();
    match_histogram(&mut short, &target);
    for (i, s) in short.iter().enumerate() {
        let q = (i as f64 + 0.5) / 10.0;
        assert!((s - (q as f32).powi(3)).abs() < 2e-3, "{i}: {s}");
    }
}

/// The output tiles: its wrap-around seams are like its interior neighbours (ratio near 1),
/// where the sample's own seams are not.
#[test]
fn output_tiles_seamlessly() {
    let photo = sample(128, 128);
    let out = synthesize(&photo, &RasterOptions::new(128, 128)).unwrap();
    let as_image = |p: &Photo| Image {
        width: p.width,
        height: p.height,
        pixels: p.pixels.clone(),
    };
    for s in seam_stats(&as_image(&out)) {
        assert!((0.7..1.3).contains(&s.ratio()), "{}", s.ratio());
    }
    let own = seam_stats(&as_image(&photo));
    assert!(own.iter().any(|s| s.ratio() > 1.5), "{}", own[0].ratio());
}

#[test]
fn deterministic_any_size_and_the_photo_colours() {
    let photo = sample(64, 64);
    let opts = RasterOptions {
        iterations: 2,
        ..RasterOptions::new(100, 70)
    };
    let a = synthesize(&photo, &opts).unwrap();
    let b = synthesize(&photo, &opts).unwrap();
    assert_eq!(a, b);
    assert_eq!((a.width, a.height), (100, 70));
    let c = synthesize(&photo, &RasterOptions { seed: 2, ..opts }).unwrap();
    assert_ne!(a, c);
    // Each RGB channel has the photo's distribution (quantiles within a 255th).
    for ch in 0..3 {
        let mine = sorted(&a.pixels.iter().map(|p| p[ch]).collect::<Vec<_>>());
        let theirs = sorted(&photo.pixels.iter().map(|p| p[ch]).collect::<Vec<_>>());
        for d in 1..20 {
            let q = d as f64 / 20.0;
            assert!((quantile(&mine, q) - quantile(&theirs, q)).abs() < 1.0 / 255.0);
        }
    }
}

#[test]
fn cancel_stops_the_loop() {
    let photo = sample(64, 64);
    let calls = AtomicUsize::new(0);
    let limit = (MAX_SYNTHESIS_PIXELS, "");
    let out = synthesize_progress(&photo, &RasterOptions::new(64, 64), limit, &|_, _| {
        calls.fetch_add(1, Ordering::SeqCst) < 2
    })
    .unwrap();
    assert!(out.is_none());
    assert!(calls.load(Ordering::SeqCst) < 3 * DEFAULT_ITERATIONS as usize);
}

#[test]
fn bad_input_is_refused_in_words() {
    let small = sample(20, 40);
    let e = synthesize(&small, &RasterOptions::new(64, 64)).unwrap_err();
    assert!(matches!(e, Error::TooSmall { .. }), "{e}");
    let photo = sample(64, 64);
    for (opts, words) in [
        (RasterOptions::new(16, 64), "at least 32"),
        (RasterOptions::new(20_000, 64), "a side may be at most"),
        (RasterOptions::new(8192, 8192), "over the limit"),
        (
            RasterOptions {
                orientations: 0,
                ..RasterOptions::new(64, 64)
            },
            "--orientations 0",
        ),
        (
            RasterOptions {
                scales: 0,
                ..RasterOptions::new(64, 64)
            },
            "--scales 0",
        ),
        (
            RasterOptions {
                iterations: 1000,
                ..RasterOptions::new(64, 64)
            },
            "--iterations 1000",
        ),
    ] {
        let e = synthesize(&photo, &opts).unwrap_err().to_string();
        assert!(e.contains(words), "{e}");
    }
}

#[test]
fn the_stepwise_synthesis_is_the_same_synthesis() {
    let photo = sample(64, 48);
    let opts = RasterOptions {
        iterations: 3,
        ..RasterOptions::new(80, 64)
    };
    let mut s = Synthesis::new(&photo, &opts, (MAX_SYNTHESIS_PIXELS, "")).unwrap();
    assert_eq!((s.done(), s.steps()), (0, 9));
    let mut rounds = 0;
    while s.step() {
        rounds += 1;
    }
    assert_eq!((rounds + 1, s.done()), (9, 9));
    assert!(!s.step(), "no rounds left");
    assert_eq!(s.photo(), synthesize(&photo, &opts).unwrap());
    // No rounds at all: the histogram-matched noise.
    let none = RasterOptions {
        iterations: 0,
        ..opts
    };
    let mut s = Synthesis::new(&photo, &none, (MAX_SYNTHESIS_PIXELS, "")).unwrap();
    assert!(!s.step());
    assert_eq!(s.photo(), synthesize(&photo, &none).unwrap());
}

/// A second test texture, unlike `sample`: blobs in other colours.
fn other(w: u32, h: u32) -> Photo {
    photo_of(w, h, |x, y, i| {
        let blobs = (0.21 * x).cos() * (0.17 * y).sin();
        let grain = rng::gaussian(9, 5, i) as f32;
        [
            0.3 + 0.1 * blobs,
            0.5 + 0.15 * blobs + 0.03 * grain,
            0.7 - 0.1 * blobs,
        ]
    })
}

#[test]
fn a_mixture_runs_from_one_synthesis_to_the_other() {
    let (a, b) = (sample(64, 64), other(80, 72));
    let opts = RasterOptions {
        iterations: 2,
        ..RasterOptions::new(64, 64)
    };
    let limit = (MAX_SYNTHESIS_PIXELS, "");
    let at = |m| synthesize_mixture(&a, &b, m, &opts, limit).unwrap();
    assert_eq!(at(0.0), synthesize(&a, &opts).unwrap());
    assert_eq!(at(1.0), synthesize(&b, &opts).unwrap());
    // Halfway, each RGB channel's median lies between the two samples'.
    let median = |p: &Photo, c: usize| {
        let v = sorted(&p.pixels.iter().map(|x| x[c]).collect::<Vec<_>>());
        v[v.len() / 2]
    };
    let half = at(0.5);
    for c in 0..3 {
        let (lo, hi) = (
            median(&a, c).min(median(&b, c)),
            median(&a, c).max(median(&b, c)),
        );
        let mid = median(&half, c);
        assert!(
            mid > lo - 0.01 && mid < hi + 0.01,
            "channel {c}: {mid} not in {lo}..{hi}"
        );
        assert!(
            (mid - (lo + hi) / 2.0).abs() < 0.25 * (hi - lo) + 0.01,
            "channel {c}"
        );
    }
    let e = synthesize_mixture(&a, &b, 1.5, &opts, limit).unwrap_err();
    assert!(e.to_string().contains("--m 1.5"), "{e}");
}

#[test]
fn the_quantile_mixture_of_sorted_values_is_sorted_and_exact_at_the_ends() {
    let a: Vec<f32> = (0..10).map(|i| i as f32).collect();
    let b: Vec<f32> = (0..25).map(|i| 100.0 + (i * i) as f32).collect();
    for m in [0.0, 0.3, 1.0] {
        let v = mix_sorted(&a, &b, m);
        assert_eq!(v.len(), 25);
        assert!(v.windows(2).all(|w| w[0] <= w[1]));
    }
    assert_eq!(mix_sorted(&b, &a, 0.0), b);
    assert_eq!(mix_sorted(&a, &b, 1.0), b);
}

#[test]
fn the_stepwise_mixture_is_the_same_mixture() {
    let (a, b) = (sample(64, 64), other(48, 56));
    let opts = RasterOptions {
        iterations: 2,
        ..RasterOptions::new(64, 40)
    };
    let limit = (MAX_SYNTHESIS_PIXELS, "");
    let mut s = Synthesis::mixture(&a, &b, 0.4, &opts, limit).unwrap();
    while s.step() {}
    assert_eq!(
        s.photo(),
        synthesize_mixture(&a, &b, 0.4, &opts, limit).unwrap()
    );
}
