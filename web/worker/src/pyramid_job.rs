//! The Heeger–Bergen raster synthesis of the current photo (or crop) in the worker, one round
//! at a time ([`proctex::heeger_bergen::Synthesis`]), so that the worker can report progress
//! and see Cancel between rounds. The crop is reduced to the analysis size first, as the
//! analysis reduces it, and synthesised at that size: a tile of the crop's extent.
//!
//! The solid texture of the crop ([`SolidJob`], Heeger & Bergen §4) runs the same way.

use proctex::analyze::Options;
use proctex::heeger_bergen::solid::{SolidOptions, SolidSynthesis};
use proctex::heeger_bergen::{MAX_SYNTHESIS_PIXELS, RasterOptions, Synthesis};
use proctex::render::Image;
use proctex::solid::Voxels;

use crate::jobs::{PAST_THE_LIMIT_IN_THE_PAGE, region};

/// A synthesis in progress.
#[derive(Clone, Debug)]
pub struct PyramidJob {
    synthesis: Synthesis,
    size: (u32, u32),
}

impl PyramidJob {
    /// Starts the synthesis of `crop` (photo pixels; `None`: all) of an RGBA image, with the
    /// paper's defaults and `seed`.
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Option<[u32; 4]>,
        seed: u32,
    ) -> proctex::error::Result<PyramidJob> {
        let photo = region(rgba, width, height, crop)?.reduce_to(Options::default().size);
        let opts = RasterOptions {
            seed,
            ..RasterOptions::new(photo.width, photo.height)
        };
        let limit = (MAX_SYNTHESIS_PIXELS, PAST_THE_LIMIT_IN_THE_PAGE);
        Ok(PyramidJob {
            synthesis: Synthesis::new(&photo, &opts, limit)?,
            size: (photo.width, photo.height),
        })
    }

    /// Starts the texture mixture `m` of the way from the synthesis of `crop` of the RGBA image
    /// to the synthesis of a second RGBA image `b` (`b_width × b_height`), at the crop's
    /// reduced size; `b` is reduced to the analysis size as the crop is.
    #[allow(clippy::too_many_arguments)]
    pub fn mixture(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Option<[u32; 4]>,
        seed: u32,
        b: &[u8],
        (b_width, b_height): (u32, u32),
        m: f32,
    ) -> proctex::error::Result<PyramidJob> {
        let size = Options::default().size;
        let photo = region(rgba, width, height, crop)?.reduce_to(size);
        let other = region(b, b_width, b_height, None)?.reduce_to(size);
        let opts = RasterOptions {
            seed,
            ..RasterOptions::new(photo.width, photo.height)
        };
        let limit = (MAX_SYNTHESIS_PIXELS, PAST_THE_LIMIT_IN_THE_PAGE);
        Ok(PyramidJob {
            synthesis: Synthesis::mixture(&photo, &other, m, &opts, limit)?,
            size: (photo.width, photo.height),
        })
    }

    /// Rounds done and in all.
    pub fn progress(&self) -> (usize, usize) {
        (self.synthesis.done(), self.synthesis.steps())
    }

    /// Runs the next round; returns whether any remain.
    pub fn step(&mut self) -> bool {
        self.synthesis.step()
    }

    /// The synthesis' size (the reduced crop's).
    pub fn size(&self) -> (u32, u32) {
        self.size
    }

    /// The texture as it stands, RGBA8.
    pub fn rgba(&self) -> Vec<u8> {
        let p = self.synthesis.photo();
        Image {
            width: p.width,
            height: p.height,
            pixels: p.pixels,
        }
        .to_rgb8()
        .chunks_exact(3)
        .flat_map(|c| [c[0], c[1], c[2], 255])
        .collect()
    }
}

/// A solid texture of the crop in progress, for the sphere and cube views.
///
/// The crop is reduced so that its longer side is twice the volume's: a slice of the volume then
/// spans half the crop, and a voxel stands for `crop / (2n)` photo pixels, so the sphere shows
/// the volume at the photo's scale (as the procedural solid is shown). Synthesising from the
/// crop at the analysis size instead would make a voxel a 512-px analysis pixel and the volume a
/// small tile repeated many times over the sphere; the volume's side, not the sample's, bounds
/// what it can hold (its pyramid has at most `max_scales(n)` scales).
#[derive(Clone, Debug)]
pub struct SolidJob {
    synthesis: SolidSynthesis,
    voxels_per_unit: f32,
}

