//! Replaying inputs of the `booleans` fuzz target: `fuzz/fuzz_targets/program.rs` decodes and
//! checks boolean programs. Shared by the test files of its findings (`fuzz_findings.rs`,
//! `fuzz_findings_files.rs`, `fuzz_forks.rs`), which include it by path; it is not part of
//! `common/mod.rs`, so the other tests do not build the fuzz programs.

#![allow(dead_code)]

#[path = "../../fuzz/fuzz_targets/program.rs"]
pub mod program;

/// Replays with tiny rotations on.
pub fn replay(data: &[u8]) {
    replay_with(data, true);
}

/// Replays with tiny rotations on or off (`tiny`; the bounded CI run has them off).
pub fn replay_with(data: &[u8], tiny: bool) {
    if let Err(e) = program::run(data, tiny) {
        panic!("{e}");
    }
}

/// The committed input `tests/fuzz_findings/booleans/NAME.bin`.
pub fn booleans_input(name: &str) -> Vec<u8> {
    let path = format!(
        "{}/tests/fuzz_findings/booleans/{name}.bin",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Replays the committed input `tests/fuzz_findings/booleans/NAME.bin` with tiny rotations on.
pub fn replay_file(name: &str) {
    replay(&booleans_input(name));
}
