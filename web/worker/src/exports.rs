//! The worker's wasm-bindgen exports (what `www/worker.js` and `www/refiner.js` call): each
//! wraps a [`crate::jobs`] function, takes and returns plain values or JSON, and throws the
//! error's message. Compiled only into the worker's module (feature `exports`), so that the
//! UI's module, which uses this crate for the jobs' message types, does not carry them.

use wasm_bindgen::prelude::*;

use crate::jobs;
use proctex::params::Params;

mod synthesis;

/// Worker job: analyses `crop` (`[x, y, w, h]` photo pixels, or empty for all) of an RGBA image
/// at `seed`, its lighting gradient divided out where `flatten_lighting` says, and returns the
/// report (params and plot statistics) as JSON; throws the error's message.
#[wasm_bindgen(js_name = analyzeRgba)]
pub fn analyze_rgba(
    rgba: &[u8],
    width: u32,
    height: u32,
    crop: Vec<u32>,
    seed: u32,
    flatten_lighting: bool,
) -> Result<String, JsValue> {
    let crop = parse_crop(&crop)?;
    let report =
        jobs::analyze_rgba(rgba, width, height, crop, seed, flatten_lighting).map_err(js_error)?;
    serde_json::to_string(&report).map_err(js_error)
}

/// Worker job: the model's plot statistics for a params document, as JSON.
/// Throws when a photo file must not be decoded (too large, TIFF); see `jobs::check_photo_file`.
#[wasm_bindgen(js_name = checkPhotoFile)]
pub fn check_photo_file(bytes: &[u8]) -> Result<(), JsValue> {
    jobs::check_photo_file(bytes).map_err(|e| JsValue::from_str(&e))
}

/// Throws when a decoded photo is over the pixel limit; see `jobs::check_photo_size`.
#[wasm_bindgen(js_name = checkPhotoSize)]
pub fn check_photo_size(width: u32, height: u32) -> Result<(), JsValue> {
    jobs::check_photo_size(width as u64, height as u64).map_err(|e| JsValue::from_str(&e))
}

#[wasm_bindgen(js_name = modelStats)]
pub fn model_stats(params_json: String) -> Result<String, JsValue> {
    let p = Params::from_json(&params_json).map_err(js_error)?;
    serde_json::to_string(&jobs::model_stats(&p)).map_err(js_error)
}

/// Worker job: the CPU reference render of a params document as RGBA8 (the preview shown when
/// the browser has no WebGPU).
#[wasm_bindgen(js_name = previewRgba)]
pub fn preview_rgba(params_json: String, width: u32, height: u32) -> Result<Vec<u8>, JsValue> {
    let p = Params::from_json(&params_json).map_err(js_error)?;
    Ok(jobs::preview_rgba(&p, width.min(2048), height.min(2048)))
}

thread_local! {
    /// The pattern database the worker fetched (`loadDatabase`), for the worker's lifetime.
    static DATABASE: std::cell::Cell<Option<&'static proctex::db::Db>> =
        const { std::cell::Cell::new(None) };
}

fn database() -> Result<&'static proctex::db::Db, JsValue> {
    DATABASE.with(|d| d.get()).ok_or_else(|| {
        JsValue::from_str("the pattern database is not loaded: structured models are unavailable")
    })
}

/// Worker job: reads the pattern database file (`patterns.ptxdb`, fetched by the worker rather
/// than embedded in the wasm); returns its number of models; throws when the bytes are bad.
#[wasm_bindgen(js_name = loadDatabase)]
pub fn load_database(bytes: &[u8]) -> Result<usize, JsValue> {
    let db = proctex::db::Db::from_bytes(bytes).map_err(js_error)?;
    let n = db.entries.len();
    DATABASE.with(|d| d.set(Some(Box::leak(Box::new(db)))));
    Ok(n)
}

