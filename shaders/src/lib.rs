//! Every WGSL source of Proctex, and the complete shaders composed from them.
//!
//! WGSL has no `#include`; modules are concatenated in a fixed order. Each WGSL function has a
//! Rust twin in the analyzer (the CPU reference renderer); `tests/twins.rs` checks that every
//! function here names one, `tests/validate.rs` validates every composed shader with naga, and
//! `web/tests/gpu_vs_cpu/` renders on a real (or software) GPU and compares with
//! `proctex::render::render`.

/// Uniform block layout and bindings of the texture parameters.
pub const PARAMS: &str = include_str!("../params.wgsl");
/// The 3D tile as the app binds it (a 3D texture): `tile3_side`, `tile3_texel`.
pub const TILE3: &str = include_str!("../tile3.wgsl");
/// The 3D tile of exported solid textures (a 2D atlas of slices): `tile3_side`, `tile3_texel`.
pub const TILE3_ATLAS: &str = include_str!("../tile3_atlas.wgsl");
/// A volume as a 2D atlas of its slices (`atlas_texel`, `atlas_voxel`).
pub const ATLAS3: &str = include_str!("../atlas3.wgsl");
/// Wavelet noise evaluation and band clamping.
pub const NOISE: &str = include_str!("../noise.wgsl");
/// Histogram matching.
pub const HISTOGRAM: &str = include_str!("../histogram.wgsl");
/// The texture at a point (`shade`).
pub const TEXTURE: &str = include_str!("../texture.wgsl");
/// The one hash (`pcg_hash`, `hash3`, `uniform01`): tile bakes and cell patterns.
pub const HASH: &str = include_str!("../hash.wgsl");
/// Structured models: the pattern's structure value and the colour ramp.
pub const PATTERN: &str = include_str!("../pattern.wgsl");
/// The 2D plane view (full-screen triangle) and the trivial baseline shader `fs_flat`.
pub const PLANE: &str = include_str!("../plane.wgsl");
/// The solid views' orbit camera and its ray through a pixel into the sphere or cube.
pub const SOLID_CAMERA: &str = include_str!("../solid_camera.wgsl");
/// The solid view of the procedural texture: the sphere or cube shaded by the 3D texture.
pub const SOLID: &str = include_str!("../solid.wgsl");
/// The solid view of a raster volume (the Heeger–Bergen solid texture), trilinear, wrapping.
pub const SOLID_VOLUME: &str = include_str!("../solid_volume.wgsl");
/// The app's frame cache of the texture view copied to the canvas, pixel for pixel.
pub const VIEW_COPY: &str = include_str!("../view_copy.wgsl");

/// Morphing with t as a uniform (exported morphs): the params of `t` from every key's constants.
pub const MORPH: &str = include_str!("../morph.wgsl");

/// The uniform declaration of `params` in [`PARAMS`].
const PARAMS_UNIFORM: &str = "@group(0) @binding(0) var<uniform> params: Params;";

/// [`PARAMS`] with the uniform `params` made a module-scope private variable (exported
/// snippets): initialised with `init` (a `Params` value), or left for the shader to assign
/// (morphs assign the params of `t` per invocation).
pub fn params_private(init: Option<&str>) -> String {
    let decl = match init {
        Some(v) => format!("var<private> params: Params = {v};"),
        None => "var<private> params: Params;".to_string(),
    };
    assert!(
        PARAMS.contains(PARAMS_UNIFORM),
        "params.wgsl declares the uniform"
    );
    PARAMS.replace(PARAMS_UNIFORM, &decl)
}

/// What every texture shader holds after the params and its access to the 3D tile (`TILE3` in
/// the app, `ATLAS3` + `TILE3_ATLAS` in exports): noise, histogram, hash, pattern, texture.
pub const SHADING: [&str; 5] = [NOISE, HISTOGRAM, HASH, PATTERN, TEXTURE];

