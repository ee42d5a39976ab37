//! What the development-set laboratories share (`retrieval_lab`, `family_lda_lab`, `corpus_lab`,
//! `coarse_lab`, `descriptor_parts`, `null_gate_lab`, `ranked_renders`, `scale_sweep`,
//! `nearer_render_lab`, `scale_ladder_lab`): the quadrant patches of the labelled photos, a
//! quadrant as the ranking sees it, and the photo-like augmentation of a clean pattern.

// Not every laboratory fits a discriminant.
#[allow(dead_code)]
pub mod lda;
// Only the topology laboratory measures the joints.
#[allow(dead_code)]
pub mod topology;
// Only the laboratories of one quadrant's ranking fits take a quadrant as the ranking sees it.
#[allow(dead_code)]
pub mod ranked;
// Only the corpus laboratory decodes DDS textures.
#[allow(dead_code)]
pub mod dds;
// Only the corpus laboratory writes contact sheets, decoded terrains and corpus sets.
#[allow(dead_code)]
pub mod corpus_files;

use proctex::cues::blur;
use proctex::db::sample;
use proctex::devset::{Category, parse_manifest};
use proctex::gabor::SIZE;
use proctex::input::{Crop, Photo};
use proctex::noise::Tile;
use proctex::pattern::PatternKind;
use proctex::render::pattern::structure_image;
use proctex::rng;

/// One quadrant of a development-set photo with its labels.
pub struct Patch {
    pub file: String,
    pub structured: bool,
    pub labels: Vec<String>,
    pub photo: Photo,
}

/// The four quadrants of a photo, as the development set's patches are cut: top-left,
/// top-right, bottom-left, bottom-right.
pub fn quadrants(photo: &Photo) -> Vec<Photo> {
    let (hw, hh) = (photo.width / 2, photo.height / 2);
    [(0, 0), (1, 0), (0, 1), (1, 1)]
        .iter()
        .map(|&(qx, qy)| {
            photo
                .crop(Crop {
                    x: qx * hw,
                    y: qy * hh,
                    w: hw,
                    h: hh,
                })
                .unwrap()
        })
        .collect()
}

/// The names the yardstick gives the quadrants ([`proctex::devset::PATCHES`]), in the order
/// of [`quadrants`].
pub const QUADRANT_NAMES: [&str; 4] = ["top-left", "top-right", "bottom-left", "bottom-right"];

/// The leading TSV columns of a laboratory's line for `p`, the `index`-th patch of [`load`]:
/// file, quadrant name, category, labels (joined by `/`).
// Only the laboratories that print one line per patch with its labels use it.
#[allow(dead_code)]
pub fn patch_columns(p: &Patch, index: usize) -> String {
    format!(
        "{}\t{}\t{}\t{}",
        p.file,
        QUADRANT_NAMES[index % 4],
        if p.structured {
            "structured"
        } else {
            "stochastic"
        },
        p.labels.join("/")
    )
}

