//! The PNG tile export: a seamless tile (`proctex::seamless`) rendered in strips on the GPU
//! (`shaders/seamless.wgsl` into an rgba32float target, read back), or on the CPU when there is
//! no GPU, and turned into PNG scanlines (8- or 16-bit RGB) for the page to compress.
//!
//! Why strips: an 8192² tile is 67 Mpx; one draw of it would stall the GPU (and, on a software
//! adapter, the page) for a minute and need a 1 GiB float target. A strip of about 2^18 pixels
//! is one short draw and a 4 MiB read-back, and the app shows progress between strips and can
//! cancel. Plain wgpu and no UI types, so that native tests can run it headless.

use std::sync::Arc;
use std::sync::atomic::{AtomicU8, Ordering};

use proctex::noise::Tile;
use proctex::params::Params;
use proctex::render::Prepared;
use proctex::seamless::{self, Seamless, render_rows};

use crate::renderer::{
    clear_pass, full_screen_pipeline, params_layout, rgba32_texture, uniform_layout,
};

/// Pixels per strip (the strip is `size` wide and `STRIP_PIXELS / size` rows high).
const STRIP_PIXELS: u32 = 1 << 18;

/// Rows per strip for a tile side.
pub fn strip_rows(size: u32) -> u32 {
    (STRIP_PIXELS / size).clamp(1, size)
}

/// Map state of the read-back buffer (0 idle, 1 pending, 2 mapped, 3 failed).
const IDLE: u8 = 0;
const PENDING: u8 = 1;
const MAPPED: u8 = 2;
const FAILED: u8 = 3;

/// A strip of the tile read back: its first row and its RGB pixels, row-major.
pub type Strip = (u32, Vec<[f32; 3]>);

/// The seamless-tile pipeline and its resources for one export.
#[derive(Debug)]
pub struct SeamlessGpu {
    pipeline: wgpu::RenderPipeline,
    params_group: wgpu::BindGroup,
    seamless_group: wgpu::BindGroup,
    seamless_buffer: wgpu::Buffer,
    target: wgpu::Texture,
    readback: wgpu::Buffer,
    seamless: Seamless,
    rows: u32,
    row_bytes: u32,
    state: Arc<AtomicU8>,
    in_flight: Option<(u32, u32)>,
}

