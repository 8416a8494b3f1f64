//! A constraint set checked against the mesh and the discretization it will be used with
//! ([`ConstraintSet::compile_for`], [`ConstraintSet::check_for`], [`ConstraintSet::load_for`]): its mesh fingerprint, if it
//! gives one, and every constraint compiled (indices in range, node kinds that fit, values
//! finite), before any expensive work (a basis, a picture) starts.

use crate::assembler::ConstraintAssembler;
use crate::constraint_file::ConstraintSet;
use crate::error::ConstraintFileError;
use crate::CompiledConstraint;
use std::path::Path;
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;

impl ConstraintSet {
    /// Loads the constraint file `path` ([`ConstraintSet::load`]) and checks it against `mesh`
    /// and `complex` ([`ConstraintSet::check_for`]).
    pub fn load_for<H: HodgeComplex + ?Sized>(
        path: &Path,
        mesh: &SurfaceMesh,
        complex: &H,
    ) -> Result<Self, ConstraintFileError> {
        let set = Self::load(path)?;
        set.check_for(path, mesh, complex)?;
        Ok(set)
    }

    /// Checks the set (read from `origin`) against `mesh` and `complex` (built on `mesh`):
    /// [`ConstraintSet::compile_for`] without keeping the compiled constraints.
    pub fn check_for<H: HodgeComplex + ?Sized>(
        &self,
        origin: &Path,
        mesh: &SurfaceMesh,
        complex: &H,
    ) -> Result<(), ConstraintFileError> {
        self.compile_for(origin, mesh, complex).map(|_| ())
    }

    /// The set (read from `origin`) checked against `mesh` and `complex` (built on `mesh`) and
    /// compiled: the file's fingerprint ([`ConstraintSet::check_fingerprint`]), then every
    /// constraint as a spline or design uses it ([`ConstraintAssembler::compile_all`]). Errors
    /// name the file and, for a constraint, its id.
    pub fn compile_for<H: HodgeComplex + ?Sized>(
        &self,
        origin: &Path,
        mesh: &SurfaceMesh,
        complex: &H,
    ) -> Result<Vec<CompiledConstraint>, ConstraintFileError> {
        self.check_fingerprint(&format!("{:016x}", mesh.fingerprint()), origin)?;
        ConstraintAssembler::new(complex, mesh)
            .compile_all(&self.constraints)
            .map_err(|source| ConstraintFileError::Invalid {
                path: origin.to_path_buf(),
                source,
            })
    }
}
