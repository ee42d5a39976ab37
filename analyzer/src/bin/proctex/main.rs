//! `proctex`: the command-line face of the analyzer. Exit codes: 0 success, 1 bad input or a
//! failed operation (the message says which), 2 bad usage.

mod args;
mod fidelity;
mod files;
mod help;
mod pyramid;

use std::process::ExitCode;
use std::time::Instant;

use args::{Args, parse_option, take_max_pixels, usage};
use files::{load_photo, read};
use help::{
    ANALYZE_HELP, BUILD_DB_HELP, EVALUATE_HELP, EXPORT_HELP, MAIN_HELP, MORPH_HELP, RENDER_HELP,
    SYNTH_HELP,
};
use proctex::analyze::Options;
use proctex::db::Db;
use proctex::distance::distances;
use proctex::evaluate::synthesize_model_progress;
use proctex::input::{Crop, Photo};
use proctex::limits::{self, quote};
use proctex::params::Params;
use proctex::render::{Image, View, period_texels, render};
use proctex::retrieve::{ModelChoice, Refinement, Suggestion, analyze_photo_model_progress};
use proctex::spectrum::Estimator;
use proctex::{Error, Result};

pub(crate) fn write_png(path: &str, img: &Image, depth16: bool) -> Result<()> {
    let io = |e: image::ImageError| Error::Io {
        path: path.into(),
        message: e.to_string(),
    };
    if !path.to_ascii_lowercase().ends_with(".png") {
        return Err(usage(format!("{path}: output must be a .png file")));
    }
    if depth16 {
        let buf: image::ImageBuffer<image::Rgb<u16>, Vec<u16>> =
            image::ImageBuffer::from_raw(img.width, img.height, img.to_rgb16())
                .expect("buffer size matches");
        buf.save(path).map_err(io)
    } else {
        image::save_buffer(
            path,
            &img.to_rgb8(),
            img.width,
            img.height,
            image::ExtendedColorType::Rgb8,
        )
        .map_err(io)
    }
}

/// Parses an analysis option at `flag`; returns false when `flag` is not one.
fn analysis_flag(flag: &str, a: &mut Args, o: &mut Options) -> Result<bool> {
    match flag {
        "--size" => o.size = a.parsed(flag)?,
        "--crop" => o.crop = Some(Crop::parse(&a.value(flag)?)?),
        "--no-histogram" => o.histogram = false,
        "--knots" => o.knots = a.parsed(flag)?,
        "--seed" => o.seed = a.parsed(flag)?,
        "--no-periodic" => o.periodic = false,
        "--isotropic" => o.orientation = false,
        "--no-tone" => o.tone = false,
        "--flatten-lighting" => o.flatten_lighting = true,
        "--estimator" => {
            o.estimator = match a.value(flag)?.as_str() {
                "lagae" => Estimator::Lagae,
                "deconvolved" => Estimator::Deconvolved,
                "rings" => Estimator::Rings,
                other => {
                    return Err(usage(format!(
                        "--estimator: `{other}` is not `rings`, `deconvolved` or `lagae`"
                    )));
                }
            }
        }
        _ => return Ok(false),
    }
    o.validate()?;
    Ok(true)
}

fn summary(p: &Params, ms: f64) -> String {
    let mut s = String::new();
    let n = p.model.noise_layer();
    if let Some(src) = &p.source {
        s += &format!(
            "photo {}×{}, analysed at {}×{} ({} estimator) in {ms:.1} ms\n",
            src.width, src.height, src.analysis_width, src.analysis_height, src.estimator
        );
    }
    s += &format!(
        "mean rgb {:.3} {:.3} {:.3}; {} bands (finest first); histogram {}\n",
        p.colour.mean[0],
        p.colour.mean[1],
        p.colour.mean[2],
        n.bands(),
        if n.histogram.enabled { "on" } else { "off" }
    );
    if let proctex::params::Model::Structured(m) = &p.model {
        let pat = &m.pattern;
        let values: Vec<String> = pat
            .kind
            .specs()
            .iter()
            .zip(pat.vector())
            .map(|(spec, v)| format!("{} {v:.3}", spec.name))
            .collect();
        s += &format!(
            "model {}: scale {:.2} texels, rotation {:.1}°; {}\n  ramp:",
            pat.kind.name(),
            pat.scale,
            pat.rotation_deg,
            values.join(", ")
        );
        for stop in &m.ramp {
            s += &format!(
                " {:.3}→({:.2} {:.2} {:.2})",
                stop.at, stop.rgb[0], stop.rgb[1], stop.rgb[2]
            );
        }
        s += "\n  residual noise:\n";
    }
    for c in 0..3 {
        let w: Vec<String> = n.weights[c].iter().map(|v| format!("{v:.4}")).collect();
        s += &format!("  channel {c} weights: {}", w.join(" "));
        if n.fine[c] > 0.0 {
            s += &format!(", finest band after the histogram {:.4}", n.fine[c]);
        }
        s += "\n";
    }
    s += &format!(
        "period: {} texels ({} world units)",
        period_texels(p),
        period_texels(p) as f64 * p.transform.scale as f64
    );
    s
}

