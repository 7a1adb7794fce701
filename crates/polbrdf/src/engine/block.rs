//! The block kernel: one block of `N` elements at a time, stage by stage, each stage a short
//! loop over the block that calls the model's formula functions (`crate::geometry::angles`,
//! `crate::optics::fresnel`, `crate::model`, `crate::optics::mueller`) once per lane, into
//! small stack arrays (structure of arrays). The loops have no branches the compiler cannot
//! turn into selects, so it vectorizes each stage across the block; the stages are short, so
//! the processor overlaps their iterations.
//!
//! Each element also gets a `fallback` flag: set where the model is so ill-conditioned that the
//! polynomial functions' last-bit differences from the standard library's would show at 1e-12
//! (see [`crate::engine`]); the kernel then takes that element from the one-geometry path.

#![allow(clippy::needless_range_loop)]

use crate::geometry::angles::{self, AngleVariables, FacetAngles, Trig};
use crate::model::material::ModelParams;
use crate::model::shadowing::{AzimuthTerm, Shadowing};
use crate::model::terms::{self, Form};
use crate::numeric::math::{Math, Real};
use crate::optics::fresnel;
use crate::optics::mueller;
use crate::optics::stokes;
use std::f64::consts::FRAC_PI_2;

mod directions;
pub(crate) use directions::geometry_of_directions;
#[cfg(test)]
pub(crate) use directions::geometry_of_directions_via_angles;

/// One lane per element of a block.
pub(crate) type Lanes<const N: usize, T = f64> = [T; N];

/// Where the block kernel hands an element to the one-geometry path, per floating-point type:
/// where the model is so ill-conditioned that the kernel's rounding would show at its accuracy
/// (docs/model.md §12).
pub(crate) trait Thresholds: Real {
    /// Beyond `b·θN²` of this, `D = a·exp(−bθN²)` is so sensitive to the last bit of θN
    /// (relative condition `2bθN²`) that it shows: in f64 (`D` below `e⁻⁶⁰⁰` of its peak) a
    /// one-ulp difference of the arctangent would show at 1e-12.
    const D_EXPONENT_MAX: Self;
    /// Below `|N² − sin²β|` of this, `q = sqrt(N² − sin²β)` is near its branch point (an index
    /// below 1 near its critical angle) and amplifies rounding.
    const BRANCH_POINT_MIN: Self;
    /// Results below this (but not zero) are near the subnormal range, where relative accuracy
    /// ends.
    const TINY: Self;
    /// The largest condition number of the Fresnel amplitudes as `N² → 1` the kernel accepts
    /// (`crate::engine::kernel`'s `index_ill`).
    const INDEX_COND_MAX: f64;
    /// Whether an element with a non-finite entry takes the one-geometry path (in f32, where
    /// an intermediate can overflow that f64 holds).
    const CHECK_FINITE: bool;
    /// Whether D beyond [`Thresholds::D_EXPONENT_MAX`] is refined (recomputed from an f64 θN,
    /// between [`front_q_d`] and [`front_terms`]) instead of sending the element to the f64 path.
    const REFINE_D: bool;
}

impl Thresholds for f64 {
    const D_EXPONENT_MAX: f64 = 600.0;
    const BRANCH_POINT_MIN: f64 = 1e-4;
    const TINY: f64 = 1e-280;
    const INDEX_COND_MAX: f64 = 100.0;
    const CHECK_FINITE: bool = false;
    const REFINE_D: bool = false;
}

/// The f32 kernel's bounds for an accuracy of 1e-5·F00 against f64 (docs/model.md §12,
/// "Precision"; beyond them the float32 contract's `1e-6·P` covers D, [`TAIL_KEEP`]): D's
/// relative error is about `2bθN²·δθN/θN` with `δθN/θN` up to about 2 f32 ulps (measured), so
/// `bθN² ≤ 20`; the Fresnel amplitudes' condition number times f32's ε
/// stays near 1e-6 at 20.
impl Thresholds for f32 {
    const D_EXPONENT_MAX: f32 = 20.0;
    const BRANCH_POINT_MIN: f32 = 0.03;
    const TINY: f32 = 1e-30;
    const INDEX_COND_MAX: f64 = 20.0;
    const CHECK_FINITE: bool = true;
    const REFINE_D: bool = true;
}

