//! The editor's HTTP edge: who may talk to it (loopback, its own Host and
//! Origin only — a web page elsewhere must not drive it through DNS
//! rebinding), how much, and the responses it sends.

use std::io::Read as _;

use tiny_http::{Header, Request, Response};

/// The largest request body accepted: a scheme is a few kilobytes.
pub const MAX_BODY: usize = 1 << 20;

/// A response ready to send.
pub type Reply = Response<std::io::Cursor<Vec<u8>>>;

/// Why a request is refused before it is read.
pub fn refusal(request: &Request, port: u16) -> Option<Reply> {
    let header = |name: &'static str| {
        request
            .headers()
            .iter()
            .find(|h| h.field.equiv(name))
            .map(|h| h.value.as_str().to_owned())
    };
    let ours = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    if !header("Host").is_some_and(|host| ours.contains(&host)) {
        return Some(text(403, "forbidden: the Host is not this editor's"));
    }
    if let Some(origin) = header("Origin")
        && !ours.iter().any(|o| origin == format!("http://{o}"))
    {
        return Some(text(403, "forbidden: the Origin is not this editor's"));
    }
    if request.body_length().is_some_and(|n| n > MAX_BODY) {
        return Some(text(413, "request too large"));
    }
    None
}

/// The body of `request`, at most [`MAX_BODY`] bytes.
pub fn body(request: &mut Request) -> Result<Vec<u8>, Reply> {
    let mut bytes = Vec::new();
    let read = request
        .as_reader()
        .take(MAX_BODY as u64 + 1)
        .read_to_end(&mut bytes);
    match read {
        Err(_) => Err(text(400, "cannot read the request")),
        Ok(n) if n > MAX_BODY => Err(text(413, "request too large")),
        Ok(_) => Ok(bytes),
    }
}

fn header(name: &str, value: &str) -> Header {
    Header::from_bytes(name.as_bytes(), value.as_bytes()).expect("a valid header")
}

/// A response of `bytes` with a content type; never cached, never framed
/// by another site.
pub fn bytes(status: u16, content_type: &str, bytes: Vec<u8>) -> Reply {
    Response::from_data(bytes)
        .with_status_code(status)
        .with_header(header("Content-Type", content_type))
        .with_header(header("Cache-Control", "no-store"))
        .with_header(header("X-Frame-Options", "DENY"))
        .with_header(header("X-Content-Type-Options", "nosniff"))
}

/// A plain-text response.
pub fn text(status: u16, message: &str) -> Reply {
    bytes(
        status,
        "text/plain; charset=utf-8",
        message.as_bytes().to_vec(),
    )
}

/// A JSON response.
pub fn json(value: &serde_json::Value) -> Reply {
    bytes(200, "application/json", value.to_string().into_bytes())
}
