//! The tests/bad corpus and other awkward inputs: a clear error or a correct result, never a
//! panic. See tests/bad/README.md.

mod common;

use proctex::Error;
use proctex::analyze::{Options, analyze_bytes};

#[derive(Debug, PartialEq)]
enum Want {
    Ok,
    Decode,
    TooSmall,
    TooLarge,
    TooLargeOrDecode,
}

fn outcome(bytes: &[u8]) -> Result<(), Error> {
    analyze_bytes(bytes, &Options::default()).map(|_| ())
}

#[test]
fn bad_corpus() {
    let dir = format!("{}/tests/bad", env!("CARGO_MANIFEST_DIR"));
    let expected = [
        ("truncated.png", Want::Decode),
        ("truncated.jpg", Want::Decode),
        ("corrupt_idat.png", Want::Decode),
        ("empty.png", Want::Decode),
        ("text.png", Want::Decode),
        ("1x1.png", Want::TooSmall),
        ("31x31.png", Want::TooSmall),
        ("grey16.png", Want::Ok),
        ("rgb16.png", Want::Ok),
        ("grey_alpha.png", Want::Ok),
        ("huge_declared.png", Want::TooLarge),
        ("huge_declared.jpg", Want::TooLargeOrDecode),
    ];
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name == "README.md" {
            continue;
        }
        let want = &expected
            .iter()
            .find(|(n, _)| *n == name)
            .unwrap_or_else(|| panic!("{name} has no expected outcome in this test"))
            .1;
        let bytes = std::fs::read(&path).unwrap();
        let got = outcome(&bytes);
        let ok = matches!(
            (&got, want),
            (Ok(()), Want::Ok)
                | (Err(Error::Decode(_)), Want::Decode | Want::TooLargeOrDecode)
                | (Err(Error::TooSmall { .. }), Want::TooSmall)
                | (
                    Err(Error::TooLarge(_)),
                    Want::TooLarge | Want::TooLargeOrDecode
                )
        );
        assert!(ok, "{name}: expected {want:?}, got {got:?}");
        if let Err(e) = got {
            let msg = e.to_string();
            assert!(msg.len() > 15 && !msg.contains("panicked"), "{name}: {msg}");
            println!("{name:<20} → {msg}");
        }
        seen += 1;
    }
    assert_eq!(seen, expected.len());
}

#[test]
fn messages_say_what_is_wrong() {
    let dir = format!("{}/tests/bad", env!("CARGO_MANIFEST_DIR"));
    let msg = |f: &str| {
        outcome(&std::fs::read(format!("{dir}/{f}")).unwrap())
            .unwrap_err()
            .to_string()
    };
    assert!(msg("empty.png").contains("empty"));
    assert!(msg("text.png").contains("not a recognised image format"));
    assert!(msg("31x31.png").contains("31×31"));
    assert!(msg("31x31.png").contains("32×32"));
    assert!(msg("huge_declared.png").contains("too large"));
}

#[test]
fn sixteen_bit_keeps_precision() {
    // A 16-bit grey ramp whose steps are finer than 8 bits: the analysis must see distinct
    // values (more than 256 levels).
    let (w, h) = (64u32, 64u32);
    let buf: image::ImageBuffer<image::Luma<u16>, Vec<u16>> =
        image::ImageBuffer::from_fn(w, h, |x, y| image::Luma([(x * 64 + y) as u16 * 7 + 1000]));
    let mut bytes = Vec::new();
    image::DynamicImage::ImageLuma16(buf)
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    let photo = proctex::input::Photo::decode(&bytes).unwrap();
    let mut levels: Vec<u32> = photo
        .pixels
        .iter()
        .map(|p| (p[0] * 65535.0).round() as u32)
        .collect();
    levels.sort();
    levels.dedup();
    assert_eq!(levels.len(), (w * h) as usize);
}

