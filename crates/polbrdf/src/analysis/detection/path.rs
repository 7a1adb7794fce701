//! The path between the surface and the sensor (detection.md §1): transmittance `τ(R)`, the
//! unpolarized path radiance ("airlight") `L_path(R)`, and the Stokes vector arriving at the
//! sensor, `S'(R) = τ(R)·S + L_path(R)·e0`.
//!
//! Radiances here are in the units of the Stokes vectors they are added to: band-integrated
//! with the sensor's spectral weights (the task layer integrates a spectral horizon radiance,
//! a Planck radiance at the air temperature, or a table's path radiance over the band before
//! building a [`Path`]).

use crate::error::{non_negative, positive, radiometric, Error, Result};
use crate::optics::stokes::Stokes;

/// Koschmieder's constant: `β = KOSCHMIEDER / V` for a meteorological visibility `V`
/// (contrast threshold 2 %, at 550 nm; detection.md §1).
pub const KOSCHMIEDER: f64 = 3.912;

/// The most rows of a path table.
pub const MAX_PATH_ROWS: usize = 100_000;

/// A tabulated path (detection.md §1): `τ` and `L_path` at strictly increasing ranges,
/// linear in `R` between rows and never extrapolated beyond the last row. The path of zero
/// length is exactly known (`τ(0) = 1`, `L_path(0) = 0`), so between `R = 0` and a first row
/// at `R > 0` the table is interpolated from that point.
#[derive(Debug, Clone, PartialEq)]
pub struct PathTable {
    range_m: Vec<f64>,
    transmittance: Vec<f64>,
    path_radiance: Vec<f64>,
}

/// The path (detection.md §1).
#[derive(Debug, Clone, PartialEq)]
pub enum Path {
    /// A homogeneous horizontal path: `τ = exp(−β·R)`, `L_path = (1 − τ)·L_h`.
    Homogeneous {
        /// The extinction coefficient `β` (m⁻¹, ≥ 0).
        extinction_per_m: f64,
        /// The horizon radiance `L_h` (≥ 0, in the units of the signal's Stokes vectors).
        horizon_radiance: f64,
    },
    /// A table of `R, τ, L_path` (e.g. exported from MODTRAN or libRadtran).
    Table(PathTable),
}

impl Path {
    /// No path: `τ = 1`, `L_path = 0` at every range.
    pub fn none() -> Self {
        Path::Homogeneous {
            extinction_per_m: 0.0,
            horizon_radiance: 0.0,
        }
    }

    /// A homogeneous path of extinction `β` (m⁻¹) and horizon radiance `L_h` (detection.md §1).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `extinction_per_m` or `horizon_radiance` when not
    /// finite and ≥ 0.
    pub fn homogeneous(extinction_per_m: f64, horizon_radiance: f64) -> Result<Self> {
        Ok(Path::Homogeneous {
            extinction_per_m: non_negative("extinction_per_m", extinction_per_m)?,
            horizon_radiance: radiometric("horizon_radiance", horizon_radiance)?,
        })
    }

    /// A homogeneous path from the meteorological visibility `V` (m): Koschmieder's
    /// `β = 3.912/V` (detection.md §1; no wavelength scaling, docs/detection.md).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `visibility_m` when not finite and > 0, or
    /// `horizon_radiance` as [`Path::homogeneous`].
    pub fn from_visibility(visibility_m: f64, horizon_radiance: f64) -> Result<Self> {
        let v = positive("visibility_m", visibility_m)?;
        Self::homogeneous(KOSCHMIEDER / v, horizon_radiance)
    }

    /// A tabulated path (detection.md §1), rows `(R, τ, L_path)`.
    ///
    /// # Errors
    /// [`Error::InvalidParameterAt`] naming `range_m` (finite, ≥ 0, strictly increasing),
    /// `transmittance` (in [0, 1]) or `path_radiance` (finite, ≥ 0) and the row;
    /// [`Error::InconsistentParameters`] for no row, or more than [`MAX_PATH_ROWS`].
    pub fn table(rows: &[(f64, f64, f64)]) -> Result<Self> {
        if rows.is_empty() || rows.len() > MAX_PATH_ROWS {
            return Err(Error::InconsistentParameters(format!(
                "a path table needs between 1 and {MAX_PATH_ROWS} rows, got {}",
                rows.len()
            )));
        }
        let at = |name, value, index, reason| Error::InvalidParameterAt {
            name,
            value,
            index,
            reason,
        };
        for (i, &(r, t, l)) in rows.iter().enumerate() {
            if !(r.is_finite() && r >= 0.0) {
                return Err(at("range_m", r, i, "must be finite and >= 0"));
            }
            if i > 0 && r <= rows[i - 1].0 {
                return Err(at(
                    "range_m",
                    r,
                    i,
                    "ranges must increase strictly from row to row",
                ));
            }
            if !(0.0..=1.0).contains(&t) {
                return Err(at("transmittance", t, i, "must lie in [0, 1]"));
            }
            radiometric("path_radiance", l).map_err(|e| e.at_position(Some(i)))?;
        }
        Ok(Path::Table(PathTable {
            range_m: rows.iter().map(|r| r.0).collect(),
            transmittance: rows.iter().map(|r| r.1).collect(),
            path_radiance: rows.iter().map(|r| r.2 + 0.0).collect(),
        }))
    }