fn read_params(path: &str) -> Result<Params> {
    let text = String::from_utf8(read(path)?)
        .map_err(|_| Error::params("(document)", format!("{path}: not UTF-8 text")))?;
    Params::from_json(&text)
}

fn cmd_export(mut a: Args) -> Result<()> {
    let (mut files, mut format, mut out) = (Vec::new(), None, None);
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{EXPORT_HELP}");
                return Ok(());
            }
            "--format" => format = Some(a.value(&arg)?),
            "-o" | "--output" => out = Some(a.value(&arg)?),
            f if f.starts_with('-') => {
                return Err(usage(format!("export: unknown option {}", quote(f))));
            }
            _ => files.push(arg),
        }
    }
    if files.is_empty() {
        return Err(usage("export: which params file? (proctex export PARAMS)"));
    }
    let format = format.ok_or_else(|| usage("export: --format json|wgsl|glsl is required"))?;
    if !["json", "wgsl", "glsl"].contains(&format.as_str()) {
        return Err(usage(format!(
            "export: unknown format `{format}` (json, wgsl or glsl)"
        )));
    }
    if format == "json" && files.len() > 1 {
        return Err(usage(
            "export: --format json takes one params file (a morph exports as wgsl or glsl)",
        ));
    }
    let keys = files
        .iter()
        .map(|f| read_params(f))
        .collect::<Result<Vec<_>>>()?;
    let text = match keys.as_slice() {
        [p] if format == "json" => p.to_json(),
        _ => proctex::export::shader(&keys, &format)?,
    };
    match out {
        Some(path) => std::fs::write(&path, &text).map_err(|e| Error::Io {
            path,
            message: e.to_string(),
        })?,
        None => println!("{text}"),
    }
    Ok(())
}

fn cmd_build_db(mut a: Args) -> Result<()> {
    let mut out = None;
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{BUILD_DB_HELP}");
                return Ok(());
            }
            "-o" | "--output" => out = Some(a.value(&arg)?),
            f => return Err(usage(format!("build-db: unexpected argument `{f}`"))),
        }
    }
    let out = out.ok_or_else(|| usage("build-db: -o FILE is required"))?;
    let t = Instant::now();
    let last = std::sync::atomic::AtomicUsize::new(0);
    let db = Db::build(&|done, total| {
        let pct = done * 100 / total;
        if pct >= last.load(std::sync::atomic::Ordering::Relaxed) + 10 {
            last.store(pct, std::sync::atomic::Ordering::Relaxed);
            eprintln!("build-db: {pct} % ({done}/{total})");
        }
    });
    let bytes = db.to_bytes();
    std::fs::write(&out, &bytes).map_err(|e| Error::Io {
        path: out.clone(),
        message: e.to_string(),
    })?;
    println!(
        "wrote {out}: {} models, {} bytes, in {:.1} s",
        db.entries.len(),
        bytes.len(),
        t.elapsed().as_secs_f64()
    );
    Ok(())
}

