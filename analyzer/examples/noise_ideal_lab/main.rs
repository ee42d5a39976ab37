//! Where the noise model loses against its own ideal: a ladder of syntheses from Lagae's ideal
//! design to the model as it renders, each judged by the fidelity protocol (quadrant pairs,
//! seeds 1..S) on the stochastic photos of a manifest, so that each step's cost shows on its
//! own.
//!
//! The rungs (every one: the model's decorrelated channels, independent Gaussian fields,
//! rotated back about the model's mean):
//! 1. `floor`: the random-phase floor (`evaluate::random_phase`: each channel's full 2D power
//!    spectrum, exact histograms), for reference.
//! 2. `octave boxes, exact`: Lagae's design with ideal bands: each channel's power averaged over
//!    octave rings of radial frequency (one box band per octave, Lagae eq. 10), random phases,
//!    rank-matched to the channel's exact values.
//! 3. `octave boxes, knots`: the same fields through the model's histogram (its knots and
//!    spline, `render::colour`) instead of the exact values: the cost of the knots alone.
//! 4. `model bands, exact`: the model's own noise (its wavelet-noise bands and fitted weights,
//!    `render::texture_noise`) rank-matched to the exact values: the cost of the band shapes
//!    and weights alone.
//! 5. `model bands scaled`: the model's noise, each channel scaled to zero mean and the
//!    deviation its knots assume (`sigma`), through its knots: whether the knots' cost on the
//!    model's noise is a mismatch of scale.
//! 6. `fine bands normalised`: the model with each of its three finest bands divided by its own
//!    deviation over the patch's pixels (at one texel per pixel a fine band is sampled at a few
//!    fixed sub-texel phases), through its knots.
//! 7. `model`: the model as it renders (its noise through its knots). Its bands are divided by
//!    the deviation the tile has at each sub-texel phase (`noise::phase_variance2`), the fix
//!    the rungs above pointed to; before that fix this ladder had it as a rung of its own.
//!
//! With `--bands` it runs a second ladder instead, on what finer band resolution could buy, every
//! rung with exact histograms and random phases: the floor, then box bands of one octave, half
//! an octave and a quarter of an octave of radial frequency, then one octave and half an octave
//! each cut into four orientation wedges of 45°.
//!
//! With `--orient`: octave boxes against one orientation profile per octave shared by the
//! channels (`1 + s·cos 2(θ−θ0)`, what `noise::oriented` renders, and a narrow von Mises one).
//! With `--colour`: the oriented octave boxes, then rounds of iterative distribution transfer
//! (rotate the decorrelated channels, rank-match each rotated axis, rotate back): what matching
//! the channels' joint distribution, not only their marginals, could buy.
//!
//! With `--expected`: the model's realisation against ideal fields of its own expected 2D
//! spectrum (the mean periodogram of 16 realisations), with exact and with Gaussian amplitudes,
//! and the realisation with its amplitudes set to the expected ones: what a realisation loses
//! against its spectrum, and whether the amplitudes or the phases lose it.
//! With `--rounds`: the product as it renders (its RGB output curve is one round of
//! distribution transfer), then further rounds along fixed rotations, fitted as the product
//! fits its curve: what more rounds would buy before the parameter budget.
//! With `--marginals` ([`marginals`]): box bands summed as Gaussian fields against the same
//! bands each given the patch's own band marginal first (Heeger & Bergen's subband histograms;
//! `PROCTEX_LAB_SHAPE_ONLY`: the marginal's shape alone, each band keeping its own deviation).
//!
//! Every random-phase rung has exact amplitudes (each frequency's modulus exactly its box's, or
//! the patch's own for the floor) unless `PROCTEX_LAB_GAUSSIAN` is set: then the white noise's
//! own moduli, scaled to the same expected spectrum (a Gaussian field of it, as a procedural
//! noise is). The rung names do not change with it.
//!
//! ```text
//! [PROCTEX_LAB_GAUSSIAN=1] cargo run --release -p proctex-analyzer --example noise_ideal_lab -- \
//!     ../shared/photos/dev/manifest.tsv [SEEDS] [--bands | --orient | --colour | --expected | --rounds | --marginals]
//! ```

