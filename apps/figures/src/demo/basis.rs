//! Demo step 1: the mesh and its Fourier basis (harmonic fields and the lowest eigenfield pairs).

use super::page::Section;
use super::DemoConfig;
use super::DemoHost;
use crate::error::FigureError;
use tvf_core::discretization::HodgeComplex;
use tvf_discretizations::BoxedComplex;
use tvf_render::save_png;
use tvf_render::{draw_field, FaceQuantity, Overlays, Style, Tint, View};
use tvf_spectral::{eigen_residual, BasisSize, FieldFamily, SpectralBasis};

/// Builds the chosen discretization, computes the basis and draws the mesh.
pub fn run(
    config: &DemoConfig,
    host: &dyn DemoHost,
) -> Result<(Section, BoxedComplex, SpectralBasis), FigureError> {
    let mesh = &config.mesh;
    let discretization = config
        .catalog
        .build_complex(&config.discretization, None, mesh)
        .map_err(|e| FigureError::InContext {
            context: config.mesh_name.clone(),
            source: Box::new(e.into()),
        })?;
    let basis = host.compute_basis(&discretization, BasisSize::Fields(config.fields))?;
    let fewest = basis
        .count(FieldFamily::Integrable)
        .min(basis.count(FieldFamily::Cointegrable));
    if fewest < 3 {
        return Err(FigureError::Invalid(format!(
            "-k {}: the basis holds only {fewest} fields of one family; the demo shows three \
             pairs, ask for more eigenfields",
            config.fields
        )));
    }
    let mut section = Section::new(
        "Mesh and Fourier basis",
        "The surface and its Fourier basis of tangent fields (Section 6): the 2g harmonic fields \
         and the lowest eigenfields of the potential (integrable, curl-free) and co-potential \
         (co-integrable, divergence-free) Laplacians, M_X-orthonormal, sorted by eigenvalue.",
    );
    let view = View {
        width: config.width,
        height: config.height,
        yaw: 30.0,
        pitch: 35.0,
        zoom: 1.0,
    };
    let overlays = Overlays {
        title: Some(format!(
            "{} ({} faces)",
            config.mesh_name,
            mesh.face_count()
        )),
        ..Default::default()
    };
    let image = draw_field(
        mesh,
        discretization.as_ref(),
        None,
        Tint::Quantity(FaceQuantity::None),
        Style::None,
        overlays,
        view,
    )?;
    save_png(&image, &config.output.join("mesh.png"))?;
    section.figure("mesh.png", "The mesh, shaded.");

    add_basis_numbers(&mut section, discretization.as_ref(), &basis);
    Ok((section, discretization, basis))
}

/// The basis's counts, eigenvalue range, worst eigen residual, harmonic orthonormality and
/// computation cost, as numbers of the `section`.
fn add_basis_numbers(section: &mut Section, complex: &dyn HodgeComplex, basis: &SpectralBasis) {
    let report = basis.report().cloned().unwrap_or_default();
    let worst_residual = (0..basis.len())
        .map(|j| {
            let u: Vec<f64> = basis.fields().col(j).iter().copied().collect();
            let lambda = basis.eigenvalues()[j];
            eigen_residual(complex, lambda, &u) / lambda.max(1.0)
        })
        .fold(0.0, f64::max);
    let eigenvalues = basis.eigenvalues();
    section.number("basis fields", basis.len().to_string());
    section.number(
        "harmonic / integrable / co-integrable",
        format!(
            "{} / {} / {}",
            basis.count(FieldFamily::Harmonic),
            basis.count(FieldFamily::Integrable),
            basis.count(FieldFamily::Cointegrable)
        ),
    );
    section.number(
        "eigenvalue range",
        format!(
            "{:.4} … {:.2}",
            eigenvalues
                .iter()
                .copied()
                .find(|&l| l > 1e-9)
                .unwrap_or(0.0),
            eigenvalues.last().copied().unwrap_or(0.0)
        ),
    );
    section.number("max ‖Lu − λu‖ / max(1, λ)", format!("{worst_residual:.2e}"));
    section.number(
        "harmonic fields: orthonormality error",
        format!("{:.2e}", report.harmonic_orthonormality_error),
    );
    section.number(
        "basis computation",
        format!(
            "{:.2} s ({} factorizations, {} solves)",
            report.seconds, report.factorizations, report.solves
        ),
    );
}
