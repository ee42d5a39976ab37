// Histogram matching. Twins: analyzer/src/histogram.rs (knot_coordinate, hermite, spline_eval).

const KNOT_Z: f32 = 2.5;

fn knot_coordinate(g: f32, sigma: f32) -> f32 {
    return clamp((g / sigma + KNOT_Z) / (2.0 * KNOT_Z), 0.0, 1.0);
}

// The cubic Hermite segment from (y0, slope m0) to (y1, slope m1) over width h, at t in [0, 1].
fn hermite(t: f32, h: f32, y0: f32, m0: f32, y1: f32, m1: f32) -> f32 {
    let t2 = t * t;
    let t3 = t2 * t;
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + t;
    let h01 = -2.0 * t3 + 3.0 * t2;
    let h11 = t3 - t2;
    return h00 * y0 + h10 * h * m0 + h01 * y1 + h11 * h * m1;
}

// The Hermite spline through (j/K, knots[j]) of channel c, at u in [0, 1].
fn spline_eval(c: u32, u: f32) -> f32 {
    let k = params.counts.y - 1u;
    let s = clamp(u, 0.0, 1.0) * f32(k);
    let i = min(u32(floor(s)), k - 1u);
    return hermite(s - f32(i), 1.0 / f32(k), params.knots[i][c], params.tangents[i][c],
        params.knots[i + 1u][c], params.tangents[i + 1u][c]);
}
