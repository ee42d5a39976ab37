//! The egui application: photo → analysis (in the page's Web Worker) → params → GPU texture,
//! with a crop rectangle on the photo, sliders for every parameter, undo/redo, plane / split /
//! sphere / cube views and plots of the photo against the model.
//!
//! Edits change `Params` and nothing else; the paint callback uploads them as one uniform
//! write. Analysis runs only when a photo or a crop arrives, and never on this thread: the app
//! asks the page (`proctexHost` in `www/main.js`) and the worker's result comes back as a
//! [`Command`].

use std::cell::RefCell;
use std::collections::BTreeMap;

use eframe::egui;
use eframe::egui_wgpu;
use proctex::params::{MAX_CONTRAST, Model, Params};
use proctex::render::{View, period_texels};
use proctex::solid::{Orbit, Shape, SolidView};
use wasm_bindgen::JsValue;

use crate::jobs::{ImageStats, Report, SuggestionRow, THUMB_SIDE};
use crate::presets::{MorphPreset, Preset, STORAGE_KEY, library_json, parse_library};
use crate::renderer::Pass;
use crate::tile_export::{SeamlessCpu, SeamlessGpu, png_scanlines};
use crate::view_cache::{CachedView, ViewSource};

/// Something JS asked for, applied at the start of the next frame.
#[derive(Debug)]
pub enum Command {
    /// The worker started (or moved to another stage of) an analysis.
    Busy {
        /// Name of the photo, or `None` for a re-analysis of the current photo's crop.
        name: Option<String>,
        /// What it is doing ("Decoding", "Analysing").
        stage: String,
    },
    /// An analysis finished.
    Analysed {
        /// Params and plot statistics.
        report: Box<Report>,
        /// Photo name.
        name: String,
        /// Milliseconds from the request to the result (decode included).
        ms: f64,
        /// For a new photo: its preview (RGBA, size) and its full size.
        preview: Option<PhotoPreview>,
    },
    /// Statistics of the model for these params (for the plots).
    ModelStats(Box<(Params, ImageStats)>),
    /// Show an error (a file that cannot be read, a denied camera, a failed analysis).
    Error(String),
    /// Replace the current params (already validated).
    SetParams(Box<Params>),
    /// Show this part of world space: top-left world point and world units per CSS pixel.
    SetView {
        origin: [f32; 2],
        units_per_point: f32,
    },
    /// Switch the view (plane, split, sphere, cube).
    SetMode(ViewMode),
    /// Draw the plane view with the trivial shader (benchmark baseline).
    FlatShader(bool),
    /// Benchmarks: render the texture on every frame instead of copying the cached view when
    /// it has not changed (to time the texture shader per frame).
    FrameCache(bool),
    /// Tests: the texture view at most this size (points), at the top-left of its panel; `None`
    /// fills the panel. Each render of the view costs in proportion to its pixels, and most
    /// checks need only a 256² part of it.
    ViewLimit(Option<egui::Vec2>),
    /// Add the presets of a library file (validated as a whole first).
    ImportPresets(String),
    /// A built-in gallery preset (a shipped sample's analysis).
    GalleryPreset(String, Box<Params>),
    /// The worker refined `done` of `total` families of the current photo's suggestions.
    SuggestProgress { done: u32, total: u32 },
    /// The photo just analysed gets its suggestions only when the user asks (the start-up
    /// sample: see `www/main.js`); the list of the previous photo goes.
    SuggestOnRequest,
    /// The ranked suggestions of the current photo (or crop).
    Suggestions {
        /// Rows, nearest first.
        rows: Vec<SuggestionRow>,
        /// `THUMB_SIDE²` RGBA8 thumbnails, concatenated in row order.
        thumbnails: Vec<u8>,
        /// The refinement was cancelled (families not reached keep their retrieved pattern).
        cancelled: bool,
        /// It was the refinement's time budget that stopped it.
        timed_out: bool,
        /// The first row's report when it is a structured model (adopted by default).
        best: Option<Box<Report>>,
    },
    /// The worker fitted suggestion `index` (the user clicked it): adopt its report.
    Adopted { index: usize, report: Box<Report> },
    /// The suggestions could not be computed.
    SuggestFailed(String),
    /// PNG tile export choices: side, bits (8 or 16), CPU even with a GPU.
    TileOptions {
        size: u32,
        bits: u8,
        force_cpu: bool,
    },
}

/// A downscaled copy of the photo for the crop panel and the split view.
#[derive(Debug)]
pub struct PhotoPreview {
    /// RGBA8 pixels.
    pub rgba: Vec<u8>,
    /// Preview size.
    pub size: [u32; 2],
    /// The photo's full size (crop coordinates are in these pixels).
    pub full: [u32; 2],
}

/// What the central panel shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ViewMode {
    /// The 2D texture, pan and zoom.
    Plane,
    /// The photo crop (left) beside the texture (right), same view.
    Split,
    /// The solid texture on a sphere.
    Sphere,
    /// The solid texture on a cube.
    Cube,
}

impl ViewMode {
    /// All modes, in toolbar order.
    pub const ALL: [ViewMode; 4] = [
        ViewMode::Plane,
        ViewMode::Split,
        ViewMode::Sphere,
        ViewMode::Cube,
    ];

    /// Parses a mode name.
    pub fn parse(s: &str) -> Option<ViewMode> {
        ViewMode::ALL.into_iter().find(|m| m.name() == s)
    }

    fn name(self) -> &'static str {
        match self {
            ViewMode::Plane => "plane",
            ViewMode::Split => "split",
            ViewMode::Sphere => "sphere",
            ViewMode::Cube => "cube",
        }
    }

    fn label(self) -> &'static str {
        match self {
            ViewMode::Plane => "Plane",
            ViewMode::Split => "Split vs photo",
            ViewMode::Sphere => "Sphere",
            ViewMode::Cube => "Cube",
        }
    }
}

/// What the app publishes for JS after every frame.
#[derive(Debug, Default, Clone, serde::Serialize)]
pub struct Snapshot {
    /// Frames drawn so far.
    pub frame: u64,
    /// Name of the analysed photo.
    pub photo: Option<String>,
    /// Full size of the photo.
    pub photo_size: Option<[u32; 2]>,
    /// Crop being analysed, photo pixels `[x, y, w, h]`.
    pub crop: Option<[u32; 4]>,
    /// Milliseconds the last analysis took (decode included).
    pub analysis_ms: Option<f64>,
    /// Number of analyses finished so far (photos and crops).
    pub analyses: u64,
    /// An analysis is running.
    pub busy: bool,
    /// The last error shown to the user.
    pub error: Option<String>,
    /// Current params as JSON.
    #[serde(skip)]
    pub params_json: Option<String>,
    /// Widget rectangles in CSS pixels: name → [x, y, w, h].
    pub widgets: BTreeMap<String, [f32; 4]>,
    /// The texture view: top-left world point, world units per CSS pixel.
    pub view_origin: [f32; 2],
    /// World units per CSS pixel.
    pub view_units_per_point: f32,
    /// Plane, split, sphere or cube.
    pub view_mode: Option<ViewMode>,
    /// Orbit camera of the solid views: yaw, pitch (degrees), distance.
    pub orbit: [f32; 3],
    /// The tile-period outline is on.
    pub period_outline: bool,
    /// Lines of the tile-period outline drawn in the last frame.
    pub period_lines: usize,
    /// The plots show the model's statistics for the current params.
    pub plots_current: bool,
    /// Names of the presets, in list order.
    pub presets: Vec<String>,
    /// Names of the built-in gallery presets.
    pub gallery: Vec<String>,
    /// The morph being shown: t, or `None` when no morph is active.
    pub morph_t: Option<f32>,
    /// The morph animation is playing.
    pub morph_playing: bool,
    /// The PNG tile export in progress: fraction done.
    pub tile_progress: Option<f32>,
    /// The model suggestions, nearest first.
    pub suggestions: Vec<SuggestionRow>,
    /// Suggestions being refined: families done, in all.
    pub suggest_progress: Option<[u32; 2]>,
    /// Row of the suggestion the current params came from (`None`: edited, or none yet).
    pub adopted: Option<usize>,
    /// Why there are no suggestions, if they failed.
    pub suggest_error: Option<String>,
    /// Undo/redo depths.
    pub undo: usize,
    /// Redo depth.
    pub redo: usize,
}

thread_local! {
    /// Commands from JS, drained each frame.
    pub static COMMANDS: RefCell<Vec<Command>> = const { RefCell::new(Vec::new()) };
    /// The latest snapshot, for JS.
    pub static SNAPSHOT: RefCell<Snapshot> = RefCell::new(Snapshot::default());
    /// The egui context, so that JS calls can request a repaint.
    pub static CONTEXT: RefCell<Option<egui::Context>> = const { RefCell::new(None) };
}

/// Queues a command and wakes the app.
pub fn send(cmd: Command) {
    COMMANDS.with(|c| c.borrow_mut().push(cmd));
    CONTEXT.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
}

/// Calls `window.proctexHost[method](...args)` (the page's side of the app: file dialog,
/// camera, worker jobs). Returns false when the page has no such function.
fn host(method: &str, args: &[JsValue]) -> bool {
    let Some(window) = web_sys::window() else {
        return false;
    };
    let Ok(h) = js_sys::Reflect::get(&window, &JsValue::from_str("proctexHost")) else {
        return false;
    };
    let Ok(f) = js_sys::Reflect::get(&h, &JsValue::from_str(method)) else {
        return false;
    };
    let Some(f) = wasm_bindgen::JsCast::dyn_ref::<js_sys::Function>(&f) else {
        return false;
    };
    let arr = js_sys::Array::new();
    for a in args {
        arr.push(a);
    }
    f.apply(&h, &arr).is_ok()
}

/// The texture view: which world rectangle the central panel shows.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ViewState {
    /// World point at the view's top-left corner.
    origin: [f32; 2],
    /// World units per CSS pixel (point).
    units_per_point: f32,
}

impl Default for ViewState {
    fn default() -> Self {
        ViewState {
            origin: [0.0, 0.0],
            units_per_point: 1.0,
        }
    }
}

/// The photo being analysed.
struct PhotoState {
    name: String,
    full: [u32; 2],
    texture: egui::TextureHandle,
    /// Region analysed, photo pixels `[x, y, w, h]`.
    crop: [u32; 4],
}

/// What a drag on the crop panel is doing.
#[derive(Clone, Copy, Debug, PartialEq)]
enum CropDrag {
    Move,
    /// Resizing from the corner opposite this fixed photo point.
    Resize {
        fixed: [f32; 2],
    },
}

/// Smallest crop side, photo pixels (the analyzer's minimum).
const MIN_CROP: u32 = proctex::input::MIN_SIDE;

