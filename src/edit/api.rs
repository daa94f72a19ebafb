//! The editor's requests and their answers, with no HTTP server in sight: a method, a URL and
//! a body in, a status, a content type and bytes out. `bspcsg edit` feeds it from a loopback
//! server; the tests feed it directly and over real HTTP.
//!
//! Every request that carries a scene parses it with the library's own reader, so the page
//! shows the same JSON-path messages as the command line. Nothing is written unless the whole
//! request is valid, and then only by an atomic rename inside the scene's folder.

use std::path::{Component, Path, PathBuf};
use std::time::Instant;

use glam::DVec3;
use serde_json::{Map, Value, json};

use super::glsl::fragment_shader_with;
use crate::error::{Error, Result};
use crate::io::{Format, OutFile, encode_mesh, write_file_atomically, write_mesh_as};
use crate::mesh::Mesh;
use crate::raymarch::{Camera, CheckOptions, CheckReport, View, check_mesh};
use crate::sdf::{BakeOptions, Projection, Scene, TessellationOptions};

/// The largest request body accepted (16 MiB): a scene with 10,000-point polygons is well
/// under it. Larger bodies get 413 before they are read.
pub const MAX_BODY_BYTES: usize = 16 << 20;

/// The largest mesh the mesh view is sent (triangles); larger ones are reported, not drawn.
const MAX_VIEW_TRIANGLES: usize = 2_000_000;

const INDEX_HTML: &str = include_str!("../../web/editor/index.html");
const EDITOR_JS: &str = include_str!("../../web/editor/editor.js");
const EDITOR_CSS: &str = include_str!("../../web/editor/editor.css");

/// What a new scene starts as: an empty union with a few materials to pick from.
const STARTER: &str = r##"{
  "kind": "sdf_scene",
  "version": 1,
  "materials": {
    "grey": [0.7, 0.7, 0.72],
    "steel": [0.56, 0.57, 0.58],
    "brass": "#c9b27c",
    "red": [0.75, 0.12, 0.1]
  },
  "tree": { "op": "union", "children": [] }
}"##;

/// An answer: HTTP status, content type, extra headers and the body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Response {
    /// 200, 400, 404, 405, 413 or 500.
    pub status: u16,
    /// The body's media type.
    pub content_type: &'static str,
    /// Extra headers (name, value); values are ASCII.
    pub headers: Vec<(&'static str, String)>,
    /// The body.
    pub body: Vec<u8>,
}

impl Response {
    fn json(status: u16, v: &Value) -> Response {
        Response {
            status,
            content_type: "application/json",
            headers: Vec::new(),
            body: serde_json::to_vec(v).unwrap_or_default(),
        }
    }

    fn text(content_type: &'static str, s: &str) -> Response {
        Response {
            status: 200,
            content_type,
            headers: Vec::new(),
            body: s.as_bytes().to_vec(),
        }
    }

    /// A 400 (or other) with `{"error": message, "json_path": path}`.
    fn error(status: u16, json_path: Option<&str>, message: impl Into<String>) -> Response {
        Response::json(
            status,
            &json!({ "error": message.into(), "json_path": json_path }),
        )
    }

    /// The answer to a body over [`MAX_BODY_BYTES`] (the server sends it without reading the
    /// body).
    #[must_use]
    pub fn too_large(length: usize) -> Response {
        Response::error(
            413,
            None,
            format!(
                "the request body of {length} bytes is over the limit of {MAX_BODY_BYTES} bytes"
            ),
        )
    }
}

/// A request's outcome: `T` (an answer by default), or the response that refuses it.
type Answer<T = Response> = std::result::Result<T, Response>;

fn bad(path: &str, message: impl Into<String>) -> Response {
    Response::error(400, Some(path), message)
}

/// A library error as a response: scene faults with their JSON path (400), geometry and
/// parameter faults (400), I/O faults (500).
fn from_error(e: Error, prefix: &str) -> Response {
    match e {
        Error::Scene {
            json_path, message, ..
        } => {
            // Paths inside a request's `document` are reported from the request's root.
            let path = if prefix.is_empty() {
                json_path
            } else {
                json_path.replacen('$', prefix, 1)
            };
            Response::error(400, Some(&path), format!("{path}: {message}"))
        }
        Error::Io { .. } => Response::error(500, None, e.to_string()),
        other => Response::error(400, None, other.to_string()),
    }
}

