//! The one pseudo-random source of the project: a counter-based hash.
//!
//! Every random number is `hash(seed, stream, index)`, a pure function of three `u32`s. There is
//! no generator state, so the same value can be produced in any order, on any thread, and in a
//! shader (WGSL has `u32` wrapping arithmetic; the GPU twin is `pcg_hash` in `shaders/`).
//!
//! The mixing function is the PCG-RXS-M-XS 32-bit output permutation used as a hash, as
//! recommended by Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020. Streams keep
//! the uses apart (tile values, per-band offsets, ...), so adding a use never shifts another.

/// Named streams, so that each use of randomness draws independent numbers.
pub mod stream {
    /// Gaussian coefficients of the 2D wavelet-noise tile.
    pub const TILE_2D: u32 = 0x7431_3244;
    /// Gaussian coefficients of the 3D (solid) wavelet-noise tile.
    pub const TILE_3D: u32 = 0x7431_3344;
    /// Per channel and band random offsets `o_i` of Lagae eq. 1.
    pub const BAND_OFFSETS: u32 = 0x6f66_6673;
    /// Offsets of the structured patterns' noise octaves.
    pub const PATTERN: u32 = 0x7061_7474;
    /// Per-cell randomness of the cell patterns (brick shades, cell centres, plank staggers).
    pub const CELLS: u32 = 0x6365_6c6c;
    /// Parameter samples of the retrieval database.
    pub const DB: u32 = 0x6462_6462;
}

/// PCG-RXS-M-XS 32 as a hash of one `u32`.
#[inline]
pub fn pcg_hash(x: u32) -> u32 {
    let state = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// The random `u32` number `index` of `stream` under `seed`.
#[inline]
pub fn hash3(seed: u32, stream: u32, index: u32) -> u32 {
    pcg_hash(index.wrapping_add(pcg_hash(stream.wrapping_add(pcg_hash(seed)))))
}

/// Uniform in the open interval (0, 1): the top 24 bits, centred in their cell.
#[inline]
pub fn uniform(seed: u32, stream: u32, index: u32) -> f64 {
    ((hash3(seed, stream, index) >> 8) as f64 + 0.5) / 16_777_216.0
}

/// Standard normal value number `index`: Box–Muller (cosine branch) on the uniforms `2·index`
/// and `2·index + 1`. Computed in `f64` on the CPU; tiles are generated here and uploaded.
#[inline]
pub fn gaussian(seed: u32, stream: u32, index: u32) -> f64 {
    let u1 = uniform(seed, stream, index.wrapping_mul(2));
    let u2 = uniform(seed, stream, index.wrapping_mul(2).wrapping_add(1));
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_are_stable() {
        // Pinned so that a change of the hash (and so of every texture) is a conscious one.
        assert_eq!(pcg_hash(0), 129_708_002);
        assert_eq!(pcg_hash(1), 2_831_084_092);
        assert_eq!(hash3(1, 2, 3), hash3(1, 2, 3));
        assert_ne!(hash3(1, 2, 3), hash3(1, 3, 2));
    }

    #[test]
    fn gaussian_moments() {
        let n = 200_000;
        let (mut s1, mut s2) = (0.0, 0.0);
        for i in 0..n {
            let g = gaussian(7, 11, i);
            s1 += g;
            s2 += g * g;
        }
        let mean = s1 / n as f64;
        let var = s2 / n as f64 - mean * mean;
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((var - 1.0).abs() < 0.015, "var {var}");
    }
}
