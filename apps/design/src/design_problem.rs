//! [`DesignProblem`]: a mesh and the constraint file designed on it, as `tvf spline` and `tvf
//! design` run them: the file loaded with its mesh fingerprint checked, its constraints
//! compiled for a discretization, the spline or soft design solved and every solved field
//! checked for non-finite values. Errors name the constraint file ([`DesignRunError`]).

use crate::design_report::ResidualReport;
use crate::regularization::default_regularization;
use crate::solution_check::checked_residuals;
use crate::timed_full_design::{timed_full_design, TimedFullDesign};
use crate::timed_reduced_solve::{timed_reduced_design, timed_spline, TimedReducedSolve};
use crate::{
    CompiledConstraint, ConstraintAssembler, ConstraintError, ConstraintFileError, ConstraintSet,
    DesignError, ReducedBasis, SoftOptions,
};
use serde::Serialize;
use std::path::{Path, PathBuf};
use thiserror::Error;
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;
use tvf_solvers::{FactorParallelism, FillOrdering};

/// A mesh and a constraint set that belongs to it.
#[derive(Debug, Clone)]
pub struct DesignProblem {
    /// The mesh.
    pub mesh: SurfaceMesh,
    /// How reports name the mesh (its file, or `example:NAME`).
    pub mesh_label: String,
    /// The constraint set (its mesh fingerprint, if any, matches the mesh).
    pub set: ConstraintSet,
    /// The constraint file (named in errors and reports).
    pub constraints_path: PathBuf,
}

/// A failed step of a design run; every error but an unreadable file names the constraint
/// file first (the file's own errors name it already).
#[derive(Debug, Error)]
pub enum DesignRunError {
    /// The constraint file cannot be read, is invalid or belongs to another mesh.
    #[error(transparent)]
    File(#[from] ConstraintFileError),
    /// A constraint cannot be turned into rows of the discretization.
    #[error("{}", path.display())]
    Constraint {
        /// The constraint file.
        path: PathBuf,
        /// What is wrong with the constraint.
        #[source]
        source: ConstraintError,
    },
    /// A solve failed, or its field or a residual is not finite.
    #[error("{}", path.display())]
    Solve {
        /// The constraint file.
        path: PathBuf,
        /// What failed.
        #[source]
        source: DesignError,
    },
    /// The full soft-design system could not be built or factored.
    #[error(
        "{}: the full soft-design system (omega {omega:e}) cannot be factored",
        path.display()
    )]
    Factor {
        /// The constraint file.
        path: PathBuf,
        /// The file's smoothness weight.
        omega: f64,
        /// What failed.
        #[source]
        source: DesignError,
    },
    /// The full solve stopped above its target and above the rounding floor of its field.
    #[error(
        "{}: the full solve reached only a relative residual of {residual:.1e} (the rounding \
         floor of an f64 field is {rounding_floor:.1e})",
        path.display()
    )]
    Inaccurate {
        /// The constraint file.
        path: PathBuf,
        /// The final relative residual.
        residual: f64,
        /// The rounding floor of the field.
        rounding_floor: f64,
    },
}

/// What was loaded, for the report. Serialized as `mesh`, `faces`, `genus`,
/// `constraints_file` and `omega`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProblemSummary {
    /// The mesh's label.
    pub mesh: String,
    /// Faces of the mesh.
    pub faces: usize,
    /// Genus of the mesh (summed over its components).
    pub genus: usize,
    /// The constraint file.
    pub constraints_file: String,
    /// The smoothness weight of the file.
    pub omega: f64,
    /// How many constraints the file holds.
    #[serde(skip)]
    pub constraints: usize,
}

impl ProblemSummary {
    /// One line on the mesh, one on the constraints.
    pub fn lines(&self) -> Vec<String> {
        vec![
            format!(
                "mesh            {} ({} faces, genus {})",
                self.mesh, self.faces, self.genus
            ),
            format!(
                "constraints     {} from {} (omega {})",
                self.constraints, self.constraints_file, self.omega
            ),
        ]
    }
}

