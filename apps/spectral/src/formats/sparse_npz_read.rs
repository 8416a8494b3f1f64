//! Reading scipy's sparse `.npz` (`scipy.sparse.save_npz`: CSR, CSC or COO, stored or
//! deflate-compressed) and integer `.npy` arrays (`vertex_map.npy`), with every size an array
//! declares checked before it is allocated or inflated. Errors say what is wrong; callers add
//! the file name.
//!
//! The `.npy` headers are parsed by the `npyz` crate (after the header length is bounded by
//! [`crate::NpyArray::data_start`]), the archive is opened with `zip`. A member's declared
//! length is never trusted: each array's header is read first, its shape checked against the
//! matrix's (and the matrix's against [`MatrixLimits`]), and then exactly the bytes its shape
//! needs are inflated, counted against an [`InflationBudget`] that the files of one complex
//! folder share (so a small archive cannot inflate to gigabytes, member after member).

use super::npy::NpyArray;
use super::sparse_file_read::{MatrixLimits, SparseMatrix};
use npyz::{DType, Deserialize, NpyFile, NpyHeader, TypeChar};
use sprs::{CsMat, TriMat};
use std::cell::Cell;
use std::io::{Read, Seek};

/// Bytes the `.npz` members read together (one complex folder's) may inflate to: 4 GiB, the
/// arrays of sparse matrices with about 170 million entries in all.
pub const NPZ_INFLATED_LIMIT: u64 = 4 << 30;

/// Longest string `format.npy` may hold (scipy writes `csr`, `csc` or `coo`).
const MAX_FORMAT_CHARACTERS: u64 = 16;

/// What is left of the bytes `.npz` members may still inflate to; shared by the files of one
/// folder ([`NPZ_INFLATED_LIMIT`] for a folder).
#[derive(Debug)]
pub struct InflationBudget(Cell<u64>);

impl InflationBudget {
    /// A budget of `bytes`.
    pub fn new(bytes: u64) -> Self {
        Self(Cell::new(bytes))
    }

    /// Takes `bytes` for the array `what`, or says that the budget is spent.
    fn take(&self, bytes: u64, what: &str) -> Result<(), String> {
        let left = self.0.get();
        if bytes > left {
            return Err(format!(
                "{what}: {bytes} more bytes to inflate, beyond the {} GiB that the .npz files \
                 of one folder may hold in all; not read",
                NPZ_INFLATED_LIMIT >> 30
            ));
        }
        self.0.set(left - bytes);
        Ok(())
    }
}

/// Reads a sparse matrix saved by `scipy.sparse.save_npz` (members `format`, `shape`, `data`
/// and `indices`, `indptr` for CSR/CSC or `row`, `col` for COO; integer indices of any width;
/// unsorted and repeated indices allowed, repeated entries summed), with no bound on its shape
/// and at most [`NPZ_INFLATED_LIMIT`] bytes inflated.
pub fn read_sparse_npz(reader: impl Read + Seek) -> Result<SparseMatrix, String> {
    let budget = InflationBudget::new(NPZ_INFLATED_LIMIT);
    read_sparse_npz_within(reader, &MatrixLimits::default(), &budget)
}

