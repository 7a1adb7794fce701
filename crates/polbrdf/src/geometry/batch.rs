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
        angles_valid(self.columns().map(|c| &c[range.clone()]))
    }

    /// The four slices as they are, not validated (for [`Unvalidated`]: the kernel validates
    /// them as it reads them).
    fn unvalidated(
        theta_i: &'a [f64],
        phi_i: &'a [f64],
        theta_r: &'a [f64],
        phi_r: &'a [f64],
    ) -> Self {
        Self {
            theta_i,
            phi_i,
            theta_r,
            phi_r,
        }
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

/// Many geometries as two slices of direction vectors `(x, y, z)` in the surface frame (z along
/// the normal): `w_i[j]` toward the source, `w_r[j]` toward the detector (docs/model.md §9.11),
/// the form a renderer or a ray tracer has them in. The vectors need not be unit (each is
/// normalized); a direction with `z ≤ 0` is at or below the horizon (a zero pBRDF). A vector
/// stands for the angles `θ = atan2(√(x² + y²), z)`, `φ = atan2(y, x)` (`φ = 0` along the
/// normal, [`crate::geometry::angles::direction_angles`]), and the engine's results are those of
/// [`GeometryBatch`] at these angles, computed from the vectors without a sine or cosine.
///
/// ```
/// use polbrdf::{DirectionBatch, Engine, GeometryBatch, MaterialSpec};
/// let m = MaterialSpec::new(1.5, 10.0).build()?;
/// let (w_i, w_r) = ([[0.5, 0.0, 0.75f64.sqrt()]], [[-0.5, 0.0, 0.75f64.sqrt()]]);
/// let mut f = [[0.0; 16]];
/// Engine::new(&m).mueller_into(&DirectionBatch::new(&w_i, &w_r)?, &mut f)?;
/// // The same geometry as angles: 30° incidence, specular.
/// let t = [30f64.to_radians()];
/// let a = GeometryBatch::new(&t, &[0.0], &t, &[std::f64::consts::PI])?;
/// let mut g = [[0.0; 16]];
/// Engine::new(&m).mueller_into(&a, &mut g)?;
/// assert!((f[0][0] - g[0][0]).abs() < 1e-12 * g[0][0]);
/// # Ok::<(), polbrdf::Error>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct DirectionBatch<'a> {
    w_i: &'a [[f64; 3]],
    w_r: &'a [[f64; 3]],
}

impl<'a> DirectionBatch<'a> {
    /// Two equally long slices of direction vectors, each finite with a length in
    /// [`crate::geometry::angles::DIRECTION_LENGTH`] (1e-15 to 1e15).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`], or [`Error::InvalidDirection`] naming the slice (`w_i` or
    /// `w_r`), the vector and its index.
    pub fn new(w_i: &'a [[f64; 3]], w_r: &'a [[f64; 3]]) -> Result<Self> {
        check_len("w_r", w_r.len(), w_i.len())?;
        for (name, ws) in [("w_i", w_i), ("w_r", w_r)] {
            ws.par_chunks(CHUNK)
                .enumerate()
                .try_for_each(|(c, chunk)| {
                    if vectors_valid(chunk) {
                        return Ok(());
                    }
                    let j = chunk
                        .iter()
                        .position(|w| !vector_valid(w))
                        .expect("a failed vector");
                    Err(Error::InvalidDirection {
                        name,
                        value: chunk[j],
                        index: Some(c * CHUNK + j),
                    })
                })?;
        }
        Ok(Self { w_i, w_r })
    }

    /// Number of geometries.
    pub fn len(&self) -> usize {
        self.w_i.len()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.w_i.is_empty()
    }

    /// The two slices (`w_i`, `w_r`), validated.
    pub fn directions(&self) -> (&'a [[f64; 3]], &'a [[f64; 3]]) {
        (self.w_i, self.w_r)
    }

    /// The `i`-th geometry as angles ([`crate::geometry::angles::direction_angles`]).
    pub fn get(&self, i: usize) -> Geometry {
        let (ti, pi) = crate::geometry::angles::direction_angles(self.w_i[i]);
        let (tr, pr) = crate::geometry::angles::direction_angles(self.w_r[i]);
        Geometry::new_unchecked(ti, pi, tr, pr)
    }
}

/// Whether every element of four equally long columns of angles (radians) passes
/// [`Geometry::checked`]: zenith angles in `[0, π]`, azimuths within
/// ±[`crate::MAX_AZIMUTH_DEG`] (in radians), all finite (a NaN or an infinity fails a
/// comparison). Branch-free, so that it vectorizes.
#[inline(always)]
pub(crate) fn angles_valid([ti, pi_, tr, pr]: [&[f64]; 4]) -> bool {
    let max_azimuth = crate::MAX_AZIMUTH_DEG.to_radians();
    let pi = std::f64::consts::PI;
    let zenith = |x: f64| (x >= 0.0) & (x <= pi);
    let azimuth = |x: f64| x.abs() <= max_azimuth;
    ti.iter()
        .zip(pi_)
        .zip(tr)
        .zip(pr)
        .fold(true, |ok, (((&ti, &pi), &tr), &pr)| {
            ok & zenith(ti) & azimuth(pi) & zenith(tr) & azimuth(pr)
        })
}

