//! The arriving beam's psps basis (docs/model.md §2) and linearly polarized light written in it:
//! the one place the frame of a sky's Stokes vectors is set.

use super::direction;
use crate::optics::stokes::Stokes;

/// The psps basis `(s_in, p_in)` of the beam arriving at the surface from the sky point in
/// direction `(theta, phi)`: `k = −w`, `s_in = unit(z × k) = (sinφ, −cosφ, 0)` (its θ → 0⁺
/// limit at the given azimuth at the zenith), `p_in = k × s_in` (docs/model.md §2). The one
/// place the arriving frame is written.
pub fn arriving_basis(theta: f64, phi: f64) -> ([f64; 3], [f64; 3]) {
    let (sp, cp) = phi.sin_cos();
    basis_of(&direction(theta, phi), sp, cp)
}

/// [`arriving_basis`] of the direction `w` at azimuth φ given by `(sinφ, cosφ)`.
pub(super) fn basis_of(w: &[f64; 3], sp: f64, cp: f64) -> ([f64; 3], [f64; 3]) {
    let s = [sp, -cp, 0.0];
    // p = k × s with k = −w.
    let p = cross(&s, w);
    (s, p)
}

pub(super) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The Stokes vector `L·(1, P·cos2ψ, P·sin2ψ, 0)` of linearly polarized light of radiance `L`
/// and degree `P` whose electric vector is along `e`, arriving from `(theta, phi)`, in the
/// arriving beam's basis: `ψ = atan2(e·p_in, e·s_in)` ([`arriving_basis`]).
pub fn linear_stokes(radiance: f64, dolp: f64, e: &[f64; 3], theta: f64, phi: f64) -> Stokes {
    let (sp, cp) = phi.sin_cos();
    linear_stokes_of(radiance, dolp, e, &direction(theta, phi), sp, cp)
}

/// [`linear_stokes`] arriving from the direction `w` at azimuth φ given by `(sinφ, cosφ)`.
pub(super) fn linear_stokes_of(
    radiance: f64,
    dolp: f64,
    e: &[f64; 3],
    w: &[f64; 3],
    sp: f64,
    cp: f64,
) -> Stokes {
    let (s, p) = basis_of(w, sp, cp);
    let (x, y) = (dot(e, &s), dot(e, &p));
    let r2 = x * x + y * y;
    if r2.is_nan() || r2 <= 0.0 || dolp == 0.0 {
        return Stokes([radiance, 0.0, 0.0, 0.0]);
    }
    // cos 2ψ = (x² − y²)/r², sin 2ψ = 2xy/r².
    Stokes([
        radiance,
        radiance * dolp * (x * x - y * y) / r2,
        radiance * dolp * 2.0 * x * y / r2,
        0.0,
    ])
}
