//! The two eigenproblems of a Whitney basis against the lumped ones of the same mesh, each
//! kind timed in a process of its own, over several rounds:
//!
//! - lumped: cotan stiffness with the barycentric lumped mass (vertices) and the
//!   Crouzeix–Raviart stiffness with its lumped mass (edges), solved together;
//! - Galerkin: cotan stiffness with the consistent P1 mass (vertices) and the mixed co-exact
//!   pencil `d1 W⁻¹ d1ᵀ ψ = μ N ψ` (`W` the Whitney 1-form mass on edges, `d1` the face–edge
//!   incidence, `N` the face areas), solved together.
//!
//! Prints each round's wall and processor seconds (the lumped and the Galerkin process in
//! alternating order), then the figures `docs/performance.md` cites: the Galerkin / lumped ratio
//! of the median wall times (and the range of the rounds' ratios), the ratio of the median
//! processor times, and the machine's load before and after. The first round also prints each
//! solve's phases and residuals, and one factorization and one blocked solve (8 right-hand
//! sides) of each kind of shifted matrix, for where the time goes.
//!
//! `cargo run --release -p tvf-solvers --example galerkin_bench -- [MESH.obj] [--k K]
//! [--runs N] [--galerkin-only]` (default: `../shared/meshes/bunny-closed.obj`, `K = 500` per
//! problem, 3 rounds; `--galerkin-only` runs the Galerkin problems once in this process, e.g.
//! for a profile).

#[allow(dead_code)]
mod bench_runs;
#[allow(dead_code)]
mod mesh_matrices;

use bench_runs::{median, range, run_child, Timing};
use faer::sparse::SparseColMat;
use faer::Mat;
use std::path::PathBuf;
use std::time::Instant;
use tvf_solvers::convert::{edge_schur_pattern, shifted_upper_triangle};
use tvf_solvers::{
    lowest_eigenpairs_of, process_cpu_seconds, EigenOptions, EigenRequest, Eigenpairs, MassMatrix,
    Pencil, SolverStatistics, SparseLdlt,
};

/// The internal flag of a child process: `--only lumped` or `--only galerkin`.
const ONLY: &str = "--only";

fn main() {
    let mut args = std::env::args().skip(1);
    let mut mesh: Option<PathBuf> = None;
    let (mut k, mut runs) = (500, 3);
    let mut only: Option<String> = None;
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--k" => k = args.next().and_then(|s| s.parse().ok()).unwrap_or(k),
            "--runs" => runs = args.next().and_then(|s| s.parse().ok()).unwrap_or(runs),
            "--galerkin-only" => only = Some("galerkin".into()),
            ONLY => only = args.next(),
            other => mesh = Some(PathBuf::from(other)),
        }
    }
    let Some(mesh) = mesh.or_else(|| mesh_matrices::shared_mesh("bunny-closed.obj")) else {
        println!("galerkin_bench: ../shared/meshes not found, nothing to do");
        return;
    };
    match only.as_deref() {
        Some(kind) => {
            if let Err(e) = solve_one(&mesh, k, kind) {
                eprintln!("galerkin_bench: {e}");
                std::process::exit(1);
            }
        }
        None => {
            if let Err(e) = compare(&mesh, k, runs.max(1)) {
                eprintln!("galerkin_bench: {e}");
                std::process::exit(1);
            }
        }
    }
}

