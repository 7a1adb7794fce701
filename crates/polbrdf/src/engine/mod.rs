//! The batch engine: the one fast path every grid of the crate goes through (docs/model.md §12).
//!
//! It evaluates the same formula functions as the one-geometry path
//! ([`crate::Material::evaluate`]) — the angle variables of [`crate::geometry::angles`], the
//! Fresnel amplitudes of [`crate::optics::fresnel`], D, SO and the surface and volume terms of
//! [`crate::model`], the assembly of F in [`crate::optics::mueller`] — with two differences
//! that change nothing but speed:
//!
//! - **Blocks, stage by stage** (`block`): [`kernel::BLOCK`] elements at a time, each stage a
//!   loop over the block calling the formula functions once per lane into per-job workspaces
//!   (structure of arrays, zeroed once per job, no heap allocation), which the compiler
//!   vectorizes across the block; the rows of a block are transposed into the row-major output
//!   with 4×4 register shuffles.
//! - **Polynomial elementary functions** ([`crate::numeric::math`]): branch-free sine/cosine,
//!   exponential and arctangent within 2 ulp of the standard library, compiled for AVX-512,
//!   AVX2+FMA and the build target's baseline and chosen at run time ([`simd`]).
//!
//! It is organized by stage:
//!
//! | file | stage |
//! |---|---|
//! | [`simd`] | which instruction set |
//! | `block` | the block kernel: sines and cosines → angles (or, from direction vectors, `geometry::vectors`' sums, differences, dot and cross products → angles) → `q` → D, SO, `g`, `f_v` → Fresnel amplitudes → rotations → F, or → BRDF, DoLP (AoLP) |
//! | [`kernel`] | the serial driver ([`Kernel`]): blocks, the per-element index ([`IndexColumns`]), the elements the block kernel must not take |
//! | [`planes`] | the planar (structure-of-arrays) output |
//! | [`batch`] | the parallel driver ([`Engine`], and the free functions of earlier releases) |
//!
//! **Accuracy.** Every entry agrees with `Material::evaluate` to within `1e-12·F00` (tested at
//! every instruction set on the test vectors and on 120 000 random cases). Where the model is
//! so ill-conditioned that a last-bit difference of an elementary function would show at that
//! level — D beyond `bθN² > 600` or near underflow, results below 10⁻²⁸⁰, `q` within 10⁻⁴ of its
//! branch point `N² = sin²β`, an index within a few percent of 1, `|Δ/2| > 2¹⁶` rad — the element
//! is taken from `Material::evaluate` itself, so there the two paths agree exactly. No element
//! of the presets takes that path (tested).

pub mod batch;
pub(crate) mod block;
pub mod kernel;
pub mod planes;
pub mod simd;

pub use batch::{Engine, Precision};
pub use kernel::{elementary_into, Elementary, IndexColumns, Kernel, Prepared, BLOCK};
pub use planes::Planes;
pub use simd::{simd_level, SimdLevel};
