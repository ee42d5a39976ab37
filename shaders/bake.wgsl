// Baking wavelet-noise tiles on the GPU from the seed (exported snippets: a tile is 16384 or
// 262144 numbers, too many to paste as a constant). This file is what both bakes share: the
// hashes, the Gaussian values, the analysis/refinement filters and the full-screen triangle. The
// passes are in bake2.wgsl (the 2D tile) and bake3.wgsl (the 3D tile of solid textures); each
// pass is a full-screen triangle into an rgba32float target (the three components in RGB). `N` is the tile side, `TILE_SEED` and
// `TILE_STREAM` the hash inputs, `TILE_ODD_OFFSET` the odd shift, and `TILE_MEAN` /
// `TILE_INV_SD` the normalisation measured by the CPU (all generated constants).
// The hashes are in hash.wgsl. Twins: analyzer/src/rng.rs (gaussian, f32 here) and
// analyzer/src/noise.rs (a_coeff; wrap_mod is its `rem_euclid` indexing).

@group(0) @binding(0) var bake_src: texture_2d<f32>;

fn gaussian(seed: u32, stream: u32, index: u32) -> f32 {
    let u1 = uniform01(seed, stream, index * 2u);
    let u2 = uniform01(seed, stream, index * 2u + 1u);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

const A_NEG: array<f32, 16> = array<f32, 16>(
    0.000334, -0.001528, 0.000410, 0.003545, -0.000938, -0.008233, 0.002172, 0.019120,
    -0.005040, -0.044412, 0.011655, 0.103311, -0.025936, -0.243780, 0.033979, 0.655340,
);
const P: array<f32, 4> = array<f32, 4>(0.25, 0.75, 0.75, 0.25);

fn a_coeff(j: i32) -> f32 {
    if (j < 0) {
        return A_NEG[j + 16];
    }
    return A_NEG[15 - j];
}

fn wrap_mod(i: i32, n: i32) -> i32 {
    return ((i % n) + n) % n;
}

@vertex
fn vs_bake(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}
