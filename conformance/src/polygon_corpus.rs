//! The polygon meshes every discretization that accepts polygons is checked on, generated in
//! code: quad tori, cube-spheres, duals of triangle meshes (non-planar pentagons, hexagons and
//! polygons of every valence), quad splits of genus-`g` surfaces, jittered (non-planar) copies,
//! meshes with holes and with several components ([`polygon_corpus`], [`open_polygon_corpus`]).
//! Genus and harmonic dimension are stated from how each mesh is made, independently of its
//! Euler characteristic.

use crate::corpus::CorpusMesh;
use crate::polygon_operations::{beside, jittered, quad_split, without_faces};
use tvf_core::generate::{
    cube_sphere, disk, dual, genus_surface, hemisphere, icosphere, open_cylinder, perforated_plate,
    quad_torus, torus,
};
use tvf_core::SurfaceMesh;

/// A corpus entry of the polygon corpus.
pub type PolygonCorpusMesh = CorpusMesh<SurfaceMesh>;

fn quad_torus_12x6() -> SurfaceMesh {
    quad_torus(1.0, 0.4, 12, 6)
        .expect("valid torus parameters")
        .into()
}

fn cube_sphere_3() -> SurfaceMesh {
    cube_sphere(3).expect("n ≥ 1").into()
}

fn dual_of(mesh: &tvf_core::TriangleMesh) -> SurfaceMesh {
    dual(mesh).expect("the dual of a generated mesh").into()
}

/// Closed polygon meshes: a quad torus (planar quads), the cube-sphere (non-planar quads), the
/// duals of an icosphere and of a genus-2 surface (non-planar pentagons to octagons), the quad
/// split of a genus-3 surface, a jittered dual torus and two components. All small enough for
/// the dense checks.
pub fn polygon_corpus() -> Vec<PolygonCorpusMesh> {
    let dual_torus = dual_of(&torus(1.0, 0.4, 16, 8).expect("valid torus parameters"));
    vec![
        CorpusMesh::new("quad torus 12×6", quad_torus_12x6(), 1),
        CorpusMesh::new("cube-sphere(3)", cube_sphere_3(), 0),
        CorpusMesh::new("dual of icosphere(2)", dual_of(&icosphere(2)), 0),
        CorpusMesh::new(
            "dual of a genus-2 surface",
            dual_of(&genus_surface(2, 2)),
            2,
        ),
        CorpusMesh::new(
            "quad split of a genus-3 surface",
            quad_split(&genus_surface(3, 2)).expect("a valid quad split"),
            3,
        ),
        CorpusMesh::new(
            "jittered dual torus 16×8",
            jittered(&dual_torus, 0.15, 7).expect("a small jitter keeps the polygons valid"),
            1,
        ),
        CorpusMesh::new(
            "quad torus + dual icosphere (two components)",
            beside(&quad_torus_12x6(), &dual_of(&icosphere(1))).expect("a valid union"),
            1,
        ),
    ]
}

/// Polygon meshes with holes (harmonic dimension `2g + b − 1` per component): a quad torus
/// without one quad (g = 1, b = 1), the duals of a disk (b = 1) and of an open cylinder (b = 2),
/// the quad split of a pair of pants (b = 3), a jittered dual hemisphere, and a holed
/// cube-sphere beside a dual disk (two components).
pub fn open_polygon_corpus() -> Vec<PolygonCorpusMesh> {
    let holed_torus = without_faces(&quad_torus_12x6(), &[0]).expect("one quad fewer");
    let holed_sphere = without_faces(&cube_sphere_3(), &[4]).expect("one quad fewer");
    let dual_hemisphere = dual_of(&hemisphere(5));
    vec![
        CorpusMesh::open("quad torus 12×6 with a hole", holed_torus, 1, 2),
        CorpusMesh::open("dual of disk(4)", dual_of(&disk(4)), 0, 0),
        CorpusMesh::open(
            "dual of an open cylinder 16×4",
            dual_of(&open_cylinder(16, 4, 1.0)),
            0,
            1,
        ),
        CorpusMesh::open(
            "quad split of a pair of pants",
            quad_split(&perforated_plate(2, 4)).expect("a valid quad split"),
            0,
            2,
        ),
        CorpusMesh::open(
            "jittered dual of hemisphere(5)",
            jittered(&dual_hemisphere, 0.15, 5).expect("a small jitter keeps the polygons valid"),
            0,
            0,
        ),
        CorpusMesh::open(
            "holed cube-sphere + dual disk (two components)",
            beside(&holed_sphere, &dual_of(&disk(3))).expect("a valid union"),
            0,
            0,
        ),
    ]
}
