//! The progress of passes over a basis file read in blocks ([`BlockObserver`]): every pass —
//! the check at opening, projections, syntheses, the fields of the basis id, the rows of `U` —
//! is reported from `0` to its total, growing at every block; the results are those of the
//! blocks without an observer, bit for bit; an observer that unwinds stops the pass, and the
//! blocks still work afterwards.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::{Arc, Mutex};
use tvf_core::discretization::HodgeOperators;
use tvf_core::generate::icosphere;
use tvf_discretizations::{BoxedComplex, Conforming, MassLumping, WhitneyGalerkin};
use tvf_spectral::{
    field_basis_id, save_computed_basis, BasisFileBlocks, BasisFileKey, BasisRequest,
    BlockObserver, BlockPass, BlockProgress, FieldBasis, ObservedBasisFile,
};

/// An observer keeping every report, and the reports it kept.
fn recorder() -> (BlockObserver, Arc<Mutex<Vec<BlockProgress>>>) {
    let reports = Arc::new(Mutex::new(Vec::new()));
    let kept = reports.clone();
    let observer: BlockObserver = Arc::new(move |p| kept.lock().unwrap().push(p));
    (observer, reports)
}

/// The reports split into passes (each starts with `done_bytes == 0`), each checked: one pass
/// and total throughout, done growing at every report up to the total; the passes' names and
/// their numbers of blocks.
fn passes(reports: &[BlockProgress]) -> Vec<(BlockPass, usize)> {
    let mut passes: Vec<Vec<BlockProgress>> = Vec::new();
    for &report in reports {
        if report.done_bytes == 0 {
            passes.push(Vec::new());
        }
        passes
            .last_mut()
            .expect("a pass starts with done 0")
            .push(report);
    }
    passes
        .iter()
        .map(|pass| {
            let (first, last) = (pass[0], pass[pass.len() - 1]);
            assert!(first.total_bytes > 0);
            assert_eq!(last.done_bytes, last.total_bytes, "{pass:?}");
            for pair in pass.windows(2) {
                assert_eq!(pair[1].pass, first.pass);
                assert_eq!(pair[1].total_bytes, first.total_bytes);
                assert!(pair[1].done_bytes > pair[0].done_bytes, "{pass:?}");
            }
            (first.pass, pass.len() - 1)
        })
        .collect()
}

/// Everything a basis in blocks computes (coefficients, two syntheses, four rows of `U`, the
/// basis id), for comparisons bit for bit.
#[derive(Debug, PartialEq)]
struct Products {
    coefficients: Vec<f64>,
    fields: Vec<Vec<f64>>,
    rows: Vec<Vec<f64>>,
    id: u64,
}

/// The [`Products`] of `basis`.
fn products(basis: &dyn FieldBasis) -> Products {
    let n1 = basis.field_dimension();
    let field: Vec<f64> = (0..n1).map(|i| (0.37 * i as f64).sin()).collect();
    let coefficients = basis.coefficients(&field).unwrap();
    let other: Vec<f64> = coefficients.iter().map(|c| 2.0 * c - 0.5).collect();
    let fields = basis.reconstruct_many(&[&coefficients, &other]).unwrap();
    let rows = basis.rows(&[0, 7, n1 / 2, n1 - 1]).unwrap();
    Products {
        coefficients,
        fields,
        rows,
        id: field_basis_id(basis).unwrap(),
    }
}

/// A basis of 40 fields of `complex` saved to `path`, read in blocks of three potentials.
fn observed_blocks(mesh: &tvf_core::TriangleMesh, complex: impl Fn() -> BoxedComplex, path: &Path) {
    let key = BasisFileKey::new(mesh, complex().as_ref());
    save_computed_basis(path, complex().as_ref(), &BasisRequest::fields(40), &key).unwrap();
    let block_bytes = 3 * 8 * complex().potential_dimension();
    let plain = BasisFileBlocks::open(path, &key, complex())
        .unwrap()
        .unwrap()
        .with_block_bytes(block_bytes);
    let expected = products(&plain);

    let (observer, reports) = recorder();
    let observed = BasisFileBlocks::open_with_observer(path, &key, complex(), Some(observer))
        .unwrap()
        .unwrap()
        .with_block_bytes(block_bytes);
    let checked = passes(&reports.lock().unwrap());
    assert_eq!(checked.len(), 1);
    assert_eq!(checked[0].0, BlockPass::Checking);
    let file_bytes = std::fs::metadata(path).unwrap().len();
    let checked_bytes = reports.lock().unwrap()[0].total_bytes;
    assert!(checked_bytes < file_bytes && checked_bytes > file_bytes / 2);
    reports.lock().unwrap().clear();

    assert_eq!(products(&observed), expected, "an observer changes nothing");
    let seen = passes(&reports.lock().unwrap());
    let names: Vec<BlockPass> = seen.iter().map(|&(pass, _)| pass).collect();
    assert_eq!(
        names,
        [
            BlockPass::Projecting,
            BlockPass::Synthesising,
            BlockPass::Rows,
            BlockPass::Fields
        ]
    );
    for &(pass, blocks) in &seen {
        assert!(blocks > 3, "{pass:?}: {blocks} blocks");
    }
    // Every pass covers all the stored columns (the rows: at the entries they touch).
    let totals: Vec<u64> = reports
        .lock()
        .unwrap()
        .iter()
        .map(|p| p.total_bytes)
        .collect();
    assert!(totals.iter().all(|&t| t == totals[0]));

    // Another observer per caller of the same blocks; the blocks' own one is not told.
    reports.lock().unwrap().clear();
    let (own, own_reports) = recorder();
    let shared = ObservedBasisFile::new(Arc::new(observed), Some(own));
    assert_eq!(products(&shared), expected);
    assert!(reports.lock().unwrap().is_empty());
    assert_eq!(passes(&own_reports.lock().unwrap()), seen);

    // An observer that unwinds at the second block stops the pass; the blocks still work.
    let calls = Arc::new(Mutex::new(0));
    let counted = calls.clone();
    let stopping: BlockObserver = Arc::new(move |_| {
        let mut calls = counted.lock().unwrap();
        *calls += 1;
        if *calls == 3 {
            drop(calls);
            std::panic::resume_unwind(Box::new("stopped"));
        }
    });
    let stopped = ObservedBasisFile::new(Arc::new(plain), Some(stopping));
    let field = vec![1.0; stopped.field_dimension()];
    assert!(catch_unwind(AssertUnwindSafe(|| stopped.coefficients(&field))).is_err());
    assert_eq!(*calls.lock().unwrap(), 3);
    assert_eq!(products(stopped.blocks()), expected);
}

/// A lumped complex (sparse rows of `U`, read at the entries they touch) and the Galerkin
/// masses (co-integrable rows through the co-gradient, read whole).
#[test]
fn passes_over_a_basis_file_report_their_progress_and_change_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let mesh = icosphere(2);
    observed_blocks(
        &mesh,
        || Box::new(Conforming::new(&mesh, MassLumping::Barycentric).unwrap()),
        &dir.path().join("lumped.tvfb"),
    );
    observed_blocks(
        &mesh,
        || Box::new(WhitneyGalerkin::new(&mesh).unwrap()),
        &dir.path().join("galerkin.tvfb"),
    );
}