/// The editor of one scene file.
#[derive(Debug)]
pub struct Editor {
    /// The scene file (it may not exist yet).
    path: PathBuf,
    /// Its folder, canonical: saves and exports stay in it.
    dir: PathBuf,
}

impl Editor {
    /// An editor of the scene at `path`, which need not exist yet (saving creates it); its
    /// folder must.
    ///
    /// # Errors
    ///
    /// [`Error::Io`] when the folder does not exist or `path` names a folder.
    pub fn open(path: impl AsRef<Path>) -> Result<Editor> {
        let path = path.as_ref();
        let io = |source| Error::Io {
            path: path.to_path_buf(),
            source,
        };
        let name = path.file_name().ok_or_else(|| {
            io(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the scene path does not name a file",
            ))
        })?;
        let parent = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        let dir = parent.canonicalize().map_err(io)?;
        let path = dir.join(name);
        if path.is_dir() {
            return Err(io(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "the scene path is a folder",
            )));
        }
        Ok(Editor { path, dir })
    }

    /// The scene file being edited.
    #[must_use]
    pub fn scene_path(&self) -> &Path {
        &self.path
    }

    /// Answers one request. `url` is the path with an optional query (`/api/shader?w=800`).
    #[must_use]
    pub fn handle(&self, method: &str, url: &str, body: &[u8]) -> Response {
        let (route, query) = url.split_once('?').unwrap_or((url, ""));
        if body.len() > MAX_BODY_BYTES {
            return Response::too_large(body.len());
        }
        let answer = match (method, route) {
            ("GET", "/" | "/index.html") => {
                Ok(Response::text("text/html; charset=utf-8", INDEX_HTML))
            }
            ("GET", "/editor.js") => {
                Ok(Response::text("text/javascript; charset=utf-8", EDITOR_JS))
            }
            ("GET", "/editor.css") => Ok(Response::text("text/css; charset=utf-8", EDITOR_CSS)),
            ("GET", "/api/scene") => Ok(self.scene()),
            ("POST", "/api/validate") => validate(body),
            ("POST", "/api/shader") => shader(body, query),
            ("POST", "/api/save") => self.save(body),
            ("POST", "/api/export") => self.export(body),
            ("POST", "/api/check") => check(body),
            ("POST", "/api/mesh") => mesh_view(body),
            (
                _,
                "/" | "/index.html" | "/editor.js" | "/editor.css" | "/api/scene" | "/api/validate"
                | "/api/shader" | "/api/save" | "/api/export" | "/api/check" | "/api/mesh",
            ) => Err(Response::error(
                405,
                None,
                format!("{method} is not allowed on {route}"),
            )),
            _ => Err(Response::error(404, None, format!("no such page: {route}"))),
        };
        answer.unwrap_or_else(|e| e)
    }

    /// `GET /api/scene`: the file's document (or the starter), and its fault if it has one.
    fn scene(&self) -> Response {
        let name = self
            .path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned());
        // The document goes out as its own text (checked to be JSON), keys in the file's order.
        let (document, exists, error) = match std::fs::read_to_string(&self.path) {
            Ok(text) => match serde_json::from_str::<Value>(&text) {
                Ok(v) => {
                    let err = Scene::from_json_value(&v).err().map(|e| e.to_string());
                    (text, true, err)
                }
                Err(e) => (
                    STARTER.to_string(),
                    true,
                    Some(format!("the file is not valid JSON ({e}); starting afresh")),
                ),
            },
            Err(_) => (STARTER.to_string(), false, None),
        };
        let head = json!({ "file": name, "exists": exists, "error": error }).to_string();
        let mut body = head[..head.len() - 1].to_string();
        body.push_str(",\"document\":");
        body.push_str(document.trim());
        body.push('}');
        Response {
            status: 200,
            content_type: "application/json",
            headers: Vec::new(),
            body: body.into_bytes(),
        }
    }

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
    fn save(&self, body: &[u8]) -> Answer {
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
    fn export(&self, body: &[u8]) -> Answer {
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

/// The body as a JSON object with only the `allowed` keys.
fn request(body: &[u8], allowed: &[&str]) -> Answer<Map<String, Value>> {
    let v: Value = serde_json::from_slice(body)
        .map_err(|e| bad("$", format!("$: the request body is not valid JSON: {e}")))?;
    let Value::Object(m) = v else {
        return Err(bad("$", "$: expected a JSON object"));
    };
    if let Some(k) = m.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(bad(
            &format!("$.{k}"),
            format!("$.{k}: unknown field; expected {}", allowed.join(", ")),
        ));
    }
    Ok(m)
}

fn field<'a>(m: &'a Map<String, Value>, name: &str) -> Answer<&'a Value> {
    m.get(name)
        .ok_or_else(|| bad("$", format!("$: missing `{name}`")))
}

