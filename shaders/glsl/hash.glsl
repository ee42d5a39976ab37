// The project's one hash (GLSL twin of shaders/hash.wgsl; Rust twins in analyzer/src/rng.rs).
// Unsigned arithmetic wraps in GLSL ES 3.00 as in WGSL.

uint pcg_hash(uint x) {
    uint state = x * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint hash3(uint seed, uint stream, uint index) {
    return pcg_hash(index + pcg_hash(stream + pcg_hash(seed)));
}

// `uniform` in Rust (a reserved word in GLSL; in WGSL it would shadow `var<uniform>`).
float uniform01(uint seed, uint stream, uint index) {
    return (float(hash3(seed, stream, index) >> 8u) + 0.5) / 16777216.0;
}
