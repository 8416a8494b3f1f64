//! The property runner: the core checks (and a catalog entry's measured reference checks) on one
//! mesh ([`check_mesh`]) or on `N` meshes drawn from [`crate::strategies`] ([`run_property`]),
//! with proptest's [`TestRunner`] on a fixed seed; on a failure, proptest shrinks the mesh
//! description and the report holds the minimal failing mesh with its measured numbers — the
//! numbers of the run that failed, and whether the failure came back when that mesh was checked
//! again (a builder whose result changes from call to call fails without reproducing).
//!
//! A builder or a check stops the whole run at once by unwinding with [`StopRun`] (the Python
//! package does on Ctrl+C): the runner passes it on to its caller instead of counting a failed
//! case.

use crate::check_outcome::{CheckOutcome, CheckStatus, Comparison};
use crate::check_report::{core_check_report, CheckReport};
use crate::corpus::CorpusMesh;
use crate::polygon_capability_checks::measure_polygon_capabilities;
use crate::reference_report::{measure_reference, ReferenceCheck};
use crate::strategies::{mesh_specs, polygon_mesh_specs, MeshNeeds, MeshSpec, PolygonMeshSpec};
use proptest::strategy::BoxedStrategy;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::fmt::Debug;
use std::panic::AssertUnwindSafe;
use tvf_core::discretization::HodgeComplex;
use tvf_core::{SurfaceMesh, TriangleMesh};

/// Builds the complex to check on a mesh (a catalog entry, a researcher's own matrices...); the
/// error says why the mesh was refused.
pub type Builder<'a> = &'a dyn Fn(&TriangleMesh) -> Result<Box<dyn HodgeComplex>, String>;

/// Builds the complex to check on a mesh of any faces (a catalog entry that accepts polygons).
pub type SurfaceBuilder<'a> = &'a dyn Fn(&SurfaceMesh) -> Result<Box<dyn HodgeComplex>, String>;

/// Name of the outcome reporting that the builder refused a mesh.
pub const CONSTRUCTION: &str = "construction";

/// Name of the outcome reporting that the builder or a check panicked (its message the detail).
pub const PANIC: &str = "panic";

/// The payload a builder or a check unwinds with (`std::panic::resume_unwind(Box::new(StopRun))`)
/// to stop a run at once — the user interrupted it: [`check_mesh`] and [`run_property`] pass it
/// on to their caller (which catches it) instead of reporting a failed check.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StopRun;

/// Runs the core checks ([`core_check_report`]) and, on a closed mesh, the measured `reference`
/// checks ([`measure_reference`]; the test suite runs them on closed meshes only, the stiffness
/// formulas know no boundary conditions) on the complex `builder` makes of `mesh`. A refused mesh
/// is one failed outcome named [`CONSTRUCTION`], a panic of the builder or of a check one named
/// [`PANIC`]; [`StopRun`] unwinds on to the caller.
pub fn check_mesh(
    builder: Builder,
    mesh: &TriangleMesh,
    reference: &[ReferenceCheck],
) -> CheckReport {
    guarded(|| checks_on_mesh(builder, mesh, reference))
}

/// The core checks ([`core_check_report`]) and the capability checks on polygons
/// ([`measure_polygon_capabilities`]) on the complex `builder` makes of `mesh`, a mesh of any
/// faces; a refused mesh and a panic are reported as by [`check_mesh`]. (The reference checks
/// are formulas on triangles and do not run here.)
pub fn check_polygon_mesh(builder: SurfaceBuilder, mesh: &SurfaceMesh) -> CheckReport {
    guarded(|| {
        let complex = match builder(mesh) {
            Ok(complex) => complex,
            Err(error) => return refusal(error),
        };
        let mut report = core_check_report(complex.as_ref(), mesh);
        report
            .outcomes
            .extend(measure_polygon_capabilities(complex.as_ref(), mesh));
        report
    })
}

/// The report of a mesh the builder refused: one failed outcome named [`CONSTRUCTION`].
fn refusal(error: String) -> CheckReport {
    CheckReport {
        outcomes: vec![CheckOutcome::failed(CONSTRUCTION, error)],
    }
}

