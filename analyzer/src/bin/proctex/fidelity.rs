//! `proctex fidelity`: the fidelity protocol on photos, and the development-set yardstick
//! (`--set DIR`) that tabulates the automatic model choice and its fidelity over a labelled set.

use std::path::Path;

use proctex::analyze::Options;
use proctex::devset::{
    Category, PhotoResult, SPECK_LIMIT, Summary, defined, fold_of, overall, parse_manifest, ratios,
    speck_ratio,
};
use proctex::evaluate::{
    RenderSeed, Synthesiser, UNSEEN_SEED_OFFSET, fidelity_by, ratio_difference,
};
use proctex::heeger_bergen::RasterOptions;
use proctex::retrieve::{ModelChoice, Refinement};
use proctex::{Error, Result};

use super::args::{Args, usage};
use super::files::{load_photo, read};
use super::{analysis_flag, parse_model_choice, refinement_of};
use proctex::limits;

const FIDELITY_HELP: &str = "\
proctex fidelity PHOTO... [--seeds N] [--first-seed S] [--model M] [--against M2] [--unseen-seed | --unseen-seeds K] [--json] [analyze OPTIONS]
proctex fidelity --set DIR [--seeds N] [--first-seed S] [--fold K/F] [--unseen-seed | --unseen-seeds K] [--json] [analyze OPTIONS]

For each photo: pairs its top-left with its bottom-left quadrant and its top-right with its
bottom-right (A, B), synthesises from each patch (seeds S..S+N−1: N 3 and S 1 unless given) and compares with the
other patch of its pair. Prints d(A,B), the mean d(synthesis, other patch), and their ratio
(near 1: as close as another patch of the same material), and the floor: the same ratio for
the patch's own spectrum with random phases, histogram-matched (the best any Gaussian model
can do). --model as for `analyze`, but noise by default (the noise-only table of docs/measurements.md),
or `pyramid`: the Heeger–Bergen raster synthesis from the patch (`proctex pyramid`'s defaults,
or --iterations N, --scales S and --orientations K as there).
--against M2 also runs M2 with the same seeds and prints the difference of the ratios (M − M2;
negative: M is nearer) with its standard error over the distinct source patches, the
independent samples (a difference within about twice it is not evidence either way): four, or
two where the quadrants repeat (a tile laid 2×2, each patch twice; the text output says so).