/// `photo` written as an 8-bit RGB PNG at `path` (values clamped to 0–1).
// Only the laboratories that write their renders out save images.
#[allow(dead_code)]
pub fn save_png(photo: &Photo, path: &std::path::Path) {
    let img = image::RgbImage::from_fn(photo.width, photo.height, |x, y| {
        let c = photo.pixels[(y * photo.width + x) as usize];
        image::Rgb(c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
    });
    img.save(path).unwrap();
}

/// `photo`'s automatic ranking (default refinement, every family fitted), with the noise
/// model's fitted params and the candidate of the classifier's nearest family: what the
/// nearer-render rule compares (`nearer_render_lab`, `scale_ladder_lab`).
// Only the nearer-render laboratories compare the nearest family with the noise model.
#[allow(dead_code)]
pub fn ranking_with_nearest(
    photo: &Photo,
    opts: &proctex::analyze::Options,
) -> (
    Option<proctex::params::Params>,
    Option<proctex::retrieve::Suggestion>,
) {
    use proctex::retrieve::{Refinement, classify, suggest_with};
    let db = proctex::db::Db::shipped();
    let ranked = suggest_with(db, photo, opts, Refinement::default(), &|_, _| true);
    let nearest = classify(photo).iter().find_map(|(c, _)| *c);
    let noise = ranked
        .iter()
        .find(|s| s.name == "noise")
        .and_then(|s| s.preview.clone());
    let family = nearest.and_then(|k| ranked.into_iter().find(|s| s.name == k.name()));
    (noise, family)
}

/// The four quadrants of every photo in the development set at `dir`.
pub fn load(dir: &str) -> Vec<Patch> {
    let text = std::fs::read_to_string(format!("{dir}/manifest.tsv")).unwrap();
    let mut out = Vec::new();
    for e in parse_manifest(&text).unwrap() {
        let bytes = std::fs::read(format!("{dir}/{}", e.file)).unwrap();
        let photo = Photo::decode(&bytes).unwrap();
        for q in quadrants(&photo) {
            out.push(Patch {
                file: e.file.clone(),
                structured: e.category == Category::Structured,
                labels: e.families.clone().unwrap_or_default(),
                photo: q,
            });
        }
    }
    out
}

pub fn std_of(v: &[f32]) -> f32 {
    let n = v.len() as f32;
    let m = v.iter().sum::<f32>() / n;
    (v.iter().map(|x| (x - m) * (x - m)).sum::<f32>() / n).sqrt()
}

/// Connected components (4-neighbour) of `mask`; label per pixel (usize::MAX outside).
pub fn components(mask: &[bool], n: usize) -> Vec<usize> {
    let mut label = vec![usize::MAX; n * n];
    let mut next = 0;
    let mut stack = Vec::new();
    for s in 0..n * n {
        if !mask[s] || label[s] != usize::MAX {
            continue;
        }
        label[s] = next;
        stack.push(s);
        while let Some(j) = stack.pop() {
            let (x, y) = (j % n, j / n);
            for (nx, ny) in [(x + n - 1, y), (x + 1, y), (x, y + n - 1), (x, y + 1)] {
                let k = (ny % n) * n + nx % n;
                if mask[k] && label[k] == usize::MAX {
                    label[k] = next;
                    stack.push(k);
                }
            }
        }
        next += 1;
    }
    label
}

/// A photo-like version of a clean structure image: per-piece tone offsets, shading, grain,
/// blur and a tone curve, amounts drawn from `u`.
pub fn augment(s: &[f32], n: usize, scale: f32, u: &dyn Fn(u32) -> f32) -> Vec<f32> {
    let sd = std_of(s).max(1e-3);
    let mut sorted = s.to_vec();
    sorted.sort_by(f32::total_cmp);
    let med = sorted[sorted.len() / 2];
    let lo = sorted[0];
    let hi = sorted[sorted.len() - 1];
    // Per piece: components of the half above the median (pieces in most families).
    let mask: Vec<bool> = s.iter().map(|&v| v > med).collect();
    let lab = components(&mask, n);
    let piece_amp = 0.5 * u(1) * sd;
    let mut out: Vec<f32> = s
        .iter()
        .zip(&lab)
        .map(|(&v, &l)| {
            let w = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
            if l == usize::MAX {
                v
            } else {
                let g = (u(100 + (l as u32 % 4000)) - 0.5) * 3.4;
                v + piece_amp * g * w
            }
        })
        .collect();
    // Shading: white noise blurred to about three pattern units.
    let shade: Vec<f32> = (0..n * n).map(|i| u(10_000 + i as u32) - 0.5).collect();
    let shade = blur(&shade, n, (3.0 * scale).clamp(4.0, 24.0));
    let ss = std_of(&shade).max(1e-6);
    let shade_amp = 0.6 * u(2) * sd;
    // Grain: white noise blurred a little.
    let grain: Vec<f32> = (0..n * n).map(|i| u(40_000 + i as u32) - 0.5).collect();
    let grain = blur(&grain, n, 0.5 + u(4));
    let gs = std_of(&grain).max(1e-6);
    let grain_amp = 0.6 * u(3) * sd;
    for i in 0..n * n {
        out[i] += shade_amp * shade[i] / ss + grain_amp * grain[i] / gs;
    }
    let out = blur(&out, n, 1.2 * u(5));
    // Tone curve: a power of the normalised value.
    let (lo, hi) = out
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let gamma = (2.0 * u(6) - 1.0).mul_add(0.7, 0.0).exp();
    out.iter()
        .map(|&v| {
            let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
            t.powf(gamma)
        })
        .collect()
}

/// `measure` of the 128² maps of `per_kind` database patterns per family, each clean and
/// `copies` times photo-like ([`augment`]), with the family's index in `PatternKind::ALL`.
#[allow(dead_code)] // the retrieval laboratory uses the shipped database instead
pub fn training_maps<T: Send>(
    per_kind: usize,
    copies: usize,
    measure: &(dyn Fn(&[f32]) -> T + Sync),
) -> Vec<(T, usize)> {
    use rayon::prelude::*;
    let tile = Tile::new_2d(1);
    let jobs: Vec<(usize, usize, usize)> = (0..PatternKind::ALL.len())
        .flat_map(|c| (0..per_kind).flat_map(move |i| (0..=copies).map(move |a| (c, i, a))))
        .collect();
    jobs.par_iter()
        .map(|&(c, i, a)| {
            let pattern = sample(PatternKind::ALL[c], i * 7);
            let n = SIZE;
            let s = structure_image(&pattern, 1, &tile, n as u32, n as u32);
            let map = if a == 0 {
                s
            } else {
                let key = ((c as u32) << 24) ^ ((i as u32) << 8) ^ (a as u32) << 2;
                let u = |j: u32| {
                    rng::uniform(7, 0x6175_6775, key.wrapping_mul(65_537).wrapping_add(j)) as f32
                };
                augment(&s, n, pattern.scale, &u)
            };
            (measure(&map), c)
        })
        .collect()
}

/// The laboratories' score of one way of ordering the families: structured patches with a
/// labelled family first and in the top three (per hash fold of 4), stochastic patches whose
/// first family is a noise-like one, and the confusion of the first choice.
#[derive(Default)]
#[allow(dead_code)] // the retrieval laboratory keeps its own counts of nearest families
pub struct Tally {
    first: usize,
    top3: usize,
    structured: usize,
    folds: [(usize, usize); 4],
    noise_like: usize,
    stochastic: usize,
    confusion: std::collections::BTreeMap<(String, String), usize>,
}

#[allow(dead_code)]
impl Tally {
    /// Counts one patch whose families, best first, are `order` (names).
    pub fn add(&mut self, file: &str, structured: bool, labels: &[String], order: &[&str]) {
        let labelled = |r: usize| labels.iter().any(|l| l == order[r]);
        if structured {
            let first = labelled(0);
            self.structured += 1;
            self.first += first as usize;
            self.top3 += (0..3).any(labelled) as usize;
            let k = proctex::devset::fold_of(file, 4);
            self.folds[k].0 += first as usize;
            self.folds[k].1 += 1;
            *self
                .confusion
                .entry((labels[0].clone(), order[0].to_string()))
                .or_default() += 1;
        } else {
            self.stochastic += 1;
            self.noise_like += ["perlin", "turbulence", "ridged"].contains(&order[0]) as usize;
        }
    }

    /// One line of counts (and the confusion when `VERBOSE` is set).
    pub fn line(&self) -> String {
        let mut s = format!(
            "structured first {}/{n} top3 {}/{n} folds {:?} stochastic→noise-like {}/{}",
            self.first,
            self.top3,
            self.folds,
            self.noise_like,
            self.stochastic,
            n = self.structured
        );
        if std::env::var("VERBOSE").is_ok() {
            s += &format!("\n  {:?}", self.confusion);
        }
        s
    }
}

/// Families ordered by `scores` (lower first), as names.
#[allow(dead_code)]
pub fn ordered(scores: &[f64]) -> Vec<&'static str> {
    let mut order: Vec<usize> = (0..scores.len()).collect();
    order.sort_by(|&x, &y| scores[x].total_cmp(&scores[y]));
    order.iter().map(|&i| PatternKind::ALL[i].name()).collect()
}
