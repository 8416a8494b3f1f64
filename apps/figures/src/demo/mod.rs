//! The demo page (`tvf demo` parses its flags and runs it): the tour of tvf on one mesh, as a
//! web page of pictures and numbers.
//!
//! Steps, one file each: the basis ([`basis`]), the eigenfields (paper Figure 1,
//! [`eigenfields`]), the Hodge decomposition of a field ([`hodge`]), filtering a noisy field
//! and its spectrum (Figures 7, 8, [`filtering`]), rate–distortion (Figure 9,
//! [`compression`]), a spline beside soft design (Figure 4, [`design`]) and fur along the
//! spline (Figure 5, also [`design`]). Figures 1, 7, 8 and 9 are this crate's, the same code
//! papers/'s reproduction runs. Every step is timed (page and the host's notes); every file is
//! written atomically. Without a mesh of the user's, the demo runs on [`default_mesh`].

mod basis;
mod compression;
mod default_mesh;
mod design;
mod eigenfields;
mod filtering;
mod hodge;
mod page;
mod screen_points;

pub use default_mesh::default_mesh;

use crate::error::FigureError;
use crate::finding::Experiment;
use image::RgbaImage;
use page::Section;
use std::path::PathBuf;
use std::time::Instant;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{BoxedComplex, Catalog};
use tvf_render::save_png;
use tvf_render::View;
use tvf_spectral::BasisSize;
use tvf_spectral::SpectralBasis;

/// What the demo runs on and how large it draws.
pub struct DemoConfig {
    /// Output folder.
    pub output: PathBuf,
    /// The mesh and its name for the page.
    pub mesh: SurfaceMesh,
    /// Name of the mesh on the page.
    pub mesh_name: String,
    /// Eigenfields of the basis (`-k`, harmonic ones included).
    pub fields: usize,
    /// The catalog the discretization is taken from (the program's: built-in entries and its
    /// own).
    pub catalog: Catalog,
    /// Id of the discretization in `catalog` (built with the entry's default boundary condition
    /// on a mesh with boundary).
    pub discretization: String,
    /// Size of a full-width picture (panels of grids are half of it each way).
    pub width: u32,
    /// Height of a full-width picture.
    pub height: u32,
    /// Fur strands.
    pub fur_strands: usize,
}

/// What the demo asks of the program that runs it: the basis (computed the program's way, e.g.
/// the CLI's with a progress bar) and a place for its progress notes.
pub trait DemoHost {
    /// The basis of `size` of `complex`.
    fn compute_basis(
        &self,
        complex: &BoxedComplex,
        size: BasisSize,
    ) -> Result<SpectralBasis, FigureError>;

    /// Shows one line of progress (e.g. on stderr).
    fn note(&self, message: &str);
}

/// What every step can use: the mesh, the discretization, the basis, the output folder.
pub struct Context<'a> {
    /// The mesh.
    pub mesh: &'a SurfaceMesh,
    /// The (conforming, barycentric) discretization.
    pub discretization: &'a BoxedComplex,
    /// The basis.
    pub basis: &'a SpectralBasis,
    /// The configuration.
    pub config: &'a DemoConfig,
}

impl Context<'_> {
    /// The view of a full-size picture.
    pub fn view(&self) -> View {
        View {
            width: self.config.width,
            height: self.config.height,
            yaw: 30.0,
            pitch: 35.0,
            zoom: 1.0,
        }
    }

    /// The view of one panel of a two-column grid.
    pub fn panel_view(&self) -> View {
        self.view().panel(2)
    }

    /// What papers/'s figures need: this mesh, complex and basis, writing into the output
    /// folder, one panel per field of [`Context::panel_view`].
    pub fn experiment(&self) -> Experiment<'_> {
        Experiment {
            name: &self.config.mesh_name,
            mesh: self.mesh,
            complex: self.discretization.as_ref(),
            basis: self.basis,
            out: &self.config.output,
            view: self.panel_view(),
        }
    }

    /// Size of a plot: the full width, three quarters of the height.
    pub fn plot_size(&self) -> (u32, u32) {
        (
            self.config.width.max(200),
            (self.config.height * 3 / 4).max(150),
        )
    }

    /// Saves `image` as `name` in the output folder.
    pub fn save(&self, image: &RgbaImage, name: &str) -> Result<(), FigureError> {
        Ok(save_png(image, &self.config.output.join(name))?)
    }
}

