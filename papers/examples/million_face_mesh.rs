//! Writes the generated genus-2 surface of the scale benchmark: `genus_surface(2, r)` at the
//! smallest even resolution `r` with at least `--faces N` faces (default 1,000,000), as an OBJ
//! file, and prints its counts. The basis of the benchmark is then computed by the command line,
//! so that its time and peak memory are those of `tvf basis`:
//!
//! ```text
//! cargo run --release -p tvf-papers --example million_face_mesh -- target/genus2-1m.obj
//! /usr/bin/time -v target/release/tvf basis target/genus2-1m.obj -k 1000 -o target/genus2-1m.tvfb
//! ```

use std::process::ExitCode;
use tvf_core::generate::genus_surface;
use tvf_core::io::write_obj;

const GENUS: usize = 2;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let mut output = None;
    let mut faces = 1_000_000usize;
    let usage = "usage: million_face_mesh [--faces N] OUTPUT.obj";
    while let Some(arg) = args.next() {
        if arg == "-h" || arg == "--help" {
            println!("{usage}");
            return ExitCode::SUCCESS;
        }
        if arg.starts_with('-') && arg != "--faces" {
            eprintln!("million_face_mesh: unknown option {arg}\n{usage}");
            return ExitCode::FAILURE;
        }
        if output.is_some() && arg != "--faces" {
            eprintln!("million_face_mesh: one output file only ({arg} is a second)\n{usage}");
            return ExitCode::FAILURE;
        }
        if arg == "--faces" {
            match args.next().and_then(|v| v.parse().ok()) {
                Some(n) => faces = n,
                None => {
                    eprintln!("--faces needs a number of faces");
                    return ExitCode::FAILURE;
                }
            }
        } else {
            output = Some(arg);
        }
    }
    let Some(output) = output else {
        eprintln!("{usage}");
        return ExitCode::FAILURE;
    };
    // Faces grow with the square of the resolution: start from the estimate and step up.
    let at_eight = genus_surface(GENUS, 8).face_count() as f64;
    let mut resolution = ((8.0 * (faces as f64 / at_eight).sqrt()) as usize / 2 * 2).max(2);
    let mut mesh = genus_surface(GENUS, resolution);
    while mesh.face_count() < faces {
        resolution += 2;
        mesh = genus_surface(GENUS, resolution);
    }
    if let Err(e) = write_obj(&output, &mesh) {
        eprintln!("{output}: {e}");
        return ExitCode::FAILURE;
    }
    println!(
        "{output}: genus {GENUS}, resolution {resolution}, {} vertices, {} faces",
        mesh.vertex_count(),
        mesh.face_count()
    );
    ExitCode::SUCCESS
}
