//! [`read_complex_folder`]: a complex from a folder of matrix files — the folder `tvf operators
//! MESH -o DIR` writes, edited, or one made by hand in MATLAB, Julia or numpy — checked like
//! `tvf.Complex.from_matrices` and wrapped as a [`MatrixComplex`].
//!
//! The folder holds `d0`, `d1`, `M0`, `M1` and `M2` (or `M2_inverse`) as `NAME.mtx` (Matrix
//! Market) or `NAME.npz` (`scipy.sparse.save_npz`), in the mesh's numbering. These five are the
//! truth: derived files (`S`, `S0`, `S2`, `B`, `J`) are ignored. `info.json` and
//! `vertex_map.npy` are optional; what each key of `info.json` adds and what is assumed without
//! it is in `docs/discretizations.md` ("your matrices from any language"). Every error names
//! the file it is about.

use crate::formats::complex_folder_info::{mass_file_name, MatrixFileFormat};
use crate::formats::folder_input::{is_plain_file_name, open_regular_file, read_small_file};
use crate::formats::sparse_file_read::{read_matrix_market_within, MatrixLimits};
use crate::formats::sparse_npz_read::{
    read_index_npy_within, read_sparse_npz_within, InflationBudget, NPZ_INFLATED_LIMIT,
};
use serde_json::Value;
use sprs::CsMat;
use std::io::BufReader;
use std::path::{Path, PathBuf};
use thiserror::Error;
use tvf_core::discretization::{BoundaryCondition, DiscretizationError, Mass, MassForm, NodeKind};
use tvf_core::SurfaceMesh;
use tvf_discretizations::{
    ComplexMatrices, FixedNodes, MatrixComplex, MatrixSampling, StatedNodeKinds,
};

/// The id of a complex read from a folder (with `+tangential` / `+normal` on a mesh with
/// boundary, like the catalog's ids).
pub const COMPLEX_FOLDER_ID: &str = "matrices";

/// The largest `info.json` read: 64 MiB (`tvf operators` writes a few kilobytes, plus the fixed
/// nodes of a mesh with boundary).
pub const MAX_INFO_BYTES: u64 = 64 << 20;

/// A problem with a file of a complex folder.
#[derive(Debug, Clone, Error)]
#[error("{}: {problem}", file.display())]
pub struct ComplexFolderError {
    /// The file (or files, or the folder) the problem is about.
    pub file: PathBuf,
    /// What is wrong.
    pub problem: String,
}

/// The complex stored in the folder `dir`, for `mesh`, whose vertex `v` is vertex
/// `original_vertex[v]` of the input file (checked against `vertex_map.npy` if the folder has
/// one; `info.json`'s `mesh_fingerprint` is checked against `mesh`).
pub fn read_complex_folder(
    dir: &Path,
    mesh: &SurfaceMesh,
    original_vertex: &[usize],
) -> Result<MatrixComplex, ComplexFolderError> {
    let folder = Folder::open(dir, mesh)?;
    folder.check_mesh(mesh, original_vertex)?;
    let (d0_file, d0) = folder.matrix("d0")?;
    let (d1_file, d1) = folder.matrix("d1")?;
    if d1.cols() != d0.rows() {
        return Err(error(
            &d1_file,
            format!(
                "d1 is {} x {}: its columns must be the {} rows of d0 ({})",
                d1.rows(),
                d1.cols(),
                d0.rows(),
                d0_file.display()
            ),
        ));
    }
    let sizes = [d0.cols(), d0.rows(), d1.rows()];
    let mut mass_files = Vec::new();
    let mut masses = Vec::new();
    for (k, name) in ["M0", "M1", "M2"].into_iter().enumerate() {
        let (file, mass) = folder.mass(name, sizes[k])?;
        mass_files.push(file);
        masses.push(mass);
    }
    let [m0, m1, m2]: [Mass; 3] = masses.try_into().expect("three masses");
    let fixed = folder.fixed_nodes()?;
    let condition = folder.boundary_condition()?;
    let sampling = folder.sampling()?;
    let stated = folder.node_kinds()?;
    let id = match mesh.is_closed() {
        true => COMPLEX_FOLDER_ID.to_string(),
        false => format!("{COMPLEX_FOLDER_ID}+{}", condition.name()),
    };
    let matrices = ComplexMatrices { d0, d1, m0, m1, m2 };
    MatrixComplex::with_boundary(&id, mesh, matrices, &stated, &fixed, condition, sampling).map_err(
        |e| {
            let file = blamed_file(&e, &folder, [&d0_file, &d1_file], &mass_files);
            error(&file, e.to_string())
        },
    )
}

