//! Photo input: decoding, EXIF orientation, crop and area-averaged reduction.
//!
//! Pixels stay *display-encoded* (sRGB-ish code values scaled to `[0, 1]`), not linearised: the
//! exported shaders then reproduce the photo's numbers directly.

#[cfg(feature = "decode")]
use std::io::Cursor;

#[cfg(feature = "decode")]
use image::{DynamicImage, ImageDecoder, ImageReader, Limits};

use crate::error::{Error, Result};

/// Smallest accepted side (after crop).
pub const MIN_SIDE: u32 = 32;
pub use crate::limits::{MAX_PIXELS, MAX_SIDE};
/// Bytes the decoder may allocate per allowed pixel (RGBA at 16 bits, the widest layout).
#[cfg(feature = "decode")]
const ALLOC_PER_PIXEL: u64 = 8;

/// An RGB image with `f32` channels in `[0, 1]`, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Photo {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width × height` pixels.
    pub pixels: Vec<[f32; 3]>,
}

/// A crop rectangle in photo pixels (after orientation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Crop {
    /// Left edge.
    pub x: u32,
    /// Top edge.
    pub y: u32,
    /// Width.
    pub w: u32,
    /// Height.
    pub h: u32,
}

impl Crop {
    /// Parses `x,y,w,h`.
    pub fn parse(s: &str) -> Result<Crop> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        if parts.len() != 4 {
            return Err(Error::Crop(format!(
                "expected x,y,w,h (four integers), got `{s}`"
            )));
        }
        let mut v = [0u32; 4];
        for (slot, p) in v.iter_mut().zip(&parts) {
            *slot = p
                .parse()
                .map_err(|_| Error::Crop(format!("`{p}` is not a non-negative integer")))?;
        }
        Ok(Crop {
            x: v[0],
            y: v[1],
            w: v[2],
            h: v[3],
        })
    }
}

#[cfg(feature = "decode")]
fn decode_error(e: image::ImageError) -> Error {
    use image::ImageError as E;
    match e {
        E::Limits(l) => Error::TooLarge(format!(
            "{l} (at most {MAX_SIDE} pixels a side; {})",
            crate::limits::PAST_THE_LIMIT
        )),
        E::Unsupported(u) => Error::Decode(format!("unsupported image: {u}")),
        E::Decoding(d) => Error::Decode(format!("the file is corrupt or truncated ({d})")),
        other => Error::Decode(other.to_string()),
    }
}

impl Photo {
    #[cfg(feature = "decode")]
    /// Decodes PNG, JPEG, WebP, GIF (first frame), BMP or TIFF bytes, 8 or 16 bit, grey, grey +
    /// alpha, RGB or RGBA (alpha ignored), applying the EXIF orientation where there is one.
    pub fn decode(bytes: &[u8]) -> Result<Photo> {
        Photo::decode_limited(bytes, MAX_PIXELS)
    }

    #[cfg(feature = "decode")]
    /// [`Photo::decode`] with a pixel limit other than [`MAX_PIXELS`], checked from the header
    /// before any pixel is decoded.
    pub fn decode_limited(bytes: &[u8], max_pixels: u64) -> Result<Photo> {
        crate::limits::check_file_bytes(bytes.len() as u64)?;
        if bytes.is_empty() {
            return Err(Error::Decode("the file is empty".into()));
        }
        // The header's own dimensions first: the decoder's limit error says neither the size nor
        // the limit.
        if let Some((w, h)) = crate::image_header::read(bytes).and_then(|h| h.size) {
            crate::limits::check_pixels(
                "the photo",
                w,
                h,
                max_pixels,
                crate::limits::PAST_THE_LIMIT,
            )?;
        }
        // The decoders are fuzzed upstream, but a panic on hostile bytes must still become an
        // error here rather than a crash of the CLI or a dead browser tab.
        let decoded = std::panic::catch_unwind(|| -> Result<DynamicImage> {
            let mut reader = ImageReader::new(Cursor::new(bytes))
                .with_guessed_format()
                .map_err(|e| Error::Decode(e.to_string()))?;
            if reader.format().is_none() {
                return Err(Error::Decode(
                    "not a recognised image format (PNG, JPEG, WebP, GIF, BMP or TIFF)".into(),
                ));
            }
            if reader.format() == Some(image::ImageFormat::Jpeg) && !jpeg_is_complete(bytes) {
                return Err(Error::Decode(
                    "the JPEG file is truncated (its last scan has no end-of-image marker)".into(),
                ));
            }
            let mut limits = Limits::default();
            limits.max_image_width = Some(MAX_SIDE);
            limits.max_image_height = Some(MAX_SIDE);
            limits.max_alloc = Some(max_pixels.saturating_mul(ALLOC_PER_PIXEL).max(1 << 26));
            reader.limits(limits);
            let mut decoder = reader.into_decoder().map_err(decode_error)?;
            let (w, h) = decoder.dimensions();
            crate::limits::check_pixels(
                "the photo",
                w as u64,
                h as u64,
                max_pixels,
                crate::limits::PAST_THE_LIMIT,
            )?;
            let orientation = decoder.orientation().map_err(decode_error)?;
            let mut img = DynamicImage::from_decoder(decoder).map_err(decode_error)?;
            img.apply_orientation(orientation);
            Ok(img)
        })
        .map_err(|_| Error::Decode("the decoder failed on this file".into()))??;
        Ok(Photo::from_dynamic(&decoded))
    }

