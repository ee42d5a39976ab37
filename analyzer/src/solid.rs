//! The solid-texture view: a sphere or a cube cut out of the 3D texture (Lagae §7: a solid
//! texture is the same model evaluated with 3D noise), seen by an orbiting camera.
//!
//! The same view of a raster volume (the Heeger–Bergen solid texture): [`Voxels`],
//! [`render_solid_volume`].
//!
//! CPU twin of `shaders/solid_camera.wgsl`, `shaders/solid.wgsl` and
//! `shaders/solid_volume.wgsl`: same ray set-up, intersection, footprint and shading, in
//! the same operation order, so the GPU-vs-CPU test can compare the two images. The object is
//! the unit sphere or the cube `[−1, 1]³`; object point `p` is world point `p · radius` (world
//! units are photo pixels, as in the plane view), so the solid shows the texture at the scale
//! of the photo.

use crate::params::Params;
use crate::render::{Image, Prepared, shade, tile_for};

/// Which object the solid view shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// The unit sphere.
    Sphere,
    /// The cube `[−1, 1]³`.
    Cube,
}

/// An orbit camera around the object at the origin (object space, y up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// Turn about the vertical axis, degrees.
    pub yaw_deg: f32,
    /// Elevation, degrees (kept within ±85).
    pub pitch_deg: f32,
    /// Eye distance from the centre, object units (the object has radius 1).
    pub distance: f32,
    /// Vertical field of view, degrees.
    pub fov_deg: f32,
    /// World units per object unit.
    pub radius: f32,
    /// Sphere or cube.
    pub shape: Shape,
}

impl Default for Orbit {
    fn default() -> Self {
        Orbit {
            yaw_deg: 35.0,
            pitch_deg: 25.0,
            distance: 4.0,
            fov_deg: 45.0,
            radius: 256.0,
            shape: Shape::Sphere,
        }
    }
}

/// Background of the solid view (linear in display values, like the texture).
pub const BACKGROUND: [f32; 3] = [0.11, 0.11, 0.11];

/// The camera as the shader sees it (`struct SolidView` in `shaders/solid.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidView {
    /// Eye position (object space).
    pub eye: [f32; 3],
    /// Camera right, up and forward unit vectors.
    pub right: [f32; 3],
    /// Camera up.
    pub up: [f32; 3],
    /// Camera forward.
    pub forward: [f32; 3],
    /// Direction towards the light (object space, unit).
    pub light: [f32; 3],
    /// tan(fov / 2).
    pub tan_half_fov: f32,
    /// World units per object unit.
    pub radius: f32,
    /// 0: sphere, 1: cube.
    pub shape: u32,
    /// Viewport size in pixels.
    pub size: [f32; 2],
    /// Framebuffer position of the viewport's top-left pixel.
    pub frame_offset: [f32; 2],
}

