//! The PNG tile export: a seamless tile rendered in strips on the GPU (or on the CPU as a
//! fallback), handed to the page row by row, with progress and Cancel.

use eframe::egui;
use proctex::params::Params;
use wasm_bindgen::JsValue;

use crate::tile_export::{SeamlessCpu, SeamlessGpu, png_scanlines};

use super::{ProctexApp, TileJob, TileSource, host, now_ms};

impl ProctexApp {
    /// PNG tile export: size, bit depth, Export PNG… (then progress and Cancel).
    pub(super) fn tile_row(&mut self, ui: &mut egui::Ui) {
        ui.horizontal(|ui| {
            ui.label("PNG tile:");
            if let Some(job) = &self.tile_job {
                let f = job.done_rows as f32 / job.size as f32;
                let on = match job.source {
                    TileSource::Gpu(_) => "GPU",
                    TileSource::Cpu(_) => "CPU",
                };
                ui.add(egui::ProgressBar::new(f).desired_width(120.0).text(format!(
                    "{}² {} % ({on})",
                    job.size,
                    (f * 100.0) as u32
                )));
                let r = ui.small_button("Cancel");
                self.record("export.png_cancel", &r);
                if r.clicked() {
                    host("tileAbort", &[]);
                    self.tile_job = None;
                    self.status_note = Some("PNG tile export cancelled".into());
                }
                return;
            }
            let r = egui::ComboBox::from_id_salt("tile_size")
                .width(70.0)
                .selected_text(format!("{}²", self.tile.size))
                .show_ui(ui, |ui| {
                    for n in [256u32, 512, 1024, 2048, 4096, 8192] {
                        ui.selectable_value(&mut self.tile.size, n, format!("{n}²"));
                    }
                });
            self.record("export.png_size", &r.response);
            let r = egui::ComboBox::from_id_salt("tile_bits")
                .width(60.0)
                .selected_text(format!("{}-bit", self.tile.bits))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.tile.bits, 8, "8-bit");
                    ui.selectable_value(&mut self.tile.bits, 16, "16-bit");
                });
            self.record("export.png_bits", &r.response);
            let r = ui
                .add_enabled(self.params.is_some(), egui::Button::new("PNG…").small())
                .on_hover_text(
                    "Download a seamless tile of the texture, one photo pixel per tile pixel \
                     (every band made periodic over the tile; structured models: the pattern \
                     turned to the nearest quarter turn, a whole number of cells over the tile; \
                     solid textures: their plane texture)",
                );
            self.record("export.png", &r);
            if r.clicked()
                && let Some(p) = self.params.clone()
            {
                self.start_tile(&p, ui.ctx());
            }
        });
    }

    /// Starts a PNG tile export of `params` on the GPU (CPU when there is none, or forced).
    pub(super) fn start_tile(&mut self, params: &Params, ctx: &egui::Context) {
        let (size, bits) = (self.tile.size, self.tile.bits);
        let gpu = if self.tile.force_cpu {
            None
        } else {
            self.gpu
                .as_ref()
                .map(|(device, queue)| SeamlessGpu::new(device, queue, params, size, 1.0))
        };
        let source = match gpu {
            Some(Ok(g)) => TileSource::Gpu(Box::new(g)),
            other => {
                if let Some(Err(e)) = other {
                    web_sys::console::warn_1(
                        &format!("PNG tile on the GPU: {e}; using the CPU").into(),
                    );
                }
                match SeamlessCpu::new(params, size, 1.0) {
                    Ok(c) => TileSource::Cpu(Box::new(c)),
                    Err(e) => {
                        self.error = Some(format!("PNG tile: {e}"));
                        return;
                    }
                }
            }
        };
        if !host(
            "tileBegin",
            &[
                JsValue::from(size),
                JsValue::from(size),
                JsValue::from(bits as u32),
            ],
        ) {
            self.error = Some("PNG tile: the page cannot write PNG files (no tileBegin)".into());
            return;
        }
        self.tile_job = Some(TileJob {
            size,
            bits,
            source,
            next_row: 0,
            done_rows: 0,
            started_ms: now_ms(),
            turn: proctex::seamless::tile_turn(params),
        });
        ctx.request_repaint();
    }

    /// Advances the PNG tile export by what is ready: a read-back strip from the GPU (and the
    /// next strip submitted), or a few CPU rows (about 30 ms of work).
    pub(super) fn step_tile(&mut self, ctx: &egui::Context, frame: &eframe::Frame) {
        if self.gpu.is_none()
            && let Some(rs) = frame.wgpu_render_state()
        {
            self.gpu = Some((rs.device.clone(), rs.queue.clone()));
        }
        let Some(job) = &mut self.tile_job else {
            return;
        };
        ctx.request_repaint();
        let size = job.size;
        let mut strip = None;
        match &mut job.source {
            TileSource::Gpu(g) => {
                match g.take() {
                    Some(Ok(s)) => strip = Some(s),
                    Some(Err(e)) => {
                        host("tileAbort", &[]);
                        self.tile_job = None;
                        self.error = Some(format!("PNG tile: {e}"));
                        return;
                    }
                    None => {}
                }
                if !g.busy()
                    && job.next_row < size
                    && let Some((device, queue)) = &self.gpu
                {
                    g.submit(device, queue, job.next_row);
                    job.next_row = (job.next_row + g.rows()).min(size);
                }
            }
            TileSource::Cpu(c) => {
                let t0 = now_ms();
                let mut rows = Vec::new();
                let first = job.next_row;
                while job.next_row < size && now_ms() - t0 < 30.0 {
                    let n = (16_384 / size).max(1);
                    rows.extend(c.strip(job.next_row, n));
                    job.next_row = (job.next_row + n).min(size);
                }
                if !rows.is_empty() {
                    strip = Some((first, rows));
                }
            }
        }
        if let Some((_, pixels)) = strip {
            let bytes = png_scanlines(&pixels, size as usize, job.bits);
            host(
                "tileRows",
                &[js_sys::Uint8Array::from(bytes.as_slice()).into()],
            );
            job.done_rows += (pixels.len() / size as usize) as u32;
        }
        if job.done_rows >= size {
            let name = format!("proctex-tile-{size}-{}bit.png", job.bits);
            host("tileEnd", &[JsValue::from_str(&name)]);
            let turn = job
                .turn
                .map(|(from, to)| format!("; the pattern turned {from:.1}° → {to:.0}° to repeat"))
                .unwrap_or_default();
            self.status_note = Some(format!(
                "PNG tile {size}² ({}-bit) rendered in {:.1} s{turn}",
                job.bits,
                (now_ms() - job.started_ms) / 1000.0
            ));
            self.tile_job = None;
        }
    }
}
