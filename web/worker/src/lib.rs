//! The Proctex analysis worker: what the browser's Web Worker (`www/worker.js`) and its
//! refinement helpers (`www/refiner.js`) run, in a wasm module of its own, apart from the UI's
//! (`proctex-web`): analysis, retrieval and refinement need none of egui or wgpu, and the UI
//! needs none of them, so each module carries only its own code and has its own size budget.
//!
//! `jobs` is plain Rust, tested natively; `exports` (feature `exports`, wasm only) wraps it for
//! JavaScript. The UI's crate uses `jobs` for the message types it reads (reports, statistics,
//! suggestion rows) and for the CPU preview of presets, with the exports off.

pub mod final_fit_job;
pub mod jobs;
pub mod pyramid_job;

#[cfg(all(target_arch = "wasm32", feature = "exports"))]
mod exports;