fn cmd_morph(mut a: Args) -> Result<()> {
    let (mut files, mut t, mut out) = (Vec::new(), None, None);
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{MORPH_HELP}");
                return Ok(());
            }
            "--t" => t = Some(a.parsed::<f32>(&arg)?),
            "-o" | "--output" => out = Some(a.value(&arg)?),
            f if f.starts_with('-') => {
                return Err(usage(format!("morph: unknown option {}", quote(f))));
            }
            _ => files.push(arg),
        }
    }
    if files.len() < 2 {
        return Err(usage("morph: give two or more params files"));
    }
    let t = t.ok_or_else(|| usage("morph: --t T is required"))?;
    if !(0.0..=1.0).contains(&t) {
        return Err(usage(format!("morph: --t {t} is not in [0, 1]")));
    }
    let keys = files
        .iter()
        .map(|f| read_params(f))
        .collect::<Result<Vec<_>>>()?;
    let text = proctex::morph::morph_path(&keys, t)?.to_json();
    match out {
        Some(path) => std::fs::write(&path, &text).map_err(|e| Error::Io {
            path,
            message: e.to_string(),
        })?,
        None => println!("{text}"),
    }
    Ok(())
}

/// `--refine N`: N Nelder–Mead evaluations for each refined family (0: retrieval alone).
fn refinement_of(evaluations: usize) -> Refinement {
    if evaluations == 0 {
        Refinement::NONE
    } else {
        Refinement {
            evaluations,
            ..Refinement::default()
        }
    }
}

fn model_choice(a: &mut Args, flag: &str) -> Result<ModelChoice> {
    parse_model_choice(flag, &a.value(flag)?, "")
}

/// `v` as a model choice of `flag`; `also` names further accepted values in the message.
fn parse_model_choice(flag: &str, v: &str, also: &str) -> Result<ModelChoice> {
    ModelChoice::parse(v).ok_or_else(|| {
        let kinds: Vec<&str> = proctex::pattern::PatternKind::ALL
            .iter()
            .map(|k| k.name())
            .collect();
        usage(format!(
            "{flag}: `{}` is not auto, noise{also} or one of {}",
            quote(v),
            kinds.join(", ")
        ))
    })
}

/// The ranked candidates, one per line (empty when there was no ranking).
fn ranking_text(suggestions: &[Suggestion]) -> String {
    let mut ranking = String::new();
    if !suggestions.is_empty() {
        ranking += &format!(
            "candidates, the best first (score: for the {n} patterns the family classifier puts \
             first, {s:.1} × structure + {t:.1} × texture distance + {c} × half its class's \
             distance in the classifier beyond the nearest's × the photo's self distance + \
             margin, the best of them first and the others by their scores, the noise \
             model first or after them by its texture distance against the best, unless the \
             classifier's margin for its nearest family over the first candidate's class is \
             larger on the photo than on that candidate's render by more than {null}, and for a \
             family the photo's margin itself as well (then that family first); then the other \
             patterns in the classifier's order, score structure distance + margin):\n",
            n = proctex::retrieve::RENDER_ORDERED,
            null = proctex::retrieve::RENDER_NULL_MARGIN,
            s = 1.0 - proctex::retrieve::TEXTURE_WEIGHT,
            t = proctex::retrieve::TEXTURE_WEIGHT,
            c = proctex::retrieve::CLASSIFIER_WEIGHT,
        );
        for s in suggestions {
            let texture = s
                .distance
                .map_or("not fitted".into(), |d| format!("{d:.3}"));
            ranking += &format!("  {:<11} score {:.3}  texture {texture}", s.name, s.score);
            if let Some((p, swapped)) = &s.pattern {
                let refined = s
                    .refined_distance
                    .map(|d| format!(" → refined {d:.3}"))
                    .unwrap_or_default();
                ranking += &format!(
                    "  (structure: retrieval {:.3}{refined}; scale {:.1}, rotation {:.1}°{})",
                    s.retrieval_distance,
                    p.scale,
                    p.rotation_deg,
                    if *swapped { ", tones swapped" } else { "" }
                );
            }
            if s.speckier {
                ranking += &format!(
                    "  [passed over: its render has more specks than {}× the photo's]",
                    proctex::specks::SPECK_LIMIT
                );
            }
            ranking += "\n";
        }
    }
    ranking
}

/// The refinement's time budget (`--refine-seconds`): a progress callback that stops the
/// refinement once the budget is spent, and what it saw.
struct TimeBudget {
    /// When the refinement began (its first evaluation's report; retrieval and fitting are
    /// not counted).
    start: std::sync::OnceLock<Instant>,
    limit: Option<f64>,
    stopped_at: std::sync::Mutex<Option<(usize, usize)>>,
}

