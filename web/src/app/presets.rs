//! The presets panel: the built-in gallery, the user's presets (save, load, rename, reorder,
//! delete, import, export) and their storage in the browser.

use eframe::egui;
use wasm_bindgen::JsValue;

use crate::preset_store::{Change, KeyValue, PresetStore, Saved};
use crate::presets::{Preset, library_json};

use super::{ProctexApp, host};

/// The browser's `localStorage` as the presets' [`KeyValue`] store.
struct LocalStorage(web_sys::Storage);

impl LocalStorage {
    fn get() -> Option<LocalStorage> {
        web_sys::window()
            .and_then(|w| w.local_storage().ok().flatten())
            .map(LocalStorage)
    }
}

impl KeyValue for LocalStorage {
    fn get(&self, key: &str) -> Result<Option<String>, String> {
        self.0.get_item(key).map_err(|e| format!("{e:?}"))
    }
    fn set(&self, key: &str, value: &str) -> Result<(), String> {
        self.0.set_item(key, value).map_err(|e| format!("{e:?}"))
    }
}

impl ProctexApp {
    /// Loads the presets from `localStorage` (see [`PresetStore`]: an unreadable library is
    /// kept aside, one bad preset costs only itself).
    pub(super) fn with_stored_presets(mut self) -> Self {
        let Some(kv) = LocalStorage::get() else {
            self.presets.store.notice = Some(
                "Presets: this browser gives the page no storage; presets will not persist".into(),
            );
            return self;
        };
        let (store, list) = PresetStore::open(&kv, js_sys::Date::now() as u64);
        self.presets.store = store;
        self.set_presets(list);
        self
    }

    pub(super) fn set_presets(&mut self, list: Vec<Preset>) {
        let n = list.len();
        self.presets.list = list;
        self.presets.thumbs = vec![None; n];
        self.presets.selected = vec![false; n];
        self.presets.renaming = None;
    }

    /// Writes the library after `change` (the list is already changed in memory). Nothing
    /// stored is lost: a full quota leaves the stored library as it was, another tab's saves
    /// are kept (see [`PresetStore::save`]).
    pub(super) fn persist_presets(&mut self, change: Change) {
        let Some(kv) = LocalStorage::get() else {
            return;
        };
        let list = self.presets.list.clone();
        match self.presets.store.save(&kv, &list, change) {
            Ok(Saved::Written) => {}
            Ok(Saved::Merged(list)) => {
                self.set_presets(list);
                self.status_note =
                    Some("Presets were changed in another tab: yours were added to them".into());
            }
            Ok(Saved::Reloaded(list)) => {
                self.set_presets(list);
                self.presets.store.notice = Some(
                    "Presets were changed in another tab, so that list is shown now; your last \
                     edit was not applied: do it again"
                        .into(),
                );
            }
            // Shown by `presets_notice` until a save goes through.
            Err(_) => {}
        }
    }

    /// Another tab wrote the library: show it (the page calls this on the `storage` event).
    pub(super) fn presets_changed_elsewhere(&mut self) {
        let Some(kv) = LocalStorage::get() else {
            return;
        };
        if let Some(list) = self.presets.store.changed_elsewhere(&kv) {
            self.set_presets(list);
            self.status_note = Some("Presets updated from another tab".into());
        }
    }

