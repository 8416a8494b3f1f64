//! The folders `tvf analyze` and `tvf rate-distortion` write, each file into a staged folder
//! (committed by the caller, so the folder appears whole or not at all): a field's coefficients,
//! energies and spectrum plot ([`write_analysis_folder`]); rate–distortion points and their
//! curves ([`write_rate_distortion_folder`]). Errors name the file in the output folder.

use crate::error::FigureError;
use crate::spectral_plots::{rate_distortion_plot, spectrum_plot};
use tvf_core::io::StagedFolder;
use tvf_render::save_png;
use tvf_spectral::{
    rate_distortion_csv, write_folder_bytes, CoefficientCoding, FolderFileError, RatePoint,
    SpectralAnalysis,
};

/// Size of the rate–distortion plot in pixels.
const RATE_DISTORTION_PLOT_SIZE: (u32, u32) = (1000, 650);

/// Writes `coefficients.csv` ([`SpectralAnalysis::coefficients_csv`]), `energy.json` (the text
/// `energy_json`, e.g. [`tvf_spectral::AnalysisReport::to_json`] printed) and `spectrum.png`
/// ([`spectrum_plot`]) into `folder`. A field without a non-zero coefficient has no plot: an
/// error.
pub fn write_analysis_folder(
    folder: &StagedFolder,
    analysis: &SpectralAnalysis,
    energy_json: &str,
) -> Result<(), FolderFileError> {
    let csv = analysis.coefficients_csv();
    write_folder_bytes(folder, "coefficients.csv", csv.as_bytes())?;
    write_folder_bytes(folder, "energy.json", energy_json.as_bytes())?;
    let name = "spectrum.png";
    let plot = spectrum_plot(analysis).ok_or_else(|| {
        let why = FigureError::Invalid("the field has no non-zero coefficient to plot".into());
        FolderFileError::new(folder, name, why)
    })?;
    let image = plot
        .render()
        .map_err(|e| FolderFileError::new(folder, name, e))?;
    save_png(&image, &folder.path().join(name)).map_err(|e| FolderFileError::new(folder, name, e))
}

/// Writes `rate_distortion.csv` ([`rate_distortion_csv`]) and `rate_distortion.png` (the
/// curves of `codings`, [`rate_distortion_plot`], titled with `mesh_name`) into `folder`.
pub fn write_rate_distortion_folder(
    folder: &StagedFolder,
    points: &[RatePoint],
    codings: &[CoefficientCoding],
    mesh_name: &str,
) -> Result<(), FolderFileError> {
    let csv = rate_distortion_csv(points);
    write_folder_bytes(folder, "rate_distortion.csv", csv.as_bytes())?;
    let name = "rate_distortion.png";
    let title = format!("Rate-distortion on {mesh_name}");
    let plot = rate_distortion_plot(points, codings, title, RATE_DISTORTION_PLOT_SIZE);
    let image = plot
        .render()
        .map_err(|e| FolderFileError::new(folder, name, e))?;
    save_png(&image, &folder.path().join(name)).map_err(|e| FolderFileError::new(folder, name, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tvf_core::generate::torus;
    use tvf_discretizations::{catalog_entry, DEFAULT_DISCRETIZATION};
    use tvf_spectral::{compute_basis, BasisRequest};

    #[test]
    fn both_folders_hold_their_files_and_a_zero_field_has_no_plot() {
        let mesh = torus(1.0, 0.4, 12, 6).unwrap();
        let complex = catalog_entry(DEFAULT_DISCRETIZATION)
            .unwrap()
            .build(&mesh)
            .unwrap();
        let basis = compute_basis(complex.as_ref(), &BasisRequest::fields(8)).unwrap();
        let field: Vec<f64> = (0..basis.field_dimension())
            .map(|i| basis.fields()[(i, 3)] + 0.5 * basis.fields()[(i, 6)])
            .collect();
        let analysis = SpectralAnalysis::new(&basis, &field).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let folder = StagedFolder::new(&dir.path().join("analysis")).unwrap();
        write_analysis_folder(&folder, &analysis, "{}").unwrap();
        for name in ["coefficients.csv", "energy.json", "spectrum.png"] {
            assert!(folder.path().join(name).is_file(), "{name}");
        }
        let zero = SpectralAnalysis::new(&basis, &vec![0.0; field.len()]).unwrap();
        let error = write_analysis_folder(&folder, &zero, "{}").unwrap_err();
        assert!(error.path.ends_with("analysis/spectrum.png"), "{error}");
        assert!(
            error.to_string().contains("no non-zero coefficient"),
            "{error}"
        );
        let point = RatePoint {
            coding: CoefficientCoding::Float64,
            pairs: 2,
            bytes: 100,
            bits_per_vertex: 1.0,
            relative_error: 0.5,
        };
        let folder = StagedFolder::new(&dir.path().join("rd")).unwrap();
        write_rate_distortion_folder(&folder, &[point], &[point.coding], "torus").unwrap();
        let csv = std::fs::read_to_string(folder.path().join("rate_distortion.csv")).unwrap();
        assert_eq!(csv.lines().count(), 2);
        assert!(folder.path().join("rate_distortion.png").is_file());
    }
}
