//! Joint topology laboratory: do the joints' junctions and pieces (`lab_common::topology`) tell
//! the families apart where the Gabor energy descriptor does not? A discriminant is trained on
//! database patterns alone (clean and photo-like copies), over the descriptor's invariant
//! features, the topology features, or both; it is scored on the development set's structured
//! patches (labelled family first / in the top three, per hash fold) and stochastic ones.
//!
//! `cargo run --release -p proctex-analyzer --example topology_lab -- DIR [PER_FAMILY] [COPIES]`

mod lab_common;

use lab_common::{Tally, ordered};

use lab_common::lda::{fit, project, scores};
use lab_common::topology::topology;
use proctex::family_classifier::descriptor_features as features;
use proctex::gabor::{SIZE, describe, descriptor_image};
use proctex::pattern::PatternKind;
use proctex::two_tone::two_tone;
use rayon::prelude::*;

/// Both tone orientations' feature blocks of one map: (descriptor, topology) each.
type Sample = [(Vec<f64>, Vec<f64>); 2];

fn sample_of(map: &[f32]) -> Sample {
    let d = describe(map);
    let negated: Vec<f32> = map.iter().map(|v| -v).collect();
    [
        (features(&d, 2), topology(map, SIZE).to_vec()),
        (features(&d.swapped(), 2), topology(&negated, SIZE).to_vec()),
    ]
}

struct Patch {
    file: String,
    structured: bool,
    labels: Vec<String>,
    sample: Sample,
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let per_kind: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(300);
    let copies: usize = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(2);
    let t = std::time::Instant::now();
    let patches: Vec<Patch> = lab_common::load(&args[1])
        .into_par_iter()
        .map(|p| {
            let map = two_tone(&p.photo).structure;
            let map = descriptor_image(&map, p.photo.width as usize, p.photo.height as usize);
            Patch {
                file: p.file,
                structured: p.structured,
                labels: p.labels,
                sample: sample_of(&map),
            }
        })
        .collect();
    let train = lab_common::training_maps(per_kind, copies, &sample_of);
    eprintln!(
        "{} training maps in {:.1} s",
        train.len(),
        t.elapsed().as_secs_f32()
    );
    let names: Vec<&str> = PatternKind::ALL.iter().map(|k| k.name()).collect();
    let classes = names.len();
    if std::env::var("MEDIANS").is_ok() {
        // Medians of the topology features per family (training, first orientation) and per
        // development label.
        let med = |rows: Vec<&Vec<f64>>| -> Vec<String> {
            let k = rows.first().map_or(0, |r| r.len());
            (0..k)
                .map(|j| {
                    let mut v: Vec<f64> = rows.iter().map(|r| r[j]).collect();
                    v.sort_by(f64::total_cmp);
                    format!("{:.2}", v.get(v.len() / 2).copied().unwrap_or(f64::NAN))
                })
                .collect()
        };
        for (c, name) in names.iter().enumerate() {
            let rows = train
                .iter()
                .filter(|(_, k)| *k == c)
                .map(|(s, _)| {
                    if s[0].1[0] >= s[1].1[0] {
                        &s[0].1
                    } else {
                        &s[1].1
                    }
                })
                .collect();
            println!("db {name:>10}: {}", med(rows).join(" "));
        }
        let mut labels: Vec<String> = patches
            .iter()
            .map(|p| {
                if p.structured {
                    p.labels[0].clone()
                } else {
                    "noise".into()
                }
            })
            .collect();
        labels.sort();
        labels.dedup();
        for l in labels {
            let rows = patches
                .iter()
                .filter(|p| (if p.structured { &p.labels[0] } else { "noise" }) == l)
                .map(|p| {
                    // The orientation whose minority is the better-connected network.
                    if p.sample[0].1[0] >= p.sample[1].1[0] {
                        &p.sample[0].1
                    } else {
                        &p.sample[1].1
                    }
                })
                .collect();
            println!("dev {l:>9}: {}", med(rows).join(" "));
        }
    }
    // Feature sets: descriptor, topology, both.
    let pick = |s: &(Vec<f64>, Vec<f64>), set: usize| -> Vec<f64> {
        match set {
            0 => s.0.clone(),
            1 => s.1.clone(),
            _ => s.0.iter().chain(&s.1).copied().collect(),
        }
    };
    for (set, set_name) in ["descriptor", "topology", "both"].iter().enumerate() {
        let mut xs = Vec::new();
        for (s, c) in &train {
            xs.push((pick(&s[0], set), *c));
            xs.push((pick(&s[1], set), *c));
        }
        // Standardise on the training set, so the ridge weighs every feature alike.
        let dim = xs[0].0.len();
        let mean: Vec<f64> = (0..dim)
            .map(|j| xs.iter().map(|x| x.0[j]).sum::<f64>() / xs.len() as f64)
            .collect();
        let sd: Vec<f64> = (0..dim)
            .map(|j| {
                (xs.iter().map(|x| (x.0[j] - mean[j]).powi(2)).sum::<f64>() / xs.len() as f64)
                    .sqrt()
                    .max(1e-9)
            })
            .collect();
        let z = |v: Vec<f64>| -> Vec<f64> {
            v.iter()
                .enumerate()
                .map(|(j, x)| (x - mean[j]) / sd[j])
                .collect()
        };
        let xs: Vec<(Vec<f64>, usize)> = xs.into_iter().map(|(v, c)| (z(v), c)).collect();
        for ridge in [1e-3, 1e-1] {
            let model = fit(&xs, classes, ridge, (classes - 1).min(dim));
            for knn in [0usize, 25] {
                let mut tally = Tally::default();
                for p in &patches {
                    let s: Vec<f64> = {
                        let a = scores(
                            &model,
                            &project(&model.proj, &z(pick(&p.sample[0], set))),
                            classes,
                            knn,
                        );
                        let b = scores(
                            &model,
                            &project(&model.proj, &z(pick(&p.sample[1], set))),
                            classes,
                            knn,
                        );
                        a.iter().zip(&b).map(|(x, y)| x.min(*y)).collect()
                    };
                    tally.add(&p.file, p.structured, &p.labels, &ordered(&s));
                }
                println!(
                    "{set_name:>10} ridge {ridge:e} knn {knn:2}: {}",
                    tally.line()
                );
            }
        }
    }
}
