//! Where buffers come from: the GLB binary chunk, base64 `data:` URIs, or files named by a
//! relative, percent-encoded URI beside the document.

use std::path::Path;

use base64::Engine as _;

use crate::error::{Error, Result};
use crate::io::parse_error;

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
            gltf::buffer::Source::Uri(uri) => read_uri(path, i, uri)?,
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

pub(super) fn read_uri(path: &Path, i: usize, uri: &str) -> Result<Vec<u8>> {
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
    let file = path.parent().unwrap_or(Path::new("")).join(name);
    std::fs::read(&file).map_err(|source| Error::Io { path: file, source })
}

/// Decodes `%XX` escapes; `None` for a malformed escape or a result that is not UTF-8.
pub(super) fn percent_decode(s: &str) -> Option<String> {
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
