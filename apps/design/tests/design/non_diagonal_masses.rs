//! Design with non-diagonal masses (consistent P1 `M0`, the Whitney `M1`, a sparse face mass,
//! `M2` stored as its inverse): the full soft design and the reference spline against dense
//! references, constraint rows through the nodal unknowns, refactorizations, orderings, and the
//! reduced solvers on complete eigenbases.

use crate::common::{node_location, truncated};
use crate::non_diagonal::{
    conforming_consistent, conforming_coupled_fields, dense_soft_design, dense_spline, flat_patch,
    mass_relative_difference, nonconforming_consistent, whitney_galerkin,
};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tvf_core::discretization::{BoundaryCondition, HodgeComplex, HodgeOperators, NodeSpace};
use tvf_core::generate::{hemisphere, icosphere, jitter};
use tvf_core::TriangleMesh;
use tvf_design::{
    default_regularization, reference_spline, CompiledConstraint, Constraint, ConstraintAssembler,
    FactorParallelism, FillOrdering, FullSoftDesign, Location, OperatorFamily, ReducedBasis,
    ReducedSoftDesign, RowOrigin, SoftOptions, SplineSession, Target,
};
use tvf_spectral::{compute_basis, BasisRequest};

/// A free node of `nodes` as a location (vertex or edge key; a face for face nodes).
fn free_node_location(nodes: &NodeSpace, rng: &mut ChaCha8Rng) -> Location {
    loop {
        let i = rng.random_range(0..nodes.len());
        if nodes.is_free(i) {
            return node_location(nodes, i);
        }
    }
}

/// Seeded constraints every complex accepts: `vectors` vectors, a divergence at a potential
/// node and a curl at a co-potential node, one of each at a point, and where the complex has a
/// rotation one divergence and one curl of the other family at points.
fn constraints<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &TriangleMesh,
    vectors: usize,
    seed: u64,
) -> Vec<CompiledConstraint> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let point = |rng: &mut ChaCha8Rng| {
        let (a, b) = (rng.random_range(0.1..0.5), rng.random_range(0.1..0.4));
        Location::Face {
            face: rng.random_range(0..mesh.face_count()),
            barycentric: Some(vec![a, b, 1.0 - a - b]),
        }
    };
    let mut list = Vec::new();
    let mut faces: Vec<usize> = Vec::new();
    while faces.len() < vectors {
        let face = rng.random_range(0..mesh.face_count());
        if !faces.contains(&face) {
            faces.push(face);
        }
    }
    for (k, &face) in faces.iter().enumerate() {
        let v = [
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        ];
        let location = Location::Face {
            face,
            barycentric: None,
        };
        list.push(Constraint::new(
            format!("v{k}"),
            Target::Vector(v),
            location,
        ));
    }
    let source = free_node_location(complex.potential_nodes(), &mut rng);
    list.push(Constraint::new("source", Target::Divergence(2.0), source));
    let vortex = free_node_location(complex.co_potential_nodes(), &mut rng);
    list.push(Constraint::new("vortex", Target::Curl(-1.5), vortex));
    list.push(Constraint::new(
        "div-point",
        Target::Divergence(-0.7),
        point(&mut rng),
    ));
    list.push(Constraint::new(
        "curl-point",
        Target::Curl(0.9),
        point(&mut rng),
    ));
    if complex.rotation().is_some() {
        list.push(
            Constraint::new("div-other", Target::Divergence(0.5), point(&mut rng))
                .with_family(OperatorFamily::Other),
        );
        list.push(
            Constraint::new("curl-other", Target::Curl(-0.4), point(&mut rng))
                .with_family(OperatorFamily::Other),
        );
    }
    ConstraintAssembler::new(complex, mesh)
        .compile_all(&list)
        .expect("valid constraints")
}

fn options<H: HodgeComplex + ?Sized>(complex: &H, omega: f64) -> SoftOptions {
    SoftOptions {
        omega,
        regularization: default_regularization(complex),
    }
}

