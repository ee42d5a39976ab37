//! Morphing between textures (Lagae et al. 2009, §8 and Fig. 15): interpolate the parameters.
//!
//! Everything interpolates linearly except the colour basis, which interpolates by quaternion
//! slerp so that it stays a rotation at every `t`. Every result validates:
//! - band weights are convex combinations of non-negative weights (a missing band weighs 0);
//! - inverse-CDF knots are convex combinations of non-decreasing sequences, hence
//!   non-decreasing; a histogram that is off takes part as the identity curve
//!   `knot_j = σ·(5j/K − 2.5)` (what "off" renders, within the ±2.5σ knot range), and knots of
//!   a different count are resampled on the spline;
//! - mean colour and contrast stay inside their (convex) ranges.
//!
//! Departures from the paper, both for perceptual smoothness (Bourque & Dudek 2004 ask for
//! transformations that look uniform in `t`):
//! - the scale interpolates geometrically (`s_a^(1−t)·s_b^t`): a linear scale spends most of
//!   `t` near the larger scale when the two differ by a large factor;
//! - the rotation takes the shorter way round (the bands' streak angles and strengths
//!   interpolate linearly: see [`morph_orientation`]).
//!
//! The noise itself (tiles, band offsets) comes from the seed and cannot be interpolated: the
//! morph renders with the first texture's seed all the way (so it is continuous in `t`); at
//! `t = 1` the image equals the second texture's exactly when the seeds agree, as for all
//! analyses with the default seed.

use crate::error::{Error, Result};
use crate::histogram::{KNOT_Z, fc_tangents, spline_eval};
use crate::params::{BandOrientation, Histogram, Model, NoiseModel, Params, Tone};

pub use crate::colour::{Quat, matrix_from_quat, quat_from_matrix, slerp};

/// The inverse-CDF knots a noise model renders with: its own when the histogram is on, the
/// identity curve otherwise; resampled to `k + 1` knots.
pub(crate) fn effective_knots(m: &NoiseModel, k: usize) -> [Vec<f32>; 3] {
    let sigma = m.sigma();
    [0, 1, 2].map(|c| {
        (0..=k)
            .map(|j| {
                let u = j as f32 / k as f32;
                if m.histogram.enabled {
                    let knots = &m.histogram.knots[c];
                    if knots.len() == k + 1 {
                        knots[j]
                    } else {
                        spline_eval(knots, &fc_tangents(knots), u)
                    }
                } else {
                    sigma[c] * (2.0 * KNOT_Z * u - KNOT_Z)
                }
            })
            .collect()
    })
}

/// The turn from angle `a` to angle `b` (degrees) the shorter way round.
pub(crate) fn shorter_turn(a: f32, b: f32) -> f32 {
    let dr = (b - a).rem_euclid(360.0);
    if dr > 180.0 { dr - 360.0 } else { dr }
}

/// The band orientations a fraction `t` of the way: strengths and angles linearly; a band
/// without strength at one end takes the other end's angle (its angle shows nothing there), so
/// that a fading orientation does not sweep round. Angles do not take the shorter way modulo
/// 180°: angles 180° apart draw the same streaks but with the band's derivative negated, so
/// the shorter way would end on the other sign and jump to the second texture at `t = 1`.
pub(crate) fn morph_orientation(
    ma: &NoiseModel,
    mb: &NoiseModel,
    bands: usize,
    t: f32,
) -> Vec<BandOrientation> {
    if ma.orientation.is_empty() && mb.orientation.is_empty() {
        return Vec::new();
    }
    (0..bands)
        .map(|j| {
            let (oa, ob) = orientation_ends(ma, mb, j);
            BandOrientation {
                angle_deg: lerp(oa.angle_deg, ob.angle_deg, t),
                strength: morph_strength(oa.strength, ob.strength, t),
            }
        })
        .collect()
}

