//! Specks of every ranked candidate as the app shows it (its thumbnail's fit, the ranking's
//! fast fit without step 6 and the tone curve, rendered at the photo's size: what `proctex
//! fidelity` records per candidate) and as the app adopts it when the user picks that row (the
//! final fit of the row's refined pattern, `structure::fit_structured`, as the worker's final
//! fit and `proctex analyze --model` run it), on every quadrant of a photo set.
//!
//! `cargo run --release -p proctex-analyzer --example adopted_specks -- SET_DIR`
//! (SET_DIR holds manifest.tsv; one line per candidate, then a summary per family).
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::devset::{SPECK_LIMIT, parse_manifest, speck_ratio};
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::{Crop, Photo};
use proctex::retrieve::{Refinement, suggest_with};
use proctex::specks::speck_fraction;
use proctex::structure::fit_structured;
use std::collections::BTreeMap;

fn main() {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).expect("SET_DIR"));
    let manifest = std::fs::read_to_string(dir.join("manifest.tsv")).expect("manifest.tsv");
    let db = Db::shipped();
    let opts = Options::default();
    // Per family: (previews within the limit, adopted within the limit, count).
    let mut clean: BTreeMap<String, [usize; 3]> = BTreeMap::new();
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
                let adopted = match &s.pattern {
                    Some((p, swapped)) => {
                        ratio(&fit_structured(db, &patch, p, &opts, *swapped).params)
                    }
                    None => preview,
                };
                println!(
                    "{}\t{qx},{qy}\t{}\t{preview:.2}\t{adopted:.2}",
                    entry.file, s.name
                );
                let c = clean.entry(s.name.to_string()).or_default();
                c[0] += (preview <= SPECK_LIMIT) as usize;
                c[1] += (adopted <= SPECK_LIMIT) as usize;
                c[2] += 1;
            }
        }
    }
    let total = clean
        .values()
        .fold([0; 3], |a, c| [a[0] + c[0], a[1] + c[1], a[2] + c[2]]);
    for (name, c) in clean.iter().chain([(&"all".to_string(), &total)]) {
        println!(
            "# {name}: within {SPECK_LIMIT}x the photo's specks: thumbnail fit {} / adopted {} of {}",
            c[0], c[1], c[2]
        );
    }
}
