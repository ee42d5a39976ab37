// The 3D wavelet-noise tile of solid textures as the app binds it: an rgba32float 3D texture (its three components in RGB),
// uploaded from the CPU tile. (Exported snippets bind a baked 2D atlas instead:
// tile3_atlas.wgsl.) Twins: analyzer/src/noise.rs (tile3_side, tile3_texel).

@group(0) @binding(2) var tile3: texture_3d<f32>;

fn tile3_side() -> i32 {
    return i32(textureDimensions(tile3).x);
}

fn tile3_texel(c: vec3<i32>) -> vec3<f32> {
    return textureLoad(tile3, c, 0).xyz;
}