/// An orientation strength a fraction `t` of the way: the band's amplitudes are `√(1 − s)`
/// (isotropic) and `√s` (derivative), `cos φ` and `sin φ` of `φ = asin √s`, so `φ` moves
/// linearly. Linear `s` would move an amplitude by a fifth in the first twentieth of the way
/// from `s = 0` or to `s = 1` (a visible jump in the morph tests); the ends exactly.
pub(crate) fn morph_strength(a: f32, b: f32, t: f32) -> f32 {
    if t == 0.0 {
        return a;
    }
    if t == 1.0 {
        return b;
    }
    let phi = lerp(strength_phase(a), strength_phase(b), t);
    (phi.sin() * phi.sin()).clamp(0.0, 1.0)
}

/// `asin √s`: the strength as the phase [`morph_strength`] interpolates.
pub(crate) fn strength_phase(s: f32) -> f32 {
    s.clamp(0.0, 1.0).sqrt().asin()
}

/// Band `j`'s orientation at both ends of a morph, a strengthless end's angle replaced by the
/// other's.
pub(crate) fn orientation_ends(
    ma: &NoiseModel,
    mb: &NoiseModel,
    j: usize,
) -> (BandOrientation, BandOrientation) {
    let (mut oa, mut ob) = (ma.band_orientation(j), mb.band_orientation(j));
    if oa.strength == 0.0 {
        oa.angle_deg = ob.angle_deg;
    } else if ob.strength == 0.0 {
        ob.angle_deg = oa.angle_deg;
    }
    (oa, ob)
}

fn lerp(a: f32, b: f32, t: f32) -> f32 {
    a + t * (b - a)
}

/// The texture a fraction `t ∈ [0, 1]` of the way from `a` to `b`.
pub fn morph(a: &Params, b: &Params, t: f32) -> Result<Params> {
    if !(0.0..=1.0).contains(&t) {
        return Err(Error::Option(format!("morph t = {t} is not in [0, 1]")));
    }
    let (ma, mb) = (a.model.noise_layer(), b.model.noise_layer());
    let mut out = a.clone();
    out.source = None;
    out.transform.scale = (a.transform.scale.ln() * (1.0 - t) + b.transform.scale.ln() * t).exp();
    let dr = shorter_turn(a.transform.rotation_deg, b.transform.rotation_deg);
    out.transform.rotation_deg = a.transform.rotation_deg + t * dr;
    for c in 0..3 {
        out.colour.mean[c] = lerp(a.colour.mean[c], b.colour.mean[c], t).clamp(0.0, 1.0);
    }
    out.colour.contrast = lerp(a.colour.contrast, b.colour.contrast, t);
    let to64 = |m: [[f32; 3]; 3]| m.map(|r| r.map(|v| v as f64));
    let q = slerp(
        quat_from_matrix(to64(a.colour.basis)),
        quat_from_matrix(to64(b.colour.basis)),
        t as f64,
    );
    out.colour.basis = matrix_from_quat(q).map(|r| r.map(|v| v as f32));
    // Endpoints exactly (the quaternion round trip is only accurate to rounding).
    if t == 0.0 {
        out.colour.basis = a.colour.basis;
    } else if t == 1.0 {
        out.colour.basis = b.colour.basis;
    }

    let bands = ma.bands().max(mb.bands());
    let weight = |m: &NoiseModel, c: usize, j: usize| m.weights[c].get(j).copied().unwrap_or(0.0);
    let weights = [0, 1, 2].map(|c| {
        (0..bands)
            .map(|j| lerp(weight(ma, c, j), weight(mb, c, j), t).max(0.0))
            .collect::<Vec<f32>>()
    });
    let k = ma.histogram.knots[0].len().max(mb.histogram.knots[0].len()) - 1;
    let (ka, kb) = (effective_knots(ma, k), effective_knots(mb, k));
    let knots = [0, 1, 2].map(|c| {
        let mut v: Vec<f32> = (0..=k).map(|j| lerp(ka[c][j], kb[c][j], t)).collect();
        // Rounding must not break monotonicity.
        for j in 1..v.len() {
            v[j] = v[j].max(v[j - 1]);
        }
        v
    });
    let enabled = ma.histogram.enabled || mb.histogram.enabled;
    let noise = NoiseModel {
        orientation: morph_orientation(ma, mb, bands, t),
        tone: None,
        fine: [0, 1, 2].map(|c| lerp(ma.fine[c], mb.fine[c], t).max(0.0)),
        weights,
        histogram: Histogram {
            enabled,
            knots: if enabled {
                knots
            } else {
                ma.histogram.knots.clone()
            },
        },
    };
    out.model = morph_structure(a, b, t, out.colour.mean, noise);
    if t == 1.0 && a.seed == b.seed {
        // Exactly the second texture (bands and knots as it has them).
        let mut end = b.clone();
        end.source = None;
        return Ok(end);
    }
    if t == 0.0 {
        let mut start = a.clone();
        start.source = None;
        return Ok(start);
    }
    out.validate()?;
    Ok(out)
}

