//! Training-corpus laboratory: a family discriminant trained on labelled real textures (other
//! games' Debian packages, `tools/corpus/labels*.tsv`) instead of rendered patterns, scored on
//! the development set, which it never sees (docs/devset.md, "A family classifier trained on
//! real textures").
//!
//! - `corpus_lab sheet LIST DIR OUT START COUNT`: the textures LIST[START..START+COUNT] (file
//!   names in DIR) as a PNG contact sheet, 8 per row, 96 px each, row-major: for labelling by eye.
//! - `corpus_lab dds DIR OUT`: every DXT1/DXT5 DDS file of DIR decoded to OUT as a PNG at most 512
//!   wide (0 A.D.'s terrains; `tools/corpus/extract.py` prints this step).
//! - `corpus_lab eval LABELS DIR DEVDIR`: LABELS' lines `file<TAB>family[<TAB>package]` (a pattern
//!   family or `noise`); the discriminant's setting chosen by cross-validation over the corpus,
//!   then trained on all of it and scored on DEVDIR's patches. `CORPUS_LAB_DUMP=1` writes each
//!   patch's class order to stderr; `CORPUS_LAB_ALSO=DIR` also prints each quadrant's nearest
//!   class and family for the PNG photos of DIR (the shipped samples, which have no labels);
//!   `CORPUS_LAB_BOOTSTRAP=N` first scores N corpora drawn from the labelled textures with
//!   replacement (the spread of the development set's count over the corpus's sampling).
//!   Measured alternatives (not the product's): `CORPUS_LAB_EXTRA=lum` also describes each
//!   patch's luminance map; `CORPUS_LAB_EXTRA=topo` also describes the topology of the
//!   descriptor image's dark and bright phases (their sum and absolute difference;
//!   `CORPUS_LAB_TOPO_LOG=1` takes their signed log1p); `CORPUS_LAB_DIAG_RIDGE=1` scales the ridge by each feature's own
//!   within-class variance instead of their mean (the same as standardising the features);
//!   `CORPUS_LAB_NO_LINES=1` zeroes the two straight-line cues (the cues' costliest).
//!   `CORPUS_LAB_AUG=half` also trains on each texture's quadrants at half its size;
//!   `CORPUS_LAB_AUG=blur:S1,S2,…` on each quadrant blurred by a Gaussian of each σ (the
//!   product's table: `blur:0.5,1`); `CORPUS_LAB_HELD_BLUR=σ` scores the held-out corpus quadrants
//!   blurred by σ as well, and the setting is chosen by the mean of the sharp and the blurred
//!   criteria; `CORPUS_LAB_SETTING=H,RIDGE` holds the setting instead of choosing it. DEVDIR may
//!   list several sets, comma-separated (the development set and its degraded copies,
//!   `examples/degraded_set`): each is scored.
//!   `CORPUS_LAB_KNN=K` measures each class's distance as the mean squared distance to its K
//!   nearest training views in the discriminant's space instead of to its mean. With
//!   `CORPUS_LAB_DUMP=1` each line also has the patch's margin (the noise class's distance minus
//!   the nearest family's).
//!   `CORPUS_LAB_QDA=ALPHA` scores each class by its own Gaussian in the discriminant's space
//!   (its covariance shrunk towards the pooled one by ALPHA: a quadratic discriminant) instead of
//!   the squared distance to its mean.
//!   `CORPUS_LAB_DEV_FOLDS=K` scores each development photo with a discriminant trained on the
//!   corpus and on the development photos of the other K − 1 folds by photo (their manifest's
//!   first family as the label): what the development photos would add as training textures.
//!   `CORPUS_LAB_FEATURES=PATH` writes every training quadrant's and development patch's
//!   features (`tools/classifier_lab.py` scores other classifiers on them).
//!   `CORPUS_LAB_PRIORS=S,…` sweeps the class prior's weight ([`prior_sweep`]).
//! - `corpus_lab table LABELS DIR OUT`: the same discriminant (setting chosen on the corpus),
//!   trained on every labelled texture and written as the product's table
//!   (`analyzer/src/family_classifier_table.rs`, read by `proctex::family_classifier`); it
//!   prints the spread of the corpus's held-out nearest-class distances.
//! - `corpus_lab set LABELS DIR OUT`: the labelled textures as a set for `proctex fidelity --set
//!   OUT` (reduced to at most 512 pixels a side, with a manifest).

#[path = "../lab_common/mod.rs"]
mod lab_common;
mod sweeps;
mod views;

