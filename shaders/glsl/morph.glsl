// Morphing between textures with t as a uniform (GLSL twin of shaders/morph.wgsl; Rust twins in
// analyzer/src/morph.rs and analyzer/src/histogram.rs). Same operation order, 32-bit floats.
// Generated constants: MORPH_SEGMENT_COUNT, MORPH_SEGMENTS, MORPH_ENDS, MORPH_OFFSETS,
// MORPH_SEED, MORPH_PATTERN_OFFSETS, and the functions morph_segment(i), morph_end(i) (constant
// indices, as in morph.wgsl). Structured models as in morph.wgsl.

struct MorphKey {
    vec4 mean;          // mean RGB, contrast
    vec4 quat;          // the colour basis as a unit quaternion (w, x, y, z)
    vec4 pose;          // ln(scale), rotation (degrees), turn to the other end (degrees)
    vec4 fine;          // the finest band's part after the histogram per channel, unused
    vec4 weights[12];   // [band] -> weight of channels 0, 1, 2
    vec4 orient[12];    // [band] -> asin(sqrt(strength)), streak angle (degrees), turn to the other end
    vec4 knots[33];     // [knot] -> inverse-CDF knot of channels 0, 1, 2 (segment's count)
};

// The structured model along (a half of) a segment, from u = 0 to u = 1.
struct MorphStructure {
    uvec4 info;         // kind (0: noise model), ramp stops, tone knots (0: none), flags: 1 the
                        // pattern interpolates, 2 / 4 the ramp at u = 0 / 1 is the flat mean
                        // colour, 8 no tone curve at u = 0
    vec4 transform;     // the fixed pattern's transform
    vec4 pose;          // ln(scale) at 0, rotation at 0 (degrees), turn (degrees), ln(scale) at 1
    vec4 values_a[2];   // structural values at u = 0
    vec4 values_b[2];   // at u = 1
    vec4 value_min[2];  // their ranges
    vec4 value_max[2];
    vec4 ramp_a[16];    // [stop] -> ramp at u = 0 (RGB, at), at the union of both ramps' stops
    vec4 ramp_b[16];    // at u = 1
    vec4 tone_range[2]; // the blended tone curve's lo (RGB) and 1 / (hi - lo)
    vec4 tone_a[33];    // [knot] -> both tone curves on the blend's grid
    vec4 tone_b[33];
};

struct MorphSegment {
    MorphKey a;
    MorphKey b;
    uvec4 counts;       // bands, knots, solid (0/1), histogram (0/1) of the blend
    uvec4 mode;         // x: 0 noise models without tone curves, 1 one pattern family (or
                        // noise models with one), 2 a cross-fade
    MorphStructure first;
    MorphStructure second;
};

// (generated constants)

vec4 slerp(vec4 a, vec4 b_in, float t) {
    float d = dot(a, b_in);
    vec4 b = b_in;
    if (d < 0.0) {
        d = -d;
        b = -b_in;
    }
    if (d > 0.9995) {
        return normalize(a + t * (b - a));
    }
    float theta = acos(clamp(d, -1.0, 1.0));
    float sa = sin((1.0 - t) * theta) / sin(theta);
    float sb = sin(t * theta) / sin(theta);
    return normalize(sa * a + sb * b);
}

vec4[3] matrix_from_quat(vec4 q_in) {
    vec4 q = normalize(q_in);
    float w = q.x;
    float x = q.y;
    float y = q.z;
    float z = q.w;
    return vec4[3](
        vec4(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y), 0.0),
        vec4(2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x), 0.0),
        vec4(2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y), 0.0));
}

