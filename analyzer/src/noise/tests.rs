//! Tests of the wavelet-noise tile and its evaluation.

use super::*;

#[test]
fn atlas_texel_and_voxel_are_inverse() {
    for size in [[32, 64], [64, 32], [64, 64]] {
        let depth = 64;
        let (w, h) = (size[0] * ATLAS_COLUMNS, size[1] * depth / ATLAS_COLUMNS);
        let mut seen = vec![false; w * h];
        for z in 0..depth {
            for y in 0..size[1] {
                for x in 0..size[0] {
                    let t = atlas_texel([x, y, z], size);
                    assert!(t[0] < w && t[1] < h);
                    assert!(!seen[t[0] + w * t[1]], "two voxels on one texel");
                    seen[t[0] + w * t[1]] = true;
                    assert_eq!(atlas_voxel(t, size), [x, y, z]);
                }
            }
        }
    }
}

#[test]
fn filters_are_as_documented() {
    // The analysis filter has unit DC gain and is symmetric about −1/2; the refinement
    // filter has gain 2 (it interpolates to twice the samples).
    let sum: f64 = (-16..16).map(a_coeff).sum();
    assert!((sum - 1.0).abs() < 1e-5, "{sum}");
    assert_eq!(P_COEFFS.iter().sum::<f64>(), 2.0);
    for j in 0..16 {
        assert_eq!(a_coeff(j), a_coeff(-1 - j));
    }
}

#[test]
fn tile_is_normalised_and_deterministic() {
    let t = Tile::new_2d(3);
    assert_eq!(t.data.len(), COMPONENTS * TILE_2D * TILE_2D);
    assert_eq!(t, Tile::new_2d(3));
    assert_ne!(t.data, Tile::new_2d(4).data);
    for k in 0..COMPONENTS {
        let c: Vec<f64> = t.plane(k).iter().map(|&v| v as f64).collect();
        let var = evaluated_variance(&c, TILE_2D, 2);
        assert!((var - 1.0).abs() < 1e-5, "{var}");
        assert!(t.stats[k].raw_variance > 0.1 && t.stats[k].raw_variance < 1.0);
    }
    // The components are independent fields: their coefficients are uncorrelated.
    for (a, b) in [(0, 1), (0, 2), (1, 2)] {
        let r: f64 = t
            .plane(a)
            .iter()
            .zip(t.plane(b))
            .map(|(x, y)| *x as f64 * *y as f64)
            .sum::<f64>()
            / (TILE_2D * TILE_2D) as f64;
        assert!(r.abs() < 0.05 * 5.58, "components {a}, {b}: {r}");
    }
}

#[test]
fn sampled_variance_matches_exact_formula() {
    let t = Tile::new_2d(9);
    let n = TILE_2D;
    let steps = 4;
    let (mut s1, mut s2, mut count) = (0.0f64, 0.0f64, 0.0f64);
    for y in 0..n * steps {
        for x in 0..n * steps {
            let p = [
                (x as f32 + 0.37) / steps as f32,
                (y as f32 + 0.61) / steps as f32,
            ];
            let v = noise2(&t.data, n, p)[1] as f64;
            s1 += v;
            s2 += v * v;
            count += 1.0;
        }
    }
    let mean = s1 / count;
    let var = s2 / count - mean * mean;
    assert!(mean.abs() < 1e-3, "{mean}");
    assert!((var - 1.0).abs() < 0.01, "{var}");
}

#[test]
fn bspline_weights_partition_unity_and_c1() {
    for i in 0..1000 {
        let p = i as f32 * 0.013;
        let (_, w) = bspline_weights(p);
        assert!((w.iter().sum::<f32>() - 1.0).abs() < 1e-6);
        assert!(w.iter().all(|&v| v >= 0.0));
    }
    // C¹ continuity of the noise across coefficient boundaries (at half-integers, where the
    // middle index changes): value and one-sided slopes agree.
    let t = Tile::new_2d(1);
    for k in 0..20 {
        let x = k as f32 + 0.5;
        let e = 1e-3f32;
        let y = 7.3;
        let l = noise2_first(&t.data, TILE_2D, [x - e, y]);
        let c = noise2_first(&t.data, TILE_2D, [x, y]);
        let r = noise2_first(&t.data, TILE_2D, [x + e, y]);
        assert!((l - c).abs() < 0.05 && (r - c).abs() < 0.05);
        let l2 = noise2_first(&t.data, TILE_2D, [x - 2.0 * e, y]);
        let r2 = noise2_first(&t.data, TILE_2D, [x + 2.0 * e, y]);
        let slope_l = (l - l2) / e;
        let slope_r = (r2 - r) / e;
        assert!(
            (slope_l - slope_r).abs() < 0.05 * (1.0 + slope_l.abs()),
            "{slope_l} {slope_r}"
        );
    }
}