/// The model a fraction `t` of the way from `a`'s to `b`'s, given the interpolated mean and
/// noise layer.
///
/// Same pattern family: its scale (geometrically), rotation (the shorter way) and values
/// interpolate, and so do the ramps (both evaluated at the union of their stops). Different
/// families (a noise model counts as the flat ramp at the mean colour): a cross-fade through
/// the noise layer. The first half fades the first pattern's ramp to the flat mean colour, the
/// second half fades the second's in, so the pattern switches at `t = ½` where the ramp is flat
/// and the switch is invisible: continuous in `t`, with no second pattern in the shader.
fn morph_structure(a: &Params, b: &Params, t: f32, mean: [f32; 3], noise: NoiseModel) -> Model {
    use crate::pattern::{Pattern, RampStop};
    let flat = |stops: &[RampStop]| -> Vec<RampStop> {
        stops
            .iter()
            .map(|s| RampStop {
                at: s.at,
                rgb: mean,
            })
            .collect()
    };
    let tone_of = |m: &Model| m.tone().filter(|t| t.enabled).cloned();
    let (ta, tb) = (tone_of(&a.model), tone_of(&b.model));
    // A noise model's own output tone curve fades like a structured model's.
    let noise_with = |tone: Option<Tone>| {
        Model::Noise(NoiseModel {
            tone,
            ..noise.clone()
        })
    };
    let structured = |pattern: Pattern, ramp: Vec<RampStop>, tone: Option<Tone>| {
        Model::Structured(crate::params::StructuredModel {
            pattern,
            ramp,
            residual: noise.clone(),
            tone,
        })
    };
    match (&a.model, &b.model) {
        (Model::Noise(_), Model::Noise(_)) => noise_with(lerp_tones(ta.as_ref(), tb.as_ref(), t)),
        (Model::Structured(sa), Model::Structured(sb)) if sa.pattern.kind == sb.pattern.kind => {
            let (pa, pb) = (&sa.pattern, &sb.pattern);
            let mut pattern = pa.clone();
            pattern.scale = (pa.scale.ln() * (1.0 - t) + pb.scale.ln() * t).exp();
            pattern.rotation_deg =
                pa.rotation_deg + t * shorter_turn(pa.rotation_deg, pb.rotation_deg);
            let (va, vb) = (pa.vector(), pb.vector());
            let values: Vec<f32> = va.iter().zip(&vb).map(|(&x, &y)| lerp(x, y, t)).collect();
            pattern.set_vector(&values);
            structured(
                pattern,
                lerp_ramps(&sa.ramp, &sb.ramp, t),
                lerp_tones(ta.as_ref(), tb.as_ref(), t),
            )
        }
        _ if t < 0.5 => match &a.model {
            Model::Structured(sa) => structured(
                sa.pattern.clone(),
                lerp_ramps(&sa.ramp, &flat(&sa.ramp), 2.0 * t),
                lerp_tones(ta.as_ref(), None, 2.0 * t),
            ),
            Model::Noise(_) => noise_with(lerp_tones(ta.as_ref(), None, 2.0 * t)),
        },
        _ => match &b.model {
            Model::Structured(sb) => structured(
                sb.pattern.clone(),
                lerp_ramps(&flat(&sb.ramp), &sb.ramp, 2.0 * t - 1.0),
                lerp_tones(None, tb.as_ref(), 2.0 * t - 1.0),
            ),
            Model::Noise(_) => noise_with(lerp_tones(None, tb.as_ref(), 2.0 * t - 1.0)),
        },
    }
}

