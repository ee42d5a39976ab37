//! Where the presets library lives, written so that no preset is ever lost: not to a corrupt
//! store, not to a full quota, not to a second tab.
//!
//! - **Reading** is per preset ([`crate::presets::read_library`]): one bad preset costs only
//!   itself and is reported by name.
//! - **An unreadable library** (or one with bad presets) is copied to a backup key before
//!   anything else, and the copy is read back to check it. If it cannot be kept (quota full),
//!   the store is *locked*: nothing is written over the original until the user has downloaded
//!   it or chosen to discard it. The notice stays until the user dismisses it.
//! - **Two tabs**: the store remembers the text it last read or wrote. Before each write it
//!   reads the key again; if another tab wrote since, an addition (save, import, save morph) is
//!   appended to the other tab's library, and an edit (rename, reorder, delete) is not applied:
//!   the other tab's library is shown instead, with a notice to do the edit again. Either way
//!   nothing the other tab saved is overwritten. (The page also reloads the library on the
//!   browser's `storage` event, so the window for this is small.)
//!
//! Why `localStorage` and not IndexedDB: a preset is a few KB (thumbnails are re-rendered), so
//! hundreds fit in the 5 MB quota; a single-key write is atomic; it is synchronous, so the
//! compare-before-write above needs no transaction. A full quota is reported and changes
//! nothing stored.
//!
//! Plain Rust behind [`KeyValue`], so that native tests cover every corruption.

use crate::presets::{Preset, STORAGE_KEY, library_json, read_library};

/// A string key-value store: the browser's `localStorage`, or a map in tests.
pub trait KeyValue {
    /// The value at `key`; an error when the store cannot be read.
    fn get(&self, key: &str) -> Result<Option<String>, String>;
    /// Writes `value` at `key`; an error when it was not written (full quota).
    fn set(&self, key: &str, value: &str) -> Result<(), String>;
}

/// A stored library that could not be read whole.
#[derive(Clone, Debug, PartialEq)]
pub struct Unreadable {
    /// The stored text, as it was.
    pub text: String,
    /// The backup key it is kept under; `None` when that write failed.
    pub backup_key: Option<String>,
    /// The user downloaded it (so it may be overwritten).
    pub downloaded: bool,
    /// The user chose to discard it.
    pub discarded: bool,
}

impl Unreadable {
    /// Whether the original may be written over: it is kept elsewhere, or the user chose.
    pub fn may_overwrite(&self) -> bool {
        self.backup_key.is_some() || self.downloaded || self.discarded
    }
}

/// What a save did.
#[derive(Debug, PartialEq)]
pub enum Saved {
    /// Written as given.
    Written,
    /// Another tab had written: the additions were appended to its library, which is now the
    /// list (returned).
    Merged(Vec<Preset>),
    /// Another tab had written and the change was an edit: nothing written; its library is now
    /// the list (returned).
    Reloaded(Vec<Preset>),
}

/// What a change to the list was.
#[derive(Debug)]
pub enum Change<'a> {
    /// These presets were added at the end.
    Added(&'a [Preset]),
    /// Presets were renamed, reordered or deleted.
    Edited,
}

/// The presets' place in a [`KeyValue`] store.
#[derive(Debug, Default)]
pub struct PresetStore {
    /// The stored text as this tab last read or wrote it (`None`: nothing was stored).
    synced: Option<String>,
    /// The library that could not be read, while the user has not dismissed its notice.
    pub unreadable: Option<Unreadable>,
    /// What to tell the user about the stored library: stays until dismissed.
    pub notice: Option<String>,
    /// Why the last save wrote nothing; cleared by the next save that writes.
    pub save_error: Option<String>,
}

