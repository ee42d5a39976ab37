//! Pyramid-based texture synthesis (Heeger & Bergen 1995): a raster texture from the photo
//! itself, whose every steerable-pyramid subband ([`crate::pyramid`]) has the photo's
//! histogram. The companion of the procedural model (shown beside it, as Lagae Fig. 16 does).
//!
//! The loop is the paper's (§3): start from white noise matched to the sample's histogram;
//! each iteration analyses the output, matches the histogram of every subband (both residuals
//! included) to the sample's, reconstructs, and matches the image histogram again.
//!
//! Colour follows the IPOL implementation (Briand, Vacher, Galerne & Rabin 2014), with the
//! colour code of the noise model: the sample's periodic component (Moisan's periodic + smooth
//! decomposition, [`crate::spectrum::spectrum_real`]) so that its borders do not add a cross of
//! spurious energy, PCA decorrelation ([`crate::colour::pca`], the noise model's), one synthesis
//! per decorrelated channel, rotation back, and a final match of each RGB channel. One
//! departure: the final match is to the photo's own RGB values, not to the periodic
//! component's (which carry the smooth component's correction near the borders, not the
//! material's colours); the periodic component is what every subband statistic comes from.
//!
//! Histogram matching is exact, by sorting with quantile interpolation
//! ([`match_histogram`]), so the output may have any size, not only multiples of the sample's.
//! Every operation is circular or per pixel, so the output tiles seamlessly; it is seeded and
//! deterministic (native runs the three channels in parallel, each alone, so the bits do not
//! depend on the threads).

pub mod solid;

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rustfft::num_complex::Complex32;

use crate::colour::{matrix_from_quat, pca, quat_from_matrix, slerp};
use crate::error::{Error, Result};
use crate::input::{MIN_SIDE, Photo};
use crate::limits;
use crate::pyramid::{MAX_ORIENTATIONS, Plan, max_scales};
use crate::radix;
use crate::rng;
use crate::spectrum::{ifft2, spectrum_real};

/// The paper's iteration count ("about 5 iterations").
pub const DEFAULT_ITERATIONS: u32 = 5;
/// Scales of the pyramid (fewer where the sample or the output is small).
pub const DEFAULT_SCALES: u32 = 4;
/// Orientations of the pyramid.
pub const DEFAULT_ORIENTATIONS: u32 = 4;
/// Most iterations one may ask for (the loop converges in a handful; more only costs time).
pub const MAX_ITERATIONS: u32 = 100;
/// Most scales one may ask for (a 16384² output supports 11).
pub const MAX_SCALES: u32 = 12;

/// What to synthesise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterOptions {
    /// Output width in pixels.
    pub width: u32,
    /// Output height in pixels.
    pub height: u32,
    /// Iterations of the loop.
    pub iterations: u32,
    /// Scales requested (at most what the sample and the output support).
    pub scales: u32,
    /// Orientations.
    pub orientations: u32,
    /// Seed of the starting noise.
    pub seed: u32,
}

impl RasterOptions {
    /// The defaults for an output of `width × height`.
    pub fn new(width: u32, height: u32) -> RasterOptions {
        RasterOptions {
            width,
            height,
            iterations: DEFAULT_ITERATIONS,
            scales: DEFAULT_SCALES,
            orientations: DEFAULT_ORIENTATIONS,
            seed: 1,
        }
    }

    /// Refuses options out of range, saying which and what is allowed; an output over
    /// `max_pixels` is refused with `past` (how to go past the limit).
    pub fn validate(&self, max_pixels: u64, past: &str) -> Result<()> {
        if self.width < MIN_SIDE || self.height < MIN_SIDE {
            return Err(Error::Option(format!(
                "the synthesis would be {}×{} pixels; each side must be at least {MIN_SIDE}",
                self.width, self.height
            )));
        }
        limits::check_pixels(
            "the synthesis",
            self.width as u64,
            self.height as u64,
            max_pixels,
            past,
        )?;
        check_loop(self.iterations, self.scales, self.orientations)
    }
}

