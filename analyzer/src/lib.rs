//! Proctex analyzer: turns a photo of a material into the parameters of a procedural texture
//! (Lagae et al. 2009, "Isotropic stochastic procedural textures by example"), renders those
//! parameters on the CPU (the reference the GPU shaders are compared against), and measures how
//! close a texture is to a photo.
//!
//! Pure Rust: no web or GPU dependency. Data flow:
//! `bytes → input::Photo → analyze::analyze → params::Params → render::render → image`.

pub mod analyze;
pub mod colour;
pub mod cues;
pub mod db;
pub mod devset;
pub mod error;
pub mod evaluate;
pub mod export;
pub mod gabor;
pub mod histogram;
pub mod input;
pub mod morph;
pub mod noise;
pub mod parallel;
pub mod params;
pub mod pattern;
pub mod radix;
pub mod refine;
pub mod render;
pub mod retrieve;
pub mod rng;
pub mod seamless;
pub mod solid;
pub mod specks;
pub mod spectrum;
pub mod structure;
pub mod two_tone;

pub use error::{Error, Result};
