//! Atomic output: every file is written to a temporary beside its destination and renamed into
//! place only once complete, so a reader never sees half a file and a failed write leaves the
//! old one untouched.
//!
//! What the destination is decides how: a regular file (or none) is replaced by rename, keeping
//! the old file's permissions; a symbolic link is written through (its target is replaced, the
//! link stays); a character device (`/dev/null`, a terminal) is written to directly, as there is
//! nothing to replace; anything else (a directory, a FIFO, a socket, a block device) is refused.
//! Temporary names stay within the file system's 255-byte name limit however long the output's
//! name. Writes in progress are registered, so that a signal handler can remove their
//! temporaries ([`cleanup_interrupted_writes`]).

use std::ffi::{OsStr, OsString};
use std::fs;
use std::io::Write;
use std::os::unix::ffi::{OsStrExt, OsStringExt};
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

use super::OutFile;
use crate::error::{Error, Result};

/// Distinguishes the temporary files of concurrent writes within one process.
static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// The longest file name most file systems take (`NAME_MAX`).
const NAME_MAX: usize = 255;

/// Temporaries not yet renamed, and backups not yet dropped (with the file they back up).
static LIVE: Mutex<Vec<(PathBuf, Option<PathBuf>)>> = Mutex::new(Vec::new());

/// Files put in place by a rename since the process started.
static COMMITTED: AtomicBool = AtomicBool::new(false);

/// The list of live temporaries and backups. Every step that makes one, or renames one into
/// place, holds it, so a signal handler that takes it sees each file either not yet made or
/// registered, and each rename either done or never to happen.
fn live() -> MutexGuard<'static, Vec<(PathBuf, Option<PathBuf>)>> {
    LIVE.lock().unwrap_or_else(PoisonError::into_inner)
}

fn unregister(live: &mut Vec<(PathBuf, Option<PathBuf>)>, path: &Path) {
    if let Some(k) = live.iter().position(|(p, _)| p == path) {
        live.swap_remove(k);
    }
}

/// Removes the temporary files of every write in progress and puts back any companion file a
/// write had replaced but not yet committed; returns whether this process had already put any
/// file in place. For a handler of SIGINT or SIGTERM that runs on an ordinary thread (it takes
/// a lock, so it is not for an asynchronous signal handler); the process must exit straight
/// afterwards: the lock stays held, so no write starts or commits after this, and one racing
/// with it waits for the exit.
pub fn cleanup_interrupted_writes() -> bool {
    let mut live = live();
    for (path, restores) in std::mem::take(&mut *live) {
        match restores {
            Some(dest) => {
                let _ = fs::rename(&path, &dest);
            }
            None => {
                let _ = fs::remove_file(&path);
            }
        }
    }
    std::mem::forget(live);
    COMMITTED.load(Ordering::SeqCst)
}

/// `.NAME.SUFFIX` beside `dest`, with NAME cut short enough that the whole stays within
/// [`NAME_MAX`] bytes.
fn hidden_sibling(dest: &Path, suffix: &str) -> PathBuf {
    let name = dest.file_name().unwrap_or(OsStr::new("output")).as_bytes();
    let room = NAME_MAX - 1 - suffix.len();
    let mut bytes = Vec::with_capacity(NAME_MAX);
    bytes.push(b'.');
    bytes.extend_from_slice(&name[..name.len().min(room)]);
    bytes.extend_from_slice(suffix.as_bytes());
    dest.with_file_name(OsString::from_vec(bytes))
}

fn unique_suffix(kind: &str) -> String {
    let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    format!(".{}.{n}.{kind}", std::process::id())
}

/// Where a file's bytes go.
enum Target {
    /// Replaced by rename: a regular file or a new one (a link's target, for a link).
    Replace(PathBuf),
    /// Written in place: a character device.
    Direct(PathBuf),
}

/// How `dest` is written (see the module docs).
fn target(dest: &Path) -> Result<Target> {
    let refuse = |why: &str| Error::Io {
        path: dest.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidInput, why.to_owned()),
    };
    let Ok(link) = fs::symlink_metadata(dest) else {
        return Ok(Target::Replace(dest.to_path_buf()));
    };
    let path = if link.file_type().is_symlink() {
        fs::canonicalize(dest).map_err(|_| {
            refuse("is a symbolic link to a missing file; give the output its own name or create the file it names")
        })?
    } else {
        dest.to_path_buf()
    };
    let kind = fs::metadata(&path)
        .map_err(|source| Error::Io {
            path: dest.to_path_buf(),
            source,
        })?
        .file_type();
    if kind.is_file() {
        Ok(Target::Replace(path))
    } else if kind.is_char_device() {
        Ok(Target::Direct(path))
    } else if kind.is_dir() {
        Err(refuse("is a directory"))
    } else {
        Err(refuse(
            "is not a regular file (a FIFO, socket or block device); outputs are only written \
             to regular files and character devices",
        ))
    }
}

/// A temporary file beside its destination, removed on drop unless renamed into place.
pub(crate) struct TempFile {
    tmp: PathBuf,
    dest: PathBuf,
    renamed: bool,
}

