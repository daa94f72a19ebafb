//! Reading: the document parsed and checked, then every scene's node tree walked with an
//! explicit stack, each primitive placed by its node's world transform.

use std::path::Path;

use glam::{DMat4, DQuat, DVec3, DVec4};
use gltf::json;
use gltf::json::validation::Checked::Valid;

use super::accessor::Reader;
use super::container::{GLB_MAGIC, split_glb};
use super::uri::load_buffers;
use crate::error::{Error, Result};
use crate::io::triangles::Triangles;
use crate::io::{MAX_READ_TRIANGLES, parse_error};
use crate::mesh::Mesh;
use crate::mesh::weld::Welder;

/// Reads a `.gltf` or `.glb` file (told apart by the GLB magic, not the extension).
pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<Mesh> {
    let (json_bytes, blob) = if bytes.starts_with(GLB_MAGIC) {
        split_glb(path, bytes)?
    } else {
        (bytes, None)
    };
    let doc = document(path, json_bytes)?;
    let nodes: Vec<gltf::Node> = doc.nodes().collect();
    let scenes = scene_roots(&doc, &nodes);
    // Before any buffer is read or triangle allocated.
    check_budget(path, &doc, &nodes, &scenes)?;
    let buffers = load_buffers(path, &doc, blob)?;
    let reader = Reader { path, buffers };

    let mut welder = Welder::default();
    let mut triangles = Triangles::default();
    for roots in scenes {
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
    triangles.into_mesh(path, welder.positions)
}

/// Refuses a document whose scenes would place more than [`MAX_READ_TRIANGLES`] triangles:
/// each primitive's triangle count (from its accessors' declared counts) times the nodes that
/// draw it. Counts only, so a 1 KB document asking for 10⁹ triangles is refused in microseconds.
fn check_budget(
    path: &Path,
    doc: &gltf::Document,
    nodes: &[gltf::Node],
    scenes: &[Vec<usize>],
) -> Result<()> {
    let per_mesh: Vec<u64> = doc
        .meshes()
        .map(|m| m.primitives().map(|p| primitive_triangles(&p)).sum())
        .collect();
    let mut total: u64 = 0;
    let mut instances: u64 = 0;
    for roots in scenes {
        // A node met twice is skipped here; the walk that reads the mesh reports it.
        let mut seen = vec![false; nodes.len()];
        let mut stack: Vec<usize> = roots.clone();
        while let Some(i) = stack.pop() {
            if i >= nodes.len() || std::mem::replace(&mut seen[i], true) {
                continue;
            }
            if let Some(m) = nodes[i].mesh() {
                instances += 1;
                total = total.saturating_add(per_mesh[m.index()]);
            }
            stack.extend(nodes[i].children().map(|c| c.index()));
        }
    }
    if total > MAX_READ_TRIANGLES {
        return Err(Error::OverBudget {
            path: path.to_path_buf(),
            message: format!(
                "the scene places {total} triangles ({instances} mesh instances), more than the \
                 reader's limit of {MAX_READ_TRIANGLES} (bspcsg::MAX_READ_TRIANGLES)"
            ),
        });
    }
    Ok(())
}

/// An upper bound on the triangles a primitive yields, from declared accessor counts.
fn primitive_triangles(prim: &gltf::Primitive) -> u64 {
    let count = match (prim.indices(), prim.get(&gltf::Semantic::Positions)) {
        (Some(a), _) | (None, Some(a)) => a.count() as u64,
        (None, None) => 0,
    };
    match prim.mode() {
        gltf::mesh::Mode::Triangles => count / 3,
        gltf::mesh::Mode::TriangleStrip | gltf::mesh::Mode::TriangleFan => count.saturating_sub(2),
        _ => 0,
    }
}

/// The glTF JSON parsed and validated, refusing required extensions.
fn document(path: &Path, json_bytes: &[u8]) -> Result<gltf::Document> {
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
            if let Some(acc) = prim.attributes.get(&Valid(json::mesh::Semantic::Positions))
                && acc.value() >= root.accessors.len()
            {
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
    gltf::Document::from_json(root).map_err(|e| {
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
    })
}

/// The root nodes of the scenes to draw: the default, else all; a file without scenes gets
/// its root nodes.
fn scene_roots(doc: &gltf::Document, nodes: &[gltf::Node]) -> Vec<Vec<usize>> {
    // The scenes to draw: the default, else all; a file without scenes gets its root nodes.
    match doc.default_scene() {
        Some(s) => vec![s.nodes().map(|n| n.index()).collect()],
        None if doc.scenes().len() > 0 => doc
            .scenes()
            .map(|s| s.nodes().map(|n| n.index()).collect())
            .collect(),
        None => {
            let mut is_child = vec![false; nodes.len()];
            for n in nodes {
                for c in n.children() {
                    is_child[c.index()] = true;
                }
            }
            vec![(0..nodes.len()).filter(|&i| !is_child[i]).collect()]
        }
    }
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn parse(json: &str) -> Result<Mesh> {
        read(Path::new("t.gltf"), json.as_bytes())
    }

    #[test]
    fn position_accessor_out_of_range_is_an_error() {
        let e = parse(
            r#"{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}]}"#,
        );
        assert!(matches!(e, Err(Error::Parse { .. })), "{e:?}");
    }
}
