//! The parameters panel: a slider for every parameter, the structured model's controls,
//! and the edit history (undo, redo, reset).

use eframe::egui;
use proctex::params::{BandOrientation, MAX_CONTRAST, Model, NoiseModel};

use super::{ProctexApp, now_ms, short};

/// The structured model's controls: family, placement, every structural value (ranges and
/// tooltips from the spec table) and the colour ramp.
fn structure_controls(
    ui: &mut egui::Ui,
    m: &mut proctex::params::StructuredModel,
    rects: &mut Vec<(String, egui::Response)>,
) {
    use proctex::pattern::{Pattern, PatternKind};
    ui.separator();
    ui.label("Structure");
    let pat = &mut m.pattern;
    let mut kind = pat.kind;
    let r = egui::ComboBox::from_label("pattern")
        .selected_text(kind.name())
        .show_ui(ui, |ui| {
            for k in PatternKind::ALL {
                ui.selectable_value(&mut kind, k, k.name());
            }
        })
        .response;
    rects.push(("pattern.kind".into(), r));
    if kind != pat.kind {
        // Another family at its defaults, in the same place.
        let (scale, rotation) = (pat.scale, pat.rotation_deg);
        *pat = Pattern::new(kind, scale);
        pat.rotation_deg = rotation;
    }
    let r = ui.add(
        param_slider(&mut pat.scale, 1.0..=512.0)
            .logarithmic(true)
            .text("pattern scale (texels)"),
    );
    rects.push(("pattern.scale".into(), r));
    let r = ui.add(param_slider(&mut pat.rotation_deg, -180.0..=180.0).text("pattern rotation °"));
    rects.push(("pattern.rotation".into(), r));
    let mut values = pat.vector();
    for (spec, v) in pat.kind.specs().iter().zip(values.iter_mut()) {
        let r = ui
            .add(param_slider(v, spec.min..=spec.max).text(spec.name))
            .on_hover_text(spec.doc);
        rects.push((format!("pattern.{}", spec.name), r));
    }
    if values != pat.vector() {
        pat.set_vector(&values);
    }
    ui.horizontal(|ui| {
        ui.label("Colour ramp along the structure value");
        let r = ui.button("swap tones").on_hover_text(
            "Reads the ramp backwards (the two-tone paper's tone swap): the pattern's \
                 cells take the joints' colours and the joints the cells'",
        );
        if r.clicked() {
            proctex::pattern::swap_tones(&mut m.ramp);
        }
        rects.push(("ramp.swap".into(), r));
    });
    let n = m.ramp.len();
    for i in 0..n {
        let lo = if i == 0 { 0.0 } else { m.ramp[i - 1].at };
        let hi = if i + 1 == n { 1.0 } else { m.ramp[i + 1].at };
        let stop = &mut m.ramp[i];
        ui.horizontal(|ui| {
            let r = colour_button(ui, &mut stop.rgb);
            rects.push((format!("ramp.{i}.colour"), r));
            let r = ui.add(param_slider(&mut stop.at, 0.0..=1.0).text("at"));
            stop.at = stop.at.clamp(lo, hi);
            rects.push((format!("ramp.{i}.at"), r));
        });
    }
    if let Some(tone) = &mut m.tone {
        tone_controls(ui, tone, rects);
    }
}

/// The output tone curve's switch and plot (the structured model's, or the noise model's).
fn tone_controls(
    ui: &mut egui::Ui,
    tone: &mut proctex::params::Tone,
    rects: &mut Vec<(String, egui::Response)>,
) {
    let r = ui
        .checkbox(&mut tone.enabled, "output tone curve")
        .on_hover_text(
            "Per RGB channel, maps the synthesis's colour distribution onto the photo's \
             (fitted by the analysis; the plot shows output against input, 0 to 1)",
        );
    rects.push(("tone".into(), r));
    tone_plot(ui, tone);
}

