//! A set's photos under a lighting ramp, for measuring how much the automatic choice depends
//! on a photo's lighting (docs/devset.md, "The photo's lighting").
//!
//! `cargo run --release -p proctex-analyzer --example lit_set -- SET OUT [LOW HIGH]` multiplies
//! every pixel of each photo of SET's manifest by a factor that runs linearly from LOW at the
//! left edge to HIGH at the right (default 0.75 and 1.25; a lamp to one side of a wall), in
//! 8-bit sRGB values (clipped at 255, as an over-exposed photo is), and writes the photos and
//! the manifest to OUT for `proctex fidelity --set OUT`.

use std::path::Path;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() != 2 && args.len() != 4 {
        eprintln!("usage: lit_set SET OUT [LOW HIGH]");
        std::process::exit(2);
    }
    let (set, out) = (Path::new(&args[0]), Path::new(&args[1]));
    let (low, high): (f64, f64) = if args.len() == 4 {
        (
            args[2].parse().expect("LOW"),
            args[3].parse().expect("HIGH"),
        )
    } else {
        (0.75, 1.25)
    };
    std::fs::create_dir_all(out).expect("OUT");
    let manifest = std::fs::read_to_string(set.join("manifest.tsv")).expect("SET/manifest.tsv");
    std::fs::write(out.join("manifest.tsv"), &manifest).expect("write the manifest");
    let mut written = 0;
    for line in manifest.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let file = line.split('\t').next().unwrap_or_default();
        let mut img = image::open(set.join(file)).expect("a photo").to_rgb8();
        let w = img.width().max(2) - 1;
        for (x, _, p) in img.enumerate_pixels_mut() {
            let gain = low + (high - low) * x as f64 / w as f64;
            p.0 =
                p.0.map(|v| (v as f64 * gain).round_ties_even().clamp(0.0, 255.0) as u8);
        }
        img.save(out.join(file)).expect("write a photo");
        written += 1;
    }
    println!(
        "{written} photos under a ramp of {low}–{high} in {}",
        out.display()
    );
}
