//! The parameters type: the one description of a texture that flows photo → analysis → GPU
//! uniforms → export. Versioned JSON (`"format": "proctex/1"`); import validates every field and
//! names the bad one.
//!
//! Texture space: a *texel* is one pixel of the analysed image. Band `j` of the noise model
//! (index 0 is the finest) holds frequencies up to `2^−(j+1)` cycles per texel, i.e. noise
//! `N(u · 2^−j + o_j)`. World coordinates map to texels through [`Transform`]: `u = R(−θ)·x / s`.
//! Models other than noise will be added as further [`Model`] variants; the colour, transform,
//! seed and dimension blocks are shared by all of them.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::pattern::{MAX_STOPS, Pattern, RampStop};

/// The format tag of this version.
pub const FORMAT: &str = "proctex/1";
/// Most bands a noise model may have (a 8192² analysis has 12).
pub const MAX_BANDS: usize = 12;
/// Most knots of a histogram spline (K ≤ 32).
pub const MAX_KNOTS: usize = 33;
/// Most knots per channel of a structured model's output [`Tone`] curve.
pub const MAX_TONE_KNOTS: usize = 33;

/// A procedural texture, completely.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Always [`FORMAT`].
    pub format: String,
    /// Seed of the noise tiles and band offsets.
    pub seed: u32,
    /// `true`: a solid texture (3D noise), `false`: a plane texture (2D noise).
    pub solid: bool,
    /// World ↔ texel mapping.
    pub transform: Transform,
    /// Mean colour and decorrelating rotation.
    pub colour: Colour,
    /// The texture model in the decorrelated colour space.
    pub model: Model,
    /// Where the parameters came from (informational; not used to render).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<Source>,
}

/// World ↔ texel mapping.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Transform {
    /// World units per texel (analysis sets it to photo pixels per analysed pixel).
    pub scale: f32,
    /// Rotation of the texture, degrees counter-clockwise.
    pub rotation_deg: f32,
}

/// Colour: `rgb = mean + contrast · Σ_k v_k · basis[k]`, where `v_k` are the decorrelated
/// channels.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Colour {
    /// Mean RGB, display-encoded, in `[0, 1]`.
    pub mean: [f32; 3],
    /// Rows are the principal axes (unit, orthogonal, determinant +1).
    pub basis: [[f32; 3]; 3],
    /// Scales the variation about the mean (1 = as analysed; 0 = flat mean colour). An artist's
    /// control, not in Lagae's model; absent in older documents, which read as 1.
    #[serde(default = "unit_contrast")]
    pub contrast: f32,
}

fn unit_contrast() -> f32 {
    1.0
}

/// Largest allowed contrast.
pub const MAX_CONTRAST: f32 = 4.0;

/// The texture model.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Model {
    /// Multiresolution wavelet noise per decorrelated channel (Lagae et al. 2009).
    Noise(NoiseModel),
    /// A structured pattern through a colour ramp, plus residual noise.
    Structured(StructuredModel),
}

/// A structured texture: `rgb = mean + contrast·((ramp(s(u)) − mean) + Σ_k v_k·basis[k])`,
/// where `s` is the pattern's structure value, `ramp` the fitted colour ramp, and `v_k` the
/// residual noise model's decorrelated channels (Lagae's model of what the pattern and ramp do
/// not explain: the grain of a brick, the fibres of a plank). The colour block's basis is the
/// residual's PCA basis and its mean the contrast pivot.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StructuredModel {
    /// The pattern and its placement.
    pub pattern: Pattern,
    /// Colours along the structure value, 2 to [`MAX_STOPS`] stops, `at` non-decreasing.
    pub ramp: Vec<RampStop>,
    /// The residual stochastic detail.
    pub residual: NoiseModel,
    /// The output tone curve (absent: none; presets from before it load unchanged).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tone: Option<Tone>,
}

