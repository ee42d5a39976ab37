// The 2D plane view: a full-screen triangle; each pixel shows the texture at its world position.
// CPU twin: analyzer/src/render.rs render_prepared (pixel centre → world, one footprint per view).

struct View {
    // world coordinates of the top-left corner of pixel (0, 0)
    origin: vec2<f32>,
    // world units per pixel
    pixel_size: f32,
    // world z of the slice (solid textures)
    z: f32,
}

@group(1) @binding(0) var<uniform> view: View;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    // frag.xy is the pixel centre (x + 0.5, y + 0.5), y down: as the CPU renderer.
    let world = vec3<f32>(view.origin + frag.xy * view.pixel_size, view.z);
    let log2_fp = log2(view.pixel_size * params.transform.x);
    return vec4<f32>(shade(world, log2_fp), 1.0);
}