fn number(m: &Map<String, Value>, name: &str) -> Answer<Option<f64>> {
    match m.get(name) {
        None | Some(Value::Null) => Ok(None),
        Some(Value::Number(n)) => match n.as_f64() {
            Some(x) if x > 0.0 && x.is_finite() => Ok(Some(x)),
            _ => Err(bad(
                &format!("$.{name}"),
                format!("$.{name}: must be a positive number"),
            )),
        },
        Some(_) => Err(bad(
            &format!("$.{name}"),
            format!("$.{name}: expected a number"),
        )),
    }
}

/// Which meshing route a request asks for: `"bsp"` (default) or `"sdf"`.
fn via_sdf(m: &Map<String, Value>) -> Answer<bool> {
    match m.get("via") {
        None => Ok(false),
        Some(Value::String(s)) if s == "bsp" => Ok(false),
        Some(Value::String(s)) if s == "sdf" => Ok(true),
        Some(_) => Err(bad("$.via", "$.via: expected \"bsp\" or \"sdf\"")),
    }
}

/// The request's scene, meshed by its route, and the seconds that took.
fn scene_mesh(m: &Map<String, Value>) -> Answer<(Scene, Mesh, f64)> {
    let scene =
        Scene::from_json_value(field(m, "document")?).map_err(|e| from_error(e, "$.document"))?;
    let sdf = via_sdf(m)?;
    let (tolerance, cell) = (number(m, "tolerance")?, number(m, "cell")?);
    let start = Instant::now();
    let mesh = if sdf {
        scene.bake(&BakeOptions {
            cell,
            ..BakeOptions::default()
        })
    } else {
        scene
            .to_solid(&TessellationOptions {
                tolerance,
                cell,
                ..TessellationOptions::default()
            })
            .map(|s| s.to_mesh())
    }
    .map_err(|e| from_error(e, "$.document"))?;
    Ok((scene, mesh, start.elapsed().as_secs_f64()))
}

