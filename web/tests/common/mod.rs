//! What the native GPU tests share: a device on a Vulkan adapter (Mesa's software lavapipe in
//! CI) and the readback of an rgba8unorm target.
#![allow(dead_code)]

/// A wgpu device on a Vulkan adapter, and the adapter's name for the printed lines.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_name: String,
}

/// The first Vulkan adapter (lavapipe in CI).
pub fn gpu() -> Gpu {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::VULKAN,
        ..wgpu::InstanceDescriptor::new_without_display_handle()
    });
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::LowPower,
        force_fallback_adapter: false,
        compatible_surface: None,
        ..Default::default()
    }))
    .expect(
        "no Vulkan adapter: install Mesa's software Vulkan driver (apt-get install \
         mesa-vulkan-drivers); scripts/test.sh does",
    );
    let adapter_name = adapter.get_info().name;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("gpu_vs_cpu"),
        required_features: wgpu::Features::empty(),
        required_limits: wgpu::Limits::downlevel_defaults(),
        ..Default::default()
    }))
    .expect("device");
    Gpu {
        device,
        queue,
        adapter_name,
    }
}

/// Reads a `w × h` texture (with `COPY_SRC`) of `texel` bytes per texel back, rows packed.
pub fn read_texture(gpu: &Gpu, target: &wgpu::Texture, w: u32, h: u32, texel: u32) -> Vec<u8> {
    let row = (w * texel).div_ceil(256) * 256;
    let readback = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: (row * h) as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: None });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: target,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row),
                rows_per_image: Some(h),
            },
        },
        wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);
    let slice = readback.slice(..);
    slice.map_async(wgpu::MapMode::Read, |r| r.expect("map"));
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("poll");
    let data = slice.get_mapped_range().expect("mapped");
    (0..h)
        .flat_map(|y| data[(y * row) as usize..(y * row + w * texel) as usize].to_vec())
        .collect()
}

/// Reads a `w × h` rgba8unorm texture (with `COPY_SRC`) back as RGB8, row-major.
pub fn read_rgb8(gpu: &Gpu, target: &wgpu::Texture, w: u32, h: u32) -> Vec<u8> {
    read_texture(gpu, target, w, h, 4)
        .chunks_exact(4)
        .flat_map(|px| [px[0], px[1], px[2]])
        .collect()
}

/// A `w × h` rgba8unorm render target that can be read back.
pub fn rgba8_target(gpu: &Gpu, w: u32, h: u32) -> wgpu::Texture {
    render_target(
        gpu,
        "target",
        w,
        h,
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureUsages::empty(),
    )
}

/// A `w × h` 2D render target of `format` that can be read back, with `usage` besides.
pub fn render_target(
    gpu: &Gpu,
    label: &str,
    w: u32,
    h: u32,
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
) -> wgpu::Texture {
    gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC | usage,
        view_formats: &[],
    })
}

/// The mean absolute difference of two 8-bit images' values (/255), and the fraction of values
/// that differ by more than 3/255.
pub fn rgb_difference(a: &[u8], b: &[u8]) -> (f64, f64) {
    let diffs: Vec<u8> = a.iter().zip(b).map(|(x, y)| x.abs_diff(*y)).collect();
    let mae = diffs.iter().map(|&d| d as f64).sum::<f64>() / diffs.len() as f64;
    let big = diffs.iter().filter(|&&d| d > 3).count() as f64 / diffs.len() as f64;
    (mae, big)
}