use sweeps::{bootstrap, dump_features, prior_sweep};
use views::{augmented, describe_blurred, held_blur};

use lab_common::lda::{fit, project, scores};
use proctex::cues::{CUE_NAMES, CUES, cues};
use proctex::db::query;
use proctex::family_classifier::{descriptor_features, features};
use proctex::gabor::{Descriptor, LEN};
use proctex::input::Photo;
use proctex::pattern::PatternKind;
use proctex::retrieve::RANK_SIZE;
use proctex::two_tone::two_tone;

/// The descriptor of a patch as the product's ranking queries it: reduced to at most
/// [`RANK_SIZE`] a side (larger textures' quadrants were described at their own size before
/// the third batch; the product never sees those scales), its two-tone structure map described;
/// the luminance map's descriptor appended when `CORPUS_LAB_EXTRA` contains `lum` (measured, not
/// kept: [`proctex::family_classifier::features`]), then the patch's cues ([`cues`]), which the
/// product's classifier reads with the descriptor.
fn describe(photo: &Photo) -> Descriptor {
    let reduced = photo.reduced(RANK_SIZE);
    let photo = reduced.as_ref().unwrap_or(photo);
    let map = two_tone(photo).structure;
    let (w, h) = (photo.width as usize, photo.height as usize);
    let mut d = query(&map, w, h).0;
    if with_luminance() {
        let lum: Vec<f32> = photo
            .pixels
            .iter()
            .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
            .collect();
        d.0.extend(query(&lum, w, h).0.0);
    }
    if with_topology() {
        let img = proctex::gabor::descriptor_image(&map, w, h);
        let n = proctex::gabor::SIZE;
        let negated: Vec<f32> = img.iter().map(|v| -v).collect();
        let dark = lab_common::topology::topology(&img, n);
        let bright = lab_common::topology::topology(&negated, n);
        for k in 0..lab_common::topology::TOPOLOGY {
            d.0.push((dark[k] + bright[k]) as f32);
            d.0.push((dark[k] - bright[k]).abs() as f32);
        }
    }
    let mut c = cues(photo);
    if std::env::var("CORPUS_LAB_NO_LINES").is_ok() {
        for (v, name) in c.iter_mut().zip(CUE_NAMES) {
            if matches!(name, "straight_lines" | "crossing_lines") {
                *v = 0.0;
            }
        }
    }
    d.0.extend(c);
    d
}

fn with_topology() -> bool {
    std::env::var("CORPUS_LAB_EXTRA").is_ok_and(|v| v.contains("topo"))
}

fn with_luminance() -> bool {
    std::env::var("CORPUS_LAB_EXTRA").is_ok_and(|v| v.contains("lum"))
}

/// The classifier's features of a [`describe`]d patch: the product's
/// ([`proctex::family_classifier::features`]), with the luminance map's descriptor's after the
/// two-tone map's where [`with_luminance`].
fn lab_features(d: &Descriptor, harmonics: usize) -> Vec<f64> {
    let cues: [f32; CUES] = d.0[d.0.len() - CUES..].try_into().unwrap();
    let map = Descriptor(d.0[..LEN].to_vec());
    if with_topology() && !with_luminance() {
        let topo = 2 * lab_common::topology::TOPOLOGY;
        let mut out = features(&map, &cues, harmonics);
        out.extend(
            d.0[d.0.len() - CUES - topo..d.0.len() - CUES]
                .iter()
                .map(|&v| {
                    let v = v as f64;
                    if std::env::var("CORPUS_LAB_TOPO_LOG").is_ok() {
                        v.signum() * v.abs().ln_1p()
                    } else {
                        v
                    }
                }),
        );
        return out;
    }
    if !with_luminance() {
        return features(&map, &cues, harmonics);
    }
    let mut out = descriptor_features(&map, harmonics);
    out.extend(descriptor_features(
        &Descriptor(d.0[LEN..2 * LEN].to_vec()),
        harmonics,
    ));
    out.extend(cues.iter().map(|&c| c as f64));
    out
}

fn class_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = PatternKind::ALL.iter().map(|k| k.name()).collect();
    v.push("noise");
    v
}

/// A labelled training texture's four quadrant descriptors.
struct Texture {
    file: String,
    class: usize,
    quadrants: Vec<Descriptor>,
    /// Training-only views ([`augmented`]; none unless `CORPUS_LAB_AUG` asks).
    extra: Vec<Descriptor>,
    /// The quadrants blurred by [`held_blur`] (none without it): scored when held out, never
    /// trained on.
    soft: Vec<Descriptor>,
}