/// An output tone curve per RGB channel, applied last (after ramp, residual and contrast):
/// `rgb_c ← spline_c((rgb_c − lo_c) / (hi_c − lo_c))`, a monotone Fritsch–Carlson spline
/// through knots at evenly spaced inputs, clamped to its end knots outside `[lo, hi]`. A
/// structured model's curve maps the ramp's colour and the residual follows it: through the
/// curve where the curve compresses it, never larger than itself
/// ([`crate::render::tone_excursion`]).
///
/// Departure from the 2014 paper (two tones) and past our ramp + residual: the ramp is fitted
/// by least squares and the residual is Gaussian-ish noise, so their sum has the right mean
/// but not the photo's colour distribution (a brick wall's bricks come out greyer, its
/// mortar less distinct). The curve maps each channel of the synthesis onto the photo's
/// distribution: fitted by quantile matching the pooled renders of four seeds to the photo
/// ([`crate::structure::fit_tone`]), which does not overfit one seed's few bricks.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tone {
    /// Whether synthesis applies it (kept either way, for toggling).
    pub enabled: bool,
    /// Per channel input range `[lo, hi]` that the knots span, `lo < hi`.
    pub range: [[f32; 2]; 3],
    /// Per channel output values at evenly spaced inputs, non-decreasing; all three the same
    /// length, 2 to [`MAX_TONE_KNOTS`].
    pub knots: [Vec<f32>; 3],
}

impl Tone {
    /// The identity curve on `[0, 1]` with `n` knots (what a model without a curve shows,
    /// up to clamping outside `[0, 1]`, which the 8-bit output clamps anyway).
    pub fn identity(n: usize) -> Tone {
        let k: Vec<f32> = (0..n).map(|i| i as f32 / (n - 1) as f32).collect();
        Tone {
            enabled: true,
            range: [[0.0, 1.0]; 3],
            knots: [k.clone(), k.clone(), k],
        }
    }

    /// The curve as a function of (channel, value), its tangents computed once (CPU-side, e.g.
    /// for fitting and morphing; the renderer uses its flattened twin
    /// [`crate::render::tone_eval`]).
    pub fn curve(&self) -> impl Fn(usize, f32) -> f32 + '_ {
        let tangents = self
            .knots
            .clone()
            .map(|k| crate::histogram::fc_tangents(&k));
        move |c, v| {
            let [lo, hi] = self.range[c];
            crate::histogram::spline_eval(&self.knots[c], &tangents[c], (v - lo) / (hi - lo))
        }
    }

    /// The curve of channel `c` at `v`, once (see [`Tone::curve`] for many values).
    pub fn eval(&self, c: usize, v: f32) -> f32 {
        self.curve()(c, v)
    }

    fn validate(&self, at: &str) -> Result<()> {
        let n = self.knots[0].len();
        for c in 0..3 {
            let k = &self.knots[c];
            if k.len() != n || !(2..=MAX_TONE_KNOTS).contains(&k.len()) {
                return Err(Error::params(
                    format!("{at}.knots[{c}]"),
                    format!(
                        "must have 2 to {MAX_TONE_KNOTS} knots, as many as channel 0, has {}",
                        k.len()
                    ),
                ));
            }
            for (i, &v) in k.iter().enumerate() {
                check_range(&format!("{at}.knots[{c}][{i}]"), v, -4.0, 4.0)?;
            }
            if k.windows(2).any(|w| w[1] < w[0]) {
                return Err(Error::params(
                    format!("{at}.knots[{c}]"),
                    "knots must be non-decreasing",
                ));
            }
            let [lo, hi] = self.range[c];
            check_range(&format!("{at}.range[{c}][0]"), lo, -4.0, 4.0)?;
            check_range(&format!("{at}.range[{c}][1]"), hi, -4.0, 4.0)?;
            if hi - lo < 1e-4 {
                return Err(Error::params(
                    format!("{at}.range[{c}]"),
                    format!("must have lo < hi (by at least 1e-4), has [{lo}, {hi}]"),
                ));
            }
        }
        Ok(())
    }
}

impl Model {
    /// The output tone curve, enabled or not: the noise model's or the structured model's.
    pub fn tone(&self) -> Option<&Tone> {
        match self {
            Model::Noise(n) => n.tone.as_ref(),
            Model::Structured(s) => s.tone.as_ref(),
        }
    }

    /// The noise layer: the whole model for noise, the residual for structured models.
    pub fn noise_layer(&self) -> &NoiseModel {
        match self {
            Model::Noise(n) => n,
            Model::Structured(s) => &s.residual,
        }
    }

    /// The noise layer, mutably.
    pub fn noise_layer_mut(&mut self) -> &mut NoiseModel {
        match self {
            Model::Noise(n) => n,
            Model::Structured(s) => &mut s.residual,
        }
    }

