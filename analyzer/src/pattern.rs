//! Structured models (issue 5): a *pattern* gives a structure value `s ∈ [0, 1]` at every
//! texel; a colour *ramp* turns `s` into RGB; the residual stochastic detail on top is Lagae's
//! noise model (see [`crate::params::StructuredModel`]).
//!
//! The two-tone paper (§3, §6) renders every model as a grey structure map between two tones;
//! its procedural models are perlin, turbulence, grid, brick, wood and rings with a handful of
//! parameters each. Departures, each for a reason:
//! - A ramp of up to [`MAX_STOPS`] colours along `s` instead of two tones, fitted to the photo
//!   (`analyze::fit_structured`): mortar, brick and their shades are more than a line segment.
//! - The noise inside the patterns is the project's own wavelet noise (the same tile, `noise2`
//!   or `noise3`), not Perlin's gradient noise: one noise on the GPU and CPU, band-limited so
//!   that octaves fade out cleanly when a pixel covers them ([`crate::noise::band_fade`]).
//! - Mortar and plank edges are softened over `max(bevel, pixel footprint)`: anti-aliasing that
//!   the paper, which rendered at one scale, did not need.
//! - The lines and rings are displaced by noise four times coarser than their spacing (wood
//!   grain meanders over several rings, it does not wiggle within one).
//! - Solid textures evaluate the noise in 3D; the cell patterns (grid, brick, cells, planks,
//!   rings) are extruded along z, as a wall or a log is: a block carved from a brick wall shows
//!   courses on its faces, a log shows rings on its end.
//!
//! Ranges: each family's structural values stop where it would render what another family
//! renders, so that a family's name is a look and the automatic choice has one right answer
//! (the papers' databases were per-model and never compared families). Brick at row offset 0 is
//! a grid and with full jitter the planks' random stagger; cells with no jitter are a grid;
//! perlin at low contrast is Gaussian noise (the noise model's class); turbulence at high
//! contrast is ridged with its tones swapped, and ridged with blunt crests is turbulence;
//! rings and lines distorted by more than about a spacing scramble into cells, and strongly
//! elliptic rings are lines; stretched cells are streaks; zero mortar or gap leaves no joints.
//! Ridged's roughness is the one value whose range goes past its look's: the database,
//! refinement and the round trip stop at 0.9 ([`ValueSpec::search_max`]; above, ridged
//! converges on turbulence), the fit's step 6 may go to 1 where the photo's spectrum asks.
//! Planks' `widths` (ours, 2026-11-25) lets the rows vary ½–1½ units ([`plank_row`]) where
//! the database and refinement search (to 0.5), 0–2 units at its range's end (1), which step 6
//! of the fit may reach ([`crate::structure::fit_structured`]).
//! Cells' `stagger` and `warp` (ours, 2026-11-25, for scales such as reptile skin's): every
//! other row shifted by up to half a cell (at low jitter a hexagonal lattice) and the lattice
//! bent by noise four cells coarse and finer. A near-regular lattice puts its power in a peak,
//! as the scales do (reptile skin's spectrum peaks about 10 dB above the quarter-octave rings
//! beside it), where jitter spreads power to every lower frequency and bending only widens the
//! peak. Jitter is searched from 0.2 ([`ValueSpec::search_min`]: unstaggered cells with less
//! are a grid); the sliders reach 0. An earlier try, a tenth *scales* family, cost the round
//! trip (docs/measurements.md); these two values on cells kept it at 66/72 and found all 8 cells cases.
//! Documents written before the ranges were narrowed load with their values clamped
//! ([`Pattern::clamp_values`]). With these ranges (and two refinement starts) the synthetic
//! round trip finds the right family in 59 of 72 cases, up from 43 (62 since the noise
//! model's margin `retrieve::OCCAM` went from 0.6 to 0.25).
//!
//! Every function here that takes `&Prepared` has a WGSL twin of the same name in
//! `shaders/pattern.wgsl`, same operation order in f32.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::noise::{Tile, band_fade, noise2, noise2_periodic, noise3, whole_period};
use crate::render::Prepared;
use crate::rng;

/// Most stops a colour ramp may have.
pub const MAX_STOPS: usize = 16;
/// Most structural parameters a pattern has.
pub const MAX_VALUES: usize = 8;
/// Octaves of the noise inside patterns.
pub const OCTAVES: usize = 5;

