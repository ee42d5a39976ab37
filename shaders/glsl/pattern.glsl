// Structured models (GLSL twin of shaders/pattern.wgsl; Rust twins in analyzer/src/pattern.rs):
// the pattern's structure value s in [0, 1] at a texel, and the colour ramp along s.

#define PATTERN_OCTAVES 5u
// rng::stream::CELLS
#define CELLS_STREAM 0x63656c6cu
// pattern::WARP_OFFSET
#define WARP_OFFSET 19.3

float soft_step(float e0, float w, float x) {
    float t = clamp((x - e0) / w, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

float cell_hash(int ix, int iy, uint k) {
    uint index = (uint(ix) * 0x8da6b343u) ^ (uint(iy) * 0xd8163841u) ^ k;
    return uniform01(params.pattern.z, CELLS_STREAM, index);
}

// Cell index i wrapped at n cells (a seamless tile's lattice); i itself for n = 0.
int wrap_cell(int i, int n) {
    if (n > 0) {
        float fi = float(i);
        float fc = float(n);
        return int(fi - fc * floor(fi / fc));
    }
    return i;
}

// The whole number of cells of width pitch (and rows of height 1) that the periods wrap hold;
// (0, 0) (no wrap) for wrap.x = 0.
ivec2 wrap_cells(float pitch, vec2 wrap) {
    if (wrap.x > 0.0) {
        return ivec2(int(floor(wrap.x / pitch + 0.5)), int(floor(wrap.y + 0.5)));
    }
    return ivec2(0, 0);
}

float cell_hash_wrapped(int ix, int iy, uint k, ivec2 cells) {
    return cell_hash(wrap_cell(ix, cells.x), wrap_cell(iy, cells.y), k);
}

// Lower edge of row k of planks: k + widths·(hash(k) − ½), the hash wrapped at rows (0: not).
float plank_edge(int k, float widths, int rows) {
    return float(k) + widths * (cell_hash_wrapped(0, k, 2u, ivec2(0, rows)) - 0.5);
}

// The row of planks that y falls in and its edges: (row, lower, upper).
vec3 plank_row(float y, float widths, int rows) {
    int k = int(floor(y));
    float lo = plank_edge(k, widths, rows);
    float hi = plank_edge(k + 1, widths, rows);
    if (y < lo) {
        return vec3(float(k - 1), plank_edge(k - 1, widths, rows), lo);
    }
    if (y >= hi) {
        return vec3(float(k + 1), hi, plank_edge(k + 2, widths, rows));
    }
    return vec3(float(k), lo, hi);
}

// Octave k at q; with per.x > 0 (seamless tiles, plane textures) q repeats with period per and
// the octave's frequency moves to a whole number of coefficients over it.
float octave(vec3 q, uint k, vec2 per) {
    float f = float(1u << k);
    vec3 o = params.pattern_offsets[k].xyz;
#ifdef PROCTEX_SOLID
    return wavelet_noise3(vec3(q.x * f + o.x, q.y * f + o.y, q.z * f + o.z)).x;
#else
    if (per.x > 0.0) {
        float n = float(textureSize(proctex_tile2, 0).x);
        vec2 m = vec2(whole_period(per.x * f, n), whole_period(per.y * f, n));
        return noise2_periodic(vec2(q.x / per.x * m.x + o.x, q.y / per.y * m.y + o.y), m).x;
    }
    return wavelet_noise2(vec2(q.x * f + o.x, q.y * f + o.y)).x;
#endif
}

// A ridged octave's crest exp(-sharpness*|n|) as a pixel shows it (Rust: crest): at least a pixel
// wide, averaged over n +- g/2, g the noise's change across the pixel.
float crest(float n, float sharpness, float g) {
    float s = min(sharpness, 2.0 / max(g, 1e-6));
    float h = 0.5 * g;
    if (s * h < 1e-3) {
        return exp(-s * abs(n));
    }
    float hi = sign(n + h) * (1.0 - exp(-s * abs(n + h))) / s;
    float lo = sign(n - h) * (1.0 - exp(-s * abs(n - h))) / s;
    return (hi - lo) / (2.0 * h);
}

// The octaves summed: n (mode 0, fractal noise) or |n| (1, turbulence) (Rust: octaves).
float octaves(vec3 q, float gain, uint mode, float lfp, vec2 per) {
    float sum = 0.0;
    float norm = 0.0;
    float amp = 1.0;
    for (uint k = 0u; k < PATTERN_OCTAVES; k++) {
        float fade = band_fade(0u, lfp + float(k));
        if (fade > 0.0) {
            float n = octave(q, k, per);
            float v = n;
            if (mode == 1u) {
                v = abs(n);
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

// The lines' profile (1/2 + 1/2 sin 2 pi v)^sharpness as a pixel shows it (Rust: line_profile):
// the sharpness bounded so that a line is at least a pixel wide, averaged over v +- g/2 (g the
// change of v across the pixel) on four points.
float line_profile(float v, float sharpness, float g_in) {
    float g = max(g_in, 1e-6);
    float s = min(sharpness, 4.0 / (3.1415927 * 3.1415927 * g * g));
    if (g < 1e-4) {
        return pow(max(0.5 + 0.5 * sin(6.2831855 * v), 1e-6), s);
    }
    float sum = 0.0;
    for (uint i = 0u; i < 4u; i++) {
        float x = v + (0.25 * float(i) - 0.375) * g;
        sum += pow(max(0.5 + 0.5 * sin(6.2831855 * x), 1e-6), s);
    }
    return 0.25 * sum;
}

// How much a coordinate changes across a pixel (Rust: pixel_change): forward differences.
float pixel_change(float at, float ax, float ay) {
    float dx = ax - at;
    float dy = ay - at;
    return sqrt(dx * dx + dy * dy);
}

// Ridged's octaves: each octave's crest over the noise's change across the pixel where it is,
// forward differences one pixel step along the pattern's axes (Rust: ridged_octaves).
float ridged_octaves(vec3 q, vec2 pixel_step, float gain, float sharpness, float lfp, vec2 per) {
    float sum = 0.0;
    float norm = 0.0;
    float amp = 1.0;
    for (uint k = 0u; k < PATTERN_OCTAVES; k++) {
        float fade = band_fade(0u, lfp + float(k));
        if (fade > 0.0) {
            float n = octave(q, k, per);
            float nx = octave(vec3(q.x + pixel_step.x, q.y, q.z), k, per);
            float ny = octave(vec3(q.x, q.y + pixel_step.y, q.z), k, per);
            sum += amp * fade * crest(n, sharpness, pixel_change(n, nx, ny));
        }
        norm += amp;
        amp *= gain;
    }
    return sum / norm;
}

// The wood lines' coordinate at pattern point q (Rust: wood_line_coordinate).
float wood_line_coordinate(vec3 q, float lfp, vec2 per) {
    vec4 w0 = params.pattern_values[0];
    float n = octaves(vec3(0.25 * q.x / w0.x, 0.25 * q.y, 0.25 * q.z), w0.w, 0u,
        lfp - 2.0, per);
    return q.y + w0.y * n;
}

// The rings' coordinate at point p from their centre (Rust: ring_coordinate).
float ring_coordinate(vec3 p, float lfp, vec2 per) {
    vec4 w0 = params.pattern_values[0];
    float n = octaves(vec3(0.25 * p.x, 0.25 * p.y, 0.25 * p.z), w0.z, 0u, lfp - 2.0,
        0.25 * per);
    return sqrt(p.x * p.x + p.y * p.y) + w0.x * n;
}

float joint_distance(float fx, float fy, float aspect) {
    return min(min(fx, 1.0 - fx) * aspect, min(fy, 1.0 - fy));
}

float pattern_at(vec3 q, float lfp, vec2 wrap);

float pattern(vec3 u, float log2_fp) {
    vec4 xf = params.pattern_transform;
    float is = xf.x;
    float c = xf.y;
    float s = xf.z;
    vec3 q = vec3((c * u.x + s * u.y) * is, (-s * u.x + c * u.y) * is, u.z * is);
    return pattern_at(q, log2_fp + xf.w, vec2(0.0, 0.0));
}

// The structure value at pattern point q; wrap (0: none) makes it repeat with period wrap
// along the pattern's axes (seamless tiles).
float pattern_at(vec3 q, float lfp, vec2 wrap) {
    float c = params.pattern_transform.y;
    float s = params.pattern_transform.z;
    vec4 w0 = params.pattern_values[0];
    vec4 w1 = params.pattern_values[1];
    float soft = exp2(lfp);
    switch (params.pattern.x) {
    case 1u: {
        // perlin: stretch, roughness, contrast, threshold
        vec2 per = vec2(wrap.x / w0.x, wrap.y);
        float n = octaves(vec3(q.x / w0.x, q.y, q.z), w0.y, 0u, lfp, per);
        return 1.0 / (1.0 + exp(-w0.z * (n - w0.w)));
    }
    case 2u: {
        // turbulence: stretch, roughness, contrast
        vec2 per = vec2(wrap.x / w0.x, wrap.y);
        float t = octaves(vec3(q.x / w0.x, q.y, q.z), w0.y, 1u, lfp, per);
        return 1.0 - exp(-w0.z * t);
    }
    case 3u: {
        // ridged: stretch, roughness, sharpness
        vec2 per = vec2(wrap.x / w0.x, wrap.y);
        return ridged_octaves(vec3(q.x / w0.x, q.y, q.z), vec2(soft / w0.x, soft), w0.y, w0.z,
            lfp, per);
    }
    case 4u: {
        // grid: aspect, mortar, bevel, variation
        ivec2 n = wrap_cells(w0.x, wrap);
        float x = q.x / w0.x;
        float ix = floor(x);
        float iy = floor(q.y);
        float d = joint_distance(x - ix, q.y - iy, w0.x);
        float shade = 1.0 - w0.w * cell_hash_wrapped(int(ix), int(iy), 0u, n);
        return soft_step(0.5 * w0.y, max(w0.z, soft), d) * shade;
    }
    case 5u: {
        // brick: aspect, mortar, row_offset, jitter, bevel, variation
        ivec2 n = wrap_cells(w0.x, wrap);
        float iy = floor(q.y);
        float row = iy;
        float offset = w0.z;
        if (n.y > 0) {
            float rows = float(n.y);
            row = float(wrap_cell(int(iy), n.y));
            offset = floor(w0.z * rows + 0.5) / rows;
        }
        float shift = row * offset + w0.w * (cell_hash(0, int(row), 1u) - 0.5);
        float x = q.x / w0.x + shift;
        float ix = floor(x);
        float d = joint_distance(x - ix, q.y - iy, w0.x);
        float shade = 1.0 - w1.y * cell_hash_wrapped(int(ix), int(iy), 0u, n);
        return soft_step(0.5 * w0.y, max(w1.x, soft), d) * shade;
    }
    case 6u: {
        // cells: jitter, mortar, bevel, variation, stretch, stagger, warp
        ivec2 n = wrap_cells(w1.x, wrap);
        vec2 p = vec2(q.x / w1.x, q.y);
        if (w1.z > 0.0) {
            vec2 per = vec2(0.25 * wrap.x / w1.x, 0.25 * wrap.y);
            vec3 b = vec3(0.25 * p.x, 0.25 * p.y, 0.25 * q.z);
            float gx = octaves(b, 0.5, 0u, lfp - 2.0, per);
            vec3 b2 = vec3(b.x + WARP_OFFSET, b.y, b.z);
            float gy = octaves(b2, 0.5, 0u, lfp - 2.0, per);
            p = vec2(p.x + w1.z * gx, p.y + w1.z * gy);
        }
        float iy = floor(p.y);
        float fy = p.y - iy;
        float f1 = 1e9;
        float f2 = 1e9;
        ivec2 id = ivec2(0, 0);
        for (int dy = -1; dy <= 1; dy++) {
            int cy = int(iy) + dy;
            float shift = 0.5 * w1.y * float(wrap_cell(cy, n.y) & 1);
            float x = p.x - shift;
            float ix = floor(x);
            float fx = x - ix;
            for (int dx = -1; dx <= 1; dx++) {
                int cx = int(ix) + dx;
                float px = float(dx) + 0.5 + w0.x * (cell_hash_wrapped(cx, cy, 0u, n) - 0.5);
                float py = float(dy) + 0.5 + w0.x * (cell_hash_wrapped(cx, cy, 1u, n) - 0.5);
                float ex = px - fx;
                float ey = py - fy;
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
        float shade = 1.0 - w0.w * cell_hash_wrapped(id.x, id.y, 2u, n);
        return soft_step(0.5 * w0.y, max(w0.z, soft), edge) * shade;
    }
    case 7u: {
        // planks: length, gap, bevel, variation, grain, widths
        ivec2 n = wrap_cells(w0.x, wrap);
        vec3 r = plank_row(q.y, w1.y, n.y);
        float iy = r.x;
        float x = q.x / w0.x + cell_hash_wrapped(0, int(iy), 1u, ivec2(0, n.y));
        float ix = floor(x);
        float fx = x - ix;
        float d = min(min(fx, 1.0 - fx) * w0.x, min(q.y - r.y, r.z - q.y));
        vec2 per = vec2(wrap.x * 0.125, wrap.y * 4.0);
        float g = octaves(vec3(q.x * 0.125, q.y * 4.0, q.z), 0.5, 0u, lfp + 2.0, per);
        float shade = (1.0 - w0.w * cell_hash_wrapped(int(ix), int(iy), 0u, n))
            * (1.0 - w1.x * (0.5 + 0.5 * tanh(g)));
        return soft_step(0.5 * w0.y, max(w0.z, soft), d) * shade;
    }
    case 8u: {
        // wood lines: stretch, distortion, sharpness, roughness
        vec2 per = vec2(0.25 * wrap.x / w0.x, 0.25 * wrap.y);
        float v = wood_line_coordinate(q, lfp, per);
        float vx = wood_line_coordinate(q + vec3(soft, 0.0, 0.0), lfp, per);
        float vy = wood_line_coordinate(q + vec3(0.0, soft, 0.0), lfp, per);
        return line_profile(v, w0.z, pixel_change(v, vx, vy));
    }
    case 9u: {
        // rings: distortion, sharpness, roughness, stretch, centre_x, centre_y; with wrap, the
        // torus distance to the centre
        vec2 qc = vec2(c * w1.x + s * w1.y, -s * w1.x + c * w1.y);
        vec3 p = vec3((q.x - qc.x) / w0.w, q.y - qc.y, q.z);
        vec2 per = vec2(wrap.x / w0.w, wrap.y);
        if (wrap.x > 0.0) {
            p.x -= per.x * floor(p.x / per.x + 0.5);
            p.y -= per.y * floor(p.y / per.y + 0.5);
        }
        float r = ring_coordinate(p, lfp, per);
        float rx = ring_coordinate(p + vec3(soft / w0.w, 0.0, 0.0), lfp, per);
        float ry = ring_coordinate(p + vec3(0.0, soft, 0.0), lfp, per);
        return line_profile(r, w0.y, pixel_change(r, rx, ry));
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