fn normalize(v: [f32; 3]) -> [f32; 3] {
    let l = dot(v, v).sqrt();
    [v[0] / l, v[1] / l, v[2] / l]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

impl SolidView {
    /// Size of [`SolidView::uniform_bytes`].
    pub const UNIFORM_SIZE: usize = 96;

    /// The camera of `orbit` for a `size` viewport at `frame_offset` in the target.
    pub fn new(orbit: &Orbit, size: [f32; 2], frame_offset: [f32; 2]) -> SolidView {
        let (y, p) = (
            orbit.yaw_deg.to_radians(),
            orbit.pitch_deg.clamp(-85.0, 85.0).to_radians(),
        );
        let eye = [
            orbit.distance * p.cos() * y.sin(),
            orbit.distance * p.sin(),
            orbit.distance * p.cos() * y.cos(),
        ];
        let forward = normalize([-eye[0], -eye[1], -eye[2]]);
        let right = normalize(cross(forward, [0.0, 1.0, 0.0]));
        let up = cross(right, forward);
        // A light above-left of the viewer.
        let light = normalize([
            -0.4 * right[0] + 0.7 * up[0] - 0.6 * forward[0],
            -0.4 * right[1] + 0.7 * up[1] - 0.6 * forward[1],
            -0.4 * right[2] + 0.7 * up[2] - 0.6 * forward[2],
        ]);
        SolidView {
            eye,
            right,
            up,
            forward,
            light,
            tan_half_fov: (orbit.fov_deg.to_radians() * 0.5).tan(),
            radius: orbit.radius,
            shape: match orbit.shape {
                Shape::Sphere => 0,
                Shape::Cube => 1,
            },
            size,
            frame_offset,
        }
    }

    /// The uniform block, little-endian, as `struct SolidView` in `shaders/solid.wgsl`:
    /// (eye, shape), (right, tan½fov), (up, radius), (forward, 0), (light, 0),
    /// (frame offset, size).
    pub fn uniform_bytes(&self) -> [u8; Self::UNIFORM_SIZE] {
        let v = |a: [f32; 3], w: f32| [a[0], a[1], a[2], w];
        let rows = [
            v(self.eye, self.shape as f32),
            v(self.right, self.tan_half_fov),
            v(self.up, self.radius),
            v(self.forward, 0.0),
            v(self.light, 0.0),
            [
                self.frame_offset[0],
                self.frame_offset[1],
                self.size[0],
                self.size[1],
            ],
        ];
        let mut out = [0u8; Self::UNIFORM_SIZE];
        for (i, x) in rows.iter().flatten().enumerate() {
            out[i * 4..i * 4 + 4].copy_from_slice(&x.to_le_bytes());
        }
        out
    }
}

/// Distance along the unit ray `d` from `o` to the unit sphere, or −1 when it misses.
#[inline]
pub fn ray_sphere(o: [f32; 3], d: [f32; 3]) -> f32 {
    let b = dot(o, d);
    let c = dot(o, o) - 1.0;
    let disc = b * b - c;
    if disc < 0.0 {
        return -1.0;
    }
    let t = -b - disc.sqrt();
    if t < 0.0 {
        return -1.0;
    }
    t
}

/// Distance along `d` from `o` to the cube `[−1, 1]³` and the entered face's normal, or
/// `(−1, 0)` when it misses (slab method).
#[inline]
pub fn ray_box(o: [f32; 3], d: [f32; 3]) -> ([f32; 3], f32) {
    let mut t_near = -1e30f32;
    let mut t_far = 1e30f32;
    let mut n = [0.0f32; 3];
    for a in 0..3 {
        let inv = 1.0 / d[a];
        let t0 = (-1.0 - o[a]) * inv;
        let t1 = (1.0 - o[a]) * inv;
        let lo = t0.min(t1);
        let hi = t0.max(t1);
        if lo > t_near {
            t_near = lo;
            n = [0.0; 3];
            n[a] = if d[a] > 0.0 { -1.0 } else { 1.0 };
        }
        t_far = t_far.min(hi);
    }
    if t_near > t_far || t_near < 0.0 {
        return ([0.0; 3], -1.0);
    }
    (n, t_near)
}

/// Where the ray through a viewport pixel enters the object (`struct SolidHit` in
/// `shaders/solid_camera.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidHit {
    /// The point (object space).
    pub p: [f32; 3],
    /// The unit normal there.
    pub n: [f32; 3],
    /// The unit ray direction.
    pub d: [f32; 3],
    /// Distance from the eye (−1: the ray misses).
    pub t: f32,
}

/// The ray through viewport pixel centre `pix` (pixels from the viewport's top-left) and where
/// it enters the sphere or cube.
#[inline]
pub fn solid_hit(v: &SolidView, pix: [f32; 2]) -> SolidHit {
    let ndc = [
        pix[0] / v.size[0] * 2.0 - 1.0,
        1.0 - pix[1] / v.size[1] * 2.0,
    ];
    let aspect = v.size[0] / v.size[1];
    let sx = ndc[0] * v.tan_half_fov * aspect;
    let sy = ndc[1] * v.tan_half_fov;
    let d = normalize([
        v.forward[0] + sx * v.right[0] + sy * v.up[0],
        v.forward[1] + sx * v.right[1] + sy * v.up[1],
        v.forward[2] + sx * v.right[2] + sy * v.up[2],
    ]);
    let (n, t) = if v.shape == 0 {
        let t = ray_sphere(v.eye, d);
        let p = [
            v.eye[0] + t * d[0],
            v.eye[1] + t * d[1],
            v.eye[2] + t * d[2],
        ];
        (p, t)
    } else {
        ray_box(v.eye, d)
    };
    if t < 0.0 {
        return SolidHit {
            p: [0.0; 3],
            n: [0.0; 3],
            d,
            t: -1.0,
        };
    }
    SolidHit {
        p: [
            v.eye[0] + t * d[0],
            v.eye[1] + t * d[1],
            v.eye[2] + t * d[2],
        ],
        n: normalize(n),
        d,
        t,
    }
}

/// The light's share of a surface of normal `n`: ambient plus diffuse.
#[inline]
fn lit(rgb: [f32; 3], n: [f32; 3], v: &SolidView) -> [f32; 3] {
    let k = 0.55 + 0.45 * dot(n, v.light).max(0.0);
    [rgb[0] * k, rgb[1] * k, rgb[2] * k]
}

