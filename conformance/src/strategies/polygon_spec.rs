//! Polygon meshes as small descriptions ([`PolygonShape`], [`PolygonMeshSpec`]) and their
//! strategy ([`polygon_mesh_specs`]): quad tori, cube-spheres, genus-`g` quad surfaces (quad
//! splits of genus-`g` triangle surfaces, `g` 0–5), duals of triangle meshes (non-planar
//! polygons of every valence), holes, several components, jitter (non-planar polygons) and rigid
//! motions. Shrinking works on the description, so every shrunk mesh is again a polygon mesh of
//! these kinds — towards one component, simpler shapes, lower genus, no jitter, no motion.

use super::perturbation::{jitters, rigid_motions, Jitter, RigidMotion};
use crate::polygon_corpus::PolygonCorpusMesh;
use crate::polygon_operations::{beside, jittered, moved, quad_split, without_faces};
use proptest::prelude::*;
use tvf_core::generate::{
    cube_sphere, disk, dual, genus_surface, icosphere, open_cylinder, perforated_plate, quad_torus,
};
use tvf_core::SurfaceMesh;

/// Highest genus of the generated quad and dual surfaces.
pub const MAX_POLYGON_GENUS: usize = 5;

/// Largest jitter amplitude of polygon meshes (a fraction of the shortest edge at a vertex).
pub const MAX_POLYGON_JITTER: f64 = 0.15;

/// One connected polygon mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PolygonShape {
    /// The cube-sphere of `6n²` non-planar quads (genus 0).
    CubeSphere {
        /// Quads along each cube edge (≥ 1).
        n: usize,
    },
    /// A torus of planar quads (genus 1), radii 1 and 0.4.
    QuadTorus {
        /// Quads around the major circle (≥ 3).
        around: usize,
        /// Quads around the tube (≥ 3).
        tube: usize,
    },
    /// The dual of `icosphere(level)`: pentagons and hexagons, non-planar (genus 0).
    DualSphere {
        /// Icosphere level (≥ 1).
        level: u32,
    },
    /// The quad split of the plate surface of genus `genus` (planar quads).
    QuadSurface {
        /// Genus, 0–5.
        genus: usize,
    },
    /// The dual of the plate surface of genus `genus`: non-planar polygons of valence 4 to 8.
    DualSurface {
        /// Genus, 0–5.
        genus: usize,
    },
    /// A quad torus without one quad: genus 1, one boundary loop.
    HoledQuadTorus {
        /// Quads around the major circle (≥ 3).
        around: usize,
        /// Quads around the tube (≥ 3).
        tube: usize,
    },
    /// The dual of `disk(rings)` (one boundary loop).
    DualDisk {
        /// Rings of the disk (≥ 2).
        rings: usize,
    },
    /// The dual of an open cylinder (two boundary loops).
    DualCylinder {
        /// Vertices per ring (≥ 3).
        around: usize,
        /// Layers (≥ 2).
        layers: usize,
    },
    /// The quad split of a plate with `holes` holes (`holes + 1` boundary loops).
    QuadPants {
        /// Holes (1 or 2).
        holes: usize,
    },
}

impl PolygonShape {
    /// Genus, from the description.
    pub fn genus(&self) -> usize {
        match *self {
            PolygonShape::QuadTorus { .. } | PolygonShape::HoledQuadTorus { .. } => 1,
            PolygonShape::QuadSurface { genus } | PolygonShape::DualSurface { genus } => genus,
            _ => 0,
        }
    }

    /// Dimension of the harmonic space, from the description: `2g` if closed, else
    /// `2g + b − 1`.
    pub fn harmonic_dimension(&self) -> usize {
        match *self {
            PolygonShape::HoledQuadTorus { .. } => 2,
            PolygonShape::DualDisk { .. } => 0,
            PolygonShape::DualCylinder { .. } => 1,
            PolygonShape::QuadPants { holes } => holes,
            _ => 2 * self.genus(),
        }
    }

    /// The mesh.
    pub fn build(&self) -> Result<SurfaceMesh, String> {
        let dual_of = |mesh: &tvf_core::TriangleMesh| -> Result<SurfaceMesh, String> {
            dual(mesh)
                .map(SurfaceMesh::from)
                .ok_or_else(|| format!("{self:?}: no valid dual"))
        };
        let quad_torus_of = |around, tube| -> Result<SurfaceMesh, String> {
            quad_torus(1.0, 0.4, around, tube)
                .map(SurfaceMesh::from)
                .ok_or_else(|| format!("{self:?}: invalid torus"))
        };
        match *self {
            PolygonShape::CubeSphere { n } => cube_sphere(n)
                .map(SurfaceMesh::from)
                .ok_or_else(|| "cube-sphere of 0 quads".to_string()),
            PolygonShape::QuadTorus { around, tube } => quad_torus_of(around, tube),
            PolygonShape::DualSphere { level } => dual_of(&icosphere(level)),
            PolygonShape::QuadSurface { genus } => quad_split(&genus_surface(genus, 2)),
            PolygonShape::DualSurface { genus } => dual_of(&genus_surface(genus, 2)),
            PolygonShape::HoledQuadTorus { around, tube } => {
                without_faces(&quad_torus_of(around, tube)?, &[0])
            }
            PolygonShape::DualDisk { rings } => dual_of(&disk(rings)),
            PolygonShape::DualCylinder { around, layers } => {
                dual_of(&open_cylinder(around, layers, 1.0))
            }
            PolygonShape::QuadPants { holes } => quad_split(&perforated_plate(holes, 2)),
        }
    }
}

