//! `tvf compare --corpus FOLDER --scheduler ADDRESS`: the mesh × entry runs on a Dask cluster.
//! Dask is Python, so the command line runs the Python package's driver, `python3 -m
//! tvf.corpus` (the interpreter named by `TVF_PYTHON`, else `python3`), which submits one task
//! per run to the scheduler and prints the rows as JSON with the keys of
//! [`CorpusRun`]; its progress goes to stderr as it comes. The rows are then summarised as the
//! local runs are. The workers compute with the package's built-in catalog, so entries of a
//! catalog of one's own (`examples/own-discretization`) run on local threads only.

use super::compare_corpus::{CorpusOptions, CorpusRun};
use anyhow::{bail, Context, Result};
use std::process::{Command, Stdio};

/// The interpreter that runs the driver: `TVF_PYTHON`, else `python3`.
fn python() -> String {
    std::env::var("TVF_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// Runs every mesh × entry of `options` on the Dask cluster at `address`.
pub fn runs_on_cluster(options: &CorpusOptions, address: &str) -> Result<Vec<CorpusRun>> {
    if options.triangulate {
        bail!("--triangulate: not available with --scheduler (the workers load the meshes as they are)");
    }
    let interpreter = python();
    let mut command = Command::new(&interpreter);
    command
        .args(["-m", "tvf.corpus"])
        .arg(options.folder)
        .args(["-k", &options.count.to_string()])
        .args(["--boundary", options.boundary.name()])
        .args(["--scheduler", address]);
    for id in options.ids {
        command.args(["--discretization", id]);
    }
    let output = command
        .stdin(Stdio::null())
        .stderr(Stdio::inherit())
        .output()
        .with_context(|| {
            format!(
                "--scheduler: cannot start {interpreter} (the Dask driver is the Python package's \
                 tvf.corpus: install it with `pip install ./python`, or name the interpreter \
                 that has it in TVF_PYTHON)"
            )
        })?;
    if !output.status.success() {
        bail!(
            "--scheduler {address}: {interpreter} -m tvf.corpus failed ({}; its message is \
             above). It needs the tvf package with dask[distributed] (`pip install \
             './python[dask]'`) and a scheduler at that address",
            output.status
        );
    }
    serde_json::from_slice(&output.stdout).with_context(|| {
        format!("--scheduler {address}: {interpreter} -m tvf.corpus printed no table of runs")
    })
}
