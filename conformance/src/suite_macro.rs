//! The [`conformance_suite!`](crate::conformance_suite) and
//! [`catalog_suites!`](crate::catalog_suites) macros.

/// Instantiates the conformance suite for one discretization: a module `name` with one `#[test]`
/// per core check of [`crate::suite`] (three of them properties over random draws), one,
/// `accuracy`, running the accuracy checks ([`crate::suite::accuracy`]: consistency on patches,
/// convergence on the sphere and hemisphere), and a
/// submodule `reference` with one `#[test]` per named check of [`crate::reference`] and one,
/// `listed`, that runs a list of them given as a value.
///
/// ```text
/// conformance_suite!(name, entry = catalog_entry);
/// conformance_suite!(name, entry = catalog_entry, reference = [cotan_formula, rotation]);
/// conformance_suite!(name, entry = catalog_entry, reference_checks = catalog_reference_checks(id));
/// conformance_suite!(name, constructor);
/// conformance_suite!(name, constructor, corpus = Corpus::Delaunay);
/// conformance_suite!(name, constructor, reference = [cotan_formula, rotation]);
/// conformance_suite!(name, constructor, cases = 16);
/// conformance_suite!(name, constructor, accuracy = false);
/// conformance_suite!(name, constructor, corpus = ..., reference = [...], reference_checks = ..., cases = ..., accuracy = ...);
/// ```
///
/// - `entry`: an expression of type [`CatalogEntry`](tvf_discretizations::CatalogEntry) (of any
///   catalog, e.g. `my_entry()`; evaluated inside the generated module, which imports
///   `super::*`, once per complex built). The module `name` then has a submodule
///   `closed_meshes`, the suite on the entry's corpus
///   ([`Corpus::for_catalog_entry`](crate::corpus::Corpus::for_catalog_entry): the Delaunay one
///   when it needs Delaunay meshes), and a submodule `open_meshes` with one test per boundary
///   condition ([`crate::open_suite::open_mesh_suite`]: the core suite on meshes with boundary
///   for a condition the entry offers; for one it does not, that the entry refuses it), and a
///   submodule `polygon_meshes`, the suite on polygon meshes ([`crate::polygon_suite`]: closed,
///   with holes under each boundary condition, generated; an entry that needs triangles must
///   refuse them), and its accuracy checks on quad meshes
///   ([`crate::polygon_suite::polygon_accuracy`]).
/// - `constructor`: `Fn(&TriangleMesh) -> Result<H, E>`, `E: Debug`, `H` a `HodgeComplex +
///   'static` or a `Box<dyn HodgeComplex>`; evaluated inside the generated module (which
///   imports `super::*`).
/// - `corpus`: an expression of type [`crate::corpus::Corpus`], default `Corpus::General`.
/// - `reference`: names of functions in [`crate::reference`] (an unknown name does not compile),
///   one test each.
/// - `reference_checks`: an expression whose `.to_vec()` is a
///   `Vec<`[`ReferenceCheck`](crate::reference_report::ReferenceCheck)`>` (e.g. a built-in
///   entry's [`catalog_reference_checks`](crate::reference_report::catalog_reference_checks)),
///   run in order by one test, `reference::listed` ([`crate::reference::run_checks`]).
/// - `cases`: cases per property (`rigid_motion_invariance`, `jittered_mesh`,
///   `generated_meshes`), default [`crate::suite::DEFAULT_CASES`] (64). The environment variable
///   `PROPTEST_CASES`, which proptest reads, can lower it (never raise it):
///   [`crate::suite::property_cases`].
/// - `accuracy = false`: no `accuracy` test, for a complex that by design does not approximate
///   the smooth operators (a wrapper that rescales an inner product, as
///   [`crate::scaled_co_potentials::ScaledCoPotentials`] does); every entry that is meant to be
///   a discretization keeps it.
#[macro_export]
macro_rules! conformance_suite {
    (
        $name:ident,
        entry = $entry:expr
        $(, reference = [$($check:ident),* $(,)?])?
        $(, reference_checks = $checks:expr)?
        $(,)?
    ) => {
        mod $name {
            #[allow(unused_imports)]
            use super::*;

            /// The suite line's catalog entry.
            fn suite_entry() -> $crate::tvf_discretizations::CatalogEntry {
                $entry
            }

            $crate::conformance_suite!(
                closed_meshes,
                |mesh| suite_entry().build(mesh),
                corpus = $crate::corpus::Corpus::for_catalog_entry(&suite_entry())
                $(, reference = [$($check),*])?
                $(, reference_checks = $checks)?
            );

            /// The core suite on meshes with boundary, one test per boundary condition.
            mod open_meshes {
                #[test]
                fn tangential() {
                    $crate::open_suite::open_mesh_suite(
                        &super::suite_entry(),
                        $crate::tvf_core::discretization::BoundaryCondition::Tangential,
                    );
                }

                #[test]
                fn normal() {
                    $crate::open_suite::open_mesh_suite(
                        &super::suite_entry(),
                        $crate::tvf_core::discretization::BoundaryCondition::Normal,
                    );
                }
            }

            /// The core suite on polygon meshes: closed, with holes under each boundary
            /// condition, and generated (an entry that needs triangles must refuse them).
            mod polygon_meshes {
                #[test]
                fn closed() {
                    $crate::polygon_suite::polygon_mesh_suite(&super::suite_entry(), None);
                }

                #[test]
                fn tangential() {
                    $crate::polygon_suite::polygon_mesh_suite(
                        &super::suite_entry(),
                        Some($crate::tvf_core::discretization::BoundaryCondition::Tangential),
                    );
                }

                #[test]
                fn normal() {
                    $crate::polygon_suite::polygon_mesh_suite(
                        &super::suite_entry(),
                        Some($crate::tvf_core::discretization::BoundaryCondition::Normal),
                    );
                }

                #[test]
                fn generated() {
                    $crate::polygon_suite::generated_polygon_meshes(
                        &super::suite_entry(),
                        $crate::suite::property_cases($crate::suite::DEFAULT_CASES),
                    );
                }

                #[test]
                fn accuracy() {
                    $crate::polygon_suite::polygon_accuracy(&super::suite_entry());
                }
            }
        }
    };
    (
        $name:ident,
        $constructor:expr
        $(, corpus = $corpus:expr)?
        $(, reference = [$($check:ident),* $(,)?])?
        $(, reference_checks = $checks:expr)?
        $(, cases = $cases:expr)?
        $(, accuracy = $accuracy:tt)?
        $(,)?
    ) => {
        mod $name {
            #[allow(unused_imports)]
            use super::*;

            /// The suite line's constructor, its complex boxed and its error formatted.
            fn build_complex(
                mesh: &$crate::tvf_core::TriangleMesh,
            ) -> ::std::result::Result<$crate::tvf_discretizations::BoxedComplex, String> {
                #[allow(unused_imports)]
                use $crate::__private::{AlreadyBoxed as _, NeedsBox as _};
                let constructor = $crate::constructor($constructor);
                let built = constructor(mesh).map_err(|e| format!("{e:?}"))?;
                Ok((&$crate::__private::Boxing::new(built)).boxed())
            }

            fn corpus() -> $crate::corpus::Corpus {
                $crate::__suite_corpus!($($corpus)?)
            }

            fn cases() -> u32 {
                $crate::suite::property_cases($crate::__suite_cases!($($cases)?))
            }

            $(
                /// The reference checks of the suite line's `reference_checks`.
                fn reference_checks() -> ::std::vec::Vec<$crate::reference_report::ReferenceCheck> {
                    $checks.to_vec()
                }
            )?

            #[test]
            fn nodes_and_masses() {
                $crate::suite::nodes_and_masses(&build_complex, corpus());
            }

            #[test]
            fn d1_d0_is_zero() {
                $crate::suite::d1_d0_is_zero(&build_complex, corpus());
            }

            #[test]
            fn symmetric_operators() {
                $crate::suite::symmetric_operators(&build_complex, corpus());
            }

            #[test]
            fn positive_semidefinite_operators() {
                $crate::suite::positive_semidefinite_operators(&build_complex, corpus());
            }

            #[test]
            fn capabilities() {
                $crate::suite::capabilities(&build_complex, corpus());
            }

            #[test]
            fn hodge_decomposition() {
                $crate::suite::hodge_decomposition(&build_complex, corpus());
            }

            #[test]
            fn kernel_is_2g_dense() {
                $crate::suite::kernel_is_2g_dense(&build_complex, corpus());
            }

            #[test]
            fn kernel_is_2g_by_harmonic_projection() {
                $crate::suite::kernel_is_2g_by_harmonic_projection(&build_complex, corpus());
            }

            #[test]
            fn spectrum_is_union_of_scalar_spectra() {
                $crate::suite::spectrum_is_union_of_scalar_spectra(&build_complex, corpus());
            }

            #[test]
            fn lemma1_eigenfields() {
                $crate::suite::lemma1_eigenfields(&build_complex, corpus());
            }

            #[test]
            fn basis_is_orthonormal() {
                $crate::suite::basis_is_orthonormal(&build_complex, corpus());
            }

            #[test]
            fn generated_meshes() {
                $crate::suite::generated_meshes(&build_complex, corpus(), cases());
            }

            $crate::__accuracy_test!($($accuracy)?);

            $crate::proptest::proptest! {
                #![proptest_config($crate::proptest::prelude::ProptestConfig::with_cases(cases()))]

                #[test]
                fn rigid_motion_invariance(
                    axis in $crate::proptest::array::uniform3(-1.0f64..1.0),
                    angle in -3.0f64..3.0,
                    translation in $crate::proptest::array::uniform3(-10.0f64..10.0),
                ) {
                    $crate::suite::rigid_motion_invariance(
                        &build_complex,
                        corpus(),
                        axis,
                        angle,
                        translation,
                    );
                }

                #[test]
                fn jittered_mesh(seed in 0u64..1_000_000) {
                    $crate::suite::jittered_mesh(&build_complex, corpus(), seed);
                }
            }

            mod reference {
                $($(
                    #[test]
                    fn $check() {
                        $crate::reference::$check(&super::build_complex, super::corpus());
                    }
                )*)?

                $crate::__listed_reference_checks!($($checks)?);
            }
        }
    };
}

