// The texture view's frame cache copied to the canvas, pixel for pixel (textureLoad: no
// filtering, no blending), so that the canvas shows exactly what the texture shader rendered
// into the cache. Rust twin: web/src/view_cache.rs.

struct ViewCopy {
    // framebuffer position (pixels) of the cache's pixel (0, 0)
    offset: vec2<i32>,
    // the cache's size in pixels
    size: vec2<i32>,
}

@group(0) @binding(0) var cached: texture_2d<f32>;
@group(0) @binding(1) var<uniform> view_copy: ViewCopy;

@vertex
fn vs_copy(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

// The cache pixel that framebuffer pixel `frame` shows: the same pixel of the view, clamped to
// the cache (egui may clip the view a pixel wider than its rounded rectangle).
fn cached_pixel(frame: vec2<i32>, offset: vec2<i32>, size: vec2<i32>) -> vec2<i32> {
    return clamp(frame - offset, vec2<i32>(0, 0), size - vec2<i32>(1, 1));
}

@fragment
fn fs_copy(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let p = cached_pixel(vec2<i32>(floor(frag.xy)), view_copy.offset, view_copy.size);
    return textureLoad(cached, p, 0);
}
