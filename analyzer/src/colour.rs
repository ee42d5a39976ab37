//! Colour decorrelation (Lagae §6): mean RGB and the principal axes of the 3×3 covariance; and
//! the sliced Wasserstein distance between two images' colour distributions.
//!
//! The basis is stored as a proper rotation (rows are the principal axes, determinant +1) with a
//! deterministic sign convention, so that it can be turned into a quaternion and slerped when
//! morphing (Lagae §8). Degenerate covariances (grey photos, flat colours) get a canonical basis
//! instead of whatever an eigen-solver happens to return.

/// Mean and principal axes of a set of RGB values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pca {
    /// Mean RGB.
    pub mean: [f64; 3],
    /// Rows are unit principal axes, by decreasing variance; a rotation (det +1).
    pub basis: [[f64; 3]; 3],
    /// Variance along each axis.
    pub variance: [f64; 3],
    /// The RGB covariance matrix.
    pub covariance: [[f64; 3]; 3],
}

/// Mean and covariance of `pixels`, in one pass of f64 sums of the values shifted by the first
/// pixel (the "shifted data" algorithm, which avoids the cancellation of raw moments).
pub fn mean_covariance(pixels: &[[f32; 3]]) -> ([f64; 3], [[f64; 3]; 3]) {
    let n = pixels.len().max(1) as f64;
    let k = pixels
        .first()
        .copied()
        .unwrap_or([0.0; 3])
        .map(|v| v as f64);
    let mut s = [0.0f64; 3];
    let mut ss = [0.0f64; 6]; // rr, rg, rb, gg, gb, bb
    for p in pixels {
        let d = [p[0] as f64 - k[0], p[1] as f64 - k[1], p[2] as f64 - k[2]];
        s[0] += d[0];
        s[1] += d[1];
        s[2] += d[2];
        ss[0] += d[0] * d[0];
        ss[1] += d[0] * d[1];
        ss[2] += d[0] * d[2];
        ss[3] += d[1] * d[1];
        ss[4] += d[1] * d[2];
        ss[5] += d[2] * d[2];
    }
    let shifted_mean = s.map(|v| v / n);
    let idx = [[0, 1, 2], [1, 3, 4], [2, 4, 5]];
    let mut cov = [[0.0f64; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            cov[i][j] = ss[idx[i][j]] / n - shifted_mean[i] * shifted_mean[j];
        }
    }
    let mean = [0, 1, 2].map(|c| shifted_mean[c] + k[c]);
    (mean, cov)
}

/// Principal component analysis of `pixels`.
pub fn pca(pixels: &[[f32; 3]]) -> Pca {
    let (mean, cov) = mean_covariance(pixels);
    let (values, vectors) = symmetric_eigen(cov);
    let scale = values[0].abs().max(1e-12);
    // Two eigenvalues closer than this (relative to the largest) span a degenerate plane.
    let tol = 1e-7;
    let mut axes = vectors;
    if values[0] <= 1e-14 {
        // Flat image: no colour variation at all.
        axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let lum = normalize([1.0, 1.0, 1.0]);
        axes[0] = lum;
        axes[1] = canonical_orthogonal(lum);
    } else if (values[1] - values[2]).abs() <= tol * scale {
        // The 2nd and 3rd axes are not determined (grey photo): pick a canonical pair.
        fix_sign(&mut axes[0]);
        axes[1] = canonical_orthogonal(axes[0]);
    } else {
        fix_sign(&mut axes[0]);
        fix_sign(&mut axes[1]);
    }
    axes[2] = cross(axes[0], axes[1]);
    Pca {
        mean,
        basis: axes,
        variance: values.map(|v| v.max(0.0)),
        covariance: cov,
    }
}

