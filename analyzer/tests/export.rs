//! Exported shaders, for every shipped sample: the WGSL validates with naga, the GLSL compiles
//! with glslang (each of its five stages, GLSL ES 3.00 and desktop 330).

mod common;

use common::{SAMPLES, sample};
use proctex::analyze::{Options, analyze_photo};

#[test]
fn exported_wgsl_validates_with_naga() {
    for name in SAMPLES {
        let params = analyze_photo(&sample(name), &Options::default())
            .unwrap()
            .params;
        let src = proctex::export::wgsl(&params).unwrap();
        let module = naga::front::wgsl::parse_str(&src)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(&src)));
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let entries: Vec<&str> = module
            .entry_points
            .iter()
            .map(|e| e.name.as_str())
            .collect();
        for want in [
            "vs_main",
            "fs_main",
            "vs_bake",
            "fs_bake_down_x",
            "fs_bake_down_y",
            "fs_bake_tile",
        ] {
            assert!(entries.contains(&want), "{name}: no {want}");
        }
        assert!(src.contains("fn proctex(p: vec2<f32>, pixel_size: f32) -> vec3<f32>"));
    }
    let mut solid = analyze_photo(&sample(SAMPLES[0]), &Options::default())
        .unwrap()
        .params;
    solid.solid = true;
    assert!(proctex::export::wgsl(&solid).is_err());
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
    for name in SAMPLES {
        let params = analyze_photo(&sample(name), &Options::default())
            .unwrap()
            .params;
        let src = proctex::export::glsl(&params).unwrap();
        let (first, rest) = src.split_once('\n').unwrap();
        assert_eq!(
            first, "#version 300 es",
            "{name}: the text must compile as-is"
        );
        assert!(src.contains("vec3 proctex(vec2 p, float pixel_size)"));
        // As-is: the display fragment shader, GLSL ES 3.00.
        compile(&dir, &format!("{name}.frag"), &src);
        // Each stage by its define, in GLSL ES 3.00 and (the header's note) desktop GLSL 330.
        for (v, version) in ["#version 300 es", "#version 330 core"].iter().enumerate() {
            for (d, (define, ext)) in [
                ("// display", "frag"),
                ("#define PROCTEX_VERTEX", "vert"),
                ("#define PROCTEX_PASS 1", "frag"),
                ("#define PROCTEX_PASS 2", "frag"),
                ("#define PROCTEX_PASS 3", "frag"),
            ]
            .iter()
            .enumerate()
            {
                let stage = format!("{version}\n{define}\n{rest}");
                let file = format!("{name}-{v}{d}.{ext}");
                compile(&dir, &file, &stage);
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let mut solid = analyze_photo(&sample(SAMPLES[0]), &Options::default())
        .unwrap()
        .params;
    solid.solid = true;
    assert!(proctex::export::glsl(&solid).is_err());
}
