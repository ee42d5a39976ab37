//! The noise model's output tone curve (`proctex::noise_tone`): its fit recovers a known
//! curve, it brings a two-colour photo's colours back where independent channels mix them,
//! and documents carry it.

mod common;

use common::noise_params;
use proctex::analyze::{Options, analyze_prepared};
use proctex::distance::colour_distance;
use proctex::input::Photo;
use proctex::noise_tone::fit_noise_tone;

/// Knots per channel of the fitted curves.
const NOISE_TONE_KNOTS: usize = 9;
use proctex::params::{Model, Params, pattern_shell};
use proctex::pattern::{Pattern, PatternKind};
use proctex::render::{View, render};

/// A grey-axis-first basis (the luminance axis, then two chroma axes).
const BASIS: [[f32; 3]; 3] = [
    [0.577_350_26, 0.577_350_26, 0.577_350_26],
    [0.707_106_77, 0.0, -0.707_106_77],
    [-0.408_248_3, 0.816_496_6, -0.408_248_3],
];

/// Noise params whose distribution holds still across seeds: fine bands only.
fn fine_noise(seed: u32) -> Params {
    noise_params(
        [
            vec![0.06, 0.07, 0.05, 0.03],
            vec![0.03, 0.03, 0.02, 0.01],
            vec![0.02, 0.02, 0.01, 0.01],
        ],
        BASIS,
        seed,
    )
}

fn with_tone(p: &Params, tone: proctex::params::Tone) -> Params {
    let mut out = p.clone();
    if let Model::Noise(n) = &mut out.model {
        n.tone = Some(tone);
    }
    out
}

/// A render of noise params mapped through a known per-channel curve: the fitted curve is that
/// curve over the bulk of the distribution (to 0.02, the pooled seeds' sampling error being a
/// few thousandths there), the fit is deterministic, and rendering with it gives the photo's
/// distribution back.
#[test]
fn fit_noise_tone_recovers_a_known_curve() {
    let p = fine_noise(3);
    let curve = |c: usize, v: f32| 0.2 + 0.6 * v.clamp(0.0, 1.0).powf([2.0, 0.5, 1.5][c]);
    let mut photo = render(&p, 256, 256, &View::default()).to_photo();
    for px in &mut photo.pixels {
        for c in 0..3 {
            px[c] = curve(c, px[c]);
        }
    }
    let tone = fit_noise_tone(&photo, &p, NOISE_TONE_KNOTS).expect("a curve");
    assert_eq!(
        Some(tone.clone()),
        fit_noise_tone(&photo, &p, NOISE_TONE_KNOTS)
    );
    assert_eq!(tone.knots[0].len(), NOISE_TONE_KNOTS);
    let with = with_tone(&p, tone.clone());
    with.validate().unwrap();
    for c in 0..3 {
        let [lo, hi] = tone.range[c];
        for k in 1..8 {
            let x = lo + (hi - lo) * k as f32 / 8.0;
            let (got, want) = (tone.eval(c, x), curve(c, x));
            assert!(
                (got - want).abs() < 0.02,
                "channel {c} at {x}: {got} vs {want}"
            );
        }
    }
    let before = colour_distance(&render(&p, 256, 256, &View::default()).to_photo(), &photo);
    let after = colour_distance(
        &render(&with, 256, 256, &View::default()).to_photo(),
        &photo,
    );
    assert!(after < 0.2 * before, "colour distance {before} → {after}");
    // A model that already has a curve, or a photo too small to fit, gets none.
    assert!(fit_noise_tone(&photo, &with, NOISE_TONE_KNOTS).is_none());
    let tiny = Photo {
        width: 7,
        height: 7,
        pixels: vec![[0.5; 3]; 49],
    };
    assert!(fit_noise_tone(&tiny, &p, NOISE_TONE_KNOTS).is_none());
}

