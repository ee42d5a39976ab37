//! The page's side of the app: the commands JS queues for the next frame, the snapshot the
//! app publishes after each frame, and the calls into `window.proctexHost`.

use std::cell::RefCell;
use std::collections::BTreeMap;

use eframe::egui;
use proctex::params::Params;
use wasm_bindgen::JsValue;

use crate::jobs::{ImageStats, Report, SuggestionRow};
use crate::preset_store::Change;
use crate::presets::{Preset, parse_library};

use super::{PhotoPreview, ProctexApp, SuggestState, TileSettings, ViewMode, ViewState, now_ms};

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
    /// Another tab wrote the presets library (the browser's `storage` event).
    PresetsChangedElsewhere,
    /// A built-in gallery preset (a shipped sample's analysis).
    GalleryPreset(String, Box<Params>),
    /// The worker refined `done` of `total` families of the current photo's suggestions.
    SuggestProgress { done: u32, total: u32 },
    /// The photo just analysed gets its suggestions only when the user asks (the start-up
    /// sample: see `www/main.js`); the list of the previous photo goes.
    SuggestOnRequest,
    /// A row of the current list fitted after the list came: its texture distance and
    /// thumbnail (`THUMB_SIDE²` RGBA8).
    SuggestionFitted {
        index: usize,
        row: Box<SuggestionRow>,
        thumbnail: Vec<u8>,
    },
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
    /// The worker ran `done` of `total` rounds of the pyramid synthesis.
    PyramidProgress { done: u32, total: u32 },
    /// The pyramid synthesis is done: RGBA8 of `size`, in `ms` milliseconds.
    PyramidDone {
        rgba: Vec<u8>,
        size: [u32; 2],
        ms: f64,
    },
    /// The pyramid synthesis was cancelled.
    PyramidCancelled,
    /// The pyramid synthesis failed.
    PyramidFailed(String),
    /// The pyramid view's mixture: B's source (`sample:NAME` or `preset:NAME`) and m (`None`:
    /// none), and A's source (`None`: the crop).
    SetPyramidMix(Option<(String, f32)>, Option<String>),
    /// The worker ran `done` of `total` rounds of the solid texture.
    SolidProgress { done: u32, total: u32 },
    /// The solid texture is done: `n³` RGBA8 voxels, their scale, in `ms` milliseconds.
    SolidDone {
        rgba: Vec<u8>,
        n: u32,
        voxels_per_unit: f32,
        ms: f64,
    },
    /// The solid texture was cancelled.
    SolidCancelled,
    /// The solid texture failed.
    SolidFailed(String),
    /// The solid views' source: the Heeger–Bergen volume (`true`) of a side, or procedural.
    SetSolidSource { raster: bool, side: u32 },
    /// PNG tile export choices: side, bits (8 or 16), CPU even with a GPU.
    TileOptions {
        size: u32,
        bits: u8,
        force_cpu: bool,
    },
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
    /// The stored library's notice (unreadable presets), until dismissed.
    pub presets_notice: Option<String>,
    /// Why the last presets save wrote nothing (until one writes).
    pub presets_save_error: Option<String>,
    /// Saving presets is refused until the unreadable stored library is downloaded or discarded.
    pub presets_locked: bool,
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
    /// The lighting option is on (the photo's lighting gradient divided out).
    pub flatten_lighting: bool,
    /// Row of the suggestion the current params came from (`None`: edited, or none yet).
    pub adopted: Option<usize>,
    /// Why there are no suggestions, if they failed.
    pub suggest_error: Option<String>,
    /// The pyramid (Heeger–Bergen) view's synthesis.
    pub pyramid: super::pyramid::PyramidSnapshot,
    /// The solid views' source and Heeger–Bergen volume.
    pub solid: super::solid::SolidSnapshot,
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
    send_within(cmd, std::time::Duration::ZERO);
}

/// Queues a command and wakes the app within `delay` (sooner if something else wakes it), so
/// that commands arriving in bursts share one frame. A zero delay is egui's `request_repaint`.
pub fn send_within(cmd: Command, delay: std::time::Duration) {
    COMMANDS.with(|c| c.borrow_mut().push(cmd));
    CONTEXT.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint_after(delay);
        }
    });
}

/// Calls `window.proctexHost[method](...args)` (the page's side of the app: file dialog,
/// camera, worker jobs). Returns false when the page has no such function.
pub(super) fn host(method: &str, args: &[JsValue]) -> bool {
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

impl ProctexApp {
    pub(super) fn apply_commands(&mut self, ctx: &egui::Context) {
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
                Command::SuggestionFitted {
                    index,
                    row,
                    thumbnail,
                } => self.suggestion_fitted(index, *row, &thumbnail),
                Command::Adopted { index, report } => {
                    self.suggest.adopting = None;
                    self.adopt(index, *report);
                }
                Command::SuggestFailed(e) => {
                    self.suggest.progress = None;
                    self.suggest.adopting = None;
                    self.suggest.error = Some(e);
                }
                Command::PyramidProgress { done, total } => self.pyramid_progress(done, total),
                Command::PyramidDone { rgba, size, ms } => self.pyramid_done(ctx, rgba, size, ms),
                Command::PyramidCancelled => self.pyramid_stopped(None),
                Command::PyramidFailed(e) => self.pyramid_stopped(Some(e)),
                Command::SetPyramidMix(mix, a) => self.set_pyramid_mix(mix, a),
                Command::SolidProgress { done, total } => self.solid_progress(done, total),
                Command::SolidDone {
                    rgba,
                    n,
                    voxels_per_unit,
                    ms,
                } => self.solid_done(rgba, n, voxels_per_unit, ms),
                Command::SolidCancelled => self.solid_stopped(None),
                Command::SolidFailed(e) => self.solid_stopped(Some(e)),
                Command::SetSolidSource { raster, side } => self.set_solid_source(raster, side),
                Command::ModelStats(stats) => {
                    let (p, s) = *stats;
                    self.model_stats = Some((p, s));
                }
                Command::Error(e) => {
                    self.busy = None;
                    self.error = Some(proctex::limits::bounded_message(&e));
                }
                Command::PresetsChangedElsewhere => self.presets_changed_elsewhere(),
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
                        list.extend(new.iter().cloned());
                        self.set_presets(list);
                        self.persist_presets(Change::Added(&new));
                        self.status_note = Some(format!("Imported {added} presets"));
                    }
                    Err(e) => {
                        self.error = Some(format!("Import: {e}. Your presets are unchanged."));
                    }
                },
            }
        }
    }

    pub(super) fn publish(&self) {
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
                presets_notice: self.presets.store.notice.clone(),
                presets_save_error: self.presets.store.save_error.clone(),
                presets_locked: self.presets.store.locked(),
                gallery: self
                    .presets
                    .gallery
                    .iter()
                    .map(|(p, _)| p.name.clone())
                    .collect(),
                morph_t: self.presets.morph.as_ref().map(|_| self.presets.t),
                morph_playing: self.presets.playing,
                pyramid: self.pyramid.snapshot(),
                solid: self.solid.snapshot(),
                undo: self.undo.len(),
                redo: self.redo.len(),
                suggestions: self.suggest.rows.clone(),
                suggest_progress: self.suggest.progress.map(|(d, t)| [d, t]),
                flatten_lighting: self.flatten_lighting,
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
