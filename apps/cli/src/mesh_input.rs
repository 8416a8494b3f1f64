//! Where a subcommand's mesh comes from: a file (`MESH`) or a built-in example
//! (`--example NAME`). Every subcommand that takes a mesh flattens [`MeshInput`] into its
//! arguments and calls [`MeshInput::load`]:
//!
//! ```ignore
//! #[derive(clap::Args)]
//! pub struct MyArgs {
//!     #[command(flatten)]
//!     input: crate::mesh_input::MeshInput,
//! }
//! let loaded = args.input.load()?; // loaded.mesh, loaded.report
//! ```

use crate::examples::{example_mesh, EXAMPLE_NAMES};
use anyhow::{Context, Result};
use clap::builder::PossibleValuesParser;
use clap::Args;
use std::path::PathBuf;
use tvf_core::io::{load_mesh, LoadedMesh};
use tvf_core::SurfaceMesh;

/// A mesh file or a built-in example; exactly one must be given.
#[derive(Args, Debug, Clone)]
pub struct MeshInput {
    /// Mesh file (.obj, .off or .ply); omit when using --example.
    #[arg(value_name = "MESH", required_unless_present = "example")]
    pub mesh: Option<PathBuf>,
    /// A built-in example mesh instead of a file.
    #[arg(
        long,
        value_name = "NAME",
        conflicts_with = "mesh",
        value_parser = PossibleValuesParser::new(EXAMPLE_NAMES)
    )]
    pub example: Option<String>,
}

impl MeshInput {
    /// Loads and validates the mesh. File errors name the file, the line where one applies,
    /// and the problem; examples are validated like files (their report has no warnings).
    pub fn load(&self) -> Result<LoadedMesh> {
        match (&self.mesh, &self.example) {
            (Some(path), _) => Ok(load_mesh(path)?),
            (None, Some(name)) => {
                let mesh = example_mesh(name)?;
                let (mesh, report) =
                    SurfaceMesh::validated(mesh.positions().to_vec(), mesh.faces().to_vec())
                        .with_context(|| format!("built-in example '{name}' is invalid"))?;
                Ok(LoadedMesh { mesh, report })
            }
            (None, None) => anyhow::bail!("give a mesh file or --example NAME"),
        }
    }

    /// A label for messages and reports: the path as given, or `example:NAME`.
    pub fn label(&self) -> String {
        match (&self.mesh, &self.example) {
            (Some(path), _) => path.display().to_string(),
            (None, Some(name)) => format!("example:{name}"),
            (None, None) => String::new(),
        }
    }
}