/// Two output tone curves blended (`None`: no curve, i.e. the identity): both evaluated at
/// evenly spaced inputs over the union of their ranges (the identity's is `[0, 1]`, outside
/// which the output clamps anyway), as many knots as the finer one. The ends are exact.
fn lerp_tones(a: Option<&Tone>, b: Option<&Tone>, t: f32) -> Option<Tone> {
    match (a, b) {
        (None, None) => return None,
        (Some(a), _) if t <= 0.0 => return Some(a.clone()),
        (_, Some(b)) if t >= 1.0 => return Some(b.clone()),
        (None, _) if t <= 0.0 => return None,
        (_, None) if t >= 1.0 => return None,
        _ => {}
    }
    let grid = tone_grid(a, b);
    let mut out = Tone::identity(grid.n);
    out.range = grid.range;
    for c in 0..3 {
        let mut prev = f32::NEG_INFINITY;
        for (k, v) in out.knots[c].iter_mut().enumerate() {
            // Rounding must not break monotonicity.
            prev = lerp(grid.a[c][k], grid.b[c][k], t)
                .clamp(-4.0, 4.0)
                .max(prev);
            *v = prev;
        }
    }
    Some(out)
}

/// Where two tone curves blend ([`lerp_tones`]): the knot count, each channel's range, and both
/// curves' values at the knots (`None` as the identity). The exported morph shader interpolates
/// these tables (`shaders/morph.wgsl`).
pub(crate) struct ToneGrid {
    /// Knots per channel.
    pub n: usize,
    /// Per RGB channel: `[lo, hi]`.
    pub range: [[f32; 2]; 3],
    /// The first curve at the knots, per channel.
    pub a: [Vec<f32>; 3],
    /// The second curve at the knots, per channel.
    pub b: [Vec<f32>; 3],
}

/// The grid [`lerp_tones`] blends `a` and `b` on.
pub(crate) fn tone_grid(a: Option<&Tone>, b: Option<&Tone>) -> ToneGrid {
    use crate::params::MAX_TONE_KNOTS;
    let count = |x: Option<&Tone>| x.map_or(2, |x| x.knots[0].len());
    let n = count(a).max(count(b)).clamp(2, MAX_TONE_KNOTS);
    let id = Tone::identity(2);
    let (a, b) = (a.unwrap_or(&id), b.unwrap_or(&id));
    let (ca, cb) = (a.curve(), b.curve());
    let mut range = [[0.0f32; 2]; 3];
    let mut va: [Vec<f32>; 3] = Default::default();
    let mut vb: [Vec<f32>; 3] = Default::default();
    for c in 0..3 {
        let lo = a.range[c][0].min(b.range[c][0]);
        let hi = a.range[c][1].max(b.range[c][1]).max(lo + 1e-4);
        range[c] = [lo, hi];
        for k in 0..n {
            let x = lo + (hi - lo) * k as f32 / (n - 1) as f32;
            va[c].push(ca(c, x));
            vb[c].push(cb(c, x));
        }
    }
    ToneGrid {
        n,
        range,
        a: va,
        b: vb,
    }
}