    /// The pattern, for structured models.
    pub fn pattern(&self) -> Option<&Pattern> {
        match self {
            Model::Noise(_) => None,
            Model::Structured(s) => Some(&s.pattern),
        }
    }

    /// A short name: "noise" or the pattern's kind.
    pub fn name(&self) -> &'static str {
        match self {
            Model::Noise(_) => "noise",
            Model::Structured(s) => s.pattern.kind.name(),
        }
    }
}

/// Lagae's model: for each decorrelated channel `c`, `M_c(u) = Σ_j w_cj N_c(u·2^−j + o_j)`,
/// optionally mapped through the channel's inverse CDF. (Lagae draws each channel's band from
/// one noise at its own offset `o_cj`; here channel `c` reads the tile's own component `N_c` at
/// the band's offset: independent fields all the same, one texture fetch for all three.)
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoiseModel {
    /// Band weights per channel, finest band first; all three the same length.
    pub weights: [Vec<f32>; 3],
    /// Histogram matching.
    pub histogram: Histogram,
    /// Per band (finest first), shared by the three channels: the orientation of its features
    /// ([`crate::noise::oriented`]). Empty: every band isotropic (documents from before it
    /// load unchanged); otherwise one entry per band.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub orientation: Vec<BandOrientation>,
    /// The noise model's output tone curve per RGB channel, applied after the decorrelated
    /// channels are rotated back (absent: none; documents from before it load unchanged). The
    /// histogram spline matches the photo's distribution along the decorrelated axes; this
    /// curve then matches it along the RGB axes, one round of iterative distribution transfer
    /// (Pitié et al. 2005), which recovers some of the channels' joint distribution that
    /// independent channels lose ([`crate::noise_tone`]). A structured model's residual has
    /// none: the structured model's own curve applies last.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tone: Option<Tone>,
    /// Per decorrelated channel, the amplitude of the finest band drawn after the histogram
    /// matching (channel units): `M_c = F_c⁻¹(Φ(Σ_j w_cj N_c(…)/σ_c)) + fine_c·g(N_c(u + o_0))`,
    /// `g` the bound of [`crate::render::fine_value`] (unit variance). Zero (documents from before
    /// it load unchanged): Lagae's model, every band through the histogram. Departure from Lagae
    /// towards Heeger & Bergen, who match each subband's histogram on its own: a histogram on the
    /// sum of all bands puts its tails on the finest band as often as on coarse ones, and a tail
    /// value on a pixel-scale band is an isolated outlier pixel (a speck), while a photo's tails
    /// are coarse (dark spots, edges). So analysis draws the finest band apart, after the
    /// histogram, with its share of the channel's variance, and leaves the tails to the coarser
    /// bands ([`NoiseModel::finest_band_gaussian`]). Measured on the development set (every
    /// quadrant, seed 1): renders within 1.5× of their photo's specks 170 → 180 of 208 (the noise
    /// model's 115 → 121 of 124), auto's fidelity paired −0.004 ± 0.003 structured, −0.003 ± 0.005
    /// stochastic (docs/devset.md). The part itself is bounded, not Gaussian
    /// ([`crate::render::fine_value`]): its own tails made specks too.
    #[serde(default, skip_serializing_if = "is_zero3")]
    pub fine: [f32; 3],
}

fn is_zero3(v: &[f32; 3]) -> bool {
    *v == [0.0; 3]
}

/// The orientation of one band: its power follows `1 + s·cos 2(θ − θ₀)` with `θ₀` across the
/// streaks, so that features stretch along `angle_deg`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BandOrientation {
    /// Direction the features run along, degrees in texel coordinates (the sense of
    /// [`Transform::rotation_deg`]), in `[−360, 360]`; analysis writes `[0, 180)`. Angles
    /// 180° apart give the same streaks, as another realisation (the band's derivative
    /// changes sign), so sliders and morphs turn them continuously.
    pub angle_deg: f32,
    /// 0: isotropic; 1: all of the band's power across the streaks (a `cos²` profile).
    pub strength: f32,
}

/// Histogram matching: inverse CDF knots per channel at probabilities `Φ(−2.5 + 5j/K)` (see
/// [`crate::histogram`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Histogram {
    /// Whether synthesis applies it (the knots are kept either way, for toggling).
    pub enabled: bool,
    /// `K + 1` non-decreasing knots per channel, in decorrelated channel units.
    pub knots: [Vec<f32>; 3],
}

