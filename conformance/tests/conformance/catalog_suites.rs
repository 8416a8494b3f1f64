//! The conformance suite, one line per catalog entry (a missing line fails
//! `every_catalog_entry_has_a_suite_line`; its reference checks are the entry's
//! `catalog_reference_checks`, the ones `tvf check` measures), and the seam's documented wrapper
//! complex.

use tvf_conformance::scaled_co_potentials::ScaledCoPotentials;
use tvf_discretizations::{Conforming, MassLumping};

tvf_conformance::catalog_suites! {
    conforming_barycentric => "conforming-barycentric";
    conforming_voronoi => "conforming-voronoi";
    conforming_consistent => "conforming-consistent";
    nonconforming_barycentric => "nonconforming-barycentric";
    nonconforming_voronoi => "nonconforming-voronoi";
    nonconforming_consistent => "nonconforming-consistent";
    dec_barycentric => "dec-barycentric";
    dec_circumcentric => "dec-circumcentric";
    whitney_galerkin => "whitney-galerkin";
    polygon_dec => "polygon-dec";
}

// The wrapper halves the co-integrable eigenvalues on purpose: no accuracy test (the mutation
// test `a_scaled_inner_product_fails_the_co_integrable_convergence` pins that the accuracy
// checks see it).
tvf_conformance::conformance_suite!(
    scaled_co_potentials,
    |mesh| ScaledCoPotentials::new(Conforming::new(mesh, MassLumping::Barycentric)?, 2.0),
    reference = [cotan_formula, face_fields],
    accuracy = false,
);
