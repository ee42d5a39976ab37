//! The model suggestions: the ranked list the worker fills after each analysis, with
//! thumbnails, progress, Cancel, the time budget, and adoption of the best or a clicked row.

use eframe::egui;
use wasm_bindgen::JsValue;

use crate::jobs::{Report, SuggestionRow, THUMB_SIDE};

use super::{Pick, ProctexApp, SuggestState, host};

impl ProctexApp {
    /// The worker's ranked suggestions arrived: thumbnails become textures; the best is
    /// adopted when it is a structured model and the params are still the analysis's (an edit
    /// made while the worker refined is not overwritten).
    pub(super) fn suggestions(
        &mut self,
        ctx: &egui::Context,
        rows: Vec<SuggestionRow>,
        thumbnails: Vec<u8>,
        (cancelled, timed_out): (bool, bool),
        best: Option<Box<Report>>,
    ) {
        let side = THUMB_SIDE as usize;
        let thumbs = thumbnails
            .chunks_exact(side * side * 4)
            .enumerate()
            .map(|(i, px)| {
                let image = egui::ColorImage::from_rgba_unmultiplied([side, side], px);
                ctx.load_texture(
                    format!("suggestion{i}"),
                    image,
                    egui::TextureOptions::LINEAR,
                )
            })
            .collect();
        let unedited = self.params.is_some() && self.params == self.analysed;
        let pick = self.suggest.pick.take();
        self.suggest = SuggestState {
            rows,
            thumbs,
            progress: None,
            cancelled,
            timed_out,
            ..SuggestState::default()
        };
        // The user's pick for this very photo and crop, where it is not the best.
        let picked = pick
            .filter(|p| {
                self.photo
                    .as_ref()
                    .is_some_and(|ph| ph.name == p.photo && ph.crop == p.crop)
            })
            .and_then(|p| {
                let i = self.suggest.rows.iter().position(|r| r.name == p.model)?;
                self.suggest.pick = Some(p);
                Some(i)
            })
            .filter(|&i| i > 0);
        if let Some(i) = picked.filter(|_| unedited) {
            self.request_adoption(i);
            return;
        }
        match best {
            Some(report) if unedited => self.adopt(0, *report),
            None if unedited && self.suggest.rows.first().is_some_and(|r| r.name == "noise") => {
                // The noise model is first: the analysis already shown is it.
                self.suggest.adopted = Some(0);
                self.suggest.adopted_params = self.params.clone();
            }
            _ => {}
        }
    }

    /// Row `index` of the list shown was fitted after the list came: its texture distance
    /// and thumbnail. (A late row of a list since replaced names another model, or none, and
    /// is dropped.)
    pub(super) fn suggestion_fitted(&mut self, index: usize, row: SuggestionRow, thumbnail: &[u8]) {
        let Some(shown) = self.suggest.rows.get_mut(index) else {
            return;
        };
        if shown.name != row.name || shown.score != row.score {
            return;
        }
        *shown = row;
        let side = THUMB_SIDE as usize;
        let image = egui::ColorImage::from_rgba_unmultiplied([side, side], thumbnail);
        if let Some(t) = self.suggest.thumbs.get_mut(index) {
            t.set(image, egui::TextureOptions::LINEAR);
        }
    }

    /// Makes suggestion `index`'s fitted params current: one undoable step; "Reset to
    /// analysed" returns to them.
    pub(super) fn adopt(&mut self, index: usize, report: Report) {
        if let Some(cur) = self.params.clone() {
            self.undo.push(cur);
            self.redo.clear();
        }
        self.presets.morph = None;
        self.params = Some(report.params.clone());
        self.committed = Some(report.params.clone());
        self.analysed = Some(report.params.clone());
        self.model_stats = Some((report.params.clone(), report.model));
        self.stats_requested = Some(report.params.clone());
        self.suggest.adopted = Some(index);
        self.suggest.adopted_params = Some(report.params);
    }

    /// The row the current params came from, while they are unedited.
    pub(super) fn adopted_row(&self) -> Option<usize> {
        self.suggest
            .adopted
            .filter(|_| self.params.is_some() && self.params == self.suggest.adopted_params)
    }

