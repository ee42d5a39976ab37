//! Export: the texture as a self-contained WGSL shader that renders the same image as the CPU
//! reference renderer in someone else's engine.
//!
//! The snippet is the app's own shader library (`shaders/`: noise, histogram, texture) with the
//! params baked in as a module-scope value instead of a uniform, plus `shaders/bake.wgsl`,
//! which rebuilds the 128² noise tile from the seed on the GPU (the tile itself, 16384 numbers,
//! would be too big to paste). The host runs three small bake passes once, then draws with
//! `fs_main` (or calls `proctex(p, pixel_size)` from its own shader).
//!
//! The GLSL snippet is the same library in GLSL ES 3.00 (`shaders/glsl/`, twins of the WGSL),
//! one text that compiles as each of the host's five shaders by a `#define` after `#version`.
//!
//! Solid (3D) textures are not exported yet.

use crate::error::{Error, Result};
use crate::params::{MAX_BANDS, MAX_KNOTS, Params};
use crate::render::{Prepared, tile_for};
use crate::rng::stream;

/// A float as a WGSL literal (tiny values flushed to 0: WGSL rejects subnormal literals).
fn lit(v: f32) -> String {
    let v = if v.abs() < 1e-30 { 0.0 } else { v };
    format!("{v:?}")
}

/// The shading language a value is written in.
#[derive(Clone, Copy)]
enum Lang {
    Wgsl,
    Glsl,
}

impl Lang {
    fn vec4(self, v: [f32; 4]) -> String {
        let ty = match self {
            Lang::Wgsl => "vec4<f32>",
            Lang::Glsl => "vec4",
        };
        format!(
            "{ty}({}, {}, {}, {})",
            lit(v[0]),
            lit(v[1]),
            lit(v[2]),
            lit(v[3])
        )
    }

    fn array(self, rows: impl Iterator<Item = [f32; 4]>, n: usize) -> String {
        let items: Vec<String> = rows.map(|r| format!("        {}", self.vec4(r))).collect();
        let ty = match self {
            Lang::Wgsl => format!("array<vec4<f32>, {n}>"),
            Lang::Glsl => format!("vec4[{n}]"),
        };
        format!("{ty}(\n{}\n    )", items.join(",\n"))
    }

    fn uvec4(self, v: [u32; 4]) -> String {
        let ty = match self {
            Lang::Wgsl => "vec4<u32>",
            Lang::Glsl => "uvec4",
        };
        format!("{ty}({}u, {}u, {}u, {}u)", v[0], v[1], v[2], v[3])
    }
}

/// The params as a `Params` value (same layout as the app's uniform block) in `lang`.
fn params_value(p: &Prepared, lang: Lang) -> String {
    let basis = lang.array(p.basis.iter().map(|r| [r[0], r[1], r[2], 0.0]), 3);
    let weights = lang.array(
        (0..MAX_BANDS).map(|j| [p.weights[0][j], p.weights[1][j], p.weights[2][j], 0.0]),
        MAX_BANDS,
    );
    let offsets = lang.array(
        (0..3)
            .flat_map(|c| (0..MAX_BANDS).map(move |j| (c, j)))
            .map(|(c, j)| {
                let o = p.offsets[c][j];
                [o[0], o[1], o[2], 0.0]
            }),
        3 * MAX_BANDS,
    );
    let knots = lang.array(
        (0..MAX_KNOTS).map(|k| {
            [
                p.knot_values[0][k],
                p.knot_values[1][k],
                p.knot_values[2][k],
                0.0,
            ]
        }),
        MAX_KNOTS,
    );
    let tangents = lang.array(
        (0..MAX_KNOTS).map(|k| [p.tangents[0][k], p.tangents[1][k], p.tangents[2][k], 0.0]),
        MAX_KNOTS,
    );
    // WGSL allows a trailing comma in a constructor; GLSL does not.
    format!(
        "Params(\n    {},\n    {basis},\n    {},\n    {},\n    {},\n    {weights},\n    {offsets},\n    {knots},\n    {tangents}\n)",
        lang.vec4([p.mean[0], p.mean[1], p.mean[2], p.contrast]),
        lang.vec4([p.inv_scale, p.rot[0], p.rot[1], 0.0]),
        lang.uvec4([p.bands, p.knots, p.solid as u32, p.histogram as u32]),
        lang.vec4([p.sigma[0], p.sigma[1], p.sigma[2], 0.0]),
    )
}

/// The complete WGSL shader of a plane texture: `proctex(p, pixel_size)`, the bake passes and
/// a minimal full-screen entry point (`vs_main`/`fs_main`, one world unit per pixel).
pub fn wgsl(params: &Params) -> Result<String> {
    if params.solid {
        return Err(Error::Option(
            "WGSL export of solid (3D) textures is not supported yet; export the plane texture"
                .into(),
        ));
    }
    let prep = Prepared::new(params);
    let tile = tile_for(params);
    let bake = proctex_shaders::bake_constants(
        tile.n as u32,
        params.seed,
        stream::TILE_2D,
        tile.stats.raw_mean,
        1.0 / tile.stats.raw_variance.sqrt(),
    );
    let header = proctex_shaders::PARAMS.replace(
        "@group(0) @binding(0) var<uniform> params: Params;",
        &format!(
            "var<private> params: Params = {};",
            params_value(&prep, Lang::Wgsl)
        ),
    );
    if header == proctex_shaders::PARAMS {
        return Err(Error::Option(
            "internal: params.wgsl no longer declares the uniform".into(),
        ));
    }
    Ok(format!(
        "{HOST_NOTES}\n{bake}\n{header}\n{noise}\n{histogram}\n{texture}\n{bakepasses}\n{ENTRY}",
        noise = proctex_shaders::NOISE,
        histogram = proctex_shaders::HISTOGRAM,
        texture = proctex_shaders::TEXTURE,
        bakepasses = proctex_shaders::BAKE,
    ))
}

