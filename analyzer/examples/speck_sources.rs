//! Where a structured model's specks come from: the speck fraction
//! (`specks::speck_fraction`) of one fitted family on one photo quadrant, rendered whole and
//! with one part taken out at a time.
//!
//! `cargo run --release -p proctex-analyzer --example speck_sources -- PHOTO FAMILY [QX QY]`
use proctex::analyze::Options;
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::{Crop, Photo};
use proctex::params::Model;
use proctex::pattern::PatternKind;
use proctex::retrieve::{ModelChoice, Refinement, analyze_photo_model};
use proctex::specks::speck_fraction;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let photo = Photo::decode(&std::fs::read(&args[1]).unwrap()).unwrap();
    let kind = PatternKind::from_name(&args[2]).expect("a family name");
    let q = |i: usize| args.get(i).map_or(0, |s| s.parse::<u32>().unwrap());
    let (w, h) = (photo.width / 2, photo.height / 2);
    let patch = photo
        .crop(Crop {
            x: q(3) * w,
            y: q(4) * h,
            w,
            h,
        })
        .unwrap();
    let o = Options::default();
    let (a, _) =
        analyze_photo_model(&patch, &o, ModelChoice::Kind(kind), Refinement::default()).unwrap();
    let full = a.params.clone();
    let variant = |f: &dyn Fn(&mut proctex::params::StructuredModel)| {
        let mut p = full.clone();
        if let Model::Structured(m) = &mut p.model {
            f(m);
        }
        speck_fraction(&render_params_at_photo_size(&p, &patch))
    };
    println!("photo                  {:.4}", speck_fraction(&patch));
    println!("model                  {:.4}", variant(&|_| {}));
    println!("no tone curve          {:.4}", variant(&|m| m.tone = None));
    println!(
        "no residual histogram  {:.4}",
        variant(&|m| m.residual.histogram.enabled = false)
    );
    println!(
        "no residual            {:.4}",
        variant(&|m| {
            m.residual.weights.iter_mut().for_each(|w| w.fill(0.0));
            m.residual.fine = [0.0; 3];
        })
    );
    // The residual without its finest band's part after the histogram, and without its `n`
    // finest bands altogether (that part included).
    let without_finest = |n: usize| {
        variant(&|m| {
            m.residual.fine = [0.0; 3];
            for w in &mut m.residual.weights {
                w.iter_mut().take(n).for_each(|v| *v = 0.0);
            }
        })
    };
    println!(
        "no finest band after the histogram {:.4}",
        without_finest(0)
    );
    println!("no finest band at all  {:.4}", without_finest(1));
    println!("no two finest bands    {:.4}", without_finest(2));
    println!(
        "ramp alone (no residual, no tone) {:.4}",
        variant(&|m| {
            m.residual.weights.iter_mut().for_each(|w| w.fill(0.0));
            m.residual.fine = [0.0; 3];
            m.tone = None;
        })
    );
    if let Some(out) = std::env::var_os("SPECK_PNG") {
        // The ramp-alone render, 4× enlarged, beside the full model's.
        let mut p = full.clone();
        if let Model::Structured(m) = &mut p.model {
            m.residual.weights.iter_mut().for_each(|w| w.fill(0.0));
            m.residual.fine = [0.0; 3];
            m.tone = None;
        }
        let a = render_params_at_photo_size(&p, &patch);
        let b = render_params_at_photo_size(&full, &patch);
        let (w, h) = (patch.width, patch.height);
        let z = 3;
        let mut img = image::RgbImage::new(3 * w * z, h * z);
        for (k, im) in [&patch, &b, &a].into_iter().enumerate() {
            for y in 0..h * z {
                for x in 0..w * z {
                    let c = im.pixels[((y / z) * w + x / z) as usize];
                    img.put_pixel(
                        k as u32 * w * z + x,
                        y,
                        image::Rgb(c.map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8)),
                    );
                }
            }
        }
        img.save(out).unwrap();
        // With `SPECK_RENDERS=DIR` the two renders at their own size too (`speck_map` reads them).
        if let Some(dir) = std::env::var_os("SPECK_RENDERS") {
            let dir = std::path::PathBuf::from(dir);
            for (name, im) in [("model.png", &b), ("ramp.png", &a)] {
                let mut one = image::RgbImage::new(w, h);
                for (i, c) in im.pixels.iter().enumerate() {
                    one.put_pixel(
                        i as u32 % w,
                        i as u32 / w,
                        image::Rgb(c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8)),
                    );
                }
                one.save(dir.join(name)).unwrap();
            }
        }
    }
    if let Model::Structured(m) = &full.model {
        println!(
            "residual weights {:?} fine {:?}",
            m.residual.weights, m.residual.fine
        );
        println!("pattern {:?}", m.pattern);
        println!(
            "ramp {:?}",
            m.ramp.iter().map(|s| (s.at, s.rgb)).collect::<Vec<_>>()
        );
    }
}
