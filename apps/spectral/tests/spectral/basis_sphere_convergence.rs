//! On icospheres of increasing resolution the lowest eigenvalues of the field Laplacian approach
//! `l(l+1)` with multiplicity `2(2l+1)` (gradient and co-gradient families), for both
//! decompositions, and the error shrinks with every refinement.
//!
//! Run with `--nocapture` to see the table.

use tvf_core::discretization::HodgeComplex;
use tvf_core::generate::icosphere;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};
use tvf_spectral::{compute_basis, BasisRequest, FieldFamily};

/// Bands l = 1, 2, 3: 6 + 10 + 14 = 30 fields.
const BANDS: [usize; 3] = [1, 2, 3];

/// Relative error `max |λ − l(l+1)| / l(l+1)` of each band `l = 1, 2, 3`, separately over its
/// `2l+1` integrable and its `2l+1` co-integrable fields: `[band][0 integrable, 1 co-integrable]`.
fn band_errors<H: HodgeComplex + ?Sized>(complex: &H) -> [[f64; 2]; 3] {
    let count: usize = BANDS.iter().map(|l| 2 * (2 * l + 1)).sum();
    let basis = compute_basis(complex, &BasisRequest::fields(count)).unwrap();
    assert_eq!(basis.count(FieldFamily::Harmonic), 0);
    let mut start = 0;
    let mut errors = [[0.0; 2]; 3];
    for (b, &l) in BANDS.iter().enumerate() {
        let multiplicity = 2 * (2 * l + 1);
        let exact = (l * (l + 1)) as f64;
        let range = start..start + multiplicity;
        for (k, family) in [FieldFamily::Integrable, FieldFamily::Cointegrable]
            .into_iter()
            .enumerate()
        {
            let members: Vec<f64> = basis.eigenvalues()[range.clone()]
                .iter()
                .zip(&basis.families()[range.clone()])
                .filter(|(_, &f)| f == family)
                .map(|(&x, _)| x)
                .collect();
            assert_eq!(members.len(), 2 * l + 1, "band l = {l}, {family:?}");
            errors[b][k] = members
                .iter()
                .map(|x| (x - exact).abs() / exact)
                .fold(0.0, f64::max);
        }
        start += multiplicity;
    }
    errors
}

#[test]
fn lowest_eigenvalues_converge_to_l_times_l_plus_one() {
    println!("relative error of the bands l = 1, 2, 3 (integrable / co-integrable fields)");
    println!("level  faces  decomposition   l=1                   l=2                   l=3");
    let mut previous: Option<[[[f64; 2]; 3]; 2]> = None;
    for level in 1..=4 {
        let mesh = icosphere(level);
        let errors = [
            band_errors(&Conforming::new(&mesh, MassLumping::Barycentric).unwrap()),
            band_errors(&Nonconforming::new(&mesh, MassLumping::Barycentric).unwrap()),
        ];
        for (name, e) in ["conforming", "nonconforming"].iter().zip(&errors) {
            println!(
                "{level:>5}  {:>5}  {name:<14}  {:.3e} / {:.3e}   {:.3e} / {:.3e}   {:.3e} / {:.3e}",
                mesh.face_count(),
                e[0][0],
                e[0][1],
                e[1][0],
                e[1][1],
                e[2][0],
                e[2][1]
            );
        }
        if let Some(before) = previous {
            for d in 0..2 {
                for b in 0..3 {
                    for k in 0..2 {
                        assert!(
                            errors[d][b][k] < 0.5 * before[d][b][k],
                            "level {level}, decomposition {d}, band {b}, family {k}: {before:?} -> {errors:?}"
                        );
                    }
                }
            }
        }
        previous = Some(errors);
    }
    let last = previous.unwrap();
    assert!(
        last.iter().flatten().flatten().all(|&e| e < 0.01),
        "level 4 errors {last:?}"
    );
    // The spectra of the two decompositions coincide with the families swapped (P1 ↔ CR).
    let [conforming, nonconforming] = last;
    for (c, n) in conforming.iter().zip(&nonconforming) {
        assert!((c[0] - n[1]).abs() < 1e-9);
        assert!((c[1] - n[0]).abs() < 1e-9);
    }
}
