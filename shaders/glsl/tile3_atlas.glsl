// The 3D wavelet-noise tile of exported solid textures, a baked 2D atlas of its slices (GLSL
// twin of shaders/tile3_atlas.wgsl; Rust twins in analyzer/src/noise.rs).

uniform highp sampler2D proctex_tile3;

int tile3_side() {
    return textureSize(proctex_tile3, 0).x / ATLAS_COLUMNS;
}

vec3 tile3_texel(ivec3 c) {
    int n = tile3_side();
    return texelFetch(proctex_tile3, atlas_texel(c, ivec2(n, n)), 0).xyz;
}