/// The library every view shader starts with: params, the 3D tile, then [`SHADING`].
pub fn texture_library() -> String {
    [&[PARAMS, TILE3][..], &SHADING].concat().join("\n")
}

/// The 2D plane view shader (entry points `vs_main`, `fs_main`).
pub fn plane_shader() -> String {
    [texture_library().as_str(), PLANE].join("\n")
}

/// Seamless tiles (the PNG tile export): every band periodic over the tile, rendered in strips.
pub const SEAMLESS: &str = include_str!("../seamless.wgsl");

/// The seamless tile shader (entry points `vs_seamless`, `fs_seamless`).
pub fn seamless_shader() -> String {
    [texture_library().as_str(), SEAMLESS].join("\n")
}

/// Baking noise tiles from the seed on the GPU (exported snippets): what the 2D and 3D bakes
/// share.
pub const BAKE: &str = include_str!("../bake.wgsl");
/// The 2D tile's bake passes (`fs_bake_spectrum`, `fs_bake_rows_inner`, `fs_bake_rows`,
/// `fs_bake_cols_inner`, `fs_bake_tile`).
pub const BAKE2: &str = include_str!("../bake2.wgsl");
/// The 3D tile's bake passes into slice atlases (`fs_bake3_down_x|y|z`, `fs_bake3_tile`).
pub const BAKE3: &str = include_str!("../bake3.wgsl");

/// The constants `bake.wgsl` needs: tile side, hash seed and stream, the odd shift of the
/// (3D tile's) even/odd fix, and the CPU-measured normalisation (`noise::Tile::stats`).
pub fn bake_constants(n: u32, seed: u32, stream: u32, mean: [f64; 3], inv_sd: [f64; 3]) -> String {
    let offset = odd_offset(n);
    let v3 = |v: [f64; 3]| {
        format!(
            "vec3<f32>({:?}, {:?}, {:?})",
            v[0] as f32, v[1] as f32, v[2] as f32
        )
    };
    format!(
        "const N: u32 = {n}u;\nconst TILE_SEED: u32 = {seed}u;\nconst TILE_STREAM: u32 = {stream}u;\n\
         const TILE_ODD_OFFSET: u32 = {offset}u;\nconst TILE_MEAN = {};\n\
         const TILE_INV_SD = {};\n",
        v3(mean),
        v3(inv_sd)
    )
}

/// The constant the 2D bake needs besides [`bake_constants`]: `TILE_PROFILE`, the ring profile
/// of the tile's rendered power (`noise::spectral::ring_profile`, N/2 + 1 values).
pub fn bake2_constants(profile: &[f64]) -> String {
    format!(
        "const TILE_PROFILE = array<f32, {}>({});\n",
        profile.len(),
        float_list(profile)
    )
}

/// `values` as f32 literals, comma-separated (the same text in WGSL and GLSL).
fn float_list(values: &[f64]) -> String {
    let values: Vec<String> = values.iter().map(|v| format!("{:?}", *v as f32)).collect();
    values.join(", ")
}

/// The 2D tile-baking shader for the given constants, [`bake_constants`] and
/// [`bake2_constants`] (entry points `vs_bake`, `fs_bake_spectrum`, `fs_bake_rows_inner`,
/// `fs_bake_rows`, `fs_bake_cols_inner`, `fs_bake_tile`).
pub fn bake_shader(constants: &str) -> String {
    [constants, HASH, BAKE, BAKE2].join("\n")
}

/// The 3D tile-baking shader for the given constants (entry points `vs_bake`,
/// `fs_bake3_down_x`, `fs_bake3_down_y`, `fs_bake3_down_z`, `fs_bake3_tile`), every volume a
/// slice atlas ([`ATLAS3`]).
pub fn bake3_shader(constants: &str) -> String {
    [constants, HASH, BAKE, ATLAS3, BAKE3].join("\n")
}

/// The plane view reading the 3D tile from a baked atlas, as exported solid textures do.
pub fn plane_atlas_shader() -> String {
    [&[PARAMS, ATLAS3, TILE3_ATLAS][..], &SHADING, &[PLANE]]
        .concat()
        .join("\n")
}

