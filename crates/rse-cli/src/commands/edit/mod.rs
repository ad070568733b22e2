//! `rse-gen edit`: the paper's GUI as a local web page — globals, the
//! obstacle table, a live top-down and 3D preview, load, save, generate.
//! The page and its script are part of the binary.

mod http;
mod server;

use std::io::Write as _;
use std::sync::Arc;

use anyhow::Context as _;
use hyper::Method;

use crate::ExitStatus;
use crate::args::{EditArgs, SchemeOverrides};
use rse_edit::{Drafts, Editor, PageScheme, api};

pub fn run(args: &EditArgs, overrides: &SchemeOverrides) -> anyhow::Result<ExitStatus> {
    let mut editor = Editor::default();
    if let Some(path) = &args.scheme {
        // A file that is not there yet starts a new scheme there, as a
        // desktop program does (Save writes it); one that cannot be read
        // is refused.
        let scheme = if path.try_exists().is_ok_and(|there| !there) {
            let new = rse_core::Scheme::from_csv(rse_edit::NEW_SCHEME, None)
                .expect("the starting scheme is valid (a test reads it)");
            super::with_overrides(new, overrides)?
        } else {
            super::load_scheme(path, overrides)?
        };
        editor.initial = PageScheme::from_scheme(&scheme);
        editor.path = Some(path.clone());
    } else {
        let scheme = rse_core::Scheme::from_csv(rse_edit::NEW_SCHEME, None)
            .expect("the starting scheme is valid (a test reads it)");
        editor.initial = PageScheme::from_scheme(&scheme);
    }
    editor.drafts = state_folder().map(Drafts::new);
    let file = args
        .scheme
        .as_ref()
        .map_or_else(String::new, |p| p.display().to_string());
    let runtime = server::runtime().context("cannot start the editor's server")?;
    runtime.block_on(async {
        let listener = match args.port {
            Some(asked) => server::listen(asked)
                .with_context(|| format!("cannot listen on 127.0.0.1:{asked}"))?,
            // The port this file was last edited on, when it is free: the
            // page's address (and what the browser keeps for it) stays the
            // same across restarts.
            None => editor
                .drafts
                .as_ref()
                .and_then(|d| d.last_port(&file))
                .and_then(|last| server::listen(last).ok())
                .map_or_else(|| server::listen(0), Ok)
                .context("cannot listen on 127.0.0.1")?,
        };
        let port = listener.local_addr()?.port();
        if let Some(drafts) = &editor.drafts
            && let Err(e) = drafts.remember_port(&file, port)
        {
            eprintln!("rse-gen: cannot remember the editor's port: {e}");
        }
        let url = format!("http://127.0.0.1:{port}/");
        let mut stdout = std::io::stdout().lock();
        writeln!(stdout, "{url}")?;
        stdout.flush()?;
        drop(stdout);
        eprintln!("rse-gen: the editor is at {url} (Ctrl-C to stop)");
        if args.open {
            open_in_browser(url.clone());
        }
        let handler = Arc::new(move |head: &hyper::http::request::Parts, body: &[u8]| {
            route(&editor, &head.method, head.uri.path(), body)
        });
        server::serve(listener, port, handler).await;
        Ok(ExitStatus::Success)
    })
}

/// The editor's state folder (drafts and last ports): `RSE_STATE_DIR`, else
/// the platform's state folder for rse (`$XDG_STATE_HOME/rse/editor`,
/// `~/.local/state/rse/editor`), else its local data folder (macOS,
/// Windows); None when there is no home to put it in.
fn state_folder() -> Option<std::path::PathBuf> {
    if let Some(dir) = std::env::var_os("RSE_STATE_DIR").filter(|d| !d.is_empty()) {
        return Some(dir.into());
    }
    let dirs = directories::ProjectDirs::from("", "", "rse")?;
    Some(
        dirs.state_dir()
            .unwrap_or_else(|| dirs.data_local_dir())
            .join("editor"),
    )
}

/// Opens `url` with the desktop's opener, in the background; when there is
/// none, or it fails (no display), says so in one line: the URL printed
/// above is the way in then.
fn open_in_browser(url: String) {
    std::thread::spawn(move || {
        if let Err(why) = rse_edit::desktop::open(url.as_ref()) {
            eprintln!("rse-gen: --open: cannot open a browser ({why}); open {url} yourself");
        }
    });
}

fn route(editor: &Editor, method: &Method, path: &str, body: &[u8]) -> http::Reply {
    match (method, path) {
        (&Method::GET, "/api/schema") => http::json(&api::schema()),
        (&Method::GET, "/api/state") => http::json(&api::state(editor)),
        (&Method::GET, "/api/job") => http::json(&api::job(editor)),
        (&Method::GET, world) if world.starts_with("/api/world-preview/") => {
            let name = &world["/api/world-preview/".len()..];
            match api::world_preview(editor, name) {
                Some(png) => http::bytes(200, "image/png", png),
                None => http::text(404, "no such world's preview"),
            }
        }
        (&Method::POST, api_path) => {
            let answer = match api_path {
                "/api/preview" => api::preview(body),
                "/api/parse" => api::parse(body),
                "/api/save" => api::save(editor, body),
                "/api/open" => api::open(editor, body),
                "/api/csv" => api::csv(body),
                "/api/draft" => api::draft(editor, body),
                "/api/generate" => api::generate(editor, body),
                "/api/open-folder" => api::open_folder(editor),
                _ => return http::text(404, "not found"),
            };
            // A refusal is an answer too: the page reads its `ok` and `error`.
            http::json(&answer.unwrap_or_else(|refusal| refusal))
        }
        (&Method::GET, file) => match rse_edit::page::FILES
            .iter()
            .find(|(path, ..)| *path == file)
        {
            Some((_, content_type, body)) => http::bytes(200, content_type, (*body).into()),
            None => http::text(404, "not found"),
        },
        _ => http::text(404, "not found"),
    }
}
