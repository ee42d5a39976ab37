//! Family classifier laboratory: a discriminant over rotation-invariant descriptor features,
//! trained on the pattern database alone (no development photo), scored on the development
//! set's structured patches (labelled family first / in the top three) and stochastic ones.
//!
//! `cargo run --release -p proctex-analyzer --example family_lda_lab -- DIR`

mod lab_common;

use lab_common::augment;
use proctex::db::{Db, describe_pattern, query, sample};
use proctex::devset::fold_of;
use proctex::gabor::{Descriptor, FREQUENCIES, ORIENTATIONS, QUANTILES, SIZE, describe};
use proctex::noise::Tile;
use proctex::pattern::PatternKind;
use proctex::render::pattern::structure_image;
use proctex::rng;
use proctex::two_tone::two_tone;

/// Descriptors of `per_kind` database patterns per family, each clean and `augmented` times
/// photo-like (the retrieval lab's augmentation), with their class.
fn augmented_set(per_kind: usize, augmented: usize) -> Vec<(Descriptor, usize)> {
    let tile = Tile::new_2d(1);
    let jobs: Vec<(usize, usize, usize)> = (0..PatternKind::ALL.len())
        .flat_map(|c| (0..per_kind).flat_map(move |i| (0..=augmented).map(move |a| (c, i, a))))
        .collect();
    use rayon::prelude::*;
    jobs.par_iter()
        .map(|&(c, i, a)| {
            let kind = PatternKind::ALL[c];
            let pattern = sample(kind, i * 7);
            let d = if a == 0 {
                describe_pattern(&pattern, 1, &tile)
            } else {
                let n = SIZE;
                let s = structure_image(&pattern, 1, &tile, n as u32, n as u32);
                let key = ((c as u32) << 24) ^ ((i as u32) << 8) ^ (a as u32) << 2;
                let u = |j: u32| {
                    rng::uniform(7, 0x6175_6775, key.wrapping_mul(65_537).wrapping_add(j)) as f32
                };
                describe(&augment(&s, n, pattern.scale, &u))
            };
            (d, c)
        })
        .collect()
}

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

/// Rotation-invariant features: per (part, frequency) the log mean energy over orientations
/// and the magnitudes of the orientation profile's harmonics relative to its mean; then the
/// quantiles.
fn features(d: &Descriptor, harmonics: usize) -> Vec<f64> {
    let block = ORIENTATIONS * FREQUENCIES;
    let mut out = Vec::new();
    for part in 0..2 {
        for k in 0..FREQUENCIES {
            let e: Vec<f64> = (0..ORIENTATIONS)
                .map(|o| d.0[part * block + o * FREQUENCIES + k] as f64)
                .collect();
            let t = e.iter().sum::<f64>() / ORIENTATIONS as f64;
            out.push((t + 1e-4).ln());
            for h in 1..=harmonics {
                let (mut re, mut im) = (0.0, 0.0);
                for (o, v) in e.iter().enumerate() {
                    let a = std::f64::consts::TAU * (h * o) as f64 / ORIENTATIONS as f64;
                    re += v * a.cos();
                    im += v * a.sin();
                }
                out.push((re * re + im * im).sqrt() / ORIENTATIONS as f64 / (t + 1e-4));
            }
        }
    }
    for i in 0..QUANTILES {
        out.push(d.0[2 * block + i] as f64);
    }
    out
}

/// Cholesky factor of a symmetric positive-definite matrix (row-major n×n).
fn cholesky(a: &[f64], n: usize) -> Vec<f64> {
    let mut l = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..=i {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= l[i * n + k] * l[j * n + k];
            }
            l[i * n + j] = if i == j {
                s.max(1e-12).sqrt()
            } else {
                s / l[j * n + j]
            };
        }
    }
    l
}

/// Solve L x = b (forward).
fn forward(l: &[f64], n: usize, b: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0; n];
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * x[k];
        }
        x[i] = s / l[i * n + i];
    }
    x
}

/// Jacobi eigen decomposition of a symmetric matrix: (values, vectors as columns).
fn jacobi(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut a = a.to_vec();
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    for _sweep in 0..60 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i * n + j] * a[i * n + j])
            .sum();
        if off < 1e-18 {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                let apq = a[p * n + q];
                if apq.abs() < 1e-30 {
                    continue;
                }
                let theta = (a[q * n + q] - a[p * n + p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for k in 0..n {
                    let akp = a[k * n + p];
                    let akq = a[k * n + q];
                    a[k * n + p] = c * akp - s * akq;
                    a[k * n + q] = s * akp + c * akq;
                }
                for k in 0..n {
                    let apk = a[p * n + k];
                    let aqk = a[q * n + k];
                    a[p * n + k] = c * apk - s * aqk;
                    a[q * n + k] = s * apk + c * aqk;
                }
                for k in 0..n {
                    let vkp = v[k * n + p];
                    let vkq = v[k * n + q];
                    v[k * n + p] = c * vkp - s * vkq;
                    v[k * n + q] = s * vkp + c * vkq;
                }
            }
        }
    }
    ((0..n).map(|i| a[i * n + i]).collect(), v)
}

struct Model {
    /// Projection rows (dims × n).
    proj: Vec<Vec<f64>>,
    /// Class means in the projected space.
    means: Vec<Vec<f64>>,
    /// Training points in the projected space with their class.
    points: Vec<(Vec<f64>, usize)>,
}

fn project(m: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    m.iter()
        .map(|r| r.iter().zip(x).map(|(a, b)| a * b).sum())
        .collect()
}

