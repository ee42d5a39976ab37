//! Proctex analyzer: turns a photo of a material into the parameters of a procedural texture
//! (Lagae et al. 2009, "Isotropic stochastic procedural textures by example"), renders those
//! parameters on the CPU (the reference the GPU shaders are compared against), and measures how
//! close a texture is to a photo.
//!
//! Pure Rust: no web or GPU dependency. Data flow:
//! `bytes → input::Photo → analyze::analyze → params::Params → render::render → image`.
//!
//! The modules are declared below in layers, lowest first. A module uses modules of lower layers
//! and of its own layer only, and no two modules use each other, directly or through others.
//! `tests/layers.rs` reads these declarations and checks both rules on every source file.

// Layer: foundations (no model yet).
pub mod colour;
pub mod error;
pub mod histogram;
pub mod image_header;
pub mod input;
pub mod json;
pub mod lighting;
pub mod limits;
pub mod parallel;
pub mod radix;
pub mod rng;

// Layer: the texture model: noise tiles, pattern families, the one parameters type.
pub mod noise;
pub mod params;
pub mod pattern;
pub mod share;

// Layer: rendering the model (the per-pixel twins of the shaders) and measuring images.
pub mod render;
pub mod seamless;
pub mod solid;
pub mod specks;

// Layer: the noise model's analysis (Lagae: colour, histogram, spectrum).
pub mod analyze;
pub mod noise_tone;
pub mod orientation;
mod ring_density_table;
pub mod ring_fit;
pub mod spectrum;

// Layer: raster synthesis from the photo itself (Heeger & Bergen: steerable pyramid,
// subband histograms).
pub mod heeger_bergen;
pub mod pyramid;

// Layer: descriptors and distances of structure (two-tone map, Gabor bank, database).
pub mod cues;
pub mod db;
pub mod distance;
pub mod family_classifier;
mod family_classifier_table;
pub mod gabor;
pub mod scattering;
mod scattering_table;
pub mod straight_lines;
pub mod two_tone;

// Layer: fitting a pattern's colours to a photo.
pub mod structure;

// Layer: the automatic model choice (retrieval, refinement, ranking).
pub mod refine;
pub mod retrieve;

// Layer: what is built on whole analyses: fidelity, the development set, morphs, shaders.
pub mod devset;
pub mod evaluate;
pub mod export;
pub mod morph;

pub use error::{Error, Result};
