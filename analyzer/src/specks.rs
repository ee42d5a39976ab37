//! Specks: isolated outlier pixels, counted so that a render can be held to the photo's own
//! (the development-set yardstick compares the two, [`speck_ratio`]).

use crate::input::Photo;

/// Most specks a render may have, in units of its photo's own ([`speck_ratio`]).
pub const SPECK_LIMIT: f64 = 1.5;

/// A render's speck fraction over its photo's, each with one pixel added (a photo without
/// specks does not divide by zero, and one speck pixel in a render of a speckless photo is
/// a ratio of 2, not infinity).
pub fn speck_ratio(render: f64, photo: f64, pixels: usize) -> f64 {
    let one = 1.0 / pixels.max(1) as f64;
    (render + one) / (photo + one)
}

/// Whether `params` rendered with their own seed at `photo`'s size (one texel a pixel, as
/// analysed) keep within [`SPECK_LIMIT`] of `photo_fraction`, the photo's own
/// [`speck_fraction`]: the check that a model's render is no speckier than its photo.
pub fn within_speck_limit(
    photo: &Photo,
    params: &crate::params::Params,
    photo_fraction: f64,
) -> bool {
    use crate::render::{View, render};
    let rendered = render(params, photo.width, photo.height, &View::default()).to_photo();
    let pixels = rendered.pixels.len();
    speck_ratio(speck_fraction(&rendered), photo_fraction, pixels) <= SPECK_LIMIT
}

/// Robust deviations past which a pixel stands out from a neighbour ([`speck_fraction`]).
pub const SPECK_DEVIATIONS: f32 = 4.0;

/// The fraction of `p`'s pixels that are specks: isolated outliers, brighter (or darker) in
/// some RGB channel than all its 8 neighbours but at most one by more than
/// [`SPECK_DEVIATIONS`] robust deviations. The robust deviation of a channel is 1.4826 × the
/// median absolute difference of its pixels from their 3×3 neighbourhoods' medians (the
/// standard deviation, were those differences Gaussian), each image its own: the measure
/// counts isolated outliers against the image's own fine texture, not a render that is merely
/// grainier.
///
/// Departure from the plain "farther than 4 deviations from the 3×3 median": in a clean,
/// piecewise flat render (a pattern's ramp alone) the deviation is a quantum, and every pixel
/// of a joint one pixel wide is that far from its median (six of its nine neighbours are
/// brick), so the plain measure counted the joints: 12–43 % of the ramp-alone renders of
/// brick, cells and planks on the development set. A pixel of a line has two neighbours like
/// it; a speck has none, or one (a speck of two pixels).
///
/// Values are quantised to 1/255 first, as an exported 8-bit image is (a render's sub-quantum
/// wobble is no speck), and the deviation is at least one quantum. Border pixels are not
/// judged (a line that leaves the image would look like one), only counted in the fraction's
/// denominator.
pub fn speck_fraction(p: &Photo) -> f64 {
    let mask = speck_mask(p);
    mask.iter().filter(|&&s| s).count() as f64 / mask.len().max(1) as f64
}

/// Which of `p`'s pixels (row by row) are specks, as [`speck_fraction`] counts them.
pub fn speck_mask(p: &Photo) -> Vec<bool> {
    let (w, h) = (p.width as usize, p.height as usize);
    if w < 3 || h < 3 {
        return vec![false; w * h];
    }
    let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round();
    let neighbours = |x: usize, y: usize| {
        let mut out = [(0usize, 0usize); 8];
        let mut k = 0;
        for yy in y.saturating_sub(1)..(y + 2).min(h) {
            for xx in x.saturating_sub(1)..(x + 2).min(w) {
                if (xx, yy) != (x, y) {
                    out[k] = (xx, yy);
                    k += 1;
                }
            }
        }
        (out, k)
    };
    let mut speck = vec![false; w * h];
    let interior = |x: usize, y: usize| x > 0 && y > 0 && x + 1 < w && y + 1 < h;
    for c in 0..3 {
        let v: Vec<f32> = p.pixels.iter().map(|px| q(px[c])).collect();
        let mut diff = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let i = y * w + x;
                let median = if interior(x, y) {
                    median_of_nine([
                        v[i - w - 1],
                        v[i - w],
                        v[i - w + 1],
                        v[i - 1],
                        v[i],
                        v[i + 1],
                        v[i + w - 1],
                        v[i + w],
                        v[i + w + 1],
                    ])
                } else {
                    let (nb, k) = neighbours(x, y);
                    let mut n = [0.0f32; 9];
                    n[0] = v[i];
                    for (j, &(xx, yy)) in nb[..k].iter().enumerate() {
                        n[j + 1] = v[yy * w + xx];
                    }
                    let n = &mut n[..=k];
                    n.sort_unstable_by(f32::total_cmp);
                    let m = n.len();
                    if m % 2 == 1 {
                        n[m / 2]
                    } else {
                        0.5 * (n[m / 2 - 1] + n[m / 2])
                    }
                };
                diff.push((v[i] - median).abs());
            }
        }
        let mid = diff.len() / 2;
        let (_, median, _) = diff.select_nth_unstable_by(mid, f32::total_cmp);
        let threshold = SPECK_DEVIATIONS * (1.4826 * *median).max(1.0);
        for y in 1..h - 1 {
            for x in 1..w - 1 {
                let i = y * w + x;
                let here = v[i];
                let (mut above, mut below) = (0, 0);
                for j in [
                    i - w - 1,
                    i - w,
                    i - w + 1,
                    i - 1,
                    i + 1,
                    i + w - 1,
                    i + w,
                    i + w + 1,
                ] {
                    let d = here - v[j];
                    above += (d > threshold) as usize;
                    below += (d < -threshold) as usize;
                }
                // All 8 neighbours but at most one.
                speck[i] |= above >= 7 || below >= 7;
            }
        }
    }
    speck
}

