//! What tells a network of thin dark lines (joints, cracks) from dark grain, pits and stains?
//! For every quadrant of a photo set, statistics of the detrended luminance map that the
//! `skewness` cue ([`proctex::cues::dark_skewness`]) reads: its skewness, the skewness of its
//! finer bands, the balance of dark against bright lines by the Hessian's eigenvalues, and the
//! share of its darkest pixels lying in long connected components (`network*`, `full*`), also
//! with hysteresis (`hyst*`: grown through the next darkest pixels), and how line-like its
//! strongest dark structures are (`linear*`, `fulllinear*`: lines against round pits).
//!
//! Prints TSV: file, patch name (as the yardstick names it), category, labels, then the
//! statistics in the order of `NAMES`.
//!
//! `cargo run --release -p proctex-analyzer --example dark_network_lab -- SET_DIR`

mod lab_common;

use proctex::cues::{blur, detrended_luminance};
use proctex::gabor::SIZE;

const NAMES: [&str; 26] = [
    "skewness",
    "skew_fine1",
    "skew_fine1.5",
    "skew_fine3",
    "dark_lines1",
    "dark_lines1.5",
    "dark_lines2",
    "network10_16",
    "network10_32",
    "network5_32",
    "network20_32",
    "full10_32",
    "full10_64",
    "full20_64",
    "hyst10_20_16",
    "hyst10_25_32",
    "hyst5_20_16",
    "fullhyst10_20_32",
    "fullhyst10_25_64",
    "fullhyst5_20_32",
    "linear1_5",
    "linear1.5_5",
    "linear2_5",
    "linear1_2",
    "fulllinear1_5",
    "fulllinear2_5",
];

fn moment3(v: &[f32]) -> f32 {
    let n = v.len() as f64;
    let m = v.iter().map(|&x| x as f64).sum::<f64>() / n;
    let var = v.iter().map(|&x| (x as f64 - m).powi(2)).sum::<f64>() / n;
    if var < 1e-12 {
        return 0.0;
    }
    (v.iter().map(|&x| (x as f64 - m).powi(3)).sum::<f64>() / n / var.powf(1.5)) as f32
}

/// The Hessian's eigenvalues (λ₁ ≥ λ₂) at every inner pixel of `map` (side `n`) smoothed at
/// `sigma`.
fn hessian_eigenvalues(map: &[f32], n: usize, sigma: f32) -> Vec<(f64, f64)> {
    let s = blur(map, n, sigma);
    let at = |x: usize, y: usize| s[y * n + x] as f64;
    let mut out = Vec::with_capacity(n * n);
    for y in 1..n - 1 {
        for x in 1..n - 1 {
            let xx = at(x + 1, y) - 2.0 * at(x, y) + at(x - 1, y);
            let yy = at(x, y + 1) - 2.0 * at(x, y) + at(x, y - 1);
            let xy =
                (at(x + 1, y + 1) - at(x - 1, y + 1) - at(x + 1, y - 1) + at(x - 1, y - 1)) / 4.0;
            let mean = (xx + yy) / 2.0;
            let r = (((xx - yy) / 2.0).powi(2) + xy * xy).sqrt();
            out.push((mean + r, mean - r));
        }
    }
    out
}

/// (Σ dark-line strength − Σ bright-line strength) / their sum, from the Hessian of the map
/// smoothed at `sigma`: a dark line curves up across and not along (λ₁ > |λ₂|), a bright one
/// down; blobs and step edges give little of either.
fn dark_lines(map: &[f32], sigma: f32) -> f32 {
    let (mut dark, mut bright) = (0.0, 0.0);
    for (l1, l2) in hessian_eigenvalues(map, SIZE, sigma) {
        dark += (l1 - l2.abs()).max(0.0);
        bright += (-l2 - l1.abs()).max(0.0);
    }
    ((dark - bright) / (dark + bright).max(1e-12)) as f32
}

/// How line-like the strongest dark structures of `map` (side `n`) smoothed at `sigma` are: over
/// the pixels whose larger Hessian eigenvalue λ₁ (the curvature across a dark line or blob) is in
/// its top `top` share, the mean of (λ₁ − max(λ₂, 0)) / λ₁ (1: a line, curving up across and
/// not along; 0: a round pit, curving up both ways).
fn dark_linearity(map: &[f32], n: usize, sigma: f32, top: f32) -> f32 {
    let eig = hessian_eigenvalues(map, n, sigma);
    let mut l1: Vec<f64> = eig.iter().map(|e| e.0).collect();
    l1.sort_by(|a, b| a.total_cmp(b));
    let k = ((1.0 - top as f64) * l1.len() as f64) as usize;
    let thr = l1[k.min(l1.len() - 1)].max(1e-12);
    let (mut sum, mut count) = (0.0, 0usize);
    for &(a, b) in &eig {
        if a >= thr {
            sum += (a - b.max(0.0)) / a;
            count += 1;
        }
    }
    (sum / count.max(1) as f64) as f32
}

/// The quadrant's own luminance at full resolution (its centre square, at most 256 px), minus
/// its blur at 24 px; its side.
fn full_map(photo: &proctex::input::Photo) -> (Vec<f32>, usize) {
    let side = photo.width.min(photo.height).min(256) as usize;
    let (x0, y0) = (
        (photo.width as usize - side) / 2,
        (photo.height as usize - side) / 2,
    );
    let mut lum = vec![0f32; side * side];
    for y in 0..side {
        for x in 0..side {
            let c = photo.pixels[(y0 + y) * photo.width as usize + x0 + x];
            lum[y * side + x] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        }
    }
    let shading = blur(&lum, side, 24.0);
    (lum.iter().zip(&shading).map(|(a, b)| a - b).collect(), side)
}

