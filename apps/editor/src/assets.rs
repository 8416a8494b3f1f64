//! The page's files, embedded in the binary (the page works offline: nothing is loaded from
//! anywhere but the tvf server).

/// One embedded file: its URL path, content type and bytes.
#[derive(Debug, Clone, Copy)]
pub struct Asset {
    /// URL path, e.g. `/app.js`.
    pub path: &'static str,
    /// MIME type sent as `Content-Type`.
    pub content_type: &'static str,
    /// The file.
    pub body: &'static str,
}

/// Every file of the page.
pub const ASSETS: &[Asset] = &[
    Asset {
        path: "/index.html",
        content_type: "text/html; charset=utf-8",
        body: include_str!("../assets/index.html"),
    },
    Asset {
        path: "/style.css",
        content_type: "text/css; charset=utf-8",
        body: include_str!("../assets/style.css"),
    },
    Asset {
        path: "/app.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_str!("../assets/app.js"),
    },
    Asset {
        path: "/mesh.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_str!("../assets/mesh.js"),
    },
    Asset {
        path: "/camera.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_str!("../assets/camera.js"),
    },
    Asset {
        path: "/gl.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_str!("../assets/gl.js"),
    },
    Asset {
        path: "/net.js",
        content_type: "text/javascript; charset=utf-8",
        body: include_str!("../assets/net.js"),
    },
];

/// The embedded file for a URL path (`/` is the page itself).
pub fn asset(path: &str) -> Option<&'static Asset> {
    let path = if path == "/" { "/index.html" } else { path };
    ASSETS.iter().find(|a| a.path == path)
}

/// Where the page template holds the session token.
const TOKEN_PLACEHOLDER: &str = "{{TVF_TOKEN}}";

/// The page (`index.html`) with the session `token` embedded, for its scripts to send with
/// every API call (see [`crate::access`]).
pub fn page(token: &str) -> String {
    include_str!("../assets/index.html").replace(TOKEN_PLACEHOLDER, token)
}