/// [`read_sparse_npz`] with the shape checked against `limits` and the inflated bytes counted
/// against `budget`, each before anything of that size is allocated. Every array must be
/// one-dimensional (a two-dimensional `data.npy`, in Fortran order or not, is not a matrix
/// scipy wrote).
pub fn read_sparse_npz_within(
    reader: impl Read + Seek,
    limits: &MatrixLimits<'_>,
    budget: &InflationBudget,
) -> Result<SparseMatrix, String> {
    let zip =
        zip::ZipArchive::new(reader).map_err(|e| format!("not an .npz (zip) archive: {e}"))?;
    let mut archive = Archive { zip, budget };
    let format = archive.format()?;
    let shape = archive.integers("shape", Some(2))?;
    let [rows, cols] = shape[..] else {
        return Err(format!("shape.npy holds {shape:?}, not (rows, cols)"));
    };
    if let Some(problem) = limits.shape_problem(rows, cols) {
        return Err(format!("shape.npy: {problem}"));
    }
    let entries = archive.length("data")?;
    if entries as u128 > rows as u128 * cols as u128 {
        return Err(format!(
            "data.npy holds {entries} entries, more than a {rows} x {cols} matrix has"
        ));
    }
    match format.as_str() {
        "csr" | "csc" => {
            let (outer, inner) = if format == "csr" {
                (rows, cols)
            } else {
                (cols, rows)
            };
            let per_value = format!("data.npy has {entries} (one per value)");
            archive.expect_length("indices", entries, &per_value)?;
            let pointers = outer.checked_add(1).ok_or("shape overflows")?;
            let per_line = match format.as_str() {
                "csr" => format!("a matrix of {outer} rows needs {pointers} (rows + 1)"),
                _ => format!("a matrix of {outer} columns needs {pointers} (columns + 1)"),
            };
            archive.expect_length("indptr", pointers, &per_line)?;
            let data = archive.floats()?;
            let indptr = archive.integers("indptr", Some(pointers))?;
            let indices = archive.integers("indices", Some(entries))?;
            check_compressed(&indptr, &indices, entries, inner)?;
            let (indptr, indices, data) = sorted_and_summed(&indptr, &indices, &data);
            let built = if format == "csr" {
                CsMat::try_new((rows, cols), indptr, indices, data)
            } else {
                CsMat::try_new_csc((rows, cols), indptr, indices, data)
            };
            let matrix = built.map_err(|(_, _, _, e)| format!("not a sparse matrix: {e}"))?;
            Ok(matrix.to_csr())
        }
        "coo" => {
            let per_value = format!("data.npy has {entries} (one per value)");
            archive.expect_length("row", entries, &per_value)?;
            archive.expect_length("col", entries, &per_value)?;
            let data = archive.floats()?;
            let row = archive.integers("row", Some(entries))?;
            let col = archive.integers("col", Some(entries))?;
            let mut triplets = TriMat::with_capacity((rows, cols), entries);
            for ((&i, &j), &value) in row.iter().zip(&col).zip(&data) {
                if i >= rows || j >= cols {
                    return Err(format!(
                        "entry ({i}, {j}) is outside the shape {rows} x {cols}"
                    ));
                }
                triplets.add_triplet(i, j, value);
            }
            Ok(triplets.to_csr())
        }
        other => Err(format!(
            "format.npy says '{other}': only csr, csc and coo matrices are read"
        )),
    }
}

/// An `.npz` archive whose members are read against a budget.
struct Archive<'b, R: Read + Seek> {
    zip: zip::ZipArchive<R>,
    budget: &'b InflationBudget,
}