/// Where D's tail (`y = bθN² > 20`) computed in f32 is kept by the f32 kernel, against the
/// float32 contract `|ΔF_ij| ≤ 1e-5·F00 + ε·P` with `ε = 1e-6` and `P` the material's F00 at
/// the specular direction of the same θi (docs/model.md §12, "Precision"): D's relative error
/// in f32 is about `2y·δθN/θN ≤ 4.8·10⁻⁷·y` (θN within 2 f32 ulps), and every entry of the
/// surface term is at most its F00, `g·R_F` with `g ∝ D·SO/(cosθi cosθr)` (`paper`:
/// `/(cosθi cosθr)²`), so the error is at most `P·4.8·10⁻⁷·y·e^{−y}·(cosθi/cosθr)²·r`, `r` the
/// ratio of the element's `R_F·SO` (and `cos²θN/|s|²`) to the specular direction's, taken
/// ≤ 100. That is within `ε·P` where `e^{−y}·y·(cosθi/cosθr)² ≤ 1/48`, ≈ 0.02: every tail
/// element but those with θr within about 10⁻⁷ rad of grazing (and θi far from it) at `y` just
/// above 20. Those few keep D's f64 refinement.
pub(crate) const TAIL_KEEP: f64 = 0.02;

/// Where D below f32's comfortable range ([`Thresholds::TINY`], `10⁻³⁰`) is set to 0 by the
/// f32 kernel instead of sending the element to the f64 path: the whole surface term is then
/// dropped, an error of at most `P·e^{−y}·(cosθi/cosθr)²·r` (as for [`TAIL_KEEP`], `r ≤ 100`),
/// within `ε·P = 10⁻⁶·P` where `D/a·(cosθi/cosθr)² ≤ 10⁻⁸`. (Mitsuba's float32 `roughconductor`
/// returns 0 where `D·cosθ < 10⁻²⁰`.)
pub(crate) const NEGLIGIBLE: f64 = 1e-8;

/// The angles (rad) of one block.
pub(crate) struct BlockIn<const N: usize> {
    pub ti: Lanes<N>,
    pub pi: Lanes<N>,
    pub tr: Lanes<N>,
    pub pr: Lanes<N>,
}

impl<const N: usize> BlockIn<N> {
    pub(crate) fn zeroed() -> Self {
        Self {
            ti: [0.0; N],
            pi: [0.0; N],
            tr: [0.0; N],
            pr: [0.0; N],
        }
    }
}

/// `N²` per element of a block, and whether the element's index is outside the kernel's
/// accurate domain.
pub(crate) struct IndexLanes<const N: usize, T = f64> {
    pub n2r: Lanes<N, T>,
    pub n2i: Lanes<N, T>,
    pub index_ill: [bool; N],
}

/// Sines and cosines of a block ([`Trig`] in structure-of-arrays form), and what they are
/// computed from: the backend's reduced arguments ([`Trig::reduce`]) and θi in `T`.
pub(crate) struct TrigLanes<const N: usize, T = f64> {
    v: [Lanes<N, T>; 8],
    reduced: [[Lanes<N, T>; 3]; 4],
    theta_i: Lanes<N, T>,
}

impl<const N: usize, T: Real> TrigLanes<N, T> {
    pub(crate) fn zeroed() -> Self {
        Self {
            v: [[T::ZERO; N]; 8],
            reduced: [[[T::ZERO; N]; 3]; 4],
            theta_i: [T::ZERO; N],
        }
    }

    #[inline(always)]
    fn set_reduced(&mut self, j: usize, r: [[T; 3]; 4]) {
        for a in 0..4 {
            for c in 0..3 {
                self.reduced[a][c][j] = r[a][c];
            }
        }
    }
    #[inline(always)]
    fn get_reduced(&self, j: usize) -> [[T; 3]; 4] {
        let r = &self.reduced;
        let at = |a: usize| [r[a][0][j], r[a][1][j], r[a][2][j]];
        [at(0), at(1), at(2), at(3)]
    }