/// `runs` rounds of one lumped and one Galerkin process (alternating which goes first), and
/// the medians and ratios over them.
fn compare(mesh: &std::path::Path, k: usize, runs: usize) -> Result<(), String> {
    let load_before = bench_runs::load();
    let child = |kind: &str| {
        run_child(&[
            mesh.display().to_string(),
            "--k".into(),
            k.to_string(),
            ONLY.into(),
            kind.into(),
        ])
    };
    let (mut lumped, mut galerkin): (Vec<Timing>, Vec<Timing>) = (Vec::new(), Vec::new());
    for round in 0..runs {
        let order = if round % 2 == 0 {
            ["lumped", "galerkin"]
        } else {
            ["galerkin", "lumped"]
        };
        for kind in order {
            let (timing, output) = child(kind)?;
            if round == 0 {
                print!("{output}");
            }
            match kind {
                "lumped" => lumped.push(timing),
                _ => galerkin.push(timing),
            }
        }
        let (l, g) = (lumped[round], galerkin[round]);
        println!(
            "round {}: lumped {:.2} s wall, {:.2} s processor; Galerkin {:.2} s wall, {:.2} s \
             processor; wall ratio {:.3}",
            round + 1,
            l.wall,
            l.cpu,
            g.wall,
            g.cpu,
            g.wall / l.wall
        );
    }
    let walls = |t: &[Timing]| t.iter().map(|t| t.wall).collect::<Vec<_>>();
    let cpus = |t: &[Timing]| t.iter().map(|t| t.cpu).collect::<Vec<_>>();
    let ratios: Vec<f64> = galerkin
        .iter()
        .zip(&lumped)
        .map(|(g, l)| g.wall / l.wall)
        .collect();
    let (lo, hi) = range(&ratios);
    let (g_wall, l_wall) = (median(&walls(&galerkin)), median(&walls(&lumped)));
    let (g_cpu, l_cpu) = (median(&cpus(&galerkin)), median(&cpus(&lumped)));
    println!(
        "Galerkin / lumped, {runs} rounds, one process each: wall ratio {:.3} ({lo:.3}–{hi:.3}), \
         medians {g_wall:.2} s and {l_wall:.2} s; processor ratio {:.3} (medians {g_cpu:.2} s and \
         {l_cpu:.2} s); load {load_before} → {}",
        g_wall / l_wall,
        g_cpu / l_cpu,
        bench_runs::load()
    );
    Ok(())
}

/// One timed solve of the `kind` ("lumped" or "galerkin") problems of `mesh` in this process,
/// its report and its [`Timing`] line.
fn solve_one(mesh: &std::path::Path, k: usize, kind: &str) -> Result<(), String> {
    let (positions, faces) = mesh_matrices::read_obj(mesh)?;
    let cotan = mesh_matrices::cotan(&positions, &faces);
    let options = EigenOptions::default();
    match kind {
        "lumped" => {
            let cr = mesh_matrices::crouzeix_raviart(&positions, &faces);
            let start = Instant::now();
            let cpu = process_cpu_seconds();
            let (vertex, edge) = (
                Pencil::new(&cotan.stiffness, &cotan.mass).expect("valid pencil"),
                Pencil::new(&cr.stiffness, &cr.mass).expect("valid pencil"),
            );
            let lumped = solve(&[&vertex, &edge], k, &options);
            let timing = Timing {
                wall: start.elapsed().as_secs_f64(),
                cpu: process_cpu_seconds() - cpu,
            };
            report(
                "lumped (cotan, Crouzeix–Raviart)",
                (timing.wall, timing.cpu),
                &lumped,
            );
            where_the_time_goes_lumped(&cr);
            bench_runs::report_child(timing);
        }
        "galerkin" => {
            let consistent = mesh_matrices::consistent_mass(&positions, &faces);
            let whitney = mesh_matrices::whitney(&positions, &faces);
            println!(
                "{}: {} vertices, {} edges, {} faces, k = {k} per problem",
                mesh.display(),
                cotan.mass.len(),
                whitney.edges.len(),
                faces.len()
            );
            let start = Instant::now();
            let cpu = process_cpu_seconds();
            let exact = Pencil::with_mass(&cotan.stiffness, MassMatrix::Sparse(&consistent))
                .expect("valid pencil");
            let exact_setup = start.elapsed().as_secs_f64();
            let coexact = Pencil::mixed(
                &whitney.mass,
                &whitney.d1,
                MassMatrix::Diagonal(&whitney.face_areas),
            )
            .expect("valid pencil");
            let setup = start.elapsed().as_secs_f64();
            let galerkin = solve(&[&exact, &coexact], k, &options);
            let timing = Timing {
                wall: start.elapsed().as_secs_f64(),
                cpu: process_cpu_seconds() - cpu,
            };
            println!(
                "  Galerkin pencils made (Cholesky of M and W, Lanczos bounds) in {setup:.2} s \
                 ({exact_setup:.2} s the consistent-mass one)"
            );
            report(
                "Galerkin (consistent P1, mixed Whitney)",
                (timing.wall, timing.cpu),
                &galerkin,
            );
            where_the_time_goes_galerkin(&whitney);
            bench_runs::report_child(timing);
        }
        other => return Err(format!("unknown kind {other:?} (lumped or galerkin)")),
    }
    Ok(())
}

