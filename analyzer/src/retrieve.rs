//! Automatic model choice: the pattern families ordered by how near their structure and their
//! fitted renders come to the photo's, and the noise model placed among them by its render.
//!
//! 1. The photo's two-tone structure map ([`crate::two_tone`]) gives the query descriptor
//!    ([`crate::gabor`]); the database ([`crate::db`]) gives each pattern family's nearest
//!    entries over rotations and both tone orientations (the two-tone paper's retrieval).
//! 2. A classifier trained on real textures ([`crate::family_classifier`]) orders the families
//!    it knows; its first three are refined by Nelder–Mead on the bare pattern's *structure
//!    distance* to the photo's map ([`crate::refine`]; Bourque & Dudek).
//! 3. Those families and the noise model are fitted to the photo
//!    ([`crate::structure::fit_structured`]: ramp and residual; Lagae's analysis) on a reduced
//!    copy of it ([`RANK_SIZE`]), rendered, projected on the photo's own tone line and
//!    described: their *texture distance*. Rendering the complete candidate (ramp and residual
//!    noise included) is what makes the noise model and the structured ones comparable, and
//!    it orders the fitted families ([`TEXTURE_WEIGHT`]); see [`Suggester::suggestions`].

mod adopt;
mod rank;
mod rules;

pub use adopt::SPECK_CLEAN_ROWS;
pub use rank::{nearer_render_margin, self_distance, texture_distance};
pub use rules::{
    CLASSIFIER_WEIGHT, DARK_NETWORK_SKEWNESS, NEARER_RENDER_MARGIN, NOISE_MODEL_MARGIN,
    RENDER_NULL_MARGIN, RENDER_ORDERED, TEXTURE_WEIGHT,
};

use crate::analyze::{Analysis, Options, analyze_photo_with, analyze_prepared};
use crate::db::{Db, Match, query};
use crate::error::Result;
use crate::family_classifier::{Class, class_distances};
use crate::gabor::Descriptor;
use crate::input::Photo;
use crate::noise::Tile;
use crate::params::Params;
use crate::pattern::{Pattern, PatternKind};
use crate::refine::refine;
use crate::structure::fit_structured;
use crate::two_tone::{TwoTone, network_phase, two_tone};

/// The ranks the app lists with thumbnails and scores: the first model and the rest of the top
/// three.
pub const RANKS_KEPT: usize = 3;

/// Longer side of the photo copy the candidates are fitted and scored on.
pub const RANK_SIZE: u32 = 256;

/// The family classifier's classes for a photo as the ranking sees it (reduced to
/// [`RANK_SIZE`], its two-tone structure map described, its cues), nearest first, with their distances
/// ([`crate::family_classifier::class_distances`]; `None`: the noise class).
pub fn classify(photo: &Photo) -> Vec<(Class, f64)> {
    let small = photo.reduced(RANK_SIZE);
    let small = small.as_ref().unwrap_or(photo);
    let tt = two_tone(small);
    let (q, _) = query(&tt.structure, small.width as usize, small.height as usize);
    class_distances(&q, &crate::cues::cues(small))
}

