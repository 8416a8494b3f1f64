//! [`ReferenceCheck`]: the reference checks of [`crate::reference`] as values, the ones each
//! catalog entry opts into ([`catalog_reference_checks`], for both the test suite and
//! `tvf check`), and [`measure_reference`], which
//! measures a reference check on one complex and one mesh as [`CheckOutcome`]s (with numbers)
//! instead of asserting — for [`crate::property_runner`] and `tvf check`.

use crate::algebra_checks::max_abs;
use crate::capability_checks::measure_div_curl_formulas;
use crate::check_outcome::CheckOutcome;
use crate::galerkin_mass_checks::measure_galerkin_masses;
use crate::reference_formulas::explicit_stiffness;
use sprs::CsMat;
use tvf_core::discretization::sparse::{product, transpose};
use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator, NodeKind};
use tvf_core::TriangleMesh;

/// Relative tolerance of the explicit stiffness formulas (as [`crate::reference::cotan_formula`]).
pub const FORMULA_TOLERANCE: f64 = 1e-10;
/// Relative tolerance of `Jᵀ M1 J = M1` (as [`crate::reference::rotation`]).
pub const ROTATION_MASS_TOLERANCE: f64 = 1e-14;
/// Relative tolerance of `M1 = (A_t, A_t)` and of `1ᵀ M2⁻¹ 1 = area`.
pub const MASS_TOLERANCE: f64 = 1e-12;

/// A reference check of [`crate::reference`], grouped by what it compares: operators against
/// explicit formulas, masses against areas and integrals, then the rotation and the spectrum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferenceCheck {
    /// Both stiffness matrices equal their explicit formulas by node kind.
    CotanFormula,
    /// The potential stiffness equals its explicit formula.
    PotentialCotanFormula,
    /// Divergence and curl against explicit sums.
    DivCurlFormulas,
    /// `1ᵀ M2⁻¹ 1 = area`.
    CoPotentialMasses,
    /// Face fields with `M1 = (A_t, A_t)`.
    FaceFields,
    /// Every mass the Galerkin mass of what the complex samples.
    GalerkinMasses,
    /// `J² = −I` and `Jᵀ M1 J = M1`.
    Rotation,
    /// Convergence to `l(l+1)` on the unit icosphere (mesh-independent; asserted by the test
    /// suite only).
    SphereSpectrum,
}

impl ReferenceCheck {
    /// The name of the function in [`crate::reference`], e.g. `cotan_formula`.
    pub fn name(self) -> &'static str {
        match self {
            ReferenceCheck::CotanFormula => "cotan_formula",
            ReferenceCheck::PotentialCotanFormula => "potential_cotan_formula",
            ReferenceCheck::DivCurlFormulas => "div_curl_formulas",
            ReferenceCheck::CoPotentialMasses => "co_potential_masses",
            ReferenceCheck::FaceFields => "face_fields",
            ReferenceCheck::GalerkinMasses => "galerkin_masses",
            ReferenceCheck::Rotation => "rotation",
            ReferenceCheck::SphereSpectrum => "sphere_spectrum",
        }
    }
}

use ReferenceCheck::*;

const FINITE_ELEMENT_LUMPED: &[ReferenceCheck] = &[
    CotanFormula,
    Rotation,
    FaceFields,
    DivCurlFormulas,
    CoPotentialMasses,
    SphereSpectrum,
];
const FINITE_ELEMENT_CONSISTENT: &[ReferenceCheck] = &[
    CotanFormula,
    Rotation,
    FaceFields,
    DivCurlFormulas,
    CoPotentialMasses,
    GalerkinMasses,
    SphereSpectrum,
];
const DEC: &[ReferenceCheck] = &[CotanFormula, CoPotentialMasses, SphereSpectrum];
const WHITNEY_GALERKIN: &[ReferenceCheck] = &[
    PotentialCotanFormula,
    CoPotentialMasses,
    GalerkinMasses,
    SphereSpectrum,
];

/// The reference checks catalog entry `id` (or a complex id `{id}+{boundary}`) opts into, in
/// the order they run: the test suite's line of the entry ([`crate::catalog_suites!`], in
/// `conformance/tests/conformance/catalog_suites.rs`) runs them and `tvf check` measures them;
/// none for an id the catalog does not know.
pub fn catalog_reference_checks(id: &str) -> &'static [ReferenceCheck] {
    match tvf_discretizations::split_complex_id(id).0 {
        "conforming-barycentric"
        | "conforming-voronoi"
        | "nonconforming-barycentric"
        | "nonconforming-voronoi" => FINITE_ELEMENT_LUMPED,
        "conforming-consistent" | "nonconforming-consistent" => FINITE_ELEMENT_CONSISTENT,
        "dec-barycentric" | "dec-circumcentric" => DEC,
        "whitney-galerkin" => WHITNEY_GALERKIN,
        _ => &[],
    }
}

