//! [`PolygonDec`]: discrete exterior calculus on polygon meshes (de Goes, Butts, Desbrun 2020),
//! catalog id `polygon-dec`.

use crate::polygon_operators::PolygonOperators;
use crate::polygon_sampling::{PolygonEvaluation, PolygonSampling};
use crate::primal_forms::PrimalForms;
use crate::sampled_complex::SampledComplex;
use tvf_core::discretization::sparse::from_triplets;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass};
use tvf_core::mesh::Mesh;

/// The default weight `β` of the stabilisation term of `M1` (de Goes et al. 2020 and Lagrange's
/// `polyddg` use 1).
pub const DEFAULT_STABILISATION: f64 = 1.0;

/// Polygonal DEC on a mesh of polygons of any size (triangles included), after de Goes, Butts
/// and Desbrun, *Discrete Differential Operators on Polygonal Meshes* (ACM TOG 39(4), 2020):
///
/// ```text
/// 0-forms (V) --d0--> 1-forms (E) --d1--> 2-forms (F)
///     ⋆0              ⋆1                    ⋆2
/// ```
///
/// - `d0`, `d1`, the edge orientation (`a → b`, `a < b`), the node spaces and both boundary
///   conditions (absolute and relative forms) are those of DEC ([`crate::PrimalForms`]).
/// - `M0 = ⋆0` (diagonal, area): vertex `v` gets `Σ_{f ∋ v} A_f / n_f`, each polygon's area
///   split equally among its `n_f` corners.
/// - `M1 = ⋆1 = Σ_f (A_f U_fᵀ U_f + β P_fᵀ P_f)` (sparse, dimensionless), with the sharp `U_f`
///   and the projection `P_f = I − V_f U_f` of [`PolygonOperators`]; symmetric positive definite
///   for `β > 0` on every mesh without a degenerate polygon, with no Delaunay condition. On a
///   triangle mesh it is a new discretization: neither DEC's cotan `⋆1` nor Whitney's mass.
/// - `M2 = ⋆2 = 1/A_f` per face (diagonal, 1/area) on integrated values.
///
/// Sampling ([`PolygonSampling`]): one tangent vector per polygon, the sharp `U_f x` of its
/// sides' 1-form values, in the plane normal to the polygon's vector area; it reproduces the
/// gradients of linear functions ([`tvf_core::discretization::SamplingReproduction::LinearGradients`]).
/// Point evaluation ([`PolygonEvaluation`]): a 0-form at a point is the point's corner weights
/// applied to its corners' values (linear functions exactly); a 2-form is constant per face.
/// There is no rotation `J` on 1-forms.
pub type PolygonDec = SampledComplex<PolygonSampling, PolygonEvaluation>;

impl PolygonDec {
    /// The complex of `mesh` with boundary condition `boundary` (absolute forms for
    /// [`BoundaryCondition::Tangential`], relative forms for [`BoundaryCondition::Normal`]) and
    /// stabilisation weight `beta`. The id is [`polygon_dec_id`]`(beta)`, with `+{boundary}`
    /// appended on a mesh with boundary. Fails for a `beta` that is not positive and finite, or
    /// a polygon of zero area.
    pub fn with_boundary<M: Mesh + ?Sized>(
        mesh: &M,
        boundary: BoundaryCondition,
        beta: f64,
    ) -> Result<Self, DiscretizationError> {
        if !(beta > 0.0 && beta.is_finite()) {
            return Err(DiscretizationError::Inconsistent(format!(
                "polygon-dec needs a positive, finite stabilisation weight β, not {beta}"
            )));
        }
        let operators: Vec<PolygonOperators> = (0..mesh.face_corners().face_count())
            .map(|f| PolygonOperators::of(mesh, f))
            .collect();
        if let Some(face) = operators
            .iter()
            .position(|o| !(o.area > 0.0 && o.area.is_finite()))
        {
            return Err(DiscretizationError::DegenerateFace {
                face,
                area: operators[face].area,
            });
        }
        let forms = PrimalForms::new(mesh, boundary);
        let nodes = &forms.nodes;
        let masses = [
            Mass::diagonal_positive_on_used_nodes(
                "M0 (polygon vertex areas ⋆0)",
                vertex_areas(mesh, &operators),
                &nodes[0].components,
            )?,
            Mass::sparse(
                "M1 (the polygonal Hodge star ⋆1)",
                one_form_inner_product(mesh, &operators, beta),
            )?,
            Mass::diagonal_positive_on_used_nodes(
                "M2 (inverse polygon areas ⋆2)",
                operators.iter().map(|o| 1.0 / o.area).collect(),
                &nodes[2].components,
            )?,
        ];
        let sampling = PolygonSampling::new(mesh, &operators, nodes[1].dirichlet.clone());
        let parts = forms.into_parts(&polygon_dec_id(beta), mesh, boundary, masses)?;
        Ok(Self::from_parts(
            parts,
            sampling,
            PolygonEvaluation::new(mesh),
        ))
    }
}

/// The catalog id of polygonal DEC with stabilisation `beta`: `polygon-dec` for the default
/// `β = 1`, else `polygon-dec-beta-{β}` with `β` as its shortest round-trip decimal and `p` for
/// the decimal point, so the id stays kebab-case (`0.5` → `polygon-dec-beta-0p5`).
pub fn polygon_dec_id(beta: f64) -> String {
    if beta == DEFAULT_STABILISATION {
        "polygon-dec".to_string()
    } else {
        format!("polygon-dec-beta-{}", beta.to_string().replace('.', "p"))
    }
}

/// `⋆0`: every polygon's area split equally among its corners (`V` entries, area).
fn vertex_areas<M: Mesh + ?Sized>(mesh: &M, operators: &[PolygonOperators]) -> Vec<f64> {
    let mut areas = vec![0.0; mesh.positions().len()];
    for (f, ops) in operators.iter().enumerate() {
        let corners = mesh.face_corners().corners(f);
        let share = ops.area / corners.len() as f64;
        for &v in corners {
            areas[v] += share;
        }
    }
    areas
}

/// `⋆1 = Σ_f M_f` scattered onto the mesh's edges (`E × E`, sparse, symmetric).
fn one_form_inner_product<M: Mesh + ?Sized>(
    mesh: &M,
    operators: &[PolygonOperators],
    beta: f64,
) -> sprs::CsMat<f64> {
    let (mut rows, mut cols, mut values) = (Vec::new(), Vec::new(), Vec::new());
    for (f, ops) in operators.iter().enumerate() {
        let n = ops.side_count();
        let local = ops.inner_product(beta);
        for i in 0..n {
            for j in 0..n {
                rows.push(mesh.face_edge(f, i));
                cols.push(mesh.face_edge(f, j));
                values.push(local[i * n + j]);
            }
        }
    }
    let e = mesh.topology().edges().len();
    from_triplets(e, e, rows, cols, values)
}
