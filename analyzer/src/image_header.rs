//! An image's format and dimensions from the first bytes of its file, without decoding it, so
//! that a photo too large to hold is refused before any pixel memory is taken. The browser's
//! decoder has no such check (a 20000² PNG of 1 MB decodes into 1.6 GB), so the worker asks here
//! first; the CLI's decoder reads the same header itself.
//!
//! Formats: PNG (IHDR), JPEG (the first start-of-frame marker), GIF (logical screen), BMP (info
//! header), WebP (VP8, VP8L, VP8X) and TIFF (recognised by its byte-order mark only: browsers do
//! not decode it).

/// A recognised image container.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG.
    Png,
    /// JPEG (JFIF or Exif).
    Jpeg,
    /// GIF 87a/89a.
    Gif,
    /// Windows bitmap.
    Bmp,
    /// WebP (lossy, lossless or extended).
    Webp,
    /// TIFF (either byte order).
    Tiff,
}

/// What the header says: the format, and the dimensions where the header holds them where we
/// look (`None` for TIFF, and for a file cut short before them).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    /// The container.
    pub format: Format,
    /// Width and height in pixels, as stored (before any EXIF turn, which keeps the area).
    pub size: Option<(u64, u64)>,
}

fn be16(b: &[u8], at: usize) -> Option<u64> {
    Some(u16::from_be_bytes(b.get(at..at + 2)?.try_into().ok()?) as u64)
}
fn le16(b: &[u8], at: usize) -> Option<u64> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?) as u64)
}
fn be32(b: &[u8], at: usize) -> Option<u64> {
    Some(u32::from_be_bytes(b.get(at..at + 4)?.try_into().ok()?) as u64)
}
fn le32(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}
fn le24(b: &[u8], at: usize) -> Option<u64> {
    let s = b.get(at..at + 3)?;
    Some(s[0] as u64 | (s[1] as u64) << 8 | (s[2] as u64) << 16)
}

/// Reads the header of `bytes`; `None` when the format is none of [`Format`]'s.
pub fn read(bytes: &[u8]) -> Option<Header> {
    let (format, size) = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        (Format::Png, be32(bytes, 16).zip(be32(bytes, 20)))
    } else if bytes.starts_with(&[0xff, 0xd8]) {
        (Format::Jpeg, jpeg_size(bytes))
    } else if bytes.starts_with(b"GIF87a") || bytes.starts_with(b"GIF89a") {
        (Format::Gif, le16(bytes, 6).zip(le16(bytes, 8)))
    } else if bytes.starts_with(b"BM") {
        // BITMAPINFOHEADER and later: signed 32-bit width and height (negative height: top-down);
        // the old 12-byte core header: unsigned 16-bit.
        let size = match le32(bytes, 14) {
            Some(12) => le16(bytes, 18).zip(le16(bytes, 20)),
            Some(_) => le32(bytes, 18).zip(le32(bytes, 22)).map(|(w, h)| {
                (
                    (w as i32).unsigned_abs() as u64,
                    (h as i32).unsigned_abs() as u64,
                )
            }),
            None => None,
        };
        (Format::Bmp, size)
    } else if bytes.starts_with(b"RIFF") && bytes.get(8..12) == Some(b"WEBP") {
        let size = match bytes.get(12..16) {
            Some(b"VP8 ") => le16(bytes, 26)
                .zip(le16(bytes, 28))
                .map(|(w, h)| (w & 0x3fff, h & 0x3fff)),
            Some(b"VP8L") => le32(bytes, 21).map(|v| {
                let v = v as u64;
                ((v & 0x3fff) + 1, ((v >> 14) & 0x3fff) + 1)
            }),
            Some(b"VP8X") => le24(bytes, 24)
                .zip(le24(bytes, 27))
                .map(|(w, h)| (w + 1, h + 1)),
            _ => None,
        };
        (Format::Webp, size)
    } else if bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*") {
        (Format::Tiff, None)
    } else {
        return None;
    };
    Some(Header { format, size })
}

/// Width and height from the first start-of-frame marker (SOF0–SOF15 but DHT, JPG and DAC).
fn jpeg_size(b: &[u8]) -> Option<(u64, u64)> {
    let mut at = 2;
    loop {
        // Markers may be preceded by fill bytes 0xff.
        while *b.get(at)? == 0xff && *b.get(at + 1)? == 0xff {
            at += 1;
        }
        if *b.get(at)? != 0xff {
            return None;
        }
        let marker = *b.get(at + 1)?;
        if matches!(marker, 0xd0..=0xd9 | 0x01) {
            at += 2; // stand-alone markers carry no length
            continue;
        }
        let len = be16(b, at + 2)? as usize;
        if (0xc0..=0xcf).contains(&marker) && !matches!(marker, 0xc4 | 0xc8 | 0xcc) {
            let h = be16(b, at + 5)?;
            let w = be16(b, at + 7)?;
            return Some((w, h));
        }
        if len < 2 {
            return None;
        }
        at += 2 + len;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(feature = "decode")]
    fn encoded(format: image::ImageFormat, w: u32, h: u32) -> Vec<u8> {
        let img = image::DynamicImage::ImageRgb8(image::RgbImage::new(w, h));
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, format).unwrap();
        out.into_inner()
    }

    /// Every format the image crate writes reads back the size it was written with.
    #[cfg(feature = "decode")]
    #[test]
    fn sizes_match_what_was_encoded() {
        use image::ImageFormat as F;
        for (f, want) in [
            (F::Png, Format::Png),
            (F::Jpeg, Format::Jpeg),
            (F::Gif, Format::Gif),
            (F::Bmp, Format::Bmp),
            (F::WebP, Format::Webp),
        ] {
            for (w, h) in [(1, 1), (37, 211), (300, 17)] {
                let bytes = encoded(f, w, h);
                let header = read(&bytes).unwrap_or_else(|| panic!("{f:?} not recognised"));
                assert_eq!(header.format, want);
                assert_eq!(header.size, Some((w as u64, h as u64)), "{f:?} {w}×{h}");
            }
        }
        let tiff = encoded(F::Tiff, 8, 8);
        assert_eq!(read(&tiff).unwrap().format, Format::Tiff);
    }

    /// A PNG header that declares 20000² is read as such from 33 bytes: no decode needed.
    #[test]
    fn a_bare_png_header_is_enough() {
        let mut b = b"\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR".to_vec();
        b.extend_from_slice(&20000u32.to_be_bytes());
        b.extend_from_slice(&20000u32.to_be_bytes());
        assert_eq!(read(&b).unwrap().size, Some((20000, 20000)));
    }

    /// Truncated and hostile headers give `None` sizes or no format, never a panic.
    #[test]
    fn short_and_garbage_inputs_do_not_panic() {
        for b in [
            &b""[..],
            b"\xff\xd8",
            b"\xff\xd8\xff",
            b"\xff\xd8\xff\xe0\x00\x00",
            b"\xff\xd8\xff\xff\xff\xff",
            b"RIFF\0\0\0\0WEBPVP8X",
            b"BM\0\0",
            b"GIF89a\x01",
            b"\x89PNG\r\n\x1a\n",
            b"hello",
        ] {
            if let Some(h) = read(b) {
                assert_eq!(h.size, None, "{b:?}");
            }
        }
    }
}
