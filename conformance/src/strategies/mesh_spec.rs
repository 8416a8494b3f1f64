//! [`MeshSpec`]: the whole description of a generated mesh (one or more components, jitter, a
//! rigid motion, Delaunay flips), the mesh it builds with its genus and harmonic dimension stated
//! by the description, and [`mesh_specs`], the strategy a property runner draws from.

use super::closed::{closed_shapes, ClosedShape};
use super::open::{open_shapes, OpenShape};
use super::perturbation::{jitters, rigid_motions, Jitter, RigidMotion, MAX_JITTER};
use crate::corpus::{disjoint_union, is_delaunay, try_delaunay_flips, CorpusMesh};
use proptest::prelude::*;
use tvf_core::TriangleMesh;

/// Largest jitter amplitude of the Delaunay variants (the flips repair what jitter breaks).
pub const MAX_DELAUNAY_JITTER: f64 = 0.15;

/// One connected component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// A closed surface.
    Closed(ClosedShape),
    /// A surface with boundary.
    Open(OpenShape),
}

impl Shape {
    fn genus(&self) -> usize {
        match self {
            Shape::Closed(shape) => shape.genus(),
            Shape::Open(shape) => shape.genus(),
        }
    }

    fn harmonic_dimension(&self) -> usize {
        match self {
            Shape::Closed(shape) => 2 * shape.genus(),
            Shape::Open(shape) => shape.harmonic_dimension(),
        }
    }

    /// The sliver torus is not jittered: a move of a fraction of its long edges could fold a
    /// sliver.
    fn may_jitter(&self) -> bool {
        !matches!(self, Shape::Closed(ClosedShape::SliverTorus { .. }))
    }

    fn build(&self) -> TriangleMesh {
        match self {
            Shape::Closed(shape) => shape.build(),
            Shape::Open(shape) => shape.build(),
        }
    }
}

/// What kind of meshes a discretization accepts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeshNeeds {
    /// Only Delaunay meshes (`cot α + cot β > 0` on every edge, e.g. DEC's diagonal `⋆1`).
    pub delaunay: bool,
    /// Only closed meshes (e.g. a complex from matrices, which carries no boundary condition).
    pub closed_only: bool,
}

/// A generated mesh, described: components (placed side by side along x), jitter (component `k`
/// with seed `seed + k`), made Delaunay by edge flips if `delaunay`, then moved by `motion`.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSpec {
    /// The connected components (at least one).
    pub components: Vec<Shape>,
    /// Vertex jitter of every component but sliver tori.
    pub jitter: Jitter,
    /// Lawson flips until every interior edge has `cot α + cot β > 0` (after the jitter).
    pub delaunay: bool,
    /// A rigid motion of the whole mesh, applied last.
    pub motion: Option<RigidMotion>,
}

impl MeshSpec {
    /// Builds the mesh, named by the description, with its genus and harmonic dimension from the
    /// description. Fails when the Delaunay flips do not converge or leave a boundary edge with
    /// `cot α ≤ 0` (the strategies reject such draws), or a parameter is not finite.
    pub fn build(&self) -> Result<CorpusMesh, String> {
        let mut mesh: Option<TriangleMesh> = None;
        for (k, shape) in self.components.iter().enumerate() {
            let mut piece = shape.build();
            if shape.may_jitter() {
                let jitter = Jitter {
                    seed: self.jitter.seed.wrapping_add(k as u64),
                    ..self.jitter
                };
                piece = jitter.apply(&piece)?;
            }
            mesh = Some(match mesh {
                None => piece,
                Some(previous) => disjoint_union(&previous, &beside(&previous, &piece)?),
            });
        }
        let mut mesh = mesh.ok_or("a mesh description without components")?;
        if self.delaunay && !is_delaunay(&mesh) {
            mesh = try_delaunay_flips(&mesh)?;
            if !is_delaunay(&mesh) {
                return Err("a boundary edge is not Delaunay (flips cannot fix it)".into());
            }
        }
        if let Some(motion) = &self.motion {
            mesh = motion.apply(&mesh)?;
        }
        let genus = self.components.iter().map(Shape::genus).sum();
        let harmonic_dimension = self.components.iter().map(Shape::harmonic_dimension).sum();
        Ok(CorpusMesh::open(
            format!("{self:?}"),
            mesh,
            genus,
            harmonic_dimension,
        ))
    }
}

/// `piece` translated along x so that it starts 1 beyond the end of `previous`.
fn beside(previous: &TriangleMesh, piece: &TriangleMesh) -> Result<TriangleMesh, String> {
    let end = previous
        .positions()
        .iter()
        .fold(f64::NEG_INFINITY, |m, p| m.max(p[0]));
    let start = piece
        .positions()
        .iter()
        .fold(f64::INFINITY, |m, p| m.min(p[0]));
    RigidMotion {
        axis: [0.0; 3],
        angle: 0.0,
        translation: [end + 1.0 - start, 0.0, 0.0],
    }
    .apply(piece)
}

/// One component: closed surfaces, and (unless `needs.closed_only`) surfaces with boundary.
fn shapes(needs: MeshNeeds) -> BoxedStrategy<Shape> {
    let closed = closed_shapes(needs.delaunay).prop_map(Shape::Closed);
    if needs.closed_only {
        return closed.boxed();
    }
    prop_oneof![closed, open_shapes().prop_map(Shape::Open)].boxed()
}

/// Generated meshes for a discretization with `needs`: one or two components (closed of genus
/// 0–5, or with boundary unless `closed_only`), jitter, an optional rigid motion and, for
/// `delaunay`, edge flips (draws whose flips do not converge are rejected). Shrinks towards one
/// component, simpler shapes, lower genus, fewer faces, no jitter and no motion.
pub fn mesh_specs(needs: MeshNeeds) -> BoxedStrategy<MeshSpec> {
    let max_jitter = if needs.delaunay {
        MAX_DELAUNAY_JITTER
    } else {
        MAX_JITTER
    };
    (
        prop::collection::vec(shapes(needs), 1..=2),
        jitters(max_jitter),
        rigid_motions(),
    )
        .prop_map(move |(components, jitter, motion)| MeshSpec {
            components,
            jitter,
            delaunay: needs.delaunay,
            motion,
        })
        .prop_filter("the Delaunay flips converge", |spec| spec.build().is_ok())
        .boxed()
}