/// Worker job: the automatic model choice of a photo (or crop) in steps (see
/// `jobs::SuggestJob`): `new` retrieves, each `step` refines one family, `rank` ranks.
#[wasm_bindgen]
#[derive(Debug)]
pub struct Suggestions {
    job: jobs::SuggestJob,
}

#[wasm_bindgen]
impl Suggestions {
    /// Retrieval for `crop` (`[x, y, w, h]` or empty) of an RGBA image analysed as
    /// `analyzeRgba` does with the same arguments; throws the error's message (no database,
    /// bad crop).
    #[wasm_bindgen(constructor)]
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Vec<u32>,
        seed: u32,
        flatten_lighting: bool,
    ) -> Result<Suggestions, JsValue> {
        let crop = parse_crop(&crop)?;
        let db = database()?;
        let job = jobs::SuggestJob::new(db, rgba, width, height, crop, seed, flatten_lighting)
            .map_err(js_error)?;
        Ok(Suggestions { job })
    }

    /// Families refined so far.
    pub fn done(&self) -> usize {
        self.job.progress().0
    }

    /// Families that may be refined (an upper bound: the refinement's bound skips some).
    pub fn steps(&self) -> usize {
        self.job.progress().1
    }

    /// The starts of the current refinement round still to refine, as pairs (family, start)
    /// flattened (empty: the refinement is complete). Refine them (here or in helpers), store
    /// them, then ask again.
    #[wasm_bindgen(js_name = pendingStarts)]
    pub fn pending_starts(&self) -> Vec<u32> {
        flat_pairs(self.job.pending_starts())
    }

    /// Refines the next family; returns whether any remain.
    pub fn step(&mut self) -> Result<bool, JsValue> {
        Ok(self.job.step(database()?))
    }

    /// The analysis-size photo the job works on, RGB `f32` triples (for `Refiner`).
    #[wasm_bindgen(js_name = preparedPixels)]
    pub fn prepared_pixels(&self) -> Vec<f32> {
        self.job.prepared().0
    }

    /// Width and height of `preparedPixels`.
    #[wasm_bindgen(js_name = preparedSize)]
    pub fn prepared_size(&self) -> Vec<u32> {
        let (_, w, h) = self.job.prepared();
        vec![w, h]
    }

    /// Refines start `k` of family `i` here without storing it; returns the result as JSON
    /// for `setRefinedStart`.
    #[wasm_bindgen(js_name = refineStart)]
    pub fn refine_start(&self, i: usize, k: usize) -> Result<String, JsValue> {
        Ok(self.job.refine_start(database()?, i, k))
    }

    /// Stores start `k` of family `i` (JSON from `refineStart` here or a helper's `Refiner`);
    /// the family is refined with its last start in.
    #[wasm_bindgen(js_name = setRefinedStart)]
    pub fn set_refined_start(&mut self, i: usize, k: usize, json: &str) -> Result<(), JsValue> {
        self.job.set_refined_start(i, k, json).map_err(js_error)
    }

    /// Ends a refinement stopped early (Cancel, its time budget): each family with some of
    /// its starts in is refined by the best of those.
    #[wasm_bindgen(js_name = settlePartialStarts)]
    pub fn settle_partial_starts(&mut self) {
        self.job.settle_partial_starts();
    }

    /// The families whose fits order the list, once the refinement is complete: fit each
    /// (`orderFit` here or a helper's `Refiner.orderFit`), store it (`setOrderFit`), then
    /// `rank` uses them.
    #[wasm_bindgen(js_name = orderFits)]
    pub fn order_fits(&self) -> Vec<u32> {
        self.job
            .order_fits()
            .into_iter()
            .map(|i| i as u32)
            .collect()
    }

    /// Family `i`'s refinement as JSON, for a helper's `Refiner.orderFit`.
    #[wasm_bindgen(js_name = refinedOf)]
    pub fn refined_of(&self, i: usize) -> String {
        self.job.refined_of(i)
    }

    /// Fits family `i` here without storing it; its fit as JSON for `setOrderFit`.
    #[wasm_bindgen(js_name = orderFit)]
    pub fn order_fit(&self, i: usize) -> Result<String, JsValue> {
        Ok(self.job.order_fit(database()?, i))
    }

    /// Stores family `i`'s fit (JSON from `orderFit` here or a helper's `Refiner.orderFit`).
    #[wasm_bindgen(js_name = setOrderFit)]
    pub fn set_order_fit(&mut self, i: usize, json: &str) -> Result<(), JsValue> {
        self.job.set_order_fit(i, json).map_err(js_error)
    }

    /// Stores the noise model's fit for `rank` from `report` (`analyzeRgba`'s JSON of the
    /// same crop and seed) where that is the same analysis; returns whether it did (otherwise
    /// `fitNoise` fits it).
    #[wasm_bindgen(js_name = setNoiseAnalysis)]
    pub fn set_noise_analysis(&mut self, report: &str) -> Result<bool, JsValue> {
        self.job
            .set_noise_analysis(database()?, report)
            .map_err(js_error)
    }

    /// Fits the noise model for `rank` (while helpers fit families).
    #[wasm_bindgen(js_name = fitNoise)]
    pub fn fit_noise(&mut self) -> Result<(), JsValue> {
        self.job.fit_noise(database()?);
        Ok(())
    }

    /// Ranks the candidates (refined so far) and returns the rows as JSON.
    pub fn rank(&mut self) -> Result<String, JsValue> {
        let rows = self.job.rank(database()?);
        serde_json::to_string(&rows).map_err(js_error)
    }

    /// The ranked candidates' thumbnails, `THUMB_SIDE²` RGBA8 each, concatenated (a row not
    /// fitted yet is transparent).
    pub fn thumbnails(&self) -> Vec<u8> {
        self.job.thumbnails()
    }

    /// Fits the first ranked row not fitted yet; returns its index, or -1 when every row is
    /// fitted (then `row` and `thumbnail` give what changed).
    #[wasm_bindgen(js_name = fitNext)]
    pub fn fit_next(&mut self) -> Result<i32, JsValue> {
        Ok(self
            .job
            .fit_next(database()?)
            .map_or(-1, |i| i32::try_from(i).unwrap_or(-1)))
    }

    /// Ranked rows not fitted yet (`fitNext` fits them).
    pub fn unfitted(&self) -> usize {
        self.job.unfitted()
    }

    /// Ranked row `i` as JSON (as `rank` gives every row).
    pub fn row(&self, i: usize) -> Result<String, JsValue> {
        serde_json::to_string(&self.job.row(self.ranked_row(i)?)).map_err(js_error)
    }

    /// Ranked row `i`'s thumbnail, `THUMB_SIDE²` RGBA8.
    pub fn thumbnail(&self, i: usize) -> Result<Vec<u8>, JsValue> {
        Ok(self.job.thumbnail(self.ranked_row(i)?))
    }

    /// Ranked row `i`'s pattern as JSON for a helper's `Refiner.fitPrepare` ("" for the noise
    /// model).
    #[wasm_bindgen(js_name = rowPattern)]
    pub fn row_pattern(&self, i: usize) -> String {
        self.job.row_pattern(i).unwrap_or_default()
    }

    /// The pattern `beginNearer` would begin (empty: none needed), without beginning it: what
    /// the helpers prepare their own fit of (`Refiner.fitPrepare` on the ranking's photo) while
    /// `beginNearer` builds the job's.
    #[wasm_bindgen(js_name = nearerPattern)]
    pub fn nearer_pattern(&self) -> Result<String, JsValue> {
        Ok(self.job.nearer_pattern(database()?).unwrap_or_default())
    }

    /// Begins the nearer-render rule's first round in tasks where the ranking needs it (after
    /// `fitNoise` and the fits that order the list): run with the final fit's task calls
    /// (`fitPending` ...), then `finishNearer`, then `rank`. Returns its pattern for the
    /// helpers (empty: none needed; `rank` directly).
    #[wasm_bindgen(js_name = beginNearer)]
    pub fn begin_nearer(&mut self) -> Result<String, JsValue> {
        Ok(self.job.begin_nearer(database()?).unwrap_or_default())
    }

    /// Whether the tasks begun run on the ranking's photo (the nearer-render rule's first
    /// round): what a helper's `Refiner.fitPrepare`, `fitTask` and `fitTone` are told.
    #[wasm_bindgen(js_name = fitOnRankingPhoto)]
    pub fn fit_on_ranking_photo(&self) -> bool {
        self.job.fit_on_ranking_photo()
    }

    /// The noise model's fitted params as JSON once `fitNoise` stored them (empty before): what
    /// a helper's `Refiner.nearerScatterings` renders.
    #[wasm_bindgen(js_name = noiseParams)]
    pub fn noise_params(&self) -> String {
        self.job.noise_params().unwrap_or_default()
    }

    /// Stores a helper's `Refiner.nearerScatterings` of `noise` (`noiseParams`).
    #[wasm_bindgen(js_name = setNearerScatterings)]
    pub fn set_nearer_scatterings(&mut self, noise: &str, both: &[f64]) -> Result<(), JsValue> {
        if !both.len().is_multiple_of(2) {
            return Err(JsValue::from_str(
                "the scatterings: an odd number of features",
            ));
        }
        let (photo, render) = both.split_at(both.len() / 2);
        self.job
            .set_nearer_scatterings(noise, photo, render)
            .map_err(js_error)
    }

    /// Hands the nearer-render rule's first round to the ranking, every task stored.
    #[wasm_bindgen(js_name = finishNearer)]
    pub fn finish_nearer(&mut self) -> Result<(), JsValue> {
        self.job.finish_nearer().map_err(js_error)
    }

    /// Begins the final fit of ranked row `i` in tasks (`fitPending`, `fitTask` here or a
    /// helper's `Refiner.fitTask`, `setFitTask`, then `fitReport`: `report(i)`'s JSON); false
    /// for the noise model (no tasks: use `report`).
    #[wasm_bindgen(js_name = beginFit)]
    pub fn begin_fit(&mut self, i: usize) -> Result<bool, JsValue> {
        self.job.begin_fit(database()?, i).map_err(js_error)
    }

    /// The final fit's tasks of its current round not stored yet (empty: done). Run them
    /// (here or in helpers), store them, then ask again.
    #[wasm_bindgen(js_name = fitPending)]
    pub fn fit_pending(&mut self) -> Vec<u32> {
        self.job
            .fit_pending()
            .into_iter()
            .map(|t| t as u32)
            .collect()
    }

    /// The first round's chosen amplitude (valid once `fitPending` lists the second round).
    #[wasm_bindgen(js_name = fitChosen)]
    pub fn fit_chosen(&self) -> usize {
        self.job.fit_pattern().map_or(0, |(_, c)| c)
    }

    /// Runs final-fit task `t` here without storing it; its result as JSON for `setFitTask`.
    #[wasm_bindgen(js_name = fitTask)]
    pub fn fit_task(&self, t: usize) -> Result<String, JsValue> {
        self.job
            .fit_task(database()?, t)
            .ok_or_else(|| JsValue::from_str(&format!("no scored final-fit task {t}")))
    }

    /// The final fit's scored tasks (its first two rounds: `fitTask`); the tasks from this
    /// number on are tone renders (`fitTone`).
    #[wasm_bindgen(js_name = fitScoredTasks)]
    pub fn fit_scored_tasks(&self) -> usize {
        self.job.fit_scored_tasks()
    }

    /// The final fit's best params as JSON once its tone renders are listed (for a helper's
    /// `Refiner.fitTone`).
    #[wasm_bindgen(js_name = fitBestParams)]
    pub fn fit_best_params(&self) -> String {
        self.job.fit_best_params().unwrap_or_default()
    }

    /// Runs tone-render task `t` here: the render as flat RGB for `setFitTone`.
    #[wasm_bindgen(js_name = fitTone)]
    pub fn fit_tone(&self, t: usize) -> Result<Vec<f32>, JsValue> {
        self.job
            .fit_tone(t)
            .ok_or_else(|| JsValue::from_str(&format!("no tone render task {t}")))
    }

    /// Stores tone-render task `t` (flat RGB from `fitTone` or a helper's `Refiner.fitTone`).
    #[wasm_bindgen(js_name = setFitTone)]
    pub fn set_fit_tone(&mut self, t: usize, rgb: &[f32]) -> Result<(), JsValue> {
        if self.job.set_fit_tone(t, rgb) {
            Ok(())
        } else {
            Err(JsValue::from_str(&format!(
                "tone render task {t}: not listed, or the wrong size"
            )))
        }
    }

    /// Stores final-fit task `t`'s result (JSON from `fitTask` or a helper's `Refiner.fitTask`).
    #[wasm_bindgen(js_name = setFitTask)]
    pub fn set_fit_task(&mut self, t: usize, json: &str) -> Result<(), JsValue> {
        self.job.set_fit_task(t, json).map_err(js_error)
    }

    /// The report JSON of the final fit, every task stored.
    #[wasm_bindgen(js_name = fitReport)]
    pub fn fit_report(&self) -> Result<String, JsValue> {
        let r = self.job.fit_report().map_err(js_error)?;
        serde_json::to_string(&r).map_err(js_error)
    }

    /// How many rows the automatic choice may adopt in place of a first family whose render is
    /// over the speck limit (`retrieve::SPECK_CLEAN_ROWS`; fewer in a shorter list).
    #[wasm_bindgen(js_name = speckCleanRows)]
    pub fn speck_clean_rows(&self) -> usize {
        self.job.speck_clean_rows()
    }

    /// Whether the final fit (every task stored) renders within the speck limit; false before.
    #[wasm_bindgen(js_name = fitSpeckClean)]
    pub fn fit_speck_clean(&self) -> bool {
        self.job.fit_speck_clean().unwrap_or(false)
    }

    /// Whether the noise model's analysis renders within the speck limit: `report`'s
    /// (`analyzeRgba`'s JSON of this crop and seed; empty: none) where it is this job's, else the
    /// noise model fitted here.
    #[wasm_bindgen(js_name = noiseSpeckClean)]
    pub fn noise_speck_clean(&self, report: &str) -> bool {
        self.job
            .noise_speck_clean(Some(report).filter(|r| !r.is_empty()))
    }

    /// Moves ranked row `i` to the front (the automatic choice adopts it in place of the
    /// speckier rows before it) and returns the rows as JSON.
    pub fn promote(&mut self, i: usize) -> Result<String, JsValue> {
        serde_json::to_string(&self.job.promote(i)).map_err(js_error)
    }

    /// The report JSON of ranked candidate `i` fitted at analysis size.
    pub fn report(&self, i: usize) -> Result<String, JsValue> {
        let r = self.job.report(database()?, i).map_err(js_error)?;
        serde_json::to_string(&r).map_err(js_error)
    }
}

