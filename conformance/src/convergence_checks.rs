//! Convergence as a property: the lowest eigenvalues of both families on refinement sequences of
//! the unit sphere and the unit hemisphere ([`crate::accuracy_meshes::Sequence`], regular and
//! jittered) against their exact values, with the observed order of the relative error.
//!
//! `convergence:{sequence}:{family}` asserts that the largest relative error `|λ_h − λ| / λ` of
//! the lowest [`SPHERE_EIGENVALUES`] (sphere) or [`HEMISPHERE_EIGENVALUES`] (hemisphere)
//! nonzero eigenvalues of the family decreases like `h^p` with an observed order
//! `p ≥` [`LEAST_ORDER`] (the least-squares slope of `log error` against `log h` over the finer
//! levels, [`fitted_order`]); the detail is the table of errors, faces and mean edge lengths per
//! level. Integrable eigenvalues are those of the potential pencil `(d0ᵀ M1 d0, M0)`,
//! co-integrable ones those of the co-potential pencil `(d1 M1⁻¹ d1ᵀ, M2⁻¹)` (Lemma 1), both on
//! the free nodes, the lowest of them by the sparse eigensolver
//! ([`crate::lowest_eigenvalues`]), their kernels (the constants of a space without Dirichlet
//! nodes) left out.
//!
//! On the sphere every eigenvalue `l(l+1)` of the Laplace–Beltrami operator appears `2l + 1`
//! times in each family. On the hemisphere a family whose space pins its values on the boundary
//! (no constants in its kernel: Dirichlet) has the spherical harmonics odd across the equator,
//! `l` per degree, the other family the even ones, `l + 1` per degree: whichever boundary
//! condition the complex imposes, its spaces say which family is which.

use crate::accuracy_meshes::{Sequence, LEVELS};
use crate::check_outcome::CheckOutcome;
use crate::lowest_eigenvalues::lowest_free_eigenvalues;
use crate::property_runner::SurfaceBuilder;
use tvf_core::discretization::{Eigenproblem, HodgeOperators, NodeSpace};
use tvf_core::geometry::{norm, sub};
use tvf_core::mesh::Mesh;

/// The least observed order of convergence accepted (consistent discretizations of the
/// Hodge–Laplacian reach 2 on these sequences; an inconsistent one stalls near 0).
pub const LEAST_ORDER: f64 = 1.5;

/// Eigenvalues compared per family on the sphere: degrees 1 and 2 (3 + 5).
pub const SPHERE_EIGENVALUES: usize = 8;

/// Eigenvalues compared per family on the hemisphere: the lowest five (degrees 1–2 of the even
/// harmonics, degrees 1–3 but one of the odd ones).
pub const HEMISPHERE_EIGENVALUES: usize = 5;

/// The lowest `count` nonzero Laplace–Beltrami eigenvalues `l(l+1)`, ascending, with
/// multiplicities: of the unit sphere (`dirichlet = None`, `2l + 1` per degree) or of the upper
/// unit hemisphere with Dirichlet (`Some(true)`, `l` per degree) or Neumann (`Some(false)`,
/// `l + 1` per degree) boundary values.
pub fn spherical_eigenvalues(dirichlet: Option<bool>, count: usize) -> Vec<f64> {
    let per_degree = |l: usize| match dirichlet {
        None => 2 * l + 1,
        Some(true) => l,
        Some(false) => l + 1,
    };
    (1..)
        .flat_map(|l| std::iter::repeat_n((l * (l + 1)) as f64, per_degree(l)))
        .take(count)
        .collect()
}

