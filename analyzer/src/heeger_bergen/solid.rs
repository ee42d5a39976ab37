//! Solid textures from a 2D photo (Heeger & Bergen 1995, §4): an `N³` volume whose slices look
//! like the photo. The paper's better variant: on the analysis side a 2D Laplacian pyramid and
//! a 2D steerable pyramid of the photo; on the synthesis side a 3D Laplacian pyramid of the
//! volume and steerable pyramids of all its 2D slices (x–y, x–z and y–z). Each round matches
//! the 3D pyramid's subband histograms to the 2D Laplacian pyramid's and every slice's
//! steerable subbands to the photo's, collapses the four, averages the four volumes, and
//! matches the volume's histogram to the photo's.
//!
//! The Laplacian pyramids here are the isotropic case of [`crate::pyramid`]'s construction (one
//! orientation: the radial masks alone; in 3D the same radial masks of `|ω|` in three
//! dimensions), so the 2D and 3D subbands cover the same radial frequencies and their values
//! the same units. Circular, like the 2D synthesis, so the volume tiles along all three axes.
//! Colour as in the 2D synthesis (PCA of the periodic component, a final match per RGB
//! channel), from [`super::prepare`].

use std::cell::RefCell;

use rustfft::FftPlanner;
use rustfft::num_complex::Complex32;

use super::{
    ChannelTargets, PreparedSample, decorrelated, match_histogram, prepare, sorted, stream,
};
use crate::error::{Error, Result};
use crate::input::Photo;
use crate::pyramid::{Plan, max_scales};
use crate::rng;

/// The default side of a solid texture.
pub const DEFAULT_SIDE: u32 = 64;
/// The largest side a solid texture may have (128³ is 2 M voxels per channel).
pub const MAX_SIDE: u32 = 128;
/// The smallest side (a pyramid needs a scale above its 8-voxel low-pass residual).
pub const MIN_SIDE: u32 = 16;

/// An `n³` RGB volume, x fastest, then y, then z.
#[derive(Clone, Debug, PartialEq)]
pub struct Volume {
    /// The side.
    pub n: u32,
    /// `n³` voxels.
    pub voxels: Vec<[f32; 3]>,
}

impl Volume {
    /// The slice at depth `z` as a photo (`n × n`).
    pub fn slice_z(&self, z: u32) -> Photo {
        let n = self.n as usize;
        let start = z as usize * n * n;
        Photo {
            width: self.n,
            height: self.n,
            pixels: self.voxels[start..start + n * n].to_vec(),
        }
    }
}

thread_local! {
    static PLANNER: RefCell<FftPlanner<f32>> = RefCell::new(FftPlanner::new());
}

/// In-place 3D FFT of an `n³` cube (x fastest); the inverse is scaled by `1/n³`.
fn fft3(data: &mut [Complex32], n: usize, inverse: bool) {
    let fft = PLANNER.with(|p| {
        let mut p = p.borrow_mut();
        if inverse {
            p.plan_fft_inverse(n)
        } else {
            p.plan_fft_forward(n)
        }
    });
    let mut scratch = vec![Complex32::default(); fft.get_inplace_scratch_len()];
    // Along x: contiguous rows.
    fft.process_with_scratch(data, &mut scratch);
    // Along y (stride n, one line per (z, x)) and z (stride n², one per (y, x)): gather each
    // line, transform, scatter.
    let mut line = vec![Complex32::default(); n];
    for (stride, bases) in [
        (
            n,
            (0..n * n)
                .map(|i| (i / n) * n * n + i % n)
                .collect::<Vec<_>>(),
        ),
        (n * n, (0..n * n).collect()),
    ] {
        for base in bases {
            for (k, v) in line.iter_mut().enumerate() {
                *v = data[base + k * stride];
            }
            fft.process_with_scratch(&mut line, &mut scratch);
            for (k, v) in line.iter().enumerate() {
                data[base + k * stride] = *v;
            }
        }
    }
    if inverse {
        let k = 1.0 / (n * n * n) as f32;
        data.iter_mut().for_each(|v| *v *= k);
    }
}

/// Signed frequency of bin `k` of `n` (as [`crate::pyramid`]'s).
fn signed(k: usize, n: usize) -> i64 {
    if k < n.div_ceil(2) {
        k as i64
    } else {
        k as i64 - n as i64
    }
}

