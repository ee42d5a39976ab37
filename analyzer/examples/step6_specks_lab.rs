//! Step 6's candidates against the speck limit: for each line `FILE QX QY` of a list
//! (tab-separated; QX, QY the quadrant, 0 or 1), the automatic choice on that quadrant of the
//! set's photo; where it is a family, every candidate of its final fit's step 6 (each residual
//! amplitude of the first round, each rougher variant at the chosen amplitude) finished as the
//! product finishes the best one (its tone curve, its grain matched) and rendered at the
//! quadrant's size. Printed per candidate: its score (lower is better), its speck ratio to the
//! photo's (`specks::speck_ratio`), and whether it has the best score; then the speck ratio of
//! the product's choice among them (`FinalFit::finish_whole`: the first by score within the
//! limit), the time of that finish and of one speck check (`FinalFit::speck_clean`).
//!
//! `cargo run --release -p proctex-analyzer --example step6_specks_lab -- SET_DIR LIST`
use proctex::analyze::{Options, analyze_photo_with};
use proctex::db::Db;
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::{Crop, Photo};
use proctex::retrieve::{ModelChoice, Refinement, analyze_with_model};
use proctex::specks::{speck_fraction, speck_ratio};
use proctex::structure::{FinalFit, Scored};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::PathBuf::from(&args[1]);
    let list = std::fs::read_to_string(&args[2]).expect("a list");
    let opts = Options::default();
    let db = Db::shipped();
    for line in list.lines().filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split('\t').collect();
        let photo = Photo::decode(&std::fs::read(dir.join(f[0])).unwrap()).unwrap();
        let (qx, qy): (u32, u32) = (f[1].parse().unwrap(), f[2].parse().unwrap());
        let (w, h) = (photo.width / 2, photo.height / 2);
        let crop = Crop {
            x: qx * w,
            y: qy * h,
            w,
            h,
        };
        let patch = photo.crop(crop).unwrap();
        analyze_photo_with(&patch, &opts, |p, o| {
            let (a, suggestions) =
                analyze_with_model(db, p, o, ModelChoice::Auto, Refinement::default());
            let Some(first) = suggestions.first() else {
                return a;
            };
            let Some((pattern, swapped)) = first.pattern.as_ref() else {
                println!("{}\t{qx}\t{qy}\tnoise", f[0]);
                return a;
            };
            let photo_specks = speck_fraction(p);
            let fit = FinalFit::new(db, p, pattern, o, *swapped);
            let scored = fit.scored_fits(db);
            let amplitudes = fit.amplitudes();
            let all: Vec<(String, Scored)> = scored
                .into_iter()
                .enumerate()
                .map(|(k, s)| match k.checked_sub(amplitudes) {
                    None => (format!("amplitude {k}"), s),
                    Some(v) => (format!("variant {}", v + 1), s),
                })
                .collect();
            let best = all
                .iter()
                .enumerate()
                .min_by(|a, b| a.1.1.score.total_cmp(&b.1.1.score))
                .map(|(i, _)| i);
            for (i, (name, s)) in all.iter().enumerate() {
                let mut finished = fit.finish([s.clone()]);
                fit.match_grain(&mut finished);
                let render = render_params_at_photo_size(&finished.params, p);
                let ratio = speck_ratio(speck_fraction(&render), photo_specks, p.pixels.len());
                println!(
                    "{}\t{qx}\t{qy}\t{}\t{name}\tscore {:.4}\tspecks {ratio:.2}\t{}",
                    f[0],
                    first.name,
                    s.score,
                    if Some(i) == best { "best score" } else { "" }
                );
            }
            let scored: Vec<Scored> = all.into_iter().map(|(_, s)| s).collect();
            let start = std::time::Instant::now();
            let product = fit.finish_whole(scored);
            let whole_ms = start.elapsed().as_secs_f64() * 1e3;
            let start = std::time::Instant::now();
            let clean = fit.speck_clean(&product);
            let check_ms = start.elapsed().as_secs_f64() * 1e3;
            let render = render_params_at_photo_size(&product.params, p);
            let ratio = speck_ratio(speck_fraction(&render), photo_specks, p.pixels.len());
            println!(
                "{}\t{qx}\t{qy}\t{}\tthe product's\tspecks {ratio:.2} (clean: {clean})\t\
                 its finish {whole_ms:.0} ms, one speck check {check_ms:.1} ms",
                f[0], first.name
            );
            a
        })
        .unwrap();
    }
}
