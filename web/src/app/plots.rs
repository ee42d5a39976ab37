//! The plots: the photo crop's power spectrum and RGB histograms against the model's, and
//! the requests for the model's statistics once edits pause.

use eframe::egui;
use wasm_bindgen::JsValue;

use super::{ProctexApp, host, now_ms};

impl ProctexApp {
    /// The plots in a window over the texture, while the toolbar's "Plots" is on.
    pub(super) fn plots_window(&mut self, ctx: &egui::Context) {
        let mut open = self.show_plots;
        // First shown at the texture's bottom right, clear of the parameters panel.
        let corner = ctx.content_rect().right_bottom() - egui::vec2(340.0, 60.0);
        egui::Window::new("Plots")
            .open(&mut open)
            .default_width(340.0)
            .pivot(egui::Align2::RIGHT_BOTTOM)
            .default_pos(corner)
            .resizable(false)
            .show(ctx, |ui| self.plots(ui));
        self.show_plots = open;
    }

    /// The radially averaged power spectrum and the RGB histograms, photo against model. The
    /// model's statistics are recomputed by the worker once edits pause.
    pub(super) fn plots(&mut self, ui: &mut egui::Ui) {
        use egui_plot::{Legend, Line, LineStyle, Plot, PlotPoints};
        let Some(photo) = self.photo_stats.clone() else {
            return;
        };
        let model = self.model_stats.as_ref().map(|(_, s)| s.clone());
        let model = model.as_ref();
        let current = self.plots_current();
        ui.label(if current {
            "Photo (solid) vs model (dashed)"
        } else {
            "Photo (solid) vs model (dashed) — updating…"
        });
        let ring_points = |spec: &[f64]| -> PlotPoints<'static> {
            spec.iter()
                .enumerate()
                .filter(|(_, p)| **p > 0.0)
                .map(|(k, p)| {
                    // Ring k spans 2^−(1 + (k+1)/4) … 2^−(1 + k/4) cycles per texel.
                    let log2_f = -(1.0 + (k as f64 + 0.5) / 4.0);
                    [log2_f, 10.0 * p.log10()]
                })
                .collect()
        };
        let r = Plot::new("spectrum")
            .height(150.0)
            .legend(Legend::default())
            .x_axis_label("log₂ frequency (cycles / texel)")
            .y_axis_label("power dB")
            .allow_scroll(false)
            .show(ui, |plot| {
                plot.line(
                    Line::new("photo", ring_points(&photo.spectrum))
                        .color(egui::Color32::from_rgb(230, 230, 230)),
                );
                if let Some(m) = model {
                    plot.line(
                        Line::new("model", ring_points(&m.spectrum))
                            .color(egui::Color32::from_rgb(250, 200, 60))
                            .style(LineStyle::dashed_loose()),
                    );
                }
            });
        self.record("plot.spectrum", &r.response);
        let colours = [
            egui::Color32::from_rgb(235, 90, 80),
            egui::Color32::from_rgb(90, 200, 100),
            egui::Color32::from_rgb(90, 140, 240),
        ];
        let hist_points = |h: &[f64]| -> PlotPoints<'static> {
            let n = h.len() as f64;
            h.iter()
                .enumerate()
                .map(|(i, v)| [(i as f64 + 0.5) / n, *v * n])
                .collect()
        };
        let r = Plot::new("histograms")
            .height(140.0)
            .x_axis_label("value")
            .y_axis_label("density")
            .allow_scroll(false)
            .show(ui, |plot| {
                for c in 0..3 {
                    let name = ["R", "G", "B"][c];
                    plot.line(
                        Line::new(format!("photo {name}"), hist_points(&photo.histograms[c]))
                            .color(colours[c]),
                    );
                    if let Some(m) = model {
                        plot.line(
                            Line::new(format!("model {name}"), hist_points(&m.histograms[c]))
                                .color(colours[c])
                                .style(LineStyle::dashed_loose()),
                        );
                    }
                }
            });
        self.record("plot.histograms", &r.response);
    }

    pub(super) fn plots_current(&self) -> bool {
        match (&self.model_stats, &self.params) {
            (Some((p, _)), Some(cur)) => p == cur,
            _ => false,
        }
    }

    /// Asks the worker for the model's statistics once edits have paused for 300 ms.
    pub(super) fn request_stats(&mut self, ctx: &egui::Context) {
        let Some(params) = &self.params else {
            return;
        };
        if self.stats_requested.as_ref() == Some(params) {
            return;
        }
        let idle = now_ms() - self.last_edit_ms;
        if ctx.dragged_id().is_some() || idle < 300.0 {
            ctx.request_repaint_after(std::time::Duration::from_millis(100));
            return;
        }
        self.stats_requested = Some(params.clone());
        host("modelStats", &[JsValue::from_str(&params.to_json())]);
    }
}