#[test]
fn noise_is_periodic() {
    let t = Tile::new_2d(2);
    let n = TILE_2D as f32;
    for i in 0..50 {
        // Dyadic steps, so that `p ± n` is exact in f32 and only the period is tested.
        let p = [i as f32 * 1.375, i as f32 * 0.6875];
        let a = noise2(&t.data, TILE_2D, p);
        let b = noise2(&t.data, TILE_2D, [p[0] + n, p[1] - n]);
        for k in 0..COMPONENTS {
            assert!((a[k] - b[k]).abs() < 1e-4);
        }
        assert_eq!(a[0], noise2_first(&t.data, TILE_2D, p));
    }
    let t3 = Tile::new_3d(2);
    let n3 = TILE_3D as f32;
    for i in 0..50 {
        let p = [i as f32 * 1.37, i as f32 * 0.71, i as f32 * 0.3];
        let a = noise3(&t3.data, TILE_3D, p);
        let b = noise3(&t3.data, TILE_3D, [p[0] + n3, p[1], p[2] - n3]);
        for k in 0..COMPONENTS {
            assert!((a[k] - b[k]).abs() < 1e-4);
        }
        assert_eq!(a[0], noise3_first(&t3.data, TILE_3D, p));
    }
}

/// The mean product of coefficients `lag` apart (periodic), over one tile.
fn autocorrelation(t: &Tile, k: usize, lag: [usize; 3]) -> f64 {
    let n = t.n;
    let depth = if t.dims == 3 { n } else { 1 };
    let mut s = 0.0f64;
    for z in 0..depth {
        for y in 0..n {
            for x in 0..n {
                let a = x + n * (y + n * z);
                let (bx, by) = ((x + lag[0]) % n, (y + lag[1]) % n);
                let bz = if t.dims == 3 { (z + lag[2]) % n } else { 0 };
                let plane = t.plane(k);
                s += plane[a] as f64 * plane[bx + n * (by + n * bz)] as f64;
            }
        }
    }
    s / t.plane(k).len() as f64
}

#[test]
fn tile_lags_match_the_constants() {
    // Expected over seeds and components; one tile's own lags scatter about them by ~1 %. The
    // 2D lags are averaged over both axes and both diagonals, as the phase variance uses them
    // (one value per kind of lag): a tile's lags along x and y, or along the two diagonals,
    // differ by its scatter (−0.754 and −0.700 on the diagonals over these 18 components), and
    // the phase variance's mean is 1 only with their average.
    let seeds = 0..6u32;
    let count = (seeds.len() * COMPONENTS) as f64;
    let mut two = [0.0f64; 3];
    let mut three = [0.0f64; 4];
    let mut two_far = 0.0f64;
    for seed in seeds {
        let t = Tile::new_2d(seed);
        let t3 = Tile::new_3d(seed);
        for c in 0..COMPONENTS {
            let n = t.n;
            let pairs = [
                [[0, 0, 0], [0, 0, 0]],
                [[1, 0, 0], [0, 1, 0]],
                [[1, 1, 0], [1, n - 1, 0]],
            ];
            for (k, [a, b]) in pairs.iter().enumerate() {
                two[k] += 0.5 * (autocorrelation(&t, c, *a) + autocorrelation(&t, c, *b)) / count;
            }
            two_far += (autocorrelation(&t, c, [2, 0, 0]) + autocorrelation(&t, c, [0, 2, 0]))
                / (2.0 * count);
            for (k, lag) in [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1]]
                .iter()
                .enumerate()
            {
                three[k] += autocorrelation(&t3, c, *lag) / count;
            }
        }
    }
    for (m, c) in two.iter().zip(TILE2_LAGS) {
        assert!(
            (m - c as f64).abs() < 0.02 * TILE2_LAGS[0] as f64,
            "2D {two:?}"
        );
    }
    for (m, c) in three.iter().zip(TILE3_LAGS) {
        assert!(
            (m - c as f64).abs() < 0.02 * TILE3_LAGS[0] as f64,
            "3D {three:?}"
        );
    }
    // Lags of 2 are left out of the phase variance. The 2D tile's mean is −0.077 (1.4 % of
    // R(0,0)); at a lag of 2 the B-spline weights' autocorrelation is at most 1/64 (phase ½,
    // where Σw² = 0.59), so |R(2)| < 0.1 moves a phase's variance by at most
    // 4 · 0.1 · (1/64) · 0.59 = 0.4 %.
    assert!(two_far.abs() < 0.1, "lag 2: {two_far}");
}