fn fit(xs: &[(Vec<f64>, usize)], classes: usize, ridge: f64, dims: usize) -> Model {
    let n = xs[0].0.len();
    let mut mean = vec![vec![0.0; n]; classes];
    let mut count = vec![0.0; classes];
    for (x, c) in xs {
        for i in 0..n {
            mean[*c][i] += x[i];
        }
        count[*c] += 1.0;
    }
    for c in 0..classes {
        for i in 0..n {
            mean[c][i] /= count[c];
        }
    }
    let grand: Vec<f64> = (0..n)
        .map(|i| (0..classes).map(|c| mean[c][i]).sum::<f64>() / classes as f64)
        .collect();
    let mut w = vec![0.0; n * n];
    for (x, c) in xs {
        for i in 0..n {
            let di = x[i] - mean[*c][i];
            for j in 0..n {
                w[i * n + j] += di * (x[j] - mean[*c][j]);
            }
        }
    }
    let tot = xs.len() as f64;
    let tr = (0..n).map(|i| w[i * n + i]).sum::<f64>() / tot / n as f64;
    for v in w.iter_mut() {
        *v /= tot;
    }
    for i in 0..n {
        w[i * n + i] += ridge * tr;
    }
    let mut b = vec![0.0; n * n];
    for c in 0..classes {
        for i in 0..n {
            for j in 0..n {
                b[i * n + j] += (mean[c][i] - grand[i]) * (mean[c][j] - grand[j]) / classes as f64;
            }
        }
    }
    // M = L⁻¹ B L⁻ᵀ
    let l = cholesky(&w, n);
    let mut lb = vec![0.0; n * n]; // L⁻¹ B, column by column
    for j in 0..n {
        let col: Vec<f64> = (0..n).map(|i| b[i * n + j]).collect();
        let s = forward(&l, n, &col);
        for i in 0..n {
            lb[i * n + j] = s[i];
        }
    }
    let mut m = vec![0.0; n * n]; // (L⁻¹ (L⁻¹ B)ᵀ)ᵀ
    for i in 0..n {
        let row: Vec<f64> = (0..n).map(|j| lb[i * n + j]).collect();
        let s = forward(&l, n, &row);
        for j in 0..n {
            m[i * n + j] = s[j];
        }
    }
    let (vals, vecs) = jacobi(&m, n);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| vals[b].total_cmp(&vals[a]));
    // Projection: rows uᵀ L⁻¹ → solve Lᵀ p = u.
    let proj: Vec<Vec<f64>> = order[..dims]
        .iter()
        .map(|&k| {
            let u: Vec<f64> = (0..n).map(|i| vecs[i * n + k]).collect();
            let mut p = vec![0.0; n];
            for i in (0..n).rev() {
                let mut s = u[i];
                for j in i + 1..n {
                    s -= l[j * n + i] * p[j];
                }
                p[i] = s / l[i * n + i];
            }
            p
        })
        .collect();
    let means = mean.iter().map(|m| project(&proj, m)).collect();
    let points = xs.iter().map(|(x, c)| (project(&proj, x), *c)).collect();
    Model {
        proj,
        means,
        points,
    }
}

fn d2(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

/// Class scores (lower is better) for one projected query.
fn scores(m: &Model, y: &[f64], classes: usize, knn: usize) -> Vec<f64> {
    if knn == 0 {
        return m.means.iter().map(|c| d2(c, y)).collect();
    }
    let mut ds: Vec<(f64, usize)> = m.points.iter().map(|(p, c)| (d2(p, y), *c)).collect();
    ds.select_nth_unstable_by(knn, |a, b| a.0.total_cmp(&b.0));
    let mut votes = vec![0.0; classes];
    for (_, c) in &ds[..knn] {
        votes[*c] += 1.0;
    }
    // Nearest point per class breaks ties and ranks the classes with no vote.
    let mut nearest = vec![f64::INFINITY; classes];
    for (d, c) in &ds {
        nearest[*c] = nearest[*c].min(*d);
    }
    (0..classes)
        .map(|c| -votes[c] + nearest[c] * 1e-6)
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
        let v = augmented_set(per_kind, augmented);
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
                let (mut first, mut top3, mut n) = (0, 0, 0);
                let mut folds = [(0, 0); 4];
                let (mut noiselike, mut stoch) = (0, 0);
                let mut confusion = std::collections::BTreeMap::<(String, String), usize>::new();
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
                    let mut order: Vec<usize> = (0..classes).collect();
                    order.sort_by(|&x, &y| s[x].total_cmp(&s[y]));
                    let fam = |r: usize| names[order[r]].to_string();
                    if p.structured {
                        n += 1;
                        let f0 = p.labels.contains(&fam(0));
                        let t3 = (0..3).any(|r| p.labels.contains(&fam(r)));
                        first += f0 as usize;
                        top3 += t3 as usize;
                        let k = fold_of(&p.file, 4);
                        folds[k].0 += f0 as usize;
                        folds[k].1 += 1;
                        *confusion.entry((p.labels[0].clone(), fam(0))).or_default() += 1;
                    } else {
                        stoch += 1;
                        if ["perlin", "turbulence", "ridged"].contains(&fam(0).as_str()) {
                            noiselike += 1;
                        }
                    }
                }
                println!(
                    "harmonics {harmonics} ridge {ridge:e} knn {knn:2}: structured first {first}/{n} top3 {top3}/{n} folds {folds:?} stochastic→noise-like {noiselike}/{stoch}"
                );
                if std::env::var("VERBOSE").is_ok() {
                    println!("  {confusion:?}");
                }
            }
        }
    }
}
