//! The crop rectangle on the photo: drag inside to move it, a corner to resize it, outside to
//! draw a new one; the region is analysed again as it changes.

use eframe::egui;
use wasm_bindgen::JsValue;

use super::{ProctexApp, host};

/// What a drag on the crop panel is doing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum CropDrag {
    Move,
    /// Resizing from the corner opposite this fixed photo point.
    Resize {
        fixed: [f32; 2],
    },
}

/// Smallest crop side, photo pixels (the analyzer's minimum).
const MIN_CROP: u32 = proctex::input::MIN_SIDE;

impl ProctexApp {
    /// The photo with the crop rectangle: drag inside to move it, at a corner to resize, outside
    /// to draw a new one. Every change asks for a re-analysis (the page coalesces requests while
    /// the worker is busy, so dragging re-analyses as fast as the worker can).
    pub(super) fn crop_widget(&mut self, ui: &mut egui::Ui) {
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
        let relit = self.lighting_control(ui);
        if crop != old || relit {
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

    /// The lighting option under the crop: the photo's lighting gradient divided out before
    /// every analysis from now on (the worker's `analyzeRgba` option, `proctex analyze
    /// --flatten-lighting`). Returns whether it changed, for the crop to be analysed again.
    fn lighting_control(&mut self, ui: &mut egui::Ui) -> bool {
        let r = ui
            .checkbox(&mut self.flatten_lighting, "Even out lighting")
            .on_hover_text(
                "Divide the photo's lighting gradient out before the analysis (the plane \
                 through its log luminance): for a photo lit from one side, whose texture \
                 should not carry the light. On evenly lit photos it usually costs more than \
                 it gains, so it is off by default",
            );
        self.record("lighting", &r);
        if !r.changed() {
            return false;
        }
        host(
            "setFlattenLighting",
            &[JsValue::from_bool(self.flatten_lighting)],
        );
        true
    }
}
