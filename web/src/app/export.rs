//! Shader export: Copy / Download WGSL and GLSL of the texture or of a morph.

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