    #[inline(always)]
    fn set(&mut self, j: usize, t: Trig<T>) {
        [
            self.v[0][j],
            self.v[1][j],
            self.v[2][j],
            self.v[3][j],
            self.v[4][j],
            self.v[5][j],
            self.v[6][j],
            self.v[7][j],
        ] = [t.si, t.ci, t.sr, t.cr, t.sh, t.ch, t.su, t.cu];
    }
    #[inline(always)]
    fn get(&self, j: usize) -> Trig<T> {
        let v = &self.v;
        Trig {
            si: v[0][j],
            ci: v[1][j],
            sr: v[2][j],
            cr: v[3][j],
            sh: v[4][j],
            ch: v[5][j],
            su: v[6][j],
            cu: v[7][j],
        }
    }
}

/// [`FacetAngles`] of a block in structure-of-arrays form.
#[derive(Clone)]
pub(crate) struct FacetLanes<const N: usize, T = f64> {
    v: [Lanes<N, T>; 10],
}

impl<const N: usize, T: Real> FacetLanes<N, T> {
    #[inline(always)]
    fn set(&mut self, j: usize, a: FacetAngles<T>) {
        let v = [
            a.theta_i,
            a.cos_i,
            a.cos_r,
            a.theta_n,
            a.beta,
            a.phi_n,
            a.cos_beta,
            a.sin2_beta,
            a.sz,
            a.s2,
        ];
        for (lane, x) in self.v.iter_mut().zip(v) {
            lane[j] = x;
        }
    }
    #[inline(always)]
    pub(crate) fn get(&self, j: usize) -> FacetAngles<T> {
        let v = &self.v;
        FacetAngles {
            theta_i: v[0][j],
            cos_i: v[1][j],
            cos_r: v[2][j],
            theta_n: v[3][j],
            beta: v[4][j],
            phi_n: v[5][j],
            cos_beta: v[6][j],
            sin2_beta: v[7][j],
            sz: v[8][j],
            s2: v[9][j],
        }
    }
}

/// The geometry part of a block, which does not depend on the material: validity, the angles
/// and cosines, the Priest–Meier pairs, the angles as given (for the one-geometry path), and
/// whether the backend's elementary functions reach the element (`|Δ/2|`). A batch of
/// geometries can be prepared once in these ([`crate::engine::Prepared`]) and evaluated for
/// many materials or wavelengths.
#[derive(Clone)]
pub(crate) struct Geom<const N: usize, T = f64> {
    /// Both directions above the horizon.
    pub valid: [bool; N],
    /// Outside the backend's range: one-geometry path.
    pub out_of_range: [bool; N],
    pub facet: FacetLanes<N, T>,
    /// `[c_i, s_i, c_r, s_r]` of [`angles::eta_pairs`].
    pub pairs: [Lanes<N, T>; 4],
    /// θi, φi, θr, φr (rad) as given.
    pub angles: [Lanes<N>; 4],
}

impl<const N: usize, T: Real> Geom<N, T> {
    pub(crate) fn zeroed() -> Self {
        let z = [T::ZERO; N];
        Self {
            valid: [false; N],
            out_of_range: [false; N],
            facet: FacetLanes { v: [z; 10] },
            pairs: [z; 4],
            angles: [[0.0; N]; 4],
        }
    }
}

/// What the geometry stages of a block work in: the angles, the sines and cosines, and the
/// results. Made (zeroed) once per job and overwritten block by block, so that no block pays
/// for initializing or moving its arrays.
pub(crate) struct GeomScratch<const N: usize, T = f64> {
    pub input: BlockIn<N>,
    /// The direction vectors of a block of the direction entry point (`x, y, z` of `w_i`,
    /// then of `w_r`), as given.
    pub dirs: [Lanes<N>; 6],
    pub trig: TrigLanes<N, T>,
    /// What the direction route carries from its f64 stage to its `T` stage.
    pub vec: VectorLanes<N, T>,
    pub geo: Geom<N, T>,
}

/// The direction route's quantities between its f64 and `T` stages
/// ([`geometry_of_directions`]).
pub(crate) struct VectorLanes<const N: usize, T = f64> {
    /// `|s_xy|²`.
    pub rho2: Lanes<N, T>,
    /// `sin²θi`.
    pub sin2_i: Lanes<N, T>,
    /// ΦN's components along and across the plane of incidence.
    pub along: Lanes<N, T>,
    pub across: Lanes<N, T>,
    /// `|s_xy|` at rounding level (ΦN = 0).
    pub flat: [bool; N],
}

