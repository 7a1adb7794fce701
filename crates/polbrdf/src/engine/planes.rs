//! Planar (structure-of-arrays) output: the 16 entries of `F` as 16 planes, each holding one
//! entry for every element — the layout of Mitsuba's and Dr.Jit's Mueller matrices, of a
//! lookup table stored entry by entry, and of NumPy's `F[i, j]` over an image. It saves the
//! transpose of the row-major output (docs/model.md §12, "Layouts").

use crate::error::{Error, Result};

/// The 16 planes of a planar pBRDF output, borrowed from the caller: plane `e = 4·i + j`
/// holds `F[i][j]` (the row-major index of the entry) of every element, element `k` at
/// position `k` of the plane.
///
/// ```
/// use polbrdf::engine::{Engine, Planes};
/// use polbrdf::{GeometryBatch, MaterialSpec};
/// let m = MaterialSpec::new(1.5, 10.0).build()?;
/// let t = [0.3, 0.5, 0.7];
/// let (pi, pr) = ([0.0; 3], [std::f64::consts::PI; 3]);
/// let batch = GeometryBatch::new(&t, &pi, &t, &pr)?;
/// let mut flat = vec![0.0; 16 * 3];
/// Engine::new(&m).mueller_planes_into(&batch, &mut Planes::new(&mut flat, 3)?)?;
/// let rows = Engine::new(&m).mueller(&batch)?;
/// // Entry (0, 1) of element 2: plane 1, position 2.
/// assert_eq!(flat[3 + 2], rows[2][1]);
/// # Ok::<(), polbrdf::Error>(())
/// ```
#[derive(Debug)]
pub struct Planes<'a, T> {
    pub(crate) planes: [&'a mut [T]; 16],
}

impl<'a, T> Planes<'a, T> {
    /// The planes of `flat`, an array of `16·n` values: plane `e` is `flat[e·n .. (e + 1)·n]`
    /// (a C-ordered `(4, 4, n)` or `(16, n)` array).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] when `flat` does not hold `16·n` values.
    pub fn new(flat: &'a mut [T], n: usize) -> Result<Self> {
        let expected = n.checked_mul(16).ok_or(Error::LengthMismatch {
            name: "out",
            got: flat.len(),
            expected: usize::MAX,
        })?;
        if flat.len() != expected {
            return Err(Error::LengthMismatch {
                name: "out",
                got: flat.len(),
                expected,
            });
        }
        let mut rest = flat;
        let planes = std::array::from_fn(|_| {
            let (plane, tail) = std::mem::take(&mut rest).split_at_mut(n);
            rest = tail;
            plane
        });
        Ok(Self { planes })
    }

    /// Sixteen planes of equal length given separately (say, the columns of a table).
    ///
    /// # Errors
    /// [`Error::LengthMismatch`] naming the first plane whose length differs from plane 0's.
    pub fn from_planes(planes: [&'a mut [T]; 16]) -> Result<Self> {
        let n = planes[0].len();
        if let Some(e) = planes.iter().position(|p| p.len() != n) {
            return Err(Error::LengthMismatch {
                name: PLANE_NAMES[e],
                got: planes[e].len(),
                expected: n,
            });
        }
        Ok(Self { planes })
    }

    /// The number of elements (the length of each plane).
    pub fn len(&self) -> usize {
        self.planes[0].len()
    }

    /// Whether the planes are empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Elements `.. mid` and `mid ..` as two sets of planes.
    ///
    /// # Panics
    /// When `mid > self.len()`.
    pub fn split_at(self, mid: usize) -> (Planes<'a, T>, Planes<'a, T>) {
        let mut tails: [&'a mut [T]; 16] = Default::default();
        let mut planes = self.planes;
        for (p, t) in planes.iter_mut().zip(tails.iter_mut()) {
            let (a, b) = std::mem::take(p).split_at_mut(mid);
            (*p, *t) = (a, b);
        }
        (Planes { planes }, Planes { planes: tails })
    }

    /// The same planes, borrowed for a shorter time.
    pub fn reborrow(&mut self) -> Planes<'_, T> {
        let mut it = self.planes.iter_mut();
        Planes {
            planes: std::array::from_fn(|_| &mut **it.next().expect("16 planes")),
        }
    }

    /// Plane `e` (entry `F[e / 4][e % 4]`).
    pub fn plane(&self, e: usize) -> &[T] {
        self.planes[e]
    }
}

/// The planes' names in messages: `F00` … `F33`.
const PLANE_NAMES: [&str; 16] = [
    "F00", "F01", "F02", "F03", "F10", "F11", "F12", "F13", "F20", "F21", "F22", "F23", "F30",
    "F31", "F32", "F33",
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_of_a_flat_array_and_their_split() {
        let mut flat: Vec<u32> = (0..16 * 5).collect();
        let p = Planes::new(&mut flat, 5).unwrap();
        assert_eq!(p.len(), 5);
        assert_eq!(p.plane(3), &[15, 16, 17, 18, 19]);
        let (a, b) = p.split_at(2);
        assert_eq!((a.len(), b.len()), (2, 3));
        assert_eq!(a.plane(15), &[75, 76]);
        assert_eq!(b.plane(15), &[77, 78, 79]);
        assert!(matches!(
            Planes::new(&mut flat[1..], 5),
            Err(Error::LengthMismatch {
                got: 79,
                expected: 80,
                ..
            })
        ));
    }

    #[test]
    fn separate_planes_must_agree_in_length() {
        let mut store = vec![vec![0.0f64; 4]; 16];
        store[7].push(1.0);
        let mut it = store.iter_mut();
        let planes = std::array::from_fn(|_| it.next().unwrap().as_mut_slice());
        let e = Planes::from_planes(planes).unwrap_err();
        assert!(matches!(
            e,
            Error::LengthMismatch {
                name: "F13",
                got: 5,
                expected: 4
            }
        ));
    }
}