fn v3(p: DVec3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// The mesh's figures: counts, closedness, genus, volume, and the seconds it took.
fn mesh_report(mesh: &Mesh, seconds: f64) -> Value {
    let r = mesh.report();
    json!({
        "triangles": r.triangles,
        "vertices": r.vertices,
        "closed_manifold": r.is_closed_manifold(),
        "boundary_edges": r.boundary_edges,
        "non_manifold_edges": r.non_manifold_edges,
        "degenerate_triangles": r.degenerate_triangles,
        "shells": r.shells.len(),
        "genus": r.genus,
        "volume": mesh.volume(),
        "area": mesh.area(),
        "seconds": seconds,
    })
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

/// A body that is a scene document, read.
fn scene_of(body: &[u8]) -> Answer<Scene> {
    let v: Value =
        serde_json::from_slice(body).map_err(|e| bad("$", format!("$: not valid JSON: {e}")))?;
    Scene::from_json_value(&v).map_err(|e| from_error(e, ""))
}

/// `POST /api/validate`: the body is a scene document.
fn validate(body: &[u8]) -> Answer {
    let scene = scene_of(body)?;
    let b = scene.bbox();
    let bbox = (!b.is_empty() && b.min.is_finite() && b.max.is_finite())
        .then(|| json!({ "min": v3(b.min), "max": v3(b.max) }));
    let materials: Vec<&str> = scene.materials().iter().map(|m| m.name.as_str()).collect();
    Ok(Response::json(
        200,
        &json!({
            "ok": true,
            "primitives": scene.primitive_count(),
            "bbox": bbox,
            "materials": materials,
        }),
    ))
}

/// A query parameter as an image side (1..=4096), or `default`.
fn side(query: &str, key: &str, default: u32) -> Answer<u32> {
    for pair in query.split('&') {
        if let Some((k, v)) = pair.split_once('=')
            && k == key
        {
            return match v.parse::<u32>() {
                Ok(n) if (1..=4096).contains(&n) => Ok(n),
                _ => Err(bad(
                    "$",
                    format!("query `{key}`: expected a whole number of pixels in 1..=4096"),
                )),
            };
        }
    }
    Ok(default)
}

/// `POST /api/shader?w=W&h=H[&cull=1]`: the body is a scene document; the answer is the fragment
/// shader, each leaf's JSON path and the camera `bspcsg render` would use at W × H.
fn shader(body: &[u8], query: &str) -> Answer {
    let (w, h) = (side(query, "w", 800)?, side(query, "h", 600)?);
    // `cull=1` skips primitives by their bounding spheres where they cannot matter. Off by
    // default: in software GL (SwiftShader, which runs branches of neighbouring pixels
    // together) it measured 30 % slower on the mechanical example.
    let cull = query.split('&').any(|kv| kv == "cull=1");
    let scene = scene_of(body)?;
    let shader = fragment_shader_with(&scene, cull);
    let camera = Camera::for_scene(&scene, View::Iso, (w, h)).unwrap_or_else(|_| {
        // Nothing to frame (an empty scene): a plain view of the unit box.
        Camera::look_at(
            DVec3::new(4.0, 3.0, 6.0),
            DVec3::ZERO,
            DVec3::Y,
            crate::sdf::DEFAULT_FOV_DEG,
            (w, h),
        )
    });
    let (fov, ortho) = match camera.projection {
        Projection::Perspective { fov_deg } => (fov_deg, 0.0),
        Projection::Orthographic { height } => (0.0, height),
    };
    Ok(Response::json(
        200,
        &json!({
            "glsl": shader.source,
            "leaf_paths": shader.leaf_paths,
            "camera": {
                "eye": v3(camera.eye), "target": v3(camera.target), "up": v3(camera.up),
                "fov_deg": fov, "ortho_height": ortho,
            },
        }),
    ))
}

/// `POST /api/check`: `{"document", "via"}`: the scene's own export checked against its
/// field, with the route's own tolerance, as `bspcsg check SCENE` does.
fn check(body: &[u8]) -> Answer {
    let req = request(body, &["document", "via", "tolerance", "cell"])?;
    let (scene, mesh, seconds) = scene_mesh(&req)?;
    let b = scene.bbox();
    let tolerance = if via_sdf(&req)? {
        number(&req, "cell")?.unwrap_or(b.size().max_element() / 128.0)
    } else {
        2.0 * number(&req, "tolerance")?.unwrap_or(b.diagonal() / 500.0)
    };
    let opts = CheckOptions {
        tolerance: Some(tolerance),
        ..CheckOptions::default()
    };
    let start = Instant::now();
    let report = check_mesh(&scene, &mesh, &opts).map_err(|e| from_error(e, "$.document"))?;
    Ok(Response::json(
        200,
        &check_json(
            &report,
            mesh_report(&mesh, seconds),
            start.elapsed().as_secs_f64(),
        ),
    ))
}

fn check_json(r: &CheckReport, mesh: Value, seconds: f64) -> Value {
    let t = &r.thresholds;
    json!({
        "passed": r.passed(),
        "tolerance": r.tolerance,
        "diagonal": r.diagonal,
        "surface": { "max": r.surface.max, "p99": r.surface.p99, "mean": r.surface.mean,
                     "samples": r.surface.samples, "limit": t.surface_max },
        "coverage": { "max": r.coverage.max, "p99": r.coverage.p99,
                      "samples": r.coverage.samples, "limit": t.coverage_max },
        "rays": { "agreement_pct": r.rays.agreement_pct, "depth_p99": r.rays.depth_p99,
                  "rays": r.rays.rays, "limit_pct": t.ray_agreement_pct },
        "sign": { "agreement_pct": r.sign.agreement_pct, "samples": r.sign.samples,
                  "limit_pct": t.sign_pct },
        "failures": r.failures,
        "mesh": mesh,
        "seconds": seconds,
    })
}

/// `POST /api/mesh`: `{"document", "via", …}`: the mesh for the page's mesh view, as flat
/// position and index arrays, with its report.
fn mesh_view(body: &[u8]) -> Answer {
    let req = request(body, &["document", "via", "tolerance", "cell"])?;
    let (_, mesh, seconds) = scene_mesh(&req)?;
    let report = mesh_report(&mesh, seconds);
    if mesh.triangle_count() > MAX_VIEW_TRIANGLES {
        return Ok(Response::json(
            200,
            &json!({ "report": report, "positions": [], "triangles": [], "too_large": true }),
        ));
    }
    let positions: Vec<f32> = mesh
        .positions
        .iter()
        .flat_map(|p| [p.x as f32, p.y as f32, p.z as f32])
        .collect();
    let triangles: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    Ok(Response::json(
        200,
        &json!({ "report": report, "positions": positions, "triangles": triangles }),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

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
