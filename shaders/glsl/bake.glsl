// Baking wavelet-noise tiles from the seed (GLSL twin of shaders/bake.wgsl; Rust twins in
// analyzer/src/rng.rs and analyzer/src/noise.rs): what the 2D and 3D bakes share. The passes are
// in bake2.glsl (2D tile, `#define PROCTEX_PASS 1|2|3|4|5`) and bake3.glsl (3D tile of solid
// textures, `PROCTEX_PASS 1|2|3|4`), fragment passes into RGBA32F targets (the three components in RGB). `N`, `TILE_SEED`,
// `TILE_STREAM`, `TILE_ODD_OFFSET`, `TILE_MEAN` and `TILE_INV_SD` are generated constants.
// Unsigned arithmetic wraps in GLSL ES 3.00 as in WGSL; indices wrap with masks (N is a power of
// two; % is undefined for negative operands in GLSL). The hashes are in hash.glsl.

float gaussian(uint seed, uint stream, uint index) {
    float u1 = uniform01(seed, stream, index * 2u);
    float u2 = uniform01(seed, stream, index * 2u + 1u);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

int wrap_mod(int i, int n) {
    return i & (n - 1);
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

// The previous pass's target (unused by pass 1).
uniform highp sampler2D proctex_bake_src;
layout(location = 0) out vec4 proctex_bake_out;
