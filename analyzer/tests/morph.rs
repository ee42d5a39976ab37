//! Morphing (Lagae §8): endpoints, validity and orthonormality along t, and smoothness.
//!
//! Smoothness measure: render a 96² view at t = 0, 1/32, …, 1 and take the mean absolute
//! difference between consecutive frames (8-bit units). A smooth morph has no step much larger
//! than the typical one: we require every step ≤ 3× the median step (and the whole change to be
//! spread over many steps).

mod common;

use common::sample;
use proctex::analyze::{Options, analyze_photo};
use proctex::morph::{morph, morph_path};
use proctex::params::Params;
use proctex::render::{View, render};

fn analysed(name: &str) -> Params {
    analyze_photo(&sample(name), &Options::default())
        .unwrap()
        .params
}

fn image(p: &Params) -> Vec<u8> {
    render(p, 96, 96, &View::default()).to_rgb8()
}

fn mad(a: &[u8], b: &[u8]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| x.abs_diff(*y) as f64)
        .sum::<f64>()
        / a.len() as f64
}

fn check_pair(a: &Params, b: &Params) -> (f64, f64) {
    assert_eq!(image(&morph(a, b, 0.0).unwrap()), image(a), "t = 0");
    assert_eq!(image(&morph(a, b, 1.0).unwrap()), image(b), "t = 1");
    let steps = 32;
    let mut frames = Vec::new();
    for s in 0..=steps {
        let t = s as f32 / steps as f32;
        let p = morph(a, b, t).unwrap();
        p.validate().unwrap();
        let m = p.colour.basis.map(|r| r.map(|v| v as f64));
        for i in 0..3 {
            for j in 0..3 {
                let d = proctex::colour::dot(m[i], m[j]);
                let want = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (d - want).abs() < 1e-5,
                    "t = {t}: basis not orthonormal ({d})"
                );
            }
        }
        frames.push(image(&p));
    }
    let mut diffs: Vec<f64> = frames.windows(2).map(|w| mad(&w[0], &w[1])).collect();
    let max = diffs.iter().cloned().fold(0.0, f64::max);
    diffs.sort_by(f64::total_cmp);
    let median = diffs[diffs.len() / 2];
    (max, median)
}

#[test]
fn morphs_are_exact_at_the_ends_valid_and_smooth() {
    // The rock with an output tone curve, fitted here where its analysis kept none (whether
    // one is kept is the analysis' choice per photo), so that the morph fades a curve.
    let mut rock = analysed("stk_rock_mountain_512.png");
    if rock.model.tone().is_none() {
        let photo = proctex::analyze::prepare_photo(
            &sample("stk_rock_mountain_512.png"),
            &Options::default(),
        )
        .unwrap();
        let tone = proctex::noise_tone::fit_noise_tone(&photo, &rock, 9);
        rock.model.noise_layer_mut().tone = tone;
    }
    let grass = analysed("skimage_grass_512.png");
    // 256² analysis: one band fewer than the 512² ones.
    let black = analysed("stk_blackrock_256.png");
    let mut no_hist = analysed("skimage_gravel_512.png");
    let m = no_hist.model.noise_layer_mut();
    m.histogram.enabled = false;
    no_hist.transform.scale = 3.0;
    no_hist.transform.rotation_deg = 170.0;
    no_hist.colour.contrast = 1.5;
    // The rock's output tone curve fading out towards a texture without one.
    let mut plain = grass.clone();
    plain.model.noise_layer_mut().tone = None;
    assert!(rock.model.tone().is_some());
    for (name, a, b) in [
        ("rock → grass without its tone curve", &rock, &plain),
        ("rock → grass", &rock, &grass),
        ("grass → blackrock (7 vs 8 bands)", &grass, &black),
        (
            "rock → gravel (histogram off, scale 3, 170°)",
            &rock,
            &no_hist,
        ),
    ] {
        let (max, median) = check_pair(a, b);
        println!("{name}: step between frames: median {median:.2}, max {max:.2} (8-bit MAD)");
        assert!(
            max <= 3.0 * median.max(0.2),
            "{name}: max step {max}, median {median}"
        );
    }
}

#[test]
fn paths_through_several_textures_pass_every_key() {
    let keys = [
        analysed("stk_rock_mountain_512.png"),
        analysed("skimage_grass_512.png"),
        analysed("skimage_gravel_512.png"),
    ];
    assert_eq!(image(&morph_path(&keys, 0.0).unwrap()), image(&keys[0]));
    assert_eq!(image(&morph_path(&keys, 0.5).unwrap()), image(&keys[1]));
    assert_eq!(image(&morph_path(&keys, 1.0).unwrap()), image(&keys[2]));
    assert!(morph_path(&keys[..1], 0.5).is_err());
    assert!(morph(&keys[0], &keys[1], 1.5).is_err());
}
