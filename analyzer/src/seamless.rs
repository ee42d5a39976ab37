//! Seamless tiles: the texture re-wrapped so that an image of `size × size` pixels repeats
//! without a seam (the PNG tile export). CPU reference of `shaders/seamless.wgsl`.
//!
//! The texture itself repeats only every `128·2^(bands−1)` texels (16384 for 8 bands: the
//! coarsest band's tile), far more than a PNG tile. So each band `j` is made periodic over the
//! tile on its own: over the tile it spans `m_j = size·pixel_size / (scale·2^j)` coefficients;
//! we round that to a whole number `m'_j` (at least 1; a multiple of the noise tile side 128
//! when it is larger, since the band already repeats every 128 coefficients) and evaluate the
//! band at `q = a·m'_j + o_j` (`a` the position in the tile, 0..1) with its coefficient indices
//! wrapped at `min(m'_j, 128)`. The quadratic B-spline of a wrapped coefficient sequence is
//! periodic and C¹, so the tile's edges continue each other exactly like interior pixels.
//!
//! What this changes against the infinite texture (departures, deliberate):
//! - A band's frequency moves by the rounding of `m_j`: nothing for the fine bands (at 1 world
//!   unit per pixel and scale 1, `m_j = size/2^j` is exact for power-of-two sizes), a visible
//!   stretch only for bands whose features are about as big as the tile.
//! - Bands coarser than the tile wrap at one or two coefficients: over a tile they are nearly
//!   constant, as they are over any crop of that size of the infinite texture.
//! - Rotation is ignored (an isotropic band rotated only picks another realisation, and a
//!   rotated lattice cannot repeat along the image axes): oriented bands show their streaks at
//!   their texel angles, as the texture does at rotation 0. A structured model's residual keeps
//!   its texel angles too, also where its pattern is moved to a quarter turn (below).
//! - A solid (3D) texture's tile is its plane texture (the 2D noise of the same seed and params).
//!
//! Structured models (ours; neither paper makes tiles of them): the pattern's total rotation
//! (the texture's plus the pattern's) is moved to the nearest multiple of 90°, so that its
//! axes run along the tile's; over the tile the pattern then spans `span` pattern units along
//! each of its axes, which [`crate::render::pattern::tile_periods`] moves to a whole number of the
//! family's cells (rows, bricks, planks, stones, wood lines), and
//! [`crate::render::pattern::pattern_at`] wraps cell indices, row shifts and noise octaves at those
//! periods (rings: the torus distance to their centre). Departures, deliberate: a turned
//! pattern (a brick wall at 30°) is tiled upright (a turned lattice cannot repeat along the
//! tile's axes with a period this small); the cells' size moves by up to half a cell over the
//! tile (a visible stretch only for a tile a few cells wide); brick's row offset moves to the
//! nearest multiple of 1 / rows.

use crate::error::{Error, Result};
use crate::noise::oriented::noise2_periodic_oriented;
use crate::noise::{Tile, noise2_periodic};
use crate::params::{MAX_BANDS, Params};
use crate::render::pattern::{pattern_at, ramp};
use crate::render::{ChannelNoise, Image, Prepared, band_sum, colour};

/// The largest tile side (the WebGPU limit on a texture side, and 256 MiB as 8-bit RGBA): the
/// render limit of [`crate::limits`], so that the app's PNG tiles and the CLI's renders stop at
/// the same size.
pub const MAX_TILE: u32 = 8192;
const _: () = assert!(MAX_TILE as u64 * MAX_TILE as u64 == crate::limits::MAX_RENDER_PIXELS);

/// A seamless tile: its size, pixel size and the period of every band over it.
#[derive(Clone, Debug, PartialEq)]
pub struct Seamless {
    /// Side in pixels.
    pub size: u32,
    /// log2 of the pixel footprint in texels (band clamping, as the plane view).
    pub log2_fp: f32,
    /// Band `j` spans `periods[j]` coefficients over the tile (a whole number).
    pub periods: [f32; MAX_BANDS],
    /// Structured models: the pattern's periods over the tile along its axes (pattern units,
    /// [`crate::render::pattern::tile_periods`]) and the cos and sin of its rotation moved to a
    /// multiple of 90° (exactly 0 or ±1); zero for the noise model.
    pub pattern: [f32; 4],
}