impl SeamlessGpu {
    /// Prepares the export of `params`' seamless tile of `size²` pixels of `pixel_size` world
    /// units (validates the size first).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        params: &Params,
        size: u32,
        pixel_size: f32,
    ) -> Result<Self, String> {
        let params = seamless::plane(params);
        let prep = Prepared::new(&params);
        let tile = Tile::new_2d(params.seed);
        let seamless = Seamless::new(&prep, tile.n, size, pixel_size).map_err(|e| e.to_string())?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("proctex seamless"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::seamless_shader().into()),
        });
        let params_layout = params_layout(device);
        let seamless_layout = uniform_layout(device, "seamless");
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("seamless"),
            bind_group_layouts: &[Some(&params_layout), Some(&seamless_layout)],
            immediate_size: 0,
        });
        let format = wgpu::TextureFormat::Rgba32Float;
        let pipeline = full_screen_pipeline(
            device,
            Some(&layout),
            &module,
            "vs_seamless",
            "fs_seamless",
            format,
        );
        let uniform = |label, contents: &[u8]| {
            let b = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: contents.len() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            queue.write_buffer(&b, 0, contents);
            b
        };
        let params_buffer = uniform("seamless params", &prep.uniform_bytes());
        let seamless_buffer = uniform("seamless", &seamless.uniform_bytes(0));
        let v2 = rgba32_texture(
            device,
            queue,
            "seamless tile2",
            tile.n as u32,
            1,
            wgpu::TextureDimension::D2,
            &tile.rgba(),
        )
        .create_view(&wgpu::TextureViewDescriptor::default());
        let v3 = rgba32_texture(
            device,
            queue,
            "seamless tile3",
            1,
            1,
            wgpu::TextureDimension::D3,
            &[0.0; 4],
        )
        .create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D3),
            ..Default::default()
        });
        let params_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("seamless params"),
            layout: &params_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&v2),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&v3),
                },
            ],
        });
        let seamless_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("seamless"),
            layout: &seamless_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: seamless_buffer.as_entire_binding(),
            }],
        });
        let rows = strip_rows(size);
        let target = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("seamless strip"),
            size: wgpu::Extent3d {
                width: size,
                height: rows,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let row_bytes = (size * 16).div_ceil(256) * 256;
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("seamless read-back"),
            size: (row_bytes * rows) as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Ok(SeamlessGpu {
            pipeline,
            params_group,
            seamless_group,
            seamless_buffer,
            target,
            readback,
            seamless,
            rows,
            row_bytes,
            state: Arc::new(AtomicU8::new(IDLE)),
            in_flight: None,
        })
    }

    /// Renders the strip starting at `first_row` and starts reading it back; [`Self::take`]
    /// returns it once mapped. One strip at a time.
    pub fn submit(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, first_row: u32) {
        let size = self.seamless.size;
        let rows = self.rows.min(size - first_row);
        queue.write_buffer(
            &self.seamless_buffer,
            0,
            &self.seamless.uniform_bytes(first_row),
        );
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("seamless strip"),
        });
        {
            let view = self
                .target
                .create_view(&wgpu::TextureViewDescriptor::default());
            let mut pass = clear_pass(&mut encoder, &view, "seamless strip");
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &self.params_group, &[]);
            pass.set_bind_group(1, &self.seamless_group, &[]);
            pass.draw(0..3, 0..1);
        }
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &self.target,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &self.readback,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(self.row_bytes),
                    rows_per_image: Some(self.rows),
                },
            },
            wgpu::Extent3d {
                width: size,
                height: rows,
                depth_or_array_layers: 1,
            },
        );
        queue.submit([encoder.finish()]);
        self.state.store(PENDING, Ordering::SeqCst);
        let state = self.state.clone();
        self.readback
            .slice(..)
            .map_async(wgpu::MapMode::Read, move |r| {
                state.store(if r.is_ok() { MAPPED } else { FAILED }, Ordering::SeqCst);
            });
        self.in_flight = Some((first_row, rows));
    }

    /// The strip in flight once read back: its first row and RGB pixels (`rows × size`).
    pub fn take(&mut self) -> Option<Result<Strip, String>> {
        match self.state.load(Ordering::SeqCst) {
            MAPPED => {}
            FAILED => {
                self.state.store(IDLE, Ordering::SeqCst);
                self.in_flight = None;
                return Some(Err("reading the tile back from the GPU failed".into()));
            }
            _ => return None,
        }
        let (first_row, rows) = self.in_flight.take()?;
        let size = self.seamless.size as usize;
        let mut out = Vec::with_capacity(size * rows as usize);
        {
            let slice = self.readback.slice(..);
            let Ok(data) = slice.get_mapped_range() else {
                return Some(Err("the tile read-back buffer is not mapped".into()));
            };
            for y in 0..rows as usize {
                let line = &data[y * self.row_bytes as usize..][..size * 16];
                out.extend(line.chunks_exact(16).map(|px| {
                    let f = |i: usize| f32::from_le_bytes([px[i], px[i + 1], px[i + 2], px[i + 3]]);
                    [f(0), f(4), f(8)]
                }));
            }
        }
        self.readback.unmap();
        self.state.store(IDLE, Ordering::SeqCst);
        Some(Ok((first_row, out)))
    }

    /// A strip is being rendered or read back.
    pub fn busy(&self) -> bool {
        self.in_flight.is_some()
    }

    /// Rows per strip.
    pub fn rows(&self) -> u32 {
        self.rows
    }
}

/// The CPU fallback: the same strips from the CPU reference renderer.
#[derive(Debug)]
pub struct SeamlessCpu {
    prep: Prepared,
    tile: Tile,
    seamless: Seamless,
}

impl SeamlessCpu {
    /// As [`SeamlessGpu::new`].
    pub fn new(params: &Params, size: u32, pixel_size: f32) -> Result<Self, String> {
        let params = seamless::plane(params);
        let prep = Prepared::new(&params);
        let tile = Tile::new_2d(params.seed);
        let seamless = Seamless::new(&prep, tile.n, size, pixel_size).map_err(|e| e.to_string())?;
        Ok(SeamlessCpu {
            prep,
            tile,
            seamless,
        })
    }

    /// Rows `first_row..first_row + rows` (clipped to the tile).
    pub fn strip(&self, first_row: u32, rows: u32) -> Vec<[f32; 3]> {
        let rows = rows.min(self.seamless.size - first_row);
        render_rows(&self.prep, &self.tile, &self.seamless, first_row, rows)
    }
}

/// PNG scanlines of RGB pixels (`width` per row): each row a filter byte (0, none) and the
/// samples, 8-bit or 16-bit big-endian (PNG's byte order), clamped to [0, 1] and rounded.
pub fn png_scanlines(pixels: &[[f32; 3]], width: usize, bits: u8) -> Vec<u8> {
    let per = if bits == 16 { 6 } else { 3 };
    let mut out = Vec::with_capacity(pixels.len() / width.max(1) * (1 + width * per));
    for row in pixels.chunks(width.max(1)) {
        out.push(0);
        for p in row {
            for v in p {
                let v = v.clamp(0.0, 1.0);
                if bits == 16 {
                    out.extend_from_slice(&((v * 65535.0).round() as u16).to_be_bytes());
                } else {
                    out.push((v * 255.0).round() as u8);
                }
            }
        }
    }
    out
}
