//! The texture view's frame cache: the procedural texture is rendered into an offscreen image
//! only when what it shows changes (params, view, shader, size), and every frame copies that
//! image to the canvas (`shaders/view_copy.wgsl`, pixel for pixel).
//!
//! Why: egui repaints on every hover, text edit and progress tick (ten times a second while
//! the worker analyses or refines), and the texture shader is the frame's whole cost. Measured
//! in Chromium on the software adapter (SwiftShader, 2 cores), a 500×775 px plane view: 2.1 s
//! a frame with the texture shader, 0.17 s with the trivial one; on a GPU the texture shader is
//! bound by its texture fetches (~15 ms for a 1080p view). With the cache a frame in which the
//! texture does not change costs one copy, and the analysis worker keeps the CPU it shares with
//! a software adapter.
//!
//! The cached image is the texture shader's output itself: the view is rendered at frame
//! offset 0 into an image of the view's size and format, so pixel `p` of the cache is the pixel
//! `p + offset` of a direct render (both shaders compute `frag.xy - frame_offset` from integral
//! offsets), and the copy reads it with `textureLoad`. The GPU-vs-CPU tests go through it.

use proctex::params::Params;
use proctex::render::View;
use proctex::solid::SolidView;

use crate::renderer::{
    Pass, TextureRenderer, clear_pass, full_screen_pipeline, tile_entry, uniform_entry,
};
use crate::volume_renderer::{VolumeRenderer, VolumeSource};

/// Size of the copy's uniform (`struct ViewCopy` in `shaders/view_copy.wgsl`).
const COPY_UNIFORM_SIZE: usize = 16;

/// The cache pixel that framebuffer pixel `frame` shows (the twin of `view_copy.wgsl`'s
/// `cached_pixel`): the same pixel of the view, clamped to the cache.
pub fn cached_pixel(frame: [i32; 2], offset: [i32; 2], size: [i32; 2]) -> [i32; 2] {
    [0, 1].map(|i| (frame[i] - offset[i]).clamp(0, size[i] - 1))
}

/// The CPU twin of the copy pass (`vs_copy`, `fs_copy`): the framebuffer rectangle at `offset`
/// of `frame_size` pixels filled from the cached image (`size`, RGBA, row-major).
pub fn copy_view(
    cached: &[[u8; 4]],
    size: [i32; 2],
    offset: [i32; 2],
    frame_size: [i32; 2],
) -> Vec<[u8; 4]> {
    let mut out = Vec::with_capacity((frame_size[0] * frame_size[1]).max(0) as usize);
    for y in 0..frame_size[1] {
        for x in 0..frame_size[0] {
            let [cx, cy] = cached_pixel([x + offset[0], y + offset[1]], offset, size);
            out.push(cached[(cy * size[0] + cx) as usize]);
        }
    }
    out
}

/// What the view shows: the plane (or flat) view, or the solid view's camera.
#[derive(Clone, Debug, PartialEq)]
pub enum ViewSource {
    /// World window of the plane view.
    Plane(View),
    /// Camera of the sphere or cube of the procedural texture.
    Solid(SolidView),
    /// Camera of the sphere or cube of a raster volume (the pass and params are not used).
    Volume(SolidView, VolumeSource),
}

/// Everything the cached pixels depend on.
#[derive(Clone, Debug, PartialEq)]
struct CacheKey {
    params: Params,
    pass: Pass,
    view: ViewSource,
    size: [u32; 2],
}

/// The offscreen image and the copy's bindings for it.
#[derive(Debug)]
struct Target {
    view: wgpu::TextureView,
    group: wgpu::BindGroup,
    size: [u32; 2],
}

/// The texture renderer behind a frame cache (the app's one callback resource).
#[derive(Debug)]
pub struct CachedView {
    renderer: TextureRenderer,
    volume: VolumeRenderer,
    format: wgpu::TextureFormat,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    target: Option<Target>,
    key: Option<CacheKey>,
    renders: u64,
}

