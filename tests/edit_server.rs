//! `bspcsg edit` over real HTTP on an ephemeral port: bad input gets a clear error and leaves
//! the disk as it was, saves are atomic and stay in the scene's folder, the server listens on
//! loopback only.

mod common;

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use common::run::Scratch;
use serde_json::{Value, json};

/// A running `bspcsg edit`, killed on drop.
struct Server {
    child: Child,
    port: u16,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn serve(scene: &Path) -> Server {
    let mut child = Command::new(env!("CARGO_BIN_EXE_bspcsg"))
        .arg("edit")
        .arg(scene)
        .args(["--port", "0"])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let port = line
        .split("http://127.0.0.1:")
        .nth(1)
        .and_then(|s| s.split('/').next())
        .and_then(|p| p.parse().ok())
        .unwrap_or_else(|| panic!("no URL in {line:?}"));
    Server { child, port }
}

/// One request; returns the status and the body. `declared` overrides Content-Length (the
/// body actually sent is `body`).
fn request(
    port: u16,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &[u8],
    declared: Option<usize>,
) -> (u16, Vec<u8>) {
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(60))).unwrap();
    let mut head = format!(
        "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\nContent-Length: {}\r\n",
        declared.unwrap_or(body.len())
    );
    for (k, v) in headers {
        head.push_str(&format!("{k}: {v}\r\n"));
    }
    head.push_str("\r\n");
    s.write_all(head.as_bytes()).unwrap();
    // The server may answer (and close) before a refused body is all sent.
    let _ = s.write_all(body);
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let text = String::from_utf8_lossy(&out);
    let status = text
        .split(' ')
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no status line in {text:?}"));
    let split = out
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .map_or(out.len(), |i| i + 4);
    (status, out[split..].to_vec())
}

fn post(port: u16, path: &str, body: &Value) -> (u16, Value) {
    let (status, bytes) = request(
        port,
        "POST",
        path,
        &[("Content-Type", "application/json")],
        body.to_string().as_bytes(),
        None,
    );
    (
        status,
        serde_json::from_slice(&bytes).unwrap_or(Value::Null),
    )
}

fn sphere(radius: Value) -> Value {
    json!({"kind": "sdf_primitive", "data": {"primitive_type": "sphere", "radius": radius}})
}

/// The folder's files and their contents, to see that nothing changed.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let bytes = std::fs::read(e.path()).unwrap_or_default();
            (e.file_name().to_string_lossy().into_owned(), bytes)
        })
        .collect();
    v.sort();
    v
}