impl<R: Read + Seek> Archive<'_, R> {
    /// The header of the member `NAME.npy` and the member, positioned at its data.
    fn open(&mut self, name: &str) -> Result<(NpyHeader, zip::read::ZipFile<'_, R>), String> {
        let budget = self.budget;
        let mut file = self
            .zip
            .by_name(&format!("{name}.npy"))
            .map_err(|e| match e {
                zip::result::ZipError::FileNotFound => {
                    format!("no member {name}.npy: not a sparse matrix of scipy.sparse.save_npz")
                }
                other => format!("{name}.npy: {other}"),
            })?;
        let header = read_npy_header(&mut file, name, budget)?;
        Ok((header, file))
    }

    /// The length of the one-dimensional array `name` (only its header is read).
    fn length(&mut self, name: &str) -> Result<usize, String> {
        let (header, _) = self.open(name)?;
        one_dimensional(&header, name)
    }

    /// Refuses the array `name` unless it has `expected` entries (`why` says where that
    /// number comes from), reading only its header.
    fn expect_length(&mut self, name: &str, expected: usize, why: &str) -> Result<(), String> {
        let found = self.length(name)?;
        if found != expected {
            return Err(format!("{name}.npy has {found} entries, but {why}"));
        }
        Ok(())
    }

    /// `format.npy`: a byte string (`scipy.sparse.save_npz`) or a unicode one (`numpy.savez`
    /// of a Python `str`), of at most [`MAX_FORMAT_CHARACTERS`].
    fn format(&mut self) -> Result<String, String> {
        let budget = self.budget;
        let (header, file) = self.open("format")?;
        let DType::Plain(ty) = header.dtype() else {
            return Err("format.npy: not a string".into());
        };
        let width = ty.size_field();
        let bytes_per_character = match ty.type_char() {
            TypeChar::ByteStr => 1,
            TypeChar::UnicodeStr => 4,
            _ => {
                return Err(format!(
                    "format.npy has dtype {ty}: a string such as 'csr' expected"
                ))
            }
        };
        if header.len() != 1 || width > MAX_FORMAT_CHARACTERS {
            return Err(format!(
                "format.npy holds {} strings of {width} characters: one such as 'csr' expected",
                header.len()
            ));
        }
        let length = width * bytes_per_character;
        budget.take(length, "format.npy")?;
        let mut raw = Vec::new();
        file.take(length)
            .read_to_end(&mut raw)
            .map_err(|e| format!("format.npy: {e}"))?;
        if raw.len() as u64 != length {
            return Err("format.npy: truncated".into());
        }
        let text: String = match bytes_per_character {
            1 => raw.iter().map(|&b| char::from(b)).collect(),
            _ => raw
                .chunks_exact(4)
                .map(|c| {
                    let code = match ty.endianness() {
                        npyz::Endianness::Big => u32::from_be_bytes([c[0], c[1], c[2], c[3]]),
                        _ => u32::from_le_bytes([c[0], c[1], c[2], c[3]]),
                    };
                    char::from_u32(code).unwrap_or(char::REPLACEMENT_CHARACTER)
                })
                .collect(),
        };
        Ok(text.trim_end_matches('\0').to_string())
    }

    /// `data.npy`: float64 or float32 values, as `f64`.
    fn floats(&mut self) -> Result<Vec<f64>, String> {
        let budget = self.budget;
        let (header, file) = self.open("data")?;
        let count = one_dimensional(&header, "data")?;
        let DType::Plain(ty) = header.dtype() else {
            return Err("data.npy: not an array of numbers".into());
        };
        match (ty.type_char(), ty.size_field()) {
            (TypeChar::Float, 8) => values::<f64>(header, file, count, 8, "data", budget),
            (TypeChar::Float, 4) => Ok(values::<f32>(header, file, count, 4, "data", budget)?
                .into_iter()
                .map(f64::from)
                .collect()),
            _ => Err(format!(
                "data.npy has dtype {ty}: only float64 or float32 values are read"
            )),
        }
    }

    /// The one-dimensional integer array `name` (of `expected` entries, if given), each entry
    /// checked non-negative.
    fn integers(&mut self, name: &str, expected: Option<usize>) -> Result<Vec<usize>, String> {
        let budget = self.budget;
        let (header, file) = self.open(name)?;
        let count = one_dimensional(&header, name)?;
        if let Some(expected) = expected.filter(|&e| e != count) {
            return Err(format!(
                "{name}.npy has {count} entries, {expected} expected"
            ));
        }
        integer_values(header, file, count, name, budget)
    }
}

/// Reads the header of an `.npy` stream (its length bounded before it is read), leaving the
/// stream at the data; the header's bytes are taken from `budget`.
fn read_npy_header(
    file: &mut impl Read,
    name: &str,
    budget: &InflationBudget,
) -> Result<NpyHeader, String> {
    let what = format!("{name}.npy");
    let mut head = Vec::new();
    let mut start = None;
    // The magic, version and header length (10 or 12 bytes), then the rest of the header.
    for prefix in [10u64, 12] {
        let more = prefix - head.len() as u64;
        file.by_ref()
            .take(more)
            .read_to_end(&mut head)
            .map_err(|e| format!("{what}: {e}"))?;
        start = NpyArray::data_start(&head).map_err(|e| format!("{what}: {e}"))?;
        if start.is_some() || (head.len() as u64) < prefix {
            break;
        }
    }
    let start = start.ok_or_else(|| format!("{what}: truncated .npy header"))?;
    budget.take(start as u64, &what)?;
    let rest = start as u64 - head.len() as u64;
    file.by_ref()
        .take(rest)
        .read_to_end(&mut head)
        .map_err(|e| format!("{what}: {e}"))?;
    if head.len() != start {
        return Err(format!("{what}: truncated .npy header"));
    }
    NpyHeader::from_reader(&head[..]).map_err(|e| format!("{what}: {e}"))
}