/// The file an error of [`MatrixComplex::with_boundary`] is about: the mass it names, both
/// `d` files for `d1 · d0`, `info.json` for fixed nodes and node kinds (stated or missing where
/// a size is ambiguous), else the folder.
fn blamed_file(
    e: &DiscretizationError,
    folder: &Folder,
    [d0, d1]: [&Path; 2],
    masses: &[PathBuf],
) -> PathBuf {
    let mass_named = |what: &str| {
        ["M0", "M1", "M2"]
            .iter()
            .position(|name| what.starts_with(name))
            .map(|k| masses[k].clone())
    };
    let joined = |a: &Path, b: &Path| PathBuf::from(format!("{} and {}", a.display(), b.display()));
    match e {
        DiscretizationError::NotPositive { what, .. }
        | DiscretizationError::NotPositiveDefinite { what, .. }
        | DiscretizationError::NotSymmetric { what, .. }
        | DiscretizationError::NonFinite { what, .. } => {
            mass_named(what).unwrap_or_else(|| folder.dir.clone())
        }
        DiscretizationError::Inconsistent(message)
            if message.starts_with("fixed")
                || message.contains("ambiguous")
                || message.contains("stated to be") =>
        {
            folder.info_path()
        }
        DiscretizationError::Inconsistent(message) if message.contains("co-potential space") => {
            d1.to_path_buf()
        }
        DiscretizationError::Inconsistent(message)
            if message.contains("(columns of d0)") || message.contains("(rows of d0)") =>
        {
            d0.to_path_buf()
        }
        DiscretizationError::Inconsistent(message) if message.contains("d1 · d0") => {
            joined(d0, d1)
        }
        _ => folder.dir.clone(),
    }
}

fn error(file: &Path, problem: impl Into<String>) -> ComplexFolderError {
    ComplexFolderError {
        file: file.to_path_buf(),
        problem: problem.into(),
    }
}

