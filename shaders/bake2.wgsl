// Baking the 2D wavelet-noise tile (plane textures) from the seed; uses bake.wgsl. Three passes:
//   pass 1, N/2 x N:  fs_bake_down_x   R↓ along x
//   pass 2, N x N/2:  fs_bake_down_y   (R↓↑ along x)↓ along y       reads pass 1 at binding 0
//   pass 3, N x N:    fs_bake_tile     R − R↓↑, odd shift, normalise reads pass 2 at binding 0
// Twins: analyzer/src/noise.rs (downsample, upsample: one output sample each here; the entry
// points' twin is Tile::generate, r_value its `r` vector, band its `band`). Every value is a
// vec3: the tile's three independent components (component k draws the Gaussian values
// k·N² …), baked side by side into the RGB of an rgba32float target.

// The Gaussian coefficients R of the three components at tile texel (x, y), wrapped.
fn r_value(x: i32, y: i32) -> vec3<f32> {
    let n = i32(N);
    let xi = u32(((x % n) + n) % n);
    let yi = u32(((y % n) + n) % n);
    let i = xi + N * yi;
    return vec3<f32>(
        gaussian(TILE_SEED, TILE_STREAM, i),
        gaussian(TILE_SEED, TILE_STREAM, i + N * N),
        gaussian(TILE_SEED, TILE_STREAM, i + 2u * N * N),
    );
}

// r↓[i] = Σ_j a_j r[(2i + j) mod n] along x, for row y.
fn downsample(i: i32, y: i32) -> vec3<f32> {
    var s = vec3<f32>(0.0);
    for (var j = -16; j < 16; j++) {
        s += a_coeff(j) * r_value(2 * i + j, y);
    }
    return s;
}

// r↑[x] = Σ_{k=⌊x/2⌋}^{⌊x/2⌋+1} p_{x−2k} r↓[k mod n/2] of row `row` of the bound texture,
// whose axis 0 (`along_x`) or axis 1 holds the n/2 coarse samples.
fn upsample(x: i32, row: i32, along_x: bool) -> vec3<f32> {
    let half = i32(N) / 2;
    var s = vec3<f32>(0.0);
    for (var k = x / 2; k <= x / 2 + 1; k++) {
        var v: vec3<f32>;
        if (along_x) {
            v = textureLoad(bake_src, vec2<i32>(wrap_mod(k, half), row), 0).xyz;
        } else {
            v = textureLoad(bake_src, vec2<i32>(row, wrap_mod(k, half)), 0).xyz;
        }
        s += P[x - 2 * k + 2] * v;
    }
    return s;
}

@fragment
fn fs_bake_down_x(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(downsample(i32(frag.x), i32(frag.y)), 0.0);
}

@fragment
fn fs_bake_down_y(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let x = i32(frag.x);
    let i = i32(frag.y);
    let n = i32(N);
    var s = vec3<f32>(0.0);
    for (var j = -16; j < 16; j++) {
        s += a_coeff(j) * upsample(x, wrap_mod(2 * i + j, n), true);
    }
    return vec4<f32>(s, 0.0);
}

fn band(x: i32, y: i32) -> vec3<f32> {
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
    return vec4<f32>(v, 0.0);
}