/// The labelled textures, without those of a class whose every texture is a variant of one
/// ([`lab_common::corpus_files::classes_of_one_texture`]).
fn load_corpus(labels: &str, dir: &str, names: &[&str]) -> Vec<Texture> {
    let mut corpus = load_labelled(labels, dir, names);
    let labelled: Vec<(&str, usize)> = corpus.iter().map(|t| (t.file.as_str(), t.class)).collect();
    let single = lab_common::corpus_files::classes_of_one_texture(&labelled, names.len());
    for &c in &single {
        let n = corpus.iter().filter(|t| t.class == c).count();
        println!(
            "not trained: {} ({n} textures, every one a variant of one)",
            names[c]
        );
    }
    corpus.retain(|t| !single.contains(&t.class));
    corpus
}

fn load_labelled(labels: &str, dir: &str, names: &[&str]) -> Vec<Texture> {
    let text = std::fs::read_to_string(labels).unwrap();
    let lines: Vec<(&str, usize)> = text
        .lines()
        .filter(|line| !line.starts_with('#'))
        .filter_map(|line| {
            let mut it = line.split('\t');
            let (file, family) = (it.next().unwrap(), it.next().unwrap_or("").trim());
            Some((file, names.iter().position(|n| *n == family)?))
        })
        .collect();
    // Described on every core: the descriptions are the laboratory's time.
    proctex::parallel::map_in_order(&lines, |&(file, class)| {
        let photo = Photo::decode(&std::fs::read(format!("{dir}/{file}")).unwrap()).unwrap();
        let parts = lab_common::quadrants(&photo);
        let quadrants = parts.iter().map(describe).collect();
        let soft = held_blur().map_or(Vec::new(), |sigma| {
            parts.iter().map(|q| describe_blurred(q, sigma)).collect()
        });
        Texture {
            file: file.to_string(),
            class,
            quadrants,
            extra: augmented(&photo),
            soft,
        }
    })
}

/// The development set's photos as training textures (`CORPUS_LAB_DEV_FOLDS`):
/// each photo's four quadrants, its class the manifest's first family (`noise` for a stochastic
/// photo), as `tools/corpus/CONVENTIONS.md` labels the corpus.
fn dev_textures(dev: &[(lab_common::Patch, Descriptor)], names: &[&str]) -> Vec<Texture> {
    let mut out: Vec<Texture> = Vec::new();
    for (p, d) in dev {
        let label = if p.structured {
            p.labels.first().map_or("noise", String::as_str)
        } else {
            "noise"
        };
        let Some(class) = names.iter().position(|n| *n == label) else {
            continue;
        };
        match out.iter_mut().find(|t| t.file == p.file) {
            Some(t) => t.quadrants.push(d.clone()),
            None => out.push(Texture {
                file: p.file.clone(),
                class,
                quadrants: vec![d.clone()],
                extra: Vec::new(),
                soft: Vec::new(),
            }),
        }
    }
    out
}

/// A discriminant over `textures` (each quadrant in both tone orientations) and the classes
/// it has examples of.
struct Classifier {
    model: lab_common::lda::Model,
    present: Vec<usize>,
    harmonics: usize,
    /// Each class's own Gaussian in the projected space (`CORPUS_LAB_QDA=ALPHA`, its shrinkage
    /// towards the pooled spread): the classes scored by quadratic discriminant.
    gaussians: Option<Vec<(Vec<f64>, f64)>>,
    /// ln of each present class's share of the training textures.
    log_prior: Vec<f64>,
}

thread_local! {
    /// The class prior's weight on the distances and whether it orders the families only: none,
    /// as in the product (`proctex::family_classifier`), unless `CORPUS_LAB_PRIORS` sweeps it.
    static PRIOR: std::cell::Cell<(f64, bool)> = const { std::cell::Cell::new((0.0, false)) };
}