    /// The stored library's notice, which stays until dismissed, with the unreadable library's
    /// download and discard.
    fn presets_notice(&mut self, ui: &mut egui::Ui) {
        if let Some(e) = &self.presets.store.save_error {
            ui.colored_label(ui.visuals().error_fg_color, e);
        }
        let Some(notice) = self.presets.store.notice.clone() else {
            return;
        };
        ui.colored_label(ui.visuals().error_fg_color, notice);
        ui.horizontal_wrapped(|ui| {
            if self.presets.store.unreadable.is_some() {
                let r = ui.small_button("Download the unreadable library");
                self.record("presets.download_unreadable", &r);
                // The text (megabytes, maybe) is read only on the click, not on every frame.
                if r.clicked()
                    && let Some(u) = &self.presets.store.unreadable
                {
                    host(
                        "downloadText",
                        &[
                            JsValue::from_str("proctex-presets-unreadable.json"),
                            JsValue::from_str(&u.text),
                        ],
                    );
                    self.presets.store.downloaded();
                }
            }
            if self.presets.store.locked() {
                let r = ui
                    .small_button("Discard it")
                    .on_hover_text("Let new saves replace the unreadable library");
                self.record("presets.discard_unreadable", &r);
                if r.clicked() {
                    self.presets.store.discard();
                }
            } else {
                let r = ui.small_button("Dismiss");
                self.record("presets.dismiss_notice", &r);
                if r.clicked() {
                    self.presets.store.dismiss();
                }
            }
        });
    }

