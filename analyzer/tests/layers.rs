//! The analyzer's layers: `src/lib.rs` declares its modules in layers (a `// Layer:` comment
//! starts each), lowest first. This test reads those declarations and every module's source
//! (its file and its folder, without its `#[cfg(test)]` tests, inline or in a `tests.rs`), collects the `crate::<module>`
//! paths each one uses, and checks that
//! - every module uses only modules of its own layer or of lower ones, and
//! - no module reaches itself through the others (no import cycle, inside a layer either).
//!
//! It reads the source as text: a `crate::x` in code counts, one in a comment does not.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The modules of `lib.rs` with their layer (0: the lowest).
fn layers(src: &Path) -> BTreeMap<String, usize> {
    let lib = std::fs::read_to_string(src.join("lib.rs")).expect("lib.rs is readable");
    let mut layer = None;
    let mut out = BTreeMap::new();
    for line in lib.lines() {
        if line.starts_with("// Layer:") {
            layer = Some(layer.map_or(0, |l| l + 1));
        } else if let Some(name) = line
            .strip_prefix("pub mod ")
            .and_then(|r| r.strip_suffix(';'))
        {
            let l = layer.unwrap_or_else(|| panic!("`pub mod {name}` comes before any layer"));
            out.insert(name.to_string(), l);
        }
    }
    out
}

/// The `.rs` files of module `name`: `src/name.rs` and everything under `src/name/` but its
/// unit tests (`tests.rs`).
fn files_of(src: &Path, name: &str) -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "rs")
                && p.file_name().is_some_and(|n| n != "tests.rs")
            {
                out.push(p);
            }
        }
    }
    let mut out = vec![src.join(format!("{name}.rs"))];
    walk(&src.join(name), &mut out);
    out.retain(|p| p.exists());
    out.sort();
    out
}

/// The modules that `code` names as `crate::<module>`, outside comments and unit tests.
fn used_modules(code: &str) -> BTreeSet<String> {
    let code = match code.find("\n#[cfg(test)]\nmod tests") {
        Some(i) => &code[..i],
        None => code,
    };
    let mut out = BTreeSet::new();
    for line in code.lines() {
        let line = line.split("//").next().unwrap_or("");
        let mut rest = line;
        while let Some(i) = rest.find("crate::") {
            let after = &rest[i + "crate::".len()..];
            let name: String = after
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.insert(name);
            }
            rest = after;
        }
    }
    out
}

/// Module → the other modules it uses.
fn graph(src: &Path, modules: &BTreeMap<String, usize>) -> BTreeMap<String, BTreeSet<String>> {
    modules
        .keys()
        .map(|m| {
            let files = files_of(src, m);
            assert!(!files.is_empty(), "module `{m}` has no source file");
            let mut uses = BTreeSet::new();
            for f in files {
                let code = std::fs::read_to_string(&f).expect("source is readable");
                uses.extend(used_modules(&code));
            }
            // Items of the crate root (`crate::Error`, `crate::Result`) are not modules.
            uses.retain(|u| u != m && modules.contains_key(u));
            (m.clone(), uses)
        })
        .collect()
}

/// One cycle of `g` as a path `a → b → … → a`, if there is one.
fn find_cycle(g: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        g: &BTreeMap<String, BTreeSet<String>>,
        v: &str,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(v.to_string(), 1);
        path.push(v.to_string());
        for w in &g[v] {
            match state.get(w.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = path.iter().position(|p| p == w).expect("w is on the path");
                    let mut cycle = path[start..].to_vec();
                    cycle.push(w.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(g, w, state, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        state.insert(v.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for v in g.keys() {
        if !state.contains_key(v)
            && let Some(c) = visit(g, v, &mut state, &mut Vec::new())
        {
            return Some(c);
        }
    }
    None
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

#[test]
fn modules_use_only_their_own_layer_and_the_ones_below() {
    let src = src_dir();
    let modules = layers(&src);
    assert!(
        modules.len() >= 20,
        "lib.rs lists {} modules",
        modules.len()
    );
    let g = graph(&src, &modules);
    let mut upward = Vec::new();
    for (m, uses) in &g {
        for u in uses {
            if modules[u] > modules[m] {
                upward.push(format!(
                    "{m} (layer {}) uses {u} (layer {})",
                    modules[m], modules[u]
                ));
            }
        }
    }
    assert!(
        upward.is_empty(),
        "uses of higher layers:\n{}",
        upward.join("\n")
    );
}

#[test]
fn no_module_reaches_itself_through_the_others() {
    let src = src_dir();
    let g = graph(&src, &layers(&src));
    if let Some(cycle) = find_cycle(&g) {
        panic!("import cycle: {}", cycle.join(" → "));
    }
}

#[test]
fn the_checker_sees_uses_in_code_and_ignores_comments_and_tests() {
    let code = "use crate::db::Db; // crate::retrieve in a comment\n\
                fn f() { crate::render::render(); }\n\
                /// crate::morph in a doc comment\n\
                \n#[cfg(test)]\nmod tests {\n    use crate::evaluate::fidelity;\n}\n";
    let used: Vec<String> = used_modules(code).into_iter().collect();
    assert_eq!(used, ["db", "render"]);
    // A cycle through three modules is found, and a chain is not taken for one.
    let edges = |pairs: &[(&str, &str)]| {
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in pairs {
            g.entry(a.to_string()).or_default().insert(b.to_string());
            g.entry(b.to_string()).or_default();
        }
        g
    };
    let cycle = find_cycle(&edges(&[("a", "b"), ("b", "c"), ("c", "a")])).expect("a cycle");
    assert_eq!(cycle.first(), cycle.last());
    assert_eq!(cycle.len(), 4);
    assert!(find_cycle(&edges(&[("a", "b"), ("b", "c"), ("a", "c")])).is_none());
}
