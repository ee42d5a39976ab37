//! wasm-bindgen glue: starting the app on a canvas, and the automation API that `www/main.js`
//! puts on `window.proctex` (documented in `www/README.md`).

use wasm_bindgen::prelude::*;

use crate::app::{Command, PhotoPreview, ProctexApp, SNAPSHOT, ViewMode, send};
use crate::jobs;
use proctex::params::Params;

/// The running app (so JS can ask whether it panicked).
#[wasm_bindgen]
pub struct WebHandle {
    runner: eframe::WebRunner,
}

impl std::fmt::Debug for WebHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WebHandle").finish_non_exhaustive()
    }
}

#[wasm_bindgen]
impl WebHandle {
    /// Whether the app panicked (the page then shows the message).
    pub fn has_panicked(&self) -> bool {
        self.runner.has_panicked()
    }

    /// The panic message, if it panicked.
    pub fn panic_message(&self) -> Option<String> {
        self.runner.panic_summary().map(|s| s.message())
    }
}

/// Starts the app on `canvas`. Fails (with a message) when the browser has no WebGPU.
#[wasm_bindgen]
pub async fn start(canvas: web_sys::HtmlCanvasElement) -> Result<WebHandle, JsValue> {
    let runner = eframe::WebRunner::new();
    let options = eframe::WebOptions::default();
    runner
        .start(
            canvas,
            options,
            Box::new(|cc| Ok(Box::new(ProctexApp::new(cc)))),
        )
        .await?;
    Ok(WebHandle { runner })
}

// ---- Worker side: pure computations, no app (see `jobs`). ----

/// Worker job: analyses `crop` (`[x, y, w, h]` photo pixels, or empty for all) of an RGBA image
/// and returns the report (params and plot statistics) as JSON; throws the error's message.
#[wasm_bindgen(js_name = analyzeRgba)]
pub fn analyze_rgba(
    rgba: &[u8],
    width: u32,
    height: u32,
    crop: Vec<u32>,
    seed: u32,
) -> Result<String, JsValue> {
    let report =
        jobs::analyze_rgba(rgba, width, height, parse_crop(&crop)?, seed).map_err(js_error)?;
    serde_json::to_string(&report).map_err(js_error)
}

