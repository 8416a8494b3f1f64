//! Compression of single fields: the rate–distortion curves of Figure 9, the many-vortex field
//! of Figure 10 with its residual, and the projection / reconstruction timings of Section 8.6.

use crate::error::FigureError;
use crate::finding::{Experiment, Finding};
use crate::numbers::{ratio, seconds};
use crate::panels::{save, save_magnitude_row};
use crate::test_fields::vortex_field;
use crate::timing::{median_time, Repetitions};
use tvf_render::{Axis, AxisScale, Plot, Series, SeriesStyle};
use tvf_spectral::{
    basis_id, rate_distortion, relative_l2_error, CoefficientCoding, FieldCodec, FieldFamily,
    FileStamp, RatePoint,
};

/// One mesh's rate–distortion curve.
#[derive(Debug, Clone, PartialEq)]
pub struct RateCurve {
    /// Mesh name.
    pub mesh: String,
    /// Which field was compressed.
    pub field: String,
    /// How the coefficients are stored (the paper's rate is [`CoefficientCoding::Float64`]).
    pub coding: CoefficientCoding,
    /// Faces of the mesh (for the rate against two doubles per face).
    pub faces: usize,
    /// Points, ascending pairs.
    pub points: Vec<RatePoint>,
}

/// Pair counts of the curves: 1, 2, 5, 10, 20, 50, … up to the largest in the basis.
pub fn pair_counts(available: usize) -> Vec<usize> {
    let mut ks: Vec<usize> = [1, 2, 5]
        .iter()
        .flat_map(|&m| (0..6).map(move |e| m * 10usize.pow(e)))
        .filter(|&k| k < available)
        .collect();
    ks.push(available);
    ks.sort_unstable();
    ks.dedup();
    ks
}

/// Pairs in the basis (the smaller family).
pub fn available_pairs(x: &Experiment) -> usize {
    x.basis
        .count(FieldFamily::Integrable)
        .min(x.basis.count(FieldFamily::Cointegrable))
}

fn stamp(x: &Experiment) -> FileStamp {
    FileStamp {
        mesh_fingerprint: x.mesh.fingerprint(),
        basis_id: basis_id(x.basis),
        vertex_count: x.mesh.vertex_count(),
    }
}

/// The rate–distortion curve of `field` on `x` with the coefficients stored as `coding`: one
/// real compressed file per pair count of [`pair_counts`], its error measured on the decoded
/// field.
pub fn rate_curve(
    x: &Experiment,
    field: &[f64],
    label: &str,
    coding: CoefficientCoding,
) -> Result<RateCurve, FigureError> {
    let points = rate_distortion(
        x.basis,
        field,
        stamp(x),
        &pair_counts(available_pairs(x)),
        &[coding],
    )?;
    Ok(RateCurve {
        mesh: x.name.to_string(),
        field: label.to_string(),
        coding,
        faces: x.mesh.face_count(),
        points,
    })
}

/// Figure 9: every curve in one log–log plot, relative error against bits per vertex.
pub fn figure9(
    curves: &[RateCurve],
    out: &std::path::Path,
    plot_size: (u32, u32),
) -> Result<Finding, FigureError> {
    let series = curves
        .iter()
        .map(|c| {
            let points = c
                .points
                .iter()
                .map(|p| (p.bits_per_vertex, p.relative_error.max(1e-16)))
                .collect();
            let name = match c.coding {
                CoefficientCoding::Float64 => format!("{} ({})", c.mesh, c.field),
                coding => format!("{} ({}, {})", c.mesh, c.field, coding.label()),
            };
            Series::new(name, points, SeriesStyle::LineAndMarkers)
        })
        .collect();
    // Room above the curves for the legend (drawn in the top-right corner).
    let lowest = curves
        .iter()
        .flat_map(|c| &c.points)
        .map(|p| p.relative_error)
        .filter(|e| *e > 0.0)
        .fold(1.0, f64::min);
    let mut y = Axis::new("relative L2 error", AxisScale::Log10);
    y.range = Some((lowest / 2.0, 100.0));
    let plot = Plot {
        title: "Rate-distortion: relative L2 error against bits per vertex".to_string(),
        x: Axis::new("bits per vertex (file size)", AxisScale::Log10),
        y,
        series,
        width: plot_size.0,
        height: plot_size.1,
    };
    let file = "figure9_rate_distortion.png";
    save(&plot.render()?, &out.join(file))?;
    let mut meshes: Vec<&str> = curves.iter().map(|c| c.mesh.as_str()).collect();
    meshes.dedup();
    let mut finding = Finding::new(
        "Figure 9",
        "Rate–distortion curves of spectral compression",
        &meshes.join(", "),
    );
    finding.files.push(file.to_string());
    for c in curves {
        for p in &c.points {
            if [10, 100].contains(&p.pairs) || Some(p) == c.points.last() {
                finding.number(
                    format!(
                        "{} ({}, {}), k = {} pairs",
                        c.mesh,
                        c.field,
                        c.coding.label(),
                        p.pairs
                    ),
                    format!(
                        "error {:.3e}, {:.1} bits/vertex, {} bytes, rate {:.1} against two \
                         doubles per face",
                        p.relative_error,
                        p.bits_per_vertex,
                        p.bytes,
                        (16 * c.faces) as f64 / p.bytes as f64
                    ),
                );
            }
        }
    }
    finding.paper = "Hand and rocker arm (regular custom fields): almost lossless with the 2k lowest \
                     pairs; rocker arm essentially lossless at k = 1100 (compression rate 36.52 \
                     against two doubles per face); the bunny's many-vortex field converges slowly."
        .to_string();
    let finals: Vec<String> = curves
        .iter()
        .filter_map(|c| {
            c.points.last().map(|p| {
                format!(
                    "{} ({}) {:.2e} at k = {}",
                    c.mesh, c.field, p.relative_error, p.pairs
                )
            })
        })
        .collect();
    finding.comparison = format!(
        "Same shape: the designed fields (full soft design with {} seeded constraints, as the \
         paper's custom fields were made with its design tools) fall steeply with k, the analytic \
         fields (a projected rotation among them, not smooth across sharp creases) more slowly, \
         and the bunny's many-vortex field stays high until k resolves the vortices. Final \
         relative errors: {}. Our basis has 500 pairs (Table 1's size), so the curves stop at \
         k = 500; the paper's curves go on to 2000 pairs, with the rocker arm 'essentially \
         lossless' at k = 1100. The fields are our own (the paper's are not published), so \
         error levels compare in trend only.",
        crate::seeded_constraints::DESIGNED_FIELD_CONSTRAINTS,
        finals.join("; ")
    );
    Ok(finding)
}

