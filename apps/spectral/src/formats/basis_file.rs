//! Basis files (`.tvfb`): a Fourier basis saved for reuse, tied to its mesh, its discretization
//! and the matrices of that discretization.
//!
//! Layout of format version 3 (all integers and floats little-endian; words are 8 bytes):
//!
//! | bytes | content |
//! |---|---|
//! | 8 | magic `TVFBASIS` |
//! | 4 | format version (`u32`, currently 3) |
//! | 4 | header length `H` in bytes, from the magic to the payload (`u32`) |
//! | 8 | mesh fingerprint ([`tvf_core::SurfaceMesh::fingerprint`]) |
//! | 8 × 6 | faces `F`, field dimension `n1` (`2F` for face fields, `E` for DEC 1-forms), fields `d`, harmonic `h`, integrable `a`, co-integrable `b` counts |
//! | 8 × 3 | layout (`0` fields, `1` eigenfunctions), potential rows `n0`, co-potential rows `n2` (`0` for the fields layout) |
//! | 8 × 6 | matrix hash of the complex ([`tvf_core::discretization::MatrixHash`]): the hashes of `d0`, `d1`, `M0`, `M1`, `M2` and of the fixed nodes |
//! | 8 × 3 | field mass `M1` ([`StoredFieldMass`]): storage (`0` not stored, the eigenfunctions layout; `1` diagonal; `2` sparse), form (`0`: the stored matrix is `M1` itself; `1`, `M1⁻¹`, is reserved and refused), stored entries `nnz` (`0` unless sparse) |
//! | 4 + L | discretization id: `u32` length, UTF-8 text: the complex id (e.g. `conforming-barycentric`) |
//! | 8 | [`Hash64`] of the header bytes before it |
//! | 8·d | eigenvalues (`f64`), ascending |
//! | d, zero-padded to a multiple of 8 | families (`0` harmonic, `1` integrable, `2` co-integrable) |
//! | layout-specific | see below |
//! | 8 | [`Hash64`] of the payload (everything between the header and this checksum) |
//!
//! The **fields layout** continues with `M1` and then `8·n1·d` bytes, the fields column by
//! column. `M1` is stored as the complex holds it ([`tvf_core::discretization::Mass`]): a
//! diagonal as its `n1` values (`f64`); a sparse matrix as its compressed sparse rows — `n1 + 1`
//! row starts (`u64`, from `0` to `nnz`), `nnz` column indices (`u64`, strictly ascending in each
//! row) and `nnz` values (`f64`), both triangles, bit for bit. Reading it back checks the
//! structure, finiteness and symmetry, and that it hashes to the header's `M1` hash; its free
//! nodes are not stored (the basis only applies `M1`, which does not need them).
//!
//! The **eigenfunctions layout** ([`crate::EigenfunctionBasis`]) stores no mass (`M1` is the
//! complex's) and continues with the `a` potentials (`8·n0` bytes each), the `b` co-potentials
//! (`8·n2` bytes each) and the `h` harmonic fields (`8·n1` bytes each), each family in the order
//! its fields appear in the basis; its fields are formed through the complex's sparse gradients
//! on loading, so it needs the complex, and it is written whenever it is the smaller of the two
//! (on every mesh of the catalog's complexes: `V + E` values for a pair of fields against `4F`,
//! about half).
//!
//! **Matrices.** A basis is loaded for a complex only if the header's matrix hash is the
//! complex's ([`BasisFileError::WrongMatrices`] names the parts that differ): the same id and
//! mesh with a changed assembly is another basis.
//!
//! **Earlier versions** still load. Version 2 has neither the matrix hash nor the field mass
//! words (the fields layout holds the diagonal of `M1`, as `1` above); version 1 has no layout
//! words either (its layout is fields). They carry no matrix hash, so [`load_basis`] accepts them
//! on id and mesh alone, and their header's [`BasisFileKey::matrix_hash`] is `None` for callers
//! that want more (the basis store never uses them; the CLI's `--basis` says so on stderr).
//!
//! Round trips are bit-exact: a fields file gives back its fields and `M1`, an eigenfunctions
//! file its eigenfunctions and so the very fields the basis had in memory. Saving is atomic;
//! loading streams (no second copy in memory), and a header whose counts promise more bytes
//! than the file has is refused before anything is allocated for them.
//!
//! **Written while computed.** Nothing in the layout needs the eigenfunctions in order: the
//! header holds only counts (fixed by the inertia counts before anything is solved), and every
//! column has a fixed place. So `tvf basis -o` writes each finished interval's eigenfunctions
//! to its place as the eigensolver hands them on, the eigenvalues and families last, and the
//! checksum after reading the payload back
//! ([`crate::formats::streamed_basis_file::save_computed_basis`]): the same bytes as saving the
//! basis computed in memory, without ever holding all its eigenfunctions.
//!
//! **Read in blocks.** For the same reason, projections `Uᵀ M1 v` and syntheses `U c` need no
//! more than one family's columns at a time, in file order: [`crate::BasisFileBlocks`] checks
//! an eigenfunctions file whole (key, size, payload checksum, finite values) and then reads its
//! stored columns a block at a time (`tvf filter` and `tvf coefficients` use it), so a basis
//! larger than memory can be used as well as computed.

