//! Unpolarized skies whose radiance depends on the zenith angle at most: one radiance everywhere
//! ([`UniformSky`]) or a tabulated zenith profile ([`ZenithProfile`], [`ProfileSky`]).

use super::SkyRadiance;
use crate::error::{Error, Result};
use crate::optics::stokes::Stokes;

/// An unpolarized sky whose radiance depends on the zenith angle only, tabulated at zenith
/// angles (degrees, strictly increasing, from 0 to 90) and linear between them.
#[derive(Debug, Clone, PartialEq)]
pub struct ZenithProfile {
    zenith_deg: Vec<f64>,
    radiance: Vec<f64>,
}

impl ZenithProfile {
    /// A profile `radiance[j]` at `zenith_deg[j]`.
    ///
    /// # Errors
    /// [`Error::InvalidParameterAt`] for a zenith angle that is not finite, outside
    /// `[0°, 90°]` or not above the previous one, or a radiance that is not finite, ≥ 0 and at
    /// most [`crate::error::MAX_RADIOMETRIC`] (1e150, as every radiance of a scene: beyond it
    /// the sky integral overflows to ∞ and NaN); [`Error::InconsistentParameters`] for fewer
    /// than two rows or a table that does not
    /// start at 0° and end at 90°.
    pub fn new(zenith_deg: Vec<f64>, radiance: Vec<f64>) -> Result<Self> {
        crate::geometry::batch::check_len("radiance", radiance.len(), zenith_deg.len())?;
        if zenith_deg.len() < 2 {
            return Err(Error::InconsistentParameters(
                "a sky profile needs at least two zenith angles".into(),
            ));
        }
        for (i, (&z, &l)) in zenith_deg.iter().zip(&radiance).enumerate() {
            let at = |name, value, reason| Error::InvalidParameterAt {
                name,
                value,
                index: i,
                reason,
            };
            if !(z.is_finite() && (0.0..=90.0).contains(&z)) {
                return Err(at("zenith_deg", z, "must lie in [0°, 90°]"));
            }
            if i > 0 && z <= zenith_deg[i - 1] {
                return Err(at("zenith_deg", z, "zenith angles must increase strictly"));
            }
            if !(l.is_finite() && (0.0..=crate::error::MAX_RADIOMETRIC).contains(&l)) {
                return Err(at("radiance", l, "must be finite, >= 0 and at most 1e150"));
            }
        }
        if zenith_deg[0] != 0.0 || zenith_deg[zenith_deg.len() - 1] != 90.0 {
            return Err(Error::InconsistentParameters(
                "a sky profile must cover the whole sky: from zenith 0° to 90°".into(),
            ));
        }
        Ok(Self {
            zenith_deg,
            radiance,
        })
    }

    /// The radiance at zenith angle `theta` (rad), linear in the table.
    pub fn at(&self, theta: f64) -> f64 {
        let z = theta.to_degrees().clamp(0.0, 90.0);
        let x = &self.zenith_deg;
        let i = x.partition_point(|&v| v <= z).clamp(1, x.len() - 1);
        let t = (z - x[i - 1]) / (x[i] - x[i - 1]);
        self.radiance[i - 1] + (self.radiance[i] - self.radiance[i - 1]) * t
    }

    /// The table's zenith angles (degrees) and radiances.
    pub fn table(&self) -> (&[f64], &[f64]) {
        (&self.zenith_deg, &self.radiance)
    }
}

/// An unpolarized sky of one radiance everywhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformSky(pub f64);

impl SkyRadiance for UniformSky {
    fn stokes(&self, _theta: f64, _phi: f64) -> Stokes {
        Stokes([self.0, 0.0, 0.0, 0.0])
    }
}

/// A [`ZenithProfile`] scaled by `scale` (e.g. the profile as relative values times a
/// radiance), unpolarized.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileSky {
    /// The profile.
    pub profile: ZenithProfile,
    /// A factor applied to it.
    pub scale: f64,
}

impl SkyRadiance for ProfileSky {
    fn stokes(&self, theta: f64, _phi: f64) -> Stokes {
        Stokes([self.scale * self.profile.at(theta), 0.0, 0.0, 0.0])
    }
}