impl SolidJob {
    /// Starts the `n³` solid texture of `crop` (photo pixels; `None`: all) of an RGBA image,
    /// with the paper's defaults and `seed`.
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Option<[u32; 4]>,
        seed: u32,
        n: u32,
    ) -> proctex::error::Result<SolidJob> {
        let region = region(rgba, width, height, crop)?;
        let sample = region.reduce_to(2 * n);
        let opts = SolidOptions {
            n,
            seed,
            ..SolidOptions::default()
        };
        Ok(SolidJob {
            synthesis: SolidSynthesis::new(&sample, &opts)?,
            voxels_per_unit: sample.width as f32 / region.width as f32,
        })
    }

    /// Rounds done and in all.
    pub fn progress(&self) -> (usize, usize) {
        (self.synthesis.done(), self.synthesis.steps())
    }

    /// Runs the next round; returns whether any remain.
    pub fn step(&mut self) -> bool {
        self.synthesis.step()
    }

    /// The volume's side.
    pub fn side(&self) -> u32 {
        self.synthesis.side()
    }

    /// Voxels per photo pixel of the crop (world units).
    pub fn voxels_per_unit(&self) -> f32 {
        self.voxels_per_unit
    }

    /// The volume as it stands, RGBA8 voxels (x fastest, then y, then z).
    pub fn rgba(&self) -> Vec<u8> {
        let v = self.synthesis.volume();
        Voxels::from_rgb(v.n, &v.voxels).rgba
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn checker(w: u32, h: u32) -> Vec<u8> {
        (0..w * h)
            .flat_map(|i| {
                let (x, y) = (i % w, i / w);
                let v = if (x / 6 + y / 9) % 2 == 0 { 200 } else { 40 };
                [v, v / 2 + (x % 7) as u8, 90, 255]
            })
            .collect()
    }

    /// The job synthesises the reduced crop in 3 × 5 rounds, to a texture of its size that is
    /// not flat; a bad crop and a too small crop are refused in words.
    #[test]
    fn synthesises_the_reduced_crop_in_rounds() {
        let rgba = checker(1200, 300);
        let mut job = PyramidJob::new(&rgba, 1200, 300, Some([100, 0, 1024, 256]), 1).unwrap();
        assert_eq!(job.size(), (512, 128));
        assert_eq!(job.progress(), (0, 15));
        let mut steps = 1;
        while job.step() {
            steps += 1;
        }
        assert_eq!((steps, job.progress()), (15, (15, 15)));
        let out = job.rgba();
        assert_eq!(out.len(), 512 * 128 * 4);
        let colours: std::collections::BTreeSet<[u8; 3]> =
            out.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect();
        assert!(colours.len() > 20, "{} distinct colours", colours.len());
        let e = PyramidJob::new(&rgba, 1200, 300, Some([1100, 0, 200, 200]), 1).unwrap_err();
        assert!(e.to_string().contains("reaches outside"), "{e}");
        let e = PyramidJob::new(&rgba, 1200, 300, Some([0, 0, 20, 20]), 1).unwrap_err();
        assert!(e.to_string().contains("at least 32"), "{e}");
    }

    fn finished(mut job: PyramidJob) -> Vec<u8> {
        while job.step() {}
        job.rgba()
    }

    /// A mixture at 0 is the crop's own synthesis, at 1 the other image's (at the crop's size).
    #[test]
    fn a_mixture_runs_between_the_two_syntheses() {
        let (a, b) = (
            checker(96, 96),
            checker(64, 80).iter().map(|v| 255 - v).collect::<Vec<u8>>(),
        );
        let crop = Some([0, 0, 64, 64]);
        let mix = |m| finished(PyramidJob::mixture(&a, 96, 96, crop, 1, &b, (64, 80), m).unwrap());
        assert_eq!(
            mix(0.0),
            finished(PyramidJob::new(&a, 96, 96, crop, 1).unwrap())
        );
        let halfway = mix(0.5);
        assert_ne!(halfway, mix(0.0));
        assert_ne!(halfway, mix(1.0));
        let e = PyramidJob::mixture(&a, 96, 96, crop, 1, &b, (64, 79), 0.5).unwrap_err();
        assert!(e.to_string().contains("bytes of RGBA"), "{e}");
    }

    /// The solid job reduces the crop to twice the volume's side, says how many voxels a photo
    /// pixel is, and makes an n³ volume of the crop's colours in 3 × 5 rounds.
    #[test]
    fn the_solid_job_makes_a_volume_at_the_crops_scale() {
        let rgba = checker(1200, 300);
        let mut job = SolidJob::new(&rgba, 1200, 300, Some([100, 0, 256, 256]), 1, 16).unwrap();
        assert_eq!((job.side(), job.progress()), (16, (0, 15)));
        assert_eq!(job.voxels_per_unit(), 32.0 / 256.0);
        while job.step() {}
        let out = job.rgba();
        assert_eq!(out.len(), 16 * 16 * 16 * 4);
        let colours: std::collections::BTreeSet<[u8; 3]> =
            out.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect();
        assert!(colours.len() > 20, "{} distinct colours", colours.len());
        assert!(out.chunks_exact(4).all(|p| p[3] == 255));
        let e = SolidJob::new(&rgba, 1200, 300, Some([0, 0, 256, 256]), 1, 200).unwrap_err();
        assert!(e.to_string().contains("--solid 200"), "{e}");
    }
}