/// One structural parameter of a pattern: its name in the params JSON and the UI, its range and
/// default, and what it does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueSpec {
    /// Name (JSON key, slider label).
    pub name: &'static str,
    /// Smallest allowed value.
    pub min: f32,
    /// Largest allowed value.
    pub max: f32,
    /// Smallest value that the database samples, refinement searches and the synthetic round
    /// trip draws (`min` but for cells' jitter): below it the family's look merges with
    /// another's. Step 6 of [`crate::structure::fit_structured`] may still go down to `min`.
    pub search_min: f32,
    /// Largest value that the database samples, refinement searches and the synthetic round
    /// trip draws (`max` but for ridged's roughness): above it the family's look merges with
    /// another's. Step 6 of [`crate::structure::fit_structured`] may still go up to `max`.
    pub search_max: f32,
    /// Default.
    pub default: f32,
    /// What it does, for tooltips and docs.
    pub doc: &'static str,
}

const fn v(name: &'static str, min: f32, max: f32, default: f32, doc: &'static str) -> ValueSpec {
    ValueSpec {
        name,
        min,
        max,
        search_min: min,
        search_max: max,
        default,
        doc,
    }
}

impl ValueSpec {
    /// The value at fraction `u` of the searched range, `search_min..=search_max`.
    pub fn searched(&self, u: f32) -> f32 {
        self.search_min + (self.search_max - self.search_min) * u
    }

    /// The fraction of the searched range at which `value` lies (outside 0..=1 beyond it).
    pub fn search_fraction(&self, value: f32) -> f32 {
        (value - self.search_min) / (self.search_max - self.search_min)
    }
}

const STRETCH: ValueSpec = v(
    "stretch",
    1.0,
    16.0,
    1.0,
    "anisotropy: features this many times longer along x than along y",
);
const ROUGHNESS: ValueSpec = v(
    "roughness",
    0.2,
    0.9,
    0.5,
    "amplitude ratio of successive noise octaves (higher: more fine detail)",
);
/// Ridged turbulence's roughness reaches 1 (octaves of equal amplitude: fine cracks as strong
/// as coarse ones, as in hacienda's ground, whose refined fits sat at the 0.9 top of
/// [`ROUGHNESS`]), but only step 6 of the fit goes above 0.9: sampled up to 1 by the database
/// (and the round trip's queries), ridged was taken for turbulence and back more often (64/72
/// right against 66/72; at equal octave amplitudes the two look alike), and widening perlin's
/// and turbulence's range as well cost more (63/72).
const ROUGHNESS_FINE: ValueSpec = ValueSpec {
    max: 1.0,
    ..ROUGHNESS
};
/// Where the rings' centre lies, in ring spacings (the pattern's scale) from the texture's
/// origin, before rotation (rings turn about their centre). Rings far from their centre are
/// straight lines (the wood-lines family), so analysis places it inside the photo.
const CENTRE_X: ValueSpec = v(
    "centre_x",
    -24.0,
    24.0,
    0.0,
    "centre of the rings along x, in ring spacings from the origin",
);
const CENTRE_Y: ValueSpec = v(
    "centre_y",
    -24.0,
    24.0,
    0.0,
    "centre of the rings along y, in ring spacings from the origin",
);
const BEVEL: ValueSpec = v(
    "bevel",
    0.0,
    0.5,
    0.04,
    "softness of the joint edges, in pattern units",
);
const VARIATION: ValueSpec = v(
    "variation",
    0.0,
    1.0,
    0.2,
    "random darkening of each piece (brick, stone, plank)",
);
const DISTORTION: ValueSpec = v(
    "distortion",
    0.0,
    1.5,
    0.5,
    "turbulent displacement of the lines or rings, in line spacings",
);
const SHARPNESS: ValueSpec = v(
    "sharpness",
    0.3,
    8.0,
    1.0,
    "exponent of the line or ridge profile (higher: thinner bright lines)",
);

/// The structured pattern families.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PatternKind {
    /// Fractal noise through a sigmoid: blotches, clouds, stains (perlin with contrast).
    Perlin,
    /// Sum of absolute octaves: veins, fire, cracks between blobs.
    Turbulence,
    /// Ridged turbulence: sharp crests (veined marble, dried mud ridges).
    Ridged,
    /// A grid of rectangular tiles with joints (tiles, paving slabs).
    Grid,
    /// Running-bond brick courses with mortar.
    Brick,
    /// Voronoi cells with joints: paving, cobbles, stone walls.
    Cells,
    /// Staggered wood planks with gaps and grain.
    Planks,
    /// Turbulent parallel lines: wood grain seen along the board, marble streaks.
    WoodLines,
    /// Turbulent concentric rings: tree rings, agate.
    Rings,
}

