//! tvf-core's integration tests: generated meshes, the mesh readers and writers, the malformed
//! file corpus and fuzzing of the readers.

mod generated_meshes;
mod generated_order;
mod generated_surfaces;
mod malformed_inputs;
mod mesh_io;
mod polygon_meshes;
mod reader_fuzz;
