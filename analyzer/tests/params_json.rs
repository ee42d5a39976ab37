//! Params JSON: export → import is lossless; hostile documents give a clear error naming the
//! bad field.

mod common;

use common::{SAMPLES, sample_bytes};
use proctex::Error;
use proctex::analyze::{Options, analyze_bytes};
use proctex::params::Params;

fn analysed(name: &str) -> Params {
    analyze_bytes(&sample_bytes(name), &Options::default())
        .unwrap()
        .params
}

#[test]
fn export_import_is_lossless() {
    for name in SAMPLES {
        for hist in [true, false] {
            let p = analyze_bytes(
                &sample_bytes(name),
                &Options {
                    histogram: hist,
                    ..Options::default()
                },
            )
            .unwrap()
            .params;
            let text = p.to_json();
            let back = Params::from_json(&text).unwrap();
            assert_eq!(back, p, "{name}");
            // Bit-exact floats, and a second trip gives the same text.
            assert_eq!(back.to_json(), text);
        }
    }
}

/// Replaces the JSON value at `path` (a JSON pointer) in the document of `p`.
fn with(p: &Params, pointer: &str, value: serde_json::Value) -> String {
    let mut v: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
    *v.pointer_mut(pointer)
        .unwrap_or_else(|| panic!("no {pointer}")) = value;
    v.to_string()
}

fn field_of(text: &str) -> (String, String) {
    match Params::from_json(text) {
        Err(Error::Params { field, message }) => (field, message),
        Err(other) => panic!("wrong error kind: {other}"),
        Ok(_) => panic!("accepted a hostile document: {text}"),
    }
}

#[test]
fn hostile_documents_name_the_bad_field() {
    let p = analysed("stk_rock_mountain_512.png");
    use serde_json::json;
    let cases: Vec<(String, &str)> = vec![
        // 1e308 becomes infinity as f32: must be caught as not finite.
        (with(&p, "/colour/mean/1", json!(1e308)), "colour.mean[1]"),
        (
            with(&p, "/model/weights/0/3", json!(1e308)),
            "model.weights[0][3]",
        ),
        (
            with(&p, "/model/weights/2/0", json!(-0.5)),
            "model.weights[2][0]",
        ),
        (with(&p, "/transform/scale", json!(0.0)), "transform.scale"),
        (
            with(&p, "/transform/rotation_deg", json!(-1e308)),
            "transform.rotation_deg",
        ),
        (
            with(&p, "/model/weights/1", json!([0.1, 0.2])),
            "model.weights[1]",
        ),
        (with(&p, "/model/weights/0", json!([])), "model.weights[0]"),
        (
            with(&p, "/model/weights/0", json!(vec![0.1; 13])),
            "model.weights[0]",
        ),
        (
            with(&p, "/model/histogram/knots/1", json!([0.3, 0.2, 0.1])),
            "model.histogram.knots[1]",
        ),
        (
            with(&p, "/model/histogram/knots/2", json!([0.3])),
            "model.histogram.knots[2]",
        ),
        (with(&p, "/colour/mean", json!([0.1, 0.2])), "colour.mean"),
        (
            with(&p, "/colour/basis/0", json!([1.0, 0.0, 0.0])),
            "colour.basis",
        ),
        (
            with(&p, "/colour/basis/2/0", json!("x")),
            "colour.basis[2][0]",
        ),
        (with(&p, "/seed", json!(-1)), "seed"),
        (with(&p, "/seed", json!(1e10)), "seed"),
        (with(&p, "/format", json!("proctex/2")), "format"),
        (with(&p, "/model/kind", json!("bricks")), "model"),
        (with(&p, "/solid", json!("yes")), "solid"),
    ];
    for (doc, want) in &cases {
        let (field, message) = field_of(doc);
        assert!(
            field.starts_with(want),
            "expected an error at `{want}`, got `{field}`: {message}"
        );
        assert!(!message.is_empty());
    }
    // A reflection (det −1) instead of a rotation.
    let mut q = p.clone();
    q.colour.basis[2] = q.colour.basis[2].map(|v| -v);
    let (field, message) = field_of(&q.to_json());
    assert_eq!(field, "colour.basis");
    assert!(message.contains("determinant"), "{message}");
}

