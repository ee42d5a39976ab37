// Histogram matching (GLSL twin of shaders/histogram.wgsl; Rust twins in
// analyzer/src/histogram.rs: knot_coordinate, hermite, spline_eval).

const float KNOT_Z = 2.5;

float knot_coordinate(float g, float sigma) {
    return clamp((g / sigma + KNOT_Z) / (2.0 * KNOT_Z), 0.0, 1.0);
}

// The cubic Hermite segment from (y0, slope m0) to (y1, slope m1) over width h, at t in [0, 1].
float hermite(float t, float h, float y0, float m0, float y1, float m1) {
    float t2 = t * t;
    float t3 = t2 * t;
    float h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    float h10 = t3 - 2.0 * t2 + t;
    float h01 = -2.0 * t3 + 3.0 * t2;
    float h11 = t3 - t2;
    return h00 * y0 + h10 * h * m0 + h01 * y1 + h11 * h * m1;
}

// The Hermite spline through (j/K, knots[j]) of channel c, at u in [0, 1].
float spline_eval(int c, float u) {
    uint k = params.counts.y - 1u;
    float s = clamp(u, 0.0, 1.0) * float(k);
    uint i = min(uint(floor(s)), k - 1u);
    return hermite(s - float(i), 1.0 / float(k), params.knots[i][c], params.tangents[i][c],
        params.knots[i + 1u][c], params.tangents[i + 1u][c]);
}
