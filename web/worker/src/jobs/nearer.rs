//! The nearer-render rule's fit in tasks (`proctex::retrieve::NEARER_RENDER_MARGIN`): where the
//! ranking will compare the classifier's nearest family's render with the noise model's, the
//! first round of that family's final fit runs before the ranking, in the final fit's tasks
//! shared with the helper workers, and a helper scatters the photo and the noise model's render
//! meanwhile; the ranking then only renders and scatters the family. On one thread the ranking
//! did all of it (the first round, its tone renders and three scatterings): natively 0.73 s of
//! the gravel sample's top-left crop's 0.20 s ranking without it.

use proctex::db::Db;
use proctex::params::Params;

use super::SuggestJob;
use crate::final_fit_job::{FinalFitJob, pattern_json};

impl SuggestJob {
    /// Begins the nearest family's first round in tasks where the ranking needs it
    /// (`Suggester::nearer_render_pattern`; the noise model's fit and those that order the
    /// list stored): the final fit's task calls ([`SuggestJob::fit_pending`],
    /// [`SuggestJob::fit_task`], [`SuggestJob::fit_tone`] and their setters) run it, on the
    /// ranking's photo ([`SuggestJob::fit_on_ranking_photo`]), and
    /// [`SuggestJob::finish_nearer`] hands it to the ranking. Returns its pattern as the final
    /// fit's tasks name it (for the helpers), or `None` where the ranking needs none.
    /// The pattern [`SuggestJob::begin_nearer`] would begin, as the final fit's tasks name it,
    /// without beginning it (what the helpers build their own fit of meanwhile); `None` where
    /// the ranking needs none.
    pub fn nearer_pattern(&self, db: &Db) -> Option<String> {
        let (pattern, swapped) = self.suggester.nearer_render_pattern(db)?;
        Some(pattern_json(&pattern, swapped))
    }

    pub fn begin_nearer(&mut self, db: &Db) -> Option<String> {
        let (pattern, swapped) = self.suggester.nearer_render_pattern(db)?;
        let photo = self.suggester.ranking_photo();
        let job = FinalFitJob::first_round(db, photo, &self.opts, &pattern, swapped);
        let json = job.pattern_json().to_string();
        self.final_fit = Some(job);
        self.nearer = Some((pattern, swapped));
        Some(json)
    }

    /// Whether the tasks begun are the nearer-render rule's first round
    /// ([`SuggestJob::begin_nearer`]), which runs on the ranking's photo (a helper fits and
    /// renders them on its own copy of it), not the analysis-size photo.
    pub fn fit_on_ranking_photo(&self) -> bool {
        self.nearer.is_some()
    }

    /// The noise model's fitted params as JSON once stored ([`SuggestJob::fit_noise`]): what a
    /// helper renders and scatters ([`crate::jobs::Refiner::nearer_scatterings`]).
    pub fn noise_params(&self) -> Option<String> {
        let fit = self.suggester.stored_noise_fit()?;
        Some(serde_json::to_string(&fit.params).expect("params serialise"))
    }

    /// Stores the photo's and the noise model's render's scatterings from a helper
    /// ([`crate::jobs::Refiner::nearer_scatterings`] for `noise_json`, the params of
    /// [`SuggestJob::noise_params`]).
    pub fn set_nearer_scatterings(
        &mut self,
        noise_json: &str,
        photo: &[f64],
        noise: &[f64],
    ) -> Result<(), serde_json::Error> {
        let params: Params = serde_json::from_str(noise_json)?;
        self.suggester
            .set_nearer_scatterings(params, photo.to_vec(), noise.to_vec());
        Ok(())
    }

    /// Hands the first round begun by [`SuggestJob::begin_nearer`] to the ranking once every
    /// task is stored; an error before, or without one begun.
    pub fn finish_nearer(&mut self) -> proctex::error::Result<()> {
        let unfinished = || {
            proctex::error::Error::Option(
                "the nearer render's fit is not begun (begin_nearer) or not every task is stored"
                    .into(),
            )
        };
        if self.nearer.is_none()
            || self
                .final_fit
                .as_mut()
                .is_none_or(|f| !f.pending().is_empty())
        {
            return Err(unfinished());
        }
        let (pattern, swapped) = self.nearer.take().ok_or_else(unfinished)?;
        let job = self.final_fit.take().ok_or_else(unfinished)?;
        let (round, analysis) = job.into_first_round().ok_or_else(unfinished)?;
        self.suggester
            .set_nearest_first_round(pattern, swapped, round, analysis.params);
        Ok(())
    }
}