/// `f(|ω|)` on every bin of an `n³` spectrum.
fn radial_mask(n: usize, f: impl Fn(f64) -> f64) -> Vec<f32> {
    let w = |k: usize| std::f64::consts::TAU * signed(k, n) as f64 / n as f64;
    let mut out = Vec::with_capacity(n * n * n);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let r = (w(x).powi(2) + w(y).powi(2) + w(z).powi(2)).sqrt();
                out.push(f(r) as f32);
            }
        }
    }
    out
}

/// The bins of an `n³` spectrum an `m³` crop keeps: (index in the crop, index in the cube).
fn crop_pairs(n: usize, m: usize) -> Vec<(usize, usize)> {
    let map = |k: usize| signed(k, m).rem_euclid(n as i64) as usize;
    let mut out = Vec::with_capacity(m * m * m);
    for z in 0..m {
        for y in 0..m {
            for x in 0..m {
                out.push(((z * m + y) * m + x, (map(z) * n + map(y)) * n + map(x)));
            }
        }
    }
    out
}

/// A 3D Laplacian pyramid of `n³` volumes in the Fourier domain: a high-pass residual, one
/// isotropic band per scale, a low-pass residual; the radial masks of the 2D construction.
#[derive(Clone, Debug)]
pub struct Plan3 {
    n: usize,
    high0: Vec<f32>,
    low0: Vec<f32>,
    /// Per scale: its side, band mask `H`, low-pass mask `L`.
    levels: Vec<(usize, Vec<f32>, Vec<f32>)>,
    bottom: usize,
    /// Per scale, the crop from its side to the next.
    crops: Vec<Vec<(usize, usize)>>,
}

impl Plan3 {
    /// The masks of an `n³` pyramid with `scales` scales (at most `max_scales(n, n)`).
    pub fn new(n: usize, scales: usize) -> Plan3 {
        assert!(scales <= max_scales(n, n));
        let (low, high) = (crate::pyramid::radial_low, crate::pyramid::radial_high);
        let mut levels = Vec::new();
        let mut crops = Vec::new();
        let mut side = n;
        for _ in 0..scales {
            levels.push((side, radial_mask(side, high), radial_mask(side, low)));
            crops.push(crop_pairs(side, side.div_ceil(2)));
            side = side.div_ceil(2);
        }
        Plan3 {
            n,
            high0: radial_mask(n, |r| high(r / 2.0)),
            low0: radial_mask(n, |r| low(r / 2.0)),
            levels,
            bottom: side,
            crops,
        }
    }

    /// The subbands of a volume: high-pass, one band per scale, low-pass.
    pub fn analyse(&self, volume: &[f32]) -> Vec<Vec<f32>> {
        let mut x: Vec<Complex32> = volume.iter().map(|&v| Complex32::new(v, 0.0)).collect();
        fft3(&mut x, self.n, false);
        let real = |mut spec: Vec<Complex32>, side: usize| {
            fft3(&mut spec, side, true);
            spec.iter().map(|v| v.re).collect::<Vec<f32>>()
        };
        let mut out = vec![real(filtered(&x, &self.high0), self.n)];
        let mut y = filtered(&x, &self.low0);
        for ((side, band, low), crop) in self.levels.iter().zip(&self.crops) {
            out.push(real(filtered(&y, band), *side));
            let next_side = side.div_ceil(2);
            let scale = (next_side as f32 / *side as f32).powi(3);
            let mut next = vec![Complex32::default(); next_side.pow(3)];
            for &(i2, i) in crop {
                next[i2] = y[i] * (low[i] * scale);
            }
            y = next;
        }
        out.push(real(y, self.bottom));
        out
    }

