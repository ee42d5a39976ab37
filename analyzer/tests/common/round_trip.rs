//! The synthetic round trip's queries (the two-tone paper's protocol, Bourque & Dudek Fig. 3):
//! each structured model rendered at random parameters, rotations, scales, tones and seeds
//! (none of them the database's). Shared by `tests/retrieval.rs` and
//! `examples/round_trip_lab.rs`.

use proctex::input::Photo;
use proctex::params::Model;
use proctex::params::pattern_shell as shell;
use proctex::pattern::{Pattern, PatternKind, RampStop};
use proctex::render::{View, render};
use proctex::retrieve::Suggestion;
use proctex::rng;

/// Side of the rendered query.
pub const SIDE: u32 = 256;
/// Stream of this test's random draws (not the database's).
pub const STREAM: u32 = 0x7274_7269;

/// Case `case`'s uniform draw `j` for `kind`.
pub fn draw(kind: PatternKind, case: usize, j: u32) -> f32 {
    rng::uniform(7, STREAM, (kind.index() << 24) | ((case as u32) << 8) | j) as f32
}

/// The query image of one case and its pattern (scale in pixels of the query).
pub fn case(kind: PatternKind, case: usize) -> (Photo, Pattern) {
    let u = |j: u32| draw(kind, case, j);
    let values: Vec<f32> = kind
        .specs()
        .iter()
        .enumerate()
        .map(|(j, s)| s.searched(u(j as u32)))
        .collect();
    let mut p = Pattern::new(kind, 1.0);
    p.set_vector(&values);
    // Scales of 8–60 texels (4–30 on the 128² descriptor image, the database's range), and
    // features at most half the query long along the stretched axis (`scale × stretch` ≤ 128
    // texels): a query must hold a few of its pattern's features to say which pattern it is.
    let stretch = p.get("stretch").unwrap_or(1.0);
    let top = (128.0 / stretch).clamp(8.0, 60.0);
    p.scale = (8.0f32.ln() + (top.ln() - 8.0f32.ln()) * u(100)).exp();
    p.rotation_deg = 180.0 * u(101);
    // Rings show their centre (as the database's do): inside the middle 60 % of the query.
    // Rings whose centre lies outside are the wood-lines family's straight lines.
    for (j, name) in [(108, "centre_x"), (109, "centre_y")] {
        p.set(name, SIDE as f32 * (0.2 + 0.6 * u(j)) / p.scale);
    }
    let mut params = shell(p.clone(), 1000 + case as u32, false);
    // Two tones, at least 0.25 apart in luminance.
    let dark = [u(102), u(103), u(104)].map(|v| 0.1 + 0.35 * v);
    let light = [u(105), u(106), u(107)].map(|v| 0.55 + 0.35 * v);
    if let Model::Structured(m) = &mut params.model {
        m.ramp = vec![
            RampStop { at: 0.0, rgb: dark },
            RampStop {
                at: 1.0,
                rgb: light,
            },
        ];
    }
    params.colour.mean = [0, 1, 2].map(|c| 0.5 * (dark[c] + light[c]));
    let img = render(&params, SIDE, SIDE, &View::default()).to_photo();
    (img, p)
}

/// The family whose refined (or, if not refined, retrieval) distance is least: the choice by
/// structure alone, without the noise model.
pub fn family_by_retrieval(ranked: &[Suggestion]) -> &'static str {
    let d = |x: &Suggestion| x.refined_distance.unwrap_or(x.retrieval_distance);
    ranked
        .iter()
        .filter(|x| x.pattern.is_some())
        .min_by(|a, b| d(a).total_cmp(&d(b)))
        .expect("every family is ranked")
        .name
}
