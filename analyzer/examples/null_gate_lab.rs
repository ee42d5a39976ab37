//! The noise model's render as the family classifier's null (a laboratory; docs/devset.md, "A
//! fourth batch of training textures; the noise model's render as the family classifier's
//! null"; `retrieve::RENDER_NULL_MARGIN`, which generalises it to any first candidate).
//!
//! For every quadrant of the development set, as the ranking sees it (reduced to `RANK_SIZE`):
//! the family classifier's squared class distances of the photo, and those of the noise model's
//! renders of it (its analysis at the default options, rendered at the photo's size with the
//! tile of seeds 1, 2, …). A photo whose structure the noise model cannot draw is nearer to a
//! family than the noise model's render of it is; a stochastic photo's render looks to the
//! classifier as the photo does. The output is one TSV row per quadrant (file, quadrant index,
//! category, labels, then `class:photo:render₁/render₂/…` for every class), read by
//! `tools/devset_null_gate_cv.py` (which uses the first render: the ranking's seed).
//!
//! `cargo run --release -p proctex-analyzer --example null_gate_lab -- DEVDIR [SEEDS] > OUT.tsv`
//! (SEEDS renders per quadrant, 2 by default).

mod lab_common;

use proctex::analyze::{Options, analyze_prepared};
use proctex::family_classifier::Class;
use proctex::noise::Tile;
use proctex::render::{Prepared, View, render_prepared};
use proctex::retrieve::{RANK_SIZE, classify};

fn name(c: Class) -> &'static str {
    c.map_or("noise", |k| k.name())
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let seeds: u32 = a.get(2).map_or(2, |s| s.parse().unwrap());
    let opts = Options::default();
    for (i, p) in lab_common::load(&a[1]).iter().enumerate() {
        let small = p.photo.reduced(RANK_SIZE);
        let small = small.as_ref().unwrap_or(&p.photo);
        let photo_d = classify(small);
        let analysis = analyze_prepared(small, &opts);
        let prepared = Prepared::new(&analysis.params);
        let renders: Vec<Vec<(Class, f64)>> = (0..seeds)
            .map(|s| {
                let tile = Tile::new_2d(opts.seed + s);
                let img = render_prepared(
                    &prepared,
                    &tile,
                    small.width,
                    small.height,
                    &View::default(),
                )
                .to_photo();
                classify(&img)
            })
            .collect();
        let mut row = vec![
            p.file.clone(),
            (i % 4).to_string(),
            if p.structured {
                "structured"
            } else {
                "stochastic"
            }
            .to_string(),
            p.labels.join(","),
        ];
        for (c, d) in &photo_d {
            let r: Vec<String> = renders
                .iter()
                .map(|rd| {
                    let x = rd.iter().find(|(k, _)| k == c).unwrap().1;
                    format!("{x:.4}")
                })
                .collect();
            row.push(format!("{}:{d:.4}:{}", name(*c), r.join("/")));
        }
        println!("{}", row.join("\t"));
    }
}