/// The classifier's margin for class `of` over class `over` among `classes` ([`classify`]):
/// the squared distance to `over` minus that to `of` (half of it a log-likelihood ratio);
/// negative infinity where either is missing (the margin then never exceeds
/// [`RENDER_NULL_MARGIN`]).
pub fn class_margin(classes: &[(Class, f64)], of: Class, over: Class) -> f64 {
    let distance = |c: Class| classes.iter().find(|(k, _)| *k == c).map(|(_, d)| *d);
    match (distance(of), distance(over)) {
        (Some(a), Some(b)) => b - a,
        _ => f64::NEG_INFINITY,
    }
}

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
    /// The ranking key, lower first ([`Suggester::suggestions`]): for the families, their
    /// structure distance (blended with `distance` for the fitted ones that order the list) plus
    /// [`NOISE_MODEL_MARGIN`] × the photo's own patch-to-patch distance; for the noise model,
    /// its `distance` moved onto the best family's scale.
    pub score: f32,
    /// The descriptor distance of the bare pattern found by retrieval (0 for noise).
    pub retrieval_distance: f32,
    /// The same after refinement (`None`: not refined).
    pub refined_distance: Option<f32>,
    /// Not refined because it is not one of the families whose fits order the list
    /// ([`Suggester::pending`]: the classifier's first three); `false` for a family not refined
    /// because the refinement was stopped.
    pub skipped: bool,
    /// One of the candidates whose fitted renders order the list: the noise model and the
    /// families of [`Suggester::render_ordered`] (the others follow them, unordered by renders).
    pub render_ordered: bool,
    /// The candidate fitted on the reduced photo (for thumbnails); `None` for a family not
    /// fitted yet.
    pub preview: Option<Params>,
    /// The family classifier's classes for that fit's render, as the ranking renders it
    /// ([`classify`]; [`RENDER_NULL_MARGIN`]); `None` for a family not fitted yet or not
    /// render-ordered ([`Fit`]).
    pub render_classes: Option<Vec<(Class, f64)>>,
    /// For the noise model where the ranking's other rules put it first: the photo's scattering
    /// distances to the noise model's render and to the render of the first round of the
    /// classifier's nearest family's final fit ([`Suggestion::nearer_render_margin`]); `None`
    /// elsewhere.
    pub nearer_render_distances: Option<(f64, f64)>,
    /// The automatic choice fitted this row and passed over it: its render is speckier than
    /// [`crate::specks::SPECK_LIMIT`] times the photo, and a later row of the top three was not
    /// ([`SPECK_CLEAN_ROWS`]); it now follows that row.
    pub speckier: bool,
}

impl Suggestion {
    /// How much nearer the photo is to the nearest family's render than to the noise model's in
    /// the scattering space, where measured ([`nearer_render_margin`],
    /// [`NEARER_RENDER_MARGIN`]; `nearer_render_distances`).
    pub fn nearer_render_margin(&self) -> Option<f64> {
        self.nearer_render_distances
            .map(|(to_noise, to_family)| to_noise - to_family)
    }
}

/// How much refinement [`suggest_with`] does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Refinement {
    /// Families refined at most, in [`Suggester::pending`]'s order (0: none).
    pub families: usize,
    /// Nelder–Mead evaluations per refined family, shared by its starts.
    pub evaluations: usize,
    /// Starts per family: its best this many database entries, each refined with an equal
    /// share of the evaluations; the best result is kept.
    pub starts: usize,
    /// Families that the analysis' ranking fits and renders, in the list's order: at least
    /// those that order it ([`Suggester::render_ordered`]); the others' fits only fill in their
    /// rows' texture distances and previews (`usize::MAX`: every family, as `proctex fidelity`
    /// records them). [`suggest_with`] fits every family whatever this says.
    pub fitted: usize,
}

impl Default for Refinement {
    /// Every family that [`Suggester::pending`] refines, two starts of 20 evaluations each.
    /// Measured on the synthetic round trip (72 cases): with one start of 60 evaluations, the
    /// query's own parameters were nearer than the refined result in 2 of 8 perlin cases; two
    /// starts gained 2 cases of 72.
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
            fitted: RENDER_ORDERED,
        }
    }
}