/// `checks()`, a panic turned into one failed outcome named [`PANIC`].
fn guarded(checks: impl FnOnce() -> CheckReport) -> CheckReport {
    catch_check_panic(checks).unwrap_or_else(|message| CheckReport {
        outcomes: vec![CheckOutcome::failed(PANIC, message)],
    })
}

/// Runs `run`; a panic comes back as its message (`"a panic without a message"` when its
/// payload is neither a `String` nor a `&str`), except a [`StopRun`], which unwinds on.
pub(crate) fn catch_check_panic<T>(run: impl FnOnce() -> T) -> Result<T, String> {
    std::panic::catch_unwind(AssertUnwindSafe(run)).map_err(|payload| {
        if payload.is::<StopRun>() {
            std::panic::resume_unwind(payload);
        }
        payload
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "a panic without a message".to_string())
    })
}

/// [`check_mesh`] without the panic guard.
fn checks_on_mesh(
    builder: Builder,
    mesh: &TriangleMesh,
    reference: &[ReferenceCheck],
) -> CheckReport {
    let complex = match builder(mesh) {
        Ok(complex) => complex,
        Err(error) => return refusal(error),
    };
    let mut report = core_check_report(complex.as_ref(), mesh);
    for &check in reference {
        if mesh.is_closed() {
            let outcomes = measure_reference(check, complex.as_ref(), mesh);
            report.outcomes.extend(outcomes);
        } else {
            report.outcomes.push(CheckOutcome::skipped(
                check.name(),
                "reference checks hold on closed meshes (as in the test suite)".to_string(),
            ));
        }
    }
    report
}

/// What [`run_property`] runs.
#[derive(Debug, Clone, PartialEq)]
pub struct PropertyRequest {
    /// Number of generated meshes.
    pub cases: u32,
    /// Seed of the mesh draws (the same seed draws the same meshes on every machine).
    pub seed: u64,
    /// The meshes the complex accepts (Delaunay only, closed only).
    pub needs: MeshNeeds,
    /// Measured reference checks to run besides the core checks.
    pub reference: Vec<ReferenceCheck>,
    /// At most this many shrinking steps after a failure.
    pub max_shrink_iters: u32,
}

impl PropertyRequest {
    /// `cases` meshes from `seed` for a complex with `needs`, no reference checks, at most 512
    /// shrinking steps.
    pub fn new(cases: u32, seed: u64, needs: MeshNeeds) -> Self {
        Self {
            cases,
            seed,
            needs,
            reference: Vec::new(),
            max_shrink_iters: 512,
        }
    }
}

/// Where [`run_property`] is, for progress bars.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PropertyProgress {
    /// Case `index` (from 1) of the request's cases passed.
    CasePassed {
        /// 1-based case number.
        index: u32,
    },
    /// A case failed; shrinking tried `steps` smaller meshes so far.
    Shrinking {
        /// Shrinking steps so far.
        steps: u32,
    },
}

/// The minimal failing mesh proptest shrank a failure to: a triangle mesh drawn from a
/// [`MeshSpec`], or a polygon mesh drawn from a [`PolygonMeshSpec`].
#[derive(Debug, Clone)]
pub struct Counterexample<Spec = MeshSpec, M = TriangleMesh> {
    /// Its description.
    pub spec: Spec,
    /// The mesh.
    pub mesh: CorpusMesh<M>,
    /// Every check measured on it in the run that failed (at least one failed).
    pub report: CheckReport,
    /// Whether it failed again when checked once more; `false`: the failure does not reproduce
    /// (a builder or a check whose result changes from call to call), still a failure.
    pub reproduced: bool,
}

/// The result of [`run_property`] (and of [`run_polygon_property`], on polygon meshes).
#[derive(Debug, Clone)]
pub struct PropertyReport<Spec = MeshSpec, M = TriangleMesh> {
    /// Meshes checked before the first failure (all of them if none failed).
    pub cases_passed: u32,
    /// Per check, the outcome with the largest measured value relative to its limit over the
    /// passing cases (skipped checks once), in name order.
    pub worst: Vec<CheckOutcome>,
    /// The shrunk failing mesh, if a case failed.
    pub counterexample: Option<Counterexample<Spec, M>>,
    /// Why the run stopped early without a counterexample (e.g. too many rejected draws).
    pub aborted: Option<String>,
}