fn solve(pencils: &[&Pencil<'_>], k: usize, options: &EigenOptions<'_>) -> Vec<Eigenpairs> {
    let requests: Vec<EigenRequest<'_, '_>> = pencils
        .iter()
        .enumerate()
        .map(|(i, pencil)| EigenRequest {
            pencil,
            count: k,
            top: None,
            seed: 17 + i as u64,
        })
        .collect();
    let mut solution = lowest_eigenpairs_of(&requests, options).expect("eigensolver");
    if let Some(first) = solution.pairs.first_mut() {
        first.statistics = solution.statistics;
    }
    solution.pairs
}

fn report(name: &str, (seconds, cpu): (f64, f64), pairs: &[Eigenpairs]) {
    let statistics: SolverStatistics = pairs[0].statistics;
    println!("{name}: {seconds:.2} s wall, {cpu:.2} s processor");
    print!("{}", statistics.phase_table());
    for (i, pair) in pairs.iter().enumerate() {
        let mut order: Vec<usize> = (0..pair.values.len()).collect();
        order.sort_by(|&a, &b| pair.field_residuals[b].total_cmp(&pair.field_residuals[a]));
        for &j in order.iter().take(4) {
            println!(
                "    pair {j}: λ {:.3e} field residual {:.1e} floor {:.1e}",
                pair.values[j], pair.field_residuals[j], pair.field_residual_floors[j]
            );
        }
        let worst = |v: &[f64]| v.iter().fold(0.0f64, |m, r| m.max(*r));
        let above_floor = pair
            .field_residuals
            .iter()
            .zip(&pair.field_residual_floors)
            .filter(|(r, f)| **r > 1e-9 && **r > 10.0 * **f)
            .count();
        println!(
            "  problem {i}: λ ∈ [{:.3e}, {:.3e}], max residual {:.1e}, max field residual {:.1e} \
             (max floor {:.1e}; {above_floor} pairs above 1e-9 and 10 × their floor)",
            pair.values.first().copied().unwrap_or(0.0),
            pair.values.last().copied().unwrap_or(0.0),
            worst(&pair.residuals),
            worst(&pair.field_residuals),
            worst(&pair.field_residual_floors)
        );
    }
}

/// Shift of the factorizations of [`where_the_time_goes_lumped`] and
/// [`where_the_time_goes_galerkin`].
const SIGMA: f64 = 1e-3;

/// Fill, factorization and blocked-solve times of `A − σM` (Crouzeix–Raviart, lumped) at a
/// small positive shift.
fn where_the_time_goes_lumped(cr: &mesh_matrices::StiffnessMass) {
    let upper = shifted_upper_triangle(&cr.stiffness, &cr.mass, SIGMA).expect("valid");
    time_factor("Crouzeix–Raviart A − σM", &upper);
}

/// The same for the matrix the mixed pencil factors at a shift: `C(σ) = d1ᵀ N⁻¹ d1 − σW` on the
/// edges (`N` the face areas).
fn where_the_time_goes_galerkin(whitney: &mesh_matrices::Whitney) {
    let pattern = edge_schur_pattern(&whitney.mass, &whitney.d1, &whitney.face_areas)
        .expect("a valid mixed pencil");
    time_factor("Whitney edge Schur complement C(σ)", &pattern.at(SIGMA));
}

fn time_factor(name: &str, upper: &SparseColMat<usize, f64>) {
    let start = Instant::now();
    let mut ldlt = SparseLdlt::new(upper.as_ref()).expect("factors");
    let analyse = start.elapsed().as_secs_f64();
    ldlt.set_parallelism(faer::Par::Seq);
    let start = Instant::now();
    ldlt.refactor(upper.as_ref()).expect("refactors");
    let numeric = start.elapsed().as_secs_f64();
    let n = upper.nrows();
    let mut rhs = Mat::from_fn(n, 8, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
    let start = Instant::now();
    ldlt.solve_in_elimination_order(rhs.as_mut());
    let solve = start.elapsed().as_secs_f64();
    println!(
        "  {name}: n = {n}, nnz(upper) = {}, nnz(L) = {}, analyse+factor {analyse:.3} s, \
         refactor {numeric:.3} s, solve of 8 {:.1} ms",
        upper.val().len(),
        ldlt.factor_len(),
        1e3 * solve
    );
}