impl<const N: usize, T: Real> GeomScratch<N, T> {
    pub(crate) fn zeroed() -> Self {
        Self {
            input: BlockIn::zeroed(),
            dirs: [[0.0; N]; 6],
            trig: TrigLanes::zeroed(),
            vec: VectorLanes {
                rho2: [T::ZERO; N],
                sin2_i: [T::ZERO; N],
                along: [T::ZERO; N],
                across: [T::ZERO; N],
                flat: [false; N],
            },
            geo: Geom::zeroed(),
        }
    }
}

/// Which of the angles that only some terms use a material needs: ΦN (only SO's eq. 3
/// azimuth factor) and β (only SO). The geometry stages skip the others (0 in their place).
#[derive(Debug, Clone, Copy)]
pub(crate) struct AngleNeeds {
    pub phi_n: bool,
    pub beta: bool,
}

impl AngleNeeds {
    /// Every angle (a prepared batch serves every material).
    pub(crate) const ALL: Self = Self {
        phi_n: true,
        beta: true,
    };

    /// What the terms of `params` use.
    pub(crate) fn of(params: &ModelParams) -> Self {
        Self {
            phi_n: params.uses_phi_n(),
            beta: params.shadowing.is_some(),
        }
    }
}

/// The geometry stages of the block `s.input` into `s.geo`: sines and cosines, the angles
/// (ΦN and β where `needs` says) and, with `PAIRS`, the Priest–Meier pairs. `s.geo.angles` is
/// left as it is (only a prepared batch keeps the angles).
#[inline(always)]
pub(crate) fn geometry<M: Math, const N: usize, const PAIRS: bool>(
    s: &mut GeomScratch<N, M::F>,
    needs: AngleNeeds,
) {
    let (b, trig, g) = (&s.input, &mut s.trig, &mut s.geo);
    // Stage 1: what needs f64 — validity, the range of `Δ/2`, θi in `M::F` and the backend's
    // reduction of the four angles — in a loop of its own, so that the f32 kernel's loops
    // after it are f32 only (at twice the vector width).
    for j in 0..N {
        trig.set_reduced(j, Trig::reduce::<M>(b.ti[j], b.pi[j], b.tr[j], b.pr[j]));
        trig.theta_i[j] = M::F::of(b.ti[j]);
        g.valid[j] = b.ti[j] < FRAC_PI_2 && b.tr[j] < FRAC_PI_2;
        g.out_of_range[j] = !Trig::<M::F>::in_range::<M>(b.pi[j], b.pr[j]);
    }
    // Stage 2: the four sine/cosine pairs.
    for j in 0..N {
        let t = Trig::from_reduced::<M>(trig.get_reduced(j));
        trig.set(j, t);
    }
    facet_stages::<M, N, PAIRS>(trig, g, needs, b);
}

/// The stages of [`geometry`] after the sines and cosines: the angles (θN, β where `needs`
/// says), the cosines, ΦN and, with `PAIRS`, the Priest–Meier pairs. ΦN's rounding level
/// ([`angles::phi_n`]) takes the azimuths' scale from the angles (direction vectors, whose
/// components carry relative rounding only, have their own stages with scale 1).
#[inline(always)]
fn facet_stages<M: Math, const N: usize, const PAIRS: bool>(
    trig: &TrigLanes<N, M::F>,
    g: &mut Geom<N, M::F>,
    needs: AngleNeeds,
    angles_in: &BlockIn<N>,
) {
    // Stage 3: the angles (θN, β) and cosines, β only where SO needs it; ΦN (eq3 only) in a
    // loop of its own. Materials without them do not pay for their arctangents.
    if needs.beta {
        for j in 0..N {
            let a = FacetAngles::from_trig::<M>(trig.theta_i[j], &trig.get(j), 1.0, false, true);
            g.facet.set(j, a);
        }
    } else {
        for j in 0..N {
            let a = FacetAngles::from_trig::<M>(trig.theta_i[j], &trig.get(j), 1.0, false, false);
            g.facet.set(j, a);
        }
    }
    if needs.phi_n {
        for j in 0..N {
            let t = trig.get(j);
            let scale = angles::phi_scale(angles_in.pi[j], angles_in.pr[j]);
            g.facet.v[5][j] = angles::phi_n::<M>(&angles::half_vector::<M>(&t), &t, scale);
        }
    }
    if PAIRS {
        for j in 0..N {
            let [ci, si, cr, sr] = angles::eta_pairs::<M>(&trig.get(j));
            [g.pairs[0][j], g.pairs[1][j], g.pairs[2][j], g.pairs[3][j]] = [ci, si, cr, sr];
        }
    }
}

