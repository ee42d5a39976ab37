// The texture parameters (GLSL twin of shaders/params.wgsl; same fields, same order). The
// export defines `params` as a constant of this struct; every array element is a vec4.

#define MAX_BANDS 12
#define MAX_KNOTS 33
#define MAX_TONE_KNOTS 33

struct Params {
    vec4 mean;              // mean RGB, contrast
    vec4 basis[3];          // rows: principal axes
    vec4 transform;         // 1/scale, cos(rotation), sin(rotation), unused
    uvec4 counts;           // bands, knots, solid (0/1), histogram (0/1)
    vec4 sigma;             // sigma_M per channel
    vec4 fine;              // per channel the finest band's amplitude after the histogram
    vec4 weights[12];       // [band] -> weight of channels 0, 1, 2
    vec4 offsets[12];       // [band] -> offset (x, y, z) in coefficient units
    vec4 orient[12];        // [band] -> mixing of the band and its derivative (alpha, beta*dx, beta*dy)
    vec4 knots[33];         // [knot] -> knot value of channels 0, 1, 2
    vec4 tangents[33];      // [knot] -> Fritsch-Carlson tangent of channels 0, 1, 2
    uvec4 pattern;          // pattern kind (0: noise model), ramp stops, cell-hash seed, tone knots
    vec4 pattern_transform; // 1/pattern scale, cos, sin of its rotation, log2(1/pattern scale)
    vec4 pattern_values[2]; // structural values in spec order
    vec4 pattern_offsets[5];// [octave] -> offset of the pattern's noise octaves
    vec4 ramp[16];          // [stop] -> ramp colour RGB, structure value `at`
    vec4 tone_range[2];     // output tone curve: [0] lo per RGB channel, [1] 1 / (hi - lo)
    vec4 tone_knots[33];    // [knot] -> tone curve value of channels 0, 1, 2
    vec4 tone_tangents[33]; // [knot] -> Fritsch-Carlson tangent of channels 0, 1, 2
};