impl Seamless {
    /// The tile of `size × size` pixels of `pixel_size` world units each, for `prep` (a plane
    /// texture; see [`plane`]) with its noise tile of side `tile_n`.
    pub fn new(prep: &Prepared, tile_n: usize, size: u32, pixel_size: f32) -> Result<Seamless> {
        if !(16..=MAX_TILE).contains(&size) {
            return Err(Error::Option(format!(
                "tile size {size}: choose 16 to {MAX_TILE} pixels"
            )));
        }
        if !(pixel_size.is_finite() && pixel_size > 0.0) {
            return Err(Error::Option(format!(
                "tile pixel size {pixel_size}: must be a positive number"
            )));
        }
        let span = size as f64 * pixel_size as f64 * prep.inv_scale as f64;
        let n = tile_n as f64;
        let mut periods = [0.0f32; MAX_BANDS];
        for (j, p) in periods.iter_mut().enumerate().take(prep.bands as usize) {
            let m = span / (1u64 << j) as f64;
            *p = if m < n {
                m.round().max(1.0)
            } else {
                n * (m / n).round()
            } as f32;
        }
        let mut pattern = [0.0f32; 4];
        if prep.pattern[0] != 0 {
            let is = prep.pattern_transform[0];
            let [c, s] = [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]][quarter_turn(prep).1];
            let [px, py] = crate::render::pattern::tile_periods(prep, (span * is as f64) as f32);
            pattern = [px, py, c, s];
        }
        Ok(Seamless {
            size,
            log2_fp: (pixel_size * prep.inv_scale).log2(),
            periods,
            pattern,
        })
    }

    /// The uniform block of `shaders/seamless.wgsl` (`struct Seamless`): the 12 band periods as
    /// three vec4, then (size, log2 footprint, first row, unused), then the pattern's periods
    /// and turn.
    pub fn uniform_bytes(&self, first_row: u32) -> Vec<u8> {
        let mut v: Vec<f32> = self.periods.to_vec();
        v.extend([self.size as f32, self.log2_fp, first_row as f32, 0.0]);
        v.extend(self.pattern);
        v.iter().flat_map(|x| x.to_le_bytes()).collect()
    }
}

/// A structured model's pattern rotation in the texture (the texture's turn plus the
/// pattern's, degrees in [0, 360)) and the quarter turn (0–3) a seamless tile renders it at.
fn quarter_turn(prep: &Prepared) -> (f64, usize) {
    let [_, pc, ps, _] = prep.pattern_transform;
    let turn =
        f64::from(prep.rot[1]).atan2(f64::from(prep.rot[0])) + f64::from(ps).atan2(f64::from(pc));
    let quarter = (turn / std::f64::consts::FRAC_PI_2).round().rem_euclid(4.0) as usize;
    (turn.to_degrees().rem_euclid(360.0), quarter)
}

/// Where a seamless tile turns a structured model's pattern: its rotation in the texture and
/// the rotation the tile renders (degrees in [0, 360)), when they differ by more than half a
/// degree; `None` for the noise model and for a pattern already at a quarter turn. What the
/// CLI and the app tell the user after a tile.
pub fn tile_turn(params: &Params) -> Option<(f32, f32)> {
    let prep = Prepared::new(&plane(params));
    if prep.pattern[0] == 0 {
        return None;
    }
    let (from, quarter) = quarter_turn(&prep);
    let to = 90.0 * quarter as f64;
    let off = (from - to).rem_euclid(360.0);
    (off.min(360.0 - off) > 0.5).then_some((from as f32, to as f32))
}

/// Size of [`Seamless::uniform_bytes`].
pub const UNIFORM_SIZE: usize = 4 * (MAX_BANDS + 8);

/// The params a tile renders: a solid texture's plane texture (see the module docs).
pub fn plane(params: &Params) -> Params {
    let mut p = params.clone();
    p.solid = false;
    p
}

