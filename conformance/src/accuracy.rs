//! The accuracy checks: what the core checks (structure: symmetric, semi-definite, the right
//! kernel, orthonormal bases) cannot see — whether the discretization approximates the smooth
//! operators. Any builder of complexes runs them (a catalog entry, a crate's own, a Python
//! builder): `tvf check`, the Python package's `tvf.check` and the suite macros
//! ([`crate::conformance_suite!`]) run them by default.
//!
//! - **Consistency** ([`crate::consistency_checks`]): on a closed box of six flat, jittered
//!   patches and on a jittered sphere (curved), the gradient of a linear function sampled
//!   exactly, both patch tests (the stiffness of each nodal space annihilates linear functions
//!   inside flat faces) and the energy of a linear function exact.
//! - **Convergence** ([`crate::convergence_checks`]): the lowest eigenvalues of both families on
//!   the unit sphere and hemisphere, regular and jittered refinement sequences
//!   ([`crate::accuracy_meshes::Sequence`]), with an observed order of at least
//!   [`crate::convergence_checks::LEAST_ORDER`].
//!
//! A check that needs what the complex lacks (sampling, nodal values, a builder for meshes with
//! boundary) is reported as not applicable with the reason; a check on one mesh given as
//! matrices ([`consistency_on_mesh`]) has only that mesh.

use crate::accuracy_meshes::{curved_sphere, deep_inside_a_box_face, flat_box, Sequence};
use crate::check_outcome::CheckOutcome;
use crate::check_report::CheckReport;
use crate::consistency_checks::measure_consistency;
use crate::convergence_checks::{convergence_names, measure_convergence};
use crate::property_runner::{catch_check_panic, SurfaceBuilder, PANIC};
use tvf_core::discretization::HodgeComplex;
use tvf_core::SurfaceMesh;

/// How far inside a box face (in units of the box's half edge) a node must lie for the patch
/// tests: two and a half grid spacings of the box, so that every node a stiffness row couples
/// to lies in the same plane.
pub const PATCH_MARGIN: f64 = 2.5 * 2.0 / crate::accuracy_meshes::BOX_CELLS as f64;

/// Seed of the jitter of the flat box.
const BOX_SEED: u64 = 5;

/// What an accuracy run covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AccuracyRequest {
    /// Run on triangle meshes (the flat box of triangles, the curved sphere, the triangle
    /// sequences).
    pub triangles: bool,
    /// Run on polygon meshes too (the flat box of quads, the quad-sphere sequences): for
    /// builders that accept polygons.
    pub polygons: bool,
    /// Whether the builder builds on meshes with boundary (the hemisphere sequences); without,
    /// they are reported as not applicable.
    pub open_meshes: bool,
}

impl AccuracyRequest {
    /// Triangle meshes, with boundary too, and polygon meshes if `polygons`.
    pub fn new(polygons: bool) -> Self {
        Self {
            triangles: true,
            polygons,
            open_meshes: true,
        }
    }
}

/// Runs `measure`, a panic turned into one failed outcome named [`PANIC`] (a [`StopRun`](crate::property_runner::StopRun) unwinds
/// on).
fn guarded(what: &str, measure: impl FnOnce() -> Vec<CheckOutcome>) -> Vec<CheckOutcome> {
    catch_check_panic(measure)
        .unwrap_or_else(|message| vec![CheckOutcome::failed(PANIC, format!("{what}: {message}"))])
}

/// The consistency checks on the patch `patch` (`mesh`), the patch tests inside the box's faces
/// if `flat`.
fn consistency_on(
    builder: SurfaceBuilder,
    patch: &str,
    mesh: &SurfaceMesh,
    flat: bool,
) -> Vec<CheckOutcome> {
    guarded(patch, || match builder(mesh) {
        Ok(complex) => {
            let inside = |p: [f64; 3]| deep_inside_a_box_face(p, PATCH_MARGIN);
            let flat_inside: Option<&dyn Fn([f64; 3]) -> bool> = flat.then_some(&inside);
            measure_consistency(complex.as_ref(), patch, mesh, flat_inside)
        }
        Err(error) => vec![CheckOutcome::failed(
            format!("consistency:construction:{patch}"),
            error,
        )],
    })
}

/// The convergence outcomes of `sequence`, or not applicable on a hemisphere without
/// `open_meshes`.
fn convergence_on(
    builder: SurfaceBuilder,
    sequence: Sequence,
    open_meshes: bool,
) -> Vec<CheckOutcome> {
    if sequence.has_boundary() && !open_meshes {
        return convergence_names(sequence)
            .into_iter()
            .map(|name| {
                CheckOutcome::not_applicable(
                    name,
                    "the builder is checked on closed meshes only".to_string(),
                )
            })
            .collect();
    }
    guarded(sequence.name(), || measure_convergence(builder, sequence))
}

/// Every accuracy check `request` asks for, of the complexes `builder` makes.
pub fn accuracy_report(builder: SurfaceBuilder, request: &AccuracyRequest) -> CheckReport {
    let mut outcomes = Vec::new();
    if request.triangles {
        outcomes.extend(consistency_on(
            builder,
            "flat box",
            &flat_box(false, BOX_SEED),
            true,
        ));
        outcomes.extend(consistency_on(
            builder,
            "curved sphere",
            &curved_sphere().into(),
            false,
        ));
        for sequence in Sequence::TRIANGLES {
            outcomes.extend(convergence_on(builder, sequence, request.open_meshes));
        }
    }
    if request.polygons {
        outcomes.extend(consistency_on(
            builder,
            "flat quad box",
            &flat_box(true, BOX_SEED),
            true,
        ));
        for sequence in Sequence::QUADS {
            outcomes.extend(convergence_on(builder, sequence, request.open_meshes));
        }
    }
    CheckReport { outcomes }
}

/// The consistency checks that need no other mesh, on the complex of one mesh (`tvf check`
/// with a folder of matrices, or any checked mesh): the gradient and the energy of a linear
/// function on `mesh`, a curved patch.
pub fn consistency_on_mesh(complex: &dyn HodgeComplex, mesh: &SurfaceMesh) -> Vec<CheckOutcome> {
    guarded("the checked mesh", || {
        measure_consistency(complex, "checked mesh", mesh, None)
    })
}

/// The convergence checks reported as not applicable: a complex given as the matrices of one
/// mesh cannot be built on the refinement sequences.
pub fn convergence_not_applicable(reason: &str) -> Vec<CheckOutcome> {
    Sequence::TRIANGLES
        .into_iter()
        .flat_map(convergence_names)
        .map(|name| CheckOutcome::not_applicable(name, reason.to_string()))
        .collect()
}
