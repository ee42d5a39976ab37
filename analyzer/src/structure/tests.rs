//! Tests of the structured fit (`structure`).

use super::*;
use crate::params::pattern_shell;
use crate::render::{View, render};

#[test]
fn the_fit_tries_rougher_and_more_irregular_patterns_within_the_range() {
    let rough = |kind, r: f32| {
        let mut p = Pattern::new(kind, 20.0);
        assert!(p.set("roughness", r));
        rougher_variants(&p)
            .iter()
            .map(|c| c.get("roughness").unwrap())
            .collect::<Vec<f32>>()
    };
    let near = |a: &[f32], b: &[f32]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5)
    };
    assert!(near(&rough(PatternKind::Ridged, 0.5), &[0.5, 0.56, 0.62]));
    // Ridged's roughness may reach 1 (its range), past the 0.9 its search stops at.
    assert!(near(&rough(PatternKind::Ridged, 0.87), &[0.87, 0.93, 0.99]));
    assert!(near(&rough(PatternKind::Ridged, 0.95), &[0.95, 1.0]));
    // Turbulence's stops at 0.9: then it is tried as it is.
    assert!(near(&rough(PatternKind::Turbulence, 0.9), &[0.9]));
    // Planks: more irregular widths, up to the range's end (1), past the searched 0.5.
    let widths = |w: f32| {
        let mut p = Pattern::new(PatternKind::Planks, 20.0);
        assert!(p.set("widths", w));
        rougher_variants(&p)
            .iter()
            .filter(|c| c.scale == p.scale)
            .map(|c| c.get("widths").unwrap())
            .collect::<Vec<f32>>()
    };
    assert!(near(&widths(0.2), &[0.2, 0.45, 0.7]));
    assert!(near(&widths(0.5), &[0.5, 0.75, 1.0]));
    assert!(near(&widths(0.9), &[0.9, 1.0]));
    // Lattices: the same a little finer and coarser (planks: then their widths raised).
    let scales = |kind| {
        rougher_variants(&Pattern::new(kind, 20.0))
            .iter()
            .map(|c| c.scale)
            .collect::<Vec<f32>>()
    };
    assert!(near(&scales(PatternKind::Cells), &[20.0, 18.0, 22.0]));
    assert!(near(&scales(PatternKind::Brick), &[20.0, 18.0, 22.0]));
    assert!(near(
        &scales(PatternKind::Planks),
        &[20.0, 18.0, 22.0, 20.0, 20.0]
    ));
    assert!(near(&scales(PatternKind::Rings), &[20.0, 20.0, 20.0]));
}

#[test]
fn tridiagonal_solver_solves() {
    let diag = [4.0, 5.0, 6.0];
    let off = [1.0, 2.0];
    let x = [[1.0, 2.0, 3.0], [-1.0, 0.5, 0.0], [2.0, 1.0, -3.0]];
    let rhs: Vec<[f64; 3]> = (0..3)
        .map(|i| {
            [0, 1, 2].map(|c| {
                diag[i] * x[i][c]
                    + if i > 0 { off[i - 1] * x[i - 1][c] } else { 0.0 }
                    + if i < 2 { off[i] * x[i + 1][c] } else { 0.0 }
            })
        })
        .collect();
    let got = solve_tridiagonal(&diag, &off, &rhs);
    for i in 0..3 {
        for c in 0..3 {
            assert!((got[i][c] - x[i][c]).abs() < 1e-12);
        }
    }
}

/// A rendered brick texture (two tones, no residual) fits back to its own tones: the
/// ramp's ends are the mortar and brick colours.
#[test]
fn fit_recovers_the_tones_of_a_two_tone_brick_wall() {
    let mut pat = Pattern::new(PatternKind::Brick, 16.0);
    pat.set_vector(&[2.0, 0.15, 0.5, 0.0, 0.02, 0.0]);
    let mut p = pattern_shell(pat.clone(), 3, false);
    let (mortar, brick) = ([0.8, 0.78, 0.7], [0.6, 0.25, 0.15]);
    if let Model::Structured(m) = &mut p.model {
        m.ramp = vec![
            RampStop {
                at: 0.0,
                rgb: mortar,
            },
            RampStop {
                at: 1.0,
                rgb: brick,
            },
        ];
    }
    p.colour.mean = [0.6, 0.4, 0.3];
    let img = render(&p, 128, 128, &View::default()).to_photo();
    // Mortar is lighter than brick here: the tones pair the other way round.
    let a = fit_structured(
        crate::db::Db::shipped(),
        &img,
        &pat,
        &Options::default(),
        true,
    );
    let Model::Structured(m) = &a.params.model else {
        panic!("structured")
    };
    let (first, last) = (m.ramp[0].rgb, m.ramp[m.ramp.len() - 1].rgb);
    for c in 0..3 {
        assert!((first[c] - mortar[c]).abs() < 0.03, "mortar {first:?}");
        assert!((last[c] - brick[c]).abs() < 0.03, "brick {last:?}");
    }
    a.params.validate().unwrap();
}