/// The geometry part of a block of explicit angle variables (the angle-variable entry point).
pub(crate) fn geometry_of_variables<const N: usize, T: Real>(
    v: &[AngleVariables; N],
    g: &mut Geom<N, T>,
) {
    for j in 0..N {
        g.valid[j] = v[j].theta_i < FRAC_PI_2 && v[j].theta_r < FRAC_PI_2;
        g.facet.set(j, FacetAngles::from_variables(&v[j]));
        let [ci, si, cr, sr] = v[j].eta_pairs().map(T::of);
        [g.pairs[0][j], g.pairs[1][j], g.pairs[2][j], g.pairs[3][j]] = [ci, si, cr, sr];
    }
}

/// What both output paths share, per element of a block: the fallback mask, `q`, the scalar
/// factor `g = f_s/R_F` and `f_v`, and `N²` (made once per job, overwritten block by block, as
/// [`GeomScratch`]).
pub(crate) struct Front<const N: usize, T = f64> {
    /// The element must take the one-geometry path.
    pub fallback: [bool; N],
    pub qr: Lanes<N, T>,
    pub qi: Lanes<N, T>,
    pub g: Lanes<N, T>,
    pub fv: Lanes<N, T>,
    pub n2r: Lanes<N, T>,
    pub n2i: Lanes<N, T>,
    /// D and SO's numerator and denominator (between stages).
    d: Lanes<N, T>,
    /// D beyond [`Thresholds::D_EXPONENT_MAX`], to be refined (with
    /// [`Thresholds::REFINE_D`]).
    d_tail: [bool; N],
    so_num: Lanes<N, T>,
    so_den: Lanes<N, T>,
}

impl<const N: usize, T: Real> Front<N, T> {
    /// D, the lanes whose D is to be refined, and the fallback mask (between [`front_q_d`]
    /// and [`front_terms`]).
    #[inline(always)]
    pub(crate) fn d_tail_mut(&mut self) -> (&mut Lanes<N, T>, &[bool; N], &mut [bool; N]) {
        (&mut self.d, &self.d_tail, &mut self.fallback)
    }

    pub(crate) fn zeroed() -> Self {
        let z = [T::ZERO; N];
        Self {
            fallback: [false; N],
            qr: z,
            qi: z,
            g: z,
            fv: z,
            n2r: z,
            n2i: z,
            d: z,
            d_tail: [false; N],
            so_num: z,
            so_den: z,
        }
    }
}

/// The material stages of a block: `q` (eq. 10's transmitted wave number) and the scalar terms
/// D, SO, `g`, `f_v` (eqs. 4, 3, 1, 6), for the index lanes of `b`.
#[inline(always)]
pub(crate) fn front<M: Math, const N: usize>(
    p: &ModelParams,
    geo: &Geom<N, M::F>,
    b: &IndexLanes<N, M::F>,
    f: &mut Front<N, M::F>,
) where
    M::F: Thresholds,
{
    front_q_d::<M, N>(p, geo, b, f);
    front_terms::<M, N>(p, geo, f);
}

