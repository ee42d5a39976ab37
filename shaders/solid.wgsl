// The solid view of the procedural texture: the sphere or cube of solid_camera.wgsl shaded by
// the 3D texture at the hit point.
// Twins: analyzer/src/solid.rs (solid_pixel; the entry point's twin is render_solid). Same
// operation order, f32.

fn solid_pixel(pix: vec2<f32>) -> vec3<f32> {
    let hit = solid_hit(pix);
    if (hit.t < 0.0) {
        return BACKGROUND;
    }
    let size = solid.frame.zw;
    let cos_i = max(abs(dot(hit.n, hit.d)), 0.25);
    let radius = solid.up.w;
    let footprint = hit.t * (2.0 * solid.right.w / size.y) * radius / cos_i;
    let log2_fp = log2(footprint * params.transform.x);
    let rgb = shade(hit.p * radius, log2_fp);
    let k = 0.55 + 0.45 * max(dot(hit.n, solid.light.xyz), 0.0);
    return rgb * k;
}

@fragment
fn fs_solid(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(solid_pixel(frag.xy - solid.frame.xy), 1.0);
}
