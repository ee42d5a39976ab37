// Structured models (GLSL twin of shaders/pattern.wgsl; Rust twins in analyzer/src/pattern.rs):
// the pattern's structure value s in [0, 1] at a texel, and the colour ramp along s.

#define PATTERN_OCTAVES 5u
// rng::stream::CELLS
#define CELLS_STREAM 0x63656c6cu

float soft_step(float e0, float w, float x) {
    float t = clamp((x - e0) / w, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

float cell_hash(int ix, int iy, uint k) {
    uint index = (uint(ix) * 0x8da6b343u) ^ (uint(iy) * 0xd8163841u) ^ k;
    return uniform01(params.pattern.z, CELLS_STREAM, index);
}

float octave(vec3 q, uint k) {
    float f = float(1u << k);
    vec3 o = params.pattern_offsets[k].xyz;
#ifdef PROCTEX_SOLID
    return wavelet_noise3(vec3(q.x * f + o.x, q.y * f + o.y, q.z * f + o.z));
#else
    return wavelet_noise2(vec2(q.x * f + o.x, q.y * f + o.y));
#endif
}

// The octaves summed: n (mode 0, fractal noise), |n| (1, turbulence) or exp(-sharpness*|n|) (2,
// ridged).
float octaves(vec3 q, float gain, uint mode, float sharpness, float lfp) {
    float sum = 0.0;
    float norm = 0.0;
    float amp = 1.0;
    for (uint k = 0u; k < PATTERN_OCTAVES; k++) {
        float fade = band_fade(0u, lfp + float(k));
        if (fade > 0.0) {
            float n = octave(q, k);
            float v = n;
            if (mode == 1u) {
                v = abs(n);
            } else if (mode == 2u) {
                v = exp(-sharpness * abs(n));
            }
            sum += amp * fade * v;
        }
        if (mode == 0u) {
            norm += amp * amp;
        } else {
            norm += amp;
        }
        amp *= gain;
    }
    if (mode == 0u) {
        return sum / sqrt(norm);
    }
    return sum / norm;
}

float joint_distance(float fx, float fy, float aspect) {
    return min(min(fx, 1.0 - fx) * aspect, min(fy, 1.0 - fy));
}

float pattern(vec3 u, float log2_fp) {
    vec4 xf = params.pattern_transform;
    float is = xf.x;
    float c = xf.y;
    float s = xf.z;
    vec3 q = vec3((c * u.x + s * u.y) * is, (-s * u.x + c * u.y) * is, u.z * is);
    float lfp = log2_fp + xf.w;
    vec4 w0 = params.pattern_values[0];
    vec4 w1 = params.pattern_values[1];
    float soft = exp2(lfp);
    switch (params.pattern.x) {
    case 1u: {
        // perlin: stretch, roughness, contrast, threshold
        float n = octaves(vec3(q.x / w0.x, q.y, q.z), w0.y, 0u, 0.0, lfp);
        return 1.0 / (1.0 + exp(-w0.z * (n - w0.w)));
    }
    case 2u: {
        // turbulence: stretch, roughness, contrast
        float t = octaves(vec3(q.x / w0.x, q.y, q.z), w0.y, 1u, 0.0, lfp);
        return 1.0 - exp(-w0.z * t);
    }
    case 3u: {
        // ridged: stretch, roughness, sharpness
        return octaves(vec3(q.x / w0.x, q.y, q.z), w0.y, 2u, w0.z, lfp);
    }
    case 4u: {
        // grid: aspect, mortar, bevel, variation
        float x = q.x / w0.x;
        float ix = floor(x);
        float iy = floor(q.y);
        float d = joint_distance(x - ix, q.y - iy, w0.x);
        float shade = 1.0 - w0.w * cell_hash(int(ix), int(iy), 0u);
        return soft_step(0.5 * w0.y, max(w0.z, soft), d) * shade;
    }
    case 5u: {
        // brick: aspect, mortar, row_offset, jitter, bevel, variation
        float iy = floor(q.y);
        float shift = iy * w0.z + w0.w * (cell_hash(0, int(iy), 1u) - 0.5);
        float x = q.x / w0.x + shift;
        float ix = floor(x);
        float d = joint_distance(x - ix, q.y - iy, w0.x);
        float shade = 1.0 - w1.y * cell_hash(int(ix), int(iy), 0u);
        return soft_step(0.5 * w0.y, max(w1.x, soft), d) * shade;
    }
    case 6u: {
        // cells: jitter, mortar, bevel, variation, stretch
        vec2 p = vec2(q.x / w1.x, q.y);
        float ix = floor(p.x);
        float iy = floor(p.y);
        vec2 f = vec2(p.x - ix, p.y - iy);
        float f1 = 1e9;
        float f2 = 1e9;
        ivec2 id = ivec2(0, 0);
        for (int dy = -1; dy <= 1; dy++) {
            for (int dx = -1; dx <= 1; dx++) {
                int cx = int(ix) + dx;
                int cy = int(iy) + dy;
                float px = float(dx) + 0.5 + w0.x * (cell_hash(cx, cy, 0u) - 0.5);
                float py = float(dy) + 0.5 + w0.x * (cell_hash(cx, cy, 1u) - 0.5);
                float ex = px - f.x;
                float ey = py - f.y;
                float d = ex * ex + ey * ey;
                if (d < f1) {
                    f2 = f1;
                    f1 = d;
                    id = ivec2(cx, cy);
                } else if (d < f2) {
                    f2 = d;
                }
            }
        }
        float edge = 0.5 * (sqrt(f2) - sqrt(f1));
        float shade = 1.0 - w0.w * cell_hash(id.x, id.y, 2u);
        return soft_step(0.5 * w0.y, max(w0.z, soft), edge) * shade;
    }
    case 7u: {
        // planks: length, gap, bevel, variation, grain
        float iy = floor(q.y);
        float x = q.x / w0.x + cell_hash(0, int(iy), 1u);
        float ix = floor(x);
        float d = joint_distance(x - ix, q.y - iy, w0.x);
        float n = octaves(vec3(q.x * 0.125, q.y * 4.0, q.z), 0.5, 0u, 0.0, lfp + 2.0);
        float shade = (1.0 - w0.w * cell_hash(int(ix), int(iy), 0u))
            * (1.0 - w1.x * (0.5 + 0.5 * tanh(n)));
        return soft_step(0.5 * w0.y, max(w0.z, soft), d) * shade;
    }
    case 8u: {
        // wood lines: stretch, distortion, sharpness, roughness
        float n = octaves(vec3(0.25 * q.x / w0.x, 0.25 * q.y, 0.25 * q.z), w0.w, 0u, 0.0, lfp - 2.0);
        float v = q.y + w0.y * n;
        return pow(max(0.5 + 0.5 * sin(6.2831855 * v), 1e-6), w0.z);
    }
    case 9u: {
        // rings: distortion, sharpness, roughness, stretch, centre_x, centre_y
        vec2 qc = vec2(c * w1.x + s * w1.y, -s * w1.x + c * w1.y);
        vec3 p = vec3((q.x - qc.x) / w0.w, q.y - qc.y, q.z);
        float n = octaves(vec3(0.25 * p.x, 0.25 * p.y, 0.25 * p.z), w0.z, 0u, 0.0, lfp - 2.0);
        float r = sqrt(p.x * p.x + p.y * p.y) + w0.x * n;
        return pow(max(0.5 + 0.5 * sin(6.2831855 * r), 1e-6), w0.y);
    }
    default:
        return 0.0;
    }
}

vec3 ramp(float s) {
    uint n = params.pattern.y;
    if (s <= params.ramp[0].w) {
        return params.ramp[0].xyz;
    }
    for (uint i = 1u; i < n; i++) {
        if (s < params.ramp[i].w) {
            vec4 a = params.ramp[i - 1u];
            vec4 b = params.ramp[i];
            float t = (s - a.w) / (b.w - a.w);
            return a.xyz + (b.xyz - a.xyz) * t;
        }
    }
    return params.ramp[n - 1u].xyz;
}