#[test]
fn bad_requests_get_clear_errors_and_change_nothing() {
    let scratch = Scratch::new("edit-bad");
    let dir = scratch.path("project");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("part.json");
    let original = format!("{}\n", sphere(json!(1.0)));
    std::fs::write(&scene, &original).unwrap();
    let server = serve(&scene);
    let port = server.port;
    let before = snapshot(&dir);
    let outside_before = snapshot(&scratch.0);

    // Invalid JSON.
    let (status, body) = request(
        port,
        "POST",
        "/api/save",
        &[("Content-Type", "application/json")],
        b"{\"document\": {",
        None,
    );
    let msg = String::from_utf8_lossy(&body).into_owned();
    assert_eq!(status, 400, "{msg}");
    assert!(msg.contains("not valid JSON"), "{msg}");
    // A wrong type, named by its JSON path within the request.
    let (status, body) = post(
        port,
        "/api/save",
        &json!({"document": sphere(json!("big"))}),
    );
    assert_eq!(status, 400);
    assert_eq!(body["json_path"], "$.document.data.radius", "{body}");
    assert!(
        body["error"]
            .as_str()
            .unwrap()
            .contains("expected a number"),
        "{body}"
    );
    let (status, body) = post(port, "/api/validate", &sphere(json!(-2)));
    assert_eq!(status, 400);
    assert_eq!(body["json_path"], "$.data.radius");
    let (status, body) = post(
        port,
        "/api/export",
        &json!({"document": sphere(json!(1)), "format": 3}),
    );
    assert_eq!(
        (status, body["json_path"].as_str()),
        (400, Some("$.format"))
    );
    let (status, body) = post(
        port,
        "/api/export",
        &json!({"document": sphere(json!(1)), "via": "magic"}),
    );
    assert_eq!((status, body["json_path"].as_str()), (400, Some("$.via")));
    let (status, body) = post(
        port,
        "/api/save",
        &json!({"document": sphere(json!(1)), "extra": 1}),
    );
    assert_eq!((status, body["json_path"].as_str()), (400, Some("$.extra")));
    // A 100 MB body: refused from its declared length, before it is read.
    let (status, body) = request(
        port,
        "POST",
        "/api/save",
        &[("Content-Type", "application/json")],
        &vec![b' '; 1 << 20],
        Some(100 << 20),
    );
    assert_eq!(status, 413, "{}", String::from_utf8_lossy(&body));
    assert!(String::from_utf8_lossy(&body).contains("over the limit"));
    // Paths out of the scene's folder, for save and export.
    for path in [
        "../escape.json",
        "/tmp/escape.json",
        "sub/escape.json",
        "..",
        "",
    ] {
        let (status, body) = post(
            port,
            "/api/save",
            &json!({"document": sphere(json!(1)), "path": path}),
        );
        assert_eq!(status, 400, "{path}: {body}");
        assert_eq!(body["json_path"], "$.path");
    }
    for path in ["../escape.glb", "/tmp/escape.stl", "part.json", "x.stl"] {
        let (status, body) = post(
            port,
            "/api/export",
            &json!({"document": sphere(json!(1)), "format": "glb", "path": path}),
        );
        assert_eq!(status, 400, "{path}: {body}");
    }
    // A cross-site post (a form's content type) and a foreign Host are refused.
    let (status, body) = request(
        port,
        "POST",
        "/api/save",
        &[("Content-Type", "text/plain")],
        json!({"document": sphere(json!(2))}).to_string().as_bytes(),
        None,
    );
    assert_eq!(status, 415);
    // The transport's refusals have the body of every other refusal.
    let body: serde_json::Value = serde_json::from_slice(&body).unwrap();
    assert!(body["error"].as_str().unwrap().contains("application/json"));
    assert!(body["json_path"].is_null() && body.as_object().unwrap().len() == 2);
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    s.write_all(b"GET /api/scene HTTP/1.1\r\nHost: evil.example:80\r\nConnection: close\r\n\r\n")
        .unwrap();
    let mut out = String::new();
    let _ = s.read_to_string(&mut out);
    assert!(out.starts_with("HTTP/1.1 403"), "{out}");
    // Unknown pages and methods.
    assert_eq!(request(port, "GET", "/nope", &[], b"", None).0, 404);
    assert_eq!(request(port, "GET", "/api/save", &[], b"", None).0, 405);

    assert_eq!(
        snapshot(&dir),
        before,
        "a refused request changed the folder"
    );
    assert_eq!(
        snapshot(&scratch.0),
        outside_before,
        "something was written outside"
    );
    assert_eq!(std::fs::read_to_string(&scene).unwrap(), original);
}