/// Refuses loop options out of range, saying which and what is allowed.
fn check_loop(iterations: u32, scales: u32, orientations: u32) -> Result<()> {
    if iterations > MAX_ITERATIONS {
        return Err(Error::Option(format!(
            "--iterations {iterations} is over {MAX_ITERATIONS}"
        )));
    }
    if !(1..=MAX_SCALES).contains(&scales) {
        return Err(Error::Option(format!(
            "--scales {scales} is not between 1 and {MAX_SCALES}"
        )));
    }
    if !(1..=MAX_ORIENTATIONS as u32).contains(&orientations) {
        return Err(Error::Option(format!(
            "--orientations {orientations} is not between 1 and {MAX_ORIENTATIONS}"
        )));
    }
    Ok(())
}

/// Most pixels a synthesis may have by default: a pyramid of `w × h` holds about seven floats
/// per pixel per channel, plus the complex spectra being filtered (about 1.5 GB at 4096²).
pub const MAX_SYNTHESIS_PIXELS: u64 = 4096 * 4096;

/// Rearranges `values` so that their histogram is `target_sorted`'s (any length), keeping
/// their order: the value of rank `i` of `n` becomes the target's quantile `(i + ½)/n`,
/// linearly interpolated between the target's sorted values (exact when the lengths are equal).
/// Ties keep their positions' order (the sort is stable), so the result is deterministic.
pub fn match_histogram(values: &mut [f32], target_sorted: &[f32]) {
    let (n, m) = (values.len(), target_sorted.len());
    if n == 0 || m == 0 {
        return;
    }
    let order = radix::argsort(values);
    for (rank, &i) in order.iter().enumerate() {
        values[i as usize] = quantile(target_sorted, (rank as f64 + 0.5) / n as f64);
    }
}

/// The `q` quantile of sorted values, `q·m − ½` interpolated between neighbours (clamped).
pub fn quantile(sorted: &[f32], q: f64) -> f32 {
    let m = sorted.len();
    let t = (q * m as f64 - 0.5).clamp(0.0, (m - 1) as f64);
    let i = t.floor() as usize;
    let f = (t - i as f64) as f32;
    if i + 1 < m {
        sorted[i] + f * (sorted[i + 1] - sorted[i])
    } else {
        sorted[i]
    }
}

fn sorted(v: &[f32]) -> Vec<f32> {
    let mut s = v.to_vec();
    radix::sort(&mut s);
    s
}

/// What the loop matches for one channel of a sample: its sorted values and the sorted values
/// of each of its subbands (in [`crate::pyramid::Pyramid::subbands`]'s order).
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelTargets {
    /// The channel's values, sorted.
    pub pixels: Vec<f32>,
    /// Each subband's values, sorted.
    pub subbands: Vec<Vec<f32>>,
}

impl ChannelTargets {
    /// The targets of `channel`, analysed with `plan` (the sample's size).
    pub fn of(channel: &[f32], plan: &Plan) -> ChannelTargets {
        ChannelTargets {
            pixels: sorted(channel),
            subbands: plan
                .analyse(channel)
                .subbands()
                .map(|b| sorted(b))
                .collect(),
        }
    }
}

/// The loop's starting point for one channel on `plan`'s grid: white noise of
/// `(seed, stream)` matched to the channel's histogram.
pub fn start_channel(
    targets: &ChannelTargets,
    plan: &Plan,
    (seed, stream): (u32, u32),
) -> Vec<f32> {
    let (w, h) = plan.size();
    let mut out: Vec<f32> = (0..w * h)
        .map(|i| rng::gaussian(seed, stream, i as u32) as f32)
        .collect();
    match_histogram(&mut out, &targets.pixels);
    out
}

