//! The GPU image equals the CPU reference image: the plane shader rendered by wgpu (natively,
//! on any Vulkan adapter — Mesa's software lavapipe in CI) against `proctex::render::render`,
//! for the same params and view.
//!
//! Tolerance: mean absolute error ≤ 0.25/255 and no pixel off by more than 3/255 over the 8-bit
//! outputs. Both sides evaluate the same f32 expressions in the same order; what differs is
//! rounding (fused multiply-adds the GPU compiler may form, `exp`-free but `floor`/`ceil` on
//! values that land within an ulp of an integer, which can pick the neighbouring coefficient
//! set where the B-spline weight is ~0) and the final conversion to 8 bits.

use proctex::analyze::{Options, analyze_bytes};
use proctex::params::Params;
use proctex::render::{View, render, render_flat};
use proctex::solid::{Orbit, Shape, SolidView, render_solid};
use proctex_web::renderer::{Pass, TextureRenderer, clear_pass, full_screen_pipeline};

mod common;
use common::{Gpu, gpu, read_rgb8, read_texture, rgb_difference, rgba8_target};

/// Renders `params` with the GPU pipeline into a `w × h` rgba8unorm texture; returns RGB8.
/// What a GPU render draws.
enum What {
    Plane(View),
    Flat,
    Solid(Orbit),
}

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

fn sample_params(name: &str) -> Params {
    let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
    analyze_bytes(&std::fs::read(path).unwrap(), &Options::default())
        .unwrap()
        .params
}

/// Sample `name`'s noise model with an output tone curve: its own where its analysis kept one,
/// otherwise one of 9 knots fitted to the photo (the analysis keeps a curve only where it
/// validates within the photo; the morph tests want curves at both ends).
fn with_curve(name: &str) -> Params {
    let mut p = sample_params(name);
    if p.model.tone().is_none() {
        let path = format!("{}/../www/samples/{name}", env!("CARGO_MANIFEST_DIR"));
        let photo = proctex::input::Photo::decode(&std::fs::read(path).unwrap()).unwrap();
        let photo = proctex::analyze::prepare_photo(&photo, &Options::default()).unwrap();
        let tone = proctex::noise_tone::fit_noise_tone(&photo, &p, 9);
        p.model.noise_layer_mut().tone = tone;
    }
    assert!(p.model.tone().is_some(), "{name}: no curve");
    p
}