/// The full soft design of `complex` against the dense normal equations, for ω = 0.1 and ω = 0;
/// returns the largest relative `M1` difference.
fn full_against_dense<H: HodgeComplex + ?Sized>(
    name: &str,
    complex: &H,
    mesh: &TriangleMesh,
) -> f64 {
    let compiled = constraints(complex, mesh, 6, 3);
    let mut worst = 0.0f64;
    for omega in [0.1, 0.0] {
        let opts = options(complex, omega);
        let design = FullSoftDesign::new(complex, opts, compiled.clone()).expect("full design");
        let (x, report) = design.solve();
        assert!(x.iter().all(|v| v.is_finite()), "{name}: non-finite field");
        assert!(
            report.meets(1e-10),
            "{name} ω={omega}: residuals {:?}, floor {:e}",
            report.residuals,
            report.rounding_floor
        );
        let reference = dense_soft_design(complex, opts, &compiled);
        let error = mass_relative_difference(complex, &x, &reference);
        let residuals: Vec<f64> = compiled
            .iter()
            .map(|c| tvf_design::residual(c, &x).relative)
            .collect();
        let dense_residuals: Vec<f64> = compiled
            .iter()
            .map(|c| tvf_design::residual(c, &reference).relative)
            .collect();
        println!(
            "{name} ω = {omega}: {} unknowns, {} refinement steps, relative M1 difference to \
             dense {error:.2e}, worst constraint residual {:.3e} (dense {:.3e})",
            x.len(),
            report.residuals.len() - 1,
            residuals.iter().fold(0.0f64, |m, &r| m.max(r)),
            dense_residuals.iter().fold(0.0f64, |m, &r| m.max(r)),
        );
        for (r, d) in residuals.iter().zip(&dense_residuals) {
            assert!(
                (r - d).abs() <= 1e-8 * d.max(1e-3),
                "{name}: residual {r:e} vs {d:e}"
            );
        }
        worst = worst.max(error);
    }
    worst
}

#[test]
fn full_soft_design_matches_dense_normal_equations() {
    let sphere = jitter(&icosphere(2), 0.2, 4).expect("mesh");
    let ico = icosphere(2);
    let cases: [(&str, f64); 4] = [
        (
            "conforming, consistent M0",
            full_against_dense(
                "conforming, consistent M0",
                &conforming_consistent(&sphere, BoundaryCondition::Tangential),
                &sphere,
            ),
        ),
        (
            "nonconforming, M2⁻¹ consistent",
            full_against_dense(
                "nonconforming, M2⁻¹ consistent",
                &nonconforming_consistent(&sphere),
                &sphere,
            ),
        ),
        (
            "Whitney M1, consistent M0",
            full_against_dense(
                "Whitney M1, consistent M0",
                &whitney_galerkin(&ico, BoundaryCondition::Tangential),
                &ico,
            ),
        ),
        (
            "coupled face M1",
            full_against_dense(
                "coupled face M1",
                &conforming_coupled_fields(&sphere),
                &sphere,
            ),
        ),
    ];
    for (name, error) in cases {
        assert!(error < 1e-9, "{name}: {error:e}");
    }
}

#[test]
fn fixed_nodes_of_the_boundary_condition_carry_no_unknown() {
    let mesh = hemisphere(4);
    let conforming = conforming_consistent(&mesh, BoundaryCondition::Normal);
    assert!(conforming.potential_nodes().dirichlet_count() > 0);
    let error = full_against_dense("conforming (normal), consistent M0", &conforming, &mesh);
    assert!(error < 1e-9, "{error:e}");
    // DEC needs a Delaunay mesh: a flat patch of equilateral triangles.
    let patch = flat_patch(6);
    let whitney = whitney_galerkin(&patch, BoundaryCondition::Normal);
    assert!(whitney.field_nodes().dirichlet_count() > 0);
    let error = full_against_dense("Whitney (relative forms)", &whitney, &patch);
    assert!(error < 1e-9, "{error:e}");
    let x = FullSoftDesign::new(
        &whitney,
        options(&whitney, 0.1),
        constraints(&whitney, &patch, 4, 9),
    )
    .expect("design")
    .solve()
    .0;
    let nodes = whitney.field_nodes();
    assert!((0..x.len()).all(|i| nodes.is_free(i) || x[i] == 0.0));
}