--set DIR: the development-set yardstick over the photos that DIR/manifest.tsv lists (columns
file, category, material, and families: the families a good match may use, `noise` for the
noise model). For every source patch of every photo: the model the automatic choice picks
(the first seed), whether it is a labelled family (y/n), the first three of its ranking and the
analysis time; per photo the ratios (spectrum, colour, structure, overall: their mean) of the
automatic choice and of the noise model alone, with seeds S..S+N−1 (default: 1 alone). Then the summary:
labelled-family rates of the structured patches (first and top three), the stochastic patches
served well (the noise model kept, or a family no farther from the photo), mean overall ratios
and their difference with standard errors over photos, times, the confusion matrix, and specks:
per patch the speck fraction of the photo, of the chosen model's synthesis and of every ranked
candidate (isolated outlier pixels), summarised against 1.5× the photo's own.
--fold K/F: only the photos of fold K (0..F-1) of F, by a hash of the file name (held-out
folds for cross-validation).
--unseen-seed: each analysed model is rendered at its seed + UNSEEN, a realisation that no
step of its fit rendered (the fit scores and pools renders of its own seed and the next
three, which are partly fitted to the photo's realisation); default: its own seed's render.
--unseen-seeds K: K such realisations (seed + UNSEEN, + UNSEEN + 1, …), their distances
averaged (specks: the first); a paired comparison of two builds then scatters less.";

/// The seeds `first..first + n`, refused where they would pass `u32::MAX` (the seeds of a
/// render's tone curve and unseen realisations lie further on).
fn seed_range(first: u32, n: u32) -> Result<Vec<u32>> {
    first
        .checked_add(n.saturating_add(UNSEEN_SEED_OFFSET))
        .map(|_| (first..first + n).collect())
        .ok_or_else(|| usage("fidelity: --first-seed too large"))
}

pub(super) fn cmd_fidelity(mut a: Args) -> Result<()> {
    let mut o = Options::default();
    let mut model = Choice::Model(ModelChoice::Noise);
    // Every family fitted: the records keep each family's texture distance (the offline
    // cross-validations reorder the families by it).
    let mut refinement = Refinement {
        fitted: usize::MAX,
        ..Refinement::default()
    };
    let mut files = Vec::new();
    let mut against = None;
    let (mut nseeds, mut first_seed, mut json) = (None, 1u32, false);
    let mut set = None;
    let mut fold = None;
    let mut raster = RasterOptions::new(0, 0);
    let mut render = RenderSeed::Fitted;
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                let offset = UNSEEN_SEED_OFFSET.to_string();
                println!("{}", FIDELITY_HELP.replace("UNSEEN", &offset));
                return Ok(());
            }
            "--seeds" => nseeds = Some(a.parsed::<u32>(&arg)?),
            "--first-seed" => first_seed = a.parsed::<u32>(&arg)?,
            "--set" => set = Some(a.value(&arg)?),
            "--fold" => fold = Some(fold_of_arg(&a.value(&arg)?)?),
            "--model" => model = choice(&mut a, &arg)?,
            "--against" => against = Some(choice(&mut a, &arg)?),
            "--refine" => {
                refinement = Refinement {
                    fitted: usize::MAX,
                    ..refinement_of(a.parsed(&arg)?)
                }
            }
            "--iterations" => raster.iterations = a.parsed(&arg)?,
            "--scales" => raster.scales = a.parsed(&arg)?,
            "--orientations" => raster.orientations = a.parsed(&arg)?,
            "--json" => json = true,
            "--unseen-seed" => render = RenderSeed::Unseen(1),
            "--unseen-seeds" => {
                let k = a.parsed::<u32>(&arg)?;
                if k == 0 {
                    return Err(usage("fidelity: --unseen-seeds needs K ≥ 1"));
                }
                render = RenderSeed::Unseen(k);
            }
            f if analysis_flag(f, &mut a, &mut o)? => {}
            f if f.starts_with('-') => return Err(usage(format!("fidelity: unknown option {f}"))),
            _ => files.push(arg),
        }
    }
    if let Some(dir) = set {
        if !files.is_empty() || against.is_some() || model != Choice::Model(ModelChoice::Noise) {
            return Err(usage(
                "fidelity --set: no photos, no --model and no --against (the set says them)",
            ));
        }
        let seeds = seed_range(first_seed, nseeds.unwrap_or(1))?;
        return dev_set(Path::new(&dir), &o, refinement, render, &seeds, fold, json);
    }
    if fold.is_some() {
        return Err(usage("fidelity: --fold needs --set"));
    }
    let nseeds = nseeds.unwrap_or(3);
    if files.is_empty() || nseeds == 0 {
        return Err(usage("fidelity: needs at least one photo and --seeds ≥ 1"));
    }
    let seeds = seed_range(first_seed, nseeds)?;
    if !json {
        println!(
            "{:<32} {:>8} {:>8} {:>6} {:>7}   {:>8} {:>8} {:>6} {:>7}   {:>8} {:>8} {:>6} {:>7}",
            "photo",
            "dB(A,B)",
            "dB(S,B)",
            "ratio",
            "floor",
            "col(A,B)",
            "col(S,B)",
            "ratio",
            "floor",
            "str(A,B)",
            "str(S,B)",
            "ratio",
            "floor"
        );
    }
    for f in &files {
        let photo = load_photo(f, a.photo_pixels())?;
        let by = |c: Choice| {
            let synthesiser = c.synthesiser(refinement, render, raster);
            fidelity_by(&photo, &o, synthesiser, &seeds, &mut |_| {})
        };
        let r = by(model)?;
        let diff = match against {
            Some(m) => {
                let other = by(m)?;
                Some((other, ratio_difference(&r, &other)))
            }
            None => None,
        };
        let name = Path::new(f)
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| f.clone());
        if json {
            let mut v = serde_json::json!({ "photo": name, "result": r });
            if let Some((other, (mean, se))) = &diff {
                v["against"] = serde_json::json!({
                    "result": other,
                    "ratio_difference": mean,
                    "standard_error": se,
                });
            }
            println!("{v}");
        } else {
            println!(
                "{:<32} {:>8.3} {:>8.3} {:>6.2} {:>7.2}   {:>8.4} {:>8.4} {:>6.2} {:>7.2}   {:>8.3} {:>8.3} {:>6.2} {:>7.2}",
                name,
                r.halves.spectrum_db,
                r.synthesis.spectrum_db,
                r.spectrum_ratio,
                r.floor_spectrum_ratio,
                r.halves.colour,
                r.synthesis.colour,
                r.colour_ratio,
                r.floor_colour_ratio,
                r.halves.structure,
                r.synthesis.structure,
                r.structure_ratio,
                r.floor_structure_ratio
            );
            if r.repeat {
                println!(
                    "  the quadrants repeat (a tile laid 2×2): two distinct source patches, each the mean of its two copies"
                );
            }
            if let Some((other, (mean, se))) = &diff {
                println!(
                    "  against it: ratios {:.2} / {:.2} / {:.2}; difference {:+.2} ± {:.2} / {:+.2} ± {:.2} / {:+.2} ± {:.2} (spectrum / colour / structure)",
                    other.spectrum_ratio,
                    other.colour_ratio,
                    other.structure_ratio,
                    mean.spectrum_db,
                    se.spectrum_db,
                    mean.colour,
                    se.colour,
                    mean.structure,
                    se.structure
                );
            }
        }
    }
    Ok(())
}