/// The application.
pub struct ProctexApp {
    photo: Option<PhotoState>,
    /// The params of the last analysis (what "Reset to analysed" restores).
    analysed: Option<Params>,
    params: Option<Params>,
    committed: Option<Params>,
    undo: Vec<Params>,
    redo: Vec<Params>,
    view: ViewState,
    mode: ViewMode,
    orbit: Orbit,
    period_outline: bool,
    period_lines: usize,
    flat_shader: bool,
    /// Whether the texture view is rendered only when it changes (see `view_cache`).
    frame_cache: bool,
    /// The texture view's largest size in points (tests), or the whole panel.
    view_limit: Option<egui::Vec2>,
    error: Option<String>,
    analysis_ms: Option<f64>,
    analyses: u64,
    busy: Option<(String, f64)>,
    crop_drag: Option<(CropDrag, [u32; 4], egui::Pos2)>,
    photo_stats: Option<ImageStats>,
    model_stats: Option<(Params, ImageStats)>,
    stats_requested: Option<Params>,
    last_edit_ms: f64,
    frame: u64,
    widgets: BTreeMap<String, [f32; 4]>,
    presets: PresetsState,
    status_note: Option<String>,
    tile: TileSettings,
    tile_job: Option<TileJob>,
    /// The GPU device and queue (from eframe), for off-screen work such as the PNG tile.
    gpu: Option<(wgpu::Device, wgpu::Queue)>,
    suggest: SuggestState,
    /// The refinement's time budget in seconds (0: none, the evaluation budget alone).
    refine_budget_s: f32,
}

/// The automatic model choice's list (issue 5): filled by the worker after each analysis.
#[derive(Default)]
struct SuggestState {
    rows: Vec<SuggestionRow>,
    thumbs: Vec<egui::TextureHandle>,
    /// Families refined, in all, while the worker refines.
    progress: Option<(u32, u32)>,
    cancelled: bool,
    /// The refinement's time budget stopped it (then `cancelled` is set too).
    timed_out: bool,
    /// Row the current params were adopted from.
    adopted: Option<usize>,
    /// Row being fitted by the worker after a click.
    adopting: Option<usize>,
    /// The params right after adoption (the row stays marked until they are edited).
    adopted_params: Option<Params>,
    error: Option<String>,
    /// The current photo's suggestions start when the user asks (a button instead of a list).
    on_request: bool,
    /// The model the user clicked in the list, with the photo and crop it was ranked for.
    pick: Option<Pick>,
}

/// A model picked by hand from the list: a later ranking of the same photo and crop (a new
/// seed, the same crop analysed again) adopts the same model rather than the best one.
#[derive(Clone, Debug, PartialEq)]
struct Pick {
    photo: String,
    crop: [u32; 4],
    model: String,
}

/// The PNG tile export's choices.
struct TileSettings {
    size: u32,
    bits: u8,
    /// Render on the CPU even with a GPU (automation: tests of the fallback).
    force_cpu: bool,
}

/// Where a PNG tile's strips come from.
enum TileSource {
    Gpu(Box<SeamlessGpu>),
    /// The CPU fallback (no GPU, or the GPU pipeline failed), a few rows per frame.
    Cpu(Box<SeamlessCpu>),
}

/// A PNG tile export in progress: strips go to the page (`tileRows`), which compresses them.
struct TileJob {
    size: u32,
    bits: u8,
    source: TileSource,
    /// Next row to render.
    next_row: u32,
    /// Rows handed to the page.
    done_rows: u32,
    started_ms: f64,
    /// A structured model's pattern rotation and the quarter turn the tile renders it at
    /// (`seamless::tile_turn`), said when the tile is done.
    turn: Option<(f32, f32)>,
}

/// The presets list, its thumbnails and the morph between presets.
#[derive(Default)]
struct PresetsState {
    list: Vec<Preset>,
    /// Thumbnails, parallel to `list` (rendered from the params on demand).
    thumbs: Vec<Option<egui::TextureHandle>>,
    /// Chosen as morph keys, parallel to `list`.
    selected: Vec<bool>,
    /// The built-in gallery: the shipped samples' analyses, with thumbnails.
    gallery: Vec<(Preset, Option<egui::TextureHandle>)>,
    new_name: String,
    renaming: Option<(usize, String)>,
    /// The morph being shown (keys, t); `None`: the params are edited directly.
    morph: Option<Vec<Params>>,
    /// The ticked presets `morph` was built from (`None`: loaded from a saved morph).
    morph_from: Option<Vec<usize>>,
    t: f32,
    playing: bool,
    looping: bool,
    duration_s: f32,
}

