//! Fuzzes the OBJ reader: any bytes must give a mesh or a typed error, never a panic.
#![no_main]

#[path = "mesh_reader.rs"]
mod mesh_reader;

use libfuzzer_sys::fuzz_target;
use tvf_core::io::MeshFormat;

fuzz_target!(|data: &[u8]| mesh_reader::check_mesh_reader(data, MeshFormat::Obj, "fuzz.obj"));
