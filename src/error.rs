//! The crate's one error type.

use std::path::PathBuf;

/// Everything that can go wrong in `bspcsg`, with enough context to fix it.
#[non_exhaustive]
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A primitive, transform or option parameter is out of range (non-finite, not positive,
    /// too few segments, a singular matrix …). Remedy: pass a value in the documented range.
    #[error("invalid parameter `{name}` = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name as the API spells it.
        name: &'static str,
        /// The value that was refused.
        value: f64,
        /// What the value must be instead.
        reason: &'static str,
    },

    /// An indexed mesh or polyhedron is not a valid closed solid (open, non-manifold, indices out
    /// of range, non-finite coordinates …). The message carries the counts. Remedy: repair the
    /// mesh, or use the lenient options where the API offers them.
    #[error("invalid mesh: {0}")]
    InvalidMesh(String),

    /// Reading or writing a file failed at the operating-system level.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file involved.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },

    /// A file's content is malformed. `line` is 1-based where the format has lines.
    #[error("{}{}: {message}", path.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
    Parse {
        /// The file involved.
        path: PathBuf,
        /// The 1-based line, where the format has lines.
        line: Option<usize>,
        /// What is wrong.
        message: String,
    },

    /// A file format or feature that is not supported (unknown extension, non-triangle glTF
    /// primitive …).
    #[error("{}: {message}", path.display())]
    Unsupported {
        /// The file involved.
        path: PathBuf,
        /// What is not supported.
        message: String,
    },

    /// A scene document is invalid. `json_path` locates the fault, e.g. `$.children[2].data.radius`;
    /// `file` names the document where it was read from a file.
    #[error("{}{json_path}: {message}", file.as_ref().map(|f| format!("{}: ", f.display())).unwrap_or_default())]
    Scene {
        /// The document's file, when it came from one.
        file: Option<PathBuf>,
        /// Where in the document the fault is.
        json_path: String,
        /// What is wrong.
        message: String,
    },
}

/// `Result` with this crate's [`Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Shorthand for [`Error::InvalidParameter`].
    pub(crate) fn param(name: &'static str, value: f64, reason: &'static str) -> Self {
        Error::InvalidParameter {
            name,
            value,
            reason,
        }
    }
}