/// The solid view shader (entry points `vs_solid`, `fs_solid`).
pub fn solid_shader() -> String {
    [texture_library().as_str(), SOLID_CAMERA, SOLID].join("\n")
}

/// The solid view of a raster volume (entry points `vs_solid`, `fs_solid_volume`): the camera
/// alone, no texture library.
pub fn solid_volume_shader() -> String {
    [SOLID_CAMERA, SOLID_VOLUME].join("\n")
}

/// The GLSL ES 3.00 twins of the texture library and the bake passes, for exported GLSL
/// snippets (`proctex::export::glsl`). Same functions, names and operation order as the WGSL
/// (where GLSL reserves a name the twin says so); compiled by glslang and WebGL2 in tests.
pub mod glsl {
    /// `struct Params` (the export defines `params` as a constant of it).
    pub const PARAMS: &str = include_str!("../glsl/params.glsl");
    /// Wavelet noise (`noise2`, or `noise3` under `PROCTEX_SOLID`, reading [`TILE3_ATLAS`])
    /// and band clamping.
    pub const NOISE: &str = include_str!("../glsl/noise.glsl");
    /// Histogram matching.
    pub const HISTOGRAM: &str = include_str!("../glsl/histogram.glsl");
    /// The texture at a point (`shade`).
    pub const TEXTURE: &str = include_str!("../glsl/texture.glsl");
    /// The one hash (display shader and bake passes alike).
    pub const HASH: &str = include_str!("../glsl/hash.glsl");
    /// Structured models: pattern and colour ramp.
    pub const PATTERN: &str = include_str!("../glsl/pattern.glsl");
    /// What the tile bakes share (hashes, Gaussian values, filters).
    pub const BAKE: &str = include_str!("../glsl/bake.glsl");
    /// The 2D tile's bake passes (`PROCTEX_PASS` 1 to 5).
    pub const BAKE2: &str = include_str!("../glsl/bake2.glsl");
    /// The 3D tile's bake passes into slice atlases (`PROCTEX_PASS` 1, 2, 3, 4).
    pub const BAKE3: &str = include_str!("../glsl/bake3.glsl");
    /// A volume as a 2D atlas of its slices.
    pub const ATLAS3: &str = include_str!("../glsl/atlas3.glsl");
    /// The 3D tile of exported solid textures (`tile3_side`, `tile3_texel` on an atlas).
    pub const TILE3_ATLAS: &str = include_str!("../glsl/tile3_atlas.glsl");

    /// Morphing with t as a uniform (exported morphs).
    pub const MORPH: &str = include_str!("../glsl/morph.glsl");

    /// Every GLSL file: (name, source, its WGSL twin).
    pub const FILES: [(&str, &str, &str); 12] = [
        ("hash.glsl", HASH, super::HASH),
        ("pattern.glsl", PATTERN, super::PATTERN),
        ("morph.glsl", MORPH, super::MORPH),
        ("params.glsl", PARAMS, super::PARAMS),
        ("noise.glsl", NOISE, super::NOISE),
        ("histogram.glsl", HISTOGRAM, super::HISTOGRAM),
        ("texture.glsl", TEXTURE, super::TEXTURE),
        ("bake.glsl", BAKE, super::BAKE),
        ("bake2.glsl", BAKE2, super::BAKE2),
        ("bake3.glsl", BAKE3, super::BAKE3),
        ("atlas3.glsl", ATLAS3, super::ATLAS3),
        ("tile3_atlas.glsl", TILE3_ATLAS, super::TILE3_ATLAS),
    ];

    /// [`super::bake2_constants`] in GLSL.
    pub fn bake2_constants(profile: &[f64]) -> String {
        format!(
            "const float TILE_PROFILE[{}] = float[{}]({});\n",
            profile.len(),
            profile.len(),
            super::float_list(profile)
        )
    }

