//! What is computed from many evaluations, all through the engine (`crate::engine`):
//! directional–hemispherical reflectance ([`albedo`]), physical validity of a parameter set
//! ([`check`]), target against background over the viewing hemisphere ([`contrast`]), and bands
//! of wavelengths ([`spectral`]).
//! Nothing below this layer imports it.

pub mod albedo;
pub mod check;
pub mod contrast;
pub mod spectral;

pub use albedo::{directional_hemispherical, Albedo};
pub use check::{physical_validity, CheckGrid, ValidityReport};
pub use contrast::{Contrast, ContrastSample, Illumination, RankOptions, Ranking, ViewGrid};
pub use spectral::{Band, Spectrum};
