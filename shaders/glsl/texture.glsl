// The procedural texture at a point (GLSL twin of shaders/texture.wgsl; Rust twins in
// analyzer/src/render.rs: Prepared::texel, fine_value, texture_noise, colour, tone_excursion,
// tone_eval, shade).

vec3 texel(vec3 world) {
    float c = params.transform.y;
    float s = params.transform.z;
    float inv_scale = params.transform.x;
    return vec3(
        (c * world.x + s * world.y) * inv_scale,
        (-s * world.x + c * world.y) * inv_scale,
        world.z * inv_scale);
}

// The three channels' noise at a point: the weighted sum of bands that the histogram maps,
// and the finest band's part drawn after it (params.fine).
struct ChannelNoise {
    vec3 sum;
    vec3 fine;
};

// The finest band's part after the histogram at the band's unit-variance values `v`: bounded,
// of the band's variance (analyzer/src/render.rs: FINE_GAIN, fine_value).
const float FINE_GAIN = 1.5925374;

vec3 fine_value(vec3 v) {
    return FINE_GAIN * tanh(v);
}

// The three channels' multiresolution noise: every band read once (one RGBA fetch per tap);
// the finest band's part after the histogram apart.
ChannelNoise texture_noise(vec3 u, float log2_fp) {
    ChannelNoise n = ChannelNoise(vec3(0.0), vec3(0.0));
    for (uint j = 0u; j < params.counts.x; j++) {
        float fade = band_fade(j, log2_fp);
        vec3 w = params.weights[j].xyz * fade;
        vec3 fw = vec3(0.0);
        if (j == 0u) {
            fw = params.fine.xyz * fade;
        }
        if (all(equal(w, vec3(0.0))) && all(equal(fw, vec3(0.0)))) {
            continue;
        }
        float f = 1.0 / float(1u << j);
        vec3 o = params.offsets[j].xyz;
        vec3 m = params.orient[j].xyz;
        bool isotropic = m.y == 0.0 && m.z == 0.0;
        vec3 v;
#ifdef PROCTEX_SOLID
        vec3 p = vec3(u.x * f + o.x, u.y * f + o.y, u.z * f + o.z);
        if (isotropic) {
            v = wavelet_noise3(p);
        } else {
            v = wavelet_noise3_oriented(p, m);
        }
#else
        vec2 p = vec2(u.x * f + o.x, u.y * f + o.y);
        if (isotropic) {
            v = wavelet_noise2(p);
        } else {
            v = wavelet_noise2_oriented(p, m);
        }
#endif
        n.sum += w * v;
        n.fine += fw * fine_value(v);
    }
    return n;
}

// The output tone curve of RGB channel c at v (either model): the Hermite spline through
// knots evenly spaced over [lo, hi], clamped to its end knots outside.
float tone_eval(int c, float v) {
    uint k = params.pattern.w - 1u;
    float u = (v - params.tone_range[0][c]) * params.tone_range[1][c];
    float s = clamp(u, 0.0, 1.0) * float(k);
    uint i = min(uint(floor(s)), k - 1u);
    return hermite(s - float(i), 1.0 / float(k), params.tone_knots[i][c], params.tone_tangents[i][c],
        params.tone_knots[i + 1u][c], params.tone_tangents[i + 1u][c]);
}

// What a structured model's output tone curve makes of the residual on the ramp's colour (one
// RGB channel): the residual through the curve where the curve compresses it, the residual
// itself where the curve would stretch it (a pixel-scale excursion through a steep stretch is
// a speck).
float tone_excursion(float through, float residual) {
    if (abs(through) > abs(residual)) {
        return residual;
    }
    return through;
}

// The colour of the three channels' noise n on the structured models' ramp colour base
// (ignored by the noise model): histogram matching of the bands' sum, the finest band's part
// after it, contrast, back to RGB, then the model's output tone curve. A structured model's
// curve maps the ramp's colour, and the residual follows it (tone_excursion).
vec3 colour(ChannelNoise n, vec3 base) {
    vec3 g = n.sum;
    vec3 rgb = params.mean.xyz;
    if (params.pattern.x != 0u) {
        for (int i = 0; i < 3; i++) {
            rgb[i] += params.mean.w * (base[i] - params.mean[i]);
        }
    }
    uint k = params.counts.y;
    bool residual_after_tone = params.pattern.x != 0u && params.pattern.w >= 2u;
    vec3 residual = vec3(0.0);
    for (int c = 0; c < 3; c++) {
        float v;
        if (params.counts.w != 0u && params.sigma[c] > 0.0) {
            v = spline_eval(c, knot_coordinate(g[c], params.sigma[c]));
        } else if (params.counts.w != 0u) {
            v = params.knots[k / 2u][c];
        } else {
            v = g[c];
        }
        if (residual_after_tone) {
            float cv = params.mean.w * v;
            float cf = params.mean.w * n.fine[c];
            residual += (cv + cf) * params.basis[c].xyz;
        } else {
            float cv = params.mean.w * (v + n.fine[c]);
            rgb += cv * params.basis[c].xyz;
        }
    }
    if (params.pattern.w >= 2u) {
        for (int c = 0; c < 3; c++) {
            float t = tone_eval(c, rgb[c]);
            if (residual[c] != 0.0) {
                rgb[c] = t + tone_excursion(tone_eval(c, rgb[c] + residual[c]) - t, residual[c]);
            } else {
                rgb[c] = t;
            }
        }
    }
    return rgb;
}

vec3 shade(vec3 world, float log2_fp) {
    vec3 u = texel(world);
    vec3 base = params.mean.xyz;
    if (params.pattern.x != 0u) {
        base = ramp(pattern(u, log2_fp));
    }
    return colour(texture_noise(u, log2_fp), base);
}
