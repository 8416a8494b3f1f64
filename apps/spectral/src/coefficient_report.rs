//! A field's Fourier coefficients as `tvf coefficients` prints them: a table for people
//! ([`FourierAnalysis::table`]) or JSON for programs ([`FourierAnalysis::to_json`]).

use crate::basis::FieldFamily;
use crate::fourier::FourierAnalysis;
use crate::FieldBasis;
use serde_json::{json, Value};
use std::fmt::Write as _;

impl FourierAnalysis {
    /// The coefficients in basis order, each with its index, family, eigenvalue `λ` and
    /// frequency `√λ` (`basis` is the basis the analysis was made in).
    fn rows<'a>(
        &'a self,
        basis: &'a (impl FieldBasis + ?Sized),
    ) -> impl Iterator<Item = (usize, FieldFamily, f64, f64)> + 'a {
        self.coefficients
            .iter()
            .zip(basis.eigenvalues())
            .zip(basis.families())
            .enumerate()
            .map(|(index, ((&c, &lambda), &family))| (index, family, lambda, c))
    }

    /// The analysis as JSON: `coefficients` (`[{index, family, eigenvalue, frequency,
    /// coefficient}, ...]` in basis order), `alpha`, `beta`, `gamma` (the coefficients of each
    /// family), `norm` (`‖v‖_{M_X}`) and `relative_rest_norm`.
    pub fn to_json(&self, basis: &(impl FieldBasis + ?Sized)) -> Value {
        let entries: Vec<Value> = self
            .rows(basis)
            .map(|(index, family, lambda, c)| {
                json!({
                    "index": index,
                    "family": family.name(),
                    "eigenvalue": lambda,
                    "frequency": lambda.sqrt(),
                    "coefficient": c,
                })
            })
            .collect();
        let pairs = |list: &[(f64, f64)]| list.iter().map(|&(_, c)| c).collect::<Vec<_>>();
        json!({
            "coefficients": entries,
            "alpha": pairs(&self.alpha),
            "beta": pairs(&self.beta),
            "gamma": self.gamma,
            "norm": self.norm,
            "relative_rest_norm": self.relative_rest_norm,
        })
    }

    /// The analysis as a table, one line each (every line ends in a newline): a header, one
    /// row per coefficient (index, family, eigenvalue, frequency, coefficient), the energy of
    /// each family with its share of `‖v‖²`, and the rest field's relative norm.
    pub fn table(&self, basis: &(impl FieldBasis + ?Sized)) -> String {
        let mut text = format!(
            "{:>6}  {:<12}  {:>14}  {:>14}  {:>22}\n",
            "index", "family", "eigenvalue", "frequency", "coefficient"
        );
        for (index, family, lambda, c) in self.rows(basis) {
            let _ = writeln!(
                text,
                "{index:>6}  {:<12}  {lambda:>14.6e}  {:>14.6e}  {c:>22.15e}",
                family.name(),
                lambda.sqrt()
            );
        }
        let norm2 = self.norm * self.norm;
        for family in [
            FieldFamily::Integrable,
            FieldFamily::Cointegrable,
            FieldFamily::Harmonic,
        ] {
            let energy = self.family_energy(family);
            let share = if norm2 > 0.0 {
                100.0 * energy / norm2
            } else {
                0.0
            };
            let _ = writeln!(
                text,
                "{:<12} energy {energy:.6e} ({share:.2} %)",
                family.name()
            );
        }
        let _ = writeln!(
            text,
            "rest field: relative L2 norm {:.6e}",
            self.relative_rest_norm
        );
        text
    }
}

#[cfg(test)]
mod tests {
    use crate::{compute_basis, BasisRequest, FourierAnalysis};
    use tvf_discretizations::DEFAULT_DISCRETIZATION;

    #[test]
    fn a_basis_field_has_one_coefficient_in_the_table_and_in_json() {
        let (_, complex) = crate::test_torus::torus_complex(DEFAULT_DISCRETIZATION);
        let basis = compute_basis(complex.as_ref(), &BasisRequest::fields(6)).unwrap();
        let field: Vec<f64> = (0..basis.field_dimension())
            .map(|i| basis.fields()[(i, 4)])
            .collect();
        let analysis = FourierAnalysis::new(&basis, &field).unwrap();
        let json = analysis.to_json(&basis);
        let entries = json["coefficients"].as_array().unwrap();
        assert_eq!(entries.len(), 6);
        assert!((entries[4]["coefficient"].as_f64().unwrap() - 1.0).abs() < 1e-9);
        assert_eq!(entries[0]["family"], "harmonic");
        assert_eq!(json["gamma"].as_array().unwrap().len(), 2);
        let table = analysis.table(&basis);
        // A header, six rows, three family energies and the rest field.
        assert_eq!(table.lines().count(), 1 + 6 + 3 + 1);
        let family = basis.families()[4].name();
        let energy_line = table.lines().find(|l| l.starts_with(family)).unwrap();
        assert!(energy_line.ends_with("(100.00 %)"), "{energy_line}");
    }
}
