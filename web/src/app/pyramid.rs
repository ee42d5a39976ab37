//! The pyramid view: the photo crop, the procedural texture and the Heeger–Bergen raster
//! synthesis of the same crop side by side, at one scale and over one world window (as Lagae et
//! al. Fig. 16 set a procedural texture beside a raster synthesis). The synthesis runs in the
//! worker (`proctexHost.synthesisePyramid`, one round per step, with progress and Cancel)
//! whenever this view shows a photo or crop it has not synthesised yet; it tiles seamlessly, so
//! it is drawn repeated across the window, and it downloads as a PNG tile. A texture mixture
//! (Heeger & Bergen §5) runs the same way between two textures A and B, each the crop, a
//! shipped sample or a preset's texture: "A" picks the first (the crop by default), "B" (mix
//! with) the second, the slider how far towards it (0: A's synthesis, 1: B's).

use eframe::egui;
use proctex::params::Params;
use proctex::render::View;
use wasm_bindgen::JsValue;

use super::{ProctexApp, SAMPLES, host};
use crate::renderer::Pass;

/// What a synthesis is of: the photo, the crop, A when it is not the crop, and the mixture
/// (B's source and m), if any.
type Key = (String, [u32; 4], Option<String>, Option<(String, f32)>);

/// The synthesis shown (or being made) and what it is of.
#[derive(Default)]
pub(super) struct PyramidState {
    /// What the synthesis shown or running is of.
    key: Option<Key>,
    /// The mixture asked for: B's source (`sample:NAME` or `preset:NAME`) and m.
    mix: Option<(String, f32)>,
    /// A's source when it is not the crop (`sample:NAME` or `preset:NAME`).
    a: Option<String>,
    /// The mixture slider's value while it is dragged (applied on release).
    slider: f32,
    texture: Option<egui::TextureHandle>,
    rgba: Vec<u8>,
    /// FNV-1a of `rgba`, computed once when it arrives (the snapshot is published every frame).
    checksum: u32,
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
    /// The mixture the synthesis shown is of: B's source and m.
    pub mix: Option<(String, f32)>,
    /// A's source when the synthesis shown is not of the crop.
    pub a: Option<String>,
    /// FNV-1a hash of the synthesis' RGBA (tests compare syntheses by it).
    pub checksum: Option<u32>,
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
            of: self
                .texture
                .as_ref()
                .and(self.key.as_ref().map(|k| (k.0.clone(), k.1))),
            mix: self
                .texture
                .as_ref()
                .and(self.key.as_ref())
                .and_then(|k| k.3.clone()),
            a: self
                .texture
                .as_ref()
                .and(self.key.as_ref())
                .and_then(|k| k.2.clone()),
            checksum: self.texture.as_ref().map(|_| self.checksum),
        }
    }
}

/// B's source when it is the photo's crop (A's is `None`).
const CROP: &str = "crop";

/// A mixture texture's name for labels: the sample's file stem, the preset's name or the crop.
fn source_label(source: &str) -> &str {
    if source == CROP {
        return "the crop";
    }
    source
        .split_once(':')
        .map_or(source, |(_, n)| n)
        .trim_end_matches(".png")
}

/// A's label: its source's, or the crop.
fn a_label(a: &Option<String>) -> &str {
    a.as_deref().map_or("the crop", source_label)
}

/// FNV-1a, 32 bits.
pub(super) fn fnv1a(bytes: &[u8]) -> u32 {
    bytes.iter().fold(0x811c_9dc5u32, |h, &b| {
        (h ^ b as u32).wrapping_mul(0x0100_0193)
    })
}

impl ProctexApp {
    /// Sets (or clears) the mixture's B and m, and A (`None`: the crop); the view synthesises
    /// it when it shows.
    pub(super) fn set_pyramid_mix(&mut self, mix: Option<(String, f32)>, a: Option<String>) {
        self.pyramid.slider = mix.as_ref().map_or(0.5, |m| m.1);
        self.pyramid.mix = mix;
        self.pyramid.a = a;
    }

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
        p.checksum = fnv1a(&rgba);
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