/// A complex folder and its `info.json` (`Value::Null` without one); the sizes its matrices
/// may have (the mesh's `V`, `E`, `F`, `2F`) and what its `.npz` files may still inflate to.
struct Folder {
    dir: PathBuf,
    info: Value,
    sizes: [(&'static str, usize); 4],
    inflation: InflationBudget,
}

impl Folder {
    fn open(dir: &Path, mesh: &SurfaceMesh) -> Result<Self, ComplexFolderError> {
        if !dir.is_dir() {
            return Err(error(
                dir,
                "not a folder (give the folder `tvf operators MESH -o DIR` wrote)",
            ));
        }
        let path = dir.join("info.json");
        let info = match path.exists() {
            false => Value::Null,
            true => {
                let bytes = read_small_file(&path, MAX_INFO_BYTES).map_err(|e| error(&path, e))?;
                // Some editors start a UTF-8 file with a byte-order mark; JSON has none.
                let text = bytes.strip_prefix(tvf_core::io::UTF8_BOM).unwrap_or(&bytes);
                serde_json::from_slice(text)
                    .map_err(|e| error(&path, format!("not valid JSON: {e}")))?
            }
        };
        if !(info.is_object() || info.is_null()) {
            return Err(error(&path, "not a JSON object"));
        }
        let faces = mesh.face_count();
        Ok(Self {
            dir: dir.to_path_buf(),
            info,
            sizes: [
                ("V", mesh.vertex_count()),
                ("E", mesh.edge_count()),
                ("F", faces),
                ("2F", 2 * faces),
            ],
            inflation: InflationBudget::new(NPZ_INFLATED_LIMIT),
        })
    }

    fn info_path(&self) -> PathBuf {
        self.dir.join("info.json")
    }

    /// The `info.json` key `key` (nested keys separated by `/`), if present and not null.
    fn key(&self, key: &str) -> Option<&Value> {
        key.split('/')
            .try_fold(&self.info, |value, part| value.get(part))
            .filter(|v| !v.is_null())
    }

    /// The string key `key`, if present (an error if it is not a string).
    fn string(&self, key: &str) -> Result<Option<&str>, ComplexFolderError> {
        match self.key(key) {
            None => Ok(None),
            Some(Value::String(s)) => Ok(Some(s)),
            Some(other) => Err(error(
                &self.info_path(),
                format!("'{key}' is {other}, not a string"),
            )),
        }
    }

    /// Checks `mesh_fingerprint` and `vertex_map.npy` against the mesh given.
    fn check_mesh(
        &self,
        mesh: &SurfaceMesh,
        original_vertex: &[usize],
    ) -> Result<(), ComplexFolderError> {
        if let Some(stored) = self.string("mesh_fingerprint")? {
            let found = format!("{:016x}", mesh.fingerprint());
            if stored != found {
                return Err(error(
                    &self.info_path(),
                    format!(
                        "the matrices were written for another mesh (mesh_fingerprint {stored}; \
                         the mesh given has {found}, {} vertices and {} faces): give the mesh \
                         the folder was written from, or remove the key to use the matrices \
                         anyway",
                        mesh.vertex_count(),
                        mesh.face_count()
                    ),
                ));
            }
        }
        let path = self.dir.join("vertex_map.npy");
        if !path.exists() {
            return Ok(());
        }
        let file = open_regular_file(&path).map_err(|e| error(&path, e))?;
        let expected = Some(original_vertex.len());
        let map = read_index_npy_within(BufReader::new(file.bounded()), "vertex_map", expected)
            .map_err(|e| {
                error(
                    &path,
                    format!(
                        "{e} (one per vertex of the mesh given: was the folder written for \
                         another mesh?)"
                    ),
                )
            })?;
        if let Some(v) = (0..map.len()).find(|&v| map[v] != original_vertex[v]) {
            return Err(error(
                &path,
                format!(
                    "mesh vertex {v} is input vertex {} here, but input vertex {} in the mesh \
                     given: the folder was written for another input file",
                    map[v], original_vertex[v]
                ),
            ));
        }
        Ok(())
    }

    /// The matrix file `name` (`NAME.mtx` or `NAME.npz`) and its matrix, finite.
    fn matrix(&self, name: &str) -> Result<(PathBuf, CsMat<f64>), ComplexFolderError> {
        let file = self.find(name)?.ok_or_else(|| {
            error(
                &self.dir.join(format!("{name}.mtx")),
                format!(
                    "missing (nor {name}.npz): a complex folder needs d0, d1, M0, M1 and M2 (or \
                     M2_inverse), each as NAME.mtx or NAME.npz"
                ),
            )
        })?;
        let matrix = self.read_matrix_file(&file)?;
        Ok((file, matrix))
    }

    /// `NAME.mtx` or `NAME.npz`, whichever exists (an error if both do).
    fn find(&self, name: &str) -> Result<Option<PathBuf>, ComplexFolderError> {
        let found: Vec<PathBuf> = MatrixFileFormat::ALL
            .iter()
            .map(|f| self.dir.join(format!("{name}.{}", f.extension())))
            .filter(|p| p.exists())
            .collect();
        match &found[..] {
            [] => Ok(None),
            [one] => Ok(Some(one.clone())),
            [first, ..] => Err(error(
                first,
                format!("both {name}.mtx and {name}.npz exist: remove the one not meant"),
            )),
        }
    }

    /// The mass `name` (`M0`, `M1`, `M2`) of `n` nodes: its file (from `info.json`'s
    /// `masses/NAME/file`, else `NAME` or `NAME_inverse`), form and storage.
    fn mass(&self, name: &'static str, n: usize) -> Result<(PathBuf, Mass), ComplexFolderError> {
        let stem = match self.string(&format!("masses/{name}/file"))? {
            Some(stem) if !is_plain_file_name(stem) => {
                return Err(error(
                    &self.info_path(),
                    format!(
                        "masses/{name}/file is '{stem}': the name of a file in this folder \
                         (without extension, folders and '..')"
                    ),
                ))
            }
            Some(stem) => stem.to_string(),
            None => {
                let direct = self.find(name)?;
                let inverse = self.find(&format!("{name}_inverse"))?;
                match (direct, inverse) {
                    (Some(_), Some(inverse)) => {
                        return Err(error(
                            &inverse,
                            format!("both {name} and {name}_inverse exist: remove one"),
                        ))
                    }
                    (None, Some(_)) => mass_file_name(name, MassForm::Inverse),
                    _ => name.to_string(),
                }
            }
        };
        let form = self.mass_form(name, &stem)?;
        let (file, matrix) = self.matrix(&stem)?;
        if matrix.shape() != (n, n) {
            return Err(error(
                &file,
                format!(
                    "{name} is {} x {}, but the complex needs {n} x {n} ({})",
                    matrix.rows(),
                    matrix.cols(),
                    match name {
                        "M0" => "the columns of d0",
                        "M1" => "the rows of d0",
                        _ => "the rows of d1",
                    }
                ),
            ));
        }
        // The file decides what the matrix is; a storage in info.json must agree with it (a
        // 'diagonal' mass with an entry off the diagonal is refused by `mass_from_matrix`).
        let diagonal = match (
            self.string(&format!("masses/{name}/storage"))?,
            off_diagonal(&matrix),
        ) {
            (Some("diagonal"), _) => true,
            (Some("sparse"), Some(_)) => false,
            (Some("sparse"), None) => {
                return Err(error(
                    &self.info_path(),
                    format!(
                        "masses/{name}/storage is 'sparse', but {} holds a diagonal matrix (a \
                         sparse mass is factorized and solved with, for nothing): the file \
                         decides; say 'diagonal' or remove the key",
                        file.display()
                    ),
                ))
            }
            (Some(other), _) => {
                return Err(error(
                    &self.info_path(),
                    format!("masses/{name}/storage is '{other}': diagonal or sparse"),
                ))
            }
            (None, off) => off.is_none(),
        };
        let what = match (form, name) {
            (MassForm::Direct, _) => name,
            (MassForm::Inverse, "M0") => "M0_inverse",
            (MassForm::Inverse, "M1") => "M1_inverse",
            (MassForm::Inverse, _) => "M2_inverse",
        };
        let mass = mass_from_matrix(what, matrix, diagonal, form).map_err(|e| error(&file, e))?;
        Ok((file, mass))
    }

    /// Whether the file `stem` holds the mass `name` or its inverse: `masses/NAME/form` if
    /// given (`direct` or `inverse`), else the file name (`…_inverse`); an error if they
    /// contradict each other.
    fn mass_form(&self, name: &str, stem: &str) -> Result<MassForm, ComplexFolderError> {
        let named = match stem.ends_with("_inverse") {
            true => MassForm::Inverse,
            false => MassForm::Direct,
        };
        let key = format!("masses/{name}/form");
        let stated = match self.string(&key)? {
            None => return Ok(named),
            Some("direct") => MassForm::Direct,
            Some("inverse") => MassForm::Inverse,
            Some(other) => {
                return Err(error(
                    &self.info_path(),
                    format!("{key} is '{other}': direct or inverse"),
                ))
            }
        };
        if stated == MassForm::Direct && named == MassForm::Inverse {
            return Err(error(
                &self.info_path(),
                format!(
                    "{key} is 'direct', but the file {stem} is named as an inverse: rename the \
                     file or say 'inverse'"
                ),
            ));
        }
        Ok(stated)
    }

    /// Reads a `.mtx` or `.npz` matrix file of this folder (a regular file; its declared shape
    /// one of the mesh's sizes, its entries what the file can hold, checked before anything
    /// is allocated) and checks every stored entry finite.
    fn read_matrix_file(&self, path: &Path) -> Result<CsMat<f64>, ComplexFolderError> {
        let input = open_regular_file(path).map_err(|e| error(path, e))?;
        let limits = MatrixLimits {
            sizes: &self.sizes,
            file_bytes: Some(input.bytes),
        };
        let reader = BufReader::new(input.bounded());
        let matrix = match path.extension().and_then(|e| e.to_str()) {
            Some("npz") => {
                // The archive's directory is at its end: it needs a seekable file.
                let file = reader.into_inner().into_inner();
                read_sparse_npz_within(BufReader::new(file), &limits, &self.inflation)
            }
            _ => read_matrix_market_within(reader, &limits),
        }
        .map_err(|e| error(path, e))?;
        for (&value, (i, j)) in matrix.iter() {
            if !value.is_finite() {
                return Err(error(
                    path,
                    format!("row {i} col {j} (0-based): not finite ({value})"),
                ));
            }
        }
        Ok(matrix)
    }

    /// `fixed_nodes/{potentials,fields,co_potentials}`: lists of indices (none if absent).
    fn fixed_nodes(&self) -> Result<FixedNodes, ComplexFolderError> {
        let list = |space: &str| -> Result<Vec<usize>, ComplexFolderError> {
            let key = format!("fixed_nodes/{space}");
            match self.key(&key) {
                None => Ok(Vec::new()),
                Some(Value::Array(items)) => items
                    .iter()
                    .map(|item| {
                        item.as_u64().map(|i| i as usize).ok_or_else(|| {
                            error(
                                &self.info_path(),
                                format!("{key}: {item} is not a node index"),
                            )
                        })
                    })
                    .collect(),
                Some(other) => Err(error(
                    &self.info_path(),
                    format!(
                        "{key} is {other}, not a list of node indices (a count is what tvf \
                         operators wrote before it listed them: write the folder again)"
                    ),
                )),
            }
        };
        Ok(FixedNodes {
            potentials: list("potentials")?,
            fields: list("fields")?,
            co_potentials: list("co_potentials")?,
        })
    }

    /// `boundary_condition` (tangential if absent).
    fn boundary_condition(&self) -> Result<BoundaryCondition, ComplexFolderError> {
        match self.string("boundary_condition")? {
            None => Ok(BoundaryCondition::default()),
            Some(name) => BoundaryCondition::from_name(name).ok_or_else(|| {
                error(
                    &self.info_path(),
                    format!("boundary_condition is '{name}': tangential or normal"),
                )
            }),
        }
    }

    /// `sampling` (none if absent).
    fn sampling(&self) -> Result<MatrixSampling, ComplexFolderError> {
        match self.string("sampling")? {
            None => Ok(MatrixSampling::None),
            Some(name) => MatrixSampling::from_name(name).ok_or_else(|| {
                error(
                    &self.info_path(),
                    format!("sampling is '{name}': none, face-frames, whitney or polygon-sharp"),
                )
            }),
        }
    }

    /// `nodes/{potentials,fields,co_potentials}`: the node kind of each space (`vertices`,
    /// `edges`, `faces` or `face-frames`), `None` where absent (then inferred from the size).
    fn node_kinds(&self) -> Result<StatedNodeKinds, ComplexFolderError> {
        let mut stated = [None; 3];
        for (kind, space) in stated
            .iter_mut()
            .zip(["potentials", "fields", "co_potentials"])
        {
            let key = format!("nodes/{space}");
            if let Some(name) = self.string(&key)? {
                *kind = Some(NodeKind::from_name(name).ok_or_else(|| {
                    error(
                        &self.info_path(),
                        format!("{key} is '{name}': vertices, edges, faces or face-frames"),
                    )
                })?);
            }
        }
        Ok(stated)
    }
}

/// The first stored nonzero off the diagonal, if any.
fn off_diagonal(matrix: &CsMat<f64>) -> Option<(usize, usize)> {
    matrix
        .iter()
        .find(|(&v, (i, j))| i != j && v != 0.0)
        .map(|(_, ij)| ij)
}

/// The [`Mass`] a square matrix file gives: a diagonal (the file may hold no nonzero off the
/// diagonal) or a sparse matrix, stored as `M` or `M⁻¹` (`what` names it in errors).
fn mass_from_matrix(
    what: &'static str,
    matrix: CsMat<f64>,
    diagonal: bool,
    form: MassForm,
) -> Result<Mass, String> {
    let checked = if diagonal {
        if let Some((i, j)) = off_diagonal(&matrix) {
            return Err(format!(
                "row {i} col {j} (0-based) is off the diagonal, but info.json says the mass is \
                 diagonal"
            ));
        }
        let values = (0..matrix.rows())
            .map(|i| matrix.get(i, i).copied().unwrap_or(0.0))
            .collect();
        Mass::diagonal(what, values).map(|mass| match form {
            MassForm::Direct => mass,
            MassForm::Inverse => mass.inverse(),
        })
    } else {
        match form {
            MassForm::Direct => Mass::sparse(what, matrix),
            MassForm::Inverse => Mass::sparse_inverse(what, matrix),
        }
    };
    checked.map_err(|e| e.to_string())
}
