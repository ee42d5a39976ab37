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

/// The solid view shader (entry points `vs_solid`, `fs_solid`).
pub fn solid_shader() -> String {
    [texture_library().as_str(), SOLID].join("\n")
}

/// Every WGSL file: (name, source).
pub const FILES: [(&str, &str); 6] = [
    ("params.wgsl", PARAMS),
    ("noise.wgsl", NOISE),
    ("histogram.wgsl", HISTOGRAM),
    ("texture.wgsl", TEXTURE),
    ("plane.wgsl", PLANE),
    ("solid.wgsl", SOLID),
];

/// Every complete shader: (name, source).
pub fn shaders() -> Vec<(&'static str, String)> {
    vec![("plane", plane_shader()), ("solid", solid_shader())]
}
