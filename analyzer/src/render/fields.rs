//! What a render draws before it colours: per pixel, the pattern's structure value and every
//! channel's band noise. The structured fit renders one pattern with one seed many times over,
//! changing only its colours (ramp, residual amplitudes and histogram, tone curve); drawing
//! these once makes each further render a per-pixel colour mapping with the same bits.

use super::pattern::{pattern, ramp};
use super::{Image, Prepared, View, band_noise, band_sum, colour, tile_for};
use crate::params::Params;

/// The colour-independent per-pixel values of a render of some params at some size and view.
/// [`render_with_fields`] uses them for any params that share the pattern, its placement, the
/// seed, the residual's band count and the noise transform; it draws afresh otherwise.
#[derive(Clone, Debug)]
pub struct Fields {
    /// What the values depend on ([`fields_key`]).
    key: Vec<u32>,
    /// Bands per channel.
    bands: usize,
    /// Per pixel, [`Fields::stride`] values: the pattern's structure value (0 for the noise
    /// model), then per channel, per band, the band's noise value (0 where the band is faded
    /// out at this view's footprint, which the colouring then skips).
    values: Vec<f32>,
}

impl Fields {
    /// Draws the fields of `params` rendered at `width × height` of `view` (with its own tile,
    /// as [`super::render`] does).
    pub fn new(params: &Params, width: u32, height: u32, view: &View) -> Fields {
        let prep = Prepared::new(params);
        let tile = tile_for(params);
        let log2_fp = (view.pixel_size * prep.inv_scale).log2();
        let bands = prep.bands as usize;
        let stride = 1 + 3 * bands;
        let structured = prep.pattern[0] != 0;
        let faded: Vec<bool> = (0..bands)
            .map(|j| crate::noise::band_fade(j as u32, log2_fp) == 0.0)
            .collect();
        let row = |y: usize, out: &mut [f32]| {
            let wy = view.origin[1] + (y as f32 + 0.5) * view.pixel_size;
            for (x, px) in out.chunks_exact_mut(stride).enumerate() {
                let wx = view.origin[0] + (x as f32 + 0.5) * view.pixel_size;
                let u = prep.texel([wx, wy, view.z]);
                if structured {
                    px[0] = pattern(&prep, &tile, u, log2_fp);
                }
                for j in (0..bands).filter(|&j| !faded[j]) {
                    let v = band_noise(&prep, &tile, j, u);
                    for c in 0..3 {
                        px[1 + c * bands + j] = v[c];
                    }
                }
            }
        };
        let mut values = vec![0.0f32; width as usize * height as usize * stride];
        if width > 0 {
            let line = width as usize * stride;
            #[cfg(not(target_arch = "wasm32"))]
            {
                use rayon::prelude::*;
                values
                    .par_chunks_mut(line)
                    .enumerate()
                    .for_each(|(y, out)| row(y, out));
            }
            #[cfg(target_arch = "wasm32")]
            for (y, out) in values.chunks_mut(line).enumerate() {
                row(y, out);
            }
        }
        Fields {
            key: fields_key(&prep, width, height, view),
            bands,
            values,
        }
    }

    /// Whether these are the fields of `prep` rendered at `width × height` of `view`.
    pub fn fit(&self, prep: &Prepared, width: u32, height: u32, view: &View) -> bool {
        self.key == fields_key(prep, width, height, view)
    }
}

/// Everything a render reads before its colouring (see [`super::shade`]): the image's size and
/// view; whether solid, the noise transform, the residual's band count, band offsets and band
/// orientations (each band's mixing with its derivative, read by [`band_noise`]); the pattern's
/// kind, seed, placement, values and octave offsets. Bit patterns, so that equal keys mean
/// bit-identical fields.
fn fields_key(prep: &Prepared, width: u32, height: u32, view: &View) -> Vec<u32> {
    let mut k = vec![
        width,
        height,
        view.origin[0].to_bits(),
        view.origin[1].to_bits(),
        view.pixel_size.to_bits(),
        view.z.to_bits(),
        prep.solid as u32,
        prep.bands,
        prep.inv_scale.to_bits(),
        prep.rot[0].to_bits(),
        prep.rot[1].to_bits(),
        prep.pattern[0],
        prep.pattern[2],
    ];
    k.extend(prep.pattern_transform.map(f32::to_bits));
    k.extend(prep.pattern_values.map(f32::to_bits));
    k.extend(prep.pattern_offsets.iter().flatten().map(|v| v.to_bits()));
    let bands = prep.bands as usize;
    k.extend(prep.offsets[..bands].iter().flatten().map(|v| v.to_bits()));
    k.extend(prep.orient[..bands].iter().flatten().map(|v| v.to_bits()));
    k
}

