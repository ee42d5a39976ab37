//! What the development-set laboratories share (`retrieval_lab`, `family_lda_lab`): the
//! quadrant patches of the labelled photos, and the photo-like augmentation of a clean pattern.

use proctex::cues::blur;
use proctex::devset::{Category, parse_manifest};
use proctex::input::{Crop, Photo};

/// One quadrant of a development-set photo with its labels.
pub struct Patch {
    pub file: String,
    pub structured: bool,
    pub labels: Vec<String>,
    pub photo: Photo,
}

/// The four quadrants of every photo in the development set at `dir`.
pub fn load(dir: &str) -> Vec<Patch> {
    let text = std::fs::read_to_string(format!("{dir}/manifest.tsv")).unwrap();
    let mut out = Vec::new();
    for e in parse_manifest(&text).unwrap() {
        let bytes = std::fs::read(format!("{dir}/{}", e.file)).unwrap();
        let photo = Photo::decode(&bytes).unwrap();
        let (hw, hh) = (photo.width / 2, photo.height / 2);
        for (qx, qy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            out.push(Patch {
                file: e.file.clone(),
                structured: e.category == Category::Structured,
                labels: e.families.clone().unwrap_or_default(),
                photo: photo
                    .crop(Crop {
                        x: qx * hw,
                        y: qy * hh,
                        w: hw,
                        h: hh,
                    })
                    .unwrap(),
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
