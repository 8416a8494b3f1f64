//! [`SampledComplex`]: a complex's parts with the sampling and point evaluation it offers — the
//! one type behind the complexes of primal forms: [`crate::PrimalFormComplex`] (DEC and Whitney
//! forms on a triangle mesh), [`crate::PolygonDec`] (polygonal DEC) and
//! [`crate::IntrinsicPrimalFormComplex`] (DEC and Whitney forms on an intrinsic triangulation).
//! Each of those is this type with its own sampling `S` and evaluation `E` and assembles its
//! parts in a constructor of its own (which ends in [`SampledComplex::from_parts`]); the
//! [`HodgeComplex`] they share is written here once.

use std::marker::PhantomData;
use std::sync::Arc;
use tvf_core::discretization::{ComplexParts, FieldSampling, HodgeComplex, PointEvaluation};
use tvf_core::intrinsic::IntrinsicTriangulation;

/// A Hodge complex given by its checked [`ComplexParts`], the [`FieldSampling`] `S` of its
/// fields, the [`PointEvaluation`] `E` of its potentials and co-potentials, and, for a complex
/// built on an intrinsic triangulation, that triangulation
/// ([`HodgeComplex::intrinsic_triangulation`]). It has no rotation `J` (1-forms have none).
///
/// `M` is a marker that tells apart complexes with the same sampling and evaluation but other
/// masses ([`crate::HodgeStars`] for DEC, [`crate::GalerkinMasses`] for Whitney forms; the
/// masses themselves are in the parts); `()` where there is one kind only.
#[derive(Debug, Clone)]
pub struct SampledComplex<S, E, M = ()> {
    parts: ComplexParts,
    sampling: S,
    evaluation: E,
    triangulation: Option<Arc<IntrinsicTriangulation>>,
    masses: PhantomData<M>,
}

impl<S, E, M> SampledComplex<S, E, M> {
    /// The complex of `parts` on the mesh they were built on, sampled by `sampling` and
    /// evaluated by `evaluation` (both on that mesh's faces).
    pub fn from_parts(parts: ComplexParts, sampling: S, evaluation: E) -> Self {
        Self {
            parts,
            sampling,
            evaluation,
            triangulation: None,
            masses: PhantomData,
        }
    }

    /// The complex of `parts` built on the intrinsic triangulation `triangulation` (its nodes
    /// are the triangulation's vertices, edges and faces), sampled by `sampling` and evaluated by
    /// `evaluation` at points of the input mesh's faces.
    pub fn from_intrinsic_parts(
        parts: ComplexParts,
        sampling: S,
        evaluation: E,
        triangulation: Arc<IntrinsicTriangulation>,
    ) -> Self {
        Self {
            triangulation: Some(triangulation),
            ..Self::from_parts(parts, sampling, evaluation)
        }
    }
}

impl<S, E, M> HodgeComplex for SampledComplex<S, E, M>
where
    S: FieldSampling,
    E: PointEvaluation,
    M: Send + Sync,
{
    fn parts(&self) -> &ComplexParts {
        &self.parts
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        Some(&self.sampling)
    }

    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        Some(&self.evaluation)
    }

    fn intrinsic_triangulation(&self) -> Option<&IntrinsicTriangulation> {
        self.triangulation.as_deref()
    }
}
