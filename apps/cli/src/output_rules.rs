//! The output rules every subcommand applies before it computes anything
//! ([`tvf_core::io::check_output`]): the output's folder must exist (tvf never creates a missing
//! parent folder; a folder output itself is created), and the output must not be one of the
//! command's inputs (`tvf render m.obj f.txt -o m.obj` is refused, not a PNG over the mesh).

use crate::mesh_input::MeshInput;
use anyhow::{Context, Result};
use std::path::Path;
use tvf_core::io::StagedFolder;

/// Checks `output` against the rules, with the mesh file of `input` and the given `others`
/// (absent ones skipped) as the inputs.
pub fn check_output(output: &Path, input: &MeshInput, others: &[Option<&Path>]) -> Result<()> {
    let inputs: Vec<&Path> = input
        .mesh
        .as_deref()
        .into_iter()
        .chain(others.iter().flatten().copied())
        .collect();
    Ok(tvf_core::io::check_output(output, &inputs)?)
}

/// [`check_output`] for an output that is one file: moreover not an existing folder
/// ([`tvf_core::io::check_file_output`]).
pub fn check_file_output(output: &Path, input: &MeshInput, others: &[Option<&Path>]) -> Result<()> {
    check_output(output, input, others)?;
    let inputs: Vec<&Path> = Vec::new();
    Ok(tvf_core::io::check_file_output(output, &inputs)?)
}

/// Starts writing the folder output `out` in a temporary sibling
/// ([`tvf_core::io::StagedFolder`]): it appears whole at [`commit`] or not at all.
pub fn stage(out: &Path) -> Result<StagedFolder> {
    StagedFolder::new(out).with_context(|| format!("cannot write the folder {}", out.display()))
}

/// Moves a complete folder output into place.
pub fn commit(staged: StagedFolder) -> Result<()> {
    let out = staged.target().to_path_buf();
    staged
        .commit()
        .with_context(|| format!("cannot write the folder {}", out.display()))
}