impl Classifier {
    fn train(textures: &[&Texture], classes: usize, harmonics: usize, ridge: f64) -> Classifier {
        let present: Vec<usize> = (0..classes)
            .filter(|&c| textures.iter().any(|t| t.class == c))
            .collect();
        let mut xs = Vec::new();
        for t in textures {
            let k = present.iter().position(|&p| p == t.class).unwrap();
            for d in t.quadrants.iter().chain(&t.extra) {
                xs.push((lab_features(d, harmonics), k));
                xs.push((lab_features(&d.swapped(), harmonics), k));
            }
        }
        let model = fit(&xs, present.len(), ridge, present.len() - 1);
        let gaussians = std::env::var("CORPUS_LAB_QDA")
            .ok()
            .and_then(|v| v.parse::<f64>().ok())
            .map(|alpha| lab_common::lda::class_gaussians(&model, present.len(), alpha));
        let total = textures.len() as f64;
        let log_prior = present
            .iter()
            .map(|&c| (textures.iter().filter(|t| t.class == c).count() as f64 / total).ln())
            .collect();
        Classifier {
            model,
            present,
            harmonics,
            gaussians,
            log_prior,
        }
    }

    /// Each present class's squared distance to the query's projection (the nearer tone
    /// orientation), as the product's `class_distances` measures it.
    fn distances(&self, d: &Descriptor) -> Vec<f64> {
        let knn: usize = std::env::var("CORPUS_LAB_KNN")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(0);
        let score = |d: &Descriptor| {
            let y = project(&self.model.proj, &lab_features(d, self.harmonics));
            if let Some(g) = &self.gaussians {
                return lab_common::lda::gaussian_scores(&self.model, g, &y);
            }
            if knn == 0 {
                return scores(&self.model, &y, self.present.len(), 0);
            }
            // Each class's mean squared distance to its `knn` nearest training views.
            let mut by_class = vec![Vec::new(); self.present.len()];
            for (p, c) in &self.model.points {
                by_class[*c].push(
                    p.iter()
                        .zip(&y)
                        .map(|(a, b)| (a - b) * (a - b))
                        .sum::<f64>(),
                );
            }
            by_class
                .into_iter()
                .map(|mut ds| {
                    ds.sort_by(f64::total_cmp);
                    let k = knn.min(ds.len()).max(1);
                    ds[..k].iter().sum::<f64>() / k as f64
                })
                .collect()
        };
        let (a, b) = (score(d), score(&d.swapped()));
        let mut out: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x.min(*y)).collect();
        let (scale, families_only) = PRIOR.with(|p| p.get());
        if scale != 0.0 {
            let noise = class_names().len() - 1;
            let fam: Vec<usize> = (0..out.len())
                .filter(|&i| self.present[i] != noise)
                .collect();
            let mean = fam.iter().map(|&i| self.log_prior[i]).sum::<f64>() / fam.len() as f64;
            for i in 0..out.len() {
                if families_only && self.present[i] == noise {
                    continue;
                }
                let centre = if families_only { mean } else { 0.0 };
                out[i] += -2.0 * scale * (self.log_prior[i] - centre);
            }
        }
        out
    }

    /// The classes nearest first (either tone orientation of the query).
    fn order(&self, d: &Descriptor) -> Vec<usize> {
        let s = self.distances(d);
        let mut order: Vec<usize> = (0..s.len()).collect();
        order.sort_by(|&x, &y| s[x].total_cmp(&s[y]));
        order.iter().map(|&i| self.present[i]).collect()
    }
}

const SETTINGS: [(usize, f64); 8] = [
    (4, 1e-5),
    (4, 1e-4),
    (2, 1e-3),
    (2, 1e-1),
    (2, 1.0),
    (4, 1e-3),
    (4, 1e-1),
    (4, 1.0),
];
const CORPUS_FOLDS: usize = 4;

/// A corpus texture's fold: by its stem ([`lab_common::corpus_files::stem`]), so that the
/// variants of one texture (`wickedmarble8`, `8a`, `8b`; 0 A.D.'s `cliff_01` … `cliff_03`) are
/// held out together. Drawn by file, they fell on both sides of a fold and the held-out numbers
/// measured recognising a texture seen in another variant, not a family: 595 of 892 held-out
/// structured quadrants with the family nearest by file, 550 by stem at the same setting
/// (docs/devset.md, "Folds by texture stem").
fn corpus_fold(file: &str) -> usize {
    let (folder, name) = lab_common::corpus_files::stem(file);
    proctex::devset::fold_of(&format!("{folder}__{name}"), CORPUS_FOLDS)
}

/// The discriminant trained without each of the corpus's [`CORPUS_FOLDS`] folds (by texture).
fn fold_classifiers(corpus: &[Texture], classes: usize, setting: (usize, f64)) -> Vec<Classifier> {
    (0..CORPUS_FOLDS)
        .map(|f| {
            let train: Vec<&Texture> = corpus
                .iter()
                .filter(|t| corpus_fold(&t.file) != f)
                .collect();
            Classifier::train(&train, classes, setting.0, setting.1)
        })
        .collect()
}

