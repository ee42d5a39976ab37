//! The egui application: photo → analysis → params → GPU texture, with sliders for every
//! parameter, undo/redo, and a pan/zoom view. Compiled for the browser only.
//!
//! Edits change `Params` and nothing else; the paint callback uploads them as one uniform
//! write. Analysis runs only when a photo (or crop) arrives.

use std::cell::RefCell;
use std::collections::BTreeMap;

use eframe::egui;
use eframe::egui_wgpu;
use proctex::analyze::{Analysis, Options, analyze_photo};
use proctex::input::Photo;
use proctex::params::{Model, Params};
use proctex::render::View;

use crate::renderer::TextureRenderer;

/// Something JS asked for, applied at the start of the next frame.
#[derive(Debug)]
pub enum Command {
    /// Analyse a decoded image: interleaved 8-bit RGBA (the browser decodes files).
    LoadPixels {
        rgba: Vec<u8>,
        width: u32,
        height: u32,
        name: String,
    },
    /// Show an error that happened outside the app (a file the browser could not decode).
    Error(String),
    /// Replace the current params (already validated).
    SetParams(Box<Params>),
    /// Show this part of world space: top-left world point and world units per CSS pixel.
    SetView {
        origin: [f32; 2],
        units_per_point: f32,
    },
}

/// What the app publishes for JS after every frame.
#[derive(Debug, Default, Clone, serde::Serialize)]
pub struct Snapshot {
    /// Frames drawn so far.
    pub frame: u64,
    /// Name of the analysed photo.
    pub photo: Option<String>,
    /// Milliseconds the last analysis took (decode included).
    pub analysis_ms: Option<f64>,
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

/// The application.
pub struct ProctexApp {
    photo: Option<String>,
    analysis: Option<Analysis>,
    params: Option<Params>,
    committed: Option<Params>,
    undo: Vec<Params>,
    redo: Vec<Params>,
    view: ViewState,
    error: Option<String>,
    analysis_ms: Option<f64>,
    frame: u64,
    widgets: BTreeMap<String, [f32; 4]>,
}

impl ProctexApp {
    /// Creates the app and registers the GPU renderer with egui's wgpu renderer.
    pub fn new(cc: &eframe::CreationContext<'_>) -> Self {
        if let Some(rs) = cc.wgpu_render_state.as_ref() {
            let renderer = TextureRenderer::new(&rs.device, rs.target_format);
            rs.renderer.write().callback_resources.insert(renderer);
        }
        cc.egui_ctx.set_fonts(ui_fonts());
        CONTEXT.with(|c| *c.borrow_mut() = Some(cc.egui_ctx.clone()));
        ProctexApp {
            photo: None,
            analysis: None,
            params: None,
            committed: None,
            undo: Vec::new(),
            redo: Vec::new(),
            view: ViewState::default(),
            error: None,
            analysis_ms: None,
            frame: 0,
            widgets: BTreeMap::new(),
        }
    }

    fn load(&mut self, rgba: &[u8], width: u32, height: u32, name: String) {
        let t = now_ms();
        let analysis = Photo::from_rgba8(width, height, rgba)
            .and_then(|photo| analyze_photo(&photo, &Options::default()));
        match analysis {
            Ok(a) => {
                self.analysis_ms = Some(now_ms() - t);
                self.params = Some(a.params.clone());
                self.committed = Some(a.params.clone());
                self.undo.clear();
                self.redo.clear();
                self.analysis = Some(a);
                self.photo = Some(name);
                self.error = None;
                self.view = ViewState::default();
            }
            Err(e) => {
                // Keep the previous texture; say what went wrong.
                self.error = Some(format!("{name}: {e}"));
            }
        }
    }

    fn apply_commands(&mut self) {
        let cmds: Vec<Command> = COMMANDS.with(|c| std::mem::take(&mut *c.borrow_mut()));
        for cmd in cmds {
            match cmd {
                Command::LoadPixels {
                    rgba,
                    width,
                    height,
                    name,
                } => self.load(&rgba, width, height, name),
                Command::Error(e) => self.error = Some(e),
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
            }
        }
    }

