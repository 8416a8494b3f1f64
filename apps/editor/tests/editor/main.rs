//! tvf-editor's integration tests: the protocol, its security rules, every discretization, a
//! request fuzzer and the page in a real headless browser. `common` serves an editor on a
//! generated mesh and holds a small HTTP client.

mod browser;
mod common;
mod every_discretization;
mod on_demand_basis;
mod protocol;
mod request_fuzz;
mod security;
