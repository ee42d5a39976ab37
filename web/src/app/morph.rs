//! The morph between ticked presets: t slider, Play with loop and duration, saving the
//! morph as a preset.

use eframe::egui;

use crate::preset_store::Change;
use crate::presets::{MorphPreset, Preset};

use super::{ProctexApp, export_shader};

impl ProctexApp {
    /// The morph: t slider, play/loop, duration, save as a preset.
    pub(super) fn morph_controls(&mut self, ui: &mut egui::Ui) {
        // Indices, not params: no per-frame clones; keys are copied only when the ticks change.
        let chosen: Vec<usize> = (0..self.presets.selected.len())
            .filter(|&i| self.presets.selected[i])
            .collect();
        if chosen.len() >= 2 && self.presets.morph_from.as_ref() != Some(&chosen) {
            let keys = chosen
                .iter()
                .map(|&i| self.presets.list[i].params.clone())
                .collect();
            self.presets.morph = Some(keys);
            self.presets.morph_from = Some(chosen);
            self.presets.t = 0.0;
            self.apply_morph();
        }
        // The keys are borrowed where used (cloned only to save): no per-frame copies.
        let Some(n_keys) = self.presets.morph.as_ref().map(Vec::len) else {
            ui.label("Tick two or more presets to morph between them.");
            return;
        };
        ui.label(format!("Morph through {n_keys} presets (Lagae §8)"));
        let r = ui.add(egui::Slider::new(&mut self.presets.t, 0.0..=1.0).text("t"));
        self.record("morph.t", &r);
        if r.changed() {
            self.presets.playing = false;
            self.apply_morph();
        }
        ui.horizontal(|ui| {
            let label = if self.presets.playing {
                "Pause"
            } else {
                "Play"
            };
            let r = ui.button(label);
            self.record("morph.play", &r);
            if r.clicked() {
                self.presets.playing = !self.presets.playing;
            }
            ui.checkbox(&mut self.presets.looping, "loop");
            ui.add(
                egui::DragValue::new(&mut self.presets.duration_s)
                    .range(0.5..=600.0)
                    .suffix(" s"),
            );
        });
        ui.horizontal(|ui| {
            let r = ui.small_button("Save morph");
            self.record("morph.save", &r);
            if r.clicked()
                && let Some(keys) = self.presets.morph.clone()
            {
                let added = Preset {
                    name: format!("morph of {n_keys}"),
                    params: keys[0].clone(),
                    morph: Some(MorphPreset {
                        keys,
                        duration_s: self.presets.duration_s,
                    }),
                };
                let mut list = self.presets.list.clone();
                list.push(added.clone());
                self.set_presets(list);
                self.persist_presets(Change::Added(&[added]));
            }
            let r = ui.small_button("Stop morphing");
            self.record("morph.stop", &r);
            if r.clicked() {
                self.presets.morph = None;
                self.presets.morph_from = None;
                self.presets.playing = false;
                self.presets.selected.iter_mut().for_each(|s| *s = false);
            }
        });
        ui.horizontal(|ui| {
            ui.label("Shader, t a uniform:");
            if let Some((format, ext, copy)) = self.shader_buttons(ui, "morph", true, "this morph")
                && let Some(keys) = &self.presets.morph
            {
                let text = export_shader(keys, ext);
                self.deliver_shader(format, ext, copy, "proctex-morph", text);
            }
        });
    }

    /// Sets the params to the morph at the current t (a uniform update only).
    pub(super) fn apply_morph(&mut self) {
        if let Some(keys) = &self.presets.morph {
            match proctex::morph::morph_path(keys, self.presets.t) {
                Ok(p) => self.params = Some(p),
                Err(e) => self.error = Some(format!("Morph: {e}")),
            }
        }
    }

    /// Advances a playing morph by the frame time.
    pub(super) fn advance_morph(&mut self, ctx: &egui::Context) {
        if !self.presets.playing || self.presets.morph.is_none() {
            return;
        }
        let dt = ctx.input(|i| i.stable_dt).min(0.25);
        let mut t = self.presets.t + dt / self.presets.duration_s.max(0.1);
        if t >= 1.0 {
            if self.presets.looping {
                t -= 1.0;
            } else {
                t = 1.0;
                self.presets.playing = false;
            }
        }
        self.presets.t = t;
        self.apply_morph();
        ctx.request_repaint();
    }
}
