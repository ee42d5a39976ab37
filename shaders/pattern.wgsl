// Structured models: the pattern's structure value s ∈ [0, 1] at a texel, and the colour ramp
// along s. Twins: analyzer/src/pattern.rs (soft_step, cell_hash, wrap_cell, wrap_cells,
// cell_hash_wrapped, octave, octaves, joint_distance, pattern, pattern_at, ramp). Same
// operation order, f32. Needs hash.wgsl (the cell hashes) and noise.wgsl (the octaves read
// the texture's own noise tile).

const PATTERN_OCTAVES: u32 = 5u;
// rng::stream::CELLS
const CELLS_STREAM: u32 = 0x63656c6cu;
// pattern::WARP_OFFSET
const WARP_OFFSET: f32 = 19.3;

fn soft_step(e0: f32, w: f32, x: f32) -> f32 {
    let t = clamp((x - e0) / w, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

fn cell_hash(ix: i32, iy: i32, k: u32) -> f32 {
    let index = (bitcast<u32>(ix) * 0x8da6b343u) ^ (bitcast<u32>(iy) * 0xd8163841u) ^ k;
    return uniform01(params.pattern.z, CELLS_STREAM, index);
}

// Cell index i wrapped at n cells (a seamless tile's lattice); i itself for n = 0.
fn wrap_cell(i: i32, n: i32) -> i32 {
    if (n > 0) {
        return ((i % n) + n) % n;
    }
    return i;
}

// The whole number of cells of width pitch (and rows of height 1) that the periods wrap hold;
// (0, 0) (no wrap) for wrap.x = 0.
fn wrap_cells(pitch: f32, wrap: vec2<f32>) -> vec2<i32> {
    if (wrap.x > 0.0) {
        return vec2<i32>(i32(floor(wrap.x / pitch + 0.5)), i32(floor(wrap.y + 0.5)));
    }
    return vec2<i32>(0, 0);
}

fn cell_hash_wrapped(ix: i32, iy: i32, k: u32, cells: vec2<i32>) -> f32 {
    return cell_hash(wrap_cell(ix, cells.x), wrap_cell(iy, cells.y), k);
}

// Lower edge of row k of planks: k + widths·(hash(k) − ½), the hash wrapped at rows (0: not).
fn plank_edge(k: i32, widths: f32, rows: i32) -> f32 {
    return f32(k) + widths * (cell_hash_wrapped(0, k, 2u, vec2<i32>(0, rows)) - 0.5);
}

// The row of planks that y falls in and its edges: (row, lower, upper).
fn plank_row(y: f32, widths: f32, rows: i32) -> vec3<f32> {
    let k = i32(floor(y));
    let lo = plank_edge(k, widths, rows);
    let hi = plank_edge(k + 1, widths, rows);
    if (y < lo) {
        return vec3<f32>(f32(k - 1), plank_edge(k - 1, widths, rows), lo);
    }
    if (y >= hi) {
        return vec3<f32>(f32(k + 1), hi, plank_edge(k + 2, widths, rows));
    }
    return vec3<f32>(f32(k), lo, hi);
}

// Octave k at q; with per.x > 0 (seamless tiles, plane textures) q repeats with period per and
// the octave's frequency moves to a whole number of coefficients over it.
fn octave(q: vec3<f32>, k: u32, per: vec2<f32>) -> f32 {
    let f = f32(1u << k);
    let o = params.pattern_offsets[k].xyz;
    if (params.counts.z != 0u) {
        return noise3(vec3<f32>(q.x * f + o.x, q.y * f + o.y, q.z * f + o.z)).x;
    }
    if (per.x > 0.0) {
        let n = f32(textureDimensions(tile2).x);
        let m = vec2<f32>(whole_period(per.x * f, n), whole_period(per.y * f, n));
        return noise2_periodic(vec2<f32>(q.x / per.x * m.x + o.x, q.y / per.y * m.y + o.y), m).x;
    }
    return noise2(vec2<f32>(q.x * f + o.x, q.y * f + o.y)).x;
}

// A ridged octave's crest exp(−sharpness·|n|) as a pixel shows it (Rust: crest): at least a pixel
// wide, averaged over n ± g/2, g the noise's change across the pixel.
fn crest(n: f32, sharpness: f32, g: f32) -> f32 {
    let s = min(sharpness, 2.0 / max(g, 1e-6));
    let h = 0.5 * g;
    if (s * h < 1e-3) {
        return exp(-s * abs(n));
    }
    let hi = sign(n + h) * (1.0 - exp(-s * abs(n + h))) / s;
    let lo = sign(n - h) * (1.0 - exp(-s * abs(n - h))) / s;
    return (hi - lo) / (2.0 * h);
}

// The octaves summed: n (mode 0, fractal noise) or |n| (1, turbulence) (Rust: octaves).
fn octaves(q: vec3<f32>, gain: f32, mode: u32, lfp: f32, per: vec2<f32>) -> f32 {
    var sum = 0.0;
    var norm = 0.0;
    var amp = 1.0;
    for (var k = 0u; k < PATTERN_OCTAVES; k++) {
        let fade = band_fade(0u, lfp + f32(k));
        if (fade > 0.0) {
            let n = octave(q, k, per);
            var v = n;
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

// The lines' profile (½ + ½ sin 2πv)^sharpness as a pixel shows it (Rust: line_profile): the
// sharpness bounded so that a line is at least a pixel wide, averaged over v ± g/2 (g the change
// of v across the pixel) on four points.
fn line_profile(v: f32, sharpness: f32, g_in: f32) -> f32 {
    let g = max(g_in, 1e-6);
    let s = min(sharpness, 4.0 / (3.1415927 * 3.1415927 * g * g));
    if (g < 1e-4) {
        return pow(max(0.5 + 0.5 * sin(6.2831855 * v), 1e-6), s);
    }
    var sum = 0.0;
    for (var i = 0u; i < 4u; i++) {
        let x = v + (0.25 * f32(i) - 0.375) * g;
        sum += pow(max(0.5 + 0.5 * sin(6.2831855 * x), 1e-6), s);
    }
    return 0.25 * sum;
}

// How much a coordinate changes across a pixel (Rust: pixel_change): forward differences.
fn pixel_change(at: f32, ax: f32, ay: f32) -> f32 {
    let dx = ax - at;
    let dy = ay - at;
    return sqrt(dx * dx + dy * dy);
}

// Ridged's octaves: each octave's crest over the noise's change across the pixel where it is,
// forward differences one pixel step along the pattern's axes (Rust: ridged_octaves).
fn ridged_octaves(
    q: vec3<f32>, pixel_step: vec2<f32>, gain: f32, sharpness: f32, lfp: f32, per: vec2<f32>,
) -> f32 {
    var sum = 0.0;
    var norm = 0.0;
    var amp = 1.0;
    for (var k = 0u; k < PATTERN_OCTAVES; k++) {
        let fade = band_fade(0u, lfp + f32(k));
        if (fade > 0.0) {
            let n = octave(q, k, per);
            let nx = octave(vec3<f32>(q.x + pixel_step.x, q.y, q.z), k, per);
            let ny = octave(vec3<f32>(q.x, q.y + pixel_step.y, q.z), k, per);
            sum += amp * fade * crest(n, sharpness, pixel_change(n, nx, ny));
        }
        norm += amp;
        amp *= gain;
    }
    return sum / norm;
}

// The wood lines' coordinate at pattern point q (Rust: wood_line_coordinate).
fn wood_line_coordinate(q: vec3<f32>, lfp: f32, per: vec2<f32>) -> f32 {
    let w0 = params.pattern_values[0];
    let n = octaves(
        vec3<f32>(0.25 * q.x / w0.x, 0.25 * q.y, 0.25 * q.z), w0.w, 0u, lfp - 2.0, per,
    );
    return q.y + w0.y * n;
}

// The rings' coordinate at point p from their centre (Rust: ring_coordinate).
fn ring_coordinate(p: vec3<f32>, lfp: f32, per: vec2<f32>) -> f32 {
    let w0 = params.pattern_values[0];
    let n = octaves(
        vec3<f32>(0.25 * p.x, 0.25 * p.y, 0.25 * p.z), w0.z, 0u, lfp - 2.0, 0.25 * per,
    );
    return sqrt(p.x * p.x + p.y * p.y) + w0.x * n;
}

fn joint_distance(fx: f32, fy: f32, aspect: f32) -> f32 {
    return min(min(fx, 1.0 - fx) * aspect, min(fy, 1.0 - fy));
}

fn pattern(u: vec3<f32>, log2_fp: f32) -> f32 {
    let xf = params.pattern_transform;
    let is = xf.x;
    let c = xf.y;
    let s = xf.z;
    let q = vec3<f32>((c * u.x + s * u.y) * is, (-s * u.x + c * u.y) * is, u.z * is);
    return pattern_at(q, log2_fp + xf.w, vec2<f32>(0.0, 0.0));
}

// The structure value at pattern point q; wrap (0: none) makes it repeat with period wrap
// along the pattern's axes (seamless tiles; see analyzer/src/pattern.rs pattern_at).
fn pattern_at(q: vec3<f32>, lfp: f32, wrap: vec2<f32>) -> f32 {
    let c = params.pattern_transform.y;
    let s = params.pattern_transform.z;
    let w0 = params.pattern_values[0];
    let w1 = params.pattern_values[1];
    let soft = exp2(lfp);
    switch (params.pattern.x) {
        // perlin: stretch, roughness, contrast, threshold
        case 1u: {
            let per = vec2<f32>(wrap.x / w0.x, wrap.y);
            let n = octaves(vec3<f32>(q.x / w0.x, q.y, q.z), w0.y, 0u, lfp, per);
            return 1.0 / (1.0 + exp(-w0.z * (n - w0.w)));
        }
        // turbulence: stretch, roughness, contrast
        case 2u: {
            let per = vec2<f32>(wrap.x / w0.x, wrap.y);
            let t = octaves(vec3<f32>(q.x / w0.x, q.y, q.z), w0.y, 1u, lfp, per);
            return 1.0 - exp(-w0.z * t);
        }
        // ridged: stretch, roughness, sharpness
        case 3u: {
            let per = vec2<f32>(wrap.x / w0.x, wrap.y);
            let pixel_step = vec2<f32>(soft / w0.x, soft);
            let stretched = vec3<f32>(q.x / w0.x, q.y, q.z);
            return ridged_octaves(stretched, pixel_step, w0.y, w0.z, lfp, per);
        }
        // grid: aspect, mortar, bevel, variation
        case 4u: {
            let n = wrap_cells(w0.x, wrap);
            let x = q.x / w0.x;
            let ix = floor(x);
            let iy = floor(q.y);
            let d = joint_distance(x - ix, q.y - iy, w0.x);
            let shade = 1.0 - w0.w * cell_hash_wrapped(i32(ix), i32(iy), 0u, n);
            return soft_step(0.5 * w0.y, max(w0.z, soft), d) * shade;
        }
        // brick: aspect, mortar, row_offset, jitter, bevel, variation
        case 5u: {
            let n = wrap_cells(w0.x, wrap);
            let iy = floor(q.y);
            var row = iy;
            var offset = w0.z;
            if (n.y > 0) {
                let rows = f32(n.y);
                row = f32(wrap_cell(i32(iy), n.y));
                offset = floor(w0.z * rows + 0.5) / rows;
            }
            let shift = row * offset + w0.w * (cell_hash(0, i32(row), 1u) - 0.5);
            let x = q.x / w0.x + shift;
            let ix = floor(x);
            let d = joint_distance(x - ix, q.y - iy, w0.x);
            let shade = 1.0 - w1.y * cell_hash_wrapped(i32(ix), i32(iy), 0u, n);
            return soft_step(0.5 * w0.y, max(w1.x, soft), d) * shade;
        }
        // cells: jitter, mortar, bevel, variation, stretch, stagger, warp
        case 6u: {
            let n = wrap_cells(w1.x, wrap);
            var p = vec2<f32>(q.x / w1.x, q.y);
            if (w1.z > 0.0) {
                let per = vec2<f32>(0.25 * wrap.x / w1.x, 0.25 * wrap.y);
                let b = vec3<f32>(0.25 * p.x, 0.25 * p.y, 0.25 * q.z);
                let gx = octaves(b, 0.5, 0u, lfp - 2.0, per);
                let b2 = vec3<f32>(b.x + WARP_OFFSET, b.y, b.z);
                let gy = octaves(b2, 0.5, 0u, lfp - 2.0, per);
                p = vec2<f32>(p.x + w1.z * gx, p.y + w1.z * gy);
            }
            let iy = floor(p.y);
            let fy = p.y - iy;
            var f1 = 1e9;
            var f2 = 1e9;
            var id = vec2<i32>(0, 0);
            for (var dy = -1; dy <= 1; dy++) {
                let cy = i32(iy) + dy;
                let shift = 0.5 * w1.y * f32(wrap_cell(cy, n.y) & 1);
                let x = p.x - shift;
                let ix = floor(x);
                let fx = x - ix;
                for (var dx = -1; dx <= 1; dx++) {
                    let cx = i32(ix) + dx;
                    let px = f32(dx) + 0.5 + w0.x * (cell_hash_wrapped(cx, cy, 0u, n) - 0.5);
                    let py = f32(dy) + 0.5 + w0.x * (cell_hash_wrapped(cx, cy, 1u, n) - 0.5);
                    let ex = px - fx;
                    let ey = py - fy;
                    let d = ex * ex + ey * ey;
                    if (d < f1) {
                        f2 = f1;
                        f1 = d;
                        id = vec2<i32>(cx, cy);
                    } else if (d < f2) {
                        f2 = d;
                    }
                }
            }
            let edge = 0.5 * (sqrt(f2) - sqrt(f1));
            let shade = 1.0 - w0.w * cell_hash_wrapped(id.x, id.y, 2u, n);
            return soft_step(0.5 * w0.y, max(w0.z, soft), edge) * shade;
        }
        // planks: length, gap, bevel, variation, grain, widths
        case 7u: {
            let n = wrap_cells(w0.x, wrap);
            let r = plank_row(q.y, w1.y, n.y);
            let iy = r.x;
            let x = q.x / w0.x + cell_hash_wrapped(0, i32(iy), 1u, vec2<i32>(0, n.y));
            let ix = floor(x);
            let fx = x - ix;
            let d = min(min(fx, 1.0 - fx) * w0.x, min(q.y - r.y, r.z - q.y));
            let per = vec2<f32>(wrap.x * 0.125, wrap.y * 4.0);
            let g = octaves(vec3<f32>(q.x * 0.125, q.y * 4.0, q.z), 0.5, 0u, lfp + 2.0, per);
            let shade = (1.0 - w0.w * cell_hash_wrapped(i32(ix), i32(iy), 0u, n))
                * (1.0 - w1.x * (0.5 + 0.5 * tanh(g)));
            return soft_step(0.5 * w0.y, max(w0.z, soft), d) * shade;
        }
        // wood lines: stretch, distortion, sharpness, roughness
        case 8u: {
            let per = vec2<f32>(0.25 * wrap.x / w0.x, 0.25 * wrap.y);
            let v = wood_line_coordinate(q, lfp, per);
            let vx = wood_line_coordinate(q + vec3<f32>(soft, 0.0, 0.0), lfp, per);
            let vy = wood_line_coordinate(q + vec3<f32>(0.0, soft, 0.0), lfp, per);
            return line_profile(v, w0.z, pixel_change(v, vx, vy));
        }
        // rings: distortion, sharpness, roughness, stretch, centre_x, centre_y; with wrap, the
        // torus distance to the centre
        case 9u: {
            let qc = vec2<f32>(c * w1.x + s * w1.y, -s * w1.x + c * w1.y);
            var p = vec3<f32>((q.x - qc.x) / w0.w, q.y - qc.y, q.z);
            let per = vec2<f32>(wrap.x / w0.w, wrap.y);
            if (wrap.x > 0.0) {
                p.x -= per.x * floor(p.x / per.x + 0.5);
                p.y -= per.y * floor(p.y / per.y + 0.5);
            }
            let r = ring_coordinate(p, lfp, per);
            let rx = ring_coordinate(p + vec3<f32>(soft / w0.w, 0.0, 0.0), lfp, per);
            let ry = ring_coordinate(p + vec3<f32>(0.0, soft, 0.0), lfp, per);
            return line_profile(r, w0.y, pixel_change(r, rx, ry));
        }
        default: {
            return 0.0;
        }
    }
}

fn ramp(s: f32) -> vec3<f32> {
    let n = params.pattern.y;
    if (s <= params.ramp[0].w) {
        return params.ramp[0].xyz;
    }
    for (var i = 1u; i < n; i++) {
        if (s < params.ramp[i].w) {
            let a = params.ramp[i - 1u];
            let b = params.ramp[i];
            let t = (s - a.w) / (b.w - a.w);
            return a.xyz + (b.xyz - a.xyz) * t;
        }
    }
    return params.ramp[n - 1u].xyz;
}
