// The project's one hash (PCG-RXS-M-XS 32, Jarzynski & Olano 2020): the tile bakes draw the
// noise coefficients from it, the cell patterns their per-cell randomness. Twins:
// analyzer/src/rng.rs (pcg_hash, hash3, uniform — uniform01 here, since `uniform` would shadow
// the address space of `var<uniform>` —; f32 here).

fn pcg_hash(x: u32) -> u32 {
    let state = x * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn hash3(seed: u32, stream: u32, index: u32) -> u32 {
    return pcg_hash(index + pcg_hash(stream + pcg_hash(seed)));
}

fn uniform01(seed: u32, stream: u32, index: u32) -> f32 {
    return (f32(hash3(seed, stream, index) >> 8u) + 0.5) / 16777216.0;
}
