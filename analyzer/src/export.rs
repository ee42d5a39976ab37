//! Export: the texture as a self-contained WGSL shader that renders the same image as the CPU
//! reference renderer in someone else's engine.
//!
//! The snippet is the app's own shader library (`shaders/`: noise, histogram, texture) with the
//! params baked in as a module-scope value instead of a uniform, plus `shaders/bake.wgsl`,
//! which rebuilds the 128² noise tile from the seed on the GPU (the tile itself, 16384 numbers,
//! would be too big to paste). The host runs three small bake passes once, then draws with
//! `fs_main` (or calls `proctex(p, pixel_size)` from its own shader).
//!
//! Solid (3D) textures and GLSL are not exported yet.

use crate::error::{Error, Result};
use crate::params::{MAX_BANDS, MAX_KNOTS, Params};
use crate::render::{Prepared, tile_for};
use crate::rng::stream;

/// A float as a WGSL literal (tiny values flushed to 0: WGSL rejects subnormal literals).
fn lit(v: f32) -> String {
    let v = if v.abs() < 1e-30 { 0.0 } else { v };
    format!("{v:?}")
}

fn vec4(v: [f32; 4]) -> String {
    format!(
        "vec4<f32>({}, {}, {}, {})",
        lit(v[0]),
        lit(v[1]),
        lit(v[2]),
        lit(v[3])
    )
}

fn array(rows: impl Iterator<Item = [f32; 4]>, n: usize) -> String {
    let items: Vec<String> = rows.map(|r| format!("        {}", vec4(r))).collect();
    format!("array<vec4<f32>, {n}>(\n{},\n    )", items.join(",\n"))
}

/// The params as a WGSL `Params` value (same layout as the app's uniform block).
fn params_value(p: &Prepared) -> String {
    let basis = array(p.basis.iter().map(|r| [r[0], r[1], r[2], 0.0]), 3);
    let weights = array(
        (0..MAX_BANDS).map(|j| [p.weights[0][j], p.weights[1][j], p.weights[2][j], 0.0]),
        MAX_BANDS,
    );
    let offsets = array(
        (0..3)
            .flat_map(|c| (0..MAX_BANDS).map(move |j| (c, j)))
            .map(|(c, j)| {
                let o = p.offsets[c][j];
                [o[0], o[1], o[2], 0.0]
            }),
        3 * MAX_BANDS,
    );
    let knots = array(
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
    let tangents = array(
        (0..MAX_KNOTS).map(|k| [p.tangents[0][k], p.tangents[1][k], p.tangents[2][k], 0.0]),
        MAX_KNOTS,
    );
    format!(
        "Params(\n    {},\n    {basis},\n    {},\n    vec4<u32>({}u, {}u, {}u, {}u),\n    {},\n    {weights},\n    {offsets},\n    {knots},\n    {tangents},\n)",
        vec4([p.mean[0], p.mean[1], p.mean[2], p.contrast]),
        vec4([p.inv_scale, p.rot[0], p.rot[1], 0.0]),
        p.bands,
        p.knots,
        p.solid as u32,
        p.histogram as u32,
        vec4([p.sigma[0], p.sigma[1], p.sigma[2], 0.0]),
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
        &format!("var<private> params: Params = {};", params_value(&prep)),
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
