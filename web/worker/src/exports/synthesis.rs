//! The worker's exports for the raster syntheses (Heeger & Bergen's pyramid, in 2D and as a
//! solid) and their benchmark: the pyramid jobs run in rounds, as the suggestion jobs do.

use wasm_bindgen::prelude::*;

use super::{js_error, parse_crop};

/// Worker job: the Heeger–Bergen raster synthesis of a photo (or crop) in rounds (see
/// `pyramid_job::PyramidJob`): `new` prepares, each `step` runs one round, `rgba` is the
/// texture.
#[wasm_bindgen]
#[derive(Debug)]
pub struct PyramidSynthesis {
    job: crate::pyramid_job::PyramidJob,
}

#[wasm_bindgen]
impl PyramidSynthesis {
    /// Prepares the synthesis of `crop` (`[x, y, w, h]` or empty) of an RGBA image; throws the
    /// error's message (bad crop, too small).
    #[wasm_bindgen(constructor)]
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Vec<u32>,
        seed: u32,
    ) -> Result<PyramidSynthesis, JsValue> {
        let job =
            crate::pyramid_job::PyramidJob::new(rgba, width, height, parse_crop(&crop)?, seed)
                .map_err(js_error)?;
        Ok(PyramidSynthesis { job })
    }

    /// Prepares the texture mixture `m` of the way from the synthesis of `crop` of the RGBA
    /// image to that of a second RGBA image `b` (`b_width × b_height`); throws the error's
    /// message.
    #[allow(clippy::too_many_arguments)]
    pub fn mixture(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Vec<u32>,
        seed: u32,
        b: &[u8],
        b_width: u32,
        b_height: u32,
        m: f32,
    ) -> Result<PyramidSynthesis, JsValue> {
        let job = crate::pyramid_job::PyramidJob::mixture(
            rgba,
            width,
            height,
            parse_crop(&crop)?,
            seed,
            b,
            (b_width, b_height),
            m,
        )
        .map_err(js_error)?;
        Ok(PyramidSynthesis { job })
    }

    /// Rounds done.
    pub fn done(&self) -> usize {
        self.job.progress().0
    }

    /// Rounds in all.
    pub fn steps(&self) -> usize {
        self.job.progress().1
    }

    /// Runs the next round; returns whether any remain.
    pub fn step(&mut self) -> bool {
        self.job.step()
    }

    /// Width and height of the texture.
    pub fn size(&self) -> Vec<u32> {
        let (w, h) = self.job.size();
        vec![w, h]
    }

    /// The texture as it stands, RGBA8.
    pub fn rgba(&self) -> Vec<u8> {
        self.job.rgba()
    }
}

/// Worker job: the Heeger–Bergen solid texture of a photo (or crop) in rounds (see
/// `pyramid_job::SolidJob`), for the sphere and cube views.
#[wasm_bindgen]
#[derive(Debug)]
pub struct SolidSynthesis {
    job: crate::pyramid_job::SolidJob,
}

#[wasm_bindgen]
impl SolidSynthesis {
    /// Prepares the `n³` solid texture of `crop` (`[x, y, w, h]` or empty) of an RGBA image;
    /// throws the error's message (bad crop, too small, side out of range).
    #[wasm_bindgen(constructor)]
    pub fn new(
        rgba: &[u8],
        width: u32,
        height: u32,
        crop: Vec<u32>,
        seed: u32,
        n: u32,
    ) -> Result<SolidSynthesis, JsValue> {
        let job =
            crate::pyramid_job::SolidJob::new(rgba, width, height, parse_crop(&crop)?, seed, n)
                .map_err(js_error)?;
        Ok(SolidSynthesis { job })
    }

    /// Rounds done.
    pub fn done(&self) -> usize {
        self.job.progress().0
    }

    /// Rounds in all.
    pub fn steps(&self) -> usize {
        self.job.progress().1
    }

    /// Runs the next round; returns whether any remain.
    pub fn step(&mut self) -> bool {
        self.job.step()
    }

    /// The volume's side.
    pub fn side(&self) -> u32 {
        self.job.side()
    }

    /// Voxels per photo pixel of the crop.
    #[wasm_bindgen(js_name = voxelsPerUnit)]
    pub fn voxels_per_unit(&self) -> f32 {
        self.job.voxels_per_unit()
    }

    /// The volume as it stands, RGBA8 voxels (x fastest, then y, then z).
    pub fn rgba(&self) -> Vec<u8> {
        self.job.rgba()
    }
}

/// Benchmark job (e2e/bench; the JS side times each call): the Heeger–Bergen synthesis of an
/// RGBA image at its own size with the paper's defaults (`stage` `"synthesis"`), or the 2D
/// FFTs that synthesis runs, as plain transforms one after another (`"ffts"`, the cost floor),
/// or a 64³ solid texture from the image (`"solid"`, Heeger & Bergen §4). Returns a checksum.
#[wasm_bindgen(js_name = benchPyramid)]
pub fn bench_pyramid(rgba: &[u8], width: u32, height: u32, stage: &str) -> Result<f64, JsValue> {
    use proctex::heeger_bergen::{RasterOptions, synthesize, transforms};
    let photo = proctex::input::Photo::from_rgba8(width, height, rgba).map_err(js_error)?;
    let opts = RasterOptions::new(width, height);
    match stage {
        "synthesis" => {
            let out = synthesize(&photo, &opts).map_err(js_error)?;
            Ok(out.pixels.iter().map(|p| p[0] as f64).sum())
        }
        "ffts" => {
            let mut sum = 0.0;
            for (w, h) in transforms((width as usize, height as usize), &opts) {
                let image = vec![1.0f32; w * h];
                sum += proctex::spectrum::fft2_real(&image, w, h)[0].re as f64;
            }
            Ok(sum)
        }
        "solid" => {
            use proctex::heeger_bergen::solid::{SolidOptions, synthesize_solid};
            let v = synthesize_solid(&photo, &SolidOptions::default(), &|_, _| true)
                .map_err(js_error)?
                .expect("never cancelled");
            Ok(v.voxels.iter().map(|p| p[0] as f64).sum())
        }
        _ => Err(JsValue::from_str("stage must be synthesis, ffts or solid")),
    }
}
