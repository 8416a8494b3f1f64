//! `--discretization ID` (and its shorthands `--decomposition`, `--mass`): which entry of the
//! program's catalog a subcommand builds; `--boundary` its boundary condition on meshes with
//! boundary; `--intrinsic-delaunay[=flip|refine]` to build it on the intrinsic Delaunay
//! triangulation; or `--complex DIR`: the five matrices of a folder (`tvf operators -o DIR`, edited,
//! or made by hand), read by [`tvf_spectral::read_complex_folder`]. The catalog is a value given
//! at run time ([`crate::run`]), which clap's value parsers cannot see: [`check_ids`] checks the
//! ids right after parsing, as a usage error.

use crate::mesh_input::MeshInput;
use anyhow::{Context, Result};
use clap::error::ErrorKind;
use clap::{ArgMatches, Args};
use std::path::PathBuf;
use tvf_core::discretization::BoundaryCondition;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{
    default_discretization, intrinsic_entry_id, parse_boundary_condition, parse_intrinsic_delaunay,
    requested_catalog_id, split_complex_id, split_intrinsic_id, BoxedComplex, Catalog,
    IntrinsicDelaunay,
};

/// The discretization flags shared by every subcommand that builds a complex.
#[derive(Args, Debug, Clone, Default)]
pub struct DiscretizationFlags {
    /// Discretization: an id of the catalog (`tvf discretizations` lists them) [default:
    /// conforming-barycentric on triangle meshes, polygon-dec on polygon meshes, or the basis
    /// file's].
    #[arg(long, value_name = "ID")]
    pub discretization: Option<String>,
    /// Shorthand for --discretization NAME-MASS: the decomposition part of the id
    /// (conforming, nonconforming, dec).
    #[arg(long, value_name = "NAME", conflicts_with = "discretization")]
    pub decomposition: Option<String>,
    /// Shorthand for --discretization DECOMPOSITION-NAME: the mass part of the id (barycentric,
    /// voronoi; circumcentric for dec).
    #[arg(long, value_name = "NAME", conflicts_with = "discretization")]
    pub mass: Option<String>,
    /// Boundary condition on meshes with boundary: tangential (potentials free, co-potentials
    /// zero on the boundary: every eigenfield and harmonic field is tangential to the boundary)
    /// or normal (potentials zero on the boundary: fields normal to it). Ignored on closed
    /// meshes [default: tangential, or the basis file's].
    #[arg(long, value_name = "CONDITION", value_parser = parse_boundary_condition)]
    pub boundary: Option<BoundaryCondition>,
    /// Build the discretization on the intrinsic Delaunay triangulation of the mesh (same
    /// surface, edges flipped on their lengths until every edge is Delaunay): `flip` (the
    /// default: flips only, no vertex inserted) or `refine` (also splits the edges flips cannot
    /// make strictly Delaunay, inserting vertices). The id gets `+intrinsic-delaunay` (or
    /// `+intrinsic-delaunay-refine`); fields are still read and written one vector per input
    /// face. DEC runs on every mesh with it; see docs/discretizations.md.
    #[arg(
        long,
        value_name = "MODE",
        num_args = 0..=1,
        require_equals = true,
        default_missing_value = "flip",
        value_parser = parse_intrinsic_delaunay
    )]
    pub intrinsic_delaunay: Option<IntrinsicDelaunay>,
    /// Your own matrices: the folder `tvf operators MESH -o DIR` writes (edited, or made by
    /// hand): d0, d1, M0, M1, M2 (or M2_inverse) as .mtx or .npz in the mesh's numbering, with
    /// optional info.json (sampling, fixed nodes, boundary condition) and vertex_map.npy.
    /// Derived files (S, S0, S2, B, J) are ignored.
    #[arg(
        long,
        value_name = "DIR",
        conflicts_with_all = ["discretization", "decomposition", "mass", "boundary", "intrinsic_delaunay"]
    )]
    pub complex: Option<PathBuf>,
}

