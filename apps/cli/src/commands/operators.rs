//! `tvf operators`: writes the paper's matrices of a mesh as Matrix Market files.

use crate::basis_source::{Decomposition, Mass};
use crate::mesh_input::MeshInput;
use crate::output_rules::{check_output, commit, stage};
use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use sprs::CsMat;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use tvf_core::discretization::sparse::diagonal;
use tvf_core::discretization::{FieldSpace, FunctionSpace, HodgeComplex, HodgeOperators};
use tvf_core::io::StagedFolder;
use tvf_core::SurfaceMesh;
use tvf_discretizations::{Conforming, MassLumping, Nonconforming};

/// Arguments of `tvf operators`.
#[derive(Args)]
#[command(
    after_help = "Examples:\n  tvf operators bunny.obj -o matrices/\n  tvf operators --example torus --decomposition nonconforming --mass voronoi -o matrices/"
)]
pub struct OperatorsArgs {
    #[command(flatten)]
    input: MeshInput,
    /// Hodge decomposition whose field matrices (S, B) are written.
    #[arg(long, value_enum, value_name = "NAME", default_value = "conforming")]
    decomposition: Decomposition,
    /// Mass lumping of M and Mstar.
    #[arg(long, value_enum, value_name = "NAME", default_value = "barycentric")]
    mass: Mass,
    /// Output folder (created if missing).
    #[arg(short, long = "output", visible_alias = "out", value_name = "DIR")]
    out: PathBuf,
}

/// Writes G, Gstar, M, Mstar, MX, J, Sc, Sstar, S, B (Matrix Market) and info.json.
pub fn run(args: OperatorsArgs) -> Result<()> {
    check_output(&args.out, &args.input, &[])?;
    let mesh = args.input.load()?.mesh;
    let lumping = args.mass.lumping();
    let staged = stage(&args.out)?;
    match args.decomposition {
        Decomposition::Conforming => {
            let complex = Conforming::new(&mesh, lumping).context("cannot build the operators")?;
            write_all(&complex, &mesh, true, &staged, lumping)?;
        }
        Decomposition::Nonconforming => {
            let complex =
                Nonconforming::new(&mesh, lumping).context("cannot build the operators")?;
            write_all(&complex, &mesh, false, &staged, lumping)?;
        }
    }
    let out = staged.target().to_path_buf();
    commit(staged)?;
    println!(
        "wrote 10 matrices and info.json to {} ({} decomposition, {} mass)",
        out.display(),
        args.decomposition.name(),
        lumping.name()
    );
    Ok(())
}

/// Writes every file; `p1_is_potential` says whether the complex's potential space is P1
/// (conforming) or Crouzeix–Raviart (nonconforming).
fn write_all<H: HodgeComplex>(
    complex: &H,
    mesh: &SurfaceMesh,
    p1_is_potential: bool,
    out: &StagedFolder,
    lumping: MassLumping,
) -> Result<()> {
    let (g, gstar) = (
        complex.potentials().gradient(),
        complex.co_potentials().gradient(),
    );
    let (m, mstar) = (complex.potentials().mass(), complex.co_potentials().mass());
    let (sc, sstar) = (
        complex.potential_stiffness(),
        complex.co_potential_stiffness(),
    );
    let (g, gstar, m, mstar, sc, sstar) = if p1_is_potential {
        (g, gstar, m, mstar, sc, sstar)
    } else {
        (gstar, g, mstar, m, sstar, sc)
    };
    let matrices: [(&str, CsMat<f64>); 10] = [
        ("G", g.clone()),
        ("Gstar", gstar.clone()),
        ("M", diagonal(m)),
        ("Mstar", diagonal(mstar)),
        ("MX", diagonal(complex.m1())),
        ("J", complex.fields().rotation().clone()),
        ("Sc", sc),
        ("Sstar", sstar),
        ("S", complex.dirichlet_energy()),
        ("B", complex.biharmonic_energy()),
    ];
    for (name, matrix) in &matrices {
        write_atomically(out, &format!("{name}.mtx"), |w| {
            sprs::io::write_matrix_market_to_bufwrite(w, matrix)
        })?;
    }
    let info = json!({
        "vertices": mesh.vertex_count(),
        "edges": mesh.edge_count(),
        "faces": mesh.face_count(),
        "components": mesh.component_count(),
        "genus": mesh.genus(),
        "harmonic_dimension": complex.harmonic_dimension(),
        "closed": mesh.is_closed(),
        "decomposition": if p1_is_potential { "conforming" } else { "nonconforming" },
        "mass_lumping": lumping.name(),
        "matrices": {
            "G": "2F x V, gradient of P1 hat functions, pointwise, face frames",
            "Gstar": "2F x E, gradient of Crouzeix-Raviart basis functions (1 - 2 phi_c), pointwise",
            "M": "V x V diagonal, lumped P1 mass (integrated, area)",
            "Mstar": "E x E diagonal, lumped CR mass (integrated, area)",
            "MX": "2F x 2F diagonal, face area twice per face",
            "J": "2F x 2F, +pi/2 rotation per face, (a, b) -> (-b, a)",
            "Sc": "V x V cotan matrix G^T MX G",
            "Sstar": "E x E CR stiffness Gstar^T MX Gstar",
            "S": "2F x 2F field Dirichlet energy of the chosen decomposition; conforming: MX (G M^-1 G^T - J Gstar Mstar^-1 Gstar^T J) MX, nonconforming: (G, M) and (Gstar, Mstar) exchanged",
            "B": "2F x 2F biharmonic energy S MX^-1 S",
        },
        "conventions": {
            "indices": "0-based in this file; Matrix Market files are 1-based",
            "field_layout": "face t stored at rows 2t, 2t+1 in the frame e1 = normalize(p_i1 - p_i0), e2 = n x e1",
            "vertex_order": "as in the input mesh",
            "edge_order": "edges (a, b) with a < b in lexicographic order",
            "face_orientation": "counter-clockwise seen from outside, n = (p1 - p0) x (p2 - p0) normalized",
        },
    });
    let text = serde_json::to_string_pretty(&info)? + "\n";
    write_atomically(out, "info.json", |w| w.write_all(text.as_bytes()))?;
    Ok(())
}

/// Writes the file `name` of the staged folder `out` atomically
/// ([`tvf_core::io::write_atomically`]); errors name the file in the output folder.
fn write_atomically(
    out: &StagedFolder,
    name: &str,
    fill: impl FnOnce(&mut BufWriter<&mut File>) -> std::io::Result<()>,
) -> Result<()> {
    tvf_core::io::write_atomically(&out.path().join(name), fill)
        .with_context(|| format!("cannot write {}", out.target().join(name).display()))
}
