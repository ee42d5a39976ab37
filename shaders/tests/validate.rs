//! Every composed shader parses and validates with naga, and the uniform block it declares has
//! exactly the size and constants the Rust side writes.

use proctex::histogram::KNOT_Z;
use proctex::params::{MAX_BANDS, MAX_KNOTS, MAX_TONE_KNOTS};
use proctex::pattern::{MAX_STOPS, MAX_VALUES, OCTAVES};
use proctex::render::Prepared;

fn parse(name: &str, src: &str) -> naga::Module {
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
fn every_shader_validates() {
    let shaders = proctex_shaders::shaders();
    assert!(!shaders.is_empty());
    for (name, src) in &shaders {
        let module = parse(name, src);
        assert!(
            module.entry_points.len() >= 2,
            "{name}: expected a vertex and a fragment entry point"
        );
    }
}

#[test]
fn every_wgsl_file_is_used_by_a_shader() {
    let all: String = proctex_shaders::shaders()
        .into_iter()
        .map(|(_, s)| s)
        .collect();
    for (name, src) in proctex_shaders::FILES {
        assert!(all.contains(src), "{name} is not part of any shader");
    }
    // And every .wgsl file in the folder is listed.
    let dir = env!("CARGO_MANIFEST_DIR");
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "wgsl") {
            let file = path.file_name().unwrap().to_string_lossy().to_string();
            assert!(
                proctex_shaders::FILES.iter().any(|(n, _)| *n == file),
                "{file} is not in proctex_shaders::FILES"
            );
        }
    }
}

#[test]
fn seamless_uniform_matches_rust() {
    let module = parse("seamless", &proctex_shaders::seamless_shader());
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Seamless"))
        .expect("struct Seamless");
    assert_eq!(
        layouter[handle].size as usize,
        proctex::seamless::UNIFORM_SIZE
    );
}

#[test]
fn uniform_layout_matches_rust() {
    // weights, offsets and orient: one vec4 per band each.
    const PATTERN_AT: u32 = 128 + 48 * MAX_BANDS as u32 + 32 * MAX_KNOTS as u32;
    const RAMP_AT: u32 = PATTERN_AT + 32 + 16 * (MAX_VALUES as u32 / 4) + 16 * OCTAVES as u32;
    const TONE_AT: u32 = RAMP_AT + 16 * MAX_STOPS as u32;
    let src = proctex_shaders::plane_shader();
    let module = parse("plane", &src);
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, ty) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("Params"))
        .expect("struct Params");
    assert_eq!(layouter[handle].size as usize, Prepared::UNIFORM_SIZE);
    let naga::TypeInner::Struct { members, .. } = &ty.inner else {
        panic!("Params is not a struct");
    };
    let offsets: Vec<(String, u32)> = members
        .iter()
        .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
        .collect();
    let want = [
        ("mean", 0),
        ("basis", 16),
        ("transform", 64),
        ("counts", 80),
        ("sigma", 96),
        ("fine", 112),
        ("weights", 128),
        ("offsets", 128 + 16 * MAX_BANDS as u32),
        ("orient", 128 + 32 * MAX_BANDS as u32),
        ("knots", 128 + 48 * MAX_BANDS as u32),
        (
            "tangents",
            128 + 48 * MAX_BANDS as u32 + 16 * MAX_KNOTS as u32,
        ),
        ("pattern", PATTERN_AT),
        ("pattern_transform", PATTERN_AT + 16),
        ("pattern_values", PATTERN_AT + 32),
        (
            "pattern_offsets",
            PATTERN_AT + 32 + 16 * (MAX_VALUES as u32 / 4),
        ),
        ("ramp", RAMP_AT),
        ("tone_range", TONE_AT),
        ("tone_knots", TONE_AT + 32),
        ("tone_tangents", TONE_AT + 32 + 16 * MAX_TONE_KNOTS as u32),
    ];
    assert_eq!(offsets.len(), want.len(), "every member is checked");
    for ((name, off), (wname, woff)) in offsets.iter().zip(want) {
        assert_eq!((name.as_str(), *off), (wname, woff));
    }
    // Constants shared with Rust.
    let constant = |name: &str| -> String {
        src.lines()
            .find(|l| l.trim_start().starts_with(&format!("const {name}:")))
            .unwrap_or_else(|| panic!("const {name}"))
            .split('=')
            .nth(1)
            .unwrap()
            .trim()
            .trim_end_matches(';')
            .trim_end_matches('u')
            .to_string()
    };
    assert_eq!(constant("MAX_BANDS"), MAX_BANDS.to_string());
    assert_eq!(constant("MAX_KNOTS"), MAX_KNOTS.to_string());
    assert_eq!(constant("MAX_TONE_KNOTS"), MAX_TONE_KNOTS.to_string());
    assert_eq!(constant("KNOT_Z").parse::<f32>().unwrap(), KNOT_Z);
    assert_eq!(constant("PATTERN_OCTAVES"), OCTAVES.to_string());
    assert_eq!(
        constant("CELLS_STREAM"),
        format!("{:#x}", proctex::rng::stream::CELLS)
    );
    assert_eq!(
        constant("WARP_OFFSET").parse::<f32>().unwrap(),
        proctex::render::pattern::WARP_OFFSET
    );
    assert_eq!(
        constant("FINE_GAIN").parse::<f32>().unwrap(),
        proctex::render::FINE_GAIN
    );
    // The GLSL twin's (exported shaders).
    let glsl = include_str!("../glsl/texture.glsl");
    let line = glsl
        .lines()
        .find(|l| l.starts_with("const float FINE_GAIN ="))
        .expect("const float FINE_GAIN");
    let value = line.split('=').nth(1).unwrap().trim().trim_end_matches(';');
    assert_eq!(value.parse::<f32>().unwrap(), proctex::render::FINE_GAIN);
}

#[test]
fn solid_view_uniform_matches_rust() {
    let src = proctex_shaders::solid_shader();
    let module = parse("solid", &src);
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("SolidView"))
        .expect("struct SolidView");
    assert_eq!(
        layouter[handle].size as usize,
        proctex::solid::SolidView::UNIFORM_SIZE
    );
    let background = src
        .lines()
        .find(|l| l.starts_with("const BACKGROUND"))
        .expect("const BACKGROUND");
    let want = proctex::solid::BACKGROUND;
    assert!(background.contains(&format!("{:?}, {:?}, {:?}", want[0], want[1], want[2])));
}

#[test]
fn solid_volume_uniform_matches_rust() {
    let module = parse("solid_volume", &proctex_shaders::solid_volume_shader());
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).unwrap();
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref() == Some("SolidVolume"))
        .expect("struct SolidVolume");
    assert_eq!(
        layouter[handle].size as usize,
        proctex::solid::VOLUME_UNIFORM_SIZE
    );
}