    /// Undo bookkeeping: once no widget is being dragged, a changed params set is one step.
    fn commit_edits(&mut self, ctx: &egui::Context) {
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

    fn controls(&mut self, ui: &mut egui::Ui) {
        ui.heading("Proctex");
        match (&self.photo, self.analysis_ms) {
            (Some(name), Some(ms)) => {
                ui.label(format!("{name} — analysed in {ms:.0} ms"));
            }
            _ => {
                ui.label("Loading the sample photo…");
            }
        }
        if let Some(err) = &self.error {
            let r = ui.colored_label(egui::Color32::from_rgb(230, 80, 60), err);
            self.record("error", &r);
        }
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
            let can_reset = self.analysis.is_some();
            let r = ui.add_enabled(can_reset, egui::Button::new("Reset to analysed"));
            self.record("reset", &r);
            if r.clicked()
                && let Some(a) = &self.analysis
            {
                self.params = Some(a.params.clone());
            }
        });
        let Some(params) = self.params.as_mut() else {
            return;
        };
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
            });
            ui.horizontal(|ui| {
                ui.label("mean colour");
                let r = ui.color_edit_button_rgb(&mut params.colour.mean);
                rects.push(("mean".into(), r));
            });
            let Model::Noise(model) = &mut params.model;
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
                    // Band j holds wavelengths of 2^(j+1)…2^(j+2) texels.
                    let lo = (1u32 << (j + 1)) as f32 * scale;
                    let hi = (1u32 << (j + 2)) as f32 * scale;
                    let r = ui
                        .add(egui::Slider::new(w, 0.0..=max).text(format!("λ {lo:.0}–{hi:.0} px")));
                    rects.push((format!("weight.{c}.{j}"), r));
                }
            }
        });
        for (name, r) in rects {
            self.record(name, &r);
        }
    }

    fn texture_view(&mut self, ui: &mut egui::Ui) {
        let (rect, response) =
            ui.allocate_exact_size(ui.available_size(), egui::Sense::click_and_drag());
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
        // Pan with the mouse; zoom about the cursor with the wheel.
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
        let ppp = ui.ctx().pixels_per_point();
        let view = View {
            origin: self.view.origin,
            pixel_size: self.view.units_per_point / ppp,
            z: 0.0,
        };
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(
            rect,
            TextureCallback {
                params,
                view,
                frame_offset: [(rect.min.x * ppp).round(), (rect.min.y * ppp).round()],
            },
        ));
    }

    fn publish(&self) {
        SNAPSHOT.with(|s| {
            *s.borrow_mut() = Snapshot {
                frame: self.frame,
                photo: self.photo.clone(),
                analysis_ms: self.analysis_ms,
                error: self.error.clone(),
                params_json: self.params.as_ref().map(Params::to_json),
                widgets: self.widgets.clone(),
                view_origin: self.view.origin,
                view_units_per_point: self.view.units_per_point,
                undo: self.undo.len(),
                redo: self.redo.len(),
            }
        });
    }
}

impl eframe::App for ProctexApp {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        self.frame += 1;
        self.apply_commands();
        let ctx = ui.ctx().clone();
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
        egui::Panel::left("controls")
            .default_size(340.0)
            .show(ui, |ui| self.controls(ui));
        egui::CentralPanel::default()
            .frame(egui::Frame::NONE)
            .show(ui, |ui| self.texture_view(ui));
        self.commit_edits(&ctx);
        self.publish();
    }
}

/// One frame's texture draw: the params and view to upload, then the full-screen triangle
/// clipped to the view rectangle by egui.
struct TextureCallback {
    params: Params,
    view: View,
    frame_offset: [f32; 2],
}

impl egui_wgpu::CallbackTrait for TextureCallback {
    fn prepare(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        _screen: &egui_wgpu::ScreenDescriptor,
        _encoder: &mut wgpu::CommandEncoder,
        resources: &mut egui_wgpu::CallbackResources,
    ) -> Vec<wgpu::CommandBuffer> {
        if let Some(r) = resources.get_mut::<TextureRenderer>() {
            r.set_params(device, queue, &self.params);
            r.set_view(queue, &self.view, self.frame_offset);
        }
        Vec::new()
    }

    fn paint(
        &self,
        _info: egui::PaintCallbackInfo,
        pass: &mut wgpu::RenderPass<'static>,
        resources: &egui_wgpu::CallbackResources,
    ) {
        if let Some(r) = resources.get::<TextureRenderer>() {
            r.draw(pass);
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

fn now_ms() -> f64 {
    web_sys::window()
        .and_then(|w| w.performance())
        .map(|p| p.now())
        .unwrap_or(0.0)
}
