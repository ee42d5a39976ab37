//! The app's frame cache (`proctex_web::view_cache`): the cached view copied into a rectangle of
//! the canvas is, pixel for pixel, what the texture shader renders there directly, and the
//! texture shader runs again only when what the view shows changes.

use proctex::analyze::{Options, analyze_bytes};
use proctex::params::Params;
use proctex::render::View;
use proctex::solid::{Orbit, Shape, SolidView};
use proctex_web::renderer::{Pass, TextureRenderer, clear_pass};
use proctex_web::view_cache::{CachedView, ViewSource};
use proctex_web::volume_renderer::{VolumeRenderer, VolumeSource};

mod common;
use common::{Gpu, gpu, read_rgb8, rgba8_target};

/// The canvas, and the view's rectangle inside it (offset and size, pixels).
const CANVAS: [u32; 2] = [96, 80];
const OFFSET: [i32; 2] = [13, 7];
const SIZE: [u32; 2] = [64, 48];

fn rock() -> Params {
    let path = format!(
        "{}/../www/samples/stk_rock_mountain_512.png",
        env!("CARGO_MANIFEST_DIR")
    );
    analyze_bytes(&std::fs::read(path).unwrap(), &Options::default())
        .unwrap()
        .params
}

/// Restricts a canvas pass to the view's rectangle, as egui does for a paint callback.
fn clip_to_view(pass: &mut wgpu::RenderPass<'_>) {
    pass.set_viewport(
        OFFSET[0] as f32,
        OFFSET[1] as f32,
        SIZE[0] as f32,
        SIZE[1] as f32,
        0.0,
        1.0,
    );
    pass.set_scissor_rect(OFFSET[0] as u32, OFFSET[1] as u32, SIZE[0], SIZE[1]);
}

/// The view rendered straight into the canvas rectangle (the app's draw before the cache).
fn direct(gpu: &Gpu, params: &Params, pass_kind: Pass, view: &ViewSource) -> Vec<u8> {
    let target = rgba8_target(gpu, CANVAS[0], CANVAS[1]);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let mut renderer = TextureRenderer::new(&gpu.device, format);
    let mut volume = VolumeRenderer::new(&gpu.device, format);
    renderer.set_params(&gpu.device, &gpu.queue, params);
    let offset = OFFSET.map(|v| v as f32);
    match view {
        ViewSource::Plane(v) => renderer.set_view(&gpu.queue, v, offset),
        ViewSource::Solid(sv) => renderer.set_solid_view(&gpu.queue, sv),
        ViewSource::Volume(sv, src) => {
            volume.set_volume(&gpu.device, &gpu.queue, src);
            volume.set_view(&gpu.queue, sv);
        }
    }
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    {
        let canvas = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut pass = clear_pass(&mut encoder, &canvas, "canvas");
        clip_to_view(&mut pass);
        match view {
            ViewSource::Volume(..) => volume.draw(&mut pass),
            _ => renderer.draw_pass(&mut pass, pass_kind),
        }
    }
    gpu.queue.submit([encoder.finish()]);
    read_rgb8(gpu, &target, CANVAS[0], CANVAS[1])
}

/// One app frame through the cache: prepare (renders into the cache when the view changed),
/// then the copy into the canvas rectangle.
fn through_cache(
    gpu: &Gpu,
    cache: &mut CachedView,
    params: &Params,
    pass_kind: Pass,
    view: &ViewSource,
    fresh: bool,
) -> Vec<u8> {
    let target = rgba8_target(gpu, CANVAS[0], CANVAS[1]);
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    cache.prepare(
        &gpu.device,
        &gpu.queue,
        &mut encoder,
        params,
        pass_kind,
        view,
        OFFSET,
        SIZE,
        fresh,
    );
    {
        let canvas = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut pass = clear_pass(&mut encoder, &canvas, "canvas");
        clip_to_view(&mut pass);
        cache.paint(&mut pass);
    }
    gpu.queue.submit([encoder.finish()]);
    read_rgb8(gpu, &target, CANVAS[0], CANVAS[1])
}

/// Variance of the view rectangle's values: the test compares textures, not blank images.
fn variance_in_view(rgb: &[u8]) -> f64 {
    let mut values = Vec::new();
    for y in OFFSET[1] as u32..OFFSET[1] as u32 + SIZE[1] {
        for x in OFFSET[0] as u32..OFFSET[0] as u32 + SIZE[0] {
            let i = ((y * CANVAS[0] + x) * 3) as usize;
            values.extend(rgb[i..i + 3].iter().map(|&v| v as f64));
        }
    }
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64
}

