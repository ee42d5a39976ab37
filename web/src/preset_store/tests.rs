//! Every corruption we know of, against the store: nothing stored is ever lost.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::rc::Rc;
use std::sync::OnceLock;

use proctex::analyze::{Options, analyze_bytes};
use proctex::params::Params;

use super::*;

/// An in-memory `localStorage`: shared between "tabs", with a quota in bytes.
#[derive(Clone, Default)]
struct Memory {
    map: Rc<RefCell<BTreeMap<String, String>>>,
    quota: Rc<RefCell<usize>>,
}

impl Memory {
    fn with_quota(bytes: usize) -> Memory {
        let m = Memory::default();
        *m.quota.borrow_mut() = bytes;
        m
    }
    fn used(&self) -> usize {
        self.map
            .borrow()
            .iter()
            .map(|(k, v)| k.len() + v.len())
            .sum()
    }
    fn raw(&self, key: &str) -> Option<String> {
        self.map.borrow().get(key).cloned()
    }
    fn put(&self, key: &str, value: &str) {
        self.map.borrow_mut().insert(key.into(), value.into());
    }
}

impl KeyValue for Memory {
    fn get(&self, key: &str) -> Result<Option<String>, String> {
        Ok(self.raw(key))
    }
    fn set(&self, key: &str, value: &str) -> Result<(), String> {
        let quota = *self.quota.borrow();
        let old = self.raw(key).map(|v| key.len() + v.len()).unwrap_or(0);
        if quota > 0 && self.used() - old + key.len() + value.len() > quota {
            return Err("QuotaExceededError".into());
        }
        self.put(key, value);
        Ok(())
    }
}

fn params() -> Params {
    static P: OnceLock<Params> = OnceLock::new();
    P.get_or_init(|| {
        let path = format!(
            "{}/../www/samples/stk_blackrock_256.png",
            env!("CARGO_MANIFEST_DIR")
        );
        analyze_bytes(&std::fs::read(path).unwrap(), &Options::default())
            .unwrap()
            .params
    })
    .clone()
}

fn preset(name: &str) -> Preset {
    Preset {
        name: name.into(),
        params: params(),
        morph: None,
    }
}

fn names(list: &[Preset]) -> Vec<&str> {
    list.iter().map(|p| p.name.as_str()).collect()
}

/// The stored library's names.
fn stored(kv: &Memory) -> Vec<String> {
    read_library(&kv.raw(STORAGE_KEY).unwrap())
        .unwrap()
        .0
        .into_iter()
        .map(|p| p.name)
        .collect()
}

fn backups(kv: &Memory) -> Vec<String> {
    kv.map
        .borrow()
        .keys()
        .filter(|k| k.starts_with("proctex.presets.unreadable-"))
        .cloned()
        .collect()
}

#[test]
fn an_empty_store_opens_empty_and_saves() {
    let kv = Memory::default();
    let (mut store, list) = PresetStore::open(&kv, 1);
    assert!(list.is_empty() && store.notice.is_none());
    let list = vec![preset("a")];
    assert_eq!(
        store.save(&kv, &list, Change::Added(&list)),
        Ok(Saved::Written)
    );
    assert_eq!(stored(&kv), ["a"]);
}

#[test]
fn unreadable_libraries_are_kept_aside_and_saving_goes_on() {
    let good = library_json(&[preset("a"), preset("b")]);
    for bad in [
        good[..good.len() / 2].to_string(), // truncated
        good.replace("proctex-presets/1", "proctex-presets/7"), // another version
        "x".repeat(3_000_000),              // the repro
        good.replacen("\"format\"", "\"format\": 1, \"format\"", 1), // a key twice
    ] {
        let kv = Memory::default();
        kv.put(STORAGE_KEY, &bad);
        let (mut store, list) = PresetStore::open(&kv, 42);
        assert!(list.is_empty());
        let notice = store.notice.clone().unwrap();
        assert!(
            notice.contains("proctex.presets.unreadable-42"),
            "{notice:.200}"
        );
        assert!(notice.len() < 600, "{} bytes", notice.len());
        assert_eq!(
            kv.raw("proctex.presets.unreadable-42").as_deref(),
            Some(bad.as_str())
        );
        assert!(!store.locked());
        let list = vec![preset("new")];
        assert_eq!(
            store.save(&kv, &list, Change::Added(&list)),
            Ok(Saved::Written)
        );
        assert_eq!(stored(&kv), ["new"]);
        // The original is still there, untouched, after the save.
        assert_eq!(
            kv.raw("proctex.presets.unreadable-42").as_deref(),
            Some(bad.as_str())
        );
        assert_eq!(store.unreadable.as_ref().unwrap().text, bad);
    }
}