/// The colour of viewport pixel centre `pix` (pixels from the viewport's top-left).
#[inline]
pub fn solid_pixel(
    prep: &Prepared,
    tile: &crate::noise::Tile,
    v: &SolidView,
    pix: [f32; 2],
) -> [f32; 3] {
    let hit = solid_hit(v, pix);
    if hit.t < 0.0 {
        return BACKGROUND;
    }
    // Footprint of the pixel on the surface, in texels (grazing angles widened, capped).
    let cos_i = dot(hit.n, hit.d).abs().max(0.25);
    let footprint = hit.t * (2.0 * v.tan_half_fov / v.size[1]) * v.radius / cos_i;
    let log2_fp = (footprint * prep.inv_scale).log2();
    let world = hit.p.map(|c| c * v.radius);
    lit(shade(prep, tile, world, log2_fp), hit.n, v)
}

/// A raster solid texture as the GPU holds it: `n³` RGBA8 voxels, x fastest, then y, then z
/// (alpha unused). The solid view samples it trilinearly and wraps (the volume tiles).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Voxels {
    /// The side.
    pub n: u32,
    /// `4 n³` bytes.
    pub rgba: Vec<u8>,
}

impl Voxels {
    /// The voxels of an RGB volume (`n³` values in `[0, 1]`, x fastest), clamped and rounded
    /// to 8 bits as a PNG is.
    pub fn from_rgb(n: u32, voxels: &[[f32; 3]]) -> Voxels {
        assert_eq!(voxels.len(), (n as usize).pow(3), "an n³ volume");
        Voxels {
            n,
            rgba: voxels
                .iter()
                .flat_map(|p| {
                    let [r, g, b] = p.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
                    [r, g, b, 255]
                })
                .collect(),
        }
    }
}

/// Size of [`volume_uniform_bytes`] (`struct SolidVolume` in `shaders/solid_volume.wgsl`).
pub const VOLUME_UNIFORM_SIZE: usize = 16;

/// The volume view's uniform: voxels per world unit, then padding.
pub fn volume_uniform_bytes(voxels_per_unit: f32) -> [u8; VOLUME_UNIFORM_SIZE] {
    let mut out = [0u8; VOLUME_UNIFORM_SIZE];
    out[..4].copy_from_slice(&voxels_per_unit.to_le_bytes());
    out
}

/// The voxel at integer coordinates `i`, wrapped into the volume, as the GPU reads an RGBA8
/// texel (`v / 255`).
#[inline]
pub fn volume_voxel(vol: &Voxels, i: [i32; 3]) -> [f32; 3] {
    let n = vol.n as i32;
    let w = i.map(|c| ((c % n) + n) % n);
    let at = 4 * ((w[2] * n + w[1]) * n + w[0]) as usize;
    [0, 1, 2].map(|c| vol.rgba[at + c] as f32 / 255.0)
}

/// Trilinear interpolation at `q` (voxel units; voxel `i` has its centre at `i + 0.5`).
#[inline]
pub fn volume_trilinear(vol: &Voxels, q: [f32; 3]) -> [f32; 3] {
    let f = q.map(|c| c - 0.5);
    let base = f.map(f32::floor);
    let t = [f[0] - base[0], f[1] - base[1], f[2] - base[2]];
    let i = base.map(|c| c as i32);
    let at = |dx: i32, dy: i32, dz: i32| volume_voxel(vol, [i[0] + dx, i[1] + dy, i[2] + dz]);
    let lerp = |a: [f32; 3], b: [f32; 3], t: f32| [0, 1, 2].map(|c| a[c] * (1.0 - t) + b[c] * t);
    let x00 = lerp(at(0, 0, 0), at(1, 0, 0), t[0]);
    let x10 = lerp(at(0, 1, 0), at(1, 1, 0), t[0]);
    let x01 = lerp(at(0, 0, 1), at(1, 0, 1), t[0]);
    let x11 = lerp(at(0, 1, 1), at(1, 1, 1), t[0]);
    let y0 = lerp(x00, x10, t[1]);
    let y1 = lerp(x01, x11, t[1]);
    lerp(y0, y1, t[2])
}

/// The colour of viewport pixel centre `pix` on the sphere or cube cut out of the raster
/// volume `vol`, `voxels_per_unit` voxels per world unit (the volume's scale against the
/// photo's pixels, which are the world's units).
#[inline]
pub fn volume_pixel(vol: &Voxels, voxels_per_unit: f32, v: &SolidView, pix: [f32; 2]) -> [f32; 3] {
    let hit = solid_hit(v, pix);
    if hit.t < 0.0 {
        return BACKGROUND;
    }
    let q = hit.p.map(|c| c * v.radius * voxels_per_unit);
    lit(volume_trilinear(vol, q), hit.n, v)
}

/// Renders the solid view of the raster volume `vol` into a `width × height` image.
pub fn render_solid_volume(
    vol: &Voxels,
    voxels_per_unit: f32,
    orbit: &Orbit,
    width: u32,
    height: u32,
) -> Image {
    let v = SolidView::new(orbit, [width as f32, height as f32], [0.0, 0.0]);
    render_view(width, height, |pix| {
        volume_pixel(vol, voxels_per_unit, &v, pix)
    })
}

