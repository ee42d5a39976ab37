//! Reading the CLI's input files within the limits of [`proctex::limits`]: a file's size is
//! checked before it is read (a regular file by its length, anything else — a pipe, a device
//! such as `/dev/zero` — by reading at most one byte past the limit), and a photo's pixel count
//! from its header before it is decoded. Every error names the file.

use std::io::Read;

use proctex::input::Photo;
use proctex::limits::{MAX_FILE_BYTES, check_file_bytes, quote};
use proctex::{Error, Result};

/// A file over [`MAX_FILE_BYTES`], as an error about that file.
fn too_big(path: &str) -> Error {
    Error::Io {
        path: quote(path),
        message: format!(
            "more than {} MiB; no photo or params file needs that many (a photo converts to PNG or \
             JPEG)",
            MAX_FILE_BYTES >> 20
        ),
    }
}

/// `error` with the file's name in front, whatever its kind.
pub fn naming(path: &str, error: Error) -> Error {
    let path = quote(path);
    match error {
        Error::Decode(m) => Error::Decode(format!("{path}: {m}")),
        Error::TooLarge(m) => Error::TooLarge(format!("{path}: {m}")),
        Error::Io { message, .. } => Error::Io { path, message },
        other => other,
    }
}

/// The bytes of `path`, at most [`MAX_FILE_BYTES`].
pub fn read(path: &str) -> Result<Vec<u8>> {
    let io = |e: std::io::Error| Error::Io {
        path: quote(path),
        message: e.to_string(),
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    if meta.is_dir() {
        return Err(Error::Io {
            path: quote(path),
            message: "is a folder, not a file".into(),
        });
    }
    if meta.is_file() {
        check_file_bytes(meta.len()).map_err(|_| too_big(path))?;
    }
    let hint = if meta.is_file() {
        meta.len() as usize
    } else {
        1 << 20
    };
    let mut bytes = Vec::with_capacity(hint.min(MAX_FILE_BYTES as usize) + 1);
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    check_file_bytes(bytes.len() as u64).map_err(|_| too_big(path))?;
    Ok(bytes)
}

/// The photo at `path`, refused from its header when it has more than `max_pixels` pixels.
pub fn load_photo(path: &str, max_pixels: u64) -> Result<Photo> {
    Photo::decode_limited(&read(path)?, max_pixels).map_err(|e| naming(path, e))
}
