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
const vec3 TILE2_LAGS = vec3(5.5791, -1.1537, -0.7334);
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

float band_fade(uint band, float log2_footprint) {
    return clamp(1.0 - (log2_footprint - float(band)), 0.0, 1.0);
}
