//! The seamless PNG tile rendered in strips on the GPU (`tile_export::SeamlessGpu`) against
//! the CPU tile (`seamless::render_seamless`).

use crate::common::{Gpu, gpu};
use crate::fixtures::{oriented, sample_params, structured};
use proctex::params::Params;

/// The PNG tile export: the seamless tile rendered in strips by `shaders/seamless.wgsl`
/// (`tile_export::SeamlessGpu`) equals the CPU reference tile (`seamless::render_seamless`),
/// on a multi-strip size and on a size whose rows need read-back padding.
#[test]
fn seamless_tile_strips_equal_the_cpu_tile() {
    use proctex_web::tile_export::png_scanlines;
    let gpu = gpu();
    for params in [
        sample_params("skimage_brick_512.png"),
        oriented(&sample_params("skimage_gravel_512.png"), 20.0),
    ] {
        for size in [1024u32, 200] {
            let (pixels, strips) = seamless_gpu(&gpu, &params, size);
            let cpu = proctex::seamless::render_seamless(&params, size, 1.0).unwrap();
            assert_eq!(pixels.len(), cpu.pixels.len());
            let mut max: f32 = 0.0;
            for (g, c) in pixels.iter().zip(&cpu.pixels) {
                for k in 0..3 {
                    max = max.max((g[k] - c[k]).abs());
                }
            }
            let (g8, c8) = (
                png_scanlines(&pixels, size as usize, 8),
                png_scanlines(&cpu.pixels, size as usize, 8),
            );
            let diff: u64 = g8.iter().zip(&c8).map(|(a, b)| a.abs_diff(*b) as u64).sum();
            let mean = diff as f64 / (size * size * 3) as f64;
            println!(
                "seamless tile {size}² in {strips} strips on {}: max |GPU − CPU| {max:.2e}, 8-bit mean {mean:.4}/255",
                gpu.adapter_name
            );
            assert!(max < 2e-3, "max diff {max}");
            assert!(mean < 0.05, "8-bit mean diff {mean}");
        }
    }
}

/// The seamless tile of `params` rendered in strips on the GPU (`tile_export::SeamlessGpu`),
/// and the number of strips.
fn seamless_gpu(gpu: &Gpu, params: &Params, size: u32) -> (Vec<[f32; 3]>, u32) {
    use proctex_web::tile_export::SeamlessGpu;
    let mut exporter = SeamlessGpu::new(&gpu.device, &gpu.queue, params, size, 1.0).unwrap();
    let mut pixels = Vec::new();
    let mut row = 0;
    while row < size {
        exporter.submit(&gpu.device, &gpu.queue, row);
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("poll");
        let (first, strip) = exporter.take().expect("mapped").expect("read back");
        assert_eq!(first, row);
        row += (strip.len() / size as usize) as u32;
        pixels.extend(strip);
    }
    (pixels, size.div_ceil(exporter.rows()))
}

/// Seamless tiles of every structured family (`shaders/seamless.wgsl` with `pattern_at`'s
/// wrapped lattices and octaves) equal the CPU tile, as the plane view does: up to a few
/// pixels moved across a joint by the last bit of a GPU division.
#[test]
fn structured_seamless_tiles_equal_the_cpu_tile() {
    use proctex_web::tile_export::png_scanlines;
    let gpu = gpu();
    let rock = sample_params("stk_rock_mountain_512.png");
    for kind in proctex::pattern::PatternKind::ALL {
        let mut params = structured(&rock, kind);
        // A turn that the tile moves to a quarter turn (110° → 90°), and a scale at which the
        // 160² tile holds a fractional number of cells before rounding.
        if let proctex::params::Model::Structured(m) = &mut params.model {
            m.pattern.rotation_deg = 110.0;
            m.pattern.scale = 13.7;
        }
        let size = 160;
        let (pixels, _) = seamless_gpu(&gpu, &params, size);
        let cpu = proctex::seamless::render_seamless(&params, size, 1.0).unwrap();
        let (g8, c8) = (
            png_scanlines(&pixels, size as usize, 8),
            png_scanlines(&cpu.pixels, size as usize, 8),
        );
        let diffs: Vec<u8> = g8.iter().zip(&c8).map(|(a, b)| a.abs_diff(*b)).collect();
        let mae = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
        let max = *diffs.iter().max().unwrap();
        let far = diffs.iter().filter(|&&d| d > 3).count() as f64 / diffs.len() as f64;
        println!(
            "{:<12} seamless tile {size}² on {}: mean |GPU − CPU| = {mae:.4}/255, max {max}/255",
            kind.name(),
            gpu.adapter_name
        );
        assert!(
            mae <= 0.25 && (max <= 3 || far <= 0.002),
            "{}: mean {mae}/255, max {max}/255, {:.3} % beyond 3/255",
            kind.name(),
            100.0 * far
        );
        let mean = c8.iter().map(|&v| v as f64).sum::<f64>() / c8.len() as f64;
        let var = c8.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / c8.len() as f64;
        assert!(var > 4.0, "{}: flat tile", kind.name());
    }
}
