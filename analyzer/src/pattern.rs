//! Structured models: a *pattern* gives a structure value `s ∈ [0, 1]` at every
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
//! Planks' `widths` (ours, 2026-11-25) lets the rows vary ½–1½ units ([`crate::render::pattern::plank_row`]) where
//! the database and refinement search (to 0.5), 0–2 units at its range's end (1), which step 6
//! of the fit may reach ([`crate::structure::fit_structured`]).
//! Cells' `stagger` and `warp` (ours, 2026-11-25, for scales such as reptile skin's): every
//! other row shifted by up to half a cell (at low jitter a hexagonal lattice) and the lattice
//! bent by noise four cells coarse and finer. A near-regular lattice puts its power in a peak,
//! as the scales do (reptile skin's spectrum peaks about 10 dB above the quarter-octave rings
//! beside it), where jitter spreads power to every lower frequency and bending only widens the
//! peak. Jitter is searched from 0.2 ([`ValueSpec::search_min`]: unstaggered cells with less
//! are a grid); the sliders reach 0. Warp is searched to 0.25 ([`ValueSpec::search_max`]), where
//! the bending still keeps the plane unfolded: the displaced lattice's Jacobian determinant is ≤ 0
//! on 0.02 % of the plane at 0.25, 0.14 % at 0.3, 4 % at 0.5 and 25 % at 1 (`tests/cells_warp.rs`),
//! and a folded lattice is no longer cells but worm-shaped fragments of them. Searched to 1, the
//! refinement drove pebbles and cracked mud to warps of 0.98–1: fragments whose pixel-scale
//! pieces were specks (on the development set the cells' renders were over the speck limit on
//! 118 of 208 patches, 95 with the range's end at 0.25; docs/devset.md, "Cells' warp searched
//! while it bends"). The sliders reach 1. An earlier try, a tenth *scales* family, cost the round
//! trip (docs/measurements.md); these two values on cells kept it at 66/72 and found all 8 cells cases.
//! Documents written before the ranges were narrowed load with their values clamped
//! ([`Pattern::clamp_values`]). With these ranges (and two refinement starts) the synthetic
//! round trip finds the right family in 59 of 72 cases, up from 43 (62 since the noise
//! model's margin `retrieve::NOISE_MODEL_MARGIN` went from 0.6 to 0.25).
//!
//! The per-pixel functions (structure value, ramp) are [`crate::render::pattern`]'s, the twins of
//! `shaders/pattern.wgsl`.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

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
                        ValueSpec {
                            search_max: 0.25,
                            ..v(
                                "warp",
                                0.0,
                                1.0,
                                0.0,
                                "smooth bending of the lattice, in cells (rows of scales that curve)",
                            )
                        },
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::pattern::ramp_rows;

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
}
