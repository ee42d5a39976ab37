//! The final fit's last step (ours): the render's fine grain raised to the photo's. The
//! ranking's previews of the fitted families (the rows' thumbnails) take the same step on the
//! reduced photo after their scores ([`match_grain_to`], from `retrieve::Suggester`).
//!
//! Why: a structured render spends its finest octaves on the pattern's edges (joints, crests,
//! plank ends), so its power spectrum, a mean over pixels, matches the photo's while its
//! typical pixel, inside a brick or a board, is smoother than the photo's: the rank pairing
//! gives the photo's grain along its tone line to the ramp ([`super`], step 1), and step 6's
//! residual amplitudes are chosen by distances that the edges dominate. Against a smooth face
//! every edge pixel that a corner or a broken joint leaves alone stands out; against the
//! photo's grain it does not. The photo's grain is measured as the speck measure scales it
//! ([`crate::specks`]): the robust deviation of each pixel from its 3×3 median, the median
//! pixel's, not the mean's. The residual's finest band drawn after the histogram
//! ([`crate::params::NoiseModel::fine`], bounded) along the tone line is raised until the
//! render's deviation reaches the photo's; a render as grainy as the photo or grainier is left
//! as it is.
//!
//! Measured (docs/devset.md, "The render's grain matched to the photo's"; `proctex fidelity`,
//! every quadrant): chosen renders within 1.5× their photo's specks on the development set 203 →
//! 205 of 208 at seed 1 (204 → 205 at seeds 2 and 3), on 183 textures never tuned on 685 → 705
//! of 732, the shipped samples 71 → 77 of 80; every choice the same; the structured photos'
//! fidelity paired ln(new / before) −0.004 ± 0.002 on the development set.

use crate::input::Photo;
use crate::params::{Model, Params};
use crate::render::{View, render};

/// Renders [`match_grain`] may make beyond the first (the secant steps).
const GRAIN_STEPS: usize = 2;

/// Largest side of the window that [`match_grain`] renders (the render's top-left corner at the
/// photo's scale; the photo's deviation is taken over the whole photo): a median over 256² pixels
/// is as steady as over the whole, at a quarter of the cost on the app's 512² analysis.
const GRAIN_WINDOW: u32 = 256;

/// Largest amplitude [`match_grain`] gives the finest band's part (the residual's own bound,
/// `structure::scale_residual`'s, is 4; no photo's grain asks for a tenth of it).
const MAX_FINE: f32 = 1.0;

/// The fine deviation of an image (`w` × `h` RGB pixels in 0–1), in 8-bit quanta: per channel
/// 1.4826 × the median over the inner pixels of their absolute difference from their 3×3
/// neighbourhood's median (the standard deviation, were those differences Gaussian), the mean
/// over the three channels. The speck measure's scale ([`crate::specks::speck_fraction`]),
/// without its quantisation, so that it moves smoothly with the grain.
pub fn fine_deviation(pixels: &[[f32; 3]], w: usize, h: usize) -> f64 {
    if w < 3 || h < 3 || pixels.len() < w * h {
        return 0.0;
    }
    let mut total = 0.0;
    let mut diff = Vec::with_capacity((w - 2) * (h - 2));
    for c in 0..3 {
        diff.clear();
        for y in 1..h - 1 {
            for x in 1..w - 1 {
                let mut n = [0.0f32; 9];
                for (k, v) in n.iter_mut().enumerate() {
                    *v = pixels[(y + k / 3 - 1) * w + x + k % 3 - 1][c];
                }
                n.sort_unstable_by(f32::total_cmp);
                diff.push((pixels[y * w + x][c] - n[4]).abs());
            }
        }
        let mid = diff.len() / 2;
        let (_, m, _) = diff.select_nth_unstable_by(mid, f32::total_cmp);
        total += 1.4826 * 255.0 * *m as f64;
    }
    total / 3.0
}

/// Raises structured `params`' finest band's part along the tone line
/// ([`crate::params::NoiseModel::fine`], channel 0) until its render of the user's seed at
/// `photo`'s scale (its top-left [`GRAIN_WINDOW`]² at most) has `photo`'s [`fine_deviation`]
/// (see the module docs); nothing when the render already has it, or for another model.
///
/// The deviation is taken to add in quadrature (`d² = a + b·v²`, `v` the amplitude): from the
/// render as it is, then one at twice the amplitude, the secant in `(v², d²)` gives the next
/// amplitude, rendered once more to correct the line, and the last secant's amplitude is kept
/// ([`GRAIN_STEPS`]: at most three renders). Deterministic: the same photo and params give the
/// same amplitude.
pub fn match_grain(photo: &Photo, params: &mut Params) {
    let target = fine_deviation(&photo.pixels, photo.width as usize, photo.height as usize);
    match_grain_to(
        target,
        photo.width,
        photo.height,
        GRAIN_WINDOW,
        None,
        params,
    );
}