/// The multiresolution noise of the three channels at tile position `a` (0..1 per axis).
#[inline]
pub fn texture_noise_wrapped(
    prep: &Prepared,
    tile: &Tile,
    s: &Seamless,
    a: [f32; 2],
) -> ChannelNoise {
    band_sum(prep, s.log2_fp, |j| {
        let m = s.periods[j];
        let o = prep.offsets[j];
        let p = [a[0] * m + o[0], a[1] * m + o[1]];
        let mix = prep.orient[j];
        if mix[1] == 0.0 && mix[2] == 0.0 {
            noise2_periodic(&tile.data, tile.n, p, [m, m])
        } else {
            noise2_periodic_oriented(&tile.data, tile.n, p, [m, m], mix)
        }
    })
}

/// The colour of tile pixel (x, y), rendered in strips from `first_row` (GPU order of
/// operations: the pixel centre within the strip, plus the strip's first row).
#[inline]
pub fn seamless_pixel(
    prep: &Prepared,
    tile: &Tile,
    s: &Seamless,
    x: u32,
    y: u32,
    first_row: u32,
) -> [f32; 3] {
    let size = s.size as f32;
    let a = [
        (x as f32 + 0.5) / size,
        ((y - first_row) as f32 + 0.5 + first_row as f32) / size,
    ];
    let base = if prep.pattern[0] != 0 {
        ramp(prep, pattern_wrapped(prep, tile, s, a))
    } else {
        prep.mean
    };
    colour(prep, texture_noise_wrapped(prep, tile, s, a), base)
}

/// The structure value of a structured model at tile position `a` (0..1 per axis): the
/// pattern turned by a multiple of 90° and spanning its periods over the tile (module docs).
#[inline]
pub fn pattern_wrapped(prep: &Prepared, tile: &Tile, s: &Seamless, a: [f32; 2]) -> f32 {
    let [px, py, c, sn] = s.pattern;
    let q = [
        px * (c * a[0] + sn * a[1]),
        py * (-sn * a[0] + c * a[1]),
        0.0,
    ];
    pattern_at(
        prep,
        tile,
        q,
        s.log2_fp + prep.pattern_transform[3],
        [px, py],
    )
}

/// Rows `first_row..first_row + rows` of the tile (a strip), row-major.
pub fn render_rows(
    prep: &Prepared,
    tile: &Tile,
    s: &Seamless,
    first_row: u32,
    rows: u32,
) -> Vec<[f32; 3]> {
    let w = s.size as usize;
    let mut out = vec![[0.0f32; 3]; w * rows as usize];
    let row = |y: u32, px: &mut [[f32; 3]]| {
        for (x, p) in px.iter_mut().enumerate() {
            *p = seamless_pixel(prep, tile, s, x as u32, first_row + y, first_row);
        }
    };
    #[cfg(not(target_arch = "wasm32"))]
    {
        use rayon::prelude::*;
        out.par_chunks_mut(w)
            .enumerate()
            .for_each(|(y, px)| row(y as u32, px));
    }
    #[cfg(target_arch = "wasm32")]
    for (y, px) in out.chunks_mut(w).enumerate() {
        row(y as u32, px);
    }
    out
}

/// The whole seamless tile of `params`: `size × size` pixels of `pixel_size` world units.
pub fn render_seamless(params: &Params, size: u32, pixel_size: f32) -> Result<Image> {
    let params = plane(params);
    let prep = Prepared::new(&params);
    let tile = Tile::new_2d(params.seed);
    let s = Seamless::new(&prep, tile.n, size, pixel_size)?;
    Ok(Image {
        width: size,
        height: size,
        pixels: render_rows(&prep, &tile, &s, 0, size),
    })
}

