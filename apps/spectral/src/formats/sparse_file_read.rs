//! Reading the sparse matrices other tools write as Matrix Market coordinate files (`.mtx`:
//! MATLAB's `mmwrite`, Julia's `MatrixMarket`, `scipy.io.mmwrite`, `tvf operators`), and the
//! bounds every matrix reader applies before it allocates ([`MatrixLimits`]). scipy's sparse
//! `.npz` is read in [`super::sparse_npz_read`]. Every error says what is wrong (with the line of
//! a `.mtx` file); callers add the file name.
//!
//! A Matrix Market file is parsed here because `sprs`'s reader panics on an index beyond the
//! declared shape, allocates what the size line declares before reading an entry, and does not
//! say which line is wrong.

use sprs::{CsMat, TriMat};
use std::io::BufRead;

/// A sparse matrix of a file, with the stored entries as given (duplicates summed).
pub type SparseMatrix = CsMat<f64>;

/// What a matrix file may declare, checked before anything of that size is allocated: the row
/// and column counts it may have (a mesh's `V`, `E`, `F` and `2F` for the matrices of a complex
/// folder) and the bytes the file holds (each `.mtx` entry line takes at least
/// [`MIN_ENTRY_LINE_BYTES`], so a size line promising more entries than that is refused).
#[derive(Debug, Clone, Copy, Default)]
pub struct MatrixLimits<'a> {
    /// The row and column counts allowed, each with its name (`("E", 1920)`); empty: any.
    pub sizes: &'a [(&'a str, usize)],
    /// The length of the file in bytes, if known.
    pub file_bytes: Option<u64>,
}

/// The shortest line a Matrix Market entry takes: `1 1 1` and its line end.
pub const MIN_ENTRY_LINE_BYTES: u64 = 6;

/// Entries allocated ahead of reading them at most; more grow as they are read.
const PREALLOCATED_ENTRIES: usize = 1 << 20;

impl MatrixLimits<'_> {
    /// Why a declared `rows × cols` shape is refused, if it is.
    pub fn shape_problem(&self, rows: usize, cols: usize) -> Option<String> {
        if self.sizes.is_empty() {
            return None;
        }
        let allowed = |n: usize| self.sizes.iter().any(|&(_, size)| size == n);
        if allowed(rows) && allowed(cols) {
            return None;
        }
        let names: Vec<String> = self
            .sizes
            .iter()
            .map(|(name, size)| format!("{name} = {size}"))
            .collect();
        Some(format!(
            "the file declares a {rows} x {cols} matrix, but each size of a matrix of this mesh \
             is one of {} (nothing was allocated)",
            names.join(", ")
        ))
    }

    /// The most entries a Matrix Market file of this length can list (`None`: unknown).
    fn most_entries(&self) -> Option<u64> {
        self.file_bytes
            .map(|bytes| bytes.saturating_add(1) / MIN_ENTRY_LINE_BYTES)
    }
}

/// A line of a file quoted in an error: at most 80 characters (a binary file's first "line" can
/// be megabytes).
pub(crate) fn quoted(line: &str) -> String {
    const SHOWN: usize = 80;
    match line.char_indices().nth(SHOWN) {
        Some((cut, _)) => format!("'{}…'", &line[..cut]),
        None => format!("'{line}'"),
    }
}

/// Reads a Matrix Market `coordinate` file of `real` or `integer` values, `general` or
/// `symmetric` (the lower triangle mirrored). Indices are 1-based in the file. Non-finite
/// values are read as they are (the caller checks them, naming the entry). No bounds but the
/// arithmetic ones: see [`read_matrix_market_within`].
pub fn read_matrix_market(reader: impl BufRead) -> Result<SparseMatrix, String> {
    read_matrix_market_within(reader, &MatrixLimits::default())
}

