//! The work the page's Web Worker does (see `www/worker.js`): analysing a photo (or a crop of
//! it), the automatic model choice in steps ([`SuggestJob`]), the model's statistics for the
//! plots, and the CPU preview for browsers without WebGPU.
//!
//! Plain Rust over the analyzer, with no browser types, so that native tests run it. The
//! worker calls it through the wasm-bindgen functions in `exports.rs`; results travel to the UI
//! thread as JSON.

use proctex::analyze::{
    Options, analyze_photo, analyze_photo_with, analyze_prepared, prepare_photo,
};
use proctex::db::Db;
use proctex::distance::radial_spectrum;
use proctex::image_header::{self, Format, Header};
use proctex::input::Photo;
use proctex::limits;
use proctex::params::Params;
use proctex::render::{View, render};
use proctex::retrieve::{Refinement, Suggester, Suggestion};
use proctex::structure::fit_structured;

use crate::final_fit_job::{FinalFitJob, FitHelper, pattern_json};
use serde::{Deserialize, Serialize};

/// How the page tells a user to go past the photo pixel limit.
pub(crate) const PAST_THE_LIMIT_IN_THE_PAGE: &str =
    "scale it down first (the proctex CLI can go past this with --max-pixels)";

/// Refuses a photo file before the browser decodes it: over [`limits::MAX_FILE_BYTES`], a TIFF
/// (browsers do not decode it), or a header that declares more than [`limits::MAX_PIXELS`]
/// pixels (a 1 MB PNG of 20000² would decode into 1.6 GB). Formats whose header is not read
/// here go to the browser's decoder, and their size is checked after it
/// ([`check_photo_size`]).
pub fn check_photo_file(bytes: &[u8]) -> Result<(), String> {
    limits::check_file_bytes(bytes.len() as u64).map_err(|e| e.to_string())?;
    match image_header::read(bytes) {
        Some(Header {
            format: Format::Tiff,
            ..
        }) => Err(
            "TIFF images cannot be opened in the browser; convert it to PNG or JPEG \
                   (the proctex CLI reads TIFF)"
                .into(),
        ),
        Some(Header {
            size: Some((w, h)), ..
        }) => check_photo_size(w, h),
        _ => Ok(()),
    }
}

/// Refuses a decoded photo of `width × height` over the photo limits.
pub fn check_photo_size(width: u64, height: u64) -> Result<(), String> {
    limits::check_pixels(
        "the photo",
        width,
        height,
        limits::MAX_PIXELS,
        PAST_THE_LIMIT_IN_THE_PAGE,
    )
    .map_err(|e| e.to_string())
}

/// Bins of the channel histograms in the plots.
pub const HIST_BINS: usize = 64;
/// Side of the CPU render the model statistics are measured on (texel resolution).
pub const STATS_SIZE: u32 = 256;

/// Statistics of an image for the plots: radially averaged luminance power and RGB histograms.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct ImageStats {
    /// Power per quarter-octave ring, finest first (see `distance::radial_spectrum`); ring `k`
    /// ends at `2^−(1 + k/4)` cycles per texel.
    pub spectrum: Vec<f64>,
    /// Per RGB channel, [`HIST_BINS`] densities over `[0, 1]` (each sums to 1).
    pub histograms: [Vec<f64>; 3],
}

/// What the worker sends back after an analysis.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Report {
    /// The analysed params.
    pub params: Params,
    /// The photo region as analysed (after reduction).
    pub photo: ImageStats,
    /// The analysed params rendered at texel resolution.
    pub model: ImageStats,
}

/// Statistics of a photo.
pub fn image_stats(p: &Photo) -> ImageStats {
    let mut histograms: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; HIST_BINS]);
    for px in &p.pixels {
        for c in 0..3 {
            let b = ((px[c].clamp(0.0, 1.0) * HIST_BINS as f32) as usize).min(HIST_BINS - 1);
            histograms[c][b] += 1.0;
        }
    }
    let n = p.pixels.len().max(1) as f64;
    for h in &mut histograms {
        h.iter_mut().for_each(|v| *v /= n);
    }
    ImageStats {
        spectrum: radial_spectrum(p),
        histograms,
    }
}

