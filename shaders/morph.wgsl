// Morphing between textures with t as a uniform (exported morphs: `proctex export A.json B.json
// ... --format wgsl`, the app's morph Copy buttons). The exported shader holds every key's
// parameters as constants and rebuilds the params of `t` exactly as the CPU does
// (analyzer/src/morph.rs): everything linear except the colour basis (quaternion slerp) and the
// scale (geometric), the inverse-CDF knots kept non-decreasing and their tangents recomputed.
// Twins: analyzer/src/morph.rs (slerp, matrix_from_quat, morph; morph_params is morph_path) and
// analyzer/src/histogram.rs (fc_tangents). Same operation order, f32 (the CPU slerps and takes
// tangents in f64). Generated constants: MORPH_SEGMENT_COUNT (u32), MORPH_SEGMENTS
// (array<MorphSegment, MORPH_SEGMENT_COUNT>), MORPH_ENDS (array<Params, MORPH_SEGMENT_COUNT + 1>:
// each key's own params, the images at the keys' t), MORPH_OFFSETS (the band offsets of the
// first key's seed, which the whole morph renders with), MORPH_SEED (that seed: the cell hash of
// structured models) and MORPH_PATTERN_OFFSETS (its pattern octaves' offsets); and the
// functions morph_segment(i) and morph_end(i), which read those arrays with constant indices
// (see `constant_selectors` in analyzer/src/export.rs: drivers compile a run-time index into a
// constant array of structs slowly).
//
// Structured models (morph.rs, morph_structure): within one family the pattern's scale
// (geometric), rotation (the shorter way) and values (clamped to their ranges) interpolate, and
// so do the ramps (both evaluated at the union of their stops) and the output tone curves (both
// evaluated on one grid over the union of their ranges, then kept non-decreasing). Between
// families (a noise model counts as the flat ramp at the mean colour) the segment's first half
// fades the first pattern's ramp to the mean colour and the second half fades the second's in.
// The tables of both ends (union stops, tone grids) are computed on the CPU at export.

// One end of a morph segment: what interpolates.
struct MorphKey {
    // mean RGB, contrast
    mean: vec4<f32>,
    // the colour basis as a unit quaternion (w, x, y, z)
    quat: vec4<f32>,
    // ln(scale), rotation (degrees), turn to the segment's other end the shorter way (degrees)
    pose: vec4<f32>,
    // the finest band's part after the histogram per channel, unused
    fine: vec4<f32>,
    // [band] → weight of channels 0, 1, 2
    weights: array<vec4<f32>, 12>,
    // [band] → asin √(orientation strength) (the phase that interpolates), streak angle (degrees), turn to the segment's other end
    // (degrees, linear: angles 180° apart negate the band's derivative)
    orient: array<vec4<f32>, 12>,
    // [knot] → inverse-CDF knot of channels 0, 1, 2 at the segment's knot count (the identity
    // curve when this key's histogram is off)
    knots: array<vec4<f32>, 33>,
}

// The structured model along (a half of) a segment, from u = 0 to u = 1.
struct MorphStructure {
    // pattern kind (0: the noise model, only its tone curve), ramp stops, tone knots (0: none),
    // flags: 1 the pattern interpolates (else `transform` and `values_a` hold), 2 the ramp at
    // u = 0 is the flat mean colour, 4 the ramp at u = 1 is, 8 no tone curve at u = 0
    info: vec4<u32>,
    // the fixed pattern's transform (Params.pattern_transform)
    transform: vec4<f32>,
    // ln(scale) at u = 0, rotation at u = 0 (degrees), turn to u = 1 (degrees), ln(scale) at 1
    pose: vec4<f32>,
    // the structural values at u = 0 and 1, and their ranges
    values_a: array<vec4<f32>, 2>,
    values_b: array<vec4<f32>, 2>,
    value_min: array<vec4<f32>, 2>,
    value_max: array<vec4<f32>, 2>,
    // [stop] → the ramp at u = 0 and at u = 1 (RGB, at), at the union of their stops
    ramp_a: array<vec4<f32>, 16>,
    ramp_b: array<vec4<f32>, 16>,
    // the blended tone curve's range: [0] lo of RGB, [1] 1 / (hi − lo)
    tone_range: array<vec4<f32>, 2>,
    // [knot] → both tone curves on the blend's grid (RGB)
    tone_a: array<vec4<f32>, 33>,
    tone_b: array<vec4<f32>, 33>,
}