    /// The ranked list of models for the photo: thumbnails, scores, progress and Cancel while
    /// the worker refines; a click adopts a row.
    pub(super) fn suggestions_panel(&mut self, ui: &mut egui::Ui) {
        if let Some(e) = &self.suggest.error {
            ui.colored_label(egui::Color32::from_rgb(240, 90, 70), e.as_str());
        }
        if let Some((done, total)) = self.suggest.progress {
            ui.horizontal(|ui| {
                let frac = if total > 0 {
                    done as f32 / total as f32
                } else {
                    0.0
                };
                let r = ui.add(
                    egui::ProgressBar::new(frac)
                        .desired_width(150.0)
                        .text(format!("refining {done}/{total} models")),
                );
                self.record("suggest.progress", &r);
                let r = ui
                    .button("Cancel")
                    .on_hover_text("Stop refining; rank with what is refined so far");
                self.record("suggest.cancel", &r);
                if r.clicked() {
                    host("cancelSuggestions", &[]);
                }
            });
            // No timed repaint: each progress message from the worker wakes the app. Without a
            // GPU (software WebGPU) a frame costs ~170 ms of CPU, so a 10 Hz repaint took one
            // of this machine's two cores from the worker and its helper while they refined.
        } else if self.suggest.on_request {
            ui.horizontal_wrapped(|ui| {
                let r = ui.button("Suggest models").on_hover_text(
                    "Retrieve and refine every structured model family for this photo and \
                     rank them against the noise model (the built-in sample waits for this \
                     click; your own photos get their suggestions at once)",
                );
                self.record("suggest.start", &r);
                if r.clicked() {
                    if host("suggestModels", &[]) {
                        self.suggest.on_request = false;
                    } else {
                        self.error =
                            Some("Model suggestions: the page's worker is unavailable".into());
                    }
                }
                ui.label("for this sample; your photos get them at once.");
            });
        } else if self.suggest.rows.is_empty() && self.suggest.error.is_none() {
            ui.label("Suggestions appear after the analysis.");
        }
        if self.suggest.timed_out {
            let refined = self
                .suggest
                .rows
                .iter()
                .filter(|r| r.refined.is_some())
                .count();
            ui.label(format!(
                "Time budget reached: {refined} models refined, the others ranked by retrieval."
            ));
        } else if self.suggest.cancelled {
            ui.label("Refinement cancelled: unrefined models ranked by retrieval.");
        }
        let adopted = self.adopted_row();
        let mut clicked = None;
        // Compact tiles (thumbnail, name, score), a few per row, so that the list does not
        // push the presets below the fold.
        ui.horizontal_wrapped(|ui| {
            ui.spacing_mut().item_spacing = egui::vec2(4.0, 4.0);
            for i in 0..self.suggest.rows.len() {
                let row = &self.suggest.rows[i];
                let texture = row
                    .distance
                    .map_or("fitting…".into(), |d| format!("{d:.3}"));
                // The noise model and the families the classifier puts first come first, those
                // by the scores of their fitted renders and the classifier's opinion; the other
                // families follow in the classifier's order (`Suggester::ranked`), their scores
                // their structure distances.
                let compared = row.render_ordered;
                let mut tip = format!(
                    "{}: score {:.3} (lower is nearer; {})\ntexture distance {texture}",
                    row.name,
                    row.score,
                    if compared {
                        "the first models are compared by their fitted renders and the family classifier"
                    } else {
                        "after the models compared by their renders; score by structure distance"
                    }
                );
                if let Some(r) = row.retrieval {
                    tip += &format!("\nstructure distance: retrieval {r:.3}");
                    if let Some(f) = row.refined {
                        tip += &format!(" → refined {f:.3}");
                    } else if row.skipped {
                        tip += " (not refined: not among the models compared by their renders)";
                    }
                }
                if row.speckier {
                    tip += "\npassed over by the automatic choice: its render has more isolated \
                            specks than 1.5× the photo's own, and a model after it has not";
                }
                tip += if adopted == Some(i) {
                    "\n(current model)"
                } else {
                    "\nclick to adopt"
                };
                let (rect, r) =
                    ui.allocate_exact_size(egui::vec2(56.0, 72.0), egui::Sense::click());
                let visuals = ui.visuals();
                let fill = if adopted == Some(i) {
                    Some(visuals.selection.bg_fill)
                } else if r.hovered() {
                    Some(visuals.widgets.hovered.bg_fill)
                } else {
                    None
                };
                let text = visuals.text_color();
                let painter = ui.painter();
                if let Some(f) = fill {
                    painter.rect_filled(rect, 3.0, f);
                }
                let img = egui::Rect::from_min_size(
                    rect.min + egui::vec2(6.0, 3.0),
                    egui::vec2(44.0, 44.0),
                );
                match self.suggest.thumbs.get(i) {
                    // Fitted after the list came (its thumbnail follows): a still placeholder.
                    // An animated spinner repaints every frame; on a software adapter each
                    // repaint takes the CPU that the worker fits these rows with (measured:
                    // 10–14 frames at ~0.2 s of the GPU process's CPU each while the rows of a
                    // 256² crop were fitted).
                    _ if row.distance.is_none() => {
                        let weak = visuals.weak_text_color();
                        painter.rect_stroke(
                            img.shrink(4.0),
                            3.0,
                            egui::Stroke::new(1.0, weak),
                            egui::StrokeKind::Inside,
                        );
                        painter.text(
                            img.center(),
                            egui::Align2::CENTER_CENTER,
                            "…",
                            egui::FontId::proportional(14.0),
                            weak,
                        );
                    }
                    Some(t) => egui::Image::new(t).paint_at(ui, img),
                    None => {}
                }
                let font = egui::FontId::proportional(10.0);
                let name = row.name.replace('_', " ");
                painter.text(
                    rect.center_bottom() - egui::vec2(0.0, 19.0),
                    egui::Align2::CENTER_CENTER,
                    name,
                    font.clone(),
                    text,
                );
                let score = if self.suggest.adopting == Some(i) {
                    "fitting…".to_string()
                } else {
                    format!("{:.2}", row.score)
                };
                // A row passed over for its specks shows its score in the warning colour.
                painter.text(
                    rect.center_bottom() - egui::vec2(0.0, 7.0),
                    egui::Align2::CENTER_CENTER,
                    score,
                    font,
                    if row.speckier {
                        visuals.warn_fg_color
                    } else {
                        text
                    },
                );
                let r = r.on_hover_text(tip);
                self.record(format!("suggestion.{i}"), &r);
                if r.clicked() && adopted != Some(i) {
                    clicked = Some(i);
                }
            }
        });
        if let Some(i) = clicked {
            self.suggest.pick = self.photo.as_ref().map(|ph| Pick {
                photo: ph.name.clone(),
                crop: ph.crop,
                model: self.suggest.rows[i].name.clone(),
            });
            self.request_adoption(i);
        }
    }

