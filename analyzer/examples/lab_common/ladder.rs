//! What the noise model's ladders share (`noise_ideal_lab`, `half_octave_lab`): exact
//! histograms by rank matching, and the table of rungs with each rung's change from the one
//! above, paired per photo.

use proctex::devset::{Category, overall, parse_manifest};
use proctex::evaluate::{Fidelity, fidelity_with};
use proctex::input::Photo;
use proctex::render::Prepared;

/// Channel `values` (any distribution) rank-matched to `target`'s exact values.
pub fn rank_match(values: &[f32], target: &[f32]) -> Vec<f32> {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut sorted = target.to_vec();
    sorted.sort_unstable_by(f32::total_cmp);
    let mut out = vec![0.0; values.len()];
    for (rank, &i) in order.iter().enumerate() {
        out[i] = sorted[rank];
    }
    out
}

/// The patch's channels in the model's decorrelated basis, about its mean.
pub fn decorrelated(src: &Photo, prep: &Prepared) -> [Vec<f32>; 3] {
    std::array::from_fn(|c| {
        src.pixels
            .iter()
            .map(|p| {
                (0..3)
                    .map(|k| prep.basis[c][k] * (p[k] - prep.mean[k]))
                    .sum::<f32>()
            })
            .collect()
    })
}

/// Decorrelated channel values back to RGB about the model's mean.
pub fn to_rgb(prep: &Prepared, v: &[Vec<f32>; 3], w: u32, h: u32) -> Photo {
    Photo {
        width: w,
        height: h,
        pixels: (0..v[0].len())
            .map(|i| {
                std::array::from_fn(|k| {
                    let rgb =
                        prep.mean[k] + (0..3).map(|c| v[c][i] * prep.basis[c][k]).sum::<f32>();
                    rgb.clamp(0.0, 1.0)
                })
            })
            .collect(),
    }
}

/// Mean and standard error of `v`.
pub fn mean_se(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (mean, (var / n).sqrt())
}

/// Prints the ladder: per rung `names[r]`, the mean ± standard error over photos of the
/// spectrum, colour, structure and overall ratios (`table[r][photo]`), and the overall ratio's
/// change from the rung above, paired per photo.
pub fn print_ladder(names: &[&str], table: &[Vec<[f64; 4]>]) {
    println!("| rung | spectrum | colour | structure | overall | overall − previous rung |");
    println!("| --- | --- | --- | --- | --- | --- |");
    for (rung, rows) in table.iter().enumerate() {
        let cell = |k: usize| {
            let (m, s) = mean_se(&rows.iter().map(|r| r[k]).collect::<Vec<_>>());
            format!("{m:.2} ± {s:.2}")
        };
        let step = if rung == 0 {
            "—".to_string()
        } else {
            let d: Vec<f64> = rows
                .iter()
                .zip(&table[rung - 1])
                .map(|(a, b)| a[3] - b[3])
                .collect();
            let (m, s) = mean_se(&d);
            format!("{m:+.3} ± {s:.3}")
        };
        println!(
            "| {} | {} | {} | {} | {} | {step} |",
            names[rung],
            cell(0),
            cell(1),
            cell(2),
            cell(3)
        );
    }
}

/// The stochastic photos of `manifest` (path, decoded), in its order.
pub fn stochastic_photos(manifest: &str) -> Vec<(String, Photo)> {
    let dir = std::path::Path::new(manifest).parent().unwrap();
    let entries = parse_manifest(&std::fs::read_to_string(manifest).unwrap()).unwrap();
    entries
        .iter()
        .filter(|e| e.category == Category::Stochastic)
        .map(|e| {
            let bytes = std::fs::read(dir.join(&e.file)).unwrap();
            (e.file.clone(), Photo::decode(&bytes).unwrap())
        })
        .collect()
}

/// Runs `rungs` rungs of a ladder on `photos` by the fidelity protocol at `seeds`
/// (`synthesise(rung, patch, seed)`), printing each photo's overall ratios to stderr; returns
/// per rung, per photo, the spectrum, colour, structure and overall ratios.
pub fn run_ladder(
    photos: &[(String, Photo)],
    seeds: &[u32],
    rungs: usize,
    synthesise: &dyn Fn(usize, &Photo, u32) -> Photo,
) -> Vec<Vec<[f64; 4]>> {
    let mut table: Vec<Vec<[f64; 4]>> = vec![Vec::new(); rungs];
    for (name, photo) in photos {
        let mut line = format!("{name:<36}");
        for (rung, rows) in table.iter_mut().enumerate() {
            let f: Fidelity = fidelity_with(photo, seeds, &mut |src, seed| {
                Ok(synthesise(rung, src, seed))
            })
            .unwrap();
            let r = [
                f.spectrum_ratio,
                f.colour_ratio,
                f.structure_ratio,
                overall(&f),
            ];
            line += &format!(" {:.2}", r[3]);
            rows.push(r);
        }
        eprintln!("{line}");
    }
    table
}
