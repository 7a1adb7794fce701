//! The scalar terms of the model that combine D, SO and the geometry: the two forms of the
//! surface term (eqs. 1 and 6) and the volume term (eq. 1) — docs/model.md §5, §6.
//!
//! The pBRDF is `F = f_s·M/M00 + f_v·diag(1, 0, 0, 0)` with `M00 = R_F(β)`; since
//! `f_s = R_F(β)·g` in both forms, `F = g·M + f_v·diag(1, 0, 0, 0)` and the model never divides
//! by M00. This module computes `g` and `f_v`.

use crate::geometry::angles::FacetAngles;
use crate::numeric::math::{Math, Real};

/// Which surface term (docs/model.md §5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Form {
    /// Eq. 1 with eq. 2 read as `f_ZBS(θN) = R_F(0)·D(θN)/(4cos²θN)`:
    /// `f_s = D·R_F(β)·SO / (4 cosθi cosθr)` (default).
    #[default]
    Standard,
    /// Eq. 6 exactly as printed: `f_s = D·R_F(β)·cos²θN·SO / (4 cos²θi cos²θr)`.
    Paper,
}

impl Form {
    /// Every form, in the order of the names in messages: the one list that the material
    /// files, the CLI and the Python module's `Literal` types spell.
    pub const ALL: [Form; 2] = [Form::Standard, Form::Paper];

    /// The name used in material files (`"standard"`, `"paper"`).
    pub fn as_str(&self) -> &'static str {
        match self {
            Form::Standard => "standard",
            Form::Paper => "paper",
        }
    }
}

impl std::str::FromStr for Form {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        crate::names::parse(&Self::ALL, |f| f.as_str(), s)
    }
}

/// The volume term (eq. 1), unpolarized: `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)`, given
/// `inv_sz = 1/(cosθi + cosθr)`.
#[inline(always)]
pub fn volume<M: Math>(rho_d: f64, rho_v: f64, inv_sz: M::F) -> M::F {
    M::mla(M::F::of(2.0 * rho_v), inv_sz, M::F::of(rho_d))
}

/// `(g, f_v)` of one element, with one division: `g = f_s/R_F(β)`, i.e.
/// `g = D·SO/(4 cosθi cosθr)` (`standard`) or `g = D·SO·cos²θN/(4 cos²θi cos²θr)` (`paper`,
/// `cos²θN = s_z²/|s|²`), and the volume term [`volume`]. `so` is SO as
/// `(numerator, denominator)` ([`crate::Shadowing::ratio`]; `(1, 1)` without shadowing).
#[inline(always)]
pub fn surface_and_volume<M: Math>(
    form: Form,
    d: M::F,
    (so_num, so_den): (M::F, M::F),
    a: &FacetAngles<M::F>,
    rho_d: f64,
    rho_v: f64,
) -> (M::F, M::F) {
    let (ci, cr, sz) = (a.cos_i, a.cos_r, a.sz);
    let four_cc = M::F::of(4.0) * ci * cr;
    let (num, den) = match form {
        Form::Standard => (so_num, so_den * four_cc),
        Form::Paper => (so_num * (sz * sz), so_den * (four_cc * ci * cr) * a.s2),
    };
    // 1/(den·s_z) gives both g = D·num/den and 1/s_z = den/(den·s_z). D multiplies last: the
    // geometric factor num/den is of normal range, while D far down a narrow lobe can be close
    // to underflow, and a product such as D·s_z² formed first would turn subnormal (and lose
    // its digits) before 1/den brought it back (docs/model.md §9.9).
    let r = M::F::ONE / (den * sz);
    (d * (num * sz * r), volume::<M>(rho_d, rho_v, den * r))
}

/// `g`, or 0 when D or the surface term `g·R_F` is below the smallest normal number
/// (≈ 2.2·10⁻³⁰⁸ sr⁻¹ in f64): a subnormal keeps too few bits for the term, or its
/// polarization, to mean anything (docs/model.md §9.9).
#[inline(always)]
pub fn flush_subnormal<T: Real>(g: T, r_f: T, d: T) -> T {
    if g * r_f >= T::MIN_POSITIVE && d >= T::MIN_POSITIVE {
        g
    } else {
        T::ZERO
    }
}
