//! The noise tiles baked on the GPU by the exported snippets' passes (`shaders/bake2.wgsl`,
//! `bake3.wgsl`) against `noise::Tile`.

use crate::common::{Gpu, gpu, read_texture, render_target};
use proctex_web::renderer::{clear_pass, full_screen_pipeline};

/// Runs one full-screen fragment pass of `module` into a new `w × h` rgba32float texture.
fn bake_pass(
    gpu: &Gpu,
    module: &wgpu::ShaderModule,
    entry: &str,
    src: Option<&wgpu::Texture>,
    w: u32,
    h: u32,
) -> wgpu::Texture {
    let format = wgpu::TextureFormat::Rgba32Float;
    let target = render_target(
        gpu,
        entry,
        w,
        h,
        format,
        wgpu::TextureUsages::TEXTURE_BINDING,
    );
    let pipeline = full_screen_pipeline(&gpu.device, None, module, "vs_bake", entry, format);
    let group = src.map(|t| {
        let view = t.create_view(&wgpu::TextureViewDescriptor::default());
        gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&view),
            }],
        })
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    {
        let view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut pass = clear_pass(&mut encoder, &view, entry);
        pass.set_pipeline(&pipeline);
        if let Some(g) = &group {
            pass.set_bind_group(0, g, &[]);
        }
        pass.draw(0..3, 0..1);
    }
    gpu.queue.submit([encoder.finish()]);
    target
}

/// The 2D tile baked by the passes of bake2.wgsl in the order its header gives, `n` × `n`.
pub fn bake2(gpu: &Gpu, module: &wgpu::ShaderModule, n: u32) -> wgpu::Texture {
    let mut tile = bake_pass(gpu, module, "fs_bake_spectrum", None, n, n);
    for entry in [
        "fs_bake_rows_inner",
        "fs_bake_rows",
        "fs_bake_cols_inner",
        "fs_bake_tile",
    ] {
        tile = bake_pass(gpu, module, entry, Some(&tile), n, n);
    }
    tile
}

/// An rgba32float texture's values, four per texel.
fn read_rgba32(gpu: &Gpu, t: &wgpu::Texture, w: u32, h: u32) -> Vec<f32> {
    read_texture(gpu, t, w, h, 16)
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

#[test]
fn tile_baked_on_the_gpu_equals_the_cpu_tile() {
    let gpu = gpu();
    for seed in [1u32, 77] {
        let tile = proctex::noise::Tile::new_2d(seed);
        let n = tile.n as u32;
        let consts =
            proctex_shaders::bake_constants(
                n,
                seed,
                proctex::rng::stream::TILE_2D,
                tile.stats.map(|s| s.raw_mean),
                tile.stats.map(|s| 1.0 / s.raw_variance.sqrt()),
            ) + &proctex_shaders::bake2_constants(proctex::noise::spectral::tile2_profile());
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("bake"),
                source: wgpu::ShaderSource::Wgsl(proctex_shaders::bake_shader(&consts).into()),
            });
        let baked = bake2(&gpu, &module, n);
        let got = read_rgba32(&gpu, &baked, n, n);
        let max = got
            .iter()
            .zip(&tile.rgba())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        println!(
            "tile of seed {seed} baked on {}: max |GPU − CPU| = {max:.2e}",
            gpu.adapter_name
        );
        assert!(max < 1e-3, "seed {seed}: max {max}");
    }
}

#[test]
fn tile3_baked_on_the_gpu_equals_the_cpu_tile() {
    let gpu = gpu();
    let seed = 5u32;
    let tile = proctex::noise::Tile::new_3d(seed);
    let n = tile.n as u32;
    let consts = proctex_shaders::bake_constants(
        n,
        seed,
        proctex::rng::stream::TILE_3D,
        tile.stats.map(|s| s.raw_mean),
        tile.stats.map(|s| 1.0 / s.raw_variance.sqrt()),
    );
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("bake3"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::bake3_shader(&consts).into()),
        });
    let baked = bake3(&gpu, &module, n);
    let (w, h, want) = tile.atlas();
    let got = read_rgba32(&gpu, &baked, w as u32, h as u32);
    let max = got
        .iter()
        .zip(&want)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    println!(
        "3D tile of seed {seed} baked as a {w}×{h} atlas on {}: max |GPU − CPU| = {max:.2e}",
        gpu.adapter_name
    );
    assert!(max < 1e-3, "max {max}");
}

/// The four passes of the 3D tile bake (the exported solid snippet's host steps).
pub fn bake3(gpu: &Gpu, module: &wgpu::ShaderModule, n: u32) -> wgpu::Texture {
    let a = bake_pass(gpu, module, "fs_bake3_down_x", None, 4 * n, n * n / 8);
    let b = bake_pass(gpu, module, "fs_bake3_down_y", Some(&a), 8 * n, n * n / 16);
    let c = bake_pass(gpu, module, "fs_bake3_down_z", Some(&b), 8 * n, n * n / 16);
    bake_pass(gpu, module, "fs_bake3_tile", Some(&c), 8 * n, n * n / 8)
}
