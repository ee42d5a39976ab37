//! The GPU renderer of the procedural texture: the plane-view pipeline of
//! `proctex_shaders::plane_shader`, its uniform buffers and noise tiles.
//!
//! Data flow per change: `Params` → `render::Prepared` → `uniform_bytes` → one buffer write.
//! A slider drag therefore costs one 2 KB upload and no pipeline or tile work; tiles are
//! regenerated only when the seed (or the 2D/solid choice) changes.

use proctex::params::Params;
use proctex::render::{Prepared, View, tile_for};
use proctex::solid::SolidView;

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

/// Which shader a draw uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// The 2D plane view (`plane.wgsl`, `fs_main`).
    Plane,
    /// The mean colour (`plane.wgsl`, `fs_flat`): the benchmarks' baseline.
    Flat,
    /// The sphere or cube of the solid view (`solid.wgsl`).
    Solid,
}

/// Everything needed to draw the texture into a render pass.
#[derive(Debug)]
pub struct TextureRenderer {
    pipeline: wgpu::RenderPipeline,
    flat_pipeline: wgpu::RenderPipeline,
    solid_pipeline: wgpu::RenderPipeline,
    params_buffer: wgpu::Buffer,
    view_buffer: wgpu::Buffer,
    solid_buffer: wgpu::Buffer,
    solid_group: wgpu::BindGroup,
    params_layout: wgpu::BindGroupLayout,
    params_group: Option<wgpu::BindGroup>,
    view_group: wgpu::BindGroup,
    tiles: Option<TileKey>,
    uploaded: Option<Params>,
}

/// A texture binding read with textureLoad, unfilterable: the noise tiles (rgba32float) and the
/// view cache's image.
pub(crate) fn tile_entry(
    binding: u32,
    view_dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension,
            multisampled: false,
        },
        count: None,
    }
}

pub(crate) fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// Group 0 of every texture shader (`shaders/params.wgsl`): the params uniform, the 2D and 3D
/// noise tiles.
pub(crate) fn params_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("proctex params"),
        entries: &[
            uniform_entry(0),
            tile_entry(1, wgpu::TextureViewDimension::D2),
            tile_entry(2, wgpu::TextureViewDimension::D3),
        ],
    })
}

/// A group of one uniform buffer at binding 0 (the views' group 1).
pub(crate) fn uniform_layout(device: &wgpu::Device, label: &str) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[uniform_entry(0)],
    })
}

/// An rgba32float texture of `n × n` (× `depth`) texels from `data`, four floats per texel: the
/// noise tiles, their three components in RGB ([`proctex::noise::Tile::rgba`]).
pub(crate) fn rgba32_texture(
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
        format: wgpu::TextureFormat::Rgba32Float,
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
            bytes_per_row: Some(16 * n),
            rows_per_image: Some(n),
        },
        size,
    );
    texture
}

/// A pipeline that draws the full-screen triangle of `vs` with the fragment shader `fs` into
/// one target of `format`, without blending (every shader of the app and its tests; `layout`
/// `None`: derived from the shader).
pub fn full_screen_pipeline(
    device: &wgpu::Device,
    layout: Option<&wgpu::PipelineLayout>,
    module: &wgpu::ShaderModule,
    vs: &str,
    fs: &str,
    format: wgpu::TextureFormat,
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fs),
        layout,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vs),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fs),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// A render pass into `view` that clears it to black and keeps what is drawn.
pub fn clear_pass<'a>(
    encoder: &'a mut wgpu::CommandEncoder,
    view: &'a wgpu::TextureView,
    label: &str,
) -> wgpu::RenderPass<'a> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

impl TextureRenderer {
    /// Creates the pipeline for a target of `format` (the canvas or an offscreen texture).
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("proctex plane"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::plane_shader().into()),
        });
        let solid_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("proctex solid"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::solid_shader().into()),
        });
        let params_layout = params_layout(device);
        let view_layout = uniform_layout(device, "proctex view");
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("proctex plane"),
            bind_group_layouts: &[Some(&params_layout), Some(&view_layout)],
            immediate_size: 0,
        });
        let make = |module: &wgpu::ShaderModule, vs: &str, fs: &str| {
            full_screen_pipeline(device, Some(&layout), module, vs, fs, format)
        };
        let pipeline = make(&module, "vs_main", "fs_main");
        let flat_pipeline = make(&module, "vs_main", "fs_flat");
        let solid_pipeline = make(&solid_module, "vs_solid", "fs_solid");
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
        let solid_buffer = uniform("proctex solid view", SolidView::UNIFORM_SIZE as u64);
        let solid_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("proctex solid view"),
            layout: &view_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: solid_buffer.as_entire_binding(),
            }],
        });
        TextureRenderer {
            pipeline,
            flat_pipeline,
            solid_pipeline,
            params_buffer,
            view_buffer,
            solid_buffer,
            solid_group,
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
                rgba32_texture(
                    device,
                    queue,
                    "tile2",
                    1,
                    1,
                    wgpu::TextureDimension::D2,
                    &[0.0; 4],
                ),
                rgba32_texture(
                    device,
                    queue,
                    "tile3",
                    n,
                    n,
                    wgpu::TextureDimension::D3,
                    &tile.rgba(),
                ),
            )
        } else {
            (
                rgba32_texture(
                    device,
                    queue,
                    "tile2",
                    n,
                    1,
                    wgpu::TextureDimension::D2,
                    &tile.rgba(),
                ),
                rgba32_texture(
                    device,
                    queue,
                    "tile3",
                    1,
                    1,
                    wgpu::TextureDimension::D3,
                    &[0.0; 4],
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

    /// Sets the solid view's camera and viewport (one 96-byte write).
    pub fn set_solid_view(&self, queue: &wgpu::Queue, view: &SolidView) {
        queue.write_buffer(&self.solid_buffer, 0, &view.uniform_bytes());
    }

    /// Draws the plane view; call after [`TextureRenderer::set_params`].
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        self.draw_pass(pass, Pass::Plane);
    }

    /// Draws the full-screen triangle with the shader of `which`. [`Pass::Solid`] needs params
    /// with `solid` set (3D tiles) and [`TextureRenderer::set_solid_view`].
    pub fn draw_pass(&self, pass: &mut wgpu::RenderPass<'_>, which: Pass) {
        let Some(params_group) = &self.params_group else {
            return;
        };
        let (pipeline, group) = match which {
            Pass::Plane => (&self.pipeline, &self.view_group),
            Pass::Flat => (&self.flat_pipeline, &self.view_group),
            Pass::Solid => (&self.solid_pipeline, &self.solid_group),
        };
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, params_group, &[]);
        pass.set_bind_group(1, group, &[]);
        pass.draw(0..3, 0..1);
    }
}
