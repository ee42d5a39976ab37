//! The Proctex browser app. `renderer` draws the procedural texture with wgpu from the shaders
//! in `shaders/`; it is plain wgpu (no UI types) so that native tests can run it headless and
//! compare its pixels with the CPU reference renderer; `volume_renderer` draws a raster solid
//! texture on the solid views the same way.

pub mod preset_store;
pub mod presets;
pub mod renderer;
pub mod tile_export;
pub mod view_cache;
pub mod volume_renderer;

#[cfg(target_arch = "wasm32")]
mod app;
#[cfg(target_arch = "wasm32")]
mod web;

/// The worker's jobs (`proctex-worker`): the message types the app reads, and the CPU preview.
pub use proctex_worker::jobs;
