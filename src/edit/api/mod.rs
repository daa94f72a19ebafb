//! The editor's requests and their answers, with no HTTP server in sight: a method, a URL and
//! a body in, a status, a content type and bytes out. `bspcsg edit` feeds it from a loopback
//! server; the tests feed it directly and over real HTTP.
//!
//! Every request that carries a scene parses it with the library's own reader, so the page
//! shows the same JSON-path messages as the command line. Nothing is written unless the whole
//! request is valid, and then only by an atomic rename inside the scene's folder.
//!
//! One file per kind of request: `scene.rs` (`GET /api/scene`, validate, shader), `files.rs`
//! (save, export), `meshing.rs` (check, the mesh view) and `transport.rs` (the [`Response`],
//! the refusals, reading a request body's fields).

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

mod files;
mod meshing;
mod scene;
mod transport;

pub use transport::Response;

/// The largest request body accepted (16 MiB): a scene with 10,000-point polygons is well
/// under it. Larger bodies get 413 before they are read.
pub const MAX_BODY_BYTES: usize = 16 << 20;

const INDEX_HTML: &str = include_str!("../../../web/editor/index.html");
const EDITOR_JS: &str = include_str!("../../../web/editor/editor.js");
const EDITOR_CSS: &str = include_str!("../../../web/editor/editor.css");

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
            ("POST", "/api/validate") => scene::validate(body),
            ("POST", "/api/shader") => scene::shader(body, query),
            ("POST", "/api/save") => self.save(body),
            ("POST", "/api/export") => self.export(body),
            ("POST", "/api/check") => meshing::check(body),
            ("POST", "/api/mesh") => meshing::mesh_view(body),
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
}
