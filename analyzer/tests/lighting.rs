//! The analysis's optional lighting flattening (`--flatten-lighting`): a photo lit from one side
//! is analysed as the same photo evenly lit, and the flag reaches the CLI's analysis.

use std::process::Command;

use proctex::analyze::{Options, analyze_photo};
use proctex::input::{Crop, Photo};

mod common;

fn brick_crop() -> Photo {
    let photo = common::sample("skimage_brick_512.png");
    photo.crop(Crop::parse("0,0,256,256").unwrap()).unwrap()
}

/// `photo` under a lamp to its right: brighter by e^0.8 ≈ 2.2 from the left edge to the right.
fn lit_from_the_right(photo: &Photo) -> Photo {
    let w = photo.width as usize;
    let pixels = photo
        .pixels
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let u = 2.0 * (i % w) as f32 / (w - 1) as f32 - 1.0;
            p.map(|v| (v * (0.4 * u).exp()).min(1.0))
        })
        .collect();
    Photo {
        pixels,
        ..photo.clone()
    }
}

fn relative_gap(a: &[f32], b: &[f32]) -> f32 {
    let num: f32 = a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum();
    num / a.iter().map(|x| x.abs()).sum::<f32>()
}

#[test]
fn a_photo_lit_from_one_side_is_analysed_as_the_evenly_lit_one() {
    let even = brick_crop();
    let lit = lit_from_the_right(&even);
    let analyse = |photo: &Photo, flatten_lighting: bool| {
        let opts = Options {
            size: 256,
            flatten_lighting,
            ..Options::default()
        };
        analyze_photo(photo, &opts).expect("analyses").params
    };
    let (plain_even, plain_lit) = (analyse(&even, false), analyse(&lit, false));
    let (flat_even, flat_lit) = (analyse(&even, true), analyse(&lit, true));
    let weights =
        |p: &proctex::params::Params| p.noise().expect("a noise model").weights[0].clone();
    let plain = relative_gap(&weights(&plain_even), &weights(&plain_lit));
    let flat = relative_gap(&weights(&flat_even), &weights(&flat_lit));
    // Lit, the gradient's energy lands in the coarse bands; flattened, both photos are the same
    // photo but for the few pixels the lamp clipped at white.
    assert!(
        plain > 0.05,
        "the lamp should show in the plain analysis: {plain}"
    );
    assert!(flat < 0.2 * plain, "flattened {flat} against plain {plain}");
    let mean = |p: &proctex::params::Params| p.colour.mean;
    let gap = |a: [f32; 3], b: [f32; 3]| (0..3).map(|c| (a[c] - b[c]).abs()).fold(0.0, f32::max);
    assert!(gap(mean(&flat_even), mean(&flat_lit)) < 0.01);
    // Off by default: the default options analyse the pixels as they are.
    assert!(!Options::default().flatten_lighting);
}

#[test]
fn the_cli_takes_the_flag() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "analyze",
            "--json",
            "--size",
            "256",
            "--crop",
            "0,0,256,256",
        ];
        args.extend_from_slice(extra);
        let photo = format!(
            "{}/../www/samples/skimage_brick_512.png",
            env!("CARGO_MANIFEST_DIR")
        );
        args.push(&photo);
        let o = Command::new(env!("CARGO_BIN_EXE_proctex"))
            .args(&args)
            .output()
            .expect("runs");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let plain = run(&["--model", "noise"]);
    let flat = run(&["--model", "noise", "--flatten-lighting"]);
    assert!(plain.contains("\"weights\"") && flat.contains("\"weights\""));
    assert_ne!(
        plain, flat,
        "the brick crop has a gradient of its own to take out"
    );
    // The params' provenance says so (and nothing when it is off).
    assert!(flat.contains("\"flattened_lighting\": true"), "{flat}");
    assert!(!plain.contains("flattened_lighting"));
}
