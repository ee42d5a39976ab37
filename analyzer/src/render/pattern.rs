//! The structured models' per-pixel functions: a pattern's structure value at a point and
//! the colour ramp, the twins of `shaders/pattern.wgsl` (same names, same operation order in
//! f32). They read the pattern's place in the prepared uniform block ([`Prepared`]), which is
//! why they live with the renderer; the families, their values and ranges are
//! [`crate::pattern`]'s.

use crate::noise::{
    Tile, band_fade, noise2_first, noise2_periodic_first, noise3_first, whole_period,
};
use crate::pattern::{OCTAVES, Pattern};
use crate::rng;

use super::Prepared;

/// A smooth step from 0 at `e0` to 1 at `e0 + w` (`w > 0`): the soft edge of joints.
#[inline]
pub fn soft_step(e0: f32, w: f32, x: f32) -> f32 {
    let t = ((x - e0) / w).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// A uniform number in (0, 1) for cell `(ix, iy)` and use `k`: the cell patterns' randomness.
#[inline]
pub fn cell_hash(prep: &Prepared, ix: i32, iy: i32, k: u32) -> f32 {
    let index = (ix as u32).wrapping_mul(0x8da6_b343) ^ (iy as u32).wrapping_mul(0xd816_3841) ^ k;
    rng::uniform(prep.pattern[2], rng::stream::CELLS, index) as f32
}

/// How far apart (in noise units) cells' `warp` reads its two displacement noises.
pub const WARP_OFFSET: f32 = 19.3;

/// Cell index `i` wrapped at `n` cells (a seamless tile's lattice, see [`pattern_at`]); `i`
/// itself for `n = 0` (the infinite texture).
#[inline]
pub fn wrap_cell(i: i32, n: i32) -> i32 {
    if n > 0 { i.rem_euclid(n) } else { i }
}

/// The whole number of cells of width `pitch` (and rows of height 1) that the periods `wrap`
/// of [`pattern_at`] hold; `[0, 0]` (no wrap) for `wrap[0] = 0`.
#[inline]
pub fn wrap_cells(pitch: f32, wrap: [f32; 2]) -> [i32; 2] {
    if wrap[0] > 0.0 {
        [
            (wrap[0] / pitch + 0.5).floor() as i32,
            (wrap[1] + 0.5).floor() as i32,
        ]
    } else {
        [0, 0]
    }
}

/// [`cell_hash`] of cell `(ix, iy)` of a lattice that wraps at `cells` (0: does not).
#[inline]
pub fn cell_hash_wrapped(prep: &Prepared, ix: i32, iy: i32, k: u32, cells: [i32; 2]) -> f32 {
    cell_hash(prep, wrap_cell(ix, cells[0]), wrap_cell(iy, cells[1]), k)
}

/// The lower edge of row `k` of planks: `k + widths·(h(k) − ½)`, `h` the row's hash (wrapped
/// at `rows`, 0: not), so that with `widths` ≤ ½ (the searched range) each edge stays within ¼
/// of its integer and rows are ½–1½ units wide; at 1 (the range's end) within ½, rows 0–2
/// units wide, edges never crossing.
///
/// Ours: the planks of a real floor or wall are seldom of one width (old wood's vary about
/// 2:1), and rows of equal width put the pattern's power into the harmonics of one period,
/// quarter-octave rings of the spectrum ±3 dB around the photo's (old wood, 128² patches).
#[inline]
pub fn plank_edge(prep: &Prepared, k: i32, widths: f32, rows: i32) -> f32 {
    k as f32 + widths * (cell_hash_wrapped(prep, 0, k, 2, [0, rows]) - 0.5)
}

/// The row of planks (see [`plank_edge`]) that `y` falls in and its lower and upper edges:
/// `[row, lower, upper]` (the row as a float, as the shader returns it).
#[inline]
pub fn plank_row(prep: &Prepared, y: f32, widths: f32, rows: i32) -> [f32; 3] {
    let k = y.floor() as i32;
    let lo = plank_edge(prep, k, widths, rows);
    let hi = plank_edge(prep, k + 1, widths, rows);
    if y < lo {
        [(k - 1) as f32, plank_edge(prep, k - 1, widths, rows), lo]
    } else if y >= hi {
        [(k + 1) as f32, hi, plank_edge(prep, k + 2, widths, rows)]
    } else {
        [k as f32, lo, hi]
    }
}

/// Noise octave `k` (frequency `2^k` per pattern unit) at pattern point `q`. With `per[0] > 0`
/// (a seamless tile; plane textures only) `q` repeats with period `per` per axis, and the
/// octave is made to repeat with it: its frequency is moved to the nearest whole number of
/// noise coefficients over the period ([`whole_period`]), as the seamless tile does with the
/// noise model's bands.
#[inline]
pub fn octave(prep: &Prepared, tile: &Tile, q: [f32; 3], k: usize, per: [f32; 2]) -> f32 {
    let f = (1u32 << k) as f32;
    let o = prep.pattern_offsets[k];
    if prep.solid {
        noise3_first(
            &tile.data,
            tile.n,
            [q[0] * f + o[0], q[1] * f + o[1], q[2] * f + o[2]],
        )
    } else if per[0] > 0.0 {
        let n = tile.n as f32;
        let m = [whole_period(per[0] * f, n), whole_period(per[1] * f, n)];
        noise2_periodic_first(
            &tile.data,
            tile.n,
            [q[0] / per[0] * m[0] + o[0], q[1] / per[1] * m[1] + o[1]],
            m,
        )
    } else {
        noise2_first(&tile.data, tile.n, [q[0] * f + o[0], q[1] * f + o[1]])
    }
}

/// A ridged octave's crest `exp(−sharpness·|n|)` as a pixel shows it, `g` the noise's change
/// across the pixel ([`pixel_change`] of the octave one pixel along each axis, as
/// [`ridged_octaves`] measures it):
/// - The sharpness is at most `2 / g`: a crest is at least one pixel wide (at `1/e`).
/// - The crest is averaged over `n ± g/2` (the noise taken as linear across the pixel; the
///   antiderivative of `exp(−s·|x|)` is `sign(x)·(1 − exp(−s·|x|)) / s`).
///
/// Why: a fine octave's crest is a tenth of a pixel wide or less; sampled at the pixel centre
/// it drew a dotted line at full contrast, isolated dark pixels that photos of cracks do not
/// have (17 of the development set's 24 chosen renders over the speck limit were ridged).
/// Measured on the development set (`proctex fidelity`, every quadrant; docs/devset.md):
/// speck-clean chosen renders 184 → 198 of 208 with both, 188 with the floor alone, 188 with
/// the average alone; 4 folds by photo all chose both (held out 198), structured labelled
/// 69 → 68. The average alone makes fine crests faint, the floor alone leaves them dotted at
/// `1/e`. On 67 structured textures never tuned on: speck-clean 215 → 227 of 268 quadrants,
/// labelled 168 → 161 (antialiased crests come nearer to some stone floors than cells do).
///
/// The change where the pixel is, not the octaves' mean gradient (2.2 per noise coefficient,
/// which the first version used): where the noise crosses 0 steeply a crest was still narrower
/// than the pixel, and drawn dotted. Ridged's own renders over the speck limit 51 → 20 of 208,
/// every fitted render within it 1376 → 1408 of 2080; 4 folds by photo all chose the local
/// change; structured labelled 68 → 68 (docs/devset.md, "Ridged's crests over the noise's
/// change where the pixel is"). On the 67 textures never tuned on: speck-clean chosen renders
/// 229 → 235 of 268, ridged's own over the limit 114 → 62.
#[inline]
pub fn crest(n: f32, sharpness: f32, g: f32) -> f32 {
    let s = sharpness.min(2.0 / g.max(1e-6));
    let h = 0.5 * g;
    if s * h < 1e-3 {
        // A pixel much finer than the crest: its centre's value (and no cancellation).
        return (-s * n.abs()).exp();
    }
    let antiderivative = |x: f32| x.signum() * (1.0 - (-s * x.abs()).exp()) / s;
    (antiderivative(n + h) - antiderivative(n - h)) / (2.0 * h)
}

/// The lines' profile `(½ + ½·sin 2πv)^sharpness` (wood lines, rings; a line's peak where `v`
/// is a whole number plus ¼) as a pixel shows it, `g` the change of `v` across the pixel
/// ([`pixel_change`]):
/// - The sharpness is at most `4 / (π·g)²`: near a peak the profile is about
///   `exp(−sharpness·π²·δ²)`, so a line is at least one pixel wide at `1/e`.
/// - The profile is averaged over `v ± g/2` (`v` taken as linear across the pixel) by the
///   midpoint rule on four points (it has no closed-form integral).
///
/// Why: as [`crest`]'s, a line finer than the pixel, sampled at the pixel's centre, draws a
/// dotted line of isolated pixels (the refinement takes sharpnesses up to 8, and the noise's
/// distortion crowds the lines, which is why `g` is measured where the pixel is). Measured on
/// the development set (`proctex fidelity`, every quadrant; docs/devset.md, "Wood lines and rings
/// averaged over the pixel"): wood lines' own renders over the speck limit 144 → 98 of 208,
/// rings' 142 → 93, every fitted render within it 1271 → 1376 of 2080; 4 folds by photo all
/// chose the local change with the bound and the average (the change from the octaves' mean
/// gradient instead: 1307; the average alone: 1370); structured labelled 68 → 68.
#[inline]
pub fn line_profile(v: f32, sharpness: f32, g: f32) -> f32 {
    let g = g.max(1e-6);
    let s = sharpness.min(4.0 / (std::f32::consts::PI * std::f32::consts::PI * g * g));
    let at = |v: f32| {
        (0.5 + 0.5 * (std::f32::consts::TAU * v).sin())
            .max(1e-6)
            .powf(s)
    };
    if g < 1e-4 {
        // A pixel much finer than the lines: its centre's value.
        return at(v);
    }
    0.25 * (at(v - 0.375 * g) + at(v - 0.125 * g) + at(v + 0.125 * g) + at(v + 0.375 * g))
}

/// How much a coordinate changes across a pixel: `at` its value at the pixel's centre, `ax`
/// and `ay` one pixel footprint further along the pattern's axes (forward differences).
#[inline]
pub fn pixel_change(at: f32, ax: f32, ay: f32) -> f32 {
    let (dx, dy) = (ax - at, ay - at);
    (dx * dx + dy * dy).sqrt()
}

/// The wood lines' coordinate at pattern point `q` (lines one pattern unit apart, [`line_profile`]
/// draws them): `q`'s second axis displaced by `distortion` times fractal noise of a quarter of
/// the lines' frequency, stretched along the first axis. `lfp` as [`pattern_at`]'s, `per` the
/// noise's period (see [`octave`]).
#[inline]
pub fn wood_line_coordinate(
    prep: &Prepared,
    tile: &Tile,
    q: [f32; 3],
    lfp: f32,
    per: [f32; 2],
) -> f32 {
    let w = prep.pattern_values;
    let n = octaves(
        prep,
        tile,
        [0.25 * q[0] / w[0], 0.25 * q[1], 0.25 * q[2]],
        w[3],
        0,
        lfp - 2.0,
        per,
    );
    q[1] + w[1] * n
}

/// The rings' coordinate at point `p` (from their centre, the first axis divided by the
/// stretch): its distance to the centre displaced by `distortion` times fractal noise of a
/// quarter of the rings' frequency. `lfp` as [`pattern_at`]'s, `per` `p`'s period.
#[inline]
pub fn ring_coordinate(prep: &Prepared, tile: &Tile, p: [f32; 3], lfp: f32, per: [f32; 2]) -> f32 {
    let w = prep.pattern_values;
    let n = octaves(
        prep,
        tile,
        [0.25 * p[0], 0.25 * p[1], 0.25 * p[2]],
        w[2],
        0,
        lfp - 2.0,
        [0.25 * per[0], 0.25 * per[1]],
    );
    (p[0] * p[0] + p[1] * p[1]).sqrt() + w[0] * n
}

/// The octaves summed with amplitude ratio `gain`, each octave's noise `n` taken as `n`
/// (`mode` 0: fractal noise, unit variance when nothing is faded) or `|n|` (1: turbulence,
/// Perlin 1985, normalised by the amplitudes' sum). `lfp`: log2 of the pixel footprint in
/// pattern units (octaves fade out as [`band_fade`] fades bands). `per`: `q`'s period (see
/// [`octave`]). Ridged's octaves are [`ridged_octaves`].
#[inline]
pub fn octaves(
    prep: &Prepared,
    tile: &Tile,
    q: [f32; 3],
    gain: f32,
    mode: u32,
    lfp: f32,
    per: [f32; 2],
) -> f32 {
    let mut sum = 0.0f32;
    let mut norm = 0.0f32;
    let mut amp = 1.0f32;
    for k in 0..OCTAVES {
        let fade = band_fade(0, lfp + k as f32);
        if fade > 0.0 {
            let n = octave(prep, tile, q, k, per);
            sum += amp * fade * if mode == 0 { n } else { n.abs() };
        }
        norm += if mode == 0 { amp * amp } else { amp };
        amp *= gain;
    }
    if mode == 0 {
        sum / norm.sqrt()
    } else {
        sum / norm
    }
}

/// Ridged's octaves (Musgrave's ridged multifractal without its weighting): with amplitude
/// ratio `gain`, each octave's [`crest`] where its noise crosses 0, drawn over the noise's
/// change across the pixel where it is (forward differences one pixel, `pixel_step`, along the
/// pattern's axes, in `q`'s units), normalised by the amplitudes' sum. `lfp`, `per` as
/// [`octaves`]'.
#[allow(clippy::too_many_arguments)] // the twin of the WGSL function's argument list
#[inline]
pub fn ridged_octaves(
    prep: &Prepared,
    tile: &Tile,
    q: [f32; 3],
    pixel_step: [f32; 2],
    gain: f32,
    sharpness: f32,
    lfp: f32,
    per: [f32; 2],
) -> f32 {
    let mut sum = 0.0f32;
    let mut norm = 0.0f32;
    let mut amp = 1.0f32;
    for k in 0..OCTAVES {
        let fade = band_fade(0, lfp + k as f32);
        if fade > 0.0 {
            let n = octave(prep, tile, q, k, per);
            let nx = octave(prep, tile, [q[0] + pixel_step[0], q[1], q[2]], k, per);
            let ny = octave(prep, tile, [q[0], q[1] + pixel_step[1], q[2]], k, per);
            sum += amp * fade * crest(n, sharpness, pixel_change(n, nx, ny));
        }
        norm += amp;
        amp *= gain;
    }
    sum / norm
}

/// The two fractal noises (octaves of 4 cells and finer, the second read [`WARP_OFFSET`] noise
/// units away) that displace cells' lattice point `p` (in cells; `z` the solid texture's
/// depth), per unit of `warp`; `per` the lattice's period in noise units (see [`octave`]). The
/// WGSL and GLSL twins write it out inside `pattern_at`.
#[inline]
pub fn cells_warp_field(
    prep: &Prepared,
    tile: &Tile,
    p: [f32; 2],
    z: f32,
    lfp: f32,
    per: [f32; 2],
) -> [f32; 2] {
    let b = [0.25 * p[0], 0.25 * p[1], 0.25 * z];
    let gx = octaves(prep, tile, b, 0.5, 0, lfp - 2.0, per);
    let b2 = [b[0] + WARP_OFFSET, b[1], b[2]];
    let gy = octaves(prep, tile, b2, 0.5, 0, lfp - 2.0, per);
    [gx, gy]
}

/// Distance to the nearest joint of the unit cell that `x` (in cells) and `y` fall in, in
/// units of the cell's height (`aspect`: cell width / height).
#[inline]
pub fn joint_distance(fx: f32, fy: f32, aspect: f32) -> f32 {
    (fx.min(1.0 - fx) * aspect).min(fy.min(1.0 - fy))
}

/// The structure value of the pattern at texel `u` (pixel footprint `2^log2_fp` texels).
pub fn pattern(prep: &Prepared, tile: &Tile, u: [f32; 3], log2_fp: f32) -> f32 {
    let [is, c, s, log2_is] = prep.pattern_transform;
    let q = [
        (c * u[0] + s * u[1]) * is,
        (-s * u[0] + c * u[1]) * is,
        u[2] * is,
    ];
    pattern_at(prep, tile, q, log2_fp + log2_is, [0.0, 0.0])
}

/// The periods in pattern units, along the pattern's own axes, of a seamless tile whose side
/// spans `span` pattern units (see [`pattern_at`]): `span` moved to the nearest whole number
/// (at least 1) of the family's lattice pitch along each axis (rows of height 1; cells, bricks,
/// planks of width aspect, stretch or length; wood lines one per unit), `span` itself along an
/// axis with no lattice (the noise octaves round their own periods).
pub fn tile_periods(prep: &Prepared, span: f32) -> [f32; 2] {
    let w = prep.pattern_values;
    let whole = |pitch: f32| pitch * (span / pitch + 0.5).floor().max(1.0);
    match prep.pattern[0] {
        4 | 5 | 7 => [whole(w[0]), whole(1.0)],
        // Staggered cells close their bond over an even number of rows.
        6 if w[5] > 0.0 => [whole(w[4]), whole(2.0)],
        6 => [whole(w[4]), whole(1.0)],
        8 => [span, whole(1.0)],
        _ => [span, span],
    }
}

/// The structure value at pattern point `q` (`lfp`: log2 of the pixel footprint in pattern
/// units). `wrap` (0: none) makes it periodic, for a seamless tile (plane textures only): `q`
/// then repeats with period `wrap` along the pattern's axes ([`tile_periods`]), the lattice
/// families' cell indices wrap at the whole number of cells the period holds (cell hashes, row
/// shifts and jitter repeat with it; brick's row offset is moved to the nearest multiple of
/// 1 / rows so that the bond closes), the noise octaves repeat ([`octave`]), and rings take
/// the torus distance to their centre (nearest copy).
pub fn pattern_at(prep: &Prepared, tile: &Tile, q: [f32; 3], lfp: f32, wrap: [f32; 2]) -> f32 {
    let [_, c, s, _] = prep.pattern_transform;
    let w = prep.pattern_values;
    let soft = lfp.exp2();
    // The noise families' octaves along the pattern stretched by its first value.
    let per = [wrap[0] / w[0], wrap[1]];
    let stretched = [q[0] / w[0], q[1], q[2]];
    match prep.pattern[0] {
        // perlin: stretch, roughness, contrast, threshold
        1 => {
            let n = octaves(prep, tile, stretched, w[1], 0, lfp, per);
            1.0 / (1.0 + (-w[2] * (n - w[3])).exp())
        }
        // turbulence: stretch, roughness, contrast
        2 => {
            let t = octaves(prep, tile, stretched, w[1], 1, lfp, per);
            1.0 - (-w[2] * t).exp()
        }
        // ridged: stretch, roughness, sharpness
        3 => {
            let pixel_step = [soft / w[0], soft];
            ridged_octaves(prep, tile, stretched, pixel_step, w[1], w[2], lfp, per)
        }
        // grid: aspect, mortar, bevel, variation
        4 => {
            let n = wrap_cells(w[0], wrap);
            let x = q[0] / w[0];
            let (ix, iy) = (x.floor(), q[1].floor());
            let d = joint_distance(x - ix, q[1] - iy, w[0]);
            let shade = 1.0 - w[3] * cell_hash_wrapped(prep, ix as i32, iy as i32, 0, n);
            soft_step(0.5 * w[1], w[2].max(soft), d) * shade
        }
        // brick: aspect, mortar, row_offset, jitter, bevel, variation
        5 => {
            let n = wrap_cells(w[0], wrap);
            let iy = q[1].floor();
            let (row, offset) = if n[1] > 0 {
                let row = wrap_cell(iy as i32, n[1]);
                let rows = n[1] as f32;
                (row as f32, (w[2] * rows + 0.5).floor() / rows)
            } else {
                (iy, w[2])
            };
            let shift = row * offset + w[3] * (cell_hash(prep, 0, row as i32, 1) - 0.5);
            let x = q[0] / w[0] + shift;
            let ix = x.floor();
            let d = joint_distance(x - ix, q[1] - iy, w[0]);
            let shade = 1.0 - w[5] * cell_hash_wrapped(prep, ix as i32, iy as i32, 0, n);
            soft_step(0.5 * w[1], w[4].max(soft), d) * shade
        }
        // cells: jitter, mortar, bevel, variation, stretch, stagger, warp
        6 => {
            let n = wrap_cells(w[4], wrap);
            let mut p = [q[0] / w[4], q[1]];
            if w[6] > 0.0 {
                // Bent rows: the lattice displaced by `warp` × two fractal noises (octaves of
                // 4 cells and finer), the second read `WARP_OFFSET` noise units away.
                let per = [0.25 * wrap[0] / w[4], 0.25 * wrap[1]];
                let [gx, gy] = cells_warp_field(prep, tile, p, q[2], lfp, per);
                p = [p[0] + w[6] * gx, p[1] + w[6] * gy];
            }
            let iy = p[1].floor();
            let fy = p[1] - iy;
            let (mut f1, mut f2) = (1e9f32, 1e9f32);
            let mut id = [0i32; 2];
            for dy in -1..=1 {
                let cy = iy as i32 + dy;
                // Every other row (of the wrapped lattice) shifted by `stagger` half cells.
                let shift = 0.5 * w[5] * (wrap_cell(cy, n[1]).rem_euclid(2)) as f32;
                let x = p[0] - shift;
                let ix = x.floor();
                let fx = x - ix;
                for dx in -1..=1 {
                    let cx = ix as i32 + dx;
                    let px = dx as f32 + 0.5 + w[0] * (cell_hash_wrapped(prep, cx, cy, 0, n) - 0.5);
                    let py = dy as f32 + 0.5 + w[0] * (cell_hash_wrapped(prep, cx, cy, 1, n) - 0.5);
                    let (ex, ey) = (px - fx, py - fy);
                    let d = ex * ex + ey * ey;
                    if d < f1 {
                        f2 = f1;
                        f1 = d;
                        id = [cx, cy];
                    } else if d < f2 {
                        f2 = d;
                    }
                }
            }
            let edge = 0.5 * (f2.sqrt() - f1.sqrt());
            let shade = 1.0 - w[3] * cell_hash_wrapped(prep, id[0], id[1], 2, n);
            soft_step(0.5 * w[1], w[2].max(soft), edge) * shade
        }
        // planks: length, gap, bevel, variation, grain, widths
        7 => {
            let n = wrap_cells(w[0], wrap);
            let [row, lo, hi] = plank_row(prep, q[1], w[5], n[1]);
            let iy = row as i32;
            let x = q[0] / w[0] + cell_hash_wrapped(prep, 0, iy, 1, [0, n[1]]);
            let ix = x.floor();
            let fx = x - ix;
            let d = (fx.min(1.0 - fx) * w[0]).min((q[1] - lo).min(hi - q[1]));
            let per = [wrap[0] * 0.125, wrap[1] * 4.0];
            let g = octaves(
                prep,
                tile,
                [q[0] * 0.125, q[1] * 4.0, q[2]],
                0.5,
                0,
                lfp + 2.0,
                per,
            );
            let shade = (1.0 - w[3] * cell_hash_wrapped(prep, ix as i32, iy, 0, n))
                * (1.0 - w[4] * (0.5 + 0.5 * g.tanh()));
            soft_step(0.5 * w[1], w[2].max(soft), d) * shade
        }
        // wood lines: stretch, distortion, sharpness, roughness
        8 => {
            let per = [0.25 * wrap[0] / w[0], 0.25 * wrap[1]];
            // `soft` is the pixel's footprint.
            let v = wood_line_coordinate(prep, tile, q, lfp, per);
            let vx = wood_line_coordinate(prep, tile, [q[0] + soft, q[1], q[2]], lfp, per);
            let vy = wood_line_coordinate(prep, tile, [q[0], q[1] + soft, q[2]], lfp, per);
            line_profile(v, w[2], pixel_change(v, vx, vy))
        }
        // rings: distortion, sharpness, roughness, stretch, centre_x, centre_y (the centre at
        // texel `scale · (centre_x, centre_y)`, so the rings turn about it)
        9 => {
            let qc = [c * w[4] + s * w[5], -s * w[4] + c * w[5]];
            let mut p = [(q[0] - qc[0]) / w[3], q[1] - qc[1], q[2]];
            let per = [wrap[0] / w[3], wrap[1]];
            if wrap[0] > 0.0 {
                p[0] -= per[0] * (p[0] / per[0] + 0.5).floor();
                p[1] -= per[1] * (p[1] / per[1] + 0.5).floor();
            }
            let r = ring_coordinate(prep, tile, p, lfp, per);
            let rx = ring_coordinate(prep, tile, [p[0] + soft / w[3], p[1], p[2]], lfp, per);
            let ry = ring_coordinate(prep, tile, [p[0], p[1] + soft, p[2]], lfp, per);
            line_profile(r, w[1], pixel_change(r, rx, ry))
        }
        _ => 0.0,
    }
}

/// The ramp's colour at structure value `s`: linear between stops, constant beyond the ends.
pub fn ramp(prep: &Prepared, s: f32) -> [f32; 3] {
    ramp_rows(&prep.ramp[..prep.pattern[1] as usize], s)
}

/// [`ramp`] over stops given as rows (RGB, at).
pub fn ramp_rows(r: &[[f32; 4]], s: f32) -> [f32; 3] {
    let n = r.len();
    if s <= r[0][3] {
        return [r[0][0], r[0][1], r[0][2]];
    }
    for i in 1..n {
        if s < r[i][3] {
            let a = r[i - 1];
            let b = r[i];
            let t = (s - a[3]) / (b[3] - a[3]);
            return [
                a[0] + (b[0] - a[0]) * t,
                a[1] + (b[1] - a[1]) * t,
                a[2] + (b[2] - a[2]) * t,
            ];
        }
    }
    let l = r[n - 1];
    [l[0], l[1], l[2]]
}

/// The pattern's structure values over a `width × height` image at one texel per pixel (pixel
/// centres, as the renderers sample), row-major. `tile` is the 2D noise tile of `seed`
/// (`Tile::new_2d(seed)`; passed in because generating it costs more than the image).
pub fn structure_image(
    pattern: &Pattern,
    seed: u32,
    tile: &Tile,
    width: u32,
    height: u32,
) -> Vec<f32> {
    let prep = Prepared::new(&crate::params::pattern_shell(pattern.clone(), seed, false));
    structure_image_prepared(&prep, tile, width, height)
}

/// [`structure_image`] with the prepared block and tile supplied.
pub fn structure_image_prepared(prep: &Prepared, tile: &Tile, width: u32, height: u32) -> Vec<f32> {
    let mut out = vec![0.0f32; width as usize * height as usize];
    let row = |y: usize, line: &mut [f32]| {
        for (x, v) in line.iter_mut().enumerate() {
            *v = pattern(prep, tile, [x as f32 + 0.5, y as f32 + 0.5, 0.0], 0.0);
        }
    };
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        out.par_chunks_mut(width as usize)
            .enumerate()
            .for_each(|(y, l)| row(y, l));
    }
    #[cfg(target_arch = "wasm32")]
    for (y, l) in out.chunks_mut(width as usize).enumerate() {
        row(y, l);
    }
    out
}

#[cfg(test)]
mod tests;
