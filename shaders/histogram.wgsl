// Histogram matching. Twins: analyzer/src/histogram.rs (knot_coordinate, spline_eval).

const KNOT_Z: f32 = 2.5;

fn knot_coordinate(g: f32, sigma: f32) -> f32 {
    return clamp((g / sigma + KNOT_Z) / (2.0 * KNOT_Z), 0.0, 1.0);
}

// The Hermite spline through (j/K, knots[j]) of channel c, at u in [0, 1].
fn spline_eval(c: u32, u: f32) -> f32 {
    let k = params.counts.y - 1u;
    let s = clamp(u, 0.0, 1.0) * f32(k);
    let i = min(u32(floor(s)), k - 1u);
    let t = s - f32(i);
    let h = 1.0 / f32(k);
    let t2 = t * t;
    let t3 = t2 * t;
    let h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    let h10 = t3 - 2.0 * t2 + t;
    let h01 = -2.0 * t3 + 3.0 * t2;
    let h11 = t3 - t2;
    return h00 * params.knots[i][c] + h10 * h * params.tangents[i][c]
        + h01 * params.knots[i + 1u][c] + h11 * h * params.tangents[i + 1u][c];
}
