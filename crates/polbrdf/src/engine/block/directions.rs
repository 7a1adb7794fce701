//! The block kernel's geometry from direction vectors (the direction entry point): the native
//! route from sums, differences, dot and cross products of the vectors, and (in tests) the
//! previous route through the angles' sines and cosines, which the native one is held to
//! (docs/engine-performance.md).

#[cfg(test)]
use super::{facet_stages, BlockIn};
use super::{AngleNeeds, GeomScratch, Thresholds};
#[cfg(test)]
use crate::geometry::angles::Trig;
use crate::geometry::vectors::{azimuth_axis, unit, VectorGeometry};
use crate::numeric::math::{Math, Real};
use std::f64::consts::FRAC_PI_2;

/// The geometry stages of the block of direction vectors `s.dirs` (the direction entry point)
/// into `s.geo`, natively: sums, differences, dot and cross products of the unit vectors in
/// f64 ([`VectorGeometry`]: the normalization, the half vector, `sin²β = |d|²/4`, the
/// Priest–Meier pairs, the parts of ΦN), rounded to `M::F`; then in `M::F` the angles the
/// model needs, θN = `atan2(|s_xy|, s_z)`, cosβ = `|s|/2`, and β, θi, ΦN only where `needs`
/// says. No conversion to the sines and cosines of angles. An element whose azimuth's axis
/// would lose digits (`x² + y²` of a unit vector below f64's `TINY`, or underflowed to 0,
/// while `(x, y)` is not exactly 0: within about 1e-140 rad of the normal) takes the
/// one-geometry path. `z > 0` is above the horizon (docs/model.md §9.11).
#[inline(always)]
pub(crate) fn geometry_of_directions<M: Math, const N: usize, const PAIRS: bool>(
    s: &mut GeomScratch<N, M::F>,
    needs: AngleNeeds,
) where
    M::F: Thresholds,
{
    if needs.phi_n {
        vector_stage::<M, N, PAIRS, true>(s);
    } else {
        vector_stage::<M, N, PAIRS, false>(s);
    }
    let (v, g) = (&s.vec, &mut s.geo);
    let f = &mut g.facet.v;
    let half = M::F::of(0.5);
    for j in 0..N {
        f[3][j] = M::atan2_pos(v.rho2[j].sqrt(), f[8][j]);
        f[6][j] = half * f[9][j].sqrt();
    }
    if needs.beta {
        for j in 0..N {
            f[4][j] = M::atan2_pos(f[7][j].sqrt(), f[6][j]);
            f[0][j] = M::atan2_pos(v.sin2_i[j].sqrt(), f[1][j].max(M::F::ZERO));
        }
    }
    if needs.phi_n {
        let right = M::F::of(FRAC_PI_2);
        for j in 0..N {
            let d = M::atan2_pos(v.across[j].abs(), v.along[j].abs()).min(right);
            f[5][j] = if v.flat[j] { M::F::ZERO } else { d };
        }
    }
}

/// The direction route this crate had before [`geometry_of_directions`] (the reference its
/// tests hold it to): the vectors converted to the sines and cosines of their angles
/// ([`Trig::from_directions`], in f64), then the angle route's stages.
#[cfg(test)]
pub(crate) fn geometry_of_directions_via_angles<M: Math, const N: usize>(
    s: &mut GeomScratch<N, M::F>,
    needs: AngleNeeds,
) {
    // Azimuth scale 1 for vectors (φ = 0 here).
    s.input = BlockIn::zeroed();
    let (w, trig, g) = (&s.dirs, &mut s.trig, &mut s.geo);
    for j in 0..N {
        let wi = [w[0][j], w[1][j], w[2][j]];
        let wr = [w[3][j], w[4][j], w[5][j]];
        let (t, r2) = Trig::<f64>::from_directions(wi, wr);
        let of = M::F::of;
        let t = [t.si, t.ci, t.sr, t.cr, t.sh, t.ch, t.su, t.cu].map(of);
        let [si, ci, sr, cr, sh, ch, su, cu] = t;
        trig.set(
            j,
            Trig {
                si,
                ci,
                sr,
                cr,
                sh,
                ch,
                su,
                cu,
            },
        );
        g.valid[j] = wi[2] > 0.0 && wr[2] > 0.0;
        g.out_of_range[j] = r2 < 1e-280;
        if needs.beta {
            trig.theta_i[j] = M::atan2_pos(si, ci.max(M::F::ZERO));
        }
    }
    facet_stages::<M, N, true>(trig, g, needs, &s.input);
}

/// The f64 part of [`geometry_of_directions`]: [`VectorGeometry`] of each element, rounded to
/// `M::F` into `s.geo` (cosines, `s_z`, `|s|²`, `sin²β`, the pairs with `PAIRS`) and `s.vec`;
/// with `PHI`, ΦN's components (scaled by a power of two, so that f32 holds them) and whether
/// `|s_xy|` is at rounding level.
#[inline(always)]
fn vector_stage<M: Math, const N: usize, const PAIRS: bool, const PHI: bool>(
    s: &mut GeomScratch<N, M::F>,
) where
    M::F: Thresholds,
{
    let (w, v, g) = (&s.dirs, &mut s.vec, &mut s.geo);
    let pair_min = M::F::PAIR_MIN.to_f64();
    let of = M::F::of;
    for j in 0..N {
        let wi = [w[0][j], w[1][j], w[2][j]];
        let wr = [w[3][j], w[4][j], w[5][j]];
        let x = VectorGeometry::new(wi, wr, [unit(wi), unit(wr)], pair_min);
        let f = &mut g.facet.v;
        [f[1][j], f[2][j], f[7][j], f[8][j], f[9][j]] =
            [x.cos_i, x.cos_r, x.sin2_beta, x.sz, x.s2].map(of);
        v.rho2[j] = of(x.rho2);
        v.sin2_i[j] = of(x.sin2_i);
        if PAIRS {
            [g.pairs[0][j], g.pairs[1][j], g.pairs[2][j], g.pairs[3][j]] = x.pairs.map(of);
        }
        if PHI {
            let [along, across] = azimuth_axis(x.along, x.across);
            (v.along[j], v.across[j], v.flat[j]) = (of(along), of(across), x.flat());
        }
        g.valid[j] = wi[2] > 0.0 && wr[2] > 0.0;
        g.out_of_range[j] = x.off_normal < <f64 as Thresholds>::TINY;
    }
}