/// How an image's wrap compares with its interior, one axis: the mean absolute difference
/// between the last and the first column (or row), and the same for the interior pairs of
/// neighbouring columns (rows) `(x, x + 1)` of the same phase as the wrap, `x ≡ w − 1
/// (mod 8)`.
///
/// Why the phase: wavelet noise sampled at one texel per pixel is not stationary at the pixel
/// scale. Band `j` is sampled at `2^−j` coefficients per pixel, so the B-spline weights, and
/// with them the size of neighbouring differences, repeat every `2^j` pixels (measured on the
/// rock sample, 256²: pairs at `x ≡ 3 (mod 4)` differ 30 % more than pairs at even `x`). The
/// wrap pair `(w − 1, 0)` is the pair `(w − 1, w)` of the repeated image, so it belongs with
/// the pairs of its own phase; the first 3 bands (the ones that make pixel-scale differences)
/// repeat every 8 pixels.
#[derive(Clone, Debug, PartialEq)]
pub struct SeamStats {
    /// Mean |difference| across the wrap (last → first).
    pub seam: f64,
    /// Mean |difference| of each interior neighbouring pair of the wrap's phase.
    pub interior: Vec<f64>,
    /// Mean |difference| over all interior neighbouring pairs.
    pub interior_all: f64,
}

impl SeamStats {
    /// The seam over the mean interior difference of its phase: 1 when the edges continue each
    /// other as well as interior neighbours do (on average), several for a visible seam.
    pub fn ratio(&self) -> f64 {
        self.seam / (self.interior.iter().sum::<f64>() / self.interior.len() as f64).max(1e-12)
    }

    /// The fraction of same-phase interior pairs that differ less than the seam (about 0.5: a
    /// typical pair; 1: the seam is the worst pair of the image).
    pub fn rank(&self) -> f64 {
        self.interior.iter().filter(|&&d| d < self.seam).count() as f64 / self.interior.len() as f64
    }
}

/// The phase period of [`SeamStats`].
pub const SEAM_PHASE: usize = 32;