impl<Spec, M> PropertyReport<Spec, M> {
    /// Whether every case passed.
    pub fn passed(&self) -> bool {
        self.counterexample.is_none() && self.aborted.is_none()
    }
}

/// Runs `check_mesh(builder, mesh, request.reference)` on `request.cases` meshes drawn from
/// [`mesh_specs`]`(request.needs)` with a [`TestRunner`] seeded by `request.seed`; on a failure,
/// proptest shrinks the description and the report holds the minimal failing mesh, with the
/// numbers of its failing run and whether a second check reproduced the failure.
/// `progress` is called after each case and each shrinking step. A [`StopRun`] from the builder
/// or a check ends the run (the remaining cases and shrinking steps pass at once) and unwinds
/// on to the caller.
pub fn run_property(
    builder: Builder,
    request: &PropertyRequest,
    progress: &dyn Fn(PropertyProgress),
) -> PropertyReport {
    run_specs(
        mesh_specs(request.needs),
        &MeshSpec::build,
        &|mesh| check_mesh(builder, mesh, &request.reference),
        request,
        progress,
    )
}

/// [`run_property`] on polygon meshes: `check_polygon_mesh(builder, mesh)` on `request.cases`
/// meshes drawn from [`polygon_mesh_specs`]`(request.needs.closed_only)` (quad tori and
/// surfaces, cube-spheres, duals, holes, several components, jitter, motions), shrinking a
/// failure to a minimal failing polygon mesh. `request.needs.delaunay` and `request.reference`
/// do not apply to polygons.
pub fn run_polygon_property(
    builder: SurfaceBuilder,
    request: &PropertyRequest,
    progress: &dyn Fn(PropertyProgress),
) -> PropertyReport<PolygonMeshSpec, SurfaceMesh> {
    run_specs(
        polygon_mesh_specs(request.needs.closed_only),
        &PolygonMeshSpec::build,
        &|mesh| check_polygon_mesh(builder, mesh),
        request,
        progress,
    )
}

/// A mesh description's mesh, or why it cannot be built.
type SpecBuild<Spec, M> = dyn Fn(&Spec) -> Result<CorpusMesh<M>, String>;

/// The property run shared by triangle and polygon meshes: `check` on the meshes `build` makes
/// of descriptions drawn from `strategy`, shrinking a failure.
fn run_specs<Spec: Clone + Debug + PartialEq, M>(
    strategy: BoxedStrategy<Spec>,
    build: &SpecBuild<Spec, M>,
    check: &dyn Fn(&M) -> CheckReport,
    request: &PropertyRequest,
    progress: &dyn Fn(PropertyProgress),
) -> PropertyReport<Spec, M> {
    let config = Config {
        cases: request.cases,
        max_shrink_iters: request.max_shrink_iters,
        failure_persistence: None,
        max_global_rejects: 64 * request.cases.max(16),
        ..Config::default()
    };
    let mut seed = [0u8; 32];
    seed[..8].copy_from_slice(&request.seed.to_le_bytes());
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &seed);
    let mut runner = TestRunner::new_with_rng(config, rng);
    let state = RefCell::new(RunState::<Spec, M>::default());
    let result = runner.run(&strategy, |spec| {
        if state.borrow().stopped {
            return Ok(());
        }
        let mesh = build(&spec).map_err(TestCaseError::reject)?;
        let checked = std::panic::catch_unwind(AssertUnwindSafe(|| check(&mesh.mesh)));
        let report = match checked {
            Ok(report) => report,
            Err(payload) if payload.is::<StopRun>() => {
                state.borrow_mut().stopped = true;
                return Ok(());
            }
            Err(payload) => std::panic::resume_unwind(payload),
        };
        let mut state = state.borrow_mut();
        if state.shrinking {
            state.shrink_steps += 1;
            progress(PropertyProgress::Shrinking {
                steps: state.shrink_steps,
            });
        } else if report.passed() {
            state.record(&report);
            progress(PropertyProgress::CasePassed {
                index: state.cases_passed,
            });
        } else {
            state.shrinking = true;
        }
        if report.passed() {
            Ok(())
        } else {
            let failed: Vec<String> = report.failures().iter().map(|o| o.name.clone()).collect();
            state.last_failure = Some((spec, mesh, report));
            Err(TestCaseError::fail(failed.join(", ")))
        }
    });
    let mut state = state.into_inner();
    if state.stopped {
        std::panic::resume_unwind(Box::new(StopRun));
    }
    let (counterexample, aborted) = match result {
        Ok(()) => (None, None),
        Err(TestError::Fail(_, spec)) => {
            let last = state.last_failure.take();
            (Some(counterexample(build, check, spec, last)), None)
        }
        Err(TestError::Abort(reason)) => (None, Some(reason.to_string())),
    };
    PropertyReport {
        cases_passed: state.cases_passed,
        worst: state.worst.into_values().collect(),
        counterexample,
        aborted,
    }
}

