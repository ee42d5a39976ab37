//! The params the GPU-vs-CPU tests render: the shipped samples' analyses and variants of them.

use proctex::analyze::{Options, analyze_bytes};
use proctex::params::Params;

/// The analysis of the shipped sample `name` (`www/samples/`).
pub fn sample_params(name: &str) -> Params {
    let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
    analyze_bytes(&std::fs::read(path).unwrap(), &Options::default())
        .unwrap()
        .params
}

/// Sample `name`'s noise model with an output tone curve: its own where its analysis kept one,
/// otherwise one of 9 knots fitted to the photo (the analysis keeps a curve only where it
/// validates within the photo; the morph tests want curves at both ends).
pub fn with_curve(name: &str) -> Params {
    let mut p = sample_params(name);
    if p.model.tone().is_none() {
        let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
        let photo = proctex::input::Photo::decode(&std::fs::read(path).unwrap()).unwrap();
        let photo = proctex::analyze::prepare_photo(&photo, &Options::default()).unwrap();
        let tone = proctex::noise_tone::fit_noise_tone(&photo, &p, 9);
        p.model.noise_layer_mut().tone = tone;
    }
    assert!(p.model.tone().is_some(), "{name}: no curve");
    p
}

/// `p` with every band oriented: streaks at `angle + 25°·j`, strengths from 0.3 to 1 (band 2
/// at full strength, band 3 isotropic: both branches of the shader).
pub fn oriented(p: &Params, angle: f32) -> Params {
    let mut p = p.clone();
    let m = p.model.noise_layer_mut();
    m.orientation = (0..m.bands())
        .map(|j| proctex::params::BandOrientation {
            angle_deg: (angle + 25.0 * j as f32).rem_euclid(180.0),
            strength: [0.3, 0.7, 1.0, 0.0][j % 4],
        })
        .collect();
    p
}

/// A structured texture of `kind` on `base`'s colours and noise: the pattern at its defaults,
/// scale 11 texels, turned 20°, a three-stop ramp about the mean, the noise at 40 %, an output
/// tone curve.
pub fn structured(base: &Params, kind: proctex::pattern::PatternKind) -> Params {
    use proctex::params::{Model, StructuredModel};
    use proctex::pattern::{Pattern, RampStop};
    let mut p = base.clone();
    let mut residual = base.model.noise_layer().clone();
    // The structured model's curve below applies last; a residual has none of its own.
    residual.tone = None;
    for w in residual.weights.iter_mut().flatten() {
        *w *= 0.4;
    }
    let m = base.colour.mean;
    let b = base.colour.basis[0];
    let tone = |k: f32| [0, 1, 2].map(|c| (m[c] + k * b[c]).clamp(0.0, 1.0));
    let mut pattern = Pattern::new(kind, 11.0);
    pattern.rotation_deg = 20.0;
    // Rings centred inside the image (texel (44, 33)), so that the centre's offset is compared.
    pattern.set("centre_x", 4.0);
    pattern.set("centre_y", 3.0);
    p.model = Model::Structured(StructuredModel {
        pattern,
        ramp: vec![
            RampStop {
                at: 0.0,
                rgb: tone(-0.25),
            },
            RampStop {
                at: 0.4,
                rgb: tone(0.05),
            },
            RampStop {
                at: 1.0,
                rgb: tone(0.2),
            },
        ],
        residual,
        // An S-shaped output tone curve, a different one per channel.
        tone: Some(proctex::params::Tone {
            enabled: true,
            range: [[0.1, 0.8], [0.15, 0.9], [0.05, 0.7]],
            knots: [0.9f32, 1.0, 1.15].map(|g| {
                (0..9)
                    .map(|k| {
                        let x = k as f32 / 8.0;
                        0.05 + 0.9 * (x * x * (3.0 - 2.0 * x)).powf(g)
                    })
                    .collect()
            }),
        }),
    });
    p.validate().unwrap();
    p
}
