// Morphing between textures with t as a uniform (exported morphs: `proctex export A.json B.json
// ... --format wgsl`, the app's morph Copy buttons). The exported shader holds every key's
// parameters as constants and rebuilds the params of `t` exactly as the CPU does
// (analyzer/src/morph.rs): everything linear except the colour basis (quaternion slerp) and the
// scale (geometric), the inverse-CDF knots kept non-decreasing and their tangents recomputed.
// Twins: analyzer/src/morph.rs (slerp, matrix_from_quat, morph; morph_params is morph_path) and
// analyzer/src/histogram.rs (fc_tangents). Same operation order, f32 (the CPU slerps and takes
// tangents in f64). Generated constants: MORPH_SEGMENT_COUNT (u32), MORPH_SEGMENTS
// (array<MorphSegment, MORPH_SEGMENT_COUNT>), MORPH_ENDS (array<Params, MORPH_SEGMENT_COUNT + 1>:
// each key's own params, the images at the keys' t) and MORPH_OFFSETS (the band offsets of the
// first key's seed, which the whole morph renders with).

// One end of a morph segment: what interpolates.
struct MorphKey {
    // mean RGB, contrast
    mean: vec4<f32>,
    // the colour basis as a unit quaternion (w, x, y, z)
    quat: vec4<f32>,
    // ln(scale), rotation (degrees), turn to the segment's other end the shorter way (degrees)
    pose: vec4<f32>,
    // [band] → weight of channels 0, 1, 2
    weights: array<vec4<f32>, 12>,
    // [knot] → inverse-CDF knot of channels 0, 1, 2 at the segment's knot count (the identity
    // curve when this key's histogram is off)
    knots: array<vec4<f32>, 33>,
}

struct MorphSegment {
    a: MorphKey,
    b: MorphKey,
    // bands, knots, solid (0/1), histogram (0/1) of the blend
    counts: vec4<u32>,
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
    p.offsets = MORPH_OFFSETS;
    for (var k = 0u; k < seg.counts.y; k++) {
        var v = a.knots[k] + t * (b.knots[k] - a.knots[k]);
        if (k > 0u) {
            // Rounding must not break monotonicity.
            v = max(v, p.knots[k - 1u]);
        }
        p.knots[k] = v;
    }
    p.tangents = fc_tangents(p.knots, seg.counts.y);
    return p;
}

// The params at t ∈ [0, 1] of the whole morph (its segments spread evenly over t).
fn morph_params(t_in: f32) -> Params {
    let t = clamp(t_in, 0.0, 1.0);
    if (t >= 1.0) {
        return MORPH_ENDS[MORPH_SEGMENT_COUNT];
    }
    let segments = f32(MORPH_SEGMENT_COUNT);
    let s = max(min(t * segments, segments - 1e-6), 0.0);
    let i = u32(floor(s));
    let local = s - f32(i);
    if (local == 0.0) {
        return MORPH_ENDS[i];
    }
    return morph(MORPH_SEGMENTS[i], local);
}
