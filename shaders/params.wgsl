// The texture parameters as the GPU sees them: the byte layout written by
// `proctex::render::Prepared::uniform_bytes` (analyzer/src/render.rs). Every array element is a
// vec4 so that the uniform layout has no padding surprises.

const MAX_BANDS: u32 = 12u;
const MAX_KNOTS: u32 = 33u;
const MAX_TONE_KNOTS: u32 = 33u;

struct Params {
    // mean RGB, contrast
    mean: vec4<f32>,
    // rows: principal axes
    basis: array<vec4<f32>, 3>,
    // 1/scale, cos(rotation), sin(rotation), unused
    transform: vec4<f32>,
    // bands, knots, solid (0/1), histogram (0/1)
    counts: vec4<u32>,
    // σ_M per channel
    sigma: vec4<f32>,
    // per channel the finest band's amplitude drawn after the histogram (0: Lagae's model)
    fine: vec4<f32>,
    // [band] → weight of channels 0, 1, 2
    weights: array<vec4<f32>, 12>,
    // [band] → offset (x, y, z) in coefficient units (the three channels read their own tile
    // components at one point)
    offsets: array<vec4<f32>, 12>,
    // [band] → mixing of the band and its derivative (α, β·dx, β·dy; (1, 0, 0): isotropic),
    // shared by the channels (analyzer/src/noise/oriented.rs)
    orient: array<vec4<f32>, 12>,
    // [knot] → knot value of channels 0, 1, 2
    knots: array<vec4<f32>, 33>,
    // [knot] → Fritsch–Carlson tangent of channels 0, 1, 2
    tangents: array<vec4<f32>, 33>,
    // structured models (pattern.wgsl): kind (0: the noise model), ramp stops, cell-hash
    // seed, knots of the output tone curve (0: none)
    pattern: vec4<u32>,
    // 1/pattern scale, cos and sin of the pattern rotation, log2(1/pattern scale)
    pattern_transform: vec4<f32>,
    // the pattern's structural values in spec order (analyzer/src/pattern.rs)
    pattern_values: array<vec4<f32>, 2>,
    // [octave] → offset (x, y, z) of the pattern's noise octaves in coefficient units
    pattern_offsets: array<vec4<f32>, 5>,
    // [stop] → ramp colour RGB and its structure value `at`
    ramp: array<vec4<f32>, 16>,
    // output tone curve: [0] lo of channels 0, 1, 2 (RGB), [1] 1 / (hi − lo)
    tone_range: array<vec4<f32>, 2>,
    // [knot] → tone curve value of channels 0, 1, 2
    tone_knots: array<vec4<f32>, 33>,
    // [knot] → Fritsch–Carlson tangent of channels 0, 1, 2
    tone_tangents: array<vec4<f32>, 33>,
}

@group(0) @binding(0) var<uniform> params: Params;
// The 2D wavelet-noise tile (rgba32float: its three components in RGB, one fetch for every
// channel; read with textureLoad: exact coefficients, no filtering). The 3D tile of solid textures is bound at binding 2 by tile3.wgsl (the app's 3D
// texture) or tile3_atlas.wgsl (exported snippets).
@group(0) @binding(1) var tile2: texture_2d<f32>;