impl TimeBudget {
    fn new(limit: Option<f64>) -> TimeBudget {
        TimeBudget {
            start: std::sync::OnceLock::new(),
            limit,
            stopped_at: std::sync::Mutex::new(None),
        }
    }

    /// The progress callback: `false` (stop) once the budget is spent.
    fn progress(&self, done: usize, total: usize) -> bool {
        let Some(limit) = self.limit else {
            return true;
        };
        if self.start.get_or_init(Instant::now).elapsed().as_secs_f64() < limit {
            return true;
        }
        if let Ok(mut s) = self.stopped_at.lock() {
            s.get_or_insert((done, total));
        }
        false
    }

    /// A line saying where the budget stopped the refinement, if it did.
    fn report(&self) -> Option<String> {
        let (done, total) = (*self.stopped_at.lock().ok()?)?;
        Some(format!(
            "refinement: time budget of {} s spent after {done} of {total} evaluations (each \
             family kept its best point so far)",
            self.limit.unwrap_or(0.0)
        ))
    }
}

/// Parses `--refine-seconds S` (S > 0, finite).
fn refine_seconds(a: &mut Args, flag: &str) -> Result<Option<f64>> {
    let v: f64 = a.parsed(flag)?;
    if v.is_finite() && v > 0.0 {
        Ok(Some(v))
    } else {
        Err(usage(format!(
            "{flag}: must be a positive number of seconds, got {v}"
        )))
    }
}

fn cmd_analyze(mut a: Args) -> Result<()> {
    let mut o = Options::default();
    let mut model = ModelChoice::Auto;
    let mut refinement = Refinement::default();
    let mut seconds = None;
    let (mut photo, mut out, mut json) = (None, None, false);
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{ANALYZE_HELP}");
                return Ok(());
            }
            "-o" | "--output" => out = Some(a.value(&arg)?),
            "--json" => json = true,
            "--model" => model = model_choice(&mut a, &arg)?,
            "--refine" => refinement = refinement_of(a.parsed(&arg)?),
            "--refine-seconds" => seconds = refine_seconds(&mut a, &arg)?,
            f if analysis_flag(f, &mut a, &mut o)? => {}
            f if f.starts_with('-') => {
                return Err(usage(format!("analyze: unknown option {}", quote(f))));
            }
            _ if photo.is_none() => photo = Some(arg),
            _ => {
                return Err(usage(format!(
                    "analyze: unexpected argument `{}`",
                    quote(&arg)
                )));
            }
        }
    }
    let photo = photo.ok_or_else(|| usage("analyze: which photo? (proctex analyze PHOTO)"))?;
    let bytes = read(&photo)?;
    let t = Instant::now();
    let photo =
        Photo::decode_limited(&bytes, a.photo_pixels()).map_err(|e| files::naming(&photo, e))?;
    let budget = TimeBudget::new(seconds);
    let (analysis, suggestions) =
        analyze_photo_model_progress(&photo, &o, model, refinement, &|d, n| budget.progress(d, n))?;
    let ms = t.elapsed().as_secs_f64() * 1e3;
    let text = analysis.params.to_json();
    let ranking =
        ranking_text(&suggestions) + &budget.report().map(|r| r + "\n").unwrap_or_default();
    let chosen = format!("model: {}\n", analysis.params.model.name());
    if let Some(path) = &out {
        std::fs::write(path, &text).map_err(|e| Error::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
    }
    if json {
        println!("{text}");
        eprint!("{ranking}{chosen}");
        eprintln!("{}", summary(&analysis.params, ms));
    } else {
        print!("{ranking}{chosen}");
        println!("{}", summary(&analysis.params, ms));
        if let Some(path) = &out {
            println!("wrote {path}");
        }
    }
    Ok(())
}

