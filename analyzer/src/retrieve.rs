//! Automatic model choice: every candidate, the noise model included,
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

use crate::analyze::{Analysis, Options, analyze_photo_with, analyze_prepared};
use crate::db::{Db, Match, query};
use crate::error::Result;
use crate::gabor::{Descriptor, describe, descriptor_image};
use crate::input::Photo;
use crate::noise::Tile;
use crate::params::Params;
use crate::pattern::{Pattern, PatternKind};
use crate::refine::refine;
use crate::render::{Prepared, View, render_prepared};
use crate::structure::{fit_structured, fit_structured_with};
use crate::two_tone::{TwoTone, network_phase, two_tone};

/// A structured candidate ranks above the noise model only when its texture distance is lower
/// by more than this fraction of the distance between two patches of the photo itself (its top
/// and bottom halves). Ours, not the papers': a pattern fitted with a ramp and refined can
/// always match a stochastic photo's descriptor a little better than the noise model (it has
/// more parameters), but a gain smaller than the photo's own variation is not a structure; then
/// the simpler, isotropic noise model is the better answer (gravel, grass).
///
/// Measured (gain of the best family over noise / the photo's self distance, with the
/// database's fine-grain rule, [`Db::pattern_distance`]): the stochastic photos of
/// `../shared/photos` below 0 (grass, mountain rock) and 0.07 (gravel; 0.15 before that
/// rule); the structured ones 0.22 (reptile skin, cells) and 0.57 (hacienda flagstones) to 2.3
/// (planks); black rock, whose ridges turbulence draws, 1.0. On the synthetic round trip,
/// structured queries lost to noise at 0.21–0.5 (coarse patterns, whose halves hold few
/// features and differ a lot). It was 0.6 until this was measured (hacienda and reptile skin
/// went to noise, 3 round-trip cases lost), then 0.25; 0.2 won a coarse ridged case (gain
/// 0.21): 63 → 64 of 72 before the fine-grain rule, 65 with it.
pub const NOISE_MODEL_MARGIN: f32 = 0.2;

/// Below this skewness of its detrended luminance ([`crate::cues::dark_skewness`]) a photo has
/// a dark network (thin dark joints, cracks, gaps between stones standing out of a lighter
/// surface), and the best family ranks above the noise model whatever their texture distances.
/// Ours, not the papers': the noise model matches such a photo's histogram, spectrum and
/// colours closely (its texture distance often wins), but it scatters the dark pixels as
/// grain instead of drawing them as lines; the texture distance cannot see that, the
/// skewness of the photo can.
///
/// Chosen by cross-validation on the development set (`tools/devset_dark_network_cv.py`,
/// 4 folds by photo; thresholds that keep ≥ 95 % of the stochastic patches served, the largest
/// structured labelled rate): held-out folds pooled, structured labelled 31 → 40 of 100
/// patches, stochastic served 106 → 105 of 108; the folds chose −0.73, −1.08, −0.73, −0.72.
/// Chosen again the same way when the noise model gained oriented bands (its texture distance
/// fell, so it won more patches): the folds chose −0.60, −0.60, −0.60, −0.65; held out,
/// structured labelled 35/100 and stochastic served 106/108 (the former −0.726 on the new
/// model: 34/100 on the whole set). This value is the whole set's choice. Single cues measured
/// the same way and not kept: kurtosis, edge sparsity, bimodality (31/100 held out), lattice,
/// coherence.
pub const DARK_NETWORK_SKEWNESS: f32 = -0.599;

/// The ranks that leaving a family unrefined must not change: the first model and the rest of
/// the top three that the app lists.
pub const RANKS_KEPT: usize = 3;

