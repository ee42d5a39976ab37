//! The exported WGSL shaders (plane, solid, structured, morphs with t as a uniform) rendered as a
//! host renders them against the CPU reference and `morph_path`.

use crate::bake::{bake2, bake3};
use crate::common::{Gpu, gpu, read_rgb8, rgba8_target};
use crate::fixtures::{oriented, sample_params, structured, with_curve};
use proctex::params::Params;
use proctex::render::{View, render};
use proctex_web::renderer::{clear_pass, full_screen_pipeline};

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
