// Baking the wavelet-noise tile from the seed (GLSL twin of shaders/bake.wgsl; Rust twins in
// analyzer/src/rng.rs and analyzer/src/noise.rs). Three fragment passes into R32F targets,
// chosen with `#define PROCTEX_PASS 1|2|3`; `N`, `TILE_SEED`, `TILE_STREAM`, `TILE_ODD_OFFSET`,
// `TILE_MEAN` and `TILE_INV_SD` are generated constants.
//   pass 1, N/2 x N:  R down-sampled along x
//   pass 2, N x N/2:  (pass 1 up-sampled along x) down-sampled along y, reads proctex_bake_src
//   pass 3, N x N:    R - pass 2 up-sampled along y, odd shift, normalised; reads proctex_bake_src
// Unsigned arithmetic wraps in GLSL ES 3.00 as in WGSL; indices wrap with masks (N is a power of
// two; % is undefined for negative operands in GLSL).

uint pcg_hash(uint x) {
    uint state = x * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint hash3(uint seed, uint stream, uint index) {
    return pcg_hash(index + pcg_hash(stream + pcg_hash(seed)));
}

// `uniform` in WGSL and Rust (a reserved word in GLSL).
float uniform01(uint seed, uint stream, uint index) {
    return (float(hash3(seed, stream, index) >> 8u) + 0.5) / 16777216.0;
}

float gaussian(uint seed, uint stream, uint index) {
    float u1 = uniform01(seed, stream, index * 2u);
    float u2 = uniform01(seed, stream, index * 2u + 1u);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

int wrap_mod(int i, int n) {
    return i & (n - 1);
}

// The Gaussian coefficient R at tile texel (x, y), wrapped.
float r_value(int x, int y) {
    int n = int(N);
    uint xi = uint(wrap_mod(x, n));
    uint yi = uint(wrap_mod(y, n));
    return gaussian(TILE_SEED, TILE_STREAM, xi + N * yi);
}

const float A_NEG[16] = float[16](
    0.000334, -0.001528, 0.000410, 0.003545, -0.000938, -0.008233, 0.002172, 0.019120,
    -0.005040, -0.044412, 0.011655, 0.103311, -0.025936, -0.243780, 0.033979, 0.655340);
const float P[4] = float[4](0.25, 0.75, 0.75, 0.25);

float a_coeff(int j) {
    if (j < 0) {
        return A_NEG[j + 16];
    }
    return A_NEG[15 - j];
}

#if PROCTEX_PASS == 1
// r_down[i] = sum_j a_j r[(2i + j) mod n] along x, for row y.
float downsample(int i, int y) {
    float s = 0.0;
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * r_value(2 * i + j, y);
    }
    return s;
}
#else
uniform highp sampler2D proctex_bake_src;

// r_up[x] = sum_{k=x/2}^{x/2+1} p_{x-2k} r_down[k mod n/2] of row `row` of proctex_bake_src,
// whose axis 0 (along_x) or axis 1 holds the n/2 coarse samples.
float upsample(int x, int row, bool along_x) {
    int halfn = int(N) / 2;
    float s = 0.0;
    for (int k = x / 2; k <= x / 2 + 1; k++) {
        float v;
        if (along_x) {
            v = texelFetch(proctex_bake_src, ivec2(wrap_mod(k, halfn), row), 0).r;
        } else {
            v = texelFetch(proctex_bake_src, ivec2(row, wrap_mod(k, halfn)), 0).r;
        }
        s += P[x - 2 * k + 2] * v;
    }
    return s;
}

float band(int x, int y) {
    int n = int(N);
    int xw = wrap_mod(x, n);
    int yw = wrap_mod(y, n);
    return r_value(xw, yw) - upsample(yw, xw, false);
}
#endif

layout(location = 0) out vec4 proctex_bake_out;

// One entry per pass (twins of fs_bake_down_x, fs_bake_down_y, fs_bake_tile).
void main() {
    int x = int(gl_FragCoord.x);
    int y = int(gl_FragCoord.y);
#if PROCTEX_PASS == 1
    proctex_bake_out = vec4(downsample(x, y), 0.0, 0.0, 1.0);
#elif PROCTEX_PASS == 2
    int n = int(N);
    float s = 0.0;
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * upsample(x, wrap_mod(2 * y + j, n), true);
    }
    proctex_bake_out = vec4(s, 0.0, 0.0, 1.0);
#else
    int o = int(TILE_ODD_OFFSET);
    float v = (band(x, y) + band(x + o, y + o) - TILE_MEAN) * TILE_INV_SD;
    proctex_bake_out = vec4(v, 0.0, 0.0, 1.0);
#endif
}