    /// The same path with its radiances (`L_h`, or the table's `L_path`) multiplied by
    /// `factor` (a band integral of a spectral radiance taken as constant across the band).
    pub fn with_radiance_scaled(&self, factor: f64) -> Self {
        match self {
            Path::Homogeneous {
                extinction_per_m,
                horizon_radiance,
            } => Path::Homogeneous {
                extinction_per_m: *extinction_per_m,
                horizon_radiance: horizon_radiance * factor,
            },
            Path::Table(t) => Path::Table(PathTable {
                path_radiance: t.path_radiance.iter().map(|l| l * factor).collect(),
                ..t.clone()
            }),
        }
    }

    /// The largest range the path is known at: the last row of a table, `None` (unbounded)
    /// for a homogeneous path.
    pub fn max_range(&self) -> Option<f64> {
        match self {
            Path::Homogeneous { .. } => None,
            Path::Table(t) => t.range_m.last().copied(),
        }
    }

    /// `(τ(R), L_path(R))` (detection.md §1).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming `range_m` for a range that is not finite and ≥ 0, or
    /// beyond the last row of a table (never extrapolated).
    pub fn at(&self, range_m: f64) -> Result<(f64, f64)> {
        non_negative("range_m", range_m)?;
        match self {
            Path::Homogeneous {
                extinction_per_m,
                horizon_radiance,
            } => {
                let tau = (-extinction_per_m * range_m).exp();
                // 1 − τ without cancellation at short range.
                let airlight = -(-extinction_per_m * range_m).exp_m1();
                Ok((tau, airlight * horizon_radiance))
            }
            Path::Table(t) => t.at(range_m),
        }
    }

    /// The Stokes vector at the sensor, `S' = τ(R)·S + L_path(R)·e0` (detection.md §1).
    ///
    /// # Errors
    /// As [`Path::at`].
    pub fn apply(&self, stokes: &Stokes, range_m: f64) -> Result<Stokes> {
        let (tau, l) = self.at(range_m)?;
        let s = stokes.0;
        Ok(Stokes([tau * s[0] + l, tau * s[1], tau * s[2], tau * s[3]]))
    }
}

impl PathTable {
    /// The rows `(R, τ, L_path)`.
    pub fn rows(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.range_m
            .iter()
            .zip(&self.transmittance)
            .zip(&self.path_radiance)
            .map(|((r, t), l)| (*r, *t, *l))
    }

    /// Linear interpolation in `R`, from `(0, 1, 0)` below the first row; an error beyond the
    /// last row.
    fn at(&self, range_m: f64) -> Result<(f64, f64)> {
        let last = *self.range_m.last().expect("a table has rows");
        if range_m > last {
            return Err(Error::InvalidParameter {
                name: "range_m",
                value: range_m,
                reason: "beyond the last row of the path table (a table is never extrapolated)",
            });
        }
        let i = self.range_m.partition_point(|&r| r < range_m);
        let (r0, t0, l0) = match i {
            0 => (0.0, 1.0, 0.0),
            _ => (
                self.range_m[i - 1],
                self.transmittance[i - 1],
                self.path_radiance[i - 1],
            ),
        };
        let (r1, t1, l1) = (
            self.range_m[i],
            self.transmittance[i],
            self.path_radiance[i],
        );
        if r1 == r0 {
            return Ok((t1, l1));
        }
        let w = (range_m - r0) / (r1 - r0);
        Ok((t0 + w * (t1 - t0), l0 + w * (l1 - l0)))
    }
}

/// The horizon radiance of a homogeneous path, as a scene file gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Horizon {
    /// A spectral radiance (W·m⁻²·sr⁻¹·µm⁻¹), constant across the band.
    Radiance(f64),
    /// The air temperature (K): `L_h = B_λ(λ, T_air)` (thermal infrared).
    AirTemperature(f64),
}

/// The path as a scene file gives it (`[path]`, docs/detection.md): before the band integral.
#[derive(Debug, Clone, PartialEq)]
pub enum PathSpec {
    /// Homogeneous: extinction (m⁻¹) and horizon radiance.
    Homogeneous {
        /// `β` (m⁻¹).
        extinction_per_m: f64,
        /// `L_h`.
        horizon: Horizon,
    },
    /// A table whose path radiance is a spectral radiance constant across the band.
    Table(Path),
}

impl PathSpec {
    /// The path in the units of signals integrated on `nodes` `(λ, weight)`
    /// ([`crate::Spectrum::integral_nodes`]): `L_h·Σw`, `Σ w·B_λ(λ, T_air)`, or the table's
    /// `L_path·Σw` (detection.md §1).
    ///
    /// # Errors
    /// As [`Path::homogeneous`]; [`Error::InvalidParameter`] naming `air_temperature_k`.
    pub fn path(&self, nodes: &[(f64, f64)]) -> Result<Path> {
        let total: f64 = nodes.iter().map(|n| n.1).sum();
        match self {
            PathSpec::Homogeneous {
                extinction_per_m,
                horizon: Horizon::Radiance(l),
            } => Path::homogeneous(*extinction_per_m, l * total),
            PathSpec::Homogeneous {
                extinction_per_m,
                horizon: Horizon::AirTemperature(t),
            } => {
                positive("air_temperature_k", *t)?;
                let l = super::noise::band_planck(nodes, *t);
                Path::homogeneous(*extinction_per_m, l)
            }
            PathSpec::Table(p) => Ok(p.with_radiance_scaled(total)),
        }
    }
}
