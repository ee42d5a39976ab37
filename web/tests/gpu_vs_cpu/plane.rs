//! The texture pass (plane, structured patterns, solid slices, the lit sphere and cube, the flat
//! baseline) rendered by `TextureRenderer` against the CPU reference renderer.

use crate::common::{Gpu, gpu, read_rgb8, rgb_difference, rgba8_target};
use crate::fixtures::{oriented, sample_params, structured, with_curve};
use proctex::params::Params;
use proctex::render::{View, render, render_flat};
use proctex::solid::{Orbit, Shape, SolidView, render_solid};
use proctex_web::renderer::{Pass, TextureRenderer, clear_pass};

/// What a GPU render draws.
enum What {
    Plane(View),
    Flat,
    Solid(Orbit),
}

/// Renders `params` with the GPU pipeline into a `w × h` rgba8unorm texture; returns RGB8.
fn render_gpu(gpu: &Gpu, params: &Params, w: u32, h: u32, what: &What) -> Vec<u8> {
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let target = rgba8_target(gpu, w, h);
    let mut renderer = TextureRenderer::new(&gpu.device, format);
    let pass_kind = match what {
        What::Plane(view) => {
            renderer.set_params(&gpu.device, &gpu.queue, params);
            renderer.set_view(&gpu.queue, view, [0.0, 0.0]);
            Pass::Plane
        }
        What::Flat => {
            renderer.set_params(&gpu.device, &gpu.queue, params);
            Pass::Flat
        }
        What::Solid(orbit) => {
            let mut solid = params.clone();
            solid.solid = true;
            renderer.set_params(&gpu.device, &gpu.queue, &solid);
            renderer.set_solid_view(
                &gpu.queue,
                &SolidView::new(orbit, [w as f32, h as f32], [0.0, 0.0]),
            );
            Pass::Solid
        }
    };
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    {
        let target_view = target.create_view(&wgpu::TextureViewDescriptor::default());
        let mut pass = clear_pass(&mut encoder, &target_view, "texture");
        renderer.draw_pass(&mut pass, pass_kind);
    }
    gpu.queue.submit([encoder.finish()]);
    read_rgb8(gpu, &target, w, h)
}

fn compare(gpu: &Gpu, what: &str, params: &Params, w: u32, h: u32, view: &View) {
    compare_within(gpu, what, params, w, h, view, 0.0);
}

/// [`compare`], allowing a fraction `outliers` of the channel values to differ by more than
/// 3/255: structured patterns have hard edges (a `floor` at a brick joint), where the last bit
/// of a GPU's division can move a pixel to the neighbouring brick.
fn compare_within(
    gpu: &Gpu,
    what: &str,
    params: &Params,
    w: u32,
    h: u32,
    view: &View,
    outliers: f64,
) {
    let cpu = render(params, w, h, view).to_rgb8();
    let gpu_rgb = render_gpu(gpu, params, w, h, &What::Plane(*view));
    let diffs: Vec<u8> = cpu
        .iter()
        .zip(&gpu_rgb)
        .map(|(a, b)| a.abs_diff(*b))
        .collect();
    let mae = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
    let max = *diffs.iter().max().unwrap();
    println!(
        "{what:<40} {w}×{h} on {}: mean |GPU − CPU| = {mae:.4}/255, max {max}/255",
        gpu.adapter_name
    );
    let far = diffs.iter().filter(|&&d| d > 3).count() as f64 / diffs.len() as f64;
    assert!(
        mae <= 0.25 && (max <= 3 || far <= outliers),
        "{what}: mean {mae}/255, max {max}/255, {:.3} % beyond 3/255",
        100.0 * far
    );
    // And the image is a texture, not a flat colour.
    let mean = cpu.iter().map(|&v| v as f64).sum::<f64>() / cpu.len() as f64;
    let var = cpu.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / cpu.len() as f64;
    assert!(var > 4.0, "{what}: flat image");
}

