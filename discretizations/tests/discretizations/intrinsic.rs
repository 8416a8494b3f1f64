//! Catalog entries on the intrinsic Delaunay triangulation (`ENTRY+intrinsic-delaunay`,
//! `ENTRY+intrinsic-delaunay-refine`): the input's complex bit for bit on Delaunay inputs, DEC
//! with positive `⋆1` on every mesh, and fields, potentials and constraints seen on the input
//! faces through the correspondence. Property tests over generated meshes (proptest shrinks a
//! failure to the smallest mesh, jitter and stretch).

use proptest::prelude::*;
use sprs::CsMat;
use tvf_core::discretization::sparse::{diagonal, linear_combination, product};
use tvf_core::discretization::{
    BoundaryCondition, DiscretizationError, HodgeComplex, HodgeOperators,
};
use tvf_core::generate::{
    disk, genus_surface, hemisphere, icosphere, jitter, open_cylinder, rigid_motion, torus,
};
use tvf_core::geometry::{dot, norm, sub};
use tvf_core::{SurfacePoint, TriangleMesh};
use tvf_discretizations::{
    build_complex, catalog_entry, complex_id, intrinsic_entry_id, Catalog, Conforming, DecComplex,
    ElementFamily, IntrinsicDec, IntrinsicDelaunay, IntrinsicFiniteElement, IntrinsicInput,
    IntrinsicWhitneyGalerkin, MassLumping, Nonconforming, SpaceMasses, WhitneyGalerkin,
    DELAUNAY_TOLERANCE,
};

/// `mesh` with every position scaled by `factors` per axis (thin, obtuse, non-Delaunay faces).
fn stretched(mesh: &TriangleMesh, factors: [f64; 3]) -> TriangleMesh {
    let positions = mesh
        .positions()
        .iter()
        .map(|p| std::array::from_fn(|k| p[k] * factors[k]))
        .collect();
    TriangleMesh::new(positions, mesh.faces().to_vec()).expect("stretching keeps a mesh valid")
}

