//! The discretization comparison: catalog entries (the built-in ones, [`crate::registry`], or
//! any others) on
//! icospheres under refinement, eigenvalues against the unit sphere's `l(l+1)`, convergence
//! orders and the time to build each basis; a Markdown table and a log–log plot.
//!
//! The icosphere's vertices lie on the unit sphere (the surface itself is inscribed, so its
//! area is below `4π`; that geometric error is `O(h²)` like the discretization error and is
//! part of what is measured). The smooth Hodge–Laplacian on tangent fields of the unit sphere
//! has every Laplace–Beltrami eigenvalue `l(l+1)` (`l ≥ 1`, multiplicity `2l+1`) once in the
//! integrable and once in the co-integrable family; each family's lowest `L(L+2)` eigenvalues
//! are compared with the first `L` such levels.

use crate::markdown::Table;
use crate::registry::basis_of;
use crate::step_log::StepLog;
use tvf_core::generate::icosphere;
use tvf_core::geometry::{norm, sub};
use tvf_core::SurfaceMesh;
use tvf_discretizations::CatalogEntry;
use tvf_figures::numbers::{seconds, thousands};
use tvf_figures::FigureError;
use tvf_render::{Axis, AxisScale, Plot, Series, SeriesStyle, PALETTE};
use tvf_spectral::{BasisRequest, FieldFamily, SpectralBasis};

/// What the comparison runs.
#[derive(Debug, Clone, PartialEq)]
pub struct ComparisonConfig {
    /// Icosphere subdivision levels (`20·4^level` faces), ascending.
    pub levels: Vec<u32>,
    /// Highest spherical-harmonic degree `L` compared: `L(L+2)` eigenvalues per family.
    pub max_degree: usize,
}

impl Default for ComparisonConfig {
    fn default() -> Self {
        Self {
            levels: (1..=6).collect(),
            max_degree: 5,
        }
    }
}

/// One discretization on one icosphere.
#[derive(Debug, Clone, PartialEq)]
pub struct LevelResult {
    /// Subdivision level.
    pub level: u32,
    /// Faces of the icosphere.
    pub faces: usize,
    /// Mean edge length (the mesh size `h`).
    pub h: f64,
    /// Largest relative eigenvalue error `|λ_h − l(l+1)| / l(l+1)` of the integrable family.
    pub integrable_error: f64,
    /// The same for the co-integrable family.
    pub cointegrable_error: f64,
    /// Seconds to assemble the complex and compute the basis.
    pub seconds: f64,
}

impl LevelResult {
    /// The larger of the two families' errors.
    pub fn error(&self) -> f64 {
        self.integrable_error.max(self.cointegrable_error)
    }
}

/// One discretization on every level.
#[derive(Debug, Clone, PartialEq)]
pub struct DiscretizationResult {
    /// Catalog id of the discretization.
    pub name: String,
    /// One entry per level, in the order of the configuration.
    pub levels: Vec<LevelResult>,
}

impl DiscretizationResult {
    /// Estimated convergence orders between consecutive levels,
    /// `log(e_i / e_{i+1}) / log(h_i / h_{i+1})`, of the error chosen by `error`.
    pub fn orders(&self, error: impl Fn(&LevelResult) -> f64) -> Vec<f64> {
        self.levels
            .windows(2)
            .map(|w| (error(&w[0]) / error(&w[1])).ln() / (w[0].h / w[1].h).ln())
            .collect()
    }
}

/// The unit sphere's lowest non-zero Laplace–Beltrami eigenvalues up to degree `max_degree`:
/// `l(l+1)` repeated `2l+1` times, `l = 1..=max_degree`.
pub fn sphere_eigenvalues(max_degree: usize) -> Vec<f64> {
    (1..=max_degree)
        .flat_map(|l| std::iter::repeat_n((l * (l + 1)) as f64, 2 * l + 1))
        .collect()
}

/// Mean edge length of `mesh`.
pub fn mean_edge_length(mesh: &SurfaceMesh) -> f64 {
    let p = mesh.positions();
    let total: f64 = mesh
        .edges()
        .iter()
        .map(|&[a, b]| norm(sub(p[a], p[b])))
        .sum();
    total / mesh.edge_count().max(1) as f64
}

/// Largest relative error of `family`'s eigenvalues in `basis` against `exact` (compared in
/// ascending order; a family with fewer eigenvalues than `exact` is an error).
pub fn family_error(
    basis: &SpectralBasis,
    family: FieldFamily,
    exact: &[f64],
) -> Result<f64, FigureError> {
    let values: Vec<f64> = basis
        .eigenvalues()
        .iter()
        .zip(basis.families())
        .filter(|(_, f)| **f == family)
        .map(|(l, _)| *l)
        .collect();
    if values.len() < exact.len() {
        return Err(FigureError::Invalid(format!(
            "the basis has {} {} eigenvalues, the comparison needs {}",
            values.len(),
            family.name(),
            exact.len()
        )));
    }
    Ok(values
        .iter()
        .zip(exact)
        .map(|(h, e)| (h - e).abs() / e)
        .fold(0.0, f64::max))
}