/// The test `accuracy` of a suite line: there unless the line says `accuracy = false`.
#[doc(hidden)]
#[macro_export]
macro_rules! __accuracy_test {
    (false) => {};
    ($($on:tt)?) => {
        #[test]
        fn accuracy() {
            $crate::suite::accuracy(&build_complex);
        }
    };
}

/// The test `listed` of a suite line with `reference_checks` (none without).
#[doc(hidden)]
#[macro_export]
macro_rules! __listed_reference_checks {
    () => {};
    ($checks:expr) => {
        #[test]
        fn listed() {
            $crate::reference::run_checks(
                &super::reference_checks(),
                &super::build_complex,
                super::corpus(),
            );
        }
    };
}

/// The cases per property of a suite line: the given expression, or
/// [`crate::suite::DEFAULT_CASES`].
#[doc(hidden)]
#[macro_export]
macro_rules! __suite_cases {
    () => {
        $crate::suite::DEFAULT_CASES
    };
    ($cases:expr) => {
        $cases
    };
}

/// The corpus of a suite line: the given expression, or `Corpus::General`.
#[doc(hidden)]
#[macro_export]
macro_rules! __suite_corpus {
    () => {
        $crate::corpus::Corpus::General
    };
    ($corpus:expr) => {
        $corpus
    };
}

