//! Arrays for numpy, written: `.npy` files of float64, int64 and Unicode-string arrays (for
//! exports, written with `npyz` like the float arrays of field files in `npy.rs`), and sparse matrices as the `.npz` files `scipy.sparse.load_npz` reads (a zip of the CSR
//! arrays `data`, `indices`, `indptr`, `shape` and the format name `csr`). The caller decides
//! how the bytes are written (atomically, into a staged folder).

use crate::formats::npy::npy_of;
use npyz::{DType, TypeStr, WriterBuilder};
use sprs::CsMat;
use std::io::{Seek, Write};
use tvf_core::discretization::sparse::{csr_arrays, CsrArrays};

/// An array for a `.npy` file: its shape and its elements in C order.
pub enum NpyData<'a> {
    /// `<f8`.
    F64(&'a [f64]),
    /// `<i8`.
    I64(&'a [i64]),
    /// `<U{n}` (UTF-32, `n` the longest string's length in characters).
    Text(&'a [&'a str]),
    /// A 0-d `|S{n}` byte string (scipy's `format` entry).
    Bytes(&'a [u8]),
}

/// The bytes of an `.npy` file holding `data` with shape `shape` (format 1.0 unless the header
/// needs more; the data start at a multiple of 64 bytes).
pub fn npy_bytes(data: &NpyData<'_>, shape: &[usize]) -> Vec<u8> {
    let shape: Vec<u64> = shape.iter().map(|&d| d as u64).collect();
    match data {
        NpyData::F64(values) => npy_of(&shape, values.iter().copied()),
        NpyData::I64(values) => npy_of(&shape, values.iter().copied()),
        NpyData::Text(strings) => {
            let width = strings
                .iter()
                .map(|s| s.chars().count())
                .max()
                .unwrap_or(0)
                .max(1);
            strings_npy(&format!("<U{width}"), &shape, strings)
        }
        NpyData::Bytes(bytes) => {
            let descr = format!("|S{}", bytes.len().max(1));
            strings_npy(&descr, &shape, &[*bytes])
        }
    }
}

/// The `.npy` bytes of `strings` (`str` or `[u8]`, each padded with zeros to the width of
/// `descr`, a `<U{n}` or `|S{n}` dtype) with shape `shape`.
fn strings_npy<T: npyz::Serialize + ?Sized>(descr: &str, shape: &[u64], strings: &[&T]) -> Vec<u8> {
    let mut out = Vec::new();
    let written = descr
        .parse::<TypeStr>()
        .map_err(std::io::Error::other)
        .and_then(|type_str| {
            let mut writer = npyz::WriteOptions::<T>::new()
                .dtype(DType::Plain(type_str))
                .shape(shape)
                .writer(&mut out)
                .begin_nd()?;
            for s in strings {
                writer.push(s)?;
            }
            writer.finish()
        });
    debug_assert!(written.is_ok(), "in-memory .npy write: {written:?}");
    out
}

/// Writes `matrix` as an uncompressed `.npz` in scipy's CSR layout.
pub fn write_sparse_npz<W: Write + Seek>(writer: W, matrix: &CsMat<f64>) -> std::io::Result<()> {
    let CsrArrays {
        indptr,
        indices,
        data,
        shape: (rows, cols),
    } = csr_arrays(matrix);
    let shape = [rows as i64, cols as i64];
    let members = [
        (
            "indices.npy",
            npy_bytes(&NpyData::I64(&indices), &[indices.len()]),
        ),
        (
            "indptr.npy",
            npy_bytes(&NpyData::I64(&indptr), &[indptr.len()]),
        ),
        ("format.npy", npy_bytes(&NpyData::Bytes(b"csr"), &[])),
        ("shape.npy", npy_bytes(&NpyData::I64(&shape), &[2])),
        ("data.npy", npy_bytes(&NpyData::F64(&data), &[data.len()])),
    ];
    let mut zip = zip::ZipWriter::new(writer);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(data.len() > 100_000_000);
    for (name, bytes) in members {
        zip.start_file(name, options)
            .map_err(std::io::Error::other)?;
        zip.write_all(&bytes)?;
    }
    zip.finish().map_err(std::io::Error::other)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_are_aligned_and_describe_the_data() {
        let bytes = npy_bytes(&NpyData::F64(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]), &[2, 3]);
        let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + header_len) % 64, 0);
        let header = std::str::from_utf8(&bytes[10..10 + header_len]).unwrap();
        assert!(header.contains("'descr': '<f8'") && header.contains("'shape': (2, 3"));
        assert_eq!(bytes.len(), 10 + header_len + 48);
        let text = npy_bytes(&NpyData::Text(&["harmonic", "é"]), &[2]);
        let header_len = u16::from_le_bytes([text[8], text[9]]) as usize;
        assert!(std::str::from_utf8(&text[10..10 + header_len])
            .unwrap()
            .contains("'<U8'"));
        assert_eq!(text.len(), 10 + header_len + 2 * 8 * 4);
        let scalar = npy_bytes(&NpyData::Bytes(b"csr"), &[]);
        assert!(scalar.ends_with(b"csr"));
    }

    /// An exported float64 array is the field files' `.npy` of the same array, byte for byte,
    /// and reads back.
    #[test]
    fn float_exports_are_field_files() {
        let data = [1.5, -2.0, 3.25, 0.0, 5.0, 6.125];
        let exported = npy_bytes(&NpyData::F64(&data), &[3, 2]);
        let array = crate::formats::npy::NpyArray {
            shape: vec![3, 2],
            data: data.to_vec(),
            dtype: crate::formats::npy::NpyDtype::F64,
        };
        assert!(exported == array.to_bytes());
        assert_eq!(
            crate::formats::npy::NpyArray::from_bytes(&exported),
            Ok(array)
        );
    }
}
