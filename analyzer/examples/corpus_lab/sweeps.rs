//! The laboratory's measured alternatives that the product does not use: the corpus's
//! bootstrap, the feature dump for `tools/classifier_lab.py`, and the class-prior sweep.

use super::*;

/// How much the development set's nearest-family count moves with the corpus's sampling: `n`
/// corpora drawn from the labelled textures with replacement (as many as there are), each trained
/// with the chosen setting and scored on the development set's structured patches.
pub fn bootstrap(
    corpus: &[Texture],
    dev: &[(lab_common::Patch, Descriptor)],
    n: u32,
    harmonics: usize,
    ridge: f64,
) {
    let names = class_names();
    let noise = names.len() - 1;
    let mut counts = Vec::new();
    for b in 0..n {
        let draw: Vec<&Texture> = (0..corpus.len() as u32)
            .map(|i| {
                let u = proctex::rng::uniform(b + 1, 7, i);
                &corpus[((u * corpus.len() as f64) as usize).min(corpus.len() - 1)]
            })
            .collect();
        let c = Classifier::train(&draw, names.len(), harmonics, ridge);
        let right = dev
            .iter()
            .filter(|(p, _)| p.structured)
            .filter(|(p, d)| {
                c.order(d)
                    .iter()
                    .find(|&&k| k != noise)
                    .is_some_and(|&k| p.labels.iter().any(|l| l == names[k]))
            })
            .count();
        counts.push(right as f64);
    }
    let m = counts.iter().sum::<f64>() / counts.len() as f64;
    let sd = (counts.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (counts.len() as f64 - 1.0))
        .sqrt();
    let (lo, hi) = counts
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    println!(
        "bootstrap ({n} corpora drawn with replacement): nearest family labelled {m:.1} ± {sd:.1} (sd), {lo}–{hi} of 100"
    );
}

/// `CORPUS_LAB_FEATURES=PATH`: every training quadrant's and development patch's classifier
/// features as TSV (`train`, file, quadrant, class; `dev`, file, quadrant, labels joined by `/`),
/// for classifiers measured outside Rust.
pub fn dump_features(
    path: &std::ffi::OsStr,
    corpus: &[Texture],
    dev: &[(lab_common::Patch, Descriptor)],
    names: &[&str],
    harmonics: usize,
) {
    use std::fmt::Write;
    let mut out = String::new();
    let row = |out: &mut String, head: String, d: &Descriptor| {
        let f: Vec<String> = lab_features(d, harmonics)
            .iter()
            .map(|v| format!("{v}"))
            .collect();
        writeln!(out, "{head}\t{}", f.join("\t")).unwrap();
    };
    for t in corpus {
        for (q, d) in t.quadrants.iter().enumerate() {
            row(
                &mut out,
                format!("train\t{}\t{q}\t{}", t.file, names[t.class]),
                d,
            );
        }
    }
    let mut seen: std::collections::HashMap<&str, usize> = Default::default();
    for (p, d) in dev {
        let q = seen.entry(&p.file).or_insert(0);
        row(
            &mut out,
            format!("dev\t{}\t{q}\t{}", p.file, p.labels.join("/")),
            d,
        );
        *q += 1;
    }
    std::fs::write(path, out).unwrap();
}

/// `CORPUS_LAB_PRIORS=S1,S2,…`: the class prior's weight on the distances (−2·S·ln of each class's
/// share of the training textures; `f` before a value: the families' terms only, centred, the
/// noise class's distance as it is), the corpus held out (4 folds) and the development set per
/// weight: the nearest family, the label among the first three families, the noise class first.
pub fn prior_sweep(
    list: &str,
    corpus: &[Texture],
    dev: &[(lab_common::Patch, Descriptor)],
    c: &Classifier,
    names: &[&str],
    setting: (usize, f64),
) {
    let noise = names.len() - 1;
    let folds = fold_classifiers(corpus, names.len(), setting);
    for item in list.split(',') {
        let (fam_only, v) = match item.strip_prefix('f') {
            Some(v) => (true, v),
            None => (false, item),
        };
        let s: f64 = v.parse().unwrap();
        PRIOR.with(|p| p.set((s, fam_only)));
        let h = held_out(corpus, &folds, noise);
        let (mut dr, mut dt3, mut dn, mut first, mut dk, mut dnt) = (0, 0, 0, 0, 0, 0);
        for (p, d) in dev {
            let order = c.order(d);
            let lab = |k: usize| p.labels.iter().any(|l| l == names[k]);
            if p.structured {
                dn += 1;
                let f: Vec<usize> = order.iter().copied().filter(|&k| k != noise).collect();
                dr += lab(f[0]) as usize;
                dt3 += f.iter().take(3).any(|&k| lab(k)) as usize;
                first += lab(order[0]) as usize;
            } else {
                dnt += 1;
                dk += (order[0] == noise) as usize;
            }
        }
        println!(
            "prior {item}: corpus held out family {}/{n} family-top3 {}/{n} noise kept {}/{} | dev family {dr}/{dn} family-top3 {dt3}/{dn} first {first}/{dn} noise kept {dk}/{dnt}",
            h.family,
            h.family_top3,
            h.noise_kept,
            h.stochastic,
            n = h.structured
        );
    }
}