impl PresetStore {
    /// Reads the library: the presets that could be read, and a store that remembers the rest.
    pub fn open(kv: &dyn KeyValue, now_ms: u64) -> (PresetStore, Vec<Preset>) {
        let mut store = PresetStore::default();
        let text = match kv.get(STORAGE_KEY) {
            Ok(Some(t)) => t,
            Ok(None) => return (store, Vec::new()),
            Err(e) => {
                store.notice = Some(format!(
                    "Presets: the browser's storage cannot be read ({e}); presets will not persist"
                ));
                store.unreadable = None;
                return (store, Vec::new());
            }
        };
        store.synced = Some(text.clone());
        let (list, problem) = match read_library(&text) {
            Ok((list, skipped)) if skipped.is_empty() => return (store, list),
            Ok((list, skipped)) => {
                let n = skipped.len();
                let shown: Vec<String> = skipped.iter().take(5).cloned().collect();
                let more = if n > 5 {
                    format!(" and {} more", n - 5)
                } else {
                    String::new()
                };
                (
                    list,
                    format!(
                        "{n} stored preset{} could not be read: {}{more}",
                        if n == 1 { "" } else { "s" },
                        shown.join("; ")
                    ),
                )
            }
            Err(e) => (
                Vec::new(),
                format!("The stored presets could not be read ({e})"),
            ),
        };
        let backup_key = format!("{STORAGE_KEY}.unreadable-{now_ms}");
        let kept = kv.set(&backup_key, &text).is_ok()
            && kv.get(&backup_key).ok().flatten().as_deref() == Some(text.as_str());
        store.notice = Some(if kept {
            format!(
                "{problem}. The library as it was is kept under the storage key {backup_key}; \
                 download it to repair it by hand."
            )
        } else {
            format!(
                "{problem}. It could not be copied aside (browser storage full), so nothing will \
                 be saved over it until you download it or discard it."
            )
        });
        store.unreadable = Some(Unreadable {
            text,
            backup_key: kept.then_some(backup_key),
            downloaded: false,
            discarded: false,
        });
        (store, list)
    }

    /// Whether saving is refused for now (see [`Unreadable::may_overwrite`]).
    pub fn locked(&self) -> bool {
        self.unreadable.as_ref().is_some_and(|u| !u.may_overwrite())
    }

    /// Writes `list`, which is the stored list after `change`. Errors say why nothing was
    /// written; the stored library is then unchanged.
    pub fn save(
        &mut self,
        kv: &dyn KeyValue,
        list: &[Preset],
        change: Change,
    ) -> Result<Saved, String> {
        let result = self.try_save(kv, list, change);
        self.save_error = result.as_ref().err().cloned();
        result
    }

    fn try_save(
        &mut self,
        kv: &dyn KeyValue,
        list: &[Preset],
        change: Change,
    ) -> Result<Saved, String> {
        if self.locked() {
            return Err(
                "Presets are not saved: the stored library could not be read or copied aside. \
                 Download it or discard it first (in the presets panel); your presets stay in \
                 this tab until then"
                    .into(),
            );
        }
        let current = kv
            .get(STORAGE_KEY)
            .map_err(|e| format!("Presets could not be saved: storage unreadable ({e})"))?;
        let elsewhere = current != self.synced;
        let (to_write, outcome) = match (elsewhere, change) {
            (false, _) => (list.to_vec(), Saved::Written),
            (true, change) => {
                let theirs = match current.as_deref().map(read_library) {
                    None => Vec::new(),
                    Some(Ok((l, _))) => l,
                    // The other tab stored something unreadable: treat it as a fresh read
                    // would, never writing over it unkept.
                    Some(Err(_)) => {
                        return Err("Presets were changed in another tab into something this \
                                    tab cannot read; reload the page"
                            .into());
                    }
                };
                match change {
                    Change::Added(new) => {
                        let mut merged = theirs;
                        merged.extend_from_slice(new);
                        (merged.clone(), Saved::Merged(merged))
                    }
                    Change::Edited => {
                        self.synced = current;
                        return Ok(Saved::Reloaded(theirs));
                    }
                }
            }
        };
        let text = library_json(&to_write);
        kv.set(STORAGE_KEY, &text).map_err(|_| {
            "Presets could not be saved (browser storage full or unavailable): the saved \
             presets are unchanged; use Export… to keep the current ones"
                .to_string()
        })?;
        self.synced = Some(text);
        Ok(outcome)
    }

    /// The library another tab stored, when it differs from what this tab last read or wrote.
    pub fn changed_elsewhere(&mut self, kv: &dyn KeyValue) -> Option<Vec<Preset>> {
        if self.locked() {
            return None;
        }
        let current = kv.get(STORAGE_KEY).ok()?;
        if current == self.synced {
            return None;
        }
        let list = match current.as_deref().map(read_library) {
            None => Vec::new(),
            Some(Ok((l, _))) => l,
            Some(Err(_)) => return None,
        };
        self.synced = current;
        Some(list)
    }

    /// The user downloaded the unreadable library: saving may go on.
    pub fn downloaded(&mut self) {
        if let Some(u) = &mut self.unreadable {
            u.downloaded = true;
        }
    }

    /// The user chose to discard the unreadable library (a backup, where one was made, stays).
    pub fn discard(&mut self) {
        if let Some(u) = &mut self.unreadable {
            u.discarded = true;
        }
        self.dismiss();
    }

    /// The user closed the notice (only allowed once saving is safe).
    pub fn dismiss(&mut self) {
        if !self.locked() {
            self.notice = None;
            self.unreadable = None;
        }
    }
}

#[cfg(test)]
mod tests;
