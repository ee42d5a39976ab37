//! A set's photos degraded as a lamp, a camera and its file format degrade a real photo, for
//! measuring how much the automatic choice depends on that (docs/devset.md, "The photo's
//! lighting" and "The photo's camera").
//!
//! `cargo run --release -p proctex-analyzer --example degraded_set -- SET OUT MODE AMOUNT…`
//! writes each photo of SET's manifest to OUT (as PNG, under its own name, with the manifest)
//! for `proctex fidelity --set OUT`, after one of:
//! - `ramp LOW HIGH`: every pixel multiplied by a factor running linearly from LOW at the left
//!   edge to HIGH at the right, in 8-bit sRGB values (clipped at 255, as an over-exposed photo
//!   is): a lamp to one side of a wall;
//! - `jpeg Q`: encoded as a baseline JPEG at quality Q (1–100) and decoded again: the 8×8
//!   blocks and the chroma subsampling of a camera's or a website's file;
//! - `noise SIGMA`: a Gaussian deviate of SIGMA 8-bit steps added to each channel of each pixel
//!   (a fixed seed: the same set every run), clipped to 0–255: a small sensor's noise;
//! - `blur SIGMA`: a Gaussian blur of SIGMA pixels: a lens out of focus or a shaken hand;
//! - `scale F`: resampled to F times its size (Catmull–Rom, its support widened when F < 1):
//!   the same material photographed from farther away (F < 1) or nearer (F > 1).

use std::path::Path;

use image::{ImageEncoder, RgbImage};

/// SplitMix64: a fixed-seed generator for the noise, so that the set is the same every run.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1].
    fn unit(&mut self) -> f64 {
        ((self.next() >> 11) + 1) as f64 / (1u64 << 53) as f64
    }

    /// A standard normal deviate (Box–Muller).
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.unit(), self.unit());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

fn jpeg(img: &RgbImage, quality: u8) -> RgbImage {
    let mut bytes = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut bytes, quality)
        .write_image(
            img.as_raw(),
            img.width(),
            img.height(),
            image::ExtendedColorType::Rgb8,
        )
        .expect("JPEG encoding");
    image::load_from_memory_with_format(&bytes, image::ImageFormat::Jpeg)
        .expect("JPEG decoding")
        .to_rgb8()
}

fn ramp(mut img: RgbImage, low: f64, high: f64) -> RgbImage {
    let w = img.width().max(2) - 1;
    for (x, _, p) in img.enumerate_pixels_mut() {
        let gain = low + (high - low) * x as f64 / w as f64;
        p.0 =
            p.0.map(|v| (v as f64 * gain).round_ties_even().clamp(0.0, 255.0) as u8);
    }
    img
}

fn noisy(mut img: RgbImage, sigma: f64, rng: &mut SplitMix) -> RgbImage {
    for p in img.pixels_mut() {
        p.0 =
            p.0.map(|v| (v as f64 + sigma * rng.normal()).round().clamp(0.0, 255.0) as u8);
    }
    img
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mode = args.get(2).map_or("", String::as_str);
    let amounts = if mode == "ramp" { 2 } else { 1 };
    if args.len() != 3 + amounts || !matches!(mode, "ramp" | "jpeg" | "noise" | "blur" | "scale") {
        eprintln!(
            "usage: degraded_set SET OUT (ramp LOW HIGH | jpeg Q | noise SIGMA | blur SIGMA \
             | scale F)"
        );
        std::process::exit(2);
    }
    let (set, out) = (Path::new(&args[0]), Path::new(&args[1]));
    let amount: f64 = args[3].parse().expect("AMOUNT");
    std::fs::create_dir_all(out).expect("OUT");
    let manifest = std::fs::read_to_string(set.join("manifest.tsv")).expect("SET/manifest.tsv");
    std::fs::write(out.join("manifest.tsv"), &manifest).expect("write the manifest");
    let mut rng = SplitMix(0x5EED);
    let mut written = 0;
    for line in manifest.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let file = line.split('\t').next().unwrap_or_default();
        let img = image::open(set.join(file)).expect("a photo").to_rgb8();
        let img = match mode {
            "ramp" => ramp(img, amount, args[4].parse().expect("HIGH")),
            "jpeg" => jpeg(&img, amount.clamp(1.0, 100.0) as u8),
            "noise" => noisy(img, amount, &mut rng),
            "scale" => {
                let size = |v: u32| ((v as f64 * amount).round() as u32).max(1);
                let (w, h) = (size(img.width()), size(img.height()));
                image::imageops::resize(&img, w, h, image::imageops::FilterType::CatmullRom)
            }
            _ => image::imageops::blur(&img, amount as f32),
        };
        img.save_with_format(out.join(file), image::ImageFormat::Png)
            .expect("write a photo");
        written += 1;
    }
    let what = args[2..].join(" ");
    println!("{written} photos, {what}, in {}", out.display());
}
