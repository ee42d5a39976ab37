//! Exported WGSL: a complete shader that naga validates, for every shipped sample.

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
