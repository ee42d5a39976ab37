//! Intensity distribution (Lagae §5): Gaussianization by rank, the inverse CDF stored as K+1
//! knots, and its monotone piecewise cubic Hermite (Fritsch–Carlson 1980) interpolation.
//!
//! **Departure from the paper (knot placement).** Lagae subsamples the inverse CDF at uniform
//! probabilities `j/K` and evaluates it at `Φ(g/σ)`. With K = 10 the outer knots are the sample
//! minimum and maximum, so the top and bottom deciles become straight ramps out to the extreme
//! pixels: on heavy-tailed channels (chroma of a mostly grey stone with a few rust spots) this
//! inflated the synthesised variance several-fold and covered the texture in speckles (measured:
//! see `uniform_knots_inflate_heavy_tails` below). We sample the inverse CDF at Gaussian-spaced
//! probabilities `p_j = Φ(z_j)`, `z_j = −Z + 2Z·j/K` with `Z = 2.5`: the same K+1 numbers and
//! the same monotone spline, but over `t = (g/σ + Z) / 2Z`, which is `Φ⁻¹` of the probability the
//! paper would use, so the composition `inverse CDF ∘ Φ` is evaluated without computing `Φ`.
//! Values beyond ±Z clamp to the 0.6 % and 99.4 % quantiles.
//!
//! [`fc_tangents`], [`knot_coordinate`] and [`spline_eval`] are per-pixel code with WGSL twins.

/// Half-width, in standard deviations, of the Gaussian range the knots span.
pub const KNOT_Z: f32 = 2.5;

/// Spline coordinate `t ∈ [0, 1]` of a Gaussian value `g` of standard deviation `sigma`.
#[inline]
pub fn knot_coordinate(g: f32, sigma: f32) -> f32 {
    ((g / sigma + KNOT_Z) / (2.0 * KNOT_Z)).clamp(0.0, 1.0)
}

/// Probability at which knot `j` of `k + 1` samples the inverse CDF.
pub fn knot_probability(j: usize, k: usize) -> f64 {
    let z = -KNOT_Z as f64 + 2.0 * KNOT_Z as f64 * j as f64 / k as f64;
    phi_f64(z)
}

/// Standard normal CDF.
pub fn phi_f64(x: f64) -> f64 {
    0.5 * erfc_f64(-x / std::f64::consts::SQRT_2)
}

