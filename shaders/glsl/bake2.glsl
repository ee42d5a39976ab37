// Baking the 2D wavelet-noise tile (GLSL twin of shaders/bake2.wgsl); uses bake.glsl.
//   pass 1, N/2 x N:  R down-sampled along x
//   pass 2, N x N/2:  (pass 1 up-sampled along x) down-sampled along y, reads proctex_bake_src
//   pass 3, N x N:    R - pass 2 up-sampled along y, odd shift, normalised; reads proctex_bake_src

// The Gaussian coefficients R of the tile's three components at texel (x, y), wrapped
// (component k draws the values k*N*N ...; baked into RGB).
vec3 r_value(int x, int y) {
    int n = int(N);
    uint xi = uint(wrap_mod(x, n));
    uint yi = uint(wrap_mod(y, n));
    uint i = xi + N * yi;
    return vec3(
        gaussian(TILE_SEED, TILE_STREAM, i),
        gaussian(TILE_SEED, TILE_STREAM, i + N * N),
        gaussian(TILE_SEED, TILE_STREAM, i + 2u * N * N));
}

#if PROCTEX_PASS == 1
// r_down[i] = sum_j a_j r[(2i + j) mod n] along x, for row y.
vec3 downsample(int i, int y) {
    vec3 s = vec3(0.0);
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * r_value(2 * i + j, y);
    }
    return s;
}
#else
// r_up[x] = sum_{k=x/2}^{x/2+1} p_{x-2k} r_down[k mod n/2] of row `row` of proctex_bake_src,
// whose axis 0 (along_x) or axis 1 holds the n/2 coarse samples.
vec3 upsample(int x, int row, bool along_x) {
    int halfn = int(N) / 2;
    vec3 s = vec3(0.0);
    for (int k = x / 2; k <= x / 2 + 1; k++) {
        vec3 v;
        if (along_x) {
            v = texelFetch(proctex_bake_src, ivec2(wrap_mod(k, halfn), row), 0).xyz;
        } else {
            v = texelFetch(proctex_bake_src, ivec2(row, wrap_mod(k, halfn)), 0).xyz;
        }
        s += P[x - 2 * k + 2] * v;
    }
    return s;
}

vec3 band(int x, int y) {
    int n = int(N);
    int xw = wrap_mod(x, n);
    int yw = wrap_mod(y, n);
    return r_value(xw, yw) - upsample(yw, xw, false);
}
#endif

// One entry per pass (twins of fs_bake_down_x, fs_bake_down_y, fs_bake_tile).
void main() {
    int x = int(gl_FragCoord.x);
    int y = int(gl_FragCoord.y);
#if PROCTEX_PASS == 1
    proctex_bake_out = vec4(downsample(x, y), 0.0);
#elif PROCTEX_PASS == 2
    int n = int(N);
    vec3 s = vec3(0.0);
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * upsample(x, wrap_mod(2 * y + j, n), true);
    }
    proctex_bake_out = vec4(s, 0.0);
#else
    int o = int(TILE_ODD_OFFSET);
    vec3 v = (band(x, y) + band(x + o, y + o) - TILE_MEAN) * TILE_INV_SD;
    proctex_bake_out = vec4(v, 0.0);
#endif
}
