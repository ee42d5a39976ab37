//! The nearer render in scattering space (`retrieve::NEARER_RENDER_MARGIN`) with the nearest
//! family's pattern at several scales. The lattices' fits come out finer than the photo's units
//! (docs/devset.md, "The lattices' scale"), and the texture distances cannot tell; the
//! scattering's second order sees the arrangement, so a coarser copy of the family may be
//! nearer to the photo than its fitted scale. For every quadrant of a photo set: the automatic
//! ranking (default refinement, seed 1), the classifier's nearest family, and the margin of the
//! noise model's render against the first round of that family's final fit
//! (`structure::FirstRound::amplitude_fit`, what the product compares) with its refined
//! pattern's scale times each factor of `FACTORS`. Prints TSV: file, patch, category, labels, then the margin at each
//! factor, then the largest of them and the factor that gave it
//! (`tools/devset_nearer_render_cv.py RUN --margins TSV COLUMN` scores a column as the rule's).
//!
//! `cargo run --release -p proctex-analyzer --example scale_ladder_lab -- SET_DIR`

mod lab_common;

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::noise::Tile;
use proctex::retrieve::nearer_render_margin;
use proctex::structure::FirstRound;

/// The pattern's scale factors tried (1: the product's).
const FACTORS: [f32; 4] = [1.0, 1.5, 2.0, 3.0];

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: scale_ladder_lab SET_DIR");
    let patches = lab_common::load(&dir);
    let db = Db::shipped();
    let opts = Options::default();
    let lines = proctex::parallel::map_in_order(&patches, |p| {
        let (noise, family) = lab_common::ranking_with_nearest(&p.photo, &opts);
        let tile = Tile::new_2d(opts.seed);
        match (noise.as_ref(), family.as_ref()) {
            (Some(noise), Some(family)) => {
                let (pattern, swapped) = family.pattern.as_ref().expect("a family");
                let margins: Vec<f64> = FACTORS
                    .iter()
                    .map(|&f| {
                        let mut pattern = pattern.clone();
                        pattern.scale *= f;
                        let params = FirstRound::new(db, &p.photo, &pattern, &opts, *swapped)
                            .amplitude_fit()
                            .params;
                        nearer_render_margin(&p.photo, noise, &params, &tile)
                    })
                    .collect();
                // The largest margin and its factor (the first of equal ones).
                let k =
                    (0..FACTORS.len()).fold(0, |b, k| if margins[k] > margins[b] { k } else { b });
                let (best, factor) = (margins[k], FACTORS[k]);
                let m: Vec<String> = margins.iter().map(|m| format!("{m:.4}")).collect();
                format!("{}\t{best:.4}\t{factor}", m.join("\t"))
            }
            _ => {
                let m = vec!["-inf"; FACTORS.len() + 1].join("\t");
                format!("{m}\t1")
            }
        }
    });
    for (k, (p, line)) in patches.iter().zip(lines).enumerate() {
        println!("{}\t{line}", lab_common::patch_columns(p, k));
    }
}