    /// The volume whose subbands are `bands` (in [`Plan3::analyse`]'s order).
    pub fn synthesise(&self, bands: &[Vec<f32>]) -> Vec<f32> {
        let spectrum = |v: &[f32], side: usize| {
            let mut s: Vec<Complex32> = v.iter().map(|&x| Complex32::new(x, 0.0)).collect();
            fft3(&mut s, side, false);
            s
        };
        let mut y = spectrum(&bands[bands.len() - 1], self.bottom);
        for (s, ((side, band, low), crop)) in self.levels.iter().zip(&self.crops).enumerate().rev()
        {
            let next_side = side.div_ceil(2);
            let scale = (*side as f32 / next_side as f32).powi(3);
            let mut up = vec![Complex32::default(); side.pow(3)];
            for &(i2, i) in crop {
                up[i] = y[i2] * (low[i] * scale);
            }
            for ((u, b), m) in up.iter_mut().zip(spectrum(&bands[s + 1], *side)).zip(band) {
                *u += b * m;
            }
            y = up;
        }
        let mut out: Vec<Complex32> = filtered(&y, &self.low0);
        for ((o, h), m) in out
            .iter_mut()
            .zip(spectrum(&bands[0], self.n))
            .zip(&self.high0)
        {
            *o += h * m;
        }
        fft3(&mut out, self.n, true);
        out.iter().map(|v| v.re).collect()
    }
}

fn filtered(spec: &[Complex32], mask: &[f32]) -> Vec<Complex32> {
    spec.iter().zip(mask).map(|(v, m)| v * m).collect()
}

/// What to synthesise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SolidOptions {
    /// The volume's side.
    pub n: u32,
    /// Rounds of the loop.
    pub iterations: u32,
    /// Scales requested (at most what the photo and the volume support).
    pub scales: u32,
    /// Orientations of the slices' steerable pyramids.
    pub orientations: u32,
    /// Seed of the starting noise.
    pub seed: u32,
}

impl Default for SolidOptions {
    fn default() -> Self {
        SolidOptions {
            n: DEFAULT_SIDE,
            iterations: super::DEFAULT_ITERATIONS,
            scales: super::DEFAULT_SCALES,
            orientations: super::DEFAULT_ORIENTATIONS,
            seed: 1,
        }
    }
}

/// The targets of one decorrelated channel for the volume: the 2D Laplacian pyramid's subbands
/// (for the 3D pyramid) and the steerable ones with the channel's values (for the slices).
struct SolidTargets<'a> {
    isotropic: &'a [Vec<f32>],
    steerable: &'a ChannelTargets,
}

/// The voxel index of pixel `(i, j)` of slice `k` of an `n³` volume, for one slicing axis.
type VoxelOfSlice = fn(usize, usize, usize, usize) -> usize;

/// One round for one channel of the volume `v` (`n³`): the four matched collapses averaged,
/// then the volume's histogram matched.
fn solid_round(t: &SolidTargets, plan3: &Plan3, slice_plan: &Plan, n: usize, v: &mut Vec<f32>) {
    let mut bands = plan3.analyse(v);
    for (b, target) in bands.iter_mut().zip(t.isotropic) {
        match_histogram(b, target);
    }
    let mut sum = plan3.synthesise(&bands);
    // Slices normal to z (x–y), y (x–z) and x (y–z): voxel (i, j) of slice `k`.
    let index: [VoxelOfSlice; 3] = [
        |i: usize, j: usize, k: usize, n: usize| (k * n + j) * n + i,
        |i: usize, j: usize, k: usize, n: usize| (j * n + k) * n + i,
        |i: usize, j: usize, k: usize, n: usize| (j * n + i) * n + k,
    ];
    // Every slice is matched on its own (in parallel on native), then added in order, so the
    // sum does not depend on the threads.
    let slices: Vec<(usize, usize)> = (0..3).flat_map(|a| (0..n).map(move |k| (a, k))).collect();
    let matched = crate::parallel::map_in_order(&slices, |&(a, k)| {
        let slice: Vec<f32> = (0..n * n)
            .map(|p| v[index[a](p % n, p / n, k, n)])
            .collect();
        let mut p = slice_plan.analyse(&slice);
        for (b, target) in p.subbands_mut().zip(&t.steerable.subbands) {
            match_histogram(b, target);
        }
        slice_plan.synthesise(&p)
    });
    for (&(a, k), slice) in slices.iter().zip(matched) {
        for (q, value) in slice.into_iter().enumerate() {
            sum[index[a](q % n, q / n, k, n)] += value;
        }
    }
    for s in &mut sum {
        *s *= 0.25;
    }
    match_histogram(&mut sum, &t.steerable.pixels);
    *v = sum;
}

