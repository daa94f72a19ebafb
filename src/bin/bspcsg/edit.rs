//! `edit`: the editor's page and API (`bspcsg::edit::api`) served on loopback by `tiny_http`.
//! This file only moves bytes: it binds 127.0.0.1, refuses foreign hosts, cross-site posts
//! and oversized bodies, and hands every other request to the library.

use std::io::{Read, Write};
use std::sync::Arc;

use bspcsg::edit::api::{Editor, MAX_BODY_BYTES, Response};
use tiny_http::{Header, Request, Server};

use crate::cli::EditArgs;
use crate::failure::Failure;

/// Requests answered at once: a slow export does not hold up the preview.
const WORKERS: usize = 4;

/// `edit`.
pub(crate) fn edit(args: &EditArgs) -> Result<(), Failure> {
    let editor = Editor::open(&args.scene)?;
    let server = Server::http(("127.0.0.1", args.port)).map_err(|e| {
        Failure::usage_or_io(format!("cannot serve on 127.0.0.1:{}: {e}", args.port))
    })?;
    let port = server.server_addr().to_ip().map_or(args.port, |a| a.port());
    let mut out = std::io::stdout();
    // The URL on a line of its own, flushed: scripts and tests read it.
    let _ = writeln!(
        out,
        "bspcsg edit: {} at http://127.0.0.1:{port}/ (Ctrl-C stops)",
        editor.scene_path().display()
    );
    let _ = out.flush();
    let server = Arc::new(server);
    let editor = Arc::new(editor);
    let workers: Vec<_> = (0..WORKERS)
        .map(|_| {
            let (server, editor) = (Arc::clone(&server), Arc::clone(&editor));
            std::thread::spawn(move || {
                for request in server.incoming_requests() {
                    serve(&editor, port, request);
                }
            })
        })
        .collect();
    for w in workers {
        let _ = w.join();
    }
    Ok(())
}

fn header<'a>(request: &'a Request, name: &str) -> Option<&'a str> {
    request
        .headers()
        .iter()
        .find(|h| h.field.as_str().as_str().eq_ignore_ascii_case(name))
        .map(|h| h.value.as_str())
}

/// The checks that belong to the transport, then the library's answer.
fn answer(editor: &Editor, port: u16, request: &mut Request) -> Response {
    // Only this server's own names: a page elsewhere that rebinds a DNS name to 127.0.0.1
    // cannot read or write through it.
    let host_ok = header(request, "host")
        .is_some_and(|h| h == format!("127.0.0.1:{port}") || h == format!("localhost:{port}"));
    if !host_ok {
        return Response::refusal(403, "requests must be addressed to 127.0.0.1 or localhost");
    }
    let post = *request.method() == tiny_http::Method::Post;
    // A cross-site form or `fetch` cannot send application/json without a CORS preflight,
    // which this server never grants: only the editor's own page can post.
    if post
        && !header(request, "content-type")
            .is_some_and(|c| c.to_ascii_lowercase().starts_with("application/json"))
    {
        return Response::refusal(415, "POST bodies must be sent as application/json");
    }
    if let Some(n) = request.body_length()
        && n > MAX_BODY_BYTES
    {
        return Response::too_large(n);
    }
    // A body without a length (chunked) is read up to one byte past the limit.
    let mut body = Vec::new();
    if let Err(e) = request
        .as_reader()
        .take(MAX_BODY_BYTES as u64 + 1)
        .read_to_end(&mut body)
    {
        return Response::refusal(400, format!("the request body could not be read: {e}"));
    }
    if body.len() > MAX_BODY_BYTES {
        return Response::too_large(body.len());
    }
    let method = request.method().as_str().to_string();
    let url = request.url().to_string();
    editor.handle(&method, &url, &body)
}

fn serve(editor: &Editor, port: u16, mut request: Request) {
    let r = answer(editor, port, &mut request);
    let mut response = tiny_http::Response::from_data(r.body).with_status_code(r.status);
    let mut headers = vec![
        ("Content-Type", r.content_type.to_string()),
        ("Cache-Control", "no-store".to_string()),
        ("X-Content-Type-Options", "nosniff".to_string()),
    ];
    headers.extend(r.headers);
    for (k, v) in headers {
        if let Ok(h) = Header::from_bytes(k.as_bytes(), v.as_bytes()) {
            response.add_header(h);
        }
    }
    // A client that went away is no concern of the server's.
    let _ = request.respond(response);
}
