//! Polarization optics, independent of the scattering model: Stokes vectors ([`stokes`]),
//! Mueller matrices ([`mueller`]), Jones matrices ([`jones`]) and Fresnel reflection
//! ([`fresnel`]), spectral indices ([`dispersion`]). Every function states its convention (the psps basis of docs/model.md §2,
//! time dependence `exp(−iωt)`) and its source.

pub mod dispersion;
pub mod fresnel;
pub mod jones;
pub mod mueller;
pub mod stokes;
