//! Input formats and EXIF orientation.

mod common;

use proctex::input::Photo;

fn test_image() -> image::RgbImage {
    // Left half red, right half blue, a green top row: orientation is visible.
    image::RgbImage::from_fn(64, 40, |x, y| {
        if y == 0 {
            image::Rgb([0, 255, 0])
        } else if x < 32 {
            image::Rgb([255, 0, 0])
        } else {
            image::Rgb([0, 0, 255])
        }
    })
}

fn encode(img: &image::DynamicImage, format: image::ImageFormat) -> Vec<u8> {
    let mut bytes = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut bytes), format)
        .unwrap();
    bytes
}

#[test]
fn every_format_decodes_to_the_same_pixels() {
    let img = image::DynamicImage::ImageRgb8(test_image());
    for format in [
        image::ImageFormat::Png,
        image::ImageFormat::Jpeg,
        image::ImageFormat::WebP,
        image::ImageFormat::Gif,
        image::ImageFormat::Bmp,
        image::ImageFormat::Tiff,
    ] {
        let photo =
            Photo::decode(&encode(&img, format)).unwrap_or_else(|e| panic!("{format:?}: {e}"));
        assert_eq!((photo.width, photo.height), (64, 40), "{format:?}");
        let lossy = format == image::ImageFormat::Jpeg;
        let tol = if lossy { 0.1 } else { 1e-6 };
        let left = photo.get(10, 20);
        let right = photo.get(50, 20);
        assert!(
            (left[0] - 1.0).abs() < tol && left[2] < tol,
            "{format:?} {left:?}"
        );
        assert!(
            (right[2] - 1.0).abs() < tol && right[0] < tol,
            "{format:?} {right:?}"
        );
    }
    // Grey, grey + alpha, RGBA, 16-bit RGBA.
    let rgba = image::DynamicImage::ImageRgb8(test_image()).to_rgba8();
    for dynamic in [
        image::DynamicImage::ImageLuma8(image::DynamicImage::ImageRgb8(test_image()).to_luma8()),
        image::DynamicImage::ImageLumaA8(
            image::DynamicImage::ImageRgb8(test_image()).to_luma_alpha8(),
        ),
        image::DynamicImage::ImageRgba8(rgba.clone()),
        image::DynamicImage::ImageRgba16(image::DynamicImage::ImageRgba8(rgba).to_rgba16()),
    ] {
        let photo = Photo::decode(&encode(&dynamic, image::ImageFormat::Png)).unwrap();
        assert_eq!((photo.width, photo.height), (64, 40));
    }
}

#[test]
fn gif_first_frame() {
    use image::codecs::gif::GifEncoder;
    let mut bytes = Vec::new();
    {
        let mut enc = GifEncoder::new(&mut bytes);
        let red = image::RgbaImage::from_pixel(40, 40, image::Rgba([255, 0, 0, 255]));
        let blue = image::RgbaImage::from_pixel(40, 40, image::Rgba([0, 0, 255, 255]));
        enc.encode_frames([image::Frame::new(red), image::Frame::new(blue)])
            .unwrap();
    }
    let p = Photo::decode(&bytes).unwrap();
    assert!(p.get(5, 5)[0] > 0.9 && p.get(5, 5)[2] < 0.1);
}

/// A JPEG with an EXIF APP1 segment carrying `orientation`.
fn jpeg_with_orientation(orientation: u16) -> Vec<u8> {
    let jpeg = encode(
        &image::DynamicImage::ImageRgb8(test_image()),
        image::ImageFormat::Jpeg,
    );
    let mut tiff = Vec::new();
    tiff.extend_from_slice(b"MM\0\x2a\0\0\0\x08"); // big-endian TIFF, IFD at 8
    tiff.extend_from_slice(&1u16.to_be_bytes()); // one entry
    tiff.extend_from_slice(&0x0112u16.to_be_bytes()); // Orientation
    tiff.extend_from_slice(&3u16.to_be_bytes()); // SHORT
    tiff.extend_from_slice(&1u32.to_be_bytes()); // count
    tiff.extend_from_slice(&orientation.to_be_bytes());
    tiff.extend_from_slice(&[0, 0]);
    tiff.extend_from_slice(&0u32.to_be_bytes()); // no next IFD
    let mut app1 = b"Exif\0\0".to_vec();
    app1.extend_from_slice(&tiff);
    let mut out = jpeg[..2].to_vec(); // SOI
    out.extend_from_slice(&[0xff, 0xe1]);
    out.extend_from_slice(&((app1.len() + 2) as u16).to_be_bytes());
    out.extend_from_slice(&app1);
    out.extend_from_slice(&jpeg[2..]);
    out
}

#[test]
fn exif_orientation_is_applied() {
    let plain = Photo::decode(&jpeg_with_orientation(1)).unwrap();
    assert_eq!((plain.width, plain.height), (64, 40));
    // 6: the stored image must be rotated 90° clockwise to display.
    let rotated = Photo::decode(&jpeg_with_orientation(6)).unwrap();
    assert_eq!((rotated.width, rotated.height), (40, 64));
    // After a clockwise turn the green top row is the right column, red (left) is on top.
    let top = rotated.get(20, 10);
    let bottom = rotated.get(20, 54);
    let right_col = rotated.get(39, 32);
    assert!(top[0] > 0.8 && top[2] < 0.2, "{top:?}");
    assert!(bottom[2] > 0.8 && bottom[0] < 0.2, "{bottom:?}");
    assert!(right_col[1] > 0.6, "{right_col:?}");
    // 3: upside down.
    let flipped = Photo::decode(&jpeg_with_orientation(3)).unwrap();
    assert_eq!((flipped.width, flipped.height), (64, 40));
    assert!(flipped.get(10, 20)[2] > 0.8);
}

#[test]
fn large_photos_are_area_averaged_to_the_analysis_size() {
    let big = image::RgbImage::from_fn(1500, 900, |x, y| {
        image::Rgb([
            ((x * 7 + y * 3) % 256) as u8,
            (x % 256) as u8,
            (y % 256) as u8,
        ])
    });
    let bytes = encode(
        &image::DynamicImage::ImageRgb8(big),
        image::ImageFormat::Png,
    );
    for (size, w, h) in [
        (256, 256, 154),
        (512, 512, 307),
        (1024, 1024, 614),
        (2048, 1500, 900),
    ] {
        let a = proctex::analyze::analyze_bytes(
            &bytes,
            &proctex::analyze::Options {
                size,
                ..Default::default()
            },
        )
        .unwrap();
        let s = a.params.source.unwrap();
        assert_eq!((s.analysis_width, s.analysis_height), (w, h), "size {size}");
        assert!((a.params.transform.scale - 1500.0 / w as f32).abs() < 1e-4);
    }
}