fn cmd_render(mut a: Args) -> Result<()> {
    let (mut params_path, mut out) = (None, None);
    let (mut width, mut height): (Option<u32>, Option<u32>) = (None, None);
    let mut view = View::default();
    let (mut solid_z, mut period, mut depth16) = (None, false, false);
    let mut seamless = false;
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{RENDER_HELP}");
                return Ok(());
            }
            "-o" | "--output" => out = Some(a.value(&arg)?),
            "--size" => {
                let n = a.parsed(&arg)?;
                width = Some(n);
                height = Some(n);
            }
            "--width" => width = Some(a.parsed(&arg)?),
            "--height" => height = Some(a.parsed(&arg)?),
            "--pixel-size" => view.pixel_size = a.parsed(&arg)?,
            "--origin" => {
                let v = a.value(&arg)?;
                let xy = v
                    .split(',')
                    .map(|s| parse_option::<f32>(&arg, s))
                    .collect::<Result<Vec<f32>>>()?;
                if xy.len() != 2 {
                    return Err(usage(format!(
                        "--origin: expected X,Y, got `{}`",
                        quote(&v)
                    )));
                }
                view.origin = [xy[0], xy[1]];
            }
            "--solid-z" => solid_z = Some(a.parsed::<f32>(&arg)?),
            "--period" => period = true,
            "--seamless" => seamless = true,
            "--depth" => {
                depth16 = match a.value(&arg)?.as_str() {
                    "8" => false,
                    "16" => true,
                    d => return Err(usage(format!("--depth: `{d}` is not 8 or 16"))),
                }
            }
            f if f.starts_with('-') => {
                return Err(usage(format!("render: unknown option {}", quote(f))));
            }
            _ if params_path.is_none() => params_path = Some(arg),
            _ => {
                return Err(usage(format!(
                    "render: unexpected argument `{}`",
                    quote(&arg)
                )));
            }
        }
    }
    let params_path =
        params_path.ok_or_else(|| usage("render: which params file? (proctex render PARAMS)"))?;
    let out = out.ok_or_else(|| usage("render: -o OUT.png is required"))?;
    let mut params = read_params(&params_path)?;
    let (dw, dh) = params
        .source
        .as_ref()
        .map(|s| match s.crop {
            Some(c) => (c[2], c[3]),
            None => (s.width, s.height),
        })
        .unwrap_or((512, 512));
    let (w, h) = (width.unwrap_or(dw), height.unwrap_or(dh));
    if w == 0 || h == 0 {
        return Err(usage(format!(
            "image size {w}×{h}: a side must be at least 1"
        )));
    }
    limits::check_pixels(
        "the render",
        w as u64,
        h as u64,
        a.render_pixels(),
        limits::PAST_THE_LIMIT,
    )?;
    if !(view.pixel_size.is_finite() && view.pixel_size > 0.0) {
        return Err(usage("--pixel-size must be a positive number"));
    }
    if let Some(z) = solid_z {
        params.solid = true;
        view.z = z;
    }
    if period {
        params.transform.rotation_deg = 0.0;
        let p = period_texels(&params) as f32 * params.transform.scale;
        view.origin = [0.0, 0.0];
        view.pixel_size = p / w.max(h) as f32;
        eprintln!(
            "one period: {p} world units; {} world units per pixel",
            view.pixel_size
        );
    }
    let img = if seamless {
        if w != h || period || solid_z.is_some() || view.origin != [0.0, 0.0] {
            return Err(usage(
                "--seamless: a square tile (--size N) with no --period, --solid-z or --origin",
            ));
        }
        let img = proctex::seamless::render_seamless(&params, w, view.pixel_size)?;
        let [c, r] = proctex::seamless::seam_stats(&img);
        let [pc, pr] = proctex::seamless::seam_stats(&render(&params, w, h, &view));
        println!(
            "seamless tile: wrap / same-phase interior neighbour difference: columns {:.3}, \
             rows {:.3} (one image scatters about 1; a plain crop of this texture: {:.3}, {:.3})",
            c.ratio(),
            r.ratio(),
            pc.ratio(),
            pr.ratio()
        );
        if let Some((from, to)) = proctex::seamless::tile_turn(&params) {
            println!(
                "the pattern, turned {from:.1}° in the texture, is turned {to:.0}° in the tile \
                 (a lattice repeats over a square tile only at a quarter turn)"
            );
        }
        img
    } else {
        render(&params, w, h, &view)
    };
    write_png(&out, &img, depth16)?;
    println!("wrote {out} ({w}×{h})");
    Ok(())
}

