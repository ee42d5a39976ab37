//! The nearer render in scattering space (`retrieve::NEARER_RENDER_MARGIN`) with several renders
//! of the nearest family: the ranking's fast fit (its `preview`), the whole final fit
//! (`structure::fit_structured`, what choosing that family adopts and `proctex synth --model
//! FAMILY` renders), the final fit on the photo reduced to the scattering's side (rendered
//! there), and the final fit's first round alone (`structure::FirstRound`, what the product
//! compares). For every quadrant of a photo set: the automatic ranking (default refinement,
//! seed 1), the classifier's nearest family, and `retrieve::nearer_render_margin` of the noise
//! model's fit against each render of that family, with their times. Prints TSV: file, patch
//! (top-left, top-right, bottom-left, bottom-right), category, labels, then the margins and
//! times: 4 the fast fit's margin, 5 the final fit's, 6 the final fit's ms, 7 the margin's ms, 8
//! the reduced final fit's margin, 9 its ms (fit and margin), 10 the first round's margin, 11
//! its ms (`tools/devset_nearer_render_cv.py RUN --margins TSV COLUMN` scores any margin column
//! as the rule's, RUN a product run that recorded where the noise model led).
//!
//! `cargo run --release -p proctex-analyzer --example nearer_render_lab -- SET_DIR`

mod lab_common;

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::noise::Tile;
use proctex::render::{Prepared, View, render_prepared};
use proctex::retrieve::nearer_render_margin;
use proctex::scattering::{SIDE, features, standardised_distance};
use proctex::structure::{FirstRound, fit_structured};
use std::time::Instant;

const PATCHES: [&str; 4] = ["top-left", "top-right", "bottom-left", "bottom-right"];

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: nearer_render_lab SET_DIR");
    let patches = lab_common::load(&dir);
    let db = Db::shipped();
    let opts = Options::default();
    let lines = proctex::parallel::map_in_order(&patches, |p| {
        let (noise, family) = lab_common::ranking_with_nearest(&p.photo, &opts);
        let tile = Tile::new_2d(opts.seed);
        match (noise.as_ref(), family.as_ref()) {
            (Some(noise), Some(family)) => {
                let fast = family
                    .preview
                    .as_ref()
                    .expect("the nearest family is fitted");
                let start = Instant::now();
                let margin_fast = nearer_render_margin(&p.photo, noise, fast, &tile);
                let margin_ms = start.elapsed().as_secs_f64() * 1000.0;
                let (pattern, swapped) = family.pattern.as_ref().expect("a family");
                let start = Instant::now();
                let fitted = fit_structured(db, &p.photo, pattern, &opts, *swapped).params;
                let fit_ms = start.elapsed().as_secs_f64() * 1000.0;
                let margin_final = nearer_render_margin(&p.photo, noise, &fitted, &tile);
                // The final fit's first round alone (the residual's amplitude; no rougher
                // variants).
                let start = Instant::now();
                let amplitude_only = FirstRound::new(db, &p.photo, pattern, &opts, *swapped)
                    .amplitude_fit()
                    .params;
                let amplitude_ms = start.elapsed().as_secs_f64() * 1000.0;
                let margin_amplitude =
                    nearer_render_margin(&p.photo, noise, &amplitude_only, &tile);
                // The final fit on the photo reduced to the scattering's side, rendered there.
                let start = Instant::now();
                let half = p.photo.reduce_to(SIDE as u32);
                let mut pattern = pattern.clone();
                pattern.scale *= half.width as f32 / p.photo.width as f32;
                let fitted = fit_structured(db, &half, &pattern, &opts, *swapped).params;
                let render = |params: &proctex::params::Params, w: u32, h: u32| {
                    let prepared = Prepared::new(params);
                    features(&render_prepared(&prepared, &tile, w, h, &View::default()).to_photo())
                };
                let photo = features(&p.photo);
                let margin_half =
                    standardised_distance(&photo, &render(noise, p.photo.width, p.photo.height))
                        - standardised_distance(&photo, &render(&fitted, half.width, half.height));
                let half_ms = start.elapsed().as_secs_f64() * 1000.0;
                format!(
                    "{margin_fast:.4}\t{margin_final:.4}\t{fit_ms:.0}\t{margin_ms:.0}\t{margin_half:.4}\t{half_ms:.0}\t{margin_amplitude:.4}\t{amplitude_ms:.0}"
                )
            }
            _ => "-inf\t-inf\t0\t0\t-inf\t0\t-inf\t0".to_string(),
        }
    });
    for (k, (p, line)) in patches.iter().zip(lines).enumerate() {
        let category = if p.structured {
            "structured"
        } else {
            "stochastic"
        };
        let labels = p.labels.join(",");
        println!(
            "{}\t{}\t{category}\t{labels}\t{line}",
            p.file,
            PATCHES[k % 4]
        );
    }
}
