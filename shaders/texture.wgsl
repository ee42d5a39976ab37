// The procedural texture at a point. Twins: analyzer/src/render.rs (Prepared::texel,
// fine_value, texture_noise, colour, tone_excursion, tone_eval, shade).

fn texel(world: vec3<f32>) -> vec3<f32> {
    let c = params.transform.y;
    let s = params.transform.z;
    let inv_scale = params.transform.x;
    return vec3<f32>(
        (c * world.x + s * world.y) * inv_scale,
        (-s * world.x + c * world.y) * inv_scale,
        world.z * inv_scale,
    );
}

// The three channels' noise at a point: the weighted sum of bands that the histogram maps,
// and the finest band's part drawn after it (params.fine).
struct ChannelNoise {
    sum: vec3<f32>,
    fine: vec3<f32>,
}

// The finest band's part after the histogram at the band's unit-variance values `v`: bounded,
// of the band's variance (analyzer/src/render.rs: FINE_GAIN, fine_value).
const FINE_GAIN: f32 = 1.5925374;

fn fine_value(v: vec3<f32>) -> vec3<f32> {
    return FINE_GAIN * tanh(v);
}

// The three channels' multiresolution noise: every band read once (one RGBA fetch per tap),
// its tile components weighted per channel; the finest band's part after the histogram apart.
fn texture_noise(u: vec3<f32>, log2_fp: f32) -> ChannelNoise {
    var n = ChannelNoise(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var j = 0u; j < params.counts.x; j++) {
        let fade = band_fade(j, log2_fp);
        let w = params.weights[j].xyz * fade;
        var fw = vec3<f32>(0.0);
        if (j == 0u) {
            fw = params.fine.xyz * fade;
        }
        if (all(w == vec3<f32>(0.0)) && all(fw == vec3<f32>(0.0))) {
            continue;
        }
        let f = 1.0 / f32(1u << j);
        let o = params.offsets[j].xyz;
        let m = params.orient[j].xyz;
        let isotropic = m.y == 0.0 && m.z == 0.0;
        var v: vec3<f32>;
        if (params.counts.z != 0u) {
            let p = vec3<f32>(u.x * f + o.x, u.y * f + o.y, u.z * f + o.z);
            if (isotropic) {
                v = noise3(p);
            } else {
                v = noise3_oriented(p, m);
            }
        } else {
            let p = vec2<f32>(u.x * f + o.x, u.y * f + o.y);
            if (isotropic) {
                v = noise2(p);
            } else {
                v = noise2_oriented(p, m);
            }
        }
        n.sum += w * v;
        n.fine += fw * fine_value(v);
    }
    return n;
}

// The colour of the three channels' noise n on the structured models' ramp colour base
// (ignored by the noise model): histogram matching of the bands' sum, the finest band's part
// after it, contrast, back to RGB, then the model's output tone curve. A structured model's
// curve maps the ramp's colour, and the residual follows it (tone_excursion).
fn colour(n: ChannelNoise, base: vec3<f32>) -> vec3<f32> {
    let g = n.sum;
    var rgb = params.mean.xyz;
    if (params.pattern.x != 0u) {
        for (var i = 0u; i < 3u; i++) {
            rgb[i] += params.mean.w * (base[i] - params.mean[i]);
        }
    }
    let k = params.counts.y;
    let residual_after_tone = params.pattern.x != 0u && params.pattern.w >= 2u;
    var residual = vec3<f32>(0.0);
    for (var c = 0u; c < 3u; c++) {
        var v: f32;
        if (params.counts.w != 0u && params.sigma[c] > 0.0) {
            v = spline_eval(c, knot_coordinate(g[c], params.sigma[c]));
        } else if (params.counts.w != 0u) {
            v = params.knots[k / 2u][c];
        } else {
            v = g[c];
        }
        if (residual_after_tone) {
            let cv = params.mean.w * v;
            let cf = params.mean.w * n.fine[c];
            residual += (cv + cf) * params.basis[c].xyz;
        } else {
            let cv = params.mean.w * (v + n.fine[c]);
            rgb += cv * params.basis[c].xyz;
        }
    }
    if (params.pattern.w >= 2u) {
        for (var c = 0u; c < 3u; c++) {
            let t = tone_eval(c, rgb[c]);
            if (residual[c] != 0.0) {
                rgb[c] = t + tone_excursion(tone_eval(c, rgb[c] + residual[c]) - t, residual[c]);
            } else {
                rgb[c] = t;
            }
        }
    }
    return rgb;
}

// What a structured model's output tone curve makes of the residual on the ramp's colour (one
// RGB channel): the residual through the curve where the curve compresses it, the residual
// itself where the curve would stretch it (a pixel-scale excursion through a steep stretch is
// a speck).
fn tone_excursion(through: f32, residual: f32) -> f32 {
    if (abs(through) > abs(residual)) {
        return residual;
    }
    return through;
}

// The output tone curve of RGB channel c at v (either model): the Hermite spline through
// knots evenly spaced over [lo, hi], clamped to its end knots outside.
fn tone_eval(c: u32, v: f32) -> f32 {
    let k = params.pattern.w - 1u;
    let u = (v - params.tone_range[0][c]) * params.tone_range[1][c];
    let s = clamp(u, 0.0, 1.0) * f32(k);
    let i = min(u32(floor(s)), k - 1u);
    return hermite(s - f32(i), 1.0 / f32(k), params.tone_knots[i][c], params.tone_tangents[i][c],
        params.tone_knots[i + 1u][c], params.tone_tangents[i + 1u][c]);
}

fn shade(world: vec3<f32>, log2_fp: f32) -> vec3<f32> {
    let u = texel(world);
    var base = params.mean.xyz;
    if (params.pattern.x != 0u) {
        base = ramp(pattern(u, log2_fp));
    }
    return colour(texture_noise(u, log2_fp), base);
}
