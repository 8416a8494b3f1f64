//! `tvf.check`: the core conformance checks of the test suite on a complex, as a report; and on
//! a Python builder `(V, F) -> matrices`, on one mesh or property-based on generated meshes with
//! the shrunk minimal failing mesh (`tvf_conformance::property_runner`). A builder's ordinary
//! exception is a failed `construction` check; `KeyboardInterrupt` (Ctrl+C), `SystemExit` and
//! the other exceptions that are not an `Exception` stop the run and are raised.

use crate::arrays::vectors_to_numpy;
use crate::complex::Complex;
use crate::interrupt::{detached, interruptible, Interruption};
use crate::mesh::Mesh;
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use tvf_conformance::accuracy::{accuracy_report, consistency_on_mesh, AccuracyRequest};
use tvf_conformance::check_outcome::CheckOutcome;
use tvf_conformance::check_report::core_check_report;
use tvf_conformance::property_runner::{check_mesh, run_property, PropertyRequest};
use tvf_conformance::strategies::MeshNeeds;
use tvf_core::discretization::PointEvaluation;
use tvf_core::discretization::{ComplexParts, FieldRotation, FieldSampling, HodgeComplex};
use tvf_core::{SurfaceMesh, TriangleMesh};

/// The complex a Python builder makes on `mesh`; its exception as the error (one that is not an
/// `Exception`, such as `KeyboardInterrupt`, stops the computation: [`Interruption::stop`]).
pub(crate) fn python_complex(
    build: &Py<PyAny>,
    mesh: &TriangleMesh,
    interruption: &Interruption,
) -> Result<Box<dyn HodgeComplex>, String> {
    Python::attach(|py| {
        let (v, f) = mesh_arrays(py, mesh);
        let built = build
            .call1(py, (v, f))
            .map_err(|e| interruption.unless_stopping(py, e).to_string())?;
        let complex = built
            .bind(py)
            .cast::<Complex>()
            .map_err(|e| format!("the builder did not return a native Complex: {e}"))?;
        Ok(Box::new(PythonComplex(complex.clone().unbind())) as Box<dyn HodgeComplex>)
    })
}

/// One dict per check: `name`, `status` (`passed`/`failed`/`skipped`/`not applicable`),
/// `measured`, `limit`, `comparison`, `detail`: the core checks, then the consistency checks of
/// linear functions on the complex's own mesh.
#[pyfunction]
pub fn check<'py>(py: Python<'py>, complex: &Complex) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let Some(mesh) = complex.mesh.as_triangles() else {
        return Err(crate::errors::tvf_error(
            "the conformance checks run on triangle meshes so far (this mesh has polygons)",
        ));
    };
    let report = detached(py, || {
        let mut report = core_check_report(complex.complex.as_ref(), mesh);
        let consistency = consistency_on_mesh(complex.complex.as_ref(), &complex.mesh);
        report.outcomes.extend(consistency);
        report
    })?;
    outcome_dicts(py, &report.outcomes)
}

/// The accuracy checks of a Python builder (triangle meshes; on meshes with boundary too if
/// `open_meshes`, else the hemisphere sequences are reported as not applicable).
fn builder_accuracy(
    build: &Py<PyAny>,
    interruption: &Interruption,
    open_meshes: bool,
) -> tvf_conformance::check_report::CheckReport {
    let builder = |mesh: &SurfaceMesh| match mesh.as_triangles() {
        Some(triangles) => python_complex(build, triangles, interruption),
        None => Err("a Python builder builds on triangle meshes".to_string()),
    };
    let request = AccuracyRequest {
        triangles: true,
        polygons: false,
        open_meshes,
    };
    accuracy_report(&builder, &request)
}