impl Suggestions {
    /// `i` when it is a ranked row, else the error JS sees.
    fn ranked_row(&self, i: usize) -> Result<usize, JsValue> {
        if i < self.job.rows() {
            Ok(i)
        } else {
            Err(JsValue::from_str(&format!("no suggestion {i}")))
        }
    }
}

/// (family, start) pairs flattened, for JavaScript.
fn flat_pairs(pairs: Vec<(usize, usize)>) -> Vec<u32> {
    pairs
        .into_iter()
        .flat_map(|(i, k)| [i as u32, k as u32])
        .collect()
}

/// The analysis-size photo of the `Suggestions` job that `new Suggestions(rgba, width, height,
/// crop, seed, flattenLighting)` would make (its `preparedPixels` and `preparedSize`), without its retrieval:
/// sent to the helpers while this worker fits the noise model. Throws as that job would on a
/// bad size or crop.
#[wasm_bindgen]
#[derive(Debug)]
pub struct SuggestionPhoto {
    pixels: Vec<f32>,
    width: u32,
    height: u32,
}

#[wasm_bindgen]
impl SuggestionPhoto {
    #[wasm_bindgen(constructor)]
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Vec<u32>,
        seed: u32,
        flatten_lighting: bool,
    ) -> Result<SuggestionPhoto, JsValue> {
        let crop = parse_crop(&crop)?;
        let (pixels, width, height) =
            jobs::suggestion_photo(rgba, width, height, crop, seed, flatten_lighting)
                .map_err(js_error)?;
        Ok(SuggestionPhoto {
            pixels,
            width,
            height,
        })
    }

    /// RGB `f32` triples (for `Refiner`).
    pub fn pixels(&self) -> Vec<f32> {
        self.pixels.clone()
    }

    /// Width and height of `pixels`.
    pub fn size(&self) -> Vec<u32> {
        vec![self.width, self.height]
    }
}

