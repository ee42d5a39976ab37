//! The adopted model's final fit (step 6 of `proctex::structure::fit_structured`) in tasks,
//! shared by the analysis worker and its helper workers: the helpers sit idle once the
//! refinement is done, and step 6 is the largest piece of the worker's path to its answer
//! after it (about 2 s natively on one thread for the brick sample, twice that in wasm).

use proctex::analyze::{Analysis, Options};
use proctex::db::Db;
use proctex::input::Photo;
use proctex::params::Params;
use proctex::pattern::Pattern;
use proctex::structure::{FinalFit, FirstRound, Scored};
use serde::{Deserialize, Serialize};

/// Step 6 of one pattern on one photo, task by task: tasks `0..A` are the first round (each
/// residual amplitude of the refined pattern), tasks `A..A+V` the second (each rougher variant
/// at the amplitude the first round chose), tasks `A+V..A+V+T` the third (the renders that the
/// best fit's output tone curve pools, [`FinalFit::tone_render`]; listed again for the next
/// fit by score where a whole fit's finished render is over the speck limit,
/// [`FinalFit::finish_whole`]). A task's result is the same wherever it ran ([`run_task`] on a
/// [`FinalFit`] built from the same photo, options and pattern; [`FitHelper::tone`]), so each
/// is stored as it comes back, in any order.
#[derive(Debug)]
pub struct FinalFitJob {
    fit: FinalFit,
    /// The pattern and its tone swap as JSON: what a helper builds its own [`FinalFit`] from.
    pattern_json: String,
    first: Vec<Option<Scored>>,
    chosen: Option<usize>,
    rest: Vec<Option<Scored>>,
    /// The scored fits' order of trial once both rounds are stored ([`FinalFit::order`]) and
    /// the one tried now: a whole fit tries them until one renders speck clean
    /// ([`FinalFit::finish_whole`]).
    order: Vec<usize>,
    attempt: usize,
    /// The fit tried now (the best of both rounds first), and its tone renders.
    best: Option<Analysis>,
    tone: Vec<Option<Vec<[f32; 3]>>>,
    /// A whole fit's first finished trial (kept where none is speck clean) and its result.
    first_tried: Option<Analysis>,
    done: Option<Analysis>,
    /// Whether the trials found the fit `done` speck clean (`None`: step 6 had fewer than two
    /// fits to try, so nothing was checked; [`FinalFitJob::speck_clean`] checks then).
    tried_clean: Option<bool>,
    /// Whether the fit ends with its grain matched ([`FinalFit::match_grain`]): a whole final
    /// fit does, the first round alone ([`FinalFitJob::first_round`]) does not.
    whole: bool,
}

impl FinalFitJob {
    /// Fits `pattern` (its scale in texels of `photo`, the analysis-size photo) up to its
    /// tasks.
    pub fn new(db: &Db, photo: &Photo, opts: &Options, pattern: &Pattern, swapped: bool) -> Self {
        let fit = FinalFit::new(db, photo, pattern, opts, swapped);
        let variants = fit.variants();
        Self::of(fit, pattern_json(pattern, swapped), variants, true)
    }

    /// The first round only, and the tone renders of its best: [`FirstRound::amplitude_fit`]
    /// in tasks ([`FinalFitJob::into_first_round`] gives both once every task is stored).
    pub fn first_round(
        db: &Db,
        photo: &Photo,
        opts: &Options,
        pattern: &Pattern,
        swapped: bool,
    ) -> Self {
        let fit = FinalFit::new(db, photo, pattern, opts, swapped);
        Self::of(fit, pattern_json(pattern, swapped), 0, false)
    }

    /// The rest of the final fit from its first round (run here or elsewhere: the ranking's
    /// [`FirstRound`] of the same pattern on the same photo): its tasks are the second round's
    /// and the tone renders', and it finishes as [`FinalFitJob::new`]'s fit does, bit for bit.
    pub fn from_first_round(round: FirstRound, pattern: &Pattern, swapped: bool) -> Self {
        let (fit, first) = round.into_parts();
        let variants = fit.variants();
        let mut job = Self::of(fit, pattern_json(pattern, swapped), variants, true);
        job.first = first.into_iter().map(Some).collect();
        job
    }

