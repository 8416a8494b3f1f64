//! [`RunContext`]: what every subcommand that builds a discretization receives besides its
//! arguments — the catalog of the program running the command line ([`crate::run`]).

use tvf_discretizations::Catalog;

/// The program's side of a command line run: its catalog of discretizations, the one place
/// where subcommands look ids up (through [`crate::discretization_flags::DiscretizationFlags`]
/// and [`crate::basis_source::BasisOptions`]).
pub struct RunContext {
    catalog: Catalog,
}

impl RunContext {
    /// The context of a run with the discretizations of `catalog`.
    pub fn new(catalog: Catalog) -> Self {
        Self { catalog }
    }

    /// The catalog: built-in entries and the program's own.
    pub fn catalog(&self) -> &Catalog {
        &self.catalog
    }
}
