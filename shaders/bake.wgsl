// Baking the wavelet-noise tile on the GPU from the seed (exported snippets: the tile is 16384
// numbers, too many to paste as a constant). Three passes, each a full-screen triangle into an
// r32float target; `N` is the tile side, `TILE_SEED` and `TILE_STREAM` the hash inputs, and
// `TILE_MEAN` / `TILE_INV_SD` the normalisation measured by the CPU (all generated constants).
// Twins: analyzer/src/rng.rs (pcg_hash, hash3, uniform, gaussian, all f32 here) and
// analyzer/src/noise.rs (downsample, upsample: one output sample each here; a_coeff;
// the entry points' twin is Tile::generate).
//   pass 1, N/2 x N:  fs_bake_down_x   R↓ along x
//   pass 2, N x N/2:  fs_bake_down_y   (R↓↑ along x)↓ along y       reads pass 1 at binding 0
//   pass 3, N x N:    fs_bake_tile     R − R↓↑, odd shift, normalise reads pass 2 at binding 0

@group(0) @binding(0) var bake_src: texture_2d<f32>;

fn pcg_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn hash3(seed: u32, stream: u32, index: u32) -> u32 {
    return pcg_hash(index + pcg_hash(stream + pcg_hash(seed)));
}

fn uniform(seed: u32, stream: u32, index: u32) -> f32 {
    return (f32(hash3(seed, stream, index) >> 8u) + 0.5) / 16777216.0;
}

fn gaussian(seed: u32, stream: u32, index: u32) -> f32 {
    let u1 = uniform(seed, stream, index * 2u);
    let u2 = uniform(seed, stream, index * 2u + 1u);
    return sqrt(-2.0 * log(u1)) * cos(6.283185307179586 * u2);
}

// The Gaussian coefficient R at tile texel (x, y), wrapped.
fn r_value(x: i32, y: i32) -> f32 {
    let n = i32(N);
    let xi = u32(((x % n) + n) % n);
    let yi = u32(((y % n) + n) % n);
    return gaussian(TILE_SEED, TILE_STREAM, xi + N * yi);
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

// r↓[i] = Σ_j a_j r[(2i + j) mod n] along x, for row y.
fn downsample(i: i32, y: i32) -> f32 {
    var s = 0.0;
    for (var j = -16; j < 16; j++) {
        s += a_coeff(j) * r_value(2 * i + j, y);
    }
    return s;
}

fn wrap_mod(i: i32, n: i32) -> i32 {
    return ((i % n) + n) % n;
}

// r↑[x] = Σ_{k=⌊x/2⌋}^{⌊x/2⌋+1} p_{x−2k} r↓[k mod n/2] of row `row` of the bound texture,
// whose axis 0 (`along_x`) or axis 1 holds the n/2 coarse samples.
fn upsample(x: i32, row: i32, along_x: bool) -> f32 {
    let half = i32(N) / 2;
    var s = 0.0;
    for (var k = x / 2; k <= x / 2 + 1; k++) {
        var v: f32;
        if (along_x) {
            v = textureLoad(bake_src, vec2<i32>(wrap_mod(k, half), row), 0).r;
        } else {
            v = textureLoad(bake_src, vec2<i32>(row, wrap_mod(k, half)), 0).r;
        }
        s += P[x - 2 * k + 2] * v;
    }
    return s;
}

@vertex
fn vs_bake(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_bake_down_x(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(downsample(i32(frag.x), i32(frag.y)), 0.0, 0.0, 1.0);
}

@fragment
fn fs_bake_down_y(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let x = i32(frag.x);
    let i = i32(frag.y);
    let n = i32(N);
    var s = 0.0;
    for (var j = -16; j < 16; j++) {
        s += a_coeff(j) * upsample(x, wrap_mod(2 * i + j, n), true);
    }
    return vec4<f32>(s, 0.0, 0.0, 1.0);
}

fn band(x: i32, y: i32) -> f32 {
    let n = i32(N);
    let xw = wrap_mod(x, n);
    let yw = wrap_mod(y, n);
    return r_value(xw, yw) - upsample(yw, xw, false);
}

@fragment
fn fs_bake_tile(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let x = i32(frag.x);
    let y = i32(frag.y);
    let o = i32(TILE_ODD_OFFSET);
    let v = (band(x, y) + band(x + o, y + o) - TILE_MEAN) * TILE_INV_SD;
    return vec4<f32>(v, 0.0, 0.0, 1.0);
}
