//! Every WGSL function has a Rust twin in the analyzer (the CPU reference renderer).

/// WGSL file → the analyzer source holding the twins of its functions. A function's twin has
/// the same name, except for the ones listed in `RENAMED`.
const TWIN_FILES: [(&str, &[&str]); 18] = [
    ("hash.wgsl", &["analyzer/src/rng.rs"]),
    ("pattern.wgsl", &["analyzer/src/render/pattern.rs"]),
    (
        "morph.wgsl",
        &[
            "analyzer/src/morph.rs",
            "analyzer/src/colour.rs",
            "analyzer/src/histogram.rs",
        ],
    ),
    ("tile3.wgsl", &["analyzer/src/noise.rs"]),
    ("tile3_atlas.wgsl", &["analyzer/src/noise.rs"]),
    ("atlas3.wgsl", &["analyzer/src/noise.rs"]),
    (
        "bake2.wgsl",
        &["analyzer/src/noise.rs", "analyzer/src/noise/spectral.rs"],
    ),
    ("bake3.wgsl", &["analyzer/src/noise.rs"]),
    (
        "noise.wgsl",
        &["analyzer/src/noise.rs", "analyzer/src/noise/oriented.rs"],
    ),
    ("histogram.wgsl", &["analyzer/src/histogram.rs"]),
    ("texture.wgsl", &["analyzer/src/render.rs"]),
    ("plane.wgsl", &["analyzer/src/render.rs"]),
    ("solid_camera.wgsl", &["analyzer/src/solid.rs"]),
    ("solid.wgsl", &["analyzer/src/solid.rs"]),
    ("solid_volume.wgsl", &["analyzer/src/solid.rs"]),
    ("seamless.wgsl", &["analyzer/src/seamless.rs"]),
    ("view_copy.wgsl", &["web/src/view_cache.rs"]),
    (
        "bake.wgsl",
        &["analyzer/src/rng.rs", "analyzer/src/noise.rs"],
    ),
];

/// WGSL function → Rust twin, where the names differ (entry points, whose twin is the CPU
/// renderer's pixel loop).
const RENAMED: [(&str, &str); 38] = [
    // `uniform` would shadow the address space of `var<uniform>` (exported morphs have one).
    ("uniform01", "uniform"),
    ("morph_params", "morph_path"),
    ("vs_main", "render_prepared"),
    ("fs_main", "render_prepared"),
    ("fs_flat", "render_flat"),
    ("vs_solid", "render_solid"),
    ("vs_seamless", "render_rows"),
    ("fs_seamless", "render_rows"),
    ("fs_solid", "render_solid"),
    ("fs_solid_volume", "render_solid_volume"),
    // The 2D bake's passes together are Tile::generate of the spectral tile: the spectrum and
    // the two inverse DFTs (each split in two passes, with their helpers) are
    // spectral::field_pair (its FFT), the magnitude and the closed form of the band's power
    // spectral::magnitude and expected_power_at (with their helpers: the transfers, the signed
    // bin, the B-spline's power); wrap is the `rem_euclid` indexing.
    ("vs_bake", "generate"),
    ("fs_bake_spectrum", "field_pair"),
    ("fs_bake_rows_inner", "field_pair"),
    ("fs_bake_rows", "field_pair"),
    ("fs_bake_cols_inner", "field_pair"),
    ("axis_texel", "field_pair"),
    ("cmul2", "field_pair"),
    ("inner_sums", "field_pair"),
    ("outer_sums", "field_pair"),
    ("fs_bake_tile", "generate"),
    ("twiddle", "field_pair"),
    ("cmul", "field_pair"),
    ("transfer_a", "expected_power_at"),
    ("transfer_p", "expected_power_at"),
    ("expected_power", "expected_power_at"),
    ("tile_magnitude", "magnitude"),
    ("signed_bin", "frequency"),
    ("sinc", "spline_power"),
    ("wrap_mod", "shift_index"),
    // The same for the 3D tile's passes (bake3.wgsl).
    ("fs_bake3_down_x", "generate"),
    ("fs_bake3_down_y", "generate"),
    ("fs_bake3_down_z", "generate"),
    ("fs_bake3_tile", "generate"),
    ("r_value3", "generate"),
    ("band3", "generate"),
    ("upsample3", "upsample"),
    // The frame cache's copy: the twin is the per-pixel copy of the cached view.
    ("vs_copy", "copy_view"),
    ("fs_copy", "copy_view"),
];

