// Wavelet noise evaluation and band clamping (noise3 reads the 3D tile through tile3_side and
// tile3_texel: tile3.wgsl or tile3_atlas.wgsl). Twins: analyzer/src/noise.rs (bspline_weights,
// weight_lags, phase_variance2/3, noise2, wrap_period, whole_period, noise2_periodic, noise3,
// band_fade; wrap_coord and wrap_index are private helpers there). Same operation order, f32.
// A band is a vec3: the tile's three independent components, read with one fetch per tap (the
// structured models' pattern noise takes .x, the Rust *_first functions).

struct BWeights {
    mid: i32,
    w: vec3<f32>,
}

fn bspline_weights(p: f32) -> BWeights {
    let mid = ceil(p - 0.5);
    let t = mid - (p - 0.5);
    let w0 = 0.5 * t * t;
    let w2 = 0.5 * (1.0 - t) * (1.0 - t);
    return BWeights(i32(mid), vec3<f32>(w0, 1.0 - w0 - w2, w2));
}

// The tile's expected coefficient autocorrelation at lags 0 and ±1, by how many axes the lag
// moves along (twins of TILE2_LAGS / TILE3_LAGS in analyzer/src/noise.rs).
const TILE2_LAGS = vec3<f32>(5.5698, -1.1486, -0.7269);
const TILE3_LAGS = vec4<f32>(8.964, -0.7905, -0.4997, -0.3143);

// The B-spline weights' autocorrelation at lags 0 and ±1.
fn weight_lags(w: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(w[0] * w[0] + w[1] * w[1] + w[2] * w[2], w[0] * w[1] + w[1] * w[2]);
}

// A 2D band's variance at the sub-texel phase of weights wx, wy (divided out: every phase has
// unit variance, not only their average).
fn phase_variance2(wx: vec3<f32>, wy: vec3<f32>) -> f32 {
    let cx = weight_lags(wx);
    let cy = weight_lags(wy);
    return TILE2_LAGS[0] * cx[0] * cy[0]
        + 2.0 * TILE2_LAGS[1] * (cx[0] * cy[1] + cx[1] * cy[0])
        + 4.0 * TILE2_LAGS[2] * cx[1] * cy[1];
}

fn phase_variance3(wx: vec3<f32>, wy: vec3<f32>, wz: vec3<f32>) -> f32 {
    let cx = weight_lags(wx);
    let cy = weight_lags(wy);
    let cz = weight_lags(wz);
    return TILE3_LAGS[0] * cx[0] * cy[0] * cz[0]
        + 2.0 * TILE3_LAGS[1] * (cx[1] * cy[0] * cz[0] + cx[0] * cy[1] * cz[0] + cx[0] * cy[0] * cz[1])
        + 4.0 * TILE3_LAGS[2] * (cx[1] * cy[1] * cz[0] + cx[1] * cy[0] * cz[1] + cx[0] * cy[1] * cz[1])
        + 8.0 * TILE3_LAGS[3] * cx[1] * cy[1] * cz[1];
}

fn wrap_coord(p: f32, n: f32) -> f32 {
    return p - n * floor(p / n);
}

// i mod n for a power-of-two tile side n: a mask (integer division is slow on software GPUs).
fn wrap_index(i: i32, n: i32) -> i32 {
    return i & (n - 1);
}

fn noise2(p: vec2<f32>) -> vec3<f32> {
    let ni = i32(textureDimensions(tile2).x);
    let nf = f32(ni);
    let bx = bspline_weights(wrap_coord(p.x, nf));
    let by = bspline_weights(wrap_coord(p.y, nf));
    let cols = vec3<i32>(
        wrap_index(bx.mid - 1, ni),
        wrap_index(bx.mid, ni),
        wrap_index(bx.mid + 1, ni),
    );
    var sum = vec3<f32>(0.0);
    for (var dy = 0; dy < 3; dy++) {
        let row = wrap_index(by.mid + dy - 1, ni);
        var line = vec3<f32>(0.0);
        for (var dx = 0; dx < 3; dx++) {
            line += bx.w[dx] * textureLoad(tile2, vec2<i32>(cols[dx], row), 0).xyz;
        }
        sum += by.w[dy] * line;
    }
    return sum / sqrt(phase_variance2(bx.w, by.w));
}

