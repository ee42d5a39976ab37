// The 2D plane view: a full-screen triangle; each pixel shows the texture at its world position.
// CPU twin: analyzer/src/render.rs render_prepared (pixel centre → world, one footprint per view).

struct View {
    // world coordinates of the top-left corner of pixel (0, 0)
    origin: vec2<f32>,
    // world units per pixel
    pixel_size: f32,
    // world z of the slice (solid textures)
    z: f32,
    // framebuffer position (pixels) of the view's top-left corner: the view may be a rectangle
    // inside a larger target (the app's canvas); 0 when the target is the view
    frame_offset: vec2<f32>,
    unused: vec2<f32>,
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
    // frag.xy is the pixel centre (x + 0.5, y + 0.5) in the target, y down: as the CPU
    // renderer once the view's own offset is removed.
    let world = vec3<f32>(view.origin + (frag.xy - view.frame_offset) * view.pixel_size, view.z);
    let log2_fp = log2(view.pixel_size * params.transform.x);
    return vec4<f32>(shade(world, log2_fp), 1.0);
}

// The trivial shader: the mean colour. Benchmarks use its frame time as the baseline.
@fragment
fn fs_flat(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(params.mean.xyz, 1.0);
}
