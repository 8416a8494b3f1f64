//! `--discretization ID` (and its shorthands `--decomposition`, `--mass`): which catalog entry a
//! subcommand builds; `--boundary` its boundary condition on meshes with boundary; or
//! `--complex DIR`: the five matrices of a folder (`tvf operators -o DIR`, edited, or made by
//! hand), read by [`tvf_spectral::read_complex_folder`].

use crate::mesh_input::MeshInput;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;
use tvf_core::discretization::BoundaryCondition;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{
    build_complex, catalog, catalog_entry, BoxedComplex, DEFAULT_DISCRETIZATION,
};

/// The discretization flags shared by every subcommand that builds a complex.
#[derive(Args, Debug, Clone, Default)]
pub struct DiscretizationFlags {
    /// Discretization: an id of the catalog (`tvf discretizations` lists them)
    /// [default: conforming-barycentric, or the basis file's].
    #[arg(long, value_name = "ID", value_parser = catalog_id)]
    pub discretization: Option<String>,
    /// Shorthand for --discretization NAME-MASS: the decomposition part of the id
    /// (conforming, nonconforming, dec).
    #[arg(long, value_name = "NAME", conflicts_with = "discretization", value_parser = decomposition_part)]
    pub decomposition: Option<String>,
    /// Shorthand for --discretization DECOMPOSITION-NAME: the mass part of the id (barycentric,
    /// voronoi; circumcentric for dec).
    #[arg(long, value_name = "NAME", conflicts_with = "discretization", value_parser = mass_part)]
    pub mass: Option<String>,
    /// Boundary condition on meshes with boundary: tangential (potentials free, co-potentials
    /// zero on the boundary: every eigenfield and harmonic field is tangential to the boundary)
    /// or normal (potentials zero on the boundary: fields normal to it). Ignored on closed
    /// meshes [default: tangential, or the basis file's].
    #[arg(long, value_name = "CONDITION", value_parser = boundary_condition)]
    pub boundary: Option<BoundaryCondition>,
    /// Your own matrices: the folder `tvf operators MESH -o DIR` writes (edited, or made by
    /// hand): d0, d1, M0, M1, M2 (or M2_inverse) as .mtx or .npz in the mesh's numbering, with
    /// optional info.json (sampling, fixed nodes, boundary condition) and vertex_map.npy.
    /// Derived files (S, S0, S2, B, J) are ignored.
    #[arg(
        long,
        value_name = "DIR",
        conflicts_with_all = ["discretization", "decomposition", "mass", "boundary"]
    )]
    pub complex: Option<PathBuf>,
}

impl DiscretizationFlags {
    /// The id the flags ask for, if any flag was given (a shorthand fills the missing part
    /// with `conforming` / `barycentric`).
    pub fn requested_id(&self) -> Option<String> {
        if let Some(id) = &self.discretization {
            return Some(id.clone());
        }
        if self.decomposition.is_none() && self.mass.is_none() {
            return None;
        }
        Some(format!(
            "{}-{}",
            self.decomposition.as_deref().unwrap_or("conforming"),
            self.mass.as_deref().unwrap_or("barycentric")
        ))
    }

    /// The id to use: the flags', else [`DEFAULT_DISCRETIZATION`].
    pub fn id(&self) -> String {
        self.requested_id()
            .unwrap_or_else(|| DEFAULT_DISCRETIZATION.to_string())
    }

    /// The boundary condition to use: the flag's, else the default (tangential).
    pub fn boundary_condition(&self) -> BoundaryCondition {
        self.boundary.unwrap_or_default()
    }

    /// Builds the chosen complex on `mesh` (loaded from `input`, which names it in errors) with
    /// the chosen boundary condition, or reads it from the `--complex` folder.
    pub fn build(&self, mesh: &SurfaceMesh, input: &MeshInput) -> Result<BoxedComplex> {
        if let Some(dir) = &self.complex {
            let identity: Vec<usize>;
            let original_vertex = match input.original_vertex() {
                Some(map) => map,
                None => {
                    identity = (0..mesh.vertex_count()).collect();
                    &identity
                }
            };
            let complex = tvf_spectral::read_complex_folder(dir, mesh, original_vertex)
                .with_context(|| format!("--complex {} on {}", dir.display(), input.label()))?;
            return Ok(Box::new(complex));
        }
        build_complex(&self.id(), Some(self.boundary_condition()), mesh)
            .with_context(|| input.label())
    }
}

/// Accepts `tangential` or `normal`.
fn boundary_condition(value: &str) -> Result<BoundaryCondition, String> {
    BoundaryCondition::from_name(value)
        .ok_or_else(|| format!("'{value}' is not a boundary condition: tangential or normal"))
}

/// Accepts an id of the catalog (a usage error lists them otherwise).
fn catalog_id(value: &str) -> Result<String, String> {
    catalog_entry(value)
        .map(|entry| entry.id.to_string())
        .map_err(|e| e.to_string())
}

/// The catalog ids split at their last `-`: (decomposition, mass).
fn id_parts() -> impl Iterator<Item = (&'static str, &'static str)> {
    catalog()
        .iter()
        .filter_map(|entry| entry.id.rsplit_once('-'))
}

/// Accepts the first part of some catalog id (`conforming`, `nonconforming`, `dec`).
fn decomposition_part(value: &str) -> Result<String, String> {
    one_of(value, id_parts().map(|(d, _)| d).collect())
}

/// Accepts the last part of some catalog id (`barycentric`, `voronoi`, `circumcentric`).
fn mass_part(value: &str) -> Result<String, String> {
    one_of(value, id_parts().map(|(_, m)| m).collect())
}

fn one_of(value: &str, mut known: Vec<&str>) -> Result<String, String> {
    known.sort_unstable();
    known.dedup();
    if known.contains(&value) {
        Ok(value.to_string())
    } else {
        Err(format!("'{value}' is not one of: {}", known.join(", ")))
    }
}