impl PatternKind {
    /// Every kind, in the order of their shader index (1-based; 0 is the noise model).
    pub const ALL: [PatternKind; 9] = [
        PatternKind::Perlin,
        PatternKind::Turbulence,
        PatternKind::Ridged,
        PatternKind::Grid,
        PatternKind::Brick,
        PatternKind::Cells,
        PatternKind::Planks,
        PatternKind::WoodLines,
        PatternKind::Rings,
    ];

    /// Which half of the family's structure values is its connected network, where it has
    /// one: `Some(false)` for the joints (s ≈ 0) around the pieces of grid, brick, cells and
    /// planks and the dark cracks between turbulence's blobs, `Some(true)` for ridged's bright
    /// crests; `None` for perlin's blobs, wood lines and rings. Retrieval pairs a photo whose
    /// network is clear ([`crate::two_tone::network_phase`]) network to network.
    pub fn network(self) -> Option<bool> {
        match self {
            PatternKind::Grid
            | PatternKind::Brick
            | PatternKind::Cells
            | PatternKind::Planks
            | PatternKind::Turbulence => Some(false),
            PatternKind::Ridged => Some(true),
            PatternKind::Perlin | PatternKind::WoodLines | PatternKind::Rings => None,
        }
    }

    /// The JSON / CLI name.
    pub fn name(self) -> &'static str {
        match self {
            PatternKind::Perlin => "perlin",
            PatternKind::Turbulence => "turbulence",
            PatternKind::Ridged => "ridged",
            PatternKind::Grid => "grid",
            PatternKind::Brick => "brick",
            PatternKind::Cells => "cells",
            PatternKind::Planks => "planks",
            PatternKind::WoodLines => "wood_lines",
            PatternKind::Rings => "rings",
        }
    }

    /// The kind of a name.
    pub fn from_name(name: &str) -> Option<PatternKind> {
        Self::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The index the shader switches on (1..=9).
    pub fn index(self) -> u32 {
        Self::ALL.iter().position(|&k| k == self).unwrap() as u32 + 1
    }

    /// The structural parameters, in the order of the uniform block's `pattern_values`.
    pub fn specs(self) -> &'static [ValueSpec] {
        match self {
            PatternKind::Perlin => {
                const {
                    &[
                        STRETCH,
                        ROUGHNESS,
                        v(
                            "contrast",
                            2.5,
                            12.0,
                            4.0,
                            "steepness of the sigmoid (high: two flat tones)",
                        ),
                        v(
                            "threshold",
                            -1.0,
                            1.0,
                            0.0,
                            "noise level of the mid tone (moves the balance of the two tones)",
                        ),
                    ]
                }
            }
            PatternKind::Turbulence => {
                const {
                    &[
                        STRETCH,
                        ROUGHNESS,
                        v(
                            "contrast",
                            0.3,
                            2.5,
                            1.5,
                            "gain before saturation: s = 1 − exp(−contrast · turbulence)",
                        ),
                    ]
                }
            }
            PatternKind::Ridged => {
                const {
                    &[
                        STRETCH,
                        ROUGHNESS_FINE,
                        v(
                            "sharpness",
                            3.0,
                            12.0,
                            5.0,
                            "crest profile exp(−sharpness·|noise|) (higher: thinner crests)",
                        ),
                    ]
                }
            }
            PatternKind::Grid => {
                const {
                    &[
                        v("aspect", 0.25, 4.0, 1.0, "tile width / tile height"),
                        v(
                            "mortar",
                            0.03,
                            0.5,
                            0.08,
                            "joint width, fraction of a tile's height",
                        ),
                        BEVEL,
                        VARIATION,
                    ]
                }
            }
            PatternKind::Brick => {
                const {
                    &[
                        v("aspect", 1.0, 4.0, 2.2, "brick length / course height"),
                        v(
                            "mortar",
                            0.03,
                            0.5,
                            0.1,
                            "joint width, fraction of a course's height",
                        ),
                        v(
                            "row_offset",
                            0.25,
                            0.75,
                            0.5,
                            "shift of each course, in brick lengths (0.5: running bond)",
                        ),
                        v(
                            "jitter",
                            0.0,
                            0.25,
                            0.05,
                            "random extra shift of each course",
                        ),
                        BEVEL,
                        VARIATION,
                    ]
                }
            }
            PatternKind::Cells => {
                const {
                    &[
                        ValueSpec {
                            search_min: 0.2,
                            ..v(
                                "jitter",
                                0.0,
                                1.0,
                                0.8,
                                "randomness of the cell centres (0: a regular lattice; 0.5: near-square stones)",
                            )
                        },
                        v("mortar", 0.03, 0.5, 0.08, "joint width, fraction of a cell"),
                        BEVEL,
                        VARIATION,
                        v(
                            "stretch",
                            1.0,
                            3.0,
                            1.0,
                            "cells this many times longer along x (longer: streaks, not stones)",
                        ),
                        v(
                            "stagger",
                            0.0,
                            1.0,
                            0.0,
                            "shift of every other row of cells, in half cells (1 and low jitter: a hexagonal lattice, scales)",
                        ),
                        v(
                            "warp",
                            0.0,
                            1.0,
                            0.0,
                            "smooth bending of the lattice, in cells (rows of scales that curve)",
                        ),
                    ]
                }
            }
            PatternKind::Planks => {
                const {
                    &[
                        v("length", 4.0, 24.0, 8.0, "plank length / plank width"),
                        v(
                            "gap",
                            0.02,
                            0.3,
                            0.04,
                            "gap width, fraction of a plank's width",
                        ),
                        BEVEL,
                        VARIATION,
                        v(
                            "grain",
                            0.0,
                            1.0,
                            0.4,
                            "strength of the grain streaks along each plank",
                        ),
                        ValueSpec {
                            search_max: 0.5,
                            ..v(
                                "widths",
                                0.0,
                                1.0,
                                0.0,
                                "irregularity of the planks' widths (0: all alike; 0.5: ½–1½×; 1: 0–2×)",
                            )
                        },
                    ]
                }
            }
            PatternKind::WoodLines => &[STRETCH, DISTORTION, SHARPNESS, ROUGHNESS],
            PatternKind::Rings => {
                const {
                    &[
                        DISTORTION,
                        SHARPNESS,
                        ROUGHNESS,
                        v(
                            "stretch",
                            1.0,
                            2.5,
                            1.0,
                            "ellipticity of the rings (more: they read as straight lines)",
                        ),
                        CENTRE_X,
                        CENTRE_Y,
                    ]
                }
            }
        }
    }

    /// The default values, in spec order.
    pub fn defaults(self) -> Vec<f32> {
        self.specs().iter().map(|s| s.default).collect()
    }
}

