//! Family classifier laboratory: a discriminant over rotation-invariant descriptor features,
//! trained on the pattern database alone (no development photo), scored on the development
//! set's structured patches (labelled family first / in the top three) and stochastic ones.
//!
//! `cargo run --release -p proctex-analyzer --example family_lda_lab -- DIR`

mod lab_common;

use lab_common::{Tally, ordered};

use lab_common::lda::{fit, project, scores};
use proctex::db::{Db, query};
use proctex::family_classifier::descriptor_features as features;
use proctex::gabor::{Descriptor, describe};
use proctex::pattern::PatternKind;
use proctex::two_tone::two_tone;

/// A development patch and its descriptor.
struct Patch {
    file: String,
    structured: bool,
    labels: Vec<String>,
    q: Descriptor,
}

fn load(dir: &str) -> Vec<Patch> {
    lab_common::load(dir)
        .into_iter()
        .map(|p| {
            let map = two_tone(&p.photo).structure;
            let (q, _) = query(&map, p.photo.width as usize, p.photo.height as usize);
            Patch {
                file: p.file,
                structured: p.structured,
                labels: p.labels,
                q,
            }
        })
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let patches = load(&args[1]);
    let per_kind: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(0);
    let augmented: usize = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(0);
    let train: Vec<(Descriptor, usize)> = if per_kind == 0 {
        Db::shipped()
            .entries
            .iter()
            .step_by(2)
            .map(|e| {
                let c = PatternKind::ALL
                    .iter()
                    .position(|k| *k == e.pattern.kind)
                    .unwrap();
                (e.descriptor.clone(), c)
            })
            .collect()
    } else {
        let t = std::time::Instant::now();
        let v = lab_common::training_maps(per_kind, augmented, &describe);
        eprintln!("built {} in {:.1} s", v.len(), t.elapsed().as_secs_f32());
        v
    };
    let names: Vec<&str> = PatternKind::ALL.iter().map(|k| k.name()).collect();
    let classes = names.len();
    for harmonics in [2usize, 4] {
        // Training set: every database entry in both tone orientations.
        let mut xs = Vec::new();
        for (d, c) in &train {
            xs.push((features(d, harmonics), *c));
            xs.push((features(&d.swapped(), harmonics), *c));
        }
        for ridge in [1e-3, 1e-1] {
            let model = fit(&xs, classes, ridge, classes - 1);
            for knn in [0usize, 25] {
                let mut tally = Tally::default();
                for p in &patches {
                    let a = scores(
                        &model,
                        &project(&model.proj, &features(&p.q, harmonics)),
                        classes,
                        knn,
                    );
                    let b = scores(
                        &model,
                        &project(&model.proj, &features(&p.q.swapped(), harmonics)),
                        classes,
                        knn,
                    );
                    let s: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x.min(*y)).collect();
                    tally.add(&p.file, p.structured, &p.labels, &ordered(&s));
                }
                println!(
                    "harmonics {harmonics} ridge {ridge:e} knn {knn:2}: {}",
                    tally.line()
                );
            }
        }
    }
}
