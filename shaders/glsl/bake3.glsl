// Baking the 3D wavelet-noise tile of solid textures into slice atlases (GLSL twin of
// shaders/bake3.wgsl); uses bake.glsl and atlas3.glsl. `#define PROCTEX_PASS` picks the pass:
//   pass 1, A (N/2, N, N), atlas 4N x N*N/8:  R down-sampled along x
//   pass 2, B (N, N/2, N), atlas 8N x N*N/16: (A up-sampled along x) down along y, reads A
//   pass 3, C (N, N, N/2), atlas 8N x N*N/16: (B up-sampled along y) down along z, reads B
//   pass 4, T (N, N, N),   atlas 8N x N*N/8:  R - C up-sampled along z, odd shift, normalised
// (the previous pass's target bound to proctex_bake_src).

// The Gaussian coefficients R of the tile's three components at voxel (x, y, z), wrapped.
vec3 r_value3(int x, int y, int z) {
    int n = int(N);
    uint xi = uint(wrap_mod(x, n));
    uint yi = uint(wrap_mod(y, n));
    uint zi = uint(wrap_mod(z, n));
    uint i = xi + N * (yi + N * zi);
    return vec3(
        gaussian(TILE_SEED, TILE_STREAM, i),
        gaussian(TILE_SEED, TILE_STREAM, i + N * N * N),
        gaussian(TILE_SEED, TILE_STREAM, i + 2u * N * N * N));
}

// proctex_bake_src up-sampled along `axis` (which holds N/2 coarse samples there), at voxel c;
// `size` is the bound volume's slice size.
vec3 upsample3(ivec3 c, int axis, ivec2 size) {
    int halfn = int(N) / 2;
    int x = c[axis];
    vec3 s = vec3(0.0);
    for (int k = x / 2; k <= x / 2 + 1; k++) {
        ivec3 q = c;
        q[axis] = wrap_mod(k, halfn);
        s += P[x - 2 * k + 2] * texelFetch(proctex_bake_src, atlas_texel(q, size), 0).xyz;
    }
    return s;
}

vec3 band3(ivec3 c) {
    int n = int(N);
    ivec3 w = ivec3(wrap_mod(c.x, n), wrap_mod(c.y, n), wrap_mod(c.z, n));
    return r_value3(w.x, w.y, w.z) - upsample3(w, 2, ivec2(n, n));
}

// One entry per pass (twins of fs_bake3_down_x, _down_y, _down_z, fs_bake3_tile).
void main() {
    ivec2 frag = ivec2(gl_FragCoord.xy);
    int n = int(N);
    vec3 s = vec3(0.0);
#if PROCTEX_PASS == 1
    ivec3 v = atlas_voxel(frag, ivec2(n / 2, n));
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * r_value3(2 * v.x + j, v.y, v.z);
    }
#elif PROCTEX_PASS == 2
    ivec3 v = atlas_voxel(frag, ivec2(n, n / 2));
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * upsample3(ivec3(v.x, wrap_mod(2 * v.y + j, n), v.z), 0, ivec2(n / 2, n));
    }
#elif PROCTEX_PASS == 3
    ivec3 v = atlas_voxel(frag, ivec2(n, n));
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * upsample3(ivec3(v.x, v.y, wrap_mod(2 * v.z + j, n)), 1, ivec2(n, n / 2));
    }
#else
    ivec3 v = atlas_voxel(frag, ivec2(n, n));
    int o = int(TILE_ODD_OFFSET);
    s = (band3(v) + band3(v + ivec3(o)) - TILE_MEAN) * TILE_INV_SD;
#endif
    proctex_bake_out = vec4(s, 0.0);
}