/// The colour statistics of `pixels` in a basis whose first axis is `first` (normalised, sign
/// fixed) and whose other two are the principal axes of the pixels' spread orthogonal to it,
/// the larger first; a rotation (det +1). `variance` holds each axis's variance, which need not
/// decrease, and the channels are decorrelated only within the orthogonal plane.
///
/// Why (ours): a structured model's residual is drawn as three independent channels, and step 4
/// of its fit gives the channel along the photo's tone line the power that the pattern's
/// structure lacks ([`crate::structure`]). In the residual's own principal axes that power
/// went into axes that mix luminance with colour (on a grey-blue rubble wall the first two
/// were 0.42 and 0.90 along the tone line), and drawing it independently per axis made
/// saturated blue and yellow blotches that the photo does not have (its blue-minus-yellow
/// deviation 5.7 of 255, the cells render's 27). With the tone line as an axis, the missing
/// structure is drawn along it and the colour axes keep the colour the photo has.
pub fn pca_with_first_axis(pixels: &[[f32; 3]], first: [f64; 3]) -> Pca {
    let (mean, cov) = mean_covariance(pixels);
    let variance_along = |b: [f64; 3]| {
        let cb = [0, 1, 2].map(|i| dot(cov[i], b));
        dot(b, cb).max(0.0)
    };
    let mut a = if dot(first, first) > 1e-18 {
        normalize(first)
    } else {
        normalize([1.0, 1.0, 1.0])
    };
    fix_sign(&mut a);
    // The 2×2 covariance in the plane orthogonal to `a`, in a fixed orthonormal pair (u, v).
    let u = canonical_orthogonal(a);
    let v = cross(a, u);
    let cu = [0, 1, 2].map(|i| dot(cov[i], u));
    let (suu, svv, suv) = (dot(u, cu), variance_along(v), dot(v, cu));
    // Its major axis at angle θ from u: tan 2θ = 2 s_uv / (s_uu − s_vv); where the spread is
    // (nearly) round, u itself.
    let theta = if suv.abs() <= 1e-14 * (suu + svv).abs().max(1e-30) {
        if svv > suu {
            std::f64::consts::FRAC_PI_2
        } else {
            0.0
        }
    } else {
        0.5 * (2.0 * suv).atan2(suu - svv)
    };
    let (c, sn) = (theta.cos(), theta.sin());
    let mut b = [0, 1, 2].map(|k| c * u[k] + sn * v[k]);
    fix_sign(&mut b);
    let basis = [a, b, cross(a, b)];
    Pca {
        mean,
        basis,
        variance: basis.map(variance_along),
        covariance: cov,
    }
}

/// Sign convention: the component of largest magnitude is positive (first one on ties).
fn fix_sign(v: &mut [f64; 3]) {
    let mut k = 0;
    for i in 1..3 {
        if v[i].abs() > v[k].abs() + 1e-12 {
            k = i;
        }
    }
    if v[k] < 0.0 {
        v.iter_mut().for_each(|x| *x = -*x);
    }
}

/// A fixed unit vector orthogonal to `a`: Gram–Schmidt on (1, −1, 0), or on (0, 1, −1) when that
/// is (nearly) parallel to `a`.
fn canonical_orthogonal(a: [f64; 3]) -> [f64; 3] {
    for cand in [[1.0, -1.0, 0.0], [0.0, 1.0, -1.0], [1.0, 0.0, 0.0]] {
        let d = dot(cand, a);
        let v = [cand[0] - d * a[0], cand[1] - d * a[1], cand[2] - d * a[2]];
        if dot(v, v) > 1e-6 {
            let mut v = normalize(v);
            fix_sign(&mut v);
            return v;
        }
    }
    unreachable!("three independent candidates cannot all be parallel to one vector")
}

/// Dot product.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = dot(v, v).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

/// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations. Returns eigenvalues
/// in decreasing order and the matching unit eigenvectors as rows. Deterministic and exact to
/// rounding for these sizes.
pub fn symmetric_eigen(m: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut a = m;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _sweep in 0..50 {
        let off = a[0][1].powi(2) + a[0][2].powi(2) + a[1][2].powi(2);
        let diag = a[0][0].powi(2) + a[1][1].powi(2) + a[2][2].powi(2);
        if off <= 1e-30 * diag.max(1e-300) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q].abs() < 1e-300 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J
            for k in 0..3 {
                let akp = a[k][p];
                let akq = a[k][q];
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let apk = a[p][k];
                let aqk = a[q][k];
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            // V ← V J (columns are eigenvectors)
            for k in 0..3 {
                let vkp = v[k][p];
                let vkq = v[k][q];
                v[k][p] = c * vkp - s * vkq;
                v[k][q] = s * vkp + c * vkq;
            }
        }
    }
    let mut order = [0usize, 1, 2];
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]).then(i.cmp(&j)));
    let values = order.map(|i| a[i][i]);
    let vectors = order.map(|i| [v[0][i], v[1][i], v[2][i]]);
    (values, vectors)
}