/// Counts over the corpus's quadrants, each ranked by its fold's classifier.
#[derive(Default)]
struct HeldOut {
    structured: usize,
    /// Structured quadrants whose nearest family is the label.
    family: usize,
    /// Structured quadrants whose label is among the first three families.
    family_top3: usize,
    stochastic: usize,
    /// Stochastic quadrants with the noise class first.
    noise_kept: usize,
    /// The counts over the blurred quadrants ([`Texture::soft`]; top three not counted).
    soft: SoftCounts,
}

/// [`HeldOut`]'s counts over the blurred held-out quadrants.
#[derive(Default)]
struct SoftCounts {
    structured: usize,
    family: usize,
    stochastic: usize,
    noise_kept: usize,
}

impl HeldOut {
    /// The rate of the label as nearest family plus the rate of the noise class kept (sharp
    /// quadrants), and the same over the blurred ones where there are any.
    fn criteria(&self) -> (f64, Option<f64>) {
        let rate = |a: usize, b: usize| a as f64 / b.max(1) as f64;
        let sharp = rate(self.family, self.structured) + rate(self.noise_kept, self.stochastic);
        let s = &self.soft;
        let soft = (s.structured + s.stochastic > 0)
            .then(|| rate(s.family, s.structured) + rate(s.noise_kept, s.stochastic));
        (sharp, soft)
    }
}

fn held_out(corpus: &[Texture], folds: &[Classifier], noise: usize) -> HeldOut {
    let mut h = HeldOut::default();
    for t in corpus {
        let c = &folds[corpus_fold(&t.file)];
        for d in &t.quadrants {
            let order = c.order(d);
            if t.class == noise {
                h.stochastic += 1;
                h.noise_kept += (order[0] == noise) as usize;
            } else {
                h.structured += 1;
                let families: Vec<usize> = order.into_iter().filter(|&k| k != noise).collect();
                h.family += (families[0] == t.class) as usize;
                h.family_top3 += families[..3].contains(&t.class) as usize;
            }
        }
        for d in &t.soft {
            let order = c.order(d);
            if t.class == noise {
                h.soft.stochastic += 1;
                h.soft.noise_kept += (order[0] == noise) as usize;
            } else {
                h.soft.structured += 1;
                let nearest = order.into_iter().find(|&k| k != noise);
                h.soft.family += (nearest == Some(t.class)) as usize;
            }
        }
    }
    h
}

/// The setting chosen by cross-validation over the corpus's textures alone ([`CORPUS_FOLDS`]
/// folds by texture stem, [`corpus_fold`]): the highest sum of the held-out structured quadrants'
/// rate of the label as nearest family and the stochastic quadrants' rate of the noise class
/// first, the two rates the product is judged by (the ranking's thresholds were chosen by the same
/// sum, `tools/pooled_cv.py`). The family rate alone was the criterion before the folds were drawn
/// by stem; by stem it chose ten times the ridge (561 against 550 of 892, noise kept 1233 against
/// 1252 of 1452), whose table lost first choices in the product on the development set (78 → 69
/// labelled at seed 1, 72 held out with the render-null threshold chosen again) and on the ufoai
/// textures never tuned on (175 → 162 of 268; top three 238 → 246). By the sum the two settings
/// nearly tie (1.4789 against 1.4781) and the product's is chosen (docs/devset.md, "Folds by
/// texture stem").
fn choose_setting(corpus: &[Texture], names: &[&str]) -> (usize, f64) {
    let noise = names.len() - 1;
    let mut best = (f64::NEG_INFINITY, SETTINGS[0]);
    for &(harmonics, ridge) in &SETTINGS {
        let folds = fold_classifiers(corpus, names.len(), (harmonics, ridge));
        let h = held_out(corpus, &folds, noise);
        // With blurred held-out quadrants, the mean of the sharp and the blurred criteria.
        let criterion = match h.criteria() {
            (sharp, Some(soft)) => (sharp + soft) / 2.0,
            (sharp, None) => sharp,
        };
        println!(
            "corpus, {CORPUS_FOLDS} folds by stem held out: harmonics {harmonics} ridge {ridge}: family {}/{}, noise kept {}/{}; blurred: family {}/{}, noise kept {}/{}; criterion {criterion:.4}",
            h.family,
            h.structured,
            h.noise_kept,
            h.stochastic,
            h.soft.family,
            h.soft.structured,
            h.soft.noise_kept,
            h.soft.stochastic
        );
        if criterion > best.0 {
            best = (criterion, (harmonics, ridge));
        }
    }
    // `CORPUS_LAB_SETTING=H,RIDGE` holds the setting (another option measured at the product's).
    if let Ok(v) = std::env::var("CORPUS_LAB_SETTING") {
        let (h, r) = v.split_once(',').expect("CORPUS_LAB_SETTING=H,RIDGE");
        return (h.parse().unwrap(), r.parse().unwrap());
    }
    best.1
}