#[test]
fn nodal_constraints_are_sparse_rows_of_the_auxiliary_unknowns() {
    let mesh = icosphere(1);
    let complex = conforming_consistent(&mesh, BoundaryCondition::Tangential);
    let compiled = constraints(&complex, &mesh, 2, 5);
    let by_id = |id: &str| compiled.iter().find(|c| c.id == id).expect("compiled");
    // The divergence of a consistent M0 is dense over the field; its origin names the node.
    let source = by_id("source");
    assert!(source.rows[0].len() > complex.field_dimension() / 2);
    match &source.origins[0] {
        // div = −M0⁻¹ d0ᵀ M1: minus the unit weight of the node.
        RowOrigin::Potential(a) => assert!(a.len() == 1 && a[0].1 == -1.0, "{a:?}"),
        other => panic!("divergence origin {other:?}"),
    }
    // The curl lives on the lumped CR space: a sparse row, origin still the co-potential node.
    assert!(matches!(
        by_id("vortex").origins[0],
        RowOrigin::CoPotential(_)
    ));
    assert!(by_id("vortex").rows[0].len() <= 8);
    // The other family's curl goes through M0⁻¹: composed; its divergence through the lumped
    // M2 and M1: a sparse row.
    assert_eq!(by_id("curl-other").origins[0], RowOrigin::Composed);
    assert_eq!(by_id("div-other").origins[0], RowOrigin::Field);
    assert!(by_id("v0").origins.iter().all(|o| *o == RowOrigin::Field));
    // In the full system neither the dense divergence row (a row of p) nor the dense row of the
    // other family's curl (an unknown of its own, eliminated last) fills the field block: the
    // factor grows by about one column.
    let mesh = icosphere(2);
    let complex = conforming_consistent(&mesh, BoundaryCondition::Tangential);
    let compiled = constraints(&complex, &mesh, 2, 5);
    let dense: Vec<CompiledConstraint> = compiled
        .into_iter()
        .filter(|c| c.id == "source" || c.id == "curl-other")
        .collect();
    assert!(dense
        .iter()
        .all(|c| c.rows[0].len() > complex.field_dimension() / 2));
    let entries = |constraints: Vec<CompiledConstraint>| {
        FullSoftDesign::new(&complex, options(&complex, 0.1), constraints)
            .expect("design")
            .factor_entries()
    };
    let (without, with) = (entries(Vec::new()), entries(dense));
    println!("factor entries: {without} without constraints, {with} with two dense rows");
    assert!(
        with - without < 8 * complex.field_dimension(),
        "{without} → {with}"
    );
}

#[test]
fn changing_constraints_refactors_and_matches_a_fresh_design() {
    let mesh = jitter(&icosphere(2), 0.2, 8).expect("mesh");
    let complex = conforming_consistent(&mesh, BoundaryCondition::Tangential);
    let opts = options(&complex, 0.1);
    let first = constraints(&complex, &mesh, 5, 1);
    let second = constraints(&complex, &mesh, 7, 2);
    let mut design = FullSoftDesign::new(&complex, opts, first.clone()).expect("design");
    assert_eq!(design.symbolic_analyses(), 1);
    // New values, same rows: a numeric refactorization.
    let mut moved = first.clone();
    for c in &mut moved {
        let values: Vec<f64> = c.values.iter().map(|v| 2.0 * v - 0.3).collect();
        c.set_values(&values).unwrap();
    }
    assert!(design.set_constraints(moved.clone()).expect("refactor"));
    assert_eq!(design.symbolic_analyses(), 1);
    let dense = dense_soft_design(&complex, opts, &moved);
    let error = mass_relative_difference(&complex, &design.solve().0, &dense);
    assert!(error < 1e-9, "same rows, new values: {error:e}");
    // Other constraints: the pattern (and the dense rows' unknowns) may change.
    let reused = design.set_constraints(second.clone()).expect("refactor");
    assert_eq!(design.symbolic_analyses(), if reused { 1 } else { 2 });
    assert_eq!(design.timings().symbolic, !reused);
    let (x, report) = design.solve();
    assert!(report.meets(1e-10), "{:?}", report.residuals);
    let fresh = FullSoftDesign::new(&complex, opts, second.clone())
        .expect("fresh")
        .solve()
        .0;
    let dense = dense_soft_design(&complex, opts, &second);
    let (to_fresh, to_dense) = (
        mass_relative_difference(&complex, &x, &fresh),
        mass_relative_difference(&complex, &x, &dense),
    );
    println!("refactored vs fresh {to_fresh:.2e}, vs dense {to_dense:.2e}");
    assert!(
        to_fresh < 1e-10 && to_dense < 1e-9,
        "{to_fresh:e} {to_dense:e}"
    );
    // Back to the first set: its sparse entries are in the union pattern now.
    let reused = design.set_constraints(first.clone()).expect("refactor");
    let back = design.solve().0;
    let dense = dense_soft_design(&complex, opts, &first);
    let error = mass_relative_difference(&complex, &back, &dense);
    println!("back to the first set (symbolic analysis reused: {reused}): vs dense {error:.2e}");
    assert!(error < 1e-9, "{error:e}");
}

