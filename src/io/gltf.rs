//! glTF 2.0: `.gltf` (external or embedded buffers) and `.glb`, in and out.
//!
//! The `gltf` crate parses and validates the JSON; the binary container, the buffers and the
//! accessors are read here, with checked arithmetic, because the crate's own readers assume
//! well-formed files (a GLB length below 12 or an accessor count of 0 underflows, an attribute
//! of the wrong type trips a debug assertion).

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use base64::Engine as _;
use glam::{DMat3, DMat4, DQuat, DVec3, DVec4, Vec3};
use gltf::accessor::{DataType, Dimensions};
use gltf::json;
use gltf::json::validation::Checked::Valid;
use gltf::mesh::Mode;

use super::{
    DEFAULT_MATERIAL_COLOR, DEFAULT_MATERIAL_NAME, Files, OutFile, generator, parse_error,
};
use crate::error::{Error, Result};
use crate::hash::FxHashMap;
use crate::mesh::weld::Welder;
use crate::mesh::{Material, Mesh};

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Accessors without a buffer view read as zeros; a count above this for one of them is
/// taken as a damaged file rather than allocated.
const MAX_VIEWLESS_COUNT: usize = 1 << 24;

/// Reads a `.gltf` or `.glb` file (told apart by the GLB magic, not the extension).
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Mesh> {
    let (json_bytes, blob) = if bytes.starts_with(GLB_MAGIC) {
        split_glb(path, bytes)?
    } else {
        (bytes, None)
    };
    let root = json::Root::from_slice(json_bytes)
        .map_err(|e| parse_error(path, None, format!("glTF JSON: {e}")))?;
    // Compression and quantization extensions change what accessors mean; refuse rather than
    // read garbage.
    if let Some(ext) = root.extensions_required.first() {
        return Err(Error::Unsupported {
            path: path.to_path_buf(),
            message: format!("glTF extension `{ext}` is required but not supported"),
        });
    }
    // gltf-json 1.4.1's validation indexes the POSITION accessor before it checks indices
    // are in range (a panic on `"POSITION": 7` with fewer accessors), so check that first.
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(acc) = prim.attributes.get(&Valid(json::mesh::Semantic::Positions)) {
                if acc.value() >= root.accessors.len() {
                    return Err(parse_error(
                        path,
                        None,
                        format!(
                            "invalid glTF: meshes[{m}].primitives[{p}] POSITION refers to \
                             accessor {}, but there are {}",
                            acc.value(),
                            root.accessors.len()
                        ),
                    ));
                }
            }
        }
    }
    let doc = gltf::Document::from_json(root).map_err(|e| {
        let message = match e {
            gltf::Error::Validation(errors) => {
                let shown: Vec<String> = errors
                    .iter()
                    .take(3)
                    .map(|(p, e)| format!("{p}: {e}"))
                    .collect();
                format!("invalid glTF: {}", shown.join("; "))
            }
            e => format!("invalid glTF: {e}"),
        };
        parse_error(path, None, message)
    })?;
    let buffers = load_buffers(path, &doc, blob)?;
    let reader = Reader { path, buffers };

    let mut welder = Welder::default();
    let mut triangles = Vec::new();
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    // The scenes to draw: the default, else all; a file without scenes gets its root nodes.
    let scene_roots: Vec<Vec<usize>> = match doc.default_scene() {
        Some(s) => vec![s.nodes().map(|n| n.index()).collect()],
        None if doc.scenes().len() > 0 => doc
            .scenes()
            .map(|s| s.nodes().map(|n| n.index()).collect())
            .collect(),
        None => {
            let mut is_child = vec![false; nodes.len()];
            for n in &nodes {
                for c in n.children() {
                    is_child[c.index()] = true;
                }
            }
            vec![(0..nodes.len()).filter(|&i| !is_child[i]).collect()]
        }
    };
    for roots in scene_roots {
        // Valid glTF node hierarchies are disjoint trees; a node met twice in one scene means
        // a cycle or a shared child, which would loop forever or duplicate geometry.
        let mut seen = vec![false; nodes.len()];
        let mut stack: Vec<(usize, DMat4)> =
            roots.iter().rev().map(|&i| (i, DMat4::IDENTITY)).collect();
        while let Some((i, parent)) = stack.pop() {
            let node = &nodes[i];
            if std::mem::replace(&mut seen[i], true) {
                return Err(parse_error(
                    path,
                    None,
                    format!(
                        "node {i} is reached twice in a scene (a cycle or a node with two parents)"
                    ),
                ));
            }
            let world = parent * local_transform(path, node)?;
            if let Some(mesh) = node.mesh() {
                for prim in mesh.primitives() {
                    reader.primitive(&prim, &world, &mut welder, &mut triangles)?;
                }
            }
            for c in node.children() {
                stack.push((c.index(), world));
            }
        }
    }
    Ok(Mesh::new(welder.positions, triangles))
}

