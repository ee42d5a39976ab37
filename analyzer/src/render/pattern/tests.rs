//! Tests of the structured models' per-pixel functions ([`super`]).

use super::*;
use crate::pattern::{Pattern, PatternKind};

/// [`NOISE_GRADIENT`] is the 2D tile's own: the mean gradient magnitude of the pattern noise
/// by central differences at random points over four seeds, within 3 %. The solid tile's
/// gradient along a slice's plane is about a tenth smaller (its crests are bounded a tenth
/// wider than a pixel).
#[test]
fn the_noise_gradient_is_the_tiles() {
    use crate::noise::{noise2_first, noise3_first};
    let points = 5_000u32;
    let d = 1e-2f32;
    let (mut g2, mut g3) = (0.0f64, 0.0f64);
    for seed in 1..=4u32 {
        let (t2, t3) = (Tile::new_2d(seed), Tile::new_3d(seed));
        let at = |k: u32, i: u32| 64.0 * rng::uniform(seed, k, i) as f32;
        for i in 0..points {
            let p = [at(0, i), at(1, i), at(2, i)];
            let n2 = |x: f32, y: f32| noise2_first(&t2.data, t2.n, [x, y]);
            let gx = (n2(p[0] + d, p[1]) - n2(p[0] - d, p[1])) / (2.0 * d);
            let gy = (n2(p[0], p[1] + d) - n2(p[0], p[1] - d)) / (2.0 * d);
            g2 += (gx * gx + gy * gy).sqrt() as f64;
            let n3 = |x: f32, y: f32| noise3_first(&t3.data, t3.n, [x, y, p[2]]);
            let gx = (n3(p[0] + d, p[1]) - n3(p[0] - d, p[1])) / (2.0 * d);
            let gy = (n3(p[0], p[1] + d) - n3(p[0], p[1] - d)) / (2.0 * d);
            g3 += (gx * gx + gy * gy).sqrt() as f64;
        }
    }
    let (g2, g3) = (g2 / (4 * points) as f64, g3 / (4 * points) as f64);
    eprintln!("mean noise gradient: 2D {g2:.3}, solid along a slice {g3:.3}");
    assert!((g2 / NOISE_GRADIENT as f64 - 1.0).abs() < 0.03, "{g2}");
    assert!((0.8..1.0).contains(&(g3 / NOISE_GRADIENT as f64)), "{g3}");
}

/// A crest finer than the pixel is drawn at least a pixel wide and averaged over it; one
/// much wider than the pixel keeps its profile.
#[test]
fn crests_are_drawn_at_least_a_pixel_wide() {
    // Zoomed in (a pixel a thousandth of a noise coefficient or less): the point value.
    for n in [-0.3f32, 0.0, 0.05, 0.4] {
        let exact = (-6.0 * n.abs()).exp();
        assert!((crest(n, 6.0, -16.0) - exact).abs() < 1e-5, "{n}");
        assert!((crest(n, 6.0, -10.0) - exact).abs() < 1e-2, "{n}");
    }
    // A pixel of one noise coefficient (the noise changes by 2.2 across it): the crest's
    // sharpness is bounded to 2 / 2.2 and its mean over the pixel is below its peak,
    // falling off smoothly; without the bound a sharpness of 12 would make it a spike.
    let c = |n: f32| crest(n, 12.0, 0.0);
    assert!(c(0.0) < 1.0 && c(0.0) > 0.5, "{}", c(0.0));
    assert!(c(0.5) > 0.4 * c(0.0), "{} {}", c(0.5), c(0.0));
    assert!(c(0.0) > c(0.3) && c(0.3) > c(0.6) && c(0.6) > c(1.2));
    assert_eq!(c(0.4), c(-0.4));
    // Whatever the footprint, a crest stays within [0, 1].
    for lfp in [-8.0f32, -3.0, -1.0, 0.0, 2.0, 6.0] {
        for n in [-2.0f32, -0.1, 0.0, 0.1, 2.0] {
            let v = crest(n, 9.0, lfp);
            assert!((0.0..=1.0).contains(&v), "{lfp} {n} {v}");
        }
    }
}

