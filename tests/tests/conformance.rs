//! The conformance suite, one line per discretization: both Hodge complexes, both lumpings.

use tvf_discretizations::{Conforming, MassLumping, Nonconforming};

tvf_tests::conformance_suite!(conforming_barycentric, |mesh| {
    Conforming::new(mesh, MassLumping::Barycentric)
});
tvf_tests::conformance_suite!(conforming_voronoi, |mesh| Conforming::new(
    mesh,
    MassLumping::Voronoi
));
tvf_tests::conformance_suite!(nonconforming_barycentric, |mesh| {
    Nonconforming::new(mesh, MassLumping::Barycentric)
});
tvf_tests::conformance_suite!(nonconforming_voronoi, |mesh| {
    Nonconforming::new(mesh, MassLumping::Voronoi)
});
