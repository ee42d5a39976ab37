//! The raster solid texture on the sphere and cube (`solid_volume.wgsl`, drawn by
//! `proctex_web::volume_renderer`) equals its CPU twin `proctex::solid::render_solid_volume`,
//! for a Heeger–Bergen volume of a shipped sample.
//!
//! Tolerance as the procedural solid view's: mean |GPU − CPU| ≤ 0.25/255 over the 8-bit
//! outputs, and at most 0.2 % of the values off by more than 3/255 (silhouette pixels, where
//! the f32 ray test can fall either side of the edge).

use std::sync::Arc;

use proctex::heeger_bergen::solid::{SolidOptions, synthesize_solid};
use proctex::input::Photo;
use proctex::solid::{Orbit, Shape, SolidView, Voxels, render_solid_volume};
use proctex_web::renderer::clear_pass;
use proctex_web::volume_renderer::{VolumeRenderer, VolumeSource};

mod common;
use common::{Gpu, gpu, read_rgb8, rgb_difference, rgba8_target};

fn render_gpu(gpu: &Gpu, src: &VolumeSource, orbit: &Orbit, w: u32, h: u32) -> Vec<u8> {
    let target = rgba8_target(gpu, w, h);
    let mut renderer = VolumeRenderer::new(&gpu.device, wgpu::TextureFormat::Rgba8Unorm);
    renderer.set_volume(&gpu.device, &gpu.queue, src);
    renderer.set_view(
        &gpu.queue,
        &SolidView::new(orbit, [w as f32, h as f32], [0.0, 0.0]),
    );
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    {
        let view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut pass = clear_pass(&mut encoder, &view, "volume");
        renderer.draw(&mut pass);
    }
    gpu.queue.submit([encoder.finish()]);
    read_rgb8(gpu, &target, w, h)
}

/// A 32³ Heeger–Bergen volume of the gravel sample (reduced to 64 px, as the app reduces a
/// crop to twice the volume's side).
fn gravel_volume() -> VolumeSource {
    let path = format!(
        "{}/../www/samples/skimage_gravel_512.png",
        env!("CARGO_MANIFEST_DIR")
    );
    let photo = Photo::decode(&std::fs::read(path).unwrap())
        .unwrap()
        .reduce_to(64);
    let opts = SolidOptions {
        n: 32,
        ..SolidOptions::default()
    };
    let v = synthesize_solid(&photo, &opts, &|_, _| true)
        .unwrap()
        .unwrap();
    VolumeSource {
        id: 1,
        voxels_per_unit: 64.0 / 512.0,
        voxels: Arc::new(Voxels::from_rgb(v.n, &v.voxels)),
    }
}

#[test]
fn the_volume_on_the_sphere_and_cube_matches_cpu() {
    let gpu = gpu();
    let src = gravel_volume();
    for (what, shape) in [("sphere", Shape::Sphere), ("cube", Shape::Cube)] {
        let orbit = Orbit {
            shape,
            yaw_deg: 20.0,
            pitch_deg: 30.0,
            ..Orbit::default()
        };
        let (w, h) = (160, 120);
        let cpu = render_solid_volume(&src.voxels, src.voxels_per_unit, &orbit, w, h).to_rgb8();
        let gpu_rgb = render_gpu(&gpu, &src, &orbit, w, h);
        let (mae, big) = rgb_difference(&cpu, &gpu_rgb);
        println!(
            "gravel volume, {what:<6} {w}×{h} on {}: mean |GPU − CPU| = {mae:.4}/255, {:.3} % of values > 3/255",
            gpu.adapter_name,
            big * 100.0
        );
        assert!(mae <= 0.25 && big <= 0.002, "{what}: mean {mae}, {big} big");
        // The object covers a good part of the view, and shows the volume's texture.
        let bg = proctex::solid::BACKGROUND.map(|v| (v * 255.0).round() as u8);
        let object: Vec<&[u8]> = cpu.chunks_exact(3).filter(|p| *p != bg).collect();
        let covered = object.len() as f64 / (w * h) as f64;
        assert!(covered > 0.2, "{what}: object covers {covered}");
        let mean = object.iter().map(|p| p[1] as f64).sum::<f64>() / object.len() as f64;
        let var = object
            .iter()
            .map(|p| (p[1] as f64 - mean).powi(2))
            .sum::<f64>()
            / object.len() as f64;
        assert!(var > 16.0, "{what}: a flat object ({var})");
    }
}