/// A solid texture like `photo`: an `n³` volume any slice of which looks like it. Errors on a
/// photo or options out of range. `progress(done, total)` after each round of each channel;
/// `false` cancels (then `Ok(None)`).
pub fn synthesize_solid(
    photo: &Photo,
    opts: &SolidOptions,
    progress: &(dyn Fn(usize, usize) -> bool + Sync),
) -> Result<Option<Volume>> {
    let mut synthesis = SolidSynthesis::new(photo, opts)?;
    while synthesis.done() < synthesis.steps() {
        synthesis.step();
        if !progress(synthesis.done(), synthesis.steps()) {
            return Ok(None);
        }
    }
    Ok(Some(synthesis.volume()))
}

/// A solid texture in progress, one round of one channel at a time (the worker reports
/// progress and sees Cancel between rounds); the same bits as [`synthesize_solid`].
#[derive(Clone, Debug)]
pub struct SolidSynthesis {
    sample: PreparedSample,
    /// Per decorrelated channel, the photo's isotropic subbands, sorted.
    isotropic: Vec<Vec<Vec<f32>>>,
    plan3: Plan3,
    slice_plan: Plan,
    n: usize,
    iterations: usize,
    channels: Vec<Vec<f32>>,
    done: usize,
}

impl SolidSynthesis {
    /// Prepares `photo` and starts the loop from noise with the photo's histogram; errors on a
    /// photo or options out of range.
    pub fn new(photo: &Photo, opts: &SolidOptions) -> Result<SolidSynthesis> {
        photo.check_min_size()?;
        if !(MIN_SIDE..=MAX_SIDE).contains(&opts.n) {
            return Err(Error::Option(format!(
                "--solid {} is not between {MIN_SIDE} and {MAX_SIDE}",
                opts.n
            )));
        }
        super::check_loop(opts.iterations, opts.scales, opts.orientations)?;
        let n = opts.n as usize;
        let scales = super::scales_for(
            (photo.width as usize, photo.height as usize),
            (n, n),
            opts.scales,
        );
        let sample = prepare(photo, scales, opts.orientations as usize);
        // The isotropic targets: the photo's decorrelated channels through a one-orientation
        // plan.
        let isotropic_plan = Plan::new(photo.width as usize, photo.height as usize, scales, 1);
        let (_, decorrelated) = decorrelated(photo);
        let isotropic = decorrelated
            .iter()
            .map(|c| {
                isotropic_plan
                    .analyse(c)
                    .subbands()
                    .map(|b| sorted(b))
                    .collect()
            })
            .collect();
        let channels = (0..3)
            .map(|j| {
                let mut v: Vec<f32> = (0..n * n * n)
                    .map(|i| rng::gaussian(opts.seed, stream(j), i as u32) as f32)
                    .collect();
                match_histogram(&mut v, &sample.channels[j].pixels);
                v
            })
            .collect();
        Ok(SolidSynthesis {
            sample,
            isotropic,
            plan3: Plan3::new(n, scales),
            slice_plan: Plan::new(n, n, scales, opts.orientations as usize),
            n,
            iterations: opts.iterations as usize,
            channels,
            done: 0,
        })
    }

    /// Rounds in all (three channels × the iterations).
    pub fn steps(&self) -> usize {
        3 * self.iterations
    }

    /// Rounds done.
    pub fn done(&self) -> usize {
        self.done
    }

    /// The volume's side.
    pub fn side(&self) -> u32 {
        self.n as u32
    }

    /// Runs the next round (channel by channel); returns whether any remain.
    pub fn step(&mut self) -> bool {
        if self.done < self.steps() {
            let j = self.done / self.iterations;
            let targets = SolidTargets {
                isotropic: &self.isotropic[j],
                steerable: &self.sample.channels[j],
            };
            solid_round(
                &targets,
                &self.plan3,
                &self.slice_plan,
                self.n,
                &mut self.channels[j],
            );
            self.done += 1;
        }
        self.done < self.steps()
    }

    /// The volume as it stands (the result once every round is done).
    pub fn volume(&self) -> Volume {
        let n = self.n;
        Volume {
            n: self.n as u32,
            voxels: super::to_photo(&self.sample, &self.channels, (n, n * n)).pixels,
        }
    }
}

#[cfg(test)]
mod tests;