/// [`read_matrix_market`], refusing a size line `limits` does not allow before anything of its
/// size is allocated.
pub fn read_matrix_market_within(
    reader: impl BufRead,
    limits: &MatrixLimits<'_>,
) -> Result<SparseMatrix, String> {
    let mut lines = reader.lines().enumerate();
    let mut next_line = || -> Result<Option<(usize, String)>, String> {
        match lines.next() {
            Some((i, Ok(line))) => Ok(Some((i + 1, line))),
            Some((i, Err(e))) if e.kind() == std::io::ErrorKind::InvalidData => Err(format!(
                "line {}: not text (not UTF-8): not a Matrix Market file",
                i + 1
            )),
            Some((i, Err(e))) => Err(format!("line {}: {e}", i + 1)),
            None => Ok(None),
        }
    };
    let (_, header) = next_line()?.ok_or("empty file (no %%MatrixMarket header)")?;
    let symmetric = header_symmetry(&header)?;
    let (size_line, size) = loop {
        match next_line()? {
            Some((_, l)) if l.trim().is_empty() || l.trim_start().starts_with('%') => continue,
            Some(found) => break found,
            None => return Err("the file ends before the size line 'rows cols entries'".into()),
        }
    };
    let not_a_size_line = || {
        format!(
            "line {size_line}: not a size line 'rows cols entries': {}",
            quoted(&size)
        )
    };
    let numbers: Vec<usize> = size
        .split_whitespace()
        .map(|w| w.parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| not_a_size_line())?;
    let [rows, cols, entries] = numbers[..] else {
        return Err(not_a_size_line());
    };
    if let Some(problem) = limits.shape_problem(rows, cols) {
        return Err(format!("line {size_line}: {problem}"));
    }
    if let Some(most) = limits.most_entries().filter(|&most| entries as u64 > most) {
        return Err(format!(
            "line {size_line}: the size line promises {entries} entries, but a file of {} bytes \
             holds at most {most} (one per line)",
            limits.file_bytes.unwrap_or(0)
        ));
    }
    let mut triplets = TriMat::with_capacity((rows, cols), entries.min(PREALLOCATED_ENTRIES));
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

/// Whether the header line declares a `symmetric` (else `general`) coordinate matrix of real or
/// integer values; an error for any other header.
fn header_symmetry(header: &str) -> Result<bool, String> {
    let words: Vec<String> = header
        .split_whitespace()
        .map(|w| w.to_lowercase())
        .collect();
    if words.len() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix" {
        return Err(format!(
            "line 1: not a Matrix Market matrix header ('%%MatrixMarket matrix coordinate real \
             general' expected): {}",
            quoted(header)
        ));
    }
    if words[2] != "coordinate" || !["real", "integer", "double"].contains(&words[3].as_str()) {
        return Err(format!(
            "line 1: only sparse 'coordinate' files of 'real' or 'integer' values are read, \
             not '{} {}'",
            words[2], words[3]
        ));
    }
    match words[4].as_str() {
        "general" => Ok(false),
        "symmetric" => Ok(true),
        other => Err(format!(
            "line 1: '{other}' matrices are not read (general or symmetric)"
        )),
    }
}

/// One entry line `i j value` (1-based), checked against the shape; returns 0-based indices.
fn entry(line: &str, rows: usize, cols: usize) -> Result<(usize, usize, f64), String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let [i, j, value] = words[..] else {
        return Err(format!("not an entry 'row col value': {}", quoted(line)));
    };
    let index = |word: &str, limit: usize, what: &str| -> Result<usize, String> {
        match word.parse::<usize>() {
            Ok(k) if (1..=limit).contains(&k) => Ok(k - 1),
            _ => Err(format!(
                "{what} index {} is not in 1..={limit} (1-based, the shape's {what}s)",
                quoted(word)
            )),
        }
    };
    let value = value
        .parse::<f64>()
        .map_err(|_| format!("{} is not a number", quoted(value)))?;
    Ok((index(i, rows, "row")?, index(j, cols, "column")?, value))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tvf_files_read_back_exactly() {
        let mut t = TriMat::new((3, 4));
        t.add_triplet(0, 1, 2.5);
        t.add_triplet(2, 3, -1.0);
        t.add_triplet(1, 0, 1e-300);
        let matrix: SparseMatrix = t.to_csr();
        let mut mtx = Vec::new();
        sprs::io::write_matrix_market_to_bufwrite(&mut mtx, &matrix).unwrap();
        assert_eq!(read_matrix_market(&mtx[..]).unwrap(), matrix);
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

    /// Declared sizes are checked before anything of their size is allocated: a shape that is
    /// none of the mesh's sizes, more entries than the file can hold, an entry count beyond
    /// `usize` arithmetic (each once aborted or took gigabytes).
    #[test]
    fn declared_sizes_are_refused_before_allocating() {
        let header = "%%MatrixMarket matrix coordinate real general\n";
        let sizes = [("V", 642), ("E", 1920), ("F", 1280), ("2F", 2560)];
        let text = |size: &str| format!("{header}{size}\n1 1 1.0\n");
        let limits = |text: &str| MatrixLimits {
            sizes: &sizes,
            file_bytes: Some(text.len() as u64),
        };
        for size in ["4000000000 4000000000 2560", "500000000 500000000 2560"] {
            let file = text(size);
            let message = read_matrix_market_within(file.as_bytes(), &limits(&file)).unwrap_err();
            assert!(message.contains("2F = 2560"), "{message}");
        }
        for size in ["2560 2560 1000000000000", "2560 2560 18446744073709551615"] {
            let file = text(size);
            let message = read_matrix_market_within(file.as_bytes(), &limits(&file)).unwrap_err();
            assert!(message.contains("holds at most"), "{message}");
            // Without limits: no allocation of the declared count either, just the short file.
            let message = read_matrix_market(file.as_bytes()).unwrap_err();
            assert!(message.contains("the file ends after 1"), "{message}");
        }
        let file = text("2560 642 1");
        assert_eq!(
            read_matrix_market_within(file.as_bytes(), &limits(&file))
                .unwrap()
                .shape(),
            (2560, 642)
        );
    }

    #[test]
    fn quoted_lines_are_cut() {
        let long = "x".repeat(1000);
        let shown = quoted(&long);
        assert!(shown.len() < 100 && shown.ends_with("…'"), "{shown}");
        assert_eq!(quoted("abc"), "'abc'");
    }
}
