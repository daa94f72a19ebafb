//! Where buffers come from: the GLB binary chunk, base64 `data:` URIs, or files named by a
//! relative, percent-encoded URI beside the document.
//!
//! A document may come from anywhere, so a file URI is held to the document's own folder: no
//! absolute path, no `..`, no symlink out of the folder, only a regular file (a FIFO would
//! block, a device would read forever), and its size checked against the declared
//! `byteLength` and [`MAX_BUFFER_BYTES`] before a byte is read.

use std::io::Read as _;
use std::path::{Component, Path};

use base64::Engine as _;

use crate::error::{Error, Result};
use crate::io::{MAX_BUFFER_BYTES, parse_error};

/// Every buffer's bytes: the GLB chunk, a `data:` URI or a file beside `path`.
pub(super) fn load_buffers(
    path: &Path,
    doc: &gltf::Document,
    blob: Option<&[u8]>,
) -> Result<Vec<Vec<u8>>> {
    let mut out = Vec::new();
    for buffer in doc.buffers() {
        let i = buffer.index();
        let data = match buffer.source() {
            gltf::buffer::Source::Bin => blob
                .ok_or_else(|| {
                    parse_error(
                        path,
                        None,
                        format!("buffer {i} refers to the GLB binary chunk, but there is none"),
                    )
                })?
                .to_vec(),
            gltf::buffer::Source::Uri(uri) => read_uri(path, i, uri, buffer.length())?,
        };
        if data.len() < buffer.length() {
            return Err(parse_error(
                path,
                None,
                format!(
                    "buffer {i} has {} bytes, fewer than its byteLength {}",
                    data.len(),
                    buffer.length()
                ),
            ));
        }
        out.push(data);
    }
    Ok(out)
}

/// Buffer `i`'s bytes from `uri`: a base64 `data:` URI or a file inside `path`'s folder of at
/// least `byte_length` bytes.
pub(super) fn read_uri(path: &Path, i: usize, uri: &str, byte_length: usize) -> Result<Vec<u8>> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, b64)) = rest.split_once(";base64,") else {
            return Err(Error::Unsupported {
                path: path.to_path_buf(),
                message: format!("buffer {i}: only base64 data URIs are supported"),
            });
        };
        return base64::engine::general_purpose::STANDARD
            .decode(b64)
            .map_err(|e| parse_error(path, None, format!("buffer {i}: bad base64 data: {e}")));
    }
    // A scheme (`http:`, `file:` …) or an absolute path is not a file beside this one.
    let has_scheme = uri.split_once(':').is_some_and(|(s, _)| {
        !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    });
    if has_scheme || uri.starts_with('/') || uri.starts_with('\\') {
        return Err(Error::Unsupported {
            path: path.to_path_buf(),
            message: format!("buffer {i} URI `{uri}`: only relative paths and data URIs are read"),
        });
    }
    let name = percent_decode(uri)
        .ok_or_else(|| parse_error(path, None, format!("buffer {i}: malformed URI `{uri}`")))?;
    read_beside(path, i, uri, Path::new(&name), byte_length)
}

