//! Tests of the structured models' per-pixel functions ([`super`]).

use super::*;
use crate::pattern::{Pattern, PatternKind};

/// A crest finer than the pixel is drawn at least a pixel wide and averaged over it; one
/// much wider than the pixel keeps its profile.
#[test]
fn crests_are_drawn_at_least_a_pixel_wide() {
    // Zoomed in (the noise changing by a ten-thousandth or a thousandth across the pixel):
    // the point value.
    for n in [-0.3f32, 0.0, 0.05, 0.4] {
        let exact = (-6.0 * n.abs()).exp();
        assert!((crest(n, 6.0, 3e-5) - exact).abs() < 1e-5, "{n}");
        assert!((crest(n, 6.0, 2e-3) - exact).abs() < 1e-2, "{n}");
    }
    // The noise changing by 2.2 across the pixel (a pixel of about one noise coefficient):
    // the crest's sharpness is bounded to 2 / 2.2 and its mean over the pixel is below its
    // peak, falling off smoothly; without the bound a sharpness of 12 would make it a spike.
    let c = |n: f32| crest(n, 12.0, 2.2);
    assert!(c(0.0) < 1.0 && c(0.0) > 0.5, "{}", c(0.0));
    assert!(c(0.5) > 0.4 * c(0.0), "{} {}", c(0.5), c(0.0));
    assert!(c(0.0) > c(0.3) && c(0.3) > c(0.6) && c(0.6) > c(1.2));
    assert_eq!(c(0.4), c(-0.4));
    // Whatever the change across the pixel (0 included), a crest stays within [0, 1].
    for g in [0.0f32, 1e-4, 0.01, 0.3, 1.0, 2.2, 9.0, 140.0] {
        for n in [-2.0f32, -0.1, 0.0, 0.1, 2.0] {
            let v = crest(n, 9.0, g);
            assert!((0.0..=1.0).contains(&v), "{g} {n} {v}");
        }
    }
}

/// Sharp, rough ridged crests (sharpness 10, roughness 0.9, 12 pixels a cell): drawn over the
/// noise's change where each pixel is, the pattern has a small fraction of the isolated pixels
/// that sampling each crest at the pixel's centre draws, and fewer than drawing it over the
/// octaves' mean change (2.2 per noise coefficient) leaves where the noise crosses 0 steeply.
#[test]
fn sharp_ridged_crests_are_not_dotted() {
    use crate::specks::speck_fraction;
    let tile = Tile::new_2d(1);
    let values = [("sharpness", 10.0), ("roughness", 0.9), ("stretch", 1.0)];
    let prep = prepared_with(PatternKind::Ridged, 12.0, &values);
    let (w, h) = (128u32, 128u32);
    let grey = |v: Vec<f32>| grey_image(w, h, v);
    let drawn = grey(structure_image_prepared(&prep, &tile, w, h));
    let [is, c, s, lfp] = prep.pattern_transform;
    // The same octaves with each crest's change across the pixel given by `change`.
    let with = |change: &dyn Fn(f32, f32, f32, usize) -> f32| {
        grey(
            (0..w * h)
                .map(|i| {
                    let u = [(i % w) as f32 + 0.5, (i / w) as f32 + 0.5];
                    let q = [(c * u[0] + s * u[1]) * is, (-s * u[0] + c * u[1]) * is, 0.0];
                    let (mut sum, mut norm, mut amp) = (0.0, 0.0, 1.0);
                    for k in 0..OCTAVES {
                        let fade = band_fade(0, lfp + k as f32);
                        if fade > 0.0 {
                            let at = |q: [f32; 3]| octave(&prep, &tile, q, k, [0.0, 0.0]);
                            let n = at(q);
                            let nx = at([q[0] + is, q[1], q[2]]);
                            let ny = at([q[0], q[1] + is, q[2]]);
                            sum += amp * fade * crest(n, 10.0, change(n, nx, ny, k));
                        }
                        norm += amp;
                        amp *= 0.9;
                    }
                    sum / norm
                })
                .collect(),
        )
    };
    let here = with(&|n, nx, ny, _| pixel_change(n, nx, ny));
    let mean = with(&|_, _, _, k| 2.2 * (lfp + k as f32).exp2());
    let sampled = with(&|_, _, _, _| 0.0);
    assert_eq!(
        here.pixels, drawn.pixels,
        "the pattern draws the local change"
    );
    let (drawn, mean, sampled) = (
        speck_fraction(&drawn),
        speck_fraction(&mean),
        speck_fraction(&sampled),
    );
    eprintln!(
        "speck fraction: over the change here {drawn:.4}, the mean change {mean:.4}, \
         point-sampled {sampled:.4}"
    );
    assert!(sampled > 0.01, "{sampled}");
    assert!(drawn < 0.25 * sampled, "{drawn} {sampled}");
    assert!(drawn < mean, "{drawn} {mean}");
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
    use crate::specks::speck_fraction;
    let tile = Tile::new_2d(1);
    let values = [
        ("sharpness", 8.0),
        ("distortion", 1.5),
        ("roughness", 0.9),
        ("stretch", 4.0),
    ];
    let prep = prepared_with(PatternKind::WoodLines, 5.0, &values);
    let (w, h) = (128u32, 128u32);
    let grey = |v: Vec<f32>| grey_image(w, h, v);
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

/// A pattern of `kind` at `scale` with the given values, prepared for rendering.
fn prepared_with(kind: PatternKind, scale: f32, values: &[(&str, f32)]) -> Prepared {
    let mut p = Pattern::new(kind, scale);
    for &(k, v) in values {
        assert!(p.set(k, v), "{k}");
    }
    Prepared::new(&crate::params::pattern_shell(p, 1, false))
}

/// A grey `w`×`h` image of the values `v`, row by row.
fn grey_image(w: u32, h: u32, v: Vec<f32>) -> crate::input::Photo {
    crate::input::Photo {
        width: w,
        height: h,
        pixels: v.into_iter().map(|x| [x, x, x]).collect(),
    }
}
