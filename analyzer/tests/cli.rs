//! The `proctex` binary: usage, outputs and exit codes.

use std::process::{Command, Output};

fn proctex(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_proctex"))
        .args(args)
        .output()
        .expect("runs")
}

fn sample(name: &str) -> String {
    format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn bad(name: &str) -> String {
    format!("{}/tests/bad/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn tmp(name: &str) -> String {
    let dir = std::env::temp_dir().join(format!("proctex-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_string_lossy().into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn help_everywhere() {
    for args in [
        vec!["help"],
        vec!["--help"],
        vec!["analyze", "--help"],
        vec!["render", "--help"],
        vec!["synth", "--help"],
        vec!["pyramid", "--help"],
        vec!["evaluate", "--help"],
        vec!["fidelity", "--help"],
        vec!["morph", "--help"],
        vec!["export", "--help"],
    ] {
        let o = proctex(&args);
        assert!(o.status.success(), "{args:?}");
        assert!(
            String::from_utf8_lossy(&o.stdout).contains("proctex"),
            "{args:?}"
        );
    }
    let o = proctex(&[]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn analyze_render_synth_evaluate() {
    let params = tmp("rock.json");
    let o = proctex(&[
        "analyze",
        &sample("stk_rock_mountain_512.png"),
        "-o",
        &params,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&params).unwrap();
    assert!(text.contains(r#""format": "proctex/1""#));

    // --json prints exactly the params document.
    let o = proctex(&["analyze", &sample("stk_rock_mountain_512.png"), "--json"]);
    assert!(o.status.success());
    let printed = proctex::params::Params::from_json(&String::from_utf8_lossy(&o.stdout)).unwrap();
    assert_eq!(printed, proctex::params::Params::from_json(&text).unwrap());

    let png = tmp("rock.png");
    let o = proctex(&[
        "render", &params, "-o", &png, "--width", "200", "--height", "120",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = image::open(&png).unwrap();
    assert_eq!((img.width(), img.height()), (200, 120));

    let slice = tmp("slice.png");
    let o = proctex(&[
        "render",
        &params,
        "-o",
        &slice,
        "--size",
        "64",
        "--solid-z",
        "3.5",
        "--depth",
        "16",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        image::open(&slice).unwrap().color(),
        image::ColorType::Rgb16
    );

    let syn = tmp("syn.png");
    let o = proctex(&[
        "synth",
        &sample("stk_wood_planks1_256.png"),
        "-o",
        &syn,
        "--crop",
        "10,20,150,90",
        "--seed",
        "4",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // synth chooses the model as analyze does (auto) and says which.
    assert!(stdout(&o).contains("candidates"), "{}", stdout(&o));
    assert!(stdout(&o).contains("model: "), "{}", stdout(&o));
    let img = image::open(&syn).unwrap();
    assert_eq!((img.width(), img.height()), (150, 90));
    let o = proctex(&[
        "synth",
        &sample("stk_wood_planks1_256.png"),
        "-o",
        &syn,
        "--model",
        "noise",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("model: noise"), "{}", stdout(&o));
    let o = proctex(&[
        "analyze",
        &sample("stk_wood_planks1_256.png"),
        "--model",
        "brick",
        "--refine",
        "0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(
        out.contains("model: brick") && !out.contains("refined"),
        "{out}"
    );

    let o = proctex(&["evaluate", &syn, &sample("stk_wood_planks1_256.png")]);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("spectrum_db") && out.contains("colour") && out.contains("structure"),
        "{out}"
    );
}

#[test]
fn bad_input_exits_1_with_a_message() {
    for f in [
        "truncated.png",
        "truncated.jpg",
        "empty.png",
        "text.png",
        "1x1.png",
        "31x31.png",
        "huge_declared.png",
    ] {
        let o = proctex(&["analyze", &bad(f)]);
        assert_eq!(o.status.code(), Some(1), "{f}");
        let e = stderr(&o);
        assert!(
            e.starts_with("proctex: ") && !e.contains("panicked"),
            "{f}: {e}"
        );
        // The pyramid synthesis reads photos the same way and says the same.
        let o = proctex(&["pyramid", &bad(f), "-o", &tmp("bad.png")]);
        assert_eq!(o.status.code(), Some(1), "pyramid {f}");
        assert_eq!(stderr(&o), e, "pyramid {f}");
    }
    let o = proctex(&["analyze", "/nonexistent/photo.png"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("/nonexistent/photo.png"));

    let hostile = tmp("hostile.json");
    std::fs::write(&hostile, r#"{"format": "proctex/1", "seed": 1, "solid": false, "transform": {"scale": 1e308, "rotation_deg": 0}}"#).unwrap();
    let o = proctex(&["render", &hostile, "-o", &tmp("x.png")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("bad params"), "{}", stderr(&o));
}

#[test]
fn a_refinement_time_budget_stops_the_refinement_and_says_so() {
    let o = proctex(&[
        "analyze",
        &sample("stk_wood_planks1_256.png"),
        "--refine-seconds",
        "0.001",
        "-o",
        &tmp("budget.json"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("time budget of 0.001 s spent after"), "{out}");
    assert!(out.contains("model: "), "{out}");
    // Without a budget, no such line.
    let o = proctex(&[
        "analyze",
        &sample("stk_wood_planks1_256.png"),
        "--refine",
        "4",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stdout(&o).contains("time budget"), "{}", stdout(&o));
}

#[test]
fn fidelity_against_another_model_prints_the_paired_difference() {
    // The same model against itself: the same syntheses, so the difference and its error are
    // exactly zero (deterministic), and the JSON carries both results.
    let photo = sample("stk_blackrock_256.png");
    let run = |seeds: &str, json: bool| {
        let mut args = vec!["fidelity", &photo, "--against", "noise", "--seeds", seeds];
        if json {
            args.push("--json");
        }
        let o = proctex(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        stdout(&o)
    };
    let v: serde_json::Value = serde_json::from_str(run("2", true).trim()).unwrap();
    assert_eq!(v["result"], v["against"]["result"]);
    for k in ["spectrum_db", "colour", "structure"] {
        assert_eq!(v["against"]["ratio_difference"][k], 0.0, "{k}");
        assert_eq!(v["against"]["standard_error"][k], 0.0, "{k}");
    }
    assert_eq!(v["result"]["per_patch"].as_array().unwrap().len(), 4);
    // Black rock is a tile laid 2×2 (`evaluate::quadrants_repeat`): two distinct patches.
    assert_eq!(v["result"]["repeat"], true);
    let text = run("1", false);
    assert!(text.contains("difference +0.00 ± 0.00"), "{text}");
    assert!(text.contains("the quadrants repeat"), "{text}");
    // Unseen realisations (`render`: the flag and its values): at seeds 1 and 2, JSON.
    let unseen = |render: &[&str]| -> serde_json::Value {
        let mut args = vec!["fidelity", &photo, "--seeds", "2", "--json"];
        args.extend_from_slice(render);
        let o = proctex(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str(stdout(&o).trim()).unwrap()
    };
    // One: the same patches, another render of each analysed model.
    let u = unseen(&["--unseen-seed"]);
    assert_eq!(u["result"]["halves"], v["result"]["halves"]);
    assert_ne!(u["result"]["per_patch"], v["result"]["per_patch"]);
    // Two averaged: the same patches, other distances; none is refused.
    let u2 = unseen(&["--unseen-seeds", "2"]);
    assert_eq!(u2["result"]["halves"], v["result"]["halves"]);
    assert_ne!(u2["result"]["per_patch"], u["result"]["per_patch"]);
    let o = proctex(&["fidelity", &photo, "--unseen-seeds", "0"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // Seeds from another first one: the same patches; seeds 2 and 3 are not 1 and 2.
    let later = |first: &str| -> serde_json::Value {
        let args = [
            "fidelity",
            &photo,
            "--seeds",
            "2",
            "--first-seed",
            first,
            "--json",
        ];
        let o = proctex(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str(stdout(&o).trim()).unwrap()
    };
    assert_eq!(later("1")["result"], v["result"]);
    let l = later("2");
    assert_eq!(l["result"]["halves"], v["result"]["halves"]);
    assert_ne!(l["result"]["per_patch"], v["result"]["per_patch"]);
    // The help names the offset (the library's constant, filled in).
    let help = stdout(&proctex(&["fidelity", "--help"]));
    assert!(help.contains("--unseen-seed: each analysed model is rendered at its seed + "));
    assert!(!help.contains("UNSEEN"), "{help}");
}

#[test]
fn the_dev_set_yardstick_tabulates_choices_and_fidelity() {
    // A one-photo set in a folder of its own, retrieval without refinement (fast): every
    // source patch's choice, both models' fidelity, and the summary.
    let dir = std::path::PathBuf::from(tmp("devset"));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(sample("stk_blackrock_256.png"), dir.join("rock.png")).unwrap();
    std::fs::write(
        dir.join("manifest.tsv"),
        "file\tcategory\tmaterial\tfamilies\tlicense\nrock.png\tstochastic\tblack rock\tnoise\tCC0\n",
    )
    .unwrap();
    let set = dir.to_string_lossy().into_owned();
    let o = proctex(&["fidelity", "--set", &set, "--refine", "0", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let lines: Vec<serde_json::Value> = stdout(&o)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2, "one photo, then the summary");
    let photo = &lines[0]["photo"];
    assert_eq!(photo["entry"]["file"], "rock.png");
    assert_eq!(photo["choices"].as_array().unwrap().len(), 4);
    assert_eq!(photo["choices"][0]["top3"].as_array().unwrap().len(), 3);
    // The whole ranking's numbers (noise and the nine families), for offline re-ranking.
    assert_eq!(photo["choices"][0]["ranking"].as_array().unwrap().len(), 10);
    assert!(photo["auto"]["spectrum_ratio"].as_f64().unwrap() > 0.0);
    // Speck fractions of the patch, the chosen synthesis and every candidate.
    let choice = &photo["choices"][0];
    for v in [
        &choice["photo_specks"],
        &choice["render_specks"],
        &choice["ranking"][9]["specks"],
    ] {
        assert!((0.0..1.0).contains(&v.as_f64().unwrap()), "{choice}");
    }
    assert_eq!(choice["pixels"], 128 * 128);
    let summary = &lines[1]["summary"];
    assert!(
        lines[1]["renders"]
            .as_str()
            .unwrap()
            .contains("the fitted realisation")
    );
    assert_eq!(summary["stochastic_ok"]["total"], 4);
    assert_eq!(summary["structured_labelled"]["total"], 0);
    assert_eq!(summary["specks_clean"]["total"], 4);
    assert_eq!(summary["specks_by_model"].as_array().unwrap().len(), 10);
    // The text table, of fold 0 of 1 (every photo); a set without a manifest is bad input.
    let args = ["fidelity", "--set", &set, "--refine", "0", "--fold", "0/1"];
    let text = stdout(&proctex(&args));
    assert!(
        text.contains("rock.png (stochastic: black rock; labels noise)"),
        "{text}"
    );
    assert!(text.contains("summary of fold 0 of 1"), "{text}");
    assert!(text.contains("stochastic patches served well: "), "{text}");
    assert!(text.contains("confusion"), "{text}");
    assert!(text.contains("specks per model"), "{text}");
    let o = proctex(&["fidelity", "--set", "/nonexistent/set"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("/nonexistent/set/manifest.tsv"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn bad_usage_exits_2() {
    for args in [
        vec!["frobnicate"],
        vec!["analyze"],
        vec!["analyze", "x.png", "--size", "300"],
        vec!["analyze", "x.png", "--size"],
        vec!["analyze", "x.png", "--wat"],
        vec!["analyze", "x.png", "--estimator", "magic"],
        vec!["render", "p.json"],
        vec!["synth", "x.png"],
        vec!["evaluate", "a.png"],
        vec!["fidelity", "x.png", "--against", "bogus"],
        vec!["analyze", "x.png", "--refine-seconds", "0"],
        vec!["synth", "x.png", "-o", "y.png", "--refine-seconds", "nan"],
        vec!["fidelity", "--set", "d", "--fold", "4/4"],
        vec!["fidelity", "--set", "d", "--fold", "x"],
        vec!["fidelity", "x.png", "--fold", "0/4"],
        vec!["fidelity", "--set", "d", "x.png"],
        vec!["fidelity", "x.png", "--first-seed", "4294967295"],
        vec!["fidelity", "--set", "d", "--first-seed", "x"],
        vec!["pyramid", "x.png"],
        vec!["pyramid", "x.png", "-o", "y.jpg"],
        vec!["pyramid", "x.png", "-o", "y.png", "--iterations", "nan"],
        vec!["pyramid", "x.png", "-o", "y.png", "--wat"],
    ] {
        let o = proctex(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).starts_with("proctex: "), "{args:?}");
    }
}

#[test]
fn morph_prints_valid_params_and_rejects_bad_t() {
    let (a, b) = (tmp("morph-a.json"), tmp("morph-b.json"));
    for (photo, out) in [
        ("stk_rock_mountain_512.png", &a),
        ("skimage_grass_512.png", &b),
    ] {
        assert!(
            proctex(&["analyze", &sample(photo), "-o", out])
                .status
                .success()
        );
    }
    let o = proctex(&["morph", &a, &b, "--t", "0.25"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let p = proctex::params::Params::from_json(&String::from_utf8_lossy(&o.stdout)).unwrap();
    assert!(p.source.is_none());
    assert_eq!(
        proctex(&["morph", &a, &b, "--t", "1.5"]).status.code(),
        Some(2)
    );
    assert_eq!(proctex(&["morph", &a, "--t", "0.5"]).status.code(), Some(2));
    let o = proctex(&["morph", &a, &bad("text.png"), "--t", "0.5"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
}

#[test]
fn export_prints_json_wgsl_and_glsl() {
    let params = tmp("export.json");
    let o = proctex(&[
        "analyze",
        &sample("skimage_gravel_512.png"),
        "--model",
        "noise",
        "-o",
        &params,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = proctex(&["export", &params, "--format", "wgsl"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let wgsl = String::from_utf8_lossy(&o.stdout);
    assert!(wgsl.contains("fn proctex(") && wgsl.contains("@fragment"));
    let o = proctex(&["export", &params, "--format", "json"]);
    assert!(o.status.success());
    proctex::params::Params::from_json(&String::from_utf8_lossy(&o.stdout)).unwrap();
    let o = proctex(&["export", &params, "--format", "glsl"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let glsl = String::from_utf8_lossy(&o.stdout);
    assert!(glsl.starts_with("#version 300 es\n") && glsl.contains("vec3 proctex(vec2 p"));
    assert_eq!(
        proctex(&["export", &params, "--format", "hlsl"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(proctex(&["export", &params]).status.code(), Some(2));
    // Two files: the morph between them with t as a uniform; json takes one file.
    let other = tmp("export-other.json");
    let o = proctex(&[
        "analyze",
        &sample("stk_wood_planks1_256.png"),
        "--model",
        "noise",
        "-o",
        &other,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    // Auto picks a structured model for the planks (and says so); a morph from the noise
    // model to it exports as a cross-fade.
    let planks = tmp("export-planks.json");
    let o = proctex(&[
        "analyze",
        &sample("stk_wood_planks1_256.png"),
        "-o",
        &planks,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("model: planks"), "{}", stdout(&o));
    let o = proctex(&["export", &params, &planks, "--format", "wgsl"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains("const MORPH_SEED: u32"),
        "{}",
        stdout(&o)
    );
    // The structured preset renders as a seamless tile too.
    let o = proctex(&[
        "render",
        &planks,
        "--seamless",
        "--size",
        "96",
        "-o",
        &tmp("planks-tile.png"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("seamless tile"), "{}", stdout(&o));
    for (format, want) in [
        ("wgsl", "var<uniform> proctex_t"),
        ("glsl", "uniform float proctex_t;"),
    ] {
        let o = proctex(&["export", &params, &other, "--format", format]);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            String::from_utf8_lossy(&o.stdout).contains(want),
            "{format}"
        );
    }
    let o = proctex(&["export", &params, &other, "--format", "json"]);
    assert_eq!(o.status.code(), Some(2));
    // A tile size out of range is a clear error, not a panic.
    let o = proctex(&[
        "render",
        &params,
        "--seamless",
        "--size",
        "9000",
        "-o",
        &tmp("tile.png"),
    ]);
    assert_ne!(o.status.code(), Some(0));
    assert!(stderr(&o).contains("8192"), "{}", stderr(&o));
    assert_eq!(
        proctex(&["export", &bad("text.png"), "--format", "wgsl"])
            .status
            .code(),
        Some(1)
    );
}

#[test]
fn pyramid_writes_a_texture_of_any_size_and_refuses_bad_options() {
    let photo = sample("stk_blackrock_256.png");
    let (a, b) = (tmp("hb-a.png"), tmp("hb-b.png"));
    let o = proctex(&["pyramid", &photo, "-o", &a, "--iterations", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("256×256"), "{}", stdout(&o));
    let o = proctex(&["pyramid", &photo, "-o", &b, "--iterations", "2"]);
    assert!(o.status.success());
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    let o = proctex(&[
        "pyramid",
        &photo,
        "-o",
        &b,
        "--width",
        "150",
        "--height",
        "90",
        "--seed",
        "3",
        "--crop",
        "0,0,128,128",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let img = proctex::input::Photo::decode(&std::fs::read(&b).unwrap()).unwrap();
    assert_eq!((img.width, img.height), (150, 90));
    for (flag, value, words) in [
        ("--orientations", "0", "--orientations 0"),
        ("--scales", "40", "--scales 40"),
        ("--width", "8", "at least 32"),
    ] {
        let o = proctex(&["pyramid", &photo, "-o", &b, flag, value]);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {}", stderr(&o));
        assert!(stderr(&o).contains(words), "{}", stderr(&o));
    }
    // A mixture at m = 0 is the plain synthesis; --m needs --mix, and a value in 0..1.
    let other = sample("stk_wood_planks1_256.png");
    let o = proctex(&[
        "pyramid",
        &photo,
        "-o",
        &b,
        "--iterations",
        "2",
        "--mix",
        &other,
        "--m",
        "0",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    for args in [vec!["--m", "0.5"], vec!["--mix", &other, "--m", "2"]] {
        let mut all = vec!["pyramid", photo.as_str(), "-o", b.as_str()];
        all.extend(args.iter().copied());
        let o = proctex(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
    // A solid texture: N slices of N², in a directory made for them.
    let dir = tmp("solid-slices");
    let o = proctex(&[
        "pyramid",
        &photo,
        "--solid",
        "16",
        "-o",
        &dir,
        "--iterations",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let slices = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(slices, 16);
    let s = proctex::input::Photo::decode(&std::fs::read(format!("{dir}/slice_015.png")).unwrap())
        .unwrap();
    assert_eq!((s.width, s.height), (16, 16));
    for args in [
        vec!["--solid", "8"],
        vec!["--solid", "300"],
        vec!["--solid", "32", "--width", "64"],
    ] {
        let mut all = vec!["pyramid", photo.as_str(), "-o", dir.as_str()];
        all.extend(args.iter().copied());
        let o = proctex(&all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    }
    // Too large an output is bad input (1), as a too large render is.
    let o = proctex(&[
        "pyramid", &photo, "-o", &b, "--width", "8000", "--height", "8000",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("over the limit"), "{}", stderr(&o));
}
