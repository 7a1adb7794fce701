//! The kernel's validating entry points: an [`Unvalidated`] batch checked block by block as the
//! kernel reads it (docs/engine-performance.md, "Input validation folded into the kernel's
//! read").

use super::sinks::{PutRows, Rows, Sink, SinkF32};
use super::sources::{BatchSource, Checked, Computed, Directions};
use super::{Kernel, BLOCK};
use crate::engine::planes::Planes;
use crate::error::Result;
use crate::geometry::batch::Input;
use crate::geometry::Unvalidated;

impl Kernel<'_> {
    /// As [`Kernel::mueller_into`] of an [`Unvalidated`] batch, validating each block of
    /// elements as the kernel reads it (the same test as [`crate::GeometryBatch::new`]'s and
    /// [`crate::DirectionBatch::new`]'s, in the pass that reads the input: no pass of its own
    /// over memory). The results of a valid batch are bit for bit those of
    /// [`Kernel::mueller_into`].
    ///
    /// # Errors
    /// At the first block with an invalid element the kernel stops, every entry of `out` is
    /// set to NaN (never a partial result), and the error is the one the batch's constructor
    /// gives for elements `start .. start + out.len()` ([`Unvalidated::validate`]: the same
    /// element, field and message, the index in the batch's numbering).
    ///
    /// # Panics
    /// When the range exceeds the batch (or a per-element index).
    pub fn try_mueller_into(
        &self,
        raw: &Unvalidated<'_>,
        start: usize,
        out: &mut [[f64; 16]],
    ) -> Result<()> {
        self.try_f64(raw, start, &mut Rows(out)).map(|_| ())
    }

    /// As [`Kernel::try_mueller_into`] into planes ([`Kernel::mueller_planes_into`]).
    ///
    /// # Errors
    /// As [`Kernel::try_mueller_into`].
    ///
    /// # Panics
    /// As [`Kernel::try_mueller_into`].
    pub fn try_mueller_planes_into(
        &self,
        raw: &Unvalidated<'_>,
        start: usize,
        out: &mut Planes<'_, f64>,
    ) -> Result<()> {
        self.try_f64(raw, start, out).map(|_| ())
    }

    /// As [`Kernel::mueller_f32_into`] of an [`Unvalidated`] batch, validated block by block
    /// as [`Kernel::try_mueller_into`]. Returns whether some finite entry was beyond f32's
    /// range.
    ///
    /// # Errors
    /// As [`Kernel::try_mueller_into`].
    ///
    /// # Panics
    /// As [`Kernel::try_mueller_into`].
    pub fn try_mueller_f32_into(
        &self,
        raw: &Unvalidated<'_>,
        start: usize,
        out: &mut [[f32; 16]],
    ) -> Result<bool> {
        self.try_f32(raw, start, &mut Rows(out))
    }

    /// As [`Kernel::try_mueller_f32_into`] into planes ([`Kernel::mueller_planes_f32_into`]).
    ///
    /// # Errors
    /// As [`Kernel::try_mueller_into`].
    ///
    /// # Panics
    /// As [`Kernel::try_mueller_into`].
    pub fn try_mueller_planes_f32_into(
        &self,
        raw: &Unvalidated<'_>,
        start: usize,
        out: &mut Planes<'_, f32>,
    ) -> Result<bool> {
        self.try_f32(raw, start, out)
    }

    fn try_f64<W: PutRows<f64>>(
        &self,
        raw: &Unvalidated<'_>,
        start: usize,
        out: &mut W,
    ) -> Result<bool> {
        let index = self.index_at(start, out.len());
        let done = with_source!(checked raw, start, out.len(), |src| {
            self.run_mueller::<_, _, BLOCK>(&src, index, out)
        });
        if !done.invalid {
            return Ok(done.overflow);
        }
        Self::refuse(raw, start, out)?;
        Ok(with_source!(@ raw.input(), start, out.len(), , |src| {
            self.run_mueller::<_, _, BLOCK>(&src, index, out)
        })
        .overflow)
    }

    fn try_f32<W: SinkF32>(
        &self,
        raw: &Unvalidated<'_>,
        start: usize,
        out: &mut W,
    ) -> Result<bool> {
        let index = self.index_at(start, out.len());
        let done = with_source!(checked raw, start, out.len(), |src| {
            self.f32_source(&src, index, out)
        });
        if !done.invalid {
            return Ok(done.overflow);
        }
        Self::refuse(raw, start, out)?;
        Ok(with_source!(@ raw.input(), start, out.len(), , |src| {
            self.f32_source(&src, index, out)
        })
        .overflow)
    }

    /// After a block failed validation: `out` set to NaN and the constructor's error for the
    /// range. (The block test is the constructors' own, so the range fails theirs; were it
    /// ever to pass, the caller evaluates the range as validated.)
    fn refuse<W: Sink>(raw: &Unvalidated<'_>, start: usize, out: &mut W) -> Result<()> {
        raw.validate(start, out.len()).inspect_err(|_| out.poison())
    }
}