/// Provenance of an analysis.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Source {
    /// Photo width (after orientation).
    pub width: u32,
    /// Photo height (after orientation).
    pub height: u32,
    /// Crop in photo pixels, `[x, y, w, h]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub crop: Option<[u32; 4]>,
    /// Size of the analysed image.
    pub analysis_width: u32,
    /// Size of the analysed image.
    pub analysis_height: u32,
    /// Which band-weight estimator produced the weights.
    pub estimator: String,
    /// The photo's lighting gradient was divided out before the analysis
    /// ([`crate::analyze::Options::flatten_lighting`]); absent: the pixels as they were.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub flattened_lighting: bool,
}

impl Params {
    /// The noise model, if that is the model.
    pub fn noise(&self) -> Option<&NoiseModel> {
        match &self.model {
            Model::Noise(n) => Some(n),
            Model::Structured(_) => None,
        }
    }

    /// Pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("params always serialise")
    }

    /// Parses and validates a params document.
    pub fn from_json(text: &str) -> Result<Params> {
        let value = crate::json::parse(text).map_err(|e| {
            let hint = if text.contains("NaN") || text.contains("Infinity") {
                " (NaN and Infinity are not JSON numbers)"
            } else {
                ""
            };
            Error::params("(document)", format!("not valid JSON: {e}{hint}"))
        })?;
        match value.get("format") {
            Some(serde_json::Value::String(f)) if f == FORMAT => {}
            Some(serde_json::Value::String(f)) => {
                return Err(Error::params(
                    "format",
                    format!(
                        "unsupported format `{}`; this version reads `{FORMAT}`",
                        crate::limits::quote(f)
                    ),
                ));
            }
            Some(_) => return Err(Error::params("format", "must be a string")),
            None => {
                return Err(Error::params(
                    "format",
                    format!("missing; a params document starts with \"format\": \"{FORMAT}\""),
                ));
            }
        }
        let mut params: Params = serde_path_to_error::deserialize(value).map_err(|e| {
            let path = e.path().to_string();
            Error::params(
                crate::limits::quote(&path),
                crate::limits::bounded_message(&e.into_inner().to_string()),
            )
        })?;
        if let Model::Structured(m) = &mut params.model {
            // Ranges narrowed since (see `pattern`'s module docs): old presets still load.
            m.pattern.clamp_values();
        }
        params.validate()?;
        Ok(params)
    }

    /// Checks every field: lengths, finiteness, ranges, and the invariants the renderer needs.
    pub fn validate(&self) -> Result<()> {
        if self.format != FORMAT {
            return Err(Error::params(
                "format",
                format!("unsupported format `{}`", self.format),
            ));
        }
        check_range("transform.scale", self.transform.scale, 1e-4, 1e6)?;
        check_range(
            "transform.rotation_deg",
            self.transform.rotation_deg,
            -3600.0,
            3600.0,
        )?;
        check_range("colour.contrast", self.colour.contrast, 0.0, MAX_CONTRAST)?;
        for c in 0..3 {
            check_range(&format!("colour.mean[{c}]"), self.colour.mean[c], 0.0, 1.0)?;
            for k in 0..3 {
                check_range(
                    &format!("colour.basis[{c}][{k}]"),
                    self.colour.basis[c][k],
                    -1.0001,
                    1.0001,
                )?;
            }
        }
        let b = self.colour.basis.map(|r| r.map(|v| v as f64));
        for i in 0..3 {
            for j in 0..3 {
                let d = crate::colour::dot(b[i], b[j]);
                let want = if i == j { 1.0 } else { 0.0 };
                if (d - want).abs() > 1e-3 {
                    return Err(Error::params(
                        "colour.basis",
                        "rows must be orthonormal (a rotation matrix)",
                    ));
                }
            }
        }
        if crate::colour::det3(b) <= 0.0 {
            return Err(Error::params(
                "colour.basis",
                "must be a proper rotation (determinant +1), not a reflection",
            ));
        }
        match &self.model {
            Model::Noise(n) => n.validate("model"),
            Model::Structured(s) => s.validate("model"),
        }?;
        if let Some(s) = &self.source
            && (s.width == 0 || s.height == 0 || s.analysis_width == 0 || s.analysis_height == 0)
        {
            return Err(Error::params("source", "sizes must be positive"));
        }
        Ok(())
    }
}

