//! The GLB container: a 12-byte header, a JSON chunk, then an optional BIN chunk.

use std::path::Path;

use crate::error::{Error, Result};
use crate::io::parse_error;

pub(super) const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Splits a GLB container into its JSON chunk and optional BIN chunk.
pub(super) fn split_glb<'a>(path: &Path, bytes: &'a [u8]) -> Result<(&'a [u8], Option<&'a [u8]>)> {
    let err = |m: &str| parse_error(path, None, format!("GLB: {m}"));
    let u32_at = |o: usize| {
        bytes
            .get(o..o + 4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    };
    let version = u32_at(4).ok_or_else(|| err("the header is truncated"))?;
    if version != 2 {
        return Err(Error::Unsupported {
            path: path.to_path_buf(),
            message: format!("GLB version {version}; only glTF 2.0 is supported"),
        });
    }
    let length = u32_at(8).ok_or_else(|| err("the header is truncated"))? as usize;
    if length > bytes.len() {
        return Err(err(&format!(
            "the header says {length} bytes but the file has {} (truncated)",
            bytes.len()
        )));
    }
    let bytes = &bytes[..length];
    let chunk = |at: usize| -> Result<Option<(u32, &'a [u8], usize)>> {
        if at >= bytes.len() {
            return Ok(None);
        }
        let (Some(len), Some(ty)) = (u32_at(at), u32_at(at + 4)) else {
            return Err(err("a chunk header is truncated"));
        };
        let start = at + 8;
        let data = start
            .checked_add(len as usize)
            .and_then(|end| bytes.get(start..end))
            .ok_or_else(|| err("a chunk runs past the end of the file"))?;
        // Chunks are padded to 4 bytes; the next one starts after the padding.
        let next = (start + data.len()).next_multiple_of(4);
        Ok(Some((ty, data, next)))
    };
    let Some((CHUNK_JSON, json_bytes, mut at)) = chunk(12)? else {
        return Err(err("the first chunk is not JSON"));
    };
    let mut bin = None;
    // Unknown chunk types are to be ignored; the BIN chunk, if any, is the first of its type.
    while let Some((ty, data, next)) = chunk(at)? {
        if ty == CHUNK_BIN && bin.is_none() {
            bin = Some(data);
        }
        at = next;
    }
    Ok((json_bytes, bin))
}

/// The GLB container: header, JSON chunk padded with spaces, BIN chunk padded with zeros.
/// `None` when the total exceeds the format's u32 length.
pub(super) fn glb_bytes(mut json: Vec<u8>, bin: Option<Vec<u8>>) -> Option<Vec<u8>> {
    json.resize(json.len().next_multiple_of(4), b' ');
    let bin = bin.map(|mut b| {
        b.resize(b.len().next_multiple_of(4), 0);
        b
    });
    let total = 12 + 8 + json.len() + bin.as_ref().map_or(0, |b| 8 + b.len());
    let total32 = u32::try_from(total).ok()?;
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(GLB_MAGIC);
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&total32.to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
    out.extend_from_slice(&json);
    if let Some(b) = bin {
        out.extend_from_slice(&(b.len() as u32).to_le_bytes());
        out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        out.extend_from_slice(&b);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::io::gltf::read;

    #[test]
    fn glb_header_shorter_than_itself() {
        let mut b = b"glTF".to_vec();
        b.extend_from_slice(&2u32.to_le_bytes());
        b.extend_from_slice(&4u32.to_le_bytes());
        assert!(read(Path::new("t.glb"), &b).is_err());
    }
}