/// One [`conformance_suite!`](crate::conformance_suite)`(name, entry = ...)` per built-in catalog
/// entry (the entry by id, [`crate::builtin_entry`]: closed meshes on the entry's corpus, meshes
/// with boundary for both boundary conditions, and the reference checks the entry opts into,
/// [`catalog_reference_checks`](crate::reference_report::catalog_reference_checks), the list
/// `tvf check` measures), plus the constant `COVERED_IDS` and a test
/// `every_catalog_entry_has_a_suite_line` that fails unless the lines cover the built-in catalog
/// exactly.
///
/// ```text
/// catalog_suites! {
///     conforming_barycentric => "conforming-barycentric";
///     dec_barycentric => "dec-barycentric";
/// }
/// ```
#[macro_export]
macro_rules! catalog_suites {
    ($($name:ident => $id:literal;)*) => {
        $(
            $crate::conformance_suite!(
                $name,
                entry = $crate::builtin_entry($id),
                reference_checks = $crate::reference_report::catalog_reference_checks($id)
            );
        )*

        /// The built-in catalog ids that have a suite line above.
        pub const COVERED_IDS: &[&str] = &[$($id),*];

        #[test]
        fn every_catalog_entry_has_a_suite_line() {
            $crate::assert_catalog_covered(COVERED_IDS);
        }
    };
}