/// Statistics of the model: a `STATS_SIZE²` CPU render at one texel per pixel.
pub fn model_stats(params: &Params) -> ImageStats {
    let view = View {
        origin: [0.0, 0.0],
        pixel_size: params.transform.scale,
        z: 0.0,
    };
    image_stats(&render(params, STATS_SIZE, STATS_SIZE, &view).to_photo())
}

/// Analyses `crop` (photo pixels; `None`: all) of an RGBA image with the default options, the
/// given seed and, where `flatten_lighting` says, the photo's lighting gradient divided out
/// (`proctex analyze --flatten-lighting`). Only the crop is converted to floating point, so a
/// 12-megapixel photo with a small crop costs little more than the crop.
pub fn analyze_rgba(
    rgba: &[u8],
    width: u32,
    height: u32,
    crop: Option<[u32; 4]>,
    seed: u32,
    flatten_lighting: bool,
) -> proctex::error::Result<Report> {
    let photo = region(rgba, width, height, crop)?;
    let opts = suggestion_options(seed, flatten_lighting);
    let analysis = analyze_photo(&photo, &opts)?;
    report(&photo, &opts, analysis.params, width, height, crop)
}

/// The report of `params` analysed from `photo` (the crop region) of a `width × height` image.
fn report(
    photo: &Photo,
    opts: &Options,
    mut params: Params,
    width: u32,
    height: u32,
    crop: Option<[u32; 4]>,
) -> proctex::error::Result<Report> {
    if let Some(s) = params.source.as_mut() {
        s.width = width;
        s.height = height;
        s.crop = crop;
    }
    let reduced = photo.reduce_to(opts.size);
    Ok(Report {
        photo: image_stats(&reduced),
        model: model_stats(&params),
        params,
    })
}

/// The `crop` (photo pixels; `None`: all) of an RGBA image, checked, as a photo.
pub(crate) fn region(
    rgba: &[u8],
    width: u32,
    height: u32,
    crop: Option<[u32; 4]>,
) -> proctex::error::Result<Photo> {
    let expected = width as usize * height as usize * 4;
    if rgba.len() != expected {
        return Err(proctex::error::Error::Decode(format!(
            "expected {expected} bytes of RGBA for {width}×{height}, got {}",
            rgba.len()
        )));
    }
    let [x, y, w, h] = crop.unwrap_or([0, 0, width, height]);
    let inside = w > 0
        && h > 0
        && x.checked_add(w).is_some_and(|r| r <= width)
        && y.checked_add(h).is_some_and(|b| b <= height);
    if !inside {
        return Err(proctex::error::Error::Crop(format!(
            "{x},{y},{w},{h} reaches outside the {width}×{height} image"
        )));
    }
    let mut region = Vec::with_capacity(w as usize * h as usize * 4);
    for row in y..y + h {
        let start = (row as usize * width as usize + x as usize) * 4;
        region.extend_from_slice(&rgba[start..start + w as usize * 4]);
    }
    Photo::from_rgba8(w, h, &region)
}

/// Side of the suggestion thumbnails.
pub const THUMB_SIDE: u32 = 64;

/// One row of the suggestion list, as the UI shows it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SuggestionRow {
    /// "noise" or the pattern family.
    pub name: String,
    /// Ranking key (lower is nearer; see `retrieve::Suggester::suggestions`).
    pub score: f32,
    /// Texture distance of the fitted candidate to the photo (`None` until it is fitted: the
    /// ranking fits what decides its order first, the other rows follow).
    pub distance: Option<f32>,
    /// Structure distance after retrieval (patterns only).
    pub retrieval: Option<f32>,
    /// The same after refinement, when refined.
    pub refined: Option<f32>,
    /// Not refined because refining it could not have changed the fitted families that order
    /// the list (see `retrieve::Suggester::pending`).
    #[serde(default)]
    pub skipped: bool,
    /// One of the candidates whose fitted renders order the list (the others follow in the
    /// classifier's order; see `retrieve::Suggester::ranked`).
    #[serde(default)]
    pub render_ordered: bool,
    /// Passed over by the automatic choice: its render is speckier than the photo (past the
    /// speck limit) and a later row of the top three was not, which now comes first (see
    /// `retrieve::SPECK_CLEAN_ROWS`).
    #[serde(default)]
    pub speckier: bool,
}