#[path = "../lab_common/ladder.rs"]
mod ladder;
mod marginals;
mod realisation;
use ladder::{decorrelated, mean_se, print_ladder, rank_match, run_ladder, stochastic_photos};
use marginals::{MARGINAL_RUNGS, synthesise_marginals};
use proctex::analyze::{Options, analyze_photo};
use proctex::evaluate::random_phase;
use proctex::input::Photo;
use proctex::render::{ChannelNoise, Prepared, colour, texture_noise, tile_for};
use proctex::rng;
use proctex::spectrum::{fft2_real, ifft2, spectrum_real};
use realisation::{EXPECTED_RUNGS, ROUNDS_RUNGS, synthesise_expected, synthesise_rounds};
use rustfft::num_complex::Complex32;

const RUNGS: [&str; 7] = [
    "floor (full spectrum, exact)",
    "octave boxes, exact histograms",
    "octave boxes, the model's knots",
    "the model's bands, exact histograms",
    "the model's bands scaled to its sigma, its knots",
    "the model, its three finest bands at unit deviation on the pixel grid",
    "the model (its bands, its knots)",
];

const BAND_RUNGS: [&str; 6] = [
    "floor (full spectrum, exact)",
    "octave boxes",
    "half-octave boxes",
    "quarter-octave boxes",
    "octave boxes, 4 orientations",
    "half-octave boxes, 4 orientations",
];

/// The `--orient` ladder: what one orientation profile per octave, shared by the three
/// channels, could buy against free wedges (every rung with exact histograms, random phases).
const ORIENT_RUNGS: [&str; 5] = [
    "floor (full spectrum, exact)",
    "octave boxes",
    "octave boxes, 4 orientations",
    "octave boxes, shared profile 1 + s·cos 2(θ−θ0)",
    "octave boxes, shared profile exp(κ·cos 2(θ−θ0))",
];

/// The `--colour` ladder: what matching the channels' joint distribution could buy. Every rung
/// starts from the oriented octave-box fields (the product's ideal), then runs `k` rounds of
/// iterative distribution transfer (Pitié et al. 2005): rotate the decorrelated channels by a
/// fixed rotation, rank-match each rotated axis to the photo's values on it, rotate back.
const COLOUR_RUNGS: [&str; 5] = [
    "oriented octave boxes, per-channel histograms (0 rounds)",
    "+ 1 round of rotation and 1D matching",
    "+ 2 rounds",
    "+ 4 rounds",
    "+ 16 rounds",
];
const COLOUR_ROUNDS: [usize; 5] = [0, 1, 2, 4, 16];

/// A fixed, well-spread rotation for round `r` (Euler angles in golden-ratio steps).
fn round_rotation(r: usize) -> [[f32; 3]; 3] {
    let g = 0.618_034_f64;
    let (a, b, c) = (
        (r as f64 * g).fract() * std::f64::consts::TAU,
        ((r as f64 * g * g).fract() * 2.0 - 1.0).acos(),
        ((r as f64 + 0.5) * g * 3.0).fract() * std::f64::consts::TAU,
    );
    let rz = |t: f64| {
        [
            [t.cos(), -t.sin(), 0.0],
            [t.sin(), t.cos(), 0.0],
            [0.0, 0.0, 1.0],
        ]
    };
    let ry = |t: f64| {
        [
            [t.cos(), 0.0, t.sin()],
            [0.0, 1.0, 0.0],
            [-t.sin(), 0.0, t.cos()],
        ]
    };
    let mul = |x: [[f64; 3]; 3], y: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
        std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| x[i][k] * y[k][j]).sum()))
    };
    mul(mul(rz(a), ry(b)), rz(c)).map(|row| row.map(|v| v as f32))
}