/// The complete GLSL ES 3.00 shader of a plane texture: one text that compiles as the display
/// fragment shader as-is, as the full-screen vertex shader with `#define PROCTEX_VERTEX`, and
/// as bake pass 1, 2, 3 with `#define PROCTEX_PASS 1|2|3` (each define inserted after the
/// `#version` line).
pub fn glsl(params: &Params) -> Result<String> {
    if params.solid {
        return Err(Error::Option(
            "GLSL export of solid (3D) textures is not supported yet; export the plane texture"
                .into(),
        ));
    }
    let prep = Prepared::new(params);
    let tile = tile_for(params);
    let g = proctex_shaders::glsl::PARAMS;
    let bake = proctex_shaders::glsl::bake_constants(
        tile.n as u32,
        params.seed,
        stream::TILE_2D,
        tile.stats.raw_mean,
        1.0 / tile.stats.raw_variance.sqrt(),
    );
    Ok(format!(
        "#version 300 es\n{GLSL_HOST_NOTES}\n\
         precision highp float;\nprecision highp int;\nprecision highp sampler2D;\n\
         #if defined(PROCTEX_VERTEX)\n{GLSL_VERTEX}\n\
         #elif defined(PROCTEX_PASS)\n{bake}\n{bakepasses}\n\
         #else\n{g}\nconst Params params = {};\n{noise}\n{histogram}\n{texture}\n{GLSL_ENTRY}\n\
         #endif\n",
        params_value(&prep, Lang::Glsl),
        bakepasses = proctex_shaders::glsl::BAKE,
        noise = proctex_shaders::glsl::NOISE,
        histogram = proctex_shaders::glsl::HISTOGRAM,
        texture = proctex_shaders::glsl::TEXTURE,
    ))
}

const GLSL_HOST_NOTES: &str = "\
// Proctex texture, exported by `proctex export --format glsl` (params format proctex/1).
// GLSL ES 3.00 (WebGL2). For desktop GLSL, replace the first line with `#version 330 core`.
// This one text is five programs' shaders: insert one line after `#version` to pick the stage.
//   `#define PROCTEX_VERTEX`  the vertex shader of every program: a full-screen triangle,
//                             drawArrays(TRIANGLES, 0, 3) with no attributes;
//   `#define PROCTEX_PASS 1`  bake pass 1 into an R32F target A of N/2 x N (N: the tile side
//                             below), no textures;
//   `#define PROCTEX_PASS 2`  bake pass 2 into an R32F target B of N x N/2, A bound to the
//                             sampler `proctex_bake_src`;
//   `#define PROCTEX_PASS 3`  bake pass 3 into an R32F target T of N x N, B bound to
//                             `proctex_bake_src`;
//   nothing                   the texture: T bound to `proctex_tile2`, one world unit (one photo
//                             pixel) per screen pixel, y down from the top of a viewport
//                             `proctex_height` pixels high; or call `proctex(p, pixel_size)`
//                             from your own shader (p in world units).
// Bake once (rendering into R32F needs EXT_color_buffer_float in WebGL2); textures are read
// with texelFetch, so NEAREST filtering and no mipmaps.";

const GLSL_VERTEX: &str = "\
void main() {
    float x = float((gl_VertexID & 1) * 4 - 1);
    float y = float((gl_VertexID >> 1) * 4 - 1);
    gl_Position = vec4(x, y, 0.0, 1.0);
}";

const GLSL_ENTRY: &str = "
// The texture at world point p (photo pixels) for a pixel footprint of pixel_size units.
vec3 proctex(vec2 p, float pixel_size) {
    return shade(vec3(p, 0.0), log2(pixel_size * params.transform.x));
}

// Viewport height in pixels: world y grows downwards from the top of the viewport, as in the
// app and the WGSL export (0 if unset: the texture still shows, shifted).
uniform float proctex_height;
layout(location = 0) out vec4 proctex_out;

void main() {
    vec2 p = vec2(gl_FragCoord.x, proctex_height - gl_FragCoord.y);
    proctex_out = vec4(proctex(p, 1.0), 1.0);
}";

const HOST_NOTES: &str = "\
// Proctex texture, exported by `proctex export --format wgsl` (params format proctex/1).
// Host, once: make three r32float render targets and draw a full-screen triangle (3 vertices,
// no buffers) into each with `vs_bake` and, in order,
//   fs_bake_down_x into A (N/2 × N), no bindings;
//   fs_bake_down_y into B (N × N/2), A bound at @group(0) @binding(0);
//   fs_bake_tile   into T (N × N),   B bound at @group(0) @binding(0).
// Then draw with `vs_main`/`fs_main` (one world unit = one photo pixel per screen pixel), T at
// @group(0) @binding(1) and a 1×1×1 r32float 3D texture at @binding(2); or call
// `proctex(p, pixel_size)` from your own fragment shader (p in world units).
// Textures are read with textureLoad (unfilterable float is enough).";

const ENTRY: &str = "
// The texture at world point p (photo pixels) for a pixel footprint of pixel_size units.
fn proctex(p: vec2<f32>, pixel_size: f32) -> vec3<f32> {
    return shade(vec3<f32>(p, 0.0), log2(pixel_size * params.transform.x));
}

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(proctex(frag.xy, 1.0), 1.0);
}
";