/// The automatic model choice of one photo (or crop), run a family at a time so that the
/// worker stays responsive between steps (a new photo or Cancel stops it), then ranked, and
/// any suggestion fitted at analysis size on request.
pub struct SuggestJob {
    photo: Photo,
    /// The analysis-size photo the suggester works on (what helpers rebuild it from).
    prepared: Photo,
    opts: Options,
    width: u32,
    height: u32,
    crop: Option<[u32; 4]>,
    suggester: Suggester,
    ranked: Vec<Suggestion>,
    /// The final fit of a ranked row in tasks ([`SuggestJob::begin_fit`]), or the nearer-render
    /// rule's first round ([`SuggestJob::begin_nearer`]).
    final_fit: Option<FinalFitJob>,
    /// The pattern and tone pairing of the nearer-render rule's first round while `final_fit`
    /// is that.
    nearer: Option<(proctex::pattern::Pattern, bool)>,
}

impl std::fmt::Debug for SuggestJob {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SuggestJob")
            .field("done", &self.suggester.done())
            .field("steps", &self.suggester.steps())
            .finish_non_exhaustive()
    }
}

/// The options the worker analyses with (a photo's analysis and its suggestion job alike): the
/// defaults at `seed`, the lighting gradient divided out where `flatten_lighting` says.
fn suggestion_options(seed: u32, flatten_lighting: bool) -> Options {
    Options {
        seed,
        flatten_lighting,
        ..Options::default()
    }
}

/// RGB `f32` triples of `photo`, its width and height.
fn flat_photo(photo: &Photo) -> (Vec<f32>, u32, u32) {
    let px = photo.pixels.iter().flatten().copied().collect();
    (px, photo.width, photo.height)
}

/// The analysis-size photo that a [`SuggestJob`] of the same arguments works on
/// ([`SuggestJob::prepared`]), without the job's retrieval: what the helper workers rebuild
/// their [`Refiner`] from while the analysis worker still fits the noise model.
pub fn suggestion_photo(
    rgba: &[u8],
    width: u32,
    height: u32,
    crop: Option<[u32; 4]>,
    seed: u32,
    flatten_lighting: bool,
) -> proctex::error::Result<(Vec<f32>, u32, u32)> {
    let photo = region(rgba, width, height, crop)?;
    Ok(flat_photo(&prepare_photo(
        &photo,
        &suggestion_options(seed, flatten_lighting),
    )?))
}

impl SuggestJob {
    /// Retrieval for `crop` of an RGBA image (as [`analyze_rgba`] analyses it).
    pub fn new(
        db: &Db,
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Option<[u32; 4]>,
        seed: u32,
        flatten_lighting: bool,
    ) -> proctex::error::Result<SuggestJob> {
        let photo = region(rgba, width, height, crop)?;
        let opts = suggestion_options(seed, flatten_lighting);
        let reduced = prepare_photo(&photo, &opts)?;
        let suggester = Suggester::new(db, &reduced, &opts, Refinement::default());
        Ok(SuggestJob {
            photo,
            prepared: reduced,
            opts,
            width,
            height,
            crop,
            suggester,
            ranked: Vec::new(),
            final_fit: None,
            nearer: None,
        })
    }

    /// Families to refine in all, and refined so far.
    pub fn progress(&self) -> (usize, usize) {
        (self.suggester.done(), self.suggester.steps())
    }

    /// The starts of the current refinement round still to refine, as (family, start) pairs
    /// (empty: complete; see `retrieve::Suggester::pending_starts`).
    pub fn pending_starts(&self) -> Vec<(usize, usize)> {
        self.suggester.pending_starts()
    }

    /// Refines the next family; returns whether any remain.
    pub fn step(&mut self, db: &Db) -> bool {
        self.suggester.step(db, &mut |_, _| true)
    }

    /// The analysis-size photo the suggester works on: RGB `f32` triples, width, height (the
    /// input of a [`Refiner`] that refines families of this job elsewhere).
    pub fn prepared(&self) -> (Vec<f32>, u32, u32) {
        flat_photo(&self.prepared)
    }

