// Wavelet noise evaluation and band clamping (GLSL twin of shaders/noise.wgsl, where
// wavelet_noise2/3 are noise2/3: desktop GLSL reserves those names; Rust twins in
// analyzer/src/noise.rs). Same operation order, 32-bit floats (highp). Indices wrap with a
// mask: tile sides are powers of two, and GLSL's % is undefined for negative operands.

struct BWeights {
    int mid;
    vec3 w;
};

BWeights bspline_weights(float p) {
    float mid = ceil(p - 0.5);
    float t = mid - (p - 0.5);
    float w0 = 0.5 * t * t;
    float w2 = 0.5 * (1.0 - t) * (1.0 - t);
    return BWeights(int(mid), vec3(w0, 1.0 - w0 - w2, w2));
}

// The tile's expected coefficient autocorrelation at lags 0 and ±1, by how many axes the lag
// moves along (twins of TILE2_LAGS / TILE3_LAGS in analyzer/src/noise.rs).
const vec3 TILE2_LAGS = vec3(5.5698, -1.1486, -0.7269);
const vec4 TILE3_LAGS = vec4(8.964, -0.7905, -0.4997, -0.3143);

// The B-spline weights' autocorrelation at lags 0 and ±1.
vec2 weight_lags(vec3 w) {
    return vec2(w[0] * w[0] + w[1] * w[1] + w[2] * w[2], w[0] * w[1] + w[1] * w[2]);
}

// A 2D band's variance at the sub-texel phase of weights wx, wy (divided out: every phase has
// unit variance, not only their average).
float phase_variance2(vec3 wx, vec3 wy) {
    vec2 cx = weight_lags(wx);
    vec2 cy = weight_lags(wy);
    return TILE2_LAGS[0] * cx[0] * cy[0]
        + 2.0 * TILE2_LAGS[1] * (cx[0] * cy[1] + cx[1] * cy[0])
        + 4.0 * TILE2_LAGS[2] * cx[1] * cy[1];
}

float phase_variance3(vec3 wx, vec3 wy, vec3 wz) {
    vec2 cx = weight_lags(wx);
    vec2 cy = weight_lags(wy);
    vec2 cz = weight_lags(wz);
    return TILE3_LAGS[0] * cx[0] * cy[0] * cz[0]
        + 2.0 * TILE3_LAGS[1] * (cx[1] * cy[0] * cz[0] + cx[0] * cy[1] * cz[0] + cx[0] * cy[0] * cz[1])
        + 4.0 * TILE3_LAGS[2] * (cx[1] * cy[1] * cz[0] + cx[1] * cy[0] * cz[1] + cx[0] * cy[1] * cz[1])
        + 8.0 * TILE3_LAGS[3] * cx[1] * cy[1] * cz[1];
}

float wrap_coord(float p, float n) {
    return p - n * floor(p / n);
}

int wrap_index(int i, int n) {
    return i & (n - 1);
}

// i mod m for any m >= 1, in float arithmetic (GLSL's % is undefined for negative operands;
// exact for |i| < 2^24, which seamless tiles' indices are).
int wrap_period(int i, int m) {
    float fi = float(i);
    float fm = float(m);
    return int(fi - fm * floor(fi / fm));
}

// The whole number of coefficients nearest m that a band of a tile of side n can repeat with.
float whole_period(float m, float n) {
    if (m < n) {
        return max(floor(m + 0.5), 1.0);
    }
    return n * floor(m / n + 0.5);
}

