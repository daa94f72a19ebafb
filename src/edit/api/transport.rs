//! Requests in, responses out: the [`Response`], the refusals every request can get (its body
//! not JSON, an unknown field, a library error with its JSON path), and a request body's fields.

use serde_json::{Map, Value, json};

use super::MAX_BODY_BYTES;
use crate::error::Error;

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
    pub(super) fn json(status: u16, v: &Value) -> Response {
        Response {
            status,
            content_type: "application/json",
            headers: Vec::new(),
            body: serde_json::to_vec(v).unwrap_or_default(),
        }
    }

    pub(super) fn text(content_type: &'static str, s: &str) -> Response {
        Response {
            status: 200,
            content_type,
            headers: Vec::new(),
            body: s.as_bytes().to_vec(),
        }
    }

    /// A 400 (or other) with `{"error": message, "json_path": path}`.
    pub(super) fn error(
        status: u16,
        json_path: Option<&str>,
        message: impl Into<String>,
    ) -> Response {
        Response::json(
            status,
            &json!({ "error": message.into(), "json_path": json_path }),
        )
    }

    /// A refusal with no JSON path, `{"error": message, "json_path": null}`: the body of every
    /// refusal, for a server in front of [`Editor::handle`](super::Editor::handle) that refuses
    /// what never reaches it (a foreign host, a cross-site post).
    #[must_use]
    pub fn refusal(status: u16, message: impl Into<String>) -> Response {
        Response::error(status, None, message)
    }

    /// The answer to a body over [`MAX_BODY_BYTES`] (the server sends it without reading the
    /// body).
    #[must_use]
    pub fn too_large(length: usize) -> Response {
        Response::refusal(
            413,
            format!(
                "the request body of {length} bytes is over the limit of {MAX_BODY_BYTES} bytes"
            ),
        )
    }
}

/// A request's outcome: `T` (an answer by default), or the response that refuses it.
pub(super) type Answer<T = Response> = std::result::Result<T, Response>;

pub(super) fn bad(path: &str, message: impl Into<String>) -> Response {
    Response::error(400, Some(path), message)
}

/// A library error as a response: scene faults with their JSON path (400), geometry and
/// parameter faults (400), I/O faults (500).
pub(super) fn from_error(e: Error, prefix: &str) -> Response {
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

/// The body as a JSON object with only the `allowed` keys.
pub(super) fn request(body: &[u8], allowed: &[&str]) -> Answer<Map<String, Value>> {
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

pub(super) fn field<'a>(m: &'a Map<String, Value>, name: &str) -> Answer<&'a Value> {
    m.get(name)
        .ok_or_else(|| bad("$", format!("$: missing `{name}`")))
}

pub(super) fn number(m: &Map<String, Value>, name: &str) -> Answer<Option<f64>> {
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
pub(super) fn via_sdf(m: &Map<String, Value>) -> Answer<bool> {
    match m.get("via") {
        None => Ok(false),
        Some(Value::String(s)) if s == "bsp" => Ok(false),
        Some(Value::String(s)) if s == "sdf" => Ok(true),
        Some(_) => Err(bad("$.via", "$.via: expected \"bsp\" or \"sdf\"")),
    }
}