/// The quantile of the held-out nearest-class distances that [`table`] prints: a photo farther
/// than that from every class is farther than all but 5 % of the real textures the classifier had
/// not seen (the conventional 5 % of a one-sided test). Fitting the family nearest by retrieval
/// as well beyond it was measured and not kept (docs/devset.md): it won the synthetic round trip
/// back but cost the benchmarks' brick crop its family and its speed.
const UNFAMILIAR_QUANTILE: f64 = 0.95;

/// Every corpus quadrant's distance to its nearest class by the discriminant trained without
/// its fold (the setting's [`CORPUS_FOLDS`]-fold cross-validation), sorted: how far real
/// textures the classifier has not seen fall from its classes.
fn held_out_distances(corpus: &[Texture], names: &[&str], setting: (usize, f64)) -> Vec<f64> {
    let folds = fold_classifiers(corpus, names.len(), setting);
    let mut out: Vec<f64> = corpus
        .iter()
        .flat_map(|t| {
            let c = &folds[corpus_fold(&t.file)];
            let nearest = |d| c.distances(d).into_iter().fold(f64::INFINITY, f64::min);
            t.quadrants.iter().map(nearest)
        })
        .collect();
    out.sort_by(f64::total_cmp);
    out
}

/// Prints the median and the [`UNFAMILIAR_QUANTILE`] quantile of [`held_out_distances`].
fn print_held_out_distances(corpus: &[Texture], names: &[&str], setting: (usize, f64)) {
    let held_out = held_out_distances(corpus, names, setting);
    let at = ((held_out.len() - 1) as f64 * UNFAMILIAR_QUANTILE).round() as usize;
    let unfamiliar = held_out[at];
    println!(
        "held-out nearest-class distances of {} quadrants: median {:.2}, {UNFAMILIAR_QUANTILE} quantile {unfamiliar:.2}",
        held_out.len(),
        held_out[held_out.len() / 2]
    );
}

