//! The `proctex` binary within its limits: unbounded inputs and outputs end in a clear error
//! with the limit and the way past it, without taking the memory first; bad values in options
//! and documents are refused, and no error repeats more than a short quote of them.

use std::process::{Command, Output};

fn proctex(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_proctex"))
        .args(args)
        .output()
        .expect("runs")
}

/// Runs `proctex` with its address space capped at `mib` MiB (`ulimit -v`): an allocation past
/// the cap aborts the process, so an exit code of 1 with a message proves the command stayed
/// within it.
fn proctex_within(mib: u64, args: &[&str]) -> Output {
    let line = format!("ulimit -v {} && exec \"$0\" \"$@\"", mib * 1024);
    Command::new("sh")
        .arg("-c")
        .arg(line)
        .arg(env!("CARGO_BIN_EXE_proctex"))
        .args(args)
        .output()
        .expect("runs")
}

fn sample(name: &str) -> String {
    format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("proctex-cli-limits-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_string_lossy().into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A params file of the shipped rock sample (the noise model: quick).
fn params_file() -> String {
    let path = tmp("rock.json");
    if !std::path::Path::new(&path).exists() {
        let o = proctex(&[
            "analyze",
            &sample("stk_blackrock_256.png"),
            "--model",
            "noise",
            "-o",
            &path,
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    path
}

/// A PNG whose header declares `w × h` and whose one IDAT chunk is a few bytes: what a hostile
/// 1 MB file of a 20000² black image looks like to a decoder before it inflates anything.
fn declared_png(w: u32, h: u32) -> Vec<u8> {
    fn chunk(out: &mut Vec<u8>, kind: &[u8], data: &[u8]) {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        out.extend_from_slice(kind);
        out.extend_from_slice(data);
        out.extend_from_slice(&[0; 4]); // CRC: never reached
    }
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    chunk(&mut out, b"IHDR", &ihdr);
    chunk(&mut out, b"IDAT", &[0x78, 0x9c, 0x03, 0x00]);
    chunk(&mut out, b"IEND", &[]);
    out
}

#[test]
fn an_endless_file_is_refused_within_a_gigabyte() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    let o = proctex_within(1024, &["analyze", "/dev/zero"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("/dev/zero") && e.contains("256 MiB"), "{e}");
}

#[test]
fn oversized_photos_are_refused_from_their_header() {
    let big = tmp("declared_20000.png");
    std::fs::write(&big, declared_png(20000, 20000)).unwrap();
    let o = proctex_within(1024, &["analyze", &big]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("declared_20000.png") && e.contains("16384"),
        "{e}"
    );

    // Within the sides but over the pixel count: the limit and the way past it.
    let wide = tmp("declared_9000.png");
    std::fs::write(&wide, declared_png(9000, 9000)).unwrap();
    let e = stderr(&proctex_within(1024, &["analyze", &wide]));
    assert!(e.contains("50.0 MP") && e.contains("--max-pixels"), "{e}");
    // Past it with --max-pixels, the (bogus) pixel data is what fails.
    let e = stderr(&proctex(&["analyze", &wide, "--max-pixels", "90000000"]));
    assert!(!e.contains("MP") && e.contains("declared_9000.png"), "{e}");
    // --max-pixels lowers the limit too, for every command.
    let e = stderr(&proctex(&[
        "--max-pixels",
        "1000",
        "analyze",
        &sample("stk_blackrock_256.png"),
    ]));
    assert!(e.contains("over the limit of 1000 pixels"), "{e}");
}

#[test]
fn renders_past_the_limit_are_refused_before_their_buffer_exists() {
    let params = params_file();
    let out = tmp("big.png");
    for args in [
        vec!["render", &params, "--size", "16384", "-o", &out],
        vec![
            "render", &params, "--width", "9000", "--height", "9000", "-o", &out,
        ],
    ] {
        let o = proctex_within(1024, &args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let e = stderr(&o);
        assert!(e.contains("67.1 MP") && e.contains("--max-pixels"), "{e}");
    }
    // A params file whose source is 16384² asks for that size by default.
    let text = std::fs::read_to_string(&params).unwrap();
    let mut doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc["source"]["width"] = 16384.into();
    doc["source"]["height"] = 16384.into();
    doc["source"]["crop"] = serde_json::Value::Null;
    let huge = tmp("huge_source.json");
    std::fs::write(&huge, doc.to_string()).unwrap();
    let e = stderr(&proctex_within(1024, &["render", &huge, "-o", &out]));
    assert!(
        e.contains("16384×16384") && e.contains("--max-pixels"),
        "{e}"
    );
    // The limit is one number: a small one refuses a small render.
    let o = proctex(&[
        "render",
        &params,
        "--size",
        "11",
        "-o",
        &out,
        "--max-pixels",
        "100",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let o = proctex(&[
        "render",
        &params,
        "--size",
        "10",
        "-o",
        &out,
        "--max-pixels",
        "100",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn numbers_that_are_not_finite_are_usage_errors() {
    let params = params_file();
    let out = tmp("nan.png");
    for (flag, value) in [
        ("--origin", "nan,0"),
        ("--origin", "0,inf"),
        ("--solid-z", "NaN"),
        ("--solid-z", "-inf"),
        ("--pixel-size", "1e999"),
    ] {
        let o = proctex(&["render", &params, "--size", "16", flag, value, "-o", &out]);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}");
        let e = stderr(&o);
        assert!(e.contains(flag) && e.contains("finite"), "{e}");
    }
    let o = proctex(&["morph", &params, &params, "--t", "nan", "-o", &out]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    for value in ["nan", "0", "-5"] {
        let o = proctex(&["--max-pixels", value, "help"]);
        assert_eq!(o.status.code(), Some(2), "--max-pixels {value}");
    }
}

#[test]
fn errors_quote_at_most_a_short_part_of_a_bad_value() {
    let long = "9".repeat(100_000);
    let o = proctex(&["analyze", "x.png", "--seed", &long]);
    assert_eq!(o.status.code(), Some(2));
    assert!(o.stderr.len() < 300, "{} bytes", o.stderr.len());
    let o = proctex(&[&long]);
    assert!(o.stderr.len() < 300, "{} bytes", o.stderr.len());
    // A document with a huge string where a number belongs.
    let text = std::fs::read_to_string(params_file()).unwrap();
    let mut doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    doc["seed"] = "7".repeat(2_000_000).into();
    let bad = tmp("huge_seed.json");
    std::fs::write(&bad, doc.to_string()).unwrap();
    let o = proctex(&["render", &bad, "-o", &tmp("x.png")]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.len() < 400 && e.contains("seed"),
        "{} bytes: {e:.300}",
        e.len()
    );
}

#[test]
fn documents_are_strict_about_keys_and_lenient_about_a_bom() {
    let text = std::fs::read_to_string(params_file()).unwrap();
    let out = tmp("doc.png");
    let dup = tmp("duplicate_format.json");
    let doubled = text.replacen("\"format\"", "\"format\": \"proctex/9\", \"format\"", 1);
    std::fs::write(&dup, &doubled).unwrap();
    let o = proctex(&["render", &dup, "--size", "16", "-o", &out]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("\"format\" appears twice"),
        "{}",
        stderr(&o)
    );

    let bom = tmp("bom.json");
    std::fs::write(&bom, format!("\u{feff}{text}")).unwrap();
    let o = proctex(&["render", &bom, "--size", "16", "-o", &out]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn decode_errors_name_the_file() {
    let junk = tmp("not_an_image.png");
    std::fs::write(&junk, b"\x89PNG\r\n\x1a\ngarbage").unwrap();
    for args in [
        vec!["analyze", junk.as_str()],
        vec!["synth", junk.as_str(), "-o", "y.png"],
        vec!["evaluate", junk.as_str(), junk.as_str()],
    ] {
        let o = proctex(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        assert!(
            stderr(&o).contains("not_an_image.png"),
            "{args:?}: {}",
            stderr(&o)
        );
    }
    let o = proctex(&["analyze", &std::env::temp_dir().to_string_lossy()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("folder"), "{}", stderr(&o));
}