/// [`match_grain`] with the photo given by its [`fine_deviation`] (`target`) and its size, the
/// renders' top-left corner at most `window` pixels a side: for a caller that matches several
/// params to one photo and measures it once. `first`: the deviation of `params`' own render in
/// that window where the caller measured it already (`None`: rendered here).
pub fn match_grain_to(
    target: f64,
    width: u32,
    height: u32,
    window: u32,
    first: Option<f64>,
    params: &mut Params,
) {
    let Model::Structured(m) = &params.model else {
        return;
    };
    let (w, h) = (width.min(window), height.min(window));
    let deviation = |p: &Params| {
        let img = render(p, w, h, &View::default());
        fine_deviation(&img.pixels, w as usize, h as usize)
    };
    let d0 = first.unwrap_or_else(|| deviation(params));
    if d0 >= target || target <= 0.0 {
        return;
    }
    let with = |v: f32| {
        let mut p = params.clone();
        if let Model::Structured(m) = &mut p.model {
            m.residual.fine[0] = v;
        }
        p
    };
    let v0 = m.residual.fine[0].max(0.0);
    let mut a = (v0 as f64, d0);
    let mut v = (2.0 * v0).clamp(1e-3, MAX_FINE);
    for _ in 0..GRAIN_STEPS {
        let b = (v as f64, deviation(&with(v)));
        let slope = (b.1 * b.1 - a.1 * a.1) / (b.0 * b.0 - a.0 * a.0);
        let next = if slope.is_finite() && slope > 0.0 {
            (b.0 * b.0 + (target * target - b.1 * b.1) / slope)
                .max(0.0)
                .sqrt()
        } else {
            2.0 * b.0
        };
        // Never below the model's own amplitude.
        a = b;
        v = (next as f32).clamp(v0, MAX_FINE);
    }
    *params = with(v);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::pattern_shell;
    use crate::pattern::{Pattern, PatternKind};
    use crate::render::{View, render};

    fn grain(pixels: &mut [[f32; 3]], sd: f32, stream: u32) {
        for (i, px) in pixels.iter_mut().enumerate() {
            let g = sd * crate::rng::gaussian(stream, 0, i as u32) as f32;
            *px = px.map(|v| v + g);
        }
    }

    /// The deviation is the median pixel's: 0 on a flat image and on a smooth ramp, twice as
    /// large for grain twice as strong, and blind to a few lone outliers.
    #[test]
    fn the_fine_deviation_is_the_typical_pixels_grain() {
        let (w, h) = (64, 48);
        let flat = vec![[0.4f32, 0.5, 0.6]; w * h];
        assert_eq!(fine_deviation(&flat, w, h), 0.0);
        let ramp: Vec<[f32; 3]> = (0..w * h).map(|i| [(i % w) as f32 / w as f32; 3]).collect();
        assert!(fine_deviation(&ramp, w, h) < 1e-3);
        let mut one = flat.clone();
        grain(&mut one, 0.02, 3);
        let mut two = flat.clone();
        grain(&mut two, 0.04, 3);
        let (d1, d2) = (fine_deviation(&one, w, h), fine_deviation(&two, w, h));
        assert!(d1 > 1.0 && (d2 / d1 - 2.0).abs() < 0.01, "{d1} {d2}");
        let mut specks = one.clone();
        for i in (0..w * h).step_by(97) {
            specks[i] = [1.0; 3];
        }
        assert!((fine_deviation(&specks, w, h) / d1 - 1.0).abs() < 0.05);
    }

    /// The window [`match_grain`] renders is the top-left corner of the render at the photo's
    /// size, pixel for pixel.
    #[test]
    fn the_grain_window_is_the_renders_corner() {
        let p = pattern_shell(Pattern::new(PatternKind::Brick, 10.0), 2, false);
        let full = render(&p, 300, 280, &View::default());
        let window = render(&p, GRAIN_WINDOW, GRAIN_WINDOW, &View::default());
        let side = GRAIN_WINDOW as usize;
        for y in 0..side {
            for x in 0..side {
                assert_eq!(window.pixels[y * side + x], full.pixels[y * 300 + x]);
            }
        }
    }

    /// A smooth render of a grainy photo gets the photo's grain; a render as grainy as its
    /// photo, and a noise model, are left as they are; the same inputs give the same params.
    #[test]
    fn a_smooth_render_gets_the_photos_grain_and_no_more() {
        let pattern = Pattern::new(PatternKind::Cells, 12.0);
        let mut p = pattern_shell(pattern, 2, false);
        if let Model::Structured(m) = &mut p.model {
            m.ramp[0].rgb = [0.3; 3];
            m.ramp[1].rgb = [0.6; 3];
        }
        let (w, h) = (96, 96);
        let mut photo = render(&p, w, h, &View::default()).to_photo();
        grain(&mut photo.pixels, 0.03, 7);
        let target = fine_deviation(&photo.pixels, w as usize, h as usize);
        let deviation = |p: &Params| {
            let img = render(p, w, h, &View::default()).to_photo();
            fine_deviation(&img.pixels, w as usize, h as usize)
        };
        assert!(deviation(&p) < 0.5 * target);
        let mut matched = p.clone();
        match_grain(&photo, &mut matched);
        let d = deviation(&matched);
        assert!(
            (d / target - 1.0).abs() < 0.1,
            "{d} against the photo's {target}"
        );
        let mut again = p.clone();
        match_grain(&photo, &mut again);
        assert_eq!(again, matched);
        // Already as grainy: unchanged.
        let mut grainy = matched.clone();
        if let Model::Structured(m) = &mut grainy.model {
            m.residual.fine[0] *= 1.5;
        }
        let before = grainy.clone();
        match_grain(&photo, &mut grainy);
        assert_eq!(grainy, before);
        let mut noise = crate::analyze::hash_noise_params(64, 3);
        let before = noise.clone();
        match_grain(&photo, &mut noise);
        assert_eq!(noise, before);
    }
}