    fn of(fit: FinalFit, pattern_json: String, variants: usize, whole: bool) -> Self {
        FinalFitJob {
            pattern_json,
            first: vec![None; fit.amplitudes()],
            chosen: None,
            rest: vec![None; variants],
            order: Vec::new(),
            attempt: 0,
            best: None,
            tone: Vec::new(),
            first_tried: None,
            done: None,
            tried_clean: None,
            whole,
            fit,
        }
    }

    /// A [`FinalFitJob::first_round`] once every task is stored: the round and its best
    /// amplitude with its tone curve ([`FirstRound::amplitude_fit`]); `None` before, or for a
    /// whole final fit (its tasks past the first round).
    pub fn into_first_round(self) -> Option<(FirstRound, Analysis)> {
        if self.whole {
            return None;
        }
        let analysis = self.finish()?;
        let first: Option<Vec<Scored>> = self.first.into_iter().collect();
        Some((FirstRound::from_scored(self.fit, first?)?, analysis))
    }

    /// The pattern and tone swap as JSON (for [`FitHelper::run`]).
    pub fn pattern_json(&self) -> &str {
        &self.pattern_json
    }

    /// The tasks of the current round not stored yet (empty: every task is done, and
    /// [`FinalFitJob::finish`] gives the fit). The second round starts once the first is
    /// stored whole: its amplitude is chosen then. The third round's tone tasks may be listed
    /// again, for another fit: a whole fit whose finished render is over the speck limit tries
    /// the next by score ([`FinalFit::finish_whole`]; [`FinalFitJob::best_params_json`] then
    /// gives that fit's params).
    pub fn pending(&mut self) -> Vec<usize> {
        let a = self.first.len();
        let first: Vec<usize> = (0..a).filter(|&t| self.first[t].is_none()).collect();
        if !first.is_empty() {
            return first;
        }
        if self.chosen.is_none() && !self.rest.is_empty() {
            let scored: Vec<Scored> = self.first.iter().flatten().cloned().collect();
            self.chosen = Some(self.fit.chosen(&scored));
        }
        let rest: Vec<usize> = (0..self.rest.len())
            .filter(|&k| self.rest[k].is_none())
            .map(|k| a + k)
            .collect();
        if !rest.is_empty() {
            return rest;
        }
        if self.best.is_none() {
            self.order = self.fit.order(&self.scored());
            self.attempt = 0;
            self.try_next();
        }
        loop {
            let s = self.scored_tasks();
            let tone: Vec<usize> = (0..self.tone.len())
                .filter(|&k| self.tone[k].is_none())
                .map(|k| s + k)
                .collect();
            if !tone.is_empty() || !self.whole || self.done.is_some() {
                return tone;
            }
            // Every tone render of the fit tried now is stored: it is finished and checked.
            let Some(a) = self.finish_tried() else {
                return tone;
            };
            if !self.fit.tries(self.order.len()) {
                self.done = Some(a);
                return Vec::new();
            }
            if self.fit.speck_clean(&a) {
                self.done = Some(a);
                self.tried_clean = Some(true);
                return Vec::new();
            }
            self.first_tried.get_or_insert(a);
            self.attempt += 1;
            if self.attempt >= self.order.len() {
                self.done = self.first_tried.take();
                self.tried_clean = Some(false);
                return Vec::new();
            }
            self.try_next();
        }
    }

    /// Both rounds' stored fits, in task order.
    fn scored(&self) -> Vec<Scored> {
        self.first
            .iter()
            .chain(&self.rest)
            .flatten()
            .cloned()
            .collect()
    }

    /// Makes the fit of trial [`FinalFitJob::attempt`] the one tried now and lists its tone
    /// renders (the base where nothing was scored).
    fn try_next(&mut self) {
        let stored = |i: usize| {
            let s = self.first.iter().chain(&self.rest).nth(i)?.as_ref()?;
            Some(s.analysis.clone())
        };
        let best = match self.order.get(self.attempt).and_then(|&i| stored(i)) {
            Some(a) => a,
            None => self.fit.best(None),
        };
        self.tone = vec![None; self.fit.tone_renders(&best) as usize];
        self.best = Some(best);
    }

    /// The fit tried now with its output tone curve and, for a whole fit, its grain matched;
    /// `None` until its tone renders are stored.
    fn finish_tried(&self) -> Option<Analysis> {
        let best = self.best.as_ref()?;
        let renders: Option<Vec<_>> = self.tone.iter().cloned().collect();
        let mut a = self.fit.finish_with(best.clone(), renders?);
        if self.whole {
            self.fit.match_grain(&mut a);
        }
        Some(a)
    }