/// A photo of two colours in blobs (leaves on soil): the analysis's independent channels mix
/// them into colours the photo does not have; its tone curve brings the colour distance down.
#[test]
fn the_tone_curve_separates_a_two_colour_photo() {
    let field = render(&fine_noise(7), 128, 128, &View::default()).to_photo();
    let (green, brown) = ([0.25, 0.55, 0.15], [0.45, 0.3, 0.2]);
    let photo = Photo {
        width: 128,
        height: 128,
        pixels: field
            .pixels
            .iter()
            .map(|px| {
                let base = if px[0] > 0.5 { green } else { brown };
                [0, 1, 2].map(|c| base[c] + 0.3 * (px[c] - 0.5))
            })
            .collect(),
    };
    let fitted = analyze_prepared(&photo, &Options::default()).params;
    let lagae = analyze_prepared(
        &photo,
        &Options {
            tone: false,
            ..Options::default()
        },
    )
    .params;
    assert!(fitted.model.tone().is_some());
    assert!(lagae.model.tone().is_none());
    let distance = |p: &Params| {
        (1..=3)
            .map(|seed| {
                let q = Params { seed, ..p.clone() };
                colour_distance(&render(&q, 128, 128, &View::default()).to_photo(), &photo)
            })
            .sum::<f64>()
    };
    let (with, without) = (distance(&fitted), distance(&lagae));
    assert!(with < 0.7 * without, "colour distance {without} → {with}");
}

/// The curve travels in documents, and a structured model's residual may not carry one.
#[test]
fn documents_carry_the_noise_models_tone_curve() {
    let p = with_tone(&fine_noise(1), proctex::params::Tone::identity(5));
    let json = p.to_json();
    assert!(json.contains("\"tone\""));
    let back = Params::from_json(&json).unwrap();
    assert_eq!(back, p);
    let mut bad = p.clone();
    if let Model::Noise(n) = &mut bad.model {
        n.tone.as_mut().unwrap().knots[1][2] = -1.0;
    }
    let err = bad.validate().unwrap_err().to_string();
    assert!(err.contains("model.tone.knots[1]"), "{err}");
    // A structured model's residual has no curve of its own.
    let mut structured = pattern_shell(Pattern::new(PatternKind::Brick, 16.0), 1, false);
    if let Model::Structured(m) = &mut structured.model {
        m.residual.tone = Some(proctex::params::Tone::identity(5));
    }
    let err = structured.validate().unwrap_err().to_string();
    assert!(err.contains("model.residual.tone"), "{err}");
}

/// Every shipped sample's analysis stays within the parameter budget, chooses its knot split
/// per photo, and is deterministic.
#[test]
fn analyses_spend_the_budget_on_knots_where_they_help() {
    use proctex::analyze::analyze_photo;
    use proctex::noise_tone::{PARAMETER_BUDGET, numbers};
    let mut curves = 0;
    for name in common::SAMPLES {
        let photo = common::sample(name);
        let a = analyze_photo(&photo, &Options::default()).unwrap().params;
        assert_eq!(
            a,
            analyze_photo(&photo, &Options::default()).unwrap().params
        );
        let n = a.noise().expect("the noise model");
        assert!(
            numbers(n) <= PARAMETER_BUDGET,
            "{name}: {} numbers",
            numbers(n)
        );
        curves += n.tone.is_some() as usize;
        let lagae = analyze_photo(
            &photo,
            &Options {
                tone: false,
                ..Options::default()
            },
        )
        .unwrap()
        .params;
        assert!(lagae.model.tone().is_none());
        assert_eq!(lagae.noise().unwrap().histogram.knots[0].len(), 11);
    }
    // The split is chosen per photo: neither every sample nor none keeps a curve (2 of the 6
    // keep one with the ring-fitted weights, 3 with the octave solve's: the within-photo
    // validation decides close calls either way).
    assert!(
        (1..common::SAMPLES.len()).contains(&curves),
        "{curves} of {} samples got a curve",
        common::SAMPLES.len()
    );
}