struct MorphSegment {
    a: MorphKey,
    b: MorphKey,
    // bands, knots, solid (0/1), histogram (0/1) of the blend
    counts: vec4<u32>,
    // x: 0 both ends noise models without tone curves, 1 one pattern family or two noise
    // models with a tone curve (`first` all the way), 2 a cross-fade
    // (`first` for t < ½, `second` after)
    mode: vec4<u32>,
    first: MorphStructure,
    second: MorphStructure,
}

// Spherical linear interpolation of unit quaternions along the shorter arc.
fn slerp(a: vec4<f32>, b_in: vec4<f32>, t: f32) -> vec4<f32> {
    var d = dot(a, b_in);
    var b = b_in;
    if (d < 0.0) {
        d = -d;
        b = -b_in;
    }
    if (d > 0.9995) {
        return normalize(a + t * (b - a));
    }
    let theta = acos(clamp(d, -1.0, 1.0));
    let sa = sin((1.0 - t) * theta) / sin(theta);
    let sb = sin(t * theta) / sin(theta);
    return normalize(sa * a + sb * b);
}

// The rows of the rotation matrix of a unit quaternion (w, x, y, z).
fn matrix_from_quat(q_in: vec4<f32>) -> array<vec4<f32>, 3> {
    let q = normalize(q_in);
    let w = q.x;
    let x = q.y;
    let y = q.z;
    let z = q.w;
    return array<vec4<f32>, 3>(
        vec4<f32>(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y), 0.0),
        vec4<f32>(2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x), 0.0),
        vec4<f32>(2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y), 0.0),
    );
}

// Fritsch–Carlson tangents of the first `count` knots, the three channels at once.
fn fc_tangents(knots: array<vec4<f32>, 33>, count: u32) -> array<vec4<f32>, 33> {
    var m: array<vec4<f32>, 33>;
    if (count < 2u) {
        return m;
    }
    let h = 1.0 / f32(count - 1u);
    var delta: array<vec4<f32>, 32>;
    for (var k = 0u; k + 1u < count; k++) {
        delta[k] = (knots[k + 1u] - knots[k]) / h;
    }
    m[0] = delta[0];
    m[count - 1u] = delta[count - 2u];
    for (var k = 1u; k + 1u < count; k++) {
        let opposite = delta[k - 1u] * delta[k] <= vec4<f32>(0.0);
        m[k] = select(0.5 * (delta[k - 1u] + delta[k]), vec4<f32>(0.0), opposite);
    }
    for (var k = 0u; k + 1u < count; k++) {
        let d = delta[k];
        let level = d == vec4<f32>(0.0);
        let safe = select(d, vec4<f32>(1.0), level);
        let a = m[k] / safe;
        let b = m[k + 1u] / safe;
        let s = a * a + b * b;
        let limit = s > vec4<f32>(9.0);
        let tau = 3.0 / sqrt(select(vec4<f32>(9.0), s, limit));
        m[k] = select(select(m[k], tau * a * d, limit), vec4<f32>(0.0), level);
        m[k + 1u] = select(select(m[k + 1u], tau * b * d, limit), vec4<f32>(0.0), level);
    }
    return m;
}

// The params a fraction t ∈ (0, 1) of the way through one segment.
fn morph(seg: MorphSegment, t: f32) -> Params {
    let a = seg.a;
    let b = seg.b;
    var p: Params;
    let mean = a.mean + t * (b.mean - a.mean);
    p.mean = vec4<f32>(clamp(mean.xyz, vec3<f32>(0.0), vec3<f32>(1.0)), mean.w);
    p.basis = matrix_from_quat(slerp(a.quat, b.quat, t));
    let scale = exp(a.pose.x * (1.0 - t) + b.pose.x * t);
    let angle = radians(a.pose.y + t * a.pose.z);
    p.transform = vec4<f32>(1.0 / scale, cos(angle), sin(angle), 0.0);
    p.counts = seg.counts;
    var energy = vec4<f32>(0.0);
    for (var j = 0u; j < MAX_BANDS; j++) {
        let w = max(a.weights[j] + t * (b.weights[j] - a.weights[j]), vec4<f32>(0.0));
        p.weights[j] = w;
        energy += w * w;
    }
    p.sigma = sqrt(energy);
    p.fine = max(a.fine + t * (b.fine - a.fine), vec4<f32>(0.0));
    p.offsets = MORPH_OFFSETS;
    var grad_var = gradient_variance2();
    if (seg.counts.z != 0u) {
        grad_var = gradient_variance3();
    }
    for (var j = 0u; j < MAX_BANDS; j++) {
        let phi = a.orient[j].x + t * (b.orient[j].x - a.orient[j].x);
        let s = clamp(sin(phi) * sin(phi), 0.0, 1.0);
        p.orient[j] = vec4<f32>(1.0, 0.0, 0.0, 0.0);
        if (s > 0.0) {
            p.orient[j] = vec4<f32>(mixing(a.orient[j].y + t * a.orient[j].z, s, grad_var), 0.0);
        }
    }
    for (var k = 0u; k < seg.counts.y; k++) {
        var v = a.knots[k] + t * (b.knots[k] - a.knots[k]);
        if (k > 0u) {
            // Rounding must not break monotonicity.
            v = max(v, p.knots[k - 1u]);
        }
        p.knots[k] = v;
    }
    p.tangents = fc_tangents(p.knots, seg.counts.y);
    p.pattern = vec4<u32>(0u, 0u, MORPH_SEED, 0u);
    if (seg.mode.x == 1u) {
        morph_structure(seg.first, t, &p);
    } else if (seg.mode.x == 2u) {
        if (t < 0.5) {
            morph_structure(seg.first, 2.0 * t, &p);
        } else {
            morph_structure(seg.second, 2.0 * t - 1.0, &p);
        }
    }
    return p;
}

