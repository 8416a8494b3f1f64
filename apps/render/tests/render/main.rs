//! tvf-render's integration tests: pictures, plots, streamline tracing and exports. `common`
//! holds the synthetic fields and the folder that keeps pictures for inspection.

mod common;
mod exports;
mod plots;
mod render_pictures;
mod tracing;
