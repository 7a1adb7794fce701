//! The model (docs/model.md §5–6, §8): a material's parameters ([`spec`]) and their validation
//! (`build`: [`MaterialSpec::build`]), the scalar terms — facet distribution D ([`distribution`], eq. 4), shadowing SO
//! ([`shadowing`], eq. 3), the surface and volume terms ([`terms`], eqs. 1, 6) — and the
//! one-geometry evaluation with every intermediate ([`material`]). Built-in materials:
//! [`presets`].

mod build;
pub mod distribution;
pub mod material;
pub mod presets;
pub mod shadowing;
pub mod spec;
pub mod terms;

pub use distribution::Distribution;
pub use material::{Evaluation, Material, ModelParams, SurfaceTerms};
pub use shadowing::{AzimuthTerm, Shadowing};
pub use spec::{KeyValue, MaterialSpec, SpectralSource, KEYS};
pub use terms::Form;
