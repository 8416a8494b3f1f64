//! tvf-papers' tests (all of them: the crate has no unit tests): one module per reproduced
//! paper, every piece on generated meshes at small sizes (they pass without `../shared`), and the
//! reports' markdown tables.

mod brandt2017;
mod markdown;