impl NoiseModel {
    /// Number of bands.
    pub fn bands(&self) -> usize {
        self.weights[0].len()
    }

    /// Model standard deviation per channel, `σ_M = sqrt(Σ w²)` (Lagae eq. 2 with `σ²_N = 1`).
    pub fn sigma(&self) -> [f32; 3] {
        [0, 1, 2].map(|c| {
            self.weights[c]
                .iter()
                .map(|&w| (w as f64).powi(2))
                .sum::<f64>()
                .sqrt() as f32
        })
    }

    /// Moves the finest band out of the histogram ([`NoiseModel::fine`]): drawn after it
    /// (bounded, [`crate::render::fine_value`]) with its share of the channel's variance,
    /// `fine = sd(F⁻¹(Φ(Z))) · w₀/σ`, the histogram's knots shrunk about their median by
    /// `σ_coarse / σ`, so that the channel keeps its variance (`σ_coarse² + w₀² = σ²`). With the
    /// histogram off the render is the same sum of bands but for the finest band's tails, which
    /// the bound takes (at the same variance). A channel whose finest band is silent or whose
    /// only band it is stays as it is.
    pub fn finest_band_gaussian(&mut self) {
        let sigma = self.sigma();
        for c in 0..3 {
            let w0 = self.weights[c][0];
            let s = sigma[c] as f64;
            let rest = (s * s - (w0 as f64).powi(2)).max(0.0).sqrt();
            if w0 == 0.0 || rest == 0.0 {
                continue;
            }
            if self.histogram.enabled {
                let knots = &self.histogram.knots[c];
                let spread = crate::histogram::spline_sd(knots);
                let median = knots[knots.len() / 2];
                let shrink = (rest / s) as f32;
                for v in self.histogram.knots[c].iter_mut() {
                    *v = (median + shrink * (*v - median)).clamp(-2.0, 2.0);
                }
                self.fine[c] = (spread * w0 as f64 / s).clamp(0.0, 4.0) as f32;
            } else {
                self.fine[c] = w0;
            }
            self.weights[c][0] = 0.0;
        }
    }

    /// Band `j`'s orientation (isotropic when none is stored).
    pub fn band_orientation(&self, j: usize) -> BandOrientation {
        self.orientation.get(j).copied().unwrap_or(BandOrientation {
            angle_deg: 0.0,
            strength: 0.0,
        })
    }

    fn validate(&self, at: &str) -> Result<()> {
        let nb = self.weights[0].len();
        for c in 0..3 {
            let w = &self.weights[c];
            let field = format!("{at}.weights[{c}]");
            if w.is_empty() || w.len() > MAX_BANDS {
                return Err(Error::params(
                    field,
                    format!("must have 1 to {MAX_BANDS} bands, has {}", w.len()),
                ));
            }
            if w.len() != nb {
                return Err(Error::params(
                    field,
                    format!(
                        "has {} bands but channel 0 has {nb}; all channels need the same count",
                        w.len()
                    ),
                ));
            }
            for (j, &v) in w.iter().enumerate() {
                check_range(&format!("{at}.weights[{c}][{j}]"), v, 0.0, 4.0)?;
            }
        }
        for (c, &v) in self.fine.iter().enumerate() {
            check_range(&format!("{at}.fine[{c}]"), v, 0.0, 4.0)?;
        }
        if !self.orientation.is_empty() && self.orientation.len() != nb {
            return Err(Error::params(
                format!("{at}.orientation"),
                format!(
                    "has {} bands but the weights have {nb}; give one entry per band or none",
                    self.orientation.len()
                ),
            ));
        }
        for (j, o) in self.orientation.iter().enumerate() {
            check_range(
                &format!("{at}.orientation[{j}].angle_deg"),
                o.angle_deg,
                -360.0,
                360.0,
            )?;
            check_range(
                &format!("{at}.orientation[{j}].strength"),
                o.strength,
                0.0,
                1.0,
            )?;
        }
        let nk = self.histogram.knots[0].len();
        for c in 0..3 {
            let k = &self.histogram.knots[c];
            let field = format!("{at}.histogram.knots[{c}]");
            if k.len() < 2 || k.len() > MAX_KNOTS {
                return Err(Error::params(
                    field,
                    format!("must have 2 to {MAX_KNOTS} knots, has {}", k.len()),
                ));
            }
            if k.len() != nk {
                return Err(Error::params(
                    field,
                    format!("has {} knots but channel 0 has {nk}", k.len()),
                ));
            }
            for (j, &v) in k.iter().enumerate() {
                check_range(&format!("{at}.histogram.knots[{c}][{j}]"), v, -2.0, 2.0)?;
            }
            if k.windows(2).any(|w| w[1] < w[0]) {
                return Err(Error::params(
                    field,
                    "knots must be non-decreasing (an inverse CDF)",
                ));
            }
        }
        if let Some(tone) = &self.tone {
            tone.validate(&format!("{at}.tone"))?;
        }
        Ok(())
    }
}