use crate::eigenfunction_basis::{field_of_stored_into, FIELD_CHUNK};
pub use crate::formats::basis_file_error::BasisFileError;
use crate::formats::basis_file_header::{encode_header, read_header};
pub use crate::formats::basis_file_header::{
    BasisFileHeader, BasisFileKey, BasisFileLayout, BASIS_FILE_MAGIC, BASIS_FILE_VERSION,
};
pub use crate::formats::basis_file_mass::StoredFieldMass;
use crate::formats::basis_file_mass::{write_field_mass, FieldMassRead};
use crate::formats::stored_basis::StoredBasis;
use crate::{EigenfunctionBasis, FieldFamily, SpectralBasis};
use faer::reborrow::{IntoConst, ReborrowMut};
use faer::{Mat, MatMut};
use std::io::{Read, Write};
use std::ops::Range;
use std::path::Path;
use tvf_core::discretization::{HodgeComplex, HodgeOperators, LinearOperator, Mass, MatrixHash};
use tvf_core::Hash64;

/// The byte a basis file stores for `family`.
pub(crate) fn family_code(family: FieldFamily) -> u8 {
    match family {
        FieldFamily::Harmonic => 0,
        FieldFamily::Integrable => 1,
        FieldFamily::Cointegrable => 2,
    }
}

/// Saves `basis` (dense fields) for the mesh and discretization of `key`, atomically, in the
/// fields layout.
pub fn save_basis(
    path: &Path,
    basis: &SpectralBasis,
    key: &BasisFileKey,
) -> Result<(), BasisFileError> {
    let fields = basis.fields();
    let contents = BasisContents {
        eigenvalues: basis.eigenvalues(),
        families: basis.families(),
        field_dimension: basis.field_dimension(),
        field_mass: basis.field_mass(),
    };
    let body = |out: &mut HashingWriter<'_>, buffer: &mut Vec<u8>| {
        (0..fields.ncols()).try_for_each(|j| write_values(out, buffer, fields.col(j).iter()))
    };
    write_basis(path, key, &contents, BasisFileLayout::Fields, body)
}