#[test]
fn saves_exports_and_serves_the_page_on_loopback() {
    let scratch = Scratch::new("edit-good");
    let scene = scratch.path("new.json");
    let server = serve(&scene);
    let port = server.port;
    // A new scene: the starter document, not yet on disk.
    let (status, body) = request(port, "GET", "/api/scene", &[], b"", None);
    assert_eq!(status, 200);
    let v: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(v["exists"], false);
    assert!(!scene.exists());
    let (status, page) = request(port, "GET", "/", &[], b"", None);
    assert_eq!(status, 200);
    assert!(String::from_utf8_lossy(&page).contains("editor.js"));

    let doc = json!({"kind": "sdf_scene", "tree": {"op": "subtract", "children": [
        {"kind": "sdf_primitive", "data": {"primitive_type": "box", "size": [1, 1, 1]}},
        sphere(json!(0.6))]}});
    let (status, body) = post(port, "/api/save", &json!({"document": doc}));
    assert_eq!(status, 200, "{body}");
    let saved: Value = serde_json::from_str(&std::fs::read_to_string(&scene).unwrap()).unwrap();
    assert_eq!(saved, doc);
    let (status, _) = post(
        port,
        "/api/save",
        &json!({"document": doc, "path": "copy.json"}),
    );
    assert_eq!(status, 200);
    assert!(scratch.path("copy.json").exists());
    // Keys keep the order they were sent in (the file is the user's).
    let ordered = r#"{"document": {"tree": {"kind": "sdf_primitive", "data": {"radius": 0.5, "primitive_type": "sphere"}}, "kind": "sdf_scene"}, "path": "copy.json"}"#;
    let (status, _) = request(
        port,
        "POST",
        "/api/save",
        &[("Content-Type", "application/json")],
        ordered.as_bytes(),
        None,
    );
    assert_eq!(status, 200);
    let text = std::fs::read_to_string(scratch.path("copy.json")).unwrap();
    assert!(
        text.find("\"tree\"") < text.find("\"kind\": \"sdf_scene\""),
        "{text}"
    );
    assert!(
        text.find("\"radius\": 0.5") < text.find("\"primitive_type\""),
        "{text}"
    );
    // No temporary file is left behind.
    let mut files = scratch.files();
    files.sort();
    assert_eq!(files, ["copy.json", "new.json"]);

    // The shader: GLSL, one leaf path per primitive, the default camera.
    let (status, body) = post(port, "/api/shader?w=320&h=240", &doc);
    assert_eq!(status, 200);
    assert!(
        body["glsl"]
            .as_str()
            .unwrap()
            .starts_with("#version 300 es")
    );
    assert_eq!(
        body["leaf_paths"],
        json!(["$.tree.children[0]", "$.tree.children[1]"])
    );
    assert_eq!(post(port, "/api/shader?w=0", &doc).0, 400);

    // Export written beside the scene, and as bytes with the report in a header.
    let (status, body) = post(
        port,
        "/api/export",
        &json!({"document": doc, "format": "stl", "via": "sdf", "path": "part.stl"}),
    );
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["closed_manifold"], true);
    assert!(scratch.path("part.stl").exists());
    let mut s = TcpStream::connect(("127.0.0.1", port)).unwrap();
    let req = json!({"document": doc, "format": "gltf"}).to_string();
    write!(
        s,
        "POST /api/export HTTP/1.1\r\nHost: localhost:{port}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{req}",
        req.len()
    )
    .unwrap();
    let mut out = Vec::new();
    s.read_to_end(&mut out).unwrap();
    let text = String::from_utf8_lossy(&out);
    assert!(
        text.starts_with("HTTP/1.1 200"),
        "{}",
        &text[..200.min(text.len())]
    );
    assert!(text.contains("\"closed_manifold\":true"));
    assert!(
        text.contains("data:application/octet-stream;base64,"),
        "the buffer is embedded"
    );

    // The check runs the scene's own export against its field.
    let (status, body) = post(port, "/api/check", &json!({"document": doc, "via": "bsp"}));
    assert_eq!(status, 200, "{body}");
    assert_eq!(body["passed"], true, "{body}");

    // Listening on 127.0.0.1 only (Linux lists listening sockets in /proc/net/tcp).
    if let Ok(table) = std::fs::read_to_string("/proc/net/tcp") {
        let port_hex = format!(":{port:04X}");
        let listening: Vec<&str> = table
            .lines()
            .filter_map(|l| {
                let f: Vec<&str> = l.split_whitespace().collect();
                (f.len() > 3 && f[1].ends_with(&port_hex) && f[3] == "0A").then_some(f[1])
            })
            .collect();
        assert_eq!(
            listening,
            [format!("0100007F{port_hex}")],
            "bound to loopback only"
        );
    }
    if let Ok(table) = std::fs::read_to_string("/proc/net/tcp6") {
        let port_hex = format!(":{port:04X}");
        assert!(
            !table.lines().any(|l| l
                .split_whitespace()
                .nth(1)
                .is_some_and(|a| a.ends_with(&port_hex))),
            "not on IPv6"
        );
    }
}