    /// What the view should show: the current photo and crop, A, and the mixture.
    fn pyramid_key(&self) -> Option<Key> {
        let p = &self.pyramid;
        self.photo
            .as_ref()
            .map(|photo| (photo.name.clone(), photo.crop, p.a.clone(), p.mix.clone()))
    }

    /// A texture of a mixture for the worker, as JSON: `{"sample": NAME, "m": m}` or
    /// `{"params": JSON, "m": m}`.
    fn mix_source(&self, (source, m): &(String, f32)) -> Result<String, String> {
        if source == CROP {
            let crop = self.photo.as_ref().map(|p| p.crop);
            return Ok(serde_json::json!({ "crop": crop, "m": m }).to_string());
        }
        if let Some(name) = source.strip_prefix("sample:") {
            return Ok(serde_json::json!({ "sample": name, "m": m }).to_string());
        }
        let p = &self.presets;
        let gallery = p.gallery.iter().map(|(g, _)| g);
        let preset = match source.strip_prefix("gallery:") {
            Some(name) => gallery.clone().find(|x| x.name == name),
            None => {
                let name = source.strip_prefix("preset:").unwrap_or(source);
                p.list.iter().chain(gallery).find(|x| x.name == name)
            }
        }
        .ok_or_else(|| {
            let name = source.split_once(':').map_or(source.as_str(), |(_, n)| n);
            format!("no preset named {}", proctex::limits::quote(name))
        })?;
        Ok(serde_json::json!({ "params": preset.params.to_json(), "m": m }).to_string())
    }

