// Baking the 2D noise tile (plane textures) from the seed; uses bake.wgsl. The tile is complex
// white noise times a fixed magnitude M, inverse-transformed (analyzer/src/noise/spectral.rs has
// why). Each inverse DFT of N points is split in two passes (the "four-step" DFT, N = SPLIT x
// N/SPLIT): SPLIT + N/SPLIT taps per texel instead of N (48 instead of 512 at N = 512). Five
// passes, N x N each:
//   pass 1: fs_bake_spectrum    Z·M of both draws at frequency bin (kx, ky) = texel (x, y)
//   pass 2: fs_bake_rows_inner  the inner sums of the inverse DFT along x     reads pass 1
//   pass 3: fs_bake_rows        the outer sums: the inverse DFT along x       reads pass 2
//   pass 4: fs_bake_cols_inner  the inner sums of the inverse DFT along y     reads pass 3
//   pass 5: fs_bake_tile        the outer sums along y, components, normalise reads pass 4
// (each at binding 0). Twins: analyzer/src/noise/spectral.rs (magnitude: tile_magnitude here,
// expected_power_at: expected_power, field_pair: the DFT passes; the CPU's FFT and these DFTs
// agree to rounding). `TILE_PROFILE` (the ring profile of the rendered power, N/2 + 1 values) is
// a generated constant. Every value is a vec4 of two complex numbers (draws 0 and 1) until pass
// 5 writes the three components into the RGB of an rgba32float target: component 0 and 1 are
// the real and imaginary parts of draw 0, component 2 the real part of draw 1.

const TAU: f32 = 6.283185307179586;

// e^{sign·2πi·k/N} for an integer phase k (reduced exactly before the float conversion).
fn twiddle(k: i32, sign: f32) -> vec2<f32> {
    let a = sign * TAU * f32(wrap_mod(k, i32(N))) / f32(N);
    return vec2<f32>(cos(a), sin(a));
}

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

// Â(k/N) = Σ_j a_j e^{−2πi·jk/N} and P̂(k/N) = Σ_m p_m e^{−2πi·mk/N} (k may exceed N).
fn transfer_a(k: i32) -> vec2<f32> {
    var s = vec2<f32>(0.0);
    for (var j = -16; j < 16; j++) {
        s += a_coeff(j) * twiddle(j * k, -1.0);
    }
    return s;
}

fn transfer_p(k: i32) -> vec2<f32> {
    var s = vec2<f32>(0.0);
    for (var m = -2; m < 2; m++) {
        s += P[m + 2] * twiddle(m * k, -1.0);
    }
    return s;
}

// The wavelet band's expected power at bin (kx, ky) in closed form (expected_power_at).
fn expected_power(kx: i32, ky: i32) -> f32 {
    let h = i32(N) / 2;
    let pp = cmul(transfer_p(kx), transfer_p(ky));
    let ax = transfer_a(kx);
    let ay = transfer_a(ky);
    let conj_a = cmul(vec2<f32>(ax.x, -ax.y), vec2<f32>(ay.x, -ay.y));
    let own = vec2<f32>(1.0, 0.0) - 0.25 * cmul(pp, conj_a);
    let axh = transfer_a(kx + h);
    let ayh = transfer_a(ky + h);
    let aliases = dot(axh, axh) * dot(ay, ay) + dot(ax, ax) * dot(ayh, ayh)
        + dot(axh, axh) * dot(ayh, ayh);
    return f32(N * N) * (dot(own, own) + dot(pp, pp) / 16.0 * aliases);
}

fn signed_bin(k: i32) -> i32 {
    let n = i32(N);
    if (k > n / 2) {
        return k - n;
    }
    return k;
}

fn sinc(u: f32) -> f32 {
    if (u == 0.0) {
        return 1.0;
    }
    let x = 3.141592653589793 * u;
    return sin(x) / x;
}