/// Splits a GLB container into its JSON chunk and optional BIN chunk.
fn split_glb<'a>(path: &Path, bytes: &'a [u8]) -> Result<(&'a [u8], Option<&'a [u8]>)> {
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

/// Every buffer's bytes: the GLB chunk, a `data:` URI or a file beside `path`.
fn load_buffers(path: &Path, doc: &gltf::Document, blob: Option<&[u8]>) -> Result<Vec<Vec<u8>>> {
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

fn read_uri(path: &Path, i: usize, uri: &str) -> Result<Vec<u8>> {
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
fn percent_decode(s: &str) -> Option<String> {
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
fn percent_encode(s: &str) -> String {
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

/// A node's own transform, in f64.
fn local_transform(path: &Path, node: &gltf::Node) -> Result<DMat4> {
    let bad = |what: &str| {
        parse_error(
            path,
            None,
            format!("node {} has an unusable {what}", node.index()),
        )
    };
    let m = match node.transform() {
        gltf::scene::Transform::Matrix { matrix } => {
            // Columns, as glTF stores them.
            DMat4::from_cols_array_2d(&matrix.map(|c| c.map(f64::from)))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            // Unit quaternions are required; tolerate rounding by normalizing.
            let q = DVec4::from_array(rotation.map(f64::from))
                .try_normalize()
                .map(DQuat::from_vec4)
                .ok_or_else(|| bad("rotation"))?;
            DMat4::from_scale_rotation_translation(
                DVec3::from_array(scale.map(f64::from)),
                q,
                DVec3::from_array(translation.map(f64::from)),
            )
        }
    };
    if !m.is_finite() {
        return Err(bad("transform"));
    }
    Ok(m)
}

/// Reads accessors out of loaded buffers.
struct Reader<'p> {
    path: &'p Path,
    buffers: Vec<Vec<u8>>,
}

impl Reader<'_> {
    fn err(&self, message: String) -> Error {
        parse_error(self.path, None, message)
    }

    /// Adds a primitive's triangles, transformed by `world`.
    fn primitive(
        &self,
        prim: &gltf::Primitive,
        world: &DMat4,
        welder: &mut Welder,
        triangles: &mut Vec<[u32; 3]>,
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
        let raw = self.accessor_bytes(&pos_acc)?;
        // glTF requires affine node matrices; a projective one is honoured rather than cut.
        let affine = world.row(3) == DVec4::W;
        let linear = DMat3::from_mat4(*world);
        let flip = linear.determinant() < 0.0;
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
        let n = ids.len();
        let indices: Vec<u32> = match prim.indices() {
            Some(acc) => self.indices(&acc, n)?,
            None => (0..n as u32).collect(),
        };
        let mut emit = |t: [u32; 3]| {
            let mut tri = t.map(|i| ids[i as usize]);
            if flip {
                tri.swap(1, 2);
            }
            if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
                triangles.push(tri);
            }
        };
        match mode {
            Mode::Triangles => {
                if indices.len() % 3 != 0 {
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

/// One primitive's vertex and index data, before it is laid into the buffer.
struct Part {
    source: u32,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    indices: Vec<u32>,
}

/// Splits the mesh by source id. Each vertex carries its triangle's flat normal, so a position
/// is repeated once per distinct face normal around it (once per flat region on a CAD part).
fn parts(mesh: &Mesh) -> Vec<Part> {
    let mut groups: BTreeMap<u32, Vec<usize>> = BTreeMap::new();
    for (t, &s) in mesh.sources.iter().enumerate() {
        groups.entry(s).or_default().push(t);
    }
    groups
        .into_iter()
        .map(|(source, tris)| {
            let mut map: FxHashMap<(u32, [u32; 3]), u32> = FxHashMap::default();
            let mut part = Part {
                source,
                positions: Vec::new(),
                normals: Vec::new(),
                indices: Vec::with_capacity(3 * tris.len()),
            };
            for t in tris {
                let tri = mesh.triangles[t];
                let [a, b, c] = mesh.triangle(t);
                // Zero-area triangles get an arbitrary unit normal: glTF requires unit normals.
                let n = (b - a)
                    .cross(c - a)
                    .try_normalize()
                    .unwrap_or(DVec3::Y)
                    .as_vec3();
                let key_n = n.to_array().map(f32::to_bits);
                for i in tri {
                    let next = part.positions.len() as u32;
                    let v = *map.entry((i, key_n)).or_insert(next);
                    if v == next {
                        part.positions.push(mesh.positions[i as usize].as_vec3());
                        part.normals.push(n);
                    }
                    part.indices.push(v);
                }
            }
            part
        })
        .collect()
}

fn push_f32s(bin: &mut Vec<u8>, v: &[Vec3]) {
    for p in v {
        for x in p.to_array() {
            bin.extend_from_slice(&x.to_le_bytes());
        }
    }
}

/// Writes `.gltf` + `.bin` (`glb == false`) or one `.glb`.
pub(crate) fn write(path: &Path, mesh: &Mesh, materials: &[Material], glb: bool) -> Result<Files> {
    let parts = parts(mesh);
    let mut root = json::Root {
        asset: json::Asset {
            generator: Some(generator()),
            ..Default::default()
        },
        ..Default::default()
    };
    let mut bin: Vec<u8> = Vec::new();
    let bin_path = path.with_extension("bin");

    // Only the materials used are written, each once.
    let mut material_index: HashMap<u32, json::Index<json::Material>> = HashMap::new();
    let mut default_material = None;
    let mut primitives = Vec::with_capacity(parts.len());
    let buffer = json::Index::<json::Buffer>::new(0);
    for part in &parts {
        // Views are laid end to end; every element is 4 bytes wide, so all stay 4-aligned.
        let view = |root: &mut json::Root, offset: usize, bytes: usize, target| {
            root.push(json::buffer::View {
                buffer,
                byte_length: bytes.into(),
                byte_offset: Some(offset.into()),
                byte_stride: None,
                name: None,
                target: Some(Valid(target)),
                extensions: None,
                extras: Default::default(),
            })
        };
        let accessor = |root: &mut json::Root, view, count: usize, ty, comp, min_max| {
            let (min, max) = match min_max {
                Some((lo, hi)) => (Some(lo), Some(hi)),
                None => (None, None),
            };
            root.push(json::Accessor {
                buffer_view: Some(view),
                byte_offset: None,
                count: count.into(),
                component_type: Valid(json::accessor::GenericComponentType(comp)),
                type_: Valid(ty),
                min,
                max,
                name: None,
                normalized: false,
                sparse: None,
                extensions: None,
                extras: Default::default(),
            })
        };
        use json::accessor::{ComponentType, Type};
        use json::buffer::Target;

        let at = bin.len();
        push_f32s(&mut bin, &part.positions);
        let pv = view(&mut root, at, bin.len() - at, Target::ArrayBuffer);
        let (lo, hi) = part.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        // f32 widened to f64 prints exactly, so the validator finds min/max equal to the data.
        let bound = |v: Vec3| json::Value::from(v.to_array().map(f64::from).to_vec());
        let pos = accessor(
            &mut root,
            pv,
            part.positions.len(),
            Type::Vec3,
            ComponentType::F32,
            Some((bound(lo), bound(hi))),
        );
        let at = bin.len();
        push_f32s(&mut bin, &part.normals);
        let nv = view(&mut root, at, bin.len() - at, Target::ArrayBuffer);
        let nrm = accessor(
            &mut root,
            nv,
            part.normals.len(),
            Type::Vec3,
            ComponentType::F32,
            None,
        );
        let at = bin.len();
        for &i in &part.indices {
            bin.extend_from_slice(&i.to_le_bytes());
        }
        let iv = view(&mut root, at, bin.len() - at, Target::ElementArrayBuffer);
        let idx = accessor(
            &mut root,
            iv,
            part.indices.len(),
            Type::Scalar,
            ComponentType::U32,
            None,
        );

        let material = match materials.get(part.source as usize) {
            Some(m) => *material_index
                .entry(part.source)
                .or_insert_with(|| root.push(material_json(&m.name, m.base_color))),
            None => *default_material.get_or_insert_with(|| {
                root.push(material_json(DEFAULT_MATERIAL_NAME, DEFAULT_MATERIAL_COLOR))
            }),
        };
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
        attributes.insert(Valid(json::mesh::Semantic::Normals), nrm);
        primitives.push(json::mesh::Primitive {
            attributes,
            indices: Some(idx),
            material: Some(material),
            mode: Valid(Mode::Triangles),
            targets: None,
            extensions: None,
            extras: Default::default(),
        });
    }

    // An empty mesh is written as a scene with one empty node: a glTF mesh needs at least one
    // primitive, and a buffer at least one byte.
    let node = if primitives.is_empty() {
        root.push(json::Node::default())
    } else {
        let buffer_uri = if glb {
            None
        } else {
            let name = bin_path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            Some(percent_encode(&name))
        };
        root.push(json::Buffer {
            byte_length: bin.len().into(),
            uri: buffer_uri,
            name: None,
            extensions: None,
            extras: Default::default(),
        });
        let m = root.push(json::Mesh {
            primitives,
            name: None,
            weights: None,
            extensions: None,
            extras: Default::default(),
        });
        root.push(json::Node {
            mesh: Some(m),
            ..Default::default()
        })
    };
    let scene = root.push(json::Scene {
        nodes: vec![node],
        name: None,
        extensions: None,
        extras: Default::default(),
    });
    root.scene = Some(scene);

    let to_json_err = |e: json::Error| Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    };
    if glb {
        let json = root.to_vec().map_err(to_json_err)?;
        let main =
            glb_bytes(json, if bin.is_empty() { None } else { Some(bin) }).ok_or_else(|| {
                Error::InvalidMesh("the mesh is too large for a GLB file (4 GiB)".into())
            })?;
        Ok(Files {
            main,
            companions: Vec::new(),
        })
    } else {
        let mut json = root.to_vec_pretty().map_err(to_json_err)?;
        json.push(b'\n');
        let companions = if bin.is_empty() {
            Vec::new()
        } else {
            vec![OutFile {
                path: bin_path,
                bytes: bin,
            }]
        };
        Ok(Files {
            main: json,
            companions,
        })
    }
}

fn material_json(name: &str, c: [f64; 4]) -> json::Material {
    let alpha = c[3] as f32;
    json::Material {
        name: Some(name.to_owned()),
        pbr_metallic_roughness: json::material::PbrMetallicRoughness {
            base_color_factor: json::material::PbrBaseColorFactor(c.map(|x| x as f32)),
            // Dielectric, so a part reads as its colour rather than as a dark mirror.
            metallic_factor: json::material::StrengthFactor(0.0),
            roughness_factor: json::material::StrengthFactor(0.5),
            ..Default::default()
        },
        alpha_mode: Valid(if alpha < 1.0 {
            json::material::AlphaMode::Blend
        } else {
            json::material::AlphaMode::Opaque
        }),
        ..Default::default()
    }
}

/// The GLB container: header, JSON chunk padded with spaces, BIN chunk padded with zeros.
/// `None` when the total exceeds the format's u32 length.
fn glb_bytes(mut json: Vec<u8>, bin: Option<Vec<u8>>) -> Option<Vec<u8>> {
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
    use super::*;

    fn parse(json: &str) -> Result<Mesh> {
        read(Path::new("t.gltf"), json.as_bytes())
    }

    /// Found by mutating written files: gltf-json's validation panicked on this.
    #[test]
    fn position_accessor_out_of_range_is_an_error() {
        let e = parse(
            r#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#,
        );
        assert!(matches!(e, Err(Error::Parse { .. })), "{e:?}");
    }

    #[test]
    fn glb_header_shorter_than_itself() {
        let mut b = b"glTF".to_vec();
        b.extend_from_slice(&2u32.to_le_bytes());
        b.extend_from_slice(&4u32.to_le_bytes());
        assert!(read(Path::new("t.glb"), &b).is_err());
    }

    #[test]
    fn percent_coding() {
        assert_eq!(percent_encode("a b%.bin"), "a%20b%25.bin");
        assert_eq!(percent_decode("a%20b%25.bin").as_deref(), Some("a b%.bin"));
        assert_eq!(percent_decode("a%2"), None);
        assert_eq!(percent_decode("a%zz"), None);
        assert_eq!(percent_decode("%FF"), None);
    }

    #[test]
    fn read_uint_widths() {
        assert_eq!(read_uint(&[0x12]), 0x12);
        assert_eq!(read_uint(&[0x34, 0x12]), 0x1234);
        assert_eq!(read_uint(&[0x78, 0x56, 0x34, 0x12]), 0x1234_5678);
    }
}
