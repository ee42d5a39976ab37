//! Diagnostic: where, per quarter-octave ring of the spectrum distance
//! ([`proctex::distance::radial_spectrum`]), the fidelity protocol's syntheses (noise model and
//! auto) differ from the other patch. `cargo run --release --example rings -- PHOTO [SEEDS]
//! [MODEL]` (MODEL, `auto` by default, is what the second column set shows: `auto`, `noise` or a
//! family's name)
//! prints, per ring, its period in pixels, the RMS dB difference between the two patches, the
//! mean (the bias) and RMS dB difference (synthesis − other patch) of each model, and the RMS
//! difference to the analysed patch itself (in-sample); on stderr, which model auto chose per
//! patch and seed. All four quadrant patches are used, repeating or not.
use proctex::analyze::Options;
use proctex::distance::radial_spectrum;
use proctex::evaluate::synthesize_model;
use proctex::input::{Crop, Photo};
use proctex::params::Model;
use proctex::retrieve::{ModelChoice, Refinement};

fn db(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| 10.0 * x.max(1e-20).log10()).collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let photo = Photo::decode(&std::fs::read(&args[1]).expect("read")).expect("decode");
    let nseeds: u32 = args.get(2).map(|s| s.parse().expect("seeds")).unwrap_or(2);
    let (hw, hh) = (photo.width / 2, photo.height / 2);
    let quad = |x: u32, y: u32| photo.crop(Crop { x, y, w: hw, h: hh }).expect("crop");
    let pairs = [
        (quad(0, 0), quad(0, photo.height - hh)),
        (
            quad(photo.width - hw, 0),
            quad(photo.width - hw, photo.height - hh),
        ),
    ];
    let rings = radial_spectrum(&pairs[0].0).len();
    let label = args.get(3).map(String::as_str).unwrap_or("auto");
    let choice = ModelChoice::parse(label).expect("MODEL: auto, noise or a family's name");
    let models = [("noise", ModelChoice::Noise), (label, choice)];
    let mut sum = vec![vec![0.0f64; rings]; 2];
    let mut sq = vec![vec![0.0f64; rings]; 2];
    let mut ab = vec![0.0f64; rings];
    let mut ins = vec![vec![0.0f64; rings]; 2];
    let mut n = 0.0;
    for (a, b) in &pairs {
        let (ra, rb) = (db(&radial_spectrum(a)), db(&radial_spectrum(b)));
        for k in 0..rings {
            ab[k] += (ra[k] - rb[k]).powi(2) / 2.0;
        }
        for seed in 1..=nseeds {
            let o = Options {
                seed,
                ..Options::default()
            };
            for (src, other) in [(a, b), (b, a)] {
                let ro = db(&radial_spectrum(other));
                let rsrc = db(&radial_spectrum(src));
                for (mi, (_, m)) in models.iter().enumerate() {
                    let (syn, an, _) =
                        synthesize_model(src, &o, *m, Refinement::default()).expect("synth");
                    if mi == 1 {
                        let name = match &an.params.model {
                            Model::Noise(_) => "noise".to_string(),
                            Model::Structured(s) => s.pattern.kind.name().to_string(),
                        };
                        eprintln!("seed {seed}: {label} = {name}");
                    }
                    let rs = db(&radial_spectrum(&syn));
                    for k in 0..rings {
                        let d = rs[k] - ro[k];
                        sum[mi][k] += d;
                        sq[mi][k] += d * d;
                        ins[mi][k] += (rs[k] - rsrc[k]).powi(2);
                    }
                }
                n += 1.0;
            }
        }
    }
    println!(
        "ring period   A-B rms   noise mean  rms   {label:>5} mean  rms   in-sample rms noise {label}"
    );
    let (mut tn, mut ta, mut tab) = (0.0, 0.0, 0.0);
    for k in 0..rings {
        let period = 2.0 * 2f64.powf((k as f64 + 0.5) / 4.0);
        let abr = (ab[k] / 2.0).sqrt();
        let (mn, rn) = (sum[0][k] / n, (sq[0][k] / n).sqrt());
        let (ma, ra) = (sum[1][k] / n, (sq[1][k] / n).sqrt());
        tn += rn * rn;
        ta += ra * ra;
        tab += abr * abr;
        println!(
            "{k:>4} {period:>6.1} {abr:>9.2} {mn:>10.2} {rn:>5.2} {ma:>10.2} {ra:>5.2}   {:>15.2} {:>4.2}",
            (ins[0][k] / n).sqrt(),
            (ins[1][k] / n).sqrt()
        );
    }
    let r = rings as f64;
    println!(
        "rms over rings: A-B {:.2}  noise {:.2}  {label} {:.2}",
        (tab / r).sqrt(),
        (tn / r).sqrt(),
        (ta / r).sqrt()
    );
}
