//! Specks: isolated outlier pixels, counted so that a render can be held to the photo's own
//! (the development-set yardstick compares the two, `crate::devset::speck_ratio`).

use crate::input::Photo;

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
    for c in 0..3 {
        let v: Vec<f32> = p.pixels.iter().map(|px| q(px[c])).collect();
        let mut diff = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let (nb, k) = neighbours(x, y);
                let mut n = [0.0f32; 9];
                n[0] = v[y * w + x];
                for (i, &(xx, yy)) in nb[..k].iter().enumerate() {
                    n[i + 1] = v[yy * w + xx];
                }
                let n = &mut n[..=k];
                n.sort_unstable_by(f32::total_cmp);
                let m = n.len();
                let median = if m % 2 == 1 {
                    n[m / 2]
                } else {
                    0.5 * (n[m / 2 - 1] + n[m / 2])
                };
                diff.push((v[y * w + x] - median).abs());
            }
        }
        diff.sort_unstable_by(f32::total_cmp);
        let threshold = SPECK_DEVIATIONS * (1.4826 * diff[diff.len() / 2]).max(1.0);
        for y in 1..h - 1 {
            for x in 1..w - 1 {
                let here = v[y * w + x];
                let (nb, k) = neighbours(x, y);
                let (mut above, mut below) = (0, 0);
                for &(xx, yy) in &nb[..k] {
                    let d = here - v[yy * w + xx];
                    above += (d > threshold) as usize;
                    below += (d < -threshold) as usize;
                }
                speck[y * w + x] |= above + 1 >= k || below + 1 >= k;
            }
        }
    }
    speck
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng;

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