/// Saves a basis computed in compact form (the eigenfunctions of `complex`) for the mesh and
/// discretization of `key`, atomically: in the eigenfunctions layout when it is the smaller,
/// else in the fields layout, the fields formed a few at a time in parallel while the file is
/// written, so they are never all in memory. Either file loads to the basis
/// [`EigenfunctionBasis::dense_fields`] gives, bit for bit: co-integrable fields through a
/// co-gradient that is not a sparse matrix (a sparse `M1`) are formed by one block solve, which
/// the loader repeats, so a basis with such fields is always written as eigenfunctions.
pub fn save_eigenfunction_basis<H: HodgeComplex + ?Sized>(
    path: &Path,
    basis: &EigenfunctionBasis,
    complex: &H,
    key: &BasisFileKey,
) -> Result<(), BasisFileError> {
    basis
        .check_complex(complex)
        .map_err(|e| BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: format!("the basis does not fit its complex: {e}"),
        })?;
    if key.matrix_hash != Some(complex.matrix_hash()) {
        return Err(BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: "the key's matrix hash is not the complex's".into(),
        });
    }
    let contents = BasisContents {
        eigenvalues: basis.eigenvalues(),
        families: basis.families(),
        field_dimension: complex.field_dimension(),
        field_mass: complex.m1(),
    };
    let (n0, n2) = (
        complex.potential_dimension(),
        complex.co_potential_dimension(),
    );
    let count = |family| basis.families().iter().filter(|&&f| f == family).count();
    let compact_values = n0 * count(FieldFamily::Integrable)
        + n2 * count(FieldFamily::Cointegrable)
        + contents.field_dimension * count(FieldFamily::Harmonic);
    let streamed_alike = complex.co_gradient().is_sparse() || count(FieldFamily::Cointegrable) == 0;
    if compact_values < contents.field_dimension * basis.len() || !streamed_alike {
        let layout = BasisFileLayout::Eigenfunctions {
            potential_dimension: n0,
            co_potential_dimension: n2,
        };
        return write_basis(path, key, &contents, layout, |out, buffer| {
            for (family, matrix) in [
                (FieldFamily::Integrable, basis.potentials()),
                (FieldFamily::Cointegrable, basis.co_potentials()),
                (FieldFamily::Harmonic, basis.harmonic_fields()),
            ] {
                for slot in basis.family_slots(family) {
                    write_values(out, buffer, matrix.col(slot).iter())?;
                }
            }
            Ok(())
        });
    }
    let columns = |range| basis.field_columns(complex, range);
    let body = |out: &mut HashingWriter<'_>, buffer: &mut Vec<u8>| {
        write_streamed_fields(out, buffer, basis.len(), &columns)
    };
    write_basis(path, key, &contents, BasisFileLayout::Fields, body)
}

/// Everything of a basis file but its stored fields or eigenfunctions.
struct BasisContents<'a> {
    eigenvalues: &'a [f64],
    families: &'a [FieldFamily],
    field_dimension: usize,
    /// `M1` (written in the fields layout).
    field_mass: &'a Mass,
}

