//! The editor's HTTP/1.1 server: hyper on one tokio thread reads and writes
//! every connection; the work behind a request (a preview, a save) runs on
//! a few blocking threads.
//!
//! Why this split: a client that is slow to send (or never sends) a request
//! costs a parked task, not a thread, so however many clients stall the
//! work threads stay free for the page; and the listener is never given a
//! timeout, so the editor accepts for as long as it runs.

use std::convert::Infallible;
use std::future::Future as _;
use std::pin::Pin;
use std::sync::Arc;
use std::task::{Context, Poll};

use hyper::Request;
use hyper::body::Incoming;
use hyper::server::conn::http1;
use hyper::service::service_fn;
use hyper_util::rt::{TokioIo, TokioTimer};
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::{TcpListener, TcpSocket, TcpStream};
use tokio::sync::Semaphore;

use super::http::{self, Reply};

/// Requests worked on at once: one long preview or save holds one of these
/// while the others go on serving.
pub const WORKERS: usize = 4;

/// Connections open at once. A browser opens about six; at the cap a new
/// connection takes the place of the one open longest that is waiting for
/// a request (70 idle connections once made 17 of 20 page requests get a
/// 503); where every one is working on a request, it gets a 503 and is
/// closed, so file descriptors cannot run out.
pub const MAX_CONNECTIONS: usize = 64;

/// How long a new connection at the cap waits for the idle one it evicts
/// to close.
const EVICTION_WAIT: std::time::Duration = std::time::Duration::from_secs(1);

/// A connection's place among the open ones: whether it is working on a
/// request, and how to close it to make room.
#[derive(Default)]
struct Slot {
    busy: std::sync::atomic::AtomicBool,
    close: tokio::sync::Notify,
}

/// The open connections by the order they opened in.
#[derive(Default)]
struct Slots {
    next: u64,
    open: std::collections::BTreeMap<u64, Arc<Slot>>,
}

impl Slots {
    fn add(&mut self) -> (u64, Arc<Slot>) {
        let id = self.next;
        self.next += 1;
        let slot = Arc::new(Slot::default());
        self.open.insert(id, Arc::clone(&slot));
        (id, slot)
    }

    /// Asks the connection open longest that is waiting for a request to
    /// close; `false` if every one is working on one.
    fn evict_idle(&self) -> bool {
        let idle = self
            .open
            .values()
            .find(|slot| !slot.busy.load(std::sync::atomic::Ordering::SeqCst));
        if let Some(slot) = idle {
            slot.close.notify_one();
        }
        idle.is_some()
    }
}

/// Marks a slot working on a request until dropped.
struct Working(Arc<Slot>);

impl Working {
    fn new(slot: &Arc<Slot>) -> Self {
        slot.busy.store(true, std::sync::atomic::Ordering::SeqCst);
        Working(Arc::clone(slot))
    }
}

impl Drop for Working {
    fn drop(&mut self) {
        self.0
            .busy
            .store(false, std::sync::atomic::Ordering::SeqCst);
    }
}

/// What the server answers with: a request's head and its whole body in, a
/// reply out. Runs on a work thread.
pub type Handler = dyn Fn(&hyper::http::request::Parts, &[u8]) -> Reply + Send + Sync;

/// A tokio runtime for the server: one thread for every connection's
/// input and output, at most [`WORKERS`] for the work.
pub fn runtime() -> std::io::Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_current_thread()
        .enable_io()
        .enable_time()
        .max_blocking_threads(WORKERS)
        .build()
}

/// The editor's listening socket on 127.0.0.1:`port` (0: a free port).
/// Loopback only: the editor reads and writes files for whoever talks to it.
/// Must be called inside [`runtime`].
pub fn listen(port: u16) -> std::io::Result<TcpListener> {
    let socket = TcpSocket::new_v4()?;
    // As std's TcpListener::bind does: a restarted editor can take its port back.
    socket.set_reuseaddr(true)?;
    socket.bind(std::net::SocketAddr::from(([127, 0, 0, 1], port)))?;
    socket.listen(128)
}