/// Determinant of a 3×3 matrix given by rows.
pub fn det3(m: [[f64; 3]; 3]) -> f64 {
    dot(m[0], cross(m[1], m[2]))
}

// Rotations of colour bases as quaternions: what a morph (Lagae §8) and a texture mixture
// (Heeger & Bergen §5) interpolate, so that every intermediate basis is a rotation.

/// A rotation as a unit quaternion `(w, x, y, z)`.
pub type Quat = [f64; 4];

/// The quaternion of a proper rotation matrix (Shepperd's method, stable for every angle).
pub fn quat_from_matrix(m: [[f64; 3]; 3]) -> Quat {
    let tr = m[0][0] + m[1][1] + m[2][2];
    let q = if tr > 0.0 {
        let s = (tr + 1.0).sqrt() * 2.0;
        [
            0.25 * s,
            (m[2][1] - m[1][2]) / s,
            (m[0][2] - m[2][0]) / s,
            (m[1][0] - m[0][1]) / s,
        ]
    } else if m[0][0] > m[1][1] && m[0][0] > m[2][2] {
        let s = (1.0 + m[0][0] - m[1][1] - m[2][2]).sqrt() * 2.0;
        [
            (m[2][1] - m[1][2]) / s,
            0.25 * s,
            (m[0][1] + m[1][0]) / s,
            (m[0][2] + m[2][0]) / s,
        ]
    } else if m[1][1] > m[2][2] {
        let s = (1.0 + m[1][1] - m[0][0] - m[2][2]).sqrt() * 2.0;
        [
            (m[0][2] - m[2][0]) / s,
            (m[0][1] + m[1][0]) / s,
            0.25 * s,
            (m[1][2] + m[2][1]) / s,
        ]
    } else {
        let s = (1.0 + m[2][2] - m[0][0] - m[1][1]).sqrt() * 2.0;
        [
            (m[1][0] - m[0][1]) / s,
            (m[0][2] + m[2][0]) / s,
            (m[1][2] + m[2][1]) / s,
            0.25 * s,
        ]
    };
    normalize4(q)
}

/// The rotation matrix of a unit quaternion.
pub fn matrix_from_quat(q: Quat) -> [[f64; 3]; 3] {
    let [w, x, y, z] = normalize4(q);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

fn normalize4(q: Quat) -> Quat {
    let l = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    q.map(|v| v / l)
}

/// Spherical linear interpolation along the shorter arc.
pub fn slerp(a: Quat, b: Quat, t: f64) -> Quat {
    let mut d: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
    let b = if d < 0.0 {
        d = -d;
        b.map(|v| -v)
    } else {
        b
    };
    if d > 0.9995 {
        // Nearly the same rotation: linear, then normalised.
        return normalize4([0, 1, 2, 3].map(|i| a[i] + t * (b[i] - a[i])));
    }
    let theta = d.clamp(-1.0, 1.0).acos();
    let (sa, sb) = (
        ((1.0 - t) * theta).sin() / theta.sin(),
        (t * theta).sin() / theta.sin(),
    );
    normalize4([0, 1, 2, 3].map(|i| sa * a[i] + sb * b[i]))
}

/// Quantile function of `v` at `count` mid-probabilities.
fn quantiles(v: Vec<f32>, count: usize) -> Vec<f64> {
    let n = v.len();
    // Each quantile interpolates between two order statistics: only those are found
    // (`radix::order_statistics`, the same bits as sorting all of `v`).
    let at: Vec<(usize, f64)> = (0..count)
        .map(|i| {
            let pos = (i as f64 + 0.5) / count as f64 * (n - 1) as f64;
            let k = pos.floor() as usize;
            (k, pos - k as f64)
        })
        .collect();
    let ranks: Vec<usize> = at
        .iter()
        .flat_map(|&(k, _)| [k, (k + 1).min(n - 1)])
        .collect();
    let stats = crate::radix::order_statistics(&v, &ranks);
    at.iter()
        .zip(stats.chunks_exact(2))
        .map(|(&(_, f), s)| s[0] as f64 * (1.0 - f) + s[1] as f64 * f)
        .collect()
}

fn directions() -> Vec<[f32; 3]> {
    let mut d = vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for (a, b) in [(0, 1), (0, 2), (1, 2)] {
        for s in [1.0f32, -1.0] {
            let mut v = [0.0f32; 3];
            v[a] = std::f32::consts::FRAC_1_SQRT_2;
            v[b] = s * std::f32::consts::FRAC_1_SQRT_2;
            d.push(v);
        }
    }
    let k = 1.0 / 3.0f32.sqrt();
    for (sy, sz) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
        d.push([k, sy * k, sz * k]);
    }
    d
}

