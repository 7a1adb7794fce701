//! What is computed from many evaluations, all through the engine (`crate::engine`):
//! directional–hemispherical reflectance ([`albedo`]), physical validity of a parameter set
//! ([`check`]), target against background over the viewing hemisphere ([`contrast`]), bands of
//! wavelengths ([`spectral`]), polarized thermal emission ([`emission`], by the facet-normal
//! quadrature of [`facets`]), Planck's law ([`thermal`]), skies and the sky integral ([`sky`]),
//! the observed Stokes radiance of a scene ([`scene`]), and whether a sensor detects a target
//! against its background and from how far ([`detection`]).
//! Nothing below this layer imports it.

pub mod albedo;
pub mod check;
pub mod contrast;
pub mod detection;
pub mod emission;
pub mod facets;
pub mod scene;
pub mod sky;
pub mod spectral;
pub mod sun_position;
pub mod thermal;

pub use albedo::{directional_hemispherical, Albedo};
pub use check::{physical_validity, CheckGrid, ValidityReport};
pub use contrast::{Contrast, ContrastSample, Illumination, RankOptions, Ranking, ViewGrid};
pub use emission::{emissivities, emissivity, Emissivity};
pub use scene::{observed_radiance, Atmosphere, Radiance, SkyModel, ThermalScene};
pub use spectral::{Band, Spectrum};