/// Rung `rung` of the `--colour` ladder ([`COLOUR_RUNGS`]).
fn synthesise_colour(rung: usize, src: &Photo, seed: u32) -> Photo {
    let (w, h) = (src.width, src.height);
    let m = model_of(src, seed);
    let fields = profiled_fields(&m.channels, w as usize, h as usize, seed, Profile::Cosine);
    let mut v: [Vec<f32>; 3] = std::array::from_fn(|c| rank_match(&fields[c], &m.channels[c]));
    for r in 0..COLOUR_ROUNDS[rung] {
        let rot = round_rotation(r + 1);
        let project = |x: &[Vec<f32>; 3]| -> [Vec<f32>; 3] {
            std::array::from_fn(|a| {
                (0..x[0].len())
                    .map(|i| (0..3).map(|c| rot[a][c] * x[c][i]).sum())
                    .collect()
            })
        };
        let (pv, pt) = (project(&v), project(&m.channels));
        let matched: [Vec<f32>; 3] = std::array::from_fn(|a| rank_match(&pv[a], &pt[a]));
        v = std::array::from_fn(|c| {
            (0..matched[0].len())
                .map(|i| (0..3).map(|a| rot[a][c] * matched[a][i]).sum())
                .collect()
        });
    }
    to_rgb(&m, &v, w, h)
}

/// Radial bins per octave and orientation wedges of each [`BAND_RUNGS`] rung after the floor.
const BAND_SHAPES: [(f64, usize); 5] = [(1.0, 1), (2.0, 1), (4.0, 1), (1.0, 4), (2.0, 4)];

/// The model of a patch: its prepared block, and its decorrelated channels' exact values.
struct Model {
    prep: Prepared,
    params: proctex::params::Params,
    channels: [Vec<f32>; 3],
}

fn model_of(src: &Photo, seed: u32) -> Model {
    // Lagae's model without the output tone curve: the ladders measure what comes before it
    // (the curve's own effect is measured in the product, `proctex fidelity --no-tone`).
    // Lagae's model: every band through the histogram (the lab rank-matches their sum).
    let opts = Options {
        seed,
        tone: false,
        fine_gaussian: false,
        ..Options::default()
    };
    let params = analyze_photo(src, &opts).expect("analysis").params;
    let prep = Prepared::new(&params);
    let channels = decorrelated(src, &prep);
    Model {
        prep,
        params,
        channels,
    }
}

/// Whether the ladders draw Gaussian amplitudes (`PROCTEX_LAB_GAUSSIAN` set).
fn gaussian_amplitudes() -> bool {
    std::env::var_os("PROCTEX_LAB_GAUSSIAN").is_some()
}

/// The floor: with `PROCTEX_LAB_GAUSSIAN`, each decorrelated channel's own full 2D amplitude
/// spectrum times white noise's moduli (a Gaussian field of the patch's own spectrum), rank
/// matched; else the product's random-phase floor (`evaluate::random_phase`).
fn floor(src: &Photo, seed: u32) -> Photo {
    if !gaussian_amplitudes() {
        return random_phase(src, seed);
    }
    let (w, h) = (src.width as usize, src.height as usize);
    let m = model_of(src, seed);
    let v = std::array::from_fn(|c| {
        let spec = spectrum_real(&m.channels[c], w, h, true);
        let field = random_phase_field(w, h, seed, c, |i| {
            if i == 0 { None } else { Some(spec[i].norm()) }
        });
        rank_match(&field, &m.channels[c])
    });
    to_rgb(&m, &v, src.width, src.height)
}

/// A Gaussian field with `chan`'s power averaged over octave rings (one box band per octave),
/// random phases of `seed`, zero mean.
fn octave_box_field(chan: &[f32], w: usize, h: usize, seed: u32, c: usize) -> Vec<f32> {
    box_field(chan, w, h, seed, c, 1.0, 1)
}

/// The signed frequency (cycles per pixel) of FFT index `i` of a `w × h` image.
fn frequency(i: usize, w: usize, h: usize) -> (f64, f64) {
    let signed = |k: usize, n: usize| if k <= n / 2 { k as f64 } else { k as f64 - n as f64 } / n as f64;
    (signed(i % w, w), signed(i / w, h))
}

