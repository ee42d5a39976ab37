//! The solid views' texture source: the procedural solid texture (the params' 3D noise), or the
//! Heeger–Bergen solid texture of the crop (§4 of the paper): an `n³` raster volume synthesised
//! in the worker (`proctexHost.synthesiseSolid`, one round per step, with progress and Cancel)
//! whenever the sphere or cube shows a photo, crop or side it has not synthesised yet, and drawn
//! on the sphere or cube from a 3D texture (`volume_renderer`, `shaders/solid_volume.wgsl`).
//! The volume tiles along its three axes; a voxel stands for `crop / (2n)` photo pixels, so the
//! sphere shows it at the photo's scale, as the procedural solid is shown.

use std::sync::Arc;

use eframe::egui;
use proctex::solid::Voxels;

use super::{ProctexApp, host};
use crate::volume_renderer::VolumeSource;

/// The volume sides offered (the analyzer's default and its largest).
pub const SIDES: [u32; 2] = [
    proctex::heeger_bergen::solid::DEFAULT_SIDE,
    proctex::heeger_bergen::solid::MAX_SIDE,
];

/// What a volume is of: the photo, the crop, the side.
type Key = (String, [u32; 4], u32);

/// The solid views' source and the Heeger–Bergen volume (shown or being made).
pub(super) struct SolidState {
    /// Show the Heeger–Bergen volume instead of the procedural texture.
    pub(super) raster: bool,
    /// The side asked for.
    side: u32,
    /// What the volume shown or running is of.
    key: Option<Key>,
    volume: Option<VolumeSource>,
    /// Volumes received so far (also the next one's id).
    finished: u64,
    /// FNV-1a of the volume's voxels, computed once when it arrives.
    checksum: u32,
    progress: Option<(u32, u32)>,
    running: bool,
    cancelled: bool,
    error: Option<String>,
    ms: Option<f64>,
}

impl Default for SolidState {
    fn default() -> Self {
        SolidState {
            raster: false,
            side: SIDES[0],
            key: None,
            volume: None,
            finished: 0,
            checksum: 0,
            progress: None,
            running: false,
            cancelled: false,
            error: None,
            ms: None,
        }
    }
}

/// What the page and the tests can read of the solid views' source.
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct SolidSnapshot {
    /// "procedural" or "heeger-bergen".
    pub source: &'static str,
    /// The volume side asked for.
    pub side: u32,
    /// A volume is being synthesised.
    pub running: bool,
    /// Rounds done and in all.
    pub progress: Option<[u32; 2]>,
    /// The side of the volume shown.
    pub n: Option<u32>,
    /// Voxels per photo pixel of the volume shown.
    pub voxels_per_unit: Option<f32>,
    /// Milliseconds the volume shown took in the worker.
    pub ms: Option<f64>,
    /// The last synthesis was cancelled.
    pub cancelled: bool,
    /// Why the last synthesis failed.
    pub error: Option<String>,
    /// Volumes finished so far.
    pub finished: u64,
    /// The photo and crop the volume shown is of.
    pub of: Option<(String, [u32; 4])>,
    /// FNV-1a hash of the volume's RGBA voxels.
    pub checksum: Option<u32>,
}

impl SolidState {
    pub(super) fn snapshot(&self) -> SolidSnapshot {
        let shown = self.volume.as_ref();
        SolidSnapshot {
            source: if self.raster {
                "heeger-bergen"
            } else {
                "procedural"
            },
            side: self.side,
            running: self.running,
            progress: self.progress.map(|(d, t)| [d, t]),
            n: shown.map(|v| v.voxels.n),
            voxels_per_unit: shown.map(|v| v.voxels_per_unit),
            ms: self.ms,
            cancelled: self.cancelled,
            error: self.error.clone(),
            finished: self.finished,
            of: shown.and(self.key.as_ref()).map(|k| (k.0.clone(), k.1)),
            checksum: shown.map(|_| self.checksum),
        }
    }

    /// The volume to draw, when the Heeger–Bergen source is chosen and one is there.
    pub(super) fn shown(&self) -> Option<&VolumeSource> {
        self.volume.as_ref().filter(|_| self.raster)
    }
}

impl ProctexApp {
    /// Chooses the solid views' source (`raster`: the Heeger–Bergen volume) and its side.
    pub(super) fn set_solid_source(&mut self, raster: bool, side: u32) {
        self.solid.raster = raster;
        self.solid.side = side;
    }

    pub(super) fn solid_progress(&mut self, done: u32, total: u32) {
        if self.solid.running {
            self.solid.progress = Some((done, total));
        }
    }

    pub(super) fn solid_done(&mut self, rgba: Vec<u8>, n: u32, voxels_per_unit: f32, ms: f64) {
        let s = &mut self.solid;
        s.finished += 1;
        s.checksum = super::pyramid::fnv1a(&rgba);
        s.volume = Some(VolumeSource {
            id: s.finished,
            voxels_per_unit,
            voxels: Arc::new(Voxels { n, rgba }),
        });
        s.ms = Some(ms);
        s.running = false;
        s.progress = None;
    }

