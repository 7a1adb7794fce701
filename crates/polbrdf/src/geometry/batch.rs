//! Many geometries at once: four slices of angles (structure of arrays), validated once. The
//! batch engine (`crate::engine`) evaluates them.

use crate::error::{Error, Result};
use crate::geometry::direction::Geometry;
use rayon::prelude::*;

/// Elements per parallel validation task.
const CHUNK: usize = 4096;

/// Many geometries as four parallel slices of angles in radians (structure of arrays).
#[derive(Debug, Clone, Copy)]
pub struct GeometryBatch<'a> {
    theta_i: &'a [f64],
    phi_i: &'a [f64],
    theta_r: &'a [f64],
    phi_r: &'a [f64],
}

impl<'a> GeometryBatch<'a> {
    /// Four equally long slices of angles in radians. Every element is validated as by
    /// [`Geometry::new`].
    ///
    /// # Errors
    /// [`Error::LengthMismatch`], or [`Error::InvalidAngle`] carrying the element's index.
    pub fn new(
        theta_i: &'a [f64],
        phi_i: &'a [f64],
        theta_r: &'a [f64],
        phi_r: &'a [f64],
    ) -> Result<Self> {
        let n = theta_i.len();
        for (name, s) in [("phi_i", phi_i), ("theta_r", theta_r), ("phi_r", phi_r)] {
            check_len(name, s.len(), n)?;
        }
        let batch = Self {
            theta_i,
            phi_i,
            theta_r,
            phi_r,
        };
        // Validate in parallel: a vectorized test of each chunk, and only in a chunk that
        // fails it the element-by-element check that finds and reports the first bad element.
        batch
            .theta_i
            .par_chunks(CHUNK)
            .enumerate()
            .try_for_each(|(c, chunk)| {
                let r = c * CHUNK..c * CHUNK + chunk.len();
                if batch.all_valid(r.clone()) {
                    return Ok(());
                }
                r.into_iter()
                    .try_for_each(|i| batch.geometry_checked(i).map(|_| ()))
            })?;
        Ok(batch)
    }

    /// Whether every element of `range` passes [`Geometry::checked`]: zenith angles in
    /// `[0, π]`, azimuths within ±[`crate::MAX_AZIMUTH_DEG`] (in radians), all finite (a NaN or
    /// an infinity fails a comparison). Branch-free, so that it vectorizes.
    fn all_valid(&self, range: std::ops::Range<usize>) -> bool {
        let max_azimuth = crate::MAX_AZIMUTH_DEG.to_radians();
        let pi = std::f64::consts::PI;
        let zenith = |x: f64| (x >= 0.0) & (x <= pi);
        let azimuth = |x: f64| x.abs() <= max_azimuth;
        let ti = &self.theta_i[range.clone()];
        let pi_ = &self.phi_i[range.clone()];
        let tr = &self.theta_r[range.clone()];
        let pr = &self.phi_r[range];
        ti.iter()
            .zip(pi_)
            .zip(tr)
            .zip(pr)
            .fold(true, |ok, (((&ti, &pi), &tr), &pr)| {
                ok & zenith(ti) & azimuth(pi) & zenith(tr) & azimuth(pr)
            })
    }

    /// Number of geometries.
    pub fn len(&self) -> usize {
        self.theta_i.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.theta_i.is_empty()
    }

    fn geometry_checked(&self, i: usize) -> Result<Geometry> {
        Geometry::checked(
            [
                self.theta_i[i],
                self.phi_i[i],
                self.theta_r[i],
                self.phi_r[i],
            ],
            false,
            Some(i),
        )
    }

    /// The four columns (θi, φi, θr, φr), validated.
    pub fn columns(&self) -> [&'a [f64]; 4] {
        [self.theta_i, self.phi_i, self.theta_r, self.phi_r]
    }

    /// The `i`-th geometry (validated at construction).
    pub fn get(&self, i: usize) -> Geometry {
        Geometry::new_unchecked(
            self.theta_i[i],
            self.phi_i[i],
            self.theta_r[i],
            self.phi_r[i],
        )
    }
}

/// `Ok` when `got == expected`, else [`Error::LengthMismatch`] naming the slice.
pub(crate) fn check_len(name: &'static str, got: usize, expected: usize) -> Result<()> {
    if got == expected {
        Ok(())
    } else {
        Err(Error::LengthMismatch {
            name,
            got,
            expected,
        })
    }
}