impl ProctexApp {
    /// Creates the app and registers the GPU renderer with egui's wgpu renderer.
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        if let Some(rs) = cc.wgpu_render_state.as_ref() {
            let renderer = CachedView::new(&rs.device, rs.target_format);
            rs.renderer.write().callback_resources.insert(renderer);
        }
        cc.egui_ctx.set_fonts(ui_fonts());
        CONTEXT.with(|c| *c.borrow_mut() = Some(cc.egui_ctx.clone()));
        ProctexApp {
            photo: None,
            analysed: None,
            params: None,
            committed: None,
            undo: Vec::new(),
            redo: Vec::new(),
            view: ViewState::default(),
            mode: ViewMode::Plane,
            orbit: Orbit::default(),
            period_outline: false,
            period_lines: 0,
            flat_shader: false,
            frame_cache: true,
            view_limit: None,
            error: None,
            analysis_ms: None,
            analyses: 0,
            busy: None,
            crop_drag: None,
            photo_stats: None,
            model_stats: None,
            stats_requested: None,
            last_edit_ms: 0.0,
            frame: 0,
            widgets: BTreeMap::new(),
            status_note: None,
            tile: TileSettings {
                size: 1024,
                bits: 8,
                force_cpu: false,
            },
            tile_job: None,
            suggest: SuggestState::default(),
            refine_budget_s: 0.0,
            gpu: None,
            presets: PresetsState {
                duration_s: 4.0,
                looping: true,
                ..PresetsState::default()
            },
        }
        .with_stored_presets()
    }

    /// Loads the presets from `localStorage`. An unreadable stored library is moved aside to a
    /// backup key (never deleted) and reported.
    fn with_stored_presets(mut self) -> Self {
        let Some(storage) = web_sys::window().and_then(|w| w.local_storage().ok().flatten()) else {
            self.error = Some(
                "Presets: this browser gives the page no storage; presets will not persist".into(),
            );
            return self;
        };
        if let Ok(Some(text)) = storage.get_item(STORAGE_KEY) {
            match parse_library(&text) {
                Ok(list) => self.set_presets(list),
                Err(e) => {
                    let backup = format!("{STORAGE_KEY}.unreadable-{}", js_sys::Date::now() as u64);
                    let _ = storage.set_item(&backup, &text);
                    self.error = Some(format!(
                        "The stored presets could not be read ({e}); they were kept under the storage key {backup}"
                    ));
                }
            }
        }
        self
    }

    fn set_presets(&mut self, list: Vec<Preset>) {
        let n = list.len();
        self.presets.list = list;
        self.presets.thumbs = vec![None; n];
        self.presets.selected = vec![false; n];
        self.presets.renaming = None;
    }

    /// Writes the library to `localStorage`. A failed write (full quota) leaves the stored
    /// library as it was; the presets stay in memory and the user is told to export them.
    fn persist_presets(&mut self) {
        let text = library_json(&self.presets.list);
        let ok = web_sys::window()
            .and_then(|w| w.local_storage().ok().flatten())
            .map(|s| s.set_item(STORAGE_KEY, &text).is_ok())
            .unwrap_or(false);
        if !ok {
            self.error = Some(
                "Presets could not be saved (browser storage full or unavailable): the previously \
                 saved presets are unchanged; use Export… to keep the current ones"
                    .into(),
            );
        }
    }

    fn analysed(
        &mut self,
        ctx: &egui::Context,
        report: Report,
        name: String,
        ms: f64,
        preview: Option<PhotoPreview>,
    ) {
        self.busy = None;
        self.analyses += 1;
        self.analysis_ms = Some(ms);
        self.error = None;
        let crop = report
            .params
            .source
            .as_ref()
            .and_then(|s| s.crop)
            .or_else(|| {
                let s = report.params.source.as_ref()?;
                Some([0, 0, s.width, s.height])
            });
        if let Some(p) = preview {
            let image = egui::ColorImage::from_rgba_unmultiplied(
                [p.size[0] as usize, p.size[1] as usize],
                &p.rgba,
            );
            let texture = ctx.load_texture("photo", image, egui::TextureOptions::LINEAR);
            self.photo = Some(PhotoState {
                name: name.clone(),
                full: p.full,
                texture,
                crop: crop.unwrap_or([0, 0, p.full[0], p.full[1]]),
            });
            self.view = ViewState::default();
            self.undo.clear();
            self.redo.clear();
        } else if let Some(photo) = self.photo.as_mut() {
            // A re-analysed crop: one undoable step.
            if let Some(cur) = self.params.clone() {
                self.undo.push(cur);
                self.redo.clear();
            }
            if self.crop_drag.is_none()
                && let Some(c) = crop
            {
                photo.crop = c;
            }
        }
        // A crop re-analysis keeps the user's seed (the request carried it).
        self.params = Some(report.params.clone());
        self.committed = Some(report.params.clone());
        self.analysed = Some(report.params.clone());
        self.photo_stats = Some(report.photo);
        self.model_stats = Some((report.params.clone(), report.model));
        self.stats_requested = Some(report.params);
    }

    /// The worker's ranked suggestions arrived: thumbnails become textures; the best is
    /// adopted when it is a structured model and the params are still the analysis's (an edit
    /// made while the worker refined is not overwritten).
    fn suggestions(
        &mut self,
        ctx: &egui::Context,
        rows: Vec<SuggestionRow>,
        thumbnails: Vec<u8>,
        (cancelled, timed_out): (bool, bool),
        best: Option<Box<Report>>,
    ) {
        let side = THUMB_SIDE as usize;
        let thumbs = thumbnails
            .chunks_exact(side * side * 4)
            .enumerate()
            .map(|(i, px)| {
                let image = egui::ColorImage::from_rgba_unmultiplied([side, side], px);
                ctx.load_texture(
                    format!("suggestion{i}"),
                    image,
                    egui::TextureOptions::LINEAR,
                )
            })
            .collect();
        let unedited = self.params.is_some() && self.params == self.analysed;
        let pick = self.suggest.pick.take();
        self.suggest = SuggestState {
            rows,
            thumbs,
            progress: None,
            cancelled,
            timed_out,
            ..SuggestState::default()
        };
        // The user's pick for this very photo and crop, where it is not the best.
        let picked = pick
            .filter(|p| {
                self.photo
                    .as_ref()
                    .is_some_and(|ph| ph.name == p.photo && ph.crop == p.crop)
            })
            .and_then(|p| {
                let i = self.suggest.rows.iter().position(|r| r.name == p.model)?;
                self.suggest.pick = Some(p);
                Some(i)
            })
            .filter(|&i| i > 0);
        if let Some(i) = picked.filter(|_| unedited) {
            self.request_adoption(i);
            return;
        }
        match best {
            Some(report) if unedited => self.adopt(0, *report),
            None if unedited && self.suggest.rows.first().is_some_and(|r| r.name == "noise") => {
                // The noise model is first: the analysis already shown is it.
                self.suggest.adopted = Some(0);
                self.suggest.adopted_params = self.params.clone();
            }
            _ => {}
        }
    }

    /// Makes suggestion `index`'s fitted params current: one undoable step; "Reset to
    /// analysed" returns to them.
    fn adopt(&mut self, index: usize, report: Report) {
        if let Some(cur) = self.params.clone() {
            self.undo.push(cur);
            self.redo.clear();
        }
        self.presets.morph = None;
        self.params = Some(report.params.clone());
        self.committed = Some(report.params.clone());
        self.analysed = Some(report.params.clone());
        self.model_stats = Some((report.params.clone(), report.model));
        self.stats_requested = Some(report.params.clone());
        self.suggest.adopted = Some(index);
        self.suggest.adopted_params = Some(report.params);
    }

    /// The row the current params came from, while they are unedited.
    fn adopted_row(&self) -> Option<usize> {
        self.suggest
            .adopted
            .filter(|_| self.params.is_some() && self.params == self.suggest.adopted_params)
    }

    /// The ranked list of models for the photo: thumbnails, scores, progress and Cancel while
    /// the worker refines; a click adopts a row.
    fn suggestions_panel(&mut self, ui: &mut egui::Ui) {
        if let Some(e) = &self.suggest.error {
            ui.colored_label(egui::Color32::from_rgb(240, 90, 70), e.as_str());
        }
        if let Some((done, total)) = self.suggest.progress {
            ui.horizontal(|ui| {
                let frac = if total > 0 {
                    done as f32 / total as f32
                } else {
                    0.0
                };
                let r = ui.add(
                    egui::ProgressBar::new(frac)
                        .desired_width(150.0)
                        .text(format!("refining {done}/{total} models")),
                );
                self.record("suggest.progress", &r);
                let r = ui
                    .button("Cancel")
                    .on_hover_text("Stop refining; rank with what is refined so far");
                self.record("suggest.cancel", &r);
                if r.clicked() {
                    host("cancelSuggestions", &[]);
                }
            });
            // No timed repaint: each progress message from the worker wakes the app. Without a
            // GPU (software WebGPU) a frame costs ~170 ms of CPU, so a 10 Hz repaint took one
            // of this machine's two cores from the worker and its helper while they refined.
        } else if self.suggest.on_request {
            ui.horizontal_wrapped(|ui| {
                let r = ui.button("Suggest models").on_hover_text(
                    "Retrieve and refine every structured model family for this photo and \
                     rank them against the noise model (the built-in sample waits for this \
                     click; your own photos get their suggestions at once)",
                );
                self.record("suggest.start", &r);
                if r.clicked() {
                    if host("suggestModels", &[]) {
                        self.suggest.on_request = false;
                    } else {
                        self.error =
                            Some("Model suggestions: the page's worker is unavailable".into());
                    }
                }
                ui.label("for this sample; your photos get them at once.");
            });
        } else if self.suggest.rows.is_empty() && self.suggest.error.is_none() {
            ui.label("Suggestions appear after the analysis.");
        }
        if self.suggest.timed_out {
            let refined = self
                .suggest
                .rows
                .iter()
                .filter(|r| r.refined.is_some())
                .count();
            ui.label(format!(
                "Time budget reached: {refined} models refined, the others ranked by retrieval."
            ));
        } else if self.suggest.cancelled {
            ui.label("Refinement cancelled: unrefined models ranked by retrieval.");
        }
        let adopted = self.adopted_row();
        let mut clicked = None;
        // Compact tiles (thumbnail, name, score), a few per row, so that the list does not
        // push the presets below the fold.
        ui.horizontal_wrapped(|ui| {
            ui.spacing_mut().item_spacing = egui::vec2(4.0, 4.0);
            for i in 0..self.suggest.rows.len() {
                let row = &self.suggest.rows[i];
                let mut tip = format!(
                    "{}: score {:.3} (lower is nearer)\ntexture distance {:.3}",
                    row.name, row.score, row.distance
                );
                if let Some(r) = row.retrieval {
                    tip += &format!("\nstructure distance: retrieval {r:.3}");
                    if let Some(f) = row.refined {
                        tip += &format!(" → refined {f:.3}");
                    } else if row.skipped {
                        tip += " (not refined: it could not reach the top three)";
                    }
                }
                tip += if adopted == Some(i) {
                    "\n(current model)"
                } else {
                    "\nclick to adopt"
                };
                let (rect, r) =
                    ui.allocate_exact_size(egui::vec2(56.0, 72.0), egui::Sense::click());
                let visuals = ui.visuals();
                let fill = if adopted == Some(i) {
                    Some(visuals.selection.bg_fill)
                } else if r.hovered() {
                    Some(visuals.widgets.hovered.bg_fill)
                } else {
                    None
                };
                let text = visuals.text_color();
                let painter = ui.painter();
                if let Some(f) = fill {
                    painter.rect_filled(rect, 3.0, f);
                }
                if let Some(t) = self.suggest.thumbs.get(i) {
                    let img = egui::Rect::from_min_size(
                        rect.min + egui::vec2(6.0, 3.0),
                        egui::vec2(44.0, 44.0),
                    );
                    egui::Image::new(t).paint_at(ui, img);
                }
                let font = egui::FontId::proportional(10.0);
                let name = row.name.replace('_', " ");
                painter.text(
                    rect.center_bottom() - egui::vec2(0.0, 19.0),
                    egui::Align2::CENTER_CENTER,
                    name,
                    font.clone(),
                    text,
                );
                let score = if self.suggest.adopting == Some(i) {
                    "fitting…".to_string()
                } else {
                    format!("{:.2}", row.score)
                };
                painter.text(
                    rect.center_bottom() - egui::vec2(0.0, 7.0),
                    egui::Align2::CENTER_CENTER,
                    score,
                    font,
                    text,
                );
                let r = r.on_hover_text(tip);
                self.record(format!("suggestion.{i}"), &r);
                if r.clicked() && adopted != Some(i) {
                    clicked = Some(i);
                }
            }
        });
        if let Some(i) = clicked {
            self.suggest.pick = self.photo.as_ref().map(|ph| Pick {
                photo: ph.name.clone(),
                crop: ph.crop,
                model: self.suggest.rows[i].name.clone(),
            });
            self.request_adoption(i);
        }
    }

    /// Asks the worker for suggestion `i` fitted to the photo ([`Command::Adopted`] brings it).
    fn request_adoption(&mut self, i: usize) {
        self.suggest.adopting = Some(i);
        if !host("adoptSuggestion", &[JsValue::from_f64(i as f64)]) {
            self.suggest.adopting = None;
            self.error = Some("Adopting a suggestion: the page's worker is unavailable".into());
        }
    }

    /// The refinement's time budget, in the "Model suggestions" header row (so that it takes
    /// no room from the list): 0 shows "none".
    fn refine_budget_control(&mut self, ui: &mut egui::Ui) {
        ui.label("Model suggestions");
        ui.add_space(12.0);
        ui.label("time budget");
        let r = ui
            .add(
                egui::DragValue::new(&mut self.refine_budget_s)
                    .range(0.0..=120.0)
                    .speed(0.1)
                    .max_decimals(1)
                    .custom_formatter(|v, _| {
                        if v <= 0.0 {
                            "none".into()
                        } else {
                            format!("{v:.1} s")
                        }
                    })
                    .custom_parser(|t| {
                        let t = t.trim().trim_end_matches('s').trim();
                        if t.eq_ignore_ascii_case("none") {
                            Some(0.0)
                        } else {
                            t.parse::<f64>().ok()
                        }
                    }),
            )
            .on_hover_text(
                "Refinement time budget: after this long the refinement stops (each model \
                 keeps its best point so far) and the list is ranked; applies to the running \
                 refinement too. none: every model gets its full refinement (the same result \
                 on every machine)",
            );
        self.record("suggest.budget", &r);
        if r.changed() {
            host(
                "setRefineBudget",
                &[JsValue::from_f64(self.refine_budget_s as f64)],
            );
        }
    }

    fn apply_commands(&mut self, ctx: &egui::Context) {
        let cmds: Vec<Command> = COMMANDS.with(|c| std::mem::take(&mut *c.borrow_mut()));
        for cmd in cmds {
            match cmd {
                Command::Busy { name, stage } => {
                    let since = self.busy.as_ref().map(|b| b.1).unwrap_or_else(now_ms);
                    let what = match name {
                        Some(n) => format!("{stage} {n}"),
                        None => stage,
                    };
                    self.busy = Some((what, since));
                }
                Command::Analysed {
                    report,
                    name,
                    ms,
                    preview,
                } => self.analysed(ctx, *report, name, ms, preview),
                Command::SuggestProgress { done, total } => {
                    if done == 0 {
                        // A new photo or crop: its list replaces the old one (the user's pick
                        // is kept for when the same crop is ranked again).
                        self.suggest = SuggestState {
                            pick: self.suggest.pick.take(),
                            ..SuggestState::default()
                        };
                    }
                    self.suggest.progress = Some((done, total));
                }
                Command::SuggestOnRequest => {
                    self.suggest = SuggestState {
                        on_request: true,
                        ..SuggestState::default()
                    };
                }
                Command::Suggestions {
                    rows,
                    thumbnails,
                    cancelled,
                    timed_out,
                    best,
                } => self.suggestions(ctx, rows, thumbnails, (cancelled, timed_out), best),
                Command::Adopted { index, report } => {
                    self.suggest.adopting = None;
                    self.adopt(index, *report);
                }
                Command::SuggestFailed(e) => {
                    self.suggest.progress = None;
                    self.suggest.adopting = None;
                    self.suggest.error = Some(e);
                }
                Command::ModelStats(stats) => {
                    let (p, s) = *stats;
                    self.model_stats = Some((p, s));
                }
                Command::Error(e) => {
                    self.busy = None;
                    self.error = Some(e);
                }
                Command::SetParams(p) => {
                    self.params = Some(*p);
                    self.error = None;
                }
                Command::SetView {
                    origin,
                    units_per_point,
                } => {
                    self.view = ViewState {
                        origin,
                        units_per_point,
                    }
                }
                Command::SetMode(m) => self.mode = m,
                Command::FlatShader(on) => self.flat_shader = on,
                Command::FrameCache(on) => self.frame_cache = on,
                Command::ViewLimit(limit) => self.view_limit = limit,
                Command::TileOptions {
                    size,
                    bits,
                    force_cpu,
                } => {
                    self.tile = TileSettings {
                        size,
                        bits,
                        force_cpu,
                    }
                }
                Command::GalleryPreset(name, params) => {
                    self.presets.gallery.push((
                        Preset {
                            name,
                            params: *params,
                            morph: None,
                        },
                        None,
                    ));
                }
                Command::ImportPresets(text) => match parse_library(&text) {
                    Ok(new) => {
                        let mut list = std::mem::take(&mut self.presets.list);
                        let added = new.len();
                        list.extend(new);
                        self.set_presets(list);
                        self.persist_presets();
                        self.status_note = Some(format!("Imported {added} presets"));
                    }
                    Err(e) => {
                        self.error = Some(format!("Import: {e}. Your presets are unchanged."));
                    }
                },
            }
        }
    }

    /// Undo bookkeeping: once no widget is being dragged, a changed params set is one step.
    fn commit_edits(&mut self, ctx: &egui::Context) {
        if self.presets.playing {
            // An animation is not an edit.
            self.committed = self.params.clone();
            return;
        }
        if ctx.dragged_id().is_some() {
            return;
        }
        if let (Some(p), Some(c)) = (&self.params, &self.committed)
            && p != c
        {
            self.undo.push(c.clone());
            self.redo.clear();
            self.committed = Some(p.clone());
        }
    }

    fn undo(&mut self) {
        if let (Some(prev), Some(cur)) = (self.undo.pop(), self.params.clone()) {
            self.redo.push(cur);
            self.params = Some(prev.clone());
            self.committed = Some(prev);
        }
    }

    fn redo(&mut self) {
        if let (Some(next), Some(cur)) = (self.redo.pop(), self.params.clone()) {
            self.undo.push(cur);
            self.params = Some(next.clone());
            self.committed = Some(next);
        }
    }

    fn record(&mut self, name: impl Into<String>, r: &egui::Response) {
        let rect = r.rect;
        self.widgets.insert(
            name.into(),
            [rect.min.x, rect.min.y, rect.width(), rect.height()],
        );
    }

    /// Left panel: samples, Open…, Camera…, the photo with its crop, status, plots.
    fn photo_panel(&mut self, ui: &mut egui::Ui) {
        ui.heading("Proctex");
        ui.label("Photo → procedural texture");
        ui.separator();
        ui.horizontal(|ui| {
            let r = ui
                .button("Open…")
                .on_hover_text("Open an image file (or drop one anywhere, or paste)");
            self.record("open", &r);
            if r.clicked() && !host("openFile", &[]) {
                self.error = Some("Open…: the page's file dialog is unavailable".into());
            }
            let r = ui
                .button("Camera…")
                .on_hover_text("Capture a photo with the camera");
            self.record("camera", &r);
            if r.clicked() && !host("openCamera", &[]) {
                self.error = Some("Camera…: the page's camera support is unavailable".into());
            }
        });
        ui.label("Samples:");
        ui.horizontal_wrapped(|ui| {
            for (i, name) in SAMPLES.iter().enumerate() {
                let short = name
                    .trim_end_matches(".png")
                    .trim_start_matches("skimage_")
                    .trim_start_matches("stk_");
                let selected = self.photo.as_ref().is_some_and(|p| p.name == *name);
                let r = ui.selectable_label(selected, short);
                self.record(format!("sample.{i}"), &r);
                if r.clicked() {
                    host("loadSample", &[JsValue::from_str(name)]);
                }
            }
        });
        ui.separator();
        self.crop_widget(ui);
        if let Some((what, since)) = self.busy.clone() {
            let elapsed = now_ms() - since;
            // Anything that takes longer than ~200 ms gets a visible progress indicator.
            if elapsed > 200.0 {
                let r = ui.label(format!("{what}… {:.1} s", elapsed / 1000.0));
                self.record("progress", &r);
            }
            // The elapsed time four times a second, not an animated spinner (which repaints
            // every frame): without a GPU each frame costs the worker CPU time (see the
            // suggestions' progress).
            ui.ctx()
                .request_repaint_after(std::time::Duration::from_millis(250));
        } else if let (Some(photo), Some(ms)) = (&self.photo, self.analysis_ms) {
            let r = ui.label(format!("{} — analysed in {ms:.0} ms", photo.name));
            self.record("status", &r);
        } else {
            ui.label("Loading the sample photo…");
        }
        if let Some(err) = self.error.clone() {
            let r = ui.colored_label(egui::Color32::from_rgb(240, 90, 70), err);
            self.record("error", &r);
            if ui.small_button("Dismiss").clicked() {
                self.error = None;
            }
        }
        if let Some(note) = &self.status_note {
            ui.label(note.as_str());
        }
        ui.separator();
        egui::CollapsingHeader::new("Presets and morph")
            .default_open(true)
            .show(ui, |ui| self.presets_panel(ui));
        egui::collapsing_header::CollapsingState::load_with_default_open(
            ui.ctx(),
            ui.make_persistent_id("model_suggestions"),
            true,
        )
        .show_header(ui, |ui| self.refine_budget_control(ui))
        .body(|ui| self.suggestions_panel(ui));
        egui::CollapsingHeader::new("Plots")
            .default_open(true)
            .show(ui, |ui| self.plots(ui));
    }

    /// PNG tile export: size, bit depth, Export PNG… (then progress and Cancel).
    fn tile_row(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.label("PNG tile:");
            if let Some(job) = &self.tile_job {
                let f = job.done_rows as f32 / job.size as f32;
                let on = match job.source {
                    TileSource::Gpu(_) => "GPU",
                    TileSource::Cpu(_) => "CPU",
                };
                ui.add(egui::ProgressBar::new(f).desired_width(120.0).text(format!(
                    "{}² {} % ({on})",
                    job.size,
                    (f * 100.0) as u32
                )));
                let r = ui.small_button("Cancel");
                self.record("export.png_cancel", &r);
                if r.clicked() {
                    host("tileAbort", &[]);
                    self.tile_job = None;
                    self.status_note = Some("PNG tile export cancelled".into());
                }
                return;
            }
            let r = egui::ComboBox::from_id_salt("tile_size")
                .width(70.0)
                .selected_text(format!("{}²", self.tile.size))
                .show_ui(ui, |ui| {
                    for n in [256u32, 512, 1024, 2048, 4096, 8192] {
                        ui.selectable_value(&mut self.tile.size, n, format!("{n}²"));
                    }
                });
            self.record("export.png_size", &r.response);
            let r = egui::ComboBox::from_id_salt("tile_bits")
                .width(60.0)
                .selected_text(format!("{}-bit", self.tile.bits))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.tile.bits, 8, "8-bit");
                    ui.selectable_value(&mut self.tile.bits, 16, "16-bit");
                });
            self.record("export.png_bits", &r.response);
            let r = ui
                .add_enabled(self.params.is_some(), egui::Button::new("PNG…").small())
                .on_hover_text(
                    "Download a seamless tile of the texture, one photo pixel per tile pixel \
                     (every band made periodic over the tile; structured models: the pattern \
                     turned to the nearest quarter turn, a whole number of cells over the tile; \
                     solid textures: their plane texture)",
                );
            self.record("export.png", &r);
            if r.clicked()
                && let Some(p) = self.params.clone()
            {
                self.start_tile(&p, ui.ctx());
            }
        });
    }

    /// Starts a PNG tile export of `params` on the GPU (CPU when there is none, or forced).
    fn start_tile(&mut self, params: &Params, ctx: &egui::Context) {
        let (size, bits) = (self.tile.size, self.tile.bits);
        let gpu = if self.tile.force_cpu {
            None
        } else {
            self.gpu
                .as_ref()
                .map(|(device, queue)| SeamlessGpu::new(device, queue, params, size, 1.0))
        };
        let source = match gpu {
            Some(Ok(g)) => TileSource::Gpu(Box::new(g)),
            other => {
                if let Some(Err(e)) = other {
                    web_sys::console::warn_1(
                        &format!("PNG tile on the GPU: {e}; using the CPU").into(),
                    );
                }
                match SeamlessCpu::new(params, size, 1.0) {
                    Ok(c) => TileSource::Cpu(Box::new(c)),
                    Err(e) => {
                        self.error = Some(format!("PNG tile: {e}"));
                        return;
                    }
                }
            }
        };
        if !host(
            "tileBegin",
            &[
                JsValue::from(size),
                JsValue::from(size),
                JsValue::from(bits as u32),
            ],
        ) {
            self.error = Some("PNG tile: the page cannot write PNG files (no tileBegin)".into());
            return;
        }
        self.tile_job = Some(TileJob {
            size,
            bits,
            source,
            next_row: 0,
            done_rows: 0,
            started_ms: now_ms(),
            turn: proctex::seamless::tile_turn(params),
        });
        ctx.request_repaint();
    }

    /// Advances the PNG tile export by what is ready: a read-back strip from the GPU (and the
    /// next strip submitted), or a few CPU rows (about 30 ms of work).
    fn step_tile(&mut self, ctx: &egui::Context, frame: &eframe::Frame) {
        if self.gpu.is_none()
            && let Some(rs) = frame.wgpu_render_state()
        {
            self.gpu = Some((rs.device.clone(), rs.queue.clone()));
        }
        let Some(job) = &mut self.tile_job else {
            return;
        };
        ctx.request_repaint();
        let size = job.size;
        let mut strip = None;
        match &mut job.source {
            TileSource::Gpu(g) => {
                match g.take() {
                    Some(Ok(s)) => strip = Some(s),
                    Some(Err(e)) => {
                        host("tileAbort", &[]);
                        self.tile_job = None;
                        self.error = Some(format!("PNG tile: {e}"));
                        return;
                    }
                    None => {}
                }
                if !g.busy()
                    && job.next_row < size
                    && let Some((device, queue)) = &self.gpu
                {
                    g.submit(device, queue, job.next_row);
                    job.next_row = (job.next_row + g.rows()).min(size);
                }
            }
            TileSource::Cpu(c) => {
                let t0 = now_ms();
                let mut rows = Vec::new();
                let first = job.next_row;
                while job.next_row < size && now_ms() - t0 < 30.0 {
                    let n = (16_384 / size).max(1);
                    rows.extend(c.strip(job.next_row, n));
                    job.next_row = (job.next_row + n).min(size);
                }
                if !rows.is_empty() {
                    strip = Some((first, rows));
                }
            }
        }
        if let Some((_, pixels)) = strip {
            let bytes = png_scanlines(&pixels, size as usize, job.bits);
            host(
                "tileRows",
                &[js_sys::Uint8Array::from(bytes.as_slice()).into()],
            );
            job.done_rows += (pixels.len() / size as usize) as u32;
        }
        if job.done_rows >= size {
            let name = format!("proctex-tile-{size}-{}bit.png", job.bits);
            host("tileEnd", &[JsValue::from_str(&name)]);
            let turn = job
                .turn
                .map(|(from, to)| format!("; the pattern turned {from:.1}° → {to:.0}° to repeat"))
                .unwrap_or_default();
            self.status_note = Some(format!(
                "PNG tile {size}² ({}-bit) rendered in {:.1} s{turn}",
                job.bits,
                (now_ms() - job.started_ms) / 1000.0
            ));
            self.tile_job = None;
        }
    }

    /// Save, load, rename, reorder, delete presets; choose two or more to morph between.
    fn presets_panel(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        ui.horizontal(|ui| {
            let r = ui.add(
                egui::TextEdit::singleline(&mut self.presets.new_name)
                    .hint_text("name")
                    .desired_width(120.0),
            );
            self.record("preset.name", &r);
            let r = ui.add_enabled(self.params.is_some(), egui::Button::new("Save preset"));
            self.record("preset.save", &r);
            if r.clicked()
                && let Some(p) = self.params.clone()
            {
                let name = match self.presets.new_name.trim() {
                    "" => self
                        .photo
                        .as_ref()
                        .map(|p| p.name.trim_end_matches(".png").to_string())
                        .unwrap_or_else(|| format!("preset {}", self.presets.list.len() + 1)),
                    n => n.to_string(),
                };
                let mut list = std::mem::take(&mut self.presets.list);
                list.push(Preset {
                    name,
                    params: p,
                    morph: None,
                });
                self.set_presets(list);
                self.presets.new_name.clear();
                self.persist_presets();
            }
        });
        ui.horizontal(|ui| {
            let json = self.params.as_ref().map(Params::to_json);
            let r = ui
                .add_enabled(json.is_some(), egui::Button::new("Params JSON…").small())
                .on_hover_text("Download the current params (proctex/1); drop or paste it back");
            self.record("params.download", &r);
            if r.clicked()
                && let Some(j) = &json
            {
                host(
                    "downloadText",
                    &[
                        JsValue::from_str("proctex-texture.json"),
                        JsValue::from_str(j),
                    ],
                );
            }
            let r = ui
                .add_enabled(json.is_some(), egui::Button::new("Copy link").small())
                .on_hover_text("Copy a link that opens this texture (params in the URL fragment)");
            self.record("params.link", &r);
            if r.clicked()
                && let Some(j) = &json
            {
                host("copyShareLink", &[JsValue::from_str(j)]);
                self.status_note = Some("Link copied to the clipboard".into());
            }
        });
        ui.horizontal(|ui| {
            ui.label("Shader:");
            let clicked = self.shader_buttons(ui, "export", self.params.is_some(), "this texture");
            if let (Some((format, ext, copy)), Some(p)) = (clicked, &self.params) {
                let text = export_shader(std::slice::from_ref(p), ext);
                self.deliver_shader(format, ext, copy, "proctex-texture", text);
            }
        });
        self.tile_row(ui);
        ui.horizontal(|ui| {
            let r = ui.small_button("Export…");
            self.record("presets.export", &r);
            if r.clicked() {
                host(
                    "downloadText",
                    &[
                        JsValue::from_str("proctex-presets.json"),
                        JsValue::from_str(&library_json(&self.presets.list)),
                    ],
                );
            }
            let r = ui.small_button("Import…");
            self.record("presets.import", &r);
            if r.clicked() {
                host("openPresets", &[]);
            }
        });
        if !self.presets.gallery.is_empty() {
            ui.label("Gallery (the samples, analysed):");
            let mut load = None;
            ui.horizontal_wrapped(|ui| {
                for i in 0..self.presets.gallery.len() {
                    let (preset, thumb) = &mut self.presets.gallery[i];
                    let id = thumb
                        .get_or_insert_with(|| {
                            let rgba = crate::jobs::preview_rgba(&preset.params, 40, 40);
                            let img = egui::ColorImage::from_rgba_unmultiplied([40, 40], &rgba);
                            ctx.load_texture(
                                format!("gallery{i}"),
                                img,
                                egui::TextureOptions::LINEAR,
                            )
                        })
                        .id();
                    let name = preset.name.clone();
                    let r = ui
                        .add(egui::Button::image((id, egui::vec2(32.0, 32.0))))
                        .on_hover_text(format!("{name}: click to load"));
                    self.record(format!("gallery.{i}"), &r);
                    if r.clicked() {
                        load = Some(i);
                    }
                }
                let r = ui
                    .small_button("+ to presets")
                    .on_hover_text("Copy the gallery into your presets (to rename, morph, export)");
                self.record("gallery.add", &r);
                if r.clicked() {
                    let mut list = std::mem::take(&mut self.presets.list);
                    list.extend(self.presets.gallery.iter().map(|(p, _)| p.clone()));
                    self.set_presets(list);
                    self.persist_presets();
                }
            });
            if let Some(i) = load {
                self.presets.morph = None;
                self.params = Some(self.presets.gallery[i].0.params.clone());
            }
        }
        let mut action: Option<(usize, &'static str)> = None;
        let n = self.presets.list.len();
        for i in 0..n {
            if self.presets.thumbs[i].is_none() {
                let rgba = crate::jobs::preview_rgba(&self.presets.list[i].params, 40, 40);
                let img = egui::ColorImage::from_rgba_unmultiplied([40, 40], &rgba);
                self.presets.thumbs[i] =
                    Some(ctx.load_texture(format!("preset{i}"), img, egui::TextureOptions::LINEAR));
            }
            let thumb = self.presets.thumbs[i].as_ref().map(|t| t.id());
            ui.horizontal(|ui| {
                let r = ui.checkbox(&mut self.presets.selected[i], "");
                self.record(format!("preset.{i}.morph"), &r);
                if let Some(id) = thumb {
                    ui.image((id, egui::vec2(24.0, 24.0)));
                }
                if let Some((j, text)) = self.presets.renaming.as_mut()
                    && *j == i
                {
                    let r = ui.add(egui::TextEdit::singleline(text).desired_width(110.0));
                    self.record(format!("preset.{i}.name"), &r);
                    if r.lost_focus() {
                        action = Some((i, "renamed"));
                    }
                } else {
                    let label = match &self.presets.list[i].morph {
                        Some(_) => format!("⟷ {}", self.presets.list[i].name),
                        None => self.presets.list[i].name.clone(),
                    };
                    let label = if label.chars().count() > 22 {
                        format!("{}…", label.chars().take(21).collect::<String>())
                    } else {
                        label
                    };
                    let r = ui.selectable_label(false, label).on_hover_text("Load");
                    self.record(format!("preset.{i}"), &r);
                    if r.clicked() {
                        action = Some((i, "load"));
                    }
                }
                for (what, icon) in [
                    ("rename", "✏"),
                    ("up", "↑"),
                    ("down", "↓"),
                    ("delete", "del"),
                ] {
                    let r = ui.small_button(icon).on_hover_text(what);
                    self.record(format!("preset.{i}.{what}"), &r);
                    if r.clicked() {
                        action = Some((i, what));
                    }
                }
            });
        }
        if let Some((i, what)) = action {
            self.preset_action(i, what);
        }
        self.morph_controls(ui);
    }

    fn preset_action(&mut self, i: usize, what: &str) {
        let mut list = self.presets.list.clone();
        match what {
            "load" => {
                let p = &self.presets.list[i];
                match &p.morph {
                    Some(m) => {
                        self.presets.morph = Some(m.keys.clone());
                        self.presets.morph_from = None;
                        self.presets.duration_s = m.duration_s;
                        self.presets.t = 0.0;
                        self.params = Some(m.keys[0].clone());
                    }
                    None => {
                        self.presets.morph = None;
                        self.params = Some(p.params.clone());
                    }
                }
                return;
            }
            "rename" => {
                self.presets.renaming = Some((i, list[i].name.clone()));
                return;
            }
            "renamed" => {
                if let Some((_, name)) = self.presets.renaming.take()
                    && !name.trim().is_empty()
                {
                    list[i].name = name.trim().to_string();
                }
            }
            "up" if i > 0 => list.swap(i, i - 1),
            "down" if i + 1 < list.len() => list.swap(i, i + 1),
            "delete" => {
                list.remove(i);
            }
            _ => return,
        }
        let selected = self.presets.selected.clone();
        self.set_presets(list);
        if what == "renamed" {
            self.presets.selected = selected;
        }
        self.persist_presets();
    }

    /// "Copy WGSL", "WGSL…", "Copy GLSL", "GLSL…" buttons (widgets `{prefix}.copy_wgsl`,
    /// `{prefix}.download_wgsl`, ...): the clicked one as (language, extension, copy?).
    fn shader_buttons(
        &mut self,
        ui: &mut egui::Ui,
        prefix: &str,
        enabled: bool,
        what: &str,
    ) -> Option<(&'static str, &'static str, bool)> {
        let mut clicked = None;
        for (format, ext) in [("WGSL", "wgsl"), ("GLSL", "glsl")] {
            let r = ui
                .add_enabled(enabled, egui::Button::new(format!("Copy {format}")).small())
                .on_hover_text(format!(
                    "Copy a complete {format} shader of {what} (params baked in, tile bake \
                     passes, host notes in its header) to the clipboard"
                ));
            self.record(format!("{prefix}.copy_{ext}"), &r);
            if r.clicked() {
                clicked = Some((format, ext, true));
            }
            let r = ui
                .add_enabled(enabled, egui::Button::new(format!("{format}…")).small())
                .on_hover_text(format!("Download the {format} shader of {what}"));
            self.record(format!("{prefix}.download_{ext}"), &r);
            if r.clicked() {
                clicked = Some((format, ext, false));
            }
        }
        clicked
    }

    /// Puts an exported shader on the clipboard or downloads it as `{stem}.{ext}`.
    fn deliver_shader(
        &mut self,
        format: &str,
        ext: &str,
        copy: bool,
        stem: &str,
        text: Result<String, String>,
    ) {
        match text {
            Ok(text) if copy => {
                host("copyText", &[JsValue::from_str(&text)]);
                self.status_note = Some(format!(
                    "{format} shader copied to the clipboard ({} lines)",
                    text.lines().count()
                ));
            }
            Ok(text) => {
                host(
                    "downloadText",
                    &[
                        JsValue::from_str(&format!("{stem}.{ext}")),
                        JsValue::from_str(&text),
                    ],
                );
            }
            Err(e) => self.error = Some(format!("{format} export: {e}")),
        }
    }

    /// The morph: t slider, play/loop, duration, save as a preset.
    fn morph_controls(&mut self, ui: &mut egui::Ui) {
        // Indices, not params: no per-frame clones; keys are copied only when the ticks change.
        let chosen: Vec<usize> = (0..self.presets.selected.len())
            .filter(|&i| self.presets.selected[i])
            .collect();
        if chosen.len() >= 2 && self.presets.morph_from.as_ref() != Some(&chosen) {
            let keys = chosen
                .iter()
                .map(|&i| self.presets.list[i].params.clone())
                .collect();
            self.presets.morph = Some(keys);
            self.presets.morph_from = Some(chosen);
            self.presets.t = 0.0;
            self.apply_morph();
        }
        // The keys are borrowed where used (cloned only to save): no per-frame copies.
        let Some(n_keys) = self.presets.morph.as_ref().map(Vec::len) else {
            ui.label("Tick two or more presets to morph between them.");
            return;
        };
        ui.label(format!("Morph through {n_keys} presets (Lagae §8)"));
        let r = ui.add(egui::Slider::new(&mut self.presets.t, 0.0..=1.0).text("t"));
        self.record("morph.t", &r);
        if r.changed() {
            self.presets.playing = false;
            self.apply_morph();
        }
        ui.horizontal(|ui| {
            let label = if self.presets.playing {
                "Pause"
            } else {
                "Play"
            };
            let r = ui.button(label);
            self.record("morph.play", &r);
            if r.clicked() {
                self.presets.playing = !self.presets.playing;
            }
            ui.checkbox(&mut self.presets.looping, "loop");
            ui.add(
                egui::DragValue::new(&mut self.presets.duration_s)
                    .range(0.5..=600.0)
                    .suffix(" s"),
            );
        });
        ui.horizontal(|ui| {
            let r = ui.small_button("Save morph");
            self.record("morph.save", &r);
            if r.clicked()
                && let Some(keys) = self.presets.morph.clone()
            {
                let mut list = self.presets.list.clone();
                list.push(Preset {
                    name: format!("morph of {n_keys}"),
                    params: keys[0].clone(),
                    morph: Some(MorphPreset {
                        keys,
                        duration_s: self.presets.duration_s,
                    }),
                });
                self.set_presets(list);
                self.persist_presets();
            }
            let r = ui.small_button("Stop morphing");
            self.record("morph.stop", &r);
            if r.clicked() {
                self.presets.morph = None;
                self.presets.morph_from = None;
                self.presets.playing = false;
                self.presets.selected.iter_mut().for_each(|s| *s = false);
            }
        });
        ui.horizontal(|ui| {
            ui.label("Shader, t a uniform:");
            if let Some((format, ext, copy)) = self.shader_buttons(ui, "morph", true, "this morph")
                && let Some(keys) = &self.presets.morph
            {
                let text = export_shader(keys, ext);
                self.deliver_shader(format, ext, copy, "proctex-morph", text);
            }
        });
    }

    /// Sets the params to the morph at the current t (a uniform update only).
    fn apply_morph(&mut self) {
        if let Some(keys) = &self.presets.morph {
            match proctex::morph::morph_path(keys, self.presets.t) {
                Ok(p) => self.params = Some(p),
                Err(e) => self.error = Some(format!("Morph: {e}")),
            }
        }
    }

    /// Advances a playing morph by the frame time.
    fn advance_morph(&mut self, ctx: &egui::Context) {
        if !self.presets.playing || self.presets.morph.is_none() {
            return;
        }
        let dt = ctx.input(|i| i.stable_dt).min(0.25);
        let mut t = self.presets.t + dt / self.presets.duration_s.max(0.1);
        if t >= 1.0 {
            if self.presets.looping {
                t -= 1.0;
            } else {
                t = 1.0;
                self.presets.playing = false;
            }
        }
        self.presets.t = t;
        self.apply_morph();
        ctx.request_repaint();
    }

    /// The photo with the crop rectangle: drag inside to move it, at a corner to resize, outside
    /// to draw a new one. Every change asks for a re-analysis (the page coalesces requests while
    /// the worker is busy, so dragging re-analyses as fast as the worker can).
    fn crop_widget(&mut self, ui: &mut egui::Ui) {
        let Some(photo) = self.photo.as_ref() else {
            return;
        };
        let (full, texture, old) = (photo.full, photo.texture.id(), photo.crop);
        let [fw, fh] = full.map(|v| v as f32);
        let k = (ui.available_width() / fw).min(200.0 / fh);
        let (rect, response) =
            ui.allocate_exact_size(egui::vec2(fw * k, fh * k), egui::Sense::drag());
        let to_screen = |x: f32, y: f32| rect.min + egui::vec2(x * k, y * k);
        let to_photo = |p: egui::Pos2| [(p.x - rect.min.x) / k, (p.y - rect.min.y) / k];
        let crop_rect = |c: [u32; 4]| {
            egui::Rect::from_min_max(
                to_screen(c[0] as f32, c[1] as f32),
                to_screen((c[0] + c[2]) as f32, (c[1] + c[3]) as f32),
            )
        };
        let mut crop = old;
        if response.drag_started()
            && let Some(pos) = response.interact_pointer_pos()
        {
            let r = crop_rect(crop);
            let corners = [
                r.left_top(),
                r.right_top(),
                r.left_bottom(),
                r.right_bottom(),
            ];
            let near = corners
                .iter()
                .enumerate()
                .find(|(_, c)| c.distance(pos) <= 10.0)
                .map(|(i, _)| i);
            let drag = if let Some(i) = near {
                // Keep the opposite corner fixed.
                let opp = corners[3 - i];
                CropDrag::Resize {
                    fixed: to_photo(opp),
                }
            } else if r.contains(pos) {
                CropDrag::Move
            } else {
                CropDrag::Resize {
                    fixed: to_photo(pos),
                }
            };
            self.crop_drag = Some((drag, crop, pos));
        }
        if let Some((drag, start_crop, start_pos)) = self.crop_drag
            && let Some(pos) = response.interact_pointer_pos()
            && response.dragged()
        {
            let (w, h) = (full[0], full[1]);
            match drag {
                CropDrag::Move => {
                    let d = (pos - start_pos) / k;
                    let x = (start_crop[0] as f32 + d.x)
                        .round()
                        .clamp(0.0, (w - start_crop[2]) as f32);
                    let y = (start_crop[1] as f32 + d.y)
                        .round()
                        .clamp(0.0, (h - start_crop[3]) as f32);
                    crop = [x as u32, y as u32, start_crop[2], start_crop[3]];
                }
                CropDrag::Resize { fixed } => {
                    let p = to_photo(pos);
                    let (x0, x1) = (fixed[0].min(p[0]), fixed[0].max(p[0]));
                    let (y0, y1) = (fixed[1].min(p[1]), fixed[1].max(p[1]));
                    let x0 = x0.round().clamp(0.0, (w - MIN_CROP) as f32) as u32;
                    let y0 = y0.round().clamp(0.0, (h - MIN_CROP) as f32) as u32;
                    let x1 = (x1.round() as u32).clamp(x0 + MIN_CROP, w);
                    let y1 = (y1.round() as u32).clamp(y0 + MIN_CROP, h);
                    crop = [x0, y0, x1 - x0, y1 - y0];
                }
            }
        }
        if response.drag_stopped() {
            self.crop_drag = None;
        }
        let painter = ui.painter_at(rect);
        painter.image(
            texture,
            rect,
            egui::Rect::from_min_max(egui::pos2(0.0, 0.0), egui::pos2(1.0, 1.0)),
            egui::Color32::WHITE,
        );
        let r = crop_rect(crop);
        let shade = egui::Color32::from_black_alpha(140);
        for outside in [
            egui::Rect::from_min_max(rect.min, egui::pos2(rect.max.x, r.min.y)),
            egui::Rect::from_min_max(egui::pos2(rect.min.x, r.max.y), rect.max),
            egui::Rect::from_min_max(
                egui::pos2(rect.min.x, r.min.y),
                egui::pos2(r.min.x, r.max.y),
            ),
            egui::Rect::from_min_max(
                egui::pos2(r.max.x, r.min.y),
                egui::pos2(rect.max.x, r.max.y),
            ),
        ] {
            painter.rect_filled(outside, 0.0, shade);
        }
        let yellow = egui::Color32::from_rgb(250, 200, 60);
        painter.rect_stroke(
            r,
            0.0,
            egui::Stroke::new(1.5, yellow),
            egui::StrokeKind::Middle,
        );
        for c in [
            r.left_top(),
            r.right_top(),
            r.left_bottom(),
            r.right_bottom(),
        ] {
            painter.circle_filled(c, 3.5, yellow);
        }
        self.record("photo", &response);
        self.widgets
            .insert("crop".into(), [r.min.x, r.min.y, r.width(), r.height()]);
        ui.horizontal(|ui| {
            ui.label(format!(
                "crop {}×{} at {}, {}",
                crop[2], crop[3], crop[0], crop[1]
            ));
            let whole = [0, 0, full[0], full[1]];
            let r = ui.add_enabled(crop != whole, egui::Button::new("Whole photo").small());
            self.record("crop_reset", &r);
            if r.clicked() {
                crop = whole;
            }
        });
        if crop != old {
            if let Some(p) = self.photo.as_mut() {
                p.crop = crop;
            }
            let seed = self.params.as_ref().map(|p| p.seed).unwrap_or(1);
            let args: Vec<JsValue> = crop
                .iter()
                .chain(std::iter::once(&seed))
                .map(|&v| JsValue::from(v))
                .collect();
            host("analyseCrop", &args);
        }
    }

    /// The radially averaged power spectrum and the RGB histograms, photo against model. The
    /// model's statistics are recomputed by the worker once edits pause.
    fn plots(&mut self, ui: &mut egui::Ui) {
        use egui_plot::{Legend, Line, LineStyle, Plot, PlotPoints};
        let Some(photo) = self.photo_stats.clone() else {
            return;
        };
        let model = self.model_stats.as_ref().map(|(_, s)| s.clone());
        let model = model.as_ref();
        let current = self.plots_current();
        ui.label(if current {
            "Photo (solid) vs model (dashed)"
        } else {
            "Photo (solid) vs model (dashed) — updating…"
        });
        let ring_points = |spec: &[f64]| -> PlotPoints<'static> {
            spec.iter()
                .enumerate()
                .filter(|(_, p)| **p > 0.0)
                .map(|(k, p)| {
                    // Ring k spans 2^−(1 + (k+1)/4) … 2^−(1 + k/4) cycles per texel.
                    let log2_f = -(1.0 + (k as f64 + 0.5) / 4.0);
                    [log2_f, 10.0 * p.log10()]
                })
                .collect()
        };
        let r = Plot::new("spectrum")
            .height(150.0)
            .legend(Legend::default())
            .x_axis_label("log₂ frequency (cycles / texel)")
            .y_axis_label("power dB")
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.line(
                    Line::new("photo", ring_points(&photo.spectrum))
                        .color(egui::Color32::from_rgb(230, 230, 230)),
                );
                if let Some(m) = model {
                    plot.line(
                        Line::new("model", ring_points(&m.spectrum))
                            .color(egui::Color32::from_rgb(250, 200, 60))
                            .style(LineStyle::dashed_loose()),
                    );
                }
            });
        self.record("plot.spectrum", &r.response);
        let colours = [
            egui::Color32::from_rgb(235, 90, 80),
            egui::Color32::from_rgb(90, 200, 100),
            egui::Color32::from_rgb(90, 140, 240),
        ];
        let hist_points = |h: &[f64]| -> PlotPoints<'static> {
            let n = h.len() as f64;
            h.iter()
                .enumerate()
                .map(|(i, v)| [(i as f64 + 0.5) / n, *v * n])
                .collect()
        };
        let r = Plot::new("histograms")
            .height(140.0)
            .x_axis_label("value")
            .y_axis_label("density")
            .allow_scroll(false)
            .show(ui, |plot| {
                for c in 0..3 {
                    let name = ["R", "G", "B"][c];
                    plot.line(
                        Line::new(format!("photo {name}"), hist_points(&photo.histograms[c]))
                            .color(colours[c]),
                    );
                    if let Some(m) = model {
                        plot.line(
                            Line::new(format!("model {name}"), hist_points(&m.histograms[c]))
                                .color(colours[c])
                                .style(LineStyle::dashed_loose()),
                        );
                    }
                }
            });
        self.record("plot.histograms", &r.response);
    }

    fn plots_current(&self) -> bool {
        match (&self.model_stats, &self.params) {
            (Some((p, _)), Some(cur)) => p == cur,
            _ => false,
        }
    }

    /// Asks the worker for the model's statistics once edits have paused for 300 ms.
    fn request_stats(&mut self, ctx: &egui::Context) {
        let Some(params) = &self.params else {
            return;
        };
        if self.stats_requested.as_ref() == Some(params) {
            return;
        }
        let idle = now_ms() - self.last_edit_ms;
        if ctx.dragged_id().is_some() || idle < 300.0 {
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
            return;
        }
        self.stats_requested = Some(params.clone());
        host("modelStats", &[JsValue::from_str(&params.to_json())]);
    }

    /// Right panel: history buttons and a slider for every parameter.
    fn controls(&mut self, ui: &mut egui::Ui) {
        ui.heading("Parameters");
        ui.horizontal(|ui| {
            let r = ui
                .add_enabled(!self.undo.is_empty(), egui::Button::new("Undo"))
                .on_hover_text("Ctrl+Z");
            self.record("undo", &r);
            if r.clicked() {
                self.undo();
            }
            let r = ui
                .add_enabled(!self.redo.is_empty(), egui::Button::new("Redo"))
                .on_hover_text("Ctrl+Shift+Z");
            self.record("redo", &r);
            if r.clicked() {
                self.redo();
            }
            let r = ui.add_enabled(
                self.analysed.is_some(),
                egui::Button::new("Reset to analysed"),
            );
            self.record("reset", &r);
            if r.clicked()
                && let Some(a) = &self.analysed
            {
                self.params = Some(a.clone());
            }
        });
        let Some(params) = self.params.as_mut() else {
            return;
        };
        let before = params.clone();
        let mut rects: Vec<(String, egui::Response)> = Vec::new();
        ui.separator();
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.label("Transform");
            let r = ui.add(
                egui::Slider::new(&mut params.transform.scale, 0.05..=50.0)
                    .logarithmic(true)
                    .text("scale (px per texel)"),
            );
            rects.push(("scale".into(), r));
            let r = ui.add(
                egui::Slider::new(&mut params.transform.rotation_deg, -180.0..=180.0)
                    .text("rotation °"),
            );
            rects.push(("rotation".into(), r));
            ui.horizontal(|ui| {
                ui.label("seed");
                let r = ui.add(egui::DragValue::new(&mut params.seed));
                rects.push(("seed".into(), r));
                let r = ui
                    .checkbox(&mut params.solid, "solid (3D noise)")
                    .on_hover_text("Plane view shows the z = 0 slice of the solid texture");
                rects.push(("solid".into(), r));
            });
            ui.separator();
            ui.label("Colour");
            ui.horizontal(|ui| {
                ui.label("mean colour");
                let r = ui.color_edit_button_rgb(&mut params.colour.mean);
                rects.push(("mean".into(), r));
            });
            let r = ui.add(
                egui::Slider::new(&mut params.colour.contrast, 0.0..=MAX_CONTRAST).text("contrast"),
            );
            rects.push(("contrast".into(), r));
            if let Model::Structured(m) = &mut params.model {
                structure_controls(ui, m, &mut rects);
                ui.separator();
                ui.label("Residual noise (what the structure does not explain)");
            }
            let model = params.model.noise_layer_mut();
            let r = ui.checkbox(&mut model.histogram.enabled, "histogram matching");
            rects.push(("histogram".into(), r));
            let scale = params.transform.scale;
            for (c, weights) in model.weights.iter_mut().enumerate() {
                ui.separator();
                ui.label(match c {
                    0 => "Channel 1 (principal axis) — band weights",
                    1 => "Channel 2 — band weights",
                    _ => "Channel 3 — band weights",
                });
                let max = weights.iter().cloned().fold(0.05f32, f32::max) * 2.0;
                for (j, w) in weights.iter_mut().enumerate() {
                    // Band j holds wavelengths of 2^(j+1)…2^(j+2) texels, i.e. frequencies
                    // 1/hi…1/lo cycles per pixel.
                    let lo = (1u32 << (j + 1)) as f32 * scale;
                    let hi = (1u32 << (j + 2)) as f32 * scale;
                    let r = ui
                        .add(egui::Slider::new(w, 0.0..=max).text(format!(
                            "1/{}–1/{} cyc/px",
                            short(hi),
                            short(lo)
                        )))
                        .on_hover_text(format!(
                            "band {j}: wavelengths {}–{} px ({}–{} texels); 0 removes it",
                            short(lo),
                            short(hi),
                            1u32 << (j + 1),
                            1u32 << (j + 2)
                        ));
                    rects.push((format!("weight.{c}.{j}"), r));
                }
            }
        });
        if *params != before {
            self.last_edit_ms = now_ms();
        }
        for (name, r) in rects {
            self.record(name, &r);
        }
    }

    /// The view toolbar (above the central panel).
    fn toolbar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            for m in ViewMode::ALL {
                let r = ui.selectable_label(self.mode == m, m.label());
                self.record(format!("mode.{}", m.name()), &r);
                if r.clicked() {
                    self.mode = m;
                }
            }
            ui.separator();
            let r = ui
                .checkbox(&mut self.period_outline, "tile outline")
                .on_hover_text("Outline the tile period: the texture repeats seamlessly across it");
            self.record("period", &r);
        });
    }

    /// Central panel: the texture.
    fn view_panel(&mut self, ui: &mut egui::Ui) {
        let size = match self.view_limit {
            Some(limit) => ui.available_size().min(limit),
            None => ui.available_size(),
        };
        let (rect, response) = ui.allocate_exact_size(size, egui::Sense::click_and_drag());
        self.record("texture", &response);
        let Some(params) = self.params.clone() else {
            ui.painter().text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                "Analysing…",
                egui::FontId::proportional(18.0),
                ui.visuals().text_color(),
            );
            return;
        };
        let ppp = ui.ctx().pixels_per_point();
        match self.mode {
            ViewMode::Sphere | ViewMode::Cube => {
                self.orbit_input(ui, &response);
                let mut solid = params;
                solid.solid = true;
                self.orbit.shape = if self.mode == ViewMode::Sphere {
                    Shape::Sphere
                } else {
                    Shape::Cube
                };
                let px = rect.size() * ppp;
                let sv = SolidView::new(
                    &self.orbit,
                    [px.x.round(), px.y.round()],
                    [(rect.min.x * ppp).round(), (rect.min.y * ppp).round()],
                );
                self.paint_texture(ui, rect, solid, Pass::Solid, View::default(), Some(sv));
            }
            ViewMode::Plane | ViewMode::Split => {
                self.pan_zoom_input(ui, rect, &response);
                let (photo_rect, tex_rect) = if self.mode == ViewMode::Split {
                    let mid = rect.center().x.round();
                    (
                        Some(egui::Rect::from_min_max(
                            rect.min,
                            egui::pos2(mid, rect.max.y),
                        )),
                        egui::Rect::from_min_max(egui::pos2(mid, rect.min.y), rect.max),
                    )
                } else {
                    (None, rect)
                };
                let view = View {
                    origin: self.view.origin,
                    pixel_size: self.view.units_per_point / ppp,
                    z: 0.0,
                };
                let pass = if self.flat_shader {
                    Pass::Flat
                } else {
                    Pass::Plane
                };
                self.paint_texture(ui, tex_rect, params.clone(), pass, view, None);
                if let Some(pr) = photo_rect {
                    self.paint_photo_crop(ui, pr);
                    ui.painter().line_segment(
                        [pr.right_top(), pr.right_bottom()],
                        egui::Stroke::new(2.0, egui::Color32::from_gray(20)),
                    );
                    self.widgets.insert(
                        "split.photo".into(),
                        [pr.min.x, pr.min.y, pr.width(), pr.height()],
                    );
                    self.widgets.insert(
                        "split.texture".into(),
                        [
                            tex_rect.min.x,
                            tex_rect.min.y,
                            tex_rect.width(),
                            tex_rect.height(),
                        ],
                    );
                }
                self.period_lines = if self.period_outline {
                    self.paint_period(ui, tex_rect, &params)
                } else {
                    0
                };
            }
        }
    }

    fn pan_zoom_input(&mut self, ui: &egui::Ui, rect: egui::Rect, response: &egui::Response) {
        if response.dragged() {
            let d = response.drag_delta();
            self.view.origin[0] -= d.x * self.view.units_per_point;
            self.view.origin[1] -= d.y * self.view.units_per_point;
        }
        if let Some(pos) = response.hover_pos() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                let k = (-scroll * 0.002).exp();
                let local = pos - rect.min;
                let before = [
                    self.view.origin[0] + local.x * self.view.units_per_point,
                    self.view.origin[1] + local.y * self.view.units_per_point,
                ];
                self.view.units_per_point = (self.view.units_per_point * k).clamp(1e-3, 1e4);
                self.view.origin = [
                    before[0] - local.x * self.view.units_per_point,
                    before[1] - local.y * self.view.units_per_point,
                ];
            }
        }
    }

    /// Orbit controls: drag turns the object, the wheel moves the camera in and out.
    fn orbit_input(&mut self, ui: &egui::Ui, response: &egui::Response) {
        if response.dragged() {
            let d = response.drag_delta();
            self.orbit.yaw_deg = (self.orbit.yaw_deg - d.x * 0.4).rem_euclid(360.0);
            self.orbit.pitch_deg = (self.orbit.pitch_deg + d.y * 0.4).clamp(-85.0, 85.0);
        }
        if response.hovered() {
            let scroll = ui.input(|i| i.smooth_scroll_delta.y);
            if scroll != 0.0 {
                self.orbit.distance =
                    (self.orbit.distance * (-scroll * 0.002).exp()).clamp(1.6, 12.0);
            }
        }
    }

    fn paint_texture(
        &self,
        ui: &egui::Ui,
        rect: egui::Rect,
        params: Params,
        pass: Pass,
        view: View,
        solid: Option<SolidView>,
    ) {
        let ppp = ui.ctx().pixels_per_point();
        let min = [(rect.min.x * ppp).round(), (rect.min.y * ppp).round()];
        let max = [(rect.max.x * ppp).round(), (rect.max.y * ppp).round()];
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(
            rect,
            TextureCallback {
                params,
                pass,
                view: match solid {
                    Some(sv) => ViewSource::Solid(sv),
                    None => ViewSource::Plane(view),
                },
                frame_offset: min.map(|v| v as i32),
                frame_size: [0, 1].map(|i| (max[i] - min[i]).max(1.0) as u32),
                fresh: !self.frame_cache,
            },
        ));
    }

    /// The photo crop at the texture view's scale: world units are photo pixels and the crop's
    /// top-left is world (0, 0), so both halves show the same world window.
    fn paint_photo_crop(&self, ui: &egui::Ui, rect: egui::Rect) {
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, egui::Color32::from_gray(28));
        let Some(photo) = &self.photo else {
            return;
        };
        let [cx, cy, cw, ch] = photo.crop.map(|v| v as f32);
        let upp = self.view.units_per_point;
        let o = self.view.origin;
        // Visible world window ∩ the crop, in world units.
        let x0 = o[0].max(0.0);
        let y0 = o[1].max(0.0);
        let x1 = (o[0] + rect.width() * upp).min(cw);
        let y1 = (o[1] + rect.height() * upp).min(ch);
        if x1 <= x0 || y1 <= y0 {
            return;
        }
        let screen = egui::Rect::from_min_max(
            rect.min + egui::vec2((x0 - o[0]) / upp, (y0 - o[1]) / upp),
            rect.min + egui::vec2((x1 - o[0]) / upp, (y1 - o[1]) / upp),
        );
        let [fw, fh] = photo.full.map(|v| v as f32);
        let uv = egui::Rect::from_min_max(
            egui::pos2((cx + x0) / fw, (cy + y0) / fh),
            egui::pos2((cx + x1) / fw, (cy + y1) / fh),
        );
        painter.image(photo.texture.id(), screen, uv, egui::Color32::WHITE);
        painter.text(
            rect.left_top() + egui::vec2(6.0, 6.0),
            egui::Align2::LEFT_TOP,
            "photo crop",
            egui::FontId::proportional(13.0),
            egui::Color32::from_gray(230),
        );
    }

    /// Outlines the tile lattice: the texture repeats every `period_texels` texels along both
    /// texture axes (rotated and scaled into world space). Returns the number of lines drawn
    /// (0 when the lattice is finer than 4 pixels, where it would hide the texture).
    fn paint_period(&self, ui: &egui::Ui, rect: egui::Rect, params: &Params) -> usize {
        let period = period_texels(params) as f32;
        let s = params.transform.scale;
        let (sin, cos) = params.transform.rotation_deg.to_radians().sin_cos();
        let upp = self.view.units_per_point;
        let o = self.view.origin;
        let painter = ui.painter_at(rect);
        let label = format!("tile period {:.0} px", period * s);
        if period * s / upp < 4.0 {
            painter.text(
                rect.left_bottom() + egui::vec2(8.0, -8.0),
                egui::Align2::LEFT_BOTTOM,
                format!("{label}: finer than 4 screen pixels here"),
                egui::FontId::proportional(13.0),
                egui::Color32::from_gray(230),
            );
            return 0;
        }
        // World → texel: u = R(−θ)·x / s; texel → world: x = s·R(θ)·u.
        let to_texel = |x: f32, y: f32| [(cos * x + sin * y) / s, (-sin * x + cos * y) / s];
        let to_screen = |u: [f32; 2]| {
            let wx = s * (cos * u[0] - sin * u[1]);
            let wy = s * (sin * u[0] + cos * u[1]);
            rect.min + egui::vec2((wx - o[0]) / upp, (wy - o[1]) / upp)
        };
        let corners = [
            to_texel(o[0], o[1]),
            to_texel(o[0] + rect.width() * upp, o[1]),
            to_texel(o[0], o[1] + rect.height() * upp),
            to_texel(o[0] + rect.width() * upp, o[1] + rect.height() * upp),
        ];
        let lo = [0, 1].map(|a| corners.iter().map(|c| c[a]).fold(f32::MAX, f32::min));
        let hi = [0, 1].map(|a| corners.iter().map(|c| c[a]).fold(f32::MIN, f32::max));
        let stroke = egui::Stroke::new(1.5, egui::Color32::from_rgb(250, 200, 60));
        let mut lines = 0;
        for a in 0..2 {
            let b = 1 - a;
            let first = (lo[a] / period).floor() as i64;
            let last = (hi[a] / period).ceil() as i64;
            for i in first..=last {
                let mut p0 = [0.0; 2];
                let mut p1 = [0.0; 2];
                p0[a] = i as f32 * period;
                p1[a] = i as f32 * period;
                p0[b] = lo[b];
                p1[b] = hi[b];
                painter.line_segment([to_screen(p0), to_screen(p1)], stroke);
                lines += 1;
            }
        }
        painter.text(
            rect.left_bottom() + egui::vec2(8.0, -8.0),
            egui::Align2::LEFT_BOTTOM,
            label,
            egui::FontId::proportional(13.0),
            egui::Color32::from_gray(230),
        );
        lines
    }

    fn publish(&self) {
        SNAPSHOT.with(|s| {
            *s.borrow_mut() = Snapshot {
                frame: self.frame,
                photo: self.photo.as_ref().map(|p| p.name.clone()),
                photo_size: self.photo.as_ref().map(|p| p.full),
                crop: self.photo.as_ref().map(|p| p.crop),
                analysis_ms: self.analysis_ms,
                analyses: self.analyses,
                busy: self.busy.is_some(),
                error: self.error.clone(),
                params_json: self.params.as_ref().map(Params::to_json),
                widgets: self.widgets.clone(),
                view_origin: self.view.origin,
                view_units_per_point: self.view.units_per_point,
                view_mode: Some(self.mode),
                orbit: [
                    self.orbit.yaw_deg,
                    self.orbit.pitch_deg,
                    self.orbit.distance,
                ],
                period_outline: self.period_outline,
                period_lines: self.period_lines,
                plots_current: self.plots_current(),
                presets: self.presets.list.iter().map(|p| p.name.clone()).collect(),
                gallery: self
                    .presets
                    .gallery
                    .iter()
                    .map(|(p, _)| p.name.clone())
                    .collect(),
                morph_t: self.presets.morph.as_ref().map(|_| self.presets.t),
                morph_playing: self.presets.playing,
                undo: self.undo.len(),
                redo: self.redo.len(),
                suggestions: self.suggest.rows.clone(),
                suggest_progress: self.suggest.progress.map(|(d, t)| [d, t]),
                adopted: self.adopted_row(),
                suggest_error: self.suggest.error.clone(),
                tile_progress: self
                    .tile_job
                    .as_ref()
                    .map(|j| j.done_rows as f32 / j.size as f32),
            }
        });
    }
}

