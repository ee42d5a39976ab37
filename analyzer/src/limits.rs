//! One policy for how much Proctex takes in and puts out, the same in the CLI, the worker and the
//! app: how many bytes a file may have, how many pixels a photo or a render may have, and how
//! much of a bad value an error message repeats.
//!
//! The limits protect the user from a tab or a shell that freezes for a minute and then dies
//! out of memory: every check happens before the memory is taken (a file's size before it is
//! read, an image's dimensions from its header before it is decoded, a render's size before its
//! buffer exists). The CLI lets a user go past the pixel limits with `--max-pixels`; the file
//! limit is fixed, since no photo a camera or an editor writes comes near it.

use crate::error::{Error, Result};

/// Most bytes read from one file (256 MiB). A 50 MP photo is 10–30 MB as JPEG and under
/// 150 MB as an 8-bit PNG; an uncompressed 16-bit TIFF of that size is the one kind of photo
/// past it, and it converts to PNG.
pub const MAX_FILE_BYTES: u64 = 256 << 20;
/// Largest side of any image, in or out (the GPU's texture limit on most devices).
pub const MAX_SIDE: u32 = 16_384;
/// Most pixels a photo may have by default (50 MP: 600 MB as `f32` RGB; a 12 MP phone photo is
/// 144 MB).
pub const MAX_PIXELS: u64 = 50_000_000;
/// Most pixels a render may have by default, in the CLI and in the app's tile export alike:
/// 8192² (67 MP, 800 MB as `f32` RGB).
pub const MAX_RENDER_PIXELS: u64 = 8192 * 8192;
/// Most characters of a bad value that an error message repeats.
pub const QUOTE_CHARS: usize = 80;

/// How the CLI tells a user to go past a pixel limit.
pub const PAST_THE_LIMIT: &str = "pass --max-pixels N to allow more";

/// `value` for an error message: itself when short, else its first [`QUOTE_CHARS`] characters
/// followed by `…` and its length.
pub fn quote(value: &str) -> String {
    let n = value.chars().count();
    if n <= QUOTE_CHARS {
        return value.to_string();
    }
    let head: String = value.chars().take(QUOTE_CHARS - 1).collect();
    format!("{head}… ({n} characters)")
}

/// A message whose quoted parts (between `"` or `` ` ``) are cut to [`QUOTE_CHARS`]
/// characters each, and which as a whole is cut to a few lines: for messages that come from
/// elsewhere (a JSON parser, an image decoder) and may repeat a whole input.
pub fn bounded_message(message: &str) -> String {
    const MAX_CHARS: usize = 600;
    let mut out = String::new();
    let mut quoted = String::new();
    let mut open: Option<char> = None;
    for c in message.chars() {
        match open {
            Some(q) if c == q => {
                out.push_str(&quote(&quoted));
                out.push(c);
                quoted.clear();
                open = None;
            }
            Some(_) => quoted.push(c),
            None => {
                out.push(c);
                if matches!(c, '"' | '`') {
                    open = Some(c);
                }
            }
        }
    }
    if open.is_some() {
        out.push_str(&quote(&quoted));
    }
    if out.chars().count() > MAX_CHARS {
        let head: String = out.chars().take(MAX_CHARS - 1).collect();
        return format!("{head}…");
    }
    out
}

/// Refuses an image of `width × height` when a side is over [`MAX_SIDE`] or it has more than
/// `max_pixels` pixels. `what` names it ("the photo", "the render"); `past` says how to go past
/// the pixel limit where one can ([`PAST_THE_LIMIT`] in the CLI).
pub fn check_pixels(
    what: &str,
    width: u64,
    height: u64,
    max_pixels: u64,
    past: &str,
) -> Result<()> {
    if width > MAX_SIDE as u64 || height > MAX_SIDE as u64 {
        return Err(Error::TooLarge(format!(
            "{what} is {width}×{height} pixels; a side may be at most {MAX_SIDE}"
        )));
    }
    if width * height > max_pixels {
        return Err(Error::TooLarge(format!(
            "{what} is {width}×{height} pixels ({}), over the limit of {}; {past}",
            pixel_count(width * height),
            pixel_count(max_pixels)
        )));
    }
    Ok(())
}

/// A pixel count as people say it: megapixels, or pixels when under a tenth of one; a square
/// count also as its side (`67.1 MP (8192×8192)`).
fn pixel_count(n: u64) -> String {
    let side = (n as f64).sqrt().round() as u64;
    let square = if side * side == n && n >= 100_000 {
        format!(" ({side}×{side})")
    } else {
        String::new()
    };
    if n >= 100_000 {
        format!("{:.1} MP{square}", n as f64 / 1e6)
    } else {
        format!("{n} pixels")
    }
}

/// Refuses a file of `bytes` bytes over [`MAX_FILE_BYTES`].
pub fn check_file_bytes(bytes: u64) -> Result<()> {
    if bytes > MAX_FILE_BYTES {
        return Err(Error::TooLarge(format!(
            "the file has more than {} MiB; no photo needs that many (convert it to PNG or JPEG)",
            MAX_FILE_BYTES >> 20
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_are_bounded_and_say_how_long_the_value_was() {
        assert_eq!(quote("short"), "short");
        let long = "x".repeat(5000);
        let q = quote(&long);
        assert!(q.chars().count() < QUOTE_CHARS + 25, "{q}");
        assert!(q.ends_with("(5000 characters)"), "{q}");
        let msg = format!("invalid type: string \"{long}\", expected u32 at `{long}`");
        let b = bounded_message(&msg);
        assert!(b.chars().count() < 260, "{b}");
        assert!(b.starts_with("invalid type: string \"xxx"), "{b}");
        assert!(b.contains("expected u32"), "{b}");
        // An unclosed quote and a message long without quotes are bounded too.
        assert!(bounded_message(&format!("\"{long}")).chars().count() < 120);
        assert!(bounded_message(&long).chars().count() <= 600);
        // Multi-byte characters are cut at character boundaries.
        assert!(quote(&"é".repeat(200)).starts_with("éé"));
    }

    #[test]
    fn pixel_and_file_limits_say_the_limit_and_the_way_past_it() {
        assert!(check_pixels("the photo", 4000, 3000, MAX_PIXELS, PAST_THE_LIMIT).is_ok());
        let e = check_pixels("the photo", 9000, 9000, MAX_PIXELS, PAST_THE_LIMIT)
            .unwrap_err()
            .to_string();
        assert!(e.contains("50.0 MP") && e.contains("--max-pixels"), "{e}");
        let e = check_pixels("the render", 20000, 10, u64::MAX, PAST_THE_LIMIT)
            .unwrap_err()
            .to_string();
        assert!(e.contains("16384"), "{e}");
        assert!(check_file_bytes(MAX_FILE_BYTES).is_ok());
        assert!(check_file_bytes(MAX_FILE_BYTES + 1).is_err());
    }
}
