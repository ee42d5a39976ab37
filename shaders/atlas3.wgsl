// A volume stored as a 2D atlas of its z slices (exported solid textures: every host can render
// into and read a 2D rgba32float texture; rendering into a 3D texture takes one pass per slice and
// WebGL2 cannot do it in one draw). Slice z of a volume whose slices are `size` texels lies at
// column z % 8, row z / 8 of the atlas, so the 64³ tile is a 512 × 512 texture (within WebGL2's
// guaranteed 2048). Twins: analyzer/src/noise.rs (atlas_texel, atlas_voxel).

const ATLAS_COLUMNS: i32 = 8;

// The atlas texel of voxel c.
fn atlas_texel(c: vec3<i32>, size: vec2<i32>) -> vec2<i32> {
    return vec2<i32>(
        c.x + size.x * (c.z % ATLAS_COLUMNS),
        c.y + size.y * (c.z / ATLAS_COLUMNS),
    );
}

// The voxel at atlas texel t.
fn atlas_voxel(t: vec2<i32>, size: vec2<i32>) -> vec3<i32> {
    let col = t.x / size.x;
    let row = t.y / size.y;
    return vec3<i32>(t.x - col * size.x, t.y - row * size.y, col + ATLAS_COLUMNS * row);
}
