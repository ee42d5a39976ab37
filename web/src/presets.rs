//! Presets: named params sets the user keeps, and the library file they travel in.
//!
//! Storage is the browser's `localStorage`, one key holding the whole library as JSON
//! (`proctex-presets/1`). Why not IndexedDB: a preset is a few KB of JSON (thumbnails are
//! re-rendered from the params, not stored), so hundreds fit in the 5 MB quota, and a
//! synchronous single-key write is atomic: either the new library is stored or the old one stays.
//! A full quota makes the write fail; the app says so, keeps the presets in memory and suggests
//! exporting them — nothing stored is lost. Import parses and validates the whole file first
//! and only then adds its presets, so a corrupt file changes nothing.
//!
//! Plain Rust (no browser types) so that native tests cover it.

use proctex::limits::quote;
use proctex::params::Params;
use serde::{Deserialize, Serialize};

/// The library format tag.
pub const LIBRARY_FORMAT: &str = "proctex-presets/1";
/// The `localStorage` key of the library.
pub const STORAGE_KEY: &str = "proctex.presets";

/// A saved texture.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Preset {
    /// Shown in the list; not necessarily unique.
    pub name: String,
    /// The texture.
    pub params: Params,
    /// For a saved morph: the presets' params in order (this preset's `params` is the first)
    /// and the animation's duration in seconds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub morph: Option<MorphPreset>,
}

/// A saved morph.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MorphPreset {
    /// Key textures, two or more.
    pub keys: Vec<Params>,
    /// Seconds for t to go from 0 to 1 when playing.
    pub duration_s: f32,
}

#[derive(Serialize)]
struct LibraryOut<'a> {
    format: &'static str,
    presets: &'a [Preset],
}

/// The library as JSON.
pub fn library_json(presets: &[Preset]) -> String {
    serde_json::to_string_pretty(&LibraryOut {
        format: LIBRARY_FORMAT,
        presets,
    })
    .expect("presets serialise")
}

/// Parses and validates a library file as a whole (Import): the first bad preset fails it, and
/// the error names the preset and the field.
pub fn parse_library(text: &str) -> Result<Vec<Preset>, String> {
    let items = match library_items(text)? {
        Items::Single(p) => return Ok(vec![*p]),
        Items::List(items) => items,
    };
    items
        .iter()
        .enumerate()
        .map(|(i, item)| parse_preset(i, item))
        .collect()
}

/// Reads a stored library preset by preset: the presets that parse, and for each one that does
/// not, what is wrong with it (`presets[i] (name): …`). An error only when the library as a
/// whole is unreadable (not JSON, another format, no list).
pub fn read_library(text: &str) -> Result<(Vec<Preset>, Vec<String>), String> {
    let items = match library_items(text)? {
        Items::Single(p) => return Ok((vec![*p], Vec::new())),
        Items::List(items) => items,
    };
    let (mut good, mut bad) = (Vec::new(), Vec::new());
    for (i, item) in items.iter().enumerate() {
        match parse_preset(i, item) {
            Ok(p) => good.push(p),
            Err(e) => bad.push(e),
        }
    }
    Ok((good, bad))
}

enum Items {
    /// A bare params document: one preset.
    Single(Box<Preset>),
    /// A library's `presets` list, unparsed.
    List(Vec<serde_json::Value>),
}

fn library_items(text: &str) -> Result<Items, String> {
    let value =
        proctex::json::parse(text).map_err(|e| format!("not a presets file: not JSON ({e})"))?;
    match value.get("format").and_then(|f| f.as_str()) {
        Some(LIBRARY_FORMAT) => {}
        // A single params document is welcome too: it becomes one preset.
        Some(proctex::params::FORMAT) => {
            let p = Params::from_json(text).map_err(|e| e.to_string())?;
            return Ok(Items::Single(Box::new(Preset {
                name: "imported".into(),
                params: p,
                morph: None,
            })));
        }
        Some(f) => {
            return Err(format!(
                "unsupported presets format `{}`; this version reads `{LIBRARY_FORMAT}`",
                quote(f)
            ));
        }
        None => {
            return Err(format!(
                "not a presets file: missing \"format\": \"{LIBRARY_FORMAT}\""
            ));
        }
    }
    match value {
        serde_json::Value::Object(mut m) => match m.remove("presets") {
            Some(serde_json::Value::Array(items)) => Ok(Items::List(items)),
            _ => Err("presets file: `presets` must be a list".into()),
        },
        _ => Err("presets file: `presets` must be a list".into()),
    }
}