vec4[33] fc_tangents(vec4 knots[33], uint count) {
    vec4 m[33];
    for (int k = 0; k < 33; k++) {
        m[k] = vec4(0.0);
    }
    if (count < 2u) {
        return m;
    }
    float h = 1.0 / float(count - 1u);
    vec4 delta[32];
    for (uint k = 0u; k + 1u < count; k++) {
        delta[k] = (knots[k + 1u] - knots[k]) / h;
    }
    m[0] = delta[0];
    m[count - 1u] = delta[count - 2u];
    for (uint k = 1u; k + 1u < count; k++) {
        bvec4 opposite = lessThanEqual(delta[k - 1u] * delta[k], vec4(0.0));
        m[k] = mix(0.5 * (delta[k - 1u] + delta[k]), vec4(0.0), opposite);
    }
    for (uint k = 0u; k + 1u < count; k++) {
        vec4 d = delta[k];
        bvec4 level = equal(d, vec4(0.0));
        vec4 safe = mix(d, vec4(1.0), level);
        vec4 a = m[k] / safe;
        vec4 b = m[k + 1u] / safe;
        vec4 s = a * a + b * b;
        bvec4 limit = greaterThan(s, vec4(9.0));
        vec4 tau = 3.0 / sqrt(mix(vec4(9.0), s, limit));
        m[k] = mix(mix(m[k], tau * a * d, limit), vec4(0.0), level);
        m[k + 1u] = mix(mix(m[k + 1u], tau * b * d, limit), vec4(0.0), level);
    }
    return m;
}

// The ramp of `st` at u (stops past the count repeat the last).
void lerp_ramps(MorphStructure st, float u, inout Params p) {
    vec3 mean = p.mean.xyz;
    uint n = st.info.y;
    for (uint i = 0u; i < 16u; i++) {
        uint j = min(i, n - 1u);
        vec3 a = (st.info.w & 2u) != 0u ? mean : st.ramp_a[j].xyz;
        vec3 b = (st.info.w & 4u) != 0u ? mean : st.ramp_b[j].xyz;
        p.ramp[i] = vec4(clamp(a + u * (b - a), vec3(0.0), vec3(1.0)), st.ramp_a[j].w);
    }
}

// The output tone curve of `st` at u: knots blended, clamped, kept non-decreasing.
void lerp_tones(MorphStructure st, float u, inout Params p) {
    uint k = st.info.z;
    if (k == 0u || (u <= 0.0 && (st.info.w & 8u) != 0u)) {
        return;
    }
    p.pattern.w = k;
    p.tone_range = st.tone_range;
    for (uint i = 0u; i < k; i++) {
        vec4 v = clamp(st.tone_a[i] + u * (st.tone_b[i] - st.tone_a[i]), vec4(-4.0), vec4(4.0));
        if (i > 0u) {
            // Rounding must not break monotonicity.
            v = max(v, p.tone_knots[i - 1u]);
        }
        p.tone_knots[i] = v;
    }
    p.tone_tangents = fc_tangents(p.tone_knots, k);
}

// The pattern, ramp and tone curve a fraction u of the way through `st`.
void morph_structure(MorphStructure st, float u, inout Params p) {
    uint kind = st.info.x;
    if (kind == 0u) {
        // The noise model: no pattern or ramp, only its own tone curve (if any).
        lerp_tones(st, u, p);
        return;
    }
    p.pattern = uvec4(kind, st.info.y, MORPH_SEED, 0u);
    p.pattern_offsets = MORPH_PATTERN_OFFSETS;
    if ((st.info.w & 1u) != 0u) {
        float scale = exp(st.pose.x * (1.0 - u) + st.pose.w * u);
        float angle = radians(st.pose.y + u * st.pose.z);
        float inv = 1.0 / scale;
        p.pattern_transform = vec4(inv, cos(angle), sin(angle), log2(inv));
        for (int i = 0; i < 2; i++) {
            vec4 v = st.values_a[i] + u * (st.values_b[i] - st.values_a[i]);
            p.pattern_values[i] = clamp(v, st.value_min[i], st.value_max[i]);
        }
    } else {
        p.pattern_transform = st.transform;
        p.pattern_values = st.values_a;
    }
    lerp_ramps(st, u, p);
    lerp_tones(st, u, p);
}

