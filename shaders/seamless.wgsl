// Seamless tiles (the PNG tile export): every band made periodic over the tile. Twins:
// analyzer/src/seamless.rs (wrap_period, noise2_wrapped, channel_noise_wrapped,
// seamless_pixel; the entry points' twin is render_rows). Same operation order, f32.
// Renders in strips: the target is `size` wide and a few rows high, `first_row` says which.

struct Seamless {
    // band j spans periods[j / 4][j % 4] coefficients over the tile (whole numbers)
    periods: array<vec4<f32>, 3>,
    // size (pixels), log2 footprint, first row of this strip, unused
    tile: vec4<f32>,
}

@group(1) @binding(0) var<uniform> seamless: Seamless;

fn wrap_period(i: i32, m: i32) -> i32 {
    return ((i % m) + m) % m;
}

fn noise2_wrapped(p: vec2<f32>, period: f32) -> f32 {
    let pw = min(period, f32(textureDimensions(tile2).x));
    let pi = i32(pw);
    let bx = bspline_weights(wrap_coord(p.x, pw));
    let by = bspline_weights(wrap_coord(p.y, pw));
    let cols = vec3<i32>(
        wrap_period(bx.mid - 1, pi),
        wrap_period(bx.mid, pi),
        wrap_period(bx.mid + 1, pi),
    );
    var sum = 0.0;
    for (var dy = 0; dy < 3; dy++) {
        let row = wrap_period(by.mid + dy - 1, pi);
        var line = 0.0;
        for (var dx = 0; dx < 3; dx++) {
            line += bx.w[dx] * textureLoad(tile2, vec2<i32>(cols[dx], row), 0).r;
        }
        sum += by.w[dy] * line;
    }
    return sum;
}

fn channel_noise_wrapped(c: u32, a: vec2<f32>) -> f32 {
    var sum = 0.0;
    for (var j = 0u; j < params.counts.x; j++) {
        let w = params.weights[j][c] * band_fade(j, seamless.tile.y);
        if (w == 0.0) {
            continue;
        }
        let m = seamless.periods[j / 4u][j % 4u];
        let o = params.offsets[c * MAX_BANDS + j].xyz;
        sum += w * noise2_wrapped(vec2<f32>(a.x * m + o.x, a.y * m + o.y), m);
    }
    return sum;
}

fn seamless_pixel(frag: vec2<f32>) -> vec3<f32> {
    let size = seamless.tile.x;
    let a = vec2<f32>(frag.x / size, (frag.y + seamless.tile.z) / size);
    return colour(vec3<f32>(
        channel_noise_wrapped(0u, a),
        channel_noise_wrapped(1u, a),
        channel_noise_wrapped(2u, a),
    ), params.mean.xyz);
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
