//! Do the fitted lattices keep the photo's proportions? For every structured quadrant of a
//! photo set, each lattice-like family (brick, grid, planks, cells) fitted as `proctex analyze
//! --model FAMILY` fits it (default refinement, seed 1) and rendered at the quadrant's size; the
//! first period vector of the photo's and of the render's detrended autocorrelation
//! (`cues::lattice_period`) and the ratio of their lengths.
//!
//! Prints TSV: file, patch index, labels, family, the photo's period length and autocorrelation
//! there, the render's, and render / photo.
//!
//! `cargo run --release -p proctex-analyzer --example lattice_period_lab -- SET_DIR [FAMILY...]`

mod lab_common;

use proctex::analyze::Options;
use proctex::cues::lattice_period;
use proctex::evaluate::render_params_at_photo_size;
use proctex::pattern::PatternKind;
use proctex::retrieve::{ModelChoice, Refinement, analyze_photo_model};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = args
        .get(1)
        .expect("usage: lattice_period_lab SET_DIR [FAMILY...]");
    let families: Vec<PatternKind> = if args.len() > 2 {
        args[2..]
            .iter()
            .map(|a| PatternKind::from_name(a).expect("a family name"))
            .collect()
    } else {
        ["brick", "grid", "planks", "cells"]
            .iter()
            .map(|a| PatternKind::from_name(a).unwrap())
            .collect()
    };
    let patches: Vec<(usize, lab_common::Patch)> = lab_common::load(dir)
        .into_iter()
        .enumerate()
        .filter(|(_, p)| p.structured)
        .collect();
    let jobs: Vec<(usize, &lab_common::Patch, PatternKind)> = patches
        .iter()
        .flat_map(|(i, p)| families.iter().map(move |&k| (*i % 4, p, k)))
        .collect();
    let lines = proctex::parallel::map_in_order(&jobs, |&(q, p, kind)| {
        let opts = Options::default();
        let (a, _) = analyze_photo_model(
            &p.photo,
            &opts,
            ModelChoice::Kind(kind),
            Refinement::default(),
        )
        .unwrap();
        let render = render_params_at_photo_size(&a.params, &p.photo);
        let len = |v: Option<((f32, f32), f32)>| {
            v.map_or((f32::NAN, 0.0), |((x, y), h)| ((x * x + y * y).sqrt(), h))
        };
        let (pl, ph) = len(lattice_period(&p.photo));
        let (rl, rh) = len(lattice_period(&render));
        format!(
            "{}\t{q}\t{}\t{}\t{pl:.2}\t{ph:.3}\t{rl:.2}\t{rh:.3}\t{:.3}",
            p.file,
            p.labels.join("/"),
            kind.name(),
            rl / pl
        )
    });
    for l in lines {
        println!("{l}");
    }
}