/// A pattern and its placement: `q = R(−θ)·u / scale` in pattern units from texels `u`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pattern {
    /// Which family.
    pub kind: PatternKind,
    /// Texels per pattern unit (a brick course, a cell, a plank's width, a line spacing).
    pub scale: f32,
    /// Rotation of the pattern, degrees counter-clockwise (on top of the texture's).
    pub rotation_deg: f32,
    /// Structural parameters by name (see [`PatternKind::specs`]); missing ones read as their
    /// defaults.
    #[serde(default)]
    pub values: BTreeMap<String, f32>,
}

impl Pattern {
    /// The pattern of `kind` at its defaults.
    pub fn new(kind: PatternKind, scale: f32) -> Pattern {
        let mut p = Pattern {
            kind,
            scale,
            rotation_deg: 0.0,
            values: BTreeMap::new(),
        };
        p.set_vector(&kind.defaults());
        p
    }

    /// The values in spec order (defaults for missing ones).
    pub fn vector(&self) -> Vec<f32> {
        self.kind
            .specs()
            .iter()
            .map(|s| self.values.get(s.name).copied().unwrap_or(s.default))
            .collect()
    }

    /// Sets the values from spec order (clamped to their ranges).
    pub fn set_vector(&mut self, values: &[f32]) {
        self.values.clear();
        for (s, &x) in self.kind.specs().iter().zip(values) {
            self.values
                .insert(s.name.to_string(), x.clamp(s.min, s.max));
        }
    }