/// What `--model` and `--against` name: a procedural model, or the pyramid synthesis.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Choice {
    Model(ModelChoice),
    Pyramid,
}

impl Choice {
    fn synthesiser(
        self,
        refinement: Refinement,
        render: RenderSeed,
        raster: RasterOptions,
    ) -> Synthesiser {
        match self {
            Choice::Model(m) => Synthesiser::Model(m, refinement, render),
            Choice::Pyramid => Synthesiser::Pyramid(raster),
        }
    }
}

fn choice(a: &mut Args, flag: &str) -> Result<Choice> {
    let v = a.value(flag)?;
    if v == "pyramid" {
        return Ok(Choice::Pyramid);
    }
    parse_model_choice(flag, &v, ", pyramid").map(Choice::Model)
}

/// `K/F` of `--fold`.
fn fold_of_arg(v: &str) -> Result<(usize, usize)> {
    let bad = || usage(format!("--fold: `{v}` is not K/F with 0 ≤ K < F"));
    let (k, f) = v.split_once('/').ok_or_else(bad)?;
    let (k, f): (usize, usize) = (k.parse().map_err(|_| bad())?, f.parse().map_err(|_| bad())?);
    if k >= f {
        return Err(bad());
    }
    Ok((k, f))
}

/// The development-set yardstick (`--set DIR`): every photo of DIR/manifest.tsv (or of one
/// fold), measured and printed as it completes, then the summary.
fn dev_set(
    dir: &Path,
    o: &Options,
    refinement: Refinement,
    render: RenderSeed,
    seeds: &[u32],
    fold: Option<(usize, usize)>,
    json: bool,
) -> Result<()> {
    let manifest = dir.join("manifest.tsv");
    let text = String::from_utf8(read(&manifest.to_string_lossy())?)
        .map_err(|_| Error::Option(format!("{}: not UTF-8 text", manifest.display())))?;
    let entries: Vec<_> = parse_manifest(&text)
        .map_err(|e| Error::Option(format!("{}: {e}", manifest.display())))?
        .into_iter()
        .filter(|e| fold.is_none_or(|(k, f)| fold_of(&e.file, f) == k))
        .collect();
    let mut results = Vec::new();
    let mut sides = Vec::new();
    for entry in entries {
        let photo = load_photo(&dir.join(&entry.file).to_string_lossy(), limits::MAX_PIXELS)?;
        sides.push(photo.width.min(photo.height) / 2);
        let r = PhotoResult::measure(
            entry,
            |observe| {
                let auto = Synthesiser::Model(ModelChoice::Auto, refinement, render);
                fidelity_by(&photo, o, auto, seeds, observe)
            },
            || {
                let noise = Synthesiser::Model(ModelChoice::Noise, refinement, render);
                fidelity_by(&photo, o, noise, seeds, &mut |_| {})
            },
        )?;
        if json {
            println!("{}", serde_json::json!({ "photo": r }));
        } else {
            print_photo(&r);
        }
        results.push(r);
    }
    let summary = Summary::of(&results, &sides);
    let seed = match render {
        RenderSeed::Fitted => "the analysis seed's (the fitted realisation)".to_string(),
        RenderSeed::Unseen(1) => {
            format!("the analysis seed + {UNSEEN_SEED_OFFSET} (unseen by the fit)")
        }
        RenderSeed::Unseen(k) => format!(
            "the analysis seed + {UNSEEN_SEED_OFFSET} … + {} (unseen by the fit; distances averaged)",
            UNSEEN_SEED_OFFSET + k - 1
        ),
    };
    if json {
        println!(
            "{}",
            serde_json::json!({ "summary": summary, "renders": seed })
        );
    } else {
        print_summary(&summary, fold);
        println!("renders scored: {seed}");
    }
    Ok(())
}

fn yes_no(v: Option<bool>) -> &'static str {
    match v {
        Some(true) => "y",
        Some(false) => "n",
        None => "-",
    }
}