/// The core checks of the complexes `build(V, F)` (a Python callable returning a native
/// `Complex`) makes: on `mesh` if given, else on `cases` closed meshes drawn with `seed`
/// (Delaunay ones if `delaunay`), shrinking a failure. A dict: `passed` (the verdict: false
/// whenever a case failed, even if its counterexample passes when checked again),
/// `cases_passed`, `outcomes` (the mesh's, or each check's worst case), `counterexample`
/// (`(V, F)` or `None`), `counterexample_outcomes` (measured in the run that failed),
/// `reproduced` (whether the counterexample failed again; `None` without one) and `accuracy`
/// (the accuracy checks' outcomes if `accuracy`, else empty; a failed one makes `passed` false).
/// With `open_meshes` the generated meshes and the accuracy sequences include meshes with
/// boundary (the builder then gives `fixed_nodes` and `boundary_condition`). Shrinking a failure
/// takes at most `shrink_steps` steps (each a run of the core checks on a smaller mesh).
#[pyfunction]
#[pyo3(signature = (build, cases, seed, mesh, delaunay, accuracy, open_meshes, shrink_steps))]
#[allow(clippy::too_many_arguments)]
pub fn check_builder<'py>(
    py: Python<'py>,
    build: Py<PyAny>,
    cases: u32,
    seed: u64,
    mesh: Option<&Mesh>,
    delaunay: bool,
    accuracy: bool,
    open_meshes: bool,
    shrink_steps: u32,
) -> PyResult<Bound<'py, PyDict>> {
    let interruption = Interruption::default();
    let accuracy_outcomes = if accuracy {
        interruptible(py, &interruption, || {
            builder_accuracy(&build, &interruption, open_meshes)
        })?
        .outcomes
    } else {
        Vec::new()
    };
    let accurate = !accuracy_outcomes.iter().any(CheckOutcome::failed_check);
    let builder = |mesh: &TriangleMesh| python_complex(&build, mesh, &interruption);
    let result = PyDict::new(py);
    result.set_item("accuracy", outcome_dicts(py, &accuracy_outcomes)?)?;
    if let Some(mesh) = mesh {
        let Some(triangles) = mesh.mesh.as_triangles() else {
            return Err(crate::errors::tvf_error(
                "the conformance checks run on triangle meshes so far (this mesh has polygons)",
            ));
        };
        let report = interruptible(py, &interruption, || check_mesh(&builder, triangles, &[]))?;
        result.set_item("passed", report.passed() && accurate)?;
        result.set_item("cases_passed", u32::from(report.passed()))?;
        result.set_item("outcomes", outcome_dicts(py, &report.outcomes)?)?;
        result.set_item("counterexample", py.None())?;
        result.set_item("counterexample_outcomes", Vec::<Bound<'py, PyDict>>::new())?;
        result.set_item("reproduced", py.None())?;
        return Ok(result);
    }
    let needs = MeshNeeds {
        delaunay,
        closed_only: !open_meshes,
    };
    let request = PropertyRequest {
        max_shrink_iters: shrink_steps,
        ..PropertyRequest::new(cases, seed, needs)
    };
    let report = interruptible(py, &interruption, || {
        run_property(&builder, &request, &|_| {})
    })?;
    if let Some(reason) = &report.aborted {
        return Err(crate::errors::tvf_error(format!(
            "the property run stopped: {reason}"
        )));
    }
    result.set_item("passed", report.passed() && accurate)?;
    result.set_item("cases_passed", report.cases_passed)?;
    result.set_item("outcomes", outcome_dicts(py, &report.worst)?)?;
    match &report.counterexample {
        Some(counterexample) => {
            result.set_item("counterexample", mesh_arrays(py, &counterexample.mesh.mesh))?;
            let outcomes = outcome_dicts(py, &counterexample.report.outcomes)?;
            result.set_item("counterexample_outcomes", outcomes)?;
            result.set_item("reproduced", counterexample.reproduced)?;
        }
        None => {
            result.set_item("counterexample", py.None())?;
            result.set_item("counterexample_outcomes", Vec::<Bound<'py, PyDict>>::new())?;
            result.set_item("reproduced", py.None())?;
        }
    }
    Ok(result)
}

/// `(V, F)`: positions `n × 3` float64 and faces `m × 3` int64.
pub(crate) fn mesh_arrays<'py>(
    py: Python<'py>,
    mesh: &TriangleMesh,
) -> (Bound<'py, PyAny>, Bound<'py, PyAny>) {
    let faces = mesh.faces();
    let f = Array2::from_shape_fn((faces.len(), 3), |(t, c)| faces[t][c] as i64)
        .into_pyarray(py)
        .into_any();
    (vectors_to_numpy(py, mesh.positions()), f)
}

fn outcome_dicts<'py>(
    py: Python<'py>,
    outcomes: &[CheckOutcome],
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    outcomes
        .iter()
        .map(|o| {
            let d = PyDict::new(py);
            d.set_item("name", &o.name)?;
            d.set_item("status", o.status.name())?;
            d.set_item("measured", o.measured)?;
            d.set_item("limit", o.limit)?;
            d.set_item("comparison", o.comparison.name())?;
            d.set_item("detail", &o.detail)?;
            Ok(d)
        })
        .collect()
}

/// A complex the Python builder made, owned by Python; the checks read it through the seam.
pub(crate) struct PythonComplex(pub(crate) Py<Complex>);

impl PythonComplex {
    fn inner(&self) -> &dyn HodgeComplex {
        self.0.get().complex.as_ref()
    }
}

impl HodgeComplex for PythonComplex {
    fn parts(&self) -> &ComplexParts {
        self.inner().parts()
    }

    fn sampling(&self) -> Option<&dyn FieldSampling> {
        self.inner().sampling()
    }

    fn rotation(&self) -> Option<&dyn FieldRotation> {
        self.inner().rotation()
    }

    fn point_evaluation(&self) -> Option<&dyn PointEvaluation> {
        self.inner().point_evaluation()
    }
}