    /// Clamps every known value into its range (finite values only; unknown names and
    /// non-finite values are left for validation to report). Used on import, so presets saved
    /// before a range was narrowed still load.
    pub fn clamp_values(&mut self) {
        for s in self.kind.specs() {
            if let Some(v) = self.values.get_mut(s.name)
                && v.is_finite()
            {
                *v = v.clamp(s.min, s.max);
            }
        }
    }

    /// Sets the value called `name` (clamped to its range); false for a name `kind` lacks.
    pub fn set(&mut self, name: &str, value: f32) -> bool {
        match self.kind.specs().iter().find(|s| s.name == name) {
            Some(s) => {
                self.values
                    .insert(name.to_string(), value.clamp(s.min, s.max));
                true
            }
            None => false,
        }
    }

    /// The value called `name` (its default when missing).
    pub fn get(&self, name: &str) -> Option<f32> {
        let s = self.kind.specs().iter().find(|s| s.name == name)?;
        Some(self.values.get(name).copied().unwrap_or(s.default))
    }
}

/// One stop of a colour ramp: the colour at structure value `at`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RampStop {
    /// Structure value in [0, 1]; stops are non-decreasing in `at`.
    pub at: f32,
    /// RGB, display-encoded, in [0, 1].
    pub rgb: [f32; 3],
}

/// The two-tone paper's tone swap (§3) on a fitted ramp: the ramp read backwards, so that
/// structure value `s` gets the colour `1 − s` had (the stops reversed, each `at` → `1 − at`,
/// which keeps them non-decreasing). Retrieval chooses the pairing by the descriptor's
/// quantiles alone (the Gabor magnitudes are the same for `s` and `1 − s`); where it pairs a
/// pattern's cells with the photo's joints, this is the one-click fix (the app's "swap tones").
pub fn swap_tones(ramp: &mut [RampStop]) {
    ramp.reverse();
    for stop in ramp.iter_mut() {
        stop.at = 1.0 - stop.at;
    }
}

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
        noise3(
            &tile.data,
            tile.n,
            [q[0] * f + o[0], q[1] * f + o[1], q[2] * f + o[2]],
        )
    } else if per[0] > 0.0 {
        let n = tile.n as f32;
        let m = [whole_period(per[0] * f, n), whole_period(per[1] * f, n)];
        noise2_periodic(
            &tile.data,
            tile.n,
            [q[0] / per[0] * m[0] + o[0], q[1] / per[1] * m[1] + o[1]],
            m,
        )
    } else {
        noise2(&tile.data, tile.n, [q[0] * f + o[0], q[1] * f + o[1]])
    }
}

