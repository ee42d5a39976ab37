//! Long straight lines in a map: the joints of brick, ashlar and panels, the edges of boards,
//! found by line integrals (a discrete Radon transform) of a detrended, standardised map.
//!
//! Why line integrals: grain averages out along a line of `L` pixels (the mean of `L`
//! independent unit values has deviation `1/√L`) and a joint does not, so a faint joint in a
//! grainy stone stands out where energies averaged over the patch (the Gabor descriptor) see
//! mostly grain. Each line's mean is scaled by `√L` (white noise: unit deviation at any
//! length), each angle's profile across offsets is high-passed (a thin joint stays, shading and
//! broad stripes go), and the strongest line is expressed in robust deviations of all lines
//! (the median absolute value over every scored line, as 1.4826·MAD): grain that is correlated
//! over a few pixels inflates every line alike and cancels out.
//!
//! On the development set's patches (128² maps) the strongest line measures 3.7–9.0 deviations
//! on 26 of its 27 stochastic photos (rippled sand: 12.7–14.0) and 10.8–129 on its walls,
//! boards and panels; cracks, pebbles and rubble walls (4.3–11.4) lie with the stochastic
//! photos: their edges are not straight over a patch (docs/devset.md, "Long straight lines").

use crate::gabor::SIZE;

/// Angles over 180°, 1° apart: a line across the whole map moves by about one pixel at its
/// ends between neighbouring angles, within the profile's high-pass width.
const ANGLES: usize = 180;
/// Lines shorter than this inside the map are not scored: near the corners a line is too
/// short for grain to average out.
const MIN_LENGTH: usize = 64;
/// σ in pixels, across the lines, of the smoothing subtracted from each angle's profile.
const PROFILE_SIGMA: f32 = 3.0;
/// How far from the exact perpendicular (in angle steps, each way) the crossing lines are
/// looked for: a photographed lattice is rarely square to a degree.
const PERPENDICULAR_SLACK: usize = 3;

/// The straight lines of a [`SIZE`]² map (zero mean, unit deviation, shading removed):
/// `(strength, crossing)`: the strongest line in robust deviations of all lines (about 4–5 for
/// Gaussian noise), and the strongest line within a few degrees of its perpendicular as a
/// share of it (near 0: one direction, as boards and strata; near 1: a grid).
/// A flat map gives `(0, 0)`.
pub fn straight_lines(map: &[f32]) -> (f32, f32) {
    assert_eq!(map.len(), SIZE * SIZE, "straight_lines takes a SIZE² map");
    // Each angle independent: in parallel on native, in order either way.
    let angles: Vec<usize> = (0..ANGLES).collect();
    let profiles: Vec<Vec<f32>> =
        crate::parallel::map_in_order(&angles, |&a| high_passed(&profile(map, a)));
    let mut magnitudes: Vec<f32> = profiles
        .iter()
        .flatten()
        .filter(|v| !v.is_nan())
        .map(|v| v.abs())
        .collect();
    if magnitudes.is_empty() {
        return (0.0, 0.0);
    }
    let mid = magnitudes.len() / 2;
    let median = *magnitudes.select_nth_unstable_by(mid, f32::total_cmp).1;
    let deviation = 1.4826 * median;
    if deviation <= 1e-9 {
        return (0.0, 0.0);
    }
    let strength: Vec<f32> = profiles
        .iter()
        .map(|p| {
            p.iter()
                .filter(|v| !v.is_nan())
                .fold(0.0f32, |m, v| m.max(v.abs()))
                / deviation
        })
        .collect();
    let strongest = (0..ANGLES)
        .max_by(|&x, &y| strength[x].total_cmp(&strength[y]))
        .expect("ANGLES > 0");
    let crossing = (0..=2 * PERPENDICULAR_SLACK)
        .map(|d| strength[(strongest + ANGLES / 2 + ANGLES + d - PERPENDICULAR_SLACK) % ANGLES])
        .fold(0.0f32, f32::max);
    let top = strength[strongest];
    (top, if top > 0.0 { crossing / top } else { 0.0 })
}

/// The scaled line means `mean·√L` of angle index `a` at every whole offset from the centre
/// (NaN where the line is shorter than [`MIN_LENGTH`]), bilinear samples one pixel apart.
fn profile(map: &[f32], a: usize) -> Vec<f32> {
    let n = SIZE as f32;
    // The centre on a pixel, so that the axis-aligned lines (joints of square-on walls) run
    // along pixel rows and columns instead of being split between two.
    let c = (SIZE / 2) as f32;
    let half = (n * std::f32::consts::SQRT_2 / 2.0).ceil() as i32;
    let th = std::f32::consts::PI * a as f32 / ANGLES as f32;
    let (dx, dy) = (th.cos(), th.sin());
    (-half..=half)
        .map(|r| {
            // The line through the centre's offset point along the normal (−dy, dx).
            let (ox, oy) = (c - dy * r as f32, c + dx * r as f32);
            let (mut sum, mut len) = (0.0f32, 0usize);
            // The steps inside the map, found analytically and widened by one each way (the
            // test below decides, as before: the same sum, without visiting the steps that
            // fall far outside).
            let (lo, hi) = inside(ox, dx, n).intersect(inside(oy, dy, n));
            let lo = (lo.floor() as i32).saturating_sub(1).max(-half);
            let hi = (hi.ceil() as i32).saturating_add(1).min(half);
            for t in lo..=hi {
                let (x, y) = (ox + dx * t as f32, oy + dy * t as f32);
                if x < 0.0 || y < 0.0 || x > n - 1.0 || y > n - 1.0 {
                    continue;
                }
                sum += bilinear(map, x, y);
                len += 1;
            }
            if len < MIN_LENGTH {
                f32::NAN
            } else {
                sum / (len as f32).sqrt()
            }
        })
        .collect()
}

