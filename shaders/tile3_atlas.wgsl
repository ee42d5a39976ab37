// The 3D wavelet-noise tile of exported solid textures: a 2D atlas of its slices (atlas3.wgsl),
// baked by bake3.wgsl. Same functions as tile3.wgsl, which the app uses. Twins:
// analyzer/src/noise.rs (tile3_side, tile3_texel).

@group(0) @binding(2) var tile3: texture_2d<f32>;

fn tile3_side() -> i32 {
    return i32(textureDimensions(tile3).x) / ATLAS_COLUMNS;
}

fn tile3_texel(c: vec3<i32>) -> vec3<f32> {
    let n = tile3_side();
    return textureLoad(tile3, atlas_texel(c, vec2<i32>(n, n)), 0).xyz;
}