impl StructuredModel {
    fn validate(&self, at: &str) -> Result<()> {
        let p = &self.pattern;
        check_range(&format!("{at}.pattern.scale"), p.scale, 1e-2, 1e5)?;
        check_range(
            &format!("{at}.pattern.rotation_deg"),
            p.rotation_deg,
            -3600.0,
            3600.0,
        )?;
        let specs = p.kind.specs();
        for (name, &v) in &p.values {
            let Some(s) = specs.iter().find(|s| s.name == name) else {
                let known: Vec<&str> = specs.iter().map(|s| s.name).collect();
                return Err(Error::params(
                    format!("{at}.pattern.values.{name}"),
                    format!(
                        "`{name}` is not a parameter of `{}` (it has: {})",
                        p.kind.name(),
                        known.join(", ")
                    ),
                ));
            };
            check_range(&format!("{at}.pattern.values.{name}"), v, s.min, s.max)?;
        }
        let n = self.ramp.len();
        if !(2..=MAX_STOPS).contains(&n) {
            return Err(Error::params(
                format!("{at}.ramp"),
                format!("must have 2 to {MAX_STOPS} stops, has {n}"),
            ));
        }
        for (i, stop) in self.ramp.iter().enumerate() {
            check_range(&format!("{at}.ramp[{i}].at"), stop.at, 0.0, 1.0)?;
            for c in 0..3 {
                check_range(&format!("{at}.ramp[{i}].rgb[{c}]"), stop.rgb[c], 0.0, 1.0)?;
            }
        }
        if self.ramp.windows(2).any(|w| w[1].at < w[0].at) {
            return Err(Error::params(
                format!("{at}.ramp"),
                "stops must be in non-decreasing order of `at`",
            ));
        }
        if let Some(tone) = &self.tone {
            tone.validate(&format!("{at}.tone"))?;
        }
        if self.residual.tone.is_some() {
            return Err(Error::params(
                format!("{at}.residual.tone"),
                "a residual has no tone curve of its own (the structured model's `tone` applies last)",
            ));
        }
        self.residual.validate(&format!("{at}.residual"))
    }
}

fn check_range(field: &str, v: f32, lo: f32, hi: f32) -> Result<()> {
    if !v.is_finite() {
        return Err(Error::params(field, format!("must be finite, got {v}")));
    }
    if v < lo || v > hi {
        return Err(Error::params(
            field,
            format!("{v} is outside the allowed range [{lo}, {hi}]"),
        ));
    }
    Ok(())
}

/// A structured params shell around `pattern` (flat grey ramp, silent residual): what the
/// pattern functions need to render `s`, and the start of a fit.
pub fn pattern_shell(pattern: Pattern, seed: u32, solid: bool) -> Params {
    Params {
        format: FORMAT.into(),
        seed,
        solid,
        transform: Transform {
            scale: 1.0,
            rotation_deg: 0.0,
        },
        colour: Colour {
            mean: [0.5; 3],
            basis: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            contrast: 1.0,
        },
        model: Model::Structured(StructuredModel {
            pattern,
            ramp: vec![
                RampStop {
                    at: 0.0,
                    rgb: [0.0; 3],
                },
                RampStop {
                    at: 1.0,
                    rgb: [1.0; 3],
                },
            ],
            residual: NoiseModel {
                weights: [vec![0.0], vec![0.0], vec![0.0]],
                histogram: Histogram {
                    enabled: false,
                    knots: [vec![0.0, 0.0], vec![0.0, 0.0], vec![0.0, 0.0]],
                },
                orientation: Vec::new(),
                tone: None,
                fine: [0.0; 3],
            },
            tone: None,
        }),
        source: None,
    }
}
