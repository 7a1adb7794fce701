//! Batch evaluation over many geometries: structure of arrays, parallel with rayon.

use crate::error::{Error, Result};
use crate::geometry::Geometry;
use crate::kernel::Kernel;
use crate::model::Material;
use crate::mueller::Mueller;
use rayon::prelude::*;

/// Elements per parallel task: large enough to amortize scheduling, small enough to balance.
const CHUNK: usize = 4096;

/// Full-Mueller outputs of at least this many elements (8 MB) bypass the caches.
const STREAM_MIN: usize = 1 << 16;

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
            self.theta_i[i],
            self.phi_i[i],
            self.theta_r[i],
            self.phi_r[i],
            Some(i),
        )
    }

    /// The four columns (θi, φi, θr, φr), validated.
    pub(crate) fn columns(&self) -> [&'a [f64]; 4] {
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

fn check_len(name: &'static str, got: usize, expected: usize) -> Result<()> {
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

/// The full pBRDF `F` (row-major 4×4, sr⁻¹) at every geometry, written into `out`.
///
/// Evaluated by the vectorized [`crate::kernel`] (the same equations as
/// [`Material::evaluate`], to within `1e-12·F00`), in parallel chunks.
///
/// # Errors
/// [`Error::LengthMismatch`] when `out` is not as long as the batch.
pub fn mueller_into(
    material: &Material,
    batch: &GeometryBatch<'_>,
    out: &mut [[f64; 16]],
) -> Result<()> {
    check_len("out", out.len(), batch.len())?;
    // Outputs far beyond the caches (≥ 8 MB) are written with non-temporal stores.
    let kernel = Kernel::new(material).streaming(out.len() >= STREAM_MIN);
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(c, chunk)| kernel.mueller_into(batch, c * CHUNK, chunk));
    Ok(())
}

/// The scalar BRDF `f` (sr⁻¹) and DoLP for unpolarized input at every geometry.
///
/// Evaluated by the vectorized [`crate::kernel`], which skips what these two need not (the
/// rotation angles and all but three entries of `F`), in parallel chunks.
///
/// # Errors
/// [`Error::LengthMismatch`] when an output slice is not as long as the batch.
pub fn brdf_dolp_into(
    material: &Material,
    batch: &GeometryBatch<'_>,
    brdf: &mut [f64],
    dolp: &mut [f64],
) -> Result<()> {
    check_len("brdf", brdf.len(), batch.len())?;
    check_len("dolp", dolp.len(), batch.len())?;
    let kernel = Kernel::new(material);
    brdf.par_chunks_mut(CHUNK)
        .zip(dolp.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(c, (fb, fd))| kernel.brdf_dolp_into(batch, c * CHUNK, fb, fd));
    Ok(())
}

/// The scalar BRDF `f` (sr⁻¹), the DoLP and the AoLP (rad, in (−π/2, π/2], measured from the
/// reflected beam's s axis toward its p axis; 0 without linear polarization) for unpolarized
/// input at every geometry — `Stokes::dolp` and `Stokes::aolp` of `F·(1, 0, 0, 0)`.
///
/// Evaluated by the vectorized [`crate::kernel`] (only the reflected beam's rotation, and only
/// the first column of `F`), in parallel chunks.
///
/// # Errors
/// [`Error::LengthMismatch`] when an output slice is not as long as the batch.
pub fn brdf_dolp_aolp_into(
    material: &Material,
    batch: &GeometryBatch<'_>,
    brdf: &mut [f64],
    dolp: &mut [f64],
    aolp: &mut [f64],
) -> Result<()> {
    check_len("brdf", brdf.len(), batch.len())?;
    check_len("dolp", dolp.len(), batch.len())?;
    check_len("aolp", aolp.len(), batch.len())?;
    let kernel = Kernel::new(material);
    brdf.par_chunks_mut(CHUNK)
        .zip(dolp.par_chunks_mut(CHUNK))
        .zip(aolp.par_chunks_mut(CHUNK))
        .enumerate()
        .for_each(|(c, ((fb, fd), fa))| kernel.brdf_dolp_aolp_into(batch, c * CHUNK, fb, fd, fa));
    Ok(())
}

/// The pBRDF at every geometry of a slice of already validated geometries, in parallel
/// (through the vectorized [`crate::kernel`]).
pub fn pbrdf_of(material: &Material, geometries: &[Geometry]) -> Vec<Mueller> {
    let kernel = Kernel::new(material);
    let mut out = vec![Mueller::zero(); geometries.len()];
    out.par_chunks_mut(CHUNK)
        .zip(geometries.par_chunks(CHUNK))
        .for_each(|(o, g)| kernel.mueller_of(g, o));
    out
}

/// Convenience: the pBRDF at every geometry as a new vector.
///
/// # Errors
/// As [`mueller_into`].
pub fn mueller(material: &Material, batch: &GeometryBatch<'_>) -> Result<Vec<[f64; 16]>> {
    let mut out = vec![[0.0; 16]; batch.len()];
    mueller_into(material, batch, &mut out)?;
    Ok(out)
}