/// The counterexample of the shrunk description `spec`: the numbers of its failing run (`last`,
/// the last failure the runner saw, which is the shrunk one), checked once more to tell whether
/// the failure reproduces. Without them (never expected) it is measured again.
fn counterexample<Spec: PartialEq, M>(
    build: &SpecBuild<Spec, M>,
    check: &dyn Fn(&M) -> CheckReport,
    spec: Spec,
    last: Option<(Spec, CorpusMesh<M>, CheckReport)>,
) -> Counterexample<Spec, M> {
    match last.filter(|(failed, _, _)| *failed == spec) {
        Some((spec, mesh, report)) => {
            let reproduced = !check(&mesh.mesh).passed();
            Counterexample {
                spec,
                mesh,
                report,
                reproduced,
            }
        }
        None => {
            let mesh = build(&spec).expect("a description that failed was built before");
            let report = check(&mesh.mesh);
            let reproduced = !report.passed();
            Counterexample {
                spec,
                mesh,
                report,
                reproduced,
            }
        }
    }
}

/// What the test closure of [`run_property`] accumulates.
struct RunState<Spec, M> {
    cases_passed: u32,
    shrinking: bool,
    shrink_steps: u32,
    worst: BTreeMap<String, CheckOutcome>,
    /// The last failing case: its description, mesh and report.
    last_failure: Option<(Spec, CorpusMesh<M>, CheckReport)>,
    /// A builder or check stopped the run ([`StopRun`]).
    stopped: bool,
}

impl<Spec, M> Default for RunState<Spec, M> {
    fn default() -> Self {
        Self {
            cases_passed: 0,
            shrinking: false,
            shrink_steps: 0,
            worst: BTreeMap::new(),
            last_failure: None,
            stopped: false,
        }
    }
}

impl<Spec, M> RunState<Spec, M> {
    /// Counts a passing case and keeps, per check, its worst outcome.
    fn record(&mut self, report: &CheckReport) {
        self.cases_passed += 1;
        for outcome in &report.outcomes {
            let replace = match self.worst.get(&outcome.name) {
                None => true,
                Some(kept) => badness(outcome) > badness(kept),
            };
            if replace {
                self.worst.insert(outcome.name.clone(), outcome.clone());
            }
        }
    }
}

/// How close an outcome came to failing: `measured / limit` (the measured value itself for a
/// zero limit; `limit − measured` for a lower bound; −1 for skipped ones, so any measurement
/// replaces them).
fn badness(outcome: &CheckOutcome) -> f64 {
    match outcome.status {
        CheckStatus::Skipped | CheckStatus::NotApplicable => -1.0,
        _ if outcome.comparison == Comparison::AtLeast => outcome.limit - outcome.measured,
        _ if outcome.limit > 0.0 => outcome.measured / outcome.limit,
        _ => outcome.measured,
    }
}
