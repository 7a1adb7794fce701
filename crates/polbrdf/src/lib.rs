//! # polbrdf — the simplified Maxwell–Beard polarimetric BRDF
//!
//! The model of Zhuansun et al., *Infrared and Laser Engineering* 44(3), 2015, implemented
//! exactly as pinned by the project's `docs/model.md`. Equation numbers in the documentation are
//! the paper's. The library works in radians; files and the command line use degrees.
//!
//! The crate is layered; each layer imports only those above it in this list (the project's
//! `scripts/check-layers` checks it):
//!
//! | layer | holds |
//! |---|---|
//! | [`error`] | the error type (a leaf) |
//! | [`names`] | the closed sets of names: parsing and messages from each enum's `ALL` |
//! | [`numeric`] | elementary-function backends, quadrature, linear algebra, the random generator |
//! | [`optics`] | Stokes, Mueller, Jones, Fresnel — the psps basis and its conventions |
//! | [`geometry`] | directions, a geometry, the angle variables in closed form, batches of geometries |
//! | [`model`] | parameters and their validation, D, SO, the surface and volume terms, the one-geometry evaluation |
//! | [`engine`] | the batch engine: the same formulas over blocks, vectorized, in parallel |
//! | [`analysis`] | albedo, physical validity, target-versus-background contrast — all on the engine |
//!
//! One call path leads to every number: [`Material::evaluate`] (the readable one-geometry path,
//! with every intermediate) calls one function per equation — its module documentation
//! ([`model::material`]) lists them — and the engine ([`engine::Engine`]) calls the same
//! functions across blocks.
//!
//! ```
//! use polbrdf::{Geometry, MaterialSpec};
//! let paint = MaterialSpec::new(1.65, 15.0).build()?;               // n = 1.65, σ = 15°
//! let g = Geometry::from_degrees(60.0, 0.0, 60.0, 180.0)?;           // specular at 60°
//! let e = paint.evaluate(&g);
//! println!("f = {:.4} sr⁻¹, DoLP = {:.3}", e.brdf(), e.dolp());
//! assert!(e.dolp() > 0.9);                                          // near Brewster
//! # Ok::<(), polbrdf::Error>(())
//! ```

#![warn(missing_docs)]

pub mod analysis;
pub mod engine;
pub mod error;
pub mod geometry;
pub mod model;
pub mod names;
pub mod numeric;
pub mod optics;

pub use analysis::{
    directional_hemispherical, physical_validity, Albedo, Band, CheckGrid, Contrast,
    ContrastSample, Illumination, RankOptions, Ranking, Spectrum, ValidityReport, ViewGrid,
};
pub use engine::batch;
pub use engine::{Engine, IndexColumns};
pub use error::{AngleProblem, Error, Result};
pub use geometry::{AngleVariables, Batch, DirectionBatch, Geometry, GeometryBatch, Unvalidated};
pub use model::presets::{self, preset};
pub use model::{
    AzimuthTerm, Distribution, Evaluation, Form, Material, MaterialSpec, Shadowing, SurfaceTerms,
};
pub use numeric::sample;
pub use optics::fresnel::{Fresnel, RefractiveIndex};
pub use optics::jones::Jones;
pub use optics::mueller::Mueller;
pub use optics::stokes::Stokes;

/// The README's code blocks, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The largest azimuth magnitude accepted anywhere (degrees; `MAX_AZIMUTH_DEG.to_radians()` in
/// radians): 10⁸° keeps the angle modulo 360° to about 1e-8°, while at 1e17° no digit of it is
/// left. Beyond it an azimuth is an error ([`AngleProblem::AzimuthTooLarge`]).
pub const MAX_AZIMUTH_DEG: f64 = 1e8;