impl ProctexApp {
    /// Right panel: history buttons and a slider for every parameter.
    pub(super) fn controls(&mut self, ui: &mut egui::Ui) {
        ui.heading("Parameters");
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
            let r = ui.add_enabled(
                self.analysed.is_some(),
                egui::Button::new("Reset to analysed"),
            );
            self.record("reset", &r);
            if r.clicked()
                && let Some(a) = &self.analysed
            {
                self.params = Some(a.clone());
            }
        });
        let Some(params) = self.params.as_mut() else {
            return;
        };
        let before = params.clone();
        let mut rects: Vec<(String, egui::Response)> = Vec::new();
        ui.separator();
        egui::ScrollArea::vertical().show(ui, |ui| {
            ui.label("Transform");
            let r = ui.add(
                param_slider(&mut params.transform.scale, 0.05..=50.0)
                    .logarithmic(true)
                    .text("scale (px per texel)"),
            );
            rects.push(("scale".into(), r));
            let r = ui.add(
                param_slider(&mut params.transform.rotation_deg, -180.0..=180.0).text("rotation °"),
            );
            rects.push(("rotation".into(), r));
            ui.horizontal(|ui| {
                ui.label("seed");
                let r = ui.add(egui::DragValue::new(&mut params.seed));
                rects.push(("seed".into(), r));
                let r = ui
                    .checkbox(&mut params.solid, "solid (3D noise)")
                    .on_hover_text("Plane view shows the z = 0 slice of the solid texture");
                rects.push(("solid".into(), r));
            });
            ui.separator();
            ui.label("Colour");
            ui.horizontal(|ui| {
                ui.label("mean colour");
                let r = colour_button(ui, &mut params.colour.mean);
                rects.push(("mean".into(), r));
            });
            let r = ui.add(
                param_slider(&mut params.colour.contrast, 0.0..=MAX_CONTRAST).text("contrast"),
            );
            rects.push(("contrast".into(), r));
            if let Model::Structured(m) = &mut params.model {
                structure_controls(ui, m, &mut rects);
                ui.separator();
                ui.label("Residual noise (what the structure does not explain)");
            }
            let model = params.model.noise_layer_mut();
            let r = ui.checkbox(&mut model.histogram.enabled, "histogram matching");
            rects.push(("histogram".into(), r));
            if let Some(tone) = &mut model.tone {
                tone_controls(ui, tone, &mut rects);
            }
            let scale = params.transform.scale;
            for (c, weights) in model.weights.iter_mut().enumerate() {
                let fine = &mut model.fine[c];
                ui.separator();
                ui.label(match c {
                    0 => "Channel 1 (principal axis) — band weights",
                    1 => "Channel 2 — band weights",
                    _ => "Channel 3 — band weights",
                });
                let max = weights.iter().cloned().fold(0.05f32, f32::max) * 2.0;
                for (j, w) in weights.iter_mut().enumerate() {
                    // Band j holds wavelengths of 2^(j+1)…2^(j+2) texels, i.e. frequencies
                    // 1/hi…1/lo cycles per pixel.
                    let lo = (1u32 << (j + 1)) as f32 * scale;
                    let hi = (1u32 << (j + 2)) as f32 * scale;
                    let r = ui
                        .add(param_slider(w, 0.0..=max).text(format!(
                            "1/{}–1/{} cyc/px",
                            short(hi),
                            short(lo)
                        )))
                        .on_hover_text(format!(
                            "band {j}: wavelengths {}–{} px ({}–{} texels); 0 removes it",
                            short(lo),
                            short(hi),
                            1u32 << (j + 1),
                            1u32 << (j + 2)
                        ));
                    rects.push((format!("weight.{c}.{j}"), r));
                }
                // The finest band's part drawn after the histogram, bounded.
                // Up to four times the analysed part (a band's power sixteen times), within
                // the valid range.
                let max = (fine.max(0.05) * 4.0).min(4.0);
                let r = ui
                    .add(param_slider(fine, 0.0..=max).text(format!(
                        "1/{}–1/{} cyc/px, bounded",
                        short(4.0 * scale),
                        short(2.0 * scale)
                    )))
                    .on_hover_text(
                        "the finest band drawn after the histogram matching, bounded at 1.6 \
                         of its deviations (in channel units): fine grain without tails, which \
                         on this band would be isolated bright or dark pixels; 0: the finest \
                         band only through its weight above",
                    );
                rects.push((format!("fine.{c}"), r));
            }
            orientation_controls(ui, model, scale, &mut rects);
        });
        if *params != before {
            self.last_edit_ms = now_ms();
        }
        for (name, r) in rects {
            self.record(name, &r);
        }
    }

    /// Undo bookkeeping: once no widget is being dragged, a changed params set is one step.
    pub(super) fn commit_edits(&mut self, ctx: &egui::Context) {
        if self.presets.playing {
            // An animation is not an edit.
            self.committed = self.params.clone();
            return;
        }
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

    pub(super) fn undo(&mut self) {
        if let (Some(prev), Some(cur)) = (self.undo.pop(), self.params.clone()) {
            self.redo.push(cur);
            self.params = Some(prev.clone());
            self.committed = Some(prev);
        }
    }

    pub(super) fn redo(&mut self) {
        if let (Some(next), Some(cur)) = (self.redo.pop(), self.params.clone()) {
            self.undo.push(cur);
            self.params = Some(next.clone());
            self.committed = Some(next);
        }
    }

    pub(super) fn record(&mut self, name: impl Into<String>, r: &egui::Response) {
        let rect = r.rect;
        self.widgets.insert(
            name.into(),
            [rect.min.x, rect.min.y, rect.width(), rect.height()],
        );
    }
}