/// Trains the discriminant on every labelled texture of LABELS (in DIR) with the setting
/// [`choose_setting`] chooses and writes it as the product's table (`OUT`:
/// `analyzer/src/family_classifier_table.rs`): the classes with examples, the projection and
/// the class means in the projected space.
fn table(labels: &str, dir: &str, out: &str) {
    let names = class_names();
    let corpus = load_corpus(labels, dir, &names);
    let (harmonics, ridge) = choose_setting(&corpus, &names);
    print_held_out_distances(&corpus, &names, (harmonics, ridge));
    let all: Vec<&Texture> = corpus.iter().collect();
    let c = Classifier::train(&all, names.len(), harmonics, ridge);
    let count = |k: usize| corpus.iter().filter(|t| t.class == k).count();
    let row = |v: &[f64]| {
        let cells: Vec<String> = v.iter().map(|x| format!("{x:e}")).collect();
        format!("    [{}],\n", cells.join(", "))
    };
    // The command that wrote the table, with the options that shaped it.
    let options: Vec<String> = ["CORPUS_LAB_AUG", "CORPUS_LAB_SETTING"]
        .iter()
        .filter_map(|k| Some(format!("{k}={}", std::env::var(k).ok()?)))
        .collect();
    let mut text = String::from(
        "//! The family classifier's discriminant ([`crate::family_classifier`]), generated by\n",
    );
    if !options.is_empty() {
        text += &format!("//! `{}`\n", options.join(" "));
    }
    text += "//! `cargo run --release -p proctex-analyzer --example corpus_lab -- table LABELS DIR OUT`\n\
             //! from the labelled textures of `tools/corpus/` (`extract.py`).\n\n";
    let present: Vec<String> = c
        .present
        .iter()
        .map(|&k| format!("{} ({})", names[k], count(k)))
        .collect();
    // The comment wrapped at 100 columns, as the sources are.
    let held = std::env::var("CORPUS_LAB_SETTING").is_ok();
    let words = match std::env::var("CORPUS_LAB_AUG") {
        Ok(a) if a.starts_with("blur:") => format!(
            "Trained on {} textures (four quadrants each, and each quadrant blurred by a Gaussian \
             of σ {} px, both tone orientations; the blurs chosen by {CORPUS_FOLDS}-fold \
             cross-validation over them, the held-out quadrants sharp and blurred): {}; \
             orientation harmonics {harmonics}, ridge {ridge} ({}; {CORPUS_FOLDS} folds by \
             texture stem).",
            corpus.len(),
            a["blur:".len()..].replace(',', " and "),
            present.join(", "),
            if held {
                "held at the setting the same cross-validation chose for the sharp views alone"
            } else {
                "chosen by the same cross-validation"
            }
        ),
        _ => format!(
            "Trained on {} textures (four quadrants each, both tone orientations): {}; orientation \
             harmonics {harmonics}, ridge {ridge} ({} {CORPUS_FOLDS}-fold cross-validation over \
             them, folds by texture stem).",
            corpus.len(),
            present.join(", "),
            if held {
                "held, not chosen by"
            } else {
                "chosen by"
            }
        ),
    };
    let mut line = String::from("//");
    for w in words.split(' ') {
        if line.len() + 1 + w.len() > 100 {
            text += &line;
            text += "\n";
            line = String::from("//");
        }
        line += " ";
        line += w;
    }
    text += &line;
    text += "\n\n";
    text +=
        "/// The orientation harmonics of the features ([`crate::family_classifier::features`]).\n";
    text += &format!("pub const HARMONICS: usize = {harmonics};\n\n");
    text += "/// The classes: pattern families' names and `noise`.\n#[rustfmt::skip]\n";
    let quoted: Vec<String> = c
        .present
        .iter()
        .map(|&k| format!("{:?}", names[k]))
        .collect();
    text += &format!(
        "pub const CLASSES: [&str; {}] = [{}];\n\n",
        quoted.len(),
        quoted.join(", ")
    );
    let (dims, n) = (c.model.proj.len(), c.model.proj[0].len());
    text += "/// The discriminant's projection: one row of feature weights per dimension.\n#[rustfmt::skip]\n";
    text += &format!("pub const PROJECTION: [[f64; {n}]; {dims}] = [\n");
    for r in &c.model.proj {
        text += &row(r);
    }
    text += "];\n\n/// Each class's mean in the projected space ([`CLASSES`] order).\n#[rustfmt::skip]\n";
    text += &format!(
        "pub const MEANS: [[f64; {dims}]; {}] = [\n",
        c.present.len()
    );
    for m in &c.model.means {
        text += &row(m);
    }
    text += "];\n";
    std::fs::write(out, text).unwrap();
}