/// The shipped sample photos (`www/samples/`).
pub const SAMPLES: [&str; 6] = [
    "stk_rock_mountain_512.png",
    "skimage_gravel_512.png",
    "skimage_grass_512.png",
    "stk_blackrock_256.png",
    "skimage_brick_512.png",
    "stk_wood_planks1_256.png",
];

impl eframe::App for ProctexApp {
    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.frame += 1;
        let ctx = ui.ctx().clone();
        self.apply_commands(&ctx);
        self.step_tile(&ctx, frame);
        let (undo, redo) = ctx.input_mut(|i| {
            let redo = i.consume_key(
                egui::Modifiers::COMMAND | egui::Modifiers::SHIFT,
                egui::Key::Z,
            );
            let undo = i.consume_key(egui::Modifiers::COMMAND, egui::Key::Z);
            (undo, redo)
        });
        if redo {
            self.redo();
        } else if undo {
            self.undo();
        }
        self.widgets.clear();
        egui::Panel::left("photo")
            .default_size(300.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .id_salt("photo_scroll")
                    .show(ui, |ui| self.photo_panel(ui))
            });
        egui::Panel::right("controls")
            .default_size(320.0)
            .show(ui, |ui| self.controls(ui));
        egui::Panel::top("toolbar").show(ui, |ui| self.toolbar(ui));
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.view_panel(ui));
        self.advance_morph(&ctx);
        self.commit_edits(&ctx);
        self.request_stats(&ctx);
        self.publish();
    }
}