#[test]
fn orderings_and_threading_give_the_same_field() {
    let mesh = icosphere(2);
    let complex = whitney_galerkin(&mesh, BoundaryCondition::Tangential);
    let opts = options(&complex, 0.1);
    let compiled = constraints(&complex, &mesh, 6, 4);
    let field = |ordering, parallelism| {
        let design =
            FullSoftDesign::of_complex(&complex, opts, compiled.clone(), ordering, parallelism)
                .expect("design");
        assert_eq!(design.ordering(), ordering);
        assert!(design.factor_entries() > 0 && design.factor_flop_count() > 0.0);
        design.solve().0
    };
    let nd = field(
        FillOrdering::NestedDissection,
        FactorParallelism::Sequential,
    );
    let amd = field(FillOrdering::Amd, FactorParallelism::Sequential);
    let parallel = field(FillOrdering::NestedDissection, FactorParallelism::Parallel);
    for other in [&amd, &parallel] {
        let difference = mass_relative_difference(&complex, other, &nd);
        assert!(difference < 1e-11, "{difference:e}");
    }
}

#[test]
fn reference_spline_matches_the_dense_kkt_system() {
    let sphere = jitter(&icosphere(1), 0.2, 2).expect("mesh");
    let ico = icosphere(1);
    let check = |name: &str, complex: &dyn HodgeComplex, mesh: &TriangleMesh| {
        let compiled = constraints(complex, mesh, 4, 6);
        for (omega, epsilon) in [(0.1, 0.0), (0.0, 0.0), (0.1, 1e-3)] {
            let spline = reference_spline(complex, omega, epsilon, &compiled).expect("spline");
            for report in &spline.solve_reports {
                assert!(report.meets(1e-10), "{name}: {:?}", report.residuals);
            }
            let dense = dense_spline(complex, omega, epsilon, &compiled);
            let error = mass_relative_difference(complex, &spline.field, &dense);
            let steps = spline
                .solve_reports
                .iter()
                .map(|r| r.residuals.len() - 1)
                .max()
                .unwrap_or(0);
            println!(
                "{name} ω = {omega} ε = {epsilon}: relative M1 difference to dense {error:.2e} \
                 (at most {steps} refinement steps)"
            );
            assert!(error < 1e-9, "{name} ω = {omega} ε = {epsilon}: {error:e}");
            for c in &compiled {
                let r = tvf_design::residual(c, &spline.field);
                assert!(r.relative < 1e-9, "{name}: {} {:e}", c.id, r.relative);
            }
        }
    };
    check(
        "conforming, consistent M0",
        &conforming_consistent(&sphere, BoundaryCondition::Tangential),
        &sphere,
    );
    check(
        "nonconforming, M2⁻¹ consistent",
        &nonconforming_consistent(&sphere),
        &sphere,
    );
    check(
        "Whitney M1, consistent M0",
        &whitney_galerkin(&ico, BoundaryCondition::Tangential),
        &ico,
    );
    check(
        "coupled face M1",
        &conforming_coupled_fields(&sphere),
        &sphere,
    );
}

