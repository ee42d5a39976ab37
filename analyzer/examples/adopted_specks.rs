//! Specks of every ranked candidate as the app shows it (its thumbnail's fit, the ranking's
//! fast fit without step 6 and the tone curve, rendered at the photo's size: what `proctex
//! fidelity` records per candidate) and as the app adopts it when the user picks that row (the
//! final fit of the row's refined pattern, `structure::fit_structured`, as the worker's final
//! fit and `proctex analyze --model` run it), on every quadrant of a photo set; and, from the
//! same final fit, the fit of step 6's best score alone with its tone curve and grain (what the
//! app adopted before the speck limit constrained that choice: `FinalFit::finish_whole`).
//!
//! `cargo run --release -p proctex-analyzer --example adopted_specks -- SET_DIR`
//! (SET_DIR holds manifest.tsv; one line per candidate: its speck ratios as the thumbnail, as
//! step 6's best score and as adopted; then a summary per family).
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::devset::{SPECK_LIMIT, parse_manifest, speck_ratio};
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::{Crop, Photo};
use proctex::retrieve::{Refinement, suggest_with};
use proctex::specks::speck_fraction;
use proctex::structure::FinalFit;
use std::collections::BTreeMap;

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("SET_DIR"));
    let manifest = std::fs::read_to_string(dir.join("manifest.tsv")).expect("manifest.tsv");
    let db = Db::shipped();
    let opts = Options::default();
    // Per family: previews, step 6's best score and adopted fits within the limit; the count.
    let mut clean: BTreeMap<String, [usize; 4]> = BTreeMap::new();
    for entry in parse_manifest(&manifest).expect("a manifest") {
        let photo = Photo::decode(&std::fs::read(dir.join(&entry.file)).unwrap()).unwrap();
        let (w, h) = (photo.width / 2, photo.height / 2);
        for (qx, qy) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            let crop = Crop {
                x: qx * w,
                y: qy * h,
                w,
                h,
            };
            let patch = photo.crop(crop).unwrap();
            let pixels = (w * h) as usize;
            let own = speck_fraction(&patch);
            let ratio = |params: &proctex::params::Params| {
                speck_ratio(
                    speck_fraction(&render_params_at_photo_size(params, &patch)),
                    own,
                    pixels,
                )
            };
            let list = suggest_with(db, &patch, &opts, Refinement::default(), &|_, _| true);
            for s in &list {
                let preview = ratio(s.preview.as_ref().expect("every candidate fitted"));
                let (by_score, adopted) = match &s.pattern {
                    Some((p, swapped)) => {
                        let (by_score, adopted) = final_fits(db, &patch, p, &opts, *swapped);
                        (ratio(&by_score.params), ratio(&adopted.params))
                    }
                    None => (preview, preview),
                };
                println!(
                    "{}\t{qx},{qy}\t{}\t{preview:.2}\t{by_score:.2}\t{adopted:.2}",
                    entry.file, s.name
                );
                let c = clean.entry(s.name.to_string()).or_default();
                c[0] += (preview <= SPECK_LIMIT) as usize;
                c[1] += (by_score <= SPECK_LIMIT) as usize;
                c[2] += (adopted <= SPECK_LIMIT) as usize;
                c[3] += 1;
            }
        }
    }
    let total = clean
        .values()
        .fold([0; 4], |a, c| std::array::from_fn(|i| a[i] + c[i]));
    for (name, c) in clean.iter().chain([(&"all".to_string(), &total)]) {
        println!(
            "# {name}: within {SPECK_LIMIT}x the photo's specks: thumbnail fit {} / step 6's best \
             score {} / adopted {} of {}",
            c[0], c[1], c[2], c[3]
        );
    }
}

/// The final fit of `pattern` as the app adopts it (`structure::fit_structured`, bit for bit:
/// the first fit by score whose render keeps within the speck limit) and, from the same scored
/// fits, step 6's best score finished alone (what was adopted before the limit was a
/// constraint).
fn final_fits(
    db: &Db,
    photo: &Photo,
    pattern: &proctex::pattern::Pattern,
    opts: &Options,
    swapped: bool,
) -> (proctex::analyze::Analysis, proctex::analyze::Analysis) {
    let fit = FinalFit::new(db, photo, pattern, opts, swapped);
    let scored = fit.scored_fits(db);
    let mut by_score = fit.finish(scored.clone());
    fit.match_grain(&mut by_score);
    (by_score, fit.finish_whole(scored))
}