/// Runs one step: times it, reports it through the host, and records the time in its section.
fn timed(
    host: &dyn DemoHost,
    (number, total): (usize, usize),
    title: &str,
    step: impl FnOnce() -> Result<Section, FigureError>,
) -> Result<Section, FigureError> {
    host.note(&format!("demo [{number}/{total}] {title} ..."));
    let start = Instant::now();
    let mut section = step().map_err(|e| FigureError::InContext {
        context: format!("demo step '{title}'"),
        source: Box::new(e),
    })?;
    section.title = title.to_string();
    section.seconds = start.elapsed().as_secs_f64();
    host.note(&format!(
        "demo [{number}/{total}] {title}: {:.2} s",
        section.seconds
    ));
    Ok(section)
}

/// Runs the whole demo and writes `index.html`; returns the page's path.
pub fn run(config: &DemoConfig, host: &dyn DemoHost) -> Result<PathBuf, FigureError> {
    let start = Instant::now();
    const STEPS: usize = 7;
    let mut sections = Vec::new();
    let mut computed = None;
    sections.push(timed(host, (1, STEPS), "Mesh and Fourier basis", || {
        let (section, discretization, basis) = basis::run(config, host)?;
        computed = Some((discretization, basis));
        Ok(section)
    })?);
    let Some((discretization, basis)) = computed else {
        return Err(FigureError::Invalid(
            "the basis step produced no basis".to_string(),
        ));
    };
    let cx = Context {
        mesh: &config.mesh,
        discretization: &discretization,
        basis: &basis,
        config,
    };
    sections.push(timed(host, (2, STEPS), "Eigenfields (Figure 1)", || {
        eigenfields::run(&cx)
    })?);
    let mut test_field = Vec::new();
    sections.push(timed(host, (3, STEPS), "Hodge decomposition", || {
        let (section, field) = hodge::run(&cx)?;
        test_field = field;
        Ok(section)
    })?);
    sections.push(timed(
        host,
        (4, STEPS),
        "Filtering a noisy field (Figures 7 and 8)",
        || filtering::run(&cx),
    )?);
    sections.push(timed(
        host,
        (5, STEPS),
        "Compression: rate and distortion (Figure 9)",
        || compression::run(&cx, &test_field),
    )?);
    let mut spline = Vec::new();
    sections.push(timed(
        host,
        (6, STEPS),
        "Spline and soft design (Figure 4)",
        || {
            let (section, field) = design::run(&cx)?;
            spline = field;
            Ok(section)
        },
    )?);
    sections.push(timed(
        host,
        (7, STEPS),
        "Fur along the spline field (Figure 5)",
        || design::fur(&cx, &spline),
    )?);
    let total = start.elapsed().as_secs_f64();
    let intro = vec![
        ("mesh".to_string(), config.mesh_name.clone()),
        (
            "size".to_string(),
            format!(
                "{} vertices, {} edges, {} faces, genus {}",
                config.mesh.vertex_count(),
                config.mesh.edge_count(),
                config.mesh.face_count(),
                config.mesh.genus()
            ),
        ),
        (
            "discretization".to_string(),
            discretization.id().to_string(),
        ),
        (
            "basis".to_string(),
            format!(
                "{} lowest eigenfields ({} harmonic, {} integrable, {} co-integrable)",
                basis.len(),
                basis.count(tvf_spectral::FieldFamily::Harmonic),
                basis.count(tvf_spectral::FieldFamily::Integrable),
                basis.count(tvf_spectral::FieldFamily::Cointegrable)
            ),
        ),
        ("total time".to_string(), format!("{total:.1} s")),
    ];
    let html = page::html(
        "tvf: spectral processing of tangential vector fields",
        &intro,
        &sections,
        total,
    );
    page::write_page(&config.output, &html)?;
    let index = config.output.join("index.html");
    host.note(&format!("demo finished in {total:.1} s"));
    Ok(index)
}