    /// Save, load, rename, reorder, delete presets; choose two or more to morph between.
    pub(super) fn presets_panel(&mut self, ui: &mut egui::Ui) {
        let ctx = ui.ctx().clone();
        self.presets_notice(ui);
        ui.horizontal(|ui| {
            let r = ui.add(
                egui::TextEdit::singleline(&mut self.presets.new_name)
                    .hint_text("name")
                    .desired_width(120.0),
            );
            self.record("preset.name", &r);
            let r = ui.add_enabled(self.params.is_some(), egui::Button::new("Save preset"));
            self.record("preset.save", &r);
            if r.clicked()
                && let Some(p) = self.params.clone()
            {
                let name = match self.presets.new_name.trim() {
                    "" => self
                        .photo
                        .as_ref()
                        .map(|p| p.name.trim_end_matches(".png").to_string())
                        .unwrap_or_else(|| format!("preset {}", self.presets.list.len() + 1)),
                    n => n.to_string(),
                };
                let added = Preset {
                    name,
                    params: p,
                    morph: None,
                };
                let mut list = std::mem::take(&mut self.presets.list);
                list.push(added.clone());
                self.set_presets(list);
                self.presets.new_name.clear();
                self.persist_presets(Change::Added(&[added]));
            }
        });
        ui.horizontal(|ui| {
            let r = ui.small_button("Export…");
            self.record("presets.export", &r);
            if r.clicked() {
                host(
                    "downloadText",
                    &[
                        JsValue::from_str("proctex-presets.json"),
                        JsValue::from_str(&library_json(&self.presets.list)),
                    ],
                );
            }
            let r = ui.small_button("Import…");
            self.record("presets.import", &r);
            if r.clicked() {
                host("openPresets", &[]);
            }
        });
        if !self.presets.gallery.is_empty() {
            ui.label("Gallery (the samples, analysed):");
            let mut load = None;
            ui.horizontal_wrapped(|ui| {
                for i in 0..self.presets.gallery.len() {
                    let (preset, thumb) = &mut self.presets.gallery[i];
                    let id = thumb
                        .get_or_insert_with(|| {
                            let rgba = crate::jobs::preview_rgba(&preset.params, 40, 40);
                            let img = egui::ColorImage::from_rgba_unmultiplied([40, 40], &rgba);
                            ctx.load_texture(
                                format!("gallery{i}"),
                                img,
                                egui::TextureOptions::LINEAR,
                            )
                        })
                        .id();
                    let name = preset.name.clone();
                    let r = ui
                        .add(egui::Button::image((id, egui::vec2(32.0, 32.0))))
                        .on_hover_text(format!("{name}: click to load"));
                    self.record(format!("gallery.{i}"), &r);
                    if r.clicked() {
                        load = Some(i);
                    }
                }
                let r = ui
                    .small_button("+ to presets")
                    .on_hover_text("Copy the gallery into your presets (to rename, morph, export)");
                self.record("gallery.add", &r);
                if r.clicked() {
                    let added: Vec<Preset> = self
                        .presets
                        .gallery
                        .iter()
                        .map(|(p, _)| p.clone())
                        .collect();
                    let mut list = std::mem::take(&mut self.presets.list);
                    list.extend(added.iter().cloned());
                    self.set_presets(list);
                    self.persist_presets(Change::Added(&added));
                }
            });
            if let Some(i) = load {
                self.presets.morph = None;
                self.params = Some(self.presets.gallery[i].0.params.clone());
            }
        }
        let mut action: Option<(usize, &'static str)> = None;
        let n = self.presets.list.len();
        for i in 0..n {
            if self.presets.thumbs[i].is_none() {
                let rgba = crate::jobs::preview_rgba(&self.presets.list[i].params, 40, 40);
                let img = egui::ColorImage::from_rgba_unmultiplied([40, 40], &rgba);
                self.presets.thumbs[i] =
                    Some(ctx.load_texture(format!("preset{i}"), img, egui::TextureOptions::LINEAR));
            }
            let thumb = self.presets.thumbs[i].as_ref().map(|t| t.id());
            ui.horizontal(|ui| {
                let r = ui.checkbox(&mut self.presets.selected[i], "");
                self.record(format!("preset.{i}.morph"), &r);
                if let Some(id) = thumb {
                    ui.image((id, egui::vec2(24.0, 24.0)));
                }
                if let Some((j, text)) = self.presets.renaming.as_mut()
                    && *j == i
                {
                    let r = ui.add(egui::TextEdit::singleline(text).desired_width(110.0));
                    self.record(format!("preset.{i}.name"), &r);
                    if r.lost_focus() {
                        action = Some((i, "renamed"));
                    }
                } else {
                    let label = match &self.presets.list[i].morph {
                        Some(_) => format!("⟷ {}", self.presets.list[i].name),
                        None => self.presets.list[i].name.clone(),
                    };
                    let label = if label.chars().count() > 22 {
                        format!("{}…", label.chars().take(21).collect::<String>())
                    } else {
                        label
                    };
                    let r = ui.selectable_label(false, label).on_hover_text("Load");
                    self.record(format!("preset.{i}"), &r);
                    if r.clicked() {
                        action = Some((i, "load"));
                    }
                }
                for (what, icon) in [
                    ("rename", "✏"),
                    ("up", "↑"),
                    ("down", "↓"),
                    ("delete", "del"),
                ] {
                    let r = ui.small_button(icon).on_hover_text(what);
                    self.record(format!("preset.{i}.{what}"), &r);
                    if r.clicked() {
                        action = Some((i, what));
                    }
                }
            });
        }
        if let Some((i, what)) = action {
            self.preset_action(i, what);
        }
        self.morph_controls(ui);
    }

    pub(super) fn preset_action(&mut self, i: usize, what: &str) {
        let mut list = self.presets.list.clone();
        match what {
            "load" => {
                let p = &self.presets.list[i];
                match &p.morph {
                    Some(m) => {
                        self.presets.morph = Some(m.keys.clone());
                        self.presets.morph_from = None;
                        self.presets.duration_s = m.duration_s;
                        self.presets.t = 0.0;
                        self.params = Some(m.keys[0].clone());
                    }
                    None => {
                        self.presets.morph = None;
                        self.params = Some(p.params.clone());
                    }
                }
                return;
            }
            "rename" => {
                self.presets.renaming = Some((i, list[i].name.clone()));
                return;
            }
            "renamed" => {
                if let Some((_, name)) = self.presets.renaming.take()
                    && !name.trim().is_empty()
                {
                    list[i].name = name.trim().to_string();
                }
            }
            "up" if i > 0 => list.swap(i, i - 1),
            "down" if i + 1 < list.len() => list.swap(i, i + 1),
            "delete" => {
                list.remove(i);
            }
            _ => return,
        }
        let selected = self.presets.selected.clone();
        self.set_presets(list);
        if what == "renamed" {
            self.presets.selected = selected;
        }
        self.persist_presets(Change::Edited);
    }
}