// M at bin (kx, ky): inside the disk of N/2 bins the ring profile over the B-spline's transfer,
// outside it the wavelet band's own expected power; both over N² (spectral::magnitude).
fn tile_magnitude(kx: i32, ky: i32) -> f32 {
    let sx = signed_bin(kx);
    let sy = signed_bin(ky);
    let ring = i32(round(sqrt(f32(sx * sx + sy * sy))));
    var power: f32;
    if (ring <= i32(N) / 2) {
        let spline = pow(sinc(f32(sx) / f32(N)) * sinc(f32(sy) / f32(N)), 6.0);
        power = TILE_PROFILE[ring] / spline;
    } else {
        power = expected_power(kx, ky);
    }
    return sqrt(power) / f32(N * N);
}

@fragment
fn fs_bake_spectrum(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let kx = i32(frag.x);
    let ky = i32(frag.y);
    let b = u32(kx) + N * u32(ky);
    let m = tile_magnitude(kx, ky);
    let draw = 2u * N * N;
    return m * vec4<f32>(
        gaussian(TILE_SEED, TILE_STREAM, 2u * b),
        gaussian(TILE_SEED, TILE_STREAM, 2u * b + 1u),
        gaussian(TILE_SEED, TILE_STREAM, draw + 2u * b),
        gaussian(TILE_SEED, TILE_STREAM, draw + 2u * b + 1u),
    );
}

// The four-step split of an inverse DFT along one axis (`axis` 0: x, 1: y; `other` the texel's
// coordinate along the other axis). With N1 = SPLIT, N2 = N / SPLIT, a bin k = k1 + N1·k2 and a
// position x = x2 + N2·x1, e^{2πi·kx/N} = e^{2πi·k1·x2/N} e^{2πi·k1·x1/N1} e^{2πi·k2·x2/N2}, so
//   inner(k1, x2) = e^{2πi·k1·x2/N} Σ_k2 v[k1 + N1·k2] e^{2πi·k2·x2/N2}   (stored at k1 + N1·x2)
//   s[x2 + N2·x1] = Σ_k1 inner(k1, x2) e^{2πi·k1·x1/N1}.
const SPLIT: i32 = 16;

fn axis_texel(along: i32, other: i32, axis: i32) -> vec4<f32> {
    if (axis == 0) {
        return textureLoad(bake_src, vec2<i32>(along, other), 0);
    }
    return textureLoad(bake_src, vec2<i32>(other, along), 0);
}

fn cmul2(v: vec4<f32>, e: vec2<f32>) -> vec4<f32> {
    return vec4<f32>(cmul(v.xy, e), cmul(v.zw, e));
}

fn inner_sums(c: i32, other: i32, axis: i32) -> vec4<f32> {
    let n2 = i32(N) / SPLIT;
    let k1 = c % SPLIT;
    let x2 = c / SPLIT;
    var s = vec4<f32>(0.0);
    for (var k2 = 0; k2 < n2; k2++) {
        s += cmul2(axis_texel(k1 + SPLIT * k2, other, axis), twiddle(k2 * x2 * SPLIT, 1.0));
    }
    return cmul2(s, twiddle(k1 * x2, 1.0));
}

fn outer_sums(x: i32, other: i32, axis: i32) -> vec4<f32> {
    let n2 = i32(N) / SPLIT;
    let x2 = x % n2;
    let x1 = x / n2;
    var s = vec4<f32>(0.0);
    for (var k1 = 0; k1 < SPLIT; k1++) {
        s += cmul2(axis_texel(k1 + SPLIT * x2, other, axis), twiddle(k1 * x1 * n2, 1.0));
    }
    return s;
}

@fragment
fn fs_bake_rows_inner(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return inner_sums(i32(frag.x), i32(frag.y), 0);
}

@fragment
fn fs_bake_rows(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return outer_sums(i32(frag.x), i32(frag.y), 0);
}

@fragment
fn fs_bake_cols_inner(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return inner_sums(i32(frag.y), i32(frag.x), 1);
}

@fragment
fn fs_bake_tile(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    let s = outer_sums(i32(frag.y), i32(frag.x), 1);
    let v = (s.xyz - TILE_MEAN) * TILE_INV_SD;
    return vec4<f32>(v, 0.0);
}