/// Writes a basis file: header, eigenvalues, families (and in the fields layout `M1`), then
/// `body(out, buffer)` writes the stored fields or eigenfunctions through the checksumming
/// `out` (with `buffer` as scratch space). Refuses a key without a matrix hash and, in the
/// fields layout, an `M1` that is not the one the key's matrix hash names.
fn write_basis(
    path: &Path,
    key: &BasisFileKey,
    contents: &BasisContents<'_>,
    layout: BasisFileLayout,
    body: impl FnOnce(&mut HashingWriter<'_>, &mut Vec<u8>) -> std::io::Result<()>,
) -> Result<(), BasisFileError> {
    let n = contents.field_dimension;
    let count = contents.eigenvalues.len();
    if n != key.field_dimension {
        return Err(BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: format!(
                "basis fields have {n} rows, the fields of '{}' on this mesh have {}",
                key.discretization, key.field_dimension
            ),
        });
    }
    let invalid = |reason: String| BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason,
    };
    let Some(matrix_hash) = key.matrix_hash else {
        return Err(invalid(
            "the key carries no matrix hash of the complex (BasisFileKey::new gives it)".into(),
        ));
    };
    let field_mass = match layout {
        BasisFileLayout::Fields => {
            if MatrixHash::of_mass(contents.field_mass) != matrix_hash.m1 {
                return Err(invalid(format!(
                    "the basis's field mass is not the M1 of the complex '{}' of the key",
                    key.discretization
                )));
            }
            StoredFieldMass::of(contents.field_mass).map_err(invalid)?
        }
        BasisFileLayout::Eigenfunctions { .. } => StoredFieldMass::FromComplex,
    };
    let family_count = |family| contents.families.iter().filter(|&&f| f == family).count();
    let header = encode_header(
        &BasisFileHeader {
            version: BASIS_FILE_VERSION,
            key: key.clone(),
            field_count: count,
            harmonic_count: family_count(FieldFamily::Harmonic),
            integrable_count: family_count(FieldFamily::Integrable),
            cointegrable_count: family_count(FieldFamily::Cointegrable),
            layout,
            field_mass,
        },
        &matrix_hash,
    );
    tvf_core::io::write_atomically(path, |w| {
        w.write_all(&header)?;
        let mut out = HashingWriter {
            inner: w,
            hash: Hash64::new(),
        };
        let mut buffer = Vec::with_capacity(8 * n.max(count) + 8);
        write_values(&mut out, &mut buffer, contents.eigenvalues)?;
        buffer.clear();
        buffer.extend(contents.families.iter().map(|&f| family_code(f)));
        buffer.resize(count.div_ceil(8) * 8, 0);
        out.write_all(&buffer)?;
        if layout == BasisFileLayout::Fields {
            write_field_mass(&mut out, contents.field_mass)?;
        }
        body(&mut out, &mut buffer)?;
        let checksum = out.hash.finish();
        w.write_all(&checksum.to_le_bytes())
    })
    .map_err(|source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes `values` (a slice or a matrix column) as little-endian `f64`s through `buffer`.
fn write_values<'v>(
    out: &mut impl Write,
    buffer: &mut Vec<u8>,
    values: impl IntoIterator<Item = &'v f64>,
) -> std::io::Result<()> {
    buffer.clear();
    buffer.extend(values.into_iter().flat_map(|x| x.to_le_bytes()));
    out.write_all(buffer)
}

/// Writes `count` fields whose columns `range` are `columns(range)` (each `n1` values, checked
/// against the header by the reader's size check).
///
/// The next chunk of fields is formed on another thread while this one is written, so forming
/// (parallel) and writing (one thread) overlap; the channel holds no chunk of its own, so at
/// most two chunks exist at a time.
fn write_streamed_fields(
    out: &mut impl Write,
    buffer: &mut Vec<u8>,
    count: usize,
    columns: &(dyn Fn(Range<usize>) -> Vec<Vec<f64>> + Sync),
) -> std::io::Result<()> {
    std::thread::scope(|scope| {
        let (sender, receiver) = std::sync::mpsc::sync_channel::<Vec<Vec<f64>>>(0);
        scope.spawn(move || {
            for start in (0..count).step_by(FIELD_CHUNK) {
                let chunk = columns(start..(start + FIELD_CHUNK).min(count));
                // A closed channel means the writer failed and stopped.
                if sender.send(chunk).is_err() {
                    break;
                }
            }
        });
        for chunk in &receiver {
            for column in chunk {
                write_values(out, buffer, &column)?;
            }
        }
        Ok(())
    })
}

/// Loads a basis with dense fields and checks that it belongs to `expected`: its mesh, its
/// discretization and, for a file of format version 3, its matrix hash
/// ([`BasisFileError::WrongMatrices`]; a file of versions 1 and 2 carries none and is accepted
/// on id and mesh). The eigenfunctions of an eigenfunctions file are turned into fields through
/// `complex` (the complex `expected` was made from) a chunk at a time while the file is read, so
/// they are never all in memory next to the fields (the co-integrable ones all at once where
/// the co-gradient has mass solves, as the basis formed them).
pub fn load_basis<H: HodgeComplex + ?Sized>(
    path: &Path,
    expected: &BasisFileKey,
    complex: &H,
) -> Result<SpectralBasis, BasisFileError> {
    let file = std::fs::File::open(path).map_err(io(path))?;
    load_basis_from_file(file, path, expected, complex)
}