#[test]
fn phase_variance_averages_to_one() {
    // Over a uniform grid of phases the variance is the tile's normalisation, 1.
    let steps = 64;
    let ws: Vec<[f32; 3]> = (0..steps)
        .map(|i| bspline_weights((i as f32 + 0.5) / steps as f32).1)
        .collect();
    let mut two = 0.0f64;
    let mut three = 0.0f64;
    for wx in &ws {
        for wy in &ws {
            two += phase_variance2(*wx, *wy) as f64;
            for wz in ws.iter().step_by(8) {
                three += phase_variance3(*wx, *wy, *wz) as f64;
            }
        }
    }
    two /= (steps * steps) as f64;
    three /= (steps * steps * steps / 8) as f64;
    assert!((two - 1.0).abs() < 2e-3, "{two}");
    assert!((three - 1.0).abs() < 2e-3, "{three}");
    // Unnormalised, a band is 1.35 on the coefficients and 0.64 midway between them.
    // (Coefficient k sits at p = k; p = k + 1/2 is midway.)
    let on = bspline_weights(1.0).1;
    let mid = bspline_weights(0.5).1;
    assert!((phase_variance2(on, on) - 1.35).abs() < 0.02);
    assert!((phase_variance2(mid, mid) - 0.64).abs() < 0.02);
}

#[test]
fn every_phase_has_unit_variance() {
    // One band sampled at a fixed sub-texel phase over the whole tile, for several phases:
    // without the phase normalisation its deviation runs from 0.80 to 1.16.
    let t = Tile::new_2d(5);
    let n = TILE_2D;
    for (fx, fy) in [(0.5, 0.5), (0.0, 0.0), (0.25, 0.5), (0.0, 0.5), (0.8, 0.1)] {
        let mut s2 = 0.0f64;
        for y in 0..n {
            for x in 0..n {
                for v in noise2(&t.data, n, [x as f32 + fx, y as f32 + fy]) {
                    s2 += (v as f64).powi(2) / COMPONENTS as f64;
                }
            }
        }
        let sd = (s2 / (n * n) as f64).sqrt();
        assert!((sd - 1.0).abs() < 0.03, "phase ({fx}, {fy}): {sd}");
    }
}

#[test]
fn band_fade_ramps() {
    assert_eq!(band_fade(0, 0.0), 1.0);
    assert_eq!(band_fade(0, 1.0), 0.0);
    assert!((band_fade(0, 0.5) - 0.5).abs() < 1e-6);
    assert_eq!(band_fade(3, 2.0), 1.0);
    assert_eq!(band_fade(3, -5.0), 1.0);
}

#[test]
fn derivative_weights_are_the_slope_of_the_weights() {
    for p in [3.1f32, 3.7, 3.93, 10.0, 0.6] {
        let h = 1e-3;
        let (mid, w) = bspline_weights(p);
        let (mid2, w2) = bspline_weights(p + h);
        assert_eq!(mid, mid2);
        let d = oriented::bspline_derivative(p);
        for k in 0..3 {
            assert!(((w2[k] - w[k]) / h - d[k]).abs() < 2e-3, "p {p} k {k}");
        }
    }
}