/// Inverse standard normal CDF (Acklam's rational approximation refined by one Halley step;
/// relative error ~1e-15). Analysis only, so f64.
pub fn phi_inv(p: f64) -> f64 {
    const A: [f64; 6] = [
        -3.969_683_028_665_376e1,
        2.209_460_984_245_205e2,
        -2.759_285_104_469_687e2,
        1.383_577_518_672_69e2,
        -3.066_479_806_614_716e1,
        2.506_628_277_459_239,
    ];
    const B: [f64; 5] = [
        -5.447_609_879_822_406e1,
        1.615_858_368_580_409e2,
        -1.556_989_798_598_866e2,
        6.680_131_188_771_972e1,
        -1.328_068_155_288_572e1,
    ];
    const C: [f64; 6] = [
        -7.784_894_002_430_293e-3,
        -3.223_964_580_411_365e-1,
        -2.400_758_277_161_838,
        -2.549_732_539_343_734,
        4.374_664_141_464_968,
        2.938_163_982_698_783,
    ];
    const D: [f64; 4] = [
        7.784_695_709_041_462e-3,
        3.224_671_290_700_398e-1,
        2.445_134_137_142_996,
        3.754_408_661_907_416,
    ];
    let p = p.clamp(1e-300, 1.0 - 1e-16);
    let plow = 0.02425;
    let x = if p < plow {
        let q = (-2.0 * p.ln()).sqrt();
        (((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    } else if p <= 1.0 - plow {
        let q = p - 0.5;
        let r = q * q;
        (((((A[0] * r + A[1]) * r + A[2]) * r + A[3]) * r + A[4]) * r + A[5]) * q
            / (((((B[0] * r + B[1]) * r + B[2]) * r + B[3]) * r + B[4]) * r + 1.0)
    } else {
        let q = (-2.0 * (1.0 - p).ln()).sqrt();
        -(((((C[0] * q + C[1]) * q + C[2]) * q + C[3]) * q + C[4]) * q + C[5])
            / ((((D[0] * q + D[1]) * q + D[2]) * q + D[3]) * q + 1.0)
    };
    // One Halley step on erfc-based CDF for full precision.
    let e = 0.5 * erfc_f64(-x / std::f64::consts::SQRT_2) - p;
    let u = e * (2.0 * std::f64::consts::PI).sqrt() * (x * x / 2.0).exp();
    x - u / (1.0 + x * u / 2.0)
}

/// Complementary error function (Numerical Recipes' Chebyshev fit, |rel. error| < 1.2e-7).
pub fn erfc_f64(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let r = t
        * (-z * z - 1.265_512_23
            + t * (1.000_023_68
                + t * (0.374_091_96
                    + t * (0.096_784_18
                        + t * (-0.186_288_06
                            + t * (0.278_868_07
                                + t * (-1.135_203_98
                                    + t * (1.488_515_87
                                        + t * (-0.822_152_23 + t * 0.170_872_77)))))))))
            .exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// Result of Gaussianizing one channel.
#[derive(Clone, Debug, PartialEq)]
pub struct Gaussianized {
    /// The channel mapped to a Gaussian of the channel's own standard deviation, by mid-rank.
    pub values: Vec<f32>,
    /// `K + 1` quantiles of the original channel at probabilities [`knot_probability`].
    pub knots: Vec<f32>,
    /// Standard deviation of the original channel.
    pub sigma: f64,
}

/// Gaussianizes `values` by rank (ties share their mid-rank, so equal inputs stay equal and no
/// noise is invented), and samples the inverse CDF at `knots + 1` probabilities.
pub fn gaussianize(values: &[f32], knots: usize) -> Gaussianized {
    let n = values.len();
    assert!(n > 0 && knots >= 1);
    let mean = values.iter().map(|&v| v as f64).sum::<f64>() / n as f64;
    let var = values
        .iter()
        .map(|&v| (v as f64 - mean).powi(2))
        .sum::<f64>()
        / n as f64;
    let sigma = var.sqrt();

    let order = sort_indices(values);
    let quantile = |p: f64| -> f32 {
        // Linear interpolation between order statistics.
        let pos = p * (n - 1) as f64;
        let i = pos.floor() as usize;
        let f = pos - i as f64;
        let a = values[order[i] as usize] as f64;
        let b = values[order[(i + 1).min(n - 1)] as usize] as f64;
        (a + f * (b - a)) as f32
    };
    let knot_values: Vec<f32> = (0..=knots)
        .map(|j| quantile(knot_probability(j, knots)))
        .collect();

    let mut out = vec![0.0f32; n];
    let mut start = 0;
    while start < n {
        let v = values[order[start] as usize];
        let mut end = start + 1;
        while end < n && values[order[end] as usize] == v {
            end += 1;
        }
        // Ranks start..end share the mid-rank; probability at its centre.
        let mid = (start + end - 1) as f64 / 2.0;
        let g = (sigma * phi_inv((mid + 0.5) / n as f64)) as f32;
        for &i in &order[start..end] {
            out[i as usize] = g;
        }
        start = end;
    }
    Gaussianized {
        values: out,
        knots: knot_values,
        sigma,
    }
}

/// Indices that sort `values` ascending (stable): an LSD radix sort on the order-preserving
/// integer image of the floats, O(n) instead of a comparison sort.
pub fn sort_indices(values: &[f32]) -> Vec<u32> {
    let n = values.len();
    let key = |v: f32| -> u32 {
        let b = v.to_bits();
        if b & 0x8000_0000 != 0 {
            !b
        } else {
            b | 0x8000_0000
        }
    };
    let mut keys: Vec<(u32, u32)> = values
        .iter()
        .enumerate()
        .map(|(i, &v)| (key(v), i as u32))
        .collect();
    let mut tmp = vec![(0u32, 0u32); n];
    for pass in 0..3 {
        let shift = pass * 11;
        let mut count = [0usize; 2049];
        for &(k, _) in &keys {
            count[((k >> shift) & 0x7ff) as usize + 1] += 1;
        }
        for i in 0..2048 {
            count[i + 1] += count[i];
        }
        for &e in &keys {
            let b = ((e.0 >> shift) & 0x7ff) as usize;
            tmp[count[b]] = e;
            count[b] += 1;
        }
        std::mem::swap(&mut keys, &mut tmp);
    }
    keys.into_iter().map(|(_, i)| i).collect()
}

/// Fritsch–Carlson tangents for knots at uniform spacing `h = 1/K`: three-point average slopes,
/// zero at local extrema, then limited so that `α² + β² ≤ 9` on every interval (monotone).
pub fn fc_tangents(knots: &[f32]) -> Vec<f32> {
    let n = knots.len();
    if n < 2 {
        return vec![0.0; n];
    }
    let h = 1.0 / (n - 1) as f64;
    let delta: Vec<f64> = knots
        .windows(2)
        .map(|w| (w[1] as f64 - w[0] as f64) / h)
        .collect();
    let mut m = vec![0.0f64; n];
    m[0] = delta[0];
    m[n - 1] = delta[n - 2];
    for k in 1..n - 1 {
        m[k] = if delta[k - 1] * delta[k] <= 0.0 {
            0.0
        } else {
            0.5 * (delta[k - 1] + delta[k])
        };
    }
    for k in 0..n - 1 {
        if delta[k] == 0.0 {
            m[k] = 0.0;
            m[k + 1] = 0.0;
            continue;
        }
        let a = m[k] / delta[k];
        let b = m[k + 1] / delta[k];
        let s = a * a + b * b;
        if s > 9.0 {
            let tau = 3.0 / s.sqrt();
            m[k] = tau * a * delta[k];
            m[k + 1] = tau * b * delta[k];
        }
    }
    m.into_iter().map(|v| v as f32).collect()
}

/// The Hermite spline through `(j/K, knots[j])` with `tangents`, at `u ∈ [0, 1]` (clamped).
/// Synthesis calls it at `u = knot_coordinate(g, σ)`.
#[inline]
pub fn spline_eval(knots: &[f32], tangents: &[f32], u: f32) -> f32 {
    let k = knots.len() - 1;
    let s = u.clamp(0.0, 1.0) * k as f32;
    let i = (s.floor() as usize).min(k - 1);
    let t = s - i as f32;
    let h = 1.0 / k as f32;
    let t2 = t * t;
    let t3 = t2 * t;
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + t;
    let h01 = -2.0 * t3 + 3.0 * t2;
    let h11 = t3 - t2;
    h00 * knots[i] + h10 * h * tangents[i] + h01 * knots[i + 1] + h11 * h * tangents[i + 1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phi_and_inverse() {
        for &(x, p) in &[(0.0, 0.5), (1.0, 0.841_344_746), (-2.0, 0.022_750_132)] {
            assert!((phi_f64(x) - p).abs() < 3e-7, "{x}");
            assert!((phi_inv(p) - x).abs() < 1e-6, "{p}");
        }
        for i in 1..1000 {
            let p = i as f64 / 1000.0;
            assert!((phi_f64(phi_inv(p)) - p).abs() < 1e-6);
        }
        assert!((knot_probability(5, 10) - 0.5).abs() < 1e-6);
        assert!((knot_probability(0, 10) - 0.00621).abs() < 1e-4);
        assert_eq!(knot_coordinate(0.0, 2.0), 0.5);
        assert_eq!(knot_coordinate(-100.0, 1.0), 0.0);
    }

    /// Samples `n` values of a heavy-tailed distribution (mostly near 0, 0.3 % far out) through its
    /// quantile function, as a Gaussian model would, with the paper's uniform knots and ours; the
    /// variance of the result relative to the true variance.
    fn synthesized_variance_ratio(uniform: bool) -> f64 {
        let n = 20_000;
        let vals: Vec<f32> = (0..n)
            .map(|i| {
                let u = (i as f64 + 0.5) / n as f64;
                let v = 0.01 * phi_inv(u);
                (if i % 333 == 0 { v + 0.3 } else { v }) as f32
            })
            .collect();
        let k = 10;
        let g = gaussianize(&vals, k);
        let order = sort_indices(&vals);
        let knots: Vec<f32> = if uniform {
            (0..=k)
                .map(|j| vals[order[((n - 1) * j) / k] as usize])
                .collect()
        } else {
            g.knots.clone()
        };
        let t = fc_tangents(&knots);
        let var = |v: &[f64]| {
            let m = v.iter().sum::<f64>() / v.len() as f64;
            v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len() as f64
        };
        let synth: Vec<f64> = (0..n)
            .map(|i| {
                let z = phi_inv((i as f64 + 0.5) / n as f64) as f32;
                let u = if uniform {
                    phi_f64(z as f64) as f32
                } else {
                    knot_coordinate(z, 1.0)
                };
                spline_eval(&knots, &t, u) as f64
            })
            .collect();
        let orig: Vec<f64> = vals.iter().map(|&v| v as f64).collect();
        var(&synth) / var(&orig)
    }

    #[test]
    fn uniform_knots_inflate_heavy_tails() {
        let paper = synthesized_variance_ratio(true);
        let ours = synthesized_variance_ratio(false);
        println!("variance ratio, uniform knots {paper:.2}, gaussian-spaced {ours:.2}");
        assert!(paper > 1.5, "{paper}");
        assert!(
            (ours - 1.0).abs() < (paper - 1.0).abs(),
            "{ours} vs {paper}"
        );
    }

    #[test]
    fn radix_sort_sorts() {
        let v: Vec<f32> = (0..10_000)
            .map(|i| (((i * 7919) % 10007) as f32 - 5000.0) * 0.013)
            .chain([0.0, -0.0, 1e-30, -1e-30, f32::MAX, f32::MIN])
            .collect();
        let idx = sort_indices(&v);
        for w in idx.windows(2) {
            assert!(v[w[0] as usize] <= v[w[1] as usize]);
        }
    }

    #[test]
    fn gaussianize_gives_gaussian_and_quantiles() {
        // A skewed (exponential-like) channel with ties.
        let vals: Vec<f32> = (0..20_000)
            .map(|i| {
                let u = (i as f64 + 0.5) / 20_000.0;
                ((-(1.0 - u).ln() * 50.0).floor() / 200.0) as f32
            })
            .collect();
        let g = gaussianize(&vals, 10);
        assert_eq!(g.knots.len(), 11);
        assert!(g.knots.windows(2).all(|w| w[0] <= w[1]));
        let m = g.values.iter().map(|&v| v as f64).sum::<f64>() / vals.len() as f64;
        assert!(m.abs() < 0.02 * g.sigma, "{m}");
        // Equal inputs map to equal outputs.
        for i in 1..vals.len() {
            if vals[i] == vals[i - 1] {
                assert_eq!(g.values[i], g.values[i - 1]);
            }
        }
    }

    #[test]
    fn spline_is_monotone_and_interpolates() {
        let knots = [0.0f32, 0.0, 0.1, 0.5, 0.52, 0.9, 1.0, 1.0, 1.3, 2.0, 2.0];
        let tang = fc_tangents(&knots);
        for (j, &k) in knots.iter().enumerate() {
            let u = j as f32 / 10.0;
            assert!((spline_eval(&knots, &tang, u) - k).abs() < 1e-5);
        }
        let mut prev = f32::MIN;
        for i in 0..=10_000 {
            let y = spline_eval(&knots, &tang, i as f32 / 10_000.0);
            assert!(y >= prev - 1e-6, "not monotone at {i}");
            prev = y;
        }
    }
}