/// One frame's texture draw: the view rendered into the frame cache when it changed, then
/// copied into the view rectangle (clipped by egui).
struct TextureCallback {
    params: Params,
    pass: Pass,
    view: ViewSource,
    frame_offset: [i32; 2],
    frame_size: [u32; 2],
    fresh: bool,
}

impl egui_wgpu::CallbackTrait for TextureCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(r) = resources.get_mut::<CachedView>() {
            r.prepare(
                device,
                queue,
                encoder,
                &self.params,
                self.pass,
                &self.view,
                self.frame_offset,
                self.frame_size,
                self.fresh,
            );
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        if let Some(r) = resources.get::<CachedView>() {
            r.paint(pass);
        }
    }
}

/// One text face (Ubuntu Light) and egui's icons, for every family (see assets/fonts).
fn ui_fonts() -> egui::FontDefinitions {
    use std::sync::Arc;
    let mut fonts = egui::FontDefinitions::empty();
    fonts.font_data.insert(
        "Ubuntu-Light".into(),
        Arc::new(egui::FontData::from_static(include_bytes!(
            "../assets/fonts/Ubuntu-Light.ttf"
        ))),
    );
    fonts.font_data.insert(
        "egui-icons".into(),
        Arc::new(egui::FontData::from_static(include_bytes!(
            "../assets/fonts/egui-icons.ttf"
        ))),
    );
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        fonts
            .families
            .insert(family, vec!["Ubuntu-Light".into(), "egui-icons".into()]);
    }
    fonts
}