impl Refinement {
    /// No refinement: retrieval alone.
    pub const NONE: Refinement = Refinement {
        families: 0,
        evaluations: 0,
        starts: 1,
        fitted: RENDER_ORDERED,
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
    rank_keeping_noise(db, photo, opts, refinement, fitted, None, progress).0
}

/// [`rank_with`], and the noise model's analysis of `photo` when the ranking fitted it on
/// `photo` unreduced ([`Suggester::fit_noise_unreduced`]): the analysis that choosing the noise
/// model needs, bit for bit, at no further cost. A 256² crop whose best model is the noise
/// model was analysed twice: the gravel sample's top-left crop analysed warm, old and new
/// alternated, median of six each, 1.02 → 0.74 s and 1.01 → 0.74 s (two threads). Likewise
/// the first round of the nearest family's final fit that [`NEARER_RENDER_MARGIN`] made on
/// `photo` unreduced, from which choosing that family goes on.
///
/// `also`: a family refined as well when the refinement leaves it out (the one asked for by
/// name: `--model brick`), so that it is refined whatever the classifier says.
fn rank_keeping_noise(
    db: &Db,
    photo: &Photo,
    opts: &Options,
    refinement: Refinement,
    fitted: usize,
    also: Option<PatternKind>,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> (Vec<Suggestion>, Unreduced) {
    let mut s = Suggester::new(db, photo, opts, refinement);
    let total = s.evaluations();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let stop = std::sync::atomic::AtomicBool::new(false);
    let step = |_: usize, _: usize| {
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
    };
    let one = |s: &Suggester, i: usize| s.refine_family(db, i, &mut step.clone());
    // The database's tile made here, before the starts run in parallel: each start's
    // refinement needs it first, and in a fresh process every thread made it for itself at
    // once (the same work twice on two cores, about 150 ms natively).
    db_tile();
    // Round by round ([`Suggester::pending`]), each round's starts in parallel on native (three
    // families of two starts: three starts a thread instead of two families, four starts).
    loop {
        let round = s.pending_starts();
        if round.is_empty() || stop.load(std::sync::atomic::Ordering::Relaxed) {
            break;
        }
        #[cfg(not(target_arch = "wasm32"))]
        let refined: Vec<Refined> = {
            use rayon::prelude::*;
            round
                .par_iter()
                .map(|&(i, k)| s.refine_start(db, i, k, &mut step.clone()))
                .collect()
        };
        #[cfg(target_arch = "wasm32")]
        let refined: Vec<Refined> = round
            .iter()
            .map(|&(i, k)| s.refine_start(db, i, k, &mut step.clone()))
            .collect();
        for (&(i, k), r) in round.iter().zip(refined) {
            s.set_refined_start(i, k, r);
        }
    }
    s.settle_partial_starts();
    let asked = also.and_then(|k| (0..s.starts.len()).find(|&i| s.family(i) == k));
    if let Some(i) = asked.filter(|&i| !s.is_refined[i] && refinement.families > 0)
        && !stop.load(std::sync::atomic::Ordering::Relaxed)
    {
        let r = one(&s, i);
        s.set_refined(i, r);
    }
    let noise = s.fit_noise_unreduced(db);
    let ranked = s.ranked(db, fitted);
    let family = s.take_nearest_first_round();
    (ranked, Unreduced { noise, family })
}

/// What [`rank_keeping_noise`]'s ranking computed on the photo unreduced that choosing a model
/// would compute again, bit for bit: the noise model's analysis, and the first round of the
/// nearest family's final fit.
struct Unreduced {
    noise: Option<Analysis>,
    family: Option<rank::NearestFirstRound>,
}

/// The automatic model choice in steps, for callers that must stay responsive (the browser's
/// worker): [`Suggester::new`] does the retrieval (fast), each [`Suggester::step`] refines one
/// family of those [`Suggester::pending`] lists, [`Suggester::suggestions`] ranks what there
/// is. [`suggest_with`] is the same, with each round's starts ([`Suggester::pending_starts`])
/// refined in parallel on native.
#[derive(Clone, Debug)]
pub struct Suggester {
    small: Photo,
    /// `small` is the photo itself (no longer than [`RANK_SIZE`]).
    unreduced: bool,
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
    /// The families (in `starts` order) in the list's order before the fitted ones are
    /// reordered: the classifier's families nearest first ([`crate::family_classifier`]), then
    /// those it has no example of (turbulence, rings, perlin) by retrieval distance. The first
    /// [`RENDER_ORDERED`] are refined and fitted to order the list.
    order: Vec<usize>,
    /// Each family's squared distance to its class in the family classifier, in `starts`
    /// order (infinite for a family it has no example of): what [`CLASSIFIER_WEIGHT`] adds to
    /// the fitted families' order.
    class_distance: Vec<f64>,
    /// Each family's refined result, in `starts` order.
    refined: Vec<Refined>,
    /// Which families are refined (in any order: [`Suggester::set_refined`]).
    is_refined: Vec<bool>,
    /// Each family's starts refined so far where they were refined one by one
    /// ([`Suggester::set_refined_start`]), in `starts` order.
    start_results: Vec<Vec<Option<Refined>>>,
    /// Fits computed elsewhere ([`Suggester::set_fitted`]: the browser's helper workers), by
    /// family (in `starts` order), and the noise model's ([`Suggester::set_noise_fit`]).
    fitted: Vec<Option<Fit>>,
    noise_fit: Option<Fit>,
    /// The family classifier's classes for the photo ([`classify`]), and its nearest family
    /// (the first of `order`, when it knows it): what [`RENDER_NULL_MARGIN`] compares the first
    /// candidate's render with.
    classes: Vec<(Class, f64)>,
    nearest_family: Option<PatternKind>,
    /// The nearest family's fit made for [`NEARER_RENDER_MARGIN`], kept for a later ranking of
    /// the same refinement and for choosing that family
    /// ([`Suggester::take_nearest_first_round`]).
    nearest_first_round: std::sync::Arc<std::sync::Mutex<Option<rank::NearestFirstRound>>>,
    /// The photo's and the noise render's scatterings for [`NEARER_RENDER_MARGIN`] where
    /// computed elsewhere ([`Suggester::set_nearer_scatterings`]).
    nearer_scatterings: Option<rank::NearerScatterings>,
    /// The photo's own patch-to-patch distance ([`rank::self_distance`]), once computed.
    self_distance: std::sync::OnceLock<f32>,
    /// The reduced photo's fine deviation ([`crate::structure::grain::fine_deviation`]), what
    /// each fitted family's preview is grain matched to, once computed.
    grain_target: std::sync::OnceLock<f64>,
}

/// A candidate fitted on the reduced photo: its parameters, the texture distance of their
/// render to the photo, and the family classifier's classes for that render ([`classify`]):
/// `None` for a family after [`Suggester::render_ordered`]'s, which cannot come first, so its
/// render's classes decide nothing ([`RENDER_NULL_MARGIN`] reads the first candidate's) and
/// would cost a classification per thumbnail.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Fit {
    pub params: Params,
    pub distance: f32,
    pub render_classes: Option<Vec<(Class, f64)>>,
}

/// A family's pattern after refinement (or its retrieved one), its refined distance (`None`:
/// not refined), and whether its tones pair reversed.
pub type Refined = (Pattern, Option<f32>, bool);

impl Suggester {
    /// Describes the photo (reduced to [`RANK_SIZE`]) and retrieves each family's best entry.
    pub fn new(db: &Db, photo: &Photo, opts: &Options, refinement: Refinement) -> Suggester {
        let reduced = photo.reduced(RANK_SIZE);
        let unreduced = reduced.is_none();
        let small = reduced.unwrap_or_else(|| photo.clone());
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
        let start_results = starts.iter().map(|v| vec![None; v.len()]).collect();
        let fitted = vec![None; refined.len()];
        let index = |k: PatternKind| starts.iter().position(|v| v[0].pattern.kind == k);
        let cues = crate::cues::cues(&small);
        let classes = class_distances(&q, &cues);
        let mut class_distance = vec![f64::INFINITY; starts.len()];
        let mut order = Vec::new();
        for (kind, distance) in classes.iter().filter_map(|&(c, d)| Some((c?, d))) {
            if let Some(i) = index(kind) {
                class_distance[i] = distance;
                order.push(i);
            }
        }
        let nearest_family = order.first().map(|&i| starts[i][0].pattern.kind);
        let unknown: Vec<usize> = (0..starts.len()).filter(|i| !order.contains(i)).collect();
        order.extend(unknown);
        Suggester {
            order,
            class_distance,
            // The same value as `cues::dark_skewness` (tested there).
            dark_network: cues[crate::cues::SKEWNESS] < DARK_NETWORK_SKEWNESS,
            unreduced,
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
            start_results,
            fitted,
            noise_fit: None,
            classes,
            nearest_family,
            nearest_first_round: Default::default(),
            nearer_scatterings: None,
            self_distance: std::sync::OnceLock::new(),
            grain_target: std::sync::OnceLock::new(),
        }
    }

