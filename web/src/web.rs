//! wasm-bindgen glue: starting the app on a canvas, and the automation API that `www/main.js`
//! puts on `window.proctex` (documented in `www/README.md`).

use wasm_bindgen::prelude::*;

use crate::app::{Command, PhotoPreview, ProctexApp, SNAPSHOT, ViewMode, send, send_within};
use proctex::params::Params;
use proctex_worker::jobs;

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

/// The worker fitted ranked row `index` after the list came (`suggestionsDone` fits only what
/// decides the order): the row JSON with its texture distance, and its `THUMB_SIDE²` RGBA8
/// thumbnail.
#[wasm_bindgen(js_name = suggestionFitted)]
pub fn suggestion_fitted(
    index: usize,
    row_json: String,
    thumbnail: Vec<u8>,
) -> Result<(), JsValue> {
    let row: jobs::SuggestionRow = serde_json::from_str(&row_json).map_err(js_error)?;
    let side = jobs::THUMB_SIDE as usize;
    if thumbnail.len() != side * side * 4 {
        return Err(JsValue::from_str("suggestion thumbnail: wrong size"));
    }
    // The rows' fits arrive every ~0.1 s while the worker fits the rest of the list; on a
    // software adapter each repaint costs the CPU the worker fits them with, so the rows that
    // arrive within a quarter of a second are shown in one frame.
    send_within(
        Command::SuggestionFitted {
            index,
            row: Box::new(row),
            thumbnail,
        },
        std::time::Duration::from_millis(250),
    );
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

/// The worker ran `done` of `total` rounds of the Heeger–Bergen synthesis the app asked for.
#[wasm_bindgen(js_name = pyramidProgress)]
pub fn pyramid_progress(done: u32, total: u32) {
    send(Command::PyramidProgress { done, total });
}

/// The Heeger–Bergen synthesis the app asked for: RGBA8, `width × height`, and its time.
#[wasm_bindgen(js_name = pyramidDone)]
pub fn pyramid_done(rgba: Vec<u8>, width: u32, height: u32, ms: f64) -> Result<(), JsValue> {
    if width == 0 || height == 0 || rgba.len() != width as usize * height as usize * 4 {
        return Err(JsValue::from_str("pyramid synthesis: wrong size"));
    }
    send(Command::PyramidDone {
        rgba,
        size: [width, height],
        ms,
    });
    Ok(())
}

/// The Heeger–Bergen synthesis was cancelled (the user's Cancel, or a newer one).
#[wasm_bindgen(js_name = pyramidCancelled)]
pub fn pyramid_cancelled() {
    send(Command::PyramidCancelled);
}

/// The Heeger–Bergen synthesis failed; the message says why.
#[wasm_bindgen(js_name = pyramidFailed)]
pub fn pyramid_failed(message: String) {
    send(Command::PyramidFailed(message));
}

/// The worker ran `done` of `total` rounds of the solid texture the app asked for.
#[wasm_bindgen(js_name = solidProgress)]
pub fn solid_progress(done: u32, total: u32) {
    send(Command::SolidProgress { done, total });
}

/// The solid texture the app asked for: `n³` RGBA8 voxels (x fastest), voxels per photo pixel,
/// and its time.
#[wasm_bindgen(js_name = solidDone)]
pub fn solid_done(rgba: Vec<u8>, n: u32, voxels_per_unit: f32, ms: f64) -> Result<(), JsValue> {
    if n == 0 || rgba.len() != (n as usize).pow(3) * 4 {
        return Err(JsValue::from_str("solid texture: wrong size"));
    }
    if !(voxels_per_unit.is_finite() && voxels_per_unit > 0.0) {
        return Err(JsValue::from_str("solid texture: bad scale"));
    }
    send(Command::SolidDone {
        rgba,
        n,
        voxels_per_unit,
        ms,
    });
    Ok(())
}

/// The solid texture was cancelled (the user's Cancel, or a newer one).
#[wasm_bindgen(js_name = solidCancelled)]
pub fn solid_cancelled() {
    send(Command::SolidCancelled);
}

/// The solid texture failed; the message says why.
#[wasm_bindgen(js_name = solidFailed)]
pub fn solid_failed(message: String) {
    send(Command::SolidFailed(message));
}

/// The sphere and cube views' texture: `source` "procedural" or "heeger-bergen" (the raster
/// volume of the crop, `side³` voxels: 64 or 128).
#[wasm_bindgen(js_name = setSolidSource)]
pub fn set_solid_source(source: String, side: u32) -> Result<(), JsValue> {
    let raster = match source.as_str() {
        "procedural" => false,
        "heeger-bergen" => true,
        _ => {
            return Err(JsValue::from_str(
                "solid source must be procedural or heeger-bergen",
            ));
        }
    };
    if !crate::app::SOLID_SIDES.contains(&side) {
        return Err(JsValue::from_str("solid side must be 64 or 128"));
    }
    send(Command::SetSolidSource { raster, side });
    Ok(())
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
    let m = ViewMode::parse(&mode).ok_or_else(|| {
        JsValue::from_str("view mode must be plane, split, pyramid, sphere or cube")
    })?;
    send(Command::SetMode(m));
    Ok(())
}

/// The pyramid view's texture mixture: `source` (B) `sample:NAME` (a shipped sample photo),
/// `gallery:NAME` (a gallery texture), `preset:NAME` (a preset's) or `crop` (the photo's crop),
/// or absent for none; `m` from 0 (A's synthesis) to 1
/// (B's); `a` (A) likewise, or absent for the photo's crop.
#[wasm_bindgen(js_name = setPyramidMix)]
pub fn set_pyramid_mix(source: Option<String>, m: f32, a: Option<String>) -> Result<(), JsValue> {
    if !(0.0..=1.0).contains(&m) {
        return Err(JsValue::from_str("m must be between 0 and 1"));
    }
    let named = |s: &str| {
        ["sample:", "preset:", "gallery:"]
            .iter()
            .any(|p| s.starts_with(p))
    };
    if source.as_deref().is_some_and(|s| !named(s) && s != "crop")
        || a.as_deref().is_some_and(|s| !named(s))
    {
        return Err(JsValue::from_str(
            "B must be crop, sample:NAME, gallery:NAME or preset:NAME; A one of the last three",
        ));
    }
    send(Command::SetPyramidMix(source.map(|s| (s, m)), a));
    Ok(())
}

/// Adds the presets of a library file (or one params document); a bad file shows an error and
/// changes nothing.
#[wasm_bindgen(js_name = importPresets)]
pub fn import_presets(text: String) {
    send(Command::ImportPresets(text));
}

/// Another tab wrote the presets library: the app shows it (the page listens for `storage`).
#[wasm_bindgen(js_name = presetsChangedElsewhere)]
pub fn presets_changed_elsewhere() {
    send(Command::PresetsChangedElsewhere);
}

/// The WGSL or GLSL shader (`format`: "wgsl" or "glsl") of a params document: the export that
/// needs no GPU, for the page without WebGPU.
#[wasm_bindgen(js_name = exportShader)]
pub fn export_shader(params_json: String, format: String) -> Result<String, JsValue> {
    let p = Params::from_json(&params_json).map_err(js_error)?;
    proctex::export::shader(std::slice::from_ref(&p), &format).map_err(js_error)
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

/// Opens the texture of a share link's fragment (`#p=…`, see `proctex::share`); throws the
/// reason when the link holds no texture (a presets library, junk, too long).
#[wasm_bindgen(js_name = openShareFragment)]
pub fn open_share_fragment(fragment: String) -> Result<(), JsValue> {
    let p = proctex::share::params_of_fragment(&fragment).map_err(js_error)?;
    send(Command::SetParams(Box::new(p)));
    Ok(())
}

/// The share-link fragment (`#p=…`) of a params document.
#[wasm_bindgen(js_name = shareFragment)]
pub fn share_fragment(params_json: String) -> Result<String, JsValue> {
    let p = Params::from_json(&params_json).map_err(js_error)?;
    Ok(proctex::share::fragment(&p))
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

fn js_error(e: impl std::fmt::Display) -> JsValue {
    JsValue::from_str(&e.to_string())
}