    /// The synthesis stopped without a volume: cancelled (`None`) or failed.
    pub(super) fn solid_stopped(&mut self, error: Option<String>) {
        let s = &mut self.solid;
        s.running = false;
        s.progress = None;
        s.cancelled = error.is_none();
        s.error = error.map(|e| proctex::limits::bounded_message(&e));
    }

    fn solid_key(&self) -> Option<Key> {
        self.photo
            .as_ref()
            .map(|p| (p.name.clone(), p.crop, self.solid.side))
    }

    /// Asks the worker for the volume of the current crop.
    fn request_solid(&mut self) {
        let Some(key) = self.solid_key() else {
            return;
        };
        let mut args: Vec<wasm_bindgen::JsValue> = key.1.iter().map(|&v| v.into()).collect();
        args.push(1.into()); // the seed
        args.push(key.2.into());
        if !host("synthesiseSolid", &args) {
            self.solid.error = Some("this page cannot run the synthesis".into());
            return;
        }
        let s = &mut self.solid;
        s.key = Some(key);
        s.volume = None;
        s.running = true;
        s.cancelled = false;
        s.error = None;
        s.progress = None;
    }

    /// Starts the volume the sphere or cube should show when the Heeger–Bergen source is chosen
    /// and the photo, crop or side changed (a stopped one waits for "Synthesise again").
    pub(super) fn keep_solid_current(&mut self) {
        let key = self.solid_key();
        if self.solid.raster && key.is_some() && key != self.solid.key {
            self.request_solid();
        }
    }

    /// The source choice over the top-left of the solid view, the side, and while the volume
    /// is missing, where it stands (with Cancel or "Synthesise again").
    pub(super) fn solid_controls(&mut self, ui: &mut egui::Ui, rect: egui::Rect) {
        // An area above the view's layer, on a dark backing: readable over the object.
        let width = (rect.width() - 16.0).max(160.0);
        let mut raster = self.solid.raster;
        let mut side = self.solid.side;
        let mut rects = Vec::new();
        let (mut cancel, mut again) = (false, false);
        let s = &self.solid;
        let area = egui::Area::new(egui::Id::unique("solid.controls"))
            .fixed_pos(rect.left_top() + egui::vec2(8.0, 8.0))
            .order(egui::Order::Middle)
            .constrain_to(rect);
        let frame = egui::Frame::new()
            .fill(egui::Color32::from_black_alpha(150))
            .inner_margin(egui::Margin::same(4))
            .corner_radius(egui::CornerRadius::same(4));
        area.show(ui.ctx(), |ui| {
            frame.show(ui, |ui| {
                ui.set_max_width(width);
                ui.horizontal_wrapped(|ui| {
                    let r = ui
                        .selectable_label(!raster, "Procedural")
                        .on_hover_text("The solid texture of the parameters (3D noise)");
                    if r.clicked() {
                        raster = false;
                    }
                    rects.push(("solid.procedural", r));
                    let r = ui
                    .selectable_label(raster, "Heeger–Bergen volume")
                    .on_hover_text(
                        "A raster solid texture synthesised from the crop (Heeger & Bergen §4): \
                     every slice matches the crop's subband histograms; it tiles in 3D",
                    );
                    if r.clicked() {
                        raster = true;
                    }
                    rects.push(("solid.raster", r));
                    if raster {
                        let r = egui::ComboBox::from_id_salt("solid.side")
                            .selected_text(format!("{side}³"))
                            .width(64.0)
                            .show_ui(ui, |ui| {
                                for n in SIDES {
                                    ui.selectable_value(&mut side, n, format!("{n}³"));
                                }
                            })
                            .response
                            .on_hover_text(
                                "The volume's side in voxels (128³ takes about 8× as long)",
                            );
                        rects.push(("solid.side", r));
                    }
                });
                if !raster {
                    return;
                }
                ui.horizontal(|ui| {
                    let status = if let Some(e) = &s.error {
                        Some(format!("Volume failed: {e}"))
                    } else if s.running {
                        Some(match s.progress {
                            Some((d, t)) => format!("Synthesising the volume: round {d} of {t}"),
                            None => "Synthesising the volume: preparing".into(),
                        })
                    } else if s.cancelled {
                        Some("Volume cancelled".into())
                    } else {
                        s.volume.as_ref().map(|v| {
                            format!(
                                "{}³ volume, {:.1} s",
                                v.voxels.n,
                                s.ms.unwrap_or(0.0) / 1000.0
                            )
                        })
                    };
                    if let Some(text) = status {
                        ui.label(egui::RichText::new(text).color(egui::Color32::from_gray(230)));
                    }
                    if s.running {
                        let r = ui.button("Cancel");
                        cancel = r.clicked();
                        rects.push(("solid.cancel", r));
                    } else if s.cancelled || s.error.is_some() {
                        let r = ui.button("Synthesise again");
                        again = r.clicked();
                        rects.push(("solid.again", r));
                    }
                });
            })
        });
        for (name, r) in rects {
            self.record(name, &r);
        }
        self.set_solid_source(raster, side);
        if cancel {
            host("cancelSolid", &[]);
        }
        if again {
            self.request_solid();
        }
    }
}