/// A generated polygon mesh, described: components side by side along x, each jittered (the
/// component `k` with seed `seed + k`), then the whole mesh moved by `motion`.
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonMeshSpec {
    /// The connected components (at least one).
    pub components: Vec<PolygonShape>,
    /// Vertex jitter of every component.
    pub jitter: Jitter,
    /// A rigid motion of the whole mesh, applied last.
    pub motion: Option<RigidMotion>,
}

impl PolygonMeshSpec {
    /// Builds the mesh, named by the description, with its genus and harmonic dimension from
    /// the description. Fails when a jitter folds a polygon or the result has only triangles
    /// (the strategy rejects such draws).
    pub fn build(&self) -> Result<PolygonCorpusMesh, String> {
        let mut mesh: Option<SurfaceMesh> = None;
        for (k, shape) in self.components.iter().enumerate() {
            let mut piece = shape.build()?;
            if self.jitter.amplitude > 0.0 {
                let seed = self.jitter.seed.wrapping_add(k as u64);
                piece = jittered(&piece, self.jitter.amplitude, seed)?;
            }
            mesh = Some(match mesh {
                None => piece,
                Some(previous) => beside(&previous, &piece)?,
            });
        }
        let mut mesh = mesh.ok_or("a mesh description without components")?;
        if let Some(motion) = &self.motion {
            mesh = moved(&mesh, motion.axis, motion.angle, motion.translation)?;
        }
        if mesh.is_triangle_mesh() {
            return Err(format!("{self:?} has only triangles"));
        }
        let genus = self.components.iter().map(PolygonShape::genus).sum();
        let harmonic_dimension = self
            .components
            .iter()
            .map(PolygonShape::harmonic_dimension)
            .sum();
        Ok(PolygonCorpusMesh::open(
            format!("{self:?}"),
            mesh,
            genus,
            harmonic_dimension,
        ))
    }
}

/// Closed polygon shapes, simplest first (shrinking goes towards the front).
fn closed_polygon_shapes() -> BoxedStrategy<PolygonShape> {
    prop_oneof![
        (1usize..=4).prop_map(|n| PolygonShape::CubeSphere { n }),
        (3usize..=10, 3usize..=6)
            .prop_map(|(around, tube)| PolygonShape::QuadTorus { around, tube }),
        (1u32..=2).prop_map(|level| PolygonShape::DualSphere { level }),
        (0..=MAX_POLYGON_GENUS).prop_map(|genus| PolygonShape::QuadSurface { genus }),
        (0..=MAX_POLYGON_GENUS).prop_map(|genus| PolygonShape::DualSurface { genus }),
    ]
    .boxed()
}

/// Polygon shapes with holes.
fn open_polygon_shapes() -> BoxedStrategy<PolygonShape> {
    prop_oneof![
        (2usize..=4).prop_map(|rings| PolygonShape::DualDisk { rings }),
        (3usize..=10, 3usize..=6)
            .prop_map(|(around, tube)| PolygonShape::HoledQuadTorus { around, tube }),
        (4usize..=12, 2usize..=4)
            .prop_map(|(around, layers)| PolygonShape::DualCylinder { around, layers }),
        (1usize..=2).prop_map(|holes| PolygonShape::QuadPants { holes }),
    ]
    .boxed()
}

/// Generated polygon meshes: one or two components (closed of genus 0–5, or with holes unless
/// `closed_only`), jitter up to [`MAX_POLYGON_JITTER`], an optional rigid motion. Draws a jitter
/// breaks are rejected.
pub fn polygon_mesh_specs(closed_only: bool) -> BoxedStrategy<PolygonMeshSpec> {
    let shape = if closed_only {
        closed_polygon_shapes()
    } else {
        prop_oneof![closed_polygon_shapes(), open_polygon_shapes()].boxed()
    };
    (
        prop::collection::vec(shape, 1..=2),
        jitters(MAX_POLYGON_JITTER),
        rigid_motions(),
    )
        .prop_map(|(components, jitter, motion)| PolygonMeshSpec {
            components,
            jitter,
            motion,
        })
        .prop_filter("the polygons stay valid", |spec| spec.build().is_ok())
        .boxed()
}
