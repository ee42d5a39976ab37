//! Round-trip laboratory: the synthetic round trip of `tests/retrieval.rs` (the same queries)
//! over any range of cases, per family, with each case's outcome, so that a change's effect on
//! one family can be measured on more cases than the test holds, and paired case by case.
//!
//! `cargo run --release -p proctex-analyzer --example round_trip_lab -- FAMILIES FIRST COUNT [DIR]`
//!
//! FAMILIES: comma-separated family names or `all`; cases FIRST … FIRST + COUNT − 1 of each.
//! Prints one line per case (case, automatic first choice, choice by refined distance alone,
//! the family's own refined distance, the best family's, scale, rotation, drawn values) and a
//! per-family count with its standard error. With DIR, each query is also written there as
//! `FAMILY_CASE.png`.

#[path = "../tests/common/round_trip.rs"]
mod round_trip;

use proctex::analyze::Options;
use proctex::db::Db;
use proctex::pattern::PatternKind;
use proctex::retrieve::{Suggestion, suggest};
use round_trip::{case, family_by_retrieval};

fn distance(s: &Suggestion) -> f32 {
    s.refined_distance.unwrap_or(s.retrieval_distance)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() < 4 {
        eprintln!("usage: round_trip_lab FAMILIES FIRST COUNT [DIR]");
        std::process::exit(2);
    }
    let kinds: Vec<PatternKind> = if args[1] == "all" {
        PatternKind::ALL.to_vec()
    } else {
        args[1]
            .split(',')
            .map(|name| {
                PatternKind::ALL
                    .into_iter()
                    .find(|k| k.name() == name)
                    .unwrap_or_else(|| panic!("no family {name}"))
            })
            .collect()
    };
    let first: usize = args[2].parse().expect("FIRST: a case number");
    let count: usize = args[3].parse().expect("COUNT: a number of cases");
    let dir = args.get(4);
    let db = Db::shipped();
    let opts = Options::default();
    let mut summary = Vec::new();
    for kind in kinds {
        use rayon::prelude::*;
        let rows: Vec<(bool, bool, String)> = (first..first + count)
            .into_par_iter()
            .map(|c| {
                let (img, p) = case(kind, c);
                if let Some(dir) = dir {
                    let bytes: Vec<u8> = img
                        .pixels
                        .iter()
                        .flat_map(|px| px.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
                        .collect();
                    let path = format!("{dir}/{}_{c}.png", kind.name());
                    image::save_buffer(
                        &path,
                        &bytes,
                        img.width,
                        img.height,
                        image::ColorType::Rgb8,
                    )
                    .unwrap_or_else(|e| panic!("{path}: {e}"));
                }
                let s = suggest(db, &img, &opts);
                let by_retrieval = family_by_retrieval(&s);
                let own = s.iter().find(|x| x.name == kind.name()).map(distance);
                let best = s
                    .iter()
                    .filter(|x| x.pattern.is_some())
                    .map(distance)
                    .fold(f32::INFINITY, f32::min);
                let line = format!(
                    "{}\t{c}\t{}\t{by_retrieval}\t{:.3}\t{best:.3}\t{:.1}\t{:.0}\t{:?}",
                    kind.name(),
                    s[0].name,
                    own.unwrap_or(f32::NAN),
                    p.scale,
                    p.rotation_deg,
                    p.values
                );
                (s[0].name == kind.name(), by_retrieval == kind.name(), line)
            })
            .collect();
        for (_, _, line) in &rows {
            println!("{line}");
        }
        let right = rows.iter().filter(|r| r.0).count();
        let right_r = rows.iter().filter(|r| r.1).count();
        summary.push((kind.name(), right, right_r));
    }
    println!("family\tright\tby refined distance\tof");
    let (mut all, mut all_r) = (0, 0);
    for (name, right, right_r) in &summary {
        println!("{name}\t{right}\t{right_r}\t{count}");
        all += right;
        all_r += right_r;
    }
    let total = (count * summary.len()) as f64;
    let rate = all as f64 / total;
    let se = (rate * (1.0 - rate) / total).sqrt();
    println!(
        "all\t{all}\t{all_r}\t{total} ({:.1} % ± {:.1})",
        100.0 * rate,
        100.0 * se
    );
}
