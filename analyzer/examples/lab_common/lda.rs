//! Fisher's linear discriminant for the laboratories: pooled within-class covariance with a
//! ridge, the generalised eigenproblem solved by Cholesky + Jacobi, class scores by the
//! distance to the class means or by k-nearest-neighbour votes in the projected space.

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

/// Solve Lᵀ x = b (backward), `l` the Cholesky factor.
fn backward(l: &[f64], n: usize, b: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0; n];
    for i in (0..n).rev() {
        let mut s = b[i];
        for k in i + 1..n {
            s -= l[k * n + i] * x[k];
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

pub struct Model {
    /// Projection rows (dims × n).
    pub proj: Vec<Vec<f64>>,
    /// Class means in the projected space.
    pub means: Vec<Vec<f64>>,
    /// Training points in the projected space with their class.
    pub points: Vec<(Vec<f64>, usize)>,
}

pub fn project(m: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
    m.iter()
        .map(|r| r.iter().zip(x).map(|(a, b)| a * b).sum())
        .collect()
}

pub fn fit(xs: &[(Vec<f64>, usize)], classes: usize, ridge: f64, dims: usize) -> Model {
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
    let diagonal = std::env::var("CORPUS_LAB_DIAG_RIDGE").is_ok();
    for i in 0..n {
        w[i * n + i] += if diagonal {
            ridge * w[i * n + i]
        } else {
            ridge * tr
        };
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
            backward(&l, n, &u)
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
pub fn scores(m: &Model, y: &[f64], classes: usize, knn: usize) -> Vec<f64> {
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

/// Each class's covariance in the projected space, shrunk towards the identity (the pooled
/// within-class covariance there, which the projection whitens): `(1 − alpha) Σ_c + alpha I`,
/// as its inverse (row-major) and the log of its determinant. For `CORPUS_LAB_QDA`: classes
/// scored by their own spread (quadratic discriminant) instead of the pooled one.
pub fn class_gaussians(m: &Model, classes: usize, alpha: f64) -> Vec<(Vec<f64>, f64)> {
    let n = m.means[0].len();
    (0..classes)
        .map(|c| {
            let mut s = vec![0.0; n * n];
            let mut count = 0.0;
            for (p, k) in &m.points {
                if *k != c {
                    continue;
                }
                count += 1.0;
                for i in 0..n {
                    for j in 0..n {
                        s[i * n + j] += (p[i] - m.means[c][i]) * (p[j] - m.means[c][j]);
                    }
                }
            }
            for i in 0..n {
                for j in 0..n {
                    let own = if count > 1.0 {
                        s[i * n + j] / count
                    } else {
                        0.0
                    };
                    let target = if i == j { 1.0 } else { 0.0 };
                    s[i * n + j] = (1.0 - alpha) * own + alpha * target;
                }
            }
            let l = cholesky(&s, n);
            let logdet = 2.0 * (0..n).map(|i| l[i * n + i].ln()).sum::<f64>();
            // Inverse column by column: solve L Lᵀ x = e_j.
            let mut inv = vec![0.0; n * n];
            for j in 0..n {
                let e: Vec<f64> = (0..n).map(|i| (i == j) as u8 as f64).collect();
                let x = backward(&l, n, &forward(&l, n, &e));
                for i in 0..n {
                    inv[i * n + j] = x[i];
                }
            }
            (inv, logdet)
        })
        .collect()
}

/// A projected query's quadratic-discriminant score for each class ([`class_gaussians`]):
/// Mahalanobis distance to the class mean plus the log determinant (−2 log-likelihood up to a
/// constant).
pub fn gaussian_scores(m: &Model, g: &[(Vec<f64>, f64)], y: &[f64]) -> Vec<f64> {
    let n = y.len();
    m.means
        .iter()
        .zip(g)
        .map(|(mu, (inv, logdet))| {
            let d: Vec<f64> = (0..n).map(|i| y[i] - mu[i]).collect();
            let mut q = 0.0;
            for i in 0..n {
                for j in 0..n {
                    q += d[i] * inv[i * n + j] * d[j];
                }
            }
            q + logdet
        })
        .collect()
}