/// The output tone curve of each RGB channel, output against input over `[0, 1]`.
fn tone_plot(ui: &mut egui::Ui, tone: &proctex::params::Tone) {
    let (rect, _) = ui.allocate_exact_size(egui::vec2(160.0, 100.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let visuals = ui.visuals();
    painter.rect_filled(rect, 2.0, visuals.extreme_bg_color);
    painter.line_segment(
        [rect.left_bottom(), rect.right_top()],
        egui::Stroke::new(1.0, visuals.weak_text_color()),
    );
    let colours = [
        egui::Color32::from_rgb(230, 80, 80),
        egui::Color32::from_rgb(80, 200, 80),
        egui::Color32::from_rgb(90, 130, 240),
    ];
    let alpha = if tone.enabled { 1.0 } else { 0.35 };
    let curve = tone.curve();
    for (c, colour) in colours.into_iter().enumerate() {
        let points: Vec<egui::Pos2> = (0..=64)
            .map(|i| {
                let x = i as f32 / 64.0;
                let y = curve(c, x).clamp(0.0, 1.0);
                egui::pos2(
                    rect.left() + x * rect.width(),
                    rect.bottom() - y * rect.height(),
                )
            })
            .collect();
        painter.add(egui::Shape::line(
            points,
            egui::Stroke::new(1.5, colour.gamma_multiply(alpha)),
        ));
    }
}

/// Per band, shared by the three channels: the direction its streaks run along and how strongly
/// (0: isotropic). A model without orientations gets them on the first edit.
fn orientation_controls(
    ui: &mut egui::Ui,
    model: &mut NoiseModel,
    scale: f32,
    rects: &mut Vec<(String, egui::Response)>,
) {
    ui.separator();
    ui.label("Band orientation (all channels) — streak direction and strength");
    let mut bands: Vec<BandOrientation> = (0..model.bands())
        .map(|j| model.band_orientation(j))
        .collect();
    let mut changed = false;
    for (j, o) in bands.iter_mut().enumerate() {
        let lo = (1u32 << (j + 1)) as f32 * scale;
        let hi = (1u32 << (j + 2)) as f32 * scale;
        let hover = format!(
            "band {j} (wavelengths {}–{} px): its features stretch along this direction; \
             strength 0 is isotropic, 1 puts all of its power across the streaks",
            short(lo),
            short(hi)
        );
        ui.horizontal(|ui| {
            // Angles outside [0, 180] (a morph's path) show wrapped; only an edit writes back.
            let mut angle = o.angle_deg.rem_euclid(180.0);
            let r = ui
                .add(param_slider(&mut angle, 0.0..=180.0).suffix("°"))
                .on_hover_text(hover.clone());
            if r.changed() {
                o.angle_deg = angle;
                changed = true;
            }
            rects.push((format!("orient.angle.{j}"), r));
            let r = ui
                .add(param_slider(&mut o.strength, 0.0..=1.0).text(format!("band {j}")))
                .on_hover_text(hover);
            changed |= r.changed();
            rects.push((format!("orient.strength.{j}"), r));
        });
    }
    if changed {
        model.orientation = bands;
    }
}

/// A colour button (egui's picker on click) that writes `rgb` back only when the user changed
/// it: egui's button converts the colour to HSVA and back on every frame it is drawn, which
/// moved some colours by a unit in the last place (a photo's mean colour 0.5563771 →
/// 0.55637705), so merely showing the controls made the params differ from the analysis'
/// (then the list's best model was not adopted: the params counted as edited).
fn colour_button(ui: &mut egui::Ui, rgb: &mut [f32; 3]) -> egui::Response {
    let mut shown = *rgb;
    let r = ui.color_edit_button_rgb(&mut shown);
    if r.changed() {
        *rgb = shown;
    }
    r
}

/// A slider over a parameter that leaves a value outside its range as it is until the user
/// drags it: egui's default clamps every value to the range whenever the slider is drawn, which
/// would change an analysed or imported value without the user touching it (and count as an
/// edit: then the list's best model is not adopted, as with the colour buttons above).
fn param_slider<Num: egui::emath::Numeric>(
    value: &mut Num,
    range: std::ops::RangeInclusive<Num>,
) -> egui::Slider<'_> {
    egui::Slider::new(value, range).clamping(egui::SliderClamping::Edits)
}
