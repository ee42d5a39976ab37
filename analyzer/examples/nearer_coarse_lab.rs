//! The nearer render in scattering space (`retrieve::NEARER_RENDER_MARGIN`) with the finest
//! scale left out: whether the rule's margin holds on a soft photo when the features that the
//! camera's blur moves most are not compared. For every quadrant of a photo set: the automatic
//! ranking (default refinement, seed 1), the classifier's nearest family's first round of its
//! final fit (what the product compares), and the margin of the noise model's render against it
//! twice: over every scattering feature (the product's) and over the features of scales 1–3
//! alone (the first order's log mean and harmonics of scale 0 and every second-order ratio from
//! it left out). Prints TSV: file, patch, category, labels, 4 the whole margin, 5 the coarse
//! margin (`tools/devset_nearer_render_cv.py RUN --margins TSV COLUMN`).
//!
//! `cargo run --release -p proctex-analyzer --example nearer_coarse_lab -- SET_DIR`

mod lab_common;

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::noise::Tile;
use proctex::render::{Prepared, View, render_prepared};
use proctex::scattering::{DEVIATIONS, ORIENTATIONS, SCALES, features};
use proctex::structure::FirstRound;

/// Whether feature `i` of [`features`] involves the finest scale (the layout its doc gives:
/// per scale a log mean, then per scale two harmonics, then per pair of scales `j1 < j2` one
/// number per orientation difference).
fn involves_finest(i: usize) -> bool {
    if i < SCALES {
        return i == 0;
    }
    if i < 3 * SCALES {
        return (i - SCALES) / 2 == 0;
    }
    // The pairs (0, 1), (0, 2), … come first.
    (i - 3 * SCALES) / ORIENTATIONS < SCALES - 1
}

fn distance(a: &[f64], b: &[f64], coarse: bool) -> f64 {
    (0..a.len())
        .filter(|&i| !(coarse && involves_finest(i)))
        .map(|i| ((a[i] - b[i]) / DEVIATIONS[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: nearer_coarse_lab SET_DIR");
    let patches = lab_common::load(&dir);
    let db = Db::shipped();
    let opts = Options::default();
    let lines = proctex::parallel::map_in_order(&patches, |p| {
        let (noise, family) = lab_common::ranking_with_nearest(&p.photo, &opts);
        let tile = Tile::new_2d(opts.seed);
        let (Some(noise), Some(family)) = (noise.as_ref(), family.as_ref()) else {
            return "-inf\t-inf".to_string();
        };
        let (pattern, swapped) = family.pattern.as_ref().expect("a family");
        let round = FirstRound::new(db, &p.photo, pattern, &opts, *swapped)
            .amplitude_fit()
            .params;
        let render = |params: &proctex::params::Params| {
            let prepared = Prepared::new(params);
            let (w, h) = (p.photo.width, p.photo.height);
            features(&render_prepared(&prepared, &tile, w, h, &View::default()).to_photo())
        };
        let photo = features(&p.photo);
        let (to_noise, to_family) = (render(noise), render(&round));
        let margin =
            |coarse| distance(&photo, &to_noise, coarse) - distance(&photo, &to_family, coarse);
        format!("{:.4}\t{:.4}", margin(false), margin(true))
    });
    for (k, (p, line)) in patches.iter().zip(lines).enumerate() {
        println!("{}\t{line}", lab_common::patch_columns(p, k));
    }
}