/// The median of nine finite values by a fixed network of 19 compare-exchanges (the same value
/// as the fifth of them sorted): the speck measure takes one per pixel and channel, and the
/// final fit measures every render it adopts ([`crate::structure::FinalFit::speck_clean`]).
fn median_of_nine(mut p: [f32; 9]) -> f32 {
    let mut s = |a: usize, b: usize| {
        let (lo, hi) = (p[a].min(p[b]), p[a].max(p[b]));
        p[a] = lo;
        p[b] = hi;
    };
    for (a, b) in [
        (1, 2),
        (4, 5),
        (7, 8),
        (0, 1),
        (3, 4),
        (6, 7),
        (1, 2),
        (4, 5),
        (7, 8),
        (0, 3),
        (5, 8),
        (4, 7),
        (3, 6),
        (1, 4),
        (2, 5),
        (4, 7),
        (4, 2),
        (6, 4),
        (4, 2),
    ] {
        s(a, b);
    }
    p[4]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng;

    /// The network's median is the sorted fifth on every arrangement of ties and distinct
    /// quantised values.
    #[test]
    fn the_median_of_nine_is_the_sorted_fifth() {
        for case in 0..20_000u32 {
            let levels = [2.0, 5.0, 255.0][case as usize % 3];
            let p: [f32; 9] =
                std::array::from_fn(|k| (rng::uniform(case, 3, k as u32) as f32 * levels).floor());
            let mut sorted = p;
            sorted.sort_unstable_by(f32::total_cmp);
            assert_eq!(median_of_nine(p), sorted[4], "{p:?}");
        }
    }

    /// Specks are the pixels planted far from their neighbourhood, whatever the texture's own
    /// fine variation; a smooth ramp and an image of bounded (uniform) grain have none.
    #[test]
    fn speck_fraction_counts_isolated_outliers() {
        let (w, h) = (64u32, 48u32);
        let grain = |x: u32, y: u32| 0.47 + 0.06 * rng::uniform(3, 9, y * w + x) as f32;
        let mut p = Photo {
            width: w,
            height: h,
            pixels: (0..h)
                .flat_map(|y| (0..w).map(move |x| [grain(x, y), 0.4, 0.3]))
                .collect(),
        };
        assert_eq!(speck_fraction(&p), 0.0);
        let ramp = Photo {
            width: w,
            height: h,
            pixels: (0..w * h)
                .map(|i| [(i % w) as f32 / w as f32, 0.2, 0.9])
                .collect(),
        };
        assert_eq!(speck_fraction(&ramp), 0.0);
        // Lines one pixel wide (joints) on a flat image are not specks.
        let mut lines = ramp.clone();
        for (i, px) in lines.pixels.iter_mut().enumerate() {
            let (x, y) = (i as u32 % w, i as u32 / w);
            *px = if x % 9 == 4 || y % 7 == 3 {
                [0.1, 0.1, 0.1]
            } else {
                [0.6, 0.3, 0.2]
            };
        }
        assert_eq!(speck_fraction(&lines), 0.0);
        // Twelve pixels, apart from each other, a bright blue speck each.
        for k in 0..12u32 {
            let (x, y) = (3 + 5 * k, 4 + 3 * k);
            p.pixels[(y * w + x) as usize] = [0.5, 0.4, 1.0];
        }
        assert_eq!(speck_fraction(&p), 12.0 / (w * h) as f64);
    }
}