/// Helper-worker job: refines families of a `Suggestions` job of another worker, from that
/// job's `preparedPixels`, `preparedSize` and seed (the same retrieval, so the same results).
#[wasm_bindgen]
#[derive(Debug)]
pub struct Refiner {
    inner: jobs::Refiner,
}

#[wasm_bindgen]
impl Refiner {
    /// Retrieval for the prepared photo; throws when the database is not loaded or the pixels
    /// do not fit the size.
    #[wasm_bindgen(constructor)]
    pub fn new(rgb: &[f32], width: u32, height: u32, seed: u32) -> Result<Refiner, JsValue> {
        let inner = jobs::Refiner::new(database()?, rgb, width, height, seed).map_err(js_error)?;
        Ok(Refiner { inner })
    }

    /// The refinement's starts as `Suggestions.pendingStarts` lists them for a new job of the
    /// same photo: pairs (family, start) flattened.
    #[wasm_bindgen(js_name = pendingStarts)]
    pub fn pending_starts(&self) -> Vec<u32> {
        flat_pairs(self.inner.pending_starts())
    }

    /// Start `k` of family `i`'s refinement as JSON (for `Suggestions.setRefinedStart`).
    #[wasm_bindgen(js_name = refineStart)]
    pub fn refine_start(&self, i: usize, k: usize) -> Result<String, JsValue> {
        Ok(self.inner.refine_start(database()?, i, k))
    }