impl DiscretizationFlags {
    /// The id the flags ask for, if any flag was given (a shorthand fills the missing part
    /// with `conforming` / `barycentric`).
    /// With `--intrinsic-delaunay` the id of the entry on the intrinsic Delaunay triangulation
    /// (`{id}+intrinsic-delaunay`).
    pub fn requested_id(&self) -> Option<String> {
        let decomposition = self.decomposition.as_deref();
        let id = requested_catalog_id(
            self.discretization.as_deref(),
            decomposition,
            self.mass.as_deref(),
        )?;
        Some(self.with_intrinsic(id))
    }

    /// The id to use on `mesh`: the flags', else [`default_discretization`] (polygon-dec on a
    /// mesh with polygons), on the intrinsic Delaunay triangulation with `--intrinsic-delaunay`.
    pub fn id(&self, mesh: &SurfaceMesh) -> String {
        self.requested_id()
            .unwrap_or_else(|| self.with_intrinsic(default_discretization(mesh).to_string()))
    }

    /// `id` with the intrinsic suffix of `--intrinsic-delaunay`, if given (and not already in
    /// the id).
    fn with_intrinsic(&self, id: String) -> String {
        with_intrinsic_suffix(id, self.intrinsic_delaunay)
    }

    /// The boundary condition to use: the flag's, else the default (tangential).
    pub fn boundary_condition(&self) -> BoundaryCondition {
        self.boundary.unwrap_or_default()
    }

    /// Builds the chosen entry of `catalog` on `mesh` (loaded from `input`, which names it in
    /// errors) with the chosen boundary condition, or reads the complex from the `--complex`
    /// folder.
    pub fn build(
        &self,
        catalog: &Catalog,
        mesh: &SurfaceMesh,
        input: &MeshInput,
    ) -> Result<BoxedComplex> {
        if let Some(dir) = &self.complex {
            let identity: Vec<usize> = (0..mesh.vertex_count()).collect();
            let original_vertex = input.original_vertex().unwrap_or(&identity);
            let complex = tvf_spectral::read_complex_folder(dir, mesh, original_vertex)
                .with_context(|| format!("--complex {} on {}", dir.display(), input.label()))?;
            return Ok(Box::new(complex));
        }
        catalog
            .build_complex(&self.id(mesh), Some(self.boundary_condition()), mesh)
            .with_context(|| input.label())
    }
}

/// Checks one flag's value against the catalog; the error says what the catalog offers.
type IdCheck = fn(&Catalog, &str) -> Result<(), String>;

/// Checks the discretization flags of the subcommand in `matches` against `catalog`:
/// `--discretization` must be an id of the catalog, `--decomposition` / `--mass` the first /
/// last part of one. The error is a usage error of the subcommand of `command` (exit code 2),
/// naming the flag and listing what the catalog offers.
pub fn check_ids(
    command: &mut clap::Command,
    matches: &ArgMatches,
    catalog: &Catalog,
) -> Result<(), clap::Error> {
    let Some((name, sub_matches)) = matches.subcommand() else {
        return Ok(());
    };
    let checks: [(&str, &str, IdCheck); 3] = [
        ("discretization", "--discretization <ID>", Catalog::check_id),
        (
            "decomposition",
            "--decomposition <NAME>",
            Catalog::check_decomposition_part,
        ),
        ("mass", "--mass <NAME>", Catalog::check_mass_part),
    ];
    for (id, flag, check) in checks {
        // A subcommand without the flag has no such argument: nothing to check.
        let Ok(Some(value)) = sub_matches.try_get_one::<String>(id) else {
            continue;
        };
        if let Err(problem) = check(catalog, value) {
            command.build();
            let message = format!("invalid value '{value}' for '{flag}': {problem}");
            return Err(match command.find_subcommand_mut(name) {
                Some(subcommand) => subcommand.error(ErrorKind::InvalidValue, message),
                None => command.error(ErrorKind::InvalidValue, message),
            });
        }
    }
    Ok(())
}

/// `id` with the suffix of intrinsic Delaunay `mode` (`+intrinsic-delaunay` or `-refine`), unless
/// `mode` is `None` or the id carries an intrinsic suffix of its own.
pub fn with_intrinsic_suffix(id: String, mode: Option<IntrinsicDelaunay>) -> String {
    match mode {
        Some(mode) if split_intrinsic_id(split_complex_id(&id).0).1.is_none() => {
            intrinsic_entry_id(&id, mode)
        }
        _ => id,
    }
}