/// Section 8.6's timings on the hand: all coefficients of a field (`Uᵀ M_X v`) and the
/// reconstruction `U c`, beside the paper's 0.67 s and 0.06 s for k = 1000.
pub fn projection_timings(
    x: &Experiment,
    field: &[f64],
    repetitions: Repetitions,
) -> Result<Finding, FigureError> {
    let (project, coefficients) = median_time(repetitions, || x.basis.coefficients(field))?;
    let (reconstruct, _) = median_time(repetitions, || x.basis.reconstruct(&coefficients))?;
    let mut finding = Finding::new(
        "Section 8.6 timings",
        "Projection onto the basis and reconstruction (one field)",
        x.name,
    );
    finding.number(
        format!("projection onto {} fields", x.basis.len()),
        format!(
            "{} (paper 0.67 s, paper/ours {})",
            seconds(project.median),
            ratio(Some(0.67), Some(project.median))
        ),
    );
    finding.number(
        "reconstruction",
        format!(
            "{} (paper 0.06 s, paper/ours {})",
            seconds(reconstruct.median),
            ratio(Some(0.06), Some(reconstruct.median))
        ),
    );
    finding.paper = "Hand, k = 1000: projection 0.67 s, reconstruction 0.06 s (CPU).".to_string();
    finding.comparison = format!(
        "Projection {} (paper 0.67 s), reconstruction {} (paper 0.06 s): both are dense products \
         with the 2F × d basis, ours multi-threaded (faer / rayon) in f64.",
        seconds(project.median),
        seconds(reconstruct.median)
    );
    Ok(finding)
}

/// Vortices in the Figure 10 field.
pub const VORTICES: usize = 120;

/// Figure 10: a field of [`VORTICES`] small vortices, its compression with every pair of the
/// basis and the residual (what those pairs cannot represent). Returns the finding and the
/// field (for the rate–distortion curve).
pub fn figure10(x: &Experiment) -> Result<(Finding, Vec<f64>), FigureError> {
    let field = vortex_field(x.complex, x.mesh, VORTICES, 10);
    let pairs = available_pairs(x);
    let s = stamp(x);
    let codec = FieldCodec::new(
        x.basis,
        s.mesh_fingerprint,
        s.basis_id,
        pairs,
        CoefficientCoding::Float64,
    )?;
    let compressed = codec.decode(&codec.encode(&field)?)?;
    let residual: Vec<f64> = field.iter().zip(&compressed).map(|(a, b)| a - b).collect();
    let file = "figure10_vortices.png";
    save_magnitude_row(
        x,
        file,
        &[
            (&field, &format!("{VORTICES} vortices")),
            (&compressed, &format!("from {pairs} pairs")),
            (&residual, "residual"),
        ],
    )?;
    let error = relative_l2_error(x.basis.field_mass(), &field, &compressed);
    let mut finding = Finding::new(
        "Figure 10",
        "A field with many small vortices, compressed, and its residual",
        x.name,
    );
    finding.files.push(file.to_string());
    finding.number("vortices", VORTICES.to_string());
    finding.number("pairs kept", pairs.to_string());
    finding.number("relative L2 error", format!("{error:.3}"));
    finding.number(
        "compression rate against two doubles per face",
        format!(
            "{:.1}",
            (2 * x.mesh.face_count()) as f64 / codec.selection().len() as f64
        ),
    );
    finding.paper =
        "Over 100 small curls on the bunny, compressed with the lowest 1000 pairs: all \
                     features kept; the residual (right) holds the fine detail."
            .to_string();
    finding.comparison = format!(
        "Our own field of {VORTICES} vortices with {pairs} pairs (the paper: 1000 pairs, twice \
         as many): the vortices are all in place but their cores are blurred, and the residual \
         is rings around the cores, the detail {pairs} pairs cannot hold; relative error \
         {error:.3}. With fewer pairs than the paper the residual is larger than in its Figure \
         10."
    );
    Ok((finding, field))
}
