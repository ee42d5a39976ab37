//! The pyramid view: the photo crop, the procedural texture and the Heeger–Bergen raster
//! synthesis of the same crop side by side, at one scale and over one world window (as Lagae et
//! al. Fig. 16 set a procedural texture beside a raster synthesis). The synthesis runs in the
//! worker (`proctexHost.synthesisePyramid`, one round per step, with progress and Cancel)
//! whenever this view shows a photo or crop it has not synthesised yet; it tiles seamlessly, so
//! it is drawn repeated across the window, and it downloads as a PNG tile.

use eframe::egui;
use proctex::params::Params;
use proctex::render::View;
use wasm_bindgen::JsValue;

use super::{ProctexApp, host};
use crate::renderer::Pass;

/// The synthesis shown (or being made) and what it is of.
#[derive(Default)]
pub(super) struct PyramidState {
    /// The photo and crop of the synthesis shown or running.
    key: Option<(String, [u32; 4])>,
    texture: Option<egui::TextureHandle>,
    rgba: Vec<u8>,
    size: [u32; 2],
    /// Rounds done and in all while it runs.
    progress: Option<(u32, u32)>,
    running: bool,
    cancelled: bool,
    error: Option<String>,
    ms: Option<f64>,
    /// Syntheses finished so far.
    finished: u64,
}

/// What the page and the tests can read of the pyramid view.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct PyramidSnapshot {
    /// A synthesis is running.
    pub running: bool,
    /// Rounds done and in all.
    pub progress: Option<[u32; 2]>,
    /// The size of the synthesis shown.
    pub size: Option<[u32; 2]>,
    /// Milliseconds the synthesis shown took in the worker.
    pub ms: Option<f64>,
    /// The last synthesis was cancelled.
    pub cancelled: bool,
    /// Why the last synthesis failed.
    pub error: Option<String>,
    /// Syntheses finished so far.
    pub finished: u64,
    /// The photo and crop the synthesis shown is of.
    pub of: Option<(String, [u32; 4])>,
}

impl PyramidState {
    pub(super) fn snapshot(&self) -> PyramidSnapshot {
        PyramidSnapshot {
            running: self.running,
            progress: self.progress.map(|(d, t)| [d, t]),
            size: self.texture.as_ref().map(|_| self.size),
            ms: self.ms,
            cancelled: self.cancelled,
            error: self.error.clone(),
            finished: self.finished,
            of: self.texture.as_ref().and(self.key.clone()),
        }
    }
}

impl ProctexApp {
    pub(super) fn pyramid_progress(&mut self, done: u32, total: u32) {
        if self.pyramid.running {
            self.pyramid.progress = Some((done, total));
        }
    }

    pub(super) fn pyramid_done(
        &mut self,
        ctx: &egui::Context,
        rgba: Vec<u8>,
        size: [u32; 2],
        ms: f64,
    ) {
        let image =
            egui::ColorImage::from_rgba_unmultiplied([size[0] as usize, size[1] as usize], &rgba);
        let options = egui::TextureOptions {
            wrap_mode: egui::TextureWrapMode::Repeat,
            ..egui::TextureOptions::LINEAR
        };
        let p = &mut self.pyramid;
        p.texture = Some(ctx.load_texture("pyramid", image, options));
        p.rgba = rgba;
        p.size = size;
        p.ms = Some(ms);
        p.running = false;
        p.progress = None;
        p.finished += 1;
    }

    /// The synthesis stopped without a texture: cancelled (`None`) or failed.
    pub(super) fn pyramid_stopped(&mut self, error: Option<String>) {
        let p = &mut self.pyramid;
        p.running = false;
        p.progress = None;
        p.cancelled = error.is_none();
        p.error = error.map(|e| proctex::limits::bounded_message(&e));
    }

    /// The current photo and crop.
    fn pyramid_key(&self) -> Option<(String, [u32; 4])> {
        self.photo.as_ref().map(|p| (p.name.clone(), p.crop))
    }

    /// Asks the worker for the synthesis of the current crop.
    fn request_pyramid(&mut self) {
        let Some((name, crop)) = self.pyramid_key() else {
            return;
        };
        let args: Vec<JsValue> = crop
            .iter()
            .map(|&v| JsValue::from(v))
            .chain([1.into()])
            .collect();
        if !host("synthesisePyramid", &args) {
            self.pyramid.error = Some("this page cannot run the synthesis".into());
            return;
        }
        let p = &mut self.pyramid;
        p.key = Some((name, crop));
        p.texture = None;
        p.running = true;
        p.cancelled = false;
        p.error = None;
        p.progress = None;
    }