/// The tone curve fitted to a render mapped through a known per-channel curve recovers
/// that curve over the bulk of the distribution, and the fit is deterministic.
#[test]
fn fit_tone_recovers_a_known_curve() {
    let mut pat = Pattern::new(PatternKind::Cells, 14.0);
    pat.rotation_deg = 10.0;
    let mut p = pattern_shell(pat, 5, false);
    if let Model::Structured(m) = &mut p.model {
        m.ramp[0].rgb = [0.2, 0.3, 0.25];
        m.ramp[1].rgb = [0.7, 0.6, 0.5];
        m.residual.weights = [vec![0.05, 0.08], vec![0.03, 0.04], vec![0.02, 0.02]];
    }
    p.colour.mean = [0.45, 0.45, 0.4];
    let curve = |c: usize, v: f32| (v.clamp(0.0, 1.0)).powf([2.0, 0.5, 1.5][c]);
    let mut photo = render(&p, 128, 128, &View::default()).to_photo();
    for px in &mut photo.pixels {
        for c in 0..3 {
            px[c] = curve(c, px[c]);
        }
    }
    let tone = fit_tone(&photo, &p).expect("a structured model gets a curve");
    assert_eq!(Some(tone.clone()), fit_tone(&photo, &p));
    let mut with = p.clone();
    if let Model::Structured(m) = &mut with.model {
        m.tone = Some(tone.clone());
    }
    with.validate().unwrap();
    for c in 0..3 {
        let [lo, hi] = tone.range[c];
        for k in 1..8 {
            let x = lo + (hi - lo) * k as f32 / 8.0;
            let (got, want) = (tone.eval(c, x), curve(c, x));
            assert!(
                (got - want).abs() < 0.03,
                "channel {c} at {x}: {got} vs {want}"
            );
        }
    }
    // A noise model gets none.
    let noise = crate::analyze::analyze_prepared(&photo, &Options::default()).params;
    assert!(fit_tone(&photo, &noise).is_none());
}

/// Step 6's ramp contraction: nothing grown, nothing changed; the more the residual
/// grows, the more the stops move towards the ramp's mean, never past half way.
#[test]
fn a_grown_residual_takes_its_variance_from_the_ramp() {
    let balance = Balance {
        ramp_mean: [0.5; 3],
        residual_var: [0.001, 0.0005, 0.0001],
        photo_var: 0.0316,
    };
    let ramp = vec![
        RampStop {
            at: 0.0,
            rgb: [0.3, 0.35, 0.4],
        },
        RampStop {
            at: 1.0,
            rgb: [0.7, 0.65, 0.6],
        },
    ];
    let contracted = |grow: [f64; 3]| {
        let mut r = ramp.clone();
        balance.contract_ramp(&mut r, grow);
        r
    };
    assert_eq!(contracted([1.0; 3]), ramp);
    // The first channel grown 4×: 0.015 more variance of the ramp's 0.03 → β = √½.
    let r = contracted([4.0, 1.0, 1.0]);
    let beta = (0.0316f64 - 0.016 - 0.0005 - 0.0001).sqrt() / (0.0316f64 - 0.0016).sqrt();
    for (a, b) in r.iter().zip(&ramp) {
        for c in 0..3 {
            let want = 0.5 + beta as f32 * (b.rgb[c] - 0.5);
            assert!((a.rgb[c] - want).abs() < 1e-5, "{} vs {want}", a.rgb[c]);
        }
    }
    // Grown past the photo's variance: half way, no further.
    let r = contracted([100.0; 3]);
    assert!((r[0].rgb[0] - 0.4).abs() < 1e-5 && (r[1].rgb[2] - 0.55).abs() < 1e-5);
}

/// Step 6: on a grey photo whose fine grain the rank pairing absorbs into `ramp(ŝ)`, the
/// fit grows the residual, and its render's spectrum comes nearer the photo's than the fit
/// without the gain.
#[test]
fn a_grey_photos_fine_grain_grows_the_residual() {
    use crate::distance::distances;
    let pat = Pattern::new(PatternKind::Cells, 12.0);
    let mut p = pattern_shell(pat.clone(), 2, false);
    if let Model::Structured(m) = &mut p.model {
        m.ramp[0].rgb = [0.3; 3];
        m.ramp[1].rgb = [0.6; 3];
    }
    let mut photo = render(&p, 128, 128, &View::default()).to_photo();
    for (i, px) in photo.pixels.iter_mut().enumerate() {
        let g = 0.06 * crate::rng::gaussian(7, 0, i as u32) as f32;
        *px = px.map(|v| (v + g).clamp(0.0, 1.0));
    }
    let opts = Options::default();
    let (base, gains, _) =
        fit_structured_gains(&photo, &pat, &opts, false, &Tile::new_2d(opts.seed));
    assert!(gains[0] > 2.0, "gains {gains:?}");
    let fitted = fit_structured(crate::db::Db::shipped(), &photo, &pat, &opts, false);
    assert_eq!(
        fitted,
        fit_structured(crate::db::Db::shipped(), &photo, &pat, &opts, false)
    );
    fitted.params.validate().unwrap();
    // The residual's standard deviation in its first channel: its histogram's and the finest
    // band's part after it.
    let spread = |a: &Analysis| match &a.params.model {
        Model::Structured(m) => {
            let h = crate::histogram::spline_sd(&m.residual.histogram.knots[0]);
            (h * h + (m.residual.fine[0] as f64).powi(2)).sqrt()
        }
        Model::Noise(_) => panic!("structured"),
    };
    assert!(
        spread(&fitted) > 2.0 * spread(&base),
        "{} vs {}",
        spread(&fitted),
        spread(&base)
    );
    let spectrum = |a: &Analysis| {
        let img = render(&a.params, 128, 128, &View::default()).to_photo();
        distances(&img, &photo).spectrum_db
    };
    assert!(
        spectrum(&fitted) < spectrum(&base),
        "{} vs {}",
        spectrum(&fitted),
        spectrum(&base)
    );
}