/// A line finer than the pixel is drawn at least a pixel wide and averaged over it; one
/// much wider than the pixel keeps its profile.
#[test]
fn lines_are_drawn_at_least_a_pixel_wide() {
    let exact = |v: f32, s: f32| (0.5 + 0.5 * (std::f32::consts::TAU * v).sin()).powf(s);
    // Zoomed in: the point value.
    for v in [0.0f32, 0.2, 0.25, 0.6] {
        assert!(
            (line_profile(v, 6.0, 1e-5) - exact(v, 6.0)).abs() < 1e-5,
            "{v}"
        );
        assert!(
            (line_profile(v, 6.0, 1e-3) - exact(v, 6.0)).abs() < 1e-3,
            "{v}"
        );
    }
    // Half a line spacing across the pixel: the sharpness is bounded (at 8 a line is under
    // half a pixel wide at 1/e), the peak's mean over the pixel is below 1, and the profile
    // falls off symmetrically about the peak (v = ¼).
    let l = |v: f32| line_profile(v, 8.0, 0.5);
    assert!(l(0.25) < 0.9 && l(0.25) > 0.5, "{}", l(0.25));
    assert!(l(0.25) > l(0.35) && l(0.35) > l(0.45) && l(0.45) > l(0.75));
    assert!((l(0.4) - l(0.1)).abs() < 1e-5, "{} {}", l(0.4), l(0.1));
    assert!(l(0.4) > 0.3 * l(0.25), "{} {}", l(0.4), l(0.25));
    // Whatever the change across the pixel, the profile stays within [0, 1].
    for g in [0.0f32, 1e-3, 0.1, 0.5, 1.0, 7.0] {
        for v in [-1.3f32, 0.0, 0.25, 0.5, 0.75, 3.1] {
            let x = line_profile(v, 8.0, g);
            assert!((0.0..=1.0).contains(&x), "{g} {v} {x}");
        }
    }
}

/// Sharp, crowded wood lines (sharpness 8, distortion 1.5, five pixels apart): averaged over
/// the pixel where the lines are, the pattern has a small fraction of the isolated pixels
/// that sampling the profile at each pixel's centre draws (its dotted lines).
#[test]
fn sharp_wood_lines_are_not_dotted() {
    use crate::input::Photo;
    use crate::specks::speck_fraction;
    let tile = Tile::new_2d(1);
    let mut p = Pattern::new(PatternKind::WoodLines, 5.0);
    for (k, v) in [
        ("sharpness", 8.0),
        ("distortion", 1.5),
        ("roughness", 0.9),
        ("stretch", 4.0),
    ] {
        assert!(p.set(k, v), "{k}");
    }
    let prep = Prepared::new(&crate::params::pattern_shell(p, 1, false));
    let (w, h) = (128u32, 128u32);
    let grey = |v: Vec<f32>| Photo {
        width: w,
        height: h,
        pixels: v.into_iter().map(|x| [x, x, x]).collect(),
    };
    let drawn = grey(structure_image_prepared(&prep, &tile, w, h));
    let [is, c, s, log2_is] = prep.pattern_transform;
    let sampled = grey(
        (0..w * h)
            .map(|i| {
                let u = [(i % w) as f32 + 0.5, (i / w) as f32 + 0.5];
                let q = [(c * u[0] + s * u[1]) * is, (-s * u[0] + c * u[1]) * is, 0.0];
                let v = wood_line_coordinate(&prep, &tile, q, log2_is, [0.0, 0.0]);
                line_profile(v, 8.0, 0.0)
            })
            .collect(),
    );
    let (drawn, sampled) = (speck_fraction(&drawn), speck_fraction(&sampled));
    eprintln!("speck fraction: averaged {drawn:.4}, point-sampled {sampled:.4}");
    assert!(sampled > 0.01, "{sampled}");
    assert!(drawn < 0.25 * sampled, "{drawn} {sampled}");
}

#[test]
fn rings_turn_about_their_centre() {
    // Without distortion and ellipticity the rings' value depends only on the distance
    // to their centre, at texel `scale · (centre_x, centre_y)` whatever the rotation.
    let tile = Tile::new_2d(1);
    for rotation in [0.0, 30.0, 90.0, 135.0] {
        let mut p = Pattern::new(PatternKind::Rings, 10.0);
        p.rotation_deg = rotation;
        assert!(p.set("distortion", 0.0) && p.set("centre_x", 3.0) && p.set("centre_y", 5.0));
        let prep = Prepared::new(&crate::params::pattern_shell(p, 1, false));
        let at = |phi: f32| {
            let u = [30.0 + 12.3 * phi.cos(), 50.0 + 12.3 * phi.sin(), 0.0];
            pattern(&prep, &tile, u, 0.0)
        };
        let v0 = at(0.0);
        for phi in [0.7, 1.9, 3.1, 4.4, 5.6] {
            assert!((at(phi) - v0).abs() < 1e-3, "{rotation}°, {phi}");
        }
    }
}