/// The complete eigenbasis of `complex` (sparse and mixed pencils), row-major.
fn complete_basis<H: HodgeComplex + ?Sized>(complex: &H) -> ReducedBasis {
    let basis = compute_basis(complex, &BasisRequest::complete()).expect("complete basis");
    assert_eq!(basis.len(), complex.field_dimension());
    truncated(&basis, basis.len())
}

#[test]
fn reduced_solvers_on_complete_eigenbases_equal_the_full_ones() {
    let mesh = icosphere(1);
    let complexes: [(&str, Box<dyn HodgeComplex>); 3] = [
        (
            "conforming, consistent M0",
            Box::new(conforming_consistent(&mesh, BoundaryCondition::Tangential)),
        ),
        (
            "nonconforming, M2⁻¹ consistent",
            Box::new(nonconforming_consistent(&mesh)),
        ),
        (
            "Whitney M1, consistent M0",
            Box::new(whitney_galerkin(&mesh, BoundaryCondition::Tangential)),
        ),
    ];
    for (name, complex) in &complexes {
        let complex = complex.as_ref();
        let basis = complete_basis(complex);
        let compiled = constraints(complex, &mesh, 4, 8);
        // Hard constraints on a sphere (no harmonic field): the reduced spline is the full one.
        let mut session = SplineSession::new(&basis, 0.1).expect("session");
        for c in compiled.iter().cloned() {
            session.add(c).expect("independent");
        }
        let reduced = session.field();
        let full = reference_spline(complex, 0.1, 0.0, &compiled).expect("spline");
        let spline_error = mass_relative_difference(complex, &reduced, &full.field);
        // Soft design: in the eigenbasis Uᵀ S U = Λ, Uᵀ B U = Λ², Uᵀ M1 U = I.
        let opts = options(complex, 0.1);
        let mut soft = ReducedSoftDesign::new(&basis, opts).expect("reduced design");
        soft.add_all(compiled.iter().cloned()).expect("updates");
        let full_soft = FullSoftDesign::new(complex, opts, compiled.clone())
            .expect("full design")
            .solve()
            .0;
        let soft_error = mass_relative_difference(complex, &soft.field(), &full_soft);
        println!(
            "{name}: complete basis of {} fields: spline {spline_error:.2e}, soft design \
             {soft_error:.2e} (relative M1 differences, reduced vs full)",
            basis.len()
        );
        assert!(spline_error < 1e-7, "{name}: spline {spline_error:e}");
        assert!(soft_error < 1e-7, "{name}: soft {soft_error:e}");
    }
}

#[test]
fn editing_a_session_with_dense_rows_keeps_the_field_finite_and_exact() {
    let mesh = icosphere(1);
    let complex = conforming_coupled_fields(&mesh);
    let basis = complete_basis(&complex);
    let assembler = ConstraintAssembler::new(&complex, &mesh);
    let compiled = constraints(&complex, &mesh, 3, 12);
    assert!(compiled
        .iter()
        .any(|c| c.origins.contains(&RowOrigin::Composed)));
    let mut session = SplineSession::new(&basis, 0.1).expect("session");
    for c in compiled.iter().cloned() {
        session.add(c).expect("independent");
    }
    // Drag a composed-row constraint (values only), move it, remove another: as the editor does.
    let other = compiled
        .iter()
        .find(|c| c.origins.contains(&RowOrigin::Composed))
        .expect("a composed row")
        .clone();
    for step in 0..3 {
        let mut dragged = other.clone();
        dragged.set_values(&[0.2 * step as f64 - 0.5]).unwrap();
        session.modify(dragged).expect("value change");
    }
    let moved = assembler
        .compile(
            &Constraint::new(
                other.id.clone(),
                Target::Curl(0.3),
                Location::Face {
                    face: 11,
                    barycentric: Some(vec![0.5, 0.25, 0.25]),
                },
            )
            .with_family(OperatorFamily::Other),
        )
        .expect("compiled");
    session.modify(moved).expect("moved");
    session.remove("v0").expect("removed");
    let field = session.field();
    assert!(field.iter().all(|x| x.is_finite()));
    for r in session.residuals(&field) {
        assert!(r.relative < 1e-9, "{} {:e}", r.id, r.relative);
    }
}
