//! Where the noise model's specks come from, on every quadrant of a photo set: the noise model's
//! analysis rendered at the quadrant's size at four seeds with one part taken out at a time
//! (the output tone curve, the histogram spline), speck fractions
//! ([`proctex::specks::speck_fraction`]) averaged over the seeds.
//!
//! Prints TSV: file, patch, category, labels, the photo's fraction, then the model's, without
//! the tone curve, without the histogram, without either, and without the finest band's part
//! drawn after the histogram (that band then absent).
//!
//! `cargo run --release -p proctex-analyzer --example noise_speck_lab -- SET_DIR`

mod lab_common;

use proctex::analyze::Options;
use proctex::evaluate::render_params_at_photo_size;
use proctex::params::{Model, Params};
use proctex::retrieve::{ModelChoice, Refinement, analyze_photo_model};
use proctex::specks::speck_fraction;

const SEEDS: u32 = 4;

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: noise_speck_lab SET_DIR");
    let patches: Vec<(usize, lab_common::Patch)> =
        lab_common::load(&dir).into_iter().enumerate().collect();
    let lines = proctex::parallel::map_in_order(&patches, |(i, p)| {
        let (a, _) = analyze_photo_model(
            &p.photo,
            &Options::default(),
            ModelChoice::Noise,
            Refinement::default(),
        )
        .unwrap();
        let specks = |f: &dyn Fn(&mut Params)| {
            let mut params = a.params.clone();
            f(&mut params);
            (0..SEEDS)
                .map(|s| {
                    params.seed = a.params.seed + s;
                    speck_fraction(&render_params_at_photo_size(&params, &p.photo))
                })
                .sum::<f64>()
                / SEEDS as f64
        };
        let no_tone = |q: &mut Params| {
            if let Model::Noise(m) = &mut q.model {
                m.tone = None;
            }
        };
        let no_histogram = |q: &mut Params| {
            if let Model::Noise(m) = &mut q.model {
                m.histogram.enabled = false;
            }
        };
        let v = [
            specks(&|_| {}),
            specks(&no_tone),
            specks(&no_histogram),
            specks(&|q| {
                no_tone(q);
                no_histogram(q);
            }),
            specks(&|q| {
                if let Model::Noise(m) = &mut q.model {
                    m.fine = [0.0; 3];
                }
            }),
        ];
        let v: Vec<String> = v.iter().map(|x| format!("{x:.5}")).collect();
        format!(
            "{}\t{:.5}\t{}",
            lab_common::patch_columns(p, *i),
            speck_fraction(&p.photo),
            v.join("\t")
        )
    });
    println!(
        "file\tpatch\tcategory\tlabels\tphoto\tmodel\tno_tone\tno_histogram\tneither\tno_fine_part"
    );
    for l in lines {
        println!("{l}");
    }
}