    /// Tasks of the first two rounds (scored fits, JSON); the tone renders' tasks follow.
    pub fn scored_tasks(&self) -> usize {
        self.first.len() + self.rest.len()
    }

    /// The params of the fit tried now (the best first) as JSON once the third round is listed
    /// (for [`FitHelper::tone`]).
    pub fn best_params_json(&self) -> Option<String> {
        let best = self.best.as_ref()?;
        Some(serde_json::to_string(&best.params).expect("params serialise"))
    }

    /// Runs tone-render task `t` here (a third-round task): the render's RGB as flat `f32`s
    /// (for [`FinalFitJob::set_tone`]); `None` for another task or before the third round.
    pub fn run_tone(&self, t: usize) -> Option<Vec<f32>> {
        let k = t.checked_sub(self.scored_tasks())?;
        let best = self.best.as_ref()?;
        (k < self.tone.len()).then(|| flat(self.fit.tone_render(&best.params, k as u32)))
    }

    /// Stores tone-render task `t`'s render (flat RGB from [`FinalFitJob::run_tone`] or a
    /// helper's [`FitHelper::tone`]); false when it is not a listed tone task or has the wrong
    /// size.
    pub fn set_tone(&mut self, t: usize, rgb: &[f32]) -> bool {
        let Some(k) = t.checked_sub(self.scored_tasks()) else {
            return false;
        };
        let n = self.best.as_ref().map_or(0, |_| self.fit.pixels());
        match self.tone.get_mut(k) {
            Some(slot) if rgb.len() == 3 * n => {
                *slot = Some(rgb.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect());
                true
            }
            _ => false,
        }
    }

    /// The first round's choice, once [`FinalFitJob::pending`] has made it (the second
    /// round's tasks need it); 0 before.
    pub fn chosen(&self) -> usize {
        self.chosen.unwrap_or(0)
    }

    /// Runs scored task `t` (first or second round) here without storing it: its result as
    /// JSON (for [`FinalFitJob::set`]); `None` for another task.
    pub fn run(&self, db: &Db, t: usize) -> Option<String> {
        run_task(&self.fit, db, t, self.chosen()).map(|r| to_json(&r))
    }

    /// Stores task `t`'s result (JSON from [`FinalFitJob::run`] or a helper's
    /// [`FitHelper::run`]); a task out of range is ignored.
    pub fn set(&mut self, t: usize, json: &str) -> Result<(), serde_json::Error> {
        let r = from_json(json)?;
        let a = self.first.len();
        if t < a {
            self.first[t] = Some(r);
        } else if let Some(slot) = self.rest.get_mut(t - a) {
            *slot = Some(r);
        }
        Ok(())
    }

    /// Whether the whole fit's result renders within the speck limit, as
    /// `FirstRound::complete_checked` says (checked here where step 6 had nothing to try);
    /// `None` until [`FinalFitJob::finish`] gives it, or for a first round alone.
    pub fn speck_clean(&self) -> Option<bool> {
        let done = self.done.as_ref()?;
        Some(
            self.tried_clean
                .unwrap_or_else(|| self.fit.within_speck_limit(done)),
        )
    }

    /// The fit: the best stored task with its output tone curve (the base when there was
    /// nothing to choose), as [`FinalFit::finish`] gives it; for a whole final fit the first
    /// by score whose render keeps within the speck limit, its grain matched
    /// ([`FinalFit::finish_whole`]: `fit_structured`'s result, bit for bit). `None` until
    /// every task is stored and [`FinalFitJob::pending`] has come back empty.
    pub fn finish(&self) -> Option<Analysis> {
        if self.whole {
            self.done.clone()
        } else {
            self.finish_tried()
        }
    }
}

/// A render's pixels as flat RGB `f32`s (how a tone render travels between workers).
fn flat(pixels: Vec<[f32; 3]>) -> Vec<f32> {
    pixels.into_iter().flatten().collect()
}

/// A pattern and its tone swap as the final fit's tasks name them (JSON).
pub fn pattern_json(pattern: &Pattern, swapped: bool) -> String {
    serde_json::to_string(&(pattern, swapped)).expect("patterns serialise")
}

