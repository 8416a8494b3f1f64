//! [`Finding`]: one reproduced result (a figure or an experiment) with its files, its numbers
//! and how it compares with the paper; [`Experiment`]: what every experiment needs.

use std::path::Path;
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;
use tvf_render::View;
use tvf_spectral::SpectralBasis;

/// One reproduced result.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Finding {
    /// Which result of the paper (e.g. "Figure 1").
    pub id: String,
    /// What it shows.
    pub title: String,
    /// Mesh it was computed on.
    pub mesh: String,
    /// Pictures, as file names in the output folder.
    pub files: Vec<String>,
    /// Measured numbers: `(what, value)`.
    pub numbers: Vec<(String, String)>,
    /// What the paper reports.
    pub paper: String,
    /// How ours compares; differences beyond noise are named with their reason.
    pub comparison: String,
}

impl Finding {
    /// An empty finding for `id` on `mesh`.
    pub fn new(id: &str, title: &str, mesh: &str) -> Self {
        Self {
            id: id.to_string(),
            title: title.to_string(),
            mesh: mesh.to_string(),
            ..Self::default()
        }
    }

    /// Records a number.
    pub fn number(&mut self, what: impl Into<String>, value: impl Into<String>) {
        self.numbers.push((what.into(), value.into()));
    }
}

/// What an experiment on one mesh works with: the mesh, its complex (the catalog's default),
/// the basis computed once for it, where to write and how large to draw.
#[derive(Clone, Copy)]
pub struct Experiment<'a> {
    /// Mesh name (file stem).
    pub name: &'a str,
    /// The mesh.
    pub mesh: &'a SurfaceMesh,
    /// Its complex: the catalog's default, the paper's conforming decomposition with
    /// barycentric lumping.
    pub complex: &'a dyn HodgeComplex,
    /// The basis, computed once per mesh.
    pub basis: &'a SpectralBasis,
    /// Output folder.
    pub out: &'a Path,
    /// Size and camera of one panel.
    pub view: View,
}