/// The first part of [`front`]: `q` and D. Where [`Thresholds::REFINE_D`], the lanes with D
/// beyond [`Thresholds::D_EXPONENT_MAX`] (where θN's rounding shows) are flagged in
/// `f.d_tail` instead of `f.fallback`, for the caller to replace their D by a more accurate
/// value ([`Front::d_tail_mut`]) before [`front_terms`].
#[inline(always)]
pub(crate) fn front_q_d<M: Math, const N: usize>(
    p: &ModelParams,
    geo: &Geom<N, M::F>,
    b: &IndexLanes<N, M::F>,
    f: &mut Front<N, M::F>,
) where
    M::F: Thresholds,
{
    let zero = M::F::ZERO;
    f.n2r = b.n2r;
    f.n2i = b.n2i;
    for j in 0..N {
        f.fallback[j] = b.index_ill[j] || geo.out_of_range[j];
    }
    // Stage 3: q = sqrt(N² − sin²β) on the principal branch; a real N² (k = 0, the same in
    // every lane) needs one square root and no division.
    if f.n2i.iter().all(|v| *v == zero) {
        for j in 0..N {
            let s2b = geo.facet.get(j).sin2_beta;
            (f.qr[j], f.qi[j]) = fresnel::transmitted_q_real(f.n2r[j], s2b);
            f.fallback[j] |= (f.n2r[j] - s2b).abs() < M::F::BRANCH_POINT_MIN;
        }
    } else {
        for j in 0..N {
            let s2b = geo.facet.get(j).sin2_beta;
            (f.qr[j], f.qi[j]) = fresnel::transmitted_q_complex::<M>(f.n2r[j], f.n2i[j], s2b);
            let zr = f.n2r[j] - s2b;
            let z2 = M::mla(zr, zr, f.n2i[j] * f.n2i[j]);
            f.fallback[j] |= z2 < M::F::BRANCH_POINT_MIN * M::F::BRANCH_POINT_MIN;
        }
    }
    // Stage 4: D (eq. 4), SO (eq. 3), g and f_v (eqs. 1, 6) — the same formulas as
    // `ModelParams::scalar_terms`, one loop per term with the material's choices (shadowing
    // on or off, its azimuth factor, the form) made before the loops, so that each loop is
    // straight-line code the compiler vectorizes.
    let dist = p.distribution;
    let d = &mut f.d;
    for j in 0..N {
        let tn = geo.facet.v[3][j];
        d[j] = dist.eval_with::<M>(tn);
        // D so far down its tail that θN's last bit shows, or near the underflow limit.
        let y = dist.exponent(tn);
        let lobe = dist.a() > 0.0 && y > M::F::of(-750.0);
        let tail = lobe && -y > M::F::D_EXPONENT_MAX;
        let under = lobe && d[j] < M::F::TINY;
        // Under the float32 contract ([`TAIL_KEEP`], [`NEGLIGIBLE`]; without a division):
        // D's tail as computed stays where `D/a·y·(cosθi/cosθr)² ≤ TAIL_KEEP`; a D below
        // f32's comfortable range is 0 where `D/a·(cosθi/cosθr)² ≤ NEGLIGIBLE`.
        let a = geo.facet.get(j);
        let (lhs, rhs) = (
            d[j] * (a.cos_i * a.cos_i),
            M::F::of(dist.a()) * (a.cos_r * a.cos_r),
        );
        let keep = lhs * -y <= M::F::of(TAIL_KEEP) * rhs;
        let drop = M::F::REFINE_D && under && lhs <= M::F::of(NEGLIGIBLE) * rhs;
        if drop {
            d[j] = M::F::ZERO;
        }
        f.fallback[j] |= (under && !drop) || (tail && !M::F::REFINE_D);
        f.d_tail[j] = tail && M::F::REFINE_D && !keep && !drop;
    }
}

/// The second part of [`front`]: SO, `g` and `f_v` from D.
#[inline(always)]
pub(crate) fn front_terms<M: Math, const N: usize>(
    p: &ModelParams,
    geo: &Geom<N, M::F>,
    f: &mut Front<N, M::F>,
) where
    M::F: Thresholds,
{
    let (so_num, so_den) = (&mut f.so_num, &mut f.so_den);
    so_num.fill(M::F::ONE);
    so_den.fill(M::F::ONE);
    if let Some(s) = p.shadowing {
        let mut ratio = |s: Shadowing| {
            for j in 0..N {
                let a = geo.facet.get(j);
                (so_num[j], so_den[j]) = s.ratio::<M>(a.theta_n, a.beta, a.phi_n, a.theta_i);
            }
        };
        match s.azimuth_term() {
            AzimuthTerm::None => ratio(s.with_azimuth(AzimuthTerm::None)),
            AzimuthTerm::Eq3 => ratio(s.with_azimuth(AzimuthTerm::Eq3)),
        }
    }
    let mut surface = |form: Form| {
        for j in 0..N {
            let a = geo.facet.get(j);
            (f.g[j], f.fv[j]) = terms::surface_and_volume::<M>(
                form,
                f.d[j],
                (f.so_num[j], f.so_den[j]),
                &a,
                p.rho_d,
                p.rho_v,
            );
        }
    };
    match p.form {
        Form::Standard => surface(Form::Standard),
        Form::Paper => surface(Form::Paper),
    }
    for j in 0..N {
        f.fallback[j] = geo.valid[j] && f.fallback[j];
    }
}

