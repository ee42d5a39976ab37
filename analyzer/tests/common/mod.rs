//! Shared helpers of the integration tests.
#![allow(dead_code)]

pub mod round_trip;

use proctex::input::Photo;
use proctex::params::{Colour, FORMAT, Histogram, Model, NoiseModel, Params, Transform};

/// Bytes of a shipped sample photo (`www/samples/`).
pub fn sample_bytes(name: &str) -> Vec<u8> {
    let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
    std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A decoded shipped sample photo.
pub fn sample(name: &str) -> Photo {
    Photo::decode(&sample_bytes(name)).expect("sample decodes")
}

/// The top-left quadrant of a development-set photo (`../shared/photos/dev/`, beside the
/// repository), as the development-set yardstick analyses it.
pub fn dev_quadrant(name: &str) -> Photo {
    let path = format!(
        "{}/../../shared/photos/dev/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let photo = Photo::decode(&bytes).expect("development photo decodes");
    let (w, h) = (photo.width / 2, photo.height / 2);
    photo
        .crop(proctex::input::Crop { x: 0, y: 0, w, h })
        .expect("quadrant")
}

/// Shipped samples used across tests.
pub const SAMPLES: [&str; 6] = [
    "skimage_gravel_512.png",
    "skimage_grass_512.png",
    "skimage_brick_512.png",
    "stk_rock_mountain_512.png",
    "stk_blackrock_256.png",
    "stk_wood_planks1_256.png",
];

/// A noise params set with the given weights (finest first), histogram off, grey axis first.
pub fn noise_params(weights: [Vec<f32>; 3], basis: [[f32; 3]; 3], seed: u32) -> Params {
    let nb = weights[0].len();
    let _ = nb;
    Params {
        format: FORMAT.into(),
        seed,
        solid: false,
        transform: Transform {
            scale: 1.0,
            rotation_deg: 0.0,
        },
        colour: Colour {
            mean: [0.5, 0.5, 0.5],
            basis,
            contrast: 1.0,
        },
        model: Model::Noise(NoiseModel {
            weights,
            histogram: Histogram {
                enabled: false,
                knots: [
                    vec![-0.1, 0.0, 0.1],
                    vec![-0.1, 0.0, 0.1],
                    vec![-0.1, 0.0, 0.1],
                ],
            },
            orientation: Vec::new(),
            tone: None,
            fine: [0.0; 3],
        }),
        source: None,
    }
}

/// A proper rotation whose first row is the grey axis.
pub fn grey_basis() -> [[f32; 3]; 3] {
    let s3 = 1.0 / 3.0f32.sqrt();
    let s2 = 1.0 / 2.0f32.sqrt();
    let s6 = 1.0 / 6.0f32.sqrt();
    [[s3, s3, s3], [s2, -s2, 0.0], [s6, s6, -2.0 * s6]]
}

/// Quantile of `v` at probability `p` (linear interpolation).
pub fn quantile(v: &mut [f32], p: f64) -> f64 {
    v.sort_unstable_by(f32::total_cmp);
    let pos = p * (v.len() - 1) as f64;
    let k = pos.floor() as usize;
    let f = pos - k as f64;
    v[k] as f64 * (1.0 - f) + v[(k + 1).min(v.len() - 1)] as f64 * f
}

/// Deterministic uniform numbers for test parameters.
pub fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}
