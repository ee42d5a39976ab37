use super::*;

fn relative_error(a: &[f32], b: &[f32]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| ((x - y) as f64).powi(2)).sum();
    let den: f64 = a.iter().map(|x| (*x as f64).powi(2)).sum();
    (num / den).sqrt()
}

#[test]
fn the_3d_fft_is_the_dft_and_inverts() {
    let n = 5;
    let v: Vec<Complex32> = (0..n * n * n)
        .map(|i| Complex32::new(rng::gaussian(1, 2, i as u32) as f32, 0.0))
        .collect();
    let mut f = v.clone();
    fft3(&mut f, n, false);
    // The DFT at one frequency (1, 2, 3), directly.
    let (kx, ky, kz) = (1.0, 2.0, 3.0);
    let mut want = Complex32::default();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let phase = -std::f32::consts::TAU
                    * (kx * x as f32 + ky * y as f32 + kz * z as f32)
                    / n as f32;
                want += v[(z * n + y) * n + x] * Complex32::new(phase.cos(), phase.sin());
            }
        }
    }
    let got = f[(3 * n + 2) * n + 1];
    assert!((got - want).norm() < 1e-3, "{got} vs {want}");
    fft3(&mut f, n, true);
    for (a, b) in f.iter().zip(&v) {
        assert!((a - b).norm() < 1e-5);
    }
}

/// The 3D pyramid gives the volume back to float precision, odd sides included.
#[test]
fn the_3d_pyramid_reconstructs() {
    for n in [16usize, 17, 24, 32] {
        let v: Vec<f32> = (0..n * n * n)
            .map(|i| rng::gaussian(3, n as u32, i as u32) as f32 + ((i % n) as f32 * 0.3).sin())
            .collect();
        for scales in 0..=max_scales(n, n) {
            let plan = Plan3::new(n, scales);
            let bands = plan.analyse(&v);
            assert_eq!(bands.len(), scales + 2);
            let e = relative_error(&v, &plan.synthesise(&bands));
            assert!(e <= 1e-5, "{n}³, {scales} scales: {e:e}");
        }
    }
}

fn sample_photo() -> Photo {
    let (w, h) = (64u32, 64u32);
    Photo {
        width: w,
        height: h,
        pixels: (0..w * h)
            .map(|i| {
                let (x, y) = ((i % w) as f32, (i / w) as f32);
                let blobs = (0.3 * x).sin() * (0.25 * y).cos();
                let grain = rng::gaussian(5, 1, i) as f32;
                let v = 0.5 + 0.2 * blobs + 0.05 * grain;
                [v, 0.7 * v + 0.1, 0.4 + 0.3 * (v - 0.5)]
            })
            .collect(),
    }
}

/// The volume is deterministic, tiles along all three axes (the wrap between the last slice
/// and the first is like neighbouring slices), and its slices have the photo's colours.
#[test]
fn a_solid_tiles_and_has_the_photos_colours() {
    let photo = sample_photo();
    let opts = SolidOptions {
        n: 32,
        iterations: 2,
        ..SolidOptions::default()
    };
    let v = synthesize_solid(&photo, &opts, &|_, _| true)
        .unwrap()
        .unwrap();
    assert_eq!(v.voxels.len(), 32 * 32 * 32);
    assert_eq!(
        v,
        synthesize_solid(&photo, &opts, &|_, _| true)
            .unwrap()
            .unwrap()
    );
    let n = 32usize;
    let diff = |a: u32, b: u32| {
        let (p, q) = (v.slice_z(a), v.slice_z(b));
        p.pixels
            .iter()
            .zip(&q.pixels)
            .map(|(x, y)| (0..3).map(|c| (x[c] - y[c]).abs() as f64).sum::<f64>())
            .sum::<f64>()
            / (3 * n * n) as f64
    };
    let interior = (0..n as u32 - 1).map(|z| diff(z, z + 1)).sum::<f64>() / (n - 1) as f64;
    let wrap = diff(n as u32 - 1, 0);
    assert!(
        wrap < 1.3 * interior && wrap > 0.7 * interior,
        "{wrap} vs {interior}"
    );
    let mean =
        |p: &[[f32; 3]], c: usize| p.iter().map(|x| x[c] as f64).sum::<f64>() / p.len() as f64;
    for c in 0..3 {
        for z in [0, 13] {
            let m = mean(&v.slice_z(z).pixels, c);
            assert!(
                (m - mean(&photo.pixels, c)).abs() < 0.03,
                "slice {z} channel {c}: {m}"
            );
        }
    }
}

#[test]
fn solid_options_out_of_range_are_refused() {
    let photo = sample_photo();
    for (opts, words) in [
        (
            SolidOptions {
                n: 8,
                ..SolidOptions::default()
            },
            "--solid 8",
        ),
        (
            SolidOptions {
                n: 256,
                ..SolidOptions::default()
            },
            "--solid 256",
        ),
        (
            SolidOptions {
                orientations: 0,
                ..SolidOptions::default()
            },
            "--orientations 0",
        ),
    ] {
        let e = synthesize_solid(&photo, &opts, &|_, _| true)
            .unwrap_err()
            .to_string();
        assert!(e.contains(words), "{e}");
    }
    let cancelled = synthesize_solid(
        &photo,
        &SolidOptions {
            n: 16,
            ..SolidOptions::default()
        },
        &|d, _| d < 2,
    );
    assert!(cancelled.unwrap().is_none());
}
