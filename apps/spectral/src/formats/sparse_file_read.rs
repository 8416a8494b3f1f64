//! Reading the sparse matrices and integer arrays other tools write: Matrix Market coordinate
//! files (`.mtx`: MATLAB's `mmwrite`, Julia's `MatrixMarket`, `scipy.io.mmwrite`, `tvf
//! operators`), scipy's sparse `.npz` (`scipy.sparse.save_npz`: CSR, CSC or COO) and integer
//! `.npy` arrays. Every error says what is wrong (with the line of a `.mtx` file); callers add
//! the file name.
//!
//! The `.npy` members are parsed by the `npyz` crate; the `.npz` archive is opened with `zip`.
//! A Matrix Market file is parsed here because `sprs`'s reader panics on an index beyond the
//! declared shape and does not say which line is wrong.

use sprs::{CsMat, TriMat};
use std::io::{BufRead, Read, Seek};

/// A sparse matrix of a file, with the stored entries as given (duplicates summed).
pub type SparseMatrix = CsMat<f64>;

/// Reads a Matrix Market `coordinate` file of `real` or `integer` values, `general` or
/// `symmetric` (the lower triangle mirrored). Indices are 1-based in the file. Non-finite
/// values are read as they are (the caller checks them, naming the entry).
pub fn read_matrix_market(reader: impl BufRead) -> Result<SparseMatrix, String> {
    let mut lines = reader.lines().enumerate();
    let mut next_line = || -> Result<Option<(usize, String)>, String> {
        match lines.next() {
            Some((i, Ok(line))) => Ok(Some((i + 1, line))),
            Some((i, Err(e))) => Err(format!("line {}: {e}", i + 1)),
            None => Ok(None),
        }
    };
    let (_, header) = next_line()?.ok_or("empty file (no %%MatrixMarket header)")?;
    let words: Vec<String> = header
        .split_whitespace()
        .map(|w| w.to_lowercase())
        .collect();
    if words.len() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix" {
        return Err(format!(
            "line 1: not a Matrix Market matrix header ('%%MatrixMarket matrix coordinate real \
             general' expected): '{header}'"
        ));
    }
    if words[2] != "coordinate" || !["real", "integer", "double"].contains(&words[3].as_str()) {
        return Err(format!(
            "line 1: only sparse 'coordinate' files of 'real' or 'integer' values are read, \
             not '{} {}'",
            words[2], words[3]
        ));
    }
    let symmetric = match words[4].as_str() {
        "general" => false,
        "symmetric" => true,
        other => {
            return Err(format!(
                "line 1: '{other}' matrices are not read (general or symmetric)"
            ))
        }
    };
    let (size_line, size) = loop {
        match next_line()? {
            Some((_, l)) if l.trim().is_empty() || l.trim_start().starts_with('%') => continue,
            Some(found) => break found,
            None => return Err("the file ends before the size line 'rows cols entries'".into()),
        }
    };
    let numbers: Vec<usize> = size
        .split_whitespace()
        .map(|w| w.parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("line {size_line}: not a size line 'rows cols entries': '{size}'"))?;
    let [rows, cols, entries] = numbers[..] else {
        return Err(format!(
            "line {size_line}: not a size line 'rows cols entries': '{size}'"
        ));
    };
    let mut triplets = TriMat::with_capacity((rows, cols), entries);
    let mut read = 0;
    while read < entries {
        let Some((number, line)) = next_line()? else {
            return Err(format!(
                "the file ends after {read} of the {entries} entries the size line promises"
            ));
        };
        if line.trim().is_empty() || line.trim_start().starts_with('%') {
            continue;
        }
        let (i, j, value) = entry(&line, rows, cols).map_err(|e| format!("line {number}: {e}"))?;
        triplets.add_triplet(i, j, value);
        if symmetric && i != j {
            triplets.add_triplet(j, i, value);
        }
        read += 1;
    }
    while let Some((number, line)) = next_line()? {
        if !line.trim().is_empty() && !line.trim_start().starts_with('%') {
            return Err(format!(
                "line {number}: more entries than the {entries} the size line promises"
            ));
        }
    }
    Ok(triplets.to_csr())
}