/// Renders the solid view of `params` (rendered as a solid texture whatever `params.solid`
/// says) into a `width × height` image.
pub fn render_solid(params: &Params, orbit: &Orbit, width: u32, height: u32) -> Image {
    let mut solid = params.clone();
    solid.solid = true;
    let prep = Prepared::new(&solid);
    let tile = tile_for(&solid);
    let v = SolidView::new(orbit, [width as f32, height as f32], [0.0, 0.0]);
    render_view(width, height, |pix| solid_pixel(&prep, &tile, &v, pix))
}

/// A `width × height` image of `pixel(pixel centre)`, row by row.
fn render_view(width: u32, height: u32, pixel: impl Fn([f32; 2]) -> [f32; 3]) -> Image {
    let mut pixels = Vec::with_capacity(width as usize * height as usize);
    for y in 0..height {
        for x in 0..width {
            pixels.push(pixel([x as f32 + 0.5, y as f32 + 0.5]));
        }
    }
    Image {
        width,
        height,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rays_hit_the_objects_where_expected() {
        let o = [0.0, 0.0, 3.0];
        let d = [0.0, 0.0, -1.0];
        assert!((ray_sphere(o, d) - 2.0).abs() < 1e-6);
        assert_eq!(ray_sphere(o, [0.0, 1.0, 0.0]), -1.0);
        let (n, t) = ray_box(o, d);
        assert!((t - 2.0).abs() < 1e-6);
        assert_eq!(n, [0.0, 0.0, 1.0]);
        assert_eq!(ray_box(o, [0.0, 0.0, 1.0]).1, -1.0);
    }

    #[test]
    fn camera_is_orthonormal_and_looks_at_the_centre() {
        let v = SolidView::new(&Orbit::default(), [300.0, 200.0], [0.0, 0.0]);
        for (a, b) in [(v.right, v.up), (v.up, v.forward), (v.right, v.forward)] {
            assert!(dot(a, b).abs() < 1e-5);
        }
        let to_centre = normalize([-v.eye[0], -v.eye[1], -v.eye[2]]);
        assert!((dot(to_centre, v.forward) - 1.0).abs() < 1e-6);
        assert_eq!(v.uniform_bytes().len(), SolidView::UNIFORM_SIZE);
    }

    fn ramp_volume(n: u32) -> Voxels {
        let voxels: Vec<[f32; 3]> = (0..n.pow(3))
            .map(|i| {
                let (x, y, z) = (i % n, i / n % n, i / (n * n));
                [x, y, z].map(|c| c as f32 / (n - 1) as f32)
            })
            .collect();
        Voxels::from_rgb(n, &voxels)
    }

    /// Trilinear lookups give the voxel at its centre, interpolate between centres, and wrap
    /// across the volume's faces (the last voxel's neighbour is the first).
    #[test]
    fn the_volume_lookup_is_trilinear_and_wraps() {
        let vol = ramp_volume(4);
        let third = 85.0 / 255.0;
        let close = |a: [f32; 3], b: [f32; 3]| (0..3).all(|c| (a[c] - b[c]).abs() < 1e-6);
        assert!(close(
            volume_trilinear(&vol, [1.5, 2.5, 0.5]),
            [third, 2.0 * third, 0.0]
        ));
        assert!(close(
            volume_trilinear(&vol, [2.0, 2.5, 0.5]),
            [1.5 * third, 2.0 * third, 0.0]
        ));
        // Halfway between voxel 3 and voxel 0 (wrapped) along x, and the same a period away.
        let wrap = volume_trilinear(&vol, [4.0, 0.5, 0.5]);
        assert!(close(wrap, [0.5, 0.0, 0.0]), "{wrap:?}");
        assert!(close(volume_trilinear(&vol, [-4.0, 4.5, -3.5]), wrap));
    }

    /// The sphere of a volume shows the volume's colours, lit, on the background.
    #[test]
    fn a_volume_renders_on_the_sphere_and_the_cube() {
        let vol = ramp_volume(8);
        for shape in [Shape::Sphere, Shape::Cube] {
            let orbit = Orbit {
                shape,
                ..Orbit::default()
            };
            let img = render_solid_volume(&vol, 1.0 / 64.0, &orbit, 48, 32);
            assert_eq!(img.pixels[0], BACKGROUND);
            let centre = img.pixels[16 * 48 + 24];
            assert_ne!(centre, BACKGROUND);
            let colours: std::collections::BTreeSet<[u32; 3]> = img
                .pixels
                .iter()
                .map(|p| p.map(|c| (c * 255.0) as u32))
                .collect();
            assert!(colours.len() > 50, "{shape:?}: {} colours", colours.len());
        }
    }
}