/// BRDF (F00), DoLP and, with `AOLP`, AoLP (rad) of a block for unpolarized input.
///
/// `F10 = g·B·cos2η_r` and `F20 = g·B·sin2η_r`, so the magnitude of the linear part is `|g·B|`
/// and the DoLP needs no rotation; the AoLP needs η_r.
#[inline(always)]
pub(crate) fn brdf_dolp<M: Math, const N: usize, const AOLP: bool>(
    f: &mut Front<N, M::F>,
    geo: &Geom<N, M::F>,
    out: &mut [Lanes<N, M::F>; 3],
) where
    M::F: Thresholds,
{
    let zero = M::F::ZERO;
    let mut gb = [zero; N];
    for j in 0..N {
        let c = geo.facet.get(j).cos_beta;
        let [rs2, rp2, _, _] = fresnel::reflectances::<M>(f.n2r[j], f.n2i[j], c, f.qr[j], f.qi[j]);
        let [a, b] = mueller::intensity_coefficients(rs2, rp2);
        let g = terms::flush_subnormal(f.g[j], a, f.d[j]);
        let f00 = g * a + f.fv[j];
        gb[j] = g * b;
        let d = stokes::dolp(gb[j].abs(), f00);
        f.fallback[j] |= geo.valid[j] && f00 > zero && f00 < M::F::TINY;
        out[0][j] = if geo.valid[j] { f00 } else { zero };
        out[1][j] = if geo.valid[j] { d } else { zero };
    }
    if AOLP {
        for j in 0..N {
            let p = [
                geo.pairs[0][j],
                geo.pairs[1][j],
                geo.pairs[2][j],
                geo.pairs[3][j],
            ];
            let [_, _, cr2, sr2] = angles::rotations::<M>(p);
            let a = stokes::aolp::<M>(cr2 * gb[j], sr2 * gb[j]);
            out[2][j] = if geo.valid[j] && gb[j] != zero {
                a
            } else {
                zero
            };
        }
    }
}

/// The full pBRDF of a block, as 16 rows of lanes (row-major entry index first): the Fresnel
/// amplitudes, `g·(A, B, C, S)`, the rotations and
/// `F = R(η_r)·(g·M_d)·R(−η_i) + f_v·diag(1, 0, 0, 0)`, in one loop.
#[inline(always)]
pub(crate) fn mueller<M: Math, const N: usize>(
    f: &mut Front<N, M::F>,
    geo: &Geom<N, M::F>,
    out: &mut [Lanes<N, M::F>; 16],
) where
    M::F: Thresholds,
{
    let zero = M::F::ZERO;
    for j in 0..N {
        let c = geo.facet.get(j).cos_beta;
        let (n2r, n2i, qr, qi) = (f.n2r[j], f.n2i[j], f.qr[j], f.qi[j]);
        let [rs2, rp2, inv_s, inv_p] = fresnel::reflectances::<M>(n2r, n2i, c, qr, qi);
        let amp = fresnel::amplitudes::<M>(n2r, n2i, c, qr, qi, inv_s, inv_p);
        let coef = mueller::diagonal_coefficients::<M>(rs2, rp2, amp);
        let g = terms::flush_subnormal(f.g[j], coef[0], f.d[j]);
        let pairs = [
            geo.pairs[0][j],
            geo.pairs[1][j],
            geo.pairs[2][j],
            geo.pairs[3][j],
        ];
        let v =
            mueller::facet_pbrdf::<M>(coef.map(|x| g * x), f.fv[j], angles::rotations::<M>(pairs));
        let valid = geo.valid[j];
        f.fallback[j] |= valid && v[0] > zero && v[0] < M::F::TINY;
        if M::F::CHECK_FINITE {
            // x·0 is 0 for every finite x, NaN for ±∞ and NaN; the sum (pairwise, to keep the
            // chain short) is non-finite if an entry is (or, harmlessly, if it overflows).
            let s8: [M::F; 8] = std::array::from_fn(|i| v[i] + v[i + 8]);
            let s4: [M::F; 4] = std::array::from_fn(|i| s8[i] + s8[i + 4]);
            let probe = ((s4[0] + s4[2]) + (s4[1] + s4[3])) * zero;
            f.fallback[j] |= valid && probe != zero;
        }
        for (o, x) in out.iter_mut().zip(v) {
            o[j] = if valid { x } else { zero };
        }
    }
}
