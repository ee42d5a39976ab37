//! `proctex pyramid`: the Heeger–Bergen raster synthesis of a photo.

use std::time::Instant;

use proctex::Error;
use proctex::Result;
use proctex::heeger_bergen::solid::{SolidOptions, synthesize_solid};
use proctex::heeger_bergen::{RasterOptions, synthesize_mixture, synthesize_progress};
use proctex::input::Crop;
use proctex::input::Photo;
use proctex::limits::{self, quote};
use proctex::render::Image;

use crate::args::{Args, usage};
use crate::files::{load_photo, naming};
use crate::help::PYRAMID_HELP;
use crate::write_png;

pub(super) fn cmd_pyramid(mut a: Args) -> Result<()> {
    let (mut photo, mut out, mut crop) = (None, None, None);
    let (mut mix, mut m) = (None, None);
    let mut solid = None;
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
            "--solid" => solid = Some(a.parsed::<u32>(&arg)?),
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
    let out =
        out.ok_or_else(|| usage("pyramid: -o OUT.png (or OUT_DIR with --solid) is required"))?;
    if let Some(n) = solid {
        if mix.is_some() || m.is_some() || width.is_some() || height.is_some() {
            return Err(usage(
                "pyramid --solid: no --mix, --m, --width or --height (the volume is N³)",
            ));
        }
        let decoded = load_photo(&photo, a.photo_pixels())?;
        let region = match crop {
            Some(c) => decoded.crop(c)?,
            None => decoded,
        };
        return write_solid(
            &region,
            &photo,
            &out,
            &SolidOptions {
                n,
                iterations: opts.iterations,
                scales: opts.scales,
                orientations: opts.orientations,
                seed: opts.seed,
            },
        );
    }
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

/// The solid texture of `region` as `n` PNG slices (`slice_000.png`, … along z) in `dir`.
fn write_solid(region: &Photo, photo: &str, dir: &str, opts: &SolidOptions) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::Io {
        path: quote(dir),
        message: e.to_string(),
    })?;
    let start = Instant::now();
    let volume = synthesize_solid(region, opts, &|_, _| true)
        .map_err(|e| naming(photo, e))?
        .expect("the CLI never cancels");
    let ms = start.elapsed().as_secs_f64() * 1000.0;
    for z in 0..volume.n {
        let slice = volume.slice_z(z);
        let img = Image {
            width: slice.width,
            height: slice.height,
            pixels: slice.pixels,
        };
        write_png(&format!("{dir}/slice_{z:03}.png"), &img, false)?;
    }
    println!(
        "wrote {dir}/slice_000.png … slice_{:03}.png ({n}³, {} iterations, {:.0} ms)",
        volume.n - 1,
        opts.iterations,
        ms,
        n = volume.n
    );
    Ok(())
}