/// Channel `c`'s random phases of `seed` (white Gaussian noise's spectrum) with the modulus
/// `amplitude(i)` at FFT index `i` (`None`: zero), back to a real field.
fn random_phase_field(
    w: usize,
    h: usize,
    seed: u32,
    c: usize,
    amplitude: impl Fn(usize) -> Option<f32>,
) -> Vec<f32> {
    let noise: Vec<f32> = (0..w * h)
        .map(|i| rng::gaussian(seed, 0x6f63_7462 + c as u32, i as u32) as f32)
        .collect();
    // `PROCTEX_LAB_GAUSSIAN`: the white noise's own (Rayleigh) moduli kept, scaled so that
    // their expected square is `a²`: a Gaussian field of expected spectrum `a²`, as any
    // procedural noise of that spectrum is, instead of one with the moduli exactly `a`.
    let gaussian = gaussian_amplitudes();
    let unit = 1.0 / ((w * h) as f32).sqrt();
    let shaped: Vec<_> = fft2_real(&noise, w, h)
        .iter()
        .enumerate()
        .map(|(i, ph)| match amplitude(i) {
            Some(a) if gaussian => ph * (a * unit),
            Some(a) => {
                let m = ph.norm();
                if m > 0.0 { ph * (a / m) } else { *ph }
            }
            None => ph * 0.0,
        })
        .collect();
    ifft2(shaped, w, h).iter().map(|v| v.re).collect()
}

/// A Gaussian field with `chan`'s power averaged over boxes of `per_octave` radial bins per
/// octave, each cut into `wedges` orientation wedges over 180°, random phases of `seed`.
fn box_field(
    chan: &[f32],
    w: usize,
    h: usize,
    seed: u32,
    c: usize,
    per_octave: f64,
    wedges: usize,
) -> Vec<f32> {
    let spec = spectrum_real(chan, w, h, true);
    let (bins_of, count) = box_bins(w, h, per_octave, wedges);
    let amplitude = box_amplitudes(&spec, &bins_of, count);
    random_phase_field(w, h, seed, c, |i| bins_of[i].map(|j| amplitude[j]))
}

/// Each box's amplitude: the square root of the mean power of the spectrum `spec` over the FFT
/// indices that [`box_bins`] put in it.
fn box_amplitudes(spec: &[Complex32], bins_of: &[Option<usize>], count: usize) -> Vec<f32> {
    let (mut power, mut bins) = (vec![0.0f64; count], vec![0usize; count]);
    for (s, b) in spec.iter().zip(bins_of) {
        if let Some(j) = b {
            power[*j] += s.norm_sqr() as f64;
            bins[*j] += 1;
        }
    }
    power
        .iter()
        .zip(&bins)
        .map(|(p, &n)| (p / n.max(1) as f64).sqrt() as f32)
        .collect()
}

/// The box of every FFT index of a `w × h` image (`None`: the mean) for boxes of `per_octave`
/// radial bins per octave, each cut into `wedges` orientation wedges over 180°, and the number
/// of boxes.
fn box_bins(w: usize, h: usize, per_octave: f64, wedges: usize) -> (Vec<Option<usize>>, usize) {
    let lowest = ((w.max(h) as f64).log2() * per_octave).floor() as usize;
    let bin = |i: usize| {
        let (fx, fy) = frequency(i, w, h);
        let r = (fx * fx + fy * fy).sqrt();
        if r == 0.0 {
            return None;
        }
        // Radial bin j holds frequencies in (2^-(j+1)/k, 2^-j/k] cycles per pixel for k bins
        // per octave; the lowest takes everything below. The wedge is the orientation modulo
        // 180° (f and −f are one Hermitian pair).
        let radial = ((-r.log2() * per_octave).floor().max(0.0) as usize).min(lowest);
        let angle = fy.atan2(fx).rem_euclid(std::f64::consts::PI);
        let wedge = ((angle / std::f64::consts::PI * wedges as f64) as usize).min(wedges - 1);
        Some(radial * wedges + wedge)
    };
    let bins_of: Vec<Option<usize>> = (0..w * h).map(bin).collect();
    let count = bins_of.iter().flatten().max().map_or(0, |m| m + 1);
    (bins_of, count)
}