    /// Converts any decoded image; 16-bit values keep their precision.
    #[cfg(feature = "decode")]
    pub fn from_dynamic(img: &DynamicImage) -> Photo {
        let rgb = img.to_rgb32f();
        Photo {
            width: rgb.width(),
            height: rgb.height(),
            pixels: rgb.pixels().map(|p| p.0).collect(),
        }
    }

    /// From interleaved 8-bit RGBA (a canvas or camera frame); alpha is ignored.
    pub fn from_rgba8(width: u32, height: u32, rgba: &[u8]) -> Result<Photo> {
        if rgba.len() != width as usize * height as usize * 4 {
            return Err(Error::Decode(format!(
                "expected {} bytes of RGBA for {width}×{height}, got {}",
                width as usize * height as usize * 4,
                rgba.len()
            )));
        }
        Ok(Photo {
            width,
            height,
            pixels: rgba
                .chunks_exact(4)
                .map(|p| {
                    [
                        p[0] as f32 / 255.0,
                        p[1] as f32 / 255.0,
                        p[2] as f32 / 255.0,
                    ]
                })
                .collect(),
        })
    }

    /// The pixel at `(x, y)`.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[(y * self.width + x) as usize]
    }

    /// The pixels inside `crop`, which must lie inside the photo.
    pub fn crop(&self, crop: Crop) -> Result<Photo> {
        if crop.w == 0 || crop.h == 0 {
            return Err(Error::Crop("width and height must be positive".into()));
        }
        let inside = crop.x.checked_add(crop.w).is_some_and(|r| r <= self.width)
            && crop.y.checked_add(crop.h).is_some_and(|b| b <= self.height);
        if !inside {
            return Err(Error::Crop(format!(
                "{},{},{},{} reaches outside the {}×{} image",
                crop.x, crop.y, crop.w, crop.h, self.width, self.height
            )));
        }
        let mut pixels = Vec::with_capacity(crop.w as usize * crop.h as usize);
        for y in crop.y..crop.y + crop.h {
            let row = (y * self.width) as usize;
            pixels.extend_from_slice(
                &self.pixels[row + crop.x as usize..row + (crop.x + crop.w) as usize],
            );
        }
        Ok(Photo {
            width: crop.w,
            height: crop.h,
            pixels,
        })
    }

    /// Fails with a clear message when a side is below [`MIN_SIDE`].
    pub fn check_min_size(&self) -> Result<()> {
        if self.width < MIN_SIDE || self.height < MIN_SIDE {
            return Err(Error::TooSmall {
                width: self.width,
                height: self.height,
                min: MIN_SIDE,
            });
        }
        Ok(())
    }

    /// Area-averages the photo so that its longer side is at most `max_side`; the aspect ratio is
    /// kept (each output pixel is the exact coverage-weighted mean of the source pixels under it).
    /// Returns the photo unchanged when it is small enough.
    pub fn reduce_to(&self, max_side: u32) -> Photo {
        self.reduced(max_side).unwrap_or_else(|| self.clone())
    }

    /// [`Photo::reduce_to`] without the copy: `None` when no reduction is needed.
    pub fn reduced(&self, max_side: u32) -> Option<Photo> {
        let long = self.width.max(self.height);
        if long <= max_side {
            return None;
        }
        let s = max_side as f64 / long as f64;
        let w = ((self.width as f64 * s).round() as u32).max(1);
        let h = ((self.height as f64 * s).round() as u32).max(1);
        Some(self.resample_box(w, h))
    }

    /// Box (area-coverage) resampling to `w × h`, separable.
    pub fn resample_box(&self, w: u32, h: u32) -> Photo {
        let xw = box_weights(self.width, w);
        let yw = box_weights(self.height, h);
        // Horizontal pass: height × w.
        let mut tmp = vec![[0.0f32; 3]; (self.height * w) as usize];
        for y in 0..self.height as usize {
            let src = &self.pixels[y * self.width as usize..(y + 1) * self.width as usize];
            for (x, taps) in xw.iter().enumerate() {
                let mut acc = [0.0f64; 3];
                for &(i, wt) in taps {
                    for c in 0..3 {
                        acc[c] += src[i][c] as f64 * wt;
                    }
                }
                tmp[y * w as usize + x] = acc.map(|v| v as f32);
            }
        }
        let mut pixels = vec![[0.0f32; 3]; (w * h) as usize];
        for (y, taps) in yw.iter().enumerate() {
            for x in 0..w as usize {
                let mut acc = [0.0f64; 3];
                for &(i, wt) in taps {
                    let p = tmp[i * w as usize + x];
                    for c in 0..3 {
                        acc[c] += p[c] as f64 * wt;
                    }
                }
                pixels[y * w as usize + x] = acc.map(|v| v as f32);
            }
        }
        Photo {
            width: w,
            height: h,
            pixels,
        }
    }
}

