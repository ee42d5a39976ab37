//! Two-tone decomposition (two-tone paper §3) of the shipped photos: how much of each photo's
//! colour the tone line keeps (RMS of photo − reconstruction against the photo's own RGB
//! standard deviation), tones inside the RGB cube, and the swap leaving colours unchanged.

mod common;

use common::{SAMPLES, sample};
use proctex::two_tone::two_tone;

fn rms(a: &[[f32; 3]], b: &[[f32; 3]]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| (0..3).map(|k| ((p[k] - q[k]) as f64).powi(2)).sum::<f64>())
        .sum();
    (s / (3 * a.len()) as f64).sqrt()
}

#[test]
fn the_tone_line_keeps_most_of_every_photo() {
    for name in SAMPLES {
        let photo = sample(name);
        let tt = two_tone(&photo);
        for t in tt.tones {
            assert!(t.iter().all(|v| (0.0..=1.0).contains(v)), "{name}: {t:?}");
        }
        let n = photo.pixels.len() as f64;
        let mean: [f64; 3] =
            [0, 1, 2].map(|k| photo.pixels.iter().map(|p| p[k] as f64).sum::<f64>() / n);
        let flat: Vec<[f32; 3]> = vec![mean.map(|v| v as f32); photo.pixels.len()];
        let sd = rms(&photo.pixels, &flat);
        let err = rms(&photo.pixels, &tt.reconstruct().pixels);
        let s_mean = tt.structure.iter().map(|&s| s as f64).sum::<f64>() / n;
        println!(
            "{name:28} tones {:?} → {:?}; structure mean {s_mean:.3}; RMS photo − two-tone {err:.4} vs photo sd {sd:.4} ({:.0} % of it)",
            tt.tones[0],
            tt.tones[1],
            100.0 * err / sd
        );
        // The first principal axis carries most of a material photo's colour variation.
        assert!(err < 0.75 * sd, "{name}: {err} vs {sd}");
        let sw = tt.swapped();
        assert_eq!(sw.tones, [tt.tones[1], tt.tones[0]]);
        let back = sw.reconstruct();
        assert!(rms(&back.pixels, &tt.reconstruct().pixels) < 1e-6, "{name}");
    }
}