#ifdef PROCTEX_SOLID
// The 3D tile through tile3_side / tile3_texel (tile3_atlas.glsl).
vec3 wavelet_noise3(vec3 p) {
    int ni = tile3_side();
    float nf = float(ni);
    BWeights bx = bspline_weights(wrap_coord(p.x, nf));
    BWeights by = bspline_weights(wrap_coord(p.y, nf));
    BWeights bz = bspline_weights(wrap_coord(p.z, nf));
    ivec3 cols = ivec3(
        wrap_index(bx.mid - 1, ni),
        wrap_index(bx.mid, ni),
        wrap_index(bx.mid + 1, ni));
    vec3 sum = vec3(0.0);
    for (int dz = 0; dz < 3; dz++) {
        int slab = wrap_index(bz.mid + dz - 1, ni);
        vec3 plane = vec3(0.0);
        for (int dy = 0; dy < 3; dy++) {
            int row = wrap_index(by.mid + dy - 1, ni);
            vec3 line = vec3(0.0);
            for (int dx = 0; dx < 3; dx++) {
                line += bx.w[dx] * tile3_texel(ivec3(cols[dx], row, slab));
            }
            plane += by.w[dy] * line;
        }
        sum += bz.w[dz] * plane;
    }
    return sum / sqrt(phase_variance3(bx.w, by.w, bz.w));
}
#else
uniform highp sampler2D proctex_tile2;

vec3 wavelet_noise2(vec2 p) {
    int ni = textureSize(proctex_tile2, 0).x;
    float nf = float(ni);
    BWeights bx = bspline_weights(wrap_coord(p.x, nf));
    BWeights by = bspline_weights(wrap_coord(p.y, nf));
    ivec3 cols = ivec3(
        wrap_index(bx.mid - 1, ni),
        wrap_index(bx.mid, ni),
        wrap_index(bx.mid + 1, ni));
    vec3 sum = vec3(0.0);
    for (int dy = 0; dy < 3; dy++) {
        int row = wrap_index(by.mid + dy - 1, ni);
        vec3 line = vec3(0.0);
        for (int dx = 0; dx < 3; dx++) {
            line += bx.w[dx] * texelFetch(proctex_tile2, ivec2(cols[dx], row), 0).xyz;
        }
        sum += by.w[dy] * line;
    }
    return sum / sqrt(phase_variance2(bx.w, by.w));
}

// One 2D band with its coefficient indices wrapped at min(period, n) per axis (seamless tiles).
vec3 noise2_periodic(vec2 p, vec2 period) {
    float nf = float(textureSize(proctex_tile2, 0).x);
    vec2 pw = vec2(min(period.x, nf), min(period.y, nf));
    int px = int(pw.x);
    int py = int(pw.y);
    BWeights bx = bspline_weights(wrap_coord(p.x, pw.x));
    BWeights by = bspline_weights(wrap_coord(p.y, pw.y));
    ivec3 cols = ivec3(
        wrap_period(bx.mid - 1, px),
        wrap_period(bx.mid, px),
        wrap_period(bx.mid + 1, px));
    vec3 sum = vec3(0.0);
    for (int dy = 0; dy < 3; dy++) {
        int row = wrap_period(by.mid + dy - 1, py);
        vec3 line = vec3(0.0);
        for (int dx = 0; dx < 3; dx++) {
            line += bx.w[dx] * texelFetch(proctex_tile2, ivec2(cols[dx], row), 0).xyz;
        }
        sum += by.w[dy] * line;
    }
    return sum / sqrt(phase_variance2(bx.w, by.w));
}
#endif

// Oriented bands: a band mixed with its own derivative, m = (alpha, beta*dx, beta*dy), divided
// by the mixture's deviation at the phase (twins in analyzer/src/noise/oriented.rs, where
// wavelet_noise2/3_oriented are noise2/3_oriented).

vec3 bspline_derivative(float p) {
    float mid = ceil(p - 0.5);
    float t = mid - (p - 0.5);
    return vec3(-t, 2.0 * t - 1.0, 1.0 - t);
}

vec2 cross_lags(vec3 a, vec3 b) {
    return vec2(
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
        a[0] * b[1] + a[1] * b[0] + a[1] * b[2] + a[2] * b[1]);
}

