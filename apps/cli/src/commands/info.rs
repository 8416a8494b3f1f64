//! `tvf info`: a mesh report.

use crate::examples::example_mesh;
use anyhow::Result;
use clap::Args;

/// Arguments of `tvf info`.
#[derive(Args)]
pub struct InfoArgs {
    /// A built-in example mesh instead of a file.
    #[arg(long)]
    example: String,
}

/// Prints the report.
pub fn run(args: InfoArgs) -> Result<()> {
    let mesh = example_mesh(&args.example)?;
    println!("vertices       {}", mesh.vertex_count());
    println!("edges          {}", mesh.edge_count());
    println!("faces          {}", mesh.face_count());
    println!("components     {}", mesh.component_count());
    println!("boundary loops {}", mesh.boundary_loops().len());
    println!("genus          {}", mesh.genus());
    println!("closed         {}", mesh.is_closed());
    Ok(())
}