/// Whether the last scan (SOS, `FF DA`) of a JPEG is followed by an end-of-image marker
/// (`FF D9`). The JPEG decoder is lenient and fills a cut-off file with grey, which would be
/// analysed as if it were texture; a browser shows such a file half grey too.
#[cfg(feature = "decode")]
fn jpeg_is_complete(bytes: &[u8]) -> bool {
    let last = |m: u8| bytes.windows(2).rposition(|w| w == [0xff, m]);
    match (last(0xda), last(0xd9)) {
        (Some(sos), Some(eoi)) => eoi > sos,
        _ => false,
    }
}

/// For each output sample, the source samples it covers and their normalised coverage.
fn box_weights(src: u32, dst: u32) -> Vec<Vec<(usize, f64)>> {
    let ratio = src as f64 / dst as f64;
    (0..dst)
        .map(|o| {
            let a = o as f64 * ratio;
            let b = (o + 1) as f64 * ratio;
            let mut taps = Vec::new();
            let mut i = a.floor() as usize;
            while (i as f64) < b && i < src as usize {
                let lo = (i as f64).max(a);
                let hi = ((i + 1) as f64).min(b);
                if hi > lo {
                    taps.push((i, (hi - lo) / ratio));
                }
                i += 1;
            }
            taps
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(w: u32, h: u32) -> Photo {
        Photo {
            width: w,
            height: h,
            pixels: (0..w * h)
                .map(|i| {
                    let (x, y) = (i % w, i / w);
                    [x as f32 / w as f32, y as f32 / h as f32, 0.5]
                })
                .collect(),
        }
    }

    #[test]
    fn box_reduction_preserves_mean_and_aspect() {
        let p = ramp(1000, 600);
        let r = p.reduce_to(512);
        assert_eq!((r.width, r.height), (512, 307));
        let mean = |ph: &Photo| {
            ph.pixels.iter().map(|v| v[0] as f64).sum::<f64>() / ph.pixels.len() as f64
        };
        assert!((mean(&p) - mean(&r)).abs() < 1e-3);
        assert_eq!(ramp(300, 200).reduce_to(512), ramp(300, 200));
    }

    #[test]
    fn crop_checks_bounds() {
        let p = ramp(64, 48);
        assert!(
            p.crop(Crop {
                x: 10,
                y: 10,
                w: 54,
                h: 38
            })
            .is_ok()
        );
        assert!(
            p.crop(Crop {
                x: 10,
                y: 10,
                w: 55,
                h: 38
            })
            .is_err()
        );
        assert!(
            p.crop(Crop {
                x: u32::MAX,
                y: 0,
                w: 2,
                h: 2
            })
            .is_err()
        );
        assert!(
            p.crop(Crop {
                x: 0,
                y: 0,
                w: 0,
                h: 2
            })
            .is_err()
        );
        let c = p
            .crop(Crop {
                x: 3,
                y: 5,
                w: 4,
                h: 2,
            })
            .unwrap();
        assert_eq!(c.get(0, 0), p.get(3, 5));
        assert_eq!(c.get(3, 1), p.get(6, 6));
        assert!(Crop::parse("1,2,3").is_err());
        assert!(Crop::parse("1,2,3,-4").is_err());
        assert_eq!(
            Crop::parse("1, 2,3,4").unwrap(),
            Crop {
                x: 1,
                y: 2,
                w: 3,
                h: 4
            }
        );
    }
}