/// Reads `name` (a decoded relative URI) from `path`'s folder, refusing anything that is not a
/// regular file inside that folder or whose size disagrees with `byte_length`.
fn read_beside(
    path: &Path,
    i: usize,
    uri: &str,
    name: &Path,
    byte_length: usize,
) -> Result<Vec<u8>> {
    let refuse = |why: String| Error::Unsupported {
        path: path.to_path_buf(),
        message: format!("buffer {i} URI `{uri}`: {why}"),
    };
    // Decoded, `%2F..%2F` is `/../`, so the components are checked after decoding.
    if name.as_os_str().is_empty()
        || name
            .components()
            .any(|c| !matches!(c, Component::Normal(_) | Component::CurDir))
    {
        return Err(refuse(
            "only a file inside the document's folder is read (no absolute path, no `..`)".into(),
        ));
    }
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let file = dir.join(name);
    // Named with the document that refers to the file: a missing `.bin` is the `.gltf`'s fault.
    let io_err = |p: &Path| {
        let shown = format!("buffer {i} URI `{uri}`: {}", p.display());
        move |source: std::io::Error| Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(source.kind(), format!("{shown}: {source}")),
        }
    };
    // Symlinks resolved on both sides: a link inside the folder may not lead out of it.
    let real_dir = std::fs::canonicalize(dir).map_err(io_err(dir))?;
    let real = std::fs::canonicalize(&file).map_err(io_err(&file))?;
    if !real.starts_with(&real_dir) {
        return Err(refuse(format!(
            "{} leads outside the document's folder (through a symbolic link)",
            file.display()
        )));
    }
    // Checked before opening: opening a FIFO for reading blocks until a writer comes.
    let meta = std::fs::metadata(&real).map_err(io_err(&file))?;
    if !meta.is_file() {
        return Err(refuse(format!(
            "{} is not a regular file (a directory, FIFO, socket or device)",
            file.display()
        )));
    }
    check_size(meta.len(), byte_length).map_err(|why| size_error(path, i, uri, &file, why))?;
    let f = std::fs::File::open(&real).map_err(io_err(&file))?;
    // The file may have been swapped since the check; the handle's own metadata is what counts.
    let meta = f.metadata().map_err(io_err(&file))?;
    if !meta.is_file() {
        return Err(refuse(format!("{} is not a regular file", file.display())));
    }
    check_size(meta.len(), byte_length).map_err(|why| size_error(path, i, uri, &file, why))?;
    let mut data = Vec::with_capacity(byte_length);
    // Never more than the declared length: a file growing meanwhile cannot enlarge the read.
    f.take(byte_length as u64)
        .read_to_end(&mut data)
        .map_err(io_err(&file))?;
    Ok(data)
}

/// A buffer file whose size cannot be right, named with the document that refers to it.
fn size_error(path: &Path, i: usize, uri: &str, file: &Path, why: String) -> Error {
    parse_error(
        path,
        None,
        format!("buffer {i} URI `{uri}`: {}: {why}", file.display()),
    )
}

/// Why a buffer file of `len` bytes cannot hold a declared `byte_length`, if it cannot.
fn check_size(len: u64, byte_length: usize) -> std::result::Result<(), String> {
    if byte_length as u64 > MAX_BUFFER_BYTES {
        return Err(format!(
            "byteLength {byte_length} exceeds the limit of {MAX_BUFFER_BYTES} bytes per buffer"
        ));
    }
    if len < byte_length as u64 {
        return Err(format!(
            "the file has {len} bytes, fewer than the buffer's byteLength {byte_length}"
        ));
    }
    Ok(())
}

/// Decodes `%XX` escapes; `None` for a malformed escape or a result that is not UTF-8.
pub(crate) fn percent_decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut k = 0;
    while k < b.len() {
        if b[k] == b'%' {
            let hex = std::str::from_utf8(b.get(k + 1..k + 3)?).ok()?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            k += 3;
        } else {
            out.push(b[k]);
            k += 1;
        }
    }
    String::from_utf8(out).ok()
}

/// Encodes every byte outside RFC 3986's unreserved set.
pub(super) fn percent_encode(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for &c in s.as_bytes() {
        if c.is_ascii_alphanumeric() || b"-._~".contains(&c) {
            out.push(c as char);
        } else {
            out.push_str(&format!("%{c:02X}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_coding() {
        assert_eq!(percent_encode("a b%.bin"), "a%20b%25.bin");
        assert_eq!(percent_decode("a%20b%25.bin").as_deref(), Some("a b%.bin"));
        assert_eq!(percent_decode("a%2"), None);
        assert_eq!(percent_decode("a%zz"), None);
        assert_eq!(percent_decode("%FF"), None);
    }
}