/// The length of a one-dimensional array; an error naming `name` for any other shape.
fn one_dimensional(header: &NpyHeader, name: &str) -> Result<usize, String> {
    match header.shape() {
        [n] => usize::try_from(*n).map_err(|_| format!("{name}.npy: {n} entries overflow")),
        shape => Err(format!(
            "{name}.npy has shape {shape:?}{}: a sparse matrix's arrays are one-dimensional",
            match header.order() {
                npyz::Order::Fortran => " in Fortran order",
                npyz::Order::C => "",
            }
        )),
    }
}

/// The `count` values of an array of `size`-byte elements whose header was read from `file`,
/// inflating exactly the bytes they take (taken from `budget` first).
fn values<T: Deserialize>(
    header: NpyHeader,
    file: impl Read,
    count: usize,
    size: u64,
    name: &str,
    budget: &InflationBudget,
) -> Result<Vec<T>, String> {
    let bytes = (count as u64)
        .checked_mul(size)
        .ok_or_else(|| format!("{name}.npy: its size overflows"))?;
    budget.take(bytes, &format!("{name}.npy"))?;
    let values = NpyFile::with_header(header, file.take(bytes))
        .into_vec::<T>()
        .map_err(|e| format!("{name}.npy: {e}"))?;
    if values.len() != count {
        return Err(format!(
            "{name}.npy: {} of its {count} entries present",
            values.len()
        ));
    }
    Ok(values)
}

/// The entries of an integer array (signed or unsigned, any width) as indices, each checked
/// non-negative.
fn integer_values(
    header: NpyHeader,
    file: impl Read,
    count: usize,
    name: &str,
    budget: &InflationBudget,
) -> Result<Vec<usize>, String> {
    let DType::Plain(ty) = header.dtype() else {
        return Err(format!("{name}.npy: not an array of integers"));
    };
    let size = ty.size_field();
    macro_rules! read_as {
        ($t:ty) => {
            indices(values::<$t>(header, file, count, size, name, budget)?, name)
        };
    }
    match (ty.type_char(), size) {
        (TypeChar::Int, 8) => read_as!(i64),
        (TypeChar::Int, 4) => read_as!(i32),
        (TypeChar::Int, 2) => read_as!(i16),
        (TypeChar::Int, 1) => read_as!(i8),
        (TypeChar::Uint, 8) => read_as!(u64),
        (TypeChar::Uint, 4) => read_as!(u32),
        (TypeChar::Uint, 2) => read_as!(u16),
        (TypeChar::Uint, 1) => read_as!(u8),
        _ => Err(format!("{name}.npy has dtype {ty}, not integers")),
    }
}

/// Integers as indices; an error naming the first that is negative or too large.
fn indices<T>(values: Vec<T>, name: &str) -> Result<Vec<usize>, String>
where
    T: Copy + TryInto<usize> + std::fmt::Display,
{
    values
        .into_iter()
        .enumerate()
        .map(|(k, v)| {
            v.try_into()
                .map_err(|_| format!("{name}.npy: entry {k} is {v}, not an index"))
        })
        .collect()
}

/// Checks compressed-storage arrays: pointers from 0 to `nnz`, non-decreasing, indices below
/// `inner` (the lengths were checked before they were read).
fn check_compressed(
    indptr: &[usize],
    indices: &[usize],
    nnz: usize,
    inner: usize,
) -> Result<(), String> {
    if indptr.first() != Some(&0) || indptr.last() != Some(&nnz) {
        return Err(format!(
            "indptr.npy runs from {:?} to {:?}: expected 0 to {nnz} (the entries of data.npy)",
            indptr.first(),
            indptr.last(),
        ));
    }
    if indptr.windows(2).any(|w| w[0] > w[1]) {
        return Err("indptr.npy is not non-decreasing".into());
    }
    if let Some(bad) = indices.iter().find(|&&k| k >= inner) {
        return Err(format!(
            "index {bad} in indices.npy is beyond the shape ({inner})"
        ));
    }
    Ok(())
}