impl DesignProblem {
    /// Loads the constraint file `constraints_path` for `mesh` (called `mesh_label` in
    /// reports), checking the file's mesh fingerprint if it has one.
    pub fn load(
        mesh: SurfaceMesh,
        mesh_label: impl Into<String>,
        constraints_path: &Path,
    ) -> Result<Self, ConstraintFileError> {
        let set = ConstraintSet::load(constraints_path)?;
        set.check_fingerprint(&format!("{:016x}", mesh.fingerprint()), constraints_path)?;
        Ok(Self {
            mesh,
            mesh_label: mesh_label.into(),
            set,
            constraints_path: constraints_path.to_path_buf(),
        })
    }

    /// The mesh's size and genus and the constraint file's count and weight.
    pub fn summary(&self) -> ProblemSummary {
        ProblemSummary {
            mesh: self.mesh_label.clone(),
            faces: self.mesh.face_count(),
            genus: self.mesh.genus(),
            constraints_file: self.constraints_path.display().to_string(),
            omega: self.set.omega,
            constraints: self.set.constraints.len(),
        }
    }

    /// The set's constraints compiled for `complex` (built on the problem's mesh).
    pub fn compile<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
    ) -> Result<Vec<CompiledConstraint>, DesignRunError> {
        ConstraintAssembler::new(complex, &self.mesh)
            .compile_all(&self.set.constraints)
            .map_err(|source| DesignRunError::Constraint {
                path: self.constraints_path.clone(),
                source,
            })
    }

    /// The residuals of the solved `field`; an error when the field or a residual is NaN or
    /// infinite (see [`checked_residuals`]).
    pub fn residuals(
        &self,
        field: &[f64],
        constraints: &[CompiledConstraint],
    ) -> Result<ResidualReport, DesignRunError> {
        let residuals = checked_residuals(field, constraints, self.set.omega)
            .map_err(|source| self.solve_error(source))?;
        Ok(ResidualReport::new(residuals))
    }

    /// The vector spline through `constraints` in `basis` (hard constraints, the set's
    /// `omega`), timed.
    pub fn spline(
        &self,
        basis: &ReducedBasis,
        constraints: &[CompiledConstraint],
    ) -> Result<TimedReducedSolve, DesignRunError> {
        timed_spline(basis, self.set.omega, constraints).map_err(|source| self.solve_error(source))
    }

    /// The reduced soft design with `constraints` in `basis`, with the set's `omega` and the
    /// [`default_regularization`] of `complex` (the discretization of the basis), timed.
    pub fn reduced_design<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
        basis: &ReducedBasis,
        constraints: &[CompiledConstraint],
    ) -> Result<TimedReducedSolve, DesignRunError> {
        let options = SoftOptions {
            omega: self.set.omega,
            regularization: default_regularization(complex),
        };
        timed_reduced_design(basis, options, constraints).map_err(|source| self.solve_error(source))
    }

    /// The full soft design of `complex` with `constraints`, timed ([`timed_full_design`]).
    pub fn full_design<H: HodgeComplex + ?Sized>(
        &self,
        complex: &H,
        constraints: Vec<CompiledConstraint>,
        ordering: FillOrdering,
        parallelism: FactorParallelism,
    ) -> Result<TimedFullDesign, DesignRunError> {
        let omega = self.set.omega;
        timed_full_design(complex, omega, constraints, ordering, parallelism).map_err(|source| {
            DesignRunError::Factor {
                path: self.constraints_path.clone(),
                omega,
                source,
            }
        })
    }

    /// [`TimedFullDesign::accuracy_note`], its failure an error naming the constraint file.
    pub fn accuracy_note(
        &self,
        solved: &TimedFullDesign,
    ) -> Result<Option<String>, DesignRunError> {
        solved
            .accuracy_note()
            .map_err(|report| DesignRunError::Inaccurate {
                path: self.constraints_path.clone(),
                residual: report.final_residual(),
                rounding_floor: report.rounding_floor,
            })
    }

    fn solve_error(&self, source: DesignError) -> DesignRunError {
        DesignRunError::Solve {
            path: self.constraints_path.clone(),
            source,
        }
    }
}
