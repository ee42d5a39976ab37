//! What refinement does to each family's structure distance, per patch of a photo set: the
//! data of `tools/refinement_reach_cv.py`, which cross-validates the refinement's bound
//! (`retrieve::refinement_reach`).
//!
//! `cargo run --release -p proctex-analyzer --example refinement_reach -- DIR > OUT.jsonl`
//! (DIR holds a `manifest.tsv`; `WHOLE=1`: each whole photo instead of its four quadrants).
//! One line per patch: per family its retrieval distance, its distance after a short
//! refinement of its first start alone (`short`, at each of [`SHORT`] evaluations), and after
//! the default refinement (`full`: every family refined, no bound).
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::input::{Crop, Photo};
use proctex::retrieve::{Refinement, Suggester};
use rayon::prelude::*;

/// Evaluations of the short refinements.
const SHORT: [usize; 3] = [4, 8, 12];

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: refinement_reach DIR");
    let whole = std::env::var("WHOLE").is_ok();
    let manifest = std::fs::read_to_string(format!("{dir}/manifest.tsv")).expect("manifest.tsv");
    let db = Db::shipped();
    let o = Options::default();
    for line in manifest.lines().skip(1) {
        let file = line.split('\t').next().unwrap_or_default();
        let bytes = std::fs::read(format!("{dir}/{file}")).expect("photo");
        let photo = Photo::decode(&bytes).expect("decodable photo");
        let (hw, hh) = (photo.width / 2, photo.height / 2);
        let (r, b) = (photo.width - hw, photo.height - hh);
        // The fidelity protocol's patch order: top-left, bottom-left, top-right, bottom-right.
        let patches: Vec<Photo> = if whole {
            vec![photo.clone()]
        } else {
            [(0, 0), (0, b), (r, 0), (r, b)]
                .map(|(x, y)| photo.crop(Crop { x, y, w: hw, h: hh }).expect("quadrant"))
                .to_vec()
        };
        for (pi, patch) in patches.iter().enumerate() {
            let full = Suggester::new(db, patch, &o, Refinement::default());
            let shorts: Vec<Suggester> = SHORT
                .iter()
                .map(|&e| {
                    let r = Refinement {
                        families: full.steps(),
                        evaluations: e,
                        starts: 1,
                        ..Refinement::default()
                    };
                    Suggester::new(db, patch, &o, r)
                })
                .collect();
            let families: Vec<String> = (0..full.steps())
                .into_par_iter()
                .map(|i| {
                    let kind = full.family(i);
                    let (_, d, _) = full.refine_family(db, i, &mut |_, _| true);
                    let short: Vec<f32> = shorts
                        .iter()
                        .map(|s| {
                            let j = (0..s.steps()).find(|&j| s.family(j) == kind).unwrap();
                            s.refine_family(db, j, &mut |_, _| true)
                                .1
                                .unwrap_or(f32::NAN)
                        })
                        .collect();
                    format!(
                        "{{\"name\":\"{}\",\"retrieval\":{},\"short\":{:?},\"full\":{}}}",
                        kind.name(),
                        full.retrieval_distance(i),
                        short,
                        d.unwrap_or(f32::NAN)
                    )
                })
                .collect();
            let patch = if whole { 4 } else { pi };
            println!(
                "{{\"file\":\"{file}\",\"patch\":{patch},\"short_evaluations\":{SHORT:?},\"families\":[{}]}}",
                families.join(",")
            );
        }
    }
}
