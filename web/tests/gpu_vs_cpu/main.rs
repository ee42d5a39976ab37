//! The GPU image equals the CPU reference image: the plane shader rendered by wgpu (natively,
//! on any Vulkan adapter — Mesa's software lavapipe in CI) against `proctex::render::render`,
//! for the same params and view.
//!
//! Tolerance: mean absolute error ≤ 0.25/255 and no pixel off by more than 3/255 over the 8-bit
//! outputs. Both sides evaluate the same f32 expressions in the same order; what differs is
//! rounding (fused multiply-adds the GPU compiler may form, `exp`-free but `floor`/`ceil` on
//! values that land within an ulp of an integer, which can pick the neighbouring coefficient
//! set where the B-spline weight is ~0) and the final conversion to 8 bits.
//!
//! One module per concern: the plane, structured and solid views (`plane`), the noise tiles baked
//! on the GPU (`bake`), the exported WGSL shaders and morphs (`exported`), the seamless PNG
//! tiles (`seamless`); the params they render are `fixtures`.

#[path = "../common/mod.rs"]
mod common;

mod bake;
mod exported;
mod fixtures;
mod plane;
mod seamless;