#[test]
fn gradient_variance_matches_the_tile() {
    // The derivative along x of the B-spline surface, averaged over phases and the tile,
    // against the closed form from the tile's lags (2 % of it: the lags' own precision).
    let t = Tile::new_2d(7);
    let n = TILE_2D;
    let mut s2 = 0.0f64;
    let phases = [0.05f32, 0.3, 0.55, 0.8];
    for &fx in &phases {
        for &fy in &phases {
            for y in 0..n {
                for x in 0..n {
                    let (px, py) = (x as f32 + fx, y as f32 + fy);
                    let (mx, _) = bspline_weights(px);
                    let (my, wy) = bspline_weights(py);
                    let dwx = oriented::bspline_derivative(px);
                    let mut g = 0.0f32;
                    for dy in 0..3 {
                        for dx in 0..3 {
                            let i = wrap_index(my + dy as i32 - 1, n as i32) * n
                                + wrap_index(mx + dx as i32 - 1, n as i32);
                            g += wy[dy] * dwx[dx] * t.data[i];
                        }
                    }
                    s2 += (g as f64).powi(2);
                }
            }
        }
    }
    let measured = s2 / (n * n * phases.len() * phases.len()) as f64;
    let closed = oriented::gradient_variance2() as f64;
    assert!(
        (measured / closed - 1.0).abs() < 0.02,
        "{measured} vs {closed}"
    );
}

#[test]
fn oriented_bands_have_unit_variance_at_every_phase() {
    let t = Tile::new_2d(5);
    let n = TILE_2D;
    for (angle, strength) in [(0.0f32, 1.0f32), (30.0, 0.6), (135.0, 0.3)] {
        let m = oriented::mixing(angle, strength, oriented::gradient_variance2());
        for (fx, fy) in [(0.5, 0.5), (0.0, 0.0), (0.25, 0.5), (0.8, 0.1)] {
            let mut s2 = 0.0f64;
            for y in 0..n {
                for x in 0..n {
                    let p = [x as f32 + fx, y as f32 + fy];
                    for v in oriented::noise2_oriented(&t.data, n, p, m) {
                        s2 += (v as f64).powi(2) / COMPONENTS as f64;
                    }
                }
            }
            let sd = (s2 / (n * n) as f64).sqrt();
            assert!(
                (sd - 1.0).abs() < 0.03,
                "{angle}° {strength} phase ({fx}, {fy}): {sd}"
            );
        }
    }
}

#[test]
fn an_isotropic_mixture_is_the_plain_band() {
    // Strength 0 (α = 1, no derivative) reproduces the plain band within rounding, so the
    // shaders' isotropic branch and the oriented one agree there.
    let t = Tile::new_2d(3);
    let m = oriented::mixing(40.0, 0.0, oriented::gradient_variance2());
    for p in [[3.3f32, 7.9], [100.25, 0.5], [64.0, 12.7]] {
        let a = noise2(&t.data, TILE_2D, p);
        let b = oriented::noise2_oriented(&t.data, TILE_2D, p, m);
        for k in 0..COMPONENTS {
            assert!((a[k] - b[k]).abs() < 1e-5, "{p:?}: {a:?} {b:?}");
        }
    }
}

#[test]
fn periodic_oriented_band_repeats() {
    let t = Tile::new_2d(9);
    let m = oriented::mixing(70.0, 0.8, oriented::gradient_variance2());
    for p in [[1.3f32, 2.7], [20.5, 3.25]] {
        let a = oriented::noise2_periodic_oriented(&t.data, TILE_2D, p, [24.0, 24.0], m);
        let b = oriented::noise2_periodic_oriented(
            &t.data,
            TILE_2D,
            [p[0] + 24.0, p[1] + 48.0],
            [24.0, 24.0],
            m,
        );
        for k in 0..COMPONENTS {
            assert!((a[k] - b[k]).abs() < 1e-4, "{p:?}");
        }
    }
}

#[test]
fn spectral_expected_power_closed_form_matches_the_impulse_responses() {
    // The closed form a shader evaluates per bin against the exact sum over the construction's
    // four polyphase impulse responses.
    let n = 32;
    let exact = spectral::expected_power(n);
    let grid = spectral::expected_power_grid(n);
    for ky in 0..n {
        for kx in 0..n {
            let closed = spectral::expected_power_at(n, kx, ky);
            assert_eq!(closed, grid[kx + n * ky], "bin ({kx}, {ky})");
            let want = exact[kx + n * ky];
            assert!(
                (closed - want).abs() <= 1e-9 * (n * n) as f64 + 1e-9 * want,
                "bin ({kx}, {ky}): {closed} vs {want}"
            );
        }
    }
}
