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
//! [`fc_tangents`], [`knot_coordinate`], [`spline_eval`] and [`hermite`] are per-pixel code with WGSL twins.

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

/// The standard deviation of `F⁻¹(Φ(Z))`, `Z` standard normal, for the inverse-CDF spline
/// through `knots` as the renderer evaluates it (clamped to its end knots past `±KNOT_Z`):
/// the midpoint rule over 400 steps of `z ∈ [−KNOT_Z, KNOT_Z]` weighted by the normal density,
/// the tails beyond at the end knots.
pub fn spline_sd(knots: &[f32]) -> f64 {
    const STEPS: usize = 400;
    let tangents = fc_tangents(knots);
    let z_max = KNOT_Z as f64;
    let tail = phi_f64(-z_max);
    let (first, last) = (knots[0] as f64, knots[knots.len() - 1] as f64);
    let (mut m0, mut m1, mut m2) = (
        2.0 * tail,
        tail * (first + last),
        tail * (first * first + last * last),
    );
    let dz = 2.0 * z_max / STEPS as f64;
    for i in 0..STEPS {
        let z = -z_max + (i as f64 + 0.5) * dz;
        let weight = (-0.5 * z * z).exp() / (2.0 * std::f64::consts::PI).sqrt() * dz;
        let v = spline_eval(knots, &tangents, ((z + z_max) / (2.0 * z_max)) as f32) as f64;
        m0 += weight;
        m1 += weight * v;
        m2 += weight * v * v;
    }
    let mean = m1 / m0;
    (m2 / m0 - mean * mean).max(0.0).sqrt()
}

/// Standard normal CDF.
pub fn phi_f64(x: f64) -> f64 {
    0.5 * erfc_f64(-x / std::f64::consts::SQRT_2)
}

/// Inverse standard normal CDF (Acklam's rational approximation, relative error < 1.2e-9).
/// Analysis only, so f64.
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
    if p < plow {
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
    }
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

/// Resolution of the rank computation: values are ranked in `2^14` bins across the channel's
/// range.
pub const RANK_BINS: usize = 1 << 14;

/// Range and moments of a channel (computed while projecting, so no extra pass).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChannelStats {
    /// Smallest value.
    pub lo: f32,
    /// Largest value.
    pub hi: f32,
    /// Number of values.
    pub n: usize,
    /// Mean.
    pub mean: f64,
    /// Standard deviation.
    pub sigma: f64,
}

/// Accumulates [`ChannelStats`]: f32 running sums over short runs, f64 across them.
#[derive(Clone, Debug)]
pub struct StatsAccumulator {
    lo: f32,
    hi: f32,
    n: usize,
    s1: f64,
    s2: f64,
}

impl Default for StatsAccumulator {
    fn default() -> Self {
        StatsAccumulator {
            lo: f32::INFINITY,
            hi: f32::NEG_INFINITY,
            n: 0,
            s1: 0.0,
            s2: 0.0,
        }
    }
}

impl StatsAccumulator {
    /// Adds a run of values (keep runs to a few thousand for f32 accuracy). Eight independent
    /// lanes, so that the min/max/sum dependency chains do not serialise.
    pub fn add_run(&mut self, values: &[f32]) {
        const L: usize = 8;
        let (mut lo, mut hi) = ([self.lo; L], [self.hi; L]);
        let (mut s1, mut s2) = ([0.0f32; L], [0.0f32; L]);
        let mut chunks = values.chunks_exact(L);
        for c in &mut chunks {
            for k in 0..L {
                let v = c[k];
                lo[k] = if v < lo[k] { v } else { lo[k] };
                hi[k] = if v > hi[k] { v } else { hi[k] };
                s1[k] += v;
                s2[k] += v * v;
            }
        }
        for (k, &v) in chunks.remainder().iter().enumerate() {
            lo[k] = lo[k].min(v);
            hi[k] = hi[k].max(v);
            s1[k] += v;
            s2[k] += v * v;
        }
        for k in 0..L {
            self.lo = self.lo.min(lo[k]);
            self.hi = self.hi.max(hi[k]);
            self.s1 += s1[k] as f64;
            self.s2 += s2[k] as f64;
        }
        self.n += values.len();
    }

    /// The statistics.
    pub fn finish(&self) -> ChannelStats {
        let n = self.n.max(1) as f64;
        let mean = self.s1 / n;
        ChannelStats {
            lo: self.lo,
            hi: self.hi,
            n: self.n,
            mean,
            sigma: (self.s2 / n - mean * mean).max(0.0).sqrt(),
        }
    }
}

/// Statistics of a slice.
pub fn channel_stats(values: &[f32]) -> ChannelStats {
    let mut acc = StatsAccumulator::default();
    for run in values.chunks(4096) {
        acc.add_run(run);
    }
    acc.finish()
}

