//! Every ranked candidate's render, written out for measuring other distances than the
//! ranking's: for each quadrant of a photo set (its manifest.tsv), the quadrant itself and the
//! render of every fitted candidate of the automatic ranking (`retrieve::suggest_with`, the
//! default refinement, seed 1; the ranking's fast fits, rendered at the quadrant's size as
//! `proctex fidelity` renders them for its per-candidate numbers), as PNG files in OUT_DIR:
//! `STEM_Q_photo.png`, `STEM_Q_NAME.png` (Q: tl, tr, bl, br). Prints one line per quadrant:
//! file, quadrant, category, labels (comma-separated), the candidates in the ranking's order.
//!
//! `cargo run --release -p proctex-analyzer --example ranked_renders -- SET_DIR OUT_DIR`
// Only the quadrant cut and the PNG writer are used here.
#[allow(dead_code)]
mod lab_common;

use lab_common::{quadrants, save_png};
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::devset::parse_manifest;
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::Photo;
use proctex::retrieve::{Refinement, suggest_with};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::PathBuf::from(&args[1]);
    let out = std::path::PathBuf::from(&args[2]);
    std::fs::create_dir_all(&out).unwrap();
    let manifest = std::fs::read_to_string(dir.join("manifest.tsv")).expect("manifest.tsv");
    let db = Db::shipped();
    let opts = Options::default();
    for entry in parse_manifest(&manifest).expect("a manifest") {
        let photo = Photo::decode(&std::fs::read(dir.join(&entry.file)).unwrap()).unwrap();
        let stem = entry.file.trim_end_matches(".png").to_string();
        // `quadrants` cuts them in this order.
        for (q, patch) in ["tl", "tr", "bl", "br"].into_iter().zip(quadrants(&photo)) {
            save_png(&patch, &out.join(format!("{stem}_{q}_photo.png")));
            let ranked = suggest_with(db, &patch, &opts, Refinement::default(), &|_, _| true);
            let mut names = Vec::new();
            for s in &ranked {
                names.push(s.name);
                if let Some(p) = &s.preview {
                    let r = render_params_at_photo_size(p, &patch);
                    save_png(&r, &out.join(format!("{stem}_{q}_{}.png", s.name)));
                }
            }
            println!(
                "{}\t{q}\t{}\t{}\t{}",
                entry.file,
                format!("{:?}", entry.category).to_lowercase(),
                entry.families.as_deref().unwrap_or(&[]).join(","),
                names.join(",")
            );
        }
    }
}