/// Serves `listener` for ever: every request passes [`http::refusal`], its
/// body is read within [`http::BODY_DEADLINE`], then `handler` answers it.
pub async fn serve(listener: TcpListener, port: u16, handler: Arc<Handler>) {
    let open = Arc::new(Semaphore::new(MAX_CONNECTIONS));
    let slots = Arc::new(std::sync::Mutex::new(Slots::default()));
    loop {
        // Out of descriptors, or a connection reset before it was accepted:
        // the listener is fine; wait a moment and go on.
        let Ok((stream, _)) = listener.accept().await else {
            tokio::time::sleep(std::time::Duration::from_millis(50)).await;
            continue;
        };
        let permit = if let Ok(permit) = Arc::clone(&open).try_acquire_owned() {
            permit
        } else {
            let evicted = slots.lock().is_ok_and(|slots| slots.evict_idle());
            let freed = if evicted {
                tokio::time::timeout(EVICTION_WAIT, Arc::clone(&open).acquire_owned())
                    .await
                    .ok()
                    .and_then(Result::ok)
            } else {
                None
            };
            let Some(permit) = freed else {
                turn_away(&stream);
                continue;
            };
            permit
        };
        let Ok((id, slot)) = slots.lock().map(|mut slots| slots.add()) else {
            turn_away(&stream);
            continue;
        };
        let handler = Arc::clone(&handler);
        let slots = Arc::clone(&slots);
        tokio::spawn(async move {
            // Served to the end, or closed (dropped) to make room.
            let served = std::pin::pin!(connection(stream, port, handler, Arc::clone(&slot)));
            let evicted = std::pin::pin!(slot.close.notified());
            first_of(served, evicted).await;
            if let Ok(mut slots) = slots.lock() {
                slots.open.remove(&id);
            }
            drop(permit);
        });
    }
}

/// Waits for the first of two futures to finish; the other is dropped
/// with them by the caller.
async fn first_of(
    mut a: Pin<&mut impl std::future::Future<Output = ()>>,
    mut b: Pin<&mut impl std::future::Future<Output = ()>>,
) {
    std::future::poll_fn(|cx| {
        if a.as_mut().poll(cx).is_ready() || b.as_mut().poll(cx).is_ready() {
            Poll::Ready(())
        } else {
            Poll::Pending
        }
    })
    .await;
}

/// One connection, request after request, until either side closes it or
/// its head does not arrive within [`http::HEAD_TIMEOUT`].
async fn connection(stream: TcpStream, port: u16, handler: Arc<Handler>, slot: Arc<Slot>) {
    // hyper writes a small response in one piece, but a body it streams
    // would otherwise wait for the browser's delayed ACK (40 ms).
    let _ = stream.set_nodelay(true);
    let service = service_fn(move |request| {
        let working = Working::new(&slot);
        let answered = answer(request, port, Arc::clone(&handler));
        async move {
            let reply = answered.await;
            drop(working);
            reply
        }
    });
    // One request at a time per connection, its reply written within
    // WRITE_DEADLINE: what a connection holds is bounded by one request's
    // head and body and one reply, for a bounded time.
    let served = http1::Builder::new()
        .timer(TokioTimer::new())
        .header_read_timeout(http::HEAD_TIMEOUT)
        .max_buf_size(http::MAX_HEAD)
        .serve_connection(TokioIo::new(WriteDeadline::new(stream)), service)
        .await;
    // A client that went away, or was too slow, is not the editor's problem.
    drop(served);
}

/// A stream whose writes must make progress within [`http::WRITE_DEADLINE`]:
/// a write the client's window keeps waiting longer fails with `TimedOut`,
/// and hyper closes the connection (freeing its slot and its reply).
struct WriteDeadline<S> {
    inner: S,
    deadline: Pin<Box<tokio::time::Sleep>>,
    /// A write is waiting, since the deadline was set.
    waiting: bool,
}

impl<S> WriteDeadline<S> {
    fn new(inner: S) -> Self {
        WriteDeadline {
            inner,
            deadline: Box::pin(tokio::time::sleep(http::WRITE_DEADLINE)),
            waiting: false,
        }
    }

    /// `polled` is a write's outcome: progress clears the clock; waiting
    /// starts it, and past the deadline is an error.
    fn timed<T>(
        &mut self,
        cx: &mut Context<'_>,
        polled: Poll<std::io::Result<T>>,
    ) -> Poll<std::io::Result<T>> {
        if polled.is_ready() {
            self.waiting = false;
            return polled;
        }
        if !self.waiting {
            self.waiting = true;
            let at = tokio::time::Instant::now() + http::WRITE_DEADLINE;
            self.deadline.as_mut().reset(at);
        }
        match self.deadline.as_mut().poll(cx) {
            Poll::Ready(()) => Poll::Ready(Err(std::io::Error::new(
                std::io::ErrorKind::TimedOut,
                "the client did not take the reply in time",
            ))),
            Poll::Pending => Poll::Pending,
        }
    }
}

