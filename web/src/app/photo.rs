//! The photo panel: the photo's name, size and crop, the gallery, errors and notes; what an
//! analysis result does to the app's state.

use eframe::egui;
use wasm_bindgen::JsValue;

use crate::jobs::Report;

use super::{PhotoPreview, PhotoState, ProctexApp, SAMPLES, ViewState, host, now_ms};

impl ProctexApp {
    pub(super) fn analysed(
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

    /// Left panel: samples, Open…, Camera…, the photo with its crop, status, plots.
    pub(super) fn photo_panel(&mut self, ui: &mut egui::Ui) {
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
            let flattened = self
                .analysed
                .as_ref()
                .and_then(|p| p.source.as_ref())
                .is_some_and(|s| s.flattened_lighting);
            let lighting = if flattened {
                ", lighting evened out"
            } else {
                ""
            };
            let r = ui.label(format!("{} — analysed in {ms:.0} ms{lighting}", photo.name));
            self.record("status", &r);
        } else {
            ui.label("Loading the sample photo…");
        }
        if let Some(err) = self.error.clone() {
            let err = proctex::limits::bounded_message(&err);
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
        egui::collapsing_header::CollapsingState::load_with_default_open(
            ui.ctx(),
            ui.make_persistent_id("model_suggestions"),
            true,
        )
        .show_header(ui, |ui| self.refine_budget_control(ui))
        .body(|ui| self.suggestions_panel(ui));
        egui::CollapsingHeader::new("Presets and morph")
            .default_open(true)
            .show(ui, |ui| self.presets_panel(ui));
    }
}