    /// The central panel in pyramid mode: photo crop | texture | synthesis.
    pub(super) fn pyramid_view(
        &mut self,
        ui: &mut egui::Ui,
        rect: egui::Rect,
        response: &egui::Response,
        params: Params,
    ) {
        // A photo or crop this view has not synthesised (nor been told to stop for) starts one.
        let key = self.pyramid_key();
        if key.is_some() && key != self.pyramid.key {
            self.request_pyramid();
        }
        self.pan_zoom_input(ui, rect, response);
        let third = rect.width() / 3.0;
        let pane = |i: f32| {
            egui::Rect::from_min_max(
                egui::pos2((rect.min.x + i * third).round(), rect.min.y),
                egui::pos2((rect.min.x + (i + 1.0) * third).round(), rect.max.y),
            )
        };
        let (photo_rect, tex_rect, syn_rect) = (pane(0.0), pane(1.0), pane(2.0));
        let ppp = ui.ctx().pixels_per_point();
        let view = View {
            origin: self.view.origin,
            pixel_size: self.view.units_per_point / ppp,
            z: 0.0,
        };
        self.paint_texture(ui, tex_rect, params, Pass::Plane, view, None);
        ui.painter_at(tex_rect).text(
            tex_rect.left_top() + egui::vec2(6.0, 6.0),
            egui::Align2::LEFT_TOP,
            "procedural",
            egui::FontId::proportional(13.0),
            egui::Color32::from_gray(230),
        );
        self.paint_photo_crop(ui, photo_rect);
        self.paint_synthesis(ui, syn_rect);
        for r in [photo_rect, tex_rect] {
            ui.painter().line_segment(
                [r.right_top(), r.right_bottom()],
                egui::Stroke::new(2.0, egui::Color32::from_gray(20)),
            );
        }
        for (name, r) in [
            ("pyramid.photo", photo_rect),
            ("pyramid.texture", tex_rect),
            ("pyramid.synthesis", syn_rect),
        ] {
            self.widgets
                .insert(name.into(), [r.min.x, r.min.y, r.width(), r.height()]);
        }
        self.pyramid_buttons(ui, syn_rect);
    }

    /// The synthesis repeated over the view's world window (it tiles), or where it stands.
    fn paint_synthesis(&self, ui: &egui::Ui, rect: egui::Rect) {
        let painter = ui.painter_at(rect);
        painter.rect_filled(rect, 0.0, egui::Color32::from_gray(28));
        let label = |text: String| {
            painter.text(
                rect.left_top() + egui::vec2(6.0, 6.0),
                egui::Align2::LEFT_TOP,
                text,
                egui::FontId::proportional(13.0),
                egui::Color32::from_gray(230),
            );
        };
        let (Some(texture), Some((_, crop))) = (&self.pyramid.texture, &self.pyramid.key) else {
            let p = &self.pyramid;
            let status = if let Some(e) = &p.error {
                format!("Heeger–Bergen synthesis failed: {e}")
            } else if p.cancelled {
                "Heeger–Bergen synthesis cancelled".into()
            } else if let Some((d, t)) = p.progress {
                format!("Heeger–Bergen synthesis: round {d} of {t}")
            } else {
                "Heeger–Bergen synthesis: preparing".into()
            };
            painter.text(
                rect.center(),
                egui::Align2::CENTER_CENTER,
                status,
                egui::FontId::proportional(15.0),
                ui.visuals().text_color(),
            );
            return;
        };
        // World units are the crop's photo pixels; the synthesis covers the crop's extent and
        // repeats (the texture's wrap mode).
        let [cw, ch] = [crop[2] as f32, crop[3] as f32];
        let upp = self.view.units_per_point;
        let o = self.view.origin;
        let uv = egui::Rect::from_min_max(
            egui::pos2(o[0] / cw, o[1] / ch),
            egui::pos2(
                (o[0] + rect.width() * upp) / cw,
                (o[1] + rect.height() * upp) / ch,
            ),
        );
        painter.image(texture.id(), rect, uv, egui::Color32::WHITE);
        label(match self.pyramid.ms {
            Some(ms) => format!("Heeger–Bergen ({:.1} s)", ms / 1000.0),
            None => "Heeger–Bergen".into(),
        });
    }

    /// Cancel while it runs; Download PNG when it is there; Synthesise again after a stop.
    fn pyramid_buttons(&mut self, ui: &mut egui::Ui, rect: egui::Rect) {
        let at = egui::Rect::from_min_size(
            rect.left_bottom() + egui::vec2(8.0, -34.0),
            egui::vec2(170.0, 26.0),
        );
        if self.pyramid.running {
            let r = ui.put(at, egui::Button::new("Cancel"));
            self.record("pyramid.cancel", &r);
            if r.clicked() {
                host("cancelPyramid", &[]);
            }
        } else if self.pyramid.texture.is_some() {
            let r = ui
                .put(at, egui::Button::new("Download PNG (tiles)"))
                .on_hover_text("The synthesis at the crop's analysis size; it tiles seamlessly");
            self.record("pyramid.download", &r);
            if r.clicked() {
                self.download_pyramid();
            }
        } else if self.pyramid.cancelled || self.pyramid.error.is_some() {
            let r = ui.put(at, egui::Button::new("Synthesise again"));
            self.record("pyramid.again", &r);
            if r.clicked() {
                self.request_pyramid();
            }
        }
    }

    fn download_pyramid(&self) {
        let p = &self.pyramid;
        let Some((name, _)) = &p.key else {
            return;
        };
        let stem = name.rsplit_once('.').map_or(name.as_str(), |(s, _)| s);
        let file = format!("{stem}_heeger_bergen_{}x{}.png", p.size[0], p.size[1]);
        let rgba = js_sys::Uint8Array::from(&p.rgba[..]);
        host(
            "downloadPng",
            &[file.into(), rgba.into(), p.size[0].into(), p.size[1].into()],
        );
    }
}
