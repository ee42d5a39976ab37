//! The host-facing text of the exported shaders: the header notes that tell a host how to
//! bake the tile and draw (plane, solid, morph; WGSL and GLSL), and the entry points.

/// "W x H" of a bake target.
fn atlas_size(w: u32, h: u32, times: &str) -> String {
    format!("{w} {times} {h}")
}

pub(super) fn glsl_host_notes_plane(n: u32) -> String {
    format!(
        "\
// Proctex texture, exported by `proctex export --format glsl` (params format proctex/1).
// GLSL ES 3.00 (WebGL2). For desktop GLSL, replace the first line with `#version 330 core`.
// This one text is seven programs' shaders: insert one line after `#version` to pick the stage.
//   `#define PROCTEX_VERTEX`  the vertex shader of every program: a full-screen triangle,
//                             drawArrays(TRIANGLES, 0, 3) with no attributes;
//   `#define PROCTEX_PASS 1`  bake pass 1 into an RGBA32F target A of {n} x {n}, no textures;
//   `#define PROCTEX_PASS 2`  bake pass 2 into an RGBA32F target B of {n} x {n}, A bound to the
//                             sampler `proctex_bake_src`;
//   `#define PROCTEX_PASS 3`  bake pass 3 into A, B bound to `proctex_bake_src`;
//   `#define PROCTEX_PASS 4`  bake pass 4 into B, A bound to `proctex_bake_src`;
//   `#define PROCTEX_PASS 5`  bake pass 5 into an RGBA32F target T of {n} x {n}, B bound to
//                             `proctex_bake_src`;
//   nothing                   the texture: T bound to `proctex_tile2`, one world unit (one photo
//                             pixel) per screen pixel, y down from the top of a viewport
//                             `proctex_height` pixels high; or call `proctex(p, pixel_size)`
//                             from your own shader (p in world units).
// Bake once (rendering into RGBA32F needs EXT_color_buffer_float in WebGL2); textures are read
// with texelFetch, so NEAREST filtering and no mipmaps."
    )
}

pub(super) fn glsl_host_notes_solid(n: u32) -> String {
    format!(
        "\
// Proctex solid (3D) texture, exported by `proctex export --format glsl` (params format
// proctex/1). GLSL ES 3.00 (WebGL2). For desktop GLSL, replace the first line with
// `#version 330 core`. This one text is six programs' shaders: insert one line after `#version`
// to pick the stage.
//   `#define PROCTEX_VERTEX`  the vertex shader of every program: a full-screen triangle,
//                             drawArrays(TRIANGLES, 0, 3) with no attributes;
//   `#define PROCTEX_PASS 1`  bake pass 1 into an RGBA32F target A of {a}, no textures;
//   `#define PROCTEX_PASS 2`  bake pass 2 into an RGBA32F target B of {b}, A bound to the sampler
//                             `proctex_bake_src`;
//   `#define PROCTEX_PASS 3`  bake pass 3 into an RGBA32F target C of {b}, B bound to
//                             `proctex_bake_src`;
//   `#define PROCTEX_PASS 4`  bake pass 4 into an RGBA32F target T of {t}, C bound to
//                             `proctex_bake_src`;
//   nothing                   the texture: T bound to `proctex_tile3`; shows the z = 0 slice at
//                             one world unit (one photo pixel) per screen pixel, y down from the
//                             top of a viewport `proctex_height` pixels high. Or call
//                             `proctex3(p, pixel_size)` (p a 3D point in world units) or
//                             `proctex(p, pixel_size)` (the z = 0 plane) from your own shader.
// The targets are 2D atlases of the {n}^3 noise tile's slices (8 slices per row). Bake once
// (rendering into RGBA32F needs EXT_color_buffer_float in WebGL2); textures are read with
// texelFetch, so NEAREST filtering and no mipmaps.",
        a = atlas_size(4 * n, n * n / 8, "x"),
        b = atlas_size(8 * n, n * n / 16, "x"),
        t = atlas_size(8 * n, n * n / 8, "x"),
    )
}

pub(super) const GLSL_VERTEX: &str = "\
void main() {
    float x = float((gl_VertexID & 1) * 4 - 1);
    float y = float((gl_VertexID >> 1) * 4 - 1);
    gl_Position = vec4(x, y, 0.0, 1.0);
}";

pub(super) fn wgsl_host_notes_plane(n: u32) -> String {
    format!(
        "\
// Proctex texture, exported by `proctex export --format wgsl` (params format proctex/1).
// Host, once: make three rgba32float render targets A, B and T, each {n} × {n}, and draw a
// full-screen triangle (3 vertices, no buffers) with `vs_bake` and, in order,
//   fs_bake_spectrum   into A, no bindings;
//   fs_bake_rows_inner into B, A bound at @group(0) @binding(0);
//   fs_bake_rows       into A, B bound at @group(0) @binding(0);
//   fs_bake_cols_inner into B, A bound at @group(0) @binding(0);
//   fs_bake_tile       into T, B bound at @group(0) @binding(0).
// Then draw with `vs_main`/`fs_main` (one world unit = one photo pixel per screen pixel), T at
// @group(0) @binding(1) and @binding(2); or call `proctex(p, pixel_size)` from your own
// fragment shader (p in world units).
// Textures are read with textureLoad (unfilterable float is enough)."
    )
}

