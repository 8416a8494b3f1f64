//! Demo steps 6 and 7 (paper Figures 4 and 5): a tangential vector field spline from a handful
//! of vector, source, sink and vortex constraints beside the soft-constrained design of Fisher
//! et al., and fur grown along the spline field.

use super::page::Section;
use super::screen_points::faces_at_screen_points;
use super::Context;
use crate::constraint_markers::constraint_markers;
use crate::error::FigureError;
use std::time::Instant;
use tvf_core::discretization::{FieldSampling, HodgeOperators};
use tvf_core::geometry::{add, norm, scale};
use tvf_design::{
    default_regularization, residual, Constraint, ConstraintAssembler, Location, ReducedBasis,
    ReducedSoftDesign, SoftOptions, SplineSession, Target, DEFAULT_OMEGA,
};
use tvf_render::{draw_field, grid, FaceQuantity, Overlays, Style, Tint};
use tvf_render::{grow_fur, FurOptions, Polyline};

/// Soft-design weight of every constraint (soft constraints trade accuracy for smoothness).
const SOFT_WEIGHT: f64 = 10.0;

/// Three vectors, a source, a sink and a vortex on faces spread over the visible surface. Divergence and curl values are `±8/r` with `r = √(area / 6π)`: a point
/// constraint spreads over a small disc only, so it needs this strength to show beside unit
/// vectors.
fn constraints(cx: &Context, fields: &dyn FieldSampling) -> Vec<Constraint> {
    // Image-plane targets: left, right and front for the vectors; then the source (front left),
    // the sink (front right) and the vortex (at the back).
    let targets = [
        [-0.8, 0.1],
        [0.8, 0.1],
        [0.0, -0.85],
        [-0.45, -0.55],
        [0.45, -0.55],
        [0.0, 0.75],
    ];
    let faces = faces_at_screen_points(cx.mesh, cx.view().to_eye(), &targets);
    let r = (cx.mesh.total_area() / (6.0 * std::f64::consts::PI)).sqrt();
    let strength = 8.0 / r.max(1e-300);
    let at = |face| Location::Face {
        face,
        barycentric: None,
    };
    let mut out = Vec::new();
    for (k, &face) in faces.iter().take(3).enumerate() {
        let [e1, e2] = fields.frame(face);
        let angle = 2.0 * std::f64::consts::PI * k as f64 / 3.0;
        let value = add(scale(e1, angle.cos()), scale(e2, angle.sin()));
        out.push(Constraint::new(
            format!("vector{}", k + 1),
            Target::Vector(value),
            at(face),
        ));
    }
    let scalars = [
        ("source", Target::Divergence(strength)),
        ("sink", Target::Divergence(-strength)),
        ("vortex", Target::Curl(strength)),
    ];
    for ((id, target), &face) in scalars.into_iter().zip(faces.iter().skip(3)) {
        out.push(Constraint::new(id, target, at(face)));
    }
    for c in out.iter_mut() {
        c.weight = SOFT_WEIGHT;
    }
    out
}