    /// Family `i`'s fit with `refined` (`Suggestions.refinedOf`) as its refinement, as JSON for
    /// `Suggestions.setOrderFit`.
    #[wasm_bindgen(js_name = orderFit)]
    pub fn order_fit(&mut self, i: usize, refined: &str) -> Result<String, JsValue> {
        self.inner
            .order_fit(database()?, i, refined)
            .map_err(js_error)
    }

    /// Builds the final fit of `pattern` (`Suggestions.rowPattern`, or `beginNearer`'s on the
    /// ranking's photo where `onRankingPhoto`: `Suggestions.fitOnRankingPhoto`) ahead of its
    /// tasks, while the analysis worker builds its own.
    #[wasm_bindgen(js_name = fitPrepare)]
    pub fn fit_prepare(&mut self, pattern: &str, on_ranking_photo: bool) -> Result<(), JsValue> {
        self.inner
            .fit_prepare(database()?, pattern, on_ranking_photo)
            .map_err(js_error)
    }

    /// Tone render `k` of the final fit's best params (`Suggestions.fitBestParams`), as flat RGB
    /// for `Suggestions.setFitTone` (task `fitScoredTasks() + k`).
    #[wasm_bindgen(js_name = fitTone)]
    pub fn fit_tone(
        &mut self,
        params: &str,
        k: u32,
        on_ranking_photo: bool,
    ) -> Result<Vec<f32>, JsValue> {
        self.inner
            .fit_tone(params, k, on_ranking_photo)
            .map_err(js_error)
    }