/// The Gaussianizing map of one channel: value → rank bin → Gaussian value by mid-rank.
///
/// Ranks come from a counting pass over [`RANK_BINS`] bins spanning the channel's range instead
/// of a sort: values closer than 1/16384 of the range share a bin and so their mid-rank (exact
/// ties always do, so equal inputs stay equal and no noise is invented). For an 8-bit photo the
/// bins are finer than a code value (at least 1/255 of the range), and the pass is O(n) with at
/// most 16384 evaluations of `Φ⁻¹`, where a sort was the most expensive step of the analysis.
/// Quantiles interpolate linearly inside a bin.
#[derive(Clone, Debug, PartialEq)]
pub struct RankMap {
    lo: f32,
    scale: f32,
    z: Vec<f32>,
}

impl RankMap {
    /// The binning of a channel with `stats`: `(lo, scale)` with `bin = (v − lo)·scale`.
    pub fn binning(stats: &ChannelStats) -> (f32, f32) {
        if stats.hi <= stats.lo || stats.sigma == 0.0 {
            (stats.lo, 0.0)
        } else {
            (stats.lo, (RANK_BINS - 1) as f32 / (stats.hi - stats.lo))
        }
    }

    /// The bin of `v` under `binning`.
    #[inline]
    pub fn bin_of(v: f32, (lo, scale): (f32, f32)) -> u16 {
        (((v - lo) * scale) as usize).min(RANK_BINS - 1) as u16
    }

    /// The rank bin of `v`.
    #[inline]
    pub fn bin(&self, v: f32) -> u16 {
        Self::bin_of(v, (self.lo, self.scale))
    }

    /// The Gaussian value of rank bin `b`.
    #[inline]
    pub fn z(&self, b: u16) -> f32 {
        self.z[b as usize]
    }

    /// The Gaussian value of `v` (one of the values the map was built from).
    #[inline]
    pub fn map(&self, v: f32) -> f32 {
        self.z(self.bin(v))
    }

    /// The map and the `knots + 1` inverse-CDF knots from the bin counts of a channel with
    /// `stats` (binned with [`RankMap::binning`]).
    pub fn from_counts(count: &[u32], stats: &ChannelStats, knots: usize) -> (RankMap, Vec<f32>) {
        let n = stats.n;
        assert!(n > 0 && knots >= 1 && count.len() == RANK_BINS);
        let (lo, scale) = Self::binning(stats);
        if scale == 0.0 {
            let flat = RankMap {
                lo,
                scale,
                z: vec![0.0; RANK_BINS],
            };
            return (flat, vec![lo; knots + 1]);
        }
        // Mid-rank of each bin → Gaussian value; cumulative counts for the quantiles.
        let mut z = vec![0.0f32; RANK_BINS];
        let mut below = vec![0u64; RANK_BINS];
        let mut cum = 0u64;
        for b in 0..RANK_BINS {
            below[b] = cum;
            let c = count[b] as u64;
            if c > 0 {
                // Ranks cum..cum+c−1 share the mid-rank; probability at its centre.
                let p = (2 * cum + c) as f64 / (2 * n) as f64;
                z[b] = (stats.sigma * phi_inv(p)) as f32;
            }
            cum += c;
        }
        // Quantile at probability p: the value of (fractional) order statistic p·(n−1),
        // spreading each bin's members evenly across the bin.
        let width = 1.0 / scale as f64;
        let (lo64, hi64) = (lo as f64, stats.hi as f64);
        let quantile = |p: f64| -> f32 {
            let pos = p * (n - 1) as f64;
            let b = below
                .partition_point(|&c| (c as f64) <= pos)
                .saturating_sub(1);
            let c = count[b].max(1) as f64;
            let frac = ((pos - below[b] as f64 + 0.5) / c).clamp(0.0, 1.0);
            (lo64 + (b as f64 + frac) * width).clamp(lo64, hi64) as f32
        };
        let knot_values = (0..=knots)
            .map(|j| quantile(knot_probability(j, knots)))
            .collect();
        (RankMap { lo, scale, z }, knot_values)
    }
}

/// The rank map of `values` (with their `stats`) and the `knots + 1` inverse-CDF knots.
pub fn rank_map(values: &[f32], stats: &ChannelStats, knots: usize) -> (RankMap, Vec<f32>) {
    let binning = RankMap::binning(stats);
    let mut count = vec![0u32; RANK_BINS];
    for &v in values {
        count[RankMap::bin_of(v, binning) as usize] += 1;
    }
    RankMap::from_counts(&count, stats, knots)
}

/// Gaussianizes `values` by rank and samples the inverse CDF at `knots + 1` probabilities
/// ([`rank_map`] applied to the values).
pub fn gaussianize(values: &[f32], knots: usize) -> Gaussianized {
    let stats = channel_stats(values);
    let (map, knot_values) = rank_map(values, &stats, knots);
    Gaussianized {
        values: values.iter().map(|&v| map.map(v)).collect(),
        knots: knot_values,
        sigma: stats.sigma,
    }
}

