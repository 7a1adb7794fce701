//! # polbrdf — the simplified Maxwell–Beard polarimetric BRDF
//!
//! The model of Zhuansun et al., *Infrared and Laser Engineering* 44(3), 2015, implemented
//! exactly as pinned by the project's `docs/model.md`. Equation numbers in the documentation are
//! the paper's. The library works in radians; files and the command line use degrees.
//!
//! One call path leads to every number:
//! [`Geometry`] → [`Geometry::angle_variables`] (θN, β, ΦN, η_i, η_r; spec §1, §3) →
//! [`Material::evaluate_angles`]: [`Distribution::eval`] (eq. 4) × [`Fresnel::reflectance`]
//! (eq. 1) × [`Shadowing::eval`] (eq. 3) → surface term (eq. 1 or 6), [`Jones::microfacet`]
//! (eq. 11) → [`Mueller::from_jones`] → `F` (eq. 9 corrected), [`Mueller::apply`] (eq. 12),
//! [`Stokes::dolp`] (eq. 13).
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

pub mod albedo;
pub mod batch;
pub mod check;
pub mod contrast;
pub mod distribution;
pub mod error;
pub mod fresnel;
pub mod geometry;
pub mod jones;
pub mod kernel;
pub mod linalg;
pub mod model;
pub mod mueller;
pub mod presets;
pub mod quadrature;
pub mod sample;
pub mod shadowing;

pub use albedo::{directional_hemispherical, Albedo};
pub use batch::GeometryBatch;
pub use check::{physical_validity, CheckGrid, ValidityReport};
pub use contrast::{Contrast, ContrastSample, Illumination, RankOptions, Ranking, ViewGrid};
pub use distribution::Distribution;
pub use error::{Error, Result};
pub use fresnel::{Fresnel, RefractiveIndex};
pub use geometry::{AngleVariables, Geometry};
pub use jones::Jones;
pub use model::{Evaluation, Form, Material, MaterialSpec, SurfaceTerms};
pub use mueller::{Mueller, Stokes};
pub use presets::preset;
pub use shadowing::{AzimuthTerm, Shadowing};

/// The README's code blocks, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
