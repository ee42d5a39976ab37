//! Where the structure distance of a synthesis goes: the retrieval descriptor's weighted
//! squared distance (`Db::distance`) split into its parts — the mean log-Gabor energy per
//! frequency (summed over orientations), the energies' spreads, and the luminance quantiles —
//! for syntheses judged by the fidelity protocol's pairs (quadrants top-left/bottom-left and
//! top-right/bottom-right, both ways, seeds 1..S) on the stochastic photos of a manifest.
//!
//! Each part is printed as its share of the halves' total squared distance (mean ± standard
//! error over photos), so a row's parts sum to the squared structure ratio (before the ratio's
//! square root and per-patch averaging); the halves' row sums to 1.
//!
//! ```text
//! cargo run --release -p proctex-analyzer --example structure_parts_lab -- \
//!     ../shared/photos/dev/manifest.tsv [SEEDS]
//! ```

#[path = "lab_common/ladder.rs"]
#[allow(dead_code)]
mod ladder;
use ladder::{mean_se, stochastic_photos};
use proctex::analyze::{Options, analyze_photo};
use proctex::db::Db;
use proctex::distance::describe_luminance;
use proctex::evaluate::{quadrants, random_phase, render_params_at_photo_size};
use proctex::gabor::{FREQUENCIES, ORIENTATIONS, QUANTILES};
use proctex::input::Photo;

/// Parts: mean energy per frequency, spread per frequency, quantiles.
const PARTS: usize = 2 * FREQUENCIES + 1;

fn part_names() -> Vec<String> {
    let mut v: Vec<String> = (0..FREQUENCIES).map(|k| format!("mean f{k}")).collect();
    v.extend((0..FREQUENCIES).map(|k| format!("spread f{k}")));
    v.push("quantiles".into());
    v
}

fn descriptor(p: &Photo) -> Vec<f32> {
    describe_luminance(p).0
}

/// Weighted squared differences of two descriptors, per part.
fn parts(db: &Db, a: &[f32], b: &[f32]) -> [f64; PARTS] {
    let block = ORIENTATIONS * FREQUENCIES;
    let mut out = [0.0; PARTS];
    for (i, ((x, y), w)) in a.iter().zip(b).zip(&db.weights).enumerate() {
        let d = (w * (x - y) * (x - y)) as f64;
        let part = if i < block {
            i % FREQUENCIES
        } else if i < 2 * block {
            FREQUENCIES + (i - block) % FREQUENCIES
        } else {
            2 * FREQUENCIES
        };
        out[part] += d;
    }
    debug_assert_eq!(a.len(), 2 * block + QUANTILES);
    out
}

const SYNTHESES: [&str; 4] = [
    "random-phase floor (full spectrum, exact histograms)",
    "noise model, isotropic, no tone curve",
    "noise model, oriented, no tone curve",
    "noise model as it renders",
];