/// An orientation profile per octave, fitted from the octave's angular moment
/// `c2 = Σ P(f)·e^{2iθ} / Σ P(f)` over the three channels' power.
#[derive(Clone, Copy)]
enum Profile {
    /// `1 + s·cos 2(θ−θ0)`, `s = min(2|c2|, 1)` (its own moment is `s/2`): what one directional
    /// derivative of a band mixed with the band gives.
    Cosine,
    /// `exp(κ·cos 2(θ−θ0))` with `I1(κ)/I0(κ) = |c2|`: a narrow profile of the same moment.
    VonMises,
}

/// `I1(κ)/I0(κ)` by the series of both.
fn bessel_ratio(k: f64) -> f64 {
    let (mut i0, mut i1, mut term0, mut term1) = (0.0, 0.0, 1.0, k / 2.0);
    for m in 0..200 {
        i0 += term0;
        i1 += term1;
        let m = m as f64;
        term0 *= (k / 2.0).powi(2) / ((m + 1.0) * (m + 1.0));
        term1 *= (k / 2.0).powi(2) / ((m + 1.0) * (m + 2.0));
    }
    i1 / i0
}

/// The three channels' Gaussian fields with octave-box power shaped by one orientation profile
/// per octave, shared by the channels.
fn profiled_fields(
    chans: &[Vec<f32>; 3],
    w: usize,
    h: usize,
    seed: u32,
    kind: Profile,
) -> [Vec<f32>; 3] {
    let specs: Vec<_> = chans.iter().map(|c| spectrum_real(c, w, h, true)).collect();
    let lowest = (w.max(h) as f64).log2().floor() as usize;
    let octave_of: Vec<Option<(usize, f64)>> = (0..w * h)
        .map(|i| {
            let (fx, fy) = frequency(i, w, h);
            let r = (fx * fx + fy * fy).sqrt();
            (r > 0.0).then(|| {
                (
                    ((-r.log2()).floor().max(0.0) as usize).min(lowest),
                    fy.atan2(fx),
                )
            })
        })
        .collect();
    let mut moment = vec![(0.0f64, 0.0f64, 0.0f64); lowest + 1];
    for spec in &specs {
        for (s, o) in spec.iter().zip(&octave_of) {
            if let Some((j, a)) = o {
                let p = s.norm_sqr() as f64;
                moment[*j].0 += p * (2.0 * a).cos();
                moment[*j].1 += p * (2.0 * a).sin();
                moment[*j].2 += p;
            }
        }
    }
    let shape: Vec<Box<dyn Fn(f64) -> f64>> = moment
        .iter()
        .map(|&(c, s, p)| {
            let (c, s) = if p > 0.0 { (c / p, s / p) } else { (0.0, 0.0) };
            let r = (c * c + s * s).sqrt();
            let theta0 = s.atan2(c) / 2.0;
            let f: Box<dyn Fn(f64) -> f64> = match kind {
                Profile::Cosine => {
                    let strength = (2.0 * r).min(1.0);
                    Box::new(move |a: f64| 1.0 + strength * (2.0 * (a - theta0)).cos())
                }
                Profile::VonMises => {
                    let (mut lo, mut hi) = (0.0, 500.0);
                    for _ in 0..60 {
                        let mid = 0.5 * (lo + hi);
                        if bessel_ratio(mid) < r.min(0.995) {
                            lo = mid
                        } else {
                            hi = mid
                        }
                    }
                    let kappa = 0.5 * (lo + hi);
                    Box::new(move |a: f64| (kappa * ((2.0 * (a - theta0)).cos() - 1.0)).exp())
                }
            };
            f
        })
        .collect();
    // The profile's mean over each octave's bins, so that it moves power within the octave only.
    let mut mean_shape = vec![(0.0f64, 0usize); lowest + 1];
    for o in octave_of.iter().flatten() {
        mean_shape[o.0].0 += shape[o.0](o.1);
        mean_shape[o.0].1 += 1;
    }
    std::array::from_fn(|c| {
        let mut power = vec![0.0f64; lowest + 1];
        for (s, o) in specs[c].iter().zip(&octave_of) {
            if let Some((j, _)) = o {
                power[*j] += s.norm_sqr() as f64;
            }
        }
        random_phase_field(w, h, seed, c, |i| {
            octave_of[i].map(|(j, a)| {
                let (sum, n) = mean_shape[j];
                let g = shape[j](a) / (sum / n as f64).max(1e-300);
                (power[j] / n as f64 * g).sqrt() as f32
            })
        })
    })
}

