//! Why a command failed: the message printed and the exit code.

use bspcsg::Error;

/// Why a command failed: the message printed and the exit code.
#[derive(Debug)]
pub(crate) struct Failure {
    pub(crate) message: String,
    pub(crate) code: u8,
}

impl Failure {
    /// Exit code 1: usage, or a file that cannot be read, parsed or written.
    pub(crate) fn usage_or_io(message: impl Into<String>) -> Self {
        Failure {
            message: message.into(),
            code: 1,
        }
    }
}

impl From<Error> for Failure {
    /// The library's errors name their file already (except scene faults, which the export
    /// command prefixes). Invalid geometry, input over a reader's budget and booleans over
    /// their work budget exit 2; everything else concerns reading, parsing, options or writing,
    /// and exits 1.
    fn from(e: Error) -> Self {
        let code = match e {
            Error::InvalidMesh { .. }
            | Error::BrokenResult { .. }
            | Error::WrongVolume { .. }
            | Error::OverBudget { .. }
            | Error::BeyondBudget { .. }
            | Error::BeyondPrecision { .. } => 2,
            _ => 1,
        };
        Failure {
            message: e.to_string(),
            code,
        }
    }
}
