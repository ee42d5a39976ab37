//! How far the Heeger–Bergen loop leaves each subband's histogram from the sample's, by the
//! number of rounds: the largest decile difference over every subband of each decorrelated
//! channel, in units of the subband's deviation (worst band) and of the channel's deviation;
//! and the pyramid's relative reconstruction error on each channel.
//!
//! `cargo run --release -p proctex-analyzer --example hb_convergence -- PHOTO...`

use proctex::heeger_bergen::{ChannelTargets, prepare, quantile, synthesize_channel};
use proctex::input::Photo;
use proctex::pyramid::Plan;

fn deviation(sorted: &[f32]) -> f32 {
    let m = sorted.iter().sum::<f32>() / sorted.len() as f32;
    (sorted.iter().map(|v| (v - m).powi(2)).sum::<f32>() / sorted.len() as f32).sqrt()
}

fn main() {
    for path in std::env::args().skip(1) {
        let photo = Photo::decode(&std::fs::read(&path).unwrap()).unwrap();
        let (w, h) = (photo.width as usize, photo.height as usize);
        let prepared = prepare(&photo, 4, 4);
        let plan = Plan::new(w, h, 4, 4);
        for (j, targets) in prepared.channels.iter().enumerate() {
            let channel_sd = deviation(&targets.pixels);
            let channel = synthesize_channel(targets, &plan, 0, (1, j as u32), &|| true).unwrap();
            let back = plan.synthesise(&plan.analyse(&channel));
            let (num, den) = channel
                .iter()
                .zip(&back)
                .fold((0.0f64, 0.0f64), |(n, d), (a, b)| {
                    (n + ((a - b) as f64).powi(2), d + (*a as f64).powi(2))
                });
            let mut line = format!(
                "{} ch {j}: reconstruction {:.1e};",
                path.rsplit('/').next().unwrap(),
                (num / den.max(1e-30)).sqrt()
            );
            for rounds in [0, 1, 2, 5, 10, 20] {
                let out =
                    synthesize_channel(targets, &plan, rounds, (1, j as u32), &|| true).unwrap();
                let mine = ChannelTargets::of(&out, &plan);
                let (mut by_band, mut by_channel) = (0.0f32, 0.0f32);
                for (a, b) in mine.subbands.iter().zip(&targets.subbands) {
                    let sd = deviation(b).max(1e-9);
                    for d in 1..10 {
                        let e = (quantile(a, d as f64 / 10.0) - quantile(b, d as f64 / 10.0)).abs();
                        by_band = by_band.max(e / sd);
                        by_channel = by_channel.max(e / channel_sd.max(1e-9));
                    }
                }
                line += &format!(" {rounds}: {by_band:.3}/{by_channel:.4}");
            }
            println!("{line}");
        }
    }
}