/// `p` with every band oriented: streaks at `angle + 25°·j`, strengths from 0.3 to 1 (band 2
/// at full strength, band 3 isotropic: both branches of the shader).
fn oriented(p: &Params, angle: f32) -> Params {
    let mut p = p.clone();
    let m = p.model.noise_layer_mut();
    m.orientation = (0..m.bands())
        .map(|j| proctex::params::BandOrientation {
            angle_deg: (angle + 25.0 * j as f32).rem_euclid(180.0),
            strength: [0.3, 0.7, 1.0, 0.0][j % 4],
        })
        .collect();
    p
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

/// A structured texture of `kind` on `base`'s colours and noise: the pattern at its defaults,
/// scale 11 texels, turned 20°, a three-stop ramp about the mean, the noise at 40 %, an output
/// tone curve.
fn structured(base: &Params, kind: proctex::pattern::PatternKind) -> Params {
    use proctex::params::{Model, StructuredModel};
    use proctex::pattern::{Pattern, RampStop};
    let mut p = base.clone();
    let mut residual = base.model.noise_layer().clone();
    // The structured model's curve below applies last; a residual has none of its own.
    residual.tone = None;
    for w in residual.weights.iter_mut().flatten() {
        *w *= 0.4;
    }
    let m = base.colour.mean;
    let b = base.colour.basis[0];
    let tone = |k: f32| [0, 1, 2].map(|c| (m[c] + k * b[c]).clamp(0.0, 1.0));
    let mut pattern = Pattern::new(kind, 11.0);
    pattern.rotation_deg = 20.0;
    // Rings centred inside the image (texel (44, 33)), so that the centre's offset is compared.
    pattern.set("centre_x", 4.0);
    pattern.set("centre_y", 3.0);
    p.model = Model::Structured(StructuredModel {
        pattern,
        ramp: vec![
            RampStop {
                at: 0.0,
                rgb: tone(-0.25),
            },
            RampStop {
                at: 0.4,
                rgb: tone(0.05),
            },
            RampStop {
                at: 1.0,
                rgb: tone(0.2),
            },
        ],
        residual,
        // An S-shaped output tone curve, a different one per channel.
        tone: Some(proctex::params::Tone {
            enabled: true,
            range: [[0.1, 0.8], [0.15, 0.9], [0.05, 0.7]],
            knots: [0.9f32, 1.0, 1.15].map(|g| {
                (0..9)
                    .map(|k| {
                        let x = k as f32 / 8.0;
                        0.05 + 0.9 * (x * x * (3.0 - 2.0 * x)).powf(g)
                    })
                    .collect()
            }),
        }),
    });
    p.validate().unwrap();
    p
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
    let target = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(entry),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
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
fn bake2(gpu: &Gpu, module: &wgpu::ShaderModule, n: u32) -> wgpu::Texture {
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
fn bake3(gpu: &Gpu, module: &wgpu::ShaderModule, n: u32) -> wgpu::Texture {
    let a = bake_pass(gpu, module, "fs_bake3_down_x", None, 4 * n, n * n / 8);
    let b = bake_pass(gpu, module, "fs_bake3_down_y", Some(&a), 8 * n, n * n / 16);
    let c = bake_pass(gpu, module, "fs_bake3_down_z", Some(&b), 8 * n, n * n / 16);
    bake_pass(gpu, module, "fs_bake3_tile", Some(&c), 8 * n, n * n / 8)
}

#[test]
fn exported_wgsl_renders_the_cpu_image() {
    let gpu = gpu();
    let plane = with_curve("skimage_gravel_512.png");
    let mut solid = with_curve("stk_rock_mountain_512.png");
    solid.solid = true;
    let brick = structured(
        &sample_params("skimage_brick_512.png"),
        proctex::pattern::PatternKind::Brick,
    );
    let mut rings = structured(&solid, proctex::pattern::PatternKind::Rings);
    rings.solid = true;
    let oriented_plane = oriented(&plane, 45.0);
    let oriented_solid = oriented(&solid, 120.0);
    for (name, params) in [
        ("gravel, oriented", oriented_plane),
        ("rock, solid, oriented", oriented_solid),
        ("gravel", plane),
        ("rock, solid", solid),
        ("brick (structured)", brick),
        ("rings (structured, solid)", rings),
    ] {
        let src = proctex::export::wgsl(&params).unwrap();
        exported_wgsl_matches_cpu(&gpu, &src, &[(name.to_string(), params, None)]);
    }
}

/// The exported morph with t as a uniform equals the CPU's morph (`morph_path`) along t.
#[test]
fn exported_morph_renders_the_cpu_morph() {
    let gpu = gpu();
    let gravel = with_curve("skimage_gravel_512.png");
    let rock = with_curve("stk_rock_mountain_512.png");
    let mut wood = sample_params("stk_wood_planks1_256.png");
    wood.transform.rotation_deg = 300.0;
    // The rock's output tone curve fades out towards the wood, which has none.
    wood.model.noise_layer_mut().tone = None;
    // Oriented ends whose streaks turn through 180° (170° → 10°+25°j): the angle keeps turning
    // the shorter way without a jump, on the GPU as on the CPU.
    let keys = vec![oriented(&gravel, 170.0), oriented(&rock, 10.0), wood];
    let src = proctex::export::morph_wgsl(&keys).unwrap();
    let cases: Vec<_> = [0.0f32, 0.2, 0.5, 0.75, 0.9, 1.0]
        .into_iter()
        .map(|t| {
            let params = proctex::morph::morph_path(&keys, t).unwrap();
            (format!("morph of 3, t = {t}"), params, Some(t))
        })
        .collect();
    exported_wgsl_matches_cpu(&gpu, &src, &cases);
}

/// The exported morph through structured models equals the CPU's morph along t: one family
/// (brick to brick: pattern, ramp and tone curve interpolate), then across families and the
/// noise model (cross-fades through the flat ramp), plane and solid.
#[test]
fn exported_structured_morph_renders_the_cpu_morph() {
    use proctex::pattern::PatternKind;
    let gpu = gpu();
    let rock = sample_params("stk_rock_mountain_512.png");
    let gravel = sample_params("skimage_gravel_512.png");
    let brick_a = structured(&rock, PatternKind::Brick);
    let mut brick_b = structured(&gravel, PatternKind::Brick);
    if let proctex::params::Model::Structured(m) = &mut brick_b.model {
        m.pattern.scale = 17.0;
        m.pattern.rotation_deg = 340.0;
        m.pattern.set("aspect", 3.0);
        m.pattern.set("mortar", 0.2);
        m.tone = None;
        m.ramp.truncate(2);
    }
    let cells = structured(&gravel, PatternKind::Cells);
    let keys = vec![brick_a, brick_b, gravel, cells];
    let src = proctex::export::morph_wgsl(&keys).unwrap();
    let cases: Vec<_> = [0.1f32, 0.3, 0.45, 0.5, 0.9]
        .into_iter()
        .map(|t| {
            let params = proctex::morph::morph_path(&keys, t).unwrap();
            (format!("structured morph of 4, t = {t}"), params, Some(t))
        })
        .collect();
    exported_wgsl_matches_cpu(&gpu, &src, &cases);
    let mut rings = structured(&rock, PatternKind::Rings);
    rings.solid = true;
    let mut cells = structured(&rock, PatternKind::Cells);
    cells.solid = true;
    let keys = vec![rings, cells];
    let src = proctex::export::morph_wgsl(&keys).unwrap();
    let cases: Vec<_> = [0.3f32, 0.7]
        .into_iter()
        .map(|t| {
            let params = proctex::morph::morph_path(&keys, t).unwrap();
            (format!("solid structured morph, t = {t}"), params, Some(t))
        })
        .collect();
    exported_wgsl_matches_cpu(&gpu, &src, &cases);
}

/// Renders the exported shader `src` as a host does (its header's steps: the tile baked by its
/// own passes, the full-screen pass) for each case (a name, the params the CPU renders, and a
/// morph's t), and compares with the CPU reference. One shader module and pipeline serve every
/// case, as a host animating a morph's t would use them: compiling a morph shader is the slow
/// step on a software driver.
fn exported_wgsl_matches_cpu(gpu: &Gpu, src: &str, cases: &[(String, Params, Option<f32>)]) {
    let module = gpu
        .device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("exported"),
            source: wgpu::ShaderSource::Wgsl(src.to_string().into()),
        });
    let solid = cases[0].1.solid;
    assert!(
        cases.iter().all(|(_, p, _)| p.solid == solid),
        "one shader is plane or solid"
    );
    // The host steps of the snippet's header comment.
    let tile = if solid {
        bake3(gpu, &module, proctex::noise::TILE_3D as u32)
    } else {
        bake2(gpu, &module, proctex::noise::TILE_2D as u32)
    };
    let (w, h) = (256u32, 192u32);
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let pipeline = full_screen_pipeline(&gpu.device, None, &module, "vs_main", "fs_main", format);
    let tile_view = tile.create_view(&wgpu::TextureViewDescriptor::default());
    for (name, params, t) in cases {
        let target = rgba8_target(gpu, w, h);
        // The morph's t: a 16-byte uniform buffer at binding 3, t in its first f32.
        let t_buffer = t.map(|t| {
            use wgpu::util::DeviceExt;
            let mut bytes = [0u8; 16];
            bytes[..4].copy_from_slice(&t.to_le_bytes());
            gpu.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("proctex_t"),
                    contents: &bytes,
                    usage: wgpu::BufferUsages::UNIFORM,
                })
        });
        let t_entry = t_buffer.as_ref().map(|b| wgpu::BindGroupEntry {
            binding: 3,
            resource: b.as_entire_binding(),
        });
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&tile_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&tile_view),
                },
            ]
            .into_iter()
            .chain(t_entry)
            .collect::<Vec<_>>(),
        });
        let mut encoder = gpu
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
        {
            let view = target.create_view(&wgpu::TextureViewDescriptor::default());
            let mut pass = clear_pass(&mut encoder, &view, "exported");
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.draw(0..3, 0..1);
        }
        gpu.queue.submit([encoder.finish()]);
        let got = read_rgb8(gpu, &target, w, h);
        let cpu = render(params, w, h, &View::default()).to_rgb8();
        let mut sum = 0.0f64;
        let mut max = 0u8;
        let mut far = 0usize;
        for (g, c) in got.iter().zip(&cpu) {
            let d = g.abs_diff(*c);
            sum += d as f64;
            max = max.max(d);
            far += (d > 3) as usize;
        }
        let mae = sum / (w * h * 3) as f64;
        let far = far as f64 / (w * h * 3) as f64;
        println!(
            "exported WGSL (tile baked on the GPU) vs CPU, {name} {w}×{h} on {}: mean {mae:.4}/255, max {max}/255, {:.3} % beyond 3/255",
            gpu.adapter_name,
            100.0 * far
        );
        // Structured patterns: see compare_within.
        assert!(
            mae <= 0.25 && (max <= 3 || far <= 0.002),
            "{name}: mean {mae}, max {max}"
        );
    }
}

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
