//! The editor's HTTP edge: who may talk to it (loopback, its own Host and
//! Origin only — a web page elsewhere must not drive it through DNS
//! rebinding), how much and how slowly, and the responses it sends.

use std::time::Duration;

use http_body_util::{BodyExt as _, Full};
use hyper::body::{Body as _, Bytes, Incoming};
use hyper::header::{CACHE_CONTROL, CONNECTION, CONTENT_TYPE, HOST, HeaderValue, ORIGIN};
use hyper::{Request, Response, StatusCode};

/// The largest request body accepted: a scheme is a few kilobytes.
pub const MAX_BODY: usize = 1 << 20;

/// The largest request line and headers, together (431 above it). A
/// browser's request to the editor is well under 2 KiB; hyper's smallest
/// read buffer is 8 KiB.
pub const MAX_HEAD: usize = 16 << 10;

/// How long the request line and headers may take to arrive, from the
/// connection's first byte or, on a kept-alive connection, from the end of
/// the previous response: an idle connection is closed after it.
pub const HEAD_TIMEOUT: Duration = Duration::from_secs(5);

/// How long a request's whole body may take once its headers are in: a
/// deadline for the body, not a limit on each silent gap, so a client that
/// trickles a byte every few seconds is cut off all the same.
pub const BODY_DEADLINE: Duration = Duration::from_secs(10);

/// How long a reply's bytes may wait to be taken by the client: a client
/// that sends requests but never reads the replies is cut off after this
/// (64 such clients once held every connection slot, and 1.2 GB of unread
/// replies, for as long as they stayed).
pub const WRITE_DEADLINE: Duration = Duration::from_secs(10);

/// A response ready to send.
pub type Reply = Response<Full<Bytes>>;

/// Why a request is refused before its body is read.
pub fn refusal(request: &Request<Incoming>, port: u16) -> Option<Reply> {
    let ours = [format!("127.0.0.1:{port}"), format!("localhost:{port}")];
    // Exactly one Host, and ours: a second Host header could otherwise
    // smuggle a foreign name past a check of the first.
    let mut hosts = request.headers().get_all(HOST).iter();
    let host = hosts.next().and_then(|h| h.to_str().ok());
    if hosts.next().is_some() || !host.is_some_and(|host| ours.iter().any(|o| o == host)) {
        return Some(text(403, "forbidden: the Host is not this editor's"));
    }
    let mut origins = request.headers().get_all(ORIGIN).iter();
    if let Some(origin) = origins.next() {
        let origin = origin.to_str().unwrap_or("");
        if origins.next().is_some() || !ours.iter().any(|o| origin == format!("http://{o}")) {
            return Some(text(403, "forbidden: the Origin is not this editor's"));
        }
    }
    None
}

/// How much of a body too large is read and thrown away before the 413 is
/// sent: a client still sending when the connection closes gets a broken
/// pipe instead of the answer (a lingering close, as web servers do).
const MAX_DISCARD: usize = 16 << 20;

/// The body of a request, at most [`MAX_BODY`] bytes, all of it within
/// [`BODY_DEADLINE`] of its headers.
pub async fn body(mut body: Incoming) -> Result<Vec<u8>, Reply> {
    let announced = body.size_hint().lower();
    let read = tokio::time::timeout(BODY_DEADLINE, async {
        let mut bytes = Vec::new();
        let mut seen = 0;
        while seen <= MAX_DISCARD {
            let Some(frame) = body.frame().await else {
                return Ok((seen <= MAX_BODY).then_some(bytes));
            };
            let Ok(data) = frame?.into_data() else {
                continue; // trailers
            };
            seen += data.len();
            if seen <= MAX_BODY && announced <= MAX_BODY as u64 {
                bytes.extend_from_slice(&data);
            }
        }
        Ok::<_, hyper::Error>(None)
    })
    .await;
    match read {
        Ok(Ok(Some(bytes))) if announced <= MAX_BODY as u64 => Ok(bytes),
        Ok(Ok(_)) => Err(closing(text(413, "request too large"))),
        Ok(Err(_)) => Err(closing(text(400, "cannot read the request"))),
        Err(_) => Err(closing(text(
            408,
            &format!("request timeout: the body did not arrive within {BODY_DEADLINE:?}"),
        ))),
    }
}

/// `reply`, and the connection closed after it: the rest of a refused body
/// is never read.
pub fn closing(mut reply: Reply) -> Reply {
    reply
        .headers_mut()
        .insert(CONNECTION, HeaderValue::from_static("close"));
    reply
}

/// A response of `bytes` with a content type; never cached, never framed
/// by another site.
pub fn bytes(status: u16, content_type: &'static str, bytes: Vec<u8>) -> Reply {
    let mut reply = Response::new(Full::new(Bytes::from(bytes)));
    *reply.status_mut() = StatusCode::from_u16(status).expect("a valid status code");
    let headers = reply.headers_mut();
    headers.insert(CONTENT_TYPE, HeaderValue::from_static(content_type));
    headers.insert(CACHE_CONTROL, HeaderValue::from_static("no-store"));
    headers.insert("x-frame-options", HeaderValue::from_static("DENY"));
    headers.insert(
        "x-content-type-options",
        HeaderValue::from_static("nosniff"),
    );
    reply
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