/// Whether a direction vector is valid for [`DirectionBatch::new`]: finite, with a length in
/// [`crate::geometry::angles::DIRECTION_LENGTH`].
#[inline(always)]
pub(crate) fn vector_valid(w: &[f64; 3]) -> bool {
    let n2 = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
    let (lo, hi) = crate::geometry::angles::DIRECTION_LENGTH;
    (n2 >= lo * lo) & (n2 <= hi * hi)
}

/// Whether every vector of `ws` is [`vector_valid`] (branch-free).
#[inline(always)]
pub(crate) fn vectors_valid(ws: &[[f64; 3]]) -> bool {
    ws.iter().fold(true, |a, w| a & vector_valid(w))
}

/// Angles or direction vectors as given, not validated yet: the kernel's validating entry
/// points ([`crate::engine::Kernel::try_mueller_into`] and its siblings) check each block of
/// elements as they read it, so that a caller that evaluates its input once also reads it once
/// (Python's `mueller` and `mueller_directions`). On an invalid element they stop, set every
/// result of their range to NaN (never a partial result) and return the error
/// [`GeometryBatch::new`] or [`DirectionBatch::new`] gives for that range — the same element,
/// field and message. Only the lengths are checked here.
#[derive(Debug, Clone, Copy)]
pub struct Unvalidated<'a>(Input<'a>);

impl<'a> Unvalidated<'a> {
    /// Four slices of angles in radians, as [`GeometryBatch::new`] takes them.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`].
    pub fn angles(
        theta_i: &'a [f64],
        phi_i: &'a [f64],
        theta_r: &'a [f64],
        phi_r: &'a [f64],
    ) -> Result<Self> {
        let n = theta_i.len();
        for (name, s) in [("phi_i", phi_i), ("theta_r", theta_r), ("phi_r", phi_r)] {
            check_len(name, s.len(), n)?;
        }
        Ok(Self(Input::Angles(GeometryBatch::unvalidated(
            theta_i, phi_i, theta_r, phi_r,
        ))))
    }

    /// Two slices of direction vectors, as [`DirectionBatch::new`] takes them.
    ///
    /// # Errors
    /// [`Error::LengthMismatch`].
    pub fn directions(w_i: &'a [[f64; 3]], w_r: &'a [[f64; 3]]) -> Result<Self> {
        check_len("w_r", w_r.len(), w_i.len())?;
        Ok(Self(Input::Directions(DirectionBatch { w_i, w_r })))
    }

    /// Number of geometries.
    pub fn len(&self) -> usize {
        match self.0 {
            Input::Angles(b) => b.len(),
            Input::Directions(d) => d.len(),
        }
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The input, not validated (for the kernel's validating sources only).
    pub(crate) fn input(&self) -> Input<'a> {
        self.0
    }

    /// The validation of elements `start .. start + len` as [`GeometryBatch::new`] or
    /// [`DirectionBatch::new`] does it (the index of an invalid element in this batch's
    /// numbering).
    ///
    /// # Errors
    /// As those constructors.
    pub fn validate(&self, start: usize, len: usize) -> Result<()> {
        let r = start..start + len;
        let shift = |e: Error| match e {
            Error::InvalidAngle {
                name,
                value,
                degrees,
                index,
                problem,
            } => Error::InvalidAngle {
                name,
                value,
                degrees,
                index: index.map(|i| i + start),
                problem,
            },
            Error::InvalidDirection { name, value, index } => Error::InvalidDirection {
                name,
                value,
                index: index.map(|i| i + start),
            },
            other => other,
        };
        match self.0 {
            Input::Angles(b) => {
                let [ti, pi, tr, pr] = b.columns().map(|c| &c[r.clone()]);
                GeometryBatch::new(ti, pi, tr, pr)
                    .map(|_| ())
                    .map_err(shift)
            }
            Input::Directions(d) => {
                let (wi, wr) = d.directions();
                DirectionBatch::new(&wi[r.clone()], &wr[r])
                    .map(|_| ())
                    .map_err(shift)
            }
        }
    }
}

/// A batch of geometries the engine evaluates: [`GeometryBatch`] (angles) or
/// [`DirectionBatch`] (direction vectors). Sealed: the engine knows how to read each.
pub trait Batch: Sync + sealed::Sealed {
    /// Number of geometries.
    fn len(&self) -> usize;
    /// True when there are none.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The `i`-th geometry as angles.
    fn get(&self, i: usize) -> Geometry;
    /// Which kind of batch this is (for the engine).
    #[doc(hidden)]
    fn input(&self) -> Input<'_>;
}

/// The two kinds of [`Batch`] (for the engine).
#[doc(hidden)]
#[derive(Debug, Clone, Copy)]
pub enum Input<'a> {
    Angles(GeometryBatch<'a>),
    Directions(DirectionBatch<'a>),
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for super::GeometryBatch<'_> {}
    impl Sealed for super::DirectionBatch<'_> {}
}

impl Batch for GeometryBatch<'_> {
    fn len(&self) -> usize {
        GeometryBatch::len(self)
    }
    fn get(&self, i: usize) -> Geometry {
        GeometryBatch::get(self, i)
    }
    fn input(&self) -> Input<'_> {
        Input::Angles(*self)
    }
}

impl Batch for DirectionBatch<'_> {
    fn len(&self) -> usize {
        DirectionBatch::len(self)
    }
    fn get(&self, i: usize) -> Geometry {
        DirectionBatch::get(self, i)
    }
    fn input(&self) -> Input<'_> {
        Input::Directions(*self)
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
