//! tvf-papers' integration tests: one module per reproduced paper, every piece on generated
//! meshes at small sizes (they pass without `../shared`).

mod brandt2017;