fn synthesise(which: usize, src: &Photo, seed: u32) -> Photo {
    if which == 0 {
        return random_phase(src, seed);
    }
    let opts = Options {
        seed,
        orientation: which >= 2,
        tone: which >= 3,
        ..Options::default()
    };
    let params = analyze_photo(src, &opts).expect("analysis").params;
    render_params_at_photo_size(&params, src)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let manifest = args.first().expect("MANIFEST.tsv");
    let seeds: Vec<u32> = (1..=args.get(1).map_or(2, |s| s.parse().unwrap())).collect();
    let photos = stochastic_photos(manifest);
    let db = Db::shipped();
    // Per row (halves, then each synthesis), per photo, the parts' shares.
    let mut table: Vec<Vec<[f64; PARTS]>> = vec![Vec::new(); SYNTHESES.len() + 1];
    let mut log_ratios = Vec::new();
    for (name, photo) in &photos {
        let [tl, tr, bl, br] = quadrants(photo).unwrap();
        let pairs = [(&tl, &bl), (&tr, &br)];
        let mut halves = [0.0; PARTS];
        let mut syn = vec![[0.0; PARTS]; SYNTHESES.len()];
        let mut ratio = vec![[[0.0f64; 3]; ORIENTATIONS]; SYNTHESES.len()];
        for (a, b) in pairs {
            let (da, dbd) = (descriptor(a), descriptor(b));
            for (h, p) in halves.iter_mut().zip(parts(db, &da, &dbd)) {
                *h += p / 2.0;
            }
            for (which, acc) in syn.iter_mut().enumerate() {
                for &seed in &seeds {
                    for (src, other) in [(a, &dbd), (b, &da)] {
                        let d = descriptor(&synthesise(which, src, seed));
                        let n = (2 * 2 * seeds.len()) as f64;
                        for (o, row) in ratio[which].iter_mut().enumerate() {
                            for (k, r) in row.iter_mut().enumerate() {
                                let i = o * FREQUENCIES + k;
                                *r += ((d[i] as f64).max(1e-9) / (other[i] as f64).max(1e-9)).ln()
                                    / n;
                            }
                        }
                        for (s, p) in acc.iter_mut().zip(parts(db, &d, other)) {
                            *s += p / n;
                        }
                    }
                }
            }
        }
        let total: f64 = halves.iter().sum::<f64>().max(1e-12);
        table[0].push(halves.map(|v| v / total));
        let mut line = format!("{name:<36}");
        for (which, acc) in syn.iter().enumerate() {
            let shares = acc.map(|v| v / total);
            line += &format!(" {:.2}", shares.iter().sum::<f64>().sqrt());
            table[which + 1].push(shares);
        }
        eprintln!("{line}");
        log_ratios.push(ratio);
    }
    println!(
        "{} stochastic photos of {manifest}, seeds {seeds:?}: each part's weighted squared \
         descriptor distance over the halves' total (mean ± s.e. over photos)",
        photos.len()
    );
    let names = part_names();
    println!("| row | total | {} |", names.join(" | "));
    println!("| --- | --- |{}", " --- |".repeat(PARTS));
    let rows: Vec<&str> = std::iter::once("halves").chain(SYNTHESES).collect();
    for (row, shares) in rows.iter().zip(&table) {
        let cell = |k: Option<usize>| {
            let v: Vec<f64> = shares
                .iter()
                .map(|s| k.map_or(s.iter().sum(), |k| s[k]))
                .collect();
            let (m, se) = mean_se(&v);
            format!("{m:.2} ± {se:.2}")
        };
        let cells: Vec<String> = (0..PARTS).map(|k| cell(Some(k))).collect();
        println!("| {row} | {} | {} |", cell(None), cells.join(" | "));
    }
    // A few photos (sand ripples, gravel) dominate the means; the medians show the typical
    // photo.
    println!("\nMedians over photos:");
    println!("| row | total | {} |", names.join(" | "));
    println!("| --- | --- |{}", " --- |".repeat(PARTS));
    for (row, shares) in rows.iter().zip(&table) {
        let median = |k: Option<usize>| {
            let mut v: Vec<f64> = shares
                .iter()
                .map(|s| k.map_or(s.iter().sum(), |k| s[k]))
                .collect();
            v.sort_by(f64::total_cmp);
            format!("{:.2}", v[v.len() / 2])
        };
        let cells: Vec<String> = (0..PARTS).map(|k| median(Some(k))).collect();
        println!("| {row} | {} | {} |", median(None), cells.join(" | "));
    }
    println!();
    println!(
        "Mean log-Gabor energy of the synthesis over the other patch's, ln, per orientation \
         (0° = horizontal frequency), frequencies f0–f2 (mean ± s.e. over photos):"
    );
    for (which, name) in SYNTHESES.iter().enumerate() {
        println!("\n{name}\n| orientation | f0 | f1 | f2 |\n| --- | --- | --- | --- |");
        for o in 0..ORIENTATIONS {
            let cells: Vec<String> = (0..3)
                .map(|k| {
                    let v: Vec<f64> = log_ratios
                        .iter()
                        .map(|r: &Vec<[[f64; 3]; ORIENTATIONS]>| r[which][o][k])
                        .collect();
                    let (m, se) = mean_se(&v);
                    format!("{m:+.2} ± {se:.2}")
                })
                .collect();
            println!(
                "| {:.1}° | {} |",
                o as f64 * 180.0 / ORIENTATIONS as f64,
                cells.join(" | ")
            );
        }
    }
}
