//! Requests that produce files: `POST /api/save` (the scene) and `POST /api/export` (its
//! mesh, written beside it or sent back as the body). Only names inside the scene's folder are
//! written, and only by an atomic rename.

use std::path::{Component, Path, PathBuf};

use serde_json::{Value, json};

use super::Editor;
use super::meshing::{mesh_report, scene_mesh};
use super::transport::{Answer, Response, bad, field, from_error, request};
use crate::error::{Error, Result};
use crate::io::{Format, OutFile, encode_mesh, write_file_atomically, write_mesh_as};
use crate::mesh::Mesh;
use crate::sdf::Scene;

impl Editor {
    /// A file name inside the scene's folder: no folders, no `..`, not a link or a folder.
    fn inside(&self, name: &str, what: &str, extensions: &[&str]) -> Answer<PathBuf> {
        let p = Path::new(name);
        let mut parts = p.components();
        let plain = matches!(parts.next(), Some(Component::Normal(_))) && parts.next().is_none();
        if !plain {
            return Err(bad(
                "$.path",
                format!(
                    "$.path: {what} `{name}` must be a file name in the scene's folder {} \
                     (no folders, `..` or absolute paths)",
                    self.dir.display()
                ),
            ));
        }
        let ext = p
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase());
        if !ext.as_deref().is_some_and(|e| extensions.contains(&e)) {
            return Err(bad(
                "$.path",
                format!(
                    "$.path: {what} `{name}` must end in .{}",
                    extensions.join(" or .")
                ),
            ));
        }
        let full = self.dir.join(p);
        if let Ok(md) = std::fs::symlink_metadata(&full)
            && !md.file_type().is_file()
        {
            return Err(bad(
                "$.path",
                format!("$.path: {what} `{name}` exists and is not a regular file"),
            ));
        }
        Ok(full)
    }

    /// `POST /api/save`: `{"document": …, "path"?: "name.json"}`, written atomically once the
    /// document is a valid scene.
    pub(super) fn save(&self, body: &[u8]) -> Answer {
        let req = request(body, &["document", "path"])?;
        let document = field(&req, "document")?;
        Scene::from_json_value(document).map_err(|e| from_error(e, "$.document"))?;
        // The document's own text, so that its keys keep their order (a `Value` sorts them).
        let raw: std::collections::HashMap<String, Box<serde_json::value::RawValue>> =
            serde_json::from_slice(body)
                .map_err(|e| bad("$", format!("$: the request body is not valid JSON: {e}")))?;
        let document = raw.get("document").map_or("null", |r| r.get());
        let target = match req.get("path") {
            None => self.path.clone(),
            Some(Value::String(name)) => self.inside(name, "the scene file", &["json"])?,
            Some(_) => return Err(bad("$.path", "$.path: expected a file name (a string)")),
        };
        let mut text = pretty(document);
        text.push('\n');
        write_file_atomically(&target, text.as_bytes()).map_err(|e| from_error(e, ""))?;
        Ok(Response::json(
            200,
            &json!({
                "saved": target.file_name().map(|n| n.to_string_lossy().into_owned()),
                "bytes": text.len(),
            }),
        ))
    }

    /// `POST /api/export`: `{"document", "format": "obj"|"stl"|"gltf"|"glb", "via":
    /// "bsp"|"sdf", "tolerance"?, "cell"?, "path"?}`. Without `path` the file comes back as
    /// the body (a `.gltf` with its buffer embedded) and the mesh report in the
    /// `X-Bspcsg-Report` header; with it, the file is written in the scene's folder and the
    /// report is the body.
    pub(super) fn export(&self, body: &[u8]) -> Answer {
        let req = request(
            body,
            &["document", "format", "via", "tolerance", "cell", "path"],
        )?;
        let format = match req.get("format") {
            None => Format::Glb,
            Some(Value::String(s)) => s.parse::<Format>().map_err(|_| {
                bad(
                    "$.format",
                    format!("$.format: unknown format `{s}`; expected obj, stl, gltf or glb"),
                )
            })?,
            Some(_) => return Err(bad("$.format", "$.format: expected a string")),
        };
        let (scene, mesh, seconds) = scene_mesh(&req)?;
        let report = mesh_report(&mesh, seconds);
        if let Some(p) = req.get("path") {
            let Value::String(name) = p else {
                return Err(bad("$.path", "$.path: expected a file name (a string)"));
            };
            let target = self.inside(name, "the export", &[format.extension()])?;
            write_mesh_as(&target, &mesh, scene.materials(), format)
                .map_err(|e| from_error(e, ""))?;
            return Ok(Response::json(200, &report));
        }
        let bytes = mesh_bytes(&mesh, &scene, format).map_err(|e| from_error(e, ""))?;
        Ok(Response {
            status: 200,
            content_type: match format {
                Format::Gltf => "model/gltf+json",
                Format::Glb => "model/gltf-binary",
                Format::Stl => "model/stl",
                Format::Obj => "model/obj",
            },
            headers: vec![("X-Bspcsg-Report", report.to_string())],
            body: bytes,
        })
    }
}