/// [`super::render`] of `params` at `width × height` of `view`, coloured from `fields` where
/// they fit (bit for bit the same image), drawn afresh where they do not.
pub fn render_with_fields(
    params: &Params,
    width: u32,
    height: u32,
    view: &View,
    fields: &Fields,
) -> Image {
    let prep = Prepared::new(params);
    if !fields.fit(&prep, width, height, view) {
        return super::render_prepared(&prep, &tile_for(params), width, height, view);
    }
    let log2_fp = (view.pixel_size * prep.inv_scale).log2();
    let bands = fields.bands;
    let structured = prep.pattern[0] != 0;
    let pixels = fields
        .values
        .chunks_exact(1 + 3 * bands)
        .map(|px| {
            let base = if structured {
                ramp(&prep, px[0])
            } else {
                prep.mean
            };
            let noise = band_sum(&prep, log2_fp, |j| [0, 1, 2].map(|c| px[1 + c * bands + j]));
            colour(&prep, noise, base)
        })
        .collect();
    Image {
        width,
        height,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Model;
    use crate::pattern::{Pattern, PatternKind};

    /// A structured model whose residual has four bands, one of them silent in one channel.
    fn structured(kind: PatternKind, seed: u32) -> Params {
        let mut p = crate::params::pattern_shell(Pattern::new(kind, 9.0), seed, false);
        if let Model::Structured(m) = &mut p.model {
            m.residual.weights = [
                vec![0.2, 0.3, 0.1, 0.05],
                vec![0.1, 0.0, 0.2, 0.1],
                vec![0.3, 0.1, 0.1, 0.0],
            ];
        }
        p
    }

    #[test]
    fn a_render_through_fitting_fields_is_the_render() {
        let view = View {
            origin: [3.0, -5.0],
            pixel_size: 1.5,
            z: 0.0,
        };
        for (kind, seed) in [(PatternKind::Brick, 3), (PatternKind::Ridged, 11)] {
            let p = structured(kind, seed);
            let fields = Fields::new(&p, 37, 21, &view);
            // The same pattern with other colours: a redder ramp, a louder residual.
            let mut q = p.clone();
            if let Model::Structured(m) = &mut q.model {
                m.ramp[0].rgb[0] += 0.2;
                m.residual.weights[1][2] = 0.5;
            }
            for params in [&p, &q] {
                let prep = Prepared::new(params);
                assert!(fields.fit(&prep, 37, 21, &view));
                assert_eq!(
                    render_with_fields(params, 37, 21, &view, &fields),
                    super::super::render(params, 37, 21, &view)
                );
            }
        }
        let noise = crate::analyze::hash_noise_params(48, 5);
        let fields = Fields::new(&noise, 16, 16, &View::default());
        assert_eq!(
            render_with_fields(&noise, 16, 16, &View::default(), &fields),
            super::super::render(&noise, 16, 16, &View::default())
        );
    }

    #[test]
    fn fields_that_do_not_fit_are_not_used() {
        let p = structured(PatternKind::Brick, 3);
        let fields = Fields::new(&p, 24, 24, &View::default());
        let other_seed = Params {
            seed: 4,
            ..p.clone()
        };
        let mut rougher = p.clone();
        if let Model::Structured(m) = &mut rougher.model {
            m.pattern.scale *= 1.1;
        }
        // The residual's third band streaked: the band noise itself changes.
        let mut oriented = p.clone();
        if let Model::Structured(m) = &mut oriented.model {
            m.residual.orientation = vec![
                crate::params::BandOrientation {
                    angle_deg: 0.0,
                    strength: 0.0,
                };
                4
            ];
            m.residual.orientation[2] = crate::params::BandOrientation {
                angle_deg: 30.0,
                strength: 0.8,
            };
        }
        for q in [&other_seed, &rougher, &oriented] {
            assert!(!fields.fit(&Prepared::new(q), 24, 24, &View::default()));
            assert_eq!(
                render_with_fields(q, 24, 24, &View::default(), &fields),
                super::super::render(q, 24, 24, &View::default())
            );
        }
        assert!(!fields.fit(&Prepared::new(&p), 24, 23, &View::default()));
    }
}
