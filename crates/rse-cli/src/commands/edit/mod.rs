//! `rse-gen edit`: the paper's GUI as a local web page — globals, the
//! obstacle table, a live top-down and 3D preview, load, save, generate.
//! The page and its script are part of the binary.

mod http;

use std::io::Write as _;

use anyhow::Context as _;
use tiny_http::{Method, Server};

use crate::ExitStatus;
use crate::args::{EditArgs, SchemeOverrides};
use rse_edit::{Editor, PageScheme, api};

/// Requests served at once: one client stalling, or one long preview or
/// batch, holds one worker while the others go on serving.
const WORKERS: usize = 4;

/// How long a connection may stay silent in the middle of a request.
const READ_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(5);

/// The editor's listening socket on 127.0.0.1:`port` (0: a free port).
///
/// Loopback only: the editor reads and writes files for whoever talks to it.
/// `TCP_NODELAY` is set on the listening socket, which Linux hands on to every
/// accepted connection: `tiny_http` writes a response's headers and its body
/// separately, and with Nagle's algorithm the body then waits for the browser's
/// delayed ACK of the headers, 40 ms on every preview.
///
/// A read timeout is set on it too, handed on the same way: a client that
/// stalls mid-request (announcing a body it never sends) is dropped after
/// [`READ_TIMEOUT`] instead of holding a worker for ever.
fn listener(port: u16) -> std::io::Result<std::net::TcpListener> {
    use socket2::{Domain, Protocol, Socket, Type};
    let socket = Socket::new(Domain::IPV4, Type::STREAM, Some(Protocol::TCP))?;
    // As std's TcpListener::bind does: a restarted editor can take its port back.
    socket.set_reuse_address(true)?;
    socket.set_tcp_nodelay(true)?;
    socket.set_read_timeout(Some(READ_TIMEOUT))?;
    socket.bind(&std::net::SocketAddr::from(([127, 0, 0, 1], port)).into())?;
    socket.listen(128)?;
    Ok(socket.into())
}

pub fn run(args: &EditArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let mut editor = Editor::default();
    if let Some(path) = &args.scheme {
        let scheme = super::load_scheme(path, overrides)?;
        editor.initial = PageScheme::from_scheme(&scheme);
        editor.path = Some(path.clone());
    } else {
        let scheme = rse_core::Scheme::from_csv("# size: 20x20\ntype,height\nrandom,1\n", None)
            .expect("the starting scheme is valid");
        editor.initial = PageScheme::from_scheme(&scheme);
    }
    let asked = args.port.unwrap_or(0);
    let server = listener(asked)
        .map_err(anyhow::Error::from)
        .and_then(|l| Server::from_listener(l, None).map_err(|e| anyhow::anyhow!("{e}")))
        .with_context(|| format!("cannot listen on 127.0.0.1:{asked}"))?;
    let port = server
        .server_addr()
        .to_ip()
        .context("the server has an IP address")?
        .port();
    let url = format!("http://127.0.0.1:{port}/");
    let mut stdout = std::io::stdout().lock();
    writeln!(stdout, "{url}")?;
    stdout.flush()?;
    drop(stdout);
    eprintln!("rse-gen: the editor is at {url} (Ctrl-C to stop)");
    if args.open {
        open_in_browser(url.clone());
    }
    let serve = || {
        while let Ok(mut request) = server.recv() {
            let reply = match http::refusal(&request, port) {
                Some(refused) => refused,
                None => route(&editor, &mut request),
            };
            // A client that went away is not the editor's problem.
            let _ = request.respond(reply);
        }
    };
    std::thread::scope(|scope| {
        for _ in 0..WORKERS {
            scope.spawn(serve);
        }
    });
    Ok(ExitStatus::Success)
}

/// Opens `url` with the desktop's opener, in the background; when there is
/// none, or it fails (no display), says so in one line: the URL printed
/// above is the way in then.
fn open_in_browser(url: String) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else {
        "xdg-open"
    };
    std::thread::spawn(move || {
        let status = std::process::Command::new(opener)
            .arg(&url)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .status();
        let why = match status {
            Ok(s) if s.success() => return,
            Ok(s) => format!("{opener} failed ({s})"),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => format!("no {opener} here"),
            Err(e) => format!("{opener}: {e}"),
        };
        eprintln!("rse-gen: --open: cannot open a browser ({why}); open {url} yourself");
    });
}

fn route(editor: &Editor, request: &mut tiny_http::Request) -> http::Reply {
    let path = request.url().split('?').next().unwrap_or("").to_owned();
    match (request.method(), path.as_str()) {
        (Method::Get, "/api/schema") => http::json(&api::schema()),
        (Method::Get, "/api/state") => http::json(&api::state(editor)),
        (Method::Get, "/api/job") => http::json(&api::job(editor)),
        (Method::Post, api_path) => {
            let body = match http::body(request) {
                Ok(body) => body,
                Err(reply) => return reply,
            };
            let answer = match api_path {
                "/api/preview" => api::preview(&body),
                "/api/parse" => api::parse(&body),
                "/api/save" => api::save(&body),
                "/api/generate" => api::generate(editor, &body),
                _ => return http::text(404, "not found"),
            };
            // A refusal is an answer too: the page reads its `ok` and `error`.
            http::json(&answer.unwrap_or_else(|refusal| refusal))
        }
        (Method::Get, file) => match rse_edit::page::FILES
            .iter()
            .find(|(path, ..)| *path == file)
        {
            Some((_, content_type, body)) => http::bytes(200, content_type, (*body).into()),
            None => http::text(404, "not found"),
        },
        _ => http::text(404, "not found"),
    }
}

#[cfg(test)]
mod tests {
    use super::listener;
    use std::net::TcpStream;

    #[test]
    fn accepted_connections_send_without_nagle_delay() {
        let listener = listener(0).unwrap();
        assert!(socket2::SockRef::from(&listener).tcp_nodelay().unwrap());
        let address = listener.local_addr().unwrap();
        assert!(address.ip().is_loopback());
        let _client = TcpStream::connect(address).unwrap();
        let (accepted, _) = listener.accept().unwrap();
        // The options tiny_http's connections rely on, inherited from the listener.
        assert!(accepted.nodelay().unwrap());
        assert_eq!(accepted.read_timeout().unwrap(), Some(super::READ_TIMEOUT));
    }
}