/// Valid JSON text laid out two spaces an indent, keys and numbers as written. Strings cannot
/// hold a raw newline, so every line break written here is structural; a loop, no recursion.
fn pretty(json: &str) -> String {
    let mut out = String::with_capacity(json.len() * 2);
    let mut depth = 0usize;
    let (mut in_string, mut escaped) = (false, false);
    let mut chars = json.chars().peekable();
    let newline = |out: &mut String, depth: usize| {
        out.push('\n');
        out.extend(std::iter::repeat_n("  ", depth));
    };
    while let Some(c) = chars.next() {
        if in_string {
            out.push(c);
            if escaped {
                escaped = false;
            } else if c == '\\' {
                escaped = true;
            } else if c == '"' {
                in_string = false;
            }
            continue;
        }
        match c {
            '"' => {
                in_string = true;
                out.push(c);
            }
            '{' | '[' => {
                out.push(c);
                while chars.peek().is_some_and(|c| c.is_ascii_whitespace()) {
                    chars.next();
                }
                if matches!(chars.peek(), Some('}' | ']')) {
                    out.extend(chars.next());
                } else {
                    depth += 1;
                    newline(&mut out, depth);
                }
            }
            '}' | ']' => {
                depth = depth.saturating_sub(1);
                newline(&mut out, depth);
                out.push(c);
            }
            ',' => {
                out.push(c);
                newline(&mut out, depth);
            }
            ':' => out.push_str(": "),
            c if c.is_ascii_whitespace() => {}
            c => out.push(c),
        }
    }
    out
}

/// A mesh file's bytes, encoded in memory by the crate's writers. A `.gltf` gets its buffer
/// embedded as a `data:` URI (one download); an OBJ goes without its `.mtl`.
fn mesh_bytes(mesh: &Mesh, scene: &Scene, format: Format) -> Result<Vec<u8>> {
    let materials = if format == Format::Obj {
        &[][..]
    } else {
        scene.materials()
    };
    let name = format!("mesh.{}", format.extension());
    let mut files = encode_mesh(&name, mesh, materials, format)?.into_iter();
    let main = files.next().map(|f| f.bytes).unwrap_or_default();
    if format != Format::Gltf {
        return Ok(main);
    }
    embed_buffers(&main, &files.collect::<Vec<_>>()).map_err(|source| Error::Io {
        path: PathBuf::from(name),
        source,
    })
}

/// Rewrites a `.gltf`'s relative buffer URIs as base64 `data:` URIs of the `companions` they
/// name.
fn embed_buffers(gltf: &[u8], companions: &[OutFile]) -> std::io::Result<Vec<u8>> {
    use base64::Engine as _;
    let mut doc: Value = serde_json::from_slice(gltf).map_err(std::io::Error::other)?;
    if let Some(Value::Array(buffers)) = doc.get_mut("buffers") {
        for b in buffers {
            if let Some(Value::String(uri)) = b.get("uri").cloned()
                && !uri.starts_with("data:")
            {
                let file = companions
                    .iter()
                    .find(|f| f.path == Path::new(&uri))
                    .ok_or_else(|| {
                        std::io::Error::other(format!("the glTF names a buffer `{uri}` it lacks"))
                    })?;
                let enc = base64::engine::general_purpose::STANDARD.encode(&file.bytes);
                b["uri"] = Value::String(format!("data:application/octet-stream;base64,{enc}"));
            }
        }
    }
    serde_json::to_vec(&doc).map_err(std::io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sdf::TessellationOptions;

    #[test]
    fn pretty_keeps_order_text_and_value() {
        let text = r#"{"tree":{"op":"union","children":[{"kind":"sdf_primitive","data":{"radius":1.0,"primitive_type":"sphere"}}]},"a":[], "s":"x,\"{:}[","e":{}}"#;
        let out = pretty(text);
        let a: Value = serde_json::from_str(text).unwrap();
        let b: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(a, b);
        assert!(out.find("\"tree\"").unwrap() < out.find("\"a\"").unwrap());
        assert!(out.find("\"radius\": 1.0").unwrap() < out.find("primitive_type").unwrap());
        assert!(out.contains("\"s\": \"x,\\\"{:}[\""), "{out}");
        assert!(out.contains("\"a\": []") && out.contains("\"e\": {}"));
        assert!(
            out.starts_with("{\n  \"tree\": {\n    \"op\": \"union\","),
            "{out}"
        );
    }

    #[test]
    fn export_bytes_read_back_in_every_format() {
        let scene = Scene::from_json_str(
            r#"{"kind": "sdf_scene", "version": 1, "materials": {"red": [1, 0, 0]},
                "tree": {"kind": "sdf_primitive", "data": {"primitive_type": "box",
                         "size": [1, 2, 3], "material": "red"}}}"#,
        )
        .unwrap();
        let mesh = scene
            .to_solid(&TessellationOptions::default())
            .unwrap()
            .to_mesh();
        for format in Format::ALL {
            let bytes = mesh_bytes(&mesh, &scene, format).unwrap();
            // One file: a `.gltf`'s buffer travels inside it, so it reads without a folder.
            let name = Path::new("/nonexistent").join(format!("m.{format}"));
            let back = crate::io::read_mesh_from_bytes(&name, &bytes, format).unwrap();
            assert_eq!(back.triangle_count(), mesh.triangle_count(), "{format}");
            assert!((back.volume() - 6.0).abs() < 1e-9, "{format}");
        }
    }
}