/// One round of the loop: analyse, match every subband, reconstruct, match the histogram.
pub fn round(targets: &ChannelTargets, plan: &Plan, channel: &mut Vec<f32>) {
    let mut p = plan.analyse(channel);
    for (band, target) in p.subbands_mut().zip(&targets.subbands) {
        match_histogram(band, target);
    }
    *channel = plan.synthesise(&p);
    match_histogram(channel, &targets.pixels);
}

/// One channel synthesised on `plan`'s grid from `targets` (made with the same scales and
/// orientations): [`start_channel`], then `iterations` [`round`]s. `step()` is called after
/// each round; `false` stops (returns `None`).
pub fn synthesize_channel(
    targets: &ChannelTargets,
    plan: &Plan,
    iterations: u32,
    noise: (u32, u32),
    step: &dyn Fn() -> bool,
) -> Option<Vec<f32>> {
    let mut out = start_channel(targets, plan, noise);
    for _ in 0..iterations {
        round(targets, plan, &mut out);
        if !step() {
            return None;
        }
    }
    Some(out)
}

/// The periodic component of a channel (Moisan's decomposition; the same mean).
fn periodic_component(channel: &[f32], w: usize, h: usize) -> Vec<f32> {
    let spec: Vec<Complex32> = spectrum_real(channel, w, h, true);
    ifft2(spec, w, h).iter().map(|v| v.re).collect()
}

/// A sample prepared for synthesis: its colour axes and, per decorrelated channel, the
/// targets; what a mixture of two samples interpolates.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedSample {
    /// Mean RGB of the periodic component.
    pub mean: [f64; 3],
    /// Rows: the principal colour axes (a rotation).
    pub basis: [[f64; 3]; 3],
    /// Targets of each decorrelated channel.
    pub channels: [ChannelTargets; 3],
    /// The photo's own RGB values per channel, sorted (the final colour match).
    pub rgb: [Vec<f32>; 3],
}

/// Sorted values `m` of the way from `a` to `b` by quantile (1-D optimal transport: the
/// `q` quantile of the result is `(1 − m)·a(q) + m·b(q)`), at as many quantiles as the longer
/// of the two. Sorted, since both are.
fn mix_sorted(a: &[f32], b: &[f32], m: f32) -> Vec<f32> {
    let n = a.len().max(b.len());
    (0..n)
        .map(|i| {
            let q = (i as f64 + 0.5) / n as f64;
            (1.0 - m) * quantile(a, q) + m * quantile(b, q)
        })
        .collect()
}

/// The texture mixture of Heeger & Bergen §5 ("combine two or more textures by averaging their
/// pyramid histograms"): the sample `m` of the way from `a` to `b` (0 ≤ m ≤ 1), every target
/// (each subband's histogram, each decorrelated channel's and each RGB channel's) interpolated
/// by quantile, the colour mean linearly and the colour axes along the shorter rotation
/// (quaternion slerp, as a morph does). `m = 0` is `a` and `m = 1` is `b` exactly. Both must be
/// prepared with the same scales and orientations.
///
/// Departure from the paper's Fig. 6, which takes the palette (the colour transform) from one
/// image and the pattern (the subband statistics) from the other: a slider between the two is
/// what an artist can use, and its ends are the two syntheses; the paper's mixture is the pair
/// of ends crossed, which this does not offer.
pub fn mix(a: &PreparedSample, b: &PreparedSample, m: f32) -> PreparedSample {
    assert_eq!(a.channels[0].subbands.len(), b.channels[0].subbands.len());
    if m <= 0.0 {
        return a.clone();
    }
    if m >= 1.0 {
        return b.clone();
    }
    let channel = |x: &ChannelTargets, y: &ChannelTargets| ChannelTargets {
        pixels: mix_sorted(&x.pixels, &y.pixels, m),
        subbands: x
            .subbands
            .iter()
            .zip(&y.subbands)
            .map(|(p, q)| mix_sorted(p, q, m))
            .collect(),
    };
    let basis = matrix_from_quat(slerp(
        quat_from_matrix(a.basis),
        quat_from_matrix(b.basis),
        m as f64,
    ));
    PreparedSample {
        mean: std::array::from_fn(|c| (1.0 - m as f64) * a.mean[c] + m as f64 * b.mean[c]),
        basis,
        channels: std::array::from_fn(|j| channel(&a.channels[j], &b.channels[j])),
        rgb: std::array::from_fn(|c| mix_sorted(&a.rgb[c], &b.rgb[c], m)),
    }
}