impl TempFile {
    /// Creates the temporary file for `dest` (with the permissions of an existing `dest`) and
    /// lets `fill` write it.
    fn write(
        dest: &Path,
        fill: impl FnOnce(&mut fs::File) -> std::io::Result<()>,
    ) -> Result<TempFile> {
        let io_err = |source| Error::Io {
            path: dest.to_path_buf(),
            source,
        };
        if dest.file_name().is_none() {
            return Err(io_err(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the output path does not name a file",
            )));
        }
        let tmp = hidden_sibling(dest, &unique_suffix("tmp"));
        // `create_new` never clobbers a stranger's file that happens to have the same name.
        let mut live = live();
        let mut file = fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(io_err)?;
        live.push((tmp.clone(), None));
        drop(live);
        // From here on the guard removes the temporary file if anything fails.
        let guard = TempFile {
            tmp,
            dest: dest.to_path_buf(),
            renamed: false,
        };
        if let Ok(old) = fs::metadata(dest) {
            file.set_permissions(old.permissions()).map_err(io_err)?;
        }
        fill(&mut file).map_err(io_err)?;
        // Flushed to disk before the rename, so a crash cannot leave a renamed but empty file.
        file.sync_all().map_err(io_err)?;
        Ok(guard)
    }

    fn rename(&mut self) -> Result<()> {
        let mut live = live();
        fs::rename(&self.tmp, &self.dest).map_err(|source| Error::Io {
            path: self.dest.clone(),
            source,
        })?;
        self.renamed = true;
        COMMITTED.store(true, Ordering::SeqCst);
        unregister(&mut live, &self.tmp);
        Ok(())
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if !self.renamed {
            // Nothing more can be done about a failure here; the write already failed.
            let mut live = live();
            let _ = fs::remove_file(&self.tmp);
            unregister(&mut live, &self.tmp);
        }
    }
}

/// Writes one file atomically (see the module docs): a reader sees the old file or the new
/// one, never a part (the editor's scene saves).
pub(crate) fn write_file_atomically(dest: &Path, bytes: &[u8]) -> Result<()> {
    write_file_with(dest, |w| w.write_all(bytes))
}

/// Writes one file atomically (see the module docs), its content made by `fill`.
pub(crate) fn write_file_with(
    dest: &Path,
    fill: impl FnOnce(&mut fs::File) -> std::io::Result<()>,
) -> Result<()> {
    match target(dest)? {
        Target::Direct(path) => direct(&path, fill),
        Target::Replace(path) => TempFile::write(&path, fill)?.rename(),
    }
}

fn direct(path: &Path, fill: impl FnOnce(&mut fs::File) -> std::io::Result<()>) -> Result<()> {
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut file = fs::OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(io_err)?;
    fill(&mut file).map_err(io_err)
}

/// Writes every file to a temporary first and renames them, in order, only once all are
/// complete. The last file is the main one; each companion replaced before it is kept as a
/// hidden backup until the main file is in place, and put back if that rename fails, so the
/// old main file never refers to a new companion. A main file that is a character device is
/// written directly, after the companions.
pub(crate) fn write_atomically(files: &[OutFile]) -> Result<()> {
    let Some((main_file, companion_files)) = files.split_last() else {
        return Ok(());
    };
    let main_target = target(&main_file.path)?;
    let mut companions = Vec::with_capacity(companion_files.len());
    for f in companion_files {
        let path = match target(&f.path)? {
            Target::Replace(p) => p,
            Target::Direct(_) => {
                return Err(Error::Io {
                    path: f.path.clone(),
                    source: std::io::Error::new(
                        std::io::ErrorKind::InvalidInput,
                        "a companion file cannot be a device; choose another output name",
                    ),
                });
            }
        };
        companions.push(TempFile::write(&path, |w| w.write_all(&f.bytes))?);
    }
    let mut main = match &main_target {
        Target::Replace(p) => Some(TempFile::write(p, |w| w.write_all(&main_file.bytes))?),
        Target::Direct(_) => None,
    };
    let mut backups: Vec<Backup> = Vec::new();
    let mut created: Vec<PathBuf> = Vec::new();
    let result = (|| {
        for t in companions.iter_mut() {
            match Backup::of(&t.dest)? {
                Some(b) => backups.push(b),
                None => created.push(t.dest.clone()),
            }
            t.rename()?;
        }
        match (&mut main, &main_target) {
            (Some(t), _) => t.rename(),
            (None, Target::Direct(p)) => direct(p, |w| w.write_all(&main_file.bytes)),
            (None, Target::Replace(_)) => Ok(()),
        }
    })();
    match result {
        Ok(()) => {
            for b in backups {
                let mut live = live();
                let _ = fs::remove_file(&b.copy);
                unregister(&mut live, &b.copy);
            }
            Ok(())
        }
        Err(e) => {
            // Restore the companions the old main file refers to; drop new ones.
            for b in backups {
                let mut live = live();
                let _ = fs::rename(&b.copy, &b.dest);
                unregister(&mut live, &b.copy);
            }
            for c in created {
                let _ = fs::remove_file(c);
            }
            Err(e)
        }
    }
}

/// An existing file kept under a hidden name beside it while it is being replaced.
struct Backup {
    dest: PathBuf,
    copy: PathBuf,
}

impl Backup {
    /// A hard link to `dest` (a copy where links are not supported), or `None` when `dest`
    /// does not exist yet.
    fn of(dest: &Path) -> Result<Option<Backup>> {
        if fs::symlink_metadata(dest).is_err() {
            return Ok(None);
        }
        let copy = hidden_sibling(dest, &unique_suffix("old"));
        let mut live = live();
        fs::hard_link(dest, &copy)
            .or_else(|_| fs::copy(dest, &copy).map(|_| ()))
            .map_err(|source| Error::Io {
                path: dest.to_path_buf(),
                source,
            })?;
        live.push((copy.clone(), Some(dest.to_path_buf())));
        Ok(Some(Backup {
            dest: dest.to_path_buf(),
            copy,
        }))
    }
}
