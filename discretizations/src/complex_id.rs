//! The id a complex reports: its catalog entry's id on a closed mesh, `{entry id}+{condition}`
//! on a mesh with boundary. Basis files store it and cached bases are named with it, so that a
//! basis of one boundary condition is never taken for the other; [`split_complex_id`] reads it
//! back.

use tvf_core::discretization::BoundaryCondition;
use tvf_core::mesh::MeshTopology;

/// The id of the complex of catalog entry `entry_id` on a mesh of topology `topology`
/// (`mesh.topology()`) with boundary condition `boundary`: `entry_id` on a closed mesh,
/// `{entry_id}+{boundary}` on a mesh with boundary.
pub fn complex_id(entry_id: &str, topology: &MeshTopology, boundary: BoundaryCondition) -> String {
    if topology.is_closed() {
        entry_id.to_string()
    } else {
        format!("{entry_id}+{}", boundary.name())
    }
}

/// Splits a complex id into the catalog entry's id and the boundary condition it names:
/// `conforming-barycentric+normal` → (`conforming-barycentric`, `Some(Normal)`);
/// `conforming-barycentric` → (`conforming-barycentric`, `None`) (a closed mesh). A suffix that
/// names no boundary condition is part of the id: the entry of
/// `dec-barycentric+intrinsic-delaunay+normal` is `dec-barycentric+intrinsic-delaunay` (see
/// [`crate::split_intrinsic_id`]).
pub fn split_complex_id(id: &str) -> (&str, Option<BoundaryCondition>) {
    match id.rsplit_once('+') {
        Some((entry, boundary)) => match BoundaryCondition::from_name(boundary) {
            Some(condition) => (entry, Some(condition)),
            None => (id, None),
        },
        None => (id, None),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::{disk, icosphere};

    #[test]
    fn ids_name_the_condition_on_meshes_with_boundary_only_and_split_back() {
        let closed = icosphere(1);
        assert_eq!(
            complex_id("x-y", closed.topology(), BoundaryCondition::Normal),
            "x-y"
        );
        let open = disk(2);
        let id = complex_id("x-y", open.topology(), BoundaryCondition::Normal);
        assert_eq!(id, "x-y+normal");
        assert_eq!(
            split_complex_id(&id),
            ("x-y", Some(BoundaryCondition::Normal))
        );
        assert_eq!(split_complex_id("x-y"), ("x-y", None));
        assert_eq!(split_complex_id("x+z"), ("x+z", None));
        assert_eq!(
            split_complex_id("x-y+intrinsic-delaunay+normal"),
            ("x-y+intrinsic-delaunay", Some(BoundaryCondition::Normal))
        );
    }
}
