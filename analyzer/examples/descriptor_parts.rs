//! Laboratory: where a fitted render's texture distance to a photo comes from. For one
//! development-set quadrant, the noise model and each named family (its best database start
//! refined with the ranking's budget of evaluations, one start where the ranking shares them
//! between two, and fitted as the ranking fits, with step 6's residual amplitudes `g^α`, α from
//! `ALPHAS`, default `0`: the ranking's fit) are rendered, projected on the photo's tone line and
//! described; prints the weighted squared descriptor differences by part (mean energies, their
//! spreads, by frequency from the finest; the quantiles), the render's mean energy and sparsity
//! (spread / mean) against the photo's per frequency, and the total (the texture distance).
//! `cargo run --release -p proctex-analyzer --example descriptor_parts -- PHOTO QX QY FAMILY[,FAMILY…]`
// Only `ranked` of the shared laboratory code.
#[allow(dead_code)]
mod lab_common;

use proctex::analyze::{Options, analyze_prepared};
use proctex::db::Db;
use proctex::gabor::{Descriptor, FREQUENCIES, ORIENTATIONS, describe, descriptor_image};
use proctex::noise::Tile;
use proctex::params::Params;
use proctex::pattern::PatternKind;
use proctex::refine::refine;
use proctex::render::{Prepared, View, render_prepared};
use proctex::structure::fit_structured_grown;
use proctex::two_tone::TwoTone;

/// Entries of one part (means or spreads) of a descriptor.
const BLOCK: usize = ORIENTATIONS * FREQUENCIES;

/// Prints the parts of `params`' texture distance to the photo (see the module docs).
fn parts(db: &Db, tt: &TwoTone, photo: &Descriptor, params: &Params, tile: &Tile, name: &str) {
    let (w, h) = (tt.width, tt.height);
    let img = render_prepared(&Prepared::new(params), tile, w, h, &View::default()).to_photo();
    let render = describe(&descriptor_image(&tt.project(&img), w as usize, h as usize));
    let mut by_part = [0f32; 2 * FREQUENCIES + 1];
    for (i, ((x, y), wt)) in photo.0.iter().zip(&render.0).zip(&db.weights).enumerate() {
        let part = if i < 2 * BLOCK {
            (i / BLOCK) * FREQUENCIES + (i % BLOCK) % FREQUENCIES
        } else {
            2 * FREQUENCIES
        };
        by_part[part] += wt * (x - y) * (x - y);
    }
    let sum_over_orientations = |d: &Descriptor, part: usize, k: usize| -> f32 {
        (0..ORIENTATIONS)
            .map(|o| d.0[part * BLOCK + o * FREQUENCIES + k])
            .sum()
    };
    let ratios: Vec<String> = (0..FREQUENCIES)
        .map(|k| {
            let (pm, rm) = (
                sum_over_orientations(photo, 0, k),
                sum_over_orientations(&render, 0, k),
            );
            let (ps, rs) = (
                sum_over_orientations(photo, 1, k),
                sum_over_orientations(&render, 1, k),
            );
            format!("{:.2}/{:.2}", rm / pm, (rs / rm) / (ps / pm))
        })
        .collect();
    let list = |v: &[f32]| {
        v.iter()
            .map(|x| format!("{x:.2}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    println!(
        "{name:14} total {:.3} | means {} | spreads {} | quantiles {:.2}",
        by_part.iter().sum::<f32>().sqrt(),
        list(&by_part[..FREQUENCIES]),
        list(&by_part[FREQUENCIES..2 * FREQUENCIES]),
        by_part[2 * FREQUENCIES]
    );
    println!(
        "{:14} energy / sparsity against the photo's, finest first: {}",
        "",
        ratios.join(" ")
    );
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let q = |i: usize| args[i].parse::<u32>().unwrap();
    let alphas: Vec<f64> = std::env::var("ALPHAS")
        .unwrap_or("0".into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let db = Db::shipped();
    let tile = Tile::new_2d(1);
    let dbtile = Tile::new_2d(proctex::db::DB_SEED);
    let opts = Options::default();
    let rq = lab_common::ranked::RankedQuadrant::of(&args[1], q(2), q(3));
    let noise = analyze_prepared(&rq.small, &opts).params;
    parts(db, &rq.tt, &rq.query, &noise, &tile, "noise");
    for family in args[4].split(',') {
        let kind = PatternKind::from_name(family).expect("a family name");
        let m = rq.start(kind);
        let qm = if m.swapped {
            rq.query.swapped()
        } else {
            rq.query.clone()
        };
        let evals = proctex::refine::DEFAULT_EVALUATIONS;
        let mut p = refine(db, &qm, &m.pattern, evals, &dbtile, &mut |_, _| true).pattern;
        p.scale *= rq.per_px;
        for &alpha in &alphas {
            let fitted = fit_structured_grown(&rq.small, &p, &opts, m.swapped, &tile, alpha).params;
            let name = format!("{family} α {alpha}");
            parts(db, &rq.tt, &rq.query, &fitted, &tile, &name);
        }
    }
}