/// The steps `t` (as a real interval) where `o + d·t` lies in `[0, n − 1]`; all of them where
/// `d` is (nearly) zero.
fn inside(o: f32, d: f32, n: f32) -> Interval {
    if d.abs() < 1e-6 {
        return Interval(f32::NEG_INFINITY, f32::INFINITY);
    }
    let (a, b) = ((0.0 - o) / d, (n - 1.0 - o) / d);
    Interval(a.min(b), a.max(b))
}

/// A closed real interval.
#[derive(Clone, Copy)]
struct Interval(f32, f32);

impl Interval {
    /// The common part of both intervals, as `(low, high)` (empty: low > high).
    fn intersect(self, other: Interval) -> (f32, f32) {
        (self.0.max(other.0), self.1.min(other.1))
    }
}

fn bilinear(map: &[f32], x: f32, y: f32) -> f32 {
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(SIZE - 1), (y0 + 1).min(SIZE - 1));
    let (fx, fy) = (x - x0 as f32, y - y0 as f32);
    let row = |y: usize| map[y * SIZE + x0] * (1.0 - fx) + map[y * SIZE + x1] * fx;
    row(y0) * (1.0 - fy) + row(y1) * fy
}

/// A profile minus its Gaussian smoothing across offsets (NaNs left out of the smoothing).
fn high_passed(profile: &[f32]) -> Vec<f32> {
    let r = (3.0 * PROFILE_SIGMA).ceil() as i64;
    let len = profile.len() as i64;
    (0..len)
        .map(|i| {
            let v = profile[i as usize];
            if v.is_nan() {
                return f32::NAN;
            }
            let (mut s, mut w) = (0.0f32, 0.0f32);
            for j in -r..=r {
                let k = i + j;
                if k < 0 || k >= len || profile[k as usize].is_nan() {
                    continue;
                }
                let g = (-((j * j) as f32) / (2.0 * PROFILE_SIGMA * PROFILE_SIGMA)).exp();
                s += g * profile[k as usize];
                w += g;
            }
            v - s / w
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f` over the map, then standardised.
    fn map(f: impl Fn(usize, usize) -> f32) -> Vec<f32> {
        let v: Vec<f32> = (0..SIZE * SIZE).map(|i| f(i % SIZE, i / SIZE)).collect();
        let m = v.iter().sum::<f32>() / v.len() as f32;
        let sd = (v.iter().map(|x| (x - m) * (x - m)).sum::<f32>() / v.len() as f32).sqrt();
        v.iter().map(|x| (x - m) / sd).collect()
    }

    fn grain(x: usize, y: usize) -> f32 {
        crate::rng::uniform(7, 0, (y * SIZE + x) as u32) as f32 - 0.5
    }

    #[test]
    fn grain_has_no_strong_line_and_a_faint_joint_in_grain_does() {
        let (noise, _) = straight_lines(&map(grain));
        assert!((3.0..7.0).contains(&noise), "grain alone: {noise}");
        // A dark joint a pixel wide, as deep as the grain's deviation: invisible pixel by pixel.
        let (joint, crossing) =
            straight_lines(&map(|x, y| grain(x, y) - 0.29 * (y == 60) as u8 as f32));
        assert!(joint > 2.0 * noise, "joint {joint} against grain {noise}");
        assert!(crossing < 0.6, "one direction: {crossing}");
    }

    #[test]
    fn a_grid_crosses_itself_and_a_running_bond_less() {
        let grid = map(|x, y| grain(x, y) - ((x % 32 == 0) || (y % 16 == 0)) as u8 as f32);
        let (g, g_cross) = straight_lines(&grid);
        assert!(g > 10.0 && g_cross > 0.7, "grid: {g}, {g_cross}");
        // Head joints that move half a brick every row: no vertical line crosses the map.
        let bond = map(|x, y| {
            let shift = if (y / 16) % 2 == 1 { 16 } else { 0 };
            grain(x, y) - (((x + shift) % 32 == 0) || (y % 16 == 0)) as u8 as f32
        });
        let (b, b_cross) = straight_lines(&bond);
        assert!(b > 10.0 && b_cross < g_cross, "bond: {b}, {b_cross}");
    }

    #[test]
    fn a_flat_map_gives_zeros() {
        assert_eq!(straight_lines(&vec![0.0; SIZE * SIZE]), (0.0, 0.0));
    }
}
