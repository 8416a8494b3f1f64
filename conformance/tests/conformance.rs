//! The conformance suite, one line per catalog entry (a missing line fails
//! `every_catalog_entry_has_a_suite_line`), and the seam's documented wrapper complex.

use tvf_conformance::scaled_co_potentials::ScaledCoPotentials;
use tvf_discretizations::{Conforming, MassLumping};

tvf_conformance::catalog_suites! {
    conforming_barycentric => "conforming-barycentric",
        reference = [cotan_formula, rotation, face_fields, div_curl_formulas, co_potential_masses, sphere_spectrum];
    conforming_voronoi => "conforming-voronoi",
        reference = [cotan_formula, rotation, face_fields, div_curl_formulas, co_potential_masses, sphere_spectrum];
    conforming_consistent => "conforming-consistent",
        reference = [cotan_formula, rotation, face_fields, div_curl_formulas, co_potential_masses, galerkin_masses, sphere_spectrum];
    nonconforming_barycentric => "nonconforming-barycentric",
        reference = [cotan_formula, rotation, face_fields, div_curl_formulas, co_potential_masses, sphere_spectrum];
    nonconforming_voronoi => "nonconforming-voronoi",
        reference = [cotan_formula, rotation, face_fields, div_curl_formulas, co_potential_masses, sphere_spectrum];
    nonconforming_consistent => "nonconforming-consistent",
        reference = [cotan_formula, rotation, face_fields, div_curl_formulas, co_potential_masses, galerkin_masses, sphere_spectrum];
    dec_barycentric => "dec-barycentric",
        reference = [cotan_formula, co_potential_masses, sphere_spectrum];
    dec_circumcentric => "dec-circumcentric",
        reference = [cotan_formula, co_potential_masses, sphere_spectrum];
    whitney_galerkin => "whitney-galerkin",
        reference = [potential_cotan_formula, co_potential_masses, galerkin_masses, sphere_spectrum];
}

tvf_conformance::conformance_suite!(
    scaled_co_potentials,
    |mesh| ScaledCoPotentials::new(Conforming::new(mesh, MassLumping::Barycentric)?, 2.0),
    reference = [cotan_formula, face_fields],
);
