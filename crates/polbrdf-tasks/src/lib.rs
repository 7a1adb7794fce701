//! # polbrdf-tasks — one library API per user job
//!
//! The layer between the pure core (`polbrdf`: physics, engine, analysis) with the file formats
//! (`polbrdf-io`) and fitting (`polbrdf-fit`) below it, and the adapters above it: the `polbrdf`
//! command line and the Python module. Each module is one job. A job takes a *request* of plain
//! Rust values (already parsed, not yet validated), validates it, computes, and returns plain Rust
//! values (numbers, tables, JSON-ready summaries). No argument parsing, no Python, no plotting, no
//! printing: the adapters parse, call and render, so the CLI and Python give the same numbers.
//!
//! Dependencies point one way: `polbrdf` ← `polbrdf-io`, `polbrdf-fit` ← `polbrdf-tasks` ←
//! `polbrdf-cli`, the Python module. Nothing below this crate imports it.

pub mod albedo;
pub mod check;
pub mod contrast;
mod contrast_json;
pub mod daytime;
pub mod detect;
pub mod emission;
mod error;
pub mod explore;
pub mod fit;
pub mod fit_covariance;
pub mod frame;
pub mod hemisphere;
pub mod limits;
pub mod lut;
pub mod pbsdf;
pub mod radiance;
pub mod scene;
pub mod spectrum;
pub mod sun;

pub use contrast_json::sky_json;
pub use error::{TaskError, TaskResult};