float pair_covariance2(vec2 x, vec2 y) {
    return TILE2_LAGS[0] * x[0] * y[0] + TILE2_LAGS[1] * (x[1] * y[0] + x[0] * y[1])
        + TILE2_LAGS[2] * x[1] * y[1];
}

float pair_covariance3(vec2 x, vec2 y, vec2 z) {
    return TILE3_LAGS[0] * x[0] * y[0] * z[0]
        + TILE3_LAGS[1] * (x[1] * y[0] * z[0] + x[0] * y[1] * z[0] + x[0] * y[0] * z[1])
        + TILE3_LAGS[2] * (x[1] * y[1] * z[0] + x[1] * y[0] * z[1] + x[0] * y[1] * z[1])
        + TILE3_LAGS[3] * x[1] * y[1] * z[1];
}

// The x weights of the mixture's first separable term, alpha*wx + gx*dwx: the mixture weighs
// the taps by ax (x) wy + gy*(wx (x) dwy).
vec3 mixed_weights(vec3 wx, vec3 dwx, vec3 m) {
    return vec3(
        m[0] * wx[0] + m[1] * dwx[0],
        m[0] * wx[1] + m[1] * dwx[1],
        m[0] * wx[2] + m[1] * dwx[2]);
}

float oriented_variance2(vec3 ax, vec3 wx, vec3 wy, vec3 dwy, float gy) {
    return pair_covariance2(cross_lags(ax, ax), cross_lags(wy, wy))
        + 2.0 * gy * pair_covariance2(cross_lags(ax, wx), cross_lags(wy, dwy))
        + gy * gy * pair_covariance2(cross_lags(wx, wx), cross_lags(dwy, dwy));
}

float oriented_variance3(vec3 ax, vec3 wx, vec3 wy, vec3 wz, vec3 dwy, float gy) {
    vec2 zz = cross_lags(wz, wz);
    return pair_covariance3(cross_lags(ax, ax), cross_lags(wy, wy), zz)
        + 2.0 * gy * pair_covariance3(cross_lags(ax, wx), cross_lags(wy, dwy), zz)
        + gy * gy * pair_covariance3(cross_lags(wx, wx), cross_lags(dwy, dwy), zz);
}

// The phase averages of the weights' and their derivatives' cross-lags, and the derivative's
// mean variance along an axis (2D, 3D).
const vec2 WEIGHT_LAGS_MEAN = vec2(11.0 / 20.0, 13.0 / 30.0);
const vec2 DERIVATIVE_LAGS_MEAN = vec2(1.0, -2.0 / 3.0);

float gradient_variance2() {
    return pair_covariance2(DERIVATIVE_LAGS_MEAN, WEIGHT_LAGS_MEAN);
}

float gradient_variance3() {
    return pair_covariance3(DERIVATIVE_LAGS_MEAN, WEIGHT_LAGS_MEAN, WEIGHT_LAGS_MEAN);
}

// A band's mixing (alpha, beta*dx, beta*dy) for streaks along angle_deg at strength s.
vec3 mixing(float angle_deg, float strength, float grad_var) {
    float s = clamp(strength, 0.0, 1.0);
    float a = radians(angle_deg);
    float beta = sqrt(s / grad_var);
    return vec3(sqrt(1.0 - s), -sin(a) * beta, cos(a) * beta);
}