/// Measures `check` on `complex` built on `mesh`: one outcome per measured property, named
/// `{check}:{what}` (e.g. `rotation:J_squared`). The sphere spectrum, which does not depend on
/// the mesh, is asserted by the test suite only and reported as skipped.
pub fn measure_reference(
    check: ReferenceCheck,
    complex: &dyn HodgeComplex,
    mesh: &TriangleMesh,
) -> Vec<CheckOutcome> {
    match check {
        CotanFormula => vec![
            measure_stiffness_formula(check, "potential", complex, mesh),
            measure_stiffness_formula(check, "co-potential", complex, mesh),
        ],
        PotentialCotanFormula => vec![measure_stiffness_formula(check, "potential", complex, mesh)],
        Rotation => measure_rotation(complex),
        FaceFields => vec![measure_face_field_mass(complex, mesh)],
        CoPotentialMasses => {
            let total = complex.m2().inverse().total();
            let area = mesh.total_area();
            vec![CheckOutcome::at_most(
                "co_potential_masses",
                (total - area).abs() / area,
                MASS_TOLERANCE,
                format!("relative |Σ M2⁻¹ − area|: Σ M2⁻¹ = {total}, area {area}"),
            )]
        }
        DivCurlFormulas => measure_div_curl_formulas(complex, mesh),
        GalerkinMasses => measure_galerkin_masses(complex, mesh),
        SphereSpectrum => vec![CheckOutcome::skipped(
            check.name(),
            "mesh-independent (the unit icosphere): asserted by the test suite \
             (cargo test -p tvf-conformance), not measured here"
                .to_string(),
        )],
    }
}

/// `max |K − K_formula| / max |K_formula|` of the potential or co-potential stiffness.
fn measure_stiffness_formula(
    check: ReferenceCheck,
    which: &str,
    complex: &dyn HodgeComplex,
    mesh: &TriangleMesh,
) -> CheckOutcome {
    let name = format!("{}:{which}", check.name());
    let (nodes, stiffness) = if which == "potential" {
        (
            complex.potential_nodes(),
            LinearOperator::Sparse(complex.potential_stiffness().clone()),
        )
    } else {
        (
            complex.co_potential_nodes(),
            complex.co_potential_stiffness().clone(),
        )
    };
    let Some(expected) = explicit_stiffness(nodes.kind, mesh) else {
        return CheckOutcome::failed(
            name,
            format!("no explicit stiffness formula on {}", nodes.kind.name()),
        );
    };
    if stiffness.shape() != expected.shape() {
        return CheckOutcome::failed(
            name,
            format!(
                "{which} stiffness is {:?}, the formula {:?}",
                stiffness.shape(),
                expected.shape()
            ),
        );
    }
    let scale = max_abs(&expected);
    let error = match stiffness.as_sparse() {
        Some(sparse) => max_abs(&(&sparse.to_csr() - &expected.to_csr())),
        None => {
            let difference = &stiffness.to_dense() - &crate::dense::dense(&expected);
            crate::algebra_checks::max_abs_dense(&difference)
        }
    };
    CheckOutcome::at_most(
        name,
        error / scale,
        FORMULA_TOLERANCE,
        format!(
            "relative max |K − K_formula| of the {which} stiffness against the {} formula",
            nodes.kind.name()
        ),
    )
}

/// `J² = −I` (max entry error, exact) and `Jᵀ M1 J = M1` (relative).
fn measure_rotation(complex: &dyn HodgeComplex) -> Vec<CheckOutcome> {
    let Some(rotation) = complex.rotation() else {
        return vec![CheckOutcome::failed(
            "rotation",
            "the complex has no rotation J".to_string(),
        )];
    };
    let j = rotation.rotation();
    let n = complex.field_dimension();
    if j.shape() != (n, n) {
        return vec![CheckOutcome::failed(
            "rotation",
            format!("J is {:?}, not {n} × {n}", j.shape()),
        )];
    }
    let identity = CsMat::<f64>::eye(n);
    let j2_plus_i = &product(j, j).to_csr() + &identity;
    let mut outcomes = vec![CheckOutcome::at_most(
        "rotation:J_squared",
        max_abs(&j2_plus_i),
        0.0,
        "max |J² + I| (J² = −I exactly)".to_string(),
    )];
    match complex.m1().sparse_matrix() {
        Some(m1) => {
            let jt_m1_j = product(&transpose(j), &product(&m1, j));
            let error = max_abs(&(&jt_m1_j.to_csr() - &m1.to_csr()));
            outcomes.push(CheckOutcome::at_most(
                "rotation:preserves_M1",
                error / max_abs(&m1),
                ROTATION_MASS_TOLERANCE,
                "relative max |Jᵀ M1 J − M1|".to_string(),
            ));
        }
        None => outcomes.push(CheckOutcome::failed(
            "rotation:preserves_M1",
            "M1 is not stored directly".to_string(),
        )),
    }
    outcomes
}

/// `M1 = (A_t, A_t)` per face, zero off the diagonal: max relative deviation.
fn measure_face_field_mass(complex: &dyn HodgeComplex, mesh: &TriangleMesh) -> CheckOutcome {
    let name = "face_fields:M1_is_face_areas";
    if complex.field_nodes().kind != NodeKind::FaceFrames
        || complex.field_dimension() != 2 * mesh.face_count()
    {
        return CheckOutcome::failed(name, "the fields are not face frames (n1 ≠ 2F)".into());
    }
    let Some(m1) = complex.m1().sparse_matrix() else {
        return CheckOutcome::failed(name, "M1 is not stored directly".to_string());
    };
    let mut diagonal = vec![0.0; m1.rows()];
    let mut worst: f64 = 0.0;
    for (&value, (i, j)) in m1.iter() {
        let area = mesh.face_area(i / 2);
        if i == j {
            diagonal[i] += value;
        } else {
            worst = worst.max(value.abs() / area);
        }
    }
    for (i, &value) in diagonal.iter().enumerate() {
        let area = mesh.face_area(i / 2);
        worst = worst.max((value - area).abs() / area);
    }
    CheckOutcome::at_most(
        name,
        worst,
        MASS_TOLERANCE,
        "max relative deviation of M1 from (A_t, A_t) per face".to_string(),
    )
}
