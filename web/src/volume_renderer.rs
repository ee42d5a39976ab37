//! The GPU renderer of a raster solid texture (the Heeger–Bergen volume) on the sphere or cube
//! of the solid views: `proctex_shaders::solid_volume_shader`, the volume as a 3D RGBA8 texture
//! (uploaded once per volume), the camera and the volume's scale as uniforms. Its CPU twin is
//! `proctex::solid::render_solid_volume`.

use std::sync::Arc;

use proctex::solid::{SolidView, VOLUME_UNIFORM_SIZE, Voxels, volume_uniform_bytes};

use crate::renderer::{full_screen_pipeline, tile_entry, uniform_entry, uniform_layout};

/// A volume to show: its voxels, their scale, and an id that changes with the voxels (so that
/// comparing two of them, every frame, compares two numbers).
#[derive(Clone, Debug)]
pub struct VolumeSource {
    /// Different for every volume the app receives.
    pub id: u64,
    /// Voxels per world unit (photo pixel).
    pub voxels_per_unit: f32,
    /// The voxels.
    pub voxels: Arc<Voxels>,
}

impl PartialEq for VolumeSource {
    fn eq(&self, other: &Self) -> bool {
        self.id == other.id && self.voxels_per_unit == other.voxels_per_unit
    }
}

/// The volume pipeline, its uniforms and the uploaded volume.
#[derive(Debug)]
pub struct VolumeRenderer {
    pipeline: wgpu::RenderPipeline,
    volume_layout: wgpu::BindGroupLayout,
    scale_buffer: wgpu::Buffer,
    view_buffer: wgpu::Buffer,
    view_group: wgpu::BindGroup,
    volume_group: Option<wgpu::BindGroup>,
    uploaded: Option<u64>,
}

impl VolumeRenderer {
    /// The pipeline for a target of `format`.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("proctex solid volume"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::solid_volume_shader().into()),
        });
        let volume_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("proctex solid volume"),
            entries: &[
                tile_entry(0, wgpu::TextureViewDimension::D3),
                uniform_entry(1),
            ],
        });
        let view_layout = uniform_layout(device, "proctex solid volume view");
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("proctex solid volume"),
            bind_group_layouts: &[Some(&volume_layout), Some(&view_layout)],
            immediate_size: 0,
        });
        let pipeline = full_screen_pipeline(
            device,
            Some(&layout),
            &module,
            "vs_solid",
            "fs_solid_volume",
            format,
        );
        let uniform = |label, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let scale_buffer = uniform("proctex solid volume scale", VOLUME_UNIFORM_SIZE);
        let view_buffer = uniform("proctex solid volume view", SolidView::UNIFORM_SIZE);
        let view_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("proctex solid volume view"),
            layout: &view_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: view_buffer.as_entire_binding(),
            }],
        });
        VolumeRenderer {
            pipeline,
            volume_layout,
            scale_buffer,
            view_buffer,
            view_group,
            volume_group: None,
            uploaded: None,
        }
    }

    /// Uploads the volume (when its id changed) and its scale.
    pub fn set_volume(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, src: &VolumeSource) {
        queue.write_buffer(
            &self.scale_buffer,
            0,
            &volume_uniform_bytes(src.voxels_per_unit),
        );
        if self.uploaded == Some(src.id) && self.volume_group.is_some() {
            return;
        }
        let n = src.voxels.n;
        let size = wgpu::Extent3d {
            width: n,
            height: n,
            depth_or_array_layers: n,
        };
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("proctex solid volume"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D3,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &src.voxels.rgba,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(4 * n),
                rows_per_image: Some(n),
            },
            size,
        );
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D3),
            ..Default::default()
        });
        self.volume_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("proctex solid volume"),
            layout: &self.volume_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.scale_buffer.as_entire_binding(),
                },
            ],
        }));
        self.uploaded = Some(src.id);
    }

    /// Sets the camera and viewport (one 96-byte write).
    pub fn set_view(&self, queue: &wgpu::Queue, view: &SolidView) {
        queue.write_buffer(&self.view_buffer, 0, &view.uniform_bytes());
    }

    /// Draws the sphere or cube of the volume; call after [`VolumeRenderer::set_volume`] and
    /// [`VolumeRenderer::set_view`].
    pub fn draw(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(group) = &self.volume_group else {
            return;
        };
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.set_bind_group(1, &self.view_group, &[]);
        pass.draw(0..3, 0..1);
    }
}