    /// Final-fit task `t` of `pattern` (`Suggestions.rowPattern`) with the first round's
    /// `chosen` amplitude (`Suggestions.fitChosen`), as JSON for `Suggestions.setFitTask`.
    #[wasm_bindgen(js_name = fitTask)]
    pub fn fit_task(
        &mut self,
        pattern: &str,
        t: usize,
        chosen: usize,
        on_ranking_photo: bool,
    ) -> Result<String, JsValue> {
        self.inner
            .fit_task(database()?, pattern, t, chosen, on_ranking_photo)
            .map_err(js_error)
    }

    /// The ranking photo's scatterings for the nearer-render rule: the photo's features, then
    /// those of the render of `noise` (`Suggestions.noiseParams`), one array (the two halves),
    /// for `Suggestions.setNearerScatterings`.
    #[wasm_bindgen(js_name = nearerScatterings)]
    pub fn nearer_scatterings(&self, noise: &str) -> Result<Vec<f64>, JsValue> {
        let (photo, render) = self.inner.nearer_scatterings(noise).map_err(js_error)?;
        Ok(photo.into_iter().chain(render).collect())
    }
}

/// Benchmark job (e2e/bench; the JS side times each call): one stage of model retrieval on an
/// RGBA image, as the worker's suggestion job runs it. `stage`: `"ffts"` (the descriptor's own
/// FFTs on a 128² map, the cost floor), `"descriptor"` (reduction to the ranking size,
/// two-tone structure map, descriptor), `"retrieval"` (all of that, then every family's best
/// database entries over rotations and tone swaps: `Suggestions`' constructor without the
/// crop). Returns a checksum.
#[wasm_bindgen(js_name = benchRetrieval)]
pub fn bench_retrieval(rgba: &[u8], width: u32, height: u32, stage: &str) -> Result<f64, JsValue> {
    use proctex::retrieve::{RANK_SIZE, Refinement, Suggester};
    let photo = proctex::input::Photo::from_rgba8(width, height, rgba).map_err(js_error)?;
    let small = photo.reduced(RANK_SIZE).unwrap_or_else(|| photo.clone());
    match stage {
        "ffts" => {
            // Any 128² map will do: the FFTs' cost does not depend on the values. The photo's
            // first channel, reduced (a cheap box average), stands in for the structure map.
            let plane: Vec<f32> = small.pixels.iter().map(|p| p[0]).collect();
            let map = proctex::gabor::descriptor_image(
                &plane,
                small.width as usize,
                small.height as usize,
            );
            Ok(proctex::gabor::fft_floor(&map) as f64)
        }
        "descriptor" => {
            let tt = proctex::two_tone::two_tone(&small);
            let (q, _) =
                proctex::db::query(&tt.structure, small.width as usize, small.height as usize);
            Ok(q.0.iter().sum::<f32>() as f64)
        }
        "retrieval" => {
            let opts = proctex::analyze::Options::default();
            let s = Suggester::new(database()?, &photo, &opts, Refinement::default());
            Ok(s.steps() as f64)
        }
        _ => Err(JsValue::from_str(
            "stage must be ffts, descriptor or retrieval",
        )),
    }
}

/// A crop from JS: `[x, y, w, h]`, or empty for the whole photo.
fn parse_crop(crop: &[u32]) -> Result<Option<[u32; 4]>, JsValue> {
    match crop {
        [] => Ok(None),
        [x, y, w, h] => Ok(Some([*x, *y, *w, *h])),
        _ => Err(JsValue::from_str("crop must be [x, y, w, h]")),
    }
}

fn js_error(e: impl std::fmt::Display) -> JsValue {
    JsValue::from_str(&e.to_string())
}
