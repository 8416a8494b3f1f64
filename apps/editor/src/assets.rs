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

impl Asset {
    /// An HTML page.
    const fn html(path: &'static str, body: &'static str) -> Self {
        Asset {
            path,
            content_type: "text/html; charset=utf-8",
            body,
        }
    }

    /// A style sheet.
    const fn css(path: &'static str, body: &'static str) -> Self {
        Asset {
            path,
            content_type: "text/css; charset=utf-8",
            body,
        }
    }

    /// A JavaScript module.
    const fn script(path: &'static str, body: &'static str) -> Self {
        Asset {
            path,
            content_type: "text/javascript; charset=utf-8",
            body,
        }
    }
}

/// Every file of the page.
pub const ASSETS: &[Asset] = &[
    Asset::html("/index.html", include_str!("../assets/index.html")),
    Asset::css("/style.css", include_str!("../assets/style.css")),
    Asset::script("/app.js", include_str!("../assets/app.js")),
    Asset::script("/mesh.js", include_str!("../assets/mesh.js")),
    Asset::script("/camera.js", include_str!("../assets/camera.js")),
    Asset::script("/gl.js", include_str!("../assets/gl.js")),
    Asset::script("/net.js", include_str!("../assets/net.js")),
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
