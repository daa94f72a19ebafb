//! Writing: one glTF primitive per source id, with flat normals, into `.gltf` + `.bin` or one
//! `.glb`.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use glam::{DVec3, Vec3};
use gltf::json;
use gltf::json::validation::Checked::Valid;
use gltf::mesh::Mode;

use super::container::glb_bytes;
use super::uri::percent_encode;
use crate::error::{Error, MeshDefect, Result};
use crate::hash::KeyedHashMap;
use crate::io::{Files, OutFile, generator};
use crate::mesh::{Material, Mesh};

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
            // Keyed: the normals come from the input's geometry (see `crate::hash`).
            let mut map: KeyedHashMap<(u32, [u32; 3]), u32> = KeyedHashMap::default();
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
    let mut out = Document {
        root: json::Root {
            asset: json::Asset {
                generator: Some(generator()),
                ..Default::default()
            },
            ..Default::default()
        },
        bin: Vec::new(),
    };
    let bin_path = path.with_extension("bin");
    let parts = parts(mesh);
    // Only the materials used are written, each once.
    let mut material_index: HashMap<u32, json::Index<json::Material>> = HashMap::new();
    let mut default_material = None;
    let mut primitives = Vec::with_capacity(parts.len());
    for part in &parts {
        let material = match materials.get(part.source as usize) {
            Some(m) => *material_index
                .entry(part.source)
                .or_insert_with(|| out.root.push(material_json(&m.name, m.base_color))),
            None => *default_material.get_or_insert_with(|| {
                out.root.push(material_json(
                    Material::DEFAULT_NAME,
                    Material::DEFAULT_COLOR,
                ))
            }),
        };
        primitives.push(out.primitive(part, material));
    }
    let buffer_uri = if glb {
        None
    } else {
        let name = bin_path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        Some(percent_encode(&name))
    };
    out.scene(primitives, buffer_uri);
    out.files(path, bin_path, glb)
}

/// The glTF document being written and its binary buffer.
struct Document {
    root: json::Root,
    bin: Vec<u8>,
}

impl Document {
    /// A part's positions, normals and indices laid into the buffer, as one primitive.
    fn primitive(
        &mut self,
        part: &Part,
        material: json::Index<json::Material>,
    ) -> json::mesh::Primitive {
        use json::accessor::{ComponentType, Type};
        use json::buffer::Target;

        let at = self.bin.len();
        push_f32s(&mut self.bin, &part.positions);
        let pv = self.view(at, Target::ArrayBuffer);
        let (lo, hi) = part.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        );
        // f32 widened to f64 prints exactly, so the validator finds min/max equal to the data.
        let bound = |v: Vec3| json::Value::from(v.to_array().map(f64::from).to_vec());
        let pos = self.accessor(
            pv,
            part.positions.len(),
            Type::Vec3,
            ComponentType::F32,
            Some((bound(lo), bound(hi))),
        );
        let at = self.bin.len();
        push_f32s(&mut self.bin, &part.normals);
        let nv = self.view(at, Target::ArrayBuffer);
        let nrm = self.accessor(nv, part.normals.len(), Type::Vec3, ComponentType::F32, None);
        let at = self.bin.len();
        for &i in &part.indices {
            self.bin.extend_from_slice(&i.to_le_bytes());
        }
        let iv = self.view(at, Target::ElementArrayBuffer);
        let idx = self.accessor(
            iv,
            part.indices.len(),
            Type::Scalar,
            ComponentType::U32,
            None,
        );
        let mut attributes = BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), pos);
        attributes.insert(Valid(json::mesh::Semantic::Normals), nrm);
        json::mesh::Primitive {
            attributes,
            indices: Some(idx),
            material: Some(material),
            mode: Valid(Mode::Triangles),
            targets: None,
            extensions: None,
            extras: Default::default(),
        }
    }

    /// A view of the buffer from `offset` to its current end. Views are laid end to end and
    /// every element is 4 bytes wide, so all stay 4-aligned.
    fn view(
        &mut self,
        offset: usize,
        target: json::buffer::Target,
    ) -> json::Index<json::buffer::View> {
        self.root.push(json::buffer::View {
            buffer: json::Index::<json::Buffer>::new(0),
            byte_length: (self.bin.len() - offset).into(),
            byte_offset: Some(offset.into()),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        })
    }

    fn accessor(
        &mut self,
        view: json::Index<json::buffer::View>,
        count: usize,
        ty: json::accessor::Type,
        comp: json::accessor::ComponentType,
        min_max: Option<(json::Value, json::Value)>,
    ) -> json::Index<json::Accessor> {
        let (min, max) = match min_max {
            Some((lo, hi)) => (Some(lo), Some(hi)),
            None => (None, None),
        };
        self.root.push(json::Accessor {
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
    }

    /// The buffer, mesh, node and default scene. An empty mesh is written as a scene with one
    /// empty node: a glTF mesh needs at least one primitive, and a buffer at least one byte.
    fn scene(&mut self, primitives: Vec<json::mesh::Primitive>, buffer_uri: Option<String>) {
        let root = &mut self.root;
        let node = if primitives.is_empty() {
            root.push(json::Node::default())
        } else {
            root.push(json::Buffer {
                byte_length: self.bin.len().into(),
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
    }

    /// The bytes to write: one GLB, or the pretty JSON and its `.bin` companion.
    fn files(self, path: &Path, bin_path: std::path::PathBuf, glb: bool) -> Result<Files> {
        let Document { root, bin } = self;
        let to_json_err = |e: json::Error| Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::other(e),
        };
        if glb {
            let json = root.to_vec().map_err(to_json_err)?;
            let main = glb_bytes(json, if bin.is_empty() { None } else { Some(bin) }).ok_or_else(
                || {
                    Error::mesh(MeshDefect::TooLargeForFormat {
                        format: "GLB",
                        detail: format!("more than {} bytes", u32::MAX),
                    })
                },
            )?;
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
