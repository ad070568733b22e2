//! The editor's page, built into the binary: one HTML file, its style and
//! its script as ES modules (no third-party script, works offline).

/// `(path, content type, body)` of each file the page is made of.
pub const FILES: [(&str, &str, &str); 6] = [
    (
        "/",
        "text/html; charset=utf-8",
        include_str!("page/index.html"),
    ),
    (
        "/style.css",
        "text/css; charset=utf-8",
        include_str!("page/style.css"),
    ),
    (
        "/app.js",
        "text/javascript; charset=utf-8",
        include_str!("page/app.js"),
    ),
    (
        "/colours.js",
        "text/javascript; charset=utf-8",
        include_str!("page/colours.js"),
    ),
    (
        "/map.js",
        "text/javascript; charset=utf-8",
        include_str!("page/map.js"),
    ),
    (
        "/view3d.js",
        "text/javascript; charset=utf-8",
        include_str!("page/view3d.js"),
    ),
];