/// One entry line `i j value` (1-based), checked against the shape; returns 0-based indices.
fn entry(line: &str, rows: usize, cols: usize) -> Result<(usize, usize, f64), String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let [i, j, value] = words[..] else {
        return Err(format!("not an entry 'row col value': '{line}'"));
    };
    let index = |word: &str, limit: usize, what: &str| -> Result<usize, String> {
        match word.parse::<usize>() {
            Ok(k) if (1..=limit).contains(&k) => Ok(k - 1),
            _ => Err(format!(
                "{what} index '{word}' is not in 1..={limit} (1-based, the shape's {what}s)"
            )),
        }
    };
    let value = value
        .parse::<f64>()
        .map_err(|_| format!("'{value}' is not a number"))?;
    Ok((index(i, rows, "row")?, index(j, cols, "column")?, value))
}

/// The largest uncompressed member of an `.npz` the reader takes: 4 GiB, the arrays of a sparse
/// matrix with about 170 million entries.
pub const NPZ_MEMBER_LIMIT: u64 = 4 << 30;

/// Reads a sparse matrix saved by `scipy.sparse.save_npz` (stored or deflate-compressed: numpy's
/// default is compressed; members `format`, `shape`, `data`
/// and `indices`, `indptr` for CSR/CSC or `row`, `col` for COO; integer indices of any width;
/// unsorted and repeated indices are allowed, repeated entries summed).
pub fn read_sparse_npz(reader: impl Read + Seek) -> Result<SparseMatrix, String> {
    let mut archive =
        zip::ZipArchive::new(reader).map_err(|e| format!("not an .npz (zip) archive: {e}"))?;
    let mut member = |name: &str| -> Result<npyz::NpyFile<std::io::Cursor<Vec<u8>>>, String> {
        let file = archive
            .by_name(&format!("{name}.npy"))
            .map_err(|e| match e {
                zip::result::ZipError::FileNotFound => {
                    format!("no member {name}.npy: not a sparse matrix of scipy.sparse.save_npz")
                }
                other => format!("{name}.npy: {other}"),
            })?;
        // A member's stated size can lie (a compressed member may inflate without end): read
        // at most the cap, and refuse a member that reaches it.
        let mut bytes = Vec::new();
        file.take(NPZ_MEMBER_LIMIT)
            .read_to_end(&mut bytes)
            .map_err(|e| format!("{name}.npy: {e}"))?;
        if bytes.len() as u64 >= NPZ_MEMBER_LIMIT {
            return Err(format!(
                "{name}.npy: more than {} GiB uncompressed; not read",
                NPZ_MEMBER_LIMIT >> 30
            ));
        }
        npyz::NpyFile::new(std::io::Cursor::new(bytes)).map_err(|e| format!("{name}.npy: {e}"))
    };
    let format = member("format")?
        .into_vec::<Vec<u8>>()
        .map_err(|e| format!("format.npy: {e}"))?
        .concat();
    let shape = integers(member("shape")?, "shape")?;
    let [rows, cols] = shape[..] else {
        return Err(format!("shape.npy holds {shape:?}, not (rows, cols)"));
    };
    let data = floats(member("data")?)?;
    let format = String::from_utf8_lossy(&format).to_string();
    match format.as_str() {
        "csr" | "csc" => {
            let indptr = integers(member("indptr")?, "indptr")?;
            let indices = integers(member("indices")?, "indices")?;
            let (outer, inner) = if format == "csr" {
                (rows, cols)
            } else {
                (cols, rows)
            };
            check_compressed(&indptr, &indices, data.len(), outer, inner)?;
            let mut triplets = TriMat::with_capacity((rows, cols), data.len());
            for (k, range) in indptr.windows(2).enumerate() {
                for entry in range[0]..range[1] {
                    let (i, j) = if format == "csr" {
                        (k, indices[entry])
                    } else {
                        (indices[entry], k)
                    };
                    triplets.add_triplet(i, j, data[entry]);
                }
            }
            Ok(triplets.to_csr())
        }
        "coo" => {
            let (row, col) = (
                integers(member("row")?, "row")?,
                integers(member("col")?, "col")?,
            );
            if row.len() != data.len() || col.len() != data.len() {
                return Err(format!(
                    "row.npy, col.npy and data.npy have {}, {} and {} entries",
                    row.len(),
                    col.len(),
                    data.len()
                ));
            }
            let mut triplets = TriMat::with_capacity((rows, cols), data.len());
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

/// Checks compressed-storage arrays: `outer + 1` pointers from 0 to `nnz`, non-decreasing,
/// indices below `inner`.
fn check_compressed(
    indptr: &[usize],
    indices: &[usize],
    nnz: usize,
    outer: usize,
    inner: usize,
) -> Result<(), String> {
    if indptr.len() != outer + 1 || indptr.first() != Some(&0) || indptr.last() != Some(&nnz) {
        return Err(format!(
            "indptr.npy has {} entries from {:?} to {:?}: expected {} from 0 to {nnz} (the \
             entries of data.npy)",
            indptr.len(),
            indptr.first(),
            indptr.last(),
            outer + 1
        ));
    }
    if indptr.windows(2).any(|w| w[0] > w[1]) {
        return Err("indptr.npy is not non-decreasing".into());
    }
    if indices.len() != nnz {
        return Err(format!(
            "indices.npy has {} entries, data.npy {nnz}",
            indices.len()
        ));
    }
    if let Some(bad) = indices.iter().find(|&&k| k >= inner) {
        return Err(format!(
            "index {bad} in indices.npy is beyond the shape ({inner})"
        ));
    }
    Ok(())
}

/// The elements of a float array (`f4` or `f8`) as `f64`.
fn floats<R: Read>(npy: npyz::NpyFile<R>) -> Result<Vec<f64>, String> {
    let npyz::DType::Plain(ty) = npy.dtype() else {
        return Err("data.npy: not an array of numbers".into());
    };
    let read = |e: std::io::Error| format!("data.npy: {e}");
    match (ty.type_char(), ty.size_field()) {
        (npyz::TypeChar::Float, 8) => npy.into_vec::<f64>().map_err(read),
        (npyz::TypeChar::Float, 4) => Ok(npy
            .into_vec::<f32>()
            .map_err(read)?
            .into_iter()
            .map(f64::from)
            .collect()),
        _ => Err(format!(
            "data.npy has dtype {ty}: only float64 or float32 values are read"
        )),
    }
}

/// The elements of an integer array (signed or unsigned, any width), each checked
/// non-negative; `what` names the array in errors.
pub fn integers<R: Read>(npy: npyz::NpyFile<R>, what: &str) -> Result<Vec<usize>, String> {
    let npyz::DType::Plain(ty) = npy.dtype() else {
        return Err(format!("{what}.npy: not an array of integers"));
    };
    let read = |e: std::io::Error| format!("{what}.npy: {e}");
    let signed: Vec<i128> = match (ty.type_char(), ty.size_field()) {
        (npyz::TypeChar::Int, 8) => widen(npy.into_vec::<i64>().map_err(read)?),
        (npyz::TypeChar::Int, 4) => widen(npy.into_vec::<i32>().map_err(read)?),
        (npyz::TypeChar::Int, 2) => widen(npy.into_vec::<i16>().map_err(read)?),
        (npyz::TypeChar::Int, 1) => widen(npy.into_vec::<i8>().map_err(read)?),
        (npyz::TypeChar::Uint, 8) => widen(npy.into_vec::<u64>().map_err(read)?),
        (npyz::TypeChar::Uint, 4) => widen(npy.into_vec::<u32>().map_err(read)?),
        (npyz::TypeChar::Uint, 2) => widen(npy.into_vec::<u16>().map_err(read)?),
        (npyz::TypeChar::Uint, 1) => widen(npy.into_vec::<u8>().map_err(read)?),
        _ => return Err(format!("{what}.npy has dtype {ty}, not integers")),
    };
    signed
        .into_iter()
        .enumerate()
        .map(|(k, v)| {
            usize::try_from(v).map_err(|_| format!("{what}.npy: entry {k} is {v}, not an index"))
        })
        .collect()
}

fn widen<T: Into<i128>>(values: Vec<T>) -> Vec<i128> {
    values.into_iter().map(Into::into).collect()
}

/// Reads an integer `.npy` file of one dimension (e.g. `vertex_map.npy`).
pub fn read_index_npy(reader: impl Read, what: &str) -> Result<Vec<usize>, String> {
    let npy = npyz::NpyFile::new(reader).map_err(|e| format!("not an .npy array: {e}"))?;
    if npy.shape().len() != 1 {
        return Err(format!(
            "{what} has shape {:?}: one dimension expected",
            npy.shape()
        ));
    }
    integers(npy, what)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{npy_bytes, write_sparse_npz, NpyData};

    fn example() -> SparseMatrix {
        let mut t = TriMat::new((3, 4));
        t.add_triplet(0, 1, 2.5);
        t.add_triplet(2, 3, -1.0);
        t.add_triplet(1, 0, 1e-300);
        t.to_csr()
    }

    #[test]
    fn tvf_files_read_back_exactly() {
        let matrix = example();
        let mut mtx = Vec::new();
        sprs::io::write_matrix_market_to_bufwrite(&mut mtx, &matrix).unwrap();
        assert_eq!(read_matrix_market(&mtx[..]).unwrap(), matrix);
        let mut npz = std::io::Cursor::new(Vec::new());
        write_sparse_npz(&mut npz, &matrix).unwrap();
        npz.set_position(0);
        assert_eq!(read_sparse_npz(npz).unwrap(), matrix);
        let map = npy_bytes(&NpyData::I64(&[0, 2, 5]), &[3]);
        assert_eq!(
            read_index_npy(&map[..], "vertex_map").unwrap(),
            vec![0, 2, 5]
        );
    }

    /// `scipy.sparse.save_npz` compresses by default: the same members, deflated.
    #[test]
    fn deflated_archives_read_like_stored_ones() {
        use std::io::Write;
        let matrix = example();
        let mut stored = std::io::Cursor::new(Vec::new());
        write_sparse_npz(&mut stored, &matrix).unwrap();
        stored.set_position(0);
        let mut source = zip::ZipArchive::new(stored).unwrap();
        let mut deflated = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
        let options = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated);
        for i in 0..source.len() {
            let mut member = source.by_index(i).unwrap();
            let mut bytes = Vec::new();
            member.read_to_end(&mut bytes).unwrap();
            deflated.start_file(member.name(), options).unwrap();
            deflated.write_all(&bytes).unwrap();
        }
        let mut archive = deflated.finish().unwrap();
        archive.set_position(0);
        assert_eq!(read_sparse_npz(archive).unwrap(), matrix);
    }

    #[test]
    fn symmetric_files_are_mirrored_and_bad_lines_named() {
        let text = "%%MatrixMarket matrix coordinate real symmetric\n% c\n2 2 2\n1 1 4\n2 1 1\n";
        let m = read_matrix_market(text.as_bytes()).unwrap();
        assert_eq!(m.get(0, 1), Some(&1.0));
        assert_eq!(m.get(1, 0), Some(&1.0));
        let beyond = "%%MatrixMarket matrix coordinate real general\n2 2 1\n3 1 4\n";
        let message = read_matrix_market(beyond.as_bytes()).unwrap_err();
        assert!(message.starts_with("line 3: row index '3'"), "{message}");
        let short = "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 4\n";
        let message = read_matrix_market(short.as_bytes()).unwrap_err();
        assert!(message.contains("after 1 of the 2 entries"), "{message}");
        let nan = "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 nan\n";
        assert!(read_matrix_market(nan.as_bytes()).unwrap().data()[0].is_nan());
    }
}