// Defined in noise.glsl, which the export places after this file.
float gradient_variance2();
float gradient_variance3();
vec3 mixing(float angle_deg, float strength, float grad_var);

Params morph(MorphSegment seg, float t) {
    MorphKey a = seg.a;
    MorphKey b = seg.b;
    Params p;
    vec4 mean = a.mean + t * (b.mean - a.mean);
    p.mean = vec4(clamp(mean.xyz, vec3(0.0), vec3(1.0)), mean.w);
    p.basis = matrix_from_quat(slerp(a.quat, b.quat, t));
    float scale = exp(a.pose.x * (1.0 - t) + b.pose.x * t);
    float angle = radians(a.pose.y + t * a.pose.z);
    p.transform = vec4(1.0 / scale, cos(angle), sin(angle), 0.0);
    p.counts = seg.counts;
    vec4 energy = vec4(0.0);
    for (int j = 0; j < MAX_BANDS; j++) {
        vec4 w = max(a.weights[j] + t * (b.weights[j] - a.weights[j]), vec4(0.0));
        p.weights[j] = w;
        energy += w * w;
    }
    p.sigma = sqrt(energy);
    p.fine = max(a.fine + t * (b.fine - a.fine), vec4(0.0));
    p.offsets = MORPH_OFFSETS;
    float grad_var = seg.counts.z != 0u ? gradient_variance3() : gradient_variance2();
    for (int j = 0; j < MAX_BANDS; j++) {
        float phi = a.orient[j].x + t * (b.orient[j].x - a.orient[j].x);
        float s = clamp(sin(phi) * sin(phi), 0.0, 1.0);
        p.orient[j] = vec4(1.0, 0.0, 0.0, 0.0);
        if (s > 0.0) {
            p.orient[j] = vec4(mixing(a.orient[j].y + t * a.orient[j].z, s, grad_var), 0.0);
        }
    }
    p.pattern = uvec4(0u);
    for (int k = 0; k < MAX_KNOTS; k++) {
        p.knots[k] = vec4(0.0);
    }
    for (uint k = 0u; k < seg.counts.y; k++) {
        vec4 v = a.knots[k] + t * (b.knots[k] - a.knots[k]);
        if (k > 0u) {
            // Rounding must not break monotonicity.
            v = max(v, p.knots[k - 1u]);
        }
        p.knots[k] = v;
    }
    p.tangents = fc_tangents(p.knots, seg.counts.y);
    p.pattern = uvec4(0u, 0u, MORPH_SEED, 0u);
    p.pattern_transform = vec4(1.0, 1.0, 0.0, 0.0);
    for (int i = 0; i < 2; i++) {
        p.pattern_values[i] = vec4(0.0);
        p.tone_range[i] = vec4(0.0);
    }
    for (int i = 0; i < 5; i++) {
        p.pattern_offsets[i] = vec4(0.0);
    }
    for (int i = 0; i < 16; i++) {
        p.ramp[i] = vec4(0.0);
    }
    for (int i = 0; i < MAX_TONE_KNOTS; i++) {
        p.tone_knots[i] = vec4(0.0);
        p.tone_tangents[i] = vec4(0.0);
    }
    if (seg.mode.x == 1u) {
        morph_structure(seg.first, t, p);
    } else if (seg.mode.x == 2u) {
        if (t < 0.5) {
            morph_structure(seg.first, 2.0 * t, p);
        } else {
            morph_structure(seg.second, 2.0 * t - 1.0, p);
        }
    }
    return p;
}

Params morph_params(float t_in) {
    float t = clamp(t_in, 0.0, 1.0);
    if (t >= 1.0) {
        return morph_end(MORPH_SEGMENT_COUNT);
    }
    float segments = float(MORPH_SEGMENT_COUNT);
    float s = max(min(t * segments, segments - 1e-6), 0.0);
    uint i = uint(floor(s));
    float local_t = s - float(i);
    if (local_t == 0.0) {
        return morph_end(i);
    }
    return morph(morph_segment(i), local_t);
}
