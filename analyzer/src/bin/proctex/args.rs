//! The command line's arguments: a cursor over positional arguments and `--flag [value]`
//! options, the parsing of option values (numbers must be finite, bad values are quoted
//! briefly), and `--max-pixels`, which applies to every command.

use proctex::limits::{self, quote};
use proctex::{Error, Result};

/// Minimal argument cursor: positional arguments and `--flag [value]` options, and the pixel
/// limit that `--max-pixels` (anywhere on the line) sets for every command.
pub struct Args {
    pub items: Vec<String>,
    pub pos: usize,
    pub max_pixels: Option<u64>,
}

pub fn usage(msg: impl Into<String>) -> Error {
    Error::Option(msg.into())
}

impl Args {
    pub fn next(&mut self) -> Option<String> {
        let v = self.items.get(self.pos).cloned();
        self.pos += 1;
        v
    }
    pub fn value(&mut self, flag: &str) -> Result<String> {
        self.next()
            .ok_or_else(|| usage(format!("{flag} needs a value")))
    }
    /// The value of `flag` parsed as `T`; a number must be finite (`nan`, `inf` and `1e999` are
    /// refused by every option, not only where they would render black).
    pub fn parsed<T: std::str::FromStr>(&mut self, flag: &str) -> Result<T> {
        let v = self.value(flag)?;
        parse_option(flag, &v)
    }
    /// The photo pixel limit: `--max-pixels`, else [`limits::MAX_PIXELS`].
    pub fn photo_pixels(&self) -> u64 {
        self.max_pixels.unwrap_or(limits::MAX_PIXELS)
    }
    /// The render pixel limit: `--max-pixels`, else [`limits::MAX_RENDER_PIXELS`].
    pub fn render_pixels(&self) -> u64 {
        self.max_pixels.unwrap_or(limits::MAX_RENDER_PIXELS)
    }
}

/// `v` parsed as the value of `flag` (see [`Args::parsed`]).
pub fn parse_option<T: std::str::FromStr>(flag: &str, v: &str) -> Result<T> {
    if v.trim().parse::<f64>().is_ok_and(|x| !x.is_finite()) {
        return Err(usage(format!(
            "{flag}: `{}` is not a finite number",
            quote(v)
        )));
    }
    v.trim()
        .parse()
        .map_err(|_| usage(format!("{flag}: `{}` is not a valid value", quote(v))))
}

/// Takes `--max-pixels N` out of the command line (it applies to every command).
pub fn take_max_pixels(items: &mut Vec<String>) -> Result<Option<u64>> {
    let Some(at) = items.iter().position(|a| a == "--max-pixels") else {
        return Ok(None);
    };
    let v = items
        .get(at + 1)
        .cloned()
        .ok_or_else(|| usage("--max-pixels needs a value"))?;
    items.drain(at..at + 2);
    let n: u64 = parse_option("--max-pixels", &v)?;
    if n == 0 {
        return Err(usage("--max-pixels must be at least 1"));
    }
    Ok(Some(n))
}
