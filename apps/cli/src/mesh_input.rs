//! Where a subcommand's mesh comes from: a file (`MESH`) or a built-in example
//! (`--example NAME`). Every subcommand that takes a mesh flattens [`MeshInput`] into its
//! arguments and calls [`MeshInput::load`]:
//!
//! ```text
//! #[derive(clap::Args)]
//! pub struct MyArgs {
//!     #[command(flatten)]
//!     input: crate::mesh_input::MeshInput,
//! }
//! let loaded = args.input.load()?; // loaded.mesh, loaded.report
//! ```
//!
//! A subcommand with a second positional (`MESH FIELD`) declares it optional, required unless
//! `--example` is given, and takes it through [`MeshInput::required_second`] (or
//! [`MeshInput::optional_second`]) before loading: with `--example NAME` clap puts the only
//! positional into `MESH`, and these move it to where it belongs, so
//! `tvf render --example bumpy-torus field.npy -o out.png` works like
//! `tvf render torus.obj field.npy -o out.png`.

use anyhow::{anyhow, Context, Result};
use clap::builder::PossibleValuesParser;
use clap::error::ErrorKind;
use clap::{Args, CommandFactory};
use std::path::PathBuf;
use tvf_core::generate::{example_mesh, EXAMPLE_NAMES};
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
        value_parser = PossibleValuesParser::new(EXAMPLE_NAMES)
    )]
    pub example: Option<String>,
    /// Split every polygon into triangles by its own corners (no new vertex) right after
    /// loading, as `tvf triangulate` does, so that a triangle entry (conforming-*,
    /// nonconforming-*, dec-*, whitney-*) can be built on a quad or polygon mesh. Without it a
    /// polygon mesh is kept as polygons and gets polygon-dec. No effect on a triangle mesh.
    #[arg(long)]
    pub triangulate: bool,
    /// The input index of every mesh vertex (`ValidationReport::original_vertex`), recorded by
    /// [`MeshInput::load`]: what `--complex DIR`'s `vertex_map.npy` is checked against.
    #[arg(skip)]
    original_vertex: std::sync::OnceLock<Vec<usize>>,
}

/// A mesh file or a built-in example, either optional: the mesh of a command that also runs
/// without one (`tvf check` on generated meshes, `tvf compare --corpus`). The command states
/// when `MESH` is required and what it is for with `mut_arg("mesh", …)`.
#[derive(Args, Debug, Clone)]
pub struct OptionalMeshInput {
    /// Mesh file (.obj, .off or .ply).
    #[arg(value_name = "MESH")]
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

impl OptionalMeshInput {
    /// The mesh given: the file `MESH`, else the example `--example`, else none.
    pub fn input(&self) -> Option<MeshInput> {
        match (&self.mesh, &self.example) {
            (Some(path), _) => Some(MeshInput::file(path.clone())),
            (None, Some(name)) => Some(MeshInput::example(name)),
            (None, None) => None,
        }
    }
}

impl MeshInput {
    /// The mesh file `path`.
    pub fn file(path: PathBuf) -> Self {
        Self {
            mesh: Some(path),
            example: None,
            triangulate: false,
            original_vertex: Default::default(),
        }
    }

    /// The built-in example `name` (one of [`EXAMPLE_NAMES`], checked when loaded).
    pub fn example(name: &str) -> Self {
        Self {
            mesh: None,
            example: Some(name.to_string()),
            triangulate: false,
            original_vertex: Default::default(),
        }
    }

    /// Loads and validates the mesh, then (with `--triangulate`) splits its polygons into
    /// triangles ([`LoadedMesh::triangulated`]). File errors name the file, the line where one
    /// applies, and the problem; examples are validated like files (their report has no
    /// warnings).
    ///
    /// Both a mesh file and `--example` is a usage error (exit code 2).
    pub fn load(&self) -> Result<LoadedMesh> {
        let mut loaded = self.load_and_validate()?;
        if self.triangulate {
            loaded = loaded
                .triangulated()
                .with_context(|| format!("{}: cannot triangulate", self.label()))?;
        }
        // A second load of the same input finds the same numbering.
        let _ = self
            .original_vertex
            .set(loaded.report.original_vertex.clone());
        Ok(loaded)
    }

    /// The input index of every vertex of the mesh [`MeshInput::load`] loaded (`None` before
    /// it did).
    pub fn original_vertex(&self) -> Option<&[usize]> {
        self.original_vertex.get().map(Vec::as_slice)
    }

    fn load_and_validate(&self) -> Result<LoadedMesh> {
        if let (Some(path), Some(name)) = (&self.mesh, &self.example) {
            usage_error(
                ErrorKind::ArgumentConflict,
                format!(
                    "give a mesh file or --example NAME, not both ('{}' and --example {name})",
                    path.display()
                ),
            );
        }
        match (&self.mesh, &self.example) {
            (Some(path), _) => {
                let loaded = load_mesh(path)?;
                let label = self.label();
                loaded
                    .mesh
                    .check_geometry_range()
                    .map_err(|e| anyhow!("{label}: {e}"))?;
                Ok(loaded)
            }
            (None, Some(name)) => {
                let Some(mesh) = example_mesh(name) else {
                    anyhow::bail!(
                        "unknown example '{name}': choose one of {}",
                        EXAMPLE_NAMES.join(", ")
                    );
                };
                let (mesh, report) =
                    SurfaceMesh::validated(mesh.positions().to_vec(), mesh.to_face_list())
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

    /// The subcommand's second positional (e.g. `FIELD`) when it is optional: with `--example`
    /// the one positional clap put into `MESH` is moved here. Two positionals with `--example`
    /// are a usage error (exit code 2).
    pub fn optional_second(&mut self, second: Option<PathBuf>, name: &str) -> Option<PathBuf> {
        if self.example.is_none() {
            return second;
        }
        match (self.mesh.take(), second) {
            (Some(first), Some(second)) => usage_error(
                ErrorKind::ArgumentConflict,
                format!(
                    "--example replaces MESH: give only {name} ('{}' and '{}' were given)",
                    first.display(),
                    second.display()
                ),
            ),
            (first, second) => first.or(second),
        }
    }

    /// Like [`MeshInput::optional_second`] for a required positional: missing is a usage error
    /// (exit code 2).
    pub fn required_second(&mut self, second: Option<PathBuf>, name: &str) -> PathBuf {
        match self.optional_second(second, name) {
            Some(path) => path,
            None => usage_error(
                ErrorKind::MissingRequiredArgument,
                format!("the required argument <{name}> was not provided"),
            ),
        }
    }
}

/// Reports a usage error the way clap does (on stderr with the subcommand's usage line, exit
/// code 2) and exits.
pub fn usage_error(kind: ErrorKind, message: String) -> ! {
    let mut command = crate::Cli::command();
    command.build();
    let name = std::env::args().skip(1).find(|a| !a.starts_with('-'));
    match name.and_then(|n| command.find_subcommand(&n).cloned()) {
        Some(sub) => {
            let bin_name = format!("tvf {}", sub.get_name());
            sub.bin_name(bin_name).error(kind, message).exit()
        }
        None => command.error(kind, message).exit(),
    }
}