    /// Stores start `k` of family `i` as JSON from [`Refiner::refine_start`] (or this job's
    /// own [`SuggestJob::refine_start`]); the family is refined with its last start in.
    pub fn set_refined_start(
        &mut self,
        i: usize,
        k: usize,
        json: &str,
    ) -> Result<(), serde_json::Error> {
        let r: proctex::retrieve::Refined = serde_json::from_str(json)?;
        self.suggester.set_refined_start(i, k, r);
        Ok(())
    }

    /// Refines start `k` of family `i` without storing it: its result as JSON (for
    /// [`SuggestJob::set_refined_start`]).
    pub fn refine_start(&self, db: &Db, i: usize, k: usize) -> String {
        refined_start_json(&self.suggester, db, i, k)
    }

    /// Ends a refinement stopped early: each family with some of its starts in is refined by
    /// the best of those (`retrieve::Suggester::settle_partial_starts`).
    pub fn settle_partial_starts(&mut self) {
        self.suggester.settle_partial_starts();
    }

    /// The families whose fits order the list (`retrieve::Suggester::render_ordered`): fit
    /// each here ([`SuggestJob::order_fit`]) or in a helper ([`Refiner::order_fit`]), store it
    /// ([`SuggestJob::set_order_fit`]), then [`SuggestJob::rank`] uses the stored fits.
    pub fn order_fits(&self) -> Vec<usize> {
        self.suggester.render_ordered()
    }

    /// Family `i`'s refinement as JSON: what a helper's [`Refiner::order_fit`] fits.
    pub fn refined_of(&self, i: usize) -> String {
        serde_json::to_string(self.suggester.refined(i)).expect("patterns serialise")
    }

    /// Fits family `i` here without storing it: its fit as JSON (for
    /// [`SuggestJob::set_order_fit`]).
    pub fn order_fit(&self, db: &Db, i: usize) -> String {
        serde_json::to_string(&self.suggester.fit_refined(db, i)).expect("params serialise")
    }

    /// Stores family `i`'s fit (JSON from [`SuggestJob::order_fit`] or a helper's
    /// [`Refiner::order_fit`]).
    pub fn set_order_fit(&mut self, i: usize, json: &str) -> Result<(), serde_json::Error> {
        let fit: proctex::retrieve::Fit = serde_json::from_str(json)?;
        self.suggester.set_fitted(i, fit);
        Ok(())
    }

    /// Fits the noise model and stores it, for [`SuggestJob::rank`] (which fits it otherwise).
    pub fn fit_noise(&mut self, db: &Db) {
        let fit = self.suggester.fit_noise(db);
        self.suggester.set_noise_fit(fit);
    }

    /// Ranks the candidates with the refinement done so far (the families not refined keep
    /// their retrieved pattern). Only the noise model and the families that order the list are
    /// fitted: they decide the order (`retrieve::Suggester::ranked`); [`SuggestJob::fit_next`]
    /// fits the other rows afterwards, one per call.
    pub fn rank(&mut self, db: &Db) -> Vec<SuggestionRow> {
        self.ranked = self.suggester.ranked(db, proctex::retrieve::RENDER_ORDERED);
        (0..self.ranked.len()).map(|i| self.row(i)).collect()
    }

    /// Ranked rows (0 before [`SuggestJob::rank`]).
    pub fn rows(&self) -> usize {
        self.ranked.len()
    }

    /// Ranked rows not fitted yet ([`SuggestJob::fit_next`] fits them).
    pub fn unfitted(&self) -> usize {
        self.ranked.iter().filter(|s| s.preview.is_none()).count()
    }

    /// Ranked row `i` as the UI shows it.
    pub fn row(&self, i: usize) -> SuggestionRow {
        let s = &self.ranked[i];
        SuggestionRow {
            name: s.name.to_string(),
            score: s.score,
            distance: s.distance,
            retrieval: s.pattern.as_ref().map(|_| s.retrieval_distance),
            refined: s.refined_distance,
            skipped: s.skipped,
            render_ordered: s.render_ordered,
            speckier: s.speckier,
        }
    }

    /// Fits the first ranked row not fitted yet (as the ranking would have fitted it) and
    /// returns its index; `None` when every row is fitted.
    pub fn fit_next(&mut self, db: &Db) -> Option<usize> {
        let i = self.ranked.iter().position(|s| s.preview.is_none())?;
        self.suggester.fit(db, &mut self.ranked[i]);
        Some(i)
    }