/// Two ramps blended: both evaluated at the union of their stops (at most
/// [`crate::pattern::MAX_STOPS`], else that many stops evenly over the union's range).
fn lerp_ramps(
    a: &[crate::pattern::RampStop],
    b: &[crate::pattern::RampStop],
    t: f32,
) -> Vec<crate::pattern::RampStop> {
    use crate::pattern::RampStop;
    use crate::render::pattern::ramp_rows;
    let (ra, rb) = (ramp_table(a), ramp_table(b));
    ramp_union(a, b)
        .iter()
        .map(|&x| {
            let (ca, cb) = (ramp_rows(&ra, x), ramp_rows(&rb, x));
            RampStop {
                at: x,
                rgb: [0, 1, 2].map(|c| lerp(ca[c], cb[c], t).clamp(0.0, 1.0)),
            }
        })
        .collect()
}

/// A ramp's stops as rows (RGB, at), as [`crate::pattern::ramp_rows`] takes them.
pub(crate) fn ramp_table(r: &[crate::pattern::RampStop]) -> Vec<[f32; 4]> {
    r.iter()
        .map(|s| [s.rgb[0], s.rgb[1], s.rgb[2], s.at])
        .collect()
}

/// The stops [`lerp_ramps`] evaluates both ramps at: the union of theirs, at most
/// [`crate::pattern::MAX_STOPS`] (else that many evenly over the union's range), at least two.
pub(crate) fn ramp_union(
    a: &[crate::pattern::RampStop],
    b: &[crate::pattern::RampStop],
) -> Vec<f32> {
    use crate::pattern::MAX_STOPS;
    let mut at: Vec<f32> = a.iter().chain(b).map(|s| s.at).collect();
    at.sort_by(f32::total_cmp);
    at.dedup();
    if at.len() > MAX_STOPS {
        let (lo, hi) = (at[0], at[at.len() - 1]);
        at = (0..MAX_STOPS)
            .map(|i| lo + (hi - lo) * i as f32 / (MAX_STOPS - 1) as f32)
            .collect();
    }
    if at.len() < 2 {
        at = vec![at.first().copied().unwrap_or(0.0), 1.0];
    }
    at
}

/// A morph through `keys` (two or more): `t ∈ [0, 1]` spread evenly over the segments.
pub fn morph_path(keys: &[Params], t: f32) -> Result<Params> {
    if keys.len() < 2 {
        return Err(Error::Option("a morph needs two or more textures".into()));
    }
    let t = t.clamp(0.0, 1.0);
    let segments = (keys.len() - 1) as f32;
    let s = (t * segments).min(segments - 1e-6).max(0.0);
    let i = s.floor() as usize;
    let local = if t >= 1.0 { 1.0 } else { s - i as f32 };
    let mut p = morph(&keys[i], &keys[i + 1], local)?;
    p.seed = keys[0].seed;
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tone_curves_blend_with_exact_ends_and_through_the_identity() {
        let a = Tone {
            enabled: true,
            range: [[0.1, 0.9]; 3],
            knots: [0, 1, 2].map(|_| {
                (0..17)
                    .map(|k| 0.2 + 0.6 * (k as f32 / 16.0).powi(2))
                    .collect()
            }),
        };
        assert_eq!(lerp_tones(Some(&a), None, 0.0), Some(a.clone()));
        assert_eq!(lerp_tones(None, Some(&a), 1.0), Some(a.clone()));
        assert_eq!(lerp_tones(Some(&a), None, 1.0), None);
        assert_eq!(lerp_tones(None, None, 0.5), None);
        let mid = lerp_tones(Some(&a), None, 0.5).unwrap();
        assert_eq!(mid.range[0], [0.0, 1.0]);
        for x in [0.2f32, 0.5, 0.8] {
            let want = 0.5 * (a.eval(0, x) + x);
            assert!((mid.eval(0, x) - want).abs() < 0.02, "{x}");
        }
        assert!(mid.knots[1].windows(2).all(|w| w[0] <= w[1]));
    }
}
