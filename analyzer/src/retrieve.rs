//! Automatic model choice (issue 5, points 3 and 5): every candidate, the noise model included,
//! gets one texture distance to the photo, and the nearest wins.
//!
//! 1. The photo's two-tone structure map ([`crate::two_tone`]) gives the query descriptor
//!    ([`crate::gabor`]); the database ([`crate::db`]) gives each pattern family's nearest
//!    entry over rotations and both tone orientations.
//! 2. Each family's match is fitted to the photo ([`crate::structure::fit_structured`]: ramp
//!    and residual), and so is the noise model (Lagae's analysis), on a reduced copy of the
//!    photo ([`RANK_SIZE`]) to keep the ranking fast.
//! 3. The texture distance: each fitted candidate is rendered, projected on the photo's own
//!    tone line, and described; its weighted descriptor distance to the photo's is its score.
//!    Rendering the complete candidate (ramp and residual noise included) is what makes the
//!    noise model and the structured ones comparable: a pure retrieval distance would compare
//!    a pattern's bare structure with the photo's, which the noise model has none of.

use crate::analyze::{Analysis, Options, analyze_prepared};
use crate::db::{Db, query};
use crate::gabor::{Descriptor, describe, descriptor_image};
use crate::input::Photo;
use crate::noise::Tile;
use crate::params::Params;
use crate::pattern::{Pattern, PatternKind};
use crate::render::{Prepared, View, render_prepared};
use crate::structure::{fit_structured, fit_structured_with};
use crate::two_tone::{TwoTone, two_tone};

/// Longer side of the photo copy the candidates are fitted and scored on.
pub const RANK_SIZE: u32 = 256;

/// Which model an analysis uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelChoice {
    /// The nearest candidate (the default).
    Auto,
    /// Lagae's noise model.
    Noise,
    /// The best match of one pattern family.
    Kind(PatternKind),
}

impl ModelChoice {
    /// Parses `auto`, `noise` or a pattern family's name.
    pub fn parse(s: &str) -> Option<ModelChoice> {
        match s {
            "auto" => Some(ModelChoice::Auto),
            "noise" => Some(ModelChoice::Noise),
            _ => PatternKind::from_name(s).map(ModelChoice::Kind),
        }
    }
}

/// A ranked candidate.
#[derive(Clone, Debug, PartialEq)]
pub struct Suggestion {
    /// "noise" or the pattern family's name.
    pub name: &'static str,
    /// The pattern (`None` for the noise model) in texels of the analysed photo, and whether
    /// its tones pair reversed.
    pub pattern: Option<(Pattern, bool)>,
    /// The texture distance of the fitted candidate to the photo (lower is nearer).
    pub distance: f32,
    /// The descriptor distance of the bare pattern found by retrieval (0 for noise).
    pub retrieval_distance: f32,
    /// The candidate fitted on the reduced photo (for thumbnails).
    pub preview: Params,
}

/// The texture distance of `params` to the photo whose two-tone line is `tt` and whose
/// descriptor is `query`: `params` rendered at the photo's size (with `tile`, its noise tile),
/// projected on that line, described.
pub fn texture_distance(
    db: &Db,
    tt: &TwoTone,
    query: &Descriptor,
    params: &Params,
    tile: &Tile,
) -> f32 {
    let (w, h) = (tt.width, tt.height);
    let img = render_prepared(&Prepared::new(params), tile, w, h, &View::default()).to_photo();
    let s = tt.project(&img);
    db.distance(
        query,
        &describe(&descriptor_image(&s, w as usize, h as usize)),
    )
}

/// Every candidate for an analysis-size photo, nearest first: the best pattern of each family
/// and the noise model. `opts` as for the analysis (seed, histogram, knots).
pub fn suggest(db: &Db, photo: &Photo, opts: &Options) -> Vec<Suggestion> {
    let small_owned = photo.reduced(RANK_SIZE);
    let small = small_owned.as_ref().unwrap_or(photo);
    let texels_per_small = photo.width as f32 / small.width as f32;
    let tt = two_tone(small);
    let (q, per_px) = query(&tt.structure, small.width as usize, small.height as usize);
    let tile = Tile::new_2d(opts.seed);
    let matches = db.best_per_kind(&q);
    let mut out: Vec<Suggestion> = Vec::with_capacity(matches.len() + 1);
    let noise = analyze_prepared(small, opts).params;
    out.push(Suggestion {
        name: "noise",
        pattern: None,
        distance: texture_distance(db, &tt, &q, &noise, &tile),
        retrieval_distance: 0.0,
        preview: noise,
    });
    for m in matches {
        let mut p = m.pattern.clone();
        p.scale *= per_px;
        let fitted = fit_structured_with(small, &p, opts, m.swapped, &tile).params;
        let distance = texture_distance(db, &tt, &q, &fitted, &tile);
        p.scale *= texels_per_small;
        out.push(Suggestion {
            name: p.kind.name(),
            pattern: Some((p, m.swapped)),
            distance,
            retrieval_distance: m.distance,
            preview: fitted,
        });
    }
    out.sort_by(|a, b| a.distance.total_cmp(&b.distance));
    out
}

/// The analysis of an analysis-size photo with the chosen model: the noise model, or the
/// pattern fitted at full size. Also returns the ranked suggestions (empty unless `Auto` or a
/// family was asked for).
pub fn analyze_with_model(
    db: &Db,
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
) -> (Analysis, Vec<Suggestion>) {
    if choice == ModelChoice::Noise {
        return (analyze_prepared(photo, opts), Vec::new());
    }
    let suggestions = suggest(db, photo, opts);
    let pick = suggestions.iter().find(|s| match choice {
        ModelChoice::Auto => true,
        ModelChoice::Kind(k) => s.name == k.name(),
        ModelChoice::Noise => s.pattern.is_none(),
    });
    let analysis = match pick.and_then(|s| s.pattern.as_ref()) {
        Some((p, swapped)) => fit_structured(photo, p, opts, *swapped),
        None => analyze_prepared(photo, opts),
    };
    (analysis, suggestions)
}
