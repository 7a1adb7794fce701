//! Geometry (docs/model.md §1, §4): directions and one source/detector geometry
//! ([`mod@direction`]), the model's angle variables in closed form ([`angles`]), and many geometries
//! at once ([`batch`]).

pub mod angles;
pub mod batch;
pub mod direction;
pub mod rusinkiewicz;
pub(crate) mod vectors;

pub use angles::AngleVariables;
pub use batch::{Batch, DirectionBatch, GeometryBatch};
pub use direction::{direction, Geometry};
