// The solid view of a raster volume (the Heeger–Bergen solid texture): the sphere or cube of
// solid_camera.wgsl coloured by the volume at the hit point, trilinear and wrapping (the
// volume tiles along its three axes), lit as the procedural solid is.
// Twins: analyzer/src/solid.rs (volume_voxel, volume_trilinear, volume_pixel; the entry
// point's twin is render_solid_volume). Same operation order, f32.

struct SolidVolume {
    // voxels per world unit, unused ×3
    scale: vec4<f32>,
}

// RGBA8 voxels, read with textureLoad (the interpolation is ours, so the CPU twin matches it).
@group(0) @binding(0) var volume: texture_3d<f32>;
@group(0) @binding(1) var<uniform> solid_volume: SolidVolume;

// The voxel at integer coordinates `i`, wrapped into the volume.
fn volume_voxel(i: vec3<i32>) -> vec3<f32> {
    let n = vec3<i32>(textureDimensions(volume));
    let w = ((i % n) + n) % n;
    return textureLoad(volume, w, 0).rgb;
}

// Trilinear interpolation at `q` (voxel units; voxel `i` has its centre at i + 0.5).
fn volume_trilinear(q: vec3<f32>) -> vec3<f32> {
    let f = q - 0.5;
    let base = floor(f);
    let t = f - base;
    let i = vec3<i32>(base);
    let c000 = volume_voxel(i);
    let c100 = volume_voxel(i + vec3<i32>(1, 0, 0));
    let c010 = volume_voxel(i + vec3<i32>(0, 1, 0));
    let c110 = volume_voxel(i + vec3<i32>(1, 1, 0));
    let c001 = volume_voxel(i + vec3<i32>(0, 0, 1));
    let c101 = volume_voxel(i + vec3<i32>(1, 0, 1));
    let c011 = volume_voxel(i + vec3<i32>(0, 1, 1));
    let c111 = volume_voxel(i + vec3<i32>(1, 1, 1));
    let x00 = c000 * (1.0 - t.x) + c100 * t.x;
    let x10 = c010 * (1.0 - t.x) + c110 * t.x;
    let x01 = c001 * (1.0 - t.x) + c101 * t.x;
    let x11 = c011 * (1.0 - t.x) + c111 * t.x;
    let y0 = x00 * (1.0 - t.y) + x10 * t.y;
    let y1 = x01 * (1.0 - t.y) + x11 * t.y;
    return y0 * (1.0 - t.z) + y1 * t.z;
}

fn volume_pixel(pix: vec2<f32>) -> vec3<f32> {
    let hit = solid_hit(pix);
    if (hit.t < 0.0) {
        return BACKGROUND;
    }
    let radius = solid.up.w;
    let rgb = volume_trilinear(hit.p * radius * solid_volume.scale.x);
    let k = 0.55 + 0.45 * max(dot(hit.n, solid.light.xyz), 0.0);
    return rgb * k;
}

@fragment
fn fs_solid_volume(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(volume_pixel(frag.xy - solid.frame.xy), 1.0);
}