#[test]
fn one_bad_preset_costs_only_itself_and_is_named() {
    let good = library_json(&[preset("keep me"), preset("broken one"), preset("me too")]);
    let doc: serde_json::Value = serde_json::from_str(&good).unwrap();
    let mut doc = doc;
    doc["presets"][1]["params"]["transform"]["scale"] = (-1.0).into();
    let text = doc.to_string();
    let kv = Memory::default();
    kv.put(STORAGE_KEY, &text);
    let (store, list) = PresetStore::open(&kv, 7);
    assert_eq!(names(&list), ["keep me", "me too"]);
    let notice = store.notice.unwrap();
    assert!(
        notice.contains("1 stored preset could not be read") && notice.contains("broken one"),
        "{notice}"
    );
    assert_eq!(backups(&kv).len(), 1);
}

#[test]
fn a_full_quota_locks_the_original_until_it_is_downloaded() {
    let good = library_json(&[preset("a")]);
    let bad = good[..good.len() - 10].to_string();
    // Room for the original but not for a second copy.
    let kv = Memory::with_quota(bad.len() + STORAGE_KEY.len() + 100);
    kv.put(STORAGE_KEY, &bad);
    let (mut store, _) = PresetStore::open(&kv, 5);
    assert!(backups(&kv).is_empty());
    assert!(store.locked());
    assert!(
        store
            .notice
            .as_ref()
            .unwrap()
            .contains("download it or discard it")
    );
    let list = vec![preset("x")];
    let e = store.save(&kv, &list, Change::Added(&list)).unwrap_err();
    assert!(e.contains("Download it or discard it"), "{e}");
    assert_eq!(store.save_error.as_deref(), Some(e.as_str()));
    assert_eq!(kv.raw(STORAGE_KEY).as_deref(), Some(bad.as_str()));
    // Dismissing does not unlock it; downloading does.
    store.dismiss();
    assert!(store.notice.is_some() && store.locked());
    store.downloaded();
    assert!(!store.locked());
    *kv.quota.borrow_mut() = 0;
    assert_eq!(
        store.save(&kv, &list, Change::Added(&list)),
        Ok(Saved::Written)
    );
    // Or discarding, explicitly.
    let kv = Memory::with_quota(bad.len() + STORAGE_KEY.len() + 100);
    kv.put(STORAGE_KEY, &bad);
    let (mut store, _) = PresetStore::open(&kv, 5);
    store.discard();
    assert!(!store.locked() && store.notice.is_none());
}

#[test]
fn a_full_quota_on_save_changes_nothing_stored() {
    let kv = Memory::default();
    let (mut store, _) = PresetStore::open(&kv, 1);
    let one = vec![preset("a")];
    store.save(&kv, &one, Change::Added(&one)).unwrap();
    *kv.quota.borrow_mut() = kv.used() + 10;
    let two = vec![preset("a"), preset("b")];
    let e = store.save(&kv, &two, Change::Added(&two[1..])).unwrap_err();
    assert!(e.contains("storage full"), "{e}");
    assert_eq!(stored(&kv), ["a"]);
}

#[test]
fn two_tabs_never_lose_a_save() {
    let kv = Memory::default();
    let start = vec![preset("shared")];
    kv.put(STORAGE_KEY, &library_json(&start));
    let (mut a, mut list_a) = PresetStore::open(&kv, 1);
    let (mut b, mut list_b) = PresetStore::open(&kv, 1);
    // Tab A saves "from a"; tab B, not yet told, saves "from b": both are kept.
    list_a.push(preset("from a"));
    assert_eq!(
        a.save(&kv, &list_a, Change::Added(&list_a[1..])),
        Ok(Saved::Written)
    );
    list_b.push(preset("from b"));
    match b.save(&kv, &list_b, Change::Added(&list_b[1..])).unwrap() {
        Saved::Merged(l) => list_b = l,
        other => panic!("{other:?}"),
    }
    assert_eq!(stored(&kv), ["shared", "from a", "from b"]);
    assert_eq!(names(&list_b), ["shared", "from a", "from b"]);
    // Tab A renames without having seen B's save: the edit is not written over it.
    list_a[0].name = "renamed".into();
    match a.save(&kv, &list_a, Change::Edited).unwrap() {
        Saved::Reloaded(l) => list_a = l,
        other => panic!("{other:?}"),
    }
    assert_eq!(stored(&kv), ["shared", "from a", "from b"]);
    assert_eq!(names(&list_a), ["shared", "from a", "from b"]);
    // Now in step, A's edit goes through, and B hears of it.
    list_a[0].name = "renamed".into();
    assert_eq!(a.save(&kv, &list_a, Change::Edited), Ok(Saved::Written));
    assert_eq!(names(&b.changed_elsewhere(&kv).unwrap())[0], "renamed");
    assert!(b.changed_elsewhere(&kv).is_none());
}
