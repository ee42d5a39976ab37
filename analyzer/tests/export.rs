//! Exported shaders, for every shipped sample as a plane texture and as a solid one: the WGSL
//! validates with naga, the GLSL compiles with glslang (each of its stages, GLSL ES 3.00 and
//! desktop 330). Structured models too: each pattern fitted to the brick sample.

mod common;

use common::{SAMPLES, sample};
use proctex::analyze::{Options, analyze_photo};

/// Every sample's params, plane and solid.
fn every_texture() -> Vec<(String, proctex::params::Params)> {
    let mut out = Vec::new();
    for name in SAMPLES {
        let params = analyze_photo(&sample(name), &Options::default())
            .unwrap()
            .params;
        let mut solid = params.clone();
        solid.solid = true;
        out.push((name.to_string(), params));
        out.push((format!("{name}-solid"), solid));
    }
    // Every structured model, fitted to the brick photo; two of them solid too.
    let brick = sample("skimage_brick_512.png").reduced(256).unwrap();
    for kind in proctex::pattern::PatternKind::ALL {
        let pattern = proctex::pattern::Pattern::new(kind, 12.0);
        let params = proctex::structure::fit_structured(
            proctex::db::Db::shipped(),
            &brick,
            &pattern,
            &Options::default(),
            false,
        )
        .params;
        if matches!(
            kind,
            proctex::pattern::PatternKind::Cells | proctex::pattern::PatternKind::Rings
        ) {
            let mut solid = params.clone();
            solid.solid = true;
            out.push((format!("{}-solid", kind.name()), solid));
        }
        out.push((kind.name().to_string(), params));
    }
    out
}

/// Parses and validates a WGSL shader with naga; panics with the message.
fn naga_validate(name: &str, src: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(src)
        .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(src)));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{name}: {e:?}"));
    module
}

#[test]
fn exported_wgsl_validates_with_naga() {
    for (name, params) in every_texture() {
        let src = proctex::export::wgsl(&params).unwrap();
        let module = naga_validate(&name, &src);
        let entries: Vec<&str> = module
            .entry_points
            .iter()
            .map(|e| e.name.as_str())
            .collect();
        let passes: &[&str] = if params.solid {
            &[
                "fs_bake3_down_x",
                "fs_bake3_down_y",
                "fs_bake3_down_z",
                "fs_bake3_tile",
            ]
        } else {
            &[
                "fs_bake_spectrum",
                "fs_bake_rows_inner",
                "fs_bake_rows",
                "fs_bake_cols_inner",
                "fs_bake_tile",
            ]
        };
        for want in ["vs_main", "fs_main", "vs_bake"].iter().chain(passes) {
            assert!(entries.contains(want), "{name}: no {want}");
        }
        // Only the passes the host is told to run.
        assert_eq!(entries.len(), 3 + passes.len(), "{name}: {entries:?}");
        assert!(src.contains("fn proctex(p: vec2<f32>, pixel_size: f32) -> vec3<f32>"));
        assert_eq!(
            src.contains("fn proctex3(p: vec3<f32>, pixel_size: f32) -> vec3<f32>"),
            params.solid
        );
    }
}

/// glslangValidator (Debian's `glslang-tools`; `scripts/test.sh` installs it).
fn glslang() -> &'static str {
    let ok = std::process::Command::new("glslangValidator")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "glslangValidator not found: install Debian's glslang-tools (scripts/test.sh does)"
    );
    "glslangValidator"
}