/// Sliced Wasserstein-1 distance between the colour distributions of `a` and `b`.
pub fn colour_distance(a: &crate::input::Photo, b: &crate::input::Photo) -> f64 {
    ColourQuantiles::of(a).distance(&ColourQuantiles::of(b))
}

/// The quantile functions of an image's colours projected on [`colour_distance`]'s directions:
/// what the distance compares, computed once for an image compared many times.
#[derive(Clone, Debug, PartialEq)]
pub struct ColourQuantiles(Vec<Vec<f64>>);

impl ColourQuantiles {
    /// The quantiles of `p`.
    pub fn of(p: &crate::input::Photo) -> ColourQuantiles {
        ColourQuantiles(
            directions()
                .iter()
                .map(|d| {
                    let proj: Vec<f32> = p
                        .pixels
                        .iter()
                        .map(|c| c[0] * d[0] + c[1] * d[1] + c[2] * d[2])
                        .collect();
                    quantiles(proj, 512)
                })
                .collect(),
        )
    }

    /// [`colour_distance`] between the two images these quantiles came from.
    pub fn distance(&self, other: &ColourQuantiles) -> f64 {
        let total: f64 = self
            .0
            .iter()
            .zip(&other.0)
            .map(|(qa, qb)| {
                qa.iter().zip(qb).map(|(x, y)| (x - y).abs()).sum::<f64>() / qa.len() as f64
            })
            .sum();
        total / self.0.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_rotation(b: [[f64; 3]; 3]) {
        for i in 0..3 {
            for j in 0..3 {
                let d = dot(b[i], b[j]);
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((d - want).abs() < 1e-9, "{b:?}");
            }
        }
        assert!((det3(b) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn eigen_of_known_matrix() {
        let m = [[4.0, 1.0, 0.0], [1.0, 3.0, 0.0], [0.0, 0.0, 1.0]];
        let (vals, vecs) = symmetric_eigen(m);
        let s5 = 5.0f64.sqrt();
        assert!((vals[0] - (7.0 + s5) / 2.0).abs() < 1e-12);
        assert!((vals[1] - (7.0 - s5) / 2.0).abs() < 1e-12);
        assert!((vals[2] - 1.0).abs() < 1e-12);
        for k in 0..3 {
            let v = vecs[k];
            let mv = [dot(m[0], v), dot(m[1], v), dot(m[2], v)];
            for c in 0..3 {
                assert!((mv[c] - vals[k] * v[c]).abs() < 1e-10);
            }
        }
    }

    /// `pixels` in the channels of `p` (their offsets from its mean along its axes).
    fn projected(pixels: &[[f32; 3]], p: &Pca) -> Vec<[f64; 3]> {
        pixels
            .iter()
            .map(|px| {
                let d = [0, 1, 2].map(|c| px[c] as f64 - p.mean[c]);
                p.basis.map(|axis| dot(axis, d))
            })
            .collect()
    }

    /// With the first axis given, the basis is a rotation that starts with it, its second axis
    /// is the spread's major axis across it, and the two axes across it are uncorrelated.
    #[test]
    fn a_given_first_axis_leads_a_rotation_whose_other_axes_decorrelate() {
        let pixels: Vec<[f32; 3]> = (0..5000)
            .map(|i| {
                let a = ((i * 7919) % 1000) as f32 / 1000.0;
                let b = ((i * 104_729) % 997) as f32 / 997.0;
                let c = ((i * 1_299_709) % 991) as f32 / 991.0;
                [
                    0.4 + 0.3 * a + 0.2 * b,
                    0.4 + 0.3 * a - 0.2 * b,
                    0.4 + 0.3 * a + 0.05 * c,
                ]
            })
            .collect();
        let grey = normalize([1.0, 1.0, 1.0]);
        let p = pca_with_first_axis(&pixels, [-2.0, -2.0, -2.0]);
        check_rotation(p.basis);
        for k in 0..3 {
            assert!((p.basis[0][k] - grey[k]).abs() < 1e-12, "{:?}", p.basis);
        }
        // The red-minus-green spread (0.2 b) is the larger one across grey.
        let rg = normalize([1.0, -1.0, 0.0]);
        assert!(dot(p.basis[1], rg).abs() > 0.95, "{:?}", p.basis);
        let proj = projected(&pixels, &p);
        let n = proj.len() as f64;
        let (s12, s11, s22) = proj.iter().fold((0.0, 0.0, 0.0), |(a, b, c), v| {
            (a + v[1] * v[2], b + v[1] * v[1], c + v[2] * v[2])
        });
        assert!((s12 / (s11 * s22).sqrt()).abs() < 1e-6);
        for k in 0..3 {
            let var = proj.iter().map(|v| v[k] * v[k]).sum::<f64>() / n;
            assert!((var - p.variance[k]).abs() < 1e-9 * (1.0 + var), "{k}");
        }
    }

    #[test]
    fn colour_photo_gives_rotation_and_decorrelates() {
        let pixels: Vec<[f32; 3]> = (0..5000)
            .map(|i| {
                let a = ((i * 7919) % 1000) as f32 / 1000.0;
                let b = ((i * 104_729) % 997) as f32 / 997.0;
                [0.2 + 0.5 * a, 0.1 + 0.4 * a + 0.1 * b, 0.3 - 0.2 * b]
            })
            .collect();
        let p = pca(&pixels);
        check_rotation(p.basis);
        assert!(p.variance[0] >= p.variance[1] && p.variance[1] >= p.variance[2]);
        // Projected channels are uncorrelated.
        let proj = projected(&pixels, &p);
        for i in 0..3 {
            for j in (i + 1)..3 {
                let (mut sij, mut sii, mut sjj) = (0.0, 0.0, 0.0);
                for v in &proj {
                    sij += v[i] * v[j];
                    sii += v[i] * v[i];
                    sjj += v[j] * v[j];
                }
                if sii > 1e-12 && sjj > 1e-12 {
                    assert!((sij / (sii * sjj).sqrt()).abs() < 1e-6);
                }
            }
        }
    }

    #[test]
    fn grey_and_flat_photos_get_canonical_bases() {
        let grey: Vec<[f32; 3]> = (0..1000).map(|i| [(i % 37) as f32 / 37.0; 3]).collect();
        let p = pca(&grey);
        check_rotation(p.basis);
        let s3 = 1.0 / 3.0f64.sqrt();
        for c in 0..3 {
            assert!((p.basis[0][c] - s3).abs() < 1e-9);
        }
        assert!(p.variance[1].abs() < 1e-12 && p.variance[2].abs() < 1e-12);
        // Same answer for another grey photo: the basis does not depend on noise.
        let grey2: Vec<[f32; 3]> = (0..500).map(|i| [(i % 11) as f32 / 11.0; 3]).collect();
        let q = pca(&grey2);
        for r in 0..3 {
            for c in 0..3 {
                assert!((p.basis[r][c] - q.basis[r][c]).abs() < 1e-9);
            }
        }
        let flat = vec![[0.3f32, 0.6, 0.1]; 100];
        let f = pca(&flat);
        check_rotation(f.basis);
        assert!((f.mean[1] - 0.6).abs() < 1e-6);
    }

    #[test]
    fn quaternion_round_trip_and_slerp_stay_rotations() {
        let m = matrix_from_quat(normalize4([0.3, -0.5, 0.7, 0.2]));
        let q = quat_from_matrix(m);
        let m2 = matrix_from_quat(q);
        for i in 0..3 {
            for j in 0..3 {
                assert!((m[i][j] - m2[i][j]).abs() < 1e-12);
            }
        }
        let a = quat_from_matrix([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        for k in 0..=10 {
            let r = matrix_from_quat(slerp(a, q, k as f64 / 10.0));
            assert!((det3(r) - 1.0).abs() < 1e-9);
        }
    }
}