pub(super) fn wgsl_host_notes_solid(n: u32) -> String {
    format!(
        "\
// Proctex solid (3D) texture, exported by `proctex export --format wgsl` (params format
// proctex/1). Host, once: make four rgba32float render targets and draw a full-screen triangle
// (3 vertices, no buffers) into each with `vs_bake` and, in order,
//   fs_bake3_down_x into A ({a}), no bindings;
//   fs_bake3_down_y into B ({b}), A bound at @group(0) @binding(0);
//   fs_bake3_down_z into C ({b}), B bound at @group(0) @binding(0);
//   fs_bake3_tile   into T ({t}), C bound at @group(0) @binding(0).
// (2D atlases of the {n}³ noise tile's slices, 8 slices per row.) Then draw with
// `vs_main`/`fs_main` (the z = 0 slice, one world unit = one photo pixel per screen pixel), T at
// @group(0) @binding(1) and @binding(2); or call `proctex3(p, pixel_size)` (p a 3D point in
// world units) or `proctex(p, pixel_size)` (the z = 0 plane) from your own fragment shader.
// Textures are read with textureLoad (unfilterable float is enough).",
        a = atlas_size(4 * n, n * n / 8, "×"),
        b = atlas_size(8 * n, n * n / 16, "×"),
        t = atlas_size(8 * n, n * n / 8, "×"),
    )
}

pub(super) const WGSL_MORPH_NOTES: &str = "\
// A morph with t as a uniform: fs_main reads t from a 16-byte uniform buffer at @group(0)
// @binding(3) (t in its first f32: 0 the first texture, 1 the last); your own shader calls
// `proctex(p, pixel_size, t)`, which rebuilds the params of t (a few hundred flops) and shades.";

pub(super) const GLSL_MORPH_NOTES: &str = "\
// A morph with t as a uniform: set `uniform float proctex_t` (0 the first texture, 1 the last)
// for the display program; your own shader calls `proctex(p, pixel_size, t)`, which rebuilds
// the params of t (a few hundred flops) and shades.";

/// The snippet's public functions and the full-screen entry point, in WGSL.
pub(super) fn wgsl_entry(solid: bool, morph: bool) -> String {
    let (t_param, t_arg, set, t_uniform) = if morph {
        (
            ", t: f32",
            ", t",
            "    params = morph_params(t);\n",
            ", proctex_t.x",
        )
    } else {
        ("", "", "", "")
    };
    let of_t = if morph { " at morph t" } else { "" };
    let mut out = String::new();
    if morph {
        out += "\n// The morph's t in x (0: the first texture, 1: the last).\n\
                @group(0) @binding(3) var<uniform> proctex_t: vec4<f32>;\n";
    }
    if solid {
        out += &format!(
            "\n// The solid texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             fn proctex3(p: vec3<f32>, pixel_size: f32{t_param}) -> vec3<f32> {{\n{set}\
             \x20   return shade(p, log2(pixel_size * params.transform.x));\n}}\n\n\
             // Its z = 0 plane.\n\
             fn proctex(p: vec2<f32>, pixel_size: f32{t_param}) -> vec3<f32> {{\n\
             \x20   return proctex3(vec3<f32>(p, 0.0), pixel_size{t_arg});\n}}\n"
        );
    } else {
        out += &format!(
            "\n// The texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             fn proctex(p: vec2<f32>, pixel_size: f32{t_param}) -> vec3<f32> {{\n{set}\
             \x20   return shade(vec3<f32>(p, 0.0), log2(pixel_size * params.transform.x));\n}}\n"
        );
    }
    out += &format!(
        "
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {{
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {{
    return vec4<f32>(proctex(frag.xy, 1.0{t_uniform}), 1.0);
}}
"
    );
    out
}

/// The snippet's public functions and the display program's `main`, in GLSL.
pub(super) fn glsl_entry(solid: bool, morph: bool) -> String {
    let (t_param, t_arg, set, t_uniform) = if morph {
        (
            ", float t",
            ", t",
            "    params = morph_params(t);\n",
            ", proctex_t",
        )
    } else {
        ("", "", "", "")
    };
    let of_t = if morph { " at morph t" } else { "" };
    let mut out = String::new();
    if solid {
        out += &format!(
            "\n// The solid texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             vec3 proctex3(vec3 p, float pixel_size{t_param}) {{\n{set}\
             \x20   return shade(p, log2(pixel_size * params.transform.x));\n}}\n\n\
             // Its z = 0 plane.\n\
             vec3 proctex(vec2 p, float pixel_size{t_param}) {{\n\
             \x20   return proctex3(vec3(p, 0.0), pixel_size{t_arg});\n}}\n"
        );
    } else {
        out += &format!(
            "\n// The texture{of_t} at world point p (photo pixels) for a pixel footprint of\n\
             // pixel_size units.\n\
             vec3 proctex(vec2 p, float pixel_size{t_param}) {{\n{set}\
             \x20   return shade(vec3(p, 0.0), log2(pixel_size * params.transform.x));\n}}\n"
        );
    }
    if morph {
        out +=
            "\n// The morph's t (0: the first texture, 1: the last).\nuniform float proctex_t;\n";
    }
    out += &format!(
        "
// Viewport height in pixels: world y grows downwards from the top of the viewport, as in the
// app and the WGSL export (0 if unset: the texture still shows, shifted).
uniform float proctex_height;
layout(location = 0) out vec4 proctex_out;

void main() {{
    vec2 p = vec2(gl_FragCoord.x, proctex_height - gl_FragCoord.y);
    proctex_out = vec4(proctex(p, 1.0{t_uniform}), 1.0);
}}"
    );
    out
}
