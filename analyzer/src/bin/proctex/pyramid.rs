//! `proctex pyramid`: the Heeger–Bergen raster synthesis of a photo.

use std::time::Instant;

use proctex::Result;
use proctex::heeger_bergen::{RasterOptions, synthesize_mixture, synthesize_progress};
use proctex::input::Crop;
use proctex::limits::{self, quote};
use proctex::render::Image;

use crate::args::{Args, usage};
use crate::files::{load_photo, naming};
use crate::help::PYRAMID_HELP;
use crate::write_png;

pub(super) fn cmd_pyramid(mut a: Args) -> Result<()> {
    let (mut photo, mut out, mut crop) = (None, None, None);
    let (mut mix, mut m) = (None, None);
    let (mut width, mut height) = (None, None);
    let mut opts = RasterOptions::new(0, 0);
    while let Some(arg) = a.next() {
        match arg.as_str() {
            "-h" | "--help" => {
                println!("{PYRAMID_HELP}");
                return Ok(());
            }
            "-o" | "--output" => out = Some(a.value(&arg)?),
            "--width" => width = Some(a.parsed::<u32>(&arg)?),
            "--height" => height = Some(a.parsed::<u32>(&arg)?),
            "--iterations" => opts.iterations = a.parsed(&arg)?,
            "--scales" => opts.scales = a.parsed(&arg)?,
            "--orientations" => opts.orientations = a.parsed(&arg)?,
            "--seed" => opts.seed = a.parsed(&arg)?,
            "--crop" => crop = Some(Crop::parse(&a.value(&arg)?)?),
            "--mix" => mix = Some(a.value(&arg)?),
            "--m" => m = Some(a.parsed::<f32>(&arg)?),
            f if f.starts_with('-') => {
                return Err(usage(format!("pyramid: unknown option {}", quote(f))));
            }
            _ if photo.is_none() => photo = Some(arg),
            _ => {
                return Err(usage(format!(
                    "pyramid: unexpected argument `{}`",
                    quote(&arg)
                )));
            }
        }
    }
    let photo =
        photo.ok_or_else(|| usage("pyramid: which photo? (proctex pyramid PHOTO -o OUT.png)"))?;
    let out = out.ok_or_else(|| usage("pyramid: -o OUT.png is required"))?;
    if !out.to_ascii_lowercase().ends_with(".png") {
        return Err(usage(format!("{out}: output must be a .png file")));
    }
    let decoded = load_photo(&photo, a.photo_pixels())?;
    let region = match crop {
        Some(c) => decoded.crop(c)?,
        None => decoded,
    };
    opts.width = width.unwrap_or(region.width);
    opts.height = height.unwrap_or(region.height);
    let limit = a
        .max_pixels
        .unwrap_or(proctex::heeger_bergen::MAX_SYNTHESIS_PIXELS);
    let limit = (limit, limits::PAST_THE_LIMIT);
    let start = Instant::now();
    let syn = match (mix, m) {
        (Some(other), Some(m)) => {
            let b = load_photo(&other, a.photo_pixels())?;
            synthesize_mixture(&region, &b, m, &opts, limit)?
        }
        (None, None) => synthesize_progress(&region, &opts, limit, &|_, _| true)
            .map_err(|e| naming(&photo, e))?
            .expect("the CLI never cancels"),
        _ => return Err(usage("pyramid: --mix B.png and --m M go together")),
    };
    let ms = start.elapsed().as_secs_f64() * 1000.0;
    let img = Image {
        width: syn.width,
        height: syn.height,
        pixels: syn.pixels,
    };
    write_png(&out, &img, false)?;
    println!(
        "wrote {out} ({}×{}, {} iterations, {:.0} ms)",
        img.width, img.height, opts.iterations, ms
    );
    Ok(())
}