    /// [`super::bake_constants`] in GLSL.
    pub fn bake_constants(
        n: u32,
        seed: u32,
        stream: u32,
        mean: [f64; 3],
        inv_sd: [f64; 3],
    ) -> String {
        let v3 = |v: [f64; 3]| {
            format!(
                "vec3({:?}, {:?}, {:?})",
                v[0] as f32, v[1] as f32, v[2] as f32
            )
        };
        format!(
            "const uint N = {n}u;\nconst uint TILE_SEED = {seed}u;\nconst uint TILE_STREAM = {stream}u;\n\
             const uint TILE_ODD_OFFSET = {}u;\nconst vec3 TILE_MEAN = {};\n\
             const vec3 TILE_INV_SD = {};\n",
            super::odd_offset(n),
            v3(mean),
            v3(inv_sd)
        )
    }
}

/// The odd shift of the even/odd fix (`noise::Tile::generate`): n/2, made odd.
fn odd_offset(n: u32) -> u32 {
    let offset = n / 2;
    if offset.is_multiple_of(2) {
        offset + 1
    } else {
        offset
    }
}

/// Every WGSL file: (name, source).
pub const FILES: [(&str, &str); 19] = [
    ("hash.wgsl", HASH),
    ("pattern.wgsl", PATTERN),
    ("params.wgsl", PARAMS),
    ("morph.wgsl", MORPH),
    ("tile3.wgsl", TILE3),
    ("tile3_atlas.wgsl", TILE3_ATLAS),
    ("atlas3.wgsl", ATLAS3),
    ("bake2.wgsl", BAKE2),
    ("bake3.wgsl", BAKE3),
    ("noise.wgsl", NOISE),
    ("histogram.wgsl", HISTOGRAM),
    ("texture.wgsl", TEXTURE),
    ("plane.wgsl", PLANE),
    ("solid_camera.wgsl", SOLID_CAMERA),
    ("solid.wgsl", SOLID),
    ("solid_volume.wgsl", SOLID_VOLUME),
    ("bake.wgsl", BAKE),
    ("seamless.wgsl", SEAMLESS),
    ("view_copy.wgsl", VIEW_COPY),
];

/// Every complete shader: (name, source).
pub fn shaders() -> Vec<(&'static str, String)> {
    vec![
        ("plane", plane_shader()),
        ("solid", solid_shader()),
        ("solid_volume", solid_volume_shader()),
        ("view_copy", VIEW_COPY.to_string()),
        ("seamless", seamless_shader()),
        (
            "bake",
            bake_shader(&format!(
                "{}{}",
                bake_constants(128, 1, 0x7431_3244, [0.01; 3], [1.9; 3]),
                bake2_constants(&[1.0; 65])
            )),
        ),
        (
            "bake3",
            bake3_shader(&bake_constants(64, 1, 0x7433_3344, [0.01; 3], [1.9; 3])),
        ),
        ("plane_atlas", plane_atlas_shader()),
        (
            "morph",
            [
                &[
                    params_private(None).as_str(),
                    "const MORPH_SEGMENT_COUNT: u32 = 1u;\n\
                     const MORPH_SEGMENTS = array<MorphSegment, 1>(MorphSegment());\n\
                     const MORPH_ENDS = array<Params, 2>(Params(), Params());\n\
                     const MORPH_OFFSETS = array<vec4<f32>, 12>();\n\
                     const MORPH_SEED: u32 = 1u;\n\
                     const MORPH_PATTERN_OFFSETS = array<vec4<f32>, 5>();\n\
                     fn morph_segment(i: u32) -> MorphSegment { return MORPH_SEGMENTS[0]; }\n\
                     fn morph_end(i: u32) -> Params { return MORPH_ENDS[min(i, 1u)]; }",
                    MORPH,
                    ATLAS3,
                    TILE3_ATLAS,
                ][..],
                &SHADING,
                &[PLANE],
            ]
            .concat()
            .join("\n"),
        ),
    ]
}
