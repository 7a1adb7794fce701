//! Properties over the whole valid parameter space (docs/model.md §13), by proptest:
//! n ∈ (0.05, 5], k ∈ [0, 10], σ ∈ [0.5°, 80°], ρ_D, ρ_V ∈ [0, 0.2], both forms, shadowing
//! on/off, azimuth term none/eq3, θ ∈ [0°, 90°) (with 0, 89.999 and values just below 90°),
//! φ ∈ [−720°, 720°], plus exact specular and backscatter geometries.

#![allow(clippy::needless_range_loop)]

use crate::limits::reference::{self, Mat4, Model, OMEGA_DEG};
use crate::limits::Lcg;
use polbrdf::batch::{brdf_dolp_into, mueller, mueller_into};
use polbrdf::{Error, Evaluation, Geometry, GeometryBatch, Material, RefractiveIndex, Stokes};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

// ---------------------------------------------------------------------------------------------
// strategies (angles in degrees, as in material files)

fn theta_deg() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => 0.0..89.99f64,
        1 => Just(0.0),
        1 => Just(89.999),
        1 => 89.99..89.9999f64,
        1 => 0.0..1e-4f64,
    ]
}

fn phi_deg() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -720.0..=720.0f64,
        1 => Just(0.0),
        1 => Just(180.0),
        1 => Just(-540.0),
    ]
}

/// (θi, φi, θr, φr) in degrees: general, exact specular, exact backscatter, in-plane.
fn angles_deg() -> impl Strategy<Value = [f64; 4]> {
    prop_oneof![
        5 => (theta_deg(), phi_deg(), theta_deg(), phi_deg()).prop_map(|(a, b, c, d)| [a, b, c, d]),
        1 => (theta_deg(), phi_deg()).prop_map(|(t, p)| [t, p, t, p + 180.0]),
        1 => (theta_deg(), phi_deg()).prop_map(|(t, p)| [t, p, t, p]),
        1 => (theta_deg(), theta_deg(), phi_deg()).prop_map(|(a, b, p)| [a, p, b, p - 180.0]),
    ]
}

fn geometry(a: [f64; 4]) -> Geometry {
    Geometry::from_degrees(a[0], a[1], a[2], a[3]).unwrap()
}

fn rho() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 2 => 0.0..=0.2f64]
}

fn model() -> impl Strategy<Value = Model> {
    (
        0.0501..=5.0f64,
        prop_oneof![1 => Just(0.0), 2 => 0.0..=10.0f64],
        0.5..=80.0f64,
        rho(),
        rho(),
        any::<bool>(),
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(
            |(n, k, sigma_deg, rho_d, rho_v, paper, shadow, eq3)| Model {
                n,
                k,
                sigma_deg,
                paper,
                shadow,
                eq3,
                rho_d,
                rho_v,
            },
        )
}

// ---------------------------------------------------------------------------------------------
// helpers

fn transpose(m: &Mat4) -> Mat4 {
    let mut t = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            t[i][j] = m[j][i];
        }
    }
    t
}

/// Largest |a − b| entry, relative to `scale` (with a floor for a vanishing scale).
fn max_diff(a: &Mat4, b: &Mat4, scale: f64) -> f64 {
    let mut d: f64 = 0.0;
    for i in 0..4 {
        for j in 0..4 {
            d = d.max((a[i][j] - b[i][j]).abs());
        }
    }
    d / scale.abs().max(1e-300)
}

/// `POLBRDF_PROPTEST_SCALE` (a positive integer, default 1) multiplies every property's number
/// of cases, for a deeper run than CI's (`POLBRDF_PROPTEST_SCALE=400` runs four million cases of
/// the comparison with the vector implementation in about 4 minutes in release).
fn scale() -> u32 {
    std::env::var("POLBRDF_PROPTEST_SCALE").map_or(1, |v| {
        v.parse()
            .ok()
            .filter(|&k| k > 0)
            .unwrap_or_else(|| panic!("POLBRDF_PROPTEST_SCALE={v:?}: expected a positive integer"))
    })
}

/// Proptest settings: `cases` cases, and no regression files written into the source tree.
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases: cases * scale(),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// The surface part of F normalized by f_s: `(F − f_v·diag(1,0,0,0))/f_s` (F00 set to 1 exactly,
/// so a volume term much larger than f_s costs no precision).
fn surface_normalized(e: &Evaluation) -> Mat4 {
    let mut m = e.pbrdf.0.map(|row| row.map(|v| v / e.surface));
    m[0][0] = 1.0;
    m
}

