//! `tvf`: spectral processing of tangential vector fields on triangle meshes, with the built-in
//! discretizations (the command line is the library `tvf_cli`).

use tvf_discretizations::Catalog;

fn main() -> std::process::ExitCode {
    tvf_cli::run(Catalog::builtin())
}
