//! Laboratory: a family's best database start at several scales, each refined and fitted as the
//! ranking does; prints the structure and texture distances (and the noise model's).
//! `cargo run --release -p proctex-analyzer --example coarse_lab -- PHOTO QX QY FAMILY`
// Only `ranked` of the shared laboratory code.
#[allow(dead_code)]
mod lab_common;

use proctex::analyze::{Options, analyze_prepared};
use proctex::db::Db;
use proctex::noise::Tile;
use proctex::pattern::PatternKind;
use proctex::refine::refine;
use proctex::retrieve::texture_distance;
use proctex::structure::fit_structured_with;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let q = |i: usize| args[i].parse::<u32>().unwrap();
    let kind = PatternKind::from_name(&args[4]).expect("family");
    let factors: Vec<f32> = std::env::var("FACTORS")
        .unwrap_or("1,1.5,2,3,4".into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let rq = lab_common::ranked::RankedQuadrant::of(&args[1], q(2), q(3));
    let (small, tt, qd, per_px, m) = (&rq.small, &rq.tt, &rq.query, rq.per_px, rq.start(kind));
    let db = Db::shipped();
    let tile = Tile::new_2d(1);
    let dbtile = Tile::new_2d(proctex::db::DB_SEED);
    let opts = Options::default();
    let noise = analyze_prepared(small, &opts).params;
    println!(
        "noise texture {:.3}",
        texture_distance(db, tt, qd, &noise, &tile)
    );
    let qm = if m.swapped { qd.swapped() } else { qd.clone() };
    let evals: usize =
        std::env::var("EVALS").map_or(proctex::refine::DEFAULT_EVALUATIONS, |s| s.parse().unwrap());
    for f in factors {
        let mut start = m.pattern.clone();
        start.scale *= f;
        let r = refine(db, &qm, &start, evals, &dbtile, &mut |_, _| true);
        let mut p = r.pattern.clone();
        p.scale *= per_px;
        let fitted = fit_structured_with(small, &p, &opts, m.swapped, &tile).params;
        let t = texture_distance(db, tt, qd, &fitted, &tile);
        println!(
            "x{f:<4} start scale {:6.1} d {:.3} -> refined scale {:6.1} d {:.3}  texture {:.3}  {:?}",
            start.scale,
            r.start_distance,
            r.pattern.scale,
            r.distance,
            t,
            r.pattern.vector()
        );
        if let Ok(dir) = std::env::var("OUT") {
            let img = proctex::evaluate::render_params_at_photo_size(&fitted, small);
            let path = format!("{dir}/{}_{}.png", args[4], f);
            let mut out = image::RgbImage::new(small.width, small.height);
            for (i, c) in img.pixels.iter().enumerate() {
                out.put_pixel(
                    i as u32 % small.width,
                    i as u32 / small.width,
                    image::Rgb(c.map(|v| (v.clamp(0.0, 1.0) * 255.0) as u8)),
                );
            }
            out.save(path).unwrap();
        }
    }
}