// The pattern, ramp and tone curve a fraction u of the way through `st` (p's mean already the
// blend's: a flat ramp is that colour).
fn morph_structure(st: MorphStructure, u: f32, p: ptr<function, Params>) {
    let kind = st.info.x;
    if (kind == 0u) {
        // The noise model: no pattern or ramp, only its own tone curve (if any).
        lerp_tones(st, u, p);
        return;
    }
    (*p).pattern = vec4<u32>(kind, st.info.y, MORPH_SEED, 0u);
    (*p).pattern_offsets = MORPH_PATTERN_OFFSETS;
    if ((st.info.w & 1u) != 0u) {
        let scale = exp(st.pose.x * (1.0 - u) + st.pose.w * u);
        let angle = radians(st.pose.y + u * st.pose.z);
        let inv = 1.0 / scale;
        (*p).pattern_transform = vec4<f32>(inv, cos(angle), sin(angle), log2(inv));
        for (var i = 0u; i < 2u; i++) {
            let v = st.values_a[i] + u * (st.values_b[i] - st.values_a[i]);
            (*p).pattern_values[i] = clamp(v, st.value_min[i], st.value_max[i]);
        }
    } else {
        (*p).pattern_transform = st.transform;
        (*p).pattern_values = st.values_a;
    }
    lerp_ramps(st, u, p);
    lerp_tones(st, u, p);
}

// The ramp of `st` at u (stops past the count repeat the last, as Params from the CPU do).
fn lerp_ramps(st: MorphStructure, u: f32, p: ptr<function, Params>) {
    let mean = (*p).mean.xyz;
    let n = st.info.y;
    for (var i = 0u; i < 16u; i++) {
        let j = min(i, n - 1u);
        let a = select(st.ramp_a[j].xyz, mean, (st.info.w & 2u) != 0u);
        let b = select(st.ramp_b[j].xyz, mean, (st.info.w & 4u) != 0u);
        (*p).ramp[i] = vec4<f32>(clamp(a + u * (b - a), vec3<f32>(0.0), vec3<f32>(1.0)), st.ramp_a[j].w);
    }
}

// The output tone curve of `st` at u: knots blended, clamped, kept non-decreasing, tangents
// recomputed.
fn lerp_tones(st: MorphStructure, u: f32, p: ptr<function, Params>) {
    let k = st.info.z;
    if (k == 0u || (u <= 0.0 && (st.info.w & 8u) != 0u)) {
        return;
    }
    (*p).pattern.w = k;
    (*p).tone_range = st.tone_range;
    for (var i = 0u; i < k; i++) {
        var v = clamp(st.tone_a[i] + u * (st.tone_b[i] - st.tone_a[i]), vec4<f32>(-4.0), vec4<f32>(4.0));
        if (i > 0u) {
            // Rounding must not break monotonicity.
            v = max(v, (*p).tone_knots[i - 1u]);
        }
        (*p).tone_knots[i] = v;
    }
    (*p).tone_tangents = fc_tangents((*p).tone_knots, k);
}

// The params at t ∈ [0, 1] of the whole morph (its segments spread evenly over t).
fn morph_params(t_in: f32) -> Params {
    let t = clamp(t_in, 0.0, 1.0);
    if (t >= 1.0) {
        return morph_end(MORPH_SEGMENT_COUNT);
    }
    let segments = f32(MORPH_SEGMENT_COUNT);
    let s = max(min(t * segments, segments - 1e-6), 0.0);
    let i = u32(floor(s));
    let local = s - f32(i);
    if (local == 0.0) {
        return morph_end(i);
    }
    return morph(morph_segment(i), local);
}