#ifdef PROCTEX_SOLID
vec3 wavelet_noise3_oriented(vec3 p, vec3 m) {
    int ni = tile3_side();
    float nf = float(ni);
    vec3 q = vec3(wrap_coord(p.x, nf), wrap_coord(p.y, nf), wrap_coord(p.z, nf));
    BWeights bx = bspline_weights(q.x);
    BWeights by = bspline_weights(q.y);
    BWeights bz = bspline_weights(q.z);
    vec3 ax = mixed_weights(bx.w, bspline_derivative(q.x), m);
    vec3 dwy = bspline_derivative(q.y);
    float gy = m[2];
    ivec3 cols = ivec3(
        wrap_index(bx.mid - 1, ni),
        wrap_index(bx.mid, ni),
        wrap_index(bx.mid + 1, ni));
    vec3 sum = vec3(0.0);
    for (int dz = 0; dz < 3; dz++) {
        int slab = wrap_index(bz.mid + dz - 1, ni);
        vec3 plane = vec3(0.0);
        for (int dy = 0; dy < 3; dy++) {
            int row = wrap_index(by.mid + dy - 1, ni);
            vec3 line_a = vec3(0.0);
            vec3 line = vec3(0.0);
            for (int dx = 0; dx < 3; dx++) {
                vec3 c = tile3_texel(ivec3(cols[dx], row, slab));
                line_a += ax[dx] * c;
                line += bx.w[dx] * c;
            }
            plane += by.w[dy] * line_a + gy * dwy[dy] * line;
        }
        sum += bz.w[dz] * plane;
    }
    return sum / sqrt(oriented_variance3(ax, bx.w, by.w, bz.w, dwy, gy));
}
#else
// The mixture over the 3x3 coefficients at cols and rows, weighted ax (x) wy + gy*(wx (x) dwy).
vec3 oriented_3x3(ivec3 cols, ivec3 rows, vec3 ax, vec3 wx, vec3 wy, vec3 dwy, float gy) {
    vec3 sum = vec3(0.0);
    for (int dy = 0; dy < 3; dy++) {
        vec3 line_a = vec3(0.0);
        vec3 line = vec3(0.0);
        for (int dx = 0; dx < 3; dx++) {
            vec3 c = texelFetch(proctex_tile2, ivec2(cols[dx], rows[dy]), 0).xyz;
            line_a += ax[dx] * c;
            line += wx[dx] * c;
        }
        sum += wy[dy] * line_a + gy * dwy[dy] * line;
    }
    return sum / sqrt(oriented_variance2(ax, wx, wy, dwy, gy));
}

vec3 wavelet_noise2_oriented(vec2 p, vec3 m) {
    int ni = textureSize(proctex_tile2, 0).x;
    float nf = float(ni);
    vec2 q = vec2(wrap_coord(p.x, nf), wrap_coord(p.y, nf));
    BWeights bx = bspline_weights(q.x);
    BWeights by = bspline_weights(q.y);
    ivec3 cols = ivec3(wrap_index(bx.mid - 1, ni), wrap_index(bx.mid, ni), wrap_index(bx.mid + 1, ni));
    ivec3 rows = ivec3(wrap_index(by.mid - 1, ni), wrap_index(by.mid, ni), wrap_index(by.mid + 1, ni));
    vec3 ax = mixed_weights(bx.w, bspline_derivative(q.x), m);
    return oriented_3x3(cols, rows, ax, bx.w, by.w, bspline_derivative(q.y), m[2]);
}

vec3 noise2_periodic_oriented(vec2 p, vec2 period, vec3 m) {
    float nf = float(textureSize(proctex_tile2, 0).x);
    vec2 pw = vec2(min(period.x, nf), min(period.y, nf));
    int px = int(pw.x);
    int py = int(pw.y);
    vec2 q = vec2(wrap_coord(p.x, pw.x), wrap_coord(p.y, pw.y));
    BWeights bx = bspline_weights(q.x);
    BWeights by = bspline_weights(q.y);
    ivec3 cols = ivec3(wrap_period(bx.mid - 1, px), wrap_period(bx.mid, px), wrap_period(bx.mid + 1, px));
    ivec3 rows = ivec3(wrap_period(by.mid - 1, py), wrap_period(by.mid, py), wrap_period(by.mid + 1, py));
    vec3 ax = mixed_weights(bx.w, bspline_derivative(q.x), m);
    return oriented_3x3(cols, rows, ax, bx.w, by.w, bspline_derivative(q.y), m[2]);
}
#endif

float band_fade(uint band, float log2_footprint) {
    return clamp(1.0 - (log2_footprint - float(band)), 0.0, 1.0);
}