/// Worker job: the model's plot statistics for a params document, as JSON.
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
    /// Retrieval for `crop` (`[x, y, w, h]` or empty) of an RGBA image; throws the error's
    /// message (no database, bad crop).
    #[wasm_bindgen(constructor)]
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Vec<u32>,
        seed: u32,
    ) -> Result<Suggestions, JsValue> {
        let crop = parse_crop(&crop)?;
        let job = jobs::SuggestJob::new(database()?, rgba, width, height, crop, seed)
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

    /// The families of the current refinement round still to refine (empty: the refinement
    /// is complete). Refine them (here or in helpers), store them, then ask again.
    pub fn pending(&self) -> Vec<u32> {
        self.job.pending().into_iter().map(|i| i as u32).collect()
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

    /// Refines family `i` here without storing it; returns the result as JSON for
    /// `setRefined`.
    pub fn refine(&self, i: usize) -> Result<String, JsValue> {
        Ok(self.job.refine(database()?, i))
    }

    /// Stores family `i`'s refinement (JSON from `refine` here or a helper's `Refiner`).
    #[wasm_bindgen(js_name = setRefined)]
    pub fn set_refined(&mut self, i: usize, json: &str) -> Result<(), JsValue> {
        self.job.set_refined(i, json).map_err(js_error)
    }

    /// Ranks the candidates (refined so far) and returns the rows as JSON.
    pub fn rank(&mut self) -> Result<String, JsValue> {
        let rows = self.job.rank(database()?);
        serde_json::to_string(&rows).map_err(js_error)
    }

    /// The ranked candidates' thumbnails, `THUMB_SIDE²` RGBA8 each, concatenated.
    pub fn thumbnails(&self) -> Vec<u8> {
        self.job.thumbnails()
    }

    /// The report JSON of ranked candidate `i` fitted at analysis size.
    pub fn report(&self, i: usize) -> Result<String, JsValue> {
        let r = self.job.report(database()?, i).map_err(js_error)?;
        serde_json::to_string(&r).map_err(js_error)
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

    /// Family `i`'s refinement as JSON (for `Suggestions.setRefined`).
    pub fn refine(&self, i: usize) -> Result<String, JsValue> {
        Ok(self.inner.refine(database()?, i))
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

// ---- UI side: the page tells the app what the worker did. ----

/// An analysis started or moved on to `stage`; `name` is the photo (absent for a crop).
#[wasm_bindgen(js_name = analysisProgress)]
pub fn analysis_progress(name: Option<String>, stage: String) {
    send(Command::Busy { name, stage });
}

/// An analysis finished: the worker's report JSON, the photo name, the time it took, and for a
/// new photo its preview (RGBA8, `preview_width × preview_height`) and full size.
#[wasm_bindgen(js_name = analysisDone)]
#[allow(clippy::too_many_arguments)]
pub fn analysis_done(
    report_json: String,
    name: String,
    ms: f64,
    preview: Option<Vec<u8>>,
    preview_width: u32,
    preview_height: u32,
    width: u32,
    height: u32,
) -> Result<(), JsValue> {
    let report: jobs::Report = serde_json::from_str(&report_json).map_err(js_error)?;
    report.params.validate().map_err(js_error)?;
    send(Command::Analysed {
        report: Box::new(report),
        name,
        ms,
        preview: preview.map(|rgba| PhotoPreview {
            rgba,
            size: [preview_width, preview_height],
            full: [width, height],
        }),
    });
    Ok(())
}

/// The worker refined `done` of `total` families for the current photo's suggestions.
#[wasm_bindgen(js_name = suggestionProgress)]
pub fn suggestion_progress(done: u32, total: u32) {
    send(Command::SuggestProgress { done, total });
}

/// The photo just analysed gets its model suggestions only when the user asks (the app shows
/// a button that calls `proctexHost.suggestModels`).
#[wasm_bindgen(js_name = suggestionsOnRequest)]
pub fn suggestions_on_request() {
    send(Command::SuggestOnRequest);
}

/// The ranked suggestions (rows JSON), their thumbnails (`THUMB_SIDE²` RGBA8 each,
/// concatenated), whether the refinement was cancelled and whether by its time budget
/// (`setRefineBudget`), and the best candidate's report JSON
/// when it is a structured model (adopted unless the user edited the params meanwhile).
#[wasm_bindgen(js_name = suggestionsDone)]
pub fn suggestions_done(
    rows_json: String,
    thumbnails: Vec<u8>,
    cancelled: bool,
    timed_out: bool,
    best_report: Option<String>,
) -> Result<(), JsValue> {
    let rows: Vec<jobs::SuggestionRow> = serde_json::from_str(&rows_json).map_err(js_error)?;
    let side = jobs::THUMB_SIDE as usize;
    if thumbnails.len() != rows.len() * side * side * 4 {
        return Err(JsValue::from_str("suggestion thumbnails: wrong size"));
    }
    let best = match best_report {
        Some(json) => {
            let r: jobs::Report = serde_json::from_str(&json).map_err(js_error)?;
            r.params.validate().map_err(js_error)?;
            Some(Box::new(r))
        }
        None => None,
    };
    send(Command::Suggestions {
        rows,
        thumbnails,
        cancelled,
        timed_out,
        best,
    });
    Ok(())
}

/// The worker fitted suggestion `index` (after the user clicked it): its report JSON.
#[wasm_bindgen(js_name = suggestionAdopted)]
pub fn suggestion_adopted(index: usize, report_json: String) -> Result<(), JsValue> {
    let report: jobs::Report = serde_json::from_str(&report_json).map_err(js_error)?;
    report.params.validate().map_err(js_error)?;
    send(Command::Adopted {
        index,
        report: Box::new(report),
    });
    Ok(())
}

/// The suggestions could not be computed (no database, a failed job): the app says so; the
/// noise model's analysis stands.
#[wasm_bindgen(js_name = suggestionsFailed)]
pub fn suggestions_failed(message: String) {
    send(Command::SuggestFailed(message));
}

/// The model statistics the app asked for (`proctexHost.modelStats(params)`).
#[wasm_bindgen(js_name = modelStatsDone)]
pub fn model_stats_done(params_json: String, stats_json: String) -> Result<(), JsValue> {
    let p = Params::from_json(&params_json).map_err(js_error)?;
    let s: jobs::ImageStats = serde_json::from_str(&stats_json).map_err(js_error)?;
    send(Command::ModelStats(Box::new((p, s))));
    Ok(())
}

/// Switches the view: "plane", "split", "sphere" or "cube".
#[wasm_bindgen(js_name = setViewMode)]
pub fn set_view_mode(mode: String) -> Result<(), JsValue> {
    let m = ViewMode::parse(&mode)
        .ok_or_else(|| JsValue::from_str("view mode must be plane, split, sphere or cube"))?;
    send(Command::SetMode(m));
    Ok(())
}

/// Adds the presets of a library file (or one params document); a bad file shows an error and
/// changes nothing.
#[wasm_bindgen(js_name = importPresets)]
pub fn import_presets(text: String) {
    send(Command::ImportPresets(text));
}

/// Adds a built-in gallery preset (the page analyses the shipped samples in the worker).
#[wasm_bindgen(js_name = addGalleryPreset)]
pub fn add_gallery_preset(name: String, params_json: String) -> Result<(), JsValue> {
    let p = Params::from_json(&params_json).map_err(js_error)?;
    send(Command::GalleryPreset(name, Box::new(p)));
    Ok(())
}

/// The presets library as JSON (`proctex-presets/1`), as stored.
#[wasm_bindgen(js_name = getPresets)]
pub fn get_presets() -> Option<String> {
    web_sys::window()
        .and_then(|w| w.local_storage().ok().flatten())
        .and_then(|s| s.get_item(crate::presets::STORAGE_KEY).ok().flatten())
}

/// Benchmarks: draw the plane view with the trivial mean-colour shader instead.
#[wasm_bindgen(js_name = setFlatShader)]
pub fn set_flat_shader(on: bool) {
    send(Command::FlatShader(on));
}

/// Benchmarks: `false` renders the texture view on every frame instead of copying the frame
/// cache while the view is unchanged (the default, `true`).
#[wasm_bindgen(js_name = setFrameCache)]
pub fn set_frame_cache(on: bool) {
    send(Command::FrameCache(on));
}

/// Tests: the texture view at most `width × height` CSS px (at the top-left of its panel), or
/// the whole panel when either is 0. A render of the view costs in proportion to its pixels.
#[wasm_bindgen(js_name = setViewLimit)]
pub fn set_view_limit(width: f32, height: f32) {
    let limit = (width > 0.0 && height > 0.0).then(|| eframe::egui::vec2(width, height));
    send(Command::ViewLimit(limit));
}

/// PNG tile export choices (the app's menus, for tests): side 16..=8192, 8 or 16 bits, and
/// whether to render on the CPU even with a GPU (to exercise the fallback).
#[wasm_bindgen(js_name = setTileOptions)]
pub fn set_tile_options(size: u32, bits: u8, force_cpu: bool) -> Result<(), JsValue> {
    if !(16..=proctex::seamless::MAX_TILE).contains(&size) || !(bits == 8 || bits == 16) {
        return Err(JsValue::from_str(&format!(
            "tile options: size {size} (16..=8192), bits {bits} (8 or 16)"
        )));
    }
    send(Command::TileOptions {
        size,
        bits,
        force_cpu,
    });
    Ok(())
}

/// Shows an error message in the app (e.g. a file the browser could not decode).
#[wasm_bindgen(js_name = reportError)]
pub fn report_error(message: String) {
    send(Command::Error(message));
}

/// The current params as JSON (`proctex/1`), or `null` before the first analysis.
#[wasm_bindgen(js_name = getParams)]
pub fn get_params() -> Option<String> {
    SNAPSHOT.with(|s| s.borrow().params_json.clone())
}

/// Replaces the params; throws the validation message when the document is bad.
#[wasm_bindgen(js_name = setParams)]
pub fn set_params(json: String) -> Result<(), JsValue> {
    let p = Params::from_json(&json).map_err(|e| JsValue::from_str(&e.to_string()))?;
    send(Command::SetParams(Box::new(p)));
    Ok(())
}

/// Sets the texture view: world point at the view's top-left, world units per CSS pixel.
#[wasm_bindgen(js_name = setView)]
pub fn set_view(origin_x: f32, origin_y: f32, units_per_point: f32) {
    send(Command::SetView {
        origin: [origin_x, origin_y],
        units_per_point,
    });
}

/// Asks for another frame (egui repaints only on events; tests use this to step frames).
#[wasm_bindgen(js_name = requestRepaint)]
pub fn request_repaint() {
    crate::app::CONTEXT.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
}

/// The app's state after the last frame, as JSON: frame, photo, analysis_ms, error, widgets
/// (name → [x, y, w, h] in CSS pixels), view, undo/redo depths.
#[wasm_bindgen]
pub fn state() -> String {
    SNAPSHOT.with(|s| serde_json::to_string(&*s.borrow()).unwrap_or_default())
}