/// Runs every discretization of `entries` on every level of `config`.
pub fn run(
    entries: &[CatalogEntry],
    config: &ComparisonConfig,
    progress: &StepLog,
) -> Result<Vec<DiscretizationResult>, FigureError> {
    let exact = sphere_eigenvalues(config.max_degree);
    let mut results: Vec<DiscretizationResult> = entries
        .iter()
        .map(|e| DiscretizationResult {
            name: e.id().to_string(),
            levels: Vec::new(),
        })
        .collect();
    for &level in &config.levels {
        let mesh = icosphere(level);
        let h = mean_edge_length(&mesh);
        for (entry, result) in entries.iter().zip(&mut results) {
            let request = BasisRequest::pairs(exact.len()).with_seed(1);
            let timed = basis_of(entry, &mesh, &request)?;
            let level_result = LevelResult {
                level,
                faces: mesh.face_count(),
                h,
                integrable_error: family_error(&timed.basis, FieldFamily::Integrable, &exact)?,
                cointegrable_error: family_error(&timed.basis, FieldFamily::Cointegrable, &exact)?,
                seconds: timed.seconds,
            };
            progress.note(format!(
                "comparison: {} on icosphere level {level} ({} faces): errors {:.2e} / {:.2e}, {}",
                entry.id(),
                thousands(mesh.face_count()),
                level_result.integrable_error,
                level_result.cointegrable_error,
                seconds(timed.seconds)
            ));
            result.levels.push(level_result);
        }
    }
    Ok(results)
}

/// The comparison as a Markdown table: per discretization and level the errors of both families,
/// the orders against the previous level and the basis time.
pub fn markdown(results: &[DiscretizationResult]) -> String {
    let mut table = Table::new([
        "discretization",
        "level",
        "faces",
        "h",
        "integrable error",
        "order",
        "co-integrable error",
        "order",
        "basis time",
    ]);
    for result in results {
        let integrable = result.orders(|l| l.integrable_error);
        let cointegrable = result.orders(|l| l.cointegrable_error);
        for (i, level) in result.levels.iter().enumerate() {
            let order = |orders: &[f64]| {
                i.checked_sub(1)
                    .and_then(|k| orders.get(k))
                    .map_or("–".to_string(), |o| format!("{o:.2}"))
            };
            table.row([
                result.name.clone(),
                level.level.to_string(),
                thousands(level.faces),
                format!("{:.4}", level.h),
                format!("{:.3e}", level.integrable_error),
                order(&integrable),
                format!("{:.3e}", level.cointegrable_error),
                order(&cointegrable),
                seconds(level.seconds),
            ]);
        }
    }
    table.to_markdown()
}

/// Log–log plot of both families' errors against `h`, one line per discretization and family.
pub fn plot(results: &[DiscretizationResult], width: u32, height: u32) -> Plot {
    let mut series = Vec::new();
    for (index, result) in results.iter().enumerate() {
        let color = PALETTE[index % PALETTE.len()];
        for (family, error) in [
            (
                "integrable",
                (|l: &LevelResult| l.integrable_error) as fn(&LevelResult) -> f64,
            ),
            ("co-integrable", |l: &LevelResult| l.cointegrable_error),
        ] {
            let points = result.levels.iter().map(|l| (l.h, error(l))).collect();
            // One hue per discretization: the integrable family as a line with markers, the
            // co-integrable one as markers only.
            let style = if family == "integrable" {
                SeriesStyle::LineAndMarkers
            } else {
                SeriesStyle::Scatter
            };
            let mut line = Series::new(format!("{}: {family}", result.name), points, style);
            line.color = Some(color);
            series.push(line);
        }
    }
    // Room above the data for the legend (drawn in the top-right corner).
    let errors = results
        .iter()
        .flat_map(|r| &r.levels)
        .flat_map(|l| [l.integrable_error, l.cointegrable_error]);
    let (lo, hi) = errors
        .filter(|e| *e > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), e| {
            (lo.min(e), hi.max(e))
        });
    let mut y = Axis::new("max relative eigenvalue error", AxisScale::Log10);
    if lo <= hi {
        y.range = Some((lo / 2.0, hi * 1000.0));
    }
    Plot {
        title: "Eigenvalue error on icospheres against l(l+1)".to_string(),
        x: Axis::new("mean edge length h", AxisScale::Log10),
        y,
        series,
        width,
        height,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_spectrum_has_the_right_multiplicities() {
        let e = sphere_eigenvalues(3);
        assert_eq!(e.len(), 3 + 5 + 7);
        assert_eq!(&e[..4], &[2.0, 2.0, 2.0, 6.0]);
        assert_eq!(e[14], 12.0);
    }

    #[test]
    fn orders_follow_the_error_ratio() {
        let level = |level, h, e| LevelResult {
            level,
            faces: 0,
            h,
            integrable_error: e,
            cointegrable_error: e,
            seconds: 0.0,
        };
        let result = DiscretizationResult {
            name: "x".into(),
            levels: vec![level(1, 0.4, 0.16), level(2, 0.2, 0.04)],
        };
        let orders = result.orders(LevelResult::error);
        assert!((orders[0] - 2.0).abs() < 1e-12);
    }
}
