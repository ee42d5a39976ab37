// Baking the 2D noise tile (GLSL twin of shaders/bake2.wgsl); uses bake.glsl. Complex white
// noise times a fixed magnitude M, inverse-transformed, each inverse DFT split in two passes
// (the four-step DFT, N = SPLIT x N/SPLIT); five passes, N x N each:
//   pass 1: Z*M of both draws at frequency bin (kx, ky) = texel (x, y)
//   pass 2: the inner sums of the inverse DFT along x, reads proctex_bake_src
//   pass 3: the outer sums: the inverse DFT along x, reads proctex_bake_src
//   pass 4: the inner sums of the inverse DFT along y, reads proctex_bake_src
//   pass 5: the outer sums along y, components, normalised; reads proctex_bake_src
// TILE_PROFILE (N/2 + 1 values) is a generated constant.

const float TAU = 6.283185307179586;

// e^{sign*2*pi*i*k/N} for an integer phase k (reduced exactly before the float conversion).
vec2 twiddle(int k, float sgn) {
    float a = sgn * TAU * float(wrap_mod(k, int(N))) / float(N);
    return vec2(cos(a), sin(a));
}

vec2 cmul(vec2 a, vec2 b) {
    return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

#if PROCTEX_PASS == 1
vec2 transfer_a(int k) {
    vec2 s = vec2(0.0);
    for (int j = -16; j < 16; j++) {
        s += a_coeff(j) * twiddle(j * k, -1.0);
    }
    return s;
}

vec2 transfer_p(int k) {
    vec2 s = vec2(0.0);
    for (int m = -2; m < 2; m++) {
        s += P[m + 2] * twiddle(m * k, -1.0);
    }
    return s;
}

float expected_power(int kx, int ky) {
    int h = int(N) / 2;
    vec2 pp = cmul(transfer_p(kx), transfer_p(ky));
    vec2 ax = transfer_a(kx);
    vec2 ay = transfer_a(ky);
    vec2 conj_a = cmul(vec2(ax.x, -ax.y), vec2(ay.x, -ay.y));
    vec2 own = vec2(1.0, 0.0) - 0.25 * cmul(pp, conj_a);
    vec2 axh = transfer_a(kx + h);
    vec2 ayh = transfer_a(ky + h);
    float aliases = dot(axh, axh) * dot(ay, ay) + dot(ax, ax) * dot(ayh, ayh)
        + dot(axh, axh) * dot(ayh, ayh);
    return float(N * N) * (dot(own, own) + dot(pp, pp) / 16.0 * aliases);
}

int signed_bin(int k) {
    int n = int(N);
    if (k > n / 2) {
        return k - n;
    }
    return k;
}

float sinc(float u) {
    if (u == 0.0) {
        return 1.0;
    }
    float x = 3.141592653589793 * u;
    return sin(x) / x;
}

float tile_magnitude(int kx, int ky) {
    int sx = signed_bin(kx);
    int sy = signed_bin(ky);
    int ring = int(round(sqrt(float(sx * sx + sy * sy))));
    float power;
    if (ring <= int(N) / 2) {
        float spline = pow(sinc(float(sx) / float(N)) * sinc(float(sy) / float(N)), 6.0);
        power = TILE_PROFILE[ring] / spline;
    } else {
        power = expected_power(kx, ky);
    }
    return sqrt(power) / float(N * N);
}
#endif

#if PROCTEX_PASS >= 2
// The four-step split of an inverse DFT along one axis (bake2.wgsl has the derivation).
const int SPLIT = 16;

vec4 axis_texel(int along, int other, int axis) {
    if (axis == 0) {
        return texelFetch(proctex_bake_src, ivec2(along, other), 0);
    }
    return texelFetch(proctex_bake_src, ivec2(other, along), 0);
}

vec4 cmul2(vec4 v, vec2 e) {
    return vec4(cmul(v.xy, e), cmul(v.zw, e));
}

vec4 inner_sums(int c, int other, int axis) {
    int n2 = int(N) / SPLIT;
    int k1 = c % SPLIT;
    int x2 = c / SPLIT;
    vec4 s = vec4(0.0);
    for (int k2 = 0; k2 < n2; k2++) {
        s += cmul2(axis_texel(k1 + SPLIT * k2, other, axis), twiddle(k2 * x2 * SPLIT, 1.0));
    }
    return cmul2(s, twiddle(k1 * x2, 1.0));
}

vec4 outer_sums(int x, int other, int axis) {
    int n2 = int(N) / SPLIT;
    int x2 = x % n2;
    int x1 = x / n2;
    vec4 s = vec4(0.0);
    for (int k1 = 0; k1 < SPLIT; k1++) {
        s += cmul2(axis_texel(k1 + SPLIT * x2, other, axis), twiddle(k1 * x1 * n2, 1.0));
    }
    return s;
}
#endif

// One entry per pass (twins of fs_bake_spectrum, fs_bake_rows_inner, fs_bake_rows,
// fs_bake_cols_inner, fs_bake_tile).
void main() {
    int x = int(gl_FragCoord.x);
    int y = int(gl_FragCoord.y);
#if PROCTEX_PASS == 1
    uint b = uint(x) + N * uint(y);
    float m = tile_magnitude(x, y);
    uint draw = 2u * N * N;
    proctex_bake_out = m * vec4(
        gaussian(TILE_SEED, TILE_STREAM, 2u * b),
        gaussian(TILE_SEED, TILE_STREAM, 2u * b + 1u),
        gaussian(TILE_SEED, TILE_STREAM, draw + 2u * b),
        gaussian(TILE_SEED, TILE_STREAM, draw + 2u * b + 1u));
#elif PROCTEX_PASS == 2
    proctex_bake_out = inner_sums(x, y, 0);
#elif PROCTEX_PASS == 3
    proctex_bake_out = outer_sums(x, y, 0);
#elif PROCTEX_PASS == 4
    proctex_bake_out = inner_sums(y, x, 1);
#else
    vec4 s = outer_sums(y, x, 1);
    proctex_bake_out = vec4((s.xyz - TILE_MEAN) * TILE_INV_SD, 0.0);
#endif
}