    /// Asks the worker for suggestion `i` fitted to the photo ([`Command::Adopted`] brings it).
    pub(super) fn request_adoption(&mut self, i: usize) {
        self.suggest.adopting = Some(i);
        if !host("adoptSuggestion", &[JsValue::from_f64(i as f64)]) {
            self.suggest.adopting = None;
            self.error = Some("Adopting a suggestion: the page's worker is unavailable".into());
        }
    }

    /// The refinement's time budget, in the "Model suggestions" header row (so that it takes
    /// no room from the list): 0 shows "none".
    pub(super) fn refine_budget_control(&mut self, ui: &mut egui::Ui) {
        ui.label("Model suggestions");
        ui.add_space(12.0);
        ui.label("time budget");
        let r = ui
            .add(
                egui::DragValue::new(&mut self.refine_budget_s)
                    .range(0.0..=120.0)
                    .speed(0.1)
                    .max_decimals(1)
                    .custom_formatter(|v, _| {
                        if v <= 0.0 {
                            "none".into()
                        } else {
                            format!("{v:.1} s")
                        }
                    })
                    .custom_parser(|t| {
                        let t = t.trim().trim_end_matches('s').trim();
                        if t.eq_ignore_ascii_case("none") {
                            Some(0.0)
                        } else {
                            t.parse::<f64>().ok()
                        }
                    }),
            )
            .on_hover_text(
                "Refinement time budget: after this long the refinement stops (each model \
                 keeps its best point so far) and the list is ranked; applies to the running \
                 refinement too. none: every model gets its full refinement (the same result \
                 on every machine)",
            );
        self.record("suggest.budget", &r);
        if r.changed() {
            host(
                "setRefineBudget",
                &[JsValue::from_f64(self.refine_budget_s as f64)],
            );
        }
    }
}
