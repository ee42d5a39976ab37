//! The egui application: photo → analysis (in the page's Web Worker) → params → GPU texture,
//! with a crop rectangle on the photo, sliders for every parameter, undo/redo, plane / split /
//! sphere / cube views and plots of the photo against the model.
//!
//! Edits change `Params` and nothing else; the paint callback uploads them as one uniform
//! write. Analysis runs only when a photo or a crop arrives, and never on this thread: the app
//! asks the page (`proctexHost` in `www/main.js`) and the worker's result comes back as a
//! [`Command`].
//!
//! One room per panel or concern, each an `impl ProctexApp` block over the shared state
//! defined here: `photo` (photo panel, analysis results), `crop` (the crop rectangle),
//! `suggestions` (the ranked models), `presets` (gallery and user presets), `morph`, `export`
//! (shaders), `tiles` (PNG tile export), `pyramid` (the Heeger–Bergen raster synthesis beside
//! the texture), `solid` (the solid views' Heeger–Bergen volume), `plots`, `controls` (parameters, undo/redo), `view`
//! (toolbar, central view, paint callback) and `bridge` (commands from the page, the snapshot
//! for it, calls into it).

use std::collections::BTreeMap;

use eframe::egui;
use proctex::params::Params;
use proctex::solid::Orbit;

use crate::jobs::{ImageStats, SuggestionRow};
use crate::presets::Preset;
use crate::tile_export::{SeamlessCpu, SeamlessGpu};
use crate::view_cache::CachedView;

mod bridge;
mod controls;
mod crop;
mod export;
mod morph;
mod photo;
mod plots;
mod presets;
mod pyramid;
mod solid;
mod suggestions;
mod tiles;
mod view;

use bridge::host;
pub use bridge::{CONTEXT, Command, SNAPSHOT, send, send_within};
use crop::CropDrag;
use export::export_shader;
pub use solid::SIDES as SOLID_SIDES;

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
    /// The photo crop, the texture and the Heeger–Bergen raster synthesis side by side.
    Pyramid,
}

impl ViewMode {
    /// All modes, in toolbar order.
    pub const ALL: [ViewMode; 5] = [
        ViewMode::Plane,
        ViewMode::Split,
        ViewMode::Pyramid,
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
            ViewMode::Pyramid => "pyramid",
        }
    }

    fn label(self) -> &'static str {
        match self {
            ViewMode::Plane => "Plane",
            ViewMode::Split => "Split vs photo",
            ViewMode::Sphere => "Sphere",
            ViewMode::Cube => "Cube",
            ViewMode::Pyramid => "Pyramid",
        }
    }

    fn hover(self) -> Option<&'static str> {
        (self == ViewMode::Pyramid).then_some(
            "Heeger–Bergen pyramid synthesis: a raster texture made from the crop, beside the \
             photo and the procedural texture",
        )
    }
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
    /// The plots window is open (the toolbar's "Plots").
    show_plots: bool,
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
    /// Analyses divide the photo's lighting gradient out (the crop panel's option).
    flatten_lighting: bool,
    /// The pyramid view's raster synthesis.
    pyramid: pyramid::PyramidState,
    /// The solid views' source and the Heeger–Bergen volume.
    solid: solid::SolidState,
}

/// The automatic model choice's list: filled by the worker after each analysis.
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
    /// Where the list is stored, and what the user must know about it.
    store: crate::preset_store::PresetStore,
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
            show_plots: false,
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
            flatten_lighting: false,
            pyramid: pyramid::PyramidState::default(),
            solid: solid::SolidState::default(),
            gpu: None,
            presets: PresetsState {
                duration_s: 4.0,
                looping: true,
                ..PresetsState::default()
            },
        }
        .with_stored_presets()
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
    /// The panels' colour: the frame is cleared to it, and the panels draw no fill of their own
    /// (`panel_frame`).
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }

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
            .frame(panel_frame(ui.style()))
            .default_size(300.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical()
                    .id_salt("photo_scroll")
                    .show(ui, |ui| self.photo_panel(ui))
            });
        egui::Panel::right("controls")
            .frame(panel_frame(ui.style()))
            .default_size(320.0)
            .show(ui, |ui| self.controls(ui));
        egui::Panel::top("toolbar")
            .frame(panel_frame(ui.style()))
            .show(ui, |ui| self.toolbar(ui));
        egui::Panel::bottom("export")
            .frame(panel_frame(ui.style()))
            .show(ui, |ui| self.export_bar(ui));
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.view_panel(ui));
        if self.show_plots {
            self.plots_window(&ctx);
        }
        self.advance_morph(&ctx);
        self.commit_edits(&ctx);
        self.request_stats(&ctx);
        self.publish();
    }
}

/// A side, top or bottom panel's frame without its fill: the frame's clear colour is the panels'
/// colour (`clear_color`), so the app looks the same. Why: on a software adapter each repaint
/// draws every pixel it covers, and the four fills were half of a repaint's cost. Measured in
/// Chromium on SwiftShader (2 cores, the whole 1680×1100 app, trivial texture shader), CPU of
/// the browser's GPU process per repaint: 517–541 ms with the fills, 277–296 ms without; clear
/// and present alone 82–94 ms. The analysis worker runs on the same cores while the app
/// repaints its progress and rows; in the same run a 256² crop's analysis to its fitted list
/// (medians of five crops, two alternated rounds) took brick 2.02/1.95 s → 1.79/1.80 s, gravel
/// 2.60/2.62 s → 2.22/2.22 s.
fn panel_frame(style: &egui::Style) -> egui::Frame {
    egui::Frame::side_top_panel(style).fill(egui::Color32::TRANSPARENT)
}

/// One text face (Ubuntu Light) and egui's icons, for every family (see assets/fonts).
fn ui_fonts() -> egui::FontDefinitions {
    use std::sync::Arc;
    let mut fonts = egui::FontDefinitions::empty();
    fonts.font_data.insert(
        "Ubuntu-Light".into(),
        Arc::new(egui::FontData::from_static(include_bytes!(
            "../../assets/fonts/Ubuntu-Light.ttf"
        ))),
    );
    fonts.font_data.insert(
        "egui-icons".into(),
        Arc::new(egui::FontData::from_static(include_bytes!(
            "../../assets/fonts/egui-icons.ttf"
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
