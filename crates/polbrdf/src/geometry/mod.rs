//! Geometry (docs/model.md §1, §4): directions and one source/detector geometry
//! ([`mod@direction`]), the model's angle variables in closed form ([`angles`]), many geometries
//! at once ([`batch`]), and other tools' conventions for the same geometry ([`bridges`]).

pub mod angles;
pub mod batch;
pub mod bridges;
pub mod direction;
pub mod rusinkiewicz;
pub(crate) mod vectors;

pub use angles::AngleVariables;
pub use batch::{Batch, DirectionBatch, GeometryBatch, Unvalidated};
pub use direction::{direction, Geometry};
