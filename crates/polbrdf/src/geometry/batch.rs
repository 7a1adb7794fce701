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
        // Validate in parallel; report the first bad element.
        batch
            .theta_i
            .par_chunks(CHUNK)
            .enumerate()
            .try_for_each(|(c, chunk)| {
                (0..chunk.len()).try_for_each(|j| batch.geometry_checked(c * CHUNK + j).map(|_| ()))
            })?;
        Ok(batch)
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