fn print_photo(r: &PhotoResult) {
    let labels = r
        .entry
        .families
        .as_ref()
        .map_or_else(|| "(no labels)".to_string(), |f| f.join(" "));
    let category = match r.entry.category {
        Category::Structured => "structured",
        Category::Stochastic => "stochastic",
    };
    let [s, c, t, all] = ratios(&r.auto);
    let [ns, nc, nt, nall] = ratios(&r.noise);
    println!(
        "{} ({category}: {}; labels {labels}){}",
        r.entry.file,
        r.entry.material,
        if !defined(&r.noise) {
            "; fidelity undefined: its paired quadrants are the same pixels"
        } else if r.auto.repeat {
            "; its quadrants repeat"
        } else {
            ""
        }
    );
    println!(
        "  ratios spectrum/colour/structure/overall: auto {s:.2} {c:.2} {t:.2} {all:.2}; noise \
         {ns:.2} {nc:.2} {nt:.2} {nall:.2}; auto − noise {:+.2}",
        overall(&r.auto) - overall(&r.noise)
    );
    for (i, ch) in r.choices.iter().enumerate() {
        let judged = match r.entry.category {
            Category::Structured => format!(
                "labelled {} top-3 {}",
                yes_no(r.labelled(ch)),
                yes_no(r.top3_labelled(ch))
            ),
            Category::Stochastic => {
                format!("served {}", yes_no(Some(r.stochastic_ok(i))))
            }
        };
        println!(
            "  {:<12} {:<11} {judged:<22} top-3 {:<34} {:>7.0} ms  specks {:.2}×  noise model {} numbers",
            ch.patch,
            ch.chosen,
            ch.top3.join(", "),
            ch.analysis_ms,
            speck_ratio(ch.render_specks, ch.photo_specks, ch.pixels),
            ch.noise_numbers
        );
    }
}

fn print_summary(s: &Summary, fold: Option<(usize, usize)>) {
    println!();
    match fold {
        Some((k, f)) => println!("== summary of fold {k} of {f}"),
        None => println!("== summary"),
    }
    let rate = |name: &str, r: &proctex::devset::Rate| {
        println!(
            "{name}: {}/{} = {:.0} % ± {:.0} % (standard error over photos)",
            r.hits,
            r.total,
            100.0 * r.fraction(),
            100.0 * r.standard_error
        );
    };
    rate(
        "structured patches, a labelled family chosen",
        &s.structured_labelled,
    );
    rate(
        "structured patches, a labelled family in the top three",
        &s.structured_top3,
    );
    rate("stochastic patches served well", &s.stochastic_ok);
    for (name, f) in [
        ("structured", &s.structured_fidelity),
        ("stochastic", &s.stochastic_fidelity),
    ] {
        println!(
            "{name} photos ({}): overall ratio auto {:.3} ± {:.3}, noise {:.3} ± {:.3}; \
             auto − noise {:+.3} ± {:.3} (median {:+.3}); mean ln(auto/noise) {:+.3} ± {:.3}",
            f.photos,
            f.auto.0,
            f.auto.1,
            f.noise.0,
            f.noise.1,
            f.difference.0,
            f.difference.1,
            f.median_difference,
            f.log_ratio.0,
            f.log_ratio.1
        );
        if f.undefined > 0 {
            println!(
                "  {} {name} photo(s) left out: paired quadrants with the same pixels (d(A,B) = 0)",
                f.undefined
            );
        }
    }
    for (side, ms) in &s.median_ms {
        println!("median automatic analysis of a {side}² patch: {ms:.0} ms");
    }
    let r = &s.specks_clean;
    println!(
        "specks: the chosen model's synthesis within {SPECK_LIMIT}× the photo's speck fraction: \
         {}/{} patches = {:.0} % ± {:.0} %",
        r.hits,
        r.total,
        100.0 * r.fraction(),
        100.0 * r.standard_error
    );
    let [least, median, most] = s.noise_numbers;
    println!(
        "the noise model's numbers per patch: {least}–{most}, median {median} (budget {})",
        proctex::noise_tone::PARAMETER_BUDGET
    );
    println!("specks per model (every patch's fitted candidate; ratio to the photo's):");
    for m in &s.specks_by_model {
        println!(
            "  {:<11} {:>3} renders, {:>3} past {SPECK_LIMIT}×; median ratio {:.2}, largest {:.2}",
            m.model, m.renders, m.over_limit, m.median_ratio, m.max_ratio
        );
    }
    println!("confusion (labels → chosen: patches):");
    for (label, cells) in &s.confusion {
        let cells: Vec<String> = cells.iter().map(|(m, n)| format!("{m} {n}")).collect();
        println!("  {label:<22} → {}", cells.join(", "));
    }
}