/// Rung `rung` of the `--orient` ladder ([`ORIENT_RUNGS`]).
fn synthesise_orient(rung: usize, src: &Photo, seed: u32) -> Photo {
    match rung {
        0 => floor(src, seed),
        1 => synthesise_bands(1, src, seed),
        2 => synthesise_bands(4, src, seed),
        _ => {
            let (w, h) = (src.width, src.height);
            let m = model_of(src, seed);
            let kind = if rung == 3 {
                Profile::Cosine
            } else {
                Profile::VonMises
            };
            let fields = profiled_fields(&m.channels, w as usize, h as usize, seed, kind);
            let v = std::array::from_fn(|c| rank_match(&fields[c], &m.channels[c]));
            to_rgb(&m, &v, w, h)
        }
    }
}

/// Rung `rung` of the `--bands` ladder ([`BAND_RUNGS`]).
fn synthesise_bands(rung: usize, src: &Photo, seed: u32) -> Photo {
    if rung == 0 {
        return floor(src, seed);
    }
    let (w, h) = (src.width, src.height);
    let m = model_of(src, seed);
    let (per_octave, wedges) = BAND_SHAPES[rung - 1];
    let v = std::array::from_fn(|c| {
        let field = box_field(
            &m.channels[c],
            w as usize,
            h as usize,
            seed,
            c,
            per_octave,
            wedges,
        );
        rank_match(&field, &m.channels[c])
    });
    to_rgb(&m, &v, w, h)
}

/// Decorrelated channel values back to RGB about the model's mean.
fn to_rgb(m: &Model, v: &[Vec<f32>; 3], w: u32, h: u32) -> Photo {
    ladder::to_rgb(&m.prep, v, w, h)
}

/// The model's Gaussian noise per channel over the patch's pixels (one world unit a pixel, as
/// the protocol renders).
fn model_noise(m: &Model, w: u32, h: u32) -> [Vec<f32>; 3] {
    let tile = tile_for(&m.params);
    let log2_fp = m.prep.inv_scale.log2();
    let mut out: [Vec<f32>; 3] = std::array::from_fn(|_| Vec::with_capacity((w * h) as usize));
    for y in 0..h {
        for x in 0..w {
            let u = m.prep.texel([x as f32 + 0.5, y as f32 + 0.5, 0.0]);
            let g = texture_noise(&m.prep, &tile, u, log2_fp);
            for (o, v) in out.iter_mut().zip(g.sum) {
                o.push(v);
            }
        }
    }
    out
}

fn synthesise(rung: usize, src: &Photo, seed: u32) -> Photo {
    if rung == 0 {
        return random_phase(src, seed);
    }
    let (w, h) = (src.width, src.height);
    let m = model_of(src, seed);
    let (wu, hu) = (w as usize, h as usize);
    match rung {
        1 | 2 => {
            let fields: [Vec<f32>; 3] =
                std::array::from_fn(|c| octave_box_field(&m.channels[c], wu, hu, seed, c));
            if rung == 1 {
                let v = std::array::from_fn(|c| rank_match(&fields[c], &m.channels[c]));
                return to_rgb(&m, &v, w, h);
            }
            // The model's histogram: each field scaled to the deviation its knots expect.
            rgb_through_model(&m, &scaled_to_sigma(&m, &fields), w, h)
        }
        3 => {
            let g = model_noise(&m, w, h);
            let v = std::array::from_fn(|c| rank_match(&g[c], &m.channels[c]));
            to_rgb(&m, &v, w, h)
        }
        4 => rgb_through_model(&m, &scaled_to_sigma(&m, &model_noise(&m, w, h)), w, h),
        5 => rgb_through_model(&m, &fine_bands_normalised(&m, w, h), w, h),
        _ => rgb_through_model(&m, &model_noise(&m, w, h), w, h),
    }
}

