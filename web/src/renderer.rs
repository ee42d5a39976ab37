//! The GPU renderer of the procedural texture: the plane-view pipeline of
//! `proctex_shaders::plane_shader`, its uniform buffers and noise tiles.
//!
//! Data flow per change: `Params` → `render::Prepared` → `uniform_bytes` → one buffer write.
//! A slider drag therefore costs one 2 KB upload and no pipeline or tile work; tiles are
//! regenerated only when the seed (or the 2D/solid choice) changes.

use proctex::params::Params;
use proctex::render::{Prepared, View, tile_for};

/// Size of the view uniform (`struct View` in `shaders/plane.wgsl`).
pub const VIEW_UNIFORM_SIZE: usize = 32;

/// Bytes of the view uniform: the CPU renderer's [`View`] plus the framebuffer position of the
/// view's top-left pixel (the view can be a rectangle inside the canvas).
pub fn view_bytes(view: &View, frame_offset: [f32; 2]) -> [u8; VIEW_UNIFORM_SIZE] {
    let mut out = [0u8; VIEW_UNIFORM_SIZE];
    let values = [
        view.origin[0],
        view.origin[1],
        view.pixel_size,
        view.z,
        frame_offset[0],
        frame_offset[1],
        0.0,
        0.0,
    ];
    for (i, v) in values.iter().enumerate() {
        out[i * 4..i * 4 + 4].copy_from_slice(&v.to_le_bytes());
    }
    out
}

/// Tiles currently uploaded: which seed and dimension they are for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct TileKey {
    seed: u32,
    solid: bool,
}

/// Everything needed to draw the texture into a render pass.
#[derive(Debug)]
pub struct TextureRenderer {
    pipeline: wgpu::RenderPipeline,
    params_buffer: wgpu::Buffer,
    view_buffer: wgpu::Buffer,
    params_layout: wgpu::BindGroupLayout,
    params_group: Option<wgpu::BindGroup>,
    view_group: wgpu::BindGroup,
    tiles: Option<TileKey>,
    uploaded: Option<Params>,
}

fn r32_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    n: u32,
    depth: u32,
    dimension: wgpu::TextureDimension,
    data: &[f32],
) -> wgpu::Texture {
    let size = wgpu::Extent3d {
        width: n,
        height: n,
        depth_or_array_layers: depth,
    };
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size,
        mip_level_count: 1,
        sample_count: 1,
        dimension,
        format: wgpu::TextureFormat::R32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_le_bytes()).collect();
    queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: &texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        &bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(4 * n),
            rows_per_image: Some(n),
        },
        size,
    );
    texture
}

impl TextureRenderer {
    /// Creates the pipeline for a target of `format` (the canvas or an offscreen texture).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("proctex plane"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::plane_shader().into()),
        });
        let tile_entry = |binding, view_dimension| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension,
                multisampled: false,
            },
            count: None,
        };
        let uniform_entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let params_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("proctex params"),
            entries: &[
                uniform_entry(0),
                tile_entry(1, wgpu::TextureViewDimension::D2),
                tile_entry(2, wgpu::TextureViewDimension::D3),
            ],
        });
        let view_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("proctex view"),
            entries: &[uniform_entry(0)],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("proctex plane"),
            bind_group_layouts: &[Some(&params_layout), Some(&view_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("proctex plane"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: None,
            multisample: wgpu::MultisampleState::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let uniform = |label, size| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let params_buffer = uniform("proctex params", Prepared::UNIFORM_SIZE as u64);
        let view_buffer = uniform("proctex view", VIEW_UNIFORM_SIZE as u64);
        let view_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("proctex view"),
            layout: &view_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: view_buffer.as_entire_binding(),
            }],
        });
        TextureRenderer {
            pipeline,
            params_buffer,
            view_buffer,
            params_layout,
            params_group: None,
            view_group,
            tiles: None,
            uploaded: None,
        }
    }

    /// Uploads the parameters (one uniform write), and the noise tiles when the seed or the
    /// dimension changed.
    pub fn set_params(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, params: &Params) {
        if self.uploaded.as_ref() == Some(params) {
            return;
        }
        self.uploaded = Some(params.clone());
        queue.write_buffer(
            &self.params_buffer,
            0,
            &Prepared::new(params).uniform_bytes(),
        );
        let key = TileKey {
            seed: params.seed,
            solid: params.solid,
        };
        if self.tiles == Some(key) && self.params_group.is_some() {
            return;
        }
        let tile = tile_for(params);
        let n = tile.n as u32;
        // The unused dimension gets a 1-texel stand-in.
        let (t2, t3) = if params.solid {
            (
                r32_texture(
                    device,
                    queue,
                    "tile2",
                    1,
                    1,
                    wgpu::TextureDimension::D2,
                    &[0.0],
                ),
                r32_texture(
                    device,
                    queue,
                    "tile3",
                    n,
                    n,
                    wgpu::TextureDimension::D3,
                    &tile.data,
                ),
            )
        } else {
            (
                r32_texture(
                    device,
                    queue,
                    "tile2",
                    n,
                    1,
                    wgpu::TextureDimension::D2,
                    &tile.data,
                ),
                r32_texture(
                    device,
                    queue,
                    "tile3",
                    1,
                    1,
                    wgpu::TextureDimension::D3,
                    &[0.0],
                ),
            )
        };
        let v2 = t2.create_view(&wgpu::TextureViewDescriptor::default());
        let v3 = t3.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D3),
            ..Default::default()
        });
        self.params_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("proctex params"),
            layout: &self.params_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.params_buffer.as_entire_binding(),
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
        }));
        self.tiles = Some(key);
    }

    /// Sets which part of world space the view shows and where the view's top-left pixel is in
    /// the target (one 32-byte write).
    pub fn set_view(&self, queue: &wgpu::Queue, view: &View, frame_offset: [f32; 2]) {
        queue.write_buffer(&self.view_buffer, 0, &view_bytes(view, frame_offset));
    }

    /// Draws the full-screen triangle; call after [`TextureRenderer::set_params`].
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(params_group) = &self.params_group else {
            return;
        };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, params_group, &[]);
        pass.set_bind_group(1, &self.view_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
