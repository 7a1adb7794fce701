//! `polbrdf explore`: serves the built web explorer (`web/dist`, built by `scripts/build-web`)
//! on localhost and prints its address. The page computes in the browser (WebAssembly); this
//! command only hands out its static files.

use crate::error::CliError;
use std::path::{Component, Path, PathBuf};

/// The command that builds the page, for the message when it is missing.
const BUILD: &str = "scripts/build-web";

/// The files the page cannot start without.
const REQUIRED: [&str; 3] = ["index.html", "explorer.js", "pkg/polbrdf_wasm_bg.wasm"];

/// The built page's folder: `dir` when given; else `web/dist` in the working directory, or
/// beside the repository the binary was built in (`target/<profile>/polbrdf` → `web/dist`).
fn folder(dir: Option<&Path>) -> PathBuf {
    if let Some(d) = dir {
        return d.to_path_buf();
    }
    let here = PathBuf::from("web/dist");
    if here.join(REQUIRED[0]).is_file() {
        return here;
    }
    std::env::current_exe()
        .ok()
        .and_then(|exe| Some(exe.parent()?.parent()?.parent()?.join("web/dist")))
        .filter(|d| d.join(REQUIRED[0]).is_file())
        .unwrap_or(here)
}

/// Checks that `dir` holds the built page.
fn check_built(dir: &Path) -> Result<(), CliError> {
    for f in REQUIRED {
        let p = dir.join(f);
        if !p.is_file() {
            return Err(CliError::Io(polbrdf_io::Error::File {
                path: p,
                message: format!(
                    "the web explorer is not built (no such file): build it with `{BUILD}` from \
                     the repository's root, or give the built folder with --dir"
                ),
            }));
        }
    }
    Ok(())
}

/// The content type of a file by its extension (`.wasm` must be `application/wasm` for the
/// browser's streaming compilation).
fn content_type(path: &Path) -> &'static str {
    match path.extension().and_then(|e| e.to_str()) {
        Some("html") => "text/html; charset=utf-8",
        Some("js") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("json") => "application/json",
        Some("png") => "image/png",
        _ => "application/octet-stream",
    }
}

/// The file of `dir` a request's URL names (`/` is `index.html`; the query is ignored), or
/// `None` for a path that leaves the folder or is not a plain relative path.
fn file_of(dir: &Path, url: &str) -> Option<PathBuf> {
    let path = url.split(['?', '#']).next().unwrap_or("");
    let rel = path.trim_start_matches('/');
    let rel = if rel.is_empty() { "index.html" } else { rel };
    let rel = Path::new(rel);
    rel.components()
        .all(|c| matches!(c, Component::Normal(_)))
        .then(|| dir.join(rel))
}

/// Runs `polbrdf explore`: serves the page in `dir` on `127.0.0.1:port` (0: a free port) until
/// interrupted.
pub fn run(dir: Option<&Path>, port: u16) -> Result<(), CliError> {
    let dir = folder(dir);
    check_built(&dir)?;
    let server = tiny_http::Server::http(("127.0.0.1", port)).map_err(|e| {
        CliError::Invalid(format!("--port: cannot listen on 127.0.0.1:{port}: {e}"))
    })?;
    let addr = server
        .server_addr()
        .to_ip()
        .map_or_else(|| format!("127.0.0.1:{port}"), |a| a.to_string());
    crate::note!("polbrdf explorer: http://{addr}/");
    crate::note!("serving {} (Ctrl-C stops)", dir.display());
    for request in server.incoming_requests() {
        let file = file_of(&dir, request.url()).filter(|p| p.is_file());
        let response = match file.map(|p| (std::fs::read(&p), p)) {
            Some((Ok(bytes), p)) => {
                let header = tiny_http::Header::from_bytes(
                    &b"Content-Type"[..],
                    content_type(&p).as_bytes(),
                )
                .expect("a valid header");
                tiny_http::Response::from_data(bytes).with_header(header)
            }
            _ => tiny_http::Response::from_string("not found").with_status_code(404),
        };
        // A client that went away is no error of the server's.
        let _ = request.respond(response);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn urls_map_to_files_inside_the_folder_only() {
        let d = Path::new("/srv/dist");
        assert_eq!(file_of(d, "/"), Some(d.join("index.html")));
        assert_eq!(file_of(d, "/?x=1#y"), Some(d.join("index.html")));
        assert_eq!(
            file_of(d, "/pkg/polbrdf_wasm_bg.wasm"),
            Some(d.join("pkg/polbrdf_wasm_bg.wasm"))
        );
        assert_eq!(file_of(d, "/../secret"), None);
        assert_eq!(file_of(d, "/pkg/../../secret"), None);
        assert_eq!(file_of(d, "/./index.html"), None);
        assert_eq!(content_type(Path::new("a.wasm")), "application/wasm");
    }
}
