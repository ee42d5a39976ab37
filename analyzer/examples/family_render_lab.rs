//! The fitted families' renders in scattering space: for every quadrant of a photo set, the
//! automatic ranking (default refinement, seed 1) and, for each family whose fit orders the
//! list (`retrieve::Suggestion::render_ordered`), the standardised scattering distance
//! (`scattering::standardised_distance`) of its fast fit's render (the ranking's `preview`,
//! rendered as the ranking renders its candidates) to the patch; likewise the noise model's;
//! and the same of each family's first round of its final fit (`structure::FirstRound`, what the
//! nearer-render rule renders for the nearest family).
//! A laboratory of choosing among the fitted families by the render nearest in scattering
//! space. Prints TSV: file, patch, category, labels, the ranking's first, then
//! `name:fast:first_round` for the noise model (its one fit twice) and each render-ordered
//! family in the ranking's order.
//!
//! `cargo run --release -p proctex-analyzer --example family_render_lab -- SET_DIR`

mod lab_common;

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::noise::Tile;
use proctex::render::{Prepared, View, render_prepared};
use proctex::retrieve::{Refinement, suggest_with};
use proctex::scattering::{features, standardised_distance};
use proctex::structure::FirstRound;

const PATCHES: [&str; 4] = ["top-left", "top-right", "bottom-left", "bottom-right"];

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: family_render_lab SET_DIR");
    let patches = lab_common::load(&dir);
    let db = Db::shipped();
    let opts = Options::default();
    let tile = Tile::new_2d(opts.seed);
    let lines = proctex::parallel::map_in_order(&patches, |p| {
        let ranked = suggest_with(db, &p.photo, &opts, Refinement::default(), &|_, _| true);
        let photo = features(&p.photo);
        let (w, h) = (p.photo.width, p.photo.height);
        let cells: Vec<String> = ranked
            .iter()
            .filter(|s| s.render_ordered)
            .filter_map(|s| {
                let distance = |params: &proctex::params::Params| {
                    let render =
                        render_prepared(&Prepared::new(params), &tile, w, h, &View::default());
                    standardised_distance(&photo, &features(&render.to_photo()))
                };
                let fast = distance(s.preview.as_ref()?);
                let first = match &s.pattern {
                    Some((pattern, swapped)) => distance(
                        &FirstRound::new(db, &p.photo, pattern, &opts, *swapped)
                            .amplitude_fit()
                            .params,
                    ),
                    None => fast,
                };
                Some(format!("{}:{fast:.4}:{first:.4}", s.name))
            })
            .collect();
        format!("{}\t{}", ranked[0].name, cells.join("\t"))
    });
    for (k, (p, line)) in patches.iter().zip(lines).enumerate() {
        let category = if p.structured {
            "structured"
        } else {
            "stochastic"
        };
        println!(
            "{}\t{}\t{category}\t{}\t{line}",
            p.file,
            PATCHES[k % 4],
            p.labels.join(",")
        );
    }
}
