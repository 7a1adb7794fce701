//! Numerical infrastructure below the physics: the elementary-function backends every formula
//! is written with ([`math`]), Gauss–Legendre quadrature ([`quadrature`]), small dense linear
//! algebra ([`linalg`]) and the project's one random generator ([`sample`]). Nothing here knows
//! about light.

pub mod linalg;
pub mod math;
pub(crate) mod math32;
pub mod quadrature;
pub mod sample;