#[test]
fn non_json_and_nan_are_clear_errors() {
    for text in [
        "",
        "not json",
        "{\"format\": \"proctex/1\", \"seed\": NaN}",
        "{\"format\": \"proctex/1\", \"seed\": Infinity}",
        "[1, 2, 3]",
        "{}",
        "{\"format\": 1}",
    ] {
        let err = Params::from_json(text).expect_err(text);
        let msg = err.to_string();
        assert!(msg.starts_with("bad params at `"), "{msg}");
    }
    let missing = r#"{"format": "proctex/1", "seed": 1}"#;
    let msg = Params::from_json(missing).unwrap_err().to_string();
    assert!(msg.contains("missing field"), "{msg}");
}

#[test]
fn unknown_fields_are_rejected() {
    let p = analysed("skimage_grass_512.png");
    let mut v: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
    v["transform"]["scael"] = serde_json::json!(2.0);
    let (field, message) = field_of(&v.to_string());
    assert!(field.starts_with("transform"), "{field}");
    assert!(message.contains("scael"), "{message}");
}

/// Presets saved before a family's ranges were narrowed (`pattern`'s module docs) still load,
/// with their structural values clamped into today's ranges; unknown names still fail.
#[test]
fn structured_values_out_of_range_are_clamped_on_import() {
    use proctex::params::pattern_shell as shell;
    use proctex::pattern::{Pattern, PatternKind};
    use serde_json::json;
    let p = shell(Pattern::new(PatternKind::Brick, 20.0), 1, false);
    let doc = |key: &str, v: serde_json::Value| {
        let mut d: serde_json::Value = serde_json::from_str(&p.to_json()).unwrap();
        d.pointer_mut("/model/pattern/values")
            .unwrap()
            .as_object_mut()
            .unwrap()
            .insert(key.to_string(), v);
        d
    };
    let mut old = doc("row_offset", json!(0.0));
    *old.pointer_mut("/model/pattern/values/jitter").unwrap() = json!(0.9);
    let back = Params::from_json(&old.to_string()).unwrap();
    let pat = back.model.pattern().unwrap();
    assert_eq!(pat.get("row_offset"), Some(0.25));
    assert_eq!(pat.get("jitter"), Some(0.25));
    assert!(back.validate().is_ok());
    let (field, _) = field_of(&doc("wobble", json!(0.5)).to_string());
    assert_eq!(field, "model.pattern.values.wobble");
}

/// A structured preset's output tone curve: absent (presets from before it) loads as none, a
/// present one survives the round trip, and bad knots or ranges name their field.
#[test]
fn tone_curves_load_round_trip_and_name_bad_fields() {
    use proctex::params::pattern_shell as shell;
    use proctex::params::{Model, Tone};
    use proctex::pattern::{Pattern, PatternKind};
    use serde_json::json;
    let mut p = shell(Pattern::new(PatternKind::Cells, 20.0), 1, false);
    let old = p.to_json();
    assert!(!old.contains("tone"), "no curve, no field");
    assert_eq!(Params::from_json(&old).unwrap(), p);
    if let Model::Structured(m) = &mut p.model {
        m.tone = Some(Tone::identity(5));
    }
    let text = p.to_json();
    assert_eq!(Params::from_json(&text).unwrap(), p);
    let cases = [
        (
            "/model/tone/knots/1",
            json!([0.0, 0.5, 0.4, 0.8, 1.0]),
            "model.tone.knots[1]",
        ),
        (
            "/model/tone/knots/2",
            json!([0.0, 1.0]),
            "model.tone.knots[2]",
        ),
        (
            "/model/tone/knots/0/3",
            json!(1e308),
            "model.tone.knots[0][3]",
        ),
        (
            "/model/tone/range/1",
            json!([0.5, 0.5]),
            "model.tone.range[1]",
        ),
        (
            "/model/tone/range/0/0",
            json!(-9.0),
            "model.tone.range[0][0]",
        ),
    ];
    for (pointer, value, want) in cases {
        let (field, message) = field_of(&with(&p, pointer, value));
        assert!(
            field.starts_with(want),
            "expected `{want}`, got `{field}`: {message}"
        );
    }
}