/// The `i`-th item of a library's list as a preset; the error names it.
fn parse_preset(i: usize, item: &serde_json::Value) -> Result<Preset, String> {
    let params_of = |v: &serde_json::Value, at: &str| -> Result<Params, String> {
        Params::from_json(&v.to_string()).map_err(|e| format!("{at}: {e}"))
    };
    let name = item
        .get("name")
        .and_then(|n| n.as_str())
        .ok_or(format!("presets[{i}]: `name` must be a string"))?
        .to_string();
    let at = format!("presets[{i}] ({})", quote(&name));
    let params = params_of(
        item.get("params")
            .ok_or(format!("{at}: `params` is missing"))?,
        &at,
    )?;
    let morph = match item.get("morph") {
        None | Some(serde_json::Value::Null) => None,
        Some(m) => {
            let keys = m
                .get("keys")
                .and_then(|k| k.as_array())
                .ok_or(format!("{at}: morph.keys must be a list"))?
                .iter()
                .enumerate()
                .map(|(k, v)| params_of(v, &format!("{at}.morph.keys[{k}]")))
                .collect::<Result<Vec<_>, _>>()?;
            if keys.len() < 2 {
                return Err(format!("{at}: a morph needs two or more keys"));
            }
            let duration_s = m
                .get("duration_s")
                .and_then(|d| d.as_f64())
                .filter(|d| d.is_finite() && *d > 0.0 && *d <= 3600.0)
                .ok_or(format!(
                    "{at}: morph.duration_s must be in (0, 3600] seconds"
                ))? as f32;
            Some(MorphPreset { keys, duration_s })
        }
    };
    Ok(Preset {
        name,
        params,
        morph,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proctex::analyze::{Options, analyze_bytes};

    fn params(name: &str) -> Params {
        let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
        analyze_bytes(&std::fs::read(path).unwrap(), &Options::default())
            .unwrap()
            .params
    }

    #[test]
    fn library_round_trip_is_lossless() {
        let rock = params("stk_rock_mountain_512.png");
        let grass = params("skimage_grass_512.png");
        let lib = vec![
            Preset {
                name: "rock".into(),
                params: rock.clone(),
                morph: None,
            },
            Preset {
                name: "rock → grass".into(),
                params: rock.clone(),
                morph: Some(MorphPreset {
                    keys: vec![rock, grass],
                    duration_s: 4.0,
                }),
            },
        ];
        assert_eq!(parse_library(&library_json(&lib)).unwrap(), lib);
    }

    #[test]
    fn corrupt_libraries_are_refused_with_the_reason() {
        let rock = params("stk_rock_mountain_512.png");
        let good = library_json(&[Preset {
            name: "rock".into(),
            params: rock.clone(),
            morph: None,
        }]);
        for (bad, want) in [
            ("{", "not JSON"),
            ("[]", "missing"),
            (
                r#"{"format": "proctex-presets/9", "presets": []}"#,
                "unsupported",
            ),
            (r#"{"format": "proctex-presets/1"}"#, "must be a list"),
            (&good.replace("\"rock\"", "7"), "name"),
            (
                &good.replacen("\"scale\": 1.0", "\"scale\": -1.0", 1),
                "transform.scale",
            ),
        ] {
            let e = parse_library(bad).unwrap_err();
            assert!(e.contains(want), "{bad:.60}: {e}");
        }
        // A bare params document imports as one preset.
        assert_eq!(parse_library(&rock.to_json()).unwrap()[0].params, rock);
    }
}