/// Compiles `src` with glslang as the stage its file extension names; panics with the log.
fn compile(dir: &std::path::Path, file: &str, src: &str) {
    let path = dir.join(file);
    std::fs::write(&path, src).unwrap();
    let out = std::process::Command::new(glslang())
        .arg(&path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{file} does not compile:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn exported_glsl_compiles_with_glslang() {
    let dir = std::env::temp_dir().join(format!("proctex-glsl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, params) in every_texture() {
        let src = proctex::export::glsl(&params).unwrap();
        let (first, rest) = src.split_once('\n').unwrap();
        assert_eq!(
            first, "#version 300 es",
            "{name}: the text must compile as-is"
        );
        assert!(src.contains("vec3 proctex(vec2 p, float pixel_size)"));
        assert_eq!(
            src.contains("vec3 proctex3(vec3 p, float pixel_size)"),
            params.solid
        );
        // As-is: the display fragment shader, GLSL ES 3.00.
        compile(&dir, &format!("{name}.frag"), &src);
        // Each stage by its define, in GLSL ES 3.00 and (the header's note) desktop GLSL 330.
        for (v, version) in ["#version 300 es", "#version 330 core"].iter().enumerate() {
            let mut stages = vec![
                ("// display", "frag"),
                ("#define PROCTEX_VERTEX", "vert"),
                ("#define PROCTEX_PASS 1", "frag"),
                ("#define PROCTEX_PASS 2", "frag"),
                ("#define PROCTEX_PASS 3", "frag"),
                ("#define PROCTEX_PASS 4", "frag"),
            ];
            if !params.solid {
                stages.push(("#define PROCTEX_PASS 5", "frag"));
            }
            for (d, (define, ext)) in stages.iter().enumerate() {
                let stage = format!("{version}\n{define}\n{rest}");
                let file = format!("{name}-{v}{d}.{ext}");
                compile(&dir, &file, &stage);
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A structured model of `kind` fitted to the brick photo at pattern scale `scale`, rotated by
/// `rotation_deg`.
fn fitted(
    kind: proctex::pattern::PatternKind,
    scale: f32,
    rotation_deg: f32,
) -> proctex::params::Params {
    let brick = sample("skimage_brick_512.png").reduced(128).unwrap();
    let mut pattern = proctex::pattern::Pattern::new(kind, scale);
    pattern.rotation_deg = rotation_deg;
    proctex::structure::fit_structured(
        proctex::db::Db::shipped(),
        &brick,
        &pattern,
        &Options::default(),
        false,
    )
    .params
}

/// Morphs through the samples: two plane keys, three plane keys (histograms off in one), two
/// solid keys; and through structured models: one family (brick to brick), across families and
/// the noise model (brick, noise, cells, rings), two solid ones.
fn every_morph() -> Vec<(String, Vec<proctex::params::Params>)> {
    let key = |i: usize| {
        analyze_photo(&sample(SAMPLES[i]), &Options::default())
            .unwrap()
            .params
    };
    let (a, b, c) = (key(0), key(1), key(2));
    let mut c_flat = c.clone();
    let m = c_flat.model.noise_layer_mut();
    m.histogram.enabled = false;
    let solid = |p: &proctex::params::Params| {
        let mut p = p.clone();
        p.solid = true;
        p
    };
    vec![
        ("morph-2".into(), vec![a.clone(), b.clone()]),
        ("morph-3".into(), vec![a.clone(), b.clone(), c_flat]),
        ("morph-solid".into(), vec![solid(&b), solid(&c)]),
        (
            "morph-brick".into(),
            vec![
                fitted(proctex::pattern::PatternKind::Brick, 12.0, 0.0),
                fitted(proctex::pattern::PatternKind::Brick, 20.0, 350.0),
            ],
        ),
        (
            "morph-families".into(),
            vec![
                fitted(proctex::pattern::PatternKind::Brick, 12.0, 0.0),
                a.clone(),
                fitted(proctex::pattern::PatternKind::Cells, 16.0, 30.0),
                fitted(proctex::pattern::PatternKind::Rings, 10.0, 0.0),
            ],
        ),
        (
            "morph-structured-solid".into(),
            vec![
                solid(&fitted(proctex::pattern::PatternKind::Rings, 10.0, 0.0)),
                solid(&fitted(proctex::pattern::PatternKind::Cells, 16.0, 30.0)),
            ],
        ),
    ]
}

#[test]
fn exported_morphs_validate_and_compile() {
    let dir = std::env::temp_dir().join(format!("proctex-morph-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, keys) in every_morph() {
        let src = proctex::export::morph_wgsl(&keys).unwrap();
        naga_validate(&name, &src);
        assert!(src.contains("var<uniform> proctex_t: vec4<f32>"));
        assert!(src.contains("fn proctex(p: vec2<f32>, pixel_size: f32, t: f32) -> vec3<f32>"));

        let src = proctex::export::morph_glsl(&keys).unwrap();
        assert!(src.contains("uniform float proctex_t;"));
        let rest = src.split_once('\n').unwrap().1;
        let stages = [
            ("// display", "frag"),
            ("#define PROCTEX_VERTEX", "vert"),
            ("#define PROCTEX_PASS 1", "frag"),
            // The last pass of either bake (plane 5, solid 4), the one that normalises.
            if keys[0].solid {
                ("#define PROCTEX_PASS 4", "frag")
            } else {
                ("#define PROCTEX_PASS 5", "frag")
            },
        ];
        for (d, (define, ext)) in stages.iter().enumerate() {
            compile(
                &dir,
                &format!("{name}-{d}.{ext}"),
                &format!("#version 300 es\n{define}\n{rest}"),
            );
        }
        compile(
            &dir,
            &format!("{name}-330.frag"),
            &format!("#version 330 core\n{rest}"),
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    // Plane and solid keys together: a clear error.
    let mut keys = every_morph().remove(0).1;
    keys[1].solid = true;
    let err = proctex::export::morph_wgsl(&keys).unwrap_err().to_string();
    assert!(err.contains("plane and solid"), "{err}");
    assert!(proctex::export::morph_glsl(&keys[..1]).is_err());
}
