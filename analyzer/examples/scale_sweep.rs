//! How the fitted render's distances change with the pattern's scale: one family fitted to one
//! photo quadrant as the product does, then its pattern scaled by each factor and fitted again
//! (ramp, residual and step 6: `structure::fit_structured`), each render's distances to the
//! quadrant it was fitted on and to the diagonal quadrant (the yardstick's pair).
//!
//! `SWEEP_PNG=DIR` writes each render to DIR as NAME.png.
//!
//! `cargo run --release -p proctex-analyzer --example scale_sweep -- PHOTO FAMILY QX QY [F...]`
// Only the PNG writer is used here.
#[allow(dead_code)]
mod lab_common;

use lab_common::save_png;
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::distance::distances;
use proctex::evaluate::render_params_at_photo_size;
use proctex::input::{Crop, Photo};
use proctex::params::Model;
use proctex::pattern::PatternKind;
use proctex::retrieve::{ModelChoice, Refinement, analyze_photo_model};
use proctex::structure::fit_structured;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let photo = Photo::decode(&std::fs::read(&args[1]).unwrap()).unwrap();
    let kind = PatternKind::from_name(&args[2]).expect("a family name");
    let q = |i: usize| args[i].parse::<u32>().unwrap();
    let (w, h) = (photo.width / 2, photo.height / 2);
    let quadrant = |x: u32, y: u32| {
        photo
            .crop(Crop {
                x: x * w,
                y: y * h,
                w,
                h,
            })
            .unwrap()
    };
    let (qx, qy) = (q(3), q(4));
    let patch = quadrant(qx, qy);
    let other = quadrant(1 - qx, 1 - qy);
    let factors: Vec<f32> = if args.len() > 5 {
        args[5..].iter().map(|s| s.parse().unwrap()).collect()
    } else {
        vec![1.0, 1.5, 2.0, 3.0, 4.0]
    };
    let o = Options::default();
    let (a, suggestions) =
        analyze_photo_model(&patch, &o, ModelChoice::Kind(kind), Refinement::default()).unwrap();
    let swapped = suggestions
        .iter()
        .find_map(|s| {
            s.pattern
                .as_ref()
                .filter(|(p, _)| p.kind == kind)
                .map(|(_, s)| *s)
        })
        .unwrap_or(false);
    let Model::Structured(m) = &a.params.model else {
        panic!("a structured family")
    };
    let noise = analyze_photo_model(&patch, &o, ModelChoice::Noise, Refinement::default())
        .unwrap()
        .0;
    let show = |name: &str, p: &proctex::params::Params| {
        let r = render_params_at_photo_size(p, &patch);
        if let Some(dir) = std::env::var_os("SWEEP_PNG") {
            save_png(&r, &std::path::Path::new(&dir).join(format!("{name}.png")));
        }
        let (s, t) = (distances(&r, &patch), distances(&r, &other));
        println!(
            "{name:>8}  own: spectrum {:.3} colour {:.4} structure {:.3}   other: spectrum {:.3} colour {:.4} structure {:.3}",
            s.spectrum_db, s.colour, s.structure, t.spectrum_db, t.colour, t.structure
        );
    };
    let h = distances(&patch, &other);
    println!(
        "  halves  spectrum {:.3} colour {:.4} structure {:.3}",
        h.spectrum_db, h.colour, h.structure
    );
    show("noise", &noise.params);
    for f in factors {
        let mut pattern = m.pattern.clone();
        pattern.scale *= f;
        let fit = fit_structured(Db::shipped(), &patch, &pattern, &o, swapped);
        show(&format!("x{f}"), &fit.params);
    }
}
