//! A structured model's output tone curve maps the ramp's colour; the residual follows it,
//! through the curve where the curve compresses it, never larger than itself where the curve
//! is steep (a pixel-scale excursion through a steep stretch of the curve would be a speck).
use proctex::params::{Model, Params, Tone, pattern_shell};
use proctex::pattern::{Pattern, PatternKind, RampStop};
use proctex::render::{View, render};

const SIDE: u32 = 128;

/// A narrow-ramped brick model, with or without its residual (coarse bands and the finest
/// band's part), its tone curve `knots` over `[lo, hi]` in every channel (`None`: no curve).
fn brick(residual: bool, curve: Option<([f32; 2], Vec<f32>)>) -> Params {
    let mut p = pattern_shell(Pattern::new(PatternKind::Brick, 18.0), 7, false);
    if let Model::Structured(m) = &mut p.model {
        m.ramp = vec![
            RampStop {
                at: 0.0,
                rgb: [0.4; 3],
            },
            RampStop {
                at: 1.0,
                rgb: [0.46; 3],
            },
        ];
        if residual {
            let w = vec![0.0, 0.005, 0.005, 0.002];
            m.residual.weights = [w.clone(), w.clone(), w];
            m.residual.fine = [0.03; 3];
        }
        m.tone = curve.map(|(range, knots)| Tone {
            enabled: true,
            range: [range; 3],
            knots: [knots.clone(), knots.clone(), knots],
        });
    }
    p.validate().expect("a valid structured model");
    p
}

fn pixels(p: &Params) -> Vec<[f32; 3]> {
    render(p, SIDE, SIDE, &View::default()).pixels
}

fn tone_of(p: &Params) -> Tone {
    match &p.model {
        Model::Structured(m) => m.tone.clone().expect("a curve"),
        Model::Noise(_) => unreachable!(),
    }
}

#[test]
fn the_tone_curve_never_stretches_the_residual() {
    let steep = ([0.38, 0.48], vec![0.1, 0.3, 0.5, 0.7, 0.9]);
    let gentle = ([0.0, 1.0], vec![0.25, 0.375, 0.5, 0.625, 0.75]);
    // The residual in RGB at each pixel: the renders without a curve, with and without it.
    let (with, without) = (pixels(&brick(true, None)), pixels(&brick(false, None)));
    let residual: Vec<[f32; 3]> = with
        .iter()
        .zip(&without)
        .map(|(a, b)| [0, 1, 2].map(|c| a[c] - b[c]))
        .collect();
    assert!(
        residual.iter().any(|p| p[0].abs() > 0.01),
        "the residual is drawn"
    );
    for (curve, name) in [(steep, "steep"), (gentle, "gentle")] {
        let toned = brick(true, Some(curve.clone()));
        let tone = tone_of(&toned);
        let (a, b) = (pixels(&toned), pixels(&brick(false, Some(curve))));
        let mut stretched = 0;
        for i in 0..a.len() {
            for c in 0..3 {
                let excursion = a[i][c] - b[i][c];
                let r = residual[i][c];
                assert!(
                    excursion.abs() <= r.abs() + 1e-5,
                    "{name}: pixel {i} channel {c}: {excursion} from a residual of {r}"
                );
                // The residual through the whole curve (the curve of the whole colour).
                let through = tone.eval(c, with[i][c]) - tone.eval(c, without[i][c]);
                if through.abs() > r.abs() + 1e-5 {
                    stretched += 1;
                } else {
                    assert!(
                        (excursion - through).abs() < 1e-4,
                        "{name}: where the curve compresses, the residual goes through it"
                    );
                }
            }
        }
        if name == "steep" {
            assert!(
                stretched > a.len(),
                "the steep curve would stretch the residual"
            );
        } else {
            assert_eq!(stretched, 0, "the gentle curve compresses everywhere");
        }
    }
}

#[test]
fn without_a_residual_the_curve_maps_the_ramps_colour() {
    let curve = ([0.38, 0.48], vec![0.1, 0.3, 0.5, 0.7, 0.9]);
    let plain = brick(false, Some(curve));
    let tone = tone_of(&plain);
    let untoned = pixels(&brick(false, None));
    for (a, u) in pixels(&plain).iter().zip(&untoned) {
        for c in 0..3 {
            assert!((a[c] - tone.eval(c, u[c]).clamp(0.0, 1.0)).abs() < 1e-5);
        }
    }
}