/// Compressed-storage arrays (checked) with the indices of each row (column) sorted and
/// repeated ones summed, as sprs stores a matrix.
fn sorted_and_summed(
    indptr: &[usize],
    indices: &[usize],
    data: &[f64],
) -> (Vec<usize>, Vec<usize>, Vec<f64>) {
    let mut pointers = Vec::with_capacity(indptr.len());
    let mut sorted_indices = Vec::with_capacity(indices.len());
    let mut values = Vec::with_capacity(data.len());
    let mut line: Vec<(usize, f64)> = Vec::new();
    pointers.push(0);
    for range in indptr.windows(2) {
        line.clear();
        line.extend((range[0]..range[1]).map(|k| (indices[k], data[k])));
        line.sort_unstable_by_key(|&(index, _)| index);
        for &(index, value) in &line {
            match sorted_indices.last() {
                Some(&last) if last == index && values.len() > *pointers.last().unwrap_or(&0) => {
                    *values.last_mut().expect("a value per index") += value;
                }
                _ => {
                    sorted_indices.push(index);
                    values.push(value);
                }
            }
        }
        pointers.push(sorted_indices.len());
    }
    (pointers, sorted_indices, values)
}

/// Reads a one-dimensional integer `.npy` file (e.g. `vertex_map.npy`); with `expected`, one of
/// another length is refused before its entries are read.
pub fn read_index_npy_within(
    mut reader: impl Read,
    what: &str,
    expected: Option<usize>,
) -> Result<Vec<usize>, String> {
    let budget = InflationBudget::new(NPZ_INFLATED_LIMIT);
    let header = read_npy_header(&mut reader, what, &budget)
        .map_err(|e| format!("not an .npy array: {e}"))?;
    let count = match header.shape() {
        [n] => usize::try_from(*n).map_err(|_| format!("{what}: {n} entries overflow"))?,
        shape => {
            return Err(format!(
                "{what} has shape {shape:?}: one dimension expected"
            ))
        }
    };
    if let Some(expected) = expected.filter(|&e| e != count) {
        return Err(format!("{what} holds {count} entries, {expected} expected"));
    }
    integer_values(header, reader, count, what, &budget)
}