// i mod m for any m >= 1 (a wrapped period need not be a power of two).
fn wrap_period(i: i32, m: i32) -> i32 {
    return ((i % m) + m) % m;
}

// The whole number of coefficients nearest m that a band of a tile of side n can repeat with
// (floor(x + 0.5): WGSL's round() rounds halves to even, the Rust twin's f32::round away).
fn whole_period(m: f32, n: f32) -> f32 {
    if (m < n) {
        return max(floor(m + 0.5), 1.0);
    }
    return n * floor(m / n + 0.5);
}

// One 2D band with its coefficient indices wrapped at min(period, n) per axis: periodic with
// period when each is a whole number (seamless tiles).
fn noise2_periodic(p: vec2<f32>, period: vec2<f32>) -> vec3<f32> {
    let nf = f32(textureDimensions(tile2).x);
    let pw = vec2<f32>(min(period.x, nf), min(period.y, nf));
    let px = i32(pw.x);
    let py = i32(pw.y);
    let bx = bspline_weights(wrap_coord(p.x, pw.x));
    let by = bspline_weights(wrap_coord(p.y, pw.y));
    let cols = vec3<i32>(
        wrap_period(bx.mid - 1, px),
        wrap_period(bx.mid, px),
        wrap_period(bx.mid + 1, px),
    );
    var sum = vec3<f32>(0.0);
    for (var dy = 0; dy < 3; dy++) {
        let row = wrap_period(by.mid + dy - 1, py);
        var line = vec3<f32>(0.0);
        for (var dx = 0; dx < 3; dx++) {
            line += bx.w[dx] * textureLoad(tile2, vec2<i32>(cols[dx], row), 0).xyz;
        }
        sum += by.w[dy] * line;
    }
    return sum / sqrt(phase_variance2(bx.w, by.w));
}

fn noise3(p: vec3<f32>) -> vec3<f32> {
    let ni = tile3_side();
    let nf = f32(ni);
    let bx = bspline_weights(wrap_coord(p.x, nf));
    let by = bspline_weights(wrap_coord(p.y, nf));
    let bz = bspline_weights(wrap_coord(p.z, nf));
    let cols = vec3<i32>(
        wrap_index(bx.mid - 1, ni),
        wrap_index(bx.mid, ni),
        wrap_index(bx.mid + 1, ni),
    );
    var sum = vec3<f32>(0.0);
    for (var dz = 0; dz < 3; dz++) {
        let slab = wrap_index(bz.mid + dz - 1, ni);
        var plane = vec3<f32>(0.0);
        for (var dy = 0; dy < 3; dy++) {
            let row = wrap_index(by.mid + dy - 1, ni);
            var line = vec3<f32>(0.0);
            for (var dx = 0; dx < 3; dx++) {
                line += bx.w[dx] * tile3_texel(vec3<i32>(cols[dx], row, slab));
            }
            plane += by.w[dy] * line;
        }
        sum += bz.w[dz] * plane;
    }
    return sum / sqrt(phase_variance3(bx.w, by.w, bz.w));
}

// Oriented bands: a band mixed with its own derivative, m = (α, β·dx, β·dy), divided by the
// mixture's deviation at the phase. Twins: analyzer/src/noise/oriented.rs (bspline_derivative,
// cross_lags, pair_covariance2/3, oriented_variance2/3, noise2_oriented,
// noise2_periodic_oriented, noise3_oriented, mixed_weights).

fn bspline_derivative(p: f32) -> vec3<f32> {
    let mid = ceil(p - 0.5);
    let t = mid - (p - 0.5);
    return vec3<f32>(-t, 2.0 * t - 1.0, 1.0 - t);
}

fn cross_lags(a: vec3<f32>, b: vec3<f32>) -> vec2<f32> {
    return vec2<f32>(
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
        a[0] * b[1] + a[1] * b[0] + a[1] * b[2] + a[2] * b[1],
    );
}