#[test]
fn gpu_matches_cpu_reference() {
    let gpu = gpu();
    let rock = with_curve("stk_rock_mountain_512.png");
    compare(&gpu, "rock, 1:1", &rock, 256, 192, &View::default());

    let mut no_hist = sample_params("skimage_gravel_512.png");
    let m = no_hist.model.noise_layer_mut();
    m.histogram.enabled = false;
    compare(
        &gpu,
        "gravel, histogram off",
        &no_hist,
        200,
        160,
        &View::default(),
    );

    // Rotated, scaled, panned, zoomed out 3.3× (band clamping active).
    let mut turned = rock.clone();
    turned.transform.rotation_deg = 33.0;
    turned.transform.scale = 1.7;
    turned.colour.contrast = 1.6;
    let view = View {
        origin: [-311.5, 97.25],
        pixel_size: 5.6,
        z: 0.0,
    };
    compare(
        &gpu,
        "rock, rotated + minified, contrast 1.6",
        &turned,
        160,
        160,
        &view,
    );

    // A solid-texture slice.
    let mut solid = sample_params("skimage_grass_512.png");
    solid.solid = true;
    let view = View {
        z: 41.3,
        ..View::default()
    };
    compare(&gpu, "grass, solid slice z = 41.3", &solid, 128, 128, &view);

    // Oriented bands: plane (turned and minified too) and solid.
    compare(
        &gpu,
        "rock, oriented bands",
        &oriented(&rock, 30.0),
        200,
        160,
        &View::default(),
    );
    compare(
        &gpu,
        "rock, oriented, rotated + minified",
        &oriented(&turned, 100.0),
        160,
        160,
        &View {
            origin: [-311.5, 97.25],
            pixel_size: 5.6,
            z: 0.0,
        },
    );
    compare(
        &gpu,
        "grass, oriented, solid slice",
        &oriented(&solid, 60.0),
        128,
        128,
        &view,
    );
}

#[test]
fn structured_models_match_cpu() {
    let gpu = gpu();
    let rock = sample_params("stk_rock_mountain_512.png");
    let minified = View {
        origin: [-40.0, 13.0],
        pixel_size: 3.1,
        z: 0.0,
    };
    for kind in proctex::pattern::PatternKind::ALL {
        let p = structured(&rock, kind);
        let name = kind.name();
        compare_within(&gpu, name, &p, 160, 120, &View::default(), 0.002);
        compare_within(
            &gpu,
            &format!("{name}, minified"),
            &p,
            96,
            96,
            &minified,
            0.002,
        );
    }
    for kind in [
        proctex::pattern::PatternKind::Turbulence,
        proctex::pattern::PatternKind::Rings,
    ] {
        let mut p = structured(&rock, kind);
        p.solid = true;
        let view = View {
            z: 17.5,
            ..View::default()
        };
        compare_within(
            &gpu,
            &format!("{}, solid slice", kind.name()),
            &p,
            128,
            96,
            &view,
            0.002,
        );
    }
}

#[test]
fn solid_view_and_flat_baseline_match_cpu() {
    let gpu = gpu();
    let rock = sample_params("stk_rock_mountain_512.png");
    for (what, shape) in [("sphere", Shape::Sphere), ("cube", Shape::Cube)] {
        let orbit = Orbit {
            shape,
            yaw_deg: 20.0,
            pitch_deg: 30.0,
            ..Orbit::default()
        };
        let (w, h) = (160, 120);
        let cpu = render_solid(&rock, &orbit, w, h).to_rgb8();
        let gpu_rgb = render_gpu(&gpu, &rock, w, h, &What::Solid(orbit));
        let (mae, big) = rgb_difference(&cpu, &gpu_rgb);
        // Silhouette pixels may fall either side of the edge in f32: `big` counts them.
        println!(
            "rock, solid {what:<30} {w}×{h} on {}: mean |GPU − CPU| = {mae:.4}/255, {:.3} % of values > 3/255",
            gpu.adapter_name,
            big * 100.0
        );
        assert!(mae <= 0.25 && big <= 0.002, "{what}: mean {mae}, {big} big");
        // The object covers a good part of the view, textured and lit.
        let bg = proctex::solid::BACKGROUND.map(|v| (v * 255.0).round() as u8);
        let covered = cpu.chunks_exact(3).filter(|p| *p != bg).count() as f64 / (w * h) as f64;
        assert!(covered > 0.2, "{what}: object covers {covered}");
    }
    let flat = render_gpu(&gpu, &rock, 64, 32, &What::Flat);
    let cpu = render_flat(&rock, 64, 32).to_rgb8();
    assert_eq!(flat, cpu, "flat baseline");
}