#[test]
fn bad_crops_and_options() {
    let bytes = common::sample_bytes("stk_blackrock_256.png");
    let crop = |x, y, w, h| Options {
        crop: Some(proctex::input::Crop { x, y, w, h }),
        ..Options::default()
    };
    assert!(matches!(
        analyze_bytes(&bytes, &crop(0, 0, 300, 10)),
        Err(Error::Crop(_))
    ));
    assert!(matches!(
        analyze_bytes(&bytes, &crop(10, 10, 20, 200)),
        Err(Error::TooSmall { .. })
    ));
    assert!(analyze_bytes(&bytes, &crop(10, 20, 100, 40)).is_ok());
    let bad_size = Options {
        size: 300,
        ..Options::default()
    };
    assert!(matches!(
        analyze_bytes(&bytes, &bad_size),
        Err(Error::Option(_))
    ));
}

#[test]
fn truncations_of_every_length_never_panic() {
    // Every prefix length of a small PNG and JPEG (a cheap stand-in for fuzzing the decode
    // path end to end).
    let img = image::RgbImage::from_fn(40, 36, |x, y| image::Rgb([x as u8 * 6, y as u8 * 7, 99]));
    for format in [image::ImageFormat::Png, image::ImageFormat::Jpeg] {
        let mut bytes = Vec::new();
        image::DynamicImage::ImageRgb8(img.clone())
            .write_to(&mut std::io::Cursor::new(&mut bytes), format)
            .unwrap();
        for len in 0..bytes.len() {
            let _ = outcome(&bytes[..len]);
        }
        assert!(outcome(&bytes).is_ok());
    }
}

/// Deterministic mutation fuzzing of the whole decode + analyse path: byte flips, inserted and
/// deleted runs, in every format. Nothing may panic; whatever decodes must analyse or fail with
/// a clear error.
#[test]
fn mutated_files_never_panic() {
    let img = image::RgbImage::from_fn(48, 40, |x, y| {
        image::Rgb([(x * 5) as u8, (y * 6) as u8, ((x ^ y) * 3) as u8])
    });
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    for format in [
        image::ImageFormat::Png,
        image::ImageFormat::Jpeg,
        image::ImageFormat::WebP,
        image::ImageFormat::Gif,
        image::ImageFormat::Bmp,
        image::ImageFormat::Tiff,
    ] {
        let mut bytes = Vec::new();
        image::DynamicImage::ImageRgb8(img.clone())
            .write_to(&mut std::io::Cursor::new(&mut bytes), format)
            .unwrap();
        for _ in 0..150 {
            let mut m = bytes.clone();
            let edits = 1 + (common::lcg(&mut state) * 4.0) as usize;
            for _ in 0..edits {
                let at = (common::lcg(&mut state) * m.len() as f64) as usize % m.len();
                match (common::lcg(&mut state) * 3.0) as u32 {
                    0 => m[at] ^= 1 << ((common::lcg(&mut state) * 8.0) as u32),
                    1 => {
                        let end = (at + 1 + (common::lcg(&mut state) * 16.0) as usize).min(m.len());
                        m.drain(at..end);
                        if m.is_empty() {
                            m.push(0);
                        }
                    }
                    _ => m.insert(at, (common::lcg(&mut state) * 256.0) as u8),
                }
            }
            if let Err(e) = outcome(&m) {
                assert!(!e.to_string().is_empty());
            }
        }
    }
}

/// The same for params documents: mutated JSON is rejected with a named field or parses to
/// params that validate.
#[test]
fn mutated_params_never_panic() {
    let text = analyze_bytes(
        &common::sample_bytes("stk_blackrock_256.png"),
        &Options::default(),
    )
    .unwrap()
    .params
    .to_json();
    let bytes = text.as_bytes();
    let mut state = 42u64;
    let junk = [
        b'0', b'9', b'-', b'e', b'.', b'"', b',', b']', b'}', b'[', b'N', b' ',
    ];
    for _ in 0..3000 {
        let mut m = bytes.to_vec();
        let at = (common::lcg(&mut state) * m.len() as f64) as usize % m.len();
        let c = junk[(common::lcg(&mut state) * junk.len() as f64) as usize % junk.len()];
        if common::lcg(&mut state) < 0.5 {
            m[at] = c;
        } else {
            m.insert(at, c);
        }
        let Ok(doc) = String::from_utf8(m) else {
            continue;
        };
        match proctex::params::Params::from_json(&doc) {
            Ok(p) => p.validate().unwrap(),
            Err(Error::Params { field, .. }) => assert!(!field.is_empty()),
            Err(other) => panic!("unexpected error kind {other}"),
        }
    }
}