/// [`load_basis`] from a file already opened (`path` names it in errors): the basis cache opens
/// its files without following links.
pub fn load_basis_from_file<H: HodgeComplex + ?Sized>(
    file: std::fs::File,
    path: &Path,
    expected: &BasisFileKey,
    complex: &H,
) -> Result<SpectralBasis, BasisFileError> {
    let (d0, co_gradient) = (complex.d0(), complex.co_gradient());
    let forming = FieldForming {
        potential_dimension: complex.potential_dimension(),
        co_potential_dimension: complex.co_potential_dimension(),
        field_mass: complex.m1(),
        d0,
        co_gradient,
    };
    match read_basis(file, path, Some(expected), Some(&forming))? {
        (_, StoredBasis::Fields(basis)) => Ok(*basis),
        // Not returned when forming is given.
        (_, StoredBasis::Eigenfunctions(_)) => Err(BasisFileError::Invalid {
            path: path.to_path_buf(),
            reason: "the eigenfunctions were not turned into fields".into(),
        }),
    }
}

/// What turns the stored eigenfunctions into fields while a file is read: the complex's
/// potential and co-potential dimensions, `M1`, its gradient `d0` and co-gradient `−M1⁻¹ d1ᵀ`.
struct FieldForming<'a> {
    potential_dimension: usize,
    co_potential_dimension: usize,
    field_mass: &'a Mass,
    d0: &'a sprs::CsMat<f64>,
    co_gradient: &'a LinearOperator,
}

/// Loads a basis in the form the file holds it, without checking what it belongs to (integrity
/// is still checked); returns its header too.
pub fn read_basis_file(path: &Path) -> Result<(BasisFileHeader, StoredBasis), BasisFileError> {
    let file = std::fs::File::open(path).map_err(io(path))?;
    read_basis(file, path, None, None)
}

/// Reads only the header of a basis file (checked against its checksum).
pub fn read_basis_header(path: &Path) -> Result<BasisFileHeader, BasisFileError> {
    let file = std::fs::File::open(path).map_err(io(path))?;
    read_basis_header_from(&file, path)
}

