//! The app's report of the photo's analysis as this job's noise model, and the automatic
//! choice's fall-back over a first family whose render is speckier than the photo
//! (`proctex::retrieve::SPECK_CLEAN_ROWS`), which the page's worker runs row by row in tasks.

use proctex::analyze::analyze_prepared;
use proctex::db::Db;
use proctex::params::{Model, Params};
use proctex::retrieve::SPECK_CLEAN_ROWS;
use proctex::specks::{speck_fraction, within_speck_limit};

use super::{SuggestJob, SuggestionRow};

impl SuggestJob {
    /// The params of `report_json` (an [`super::analyze_rgba`] report) where it is this job's
    /// analysis (the same photo, crop, analysis size, seed and lighting), less what
    /// [`proctex::analyze::analyze_photo_with`] stamps on them: their source, and their world
    /// scale, set back to one texel a pixel and returned beside them (1 where the analysed photo
    /// is the crop unreduced). `None` for another photo's, crop's, seed's or lighting's report.
    fn reported_analysis(
        &self,
        report_json: &str,
    ) -> Result<Option<(Params, f32)>, serde_json::Error> {
        #[derive(serde::Deserialize)]
        struct ReportParams {
            params: Params,
        }
        let mut params = serde_json::from_str::<ReportParams>(report_json)?.params;
        let same_photo = params.source.as_ref().is_some_and(|s| {
            (s.width, s.height, s.crop) == (self.width, self.height, self.crop)
                && (s.analysis_width, s.analysis_height)
                    == (self.prepared.width, self.prepared.height)
                && s.flattened_lighting == self.opts.flatten_lighting
        }) && params.seed == self.opts.seed;
        if !same_photo {
            return Ok(None);
        }
        let scale = params.transform.scale;
        params.transform.scale = 1.0;
        params.source = None;
        Ok(Some((params, scale)))
    }

    /// Stores the ranking's noise fit from `report_json`, the [`super::analyze_rgba`] report of
    /// this job's crop and seed, where the ranking works on the analysed photo as it is (the
    /// report's world scale 1): its params less what `analyze_photo_with` stamps on them are the
    /// analysis [`SuggestJob::fit_noise`] would run again. Returns whether it was stored
    /// (`false`: a photo that the ranking reduces, or a report of another photo, crop or seed;
    /// [`SuggestJob::fit_noise`] fits it then).
    pub fn set_noise_analysis(
        &mut self,
        db: &Db,
        report_json: &str,
    ) -> Result<bool, serde_json::Error> {
        Ok(match self.reported_analysis(report_json)? {
            Some((params, 1.0)) => self.suggester.set_noise_analysis(db, params),
            _ => false,
        })
    }

    /// How many of the ranked rows the automatic choice may adopt in place of a first family
    /// whose render is over the speck limit (the top three, fewer in a shorter list).
    pub fn speck_clean_rows(&self) -> usize {
        SPECK_CLEAN_ROWS.min(self.ranked.len())
    }

    /// Moves ranked row `i` to the front, the rows before it marked
    /// [`proctex::retrieve::Suggestion::speckier`]: the automatic choice adopts it in their
    /// place (`retrieve::SPECK_CLEAN_ROWS`), as the native analysis orders its list. Returns the
    /// rows as the UI shows them.
    pub fn promote(&mut self, i: usize) -> Vec<SuggestionRow> {
        if i < self.ranked.len() {
            for s in &mut self.ranked[..i] {
                s.speckier = true;
            }
            self.ranked[..=i].rotate_right(1);
        }
        (0..self.ranked.len()).map(|i| self.row(i)).collect()
    }

    /// Whether the final fit begun by [`SuggestJob::begin_fit`] renders within the speck limit
    /// once every task is stored (`FirstRound::complete_checked`'s flag); `None` before.
    pub fn fit_speck_clean(&self) -> Option<bool> {
        self.final_fit.as_ref()?.speck_clean()
    }

    /// Whether the noise model's analysis of this photo renders within the speck limit (what
    /// the automatic choice checks where a family's row is passed over for it): `report_json`'s
    /// params where it is this job's noise analysis, else the noise model fitted here.
    pub fn noise_speck_clean(&self, report_json: Option<&str>) -> bool {
        let reported = report_json
            .and_then(|j| self.reported_analysis(j).ok().flatten())
            .map(|(params, _)| params)
            .filter(|p| matches!(p.model, Model::Noise(_)));
        let params =
            reported.unwrap_or_else(|| analyze_prepared(&self.prepared, &self.opts).params);
        within_speck_limit(&self.prepared, &params, speck_fraction(&self.prepared))
    }
}
