// Baking the 3D wavelet-noise tile (solid textures) from the seed; uses bake.wgsl and
// atlas3.wgsl. Every volume is a 2D atlas of its slices; four passes, one axis each, as the CPU
// down- and up-samples along x, then y, then z:
//   pass 1, A (N/2, N, N):  fs_bake3_down_x  R↓ along x
//   pass 2, B (N, N/2, N):  fs_bake3_down_y  (A↑ along x)↓ along y              reads A at binding 0
//   pass 3, C (N, N, N/2):  fs_bake3_down_z  (B↑ along y)↓ along z              reads B at binding 0
//   pass 4, T (N, N, N):    fs_bake3_tile    R − C↑ along z, odd shift, normalise reads C at binding 0
// Atlas sizes (8 slices per row): A 4N × N²/8, B and C 8N × N²/16, T 8N × N²/8.
// Twins: analyzer/src/noise.rs (downsample, upsample: one output sample each here; the entry
// points' twin is Tile::generate, r_value3 its `r` vector, band3 its `band`). Every value is a
// vec3 of the tile's three components, baked into the RGB of rgba32float atlases.

// The Gaussian coefficient R at tile voxel (x, y, z), wrapped.
fn r_value3(x: i32, y: i32, z: i32) -> vec3<f32> {
    let n = i32(N);
    let xi = u32(wrap_mod(x, n));
    let yi = u32(wrap_mod(y, n));
    let zi = u32(wrap_mod(z, n));
    let i = xi + N * (yi + N * zi);
    return vec3<f32>(
        gaussian(TILE_SEED, TILE_STREAM, i),
        gaussian(TILE_SEED, TILE_STREAM, i + N * N * N),
        gaussian(TILE_SEED, TILE_STREAM, i + 2u * N * N * N),
    );
}

// The bound volume, up-sampled along `axis` (which holds N/2 coarse samples there), at voxel c
// (c[axis] in 0..N); `size` is the bound volume's slice size.
fn upsample3(c: vec3<i32>, axis: i32, size: vec2<i32>) -> vec3<f32> {
    let half = i32(N) / 2;
    let x = c[axis];
    var s = vec3<f32>(0.0);
    for (var k = x / 2; k <= x / 2 + 1; k++) {
        var q = c;
        q[axis] = wrap_mod(k, half);
        s += P[x - 2 * k + 2] * textureLoad(bake_src, atlas_texel(q, size), 0).xyz;
    }
    return s;
}

@fragment
fn fs_bake3_down_x(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let n = i32(N);
    let v = atlas_voxel(vec2<i32>(frag.xy), vec2<i32>(n / 2, n));
    var s = vec3<f32>(0.0);
    for (var j = -16; j < 16; j++) {
        s += a_coeff(j) * r_value3(2 * v.x + j, v.y, v.z);
    }
    return vec4<f32>(s, 0.0);
}

@fragment
fn fs_bake3_down_y(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let n = i32(N);
    let v = atlas_voxel(vec2<i32>(frag.xy), vec2<i32>(n, n / 2));
    var s = vec3<f32>(0.0);
    for (var j = -16; j < 16; j++) {
        let c = vec3<i32>(v.x, wrap_mod(2 * v.y + j, n), v.z);
        s += a_coeff(j) * upsample3(c, 0, vec2<i32>(n / 2, n));
    }
    return vec4<f32>(s, 0.0);
}

@fragment
fn fs_bake3_down_z(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let n = i32(N);
    let v = atlas_voxel(vec2<i32>(frag.xy), vec2<i32>(n, n));
    var s = vec3<f32>(0.0);
    for (var j = -16; j < 16; j++) {
        let c = vec3<i32>(v.x, v.y, wrap_mod(2 * v.z + j, n));
        s += a_coeff(j) * upsample3(c, 1, vec2<i32>(n, n / 2));
    }
    return vec4<f32>(s, 0.0);
}

fn band3(c: vec3<i32>) -> vec3<f32> {
    let n = i32(N);
    let w = vec3<i32>(wrap_mod(c.x, n), wrap_mod(c.y, n), wrap_mod(c.z, n));
    return r_value3(w.x, w.y, w.z) - upsample3(w, 2, vec2<i32>(n, n));
}

@fragment
fn fs_bake3_tile(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let n = i32(N);
    let v = atlas_voxel(vec2<i32>(frag.xy), vec2<i32>(n, n));
    let o = i32(TILE_ODD_OFFSET);
    let t = (band3(v) + band3(v + vec3<i32>(o)) - TILE_MEAN) * TILE_INV_SD;
    return vec4<f32>(t, 0.0);
}