/// A fully polarized Stokes vector from a point on the Poincaré sphere.
fn poincare(z: f64, psi: f64) -> Stokes {
    let r = (1.0 - z * z).max(0.0).sqrt();
    Stokes([1.0, r * psi.cos(), r * psi.sin(), z])
}

// ---------------------------------------------------------------------------------------------
// realizability

proptest! {
    #![proptest_config(config(20000))]

    #[test]
    fn pbrdf_is_physical(
        model in model(),
        angles in angles_deg(),
        z in -1.0..=1.0f64,
        psi in 0.0..(2.0 * PI),
    ) {
        let m = model.material();
        let g = geometry(angles);
        let e = m.evaluate(&g);
        let f = &e.pbrdf;
        prop_assert!(f.0.iter().flatten().all(|v| v.is_finite()), "non-finite F: {f:?}");
        let f00 = f.0[0][0];
        prop_assert!(f00 >= 0.0, "F00 = {f00}");
        prop_assert!(e.surface >= 0.0 && e.volume >= 0.0);
        prop_assert!((0.0..=1.0 + 1e-12).contains(&e.dolp()), "DoLP = {}", e.dolp());
        if let Some(t) = e.terms {
            prop_assert!(t.so > 0.0 && t.so <= 1.0, "SO = {}", t.so);
            prop_assert!(t.d >= 0.0 && (0.0..=1.0 + 1e-12).contains(&t.r_f));
        }

        // Below ~1e-290 sr⁻¹ (D underflowing far outside a narrow lobe) the entries are
        // subnormal or close to it and carry no relative precision: only the checks above apply.
        if f00 < 1e-290 {
            return Ok(());
        }

        // Coherency (Cloude) matrix positive semidefinite, trace 2·F00.
        let ev = f.coherency_eigenvalues();
        prop_assert!(f.is_physically_realizable(1e-9), "eigenvalues {ev:?}");
        prop_assert!(ev[0] >= -1e-9 * f00, "eigenvalues {ev:?}");
        let trace: f64 = ev.iter().sum();
        prop_assert!((trace - 2.0 * f00).abs() <= 1e-9 * f00, "trace {trace} vs 2F00 {f00}");

        // Any fully polarized input: a physical output, |S⃗| ≤ S0 (DoP ≤ 1). Written relative to
        // F00 so that a nearly extinguished output (p light at Brewster) is judged fairly.
        let out = f.apply(&poincare(z, psi));
        let [s0, s1, s2, s3] = out.0;
        let pol = s1.hypot(s2).hypot(s3);
        prop_assert!(pol <= s0 + 1e-9 * f00, "|S| = {pol}, S0 = {s0} (F00 = {f00})");
        if s0 > 1e-3 * f00 {
            prop_assert!(out.dop() <= 1.0 + 1e-9, "DoP = {}", out.dop());
        }

        // Without the volume term F is non-depolarizing (one Jones matrix): its coherency matrix
        // has rank 1, i.e. tr(FᵀF) = 4·F00² (Gil–Bernabeu), and the largest eigenvalue is 2·F00.
        if model.rho_d == 0.0 && model.rho_v == 0.0 {
            let ss: f64 = f.0.iter().flatten().map(|v| (v / f00).powi(2)).sum();
            prop_assert!((ss / 4.0 - 1.0).abs() < 1e-9, "tr(FᵀF)/4F00² = {}", ss / 4.0);
            prop_assert!((ev[3] / (2.0 * f00) - 1.0).abs() < 1e-9);
            // and a fully polarized input stays fully polarized
            if s0 > 1e-3 * f00 {
                prop_assert!((out.dop() - 1.0).abs() < 1e-9, "DoP = {}", out.dop());
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// an independent implementation (vector algebra, see limits::reference)

proptest! {
    #![proptest_config(config(10000))]

    #[test]
    fn pbrdf_matches_independent_vector_implementation(
        model in model(),
        angles in angles_deg(),
    ) {
        let m = model.material();
        let [ti, pi, tr, pr] = angles.map(f64::to_radians);
        let a = reference::angles(ti, pi, tr, pr);
        // Within 1e-5 rad of β = 0 the vector frames are ill-conditioned; the limit itself
        // (β = 0 exactly) is in the reference and continuity is a separate property.
        if a.beta > 0.0 && a.beta < 1e-5 {
            return Ok(());
        }
        // eq3's factor 1/(1 + ΦN·θi/Ω) jumps at θN = 0 (ΦN is undefined there; spec: ΦN = 0);
        // a nominally specular geometry whose azimuths carry rounding error is on the edge.
        if model.eq3 && a.theta_n < 1e-9 {
            return Ok(());
        }
        let (f_s, f_v, want) = model.pbrdf(m.distribution().a(), ti, pi, tr, pr);
        let e = m.evaluate(&Geometry::new(ti, pi, tr, pr).unwrap());
        let scale = want[0][0];
        // The vector reference forms |s_xy| = |s|·sinθN (|s| = 2cosβ) as the difference of two
        // horizontal vectors whose components carry rounding errors of order
        // ε·(sinθi + sinθr): its ΦN is uncertain by that over |s_xy| (the library's closed form
        // keeps full relative accuracy near specular), and with eq3 so is its SO, by
        // θi/Ω times as much.
        let s_xy = 2.0 * a.beta.cos() * a.theta_n.sin();
        let phi_n_tol = 8.0 * f64::EPSILON * (ti.sin() + tr.sin()) / s_xy;
        let tol = 1e-9 + if model.eq3 { phi_n_tol * ti / OMEGA_DEG.to_radians() } else { 0.0 };
        // Where D or f_s is below the normal f64 range the library flushes the surface term to
        // zero (docs/model.md §9.9); the reference keeps its few subnormal bits. (The margin
        // covers the two sides' last-bit differences at the threshold.)
        let near_subnormal = |v: f64| v < (1.0 + 1e-9) * f64::MIN_POSITIVE;
        let flushed = (near_subnormal(f_s) || near_subnormal(model.d(m.distribution().a(), a.theta_n)))
            && e.surface == 0.0
            && e.pbrdf.0.iter().flatten().skip(1).all(|&v| v == 0.0);
        prop_assert!(
            max_diff(&e.pbrdf.0, &want, scale) <= tol || flushed,
            "library {:?}\nreference {want:?}", e.pbrdf.0
        );
        prop_assert!(
            (e.surface - f_s).abs() <= tol * f_s || flushed,
            "f_s {} vs {f_s}", e.surface
        );
        prop_assert!((e.volume - f_v).abs() <= 1e-12 * f_v);
        // Eq. 13 on the reference matrix (where F00 is not lost in underflow: D of a narrow
        // lobe far from its peak can be ~1e-310).
        if scale > 1e-290 && !flushed {
            let dolp = want[1][0].hypot(want[2][0]) / scale;
            prop_assert!((e.dolp() - dolp).abs() <= 1e-9, "DoLP {} vs {dolp}", e.dolp());
        }
        if let Some(t) = e.terms {
            prop_assert!((t.angles.theta_n - a.theta_n).abs() < 1e-9);
            prop_assert!((t.angles.beta - a.beta).abs() < 1e-9);
            if a.theta_n >= 1e-9 {
                prop_assert!((t.angles.phi_n - a.phi_n).abs() < 1e-7 + phi_n_tol, "ΦN {} vs {}", t.angles.phi_n, a.phi_n);
            }
        }
    }

    #[test]
    fn fresnel_is_passive_and_matches_snell_form(
        n in 0.0501..=5.0f64,
        k in prop_oneof![Just(0.0), 0.0..=10.0f64],
        beta in prop_oneof![0.0..=FRAC_PI_2, Just(0.0), Just(FRAC_PI_2)],
    ) {
        let fr = RefractiveIndex::new(n, k).unwrap().amplitudes(beta);
        prop_assert!(fr.rs.norm() <= 1.0 + 1e-12 && fr.rp.norm() <= 1.0 + 1e-12, "{fr:?}");
        let (rs, rp) = reference::fresnel(n, k, beta);
        prop_assert!((fr.rs - rs).norm() < 1e-10 && (fr.rp - rp).norm() < 1e-10, "{fr:?} vs {rs} {rp}");
    }
}

/// Found by the property above in CI: both directions at 89.999° in backscatter (θN = 89.999°),
/// a narrow lobe, no shadowing. With σ = 3.4°, D = 4.5·10⁻³⁰³ is normal and the geometric
/// factor `cos²θN/(4cos²θi cos²θr) = 1/(4cos²θ)` is 8·10⁸, so F00 = 3.05·10⁻²⁹⁴; forming
/// `D·s_z²` first (2·10⁻³¹²) had passed through the subnormal range and lost digits (mpmath at
/// 40 digits: F00 = 3.050083860750443e-294 in both forms). With σ = 3.3645° (the case CI found,
/// F00 = 1.09·10⁻³⁰⁰) D = 1.6·10⁻³⁰⁹ is itself subnormal, and the surface term is exactly zero
/// (docs/model.md §9.9).
#[test]
fn a_near_underflow_d_keeps_its_digits_at_grazing() {
    let at = |sigma_deg: f64, paper: bool| {
        let model = Model {
            n: 0.0501,
            k: 0.0,
            sigma_deg,
            paper,
            shadow: false,
            eq3: false,
            rho_d: 0.0,
            rho_v: 0.0,
        };
        let m = model.material();
        let t = 89.999f64.to_radians();
        let (f_s, _, want) = model.pbrdf(m.distribution().a(), t, 0.0, t, 0.0);
        (
            m.evaluate(&Geometry::new(t, 0.0, t, 0.0).unwrap()),
            f_s,
            want,
        )
    };
    for paper in [true, false] {
        let (e, f_s, want) = at(3.4, paper);
        assert!(
            max_diff(&e.pbrdf.0, &want, f_s) < 1e-9,
            "{:?}\n{want:?}",
            e.pbrdf.0
        );
        assert!(
            (e.surface / 3.050083860750443e-294 - 1.0).abs() < 1e-9,
            "{}",
            e.surface
        );
        let (e, f_s, _) = at(3.3645022360942476, paper);
        assert!(f_s > 1e-301, "f_s = {f_s}");
        assert!(
            e.pbrdf.0.iter().flatten().all(|&v| v == 0.0),
            "{:?}",
            e.pbrdf.0
        );
        assert_eq!(e.surface, 0.0);
    }
}

// ---------------------------------------------------------------------------------------------
// invariance, continuity, reciprocity

proptest! {
    #![proptest_config(config(10000))]

    #[test]
    fn invariant_under_rotation_of_both_azimuths(
        model in model(),
        angles in angles_deg(),
        delta_deg in prop_oneof![-720.0..=720.0f64, Just(180.0), Just(-360.0)],
    ) {
        // F depends on the azimuths only through Δ = φr − φi. `rotated` adds δ in f64, which
        // moves φi and φr by up to half an ulp each: the rotated geometry is the original one
        // with Δ perturbed by at most u = 2ε(|φi| + |φr| + 2|δ| + 1). Where F is ill-conditioned
        // in Δ (grazing and almost specular, where a 1e-15 change of Δ tilts the half vector
        // sideways and changes ΦN), that perturbation is visible. So the test is backward: the
        // rotated F differs from F by 1e-9·F00 at most, plus what F itself does when Δ moves by
        // a few u (one-sided, both ways: at an in-plane geometry ΦN ∝ |Δ − π| has a kink).
        // At every well-conditioned geometry that extra term is ~1e-14.
        let m = model.material();
        let g = geometry(angles);
        let delta = delta_deg.to_radians();
        let base = m.pbrdf(&g);
        let turned = m.pbrdf(&g.rotated(delta));
        let f00 = base.0[0][0];
        let d = max_diff(&turned.0, &base.0, f00);
        let u = 2.0 * f64::EPSILON * (g.phi_i().abs() + g.phi_r().abs() + 2.0 * delta.abs() + 1.0);
        let shifted = |s: f64| {
            let g = Geometry::new(g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r() + s).unwrap();
            max_diff(&m.pbrdf(&g).0, &base.0, f00)
        };
        let wobble = shifted(4.0 * u).max(shifted(-4.0 * u));
        let tol = 1e-9 + 4.0 * wobble;
        prop_assert!(d <= tol || base == turned, "rotation by {delta_deg}°: {d:e} (tolerance {tol:e})\n{base:?}\n{turned:?}");
    }

    #[test]
    fn continuous_at_backscatter(
        model in model(),
        theta in 0.0..80.0f64,
        phi in -720.0..=720.0f64,
        dir in (-1.0..=1.0f64, -1.0..=1.0f64, -1.0..=1.0f64, -1.0..=1.0f64),
    ) {
        // β → 0: the facet-frame choice s_l = s_in at β = 0 (docs/model.md §4) is the continuous limit.
        let m = model.material();
        let (t, p) = (theta.to_radians(), phi.to_radians());
        let at = m.evaluate(&Geometry::backscatter(t, p).unwrap());
        prop_assert_eq!(at.terms.unwrap().angles.beta, 0.0);
        let delta = 1e-7;
        let norm = (dir.0.abs() + dir.1.abs() + dir.2.abs() + dir.3.abs()).max(1e-3);
        let step = [dir.0, dir.1, dir.2, dir.3].map(|x| delta * x / norm);
        let near = Geometry::new(
            (t + step[0]).abs(),
            p + step[1],
            (t + step[2]).abs(),
            p + step[3],
        ).unwrap();
        let en = m.evaluate(&near);
        let beta = en.terms.unwrap().angles.beta;
        prop_assert!(beta <= delta);
        if at.surface > 1e-250 && en.surface > 1e-250 {
            // The polarization: normalized surface Mueller matrices agree to O(δ).
            let d = max_diff(&surface_normalized(&en), &surface_normalized(&at), 1.0);
            prop_assert!(d < 1e-6, "normalized surface matrix jumps by {d:e} at β = {beta:e}");
        }
        // The scalar: Lipschitz with the slope of ln D (2bθN), of 1/cos (tanθ, twice for the
        // paper form), of SO and of R_F (both O(1)).
        let sigma = model.sigma_deg.to_radians();
        let slope = 2.0 * t / (sigma * sigma) + 4.0 * t.tan() + 20.0;
        let (f0, f1) = (at.brdf(), en.brdf());
        prop_assert!((f1 - f0).abs() <= delta * slope * f0 + 1e-300, "f {f0} → {f1}");
    }

    #[test]
    fn continuous_at_normal_incidence(
        model in model(),
        phi_i in -720.0..=720.0f64,
        theta_r in prop_oneof![3 => 0.0..80.0f64, 1 => Just(0.0)],
        phi_r in -720.0..=720.0f64,
        tiny in prop_oneof![Just(1e-9), 1e-12..1e-8f64],
        source_side in any::<bool>(),
    ) {
        // θ → 0⁺ at fixed φ (docs/model.md §2–3): θ = 1e-9 and θ = 0 give the same F.
        let m = model.material();
        let (pi, tr, pr) = (phi_i.to_radians(), theta_r.to_radians(), phi_r.to_radians());
        let (g0, g1) = if source_side {
            (Geometry::new(0.0, pi, tr, pr).unwrap(), Geometry::new(tiny, pi, tr, pr).unwrap())
        } else {
            (Geometry::new(tr, pi, 0.0, pr).unwrap(), Geometry::new(tr, pi, tiny, pr).unwrap())
        };
        let (e0, e1) = (m.evaluate(&g0), m.evaluate(&g1));
        let f00 = e0.brdf();
        let d = max_diff(&e1.pbrdf.0, &e0.pbrdf.0, f00);
        let sigma = model.sigma_deg.to_radians();
        let slope = 2.0 * tr / (sigma * sigma) + 4.0 * tr.tan() + 20.0;
        // Fresnel is continuous but not Lipschitz at a critical angle (sinβ = n, k = 0: q has a
        // square-root branch point), so the reflection coefficients are allowed to change as
        // much as they do between the two local angles (computed independently).
        let beta = |g: &Geometry| {
            reference::angles(g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()).beta
        };
        let (rs0, rp0) = reference::fresnel(model.n, model.k, beta(&g0));
        let (rs1, rp1) = reference::fresnel(model.n, model.k, beta(&g1));
        let r0 = 0.5 * (rs0.norm_sqr() + rp0.norm_sqr());
        let fresnel_change = [
            rs1.norm_sqr() - rs0.norm_sqr(),
            rp1.norm_sqr() - rp0.norm_sqr(),
            (rs1 * rp1.conj() - rs0 * rp0.conj()).norm(),
        ]
        .into_iter()
        .fold(0.0_f64, |m, v| m.max(v.abs()))
            / r0;
        let tol = tiny * slope + 4.0 * fresnel_change + 1e-12;
        prop_assert!(d <= tol || f00 < 1e-250, "θ → 0: {d:e} (tolerance {tol:e})\n{:?}\n{:?}", e0.pbrdf, e1.pbrdf);
    }

    #[test]
    fn reciprocity(model in model(), angles in angles_deg()) {
        // Scalar: f(i → r) = f(r → i) whenever SO is (azimuth term none); θN, β, the cosines
        // and the volume term are symmetric.
        // Mueller: docs/model.md's T = Rot(η_r)·diag(rs, rp)·Rot(−η_i); exchanging source and detector
        // gives η_i' = −η_r, η_r' = −η_i (closed forms of docs/model.md §4 under θi ↔ θr, Δ → −Δ), and
        // the reciprocal beams' frames are (−s, p). Hence T' = D·Tᵀ·D with D = diag(1, −1), and
        // with M(Tᵀ) = Q·M(T)ᵀ·Q, Q = diag(1, 1, 1, −1) (from A (T ⊗ T*) A⁻¹) and
        // M(D) = diag(1, 1, −1, −1): F' = P·Fᵀ·P with P = diag(1, 1, −1, 1).
        let m = model.material();
        let g = geometry(angles);
        let (e, er) = (m.evaluate(&g), m.evaluate(&g.reciprocal()));
        let p = [1.0, 1.0, -1.0, 1.0];
        let reflect = |f: &Mat4| {
            let t = transpose(f);
            let mut out = [[0.0; 4]; 4];
            for i in 0..4 {
                for j in 0..4 {
                    out[i][j] = p[i] * t[i][j] * p[j];
                }
            }
            out
        };
        if !model.eq3 {
            let (f, fr) = (e.brdf(), er.brdf());
            prop_assert!((f - fr).abs() <= 1e-12 * f + 1e-300, "f = {f}, reciprocal {fr}");
            let d = max_diff(&er.pbrdf.0, &reflect(&e.pbrdf.0), f);
            prop_assert!(d <= 1e-9, "F' vs P·Fᵀ·P: {d:e}\n{:?}\n{:?}", e.pbrdf, er.pbrdf);
        } else if e.surface > 1e-250 && er.surface > 1e-250 {
            // With eq3 the scalar SO is not symmetric (ΦN is measured from the incidence plane,
            // times θi), but the polarization of the surface term still is.
            let d = max_diff(
                &surface_normalized(&er),
                &reflect(&surface_normalized(&e)),
                1.0,
            );
            prop_assert!(d <= 1e-9, "normalized F' vs P·Fᵀ·P: {d:e}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// the batch API

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn batch_equals_per_element(
        model in model(),
        all in prop::collection::vec(angles_deg(), 0..40),
    ) {
        let m = model.material();
        let rad: Vec<[f64; 4]> = all.iter().map(|a| a.map(f64::to_radians)).collect();
        let col = |i: usize| rad.iter().map(|a| a[i]).collect::<Vec<_>>();
        let (ti, pi, tr, pr) = (col(0), col(1), col(2), col(3));
        let batch = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
        check_batch(&m, &batch)?;
    }
}

fn check_batch(m: &Material, batch: &GeometryBatch<'_>) -> Result<(), TestCaseError> {
    // The batch API runs the vectorized kernel (`polbrdf::engine`): the same equations as
    // `Material::evaluate`, to within 1e-12·F00 (tests/kernel.rs checks it in depth).
    let got = mueller(m, batch).unwrap();
    let mut brdf = vec![f64::NAN; batch.len()];
    let mut dolp = vec![f64::NAN; batch.len()];
    brdf_dolp_into(m, batch, &mut brdf, &mut dolp).unwrap();
    prop_assert_eq!(got.len(), batch.len());
    for i in 0..batch.len() {
        let e = m.evaluate(&batch.get(i));
        let want = e.pbrdf.to_row_major();
        let f00 = want[0];
        for (k, (g, w)) in got[i].iter().zip(&want).enumerate() {
            prop_assert!(
                (g - w).abs() <= 1e-12 * f00 || (f00 == 0.0 && *g == 0.0),
                "element {} entry {}: {} vs {}",
                i,
                k,
                g,
                w
            );
        }
        prop_assert!((brdf[i] - e.brdf()).abs() <= 1e-12 * e.brdf(), "brdf {}", i);
        prop_assert!((dolp[i] - e.dolp()).abs() <= 1e-12, "dolp {}", i);
    }
    Ok(())
}

#[test]
fn large_batch_across_chunks_equals_per_element() {
    let mut rng = Lcg(42);
    let n = 5000; // more than two parallel chunks
    let mut cols = [vec![], vec![], vec![], vec![]];
    for _ in 0..n {
        cols[0].push((rng.uniform() * 0.5 + 0.5) * 95f64.to_radians()); // some below the horizon
        cols[1].push(rng.uniform() * 4.0 * PI);
        cols[2].push((rng.uniform() * 0.5 + 0.5) * 89.9f64.to_radians());
        cols[3].push(rng.uniform() * 4.0 * PI);
    }
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let m = Model {
        rho_d: 0.03,
        rho_v: 0.01,
        ..Model::new(1.65, 0.0, 15.0)
    }
    .material();
    check_batch(&m, &batch).unwrap();
    // mueller_into agrees with mueller.
    let mut out = vec![[f64::NAN; 16]; n];
    mueller_into(&m, &batch, &mut out).unwrap();
    assert_eq!(out, mueller(&m, &batch).unwrap());
}

/// The batch's validation (a vectorized test of each chunk, element by element only where it
/// fails) accepts and rejects exactly what `Geometry::new` does, at the edges of every range,
/// and reports the element (also far into a batch, beyond the first chunk).
#[test]
fn batch_validation_is_geometry_new_at_the_edges() {
    let max_az = polbrdf::MAX_AZIMUTH_DEG.to_radians();
    let zeniths = [
        0.0,
        -0.0,
        1e-300,
        PI,
        PI.next_up(),
        -1e-300,
        f64::NAN,
        f64::INFINITY,
    ];
    let azimuths = [
        0.0,
        -max_az,
        max_az,
        max_az.next_up(),
        -max_az.next_up(),
        f64::NAN,
        -f64::INFINITY,
    ];
    let n = 10_000;
    for (slot, values) in [
        (0, &zeniths[..]),
        (1, &azimuths[..]),
        (2, &zeniths[..]),
        (3, &azimuths[..]),
    ] {
        for &v in values {
            let mut cols = [vec![0.3; n], vec![0.2; n], vec![0.4; n], vec![1.0; n]];
            let at = n - 3;
            cols[slot][at] = v;
            let mut g = [0.3, 0.2, 0.4, 1.0];
            g[slot] = v;
            let single = Geometry::new(g[0], g[1], g[2], g[3]);
            let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]);
            assert_eq!(batch.is_ok(), single.is_ok(), "slot {slot}, value {v}");
            if let Err(e) = batch {
                assert!(
                    matches!(e, Error::InvalidAngle { index: Some(i), .. } if i == at),
                    "slot {slot}, value {v}: {e}"
                );
            }
        }
    }
}

#[test]
fn batch_errors_name_the_element_and_the_slice() {
    let ok = [0.1, 0.2, 0.3];
    let bad = [0.1, f64::NAN, 0.3];
    let msg = GeometryBatch::new(&ok, &ok, &bad, &ok)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("`theta_r`") && msg.contains("NaN") && msg.contains("index 1"),
        "{msg}"
    );
    let neg = [0.1, 0.2, -0.3];
    let msg = GeometryBatch::new(&neg, &ok, &ok, &ok)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("`theta_i`") && msg.contains("-0.3") && msg.contains("index 2"),
        "{msg}"
    );
    let short = [0.1, 0.2];
    let err = GeometryBatch::new(&ok, &short, &ok, &ok).unwrap_err();
    assert!(matches!(
        err,
        Error::LengthMismatch {
            name: "phi_i",
            got: 2,
            expected: 3
        }
    ));
    let batch = GeometryBatch::new(&ok, &ok, &ok, &ok).unwrap();
    let m = Model::new(1.5, 0.0, 10.0).material();
    let (mut b, mut d) = (vec![0.0; 3], vec![0.0; 2]);
    let err = brdf_dolp_into(&m, &batch, &mut b, &mut d).unwrap_err();
    assert!(err.to_string().contains("`dolp`"), "{err}");
    let mut out = vec![[0.0; 16]; 4];
    assert!(mueller_into(&m, &batch, &mut out).is_err());
    // An empty batch is fine.
    let empty: [f64; 0] = [];
    let batch = GeometryBatch::new(&empty, &empty, &empty, &empty).unwrap();
    assert!(batch.is_empty() && mueller(&m, &batch).unwrap().is_empty());
}