    /// Thumbnails of the ranked candidates ([`THUMB_SIDE`]², RGBA8, concatenated in rank
    /// order): each fitted candidate rendered over the whole analysed photo; a row not
    /// fitted yet is transparent (alpha 0) until [`SuggestJob::fit_next`] fits it.
    pub fn thumbnails(&self) -> Vec<u8> {
        (0..self.ranked.len())
            .flat_map(|i| self.thumbnail(i))
            .collect()
    }

    /// Ranked row `i`'s thumbnail ([`SuggestJob::thumbnails`]).
    pub fn thumbnail(&self, i: usize) -> Vec<u8> {
        let side = THUMB_SIDE;
        let Some(p) = &self.ranked[i].preview else {
            return vec![0; (side * side * 4) as usize];
        };
        let extent = p
            .source
            .as_ref()
            .map_or(256, |s| s.analysis_width.max(s.analysis_height));
        let view = View {
            origin: [0.0, 0.0],
            pixel_size: p.transform.scale * extent as f32 / side as f32,
            z: 0.0,
        };
        render(p, side, side, &view)
            .to_rgb8()
            .chunks_exact(3)
            .flat_map(|c| [c[0], c[1], c[2], 255])
            .collect()
    }

    /// Begins the final fit of ranked row `i` in tasks, which this worker and its helpers share
    /// ([`SuggestJob::fit_pending`], [`SuggestJob::fit_task`] here or [`FitHelper::run`] in a
    /// helper, [`SuggestJob::set_fit_task`], then [`SuggestJob::fit_report`]: the same report as
    /// [`SuggestJob::report`]). Returns `false` for the noise model (no tasks: its report is
    /// [`SuggestJob::report`]'s).
    pub fn begin_fit(&mut self, db: &Db, i: usize) -> proctex::error::Result<bool> {
        let s = self.ranked.get(i).ok_or_else(|| {
            proctex::error::Error::Option(format!("no suggestion {i} (rank the photo first)"))
        })?;
        self.nearer = None;
        // The ranking's first round of this family, where it fitted one on this photo (the
        // nearer-render rule), goes on to the whole fit.
        self.final_fit = s.pattern.as_ref().map(|(pattern, swapped)| {
            match self
                .suggester
                .take_nearest_first_round_of(pattern, *swapped)
            {
                Some(round) => FinalFitJob::from_first_round(round, pattern, *swapped),
                None => FinalFitJob::new(db, &self.prepared, &self.opts, pattern, *swapped),
            }
        });
        Ok(self.final_fit.is_some())
    }

    /// Ranked row `i`'s pattern as the final fit's tasks name it (`None`: the noise model, or
    /// no such row): what helpers prepare their own final fit from while
    /// [`SuggestJob::begin_fit`] runs.
    pub fn row_pattern(&self, i: usize) -> Option<String> {
        let (pattern, swapped) = self.ranked.get(i)?.pattern.as_ref()?;
        Some(pattern_json(pattern, *swapped))
    }

    /// The final fit's tasks of its current round not stored yet (empty: done, or none begun).
    pub fn fit_pending(&mut self) -> Vec<usize> {
        self.final_fit
            .as_mut()
            .map_or_else(Vec::new, FinalFitJob::pending)
    }

    /// The final fit's pattern as JSON and the first round's chosen amplitude: what a helper's
    /// [`FitHelper::run`] takes with a task.
    pub fn fit_pattern(&self) -> Option<(&str, usize)> {
        let f = self.final_fit.as_ref()?;
        Some((f.pattern_json(), f.chosen()))
    }

    /// Runs final-fit task `t` here without storing it: its result as JSON (for
    /// [`SuggestJob::set_fit_task`]).
    pub fn fit_task(&self, db: &Db, t: usize) -> Option<String> {
        self.final_fit.as_ref()?.run(db, t)
    }

    /// The final fit's scored tasks (its first two rounds, [`SuggestJob::fit_task`]); the
    /// tasks from this number on are tone renders ([`SuggestJob::fit_tone`]).
    pub fn fit_scored_tasks(&self) -> usize {
        self.final_fit.as_ref().map_or(0, FinalFitJob::scored_tasks)
    }