/// Knots of the Gaussian with the mean and standard deviation of the distribution that `knots`
/// give a unit Gaussian input (evaluated the way the renderer evaluates them, clamped at
/// ±[`KNOT_Z`]): knot `j` at `mean + sd·z_j`, `z_j` its Gaussian coordinate. Same length.
pub fn gaussian_knots(knots: &[f32]) -> Vec<f32> {
    let k = knots.len().saturating_sub(1);
    if k == 0 {
        return knots.to_vec();
    }
    let tangents = fc_tangents(knots);
    // Quadrature over the unit Gaussian, in steps of 1/64 out to ±6.
    let (mut w_sum, mut m1, mut m2) = (0.0f64, 0.0f64, 0.0f64);
    for i in -384..=384 {
        let z = i as f64 / 64.0;
        let w = (-0.5 * z * z).exp();
        let v = spline_eval(knots, &tangents, knot_coordinate(z as f32, 1.0)) as f64;
        w_sum += w;
        m1 += w * v;
        m2 += w * v * v;
    }
    let mean = m1 / w_sum;
    let sd = (m2 / w_sum - mean * mean).max(0.0).sqrt();
    (0..=k)
        .map(|j| {
            let z = -KNOT_Z as f64 + 2.0 * KNOT_Z as f64 * j as f64 / k as f64;
            (mean + sd * z) as f32
        })
        .collect()
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
    hermite(
        s - i as f32,
        1.0 / k as f32,
        knots[i],
        tangents[i],
        knots[i + 1],
        tangents[i + 1],
    )
}

/// The cubic Hermite segment from `(y0, slope m0)` to `(y1, slope m1)` over width `h`, at
/// `t ∈ [0, 1]`.
#[inline]
pub fn hermite(t: f32, h: f32, y0: f32, m0: f32, y1: f32, m1: f32) -> f32 {
    let t2 = t * t;
    let t3 = t2 * t;
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + t;
    let h01 = -2.0 * t3 + 3.0 * t2;
    let h11 = t3 - t2;
    h00 * y0 + h10 * h * m0 + h01 * y1 + h11 * h * m1
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
        let mut sorted = vals.clone();
        sorted.sort_unstable_by(f32::total_cmp);
        let knots: Vec<f32> = if uniform {
            (0..=k).map(|j| sorted[((n - 1) * j) / k]).collect()
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
    fn quantiles_match_sorted_order_statistics() {
        let v: Vec<f32> = (0..10_007)
            .map(|i| ((i * 7919 % 10_007) as f32 / 10_007.0).powi(3))
            .collect();
        let g = gaussianize(&v, 10);
        let mut sorted = v.clone();
        sorted.sort_unstable_by(f32::total_cmp);
        for (j, &k) in g.knots.iter().enumerate() {
            let pos = knot_probability(j, 10) * (v.len() - 1) as f64;
            let exact = sorted[pos.round() as usize];
            assert!((k - exact).abs() < 4e-4, "knot {j}: {k} vs {exact}");
        }
        // Gaussianized values are monotone in the input.
        let mut idx: Vec<usize> = (0..v.len()).collect();
        idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
        for w in idx.windows(2) {
            assert!(g.values[w[0]] <= g.values[w[1]]);
        }
    }

    #[test]
    fn flat_channel() {
        let g = gaussianize(&[0.25; 100], 10);
        assert!(g.values.iter().all(|&v| v == 0.0));
        assert!(g.knots.iter().all(|&k| k == 0.25));
        assert_eq!(g.sigma, 0.0);
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

    #[test]
    fn spline_sd_is_the_spread_of_a_linear_curve_and_grows_with_its_tails() {
        let linear: Vec<f32> = (0..=10).map(|j| 0.1 * (-2.5 + 0.5 * j as f32)).collect();
        let sd = spline_sd(&linear);
        assert!((sd - 0.1).abs() < 0.002, "{sd}");
        let heavy: Vec<f32> = linear.iter().map(|&v| v + 40.0 * v * v * v).collect();
        assert!(spline_sd(&heavy) > 1.2 * sd);
        assert_eq!(spline_sd(&[0.3; 11]), 0.0);
    }

    #[test]
    fn gaussian_knots_keep_the_mean_and_spread_not_the_tails() {
        let z = |j: usize| -KNOT_Z + 2.0 * KNOT_Z * j as f32 / 10.0;
        // Knots of a Gaussian (sd 0.2 around 0.1) come back as they were, but for the few
        // per cent of variance that the clamp at ±KNOT_Z removes.
        let linear: Vec<f32> = (0..=10).map(|j| 0.1 + 0.2 * z(j)).collect();
        for (a, b) in gaussian_knots(&linear).iter().zip(&linear) {
            assert!((a - b).abs() < 0.02 * b.abs().max(0.2), "{a} vs {b}");
        }
        // Heavy tails (a narrow centre, far ends): the Gaussian of the same spread has ends
        // nearer the centre and a wider centre.
        let heavy = [
            -0.6, -0.5, -0.3, -0.09, -0.03, 0.0, 0.03, 0.1, 0.3, 0.4, 0.45,
        ];
        let g = gaussian_knots(&heavy);
        assert!(g[0] > heavy[0] && g[10] < heavy[10]);
        assert!(g[6] - g[4] > heavy[6] - heavy[4]);
        assert!(g.windows(2).all(|w| w[1] > w[0]));
        assert_eq!(gaussian_knots(&[0.5]), vec![0.5]);
    }
}
