//! Every WGSL source of Proctex, and the complete shaders composed from them.
//!
//! WGSL has no `#include`; modules are concatenated in a fixed order. Each WGSL function has a
//! Rust twin in the analyzer (the CPU reference renderer); `tests/twins.rs` checks that every
//! function here names one, `tests/validate.rs` validates every composed shader with naga, and
//! `tests/gpu_vs_cpu.rs` renders on a real (or software) GPU and compares with
//! `proctex::render::render`.

/// Uniform block layout and bindings of the texture parameters.
pub const PARAMS: &str = include_str!("../params.wgsl");
/// Wavelet noise evaluation and band clamping.
pub const NOISE: &str = include_str!("../noise.wgsl");
/// Histogram matching.
pub const HISTOGRAM: &str = include_str!("../histogram.wgsl");
/// The texture at a point (`shade`).
pub const TEXTURE: &str = include_str!("../texture.wgsl");
/// The 2D plane view (full-screen triangle) and the trivial baseline shader `fs_flat`.
pub const PLANE: &str = include_str!("../plane.wgsl");
/// The solid view: sphere or cube of the 3D texture, orbit camera.
pub const SOLID: &str = include_str!("../solid.wgsl");

/// The library every view shader starts with: params, noise, histogram, texture.
pub fn texture_library() -> String {
    [PARAMS, NOISE, HISTOGRAM, TEXTURE].join("\n")
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

/// Baking the noise tile from the seed on the GPU (exported snippets).
pub const BAKE: &str = include_str!("../bake.wgsl");

/// The constants `bake.wgsl` needs: tile side, hash seed and stream, the odd shift of the
/// even/odd fix, and the CPU-measured normalisation (`noise::Tile::stats`).
pub fn bake_constants(n: u32, seed: u32, stream: u32, mean: f64, inv_sd: f64) -> String {
    let offset = odd_offset(n);
    format!(
        "const N: u32 = {n}u;\nconst TILE_SEED: u32 = {seed}u;\nconst TILE_STREAM: u32 = {stream}u;\n\
         const TILE_ODD_OFFSET: u32 = {offset}u;\nconst TILE_MEAN: f32 = {:?};\n\
         const TILE_INV_SD: f32 = {:?};\n",
        mean as f32, inv_sd as f32
    )
}

/// The tile-baking shader for the given constants (entry points `vs_bake`, `fs_bake_down_x`,
/// `fs_bake_down_y`, `fs_bake_tile`).
pub fn bake_shader(constants: &str) -> String {
    [constants, BAKE].join("\n")
}

/// The solid view shader (entry points `vs_solid`, `fs_solid`).
pub fn solid_shader() -> String {
    [texture_library().as_str(), SOLID].join("\n")
}

/// The GLSL ES 3.00 twins of the texture library and the bake passes, for exported GLSL
/// snippets (`proctex::export::glsl`). Same functions, names and operation order as the WGSL
/// (where GLSL reserves a name the twin says so); compiled by glslang and WebGL2 in tests.
pub mod glsl {
    /// `struct Params` (the export defines `params` as a constant of it).
    pub const PARAMS: &str = include_str!("../glsl/params.glsl");
    /// Wavelet noise (`noise2`, or `noise3` under `PROCTEX_SOLID`) and band clamping.
    pub const NOISE: &str = include_str!("../glsl/noise.glsl");
    /// Histogram matching.
    pub const HISTOGRAM: &str = include_str!("../glsl/histogram.glsl");
    /// The texture at a point (`shade`).
    pub const TEXTURE: &str = include_str!("../glsl/texture.glsl");
    /// The tile bake passes (`PROCTEX_PASS` 1, 2, 3).
    pub const BAKE: &str = include_str!("../glsl/bake.glsl");

    /// Every GLSL file: (name, source, its WGSL twin).
    pub const FILES: [(&str, &str, &str); 5] = [
        ("params.glsl", PARAMS, super::PARAMS),
        ("noise.glsl", NOISE, super::NOISE),
        ("histogram.glsl", HISTOGRAM, super::HISTOGRAM),
        ("texture.glsl", TEXTURE, super::TEXTURE),
        ("bake.glsl", BAKE, super::BAKE),
    ];

    /// [`super::bake_constants`] in GLSL.
    pub fn bake_constants(n: u32, seed: u32, stream: u32, mean: f64, inv_sd: f64) -> String {
        format!(
            "const uint N = {n}u;\nconst uint TILE_SEED = {seed}u;\nconst uint TILE_STREAM = {stream}u;\n\
             const uint TILE_ODD_OFFSET = {}u;\nconst float TILE_MEAN = {:?};\n\
             const float TILE_INV_SD = {:?};\n",
            super::odd_offset(n),
            mean as f32,
            inv_sd as f32
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
pub const FILES: [(&str, &str); 8] = [
    ("params.wgsl", PARAMS),
    ("noise.wgsl", NOISE),
    ("histogram.wgsl", HISTOGRAM),
    ("texture.wgsl", TEXTURE),
    ("plane.wgsl", PLANE),
    ("solid.wgsl", SOLID),
    ("bake.wgsl", BAKE),
    ("seamless.wgsl", SEAMLESS),
];

/// Every complete shader: (name, source).
pub fn shaders() -> Vec<(&'static str, String)> {
    vec![
        ("plane", plane_shader()),
        ("solid", solid_shader()),
        ("seamless", seamless_shader()),
        (
            "bake",
            bake_shader(&bake_constants(128, 1, 0x7431_3244, 0.01, 1.9)),
        ),
    ]
}