/// A positive number in a few characters: 4, 6.8, 1024.
/// The structured model's controls: family, placement, every structural value (ranges and
/// tooltips from the spec table) and the colour ramp.
fn structure_controls(
    ui: &mut egui::Ui,
    m: &mut proctex::params::StructuredModel,
    rects: &mut Vec<(String, egui::Response)>,
) {
    use proctex::pattern::{Pattern, PatternKind};
    ui.separator();
    ui.label("Structure");
    let pat = &mut m.pattern;
    let mut kind = pat.kind;
    let r = egui::ComboBox::from_label("pattern")
        .selected_text(kind.name())
        .show_ui(ui, |ui| {
            for k in PatternKind::ALL {
                ui.selectable_value(&mut kind, k, k.name());
            }
        })
        .response;
    rects.push(("pattern.kind".into(), r));
    if kind != pat.kind {
        // Another family at its defaults, in the same place.
        let (scale, rotation) = (pat.scale, pat.rotation_deg);
        *pat = Pattern::new(kind, scale);
        pat.rotation_deg = rotation;
    }
    let r = ui.add(
        egui::Slider::new(&mut pat.scale, 1.0..=512.0)
            .logarithmic(true)
            .text("pattern scale (texels)"),
    );
    rects.push(("pattern.scale".into(), r));
    let r =
        ui.add(egui::Slider::new(&mut pat.rotation_deg, -180.0..=180.0).text("pattern rotation °"));
    rects.push(("pattern.rotation".into(), r));
    let mut values = pat.vector();
    for (spec, v) in pat.kind.specs().iter().zip(values.iter_mut()) {
        let r = ui
            .add(egui::Slider::new(v, spec.min..=spec.max).text(spec.name))
            .on_hover_text(spec.doc);
        rects.push((format!("pattern.{}", spec.name), r));
    }
    if values != pat.vector() {
        pat.set_vector(&values);
    }
    ui.horizontal(|ui| {
        ui.label("Colour ramp along the structure value");
        let r = ui.button("swap tones").on_hover_text(
            "Reads the ramp backwards (the two-tone paper's tone swap): the pattern's \
                 cells take the joints' colours and the joints the cells'",
        );
        if r.clicked() {
            proctex::pattern::swap_tones(&mut m.ramp);
        }
        rects.push(("ramp.swap".into(), r));
    });
    let n = m.ramp.len();
    for i in 0..n {
        let lo = if i == 0 { 0.0 } else { m.ramp[i - 1].at };
        let hi = if i + 1 == n { 1.0 } else { m.ramp[i + 1].at };
        let stop = &mut m.ramp[i];
        ui.horizontal(|ui| {
            let r = ui.color_edit_button_rgb(&mut stop.rgb);
            rects.push((format!("ramp.{i}.colour"), r));
            let r = ui.add(egui::Slider::new(&mut stop.at, 0.0..=1.0).text("at"));
            stop.at = stop.at.clamp(lo, hi);
            rects.push((format!("ramp.{i}.at"), r));
        });
    }
    if let Some(tone) = &mut m.tone {
        let r = ui
            .checkbox(&mut tone.enabled, "output tone curve")
            .on_hover_text(
                "Per RGB channel, maps the synthesis's colour distribution onto the photo's \
                 (fitted by the analysis; the plot shows output against input, 0 to 1)",
            );
        rects.push(("tone".into(), r));
        tone_plot(ui, tone);
    }
}

