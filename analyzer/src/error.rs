//! The one error type of the analyzer. Every message is meant to be shown to a user as is.

use thiserror::Error;

/// Everything that can go wrong between a file and a texture.
#[derive(Debug, Error)]
pub enum Error {
    /// The bytes are not an image we can decode (unknown format, truncated, corrupt).
    #[error("cannot read the image: {0}")]
    Decode(String),
    /// The image decodes but is too small to analyse.
    #[error("the image is {width}×{height} pixels; at least {min}×{min} is needed")]
    TooSmall {
        /// Width after crop.
        width: u32,
        /// Height after crop.
        height: u32,
        /// Minimum side.
        min: u32,
    },
    /// The image declares a size beyond what we accept.
    #[error("the image is too large: {0}")]
    TooLarge(String),
    /// A bad crop rectangle.
    #[error("bad crop: {0}")]
    Crop(String),
    /// A bad option value.
    #[error("bad option: {0}")]
    Option(String),
    /// A params document failed to parse or validate; `field` names the offending field.
    #[error("bad params at `{field}`: {message}")]
    Params {
        /// Path of the field, e.g. `model.weights[1][3]`.
        field: String,
        /// What is wrong with it.
        message: String,
    },
    /// A share link that holds no texture.
    #[error("{0}")]
    Link(String),
    /// File system error, with the path.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The OS message.
        message: String,
    },
}

impl Error {
    /// A params error at `field`.
    pub fn params(field: impl Into<String>, message: impl Into<String>) -> Self {
        Error::Params {
            field: field.into(),
            message: message.into(),
        }
    }
}

/// Result with the analyzer's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;
