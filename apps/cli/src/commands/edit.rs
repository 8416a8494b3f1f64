//! `tvf edit`: the interactive spline editor in the browser (a local server on 127.0.0.1).

use super::spectral_inputs::{open_basis_blocks, readable_in_blocks};
use crate::basis_source::BasisSource;
use crate::context::RunContext;
use crate::mesh_input::MeshInput;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;
use std::sync::Arc;
use tvf_core::discretization::HodgeOperators;
use tvf_core::ValidationWarning;
use tvf_design::ConstraintSet;
use tvf_design::ReducedBasis;
use tvf_editor::{Editor, EditorServer, EditorSetup};

/// Arguments of `tvf edit`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf edit bunny.obj   (then open the printed http://127.0.0.1:PORT address)\n  \
tvf edit --example bumpy-torus -k 300 --constraints constraints.json --port 8080\n\n\
The editor works in the basis of the K lowest eigenfields (-k K, the paper's d; computed once and cached, \
K ≥ n1 (the field dimension: 2F for face fields, E for DEC/Whitney): the complete basis) or of a --basis file, with the discretization of --discretization (or of the basis file)."
)]
pub struct EditArgs {
    #[command(flatten)]
    input: MeshInput,
    #[command(flatten)]
    basis: BasisSource,
    /// Constraints (and ω) to start from (JSON, see README "Constraint files").
    #[arg(long, value_name = "C.json")]
    constraints: Option<PathBuf>,
    /// Port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = 0)]
    port: u16,
}

/// Runs `tvf edit` until the process is stopped.
pub fn run(args: EditArgs, context: &RunContext) -> Result<()> {
    let loaded = args.input.load()?;
    let mesh = loaded.mesh;
    // Every input is checked before the basis is computed: the constraints against the
    // discretization they will be compiled for.
    let complex = args
        .basis
        .options
        .discretization(context.catalog(), &mesh, &args.input)?;
    // The editor draws fields in space: a complex that cannot sample them is refused now, not
    // after its basis is computed.
    complex
        .require_sampling()
        .context("the editor draws fields as vectors in space")?;
    let constraints = args
        .constraints
        .as_deref()
        .map(|path| ConstraintSet::load_for(path, &mesh, complex.as_ref()))
        .transpose()?;
    // A basis file of eigenfunctions is read on demand (rows when constraints touch them, the
    // editor's single-precision copy in one pass); any other basis is loaded and copied once.
    let (basis, complex) = match args.basis.options.basis.as_deref() {
        Some(path) if readable_in_blocks(path)? => {
            // The check at opening shows its progress; the passes of the session (rows as
            // constraints are added, the f32 copy) would print lines at every edit: not shown.
            let blocks = open_basis_blocks(path, &mesh, complex)?.with_observer(None);
            let complex =
                args.basis
                    .options
                    .discretization(context.catalog(), &mesh, &args.input)?;
            (ReducedBasis::on_demand(Arc::new(blocks))?, complex)
        }
        _ => {
            let computed_with = args.basis.options.basis.is_none().then_some(complex);
            let resolved = args.basis.options.resolve_with(
                context.catalog(),
                &mesh,
                &args.input,
                args.basis.size(),
                computed_with,
            )?;
            let basis = ReducedBasis::from_spectral(&resolved.basis)?;
            (basis, resolved.discretization)
        }
    };
    println!(
        "mesh            {} ({} faces), basis of {} fields, {}",
        args.input.label(),
        mesh.face_count(),
        basis.len(),
        complex.id()
    );
    // Vertex numbers in constraints count the referenced vertices only: say what was dropped.
    for warning in &loaded.report.warnings {
        if let ValidationWarning::UnreferencedVertices { .. } = warning {
            println!(
                "mesh            {}: {warning}; vertex numbers count the referenced vertices",
                args.input.label()
            );
        }
    }
    let editor = Editor::start(EditorSetup {
        mesh,
        basis,
        constraints,
        basis_size: None,
        complex,
    })
    .with_context(|| match &args.constraints {
        Some(path) => format!("starting the editor with {}", path.display()),
        None => "starting the editor".to_string(),
    })?;
    let server = EditorServer::start(editor, args.port)?;
    println!(
        "tvf edit: open {} in a browser (Ctrl+C stops the server)",
        server.url()
    );
    server.join();
    Ok(())
}
