//! Export: the strip under the texture (params JSON, share link, shaders, PNG tile) and the
//! shader buttons it shares with the morph controls (Copy / Download WGSL and GLSL).

use eframe::egui;
use proctex::params::Params;
use wasm_bindgen::JsValue;

use super::{ProctexApp, host};

/// The complete shader in `format` ("wgsl" or "glsl") of one texture, or of the morph through
/// two or more with t as a uniform, as `proctex export KEYS... --format FORMAT` writes it.
pub fn export_shader(keys: &[Params], format: &str) -> Result<String, String> {
    proctex::export::shader(keys, format).map_err(|e| e.to_string())
}

impl ProctexApp {
    /// The export strip under the texture: everything that takes the current texture out of the
    /// app (params JSON, share link, WGSL and GLSL shaders, seamless PNG tile), in one place.
    pub(super) fn export_bar(&mut self, ui: &mut egui::Ui) {
        ui.horizontal_wrapped(|ui| {
            ui.label("Export:");
            // Serialised on a click only: the strip is drawn every frame.
            let has_params = self.params.is_some();
            let r = ui
                .add_enabled(has_params, egui::Button::new("Params JSON…").small())
                .on_hover_text("Download the current params (proctex/1); drop or paste it back");
            self.record("params.download", &r);
            if r.clicked()
                && let Some(j) = &self.params.as_ref().map(Params::to_json)
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
                .add_enabled(has_params, egui::Button::new("Copy link").small())
                .on_hover_text("Copy a link that opens this texture (params in the URL fragment)");
            self.record("params.link", &r);
            if r.clicked()
                && let Some(j) = &self.params.as_ref().map(Params::to_json)
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
    }

    /// "Copy WGSL", "WGSL…", "Copy GLSL", "GLSL…" buttons (widgets `{prefix}.copy_wgsl`,
    /// `{prefix}.download_wgsl`, ...): the clicked one as (language, extension, copy?).
    pub(super) fn shader_buttons(
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
    pub(super) fn deliver_shader(
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
}