/// [`read_basis_header`] from a file already opened (`path` names it in errors), read from its
/// start.
pub fn read_basis_header_from(
    file: &std::fs::File,
    path: &Path,
) -> Result<BasisFileHeader, BasisFileError> {
    use std::io::Seek;
    let mut reader = std::io::BufReader::new(file);
    reader.rewind().map_err(io(path))?;
    read_header(path, &mut reader).map(|(header, _)| header)
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> BasisFileError + '_ {
    move |source| BasisFileError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Reads a basis file (checked against `expected` if given); with `forming`, an eigenfunctions
/// file is returned as dense fields.
fn read_basis(
    mut file: std::fs::File,
    path: &Path,
    expected: Option<&BasisFileKey>,
    forming: Option<&FieldForming<'_>>,
) -> Result<(BasisFileHeader, StoredBasis), BasisFileError> {
    std::io::Seek::rewind(&mut file).map_err(io(path))?;
    let size = file.metadata().map_err(io(path))?.len();
    let mut reader = std::io::BufReader::with_capacity(1 << 20, file);
    let (header, header_length) = read_header(path, &mut reader)?;
    if let Some(key) = expected {
        key.check_file(path, &header.key)?;
    }
    check_file_size(path, &header, header_length, size)?;
    if let Some(forming) = forming {
        check_forming_dimensions(path, &header, forming)?;
    }
    let mut input = HashingReader {
        inner: reader,
        hash: Hash64::new(),
    };
    let d = header.field_count;
    let eigenvalues = input.f64s(d).map_err(io(path))?;
    let mut codes = vec![0u8; d.div_ceil(8) * 8];
    input.read_exact(&mut codes).map_err(io(path))?;
    let body = read_body(&mut input, &header, &codes[..d], forming).map_err(io(path))?;
    let computed = input.hash.finish();
    let mut stored = [0u8; 8];
    input.inner.read_exact(&mut stored).map_err(io(path))?;
    if u64::from_le_bytes(stored) != computed {
        return Err(BasisFileError::Checksum {
            path: path.to_path_buf(),
            part: "payload",
        });
    }
    let families = families_of(&codes[..d], &header).map_err(|r| invalid(path, r))?;
    let stored =
        stored_basis(&header, eigenvalues, families, body).map_err(|r| invalid(path, r))?;
    Ok((header, stored))
}

/// An inconsistent basis file `path`, for `reason`.
fn invalid(path: &Path, reason: String) -> BasisFileError {
    BasisFileError::Invalid {
        path: path.to_path_buf(),
        reason,
    }
}

/// Checks that the file's `size` is what `header` (of `header_length` bytes) promises.
pub(crate) fn check_file_size(
    path: &Path,
    header: &BasisFileHeader,
    header_length: u64,
    size: u64,
) -> Result<(), BasisFileError> {
    let promised = header
        .payload_bytes()
        .and_then(|payload| payload.checked_add(header_length))
        .ok_or_else(|| invalid(path, "sizes overflow".into()))?;
    if size < promised {
        return Err(BasisFileError::Truncated {
            path: path.to_path_buf(),
            expected: promised,
            found: size,
        });
    }
    if size > promised {
        return Err(invalid(
            path,
            format!("{} bytes of trailing data", size - promised),
        ));
    }
    Ok(())
}

/// Checks that the potentials and co-potentials of an eigenfunctions file have the dimensions
/// of the complex that is to form its fields.
fn check_forming_dimensions(
    path: &Path,
    header: &BasisFileHeader,
    forming: &FieldForming<'_>,
) -> Result<(), BasisFileError> {
    if let BasisFileLayout::Eigenfunctions {
        potential_dimension,
        co_potential_dimension,
    } = header.layout
    {
        if (potential_dimension, co_potential_dimension)
            != (forming.potential_dimension, forming.co_potential_dimension)
        {
            return Err(invalid(
                path,
                format!(
                    "the file holds potentials of {potential_dimension} and co-potentials of \
                     {co_potential_dimension} values, the complex's have {} and {}",
                    forming.potential_dimension, forming.co_potential_dimension
                ),
            ));
        }
    }
    Ok(())
}

/// The layout-specific part of the payload (after the eigenvalues and the family `codes`),
/// with `forming` an eigenfunctions file's fields formed as they are read.
fn read_body<R: Read>(
    input: &mut HashingReader<R>,
    header: &BasisFileHeader,
    codes: &[u8],
    forming: Option<&FieldForming<'_>>,
) -> std::io::Result<Body> {
    let (n, d) = (header.key.field_dimension, header.field_count);
    Ok(match (header.layout, forming) {
        (BasisFileLayout::Fields, _) => {
            let field_mass = FieldMassRead::read(input, header.field_mass, n)?;
            let fields = input.matrix(n, d)?;
            Body::Fields { field_mass, fields }
        }
        (
            BasisFileLayout::Eigenfunctions {
                potential_dimension,
                co_potential_dimension,
            },
            None,
        ) => Body::Eigenfunctions {
            potentials: input.matrix(potential_dimension, header.integrable_count)?,
            co_potentials: input.matrix(co_potential_dimension, header.cointegrable_count)?,
            harmonic: input.matrix(n, header.harmonic_count)?,
        },
        (BasisFileLayout::Eigenfunctions { .. }, Some(forming)) => Body::Fields {
            field_mass: Some(FieldMassRead::Complex(forming.field_mass.clone())),
            fields: input.formed_fields(header, codes, forming)?,
        },
    })
}

/// The families of the family `codes`, whose counts must be the header's.
fn families_of(codes: &[u8], header: &BasisFileHeader) -> Result<Vec<FieldFamily>, String> {
    let families = codes
        .iter()
        .map(|&c| match c {
            0 => Ok(FieldFamily::Harmonic),
            1 => Ok(FieldFamily::Integrable),
            2 => Ok(FieldFamily::Cointegrable),
            other => Err(format!("unknown family code {other}")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let count = |family| families.iter().filter(|&&f| f == family).count();
    if count(FieldFamily::Harmonic) != header.harmonic_count
        || count(FieldFamily::Integrable) != header.integrable_count
    {
        return Err("family counts differ from the header".into());
    }
    Ok(families)
}

/// The basis of a read payload: its values finite, a stored `M1` the one the header's matrix
/// hash names.
fn stored_basis(
    header: &BasisFileHeader,
    eigenvalues: Vec<f64>,
    families: Vec<FieldFamily>,
    body: Body,
) -> Result<StoredBasis, String> {
    if let Some(problem) = body.non_finite() {
        return Err(problem);
    }
    match body {
        Body::Fields { field_mass, fields } => {
            let field_mass = field_mass
                .ok_or_else(|| "the fields layout holds no field mass".to_string())?
                .into_mass()?;
            let hash = header.key.matrix_hash.map(|h| h.m1);
            if hash.is_some_and(|m1| MatrixHash::of_mass(&field_mass) != m1) {
                return Err("the stored M1 is not the one the header's matrix hash names".into());
            }
            SpectralBasis::new(eigenvalues, families, fields, field_mass)
                .map(|basis| StoredBasis::Fields(Box::new(basis)))
        }
        Body::Eigenfunctions {
            potentials,
            co_potentials,
            harmonic,
        } => EigenfunctionBasis::from_columns(
            eigenvalues,
            families,
            potentials,
            co_potentials,
            harmonic,
        )
        .map(|basis| StoredBasis::Eigenfunctions(Box::new(basis))),
    }
    .map_err(|e| e.to_string())
}

/// The layout-specific part of a basis file, as read.
enum Body {
    Fields {
        /// `None` only for a fields file whose header says it stores no mass.
        field_mass: Option<FieldMassRead>,
        fields: Mat<f64>,
    },
    Eigenfunctions {
        potentials: Mat<f64>,
        co_potentials: Mat<f64>,
        harmonic: Mat<f64>,
    },
}

impl Body {
    /// Where the first non-finite value is, if there is one.
    fn non_finite(&self) -> Option<String> {
        let first_in = |what: &str, matrix: &Mat<f64>| {
            (0..matrix.ncols()).find_map(|j| {
                let column = matrix.col(j);
                column.iter().position(|value| !value.is_finite()).map(|i| {
                    format!(
                        "{what} {j} has the non-finite value {} at row {i}",
                        column[i]
                    )
                })
            })
        };
        match self {
            Body::Fields { fields, .. } => first_in("field", fields),
            Body::Eigenfunctions {
                potentials,
                co_potentials,
                harmonic,
            } => first_in("potential", potentials)
                .or_else(|| first_in("co-potential", co_potentials))
                .or_else(|| first_in("harmonic field", harmonic)),
        }
    }
}

/// Writes through to `inner`, hashing what it writes.
struct HashingWriter<'a> {
    inner: &'a mut dyn Write,
    hash: Hash64,
}

impl Write for HashingWriter<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let written = self.inner.write(buf)?;
        self.hash.update(&buf[..written]);
        Ok(written)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

struct HashingReader<R> {
    inner: R,
    hash: Hash64,
}

impl<R: Read> Read for HashingReader<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let read = self.inner.read(buf)?;
        self.hash.update(&buf[..read]);
        Ok(read)
    }
}

impl<R: Read> HashingReader<R> {
    fn f64s(&mut self, count: usize) -> std::io::Result<Vec<f64>> {
        let mut bytes = vec![0u8; 8 * count];
        self.read_exact(&mut bytes)?;
        Ok(bytes
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
            .collect())
    }

    /// The dense fields (`n1 × d`) of the eigenfunctions that follow in an eigenfunctions file
    /// with `header` and family `codes`, formed by `forming` a chunk of columns at a time (in
    /// parallel). Columns whose family codes are inconsistent with the header are left zero;
    /// the caller rejects such a file once its checksum is checked.
    fn formed_fields(
        &mut self,
        header: &BasisFileHeader,
        codes: &[u8],
        forming: &FieldForming<'_>,
    ) -> std::io::Result<Mat<f64>> {
        use rayon::prelude::*;
        let n1 = header.key.field_dimension;
        let mut fields = Mat::<f64>::zeros(n1, header.field_count);
        for (family, rows, count) in [
            (
                FieldFamily::Integrable,
                forming.potential_dimension,
                header.integrable_count,
            ),
            (
                FieldFamily::Cointegrable,
                forming.co_potential_dimension,
                header.cointegrable_count,
            ),
            (FieldFamily::Harmonic, n1, header.harmonic_count),
        ] {
            // The basis positions of the family's fields, in the order they are stored.
            let targets: Vec<usize> = (0..codes.len())
                .filter(|&i| codes[i] == family_code(family))
                .collect();
            if family == FieldFamily::Cointegrable && !forming.co_gradient.is_sparse() {
                // A co-gradient with mass solves forms all co-exact fields by one block solve,
                // as `EigenfunctionBasis::dense_fields` does, so the fields are the basis's bit
                // for bit (column by column they differ in round-off).
                let co_potentials = self.matrix(rows, count)?;
                let co_exact = forming.co_gradient.apply_block(co_potentials.as_ref());
                for (k, &target) in targets.iter().enumerate().take(co_exact.ncols()) {
                    fields.col_mut(target).copy_from(co_exact.col(k));
                }
                continue;
            }
            // Column of the chunk each basis field comes from, if it is in the chunk.
            let mut source = vec![None; header.field_count];
            let mut buffer = Mat::<f64>::zeros(rows, FIELD_CHUNK.min(count));
            for start in (0..count).step_by(FIELD_CHUNK) {
                let mut chunk = buffer
                    .as_mut()
                    .subcols_mut(0, FIELD_CHUNK.min(count - start));
                self.read_columns(chunk.rb_mut())?;
                let chunk = chunk.into_const();
                source.fill(None);
                for j in 0..chunk.ncols() {
                    if let Some(&target) = targets.get(start + j) {
                        source[target] = Some(j);
                    }
                }
                fields
                    .par_col_iter_mut()
                    .zip(&source)
                    .for_each(|(field, source)| {
                        let stored = source
                            .and_then(|j| chunk.col(j).try_as_col_major().map(|c| c.as_slice()));
                        let field = field.try_as_col_major_mut().map(|c| c.as_slice_mut());
                        if let (Some(stored), Some(field)) = (stored, field) {
                            field_of_stored_into(
                                forming.d0,
                                forming.co_gradient,
                                family,
                                stored,
                                field,
                            );
                        }
                    });
            }
        }
        Ok(fields)
    }

    /// A `rows × columns` matrix stored column by column.
    fn matrix(&mut self, rows: usize, columns: usize) -> std::io::Result<Mat<f64>> {
        let mut matrix = Mat::<f64>::zeros(rows, columns);
        self.read_columns(matrix.as_mut())?;
        Ok(matrix)
    }

    /// Reads the columns of `matrix`, stored one after the other.
    fn read_columns(&mut self, mut matrix: MatMut<'_, f64>) -> std::io::Result<()> {
        let mut bytes = vec![0u8; 8 * matrix.nrows()];
        for j in 0..matrix.ncols() {
            self.read_exact(&mut bytes)?;
            for (value, chunk) in matrix
                .rb_mut()
                .col_mut(j)
                .iter_mut()
                .zip(bytes.chunks_exact(8))
            {
                *value = f64::from_le_bytes(chunk.try_into().unwrap_or([0; 8]));
            }
        }
        Ok(())
    }
}
