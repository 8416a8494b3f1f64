//! The [`conformance_suite!`](crate::conformance_suite) macro.

/// Instantiates every conformance check for one discretization: `conformance_suite!(name,
/// constructor)` with `constructor: Fn(&SurfaceMesh) -> Result<impl HodgeComplex, impl Debug>`.
/// Expands to a module `name` with one `#[test]` per property.
#[macro_export]
macro_rules! conformance_suite {
    ($name:ident, $constructor:expr) => {
        mod $name {
            #[allow(unused_imports)]
            use super::*;
            use $crate::algebra_checks::*;
            use $crate::decomposition_checks::*;
            use $crate::reference_formulas::check_cotan_formula;
            use $crate::spectral_checks::*;
            use $crate::{build_complex, for_each_mesh};

            #[test]
            fn masses_positive_and_field_space_valid() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(true, |m| {
                    let complex = build_complex(&constructor, m);
                    check_masses(&complex, m.mesh.total_area());
                    check_field_space(&complex);
                });
            }

            #[test]
            fn symmetric_operators() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(true, |m| check_symmetric_operators(&build_complex(&constructor, m)));
            }

            #[test]
            fn positive_semidefinite_operators() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(false, |m| {
                    if m.dense_ok() {
                        check_psd_operators(&build_complex(&constructor, m));
                    }
                });
            }

            #[test]
            fn d1_d0_is_zero_and_parts_orthogonal() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(true, |m| {
                    let complex = build_complex(&constructor, m);
                    check_d1_d0_zero(&complex);
                    check_integrable_orthogonal_to_cointegrable(&complex);
                });
            }

            #[test]
            fn stiffness_matches_cotan_and_cr_formulas() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(true, |m| check_cotan_formula(&build_complex(&constructor, m), &m.mesh));
            }

            #[test]
            fn hodge_decomposition() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(true, |m| check_hodge_decomposition(&build_complex(&constructor, m), 17));
            }

            #[test]
            fn kernel_is_2g_dense() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(false, |m| {
                    if m.dense_ok() {
                        check_kernel_is_2g_dense(&build_complex(&constructor, m), m.genus);
                    }
                });
            }

            #[test]
            fn kernel_is_2g_by_harmonic_projection() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(true, |m| {
                    check_kernel_is_2g_sparse(&build_complex(&constructor, m), m.genus, 23)
                });
            }

            #[test]
            fn spectrum_is_union_of_function_spectra() {
                let constructor = $crate::constructor($constructor);
                for_each_mesh(false, |m| {
                    if m.dense_ok() {
                        check_spectrum_union(&build_complex(&constructor, m), m.genus);
                    }
                });
            }

            #[test]
            fn unit_sphere_spectrum() {
                let constructor = $crate::constructor($constructor);
                let sphere = $crate::tvf_core::generate::icosphere(2);
                let complex = constructor(&sphere).expect("icosphere(2) builds");
                check_sphere_spectrum(&complex);
            }

            $crate::proptest::proptest! {
                #![proptest_config($crate::proptest::prelude::ProptestConfig::with_cases(4))]

                #[test]
                fn rigid_motion_invariance(
                    axis in $crate::proptest::array::uniform3(-1.0f64..1.0),
                    angle in -3.0f64..3.0,
                    translation in $crate::proptest::array::uniform3(-10.0f64..10.0),
                ) {
                    let constructor = $crate::constructor($constructor);
                    for mesh in [
                        $crate::tvf_core::generate::icosphere(1),
                        $crate::tvf_core::generate::torus(1.0, 0.4, 12, 6).expect("valid torus"),
                    ] {
                        let moved = $crate::tvf_core::generate::rigid_motion(&mesh, axis, angle, translation)
                            .expect("finite motion");
                        let a = constructor(&mesh).expect("builds");
                        let b = constructor(&moved).expect("builds");
                        check_rigid_motion_invariance(&a, &b, true);
                    }
                }

                #[test]
                fn jittered_meshes(seed in 0u64..1_000_000) {
                    let constructor = $crate::constructor($constructor);
                    let base = $crate::tvf_core::generate::torus(1.0, 0.4, 12, 6).expect("valid torus");
                    let mesh = $crate::tvf_core::generate::jitter(&base, 0.2, seed).expect("finite");
                    let complex = constructor(&mesh).expect("builds");
                    check_d1_d0_zero(&complex);
                    check_kernel_is_2g_dense(&complex, 1);
                    check_hodge_decomposition(&complex, seed);
                    check_spectrum_union(&complex, 1);
                }
            }
        }
    };
}