/// The least that refinement has left of each family's retrieval distance (refined ÷
/// retrieval distance, the minimum over the families' refinements on every patch of the
/// development set, rounded down): a family whose retrieval distance times this is above the
/// [`RANKS_KEPT`]-th best refined distance is not refined ([`Suggester::pending`]).
///
/// Ours, not Bourque & Dudek's (who refine every shader of their catalogue's best matches):
/// refinement is most of an analysis' time, and most families cannot catch up. Measured on the
/// development set (208 patches, `tools/refinement_reach_cv.py` on the per-family distances of
/// `analyzer/examples/refinement_reach.rs`): with each fold's table taken from the other three
/// folds, the first model and the ordered top three were those of refining every family on
/// 208 of 208 held-out patches, with 6.25 ± 0.11 of 9 families refined (the rounds below);
/// taking the 1 % quantile instead of the minimum refined 5.51 and kept 208 and 208 as well
/// (not used: the minimum is the bound that assumes the least). On the shipped samples (not
/// used to make the table): the whole photos 20 of 20 and 20 of 20 (brick first on the brick
/// sample), their quadrants 80 of 80 and 79 of 80 (gravel's third model). A development-set
/// run made the same 208 choices as with every family refined. Turbulence reaches furthest (its
/// contrast and roughness are retrieved coarsely); refining only the first few families by
/// retrieval distance instead kept the first model on 204 of 208 with six of nine refined.
pub fn refinement_reach(kind: PatternKind) -> f32 {
    match kind {
        PatternKind::Perlin => 0.74,
        PatternKind::Turbulence => 0.39,
        PatternKind::Ridged => 0.71,
        PatternKind::Grid => 0.67,
        PatternKind::Brick => 0.75,
        PatternKind::Cells => 0.76,
        PatternKind::Planks => 0.62,
        PatternKind::WoodLines => 0.70,
        PatternKind::Rings => 0.53,
    }
}

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
    /// The texture distance of the fitted candidate to the photo (lower is nearer); `None`
    /// for a family not fitted yet ([`Suggester::ranked`], [`Suggester::fit`]).
    pub distance: Option<f32>,
    /// The ranking key: `distance`, plus [`NOISE_MODEL_MARGIN`] × the photo's own patch-to-patch distance
    /// for structured candidates.
    pub score: f32,
    /// The descriptor distance of the bare pattern found by retrieval (0 for noise).
    pub retrieval_distance: f32,
    /// The same after refinement (`None`: not refined).
    pub refined_distance: Option<f32>,
    /// Not refined because refining it could not have changed the top [`RANKS_KEPT`]
    /// ([`Suggester::pending`]); `false` for a family not refined because the refinement was
    /// stopped.
    pub skipped: bool,
    /// The candidate fitted on the reduced photo (for thumbnails); `None` for a family not
    /// fitted yet.
    pub preview: Option<Params>,
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

/// How much refinement [`suggest_with`] does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Refinement {
    /// Families refined: the first this many by retrieval distance (0: none).
    pub families: usize,
    /// Nelder–Mead evaluations per refined family, shared by its starts.
    pub evaluations: usize,
    /// Starts per family: its best this many database entries, each refined with an equal
    /// share of the evaluations; the best result is kept.
    pub starts: usize,
}

impl Default for Refinement {
    /// Every family, two starts of 20 evaluations each. Measured on the synthetic round trip
    /// (72 cases): with one start of 60 evaluations, the query's own parameters were nearer
    /// than the refined result in 2 of 8 perlin cases; two starts gained 2 cases of 72.
    /// Two starts of 20 instead of 40 (half the analysis' main cost): the round trip stays at
    /// 66 of 72, and the brick sample still ranks brick first (refined 6.70 → 3.42 against
    /// 3.24 with 40; planks second, 5.29). Refining only the three families nearest by
    /// retrieval (at 40 each) cost no labelled choice on the development set (docs/devset.md)
    /// but lost the brick sample to planks: its brick is sixth by retrieval (6.70) and first
    /// only after refinement, as lattices are where the database is sparsest.
    fn default() -> Self {
        Refinement {
            families: PatternKind::ALL.len(),
            evaluations: crate::refine::DEFAULT_EVALUATIONS,
            starts: 2,
        }
    }
}

impl Refinement {
    /// No refinement: retrieval alone.
    pub const NONE: Refinement = Refinement {
        families: 0,
        evaluations: 0,
        starts: 1,
    };
}