#[test]
fn the_cached_view_equals_the_direct_render_and_renders_only_on_change() {
    let gpu = gpu();
    let params = rock();
    let mut cache = CachedView::new(&gpu.device, wgpu::TextureFormat::Rgba8Unorm);
    let view = ViewSource::Plane(View {
        origin: [37.25, -11.5],
        pixel_size: 1.5,
        z: 0.0,
    });
    let want = direct(&gpu, &params, Pass::Plane, &view);
    assert!(variance_in_view(&want) > 4.0, "a texture, not a flat image");
    let first = through_cache(&gpu, &mut cache, &params, Pass::Plane, &view, false);
    assert_eq!(first, want, "plane view: the copy is the direct render");
    assert_eq!(cache.renders(), 1);
    // The same view again: copied, not rendered, and the same pixels.
    let again = through_cache(&gpu, &mut cache, &params, Pass::Plane, &view, false);
    assert_eq!(again, want);
    assert_eq!(cache.renders(), 1);
    // What it shows changes (pan, params, shader) or a fresh render is asked for: it renders.
    let panned = ViewSource::Plane(View {
        origin: [40.0, -11.5],
        pixel_size: 1.5,
        z: 0.0,
    });
    let moved = through_cache(&gpu, &mut cache, &params, Pass::Plane, &panned, false);
    assert_eq!(cache.renders(), 2);
    assert_eq!(moved, direct(&gpu, &params, Pass::Plane, &panned));
    let mut brighter = params.clone();
    brighter.colour.contrast = 1.5;
    through_cache(&gpu, &mut cache, &brighter, Pass::Plane, &panned, false);
    assert_eq!(cache.renders(), 3);
    let flat = through_cache(&gpu, &mut cache, &brighter, Pass::Flat, &panned, false);
    assert_eq!(cache.renders(), 4);
    assert_eq!(flat, direct(&gpu, &brighter, Pass::Flat, &panned));
    through_cache(&gpu, &mut cache, &brighter, Pass::Flat, &panned, true);
    assert_eq!(cache.renders(), 5);
}

#[test]
fn the_cached_solid_view_equals_the_direct_render() {
    let gpu = gpu();
    let mut params = rock();
    params.solid = true;
    let orbit = Orbit {
        shape: Shape::Cube,
        yaw_deg: 20.0,
        pitch_deg: 30.0,
        ..Orbit::default()
    };
    let view = ViewSource::Solid(SolidView::new(
        &orbit,
        SIZE.map(|v| v as f32),
        OFFSET.map(|v| v as f32),
    ));
    let want = direct(&gpu, &params, Pass::Solid, &view);
    assert!(variance_in_view(&want) > 4.0, "a lit, textured cube");
    let mut cache = CachedView::new(&gpu.device, wgpu::TextureFormat::Rgba8Unorm);
    let got = through_cache(&gpu, &mut cache, &params, Pass::Solid, &view, false);
    assert_eq!(got, want, "solid view: the copy is the direct render");
    assert_eq!(cache.renders(), 1);
}

/// A small raster volume of smooth colours (the view's subject, not a synthesis).
fn waves(id: u64, n: u32) -> VolumeSource {
    let voxels: Vec<[f32; 3]> = (0..n.pow(3))
        .map(|i| {
            let (x, y, z) = (i % n, i / n % n, i / (n * n));
            let a = std::f32::consts::TAU / n as f32;
            [
                0.5 + 0.4 * (a * x as f32).sin(),
                0.5 + 0.4 * (a * (y + z) as f32).cos(),
                (z as f32 + id as f32) / (n as f32 + 2.0),
            ]
        })
        .collect();
    VolumeSource {
        id,
        voxels_per_unit: 1.0 / 32.0,
        voxels: std::sync::Arc::new(proctex::solid::Voxels::from_rgb(n, &voxels)),
    }
}

#[test]
fn the_cached_volume_view_equals_the_direct_render_and_follows_the_volume() {
    let gpu = gpu();
    let params = rock();
    let sv = SolidView::new(
        &Orbit::default(),
        SIZE.map(|v| v as f32),
        OFFSET.map(|v| v as f32),
    );
    let view = ViewSource::Volume(sv, waves(1, 16));
    let want = direct(&gpu, &params, Pass::Solid, &view);
    assert!(variance_in_view(&want) > 4.0, "a lit, coloured sphere");
    let mut cache = CachedView::new(&gpu.device, wgpu::TextureFormat::Rgba8Unorm);
    let got = through_cache(&gpu, &mut cache, &params, Pass::Solid, &view, false);
    assert_eq!(got, want, "volume view: the copy is the direct render");
    through_cache(&gpu, &mut cache, &params, Pass::Solid, &view, false);
    assert_eq!(cache.renders(), 1);
    // A new volume (another id) renders again, and shows the new voxels.
    let other = ViewSource::Volume(sv, waves(2, 16));
    let next = through_cache(&gpu, &mut cache, &params, Pass::Solid, &other, false);
    assert_eq!(cache.renders(), 2);
    assert_ne!(next, want);
    assert_eq!(next, direct(&gpu, &params, Pass::Solid, &other));
}
