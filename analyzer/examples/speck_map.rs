//! Where an image's specks are (`specks::speck_mask`, the development set's measure): for each
//! image file, its speck fraction and count; with `SPECK_DUMP=1` each speck's position, its
//! 8-bit colour and its 3×3 neighbourhood's median; with `SPECK_MAP=DIR` the image 3× enlarged
//! with its specks painted red, written to DIR under the same name.
//!
//! `cargo run --release -p proctex-analyzer --example speck_map -- IMAGE...`
use proctex::input::Photo;
use proctex::specks::speck_mask;
fn main() {
    let map = std::env::var_os("SPECK_MAP").map(std::path::PathBuf::from);
    for a in std::env::args().skip(1) {
        let p = Photo::decode(&std::fs::read(&a).unwrap()).unwrap();
        let m = speck_mask(&p);
        let n = m.iter().filter(|&&s| s).count();
        println!("{a}\t{:.5}\t{n}", n as f64 / m.len() as f64);
        if std::env::var_os("SPECK_DUMP").is_some() {
            let w = p.width as usize;
            for (i, _) in m.iter().enumerate().filter(|(_, s)| **s) {
                let (x, y) = (i % w, i / w);
                let mut med = [0.0f32; 3];
                for (c, mc) in med.iter_mut().enumerate() {
                    let mut v: Vec<f32> = (0..9)
                        .map(|k| p.pixels[(y + k / 3 - 1) * w + x + k % 3 - 1][c])
                        .collect();
                    v.sort_by(f32::total_cmp);
                    *mc = v[4];
                }
                let q = |v: f32| (v * 255.0).round() as i32;
                println!(
                    "  ({x},{y}) {:?} median {:?}",
                    p.pixels[i].map(q),
                    med.map(q)
                );
                // With `SPECK_DUMP=2` the red channel of the 5×5 neighbourhood too.
                if std::env::var("SPECK_DUMP").as_deref() == Ok("2") {
                    let h = p.height as usize;
                    for yy in y.saturating_sub(2)..(y + 3).min(h) {
                        let row: Vec<i32> = (x.saturating_sub(2)..(x + 3).min(w))
                            .map(|xx| q(p.pixels[yy * w + xx][0]))
                            .collect();
                        println!("      {row:?}");
                    }
                }
            }
        }
        if let Some(dir) = &map {
            let (w, h, z) = (p.width, p.height, 3);
            let mut img = image::RgbImage::new(w * z, h * z);
            for y in 0..h * z {
                for x in 0..w * z {
                    let i = ((y / z) * w + x / z) as usize;
                    let c = if m[i] { [1.0, 0.0, 0.0] } else { p.pixels[i] };
                    img.put_pixel(
                        x,
                        y,
                        image::Rgb(c.map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8)),
                    );
                }
            }
            let name = std::path::Path::new(&a).file_name().unwrap();
            img.save(dir.join(name)).unwrap();
        }
    }
}