/// The output tone curve of each RGB channel, output against input over `[0, 1]`.
fn tone_plot(ui: &mut egui::Ui, tone: &proctex::params::Tone) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(160.0, 100.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let visuals = ui.visuals();
    painter.rect_filled(rect, 2.0, visuals.extreme_bg_color);
    painter.line_segment(
        [rect.left_bottom(), rect.right_top()],
        egui::Stroke::new(1.0, visuals.weak_text_color()),
    );
    let colours = [
        egui::Color32::from_rgb(230, 80, 80),
        egui::Color32::from_rgb(80, 200, 80),
        egui::Color32::from_rgb(90, 130, 240),
    ];
    let alpha = if tone.enabled { 1.0 } else { 0.35 };
    let curve = tone.curve();
    for (c, colour) in colours.into_iter().enumerate() {
        let points: Vec<egui::Pos2> = (0..=64)
            .map(|i| {
                let x = i as f32 / 64.0;
                let y = curve(c, x).clamp(0.0, 1.0);
                egui::pos2(
                    rect.left() + x * rect.width(),
                    rect.bottom() - y * rect.height(),
                )
            })
            .collect();
        painter.add(egui::Shape::line(
            points,
            egui::Stroke::new(1.5, colour.gamma_multiply(alpha)),
        ));
    }
}

fn short(v: f32) -> String {
    if (v - v.round()).abs() < 0.05 || v >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

fn now_ms() -> f64 {
    js_sys::Date::now()
}

/// The complete shader in `format` ("wgsl" or "glsl") of one texture, or of the morph through
/// two or more with t as a uniform, as `proctex export KEYS... --format FORMAT` writes it.
pub fn export_shader(keys: &[Params], format: &str) -> Result<String, String> {
    proctex::export::shader(keys, format).map_err(|e| e.to_string())
}