/// A flat square grid of `n × n` cells in the plane z = 0, each cell cut along a diagonal whose
/// direction alternates, jittered in the plane by `amplitude` cells: flat, with boundary, and
/// (for amplitude > 0) not Delaunay.
fn flat_grid(n: usize, amplitude: f64, seed: u64) -> TriangleMesh {
    let index = |i: usize, j: usize| j * (n + 1) + i;
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut random = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    let positions = (0..=n)
        .flat_map(|j| (0..=n).map(move |i| (i, j)))
        .map(|(i, j)| {
            let inside = i > 0 && j > 0 && i < n && j < n;
            let (dx, dy) = if inside {
                (amplitude * random(), amplitude * random())
            } else {
                (0.0, 0.0)
            };
            [i as f64 + dx, j as f64 + dy, 0.0]
        })
        .collect::<Vec<_>>();
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (
                index(i, j),
                index(i + 1, j),
                index(i + 1, j + 1),
                index(i, j + 1),
            );
            if (i + j) % 2 == 0 {
                faces.extend([[a, b, c], [a, c, d]]);
            } else {
                faces.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    TriangleMesh::new(positions, faces).expect("a jittered grid stays valid")
}

/// Generated meshes, jittered and stretched into non-Delaunay shapes: closed of genus 0 to 2 and
/// with boundary.
fn non_delaunay_mesh() -> impl Strategy<Value = (String, TriangleMesh)> {
    let base = prop_oneof![
        (0u32..=2).prop_map(|l| (format!("icosphere({l})"), icosphere(l))),
        (6usize..=12, 4usize..=7).prop_map(|(a, t)| (
            format!("torus({a}, {t})"),
            torus(2.0, 0.7, a, t).expect("torus")
        )),
        Just(("genus_surface(2, 2)".to_string(), genus_surface(2, 2))),
        (1usize..=3).prop_map(|r| (format!("disk({r})"), disk(r))),
        (1usize..=3).prop_map(|r| (format!("hemisphere({r})"), hemisphere(r))),
        (4usize..=8).prop_map(|a| (format!("open_cylinder({a})"), open_cylinder(a, 3, 1.5))),
    ];
    (
        base,
        0.0..0.35f64,
        any::<u64>(),
        (0.3..3.0f64, 0.3..3.0f64, 0.3..3.0f64),
    )
        .prop_filter_map(
            "a face jitter made degenerate",
            |((name, mesh), a, seed, (x, y, z))| {
                let jittered = jitter(&mesh, a, seed).ok()?;
                let mesh = stretched(&jittered, [x, y, z]);
                let degenerate = (0..mesh.face_count())
                    .any(|t| mesh.face_area(t).is_nan() || mesh.face_area(t) <= 1e-9);
                (!degenerate).then(|| {
                    (
                        format!(
                            "{name} jitter {a:.3} seed {seed} stretch [{x:.2}, {y:.2}, {z:.2}]"
                        ),
                        mesh,
                    )
                })
            },
        )
}

/// A flat patch of equilateral triangles (`n × n` rhombic cells) in the plane z = 0: Delaunay,
/// with boundary (the boundary edges face 60° angles).
fn lattice_patch(n: usize) -> TriangleMesh {
    let index = |i: usize, j: usize| j * (n + 1) + i;
    let positions = (0..=n)
        .flat_map(|j| {
            (0..=n).map(move |i| [i as f64 + 0.5 * j as f64, j as f64 * 0.75f64.sqrt(), 0.0])
        })
        .collect();
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push([index(i, j), index(i + 1, j), index(i, j + 1)]);
            faces.push([index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    TriangleMesh::new(positions, faces).expect("valid patch")
}

/// Delaunay inputs: icospheres and flat lattice patches (with boundary), turned and moved
/// rigidly, scaled.
fn delaunay_mesh() -> impl Strategy<Value = (String, TriangleMesh)> {
    let base = prop_oneof![
        (0u32..=2).prop_map(|l| (format!("icosphere({l})"), icosphere(l))),
        (1usize..=4).prop_map(|n| (format!("lattice_patch({n})"), lattice_patch(n))),
    ];
    (
        base,
        (-1.0..1.0f64, -1.0..1.0f64, 0.2..1.0f64),
        0.0..6.0f64,
        0.1..10.0f64,
    )
        .prop_map(|((name, mesh), axis, angle, size)| {
            let scaled = stretched(&mesh, [size; 3]);
            let axis = [axis.0, axis.1, axis.2];
            let moved = rigid_motion(&scaled, axis, angle, [0.5, -1.0, 2.0]).expect("finite");
            (format!("{name} size {size:.2}"), moved)
        })
}

/// Every built-in triangle entry's complex on the intrinsic Delaunay triangulation of a
/// Delaunay input is the input's complex, matrix for matrix, bit for bit; only the id differs.
fn same_as_input(mesh: &TriangleMesh, name: &str) -> Result<(), TestCaseError> {
    for entry in Catalog::builtin().iter().filter(|e| e.needs_triangles()) {
        let input = entry.build(mesh).expect("builds on a Delaunay input");
        for mode in IntrinsicDelaunay::ALL {
            let intrinsic = entry.on_intrinsic_delaunay(mode).build(mesh);
            let intrinsic = intrinsic.map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
            let id = intrinsic_entry_id(entry.id(), mode);
            let boundary = entry.default_boundary();
            prop_assert_eq!(intrinsic.id(), complex_id(&id, mesh.topology(), boundary));
            prop_assert_eq!(intrinsic.d0(), input.d0(), "{}: {}", name, entry.id());
            prop_assert_eq!(intrinsic.d1(), input.d1(), "{}: {}", name, entry.id());
            prop_assert_eq!(intrinsic.matrix_hash(), input.matrix_hash());
            let tri = intrinsic
                .intrinsic_triangulation()
                .expect("carries its triangulation");
            prop_assert_eq!(tri.flip_count(), 0);
            prop_assert_eq!(tri.inserted_vertex_count(), 0);
        }
    }
    Ok(())
}

/// `IntrinsicDec` built from the lengths of a Delaunay input (no flip) against `DecComplex` built
/// from its positions: the same incidences bit for bit, the stars, node positions and sampled
/// fields to round-off ([`agrees_with_positions`]), for both lumpings and both boundary
/// conditions.
fn agrees_with_dec_from_positions(mesh: &TriangleMesh, name: &str) -> Result<(), TestCaseError> {
    let input = IntrinsicInput::new(mesh, IntrinsicDelaunay::Flip).expect("builds");
    prop_assert_eq!(input.triangulation.flip_count(), 0);
    let signs = reversed_edge_signs(mesh, &input);
    let flip = diagonal(&signs);
    for lumping in [MassLumping::Barycentric, MassLumping::Voronoi] {
        for boundary in BoundaryCondition::ALL {
            let Ok(expected) = DecComplex::with_boundary(mesh, lumping, boundary) else {
                continue;
            };
            let id = expected.id().to_string();
            let ours = IntrinsicDec::new(mesh, &input, &id, lumping, boundary)
                .map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
            prop_assert_eq!(ours.d0(), &product(&flip, expected.d0()), "{}", name);
            prop_assert_eq!(ours.d1(), &product(expected.d1(), &flip), "{}", name);
            agrees_with_positions(&ours, &expected, &signs, name)?;
        }
    }
    Ok(())
}

/// `+1` per edge of `mesh` whose reference direction in the (unflipped) intrinsic triangulation
/// of `input` is the input's `a → b`, `−1` where it is reversed (a boundary edge whose face lies
/// on the right of `a → b`).
fn reversed_edge_signs(mesh: &TriangleMesh, input: &IntrinsicInput) -> Vec<f64> {
    (0..mesh.edge_count())
        .map(|e| {
            if input.triangulation.edge_vertices(e) == mesh.edges()[e] {
                1.0
            } else {
                -1.0
            }
        })
        .collect()
}

/// The largest entry of `|a − b|` over the largest entry of `|b|` (0 for two zero matrices).
fn relative_difference(a: &CsMat<f64>, b: &CsMat<f64>) -> f64 {
    let difference = linear_combination(1.0, a, -1.0, b);
    let largest = |m: &CsMat<f64>| m.data().iter().fold(0.0f64, |x, y| x.max(y.abs()));
    let scale = largest(b);
    if scale == 0.0 {
        largest(&difference)
    } else {
        largest(&difference) / scale
    }
}

/// `ours` (built from the lengths of a Delaunay input) against `expected` (built from its
/// positions): `d0`, `d1`, the three stored masses and `J` to 1e-12 relative, with the field
/// coefficients of `ours` multiplied by `field_signs` (the boundary edges whose reference
/// direction is reversed, for 1-forms; all `+1` for face fields); the nodes; fields sampled at the
/// input faces and turned back into fields; potentials evaluated at input points.
fn agrees_with_positions(
    ours: &dyn HodgeComplex,
    expected: &dyn HodgeComplex,
    field_signs: &[f64],
    name: &str,
) -> Result<(), TestCaseError> {
    let s = diagonal(field_signs);
    let pairs = [
        ("d0", ours.d0().clone(), product(&s, expected.d0())),
        ("d1", ours.d1().clone(), product(expected.d1(), &s)),
        (
            "M0",
            ours.m0().stored_matrix(),
            expected.m0().stored_matrix(),
        ),
        (
            "M1",
            ours.m1().stored_matrix(),
            product(&s, &product(&expected.m1().stored_matrix(), &s)),
        ),
        (
            "M2",
            ours.m2().stored_matrix(),
            expected.m2().stored_matrix(),
        ),
    ];
    for (what, a, b) in pairs {
        prop_assert_eq!(a.shape(), b.shape(), "{}: {} shape", name, what);
        let error = relative_difference(&a, &b);
        prop_assert!(error <= 1e-12, "{}: {} differs by {:e}", name, what, error);
    }
    prop_assert_eq!(ours.m0().form(), expected.m0().form());
    prop_assert_eq!(ours.m2().form(), expected.m2().form());
    prop_assert_eq!(ours.rotation().is_some(), expected.rotation().is_some());
    if let (Some(a), Some(b)) = (ours.rotation(), expected.rotation()) {
        prop_assert_eq!(a.rotation(), b.rotation());
    }
    for (a, b) in [
        (ours.potential_nodes(), expected.potential_nodes()),
        (ours.field_nodes(), expected.field_nodes()),
        (ours.co_potential_nodes(), expected.co_potential_nodes()),
    ] {
        prop_assert_eq!(a.kind, b.kind);
        prop_assert_eq!(&a.dirichlet, &b.dirichlet);
        prop_assert_eq!(&a.components, &b.components);
        prop_assert_eq!(&a.constant_kernel, &b.constant_kernel);
        for (p, q) in a.positions.iter().zip(&b.positions) {
            prop_assert!(
                norm(sub(*p, *q)) <= 1e-12 * (1.0 + norm(*q)),
                "{}: node",
                name
            );
        }
    }
    prop_assert_eq!(ours.topology(), expected.topology());
    let fixed = &expected.field_nodes().dirichlet;
    let field: Vec<f64> = (0..expected.field_dimension())
        .map(|i| {
            if fixed[i] {
                0.0
            } else {
                (i as f64 * 0.71).cos()
            }
        })
        .collect();
    let signed: Vec<f64> = field.iter().zip(field_signs).map(|(x, s)| x * s).collect();
    let (sampled, reference) = (ours.sampling().unwrap(), expected.sampling().unwrap());
    let a = sampled.to_face_vectors(&signed).unwrap();
    let b = reference.to_face_vectors(&field).unwrap();
    let scale = b.iter().fold(0.0f64, |m, v| m.max(norm(*v)));
    for (v, w) in a.iter().zip(&b) {
        prop_assert!(
            norm(sub(*v, *w)) <= 1e-10 * scale,
            "{}: {:?} vs {:?}",
            name,
            v,
            w
        );
    }
    let back = sampled.from_face_vectors(&b).unwrap().field;
    let expected_back = reference.from_face_vectors(&b).unwrap().field;
    let scale = expected_back.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for ((x, y), s) in back.iter().zip(&expected_back).zip(field_signs) {
        prop_assert!(
            (x - s * y).abs() <= 1e-10 * scale,
            "{}: {} vs {}",
            name,
            x,
            y
        );
    }
    let (ours_at, expected_at) = (
        ours.point_evaluation().unwrap(),
        expected.point_evaluation().unwrap(),
    );
    let point = SurfacePoint::barycentric(0, [0.2, 0.5, 0.3]);
    for (mut a, mut b) in [
        (
            ours_at.potential_weights(&point),
            expected_at.potential_weights(&point),
        ),
        (
            ours_at.co_potential_weights(&point),
            expected_at.co_potential_weights(&point),
        ),
    ] {
        a.sort_by_key(|&(i, _)| i);
        b.sort_by_key(|&(i, _)| i);
        prop_assert_eq!(a.len(), b.len());
        for ((i, x), (j, y)) in a.into_iter().zip(b) {
            prop_assert!(i == j && (x - y).abs() <= 1e-12, "{}: weights", name);
        }
    }
    Ok(())
}

/// The finite element complexes and Whitney forms built from the lengths of a Delaunay input (no
/// flip) against the same complexes built from its positions, for every mass choice and both
/// boundary conditions.
fn finite_elements_and_whitney_agree_with_positions(
    mesh: &TriangleMesh,
    name: &str,
) -> Result<(), TestCaseError> {
    let input = IntrinsicInput::new(mesh, IntrinsicDelaunay::Flip).expect("builds");
    prop_assert_eq!(input.triangulation.flip_count(), 0);
    let edge_signs = reversed_edge_signs(mesh, &input);
    let frame_signs = vec![1.0; 2 * mesh.face_count()];
    let failed = |e: DiscretizationError| TestCaseError::fail(format!("{name}: {e}"));
    let masses = [
        SpaceMasses::Lumped(MassLumping::Barycentric),
        SpaceMasses::Lumped(MassLumping::Voronoi),
        SpaceMasses::Consistent,
    ];
    for boundary in BoundaryCondition::ALL {
        for masses in masses {
            for family in [ElementFamily::Conforming, ElementFamily::Nonconforming] {
                let expected: Box<dyn HodgeComplex> = match family {
                    ElementFamily::Conforming => {
                        Box::new(Conforming::from_mesh(mesh, masses, boundary).map_err(failed)?)
                    }
                    ElementFamily::Nonconforming => {
                        Box::new(Nonconforming::from_mesh(mesh, masses, boundary).map_err(failed)?)
                    }
                };
                let ours = IntrinsicFiniteElement::new(
                    mesh,
                    &input,
                    expected.id(),
                    family,
                    masses,
                    boundary,
                )
                .map_err(failed)?;
                let what = format!("{name}: {family:?} {masses:?} {boundary:?}");
                agrees_with_positions(&ours, expected.as_ref(), &frame_signs, &what)?;
            }
        }
        let expected = WhitneyGalerkin::with_boundary(mesh, boundary).map_err(failed)?;
        let ours =
            IntrinsicWhitneyGalerkin::new(mesh, &input, expected.id(), boundary).map_err(failed)?;
        let what = format!("{name}: whitney-galerkin {boundary:?}");
        agrees_with_positions(&ours, &expected, &edge_signs, &what)?;
    }
    Ok(())
}

proptest! {
    #[test]
    fn finite_elements_and_whitney_from_lengths_agree_with_positions((name, mesh) in delaunay_mesh()) {
        finite_elements_and_whitney_agree_with_positions(&mesh, &name)?;
    }

    #[test]
    fn intrinsic_dec_from_lengths_agrees_with_dec_from_positions((name, mesh) in delaunay_mesh()) {
        agrees_with_dec_from_positions(&mesh, &name)?;
    }

    #[test]
    fn on_a_delaunay_input_every_entry_is_the_input_complex_bit_for_bit((name, mesh) in delaunay_mesh()) {
        same_as_input(&mesh, &name)?;
    }

    /// Refinement makes DEC build on every mesh with every `⋆1` positive, the input's total area
    /// in `⋆0` and `⋆2⁻¹`, the input's Euler characteristic, and `d1 d0 = 0`.
    #[test]
    fn refined_dec_builds_on_every_mesh((name, mesh) in non_delaunay_mesh()) {
        for id in ["dec-circumcentric", "dec-barycentric"] {
            for boundary in BoundaryCondition::ALL {
                let id = intrinsic_entry_id(id, IntrinsicDelaunay::Refine);
                let complex = build_complex(&id, Some(boundary), &mesh)
                    .map_err(|e| TestCaseError::fail(format!("{name}: {e}")))?;
                check_dec(complex.as_ref(), &mesh, &name)?;
            }
        }
    }

    /// Flips alone: DEC builds with every `⋆1` positive, or refuses naming edges that are
    /// cocircular or on the boundary (never a negative interior edge), with the advice to refine.
    #[test]
    fn flipped_dec_builds_or_names_what_refinement_cures((name, mesh) in non_delaunay_mesh()) {
        let id = intrinsic_entry_id("dec-circumcentric", IntrinsicDelaunay::Flip);
        let entry = catalog_entry("dec-circumcentric").expect("built in");
        match entry.on_intrinsic_delaunay(IntrinsicDelaunay::Flip).build(&mesh) {
            Ok(complex) => check_dec(complex.as_ref(), &mesh, &name)?,
            Err(DiscretizationError::NotStrictlyDelaunayAfterFlips { count, edges, .. }) => {
                prop_assert!(count >= edges.len() && !edges.is_empty());
                let error = build_complex(&id, None, &mesh).err().expect("refused").to_string();
                prop_assert!(error.contains("--intrinsic-delaunay=refine"), "{}", error);
            }
            Err(other) => prop_assert!(false, "{}: {}", name, other),
        }
    }

    /// On a flat mesh the sampling through the correspondence is exact: a constant vector comes
    /// back from `from_face_vectors` and the gradient of a linear function sampled at the
    /// potential nodes is that function's gradient, at every input face.
    #[test]
    fn on_a_flat_mesh_constants_and_gradients_come_back(n in 2usize..=5, amplitude in 0.0..0.35f64, seed in any::<u64>(), refine in any::<bool>()) {
        let mesh = flat_grid(n, amplitude, seed);
        let mode = if refine { IntrinsicDelaunay::Refine } else { IntrinsicDelaunay::Flip };
        let entry = catalog_entry("dec-barycentric").expect("built in").on_intrinsic_delaunay(mode);
        let complex = match entry.build(&mesh) {
            Ok(complex) => complex,
            // A grid keeps cocircular cells and obtuse boundary corners: flips alone may refuse.
            Err(DiscretizationError::NotStrictlyDelaunayAfterFlips { .. }) if !refine => return Ok(()),
            Err(error) => return Err(TestCaseError::fail(error.to_string())),
        };
        let sampling = complex.sampling().expect("samples");
        let v = [0.3, -1.2, 0.0];
        let field = sampling.from_face_vectors(&vec![v; mesh.face_count()]).unwrap().field;
        for w in sampling.to_face_vectors(&field).unwrap() {
            prop_assert!(norm(sub(w, v)) < 1e-12, "{:?} vs {:?}", w, v);
        }
        let gradient = [0.7, 0.4, 0.0];
        let phi: Vec<f64> = complex.potential_nodes().positions.iter().map(|p| dot(*p, gradient)).collect();
        let d0phi = tvf_core::discretization::sparse::mul_vec(complex.d0(), &phi);
        for w in sampling.to_face_vectors(&d0phi).unwrap() {
            prop_assert!(norm(sub(w, gradient)) < 1e-12, "{:?} vs {:?}", w, gradient);
        }
        // Potentials: the linear function evaluated at input points is its value there.
        let evaluation = complex.point_evaluation().expect("evaluates");
        for face in 0..mesh.face_count() {
            let point = SurfacePoint::barycentric(face, [0.2, 0.5, 0.3]);
            let corners = mesh.faces()[face].map(|i| mesh.positions()[i]);
            let x: [f64; 3] = std::array::from_fn(|k| 0.2 * corners[0][k] + 0.5 * corners[1][k] + 0.3 * corners[2][k]);
            let value: f64 = evaluation.potential_weights(&point).iter().map(|&(i, w)| w * phi[i]).sum();
            prop_assert!((value - dot(x, gradient)).abs() < 1e-12);
        }
    }
}

/// The checks of a DEC complex on an intrinsic triangulation of `mesh`.
fn check_dec(
    complex: &dyn HodgeComplex,
    mesh: &TriangleMesh,
    name: &str,
) -> Result<(), TestCaseError> {
    let tri = complex
        .intrinsic_triangulation()
        .expect("built on an intrinsic triangulation");
    let star = complex.m1().diagonal_values().expect("diagonal ⋆1");
    prop_assert!(
        star.iter().all(|&s| 2.0 * s > DELAUNAY_TOLERANCE),
        "{}: ⋆1 not positive",
        name
    );
    let area = mesh.total_area();
    let mut totals = vec![("⋆2⁻¹", tri.total_area())];
    if complex.potential_nodes().dirichlet_count() == 0 {
        totals.push(("⋆0", complex.m0().total()));
    }
    for (what, total) in totals {
        prop_assert!(
            (total - area).abs() <= 1e-11 * area,
            "{}: {} sums to {} not {}",
            name,
            what,
            total,
            area
        );
    }
    let euler = tri.vertex_count() as i64 - tri.edge_count() as i64 + tri.face_count() as i64;
    prop_assert_eq!(euler, mesh.euler_characteristic());
    let d1d0 = complex.d1() * complex.d0();
    prop_assert!(d1d0.data().iter().all(|&x| x == 0.0), "{}: d1 d0 ≠ 0", name);
    // Every sampled vector is tangent to its input face.
    let sampling = complex.sampling().expect("samples");
    let fixed = &complex.field_nodes().dirichlet;
    let field: Vec<f64> = (0..complex.field_dimension())
        .map(|i| {
            if fixed[i] {
                0.0
            } else {
                (i as f64 * 0.37).sin()
            }
        })
        .collect();
    for (t, w) in sampling.to_face_vectors(&field).unwrap().iter().enumerate() {
        let normal = sampling.normal(t);
        prop_assert!(
            dot(*w, normal).abs() <= 1e-9 * (1.0 + norm(*w)),
            "{}: face {}",
            name,
            t
        );
    }
    Ok(())
}

/// `polygon-dec` reads positions and vector areas: with the modifier it is refused on every mesh,
/// triangles and polygons alike, with the error that says why and what to do.
#[test]
fn polygon_dec_is_refused_on_every_mesh_with_the_modifier() {
    let quads = tvf_core::SurfaceMesh::from(
        tvf_core::generate::quad_torus(1.0, 0.4, 8, 4).expect("a quad torus"),
    );
    let triangles = tvf_core::SurfaceMesh::from(icosphere(1));
    let entry = catalog_entry("polygon-dec").expect("built in");
    assert!(!entry.builds_on_intrinsic());
    for mode in IntrinsicDelaunay::ALL {
        for mesh in [&quads, &triangles] {
            match entry.on_intrinsic_delaunay(mode).build(mesh) {
                Err(DiscretizationError::PolygonEntryNotIntrinsic { discretization }) => {
                    assert_eq!(discretization, "polygon-dec");
                }
                Err(other) => panic!("{other}"),
                Ok(_) => panic!("polygon-dec built on an intrinsic triangulation"),
            }
        }
    }
    let error = build_complex("polygon-dec+intrinsic-delaunay", None, &triangles)
        .err()
        .expect("refused")
        .to_string();
    assert!(error.contains("vector areas"), "{error}");
}