    /// Asks the worker for the synthesis of the current crop.
    fn request_pyramid(&mut self) {
        let Some(key) = self.pyramid_key() else {
            return;
        };
        let mut args: Vec<JsValue> = key.1.iter().map(|&v| JsValue::from(v)).collect();
        args.push(1.into()); // the seed
        let b = key.3.as_ref().map(|mix| self.mix_source(mix)).transpose();
        let a = key
            .2
            .as_ref()
            .map(|a| self.mix_source(&(a.clone(), 0.0)))
            .transpose();
        match (b, a) {
            (Ok(b), Ok(a)) => {
                args.push(b.map_or(JsValue::UNDEFINED, JsValue::from));
                args.push(a.map_or(JsValue::UNDEFINED, JsValue::from));
            }
            (Err(e), _) | (_, Err(e)) => {
                let p = &mut self.pyramid;
                (p.key, p.texture, p.running, p.cancelled) = (Some(key), None, false, false);
                p.error = Some(e);
                return;
            }
        }
        if !host("synthesisePyramid", &args) {
            self.pyramid.error = Some("this page cannot run the synthesis".into());
            return;
        }
        let p = &mut self.pyramid;
        p.key = Some(key);
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
        self.mix_controls(ui, syn_rect);
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
        let (Some(texture), Some((_, crop, a, mix))) = (&self.pyramid.texture, &self.pyramid.key)
        else {
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
        // repeats (the texture's wrap mode). A synthesis of another A is shown one texel per
        // world unit.
        let [cw, ch] = match a {
            None => [crop[2] as f32, crop[3] as f32],
            Some(_) => self.pyramid.size.map(|v| v as f32),
        };
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
        // What it is of, on a second line (the pane is narrow).
        let of = match (a, mix) {
            (None, None) => String::new(),
            (a, None) => format!("\nof {}", a_label(a)),
            (a, Some((b, m))) => format!("\n{} → {} at {m:.2}", a_label(a), source_label(b)),
        };
        label(match self.pyramid.ms {
            Some(ms) => format!("Heeger–Bergen ({:.1} s){of}", ms / 1000.0),
            None => format!("Heeger–Bergen{of}"),
        });
    }

    /// "A" (the crop, a sample, a preset), "B" (mix with: none, a sample, a preset) and the
    /// mixture's m, over the synthesis pane.
    fn mix_controls(&mut self, ui: &mut egui::Ui, rect: egui::Rect) {
        // Three rows above the button: A, B, then m.
        let at = egui::Rect::from_min_size(
            rect.left_bottom() + egui::vec2(8.0, -130.0),
            egui::vec2((rect.width() - 16.0).max(120.0), 92.0),
        );
        let width = (at.width() - 4.0).min(220.0);
        let mut a = self.pyramid.a.clone();
        let mut choice = self.pyramid.mix.clone();
        let mut slider = self.pyramid.slider;
        let mut released = false;
        let mut rects = Vec::new();
        let presets = &self.presets;
        // Every texture a mixture can take, as (source, label): the shipped photos, the gallery's
        // procedural textures (their analyses) and the user's presets. Listed only while a
        // combo box is open, not on every frame.
        let sources =
            || -> Vec<(String, String)> {
                SAMPLES
                    .iter()
                    .map(|n| {
                        (
                            format!("sample:{n}"),
                            n.trim_end_matches(".png").to_string(),
                        )
                    })
                    .chain(presets.gallery.iter().map(|(g, _)| {
                        (format!("gallery:{}", g.name), format!("gallery {}", g.name))
                    }))
                    .chain(
                        presets
                            .list
                            .iter()
                            .map(|p| (format!("preset:{}", p.name), format!("preset {}", p.name))),
                    )
                    .collect()
            };
        ui.scope_builder(egui::UiBuilder::new().max_rect(at), |ui| {
            ui.vertical(|ui| {
                let r = egui::ComboBox::from_id_salt("pyramid.a")
                    .selected_text(format!("A: {}", a_label(&a)))
                    .width(width)
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut a, None, "the crop");
                        for (source, label) in sources() {
                            ui.selectable_value(&mut a, Some(source), label);
                        }
                    })
                    .response
                    .on_hover_text("The texture synthesised (and mixed from)");
                rects.push(("pyramid.a", r));
                // A first pick starts halfway.
                let m = choice.as_ref().map_or(0.5, |c| c.1);
                let b = choice.as_ref().map_or("none", |c| source_label(&c.0));
                let r = egui::ComboBox::from_id_salt("pyramid.mix")
                    .selected_text(format!("B: {b}"))
                    .width(width)
                    .show_ui(ui, |ui| {
                        ui.selectable_value(&mut choice, None, "none");
                        ui.selectable_value(&mut choice, Some((CROP.into(), m)), "the crop");
                        for (source, label) in sources() {
                            ui.selectable_value(&mut choice, Some((source, m)), label);
                        }
                    })
                    .response
                    .on_hover_text("Mix with: the texture the mixture goes to at m = 1");
                rects.push(("pyramid.mix", r));
                if let Some((_, m)) = &choice
                    && self.pyramid.mix.is_none()
                {
                    slider = *m;
                }
                if choice.is_some() {
                    let r = ui
                        .add(egui::Slider::new(&mut slider, 0.0..=1.0).text("m"))
                        .on_hover_text("0: A's synthesis; 1: the other texture's");
                    released = r.drag_stopped() || (r.changed() && !r.dragged());
                    rects.push(("pyramid.m", r));
                }
            });
        });
        for (name, r) in rects {
            self.record(name, &r);
        }
        self.pyramid.slider = slider;
        if released {
            choice = choice.map(|(s, _)| (s, slider));
        }
        if choice != self.pyramid.mix {
            self.pyramid.mix = choice;
        }
        if a != self.pyramid.a {
            self.pyramid.a = a;
        }
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
        let Some((photo, _, a, mix)) = &p.key else {
            return;
        };
        let name = a
            .as_deref()
            .map_or(photo.as_str(), |a| a.split_once(':').map_or(a, |(_, n)| n));
        let stem = name.rsplit_once('.').map_or(name, |(s, _)| s);
        let mixed = match mix {
            Some((source, m)) => {
                let other = source.split_once(':').map_or(source.as_str(), |(_, n)| n);
                let other = other.rsplit_once('.').map_or(other, |(s, _)| s);
                format!("_mix_{other}_{m:.2}")
            }
            None => String::new(),
        };
        let file = format!(
            "{stem}{mixed}_heeger_bergen_{}x{}.png",
            p.size[0], p.size[1]
        );
        let rgba = js_sys::Uint8Array::from(&p.rgba[..]);
        host(
            "downloadPng",
            &[file.into(), rgba.into(), p.size[0].into(), p.size[1].into()],
        );
    }
}
