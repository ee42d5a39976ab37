//! Retrieval laboratory: how often the family nearest by retrieval distance is one the
//! development set's manifest allows, for structure-map and database variants.
//!
//! `cargo run --release -p proctex-analyzer --example retrieval_lab -- DIR [PER_KIND]`

use proctex::cues::blur;
use proctex::db::{Db, Entry, describe_pattern, query, sample};
use proctex::devset::{Category, fold_of, parse_manifest};
use proctex::gabor::{SIZE, describe};
use proctex::input::{Crop, Photo};
use proctex::noise::Tile;
use proctex::pattern::PatternKind;
use proctex::render::pattern::structure_image;
use proctex::rng;
use proctex::two_tone::{network_phase, two_tone};

struct Patch {
    file: String,
    structured: bool,
    labels: Vec<String>,
    photo: Photo,
}

fn load(dir: &str) -> Vec<Patch> {
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

fn std_of(v: &[f32]) -> f32 {
    let n = v.len() as f32;
    let m = v.iter().sum::<f32>() / n;
    (v.iter().map(|x| (x - m) * (x - m)).sum::<f32>() / n).sqrt()
}

/// Connected components (4-neighbour) of `mask`; label per pixel (usize::MAX outside).
fn components(mask: &[bool], n: usize) -> Vec<usize> {
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
fn augment(s: &[f32], n: usize, scale: f32, u: &dyn Fn(u32) -> f32) -> Vec<f32> {
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

fn build(per_kind: usize, augmented: usize) -> Db {
    let tile = Tile::new_2d(1);
    let jobs: Vec<(PatternKind, usize, usize)> = PatternKind::ALL
        .into_iter()
        .flat_map(|k| (0..per_kind).flat_map(move |i| (0..=augmented).map(move |a| (k, i, a))))
        .collect();
    use rayon::prelude::*;
    let entries: Vec<Entry> = jobs
        .par_iter()
        .map(|&(kind, i, a)| {
            let pattern = sample(kind, i);
            let descriptor = if a == 0 {
                describe_pattern(&pattern, 1, &tile)
            } else {
                let n = SIZE;
                let s = structure_image(&pattern, 1, &tile, n as u32, n as u32);
                let key = (kind.index() << 24) ^ ((i as u32) << 8) ^ (a as u32) << 2;
                let u = |j: u32| {
                    rng::uniform(7, 0x6175_6775, key.wrapping_mul(65_537).wrapping_add(j)) as f32
                };
                describe(&augment(&s, n, pattern.scale, &u))
            };
            Entry {
                pattern,
                descriptor,
            }
        })
        .collect();
    let db = Db {
        entries,
        weights: vec![],
    };
    Db::from_bytes(&db.to_bytes()).unwrap()
}

fn luminance(p: &Photo) -> Vec<f32> {
    p.pixels
        .iter()
        .map(|c| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2])
        .collect()
}

/// Local contrast normalisation: (v − local mean) / local deviation, Gaussian window σ.
fn lcn(v: &[f32], w: usize, h: usize, sigma: f32) -> Vec<f32> {
    assert_eq!(w, h);
    let m = blur(v, w, sigma);
    let d: Vec<f32> = v.iter().zip(&m).map(|(a, b)| a - b).collect();
    let d2: Vec<f32> = d.iter().map(|x| x * x).collect();
    let var = blur(&d2, w, sigma);
    let floor = 0.05 * std_of(v).max(1e-4);
    d.iter()
        .zip(&var)
        .map(|(x, v)| x / (v.sqrt() + floor))
        .collect()
}

fn median3(v: &[f32], n: usize) -> Vec<f32> {
    let mut out = vec![0.0; v.len()];
    for y in 0..n {
        for x in 0..n {
            let mut w = [0.0f32; 9];
            let mut k = 0;
            for dy in 0..3 {
                for dx in 0..3 {
                    let xx = (x + n + dx - 1) % n;
                    let yy = (y + n + dy - 1) % n;
                    w[k] = v[yy * n + xx];
                    k += 1;
                }
            }
            w.sort_by(f32::total_cmp);
            out[y * n + x] = w[4];
        }
    }
    out
}

/// Otsu's threshold over 64 bins.
fn otsu(v: &[f32]) -> f32 {
    let (lo, hi) = v
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    if hi <= lo {
        return lo;
    }
    let mut hist = [0f64; 64];
    for &x in v {
        let b = (((x - lo) / (hi - lo)) * 63.999) as usize;
        hist[b] += 1.0;
    }
    let total: f64 = hist.iter().sum();
    let sum_all: f64 = hist.iter().enumerate().map(|(i, h)| i as f64 * h).sum();
    let (mut w0, mut s0, mut best, mut at) = (0.0, 0.0, -1.0, 0);
    for (i, h) in hist.iter().enumerate() {
        w0 += h;
        s0 += i as f64 * h;
        let w1 = total - w0;
        if w0 == 0.0 || w1 == 0.0 {
            continue;
        }
        let (m0, m1) = (s0 / w0, (sum_all - s0) / w1);
        let between = w0 * w1 * (m0 - m1) * (m0 - m1);
        if between > best {
            best = between;
            at = i;
        }
    }
    lo + (at as f32 + 1.0) / 64.0 * (hi - lo)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = &args[1];
    let per_kind: usize = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(0);
    let augmented: usize = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(0);
    let patches = load(dir);
    let db_owned;
    let db = if per_kind == 0 {
        Db::shipped()
    } else {
        let t = std::time::Instant::now();
        db_owned = build(per_kind, augmented);
        eprintln!(
            "built {} entries in {:.1} s",
            db_owned.entries.len(),
            t.elapsed().as_secs_f32()
        );
        &db_owned
    };
    type MapFn = Box<dyn Fn(&Photo) -> Vec<f32>>;
    let maps: Vec<(&str, MapFn)> = vec![
        ("two-tone", Box::new(|p: &Photo| two_tone(p).structure)),
        ("luminance", Box::new(luminance)),
        (
            "lcn16",
            Box::new(|p: &Photo| lcn(&luminance(p), p.width as usize, p.height as usize, 16.0)),
        ),
        (
            "lcn32",
            Box::new(|p: &Photo| lcn(&luminance(p), p.width as usize, p.height as usize, 32.0)),
        ),
        (
            "lcn16-sign",
            Box::new(|p: &Photo| {
                lcn(&luminance(p), p.width as usize, p.height as usize, 16.0)
                    .iter()
                    .map(|&v| (v * 3.0).tanh())
                    .collect()
            }),
        ),
        (
            "tt-med3",
            Box::new(|p: &Photo| median3(&two_tone(p).structure, p.width as usize)),
        ),
        (
            "tt-med3-otsu",
            Box::new(|p: &Photo| {
                let m = median3(&two_tone(p).structure, p.width as usize);
                let t = otsu(&m);
                m.iter().map(|&v| if v > t { 1.0 } else { 0.0 }).collect()
            }),
        ),
        (
            "tt-highpass-otsu",
            Box::new(|p: &Photo| {
                let w = p.width as usize;
                let s = median3(&two_tone(p).structure, w);
                let b = blur(&s, w, 24.0);
                let m: Vec<f32> = s.iter().zip(&b).map(|(a, b)| a - b).collect();
                let t = otsu(&m);
                m.iter().map(|&v| if v > t { 1.0 } else { 0.0 }).collect()
            }),
        ),
    ];
    let names: Vec<&str> = PatternKind::ALL.iter().map(|k| k.name()).collect();
    for (name, f) in &maps {
        let (mut first, mut top3, mut n) = (0, 0, 0);
        let mut by_fold = [(0, 0); 4];
        let mut noiselike = 0;
        let mut stoch = 0;
        for p in &patches {
            let map = f(&p.photo);
            let (w, h) = (p.photo.width as usize, p.photo.height as usize);
            let (q, _) = query(&map, w, h);
            let net = network_phase(&map, w, h);
            let mut best: Vec<(f32, usize)> = db
                .top_per_kind_paired(&q, 1, net)
                .iter()
                .enumerate()
                .filter_map(|(i, v)| v.first().map(|m| (m.distance, i)))
                .collect();
            best.sort_by(|a, b| a.0.total_cmp(&b.0));
            let fam = |r: usize| names[best[r].1].to_string();
            if p.structured {
                n += 1;
                let f0 = p.labels.contains(&fam(0));
                let t3 = (0..3).any(|r| p.labels.contains(&fam(r)));
                first += f0 as usize;
                top3 += t3 as usize;
                let k = fold_of(&p.file, 4);
                by_fold[k].0 += f0 as usize;
                by_fold[k].1 += 1;
                if std::env::var("VERBOSE").is_ok() {
                    println!(
                        "{name} {} {:?} -> {} {} {}",
                        p.file,
                        p.labels,
                        fam(0),
                        fam(1),
                        fam(2)
                    );
                }
            } else {
                stoch += 1;
                if ["perlin", "turbulence", "ridged"].contains(&fam(0).as_str()) {
                    noiselike += 1;
                }
            }
        }
        println!(
            "{name:10} structured first {first}/{n}  top3 {top3}/{n}  folds {:?}  stochastic→noise-like {noiselike}/{stoch}",
            by_fold
        );
    }
}
