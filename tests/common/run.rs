//! Running the `bspcsg` binary as a user does, in scratch directories that clean up after
//! themselves.

#![allow(dead_code)]

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh directory under the system's temporary directory, removed when dropped (also when
/// a test fails).
pub struct Scratch(pub PathBuf);

impl Scratch {
    pub fn new(name: &str) -> Scratch {
        static COUNT: AtomicUsize = AtomicUsize::new(0);
        let n = COUNT.fetch_add(1, Ordering::Relaxed);
        let dir =
            std::env::temp_dir().join(format!("bspcsg-cli-test-{}-{n}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    pub fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// The file names in the directory, sorted.
    pub fn files(&self) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// What one run of the binary did.
pub struct Run {
    pub code: i32,
    pub stdout: String,
    pub stderr: String,
}

impl Run {
    /// Asserts exit 0, showing stderr otherwise.
    pub fn ok(self) -> Run {
        assert_eq!(self.code, 0, "stderr: {}", self.stderr);
        self
    }

    /// Asserts the exit code, showing both streams otherwise.
    pub fn code(self, code: i32) -> Run {
        assert_eq!(
            self.code, code,
            "stdout: {}\nstderr: {}",
            self.stdout, self.stderr
        );
        self
    }

    /// Asserts that stderr holds each of `needles`, showing it otherwise.
    pub fn says(self, needles: &[&str]) -> Run {
        for needle in needles {
            assert!(self.stderr.contains(needle), "{needle}: {}", self.stderr);
        }
        self
    }
}

/// Runs `bspcsg ARGS… -o OUT`: a command that writes one file.
pub fn bspcsg_to(args: &[&OsStr], out: &Path) -> Run {
    bspcsg(args.iter().copied().chain(["-o".as_ref(), out.as_os_str()]))
}

/// Runs `bspcsg ARGS… -o OUT` and asserts that it exits with `code`, says each of `needles`
/// and leaves nothing at `out`.
pub fn refused(args: &[&OsStr], out: &Path, code: i32, needles: &[&str]) -> Run {
    let run = bspcsg_to(args, out).code(code).says(needles);
    assert!(!out.exists(), "nothing is written at {}", out.display());
    run
}

pub fn bspcsg<I, S>(args: I) -> Run
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let out = Command::new(env!("CARGO_BIN_EXE_bspcsg"))
        .args(args)
        .output()
        .expect("the binary runs");
    Run {
        // A signal (a crash) has no code; -1 never matches what a test expects.
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}