    /// The final fit's best params as JSON once its tone renders are listed (what a helper's
    /// [`Refiner::fit_tone`] renders).
    pub fn fit_best_params(&self) -> Option<String> {
        self.final_fit.as_ref()?.best_params_json()
    }

    /// Runs tone-render task `t` here: flat RGB for [`SuggestJob::set_fit_tone`].
    pub fn fit_tone(&self, t: usize) -> Option<Vec<f32>> {
        self.final_fit.as_ref()?.run_tone(t)
    }

    /// Stores tone-render task `t` (flat RGB from here or a helper); false when it does not
    /// fit the task.
    pub fn set_fit_tone(&mut self, t: usize, rgb: &[f32]) -> bool {
        self.final_fit.as_mut().is_some_and(|f| f.set_tone(t, rgb))
    }

    /// Stores final-fit task `t`'s result (JSON from here or a helper).
    pub fn set_fit_task(&mut self, t: usize, json: &str) -> Result<(), serde_json::Error> {
        match self.final_fit.as_mut() {
            Some(f) => f.set(t, json),
            None => Ok(()),
        }
    }

    /// The report of the final fit begun by [`SuggestJob::begin_fit`] once every task is
    /// stored (an error before).
    pub fn fit_report(&self) -> proctex::error::Result<Report> {
        let analysis = self
            .final_fit
            .as_ref()
            .and_then(FinalFitJob::finish)
            .ok_or_else(|| {
                proctex::error::Error::Option(
                    "the final fit is not begun (begin_fit) or not every task is stored".into(),
                )
            })?;
        self.report_of(|_, _| analysis)
    }

    /// The report of ranked candidate `i` fitted to the photo at analysis size (what adopting
    /// it shows).
    pub fn report(&self, db: &Db, i: usize) -> proctex::error::Result<Report> {
        let s = self.ranked.get(i).ok_or_else(|| {
            proctex::error::Error::Option(format!("no suggestion {i} (rank the photo first)"))
        })?;
        self.report_of(|p, o| match &s.pattern {
            // The pattern's scale is in texels of the photo the suggester saw, which is `p`.
            Some((pattern, swapped)) => fit_structured(db, p, pattern, o, *swapped),
            None => analyze_prepared(p, o),
        })
    }

    /// The report of `analysis` run on the job's analysis-size photo.
    fn report_of(
        &self,
        analysis: impl FnOnce(&Photo, &Options) -> proctex::analyze::Analysis,
    ) -> proctex::error::Result<Report> {
        let analysis = analyze_photo_with(&self.photo, &self.opts, analysis)?;
        report(
            &self.photo,
            &self.opts,
            analysis.params,
            self.width,
            self.height,
            self.crop,
        )
    }
}

/// The CPU reference render of `params` as RGBA8 (the preview without WebGPU).
pub fn preview_rgba(params: &Params, width: u32, height: u32) -> Vec<u8> {
    let img = render(params, width, height, &View::default());
    img.to_rgb8()
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect()
}

fn refined_start_json(s: &Suggester, db: &Db, i: usize, k: usize) -> String {
    serde_json::to_string(&s.refine_start(db, i, k, &mut |_, _| true)).expect("patterns serialise")
}

/// Refines families of a [`SuggestJob`] in another worker (the page's helper workers): built
/// from the job's [`SuggestJob::prepared`] photo and seed, it retrieves exactly as the job did,
/// so each family's refinement equals the job's own.
#[derive(Debug)]
pub struct Refiner {
    suggester: Suggester,
    fit: FitHelper,
    /// The same on the ranking's photo, for the nearer-render rule's first round
    /// ([`SuggestJob::begin_nearer`]).
    ranking_fit: FitHelper,
}

impl Refiner {
    /// A refiner for the analysis-size photo `rgb` (`f32` triples) of `width × height`.
    pub fn new(
        db: &Db,
        rgb: &[f32],
        width: u32,
        height: u32,
        seed: u32,
    ) -> proctex::error::Result<Refiner> {
        if rgb.len() != width as usize * height as usize * 3 || width == 0 || height == 0 {
            return Err(proctex::error::Error::Decode(format!(
                "expected {} floats of RGB for {width}×{height}, got {}",
                width as usize * height as usize * 3,
                rgb.len()
            )));
        }
        let photo = Photo {
            width,
            height,
            pixels: rgb.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
        };
        // The photo comes prepared (its lighting divided out where the job's options said), and
        // nothing here prepares it again: the options' flag would not be read.
        let opts = suggestion_options(seed, false);
        let suggester = Suggester::new(db, &photo, &opts, Refinement::default());
        Ok(Refiner {
            ranking_fit: FitHelper::new(suggester.ranking_photo().clone(), opts),
            suggester,
            fit: FitHelper::new(photo, opts),
        })
    }

