// Seamless tiles (the PNG tile export): every band made periodic over the tile. Twins:
// analyzer/src/seamless.rs (texture_noise_wrapped, pattern_wrapped, seamless_pixel; the entry
// points' twin is render_rows). Same operation order, f32. Periodic noise: noise2_periodic
// (noise.wgsl); periodic patterns: pattern_at (pattern.wgsl).
// Renders in strips: the target is `size` wide and a few rows high, `first_row` says which.

struct Seamless {
    // band j spans periods[j / 4][j % 4] coefficients over the tile (whole numbers)
    periods: array<vec4<f32>, 3>,
    // size (pixels), log2 footprint, first row of this strip, unused
    tile: vec4<f32>,
    // structured models: the pattern's periods over the tile along its axes, cos and sin of
    // its rotation moved to a quarter turn
    pattern: vec4<f32>,
}

@group(1) @binding(0) var<uniform> seamless: Seamless;

fn texture_noise_wrapped(a: vec2<f32>) -> ChannelNoise {
    var n = ChannelNoise(vec3<f32>(0.0), vec3<f32>(0.0));
    for (var j = 0u; j < params.counts.x; j++) {
        let fade = band_fade(j, seamless.tile.y);
        let w = params.weights[j].xyz * fade;
        var fw = vec3<f32>(0.0);
        if (j == 0u) {
            fw = params.fine.xyz * fade;
        }
        if (all(w == vec3<f32>(0.0)) && all(fw == vec3<f32>(0.0))) {
            continue;
        }
        let m = seamless.periods[j / 4u][j % 4u];
        let o = params.offsets[j].xyz;
        let p = vec2<f32>(a.x * m + o.x, a.y * m + o.y);
        let mix = params.orient[j].xyz;
        var v: vec3<f32>;
        if (mix.y == 0.0 && mix.z == 0.0) {
            v = noise2_periodic(p, vec2<f32>(m, m));
        } else {
            v = noise2_periodic_oriented(p, vec2<f32>(m, m), mix);
        }
        n.sum += w * v;
        n.fine += fw * fine_value(v);
    }
    return n;
}

fn pattern_wrapped(a: vec2<f32>) -> f32 {
    let xf = seamless.pattern;
    let q = vec3<f32>(xf.x * (xf.z * a.x + xf.w * a.y), xf.y * (-xf.w * a.x + xf.z * a.y), 0.0);
    return pattern_at(q, seamless.tile.y + params.pattern_transform.w, xf.xy);
}

fn seamless_pixel(frag: vec2<f32>) -> vec3<f32> {
    let size = seamless.tile.x;
    let a = vec2<f32>(frag.x / size, (frag.y + seamless.tile.z) / size);
    var base = params.mean.xyz;
    if (params.pattern.x != 0u) {
        base = ramp(pattern_wrapped(a));
    }
    return colour(texture_noise_wrapped(a), base);
}

@vertex
fn vs_seamless(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32(i32(i & 1u) * 4 - 1);
    let y = f32(i32(i >> 1u) * 4 - 1);
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn fs_seamless(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    return vec4<f32>(seamless_pixel(frag.xy), 1.0);
}