/// The deviation of channel `c`'s noise over 2²⁰ points spread over a 2¹⁴-texel square (every
/// band's period many times over), not one patch.
fn wide_deviation(m: &Model, c: usize) -> f64 {
    let tile = tile_for(&m.params);
    let (mut sum, mut sum2, n) = (0.0f64, 0.0f64, 1u32 << 20);
    for i in 0..n {
        let u = [
            rng::uniform(7, 0x7769_6465, 2 * i) as f32 * 16384.0,
            rng::uniform(7, 0x7769_6465, 2 * i + 1) as f32 * 16384.0,
            0.0,
        ];
        let v = texture_noise(&m.prep, &tile, u, -1.0).sum[c] as f64;
        sum += v;
        sum2 += v * v;
    }
    let mean = sum / n as f64;
    (sum2 / n as f64 - mean * mean).sqrt()
}

/// The model's noise with each of its three finest bands divided by its own deviation over the
/// patch's pixels: at one texel per pixel a fine band is sampled at a few fixed sub-texel
/// phases, where the B-spline's variance is not its average (which the tile is normalised to).
fn fine_bands_normalised(m: &Model, w: u32, h: u32) -> [Vec<f32>; 3] {
    let bands = m.prep.bands as usize;
    let band = |c: usize, j: usize| {
        let mut one = Model {
            prep: m.prep.clone(),
            params: m.params.clone(),
            channels: Default::default(),
        };
        one.prep.weights[c] = [0.0; proctex::params::MAX_BANDS];
        one.prep.weights[c][j] = 1.0;
        model_noise(&one, w, h)[c].clone()
    };
    std::array::from_fn(|c| {
        let mut sum = vec![0.0f32; (w * h) as usize];
        for j in 0..bands {
            let wj = m.prep.weights[c][j];
            if wj == 0.0 {
                continue;
            }
            let v = band(c, j);
            let k = if j < 3 {
                let n = v.len() as f64;
                let mean = v.iter().map(|&x| x as f64).sum::<f64>() / n;
                let var = v.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / n;
                (1.0 / var.sqrt().max(1e-9)) as f32
            } else {
                1.0
            };
            for (s, x) in sum.iter_mut().zip(&v) {
                *s += wj * k * x;
            }
        }
        sum
    })
}

/// Each field scaled to the deviation the model's knots expect (its sigma).
fn scaled_to_sigma(m: &Model, fields: &[Vec<f32>; 3]) -> [Vec<f32>; 3] {
    std::array::from_fn(|c| {
        let f = &fields[c];
        let n = f.len() as f64;
        let mean = f.iter().map(|&v| v as f64).sum::<f64>() / n;
        let sd = (f.iter().map(|&v| (v as f64 - mean).powi(2)).sum::<f64>() / n)
            .sqrt()
            .max(1e-12);
        // PROCTEX_LAB_SCALE=mean: only the mean removed; =sd: only the deviation set.
        let (shift, scale) = match std::env::var("PROCTEX_LAB_SCALE").as_deref() {
            Ok("mean") => (mean, 1.0),
            Ok("sd") => (0.0, m.prep.sigma[c] as f64 / sd),
            _ => (mean, m.prep.sigma[c] as f64 / sd),
        };
        f.iter()
            .map(|&v| ((v as f64 - shift) * scale) as f32)
            .collect()
    })
}

/// Channel noise values through the model's colour (its histogram knots, contrast, basis).
fn rgb_through_model(m: &Model, g: &[Vec<f32>; 3], w: u32, h: u32) -> Photo {
    Photo {
        width: w,
        height: h,
        pixels: (0..g[0].len())
            .map(|i| {
                colour(
                    &m.prep,
                    ChannelNoise {
                        sum: [g[0][i], g[1][i], g[2][i]],
                        fine: [0.0; 3],
                    },
                    m.prep.mean,
                )
                .map(|v| v.clamp(0.0, 1.0))
            })
            .collect(),
    }
}