fn pair_covariance2(x: vec2<f32>, y: vec2<f32>) -> f32 {
    return TILE2_LAGS[0] * x[0] * y[0] + TILE2_LAGS[1] * (x[1] * y[0] + x[0] * y[1])
        + TILE2_LAGS[2] * x[1] * y[1];
}

fn pair_covariance3(x: vec2<f32>, y: vec2<f32>, z: vec2<f32>) -> f32 {
    return TILE3_LAGS[0] * x[0] * y[0] * z[0]
        + TILE3_LAGS[1] * (x[1] * y[0] * z[0] + x[0] * y[1] * z[0] + x[0] * y[0] * z[1])
        + TILE3_LAGS[2] * (x[1] * y[1] * z[0] + x[1] * y[0] * z[1] + x[0] * y[1] * z[1])
        + TILE3_LAGS[3] * x[1] * y[1] * z[1];
}

// The x weights of the mixture's first separable term, α·wx + gx·dwx: the mixture weighs the
// taps by ax ⊗ wy + gy·(wx ⊗ dwy).
fn mixed_weights(wx: vec3<f32>, dwx: vec3<f32>, m: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        m[0] * wx[0] + m[1] * dwx[0],
        m[0] * wx[1] + m[1] * dwx[1],
        m[0] * wx[2] + m[1] * dwx[2],
    );
}

fn oriented_variance2(ax: vec3<f32>, wx: vec3<f32>, wy: vec3<f32>, dwy: vec3<f32>, gy: f32) -> f32 {
    return pair_covariance2(cross_lags(ax, ax), cross_lags(wy, wy))
        + 2.0 * gy * pair_covariance2(cross_lags(ax, wx), cross_lags(wy, dwy))
        + gy * gy * pair_covariance2(cross_lags(wx, wx), cross_lags(dwy, dwy));
}

fn oriented_variance3(ax: vec3<f32>, wx: vec3<f32>, wy: vec3<f32>, wz: vec3<f32>, dwy: vec3<f32>, gy: f32) -> f32 {
    let zz = cross_lags(wz, wz);
    return pair_covariance3(cross_lags(ax, ax), cross_lags(wy, wy), zz)
        + 2.0 * gy * pair_covariance3(cross_lags(ax, wx), cross_lags(wy, dwy), zz)
        + gy * gy * pair_covariance3(cross_lags(wx, wx), cross_lags(dwy, dwy), zz);
}

// The phase averages of the weights' and their derivatives' cross-lags, and the derivative's
// mean variance along an axis (2D, 3D).
const WEIGHT_LAGS_MEAN = vec2<f32>(11.0 / 20.0, 13.0 / 30.0);
const DERIVATIVE_LAGS_MEAN = vec2<f32>(1.0, -2.0 / 3.0);

fn gradient_variance2() -> f32 {
    return pair_covariance2(DERIVATIVE_LAGS_MEAN, WEIGHT_LAGS_MEAN);
}

fn gradient_variance3() -> f32 {
    return pair_covariance3(DERIVATIVE_LAGS_MEAN, WEIGHT_LAGS_MEAN, WEIGHT_LAGS_MEAN);
}

// A band's mixing (α, β·dx, β·dy) for streaks along angle_deg at strength s.
fn mixing(angle_deg: f32, strength: f32, grad_var: f32) -> vec3<f32> {
    let s = clamp(strength, 0.0, 1.0);
    let a = radians(angle_deg);
    let beta = sqrt(s / grad_var);
    return vec3<f32>(sqrt(1.0 - s), -sin(a) * beta, cos(a) * beta);
}

// The mixture over the 3x3 coefficients at cols and rows, weighted ax ⊗ wy + gy·(wx ⊗ dwy).
fn oriented_3x3(cols: vec3<i32>, rows: vec3<i32>, ax: vec3<f32>, wx: vec3<f32>, wy: vec3<f32>, dwy: vec3<f32>, gy: f32) -> vec3<f32> {
    var sum = vec3<f32>(0.0);
    for (var dy = 0; dy < 3; dy++) {
        var line_a = vec3<f32>(0.0);
        var line = vec3<f32>(0.0);
        for (var dx = 0; dx < 3; dx++) {
            let c = textureLoad(tile2, vec2<i32>(cols[dx], rows[dy]), 0).xyz;
            line_a += ax[dx] * c;
            line += wx[dx] * c;
        }
        sum += wy[dy] * line_a + gy * dwy[dy] * line;
    }
    return sum / sqrt(oriented_variance2(ax, wx, wy, dwy, gy));
}