#[test]
fn staggered_cells_at_jitter_0_lie_on_a_shifted_lattice() {
    // Cells at jitter 0 are centred on the unit lattice; `stagger` 1 moves every other row
    // by half a cell, so a point that is a centre without it falls on a joint, and `warp`
    // bends the lattice (the same point moves off its centre).
    let tile = Tile::new_2d(1);
    let at = |values: &[(&str, f32)], u: [f32; 2]| {
        let mut p = Pattern::new(PatternKind::Cells, 10.0);
        for &(k, v) in values {
            assert!(p.set(k, v), "{k}");
        }
        assert!(p.set("variation", 0.0) && p.set("bevel", 0.05));
        let prep = Prepared::new(&crate::params::pattern_shell(p, 1, false));
        pattern(&prep, &tile, [10.0 * u[0], 10.0 * u[1], 0.0], -6.0)
    };
    let square = [("jitter", 0.0)];
    let hex = [("jitter", 0.0), ("stagger", 1.0)];
    // Even rows (0, 2) keep their centres; odd rows (1, −1) move by half a cell.
    for (u, centre_square, centre_hex) in [
        ([0.5, 0.5], true, true),
        ([3.5, 2.5], true, true),
        ([0.5, 1.5], true, false),
        ([1.0, 1.5], false, true),
        ([2.0, -0.5], false, true),
    ] {
        for (values, centre) in [(&square[..], centre_square), (&hex[..], centre_hex)] {
            let v = at(values, u);
            if centre {
                assert!(v > 0.99, "{values:?} at {u:?}: {v} (a cell's centre)");
            } else {
                assert!(v < 0.01, "{values:?} at {u:?}: {v} (a joint)");
            }
        }
    }
    let warped = [("jitter", 0.0), ("stagger", 1.0), ("warp", 1.0)];
    // The staggered lattice's centres over 12 × 12 cells (odd rows shifted by half a cell).
    let centres: Vec<[f32; 2]> = (0..12)
        .flat_map(|row| {
            (0..12).map(move |col| [col as f32 + 0.5 + 0.5 * (row % 2) as f32, row as f32 + 0.5])
        })
        .collect();
    assert!(centres.iter().all(|&u| at(&hex, u) > 0.99));
    // A warp of 1 moves a good part of them off their flat tops: 47 of 144 with the wavelet
    // tile of seed 1, 30 with the spectral one (neighbouring cells share the warp, so a
    // dozen or two independent displacements decide it); a tenth is the bound.
    let moved = centres.iter().filter(|&&u| at(&warped, u) < 0.9).count();
    assert!(
        moved * 10 >= centres.len(),
        "warp 1 moved {moved} of {} centres off their cells' centres",
        centres.len()
    );
}

#[test]
fn plank_rows_cover_the_line_with_irregular_widths() {
    let prep = Prepared::new(&crate::params::pattern_shell(
        Pattern::new(PatternKind::Planks, 10.0),
        3,
        false,
    ));
    // Without irregularity the rows are the integers' intervals.
    for y in [-2.5f32, -0.01, 0.0, 0.3, 7.99] {
        assert_eq!(
            plank_row(&prep, y, 0.0, 0),
            [y.floor(), y.floor(), y.floor() + 1.0]
        );
    }
    // With it, every y lies in its row, between its two edges; returns the rows' widths'
    // least and greatest.
    let spread = |widths: f32| {
        let mut seen = Vec::new();
        for i in -400..400 {
            let y = i as f32 * 0.0437;
            let [row, lo, hi] = plank_row(&prep, y, widths, 0);
            assert!(lo <= y && y < hi, "{y}: row {row} [{lo}, {hi})");
            assert_eq!(lo, plank_edge(&prep, row as i32, widths, 0));
            assert_eq!(hi, plank_edge(&prep, row as i32 + 1, widths, 0));
            seen.push(hi - lo);
        }
        seen.iter()
            .fold((f32::MAX, f32::MIN), |(a, b), &w| (a.min(w), b.max(w)))
    };
    // 0.5 (the searched range's end): widths ½–1½, some rows differ clearly.
    let (min, max) = spread(0.5);
    assert!(
        0.5 <= min && max <= 1.5 && max - min > 0.4,
        "widths {min}–{max}"
    );
    // 1 (the range's end): edges move up to ½ either way, rows 0–2 wide, never crossing.
    let (min, max) = spread(1.0);
    assert!(
        0.0 <= min && max <= 2.0 && max - min > 1.0,
        "widths {min}–{max}"
    );
    // Wrapped at 6 rows, the edges repeat every 6.
    for k in -7..7 {
        let (a, b) = (
            plank_edge(&prep, k, 0.5, 6),
            plank_edge(&prep, k + 6, 0.5, 6),
        );
        assert!((b - a - 6.0).abs() < 1e-5, "{k}: {a} {b}");
    }
}

#[test]
fn soft_step_is_a_clamped_smooth_step() {
    assert_eq!(soft_step(0.1, 0.2, 0.0), 0.0);
    assert_eq!(soft_step(0.1, 0.2, 0.3), 1.0);
    assert!((soft_step(0.1, 0.2, 0.2) - 0.5).abs() < 1e-6);
}