fn cmd_synth(mut a: Args) -> Result<()> {
    let mut o = Options::default();
    let mut model = ModelChoice::Auto;
    let mut refinement = Refinement::default();
    let mut seconds = None;
    let (mut photo, mut out) = (None, None);
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{SYNTH_HELP}");
                return Ok(());
            }
            "-o" | "--output" => out = Some(a.value(&arg)?),
            "--model" => model = model_choice(&mut a, &arg)?,
            "--refine" => refinement = refinement_of(a.parsed(&arg)?),
            "--refine-seconds" => seconds = refine_seconds(&mut a, &arg)?,
            f if analysis_flag(f, &mut a, &mut o)? => {}
            f if f.starts_with('-') => {
                return Err(usage(format!("synth: unknown option {}", quote(f))));
            }
            _ if photo.is_none() => photo = Some(arg),
            _ => {
                return Err(usage(format!(
                    "synth: unexpected argument `{}`",
                    quote(&arg)
                )));
            }
        }
    }
    let photo = photo.ok_or_else(|| usage("synth: which photo? (proctex synth PHOTO -o OUT)"))?;
    let out = out.ok_or_else(|| usage("synth: -o OUT.png is required"))?;
    let decoded = load_photo(&photo, a.photo_pixels())?;
    let region = match o.crop {
        Some(c) => decoded.crop(c)?,
        None => decoded,
    };
    let o = Options { crop: None, ..o };
    let budget = TimeBudget::new(seconds);
    let (syn, analysis, suggestions) =
        synthesize_model_progress(&region, &o, model, refinement, &|d, n| {
            budget.progress(d, n)
        })?;
    print!("{}", ranking_text(&suggestions));
    if let Some(r) = budget.report() {
        println!("{r}");
    }
    println!("model: {}", analysis.params.model.name());
    let img = Image {
        width: syn.width,
        height: syn.height,
        pixels: syn.pixels,
    };
    write_png(&out, &img, false)?;
    println!("wrote {out} ({}×{})", img.width, img.height);
    Ok(())
}

fn cmd_evaluate(mut a: Args) -> Result<()> {
    let mut files = Vec::new();
    let mut json = false;
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{EVALUATE_HELP}");
                return Ok(());
            }
            "--json" => json = true,
            f if f.starts_with('-') => {
                return Err(usage(format!("evaluate: unknown option {}", quote(f))));
            }
            _ => files.push(arg),
        }
    }
    if files.len() != 2 {
        return Err(usage(
            "evaluate: needs exactly two images (proctex evaluate A B)",
        ));
    }
    let (pa, pb) = (
        load_photo(&files[0], a.photo_pixels())?,
        load_photo(&files[1], a.photo_pixels())?,
    );
    let d = distances(&pa, &pb);
    if json {
        println!("{}", serde_json::to_string(&d).expect("serialisable"));
    } else {
        println!(
            "spectrum_db {:.4}\ncolour {:.5}\nstructure {:.4}",
            d.spectrum_db, d.colour, d.structure
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let mut items: Vec<String> = std::env::args().skip(1).collect();
    let max_pixels = match take_max_pixels(&mut items) {
        Ok(m) => m,
        Err(e) => {
            eprintln!("proctex: {}", limits::bounded_message(&e.to_string()));
            return ExitCode::from(2);
        }
    };
    if items.is_empty() {
        eprintln!("{MAIN_HELP}");
        return ExitCode::from(2);
    }
    let cmd = items.remove(0);
    let args = Args {
        items,
        pos: 0,
        max_pixels,
    };
    let result = match cmd.as_str() {
        "analyze" => cmd_analyze(args),
        "render" => cmd_render(args),
        "synth" => cmd_synth(args),
        "pyramid" => pyramid::cmd_pyramid(args),
        "evaluate" => cmd_evaluate(args),
        "fidelity" => fidelity::cmd_fidelity(args),
        "morph" => cmd_morph(args),
        "export" => cmd_export(args),
        "build-db" => cmd_build_db(args),
        "help" | "-h" | "--help" => {
            println!("{MAIN_HELP}");
            Ok(())
        }
        other => Err(usage(format!(
            "unknown command `{}`; run `proctex help`",
            quote(other)
        ))),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e @ Error::Option(_)) => {
            eprintln!("proctex: {}", limits::bounded_message(&e.to_string()));
            ExitCode::from(2)
        }
        Err(e) => {
            eprintln!("proctex: {}", limits::bounded_message(&e.to_string()));
            ExitCode::from(1)
        }
    }
}
