//! The texture view: the toolbar of view modes, the central panel (plane with pan and zoom,
//! split against the photo, sphere and cube with orbit; the pyramid view is `pyramid`'s, the
//! solid views' Heeger–Bergen source `solid`'s), the
//! tile outline, and the paint callback that draws the cached view.

use eframe::egui;
use eframe::egui_wgpu;
use proctex::params::Params;
use proctex::render::{View, period_texels};
use proctex::solid::{Shape, SolidView};

use crate::renderer::Pass;
use crate::view_cache::{CachedView, ViewSource};

use super::{ProctexApp, ViewMode};

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

impl ProctexApp {
    /// The view toolbar (above the central panel).
    pub(super) fn toolbar(&mut self, ui: &mut egui::Ui) {
        // Wrapped: on a narrow window the toolbar takes a second row rather than hiding its
        // last buttons under the parameters panel.
        ui.horizontal_wrapped(|ui| {
            for m in ViewMode::ALL {
                let r = ui.selectable_label(self.mode == m, m.label());
                let r = match m.hover() {
                    Some(text) => r.on_hover_text(text),
                    None => r,
                };
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
            ui.separator();
            let r = ui
                .selectable_label(self.show_plots, "Plots")
                .on_hover_text("The photo's power spectrum and histograms against the model's");
            self.record("plots.toggle", &r);
            if r.clicked() {
                self.show_plots = !self.show_plots;
            }
        });
    }

    /// Central panel: the texture.
    pub(super) fn view_panel(&mut self, ui: &mut egui::Ui) {
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
                self.keep_solid_current();
                if let Some(volume) = self.solid.shown() {
                    let source = ViewSource::Volume(sv, volume.clone());
                    self.paint_view(ui, rect, solid, Pass::Solid, source);
                } else if self.solid.raster {
                    // The volume is on its way (or stopped): its status is in the controls.
                    ui.painter()
                        .rect_filled(rect, 0.0, egui::Color32::from_gray(28));
                } else {
                    self.paint_view(ui, rect, solid, Pass::Solid, ViewSource::Solid(sv));
                }
                self.solid_controls(ui, rect);
            }
            ViewMode::Pyramid => self.pyramid_view(ui, rect, &response, params),
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

    pub(super) fn pan_zoom_input(
        &mut self,
        ui: &egui::Ui,
        rect: egui::Rect,
        response: &egui::Response,
    ) {
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
    pub(super) fn orbit_input(&mut self, ui: &egui::Ui, response: &egui::Response) {
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

    pub(super) fn paint_texture(
        &self,
        ui: &egui::Ui,
        rect: egui::Rect,
        params: Params,
        pass: Pass,
        view: View,
        solid: Option<SolidView>,
    ) {
        let source = match solid {
            Some(sv) => ViewSource::Solid(sv),
            None => ViewSource::Plane(view),
        };
        self.paint_view(ui, rect, params, pass, source);
    }

    /// Draws `source` (through the frame cache) into `rect`.
    fn paint_view(
        &self,
        ui: &egui::Ui,
        rect: egui::Rect,
        params: Params,
        pass: Pass,
        source: ViewSource,
    ) {
        let ppp = ui.ctx().pixels_per_point();
        let min = [(rect.min.x * ppp).round(), (rect.min.y * ppp).round()];
        let max = [(rect.max.x * ppp).round(), (rect.max.y * ppp).round()];
        ui.painter().add(egui_wgpu::Callback::new_paint_callback(
            rect,
            TextureCallback {
                params,
                pass,
                view: source,
                frame_offset: min.map(|v| v as i32),
                frame_size: [0, 1].map(|i| (max[i] - min[i]).max(1.0) as u32),
                fresh: !self.frame_cache,
            },
        ));
    }

    /// The photo crop at the texture view's scale: world units are photo pixels and the crop's
    /// top-left is world (0, 0), so both halves show the same world window.
    pub(super) fn paint_photo_crop(&self, ui: &egui::Ui, rect: egui::Rect) {
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
    pub(super) fn paint_period(&self, ui: &egui::Ui, rect: egui::Rect, params: &Params) -> usize {
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
}