/// [`SeamStats`] across columns (left/right edges) and across rows (top/bottom edges).
pub fn seam_stats(img: &Image) -> [SeamStats; 2] {
    let (w, h) = (img.width as usize, img.height as usize);
    let px = |x: usize, y: usize| img.pixels[y * w + x];
    let diff = |a: [f32; 3], b: [f32; 3]| -> f64 {
        (0..3).map(|c| (a[c] - b[c]).abs() as f64).sum::<f64>() / 3.0
    };
    let cols =
        |x0: usize, x1: usize| (0..h).map(|y| diff(px(x0, y), px(x1, y))).sum::<f64>() / h as f64;
    let rows =
        |y0: usize, y1: usize| (0..w).map(|x| diff(px(x, y0), px(x, y1))).sum::<f64>() / w as f64;
    let axis = |len: usize, pair: &dyn Fn(usize, usize) -> f64| {
        let all: Vec<f64> = (0..len - 1).map(|x| pair(x, x + 1)).collect();
        SeamStats {
            seam: pair(len - 1, 0),
            interior: all
                .iter()
                .enumerate()
                .filter(|(x, _)| x % SEAM_PHASE == (len - 1) % SEAM_PHASE)
                .map(|(_, d)| *d)
                .collect(),
            interior_all: all.iter().sum::<f64>() / all.len() as f64,
        }
    };
    [axis(w, &cols), axis(h, &rows)]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Params analysed from a small synthetic photo (hash noise).
    fn some_params() -> Params {
        crate::analyze::hash_noise_params(64, 3)
    }

    #[test]
    fn periods_are_whole_and_fine_bands_exact() {
        let params = some_params();
        let prep = Prepared::new(&params);
        let s = Seamless::new(&prep, 128, 512, 1.0 / prep.inv_scale).unwrap();
        // One texel per pixel: band j spans 512 / 2^j coefficients.
        for j in 0..prep.bands as usize {
            let m = 512.0 / (1u32 << j) as f32;
            let want = if m < 128.0 { m.max(1.0) } else { m };
            assert_eq!(s.periods[j], want, "band {j}");
        }
        assert!(Seamless::new(&prep, 128, 8, 1.0).is_err());
        assert!(Seamless::new(&prep, 128, MAX_TILE + 1, 1.0).is_err());
        assert!(Seamless::new(&prep, 128, 64, 0.0).is_err());
    }

    #[test]
    fn tile_turn_names_the_quarter_turn() {
        use crate::pattern::{Pattern, PatternKind};
        let turned = |rot: f32, texture: f32| {
            let mut pat = Pattern::new(PatternKind::Brick, 20.0);
            pat.rotation_deg = rot;
            let mut p = crate::params::pattern_shell(pat, 1, false);
            p.transform.rotation_deg = texture;
            tile_turn(&p).map(|(a, b)| (a.round(), b))
        };
        assert_eq!(turned(30.0, 0.0), Some((30.0, 0.0)));
        assert_eq!(turned(100.0, 10.0), Some((110.0, 90.0)));
        assert_eq!(turned(-100.0, 0.0), Some((260.0, 270.0)));
        assert_eq!(turned(90.0, 0.0), None);
        assert_eq!(tile_turn(&some_params()), None);
    }

    /// Every pattern family, at rotations that snap to each quarter turn and at scales from a
    /// few cells to less than one over the tile, repeats with the tile: the structure value at
    /// `a` equals the one at `a` plus a whole tile along either axis (up to the float error of
    /// `q` at the far copy: a point on a joint may flip cells, so a few mismatches are allowed).
    #[test]
    fn structured_patterns_repeat_with_the_tile() {
        use crate::pattern::{Pattern, PatternKind};
        let tile = Tile::new_2d(4);
        // Every family at its defaults, and cells' staggered, warped lattice (scales).
        let variants = PatternKind::ALL.into_iter().map(|k| (k, vec![])).chain([(
            PatternKind::Cells,
            vec![("jitter", 0.3), ("stagger", 1.0), ("warp", 0.5)],
        )]);
        for (kind, values) in variants {
            for (i, (scale, rot)) in [
                (9.0f32, 0.0f32),
                (23.5, 100.0),
                (61.0, 185.0),
                (300.0, -80.0),
            ]
            .into_iter()
            .enumerate()
            {
                let mut pat = Pattern::new(kind, scale);
                pat.rotation_deg = rot;
                for &(k, v) in &values {
                    assert!(pat.set(k, v));
                }
                let params = crate::params::pattern_shell(pat, 7 + i as u32, false);
                let prep = Prepared::new(&params);
                let s = Seamless::new(&prep, tile.n, 256, 1.0).unwrap();
                assert!(
                    s.pattern[2].abs() + s.pattern[3].abs() == 1.0,
                    "{kind:?}: turn {:?} is not a quarter turn",
                    &s.pattern[2..]
                );
                let (mut bad, mut total) = (0, 0);
                for k in 0..200u32 {
                    let a = [
                        crate::rng::uniform(11, 0, k) as f32,
                        crate::rng::uniform(11, 1, k) as f32,
                    ];
                    let v = pattern_wrapped(&prep, &tile, &s, a);
                    for b in [[a[0] + 1.0, a[1]], [a[0], a[1] - 1.0]] {
                        total += 1;
                        if (pattern_wrapped(&prep, &tile, &s, b) - v).abs() > 1e-3 {
                            bad += 1;
                        }
                    }
                }
                assert!(
                    bad * 100 <= total,
                    "{kind:?} {values:?} at scale {scale}, {rot}°: {bad} of {total} points differ a tile away"
                );
            }
        }
    }

    #[test]
    fn wrapped_noise_repeats_with_its_period() {
        let tile = Tile::new_2d(9);
        for period in [1.0f32, 3.0, 16.0, 128.0, 256.0] {
            for &(x, y) in &[(0.3f32, 7.9f32), (5.5, 0.0), (100.25, 33.5)] {
                let a = noise2_periodic(&tile.data, tile.n, [x, y], [period, period]);
                let b = noise2_periodic(
                    &tile.data,
                    tile.n,
                    [x + period, y - period],
                    [period, period],
                );
                for k in 0..a.len() {
                    assert!(
                        (a[k] - b[k]).abs() < 1e-4,
                        "period {period} at ({x}, {y}): {a:?} vs {b:?}"
                    );
                }
            }
        }
    }
}