/// The octaves summed with amplitude ratio `gain`, each octave's noise `n` taken as `n`
/// (`mode` 0: fractal noise, unit variance when nothing is faded), `|n|` (1: turbulence,
/// Perlin 1985) or `exp(−sharpness·|n|)` (2: ridged, crests where the noise crosses 0); modes 1
/// and 2 normalised by the amplitudes' sum. `lfp`: log2 of the pixel footprint in pattern units
/// (octaves fade out as [`band_fade`] fades bands). `per`: `q`'s period (see [`octave`]).
#[allow(clippy::too_many_arguments)] // the twin of the WGSL function's argument list
#[inline]
pub fn octaves(
    prep: &Prepared,
    tile: &Tile,
    q: [f32; 3],
    gain: f32,
    mode: u32,
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
            let v = match mode {
                0 => n,
                1 => n.abs(),
                _ => (-sharpness * n.abs()).exp(),
            };
            sum += amp * fade * v;
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
    let stretched = |mode: u32, sharpness: f32| {
        let per = [wrap[0] / w[0], wrap[1]];
        let q = [q[0] / w[0], q[1], q[2]];
        octaves(prep, tile, q, w[1], mode, sharpness, lfp, per)
    };
    match prep.pattern[0] {
        // perlin: stretch, roughness, contrast, threshold
        1 => {
            let n = stretched(0, 0.0);
            1.0 / (1.0 + (-w[2] * (n - w[3])).exp())
        }
        // turbulence: stretch, roughness, contrast
        2 => {
            let t = stretched(1, 0.0);
            1.0 - (-w[2] * t).exp()
        }
        // ridged: stretch, roughness, sharpness
        3 => stretched(2, w[2]),
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
                let b = [0.25 * p[0], 0.25 * p[1], 0.25 * q[2]];
                let gx = octaves(prep, tile, b, 0.5, 0, 0.0, lfp - 2.0, per);
                let b2 = [b[0] + WARP_OFFSET, b[1], b[2]];
                let gy = octaves(prep, tile, b2, 0.5, 0, 0.0, lfp - 2.0, per);
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
                0.0,
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
            let n = octaves(
                prep,
                tile,
                [0.25 * q[0] / w[0], 0.25 * q[1], 0.25 * q[2]],
                w[3],
                0,
                0.0,
                lfp - 2.0,
                per,
            );
            let v = q[1] + w[1] * n;
            (0.5 + 0.5 * (std::f32::consts::TAU * v).sin())
                .max(1e-6)
                .powf(w[2])
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
            let n = octaves(
                prep,
                tile,
                [0.25 * p[0], 0.25 * p[1], 0.25 * p[2]],
                w[2],
                0,
                0.0,
                lfp - 2.0,
                [0.25 * per[0], 0.25 * per[1]],
            );
            let r = (p[0] * p[0] + p[1] * p[1]).sqrt() + w[0] * n;
            (0.5 + 0.5 * (std::f32::consts::TAU * r).sin())
                .max(1e-6)
                .powf(w[1])
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn swapped_tones_read_the_ramp_backwards() {
        let mut r = vec![
            RampStop {
                at: 0.1,
                rgb: [0.1, 0.2, 0.3],
            },
            RampStop {
                at: 0.35,
                rgb: [0.9, 0.5, 0.0],
            },
            RampStop {
                at: 0.8,
                rgb: [0.4, 0.7, 1.0],
            },
        ];
        let before = crate::morph::ramp_table(&r);
        swap_tones(&mut r);
        assert!(r.windows(2).all(|w| w[0].at <= w[1].at));
        let after = crate::morph::ramp_table(&r);
        for i in 0..=100 {
            let s = i as f32 / 100.0;
            let (a, b) = (ramp_rows(&after, s), ramp_rows(&before, 1.0 - s));
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 1e-5, "s {s}: {a:?} vs {b:?}");
            }
        }
        swap_tones(&mut r);
        for (a, b) in crate::morph::ramp_table(&r).iter().zip(&before) {
            assert!(
                a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6),
                "{a:?} vs {b:?}"
            );
        }
    }

    #[test]
    fn kinds_round_trip_their_names_and_indices() {
        for (i, k) in PatternKind::ALL.into_iter().enumerate() {
            assert_eq!(PatternKind::from_name(k.name()), Some(k));
            assert_eq!(k.index(), i as u32 + 1);
            let specs = k.specs();
            assert!(!specs.is_empty() && specs.len() <= 7, "{k:?}: 1–7 values");
            for s in specs {
                assert!(
                    s.min <= s.search_min
                        && s.search_min < s.search_max
                        && s.search_max <= s.max
                        && (s.search_min..=s.search_max).contains(&s.default),
                    "{s:?}"
                );
            }
        }
    }

    #[test]
    fn rings_turn_about_their_centre() {
        // Without distortion and ellipticity the rings' value depends only on the distance
        // to their centre, at texel `scale · (centre_x, centre_y)` whatever the rotation.
        let tile = Tile::new_2d(1);
        for rotation in [0.0, 30.0, 90.0, 135.0] {
            let mut p = Pattern::new(PatternKind::Rings, 10.0);
            p.rotation_deg = rotation;
            assert!(p.set("distortion", 0.0) && p.set("centre_x", 3.0) && p.set("centre_y", 5.0));
            let prep = Prepared::new(&crate::structure::shell(p, 1, false));
            let at = |phi: f32| {
                let u = [30.0 + 12.3 * phi.cos(), 50.0 + 12.3 * phi.sin(), 0.0];
                pattern(&prep, &tile, u, 0.0)
            };
            let v0 = at(0.0);
            for phi in [0.7, 1.9, 3.1, 4.4, 5.6] {
                assert!((at(phi) - v0).abs() < 1e-3, "{rotation}°, {phi}");
            }
        }
    }

    #[test]
    fn staggered_cells_at_jitter_0_lie_on_a_shifted_lattice() {
        // Cells at jitter 0 are centred on the unit lattice; `stagger` 1 moves every other row
        // by half a cell, so a point that is a centre without it falls on a joint, and `warp`
        // bends the lattice (the same point moves off its centre).
        let tile = Tile::new_2d(1);
        let at = |values: &[(&str, f32)], u: [f32; 2]| {
            let mut p = Pattern::new(PatternKind::Cells, 10.0);
            for &(k, v) in values {
                assert!(p.set(k, v), "{k}");
            }
            assert!(p.set("variation", 0.0) && p.set("bevel", 0.05));
            let prep = Prepared::new(&crate::structure::shell(p, 1, false));
            pattern(&prep, &tile, [10.0 * u[0], 10.0 * u[1], 0.0], -6.0)
        };
        let square = [("jitter", 0.0)];
        let hex = [("jitter", 0.0), ("stagger", 1.0)];
        // Even rows (0, 2) keep their centres; odd rows (1, −1) move by half a cell.
        for (u, centre_square, centre_hex) in [
            ([0.5, 0.5], true, true),
            ([3.5, 2.5], true, true),
            ([0.5, 1.5], true, false),
            ([1.0, 1.5], false, true),
            ([2.0, -0.5], false, true),
        ] {
            for (values, centre) in [(&square[..], centre_square), (&hex[..], centre_hex)] {
                let v = at(values, u);
                if centre {
                    assert!(v > 0.99, "{values:?} at {u:?}: {v} (a cell's centre)");
                } else {
                    assert!(v < 0.01, "{values:?} at {u:?}: {v} (a joint)");
                }
            }
        }
        let warped = [("jitter", 0.0), ("stagger", 1.0), ("warp", 1.0)];
        let moved = [[0.5, 0.5], [3.5, 2.5], [1.0, 1.5], [6.5, 4.5], [9.0, 7.5]]
            .iter()
            .filter(|&&u| at(&warped, u) < 0.9)
            .count();
        assert!(
            moved >= 2,
            "warp 1 moved {moved} of 5 centres off their cells' centres"
        );
    }

    #[test]
    fn plank_rows_cover_the_line_with_irregular_widths() {
        let prep = Prepared::new(&crate::structure::shell(
            Pattern::new(PatternKind::Planks, 10.0),
            3,
            false,
        ));
        // Without irregularity the rows are the integers' intervals.
        for y in [-2.5f32, -0.01, 0.0, 0.3, 7.99] {
            assert_eq!(
                plank_row(&prep, y, 0.0, 0),
                [y.floor(), y.floor(), y.floor() + 1.0]
            );
        }
        // With it, every y lies in its row, between its two edges; returns the rows' widths'
        // least and greatest.
        let spread = |widths: f32| {
            let mut seen = Vec::new();
            for i in -400..400 {
                let y = i as f32 * 0.0437;
                let [row, lo, hi] = plank_row(&prep, y, widths, 0);
                assert!(lo <= y && y < hi, "{y}: row {row} [{lo}, {hi})");
                assert_eq!(lo, plank_edge(&prep, row as i32, widths, 0));
                assert_eq!(hi, plank_edge(&prep, row as i32 + 1, widths, 0));
                seen.push(hi - lo);
            }
            seen.iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &w| (a.min(w), b.max(w)))
        };
        // 0.5 (the searched range's end): widths ½–1½, some rows differ clearly.
        let (min, max) = spread(0.5);
        assert!(
            0.5 <= min && max <= 1.5 && max - min > 0.4,
            "widths {min}–{max}"
        );
        // 1 (the range's end): edges move up to ½ either way, rows 0–2 wide, never crossing.
        let (min, max) = spread(1.0);
        assert!(
            0.0 <= min && max <= 2.0 && max - min > 1.0,
            "widths {min}–{max}"
        );
        // Wrapped at 6 rows, the edges repeat every 6.
        for k in -7..7 {
            let (a, b) = (
                plank_edge(&prep, k, 0.5, 6),
                plank_edge(&prep, k + 6, 0.5, 6),
            );
            assert!((b - a - 6.0).abs() < 1e-5, "{k}: {a} {b}");
        }
    }

    #[test]
    fn soft_step_is_a_clamped_smooth_step() {
        assert_eq!(soft_step(0.1, 0.2, 0.0), 0.0);
        assert_eq!(soft_step(0.1, 0.2, 0.3), 1.0);
        assert!((soft_step(0.1, 0.2, 0.2) - 0.5).abs() < 1e-6);
    }
}