fn eval(labels: &str, dir: &str, dev: &str) {
    let names = class_names();
    let noise = names.len() - 1;
    let corpus = load_corpus(labels, dir, &names);
    let counts: Vec<usize> = (0..names.len())
        .map(|c| corpus.iter().filter(|t| t.class == c).count())
        .collect();
    println!(
        "training textures per class: {:?}",
        names.iter().zip(&counts).collect::<Vec<_>>()
    );
    let (harmonics, ridge) = choose_setting(&corpus, &names);
    // DEVDIR may list several sets, comma-separated (the development set and its degraded copies,
    // `examples/degraded_set`): each is scored; the first alone feeds the options below.
    let load_set = |dir: &str| -> Vec<(lab_common::Patch, Descriptor)> {
        let patches = lab_common::load(dir);
        let descriptors = proctex::parallel::map_in_order(&patches, |p| describe(&p.photo));
        patches.into_iter().zip(descriptors).collect()
    };
    let sets: Vec<(&str, Vec<(lab_common::Patch, Descriptor)>)> =
        dev.split(',').map(|d| (d, load_set(d))).collect();
    let dev_patches = &sets[0].1;
    if let Some(n) = std::env::var("CORPUS_LAB_BOOTSTRAP")
        .ok()
        .and_then(|v| v.parse().ok())
    {
        bootstrap(&corpus, dev_patches, n, harmonics, ridge);
    }
    if let Some(path) = std::env::var_os("CORPUS_LAB_FEATURES") {
        dump_features(&path, &corpus, dev_patches, &names, harmonics);
    }
    let all: Vec<&Texture> = corpus.iter().collect();
    let c = Classifier::train(&all, names.len(), harmonics, ridge);
    if let Ok(list) = std::env::var("CORPUS_LAB_PRIORS") {
        prior_sweep(&list, &corpus, dev_patches, &c, &names, (harmonics, ridge));
        return;
    }
    // With `CORPUS_LAB_DEV_FOLDS=K`, each development photo is scored by a discriminant trained
    // on the corpus and the development photos of the other K − 1 folds (by photo).
    let dev_folds: usize = std::env::var("CORPUS_LAB_DEV_FOLDS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);
    let dev_train = if dev_folds > 0 {
        dev_textures(dev_patches, &names)
    } else {
        Vec::new()
    };
    let fold_classifiers: Vec<Classifier> = (0..dev_folds)
        .map(|f| {
            let mut train: Vec<&Texture> = corpus.iter().collect();
            train.extend(
                dev_train
                    .iter()
                    .filter(|t| proctex::devset::fold_of(&t.file, dev_folds) != f),
            );
            Classifier::train(&train, names.len(), harmonics, ridge)
        })
        .collect();
    for (set, dev_patches) in &sets {
        let (mut first, mut top3, mut family, mut ns, mut served, mut nt) = (0, 0, 0, 0, 0, 0);
        for (p, d) in dev_patches {
            let c = if dev_folds > 0 {
                &fold_classifiers[proctex::devset::fold_of(&p.file, dev_folds)]
            } else {
                &c
            };
            let order = c.order(d);
            let name = |k: usize| names[k];
            let labelled = |k: usize| p.labels.iter().any(|l| l == name(k));
            if std::env::var("CORPUS_LAB_DUMP").is_ok() {
                let ranked: Vec<&str> = order.iter().map(|&k| name(k)).collect();
                // The photo's margin: the noise class's distance minus the nearest family's.
                let ds = c.distances(d);
                let at = |k: usize| ds[c.present.iter().position(|&q| q == k).unwrap()];
                let fam = *order.iter().find(|&&k| k != noise).unwrap();
                eprintln!(
                    "dump\t{}\t{}\t{}\t{}",
                    p.file,
                    p.structured,
                    ranked.join(","),
                    at(noise) - at(fam)
                );
            }
            if p.structured {
                ns += 1;
                first += labelled(order[0]) as usize;
                top3 += order.iter().take(3).any(|&k| labelled(k)) as usize;
                family += order
                    .iter()
                    .find(|&&k| k != noise)
                    .is_some_and(|&k| labelled(k)) as usize;
            } else {
                nt += 1;
                served += (order[0] == noise) as usize;
            }
        }
        println!(
            "{set}: development set ({}), harmonics {harmonics} ridge {ridge} (chosen on the corpus): structured first {first}/{ns}, top three {top3}/{ns}, nearest family labelled {family}/{ns}; stochastic → noise {served}/{nt}",
            if dev_folds > 0 {
                format!("{dev_folds} folds by photo held out, the others trained on")
            } else {
                "never trained on".to_string()
            }
        );
    }
    if let Some(other) = std::env::var_os("CORPUS_LAB_ALSO") {
        // Unlabelled photos (the shipped samples): each quadrant's nearest class and family.
        let dir = other.to_string_lossy().to_string();
        let mut files: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok()?.file_name().into_string().ok())
            .filter(|f| f.ends_with(".png"))
            .collect();
        files.sort();
        for f in files {
            let photo = Photo::decode(&std::fs::read(format!("{dir}/{f}")).unwrap()).unwrap();
            let mut line = Vec::new();
            for q in lab_common::quadrants(&photo) {
                let order = c.order(&describe(&q));
                let fam = order.iter().find(|&&k| k != noise).unwrap();
                line.push(format!("{}/{}", names[order[0]], names[*fam]));
            }
            println!("{f}: {}", line.join(" "));
        }
    }
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    match a[1].as_str() {
        "sheet" => lab_common::corpus_files::sheet(
            &a[2],
            &a[3],
            &a[4],
            a[5].parse().unwrap(),
            a[6].parse().unwrap(),
        ),
        "eval" => eval(&a[2], &a[3], &a[4]),
        "dds" => lab_common::corpus_files::dds(&a[2], &a[3]),
        "set" => lab_common::corpus_files::set(&a[2], &a[3], &a[4]),
        "table" => table(&a[2], &a[3], &a[4]),
        _ => panic!("sheet | eval | dds | set | table"),
    }
}