fn main() {
    let all: Vec<String> = std::env::args().skip(1).collect();
    let bands = all.iter().any(|a| a == "--bands");
    let orient = all.iter().any(|a| a == "--orient");
    let colour_ladder = all.iter().any(|a| a == "--colour");
    let expected = all.iter().any(|a| a == "--expected");
    let rounds = all.iter().any(|a| a == "--rounds");
    let marginal = all.iter().any(|a| a == "--marginals");
    let args: Vec<&String> = all.iter().filter(|a| !a.starts_with("--")).collect();
    let manifest = *args.first().expect("MANIFEST.tsv");
    let seeds: Vec<u32> = (1..=args.get(1).map_or(2, |s| s.parse().unwrap())).collect();
    let names: &[&str] = if marginal {
        &MARGINAL_RUNGS
    } else if rounds {
        &ROUNDS_RUNGS
    } else if expected {
        &EXPECTED_RUNGS
    } else if colour_ladder {
        &COLOUR_RUNGS
    } else if orient {
        &ORIENT_RUNGS
    } else if bands {
        &BAND_RUNGS
    } else {
        &RUNGS
    };
    let photos = stochastic_photos(manifest);
    let table = run_ladder(&photos, &seeds, names.len(), &|rung, src, seed| {
        if marginal {
            synthesise_marginals(rung, src, seed)
        } else if rounds {
            synthesise_rounds(rung, src, seed)
        } else if expected {
            synthesise_expected(rung, src, seed)
        } else if colour_ladder {
            synthesise_colour(rung, src, seed)
        } else if orient {
            synthesise_orient(rung, src, seed)
        } else if bands {
            synthesise_bands(rung, src, seed)
        } else {
            synthesise(rung, src, seed)
        }
    });
    // Why the knots cost more on the model's noise than on ideal fields: the deviation of the
    // model's rendered noise against the one its knots assume (sigma), and its kurtosis (3 for a
    // Gaussian), per channel with variation.
    let mut sd_ratio: [Vec<f64>; 3] = Default::default();
    let mut kurtosis: [Vec<f64>; 3] = Default::default();
    let mut wide_ratio: [Vec<f64>; 3] = Default::default();
    for (_, photo) in &photos {
        let diag_seed = std::env::var("PROCTEX_LAB_SEED").map_or(1, |s| s.parse().unwrap());
        let m = model_of(photo, diag_seed);
        let g = model_noise(&m, photo.width, photo.height);
        for c in 0..3 {
            if m.prep.sigma[c] <= 1e-6 {
                continue;
            }
            let n = g[c].len() as f64;
            let mean = g[c].iter().map(|&v| v as f64).sum::<f64>() / n;
            let moment = |k: i32| g[c].iter().map(|&v| (v as f64 - mean).powi(k)).sum::<f64>() / n;
            let var = moment(2);
            sd_ratio[c].push(var.sqrt() / m.prep.sigma[c] as f64);
            if std::env::var("PROCTEX_LAB_WIDE").is_ok() {
                wide_ratio[c].push(wide_deviation(&m, c) / m.prep.sigma[c] as f64);
            }
            kurtosis[c].push(moment(4) / (var * var).max(1e-30));
        }
    }
    for c in 0..3 {
        let (m, s) = mean_se(&sd_ratio[c]);
        let (k, ks) = mean_se(&kurtosis[c]);
        let (lo, hi) = sd_ratio[c]
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &x| (l.min(x), h.max(x)));
        let (wm, ws) = if wide_ratio[c].is_empty() {
            (f64::NAN, f64::NAN)
        } else {
            mean_se(&wide_ratio[c])
        };
        println!(
            "channel {c} ({} photos with variation): the model's noise deviation / its knots' sigma = {m:.3} ± {s:.3} (range {lo:.3}–{hi:.3}); kurtosis {k:.2} ± {ks:.2}; over 2^14 texels {wm:.3} ± {ws:.3}",
            sd_ratio[c].len()
        );
    }
    println!(
        "{} stochastic photos of {manifest}, seeds {seeds:?}: fidelity ratios, mean ± standard error over photos",
        photos.len()
    );
    print_ladder(names, &table);
}
