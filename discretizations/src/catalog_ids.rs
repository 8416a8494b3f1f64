//! Catalog ids as a user names them: a whole id, or its two parts `DECOMPOSITION-MASS` given
//! separately (`tvf --decomposition dec --mass circumcentric`, [`requested_catalog_id`]); each
//! checked against a [`Catalog`] with an error that lists what the catalog offers; the entries
//! a list of ids selects ([`Catalog::selected`]); and boundary conditions by name.

use crate::catalog::{Catalog, UnknownDiscretization};
use crate::catalog_entry::CatalogEntry;
use tvf_core::discretization::BoundaryCondition;

/// The decomposition part a shorthand id gets when only the mass is given.
pub const DEFAULT_DECOMPOSITION_PART: &str = "conforming";

/// The mass part a shorthand id gets when only the decomposition is given.
pub const DEFAULT_MASS_PART: &str = "barycentric";

/// The id asked for: `id` if given, else `DECOMPOSITION-MASS` from the parts given (a missing
/// part is [`DEFAULT_DECOMPOSITION_PART`] / [`DEFAULT_MASS_PART`]), else `None`.
pub fn requested_catalog_id(
    id: Option<&str>,
    decomposition: Option<&str>,
    mass: Option<&str>,
) -> Option<String> {
    if let Some(id) = id {
        return Some(id.to_string());
    }
    if decomposition.is_none() && mass.is_none() {
        return None;
    }
    Some(format!(
        "{}-{}",
        decomposition.unwrap_or(DEFAULT_DECOMPOSITION_PART),
        mass.unwrap_or(DEFAULT_MASS_PART)
    ))
}

/// A boundary condition by name (`tangential` or `normal`); the error names both.
pub fn parse_boundary_condition(value: &str) -> Result<BoundaryCondition, String> {
    BoundaryCondition::from_name(value)
        .ok_or_else(|| format!("'{value}' is not a boundary condition: tangential or normal"))
}

impl Catalog {
    /// Accepts an id of the catalog; the error lists the ids.
    pub fn check_id(&self, value: &str) -> Result<(), String> {
        self.get(value).map(|_| ()).map_err(|e| e.to_string())
    }

    /// Accepts the first part of some id (`conforming`, `nonconforming`, `dec`, ...); the error
    /// lists the first parts.
    pub fn check_decomposition_part(&self, value: &str) -> Result<(), String> {
        one_of(value, self.id_parts().map(|(d, _)| d).collect())
    }

    /// Accepts the last part of some id (`barycentric`, `voronoi`, `circumcentric`, ...); the
    /// error lists the last parts.
    pub fn check_mass_part(&self, value: &str) -> Result<(), String> {
        one_of(value, self.id_parts().map(|(_, m)| m).collect())
    }

    /// The entries of `ids`, in that order, or every entry when `ids` is empty.
    pub fn selected(&self, ids: &[String]) -> Result<Vec<&CatalogEntry>, UnknownDiscretization> {
        if ids.is_empty() {
            return Ok(self.iter().collect());
        }
        ids.iter().map(|id| self.get(id)).collect()
    }

    /// The ids split at their last `-`: (decomposition, mass).
    fn id_parts(&self) -> impl Iterator<Item = (&str, &str)> {
        self.ids().filter_map(|id| id.rsplit_once('-'))
    }
}

/// `Ok` if `value` is in `known`, else an error listing `known` (sorted, without repeats).
fn one_of(value: &str, mut known: Vec<&str>) -> Result<(), String> {
    known.sort_unstable();
    known.dedup();
    if known.contains(&value) {
        Ok(())
    } else {
        Err(format!("'{value}' is not one of: {}", known.join(", ")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DEFAULT_DISCRETIZATION;

    #[test]
    fn shorthands_fill_the_missing_part() {
        assert_eq!(requested_catalog_id(None, None, None), None);
        let id = |d, m| requested_catalog_id(None, d, m);
        assert_eq!(id(Some("dec"), None).unwrap(), "dec-barycentric");
        assert_eq!(id(None, Some("voronoi")).unwrap(), "conforming-voronoi");
        let whole = requested_catalog_id(Some("x-y"), Some("dec"), None);
        assert_eq!(whole.unwrap(), "x-y");
    }

    #[test]
    fn ids_and_their_parts_are_checked_against_the_catalog() {
        let catalog = Catalog::builtin();
        assert!(catalog.check_id("dec-circumcentric").is_ok());
        assert!(catalog.check_id("nosuch").is_err());
        assert!(catalog.check_decomposition_part("nonconforming").is_ok());
        let problem = catalog.check_mass_part("nosuch").unwrap_err();
        assert!(problem.starts_with("'nosuch' is not one of: "), "{problem}");
        assert!(problem.contains("barycentric, ") && problem.contains("voronoi"));
        assert_eq!(problem.matches("barycentric").count(), 1, "{problem}");
    }

    #[test]
    fn a_selection_keeps_its_order_and_an_empty_one_is_everything() {
        let catalog = Catalog::builtin();
        assert_eq!(catalog.selected(&[]).unwrap().len(), catalog.len());
        let ids = [
            "dec-circumcentric".to_string(),
            DEFAULT_DISCRETIZATION.into(),
        ];
        let chosen: Vec<&str> = catalog
            .selected(&ids)
            .unwrap()
            .iter()
            .map(|e| e.id())
            .collect();
        assert_eq!(chosen, ["dec-circumcentric", DEFAULT_DISCRETIZATION]);
        assert!(catalog.selected(&["nosuch".to_string()]).is_err());
    }

    #[test]
    fn boundary_conditions_parse_by_name() {
        assert_eq!(
            parse_boundary_condition("normal"),
            Ok(BoundaryCondition::Normal)
        );
        assert!(parse_boundary_condition("up")
            .unwrap_err()
            .contains("tangential or normal"));
    }
}