/// The least-squares slope of `log e` against `log h` (the coarsest point dropped when there
/// are three or more: it is furthest from the asymptotic regime); NaN with fewer than two
/// usable points (an error of exactly zero has no logarithm).
pub fn fitted_order(points: &[(f64, f64)]) -> f64 {
    let skip = usize::from(points.len() >= 3);
    let logs: Vec<(f64, f64)> = points[skip..]
        .iter()
        .filter(|(h, e)| *h > 0.0 && *e > 0.0)
        .map(|(h, e)| (h.ln(), e.ln()))
        .collect();
    if logs.len() < 2 {
        return f64::NAN;
    }
    let n = logs.len() as f64;
    let (mx, my) = (
        logs.iter().map(|p| p.0).sum::<f64>() / n,
        logs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// Mean edge length of `mesh`.
pub fn mean_edge_length<M: Mesh + ?Sized>(mesh: &M) -> f64 {
    let p = mesh.positions();
    let total: f64 = mesh
        .topology()
        .edges()
        .iter()
        .map(|&[a, b]| norm(sub(p[a], p[b])))
        .sum();
    total / mesh.edge_count().max(1) as f64
}

/// One level of a sequence: faces, mean edge length and the error of each family
/// (integrable, co-integrable).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelErrors {
    /// Faces of the mesh.
    pub faces: usize,
    /// Mean edge length.
    pub h: f64,
    /// Largest relative eigenvalue error of the integrable and of the co-integrable family.
    pub errors: [f64; 2],
}

/// The largest relative error of the lowest `count` nonzero eigenvalues of one scalar pencil of
/// a complex on the sphere (`closed`) or the hemisphere.
fn family_error(
    problem: &Eigenproblem,
    nodes: &NodeSpace,
    field_nodes: &NodeSpace,
    closed: bool,
    count: usize,
) -> Result<f64, String> {
    let kernel = nodes.kernel_dimension();
    let values = lowest_free_eigenvalues(problem, nodes, field_nodes, kernel + count)?;
    let dirichlet = (!closed).then(|| nodes.constant_kernel.iter().any(|&k| !k));
    let exact = spherical_eigenvalues(dirichlet, count);
    let computed = values
        .get(kernel..kernel + count)
        .ok_or_else(|| format!("the pencil has {} eigenvalues", values.len()))?;
    let error = computed
        .iter()
        .zip(&exact)
        .map(|(c, e)| (c - e).abs() / e)
        .fold(0.0, f64::max);
    if error.is_finite() {
        Ok(error)
    } else {
        Err(format!("a relative eigenvalue error is {error}"))
    }
}

/// The errors of both families of the complex `builder` makes on level `level` of `sequence`.
pub fn level_errors(
    builder: SurfaceBuilder,
    sequence: Sequence,
    level: u32,
) -> Result<LevelErrors, String> {
    let mesh = sequence.mesh(level)?;
    let complex = builder(&mesh).map_err(|e| format!("construction failed: {e}"))?;
    let closed = !sequence.has_boundary();
    let count = if closed {
        SPHERE_EIGENVALUES
    } else {
        HEMISPHERE_EIGENVALUES
    };
    let integrable = family_error(
        &complex.exact_eigenproblem(),
        complex.potential_nodes(),
        complex.field_nodes(),
        closed,
        count,
    )?;
    let cointegrable = family_error(
        &complex.co_exact_eigenproblem(),
        complex.co_potential_nodes(),
        complex.field_nodes(),
        closed,
        count,
    )?;
    Ok(LevelErrors {
        faces: mesh.face_count(),
        h: mean_edge_length(&mesh),
        errors: [integrable, cointegrable],
    })
}

/// The names of the two outcomes of `sequence`.
pub fn convergence_names(sequence: Sequence) -> [String; 2] {
    ["integrable", "cointegrable"].map(|family| format!("convergence:{}:{family}", sequence.name()))
}

/// The two outcomes (integrable, co-integrable) of the complexes `builder` makes on the levels
/// [`LEVELS`] of `sequence` (see the module documentation); a level that fails to build or to
/// solve fails both, naming the level.
pub fn measure_convergence(builder: SurfaceBuilder, sequence: Sequence) -> Vec<CheckOutcome> {
    let names = convergence_names(sequence);
    let mut levels = Vec::new();
    for level in LEVELS {
        match level_errors(builder, sequence, level) {
            Ok(errors) => levels.push(errors),
            Err(reason) => {
                return names
                    .into_iter()
                    .map(|name| CheckOutcome::failed(name, format!("level {level}: {reason}")))
                    .collect()
            }
        }
    }
    names
        .into_iter()
        .enumerate()
        .map(|(family, name)| {
            let points: Vec<(f64, f64)> = levels.iter().map(|l| (l.h, l.errors[family])).collect();
            let table: Vec<String> = levels
                .iter()
                .map(|l| format!("{:.2e} ({} faces, h {:.3})", l.errors[family], l.faces, l.h))
                .collect();
            CheckOutcome::at_least(
                name,
                fitted_order(&points),
                LEAST_ORDER,
                format!(
                    "observed order of the relative error of the lowest eigenvalues: {}",
                    table.join(", ")
                ),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_spectra_have_the_right_multiplicities() {
        let sphere = spherical_eigenvalues(None, 15);
        assert_eq!(&sphere[..4], &[2.0, 2.0, 2.0, 6.0]);
        assert_eq!(sphere[14], 12.0);
        assert_eq!(
            spherical_eigenvalues(Some(false), 5),
            vec![2.0, 2.0, 6.0, 6.0, 6.0]
        );
        assert_eq!(
            spherical_eigenvalues(Some(true), 6),
            vec![2.0, 6.0, 6.0, 12.0, 12.0, 12.0]
        );
    }

    #[test]
    fn fitted_orders_follow_the_slope() {
        let points: Vec<(f64, f64)> = [0.4, 0.2, 0.1, 0.05]
            .iter()
            .map(|&h: &f64| (h, 3.0 * h * h * (1.0 + if h > 0.3 { 0.5 } else { 0.0 })))
            .collect();
        assert!((fitted_order(&points) - 2.0).abs() < 1e-12);
        assert!(fitted_order(&points[..1]).is_nan());
    }
}
