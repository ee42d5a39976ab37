// The solid views' camera: an orbit camera around a sphere or a cube, the ray through a pixel
// and where it enters the object. Shared by the procedural solid (solid.wgsl) and the raster
// volume (solid_volume.wgsl).
// Twins: analyzer/src/solid.rs (ray_sphere, ray_box, solid_hit; vs_solid's twin is
// render_solid). Same operation order, f32.

struct SolidView {
    // eye position (object space), shape (0 sphere, 1 cube)
    eye: vec4<f32>,
    // camera right, tan(fov / 2)
    right: vec4<f32>,
    // camera up, world units per object unit
    up: vec4<f32>,
    // camera forward, unused
    forward: vec4<f32>,
    // direction to the light, unused
    light: vec4<f32>,
    // framebuffer position of the viewport's top-left pixel, viewport size
    frame: vec4<f32>,
}

@group(1) @binding(0) var<uniform> solid: SolidView;

const BACKGROUND: vec3<f32> = vec3<f32>(0.11, 0.11, 0.11);

fn ray_sphere(o: vec3<f32>, d: vec3<f32>) -> f32 {
    let b = dot(o, d);
    let c = dot(o, o) - 1.0;
    let disc = b * b - c;
    if (disc < 0.0) {
        return -1.0;
    }
    let t = -b - sqrt(disc);
    if (t < 0.0) {
        return -1.0;
    }
    return t;
}

// xyz: normal of the entered face, w: distance (-1: miss).
fn ray_box(o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    var t_near = -1e30;
    var t_far = 1e30;
    var n = vec3<f32>(0.0);
    for (var a = 0; a < 3; a++) {
        let inv = 1.0 / d[a];
        let t0 = (-1.0 - o[a]) * inv;
        let t1 = (1.0 - o[a]) * inv;
        let lo = min(t0, t1);
        let hi = max(t0, t1);
        if (lo > t_near) {
            t_near = lo;
            n = vec3<f32>(0.0);
            n[a] = select(1.0, -1.0, d[a] > 0.0);
        }
        t_far = min(t_far, hi);
    }
    if (t_near > t_far || t_near < 0.0) {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    return vec4<f32>(n, t_near);
}

// Where the ray through a viewport pixel enters the object.
struct SolidHit {
    // the point (object space)
    p: vec3<f32>,
    // the unit normal there
    n: vec3<f32>,
    // the unit ray direction
    d: vec3<f32>,
    // distance from the eye (-1: the ray misses)
    t: f32,
}

fn solid_hit(pix: vec2<f32>) -> SolidHit {
    let size = solid.frame.zw;
    let ndc = vec2<f32>(pix.x / size.x * 2.0 - 1.0, 1.0 - pix.y / size.y * 2.0);
    let aspect = size.x / size.y;
    let sx = ndc.x * solid.right.w * aspect;
    let sy = ndc.y * solid.right.w;
    let d = normalize(solid.forward.xyz + sx * solid.right.xyz + sy * solid.up.xyz);
    let eye = solid.eye.xyz;
    var n: vec3<f32>;
    var t: f32;
    if (solid.eye.w == 0.0) {
        t = ray_sphere(eye, d);
        n = eye + t * d;
    } else {
        let hit = ray_box(eye, d);
        n = hit.xyz;
        t = hit.w;
    }
    if (t < 0.0) {
        return SolidHit(vec3<f32>(0.0), vec3<f32>(0.0), d, -1.0);
    }
    return SolidHit(eye + t * d, normalize(n), d, t);
}

@vertex
fn vs_solid(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}