    /// Families that are refined ([`Suggester::pending`]).
    pub fn steps(&self) -> usize {
        self.refine_order().len()
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

    /// The families that are refined (in `starts` order): the classifier's first
    /// [`RENDER_ORDERED`] ([`crate::family_classifier`]), whose fits order the list; at most
    /// [`Refinement::families`].
    ///
    /// Ours, not Bourque & Dudek's (who refine every shader of their catalogue's best matches):
    /// the other families follow in the classifier's order whatever their structure distance,
    /// so refining them could change their rows' scores, not the list's order; refinement is
    /// most of an analysis' time.
    fn refine_order(&self) -> &[usize] {
        let n = RENDER_ORDERED
            .min(self.order.len())
            .min(self.refinement.families);
        &self.order[..n]
    }

    /// The families still to refine, in `starts` indices (empty: the refinement is complete):
    /// those of [`Suggester::refine_order`] not refined yet, in its order. The same
    /// whatever the order in which they were refined (here or by the browser's helper workers).
    pub fn pending(&self) -> Vec<usize> {
        self.refine_order()
            .iter()
            .copied()
            .filter(|&i| !self.is_refined[i])
            .collect()
    }

    /// Stores family `i`'s refinement, computed by [`Suggester::refine_family`] here or on
    /// another `Suggester` built from the same photo, options and database (the browser's
    /// helper workers): the result is the same wherever and in whatever order it ran.
    pub fn set_refined(&mut self, i: usize, r: Refined) {
        if i < self.starts.len() {
            self.refined[i] = r;
            self.is_refined[i] = true;
            self.fitted[i] = None;
        }
    }

    /// Family `i`'s refinement (or its retrieved pattern, not refined), in `starts` order.
    pub fn refined(&self, i: usize) -> &Refined {
        &self.refined[i]
    }

    /// Refinement evaluations in all (for progress bars).
    pub fn evaluations(&self) -> usize {
        self.steps() * self.refinement.evaluations
    }

    /// The refinement of family `i` (in retrieval order): each start refined with its share
    /// of the evaluations ([`Suggester::refine_start`]), the best kept
    /// ([`best_of_starts`]). `step(done, budget)` counts over all starts; once it stops one,
    /// the later starts do not run.
    pub fn refine_family(
        &self,
        db: &Db,
        i: usize,
        step: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Refined {
        let budget = self.refinement.evaluations;
        let mut results = Vec::with_capacity(self.starts[i].len());
        let mut offset = 0;
        for k in 0..self.starts[i].len() {
            let mut stopped = false;
            let (r, used) = self.refine_start_counted(db, i, k, &mut |done, _| {
                let go = step(offset + done, budget);
                stopped |= !go;
                go
            });
            offset += used;
            results.push(r);
            if stopped {
                break;
            }
        }
        best_of_starts(&results)
    }

    /// Start `k` of family `i`'s refinement alone, with its share of the family's evaluations:
    /// the starts are independent, so they can run in parallel (natively, and in the browser's
    /// helper workers) and be stored one by one ([`Suggester::set_refined_start`]), which gives
    /// the family's refinement bit for bit. With three families refined on two threads, a
    /// family per task left one thread idle for a family's refinement.
    pub fn refine_start(
        &self,
        db: &Db,
        i: usize,
        k: usize,
        step: &mut dyn FnMut(usize, usize) -> bool,
    ) -> Refined {
        self.refine_start_counted(db, i, k, step).0
    }

    /// [`Suggester::refine_start`] and the evaluations it spent.
    fn refine_start_counted(
        &self,
        db: &Db,
        i: usize,
        k: usize,
        step: &mut dyn FnMut(usize, usize) -> bool,
    ) -> (Refined, usize) {
        let m = &self.starts[i][k];
        let share = self.refinement.evaluations / self.starts[i].len();
        let qm = if m.swapped {
            self.q.swapped()
        } else {
            self.q.clone()
        };
        let r = refine(db, &qm, &m.pattern, share, db_tile(), step);
        ((r.pattern, Some(r.distance), m.swapped), r.evaluations)
    }

    /// The starts still to refine, as (family, start) pairs in `starts` order: every start of
    /// each family that [`Suggester::pending`] lists, less those stored already.
    pub fn pending_starts(&self) -> Vec<(usize, usize)> {
        self.pending()
            .into_iter()
            .flat_map(|i| {
                let stored = &self.start_results[i];
                (0..stored.len())
                    .filter(|&k| stored[k].is_none())
                    .map(move |k| (i, k))
            })
            .collect()
    }

    /// Stores start `k` of family `i` ([`Suggester::refine_start`], here or on another
    /// `Suggester` built from the same photo, options and database); with its last start in,
    /// the family is refined ([`best_of_starts`] in start order, whatever the order in which
    /// they came).
    pub fn set_refined_start(&mut self, i: usize, k: usize, r: Refined) {
        let Some(slot) = self.start_results.get_mut(i).and_then(|v| v.get_mut(k)) else {
            return;
        };
        *slot = Some(r);
        if self.start_results[i].iter().all(Option::is_some) {
            self.settle_family(i);
        }
    }

    /// Ends a refinement that stopped early (Cancel, or its time budget): each family with
    /// some of its starts stored but not all is refined by the best of those.
    pub fn settle_partial_starts(&mut self) {
        for i in 0..self.start_results.len() {
            if !self.is_refined[i] && self.start_results[i].iter().any(Option::is_some) {
                self.settle_family(i);
            }
        }
    }

    fn settle_family(&mut self, i: usize) {
        let stored: Vec<Refined> = self.start_results[i].iter().flatten().cloned().collect();
        self.set_refined(i, best_of_starts(&stored));
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
}

/// The best of a family's refined starts, in start order: a later start replaces an earlier
/// one only where strictly nearer.
fn best_of_starts(results: &[Refined]) -> Refined {
    let mut best: Option<&Refined> = None;
    for r in results {
        if best.is_none_or(|b| b.1.is_some_and(|d| r.1.is_some_and(|e| e < d))) {
            best = Some(r);
        }
    }
    best.expect("every family has a start").clone()
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

/// The analysis of an analysis-size photo with the chosen model: the noise model, or the
/// pattern fitted at full size. Also returns the ranked suggestions (empty unless `Auto` or a
/// family was asked for; the families fitted as `refinement.fitted` says).
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
    let asked = match choice {
        ModelChoice::Kind(k) => Some(k),
        _ => None,
    };
    let (mut suggestions, unreduced) = rank_keeping_noise(
        db,
        photo,
        opts,
        refinement,
        refinement.fitted,
        asked,
        progress,
    );
    if choice == ModelChoice::Auto {
        let analysis = adopt::first_speck_clean(db, photo, opts, &mut suggestions, unreduced);
        return (analysis, suggestions);
    }
    let pick = suggestions.iter().find(|s| match choice {
        ModelChoice::Auto => true,
        ModelChoice::Kind(k) => s.name == k.name(),
        ModelChoice::Noise => s.pattern.is_none(),
    });
    let analysis = match pick.and_then(|s| s.pattern.as_ref()) {
        Some((p, swapped)) => match unreduced.family {
            Some(kept) if kept.pattern == *p && kept.swapped == *swapped => kept.round.complete(db),
            _ => fit_structured(db, photo, p, opts, *swapped),
        },
        None => unreduced
            .noise
            .unwrap_or_else(|| analyze_prepared(photo, opts)),
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