/// The mixture `m` of the way from `a`'s synthesis to `b`'s ([`mix`]), of `opts`' size
/// (checks as [`synthesize_progress`], for both photos).
pub fn synthesize_mixture(
    a: &Photo,
    b: &Photo,
    m: f32,
    opts: &RasterOptions,
    limit: (u64, &str),
) -> Result<Photo> {
    let (sample, scales) = mixed_sample(a, b, m, opts, limit)?;
    let output = (opts.width as usize, opts.height as usize);
    Ok(synthesize_prepared(&sample, output, scales, opts, &|_, _| true).expect("never cancelled"))
}

/// The mixed sample of [`synthesize_mixture`] and the scales it was prepared with (the most
/// both photos and the output allow).
fn mixed_sample(
    a: &Photo,
    b: &Photo,
    m: f32,
    opts: &RasterOptions,
    (max_pixels, past): (u64, &str),
) -> Result<(PreparedSample, usize)> {
    if !(0.0..=1.0).contains(&m) {
        return Err(Error::Option(format!("--m {m} is not between 0 and 1")));
    }
    a.check_min_size()?;
    b.check_min_size()?;
    opts.validate(max_pixels, past)?;
    let output = (opts.width as usize, opts.height as usize);
    let size = |p: &Photo| (p.width as usize, p.height as usize);
    let scales =
        scales_for(size(a), output, opts.scales).min(scales_for(size(b), output, opts.scales));
    let k = opts.orientations as usize;
    Ok((
        mix(&prepare(a, scales, k), &prepare(b, scales, k), m),
        scales,
    ))
}

/// Scales used for a sample of `sample` size and an output of `output` size.
pub fn scales_for(sample: (usize, usize), output: (usize, usize), requested: u32) -> usize {
    (requested as usize)
        .min(max_scales(sample.0, sample.1))
        .min(max_scales(output.0, output.1))
}

/// The photo's colour axes (PCA of its periodic component) and its decorrelated channels:
/// the periodic component's values along each axis, the mean removed.
fn decorrelated(photo: &Photo) -> (crate::colour::Pca, [Vec<f32>; 3]) {
    let (w, h) = (photo.width as usize, photo.height as usize);
    let periodic: [Vec<f32>; 3] = std::array::from_fn(|c| {
        let channel: Vec<f32> = photo.pixels.iter().map(|p| p[c]).collect();
        periodic_component(&channel, w, h)
    });
    let pixels: Vec<[f32; 3]> = (0..w * h)
        .map(|i| [periodic[0][i], periodic[1][i], periodic[2][i]])
        .collect();
    let colour = pca(&pixels);
    let channels = std::array::from_fn(|j| {
        let axis = colour.basis[j];
        pixels
            .iter()
            .map(|p| {
                (0..3)
                    .map(|k| axis[k] * (p[k] as f64 - colour.mean[k]))
                    .sum::<f64>() as f32
            })
            .collect()
    });
    (colour, channels)
}

/// Prepares `photo` for synthesis with a pyramid of `scales` scales and `orientations`.
pub fn prepare(photo: &Photo, scales: usize, orientations: usize) -> PreparedSample {
    let (w, h) = (photo.width as usize, photo.height as usize);
    let (colour, channels) = decorrelated(photo);
    let plan = Plan::new(w, h, scales, orientations);
    PreparedSample {
        mean: colour.mean,
        basis: colour.basis,
        channels: channels.map(|c| ChannelTargets::of(&c, &plan)),
        rgb: std::array::from_fn(|c| {
            sorted(&photo.pixels.iter().map(|p| p[c]).collect::<Vec<f32>>())
        }),
    }
}