/// Scored task `t` of `fit` (numbered as [`FinalFitJob`] numbers them), the second round's
/// with the first round's `chosen` amplitude; `None` past the second round.
pub fn run_task(fit: &FinalFit, db: &Db, t: usize, chosen: usize) -> Option<Scored> {
    let a = fit.amplitudes();
    if t < a {
        Some(fit.amplitude(db, t))
    } else if t - a < fit.variants() && chosen < a {
        Some(fit.variant(db, t - a + 1, chosen))
    } else {
        None
    }
}

/// A helper worker's side of a [`FinalFitJob`]: its own [`FinalFit`] of the job's pattern on
/// the job's prepared photo (built on the first task, kept for the next ones).
#[derive(Debug)]
pub struct FitHelper {
    photo: Photo,
    opts: Options,
    fit: Option<(String, FinalFit)>,
}

impl FitHelper {
    /// A helper for the analysis-size `photo` analysed with `opts`.
    pub fn new(photo: Photo, opts: Options) -> FitHelper {
        FitHelper {
            photo,
            opts,
            fit: None,
        }
    }

    /// Builds the final fit of `pattern_json` ([`pattern_json`]) unless it is built already:
    /// while the job builds its own, so that the helper is ready for tasks when the job is.
    pub fn prepare(&mut self, db: &Db, pattern_json: &str) -> Result<&FinalFit, serde_json::Error> {
        if self.fit.as_ref().is_none_or(|(p, _)| p != pattern_json) {
            let (pattern, swapped): (Pattern, bool) = serde_json::from_str(pattern_json)?;
            let fit = FinalFit::new(db, &self.photo, &pattern, &self.opts, swapped);
            self.fit = Some((pattern_json.to_string(), fit));
        }
        Ok(&self.fit.as_ref().expect("built above").1)
    }

    /// Tone render `k` ([`FinalFitJob::run_tone`]'s task `scored_tasks + k`) of the best fit's
    /// params (`params_json`, [`FinalFitJob::best_params_json`]) at this helper's photo size,
    /// as flat RGB.
    pub fn tone(&self, params_json: &str, k: u32) -> Result<Vec<f32>, serde_json::Error> {
        let params: Params = serde_json::from_str(params_json)?;
        Ok(flat(proctex::structure::tone_render(
            &self.photo,
            &params,
            k,
        )))
    }

    /// Task `t` of the final fit of `pattern_json` ([`pattern_json`]) with the first round's
    /// `chosen` amplitude, as JSON (for [`FinalFitJob::set`]).
    pub fn run(
        &mut self,
        db: &Db,
        pattern_json: &str,
        t: usize,
        chosen: usize,
    ) -> Result<String, String> {
        let fit = self.prepare(db, pattern_json).map_err(|e| e.to_string())?;
        let r = run_task(fit, db, t, chosen).ok_or_else(|| format!("no scored task {t}"))?;
        Ok(to_json(&r))
    }
}

/// A scored fit as it travels between workers: its `f64`s as their bits (JSON's decimal
/// `f64`s need not parse back to the same bits), so that a task's result is the same wherever
/// it ran. The params' `f32`s round-trip through JSON exactly (as presets and refinements do).
#[derive(Serialize, Deserialize)]
struct Wire {
    score: u64,
    params: Params,
    band_powers: [Vec<u64>; 3],
    channel_variance: [u64; 3],
}

fn to_json(r: &Scored) -> String {
    let a = &r.analysis;
    let wire = Wire {
        score: r.score.to_bits(),
        params: a.params.clone(),
        band_powers: a
            .band_powers
            .clone()
            .map(|v| v.iter().map(|x| x.to_bits()).collect()),
        channel_variance: a.channel_variance.map(f64::to_bits),
    };
    serde_json::to_string(&wire).expect("params serialise")
}

fn from_json(json: &str) -> Result<Scored, serde_json::Error> {
    let w: Wire = serde_json::from_str(json)?;
    Ok(Scored {
        score: f64::from_bits(w.score),
        analysis: Analysis {
            params: w.params,
            band_powers: w
                .band_powers
                .map(|v| v.into_iter().map(f64::from_bits).collect()),
            channel_variance: w.channel_variance.map(f64::from_bits),
        },
    })
}
