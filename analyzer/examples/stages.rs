//! Diagnostic: per quarter-octave ring, the dB difference to the analysed patch of auto's
//! render with its tone curve, without it, and of its ramp alone (residual silenced); and of
//! the noise model's render. `cargo run --release --example stages -- PHOTO QX QY [SEED]`
//! analyses quadrant (QX, QY) ∈ {0, 1}² of PHOTO. Where the ramp alone exceeds the patch, the
//! residual (which can only add power) cannot bring the render back.
use proctex::analyze::Options;
use proctex::distance::radial_spectrum;
use proctex::evaluate::synthesize_model;
use proctex::input::{Crop, Photo};
use proctex::params::Model;
use proctex::render::{View, render};
use proctex::retrieve::{ModelChoice, Refinement};

fn db(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| 10.0 * x.max(1e-20).log10()).collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let photo = Photo::decode(&std::fs::read(&args[1]).expect("read")).expect("decode");
    let qx: u32 = args[2].parse().unwrap();
    let qy: u32 = args[3].parse().unwrap();
    let seed: u32 = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(1);
    let (hw, hh) = (photo.width / 2, photo.height / 2);
    let src = photo
        .crop(Crop {
            x: qx * hw,
            y: qy * hh,
            w: hw,
            h: hh,
        })
        .unwrap();
    let o = Options {
        seed,
        ..Options::default()
    };
    let rsrc = db(&radial_spectrum(&src));
    let (syn_n, _, _) =
        synthesize_model(&src, &o, ModelChoice::Noise, Refinement::default()).unwrap();
    let (syn, an, _) =
        synthesize_model(&src, &o, ModelChoice::Auto, Refinement::default()).unwrap();
    let mut cols = vec![
        ("noise", db(&radial_spectrum(&syn_n))),
        ("auto", db(&radial_spectrum(&syn))),
    ];
    if let Model::Structured(m) = &an.params.model {
        eprintln!(
            "kind {} scale {} tone {}",
            m.pattern.kind.name(),
            m.pattern.scale,
            m.tone.is_some()
        );
        let mut p = an.params.clone();
        if let Model::Structured(m) = &mut p.model {
            m.tone = None;
        }
        let r = render(&p, src.width, src.height, &View::default()).to_photo();
        cols.push(("notone", db(&radial_spectrum(&r))));
        if let Model::Structured(m) = &mut p.model {
            m.residual.weights.iter_mut().for_each(|w| w.fill(0.0));
            m.residual.histogram.enabled = false;
        }
        let r = render(&p, src.width, src.height, &View::default()).to_photo();
        cols.push(("ramp", db(&radial_spectrum(&r))));
    }
    print!("ring period");
    for (n, _) in &cols {
        print!(" {n:>7}");
    }
    println!();
    for k in 0..rsrc.len() {
        print!("{k:>4} {:>6.1}", 2.0 * 2f64.powf((k as f64 + 0.5) / 4.0));
        for (_, c) in &cols {
            print!(" {:>7.2}", c[k] - rsrc[k]);
        }
        println!();
    }
}
