//! Times the stages of the automatic model choice on one photo's top-left quadrant.
//! `cargo run --release -p proctex-analyzer --example suggest_stages -- PHOTO`
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::input::{Crop, Photo};
use proctex::retrieve::{Refinement, Suggester};
use std::time::Instant;

fn main() {
    let path = std::env::args().nth(1).unwrap();
    let photo = Photo::decode(&std::fs::read(path).unwrap()).unwrap();
    let (w, h) = (photo.width / 2, photo.height / 2);
    let patch = photo.crop(Crop { x: 0, y: 0, w, h }).unwrap();
    let db = Db::shipped();
    let o = Options::default();
    let t = Instant::now();
    let refinement = if std::env::var("NO_REFINE").is_ok() {
        Refinement::NONE
    } else {
        Refinement::default()
    };
    let mut s = Suggester::new(db, &patch, &o, refinement);
    let t_new = t.elapsed();
    let t = Instant::now();
    while s.step(db, &mut |_, _| true) {}
    let t_refine = t.elapsed();
    // Each ranking twice, alternated: the first call also makes the seed's noise tile.
    let _ = s.ranked(db, 1);
    let t = Instant::now();
    let list = s.suggestions(db);
    let t_rank = t.elapsed();
    let t = Instant::now();
    let first = s.ranked(db, 1);
    let t_first = t.elapsed();
    assert_eq!(first[0].name, list[0].name);
    let t = Instant::now();
    let par = proctex::retrieve::suggest_with(db, &patch, &o, refinement, &|_, _| true);
    let t_par = t.elapsed();
    assert_eq!(par[0].name, list[0].name);
    let t = Instant::now();
    let pick = &list[0];
    let _ = match &pick.pattern {
        Some((p, sw)) => proctex::structure::fit_structured(db, &patch, p, &o, *sw),
        None => proctex::analyze::analyze_prepared(&patch, &o),
    };
    let t_fit = t.elapsed();
    println!(
        "{}x{}: retrieval {:.0} ms, refinement (1 thread) {:.0} ms, ranking {:.0} ms (with only the best family fitted {:.0} ms), final fit {:.0} ms; chosen {}; all of retrieval to ranking on every thread {:.0} ms",
        w,
        h,
        t_new.as_secs_f64() * 1e3,
        t_refine.as_secs_f64() * 1e3,
        t_rank.as_secs_f64() * 1e3,
        t_first.as_secs_f64() * 1e3,
        t_fit.as_secs_f64() * 1e3,
        pick.name,
        t_par.as_secs_f64() * 1e3
    );
}