impl CachedView {
    /// The renderer and the copy pipeline for a canvas of `format`.
    pub fn new(device: &wgpu::Device, format: wgpu::TextureFormat) -> Self {
        let renderer = TextureRenderer::new(device, format);
        let volume = VolumeRenderer::new(device, format);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("proctex view copy"),
            source: wgpu::ShaderSource::Wgsl(proctex_shaders::VIEW_COPY.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("proctex view copy"),
            entries: &[
                tile_entry(0, wgpu::TextureViewDimension::D2),
                uniform_entry(1),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("proctex view copy"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = full_screen_pipeline(
            device,
            Some(&pipeline_layout),
            &module,
            "vs_copy",
            "fs_copy",
            format,
        );
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("proctex view copy"),
            size: COPY_UNIFORM_SIZE as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        CachedView {
            renderer,
            volume,
            format,
            pipeline,
            layout,
            uniform,
            target: None,
            key: None,
            renders: 0,
        }
    }

    /// How many times the texture shader has rendered the view (the rest were copies).
    pub fn renders(&self) -> u64 {
        self.renders
    }

    /// Renders the view into the cache when what it shows changed (always when `fresh`, the
    /// benchmarks' way to time the texture shader per frame), and points the copy at the
    /// framebuffer rectangle at `frame_offset` of `frame_size` pixels.
    #[allow(clippy::too_many_arguments)]
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        params: &Params,
        pass: Pass,
        view: &ViewSource,
        frame_offset: [i32; 2],
        frame_size: [u32; 2],
        fresh: bool,
    ) {
        let size = frame_size.map(|v| v.max(1));
        let mut copy = [0u8; COPY_UNIFORM_SIZE];
        for (i, v) in [
            frame_offset[0],
            frame_offset[1],
            size[0] as i32,
            size[1] as i32,
        ]
        .iter()
        .enumerate()
        {
            copy[i * 4..i * 4 + 4].copy_from_slice(&v.to_le_bytes());
        }
        queue.write_buffer(&self.uniform, 0, &copy);
        // Compared by reference: an unchanged view (most frames) clones nothing.
        let unchanged = self.key.as_ref().is_some_and(|k| {
            k.pass == pass && k.size == size && &k.view == view && &k.params == params
        });
        if unchanged && !fresh {
            return;
        }
        if self.target.as_ref().is_none_or(|t| t.size != size) {
            self.target = Some(self.make_target(device, size));
        }
        let Some(target) = &self.target else {
            return;
        };
        // The view rendered at frame offset 0: the cache is the view's own image.
        let at_origin = |sv: &SolidView| SolidView {
            frame_offset: [0.0, 0.0],
            ..*sv
        };
        match view {
            ViewSource::Plane(v) => {
                self.renderer.set_params(device, queue, params);
                self.renderer.set_view(queue, v, [0.0, 0.0]);
            }
            ViewSource::Solid(sv) => {
                self.renderer.set_params(device, queue, params);
                self.renderer.set_solid_view(queue, &at_origin(sv));
            }
            ViewSource::Volume(sv, src) => {
                self.volume.set_volume(device, queue, src);
                self.volume.set_view(queue, &at_origin(sv));
            }
        }
        let mut rp = clear_pass(encoder, &target.view, "proctex view cache");
        match view {
            ViewSource::Volume(..) => self.volume.draw(&mut rp),
            _ => self.renderer.draw_pass(&mut rp, pass),
        }
        drop(rp);
        self.key = Some(CacheKey {
            params: params.clone(),
            pass,
            view: view.clone(),
            size,
        });
        self.renders += 1;
    }

    /// Copies the cached view into the canvas pass (after [`CachedView::prepare`]).
    pub fn paint(&self, pass: &mut wgpu::RenderPass<'_>) {
        let Some(target) = &self.target else {
            return;
        };
        if self.key.is_none() {
            return;
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &target.group, &[]);
        pass.draw(0..3, 0..1);
    }

    fn make_target(&self, device: &wgpu::Device, size: [u32; 2]) -> Target {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("proctex view cache"),
            size: wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: self.format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("proctex view copy"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.uniform.as_entire_binding(),
                },
            ],
        });
        Target { view, group, size }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_copy_shows_the_view_pixel_for_pixel_and_clamps_at_its_edges() {
        let size = [3, 2];
        let cached: Vec<[u8; 4]> = (0..6).map(|i| [i as u8, 0, 0, 255]).collect();
        // The rectangle exactly over the cache: the cache itself.
        assert_eq!(copy_view(&cached, size, [10, 20], size), cached);
        // A framebuffer pixel left of / above the view reads the first column / row, one
        // beyond the view reads the last.
        assert_eq!(cached_pixel([9, 19], [10, 20], size), [0, 0]);
        assert_eq!(cached_pixel([13, 22], [10, 20], size), [2, 1]);
        assert_eq!(cached_pixel([11, 21], [10, 20], size), [1, 1]);
    }
}