fn wgsl_functions(src: &str) -> Vec<String> {
    src.lines()
        .filter_map(|l| l.trim_start().strip_prefix("fn "))
        .map(|rest| rest.split('(').next().unwrap().trim().to_string())
        .collect()
}

#[test]
fn every_wgsl_function_has_a_rust_twin() {
    let root = format!("{}/..", env!("CARGO_MANIFEST_DIR"));
    let mut checked = 0;
    for (file, src) in proctex_shaders::FILES {
        let functions = wgsl_functions(src);
        if functions.is_empty() {
            continue;
        }
        let rust_file = TWIN_FILES
            .iter()
            .find(|(w, _)| *w == file)
            .unwrap_or_else(|| panic!("{file} has functions but no twin file in TWIN_FILES"))
            .1;
        let rust: String = rust_file
            .iter()
            .map(|f| std::fs::read_to_string(format!("{root}/{f}")).unwrap())
            .collect();
        for f in functions {
            let twin = RENAMED
                .iter()
                .find(|(w, _)| *w == f)
                .map(|(_, r)| *r)
                .unwrap_or(&f);
            assert!(
                rust.contains(&format!("fn {twin}(")),
                "WGSL `{f}` in {file} has no Rust twin `fn {twin}` in {rust_file:?}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 12, "only {checked} functions checked");
}

/// GLSL function → WGSL twin, where the names differ (GLSL reserves the WGSL name, or the
/// GLSL `main` of the bake passes is the WGSL entry points).
const GLSL_RENAMED: [(&str, &str); 6] = [
    ("wavelet_noise2", "noise2"),
    ("wavelet_noise3", "noise3"),
    ("wavelet_noise2_oriented", "noise2_oriented"),
    ("wavelet_noise3_oriented", "noise3_oriented"),
    ("main", "fs_bake_tile"),
    ("main", "fs_bake3_tile"),
];

fn glsl_functions(src: &str) -> Vec<String> {
    src.lines()
        .filter(|l| !l.starts_with(' ') && !l.starts_with("//") && !l.starts_with('#'))
        .filter_map(|l| {
            let (head, _) = l.split_once('(')?;
            let mut words = head.split_whitespace();
            let (_ty, name) = (words.next()?, words.next()?);
            (words.next().is_none() && l.trim_end().ends_with('{')).then(|| name.to_string())
        })
        .collect()
}

#[test]
fn every_glsl_function_has_a_wgsl_twin() {
    let mut checked = 0;
    for (file, glsl, wgsl) in proctex_shaders::glsl::FILES {
        let wgsl_fns = wgsl_functions(wgsl);
        for f in glsl_functions(glsl) {
            let mut twins: Vec<&str> = GLSL_RENAMED
                .iter()
                .filter(|(g, _)| *g == f)
                .map(|(_, w)| *w)
                .collect();
            if twins.is_empty() {
                twins.push(&f);
            }
            assert!(
                wgsl_fns.iter().any(|w| twins.contains(&w.as_str())),
                "GLSL `{f}` in glsl/{file} has no WGSL twin `fn {}`",
                twins.join("` or `fn ")
            );
            checked += 1;
        }
        // And the other way: every WGSL function of the library has a GLSL twin (entry points
        // and the 3D noise's variants aside).
        let glsl_fns = glsl_functions(glsl);
        for w in wgsl_fns {
            let skip = w.starts_with("vs_") || w.starts_with("fs_");
            let has = glsl_fns
                .iter()
                .any(|g| *g == w || GLSL_RENAMED.iter().any(|(gn, wn)| gn == g && *wn == w));
            assert!(skip || has, "WGSL `{w}` has no GLSL twin in glsl/{file}");
        }
    }
    assert!(checked >= 15, "only {checked} GLSL functions checked");
}