impl<S: AsyncRead + Unpin> AsyncRead for WriteDeadline<S> {
    fn poll_read(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &mut ReadBuf<'_>,
    ) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.inner).poll_read(cx, buf)
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for WriteDeadline<S> {
    fn poll_write(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        buf: &[u8],
    ) -> Poll<std::io::Result<usize>> {
        let polled = Pin::new(&mut self.inner).poll_write(cx, buf);
        self.timed(cx, polled)
    }

    fn poll_write_vectored(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
        bufs: &[std::io::IoSlice<'_>],
    ) -> Poll<std::io::Result<usize>> {
        let polled = Pin::new(&mut self.inner).poll_write_vectored(cx, bufs);
        self.timed(cx, polled)
    }

    fn is_write_vectored(&self) -> bool {
        self.inner.is_write_vectored()
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        let polled = Pin::new(&mut self.inner).poll_flush(cx);
        self.timed(cx, polled)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

async fn answer(
    request: Request<Incoming>,
    port: u16,
    handler: Arc<Handler>,
) -> Result<Reply, Infallible> {
    if let Some(refused) = http::refusal(&request, port) {
        return Ok(refused);
    }
    let (head, body) = request.into_parts();
    let body = match http::body(body).await {
        Ok(body) => body,
        Err(refused) => return Ok(refused),
    };
    let worked = tokio::task::spawn_blocking(move || handler(&head, &body)).await;
    Ok(worked.unwrap_or_else(|_| http::text(500, "the editor failed on this request")))
}

/// A connection above [`MAX_CONNECTIONS`]: told so, and closed (when the
/// stream is dropped). A new socket's send buffer always has room for these
/// few bytes, so the write never waits.
fn turn_away(stream: &TcpStream) {
    let busy = b"HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\nRetry-After: 1\r\n\r\n";
    let _ = stream.try_write(busy);
}

/// An answer without a body: used by tests of the edge.
#[cfg(test)]
fn empty(status: u16) -> Reply {
    let mut reply = hyper::Response::new(http_body_util::Full::default());
    *reply.status_mut() = hyper::StatusCode::from_u16(status).unwrap();
    reply
}

#[cfg(test)]
mod tests {
    use std::io::{Read as _, Write as _};
    use std::net::TcpStream;
    use std::sync::Arc;

    /// A server answering 204 to every request that passes the edge, on a
    /// thread of its own; its port.
    fn server() -> u16 {
        let (sender, port) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let runtime = super::runtime().unwrap();
            runtime.block_on(async {
                let listener = super::listen(0).unwrap();
                let port = listener.local_addr().unwrap().port();
                sender.send(port).unwrap();
                super::serve(listener, port, Arc::new(|_, _| super::empty(204))).await;
            });
        });
        port.recv().unwrap()
    }

    fn exchange(port: u16, request: &[u8]) -> String {
        let mut stream = TcpStream::connect(("127.0.0.1", port)).unwrap();
        stream
            .set_read_timeout(Some(std::time::Duration::from_secs(20)))
            .unwrap();
        // The server may answer and close before all of an oversized
        // request is written.
        let _ = stream.write_all(request);
        let mut answer = String::new();
        let _ = stream.read_to_string(&mut answer);
        answer
    }

    #[test]
    fn headers_above_the_cap_get_431() {
        let port = server();
        let big = format!(
            "GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nX-Padding: {}\r\nConnection: close\r\n\r\n",
            "a".repeat(super::http::MAX_HEAD)
        );
        assert!(exchange(port, big.as_bytes()).starts_with("HTTP/1.1 431"));
        let small =
            format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n");
        assert!(exchange(port, small.as_bytes()).starts_with("HTTP/1.1 204"));
    }

    /// Hostile worlds VI: 70 idle local connections (sending nothing) made
    /// 17 of 20 page requests get a 503 until they timed out. A new
    /// connection takes the place of the one open longest that is waiting
    /// for a request.
    #[test]
    fn idle_connections_make_room_for_requests() {
        let port = server();
        let idle: Vec<TcpStream> = (0..70)
            .map(|_| TcpStream::connect(("127.0.0.1", port)).unwrap())
            .collect();
        let request =
            format!("GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nConnection: close\r\n\r\n");
        for i in 0..20 {
            let answer = exchange(port, request.as_bytes());
            assert!(answer.starts_with("HTTP/1.1 204"), "request {i}: {answer}");
        }
        drop(idle);
    }

    #[test]
    fn a_second_host_header_is_refused() {
        let port = server();
        let two = format!(
            "GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nHost: evil.example\r\nConnection: close\r\n\r\n"
        );
        assert!(exchange(port, two.as_bytes()).starts_with("HTTP/1.1 403"));
    }
}
