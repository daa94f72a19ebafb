//! Accessors out of loaded buffers: strides, sparse substitutions and index widths, all with
//! checked arithmetic; and a primitive's triangles (lists, strips, fans) from them.

use std::path::Path;

use glam::{DMat3, DMat4, DVec3, DVec4};
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use crate::error::{Error, Result};
use crate::io::parse_error;
use crate::io::triangles::Triangles;
use crate::mesh::weld::Welder;

/// Accessors without a buffer view read as zeros; a count above this for one of them is
/// taken as a damaged file rather than allocated.
const MAX_VIEWLESS_COUNT: usize = 1 << 24;

/// Reads accessors out of loaded buffers.
pub(super) struct Reader<'p> {
    pub(super) path: &'p Path,
    pub(super) buffers: Vec<Vec<u8>>,
}

impl Reader<'_> {
    fn err(&self, message: String) -> Error {
        parse_error(self.path, None, message)
    }

    /// Adds a primitive's triangles, transformed by `world`.
    pub(super) fn primitive(
        &self,
        prim: &gltf::Primitive,
        world: &DMat4,
        welder: &mut Welder,
        triangles: &mut Triangles,
    ) -> Result<()> {
        let mode = prim.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            return Err(Error::Unsupported {
                path: self.path.to_path_buf(),
                message: format!(
                    "primitive {} has mode {mode:?}; only triangles are supported",
                    prim.index()
                ),
            });
        }
        // A primitive without positions is not drawn (glTF 2.0, 3.7.2.1).
        let Some(pos_acc) = prim.get(&gltf::Semantic::Positions) else {
            return Ok(());
        };
        let ids = self.positions(&pos_acc, world, welder)?;
        let n = ids.len();
        let indices: Vec<u32> = match prim.indices() {
            Some(acc) => self.indices(&acc, n)?,
            None => (0..n as u32).collect(),
        };
        let flip = DMat3::from_mat4(*world).determinant() < 0.0;
        let mut emit = |t: [u32; 3]| {
            let mut tri = t.map(|i| ids[i as usize]);
            if flip {
                tri.swap(1, 2);
            }
            triangles.push(tri, t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
        };
        match mode {
            Mode::Triangles => {
                if !indices.len().is_multiple_of(3) {
                    return Err(self.err(format!(
                        "primitive {} has {} indices, not a multiple of 3",
                        prim.index(),
                        indices.len()
                    )));
                }
                for t in indices.chunks_exact(3) {
                    emit([t[0], t[1], t[2]]);
                }
            }
            Mode::TriangleStrip => {
                for (k, w) in indices.windows(3).enumerate() {
                    emit(if k % 2 == 0 {
                        [w[0], w[1], w[2]]
                    } else {
                        [w[0], w[2], w[1]]
                    });
                }
            }
            _ => {
                for w in indices.get(1..).unwrap_or_default().windows(2) {
                    emit([w[0], w[1], indices[0]]);
                }
            }
        }
        Ok(())
    }

    /// The welded vertex index of each element of a POSITION accessor, placed by `world`.
    fn positions(
        &self,
        pos_acc: &gltf::Accessor,
        world: &DMat4,
        welder: &mut Welder,
    ) -> Result<Vec<u32>> {
        if pos_acc.data_type() != DataType::F32
            || pos_acc.dimensions() != Dimensions::Vec3
            || pos_acc.normalized()
        {
            return Err(Error::Unsupported {
                path: self.path.to_path_buf(),
                message: format!(
                    "POSITION accessor {} is {:?} {:?}; only float VEC3 is supported",
                    pos_acc.index(),
                    pos_acc.data_type(),
                    pos_acc.dimensions()
                ),
            });
        }
        let raw = self.accessor_bytes(pos_acc)?;
        // glTF requires affine node matrices; a projective one is honoured rather than cut.
        let affine = world.row(3) == DVec4::W;
        let mut ids = Vec::with_capacity(raw.len() / 12);
        for (k, b) in raw.chunks_exact(12).enumerate() {
            let f = |o: usize| f32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]) as f64;
            let p = DVec3::new(f(0), f(4), f(8));
            let q = if affine {
                world.transform_point3(p)
            } else {
                world.project_point3(p)
            };
            if !q.is_finite() {
                return Err(self.err(format!(
                    "POSITION accessor {} element {k} is not finite after its node transform: {q}",
                    pos_acc.index()
                )));
            }
            ids.push(welder.index(q));
        }
        Ok(ids)
    }

    /// Index values, checked against the vertex count `n`.
    fn indices(&self, acc: &gltf::Accessor, n: usize) -> Result<Vec<u32>> {
        let size = match acc.data_type() {
            DataType::U8 => 1,
            DataType::U16 => 2,
            DataType::U32 => 4,
            other => {
                return Err(self.err(format!(
                    "index accessor {} has component type {other:?}",
                    acc.index()
                )));
            }
        };
        if acc.dimensions() != Dimensions::Scalar {
            return Err(self.err(format!("index accessor {} is not SCALAR", acc.index())));
        }
        let raw = self.accessor_bytes(acc)?;
        let mut out = Vec::with_capacity(raw.len() / size);
        for c in raw.chunks_exact(size) {
            let i = read_uint(c);
            if i as usize >= n {
                return Err(self.err(format!(
                    "index accessor {} refers to vertex {i}, but the primitive has {n}",
                    acc.index()
                )));
            }
            out.push(i);
        }
        Ok(out)
    }

    /// The accessor's elements, tightly packed, with sparse substitutions applied.
    fn accessor_bytes(&self, acc: &gltf::Accessor) -> Result<Vec<u8>> {
        let elem = acc.size();
        let count = acc.count();
        let mut out = match acc.view() {
            Some(view) => self.strided(acc.index(), &view, acc.offset(), count, elem)?,
            None => {
                if count > MAX_VIEWLESS_COUNT {
                    return Err(self.err(format!(
                        "accessor {} has {count} elements and no buffer view",
                        acc.index()
                    )));
                }
                vec![0; count * elem]
            }
        };
        if let Some(sparse) = acc.sparse() {
            let sc = sparse.count();
            let idx = sparse.indices();
            let isz = idx.index_type().size();
            let indices = self.strided(acc.index(), &idx.view(), idx.offset(), sc, isz)?;
            let vals = sparse.values();
            let values = self.strided(acc.index(), &vals.view(), vals.offset(), sc, elem)?;
            for (i, v) in indices.chunks_exact(isz).zip(values.chunks_exact(elem)) {
                let at = read_uint(i) as usize;
                let dst = at
                    .checked_mul(elem)
                    .and_then(|s| out.get_mut(s..s + elem))
                    .ok_or_else(|| {
                        self.err(format!(
                            "accessor {}: sparse index {at} is out of range ({count} elements)",
                            acc.index()
                        ))
                    })?;
                dst.copy_from_slice(v);
            }
        }
        Ok(out)
    }

    /// `count` elements of `elem` bytes from a buffer view, at `offset` with the view's stride.
    fn strided(
        &self,
        acc: usize,
        view: &gltf::buffer::View,
        offset: usize,
        count: usize,
        elem: usize,
    ) -> Result<Vec<u8>> {
        let oob = || {
            self.err(format!(
                "accessor {acc} reaches past the end of buffer view {} or its buffer",
                view.index()
            ))
        };
        let buffer = self.buffers.get(view.buffer().index()).ok_or_else(oob)?;
        let data = view
            .offset()
            .checked_add(view.length())
            .and_then(|end| buffer.get(view.offset()..end))
            .ok_or_else(oob)?;
        let stride = view.stride().unwrap_or(elem);
        if stride < elem {
            return Err(self.err(format!(
                "buffer view {} has stride {stride}, less than accessor {acc}'s element size {elem}",
                view.index()
            )));
        }
        if count == 0 {
            return Ok(Vec::new());
        }
        let end = (count - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(offset))
            .and_then(|x| x.checked_add(elem))
            .ok_or_else(oob)?;
        let data = data.get(offset..end).ok_or_else(oob)?;
        let mut out = Vec::with_capacity(count * elem);
        for k in 0..count {
            out.extend_from_slice(&data[k * stride..k * stride + elem]);
        }
        Ok(out)
    }
}

/// A little-endian unsigned integer of 1, 2 or 4 bytes.
fn read_uint(b: &[u8]) -> u32 {
    b.iter()
        .rev()
        .fold(0u32, |acc, &x| (acc << 8) | u32::from(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn read_uint_widths() {
        assert_eq!(read_uint(&[0x12]), 0x12);
        assert_eq!(read_uint(&[0x34, 0x12]), 0x1234);
        assert_eq!(read_uint(&[0x78, 0x56, 0x34, 0x12]), 0x1234_5678);
    }
}