fn noise2_oriented(p: vec2<f32>, m: vec3<f32>) -> vec3<f32> {
    let ni = i32(textureDimensions(tile2).x);
    let nf = f32(ni);
    let q = vec2<f32>(wrap_coord(p.x, nf), wrap_coord(p.y, nf));
    let bx = bspline_weights(q.x);
    let by = bspline_weights(q.y);
    let cols = vec3<i32>(wrap_index(bx.mid - 1, ni), wrap_index(bx.mid, ni), wrap_index(bx.mid + 1, ni));
    let rows = vec3<i32>(wrap_index(by.mid - 1, ni), wrap_index(by.mid, ni), wrap_index(by.mid + 1, ni));
    let ax = mixed_weights(bx.w, bspline_derivative(q.x), m);
    return oriented_3x3(cols, rows, ax, bx.w, by.w, bspline_derivative(q.y), m[2]);
}

fn noise2_periodic_oriented(p: vec2<f32>, period: vec2<f32>, m: vec3<f32>) -> vec3<f32> {
    let nf = f32(textureDimensions(tile2).x);
    let pw = vec2<f32>(min(period.x, nf), min(period.y, nf));
    let px = i32(pw.x);
    let py = i32(pw.y);
    let q = vec2<f32>(wrap_coord(p.x, pw.x), wrap_coord(p.y, pw.y));
    let bx = bspline_weights(q.x);
    let by = bspline_weights(q.y);
    let cols = vec3<i32>(wrap_period(bx.mid - 1, px), wrap_period(bx.mid, px), wrap_period(bx.mid + 1, px));
    let rows = vec3<i32>(wrap_period(by.mid - 1, py), wrap_period(by.mid, py), wrap_period(by.mid + 1, py));
    let ax = mixed_weights(bx.w, bspline_derivative(q.x), m);
    return oriented_3x3(cols, rows, ax, bx.w, by.w, bspline_derivative(q.y), m[2]);
}

fn noise3_oriented(p: vec3<f32>, m: vec3<f32>) -> vec3<f32> {
    let ni = tile3_side();
    let nf = f32(ni);
    let q = vec3<f32>(wrap_coord(p.x, nf), wrap_coord(p.y, nf), wrap_coord(p.z, nf));
    let bx = bspline_weights(q.x);
    let by = bspline_weights(q.y);
    let bz = bspline_weights(q.z);
    let ax = mixed_weights(bx.w, bspline_derivative(q.x), m);
    let dwy = bspline_derivative(q.y);
    let gy = m[2];
    let cols = vec3<i32>(
        wrap_index(bx.mid - 1, ni),
        wrap_index(bx.mid, ni),
        wrap_index(bx.mid + 1, ni),
    );
    var sum = vec3<f32>(0.0);
    for (var dz = 0; dz < 3; dz++) {
        let slab = wrap_index(bz.mid + dz - 1, ni);
        var plane = vec3<f32>(0.0);
        for (var dy = 0; dy < 3; dy++) {
            let row = wrap_index(by.mid + dy - 1, ni);
            var line_a = vec3<f32>(0.0);
            var line = vec3<f32>(0.0);
            for (var dx = 0; dx < 3; dx++) {
                let c = tile3_texel(vec3<i32>(cols[dx], row, slab));
                line_a += ax[dx] * c;
                line += bx.w[dx] * c;
            }
            plane += by.w[dy] * line_a + gy * dwy[dy] * line;
        }
        sum += bz.w[dz] * plane;
    }
    return sum / sqrt(oriented_variance3(ax, bx.w, by.w, bz.w, dwy, gy));
}

fn band_fade(band: u32, log2_footprint: f32) -> f32 {
    return clamp(1.0 - (log2_footprint - f32(band)), 0.0, 1.0);
}