    /// The refinement's starts, as the job's [`SuggestJob::pending_starts`] lists them before
    /// any is stored: the same retrieval, so the same (family, start) pairs in the same order.
    pub fn pending_starts(&self) -> Vec<(usize, usize)> {
        self.suggester.pending_starts()
    }

    /// Start `k` of family `i`'s refinement as JSON (for [`SuggestJob::set_refined_start`]).
    pub fn refine_start(&self, db: &Db, i: usize, k: usize) -> String {
        refined_start_json(&self.suggester, db, i, k)
    }

    /// Family `i`'s fit as JSON (for [`SuggestJob::set_order_fit`]), with `refined_json`
    /// ([`SuggestJob::refined_of`]) as its refinement: the same as the job's own
    /// [`SuggestJob::order_fit`].
    pub fn order_fit(
        &mut self,
        db: &Db,
        i: usize,
        refined_json: &str,
    ) -> Result<String, serde_json::Error> {
        let r: proctex::retrieve::Refined = serde_json::from_str(refined_json)?;
        self.suggester.set_refined(i, r);
        Ok(serde_json::to_string(&self.suggester.fit_refined(db, i)).expect("params serialise"))
    }

    /// Builds the final fit of `pattern_json` ([`SuggestJob::row_pattern`], or
    /// [`SuggestJob::begin_nearer`]'s on the ranking's photo where `on_ranking_photo`:
    /// [`SuggestJob::fit_on_ranking_photo`]) ahead of its tasks.
    pub fn fit_prepare(
        &mut self,
        db: &Db,
        pattern_json: &str,
        on_ranking_photo: bool,
    ) -> Result<(), serde_json::Error> {
        self.fit_helper(on_ranking_photo)
            .prepare(db, pattern_json)
            .map(|_| ())
    }

    /// Final-fit task `t` of the job's pattern ([`SuggestJob::fit_pattern`]; on the ranking's
    /// photo where `on_ranking_photo`) as JSON (for [`SuggestJob::set_fit_task`]).
    pub fn fit_task(
        &mut self,
        db: &Db,
        pattern_json: &str,
        t: usize,
        chosen: usize,
        on_ranking_photo: bool,
    ) -> Result<String, String> {
        self.fit_helper(on_ranking_photo)
            .run(db, pattern_json, t, chosen)
    }

    /// Tone render `k` of the final fit's best params ([`SuggestJob::fit_best_params`]; at the
    /// ranking photo's size where `on_ranking_photo`) as flat RGB (for
    /// [`SuggestJob::set_fit_tone`], task `fit_scored_tasks + k`).
    pub fn fit_tone(
        &mut self,
        params_json: &str,
        k: u32,
        on_ranking_photo: bool,
    ) -> Result<Vec<f32>, serde_json::Error> {
        self.fit_helper(on_ranking_photo).tone(params_json, k)
    }

    fn fit_helper(&mut self, on_ranking_photo: bool) -> &mut FitHelper {
        if on_ranking_photo {
            &mut self.ranking_fit
        } else {
            &mut self.fit
        }
    }

    /// The scatterings that the nearer-render rule compares the family's render with: the
    /// ranking photo's and that of the render of `noise_json` ([`SuggestJob::noise_params`]),
    /// for [`SuggestJob::set_nearer_scatterings`].
    pub fn nearer_scatterings(
        &self,
        noise_json: &str,
    ) -> Result<(Vec<f64>, Vec<f64>), serde_json::Error> {
        let noise: Params = serde_json::from_str(noise_json)?;
        Ok((
            self.suggester.photo_scattering(),
            self.suggester.render_scattering(&noise),
        ))
    }
}

mod adoption;
mod nearer;
#[cfg(test)]
mod tests;
