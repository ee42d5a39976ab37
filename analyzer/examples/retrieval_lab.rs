//! Retrieval laboratory: how often the family nearest by retrieval distance is one the
//! development set's manifest allows, for structure-map and database variants.
//!
//! `cargo run --release -p proctex-analyzer --example retrieval_lab -- DIR [PER_KIND]`

mod lab_common;

use lab_common::{augment, load, std_of};
use proctex::cues::blur;
use proctex::db::{Db, Entry, describe_pattern, query, sample};
use proctex::devset::fold_of;
use proctex::gabor::{SIZE, describe};
use proctex::input::Photo;
use proctex::noise::Tile;
use proctex::pattern::PatternKind;
use proctex::render::pattern::structure_image;
use proctex::rng;
use proctex::two_tone::{network_phase, two_tone};

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