/// A texture like `photo`, of `opts`' size (at most [`MAX_SYNTHESIS_PIXELS`]). Errors on a
/// photo or options out of range.
pub fn synthesize(photo: &Photo, opts: &RasterOptions) -> Result<Photo> {
    let limit = (MAX_SYNTHESIS_PIXELS, limits::PAST_THE_LIMIT);
    Ok(synthesize_progress(photo, opts, limit, &|_, _| true)?.expect("never cancelled"))
}

/// [`synthesize`] with an output limit (`max_pixels`, and how to go past it), reporting
/// `progress(done, total)` after each round of each channel; `false` cancels (then
/// `Ok(None)`).
pub fn synthesize_progress(
    photo: &Photo,
    opts: &RasterOptions,
    (max_pixels, past): (u64, &str),
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Result<Option<Photo>> {
    photo.check_min_size()?;
    opts.validate(max_pixels, past)?;
    let sample = (photo.width as usize, photo.height as usize);
    let output = (opts.width as usize, opts.height as usize);
    let scales = scales_for(sample, output, opts.scales);
    let prepared = prepare(photo, scales, opts.orientations as usize);
    Ok(synthesize_prepared(
        &prepared, output, scales, opts, progress,
    ))
}

/// The synthesis of a prepared sample (its scales and orientations those of `opts`, capped
/// by `scales`) on an output of `(width, height)`.
pub fn synthesize_prepared(
    sample: &PreparedSample,
    (width, height): (usize, usize),
    scales: usize,
    opts: &RasterOptions,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Option<Photo> {
    let plan = Plan::new(width, height, scales, opts.orientations as usize);
    let total = 3 * opts.iterations as usize;
    let done = AtomicUsize::new(0);
    let cancelled = AtomicBool::new(false);
    let step = || {
        let d = done.fetch_add(1, Ordering::SeqCst) + 1;
        let go = !cancelled.load(Ordering::SeqCst) && progress(d, total);
        if !go {
            cancelled.store(true, Ordering::SeqCst);
        }
        go
    };
    let channels: Vec<Option<Vec<f32>>> = crate::parallel::map_in_order(&[0u32, 1, 2], |&j| {
        synthesize_channel(
            &sample.channels[j as usize],
            &plan,
            opts.iterations,
            (opts.seed, stream(j as usize)),
            &step,
        )
    });
    if cancelled.load(Ordering::SeqCst) {
        return None;
    }
    let channels: Vec<Vec<f32>> = channels.into_iter().collect::<Option<_>>()?;
    Some(to_photo(sample, &channels, (width, height)))
}

/// The noise stream of decorrelated channel `j`.
fn stream(j: usize) -> u32 {
    0x4842_0000 + j as u32
}

/// Decorrelated channels back to RGB, each RGB channel matched to the photo's own.
fn to_photo(
    sample: &PreparedSample,
    channels: &[Vec<f32>],
    (width, height): (usize, usize),
) -> Photo {
    let mut rgb: [Vec<f32>; 3] = std::array::from_fn(|c| {
        (0..width * height)
            .map(|i| {
                let v: f64 = (0..3)
                    .map(|j| channels[j][i] as f64 * sample.basis[j][c])
                    .sum();
                (v + sample.mean[c]) as f32
            })
            .collect()
    });
    for (channel, target) in rgb.iter_mut().zip(&sample.rgb) {
        match_histogram(channel, target);
    }
    Photo {
        width: width as u32,
        height: height as u32,
        pixels: (0..width * height)
            .map(|i| std::array::from_fn(|c| rgb[c][i].clamp(0.0, 1.0)))
            .collect(),
    }
}

/// The 2D FFTs a synthesis of a `sample`-sized photo with `opts` runs, by size: per RGB
/// channel the periodic component's transform and inverse; per decorrelated channel the
/// sample's analysis, then each round's analysis and reconstruction. What benchmarks state the
/// synthesis' time against.
pub fn transforms(sample: (usize, usize), opts: &RasterOptions) -> Vec<(usize, usize)> {
    let output = (opts.width as usize, opts.height as usize);
    let scales = scales_for(sample, output, opts.scales);
    let k = opts.orientations as usize;
    let (on_sample, on_output) = (
        Plan::new(sample.0, sample.1, scales, k),
        Plan::new(output.0, output.1, scales, k),
    );
    let mut out = Vec::new();
    for _ in 0..3 {
        out.extend([sample, sample]);
        out.extend(on_sample.analysis_transforms());
        for _ in 0..opts.iterations {
            out.extend(on_output.analysis_transforms());
            out.extend(on_output.synthesis_transforms());
        }
    }
    out
}

/// The synthesis one round at a time, for a caller that must do other things in between (the
/// browser's worker: Cancel, progress): the same rounds as [`synthesize`], so the same bits.
#[derive(Clone, Debug)]
pub struct Synthesis {
    sample: PreparedSample,
    plan: Plan,
    iterations: usize,
    channels: Vec<Vec<f32>>,
    done: usize,
}

impl Synthesis {
    /// Prepares `photo` and starts the loop (checks as [`synthesize_progress`]).
    pub fn new(
        photo: &Photo,
        opts: &RasterOptions,
        (max_pixels, past): (u64, &str),
    ) -> Result<Synthesis> {
        photo.check_min_size()?;
        opts.validate(max_pixels, past)?;
        let output = (opts.width as usize, opts.height as usize);
        let scales = scales_for(
            (photo.width as usize, photo.height as usize),
            output,
            opts.scales,
        );
        let sample = prepare(photo, scales, opts.orientations as usize);
        Ok(Synthesis::of_sample(sample, scales, opts))
    }

    /// The mixture `m` of the way from `a`'s synthesis to `b`'s ([`mix`]; checks as
    /// [`synthesize_mixture`]), one round at a time: the same bits as
    /// [`synthesize_mixture`].
    pub fn mixture(
        a: &Photo,
        b: &Photo,
        m: f32,
        opts: &RasterOptions,
        limit: (u64, &str),
    ) -> Result<Synthesis> {
        let (sample, scales) = mixed_sample(a, b, m, opts, limit)?;
        Ok(Synthesis::of_sample(sample, scales, opts))
    }

    fn of_sample(sample: PreparedSample, scales: usize, opts: &RasterOptions) -> Synthesis {
        let plan = Plan::new(
            opts.width as usize,
            opts.height as usize,
            scales,
            opts.orientations as usize,
        );
        let channels = (0..3)
            .map(|j| start_channel(&sample.channels[j], &plan, (opts.seed, stream(j))))
            .collect();
        Synthesis {
            sample,
            plan,
            iterations: opts.iterations as usize,
            channels,
            done: 0,
        }
    }

    /// Rounds in all (three channels × the iterations).
    pub fn steps(&self) -> usize {
        3 * self.iterations
    }

    /// Rounds done.
    pub fn done(&self) -> usize {
        self.done
    }

    /// Runs the next round (channel by channel); returns whether any remain.
    pub fn step(&mut self) -> bool {
        if self.done < self.steps() {
            let j = self.done / self.iterations;
            round(&self.sample.channels[j], &self.plan, &mut self.channels[j]);
            self.done += 1;
        }
        self.done < self.steps()
    }

    /// The texture as it stands (the result once every round is done).
    pub fn photo(&self) -> Photo {
        to_photo(&self.sample, &self.channels, self.plan.size())
    }
}

#[cfg(test)]
mod tests;