/// Reads an integer `.npy` file of one dimension (e.g. `vertex_map.npy`), of any length.
pub fn read_index_npy(reader: impl Read, what: &str) -> Result<Vec<usize>, String> {
    read_index_npy_within(reader, what, None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{npy_bytes, write_sparse_npz, NpyData};
    use std::io::{Cursor, Write};

    fn example() -> SparseMatrix {
        let mut t = TriMat::new((3, 4));
        t.add_triplet(0, 1, 2.5);
        t.add_triplet(2, 3, -1.0);
        t.add_triplet(1, 0, 1e-300);
        t.to_csr()
    }

    /// An archive of the given members (name, `.npy` bytes), deflated or stored.
    fn archive(members: &[(&str, Vec<u8>)], deflated: bool) -> Cursor<Vec<u8>> {
        let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
        let method = match deflated {
            true => zip::CompressionMethod::Deflated,
            false => zip::CompressionMethod::Stored,
        };
        let options = zip::write::SimpleFileOptions::default().compression_method(method);
        for (name, bytes) in members {
            zip.start_file(format!("{name}.npy"), options).unwrap();
            zip.write_all(bytes).unwrap();
        }
        let mut bytes = zip.finish().unwrap();
        bytes.set_position(0);
        bytes
    }

    /// An `.npy` file with the header `dict` and `data` as is (format 1.0).
    fn npy_raw(dict: &str, data: &[u8]) -> Vec<u8> {
        let mut header = dict.as_bytes().to_vec();
        while !(10 + header.len() + 1).is_multiple_of(64) {
            header.push(b' ');
        }
        header.push(b'\n');
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend(header);
        out.extend_from_slice(data);
        out
    }

    fn ints(values: &[i64]) -> Vec<u8> {
        npy_bytes(&NpyData::I64(values), &[values.len()])
    }

    fn floats(values: &[f64]) -> Vec<u8> {
        npy_bytes(&NpyData::F64(values), &[values.len()])
    }

    fn format(text: &str) -> Vec<u8> {
        npy_raw(
            &format!(
                "{{'descr': '|S{}', 'fortran_order': False, 'shape': (), }}",
                text.len()
            ),
            text.as_bytes(),
        )
    }

    /// The members of a CSR `rows × cols` matrix with the given arrays.
    fn csr(
        shape: [i64; 2],
        indptr: &[i64],
        indices: &[i64],
        data: &[f64],
    ) -> Vec<(&'static str, Vec<u8>)> {
        vec![
            ("format", format("csr")),
            ("shape", ints(&shape)),
            ("indptr", ints(indptr)),
            ("indices", ints(indices)),
            ("data", floats(data)),
        ]
    }

    #[test]
    fn tvf_files_read_back_exactly() {
        let matrix = example();
        let mut npz = Cursor::new(Vec::new());
        write_sparse_npz(&mut npz, &matrix).unwrap();
        npz.set_position(0);
        assert_eq!(read_sparse_npz(npz).unwrap(), matrix);
        let map = npy_bytes(&NpyData::I64(&[0, 2, 5]), &[3]);
        assert_eq!(
            read_index_npy(&map[..], "vertex_map").unwrap(),
            vec![0, 2, 5]
        );
        let message = read_index_npy_within(&map[..], "vertex_map", Some(4)).unwrap_err();
        assert!(message.contains("3 entries, 4 expected"), "{message}");
    }

    /// `scipy.sparse.save_npz` compresses by default: the same members, deflated; unsorted and
    /// repeated indices are summed; CSC and COO read as the same matrix.
    #[test]
    fn deflated_unsorted_and_other_layouts_read_alike() {
        let matrix = example();
        let members = csr([3, 4], &[0, 1, 2, 3], &[1, 0, 3], &[2.5, 1e-300, -1.0]);
        assert_eq!(read_sparse_npz(archive(&members, true)).unwrap(), matrix);
        let repeated = csr(
            [3, 4],
            &[0, 2, 3, 4],
            &[1, 1, 0, 3],
            &[2.0, 0.5, 1e-300, -1.0],
        );
        assert_eq!(read_sparse_npz(archive(&repeated, false)).unwrap(), matrix);
        let csc = vec![
            ("format", format("csc")),
            ("shape", ints(&[3, 4])),
            ("indptr", ints(&[0, 1, 2, 2, 3])),
            ("indices", ints(&[1, 0, 2])),
            ("data", floats(&[1e-300, 2.5, -1.0])),
        ];
        assert_eq!(read_sparse_npz(archive(&csc, true)).unwrap(), matrix);
        let coo = vec![
            ("format", format("coo")),
            ("shape", ints(&[3, 4])),
            ("row", ints(&[2, 0, 1])),
            ("col", ints(&[3, 1, 0])),
            ("data", floats(&[-1.0, 2.5, 1e-300])),
        ];
        assert_eq!(read_sparse_npz(archive(&coo, false)).unwrap(), matrix);
    }

    /// `numpy.savez(..., format='csr')` stores a unicode string (`<U3`), not scipy's bytes.
    #[test]
    fn a_unicode_format_string_is_read() {
        let mut members = csr([3, 4], &[0, 1, 2, 3], &[1, 0, 3], &[2.5, 1e-300, -1.0]);
        let utf32: Vec<u8> = "csr"
            .chars()
            .flat_map(|c| (c as u32).to_le_bytes())
            .collect();
        members[0].1 = npy_raw(
            "{'descr': '<U3', 'fortran_order': False, 'shape': (), }",
            &utf32,
        );
        assert_eq!(
            read_sparse_npz(archive(&members, false)).unwrap(),
            example()
        );
        members[0].1 = npy_raw(
            "{'descr': '<f8', 'fortran_order': False, 'shape': (), }",
            &[0; 8],
        );
        let message = read_sparse_npz(archive(&members, false)).unwrap_err();
        assert!(message.contains("a string such as 'csr'"), "{message}");
    }

    /// A two-dimensional member (in Fortran order it was once flattened in the wrong order,
    /// silently) is refused, naming the member and its order.
    #[test]
    fn members_that_are_not_one_dimensional_are_refused() {
        let values: Vec<u8> = [2.5f64, 1e-300, -1.0, 0.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        let mut members = csr([3, 4], &[0, 1, 2, 3], &[1, 0, 3], &[2.5, 1e-300, -1.0]);
        for (order, shown) in [("True", "in Fortran order"), ("False", "[2, 2]")] {
            let dict = format!("{{'descr': '<f8', 'fortran_order': {order}, 'shape': (2, 2), }}");
            members[4].1 = npy_raw(&dict, &values);
            let message = read_sparse_npz(archive(&members, false)).unwrap_err();
            assert!(
                message.starts_with("data.npy has shape [2, 2]"),
                "{message}"
            );
            assert!(message.contains(shown), "{message}");
        }
    }

    /// Shapes and entry counts are checked against the limits before anything of their size is
    /// allocated or inflated, and the inflated bytes of several archives share one budget.
    #[test]
    fn declared_sizes_are_refused_before_inflating() {
        let sizes = [("V", 4), ("F", 3)];
        let limits = MatrixLimits {
            sizes: &sizes,
            file_bytes: None,
        };
        let budget = InflationBudget::new(NPZ_INFLATED_LIMIT);
        let huge = csr([4_000_000_000, 4_000_000_000], &[0], &[], &[]);
        let message = read_sparse_npz_within(archive(&huge, true), &limits, &budget).unwrap_err();
        assert!(message.contains("V = 4, F = 3"), "{message}");
        // An indices member declaring 64 million entries (deflated: a small archive) next to
        // three data values: refused from its header.
        let zeros = vec![0u8; 64 << 20];
        let mut bomb = csr([3, 4], &[0, 1, 2, 3], &[], &[2.5, 1e-300, -1.0]);
        bomb[3].1 = npy_raw(
            "{'descr': '<i8', 'fortran_order': False, 'shape': (8388608,), }",
            &zeros,
        );
        let bytes = archive(&bomb, true);
        assert!(bytes.get_ref().len() < 1 << 20, "{}", bytes.get_ref().len());
        let message = read_sparse_npz_within(bytes, &limits, &budget).unwrap_err();
        assert!(
            message.contains("indices.npy has 8388608 entries"),
            "{message}"
        );
        // More entries than the dense matrix holds.
        let dense = csr([3, 4], &[0, 13, 13, 13], &[0; 13], &[1.0; 13]);
        let message = read_sparse_npz(archive(&dense, false)).unwrap_err();
        assert!(
            message.contains("more than a 3 x 4 matrix has"),
            "{message}"
        );
        // A budget spent by earlier members refuses the next one.
        let small = InflationBudget::new(2000);
        let good = csr([3, 4], &[0, 1, 2, 3], &[1, 0, 3], &[2.5, 1e-300, -1.0]);
        assert!(read_sparse_npz_within(archive(&good, true), &limits, &small).is_ok());
        let message = read_sparse_npz_within(archive(&good, true), &limits, &small).unwrap_err();
        assert!(message.contains("more bytes to inflate"), "{message}");
    }

    #[test]
    fn broken_arrays_are_named() {
        let past = csr([3, 4], &[0, 1, 2, 9], &[1, 0, 3], &[2.5, 1e-300, -1.0]);
        let message = read_sparse_npz(archive(&past, false)).unwrap_err();
        assert!(message.contains("indptr.npy runs from"), "{message}");
        let negative = csr([3, 4], &[0, 1, 2, 3], &[1, -1, 3], &[2.5, 1e-300, -1.0]);
        let message = read_sparse_npz(archive(&negative, false)).unwrap_err();
        assert!(message.contains("entry 1 is -1"), "{message}");
        let beyond = csr([3, 4], &[0, 1, 2, 3], &[1, 0, 4], &[2.5, 1e-300, -1.0]);
        let message = read_sparse_npz(archive(&beyond, false)).unwrap_err();
        assert!(message.contains("index 4 in indices.npy"), "{message}");
        let mut truncated = csr([3, 4], &[0, 1, 2, 3], &[1, 0, 3], &[2.5, 1e-300, -1.0]);
        let cut = truncated[4].1.len() - 4;
        truncated[4].1.truncate(cut);
        let message = read_sparse_npz(archive(&truncated, false)).unwrap_err();
        assert!(message.starts_with("data.npy"), "{message}");
        let message = read_sparse_npz(Cursor::new(b"not a zip".to_vec())).unwrap_err();
        assert!(message.contains("not an .npz"), "{message}");
    }
}