/// Solves the spline and the soft design; returns the section and the spline field.
pub fn run(cx: &Context) -> Result<(Section, Vec<f64>), FigureError> {
    let set = constraints(cx, cx.discretization.require_sampling()?);
    let omega = DEFAULT_OMEGA * cx.mesh.total_area() / (4.0 * std::f64::consts::PI);
    let reduced = ReducedBasis::from_spectral(cx.basis)?;
    let mut section = Section::new(
        "Spline and soft design (Figure 4)",
        format!(
            "Three unit vectors (orange, with their direction), a source (red), a sink (blue) and \
             a vortex (green). Left: the tangential vector field spline, min E_B + ω E_D subject \
             to the constraints as hard constraints (ω = {omega:.3}), solved in the {}-field \
             basis through the Schur complement. Right: soft design (Fisher et al. 2007), \
             min E_D + ω E_B + Σ w |C̃x − c|² with weight w = {SOFT_WEIGHT} per constraint, \
             reduced to the same basis: smooth, but the constraints are only approximated.",
            cx.basis.len()
        ),
    );
    let (spline, soft, timings) = {
        let c = cx.discretization.as_ref();
        {
            let compiled = ConstraintAssembler::new(c, cx.mesh).compile_all(&set)?;
            let start = Instant::now();
            let mut session = SplineSession::new(&reduced, omega)?;
            for constraint in compiled.iter().cloned() {
                session.add(constraint)?;
            }
            let v = session.solve();
            let spline_solve = start.elapsed().as_secs_f64();
            let mut spline = vec![0.0; reduced.field_dimension()];
            reduced.map(&v, &mut spline)?;
            let start = Instant::now();
            let options = SoftOptions {
                omega,
                regularization: default_regularization(c),
            };
            let mut design = ReducedSoftDesign::new(&reduced, options)?;
            design.add_all(compiled.iter().cloned())?;
            let v = design.solve();
            let soft_solve = start.elapsed().as_secs_f64();
            let mut soft = vec![0.0; reduced.field_dimension()];
            reduced.map(&v, &mut soft)?;
            let worst = |field: &[f64]| {
                compiled
                    .iter()
                    .map(|k| residual(k, field).relative)
                    .fold(0.0, f64::max)
            };
            section.number(
                "spline: worst relative constraint residual",
                format!("{:.2e}", worst(&spline)),
            );
            section.number(
                "soft design: worst relative constraint residual",
                format!("{:.2e}", worst(&soft)),
            );
            (spline, soft, (spline_solve, soft_solve))
        }
    };
    section.number(
        "setup + solve (reduced, before mapping to faces)",
        format!(
            "spline {:.2} ms, soft design {:.2} ms",
            timings.0 * 1e3,
            timings.1 * 1e3
        ),
    );
    let radius = 5.0 * cx.panel_view().height as f64 / 300.0;
    let markers = constraint_markers(cx.mesh, &set, radius);
    let mut panels = Vec::new();
    for (title, field) in [
        ("spline (hard constraints)", &spline),
        ("soft design", &soft),
    ] {
        let overlays = Overlays {
            markers: markers.clone(),
            title: Some(title.to_string()),
            ..Default::default()
        };
        panels.push(draw_field(
            cx.mesh,
            cx.discretization.as_ref(),
            Some(field),
            Tint::Quantity(FaceQuantity::Magnitude),
            Style::Streamlines,
            overlays,
            cx.panel_view(),
        )?);
    }
    cx.save(&grid(&panels, 2), "design.png")?;
    section.figure(
        "design.png",
        "Spline (left) and soft design (right) from the same constraints; streamlines, colour: magnitude.",
    );
    Ok((section, spline))
}

/// Grows fur along `field` and draws it.
pub fn fur(cx: &Context, field: &[f64]) -> Result<Section, FigureError> {
    // Unit directions: strands of even length that follow the field's direction.
    let vectors: Vec<[f64; 3]> = cx
        .discretization
        .require_sampling()?
        .to_face_vectors(field)?
        .into_iter()
        .map(|v| {
            let length = norm(v);
            if length > 0.0 {
                scale(v, 1.0 / length)
            } else {
                v
            }
        })
        .collect();
    let options = FurOptions {
        strand_count: cx.config.fur_strands,
        length: 0.035,
        ..Default::default()
    };
    let strands = grow_fur(cx.mesh, &vectors, &options)?;
    let polylines: Vec<Polyline> = strands
        .into_iter()
        .map(|points| Polyline {
            points,
            color: [90, 55, 30],
            tip_color: [235, 200, 150],
            width_px: 1.2,
        })
        .collect();
    let count = polylines.len();
    let overlays = Overlays {
        polylines,
        title: Some("fur along the spline".to_string()),
        ..Default::default()
    };
    let image = draw_field(
        cx.mesh,
        cx.discretization.as_ref(),
        None,
        Tint::Quantity(FaceQuantity::None),
        Style::None,
        overlays,
        cx.view(),
    )?;
    cx.save(&image, "fur.png")?;
    let mut section = Section::new(
        "Fur along the spline field (Figure 5)",
        "Hair strands rooted on the surface follow the direction of the spline field (normalised \
         to unit length, so that all strands are equally long) along its streamlines and rise \
         off the surface as they grow.",
    );
    section.figure(
        "fur.png",
        "Fur grown along the spline field of the previous step.",
    );
    section.number("strands", count.to_string());
    Ok(section)
}