/// Every candidate for an analysis-size photo, nearest first, with the default refinement.
pub fn suggest(db: &Db, photo: &Photo, opts: &Options) -> Vec<Suggestion> {
    suggest_with(db, photo, opts, Refinement::default(), &|_, _| true)
}

/// Every candidate for an analysis-size photo, nearest first: the best pattern of each family
/// (refined as `refinement` says) and the noise model. `opts` as for the analysis (seed,
/// histogram, knots). `progress(done, total)` runs after each refinement evaluation (in any
/// order on native, where families are refined in parallel); returning `false` stops the
/// refinement, which then keeps the best point found so far of each family.
pub fn suggest_with(
    db: &Db,
    photo: &Photo,
    opts: &Options,
    refinement: Refinement,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Vec<Suggestion> {
    rank_with(db, photo, opts, refinement, usize::MAX, progress)
}

/// [`suggest_with`] with only the first `fitted` families fitted and rendered
/// ([`Suggester::ranked`]: the same order and scores; the others have no `distance` or
/// `preview`).
pub fn rank_with(
    db: &Db,
    photo: &Photo,
    opts: &Options,
    refinement: Refinement,
    fitted: usize,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Vec<Suggestion> {
    let mut s = Suggester::new(db, photo, opts, refinement);
    let total = s.evaluations();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let stop = std::sync::atomic::AtomicBool::new(false);
    let one = |s: &Suggester, i: usize| {
        s.refine_family(db, i, &mut |_, _| {
            use std::sync::atomic::Ordering::Relaxed;
            if stop.load(Relaxed) {
                return false;
            }
            let d = done.fetch_add(1, Relaxed) + 1;
            if !progress(d.min(total), total) {
                stop.store(true, Relaxed);
                return false;
            }
            true
        })
    };
    // Round by round ([`Suggester::pending`]), each round's families in parallel on native.
    loop {
        let round = s.pending();
        if round.is_empty() || stop.load(std::sync::atomic::Ordering::Relaxed) {
            break;
        }
        #[cfg(not(target_arch = "wasm32"))]
        let refined: Vec<Refined> = {
            use rayon::prelude::*;
            round.par_iter().map(|&i| one(&s, i)).collect()
        };
        #[cfg(target_arch = "wasm32")]
        let refined: Vec<Refined> = round.iter().map(|&i| one(&s, i)).collect();
        for (&i, r) in round.iter().zip(refined) {
            s.set_refined(i, r);
        }
    }
    s.ranked(db, fitted)
}

/// The automatic model choice in steps, for callers that must stay responsive (the browser's
/// worker): [`Suggester::new`] does the retrieval (fast), each [`Suggester::step`] refines one
/// family of those [`Suggester::pending`] lists, [`Suggester::suggestions`] ranks what there
/// is. [`suggest_with`] is the same, with each round's families refined in parallel on native.
#[derive(Clone, Debug)]
pub struct Suggester {
    small: Photo,
    /// The photo has a dark network ([`DARK_NETWORK_SKEWNESS`]).
    dark_network: bool,
    texels_per_small: f32,
    tt: TwoTone,
    q: Descriptor,
    per_px: f32,
    opts: Options,
    refinement: Refinement,
    /// Each family's starts (its best entries, best first), families best first.
    starts: Vec<Vec<Match>>,
    /// Each family's refined result, in `starts` order.
    refined: Vec<Refined>,
    /// Which families are refined (in any order: [`Suggester::set_refined`]).
    is_refined: Vec<bool>,
}

/// A family's pattern after refinement (or its retrieved one), its refined distance (`None`:
/// not refined), and whether its tones pair reversed.
pub type Refined = (Pattern, Option<f32>, bool);

impl Suggester {
    /// Describes the photo (reduced to [`RANK_SIZE`]) and retrieves each family's best entry.
    pub fn new(db: &Db, photo: &Photo, opts: &Options, refinement: Refinement) -> Suggester {
        let small = photo.reduced(RANK_SIZE).unwrap_or_else(|| photo.clone());
        let texels_per_small = photo.width as f32 / small.width as f32;
        let tt = two_tone(&small);
        let (w, h) = (small.width as usize, small.height as usize);
        let (q, per_px) = query(&tt.structure, w, h);
        let network = network_phase(&tt.structure, w, h);
        let want = refinement.starts.max(1);
        let mut starts: Vec<Vec<Match>> = db
            .top_per_kind_paired(&q, want * DIVERSE_POOL, network)
            .into_iter()
            .filter(|v| !v.is_empty())
            .map(|pool| diverse_starts(pool, want))
            .collect();
        starts.sort_by(|a, b| a[0].distance.total_cmp(&b[0].distance));
        let refined: Vec<Refined> = starts
            .iter()
            .map(|v| (v[0].pattern.clone(), None, v[0].swapped))
            .collect();
        let is_refined = vec![false; refined.len()];
        Suggester {
            dark_network: crate::cues::dark_skewness(&small) < DARK_NETWORK_SKEWNESS,
            small,
            texels_per_small,
            tt,
            q,
            per_px,
            opts: *opts,
            refinement,
            starts,
            refined,
            is_refined,
        }
    }

    /// Families that may be refined (the first this many by retrieval distance; the bound of
    /// [`Suggester::pending`] leaves some of them out).
    pub fn steps(&self) -> usize {
        self.refinement.families.min(self.starts.len())
    }

    /// Family `i` (in retrieval order).
    pub fn family(&self, i: usize) -> PatternKind {
        self.starts[i][0].pattern.kind
    }

    /// Family `i`'s retrieval distance: its best database entry's.
    pub fn retrieval_distance(&self, i: usize) -> f32 {
        self.starts[i][0].distance
    }

    /// Families refined so far.
    pub fn done(&self) -> usize {
        self.is_refined.iter().filter(|&&r| r).count()
    }

    /// The next family to refine (in retrieval order), if any.
    pub fn next_family(&self) -> Option<usize> {
        self.pending().first().copied()
    }

    /// The families of the current round still to refine, in retrieval order (empty: the
    /// refinement is complete). The first round is the first [`RANKS_KEPT`] families by
    /// retrieval distance; each next round, every family not yet in a round whose retrieval
    /// distance times its [`refinement_reach`] is at most the [`RANKS_KEPT`]-th best refined
    /// distance of the rounds so far (a family that could still enter the top three); none
    /// such ends it. A pure function of the rounds' refined distances: the same rounds
    /// whatever the order in which their families were refined (here or by helper workers).
    pub fn pending(&self) -> Vec<usize> {
        let steps = self.steps();
        let mut in_rounds = vec![false; steps];
        let mut round: Vec<usize> = (0..steps.min(RANKS_KEPT)).collect();
        while !round.is_empty() {
            let left: Vec<usize> = round
                .iter()
                .copied()
                .filter(|&i| !self.is_refined[i])
                .collect();
            if !left.is_empty() {
                return left;
            }
            for &i in &round {
                in_rounds[i] = true;
            }
            let mut refined: Vec<f32> = (0..steps)
                .filter(|&i| in_rounds[i])
                .filter_map(|i| self.refined[i].1)
                .collect();
            refined.sort_by(f32::total_cmp);
            let bound = refined
                .get(RANKS_KEPT - 1)
                .copied()
                .unwrap_or(f32::INFINITY);
            round = (0..steps)
                .filter(|&i| {
                    !in_rounds[i]
                        && self.retrieval_distance(i) * refinement_reach(self.family(i)) <= bound
                })
                .collect();
        }
        round
    }

    /// Stores family `i`'s refinement, computed by [`Suggester::refine_family`] here or on
    /// another `Suggester` built from the same photo, options and database (the browser's
    /// helper workers): the result is the same wherever and in whatever order it ran.
    pub fn set_refined(&mut self, i: usize, r: Refined) {
        if i < self.steps() {
            self.refined[i] = r;
            self.is_refined[i] = true;
        }
    }

    /// Refinement evaluations in all (for progress bars).
    pub fn evaluations(&self) -> usize {
        self.steps() * self.refinement.evaluations
    }

    /// The refinement of family `i` (in retrieval order): each start refined with its share
    /// of the evaluations, the best kept. `step(done, budget)` counts over all starts.
    pub fn refine_family(
        &self,
        db: &Db,
        i: usize,
        step: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Refined {
        let starts = &self.starts[i];
        let budget = self.refinement.evaluations;
        let share = budget / starts.len();
        let tile = db_tile();
        let mut best: Option<Refined> = None;
        let mut offset = 0;
        for m in starts {
            let qm = if m.swapped {
                self.q.swapped()
            } else {
                self.q.clone()
            };
            let mut stopped = false;
            let r = refine(db, &qm, &m.pattern, share, tile, &mut |done, _| {
                let go = step(offset + done, budget);
                stopped |= !go;
                go
            });
            offset += r.evaluations;
            if best
                .as_ref()
                .is_none_or(|b| b.1.is_some_and(|d| r.distance < d))
            {
                best = Some((r.pattern, Some(r.distance), m.swapped));
            }
            if stopped {
                break;
            }
        }
        best.expect("every family has a start")
    }

    /// Refines the next family; `progress(done, budget)` after each evaluation of it (returning
    /// `false` stops it, keeping its best point). Returns whether families remain.
    pub fn step(&mut self, db: &Db, progress: &mut dyn FnMut(usize, usize) -> bool) -> bool {
        if let Some(i) = self.next_family() {
            let r = self.refine_family(db, i, progress);
            self.set_refined(i, r);
        }
        self.next_family().is_some()
    }

    /// Every candidate, nearest first, with the refinement done so far.
    ///
    /// Ranking (`score`): the families are ordered by their *structure distance* (refined, else
    /// retrieval: the bare pattern's descriptor against the photo's structure map) plus the
    /// [`NOISE_MODEL_MARGIN`] margin. The noise model has no bare structure; it is ranked against the best
    /// family by *texture distance* (each fitted and rendered, projected on the photo's tone
    /// line, described): noise comes first when its texture distance is below the best family's
    /// plus the margin. Its `score` is its texture distance moved onto the families' scale
    /// (minus the best family's texture − score difference, minus the margin), so one sort
    /// does both. On a photo with a dark network ([`DARK_NETWORK_SKEWNESS`]) the noise model
    /// ranks right after the best family instead. Measured on
    /// the synthetic round trip (72 cases): ordering the families by texture distance picked
    /// the right one 36 times, by structure distance 43: the fitted ramp and residual noise
    /// blur the very structure that tells families apart.
    pub fn suggestions(&self, db: &Db) -> Vec<Suggestion> {
        self.ranked(db, usize::MAX)
    }

    /// [`Suggester::suggestions`] with only the first `fitted` families (by score) fitted and
    /// rendered; the others have no `distance` or `preview` until [`Suggester::fit`] fits
    /// them. The order does not depend on the fits: the families are ordered by their
    /// structure distance, and the noise model is placed against the best family's texture
    /// distance, so `fitted` = 1 gives the same order as every fit (what the browser's worker
    /// shows first; the other thumbnails follow one by one).
    pub fn ranked(&self, db: &Db, fitted: usize) -> Vec<Suggestion> {
        let tile = Tile::new_2d(self.opts.seed);
        let margin = NOISE_MODEL_MARGIN * self_distance(db, &self.tt);
        let mut out: Vec<Suggestion> = Vec::with_capacity(self.starts.len() + 1);
        let noise = analyze_prepared(&self.small, &self.opts).params;
        let distance = texture_distance(db, &self.tt, &self.q, &noise, &tile);
        out.push(Suggestion {
            name: "noise",
            pattern: None,
            distance: Some(distance),
            score: 0.0,
            retrieval_distance: 0.0,
            refined_distance: None,
            skipped: false,
            preview: Some(noise),
        });
        let complete = self.pending().is_empty();
        let mut families: Vec<Suggestion> = self
            .starts
            .iter()
            .zip(&self.refined)
            .map(|(starts, (p, refined_distance, swapped))| {
                let m = &starts[0];
                let mut p = p.clone();
                // In two steps, as the fit scales it (the same bits as before the fits
                // were split from the order).
                p.scale *= self.per_px;
                p.scale *= self.texels_per_small;
                Suggestion {
                    name: p.kind.name(),
                    pattern: Some((p, *swapped)),
                    distance: None,
                    score: refined_distance.unwrap_or(m.distance) + margin,
                    retrieval_distance: m.distance,
                    refined_distance: *refined_distance,
                    skipped: complete && refined_distance.is_none(),
                    preview: None,
                }
            })
            .collect();
        families.sort_by(|a, b| a.score.total_cmp(&b.score));
        // The first `fitted` families fitted and rendered: independent, so in parallel on
        // native.
        let n = fitted.min(families.len());
        let fits =
            crate::parallel::map_in_order(&families[..n], |f| self.fit_family(db, &tile, f.name));
        for (f, (params, distance)) in families.iter_mut().zip(fits) {
            f.distance = Some(distance);
            f.preview = Some(params);
        }
        out.extend(families);
        out[0].score = match out.get(1) {
            // Right after the best family: still offered, never first.
            Some(best) if self.dark_network => best.score.next_up(),
            Some(best) => {
                let best_distance = best.distance.expect("the best family is fitted");
                distance - (best_distance - best.score) - margin
            }
            None => distance,
        };
        out.sort_by(|a, b| a.score.total_cmp(&b.score));
        out
    }

    /// Fits `s` (a family of [`Suggester::ranked`] not fitted yet) as the ranking fits its
    /// first families; nothing for a fitted one.
    pub fn fit(&self, db: &Db, s: &mut Suggestion) {
        if s.preview.is_some() {
            return;
        }
        let (params, distance) = self.fit_family(db, &Tile::new_2d(self.opts.seed), s.name);
        s.distance = Some(distance);
        s.preview = Some(params);
    }

    /// Family `name`'s refined pattern fitted on the reduced photo, and its texture distance.
    fn fit_family(&self, db: &Db, tile: &Tile, name: &str) -> (Params, f32) {
        let (p, _, swapped) = self
            .refined
            .iter()
            .find(|(p, _, _)| p.kind.name() == name)
            .expect("a family of this suggester");
        let mut p = p.clone();
        p.scale *= self.per_px;
        let fitted = fit_structured_with(&self.small, &p, &self.opts, *swapped, tile).params;
        let distance = texture_distance(db, &self.tt, &self.q, &fitted, tile);
        (fitted, distance)
    }
}

/// Entries per wanted start that [`diverse_starts`] chooses from.
const DIVERSE_POOL: usize = 8;

/// Whether two retrieved entries are different starts: scale apart by more than 1.5×, turned
/// by a rotation step or more, or the other tone orientation.
fn distinct(a: &Match, b: &Match) -> bool {
    let turn = (a.pattern.rotation_deg - b.pattern.rotation_deg).rem_euclid(180.0);
    (a.pattern.scale / b.pattern.scale).ln().abs() > 1.5f32.ln()
        || turn.min(180.0 - turn) > 1.0
        || a.swapped != b.swapped
}

/// The `want` starts of a family from its `pool` of entries (best first): the best, then each
/// next-best entry that is [`distinct`] from every start kept; entries in order where too few
/// are. Ours: the family's best entries are often near copies of one another (the same scale,
/// rotation and tones, a structural value apart), so a second start from the next-best entry
/// explores the same valley; one from elsewhere can find another. Measured on the synthetic
/// round trip with the denser database: 63/72 either way, but a stretched perlin (scale 8
/// against a retrieved 50) found, and the wood planks sample ranked planks first again (ridged
/// by 0.11 with the next-best start); one ridged case refined less well (lost to noise).
fn diverse_starts(pool: Vec<Match>, want: usize) -> Vec<Match> {
    let mut kept: Vec<Match> = Vec::with_capacity(want);
    let mut rest = Vec::new();
    for m in pool {
        if kept.len() < want && kept.iter().all(|k| distinct(k, &m)) {
            kept.push(m);
        } else {
            rest.push(m);
        }
    }
    let missing = want.saturating_sub(kept.len());
    kept.extend(rest.into_iter().take(missing));
    kept
}

/// The database's noise tile (refinement renders patterns as the database did).
fn db_tile() -> &'static Tile {
    static TILE: std::sync::OnceLock<Tile> = std::sync::OnceLock::new();
    // Not `get_or_init`: making a tile runs parallel work (`Tile::generate`), and a rayon
    // thread that steals a job asking for this tile while it makes it would wait in
    // `get_or_init` for itself: a deadlock (seen in the retrieval tests, which rank many photos
    // at once). Two threads may both make it; the tile is the same and one is kept.
    if let Some(tile) = TILE.get() {
        return tile;
    }
    let _ = TILE.set(Tile::new_2d(crate::db::DB_SEED));
    TILE.get().expect("the tile was set")
}

/// The descriptor distance between the top and bottom halves of the photo's structure map
/// (each described from its centre square): how much the photo differs from itself.
pub fn self_distance(db: &Db, tt: &TwoTone) -> f32 {
    let (w, h) = (tt.width as usize, tt.height as usize);
    let half = h / 2;
    let top = &tt.structure[..w * half];
    let bottom = &tt.structure[(h - half) * w..];
    db.distance(
        &describe(&descriptor_image(top, w, half)),
        &describe(&descriptor_image(bottom, w, half)),
    )
}

/// The analysis of an analysis-size photo with the chosen model: the noise model, or the
/// pattern fitted at full size. Also returns the ranked suggestions (empty unless `Auto` or a
/// family was asked for).
pub fn analyze_with_model(
    db: &Db,
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
) -> (Analysis, Vec<Suggestion>) {
    analyze_with_model_progress(db, photo, opts, choice, refinement, &|_, _| true)
}

/// [`analyze_with_model`] with the refinement's `progress` as [`suggest_with`] takes it
/// (returning `false` stops the refinement: Cancel, or the CLI's `--refine-seconds`).
pub fn analyze_with_model_progress(
    db: &Db,
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> (Analysis, Vec<Suggestion>) {
    if choice == ModelChoice::Noise {
        return (analyze_prepared(photo, opts), Vec::new());
    }
    let suggestions = suggest_with(db, photo, opts, refinement, progress);
    let pick = suggestions.iter().find(|s| match choice {
        ModelChoice::Auto => true,
        ModelChoice::Kind(k) => s.name == k.name(),
        ModelChoice::Noise => s.pattern.is_none(),
    });
    let analysis = match pick.and_then(|s| s.pattern.as_ref()) {
        Some((p, swapped)) => fit_structured(db, photo, p, opts, *swapped),
        None => analyze_prepared(photo, opts),
    };
    (analysis, suggestions)
}

/// Crops and reduces `photo` as `opts` say and analyses it with the chosen model (what
/// `proctex analyze` and `proctex synth` do), with the shipped database.
pub fn analyze_photo_model(
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
) -> Result<(Analysis, Vec<Suggestion>)> {
    analyze_photo_model_progress(photo, opts, choice, refinement, &|_, _| true)
}

/// [`analyze_photo_model`] with the refinement's `progress` ([`analyze_with_model_progress`]).
pub fn analyze_photo_model_progress(
    photo: &Photo,
    opts: &Options,
    choice: ModelChoice,
    refinement: Refinement,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Result<(Analysis, Vec<Suggestion>)> {
    let mut suggestions = Vec::new();
    let analysis = analyze_photo_with(photo, opts, |p, o| {
        let (a, s) = analyze_with_model_progress(Db::shipped(), p, o, choice, refinement, progress);
        suggestions = s;
        a
    })?;
    Ok((analysis, suggestions))
}