/// The share of the darkest `fraction` of the fine band (the map minus its blur at 3 px) that
/// lies in 8-connected components at least `extent` pixels across (their bounding box's longer
/// side): joints and cracks connect into long components, pits and grain do not.
fn network(map: &[f32], fraction: f32, extent: usize) -> f32 {
    network_n(map, SIZE, fraction, extent)
}

fn network_n(map: &[f32], n: usize, fraction: f32, extent: usize) -> f32 {
    hysteresis_n(map, n, fraction, fraction, extent)
}

/// [`network_n`] with hysteresis (Canny's): components of the darkest `grow` of the fine band
/// that hold one of its darkest `seed` pixels; the share of those seed pixels lying in
/// components at least `extent` across. A crack whose darkest pixels are broken by grain
/// connects through its less dark ones; an isolated pit or stain stays small.
fn hysteresis_n(map: &[f32], n: usize, seed: f32, grow: f32, extent: usize) -> f32 {
    let b = blur(map, n, 3.0);
    let fine: Vec<f32> = map.iter().zip(&b).map(|(a, b)| a - b).collect();
    let mut sorted = fine.clone();
    sorted.sort_by(f32::total_cmp);
    let t_seed = sorted[((n * n) as f32 * seed) as usize];
    let t = sorted[((n * n) as f32 * grow) as usize];
    let mask: Vec<bool> = fine.iter().map(|&v| v < t).collect();
    let (labels, count) = lab_common::topology::label(&mask, n, true);
    // Each component's seed-pixel count and bounding box (x0, x1, y0, y1).
    let mut parts = vec![(0usize, n, 0usize, n, 0usize); count];
    for (j, &l) in labels.iter().enumerate() {
        if l == usize::MAX || fine[j] >= t_seed {
            continue;
        }
        let (x, y) = (j % n, j / n);
        let c = &mut parts[l];
        *c = (c.0 + 1, c.1.min(x), c.2.max(x), c.3.min(y), c.4.max(y));
    }
    let dark: usize = parts.iter().map(|c| c.0).sum();
    let long: usize = parts
        .iter()
        .filter(|c| (c.2 - c.1 + 1).max(c.4 - c.3 + 1) >= extent)
        .map(|c| c.0)
        .sum();
    long as f32 / dark.max(1) as f32
}

/// [`network`] on the photo's own pixels (its centre square, at most 256 px, luminance
/// detrended at 24 px), extents in those pixels.
fn full(photo: &proctex::input::Photo, fraction: f32, extent: usize) -> f32 {
    full_hysteresis(photo, fraction, fraction, extent)
}

/// [`hysteresis_n`] on the photo's own pixels, as [`full`].
fn full_hysteresis(photo: &proctex::input::Photo, seed: f32, grow: f32, extent: usize) -> f32 {
    let (map, side) = full_map(photo);
    hysteresis_n(&map, side, seed, grow, extent)
}

fn main() {
    let dir = std::env::args()
        .nth(1)
        .expect("usage: dark_network_lab SET_DIR");
    let patches: Vec<(usize, lab_common::Patch)> =
        lab_common::load(&dir).into_iter().enumerate().collect();
    let lines = proctex::parallel::map_in_order(&patches, |(i, p)| {
        let map = detrended_luminance(&p.photo);
        let fine = |sigma: f32| {
            let b = blur(&map, SIZE, sigma);
            let f: Vec<f32> = map.iter().zip(&b).map(|(a, b)| a - b).collect();
            moment3(&f)
        };
        let v = [
            moment3(&map),
            fine(1.0),
            fine(1.5),
            fine(3.0),
            dark_lines(&map, 1.0),
            dark_lines(&map, 1.5),
            dark_lines(&map, 2.0),
            network(&map, 0.10, 16),
            network(&map, 0.10, 32),
            network(&map, 0.05, 32),
            network(&map, 0.20, 32),
            full(&p.photo, 0.10, 32),
            full(&p.photo, 0.10, 64),
            full(&p.photo, 0.20, 64),
            hysteresis_n(&map, SIZE, 0.10, 0.20, 16),
            hysteresis_n(&map, SIZE, 0.10, 0.25, 32),
            hysteresis_n(&map, SIZE, 0.05, 0.20, 16),
            full_hysteresis(&p.photo, 0.10, 0.20, 32),
            full_hysteresis(&p.photo, 0.10, 0.25, 64),
            full_hysteresis(&p.photo, 0.05, 0.20, 32),
            dark_linearity(&map, SIZE, 1.0, 0.05),
            dark_linearity(&map, SIZE, 1.5, 0.05),
            dark_linearity(&map, SIZE, 2.0, 0.05),
            dark_linearity(&map, SIZE, 1.0, 0.02),
            {
                let (m, side) = full_map(&p.photo);
                dark_linearity(&m, side, 1.0, 0.05)
            },
            {
                let (m, side) = full_map(&p.photo);
                dark_linearity(&m, side, 2.0, 0.05)
            },
        ];
        let v: Vec<String> = v.iter().map(|x| format!("{x:.4}")).collect();
        format!("{}\t{}", lab_common::patch_columns(p, *i), v.join("\t"))
    });
    println!("file\tpatch\tcategory\tlabels\t{}", NAMES.join("\t"));
    for l in lines {
        println!("{l}");
    }
}
