//! A structured render's grain against its photo's: for each line `FILE QX QY FAMILY` of a list
//! (tab-separated; QX, QY the quadrant, 0 or 1), the family fitted to that quadrant of the set's
//! photo as `proctex analyze --model FAMILY` fits it, rendered at the quadrant's size; printed:
//! the speck ratio (`devset::speck_ratio`), the photo's and the render's fine deviation
//! (`structure::grain::fine_deviation`, 8-bit quanta) and the finest band's part along the tone
//! line (`NoiseModel::fine[0]`); then the analysis's wall time and that of the grain step alone
//! (`structure::grain::match_grain` on the fitted params with that part set to 0, its longest
//! path: three renders), in milliseconds.
//!
//! `cargo run --release -p proctex-analyzer --example grain_lab -- SET_DIR LIST`
use proctex::analyze::Options;
use proctex::devset::speck_ratio;
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::{Crop, Photo};
use proctex::params::Model;
use proctex::pattern::PatternKind;
use proctex::retrieve::{ModelChoice, Refinement, analyze_photo_model};
use proctex::specks::speck_fraction;
use proctex::structure::grain::fine_deviation;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let dir = std::path::PathBuf::from(&args[1]);
    let list = std::fs::read_to_string(&args[2]).expect("a list");
    let opts = Options::default();
    for line in list.lines() {
        let f: Vec<&str> = line.split('\t').collect();
        let photo = Photo::decode(&std::fs::read(dir.join(f[0])).unwrap()).unwrap();
        let (qx, qy): (u32, u32) = (f[1].parse().unwrap(), f[2].parse().unwrap());
        let kind = PatternKind::from_name(f[3]).expect("a family");
        let (w, h) = (photo.width / 2, photo.height / 2);
        let crop = Crop {
            x: qx * w,
            y: qy * h,
            w,
            h,
        };
        let patch = photo.crop(crop).unwrap();
        let start = std::time::Instant::now();
        let (a, _) = analyze_photo_model(
            &patch,
            &opts,
            ModelChoice::Kind(kind),
            Refinement::default(),
        )
        .unwrap();
        let analysis_ms = start.elapsed().as_secs_f64() * 1e3;
        let mut bare = a.params.clone();
        if let Model::Structured(m) = &mut bare.model {
            m.residual.fine[0] = 0.0;
        }
        let start = std::time::Instant::now();
        proctex::structure::grain::match_grain(&patch, &mut bare);
        let grain_ms = start.elapsed().as_secs_f64() * 1e3;
        let render = render_params_at_photo_size(&a.params, &patch);
        let ratio = speck_ratio(
            speck_fraction(&render),
            speck_fraction(&patch),
            (w * h) as usize,
        );
        let deviation = |p: &Photo| fine_deviation(&p.pixels, w as usize, h as usize);
        let fine = match &a.params.model {
            Model::Structured(m) => m.residual.fine[0],
            Model::Noise(n) => n.fine[0],
        };
        println!(
            "{}\t{qx}{qy}\t{}\t{ratio:.2}\t{:.2}\t{:.2}\t{fine:.4}\t{analysis_ms:.0}\t{grain_ms:.0}",
            f[0],
            f[3],
            deviation(&patch),
            deviation(&render)
        );
    }
}
