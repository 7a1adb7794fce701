//! Analytic limits of the model (docs/model.md §1–6, §13).
//!
//! Every expected value here is computed independently of the library, from textbook formulas
//! (Snell's law form of the Fresnel coefficients, vector algebra for the beam and facet frames,
//! brute-force complex matrix products for `A (T ⊗ T*) A⁻¹`). The module `reference` is that
//! independent implementation; `properties.rs` uses it too.

#![allow(clippy::needless_range_loop)]

use num_complex::Complex64 as C;
use polbrdf::{
    AngleVariables, AzimuthTerm, Distribution, Error, Geometry, Jones, Material, MaterialSpec,
    Mueller, RefractiveIndex, Shadowing, Stokes,
};
use reference::{Mat4, Model};
use std::f64::consts::{FRAC_PI_2, PI};

/// An independent implementation of the model, written from the definitions of docs/model.md with vector
/// algebra (no closed forms shared with the library).
pub(crate) mod reference {
    use num_complex::Complex64 as C;
    use polbrdf::{AzimuthTerm, Form, Material, MaterialSpec};
    use std::f64::consts::{FRAC_PI_2, PI};

    pub type Mat4 = [[f64; 4]; 4];
    pub type Jones2 = [[C; 2]; 2];
    pub type V3 = [f64; 3];

    /// Fresnel amplitudes in Snell's-law form: `cosθt = sqrt(1 − sin²θ/N²)` on the branch with
    /// `Im(N cosθt) ≥ 0` (decaying transmitted wave for exp(−iωt)),
    /// `rs = (cosθ − N cosθt)/(cosθ + N cosθt)`, `rp = (N cosθ − cosθt)/(N cosθ + cosθt)`.
    pub fn fresnel(n: f64, k: f64, theta: f64) -> (C, C) {
        let nn = C::new(n, k);
        let (s, c) = theta.sin_cos();
        let x = C::new(s, 0.0) / nn;
        let mut ct = (C::new(1.0, 0.0) - x * x).sqrt();
        if (nn * ct).im < 0.0 {
            ct = -ct;
        }
        let rs = (c - nn * ct) / (c + nn * ct);
        let rp = (nn * c - ct) / (nn * c + ct);
        (rs, rp)
    }

    /// `R_F = (|rs|² + |rp|²)/2`.
    pub fn reflectance(n: f64, k: f64, theta: f64) -> f64 {
        let (rs, rp) = fresnel(n, k, theta);
        0.5 * (rs.norm_sqr() + rp.norm_sqr())
    }

    /// Stokes vector of a Jones vector, docs/model.md §2–3 definition.
    pub fn stokes(es: C, ep: C) -> [f64; 4] {
        let x = es * ep.conj();
        [
            es.norm_sqr() + ep.norm_sqr(),
            es.norm_sqr() - ep.norm_sqr(),
            2.0 * x.re,
            -2.0 * x.im,
        ]
    }

    fn mat_mul(a: &[[C; 4]; 4], b: &[[C; 4]; 4]) -> [[C; 4]; 4] {
        let mut out = [[C::new(0.0, 0.0); 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                for k in 0..4 {
                    out[i][j] += a[i][k] * b[k][j];
                }
            }
        }
        out
    }

    /// Inverse of a complex 4×4 matrix by Gauss–Jordan elimination with partial pivoting.
    fn inverse(m: &[[C; 4]; 4]) -> [[C; 4]; 4] {
        let mut a = *m;
        let mut inv = [[C::new(0.0, 0.0); 4]; 4];
        for i in 0..4 {
            inv[i][i] = C::new(1.0, 0.0);
        }
        for col in 0..4 {
            let piv = (col..4)
                .max_by(|&x, &y| a[x][col].norm().total_cmp(&a[y][col].norm()))
                .unwrap();
            a.swap(col, piv);
            inv.swap(col, piv);
            let p = a[col][col];
            assert!(p.norm() > 1e-12, "singular matrix");
            for j in 0..4 {
                a[col][j] /= p;
                inv[col][j] /= p;
            }
            for r in 0..4 {
                if r != col {
                    let f = a[r][col];
                    for j in 0..4 {
                        let (acj, icj) = (a[col][j], inv[col][j]);
                        a[r][j] -= f * acj;
                        inv[r][j] -= f * icj;
                    }
                }
            }
        }
        inv
    }

    /// `M = A (T ⊗ T*) A⁻¹` (docs/model.md §4), by brute force; asserts the result is real.
    pub fn mueller(t: &Jones2) -> Mat4 {
        let (o, l, i) = (C::new(0.0, 0.0), C::new(1.0, 0.0), C::new(0.0, 1.0));
        let a = [[l, o, o, l], [l, o, o, -l], [o, l, l, o], [o, i, -i, o]];
        let mut kron = [[o; 4]; 4];
        for r in 0..2 {
            for c in 0..2 {
                for p in 0..2 {
                    for q in 0..2 {
                        kron[2 * r + p][2 * c + q] = t[r][c] * t[p][q].conj();
                    }
                }
            }
        }
        let m = mat_mul(&mat_mul(&a, &kron), &inverse(&a));
        let scale: f64 = t.iter().flatten().map(|z| z.norm_sqr()).sum::<f64>() + 1e-300;
        let mut out = [[0.0; 4]; 4];
        for r in 0..4 {
            for c in 0..4 {
                assert!(m[r][c].im.abs() <= 1e-13 * scale, "Mueller entry not real");
                out[r][c] = m[r][c].re;
            }
        }
        out
    }

    pub fn dot(a: V3, b: V3) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }
    pub fn cross(a: V3, b: V3) -> V3 {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }
    pub fn norm(a: V3) -> f64 {
        dot(a, a).sqrt()
    }
    pub fn unit(a: V3) -> V3 {
        let l = norm(a);
        [a[0] / l, a[1] / l, a[2] / l]
    }
    pub fn neg(a: V3) -> V3 {
        [-a[0], -a[1], -a[2]]
    }
    pub fn dir(theta: f64, phi: f64) -> V3 {
        [
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ]
    }

    /// The beam frame (s, p) of propagation direction `k` whose direction away from the surface
    /// has azimuth `phi`: `s = unit(z × k)`, `p = k × s`; at k = ±z the θ → 0⁺ limit.
    pub fn frame(k: V3, phi: f64, incident: bool) -> (V3, V3) {
        let zk = cross([0.0, 0.0, 1.0], k);
        let s = if norm(zk) > 1e-300 {
            unit(zk)
        } else if incident {
            // k = −w, w → z at azimuth φ: z × (−w)/|…| → (sinφ, −cosφ, 0)
            [phi.sin(), -phi.cos(), 0.0]
        } else {
            [-phi.sin(), phi.cos(), 0.0]
        };
        (s, cross(k, s))
    }

    /// Angle variables from vectors (docs/model.md §1): θN, β, ΦN.
    pub struct Angles {
        pub theta_n: f64,
        pub beta: f64,
        pub phi_n: f64,
    }

    pub fn angles(ti: f64, pi: f64, tr: f64, pr: f64) -> Angles {
        let (wi, wr) = (dir(ti, pi), dir(tr, pr));
        let h = unit([wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]]);
        let theta_n = h[0].hypot(h[1]).atan2(h[2]);
        let beta = norm(cross(wi, h)).atan2(dot(wi, h));
        let phi_n = if theta_n < 1e-12 {
            0.0
        } else {
            let d = (h[1].atan2(h[0]) - pi).rem_euclid(PI);
            d.min(PI - d)
        };
        Angles {
            theta_n,
            beta,
            phi_n,
        }
    }

    /// The Jones matrix of the facet reflection by vector algebra: decompose the incident field
    /// on the facet's s/p axes, apply rs/rp, project on the reflected beam's (s, p). At β = 0
    /// the facet is seen at normal incidence and reflects every transverse field by
    /// `(1 − N)/(1 + N)`.
    pub fn jones(n: f64, k: f64, ti: f64, pi: f64, tr: f64, pr: f64) -> Jones2 {
        let (wi, wr) = (dir(ti, pi), dir(tr, pr));
        let (k_in, k_out) = (neg(wi), wr);
        let (s_in, p_in) = frame(k_in, pi, true);
        let (s_out, p_out) = frame(k_out, pr, false);
        let ins = [s_in, p_in];
        let outs = [s_out, p_out];
        let mut t = [[C::new(0.0, 0.0); 2]; 2];
        if norm(cross(wi, wr)) == 0.0 && dot(wi, wr) > 0.0 {
            let nn = C::new(n, k);
            let r = (1.0 - nn) / (1.0 + nn);
            for a in 0..2 {
                for b in 0..2 {
                    t[a][b] = r * dot(outs[a], ins[b]);
                }
            }
            return t;
        }
        let h = unit([wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]]);
        let beta = norm(cross(wi, h)).atan2(dot(wi, h));
        let (rs, rp) = fresnel(n, k, beta);
        let s_l = unit(cross(h, k_in));
        let p_l_in = cross(k_in, s_l);
        let p_l_out = cross(k_out, s_l);
        for a in 0..2 {
            for b in 0..2 {
                t[a][b] = rs * dot(outs[a], s_l) * dot(s_l, ins[b])
                    + rp * dot(outs[a], p_l_out) * dot(p_l_in, ins[b]);
            }
        }
        t
    }

    /// A material as the test writes it (angles in degrees, as in material files).
    #[derive(Debug, Clone, Copy)]
    pub struct Model {
        pub n: f64,
        pub k: f64,
        pub sigma_deg: f64,
        pub paper: bool,
        pub shadow: bool,
        pub eq3: bool,
        pub rho_d: f64,
        pub rho_v: f64,
    }

    pub const TAU_DEG: f64 = 15.0;
    pub const OMEGA_DEG: f64 = 40.0;

    impl Model {
        pub fn new(n: f64, k: f64, sigma_deg: f64) -> Self {
            Self {
                n,
                k,
                sigma_deg,
                paper: false,
                shadow: true,
                eq3: false,
                rho_d: 0.0,
                rho_v: 0.0,
            }
        }

        pub fn spec(&self) -> MaterialSpec {
            MaterialSpec {
                name: None,
                n: self.n,
                k: self.k,
                sigma_deg: Some(self.sigma_deg),
                b: None,
                a: None,
                form: if self.paper {
                    Form::Paper
                } else {
                    Form::Standard
                },
                shadowing: self.shadow,
                tau_deg: TAU_DEG,
                omega_deg: OMEGA_DEG,
                azimuth_term: if self.eq3 {
                    AzimuthTerm::Eq3
                } else {
                    AzimuthTerm::None
                },
                rho_d: self.rho_d,
                rho_v: self.rho_v,
                spectral: None,
            }
        }

        pub fn material(&self) -> Material {
            self.spec().build().expect("valid material")
        }

        /// SO of eq. 3 by hand (radians).
        pub fn so(&self, theta_i: f64, a: &Angles) -> f64 {
            if !self.shadow {
                return 1.0;
            }
            let (tau, omega) = (TAU_DEG.to_radians(), OMEGA_DEG.to_radians());
            let x = a.theta_n / omega;
            let so = (1.0 + x * (-2.0 * a.beta / tau).exp()) / (1.0 + x);
            if self.eq3 {
                so / (1.0 + a.phi_n * theta_i / omega)
            } else {
                so
            }
        }

        /// D of eq. 4 with `b = 1/σ²` and the given `a`.
        pub fn d(&self, a_norm: f64, theta_n: f64) -> f64 {
            let sigma = self.sigma_deg.to_radians();
            a_norm * (-(theta_n * theta_n) / (sigma * sigma)).exp()
        }

        /// (f_s, f_v, F) by the formulas of docs/model.md §5–6, with `a` of the distribution given (it is
        /// checked against a brute-force normalization separately).
        pub fn pbrdf(&self, a_norm: f64, ti: f64, pi: f64, tr: f64, pr: f64) -> (f64, f64, Mat4) {
            if ti >= FRAC_PI_2 || tr >= FRAC_PI_2 {
                return (0.0, 0.0, [[0.0; 4]; 4]);
            }
            let ang = angles(ti, pi, tr, pr);
            let d = self.d(a_norm, ang.theta_n);
            let r_f = reflectance(self.n, self.k, ang.beta);
            let so = self.so(ti, &ang);
            let (ci, cr, cn) = (ti.cos(), tr.cos(), ang.theta_n.cos());
            // D last, so that the product cannot pass through the subnormal range when D is
            // near underflow and the geometric factor is large (both directions near grazing).
            let f_s = if self.paper {
                d * (r_f * cn * cn * so / (4.0 * ci * ci * cr * cr))
            } else {
                d * (r_f * so / (4.0 * ci * cr))
            };
            let f_v = self.rho_d + 2.0 * self.rho_v / (ci + cr);
            let m = mueller(&jones(self.n, self.k, ti, pi, tr, pr));
            let mut f = [[0.0; 4]; 4];
            if m[0][0] > 0.0 {
                for r in 0..4 {
                    for c in 0..4 {
                        f[r][c] = f_s * m[r][c] / m[0][0];
                    }
                }
            }
            f[0][0] += f_v;
            (f_s, f_v, f)
        }
    }
}

// ---------------------------------------------------------------------------------------------
// helpers

const DIELECTRICS: [f64; 4] = [1.33, 1.52, 1.65, 2.4];
/// (n, k) of the presets' metals at 632.8 nm.
const METALS: [(f64, f64); 5] = [
    (1.37, 7.62),
    (0.181, 3.07),
    (0.0562, 4.28),
    (0.270, 3.41),
    (2.91, 3.08),
];

fn deg(x: f64) -> f64 {
    x.to_radians()
}

fn material(n: f64, k: f64, sigma_deg: f64) -> Material {
    Model::new(n, k, sigma_deg).material()
}

fn normalized(f: &Mueller) -> Mat4 {
    let f00 = f.0[0][0];
    assert!(f00 > 0.0, "F00 = {f00}");
    let mut m = f.0;
    m.iter_mut().flatten().for_each(|v| *v /= f00);
    m
}

fn assert_mat_close(got: &Mat4, want: &Mat4, tol: f64, what: &str) {
    for r in 0..4 {
        for c in 0..4 {
            assert!(
                (got[r][c] - want[r][c]).abs() <= tol,
                "{what}: [{r}][{c}] = {}, expected {}\n got  {got:?}\n want {want:?}",
                got[r][c],
                want[r][c]
            );
        }
    }
}

fn rel_close(got: f64, want: f64, rtol: f64) -> bool {
    (got - want).abs() <= rtol * want.abs().max(got.abs())
}

/// The textbook Mueller matrix of a reflection `diag(rs, rp)`, normalized by its M00:
/// `[[A,B,0,0],[B,A,0,0],[0,0,C,S],[0,0,−S,C]]/A`.
fn fresnel_mueller(n: f64, k: f64, theta: f64) -> Mat4 {
    let (rs, rp) = reference::fresnel(n, k, theta);
    let a = 0.5 * (rs.norm_sqr() + rp.norm_sqr());
    let b = 0.5 * (rs.norm_sqr() - rp.norm_sqr());
    let x = rs * rp.conj();
    let (c, s) = (x.re, x.im);
    [
        [1.0, b / a, 0.0, 0.0],
        [b / a, 1.0, 0.0, 0.0],
        [0.0, 0.0, c / a, s / a],
        [0.0, 0.0, -s / a, c / a],
    ]
}

fn mat_mul(a: &Mat4, b: &Mat4) -> Mat4 {
    let mut out = [[0.0; 4]; 4];
    for i in 0..4 {
        for j in 0..4 {
            out[i][j] = (0..4).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// normal incidence and the mirror matrix

#[test]
fn normal_incidence_fresnel_reflectance_is_textbook() {
    let mut indices: Vec<(f64, f64)> = DIELECTRICS.iter().map(|&n| (n, 0.0)).collect();
    indices.extend(METALS);
    indices.push((0.5, 0.0));
    for (n, k) in indices {
        let want = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
        let fr = RefractiveIndex::new(n, k).unwrap().amplitudes(0.0);
        assert!(
            rel_close(fr.reflectance(), want, 1e-14),
            "R_F(0) for N = {n}+{k}i: {} vs {want}",
            fr.reflectance()
        );
        // rs(0) = (1 − N)/(1 + N), rp(0) = −rs(0) (docs/model.md §2–3).
        let nn = C::new(n, k);
        let rs0 = (1.0 - nn) / (1.0 + nn);
        assert!((fr.rs - rs0).norm() < 1e-15, "rs(0) for N = {n}+{k}i");
        assert!((fr.rp + rs0).norm() < 1e-15, "rp(0) for N = {n}+{k}i");
        // The model's F00 at θi = θr = 0: D(0)·R_F(0)·SO/4 with SO = 1, D(0) = a.
        let m = material(n, k, 10.0);
        let e = m.evaluate(&Geometry::new(0.0, 0.3, 0.0, 0.3 + PI).unwrap());
        let f00 = m.distribution().a() * want / 4.0;
        assert!(
            rel_close(e.brdf(), f00, 1e-13),
            "F00 at normal: {}",
            e.brdf()
        );
    }
}

#[test]
fn normal_incidence_gives_no_linear_polarization() {
    for (n, k) in [(1.65, 0.0), (1.37, 7.62), (2.91, 3.08)] {
        let mut model = Model::new(n, k, 10.0);
        for (rho_d, rho_v) in [(0.0, 0.0), (0.03, 0.01)] {
            model.rho_d = rho_d;
            model.rho_v = rho_v;
            let m = model.material();
            for (pi, pr) in [(0.0, 0.0), (0.0, 180.0), (30.0, 75.0), (-400.0, 10.0)] {
                let g = Geometry::from_degrees(0.0, pi, 0.0, pr).unwrap();
                let e = m.evaluate(&g);
                assert!(e.brdf() > 0.0);
                assert!(e.dolp() < 1e-14, "DoLP at normal incidence = {}", e.dolp());
                let out = e.reflect(&Stokes::unpolarized());
                assert!(out.dop() < 1e-14, "unpolarized stays unpolarized");
            }
        }
    }
}

#[test]
fn mirror_at_beta_zero_is_diag_1_1_minus1_minus1() {
    let mirror = Mueller::diagonal([1.0, 1.0, -1.0, -1.0]).0;
    for (n, k) in [(1.65, 0.0), (0.5, 0.0), (1.37, 7.62), (0.181, 3.07)] {
        let m = material(n, k, 10.0);
        // Normal incidence, both azimuth conventions (backscatter φr = φi, specular φr = φi + π),
        // and backscatter at oblique incidence: the facet is always seen at β = 0.
        let mut geometries = vec![
            Geometry::backscatter(0.0, 0.0).unwrap(),
            Geometry::specular(0.0, 0.0).unwrap(),
            Geometry::specular(0.0, deg(123.0)).unwrap(),
        ];
        for theta in [1e-6, 10.0, 45.0, 80.0, 89.0] {
            for phi in [0.0, 77.0, -200.0] {
                geometries.push(Geometry::backscatter(deg(theta), deg(phi)).unwrap());
            }
        }
        for g in geometries {
            let e = m.evaluate(&g);
            assert_eq!(e.terms.unwrap().angles.beta, 0.0);
            assert_mat_close(
                &normalized(&e.pbrdf),
                &mirror,
                1e-14,
                &format!("N = {n}+{k}i at {g:?}"),
            );
        }
    }
}

#[test]
fn beta_zero_matches_physical_normal_incidence_reflection() {
    // At θi = θr = 0 with arbitrary azimuths, and at backscatter, the reflected field is
    // (1 − N)/(1 + N) times the incident transverse field; T follows from projecting on the
    // beam frames (docs/model.md §2–3), M from A (T ⊗ T*) A⁻¹.
    let model = Model::new(1.65, 0.4, 10.0);
    let m = model.material();
    let mut cases = vec![];
    for (pi, pr) in [
        (0.0, 90.0),
        (0.0, -90.0),
        (20.0, 65.0),
        (10.0, 190.0),
        (0.0, 0.0),
    ] {
        cases.push((0.0, pi, 0.0, pr));
    }
    for t in [5.0, 40.0, 85.0] {
        cases.push((t, -33.0, t, -33.0));
    }
    for (ti, pi, tr, pr) in cases {
        let (ti, pi, tr, pr) = (deg(ti), deg(pi), deg(tr), deg(pr));
        let want = reference::mueller(&reference::jones(model.n, model.k, ti, pi, tr, pr));
        let want = want.map(|row| row.map(|v| v / want[0][0]));
        let e = m.evaluate(&Geometry::new(ti, pi, tr, pr).unwrap());
        assert_mat_close(&normalized(&e.pbrdf), &want, 1e-13, "β = 0");
    }
}

#[test]
fn source_at_zenith_only_rotates_the_input_frame() {
    // θi = 0: the source direction does not depend on φi, only its (s, p) frame does. Turning
    // φi by δ turns s_in by δ, so F(φi + δ) = F(φi)·Rot_M(−δ) (Rot_M = Mueller rotator); the
    // first column (unpolarized input: f, DoLP) does not change.
    let m = material(1.65, 0.0, 15.0);
    for tr in [0.0, 20.0, 60.0] {
        let base = m.pbrdf(&Geometry::from_degrees(0.0, 0.0, tr, 40.0).unwrap());
        for delta in [10.0, 45.0, 90.0, -130.0] {
            let g = Geometry::from_degrees(0.0, delta, tr, 40.0).unwrap();
            let got = m.pbrdf(&g);
            let want = base * Mueller::rotator(-deg(delta));
            let f00 = base.0[0][0];
            assert_mat_close(
                &normalized(&got),
                &want.scaled(1.0 / f00).0,
                1e-12,
                "rotated input frame",
            );
            for r in 0..4 {
                assert!((got.0[r][0] - base.0[r][0]).abs() <= 1e-12 * f00);
            }
            if tr > 0.0 {
                // DoLP is not zero for θi = 0, θr > 0 (β = θr/2): the test can see a frame error.
                assert!(m.dolp(&g) > 1e-3);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// specular reflection: the Fresnel Mueller matrix

#[test]
fn specular_is_the_textbook_fresnel_mueller_matrix() {
    let mut indices: Vec<(f64, f64)> = DIELECTRICS.iter().map(|&n| (n, 0.0)).collect();
    indices.extend(METALS);
    indices.push((0.5, 0.0));
    for (n, k) in indices {
        let m = material(n, k, 1.0);
        let a = m.distribution().a();
        for theta in [0.0, 5.0, 20.0, 45.0, 56.0, 60.0, 75.0, 85.0, 89.9] {
            for phi in [0.0, 135.0, -300.0] {
                let t = deg(theta);
                let e = m.evaluate(&Geometry::specular(t, deg(phi)).unwrap());
                assert_mat_close(
                    &normalized(&e.pbrdf),
                    &fresnel_mueller(n, k, t),
                    1e-12,
                    &format!("N = {n}+{k}i, θ = {theta}°, φ = {phi}°"),
                );
                // f = D(0)·R_F(θ)·SO/(4cos²θ), SO = 1 at specular (standard form).
                let f = a * reference::reflectance(n, k, t) / (4.0 * t.cos() * t.cos());
                assert!(rel_close(e.brdf(), f, 1e-12), "f at specular: {}", e.brdf());
            }
        }
    }
}

#[test]
fn brewster_angle_gives_full_linear_polarization() {
    for n in [1.65f64, 1.33, 2.4, 0.5] {
        let theta_b = n.atan();
        let index = RefractiveIndex::new(n, 0.0).unwrap();
        assert!((index.brewster_angle() - theta_b).abs() < 1e-15);
        let fr = index.amplitudes(theta_b);
        assert!(fr.rp.norm() < 1e-14, "rp(θB) = {} for n = {n}", fr.rp);
        assert!(fr.rs.norm() > 0.05);

        for sigma in [2.0, 15.0] {
            let m = material(n, 0.0, sigma);
            let g = Geometry::specular(theta_b, deg(37.0)).unwrap();
            let e = m.evaluate(&g);
            assert!(
                (e.dolp() - 1.0).abs() < 1e-12,
                "DoLP at Brewster = {} (n = {n})",
                e.dolp()
            );
            // Reflected light is s-polarized: S1 > 0, S2 = 0 ⇒ AoLP = 0.
            let out = e.reflect(&Stokes::unpolarized());
            assert!(out.0[1] > 0.0 && out.0[2].abs() < 1e-15 * out.0[0]);
            assert!(out.aolp().abs() < 1e-15);

            // Away from Brewster: DoLP = (Rs − Rp)/(Rs + Rp) < 1, maximal at θB.
            for offset in [-20.0, -5.0, -0.5, 0.5, 5.0] {
                let t = theta_b + deg(offset);
                let (rs, rp) = reference::fresnel(n, 0.0, t);
                let want = (rs.norm_sqr() - rp.norm_sqr()) / (rs.norm_sqr() + rp.norm_sqr());
                let got = m.dolp(&Geometry::specular(t, 0.0).unwrap());
                assert!((got - want).abs() < 1e-12, "DoLP at θB{offset:+}°");
                assert!(got < 1.0 - 1e-6, "DoLP < 1 away from Brewster");
            }

            // With an unpolarized volume term: DoLP = f_s/(f_s + f_v) exactly.
            let mut model = Model::new(n, 0.0, sigma);
            model.rho_d = 0.05;
            model.rho_v = 0.02;
            let e = model.material().evaluate(&g);
            let f_v = 0.05 + 2.0 * 0.02 / (2.0 * theta_b.cos());
            assert!(rel_close(e.volume, f_v, 1e-14));
            let want = e.surface / (e.surface + f_v);
            assert!(want < 1.0 - 1e-4 && (e.dolp() - want).abs() < 1e-12);
        }
    }
}

#[test]
fn metals_never_fully_polarize_and_are_retarders() {
    // For exp(−iωt), N = n + ik, the rp convention of docs/model.md §3: S = Im(rs rp*) is 0 at normal
    // incidence (rp = −rs) and tends to 2cosθ·Im q > 0 toward grazing (q = sqrt(N² − sin²θ),
    // Im q > 0); the relative phase goes from π to 0 through π/2, so F23 = S·f/A > 0 and
    // F32 = −F23 for 0 < θ < 90°.
    for (n, k) in METALS {
        let m = material(n, k, 10.0);
        let mut max_dolp: f64 = 0.0;
        for i in 1..900 {
            let theta = deg(i as f64 * 0.1);
            let e = m.evaluate(&Geometry::specular(theta, 0.0).unwrap());
            let f = normalized(&e.pbrdf);
            max_dolp = max_dolp.max(e.dolp());
            assert!(f[2][3] > 0.0, "F23 > 0 for N = {n}+{k}i at {theta} rad");
            assert!((f[3][2] + f[2][3]).abs() < 1e-14);
            assert!((f[2][2] - f[3][3]).abs() < 1e-14);
            if i % 100 == 0 {
                // A visible retardance, not rounding noise.
                assert!(f[2][3] > 1e-3, "F23/F00 = {} at {i}/10 deg", f[2][3]);
            }
        }
        assert!(max_dolp < 0.99, "max DoLP = {max_dolp} for N = {n}+{k}i");
        // At normal incidence the retardance vanishes and circular handedness flips in psps.
        let e = m.evaluate(&Geometry::specular(0.0, 0.0).unwrap());
        assert!(e.pbrdf.0[2][3].abs() < 1e-15 * e.brdf());
        let out = e.reflect(&Stokes::circular(1.0));
        assert!((out.docp() + 1.0).abs() < 1e-14);
    }
    // Aluminium is a good reflector: DoLP stays small at every angle.
    let al = material(1.37, 7.62, 10.0);
    for i in 0..90 {
        let g = Geometry::specular(deg(i as f64), 0.0).unwrap();
        assert!(al.dolp(&g) < 0.2, "Al DoLP at {i}°");
    }
}

#[test]
fn dielectric_has_no_retardance_and_flips_circular_handedness_below_brewster() {
    // k = 0, n > 1: rs and rp real, so F23 = F32 = 0; C = rs·rp < 0 below Brewster (rs < 0,
    // rp > 0) and > 0 above. Circular input stays fully polarized with DoCP = 2 rs rp/(rs² + rp²):
    // −1 at normal incidence (handedness flips in the psps basis), 0 at Brewster (s-linear),
    // positive above Brewster.
    for n in DIELECTRICS {
        let m = material(n, 0.0, 10.0);
        let theta_b = n.atan();
        for i in 0..90 {
            let t = deg(i as f64);
            let e = m.evaluate(&Geometry::specular(t, deg(20.0)).unwrap());
            let f = normalized(&e.pbrdf);
            assert_eq!(f[2][3], 0.0, "F23 at {i}°, n = {n}");
            assert_eq!(f[3][2], 0.0, "F32 at {i}°, n = {n}");
            for input in [Stokes::circular(1.0), Stokes::circular(-1.0)] {
                let out = e.reflect(&input);
                assert!((out.dop() - 1.0).abs() < 1e-12, "DoP out at {i}°");
                assert!(out.0[2].abs() < 1e-15 * out.0[0], "no S2 from circular");
                let (rs, rp) = reference::fresnel(n, 0.0, t);
                let (rs, rp) = (rs.re, rp.re);
                let docp = input.0[3] * 2.0 * rs * rp / (rs * rs + rp * rp);
                assert!((out.docp() - docp).abs() < 1e-12, "DoCP at {i}°");
                let sign = input.0[3] * out.docp();
                if t < theta_b - 1e-3 {
                    assert!(sign < 0.0, "handedness flips below Brewster ({i}°)");
                } else if t > theta_b + 1e-3 {
                    assert!(sign > 0.0, "handedness kept above Brewster ({i}°)");
                }
            }
        }
        let e = m.evaluate(&Geometry::specular(0.0, 0.0).unwrap());
        assert!((e.reflect(&Stokes::circular(1.0)).docp() + 1.0).abs() < 1e-14);
        let e = m.evaluate(&Geometry::specular(theta_b, 0.0).unwrap());
        assert!(e.reflect(&Stokes::circular(1.0)).docp().abs() < 1e-12);
    }
}

#[test]
fn total_internal_reflection_is_a_lossless_retarder() {
    // n = 0.5, k = 0: beyond the critical angle asin(0.5) = 30°, |rs| = |rp| = 1, so R_F = 1,
    // no diattenuation (F01 = F10 = 0, DoLP = 0), and a pure retardance F22² + F23² = F00².
    let m = material(0.5, 0.0, 10.0);
    for theta in [35.0, 50.0, 70.0, 85.0] {
        let t = deg(theta);
        let e = m.evaluate(&Geometry::specular(t, 0.0).unwrap());
        assert!((e.terms.unwrap().r_f - 1.0).abs() < 1e-13);
        let f = normalized(&e.pbrdf);
        assert!(f[0][1].abs() < 1e-13 && f[1][0].abs() < 1e-13 && e.dolp() < 1e-13);
        assert!((f[2][2].powi(2) + f[2][3].powi(2) - 1.0).abs() < 1e-12);
        assert!(f[2][3] > 0.01, "retardance at {theta}°: {}", f[2][3]);
    }
    // Below the critical angle the same material is an ordinary dielectric: no retardance.
    let e = m.evaluate(&Geometry::specular(deg(20.0), 0.0).unwrap());
    assert_eq!(e.pbrdf.0[2][3], 0.0);
    assert!(e.terms.unwrap().r_f < 0.5);
}

#[test]
fn grazing_local_incidence_reflects_everything() {
    for (n, k) in [(1.65, 0.0), (1.37, 7.62), (0.5, 0.0), (3.0, 0.1)] {
        let fr = RefractiveIndex::new(n, k).unwrap().amplitudes(FRAC_PI_2);
        assert!((fr.rs + 1.0).norm() < 1e-12 && (fr.rp + 1.0).norm() < 1e-12);
    }
}

// ---------------------------------------------------------------------------------------------
// the facet distribution

/// `2π ∫_0^{π/2} D(θ) cosθ sinθ dθ` by the midpoint rule in θ.
fn hemisphere_midpoint_theta(d: &Distribution, steps: usize) -> f64 {
    let h = FRAC_PI_2 / steps as f64;
    let phi_steps = 8; // the integrand does not depend on φN; sum it anyway
    let mut total = 0.0;
    for j in 0..phi_steps {
        let _phi = (j as f64 + 0.5) * 2.0 * PI / phi_steps as f64;
        let mut ring = 0.0;
        for i in 0..steps {
            let t = (i as f64 + 0.5) * h;
            ring += d.eval(t) * t.cos() * t.sin();
        }
        total += ring * h * 2.0 * PI / phi_steps as f64;
    }
    total
}

/// The same integral over the projected unit disk (`cosθ dΩ = r dr dφ`, r = sinθ), midpoint
/// rule in r: a different variable, so a different set of nodes and errors.
fn hemisphere_midpoint_disk(d: &Distribution, steps: usize) -> f64 {
    let h = 1.0 / steps as f64;
    let mut total = 0.0;
    for i in 0..steps {
        let r = (i as f64 + 0.5) * h;
        total += d.eval(r.asin()) * r;
    }
    total * h * 2.0 * PI
}

#[test]
fn hemispherical_normalization_by_brute_force() {
    for sigma_deg in [2.0, 10.0, 30.0, 80.0] {
        let m = material(1.5, 0.0, sigma_deg);
        let d = m.distribution();
        let sigma = deg(sigma_deg);
        assert!(rel_close(d.b(), 1.0 / (sigma * sigma), 1e-14), "b = 1/σ²");
        let by_theta = hemisphere_midpoint_theta(&d, 100_000);
        assert!(
            (by_theta - 1.0).abs() < 1e-7,
            "σ = {sigma_deg}°: ∫ = {by_theta}"
        );
        if sigma_deg >= 10.0 {
            // the disk variable is too coarse near r = 0 for a 2° lobe
            let by_disk = hemisphere_midpoint_disk(&d, 400_000);
            assert!(
                (by_disk - 1.0).abs() < 1e-6,
                "σ = {sigma_deg}°: ∫ = {by_disk}"
            );
        }
        assert!((d.projected_integral() - 1.0).abs() < 1e-12);
        // Explicit a is kept as given (not renormalized).
        let fixed = Distribution::new(0.7, d.b()).unwrap();
        let i = hemisphere_midpoint_theta(&fixed, 100_000);
        assert!((i - 0.7 / d.a()).abs() < 1e-7);
    }
}

#[test]
fn normalization_limits_small_and_large_sigma() {
    // Small σ: ∫_0^∞ e^{−bθ²} sinθ cosθ dθ = 1/(2b) − 1/(3b²) + 2/(15b³) − …, so
    // a·π/b = 1 + 2σ²/3 + 8σ⁴/45 + O(σ⁶) → 1 (a ≈ b/π).
    for sigma_deg in [0.5, 1.0, 2.0, 5.0] {
        let s = deg(sigma_deg);
        let d = Distribution::from_sigma(s).unwrap();
        let ratio = d.a() * PI / d.b();
        let series = 1.0 + 2.0 * s * s / 3.0 + 8.0 * s.powi(4) / 45.0;
        assert!(
            (ratio - series).abs() < s.powi(6),
            "σ = {sigma_deg}°: aπ/b = {ratio}, series {series}"
        );
        assert!((ratio - 1.0).abs() < s * s);
    }
    // Large σ (b → 0): ∫_0^{π/2} (1 − bθ²) sinθ cosθ dθ = 1/2 − b(π² − 4)/16, so
    // a·π = 1 + b(π² − 4)/8 + O(b²) → 1 (a → 1/π).
    for sigma in [10.0, 100.0, 1e4] {
        let d = Distribution::from_sigma(sigma).unwrap();
        let b = 1.0 / (sigma * sigma);
        let want = 1.0 + b * (PI * PI - 4.0) / 8.0;
        assert!(
            (d.a() * PI - want).abs() < 2.0 * b * b + 1e-14,
            "σ = {sigma} rad: aπ = {}",
            d.a() * PI
        );
    }
    let huge = MaterialSpec::new(1.5, 1e6).build().unwrap();
    assert!((huge.distribution().a() * PI - 1.0).abs() < 1e-8);
}

// ---------------------------------------------------------------------------------------------
// shadowing / obscuration

#[test]
fn shadowing_is_one_at_specular_and_backscatter() {
    for eq3 in [false, true] {
        let mut model = Model::new(1.65, 0.0, 20.0);
        model.eq3 = eq3;
        let m = model.material();
        for theta in [0.0, 10.0, 45.0, 80.0, 89.999] {
            for phi in [0.0, 100.0, -250.0] {
                for g in [
                    Geometry::specular(deg(theta), deg(phi)).unwrap(),
                    Geometry::backscatter(deg(theta), deg(phi)).unwrap(),
                ] {
                    let so = m.evaluate(&g).terms.unwrap().so;
                    // φi + π is not exact in f64 (error ~1e-16 rad): near grazing that is a
                    // genuine tilt θN ≈ 1e-16·tanθ of the half vector, so SO − 1 ≈ θN/Ω.
                    let tol = 1e-14 * (1.0 + deg(theta).tan());
                    assert!((so - 1.0).abs() < tol, "SO = {so} at {g:?}");
                }
            }
        }
    }
}

#[test]
fn eq3_keeps_so_one_at_rotated_specular() {
    // ΦN = 0 for every in-plane geometry and SO = 1 at specular (docs/model.md §1, §4), also when the
    // azimuths are large and carry rounding errors: the specular geometry φr = φi + 180° given in
    // degrees anywhere in ±720° and then turned by up to ±720°. With eq3 a spurious ΦN ≈ 90°
    // from rounding would cut SO by up to a factor 1/(1 + (π/2)·θi/Ω).
    let m = Model {
        eq3: true,
        ..Model::new(1.65, 0.0, 10.0)
    }
    .material();
    for theta in [10.0, 30.0, 60.0, 85.0, 89.0, 89.99] {
        for i in 0..200 {
            let phi = -720.0 + 7.23 * i as f64;
            for j in 0..40 {
                let delta = deg(-720.0 + 36.1 * j as f64);
                for g in [
                    Geometry::from_degrees(theta, phi, theta, phi + 180.0).unwrap(),
                    Geometry::specular(deg(theta), deg(phi)).unwrap(),
                ] {
                    let t = m.evaluate(&g.rotated(delta)).terms.unwrap();
                    assert!(
                        t.angles.phi_n < 1e-9 && (t.so - 1.0).abs() < 1e-9,
                        "θ = {theta}°, φ = {phi}°, δ = {delta} rad: ΦN = {}, SO = {}",
                        t.angles.phi_n,
                        t.so
                    );
                }
            }
        }
    }
}

#[test]
fn shadowing_formula_bound_and_switches() {
    let geometries = [
        (30.0, 0.0, 50.0, 180.0), // in plane, forward
        (30.0, 0.0, 50.0, 0.0),   // in plane, same side
        (60.0, 10.0, 20.0, 100.0),
        (40.0, 0.0, 30.0, 120.0),
        (80.0, -45.0, 85.0, 60.0),
        (0.0, 0.0, 70.0, 33.0),
    ];
    let (tau, omega) = (deg(reference::TAU_DEG), deg(reference::OMEGA_DEG));
    let on = Model::new(1.65, 0.0, 20.0);
    let off = Model {
        shadow: false,
        ..on
    };
    let eq3 = Model { eq3: true, ..on };
    let (m_on, m_off, m_eq3) = (on.material(), off.material(), eq3.material());
    for (ti, pi, tr, pr) in geometries {
        let g = Geometry::from_degrees(ti, pi, tr, pr).unwrap();
        let ang = reference::angles(deg(ti), deg(pi), deg(tr), deg(pr));
        // Eq. 3 by hand, radians.
        let x = ang.theta_n / omega;
        let so = (1.0 + x * (-2.0 * ang.beta / tau).exp()) / (1.0 + x);
        let e_on = m_on.evaluate(&g);
        assert!(rel_close(e_on.terms.unwrap().so, so, 1e-12), "SO at {g:?}");
        assert!(so < 1.0 - 1e-3, "SO < 1 off specular/backscatter");
        // Switched off: SO = 1, and the surface term scales by exactly 1/SO.
        let e_off = m_off.evaluate(&g);
        assert_eq!(e_off.terms.unwrap().so, 1.0);
        assert!(rel_close(e_on.surface / e_off.surface, so, 1e-13));
        // Azimuth factor 1/(1 + ΦN·θi/Ω): 1 in plane, < 1 off plane.
        let e_eq3 = m_eq3.evaluate(&g);
        let factor = 1.0 / (1.0 + ang.phi_n * deg(ti) / omega);
        assert!(rel_close(e_eq3.terms.unwrap().so, so * factor, 1e-12));
        let in_plane = (pr - pi).rem_euclid(180.0) == 0.0;
        if in_plane {
            assert!(ang.phi_n < 1e-12);
            assert!(rel_close(e_eq3.surface, e_on.surface, 1e-14));
        } else if ti > 0.0 {
            assert!(ang.phi_n > 0.05);
            assert!(e_eq3.surface < e_on.surface * (1.0 - 1e-3));
        }
    }
    // SO ≤ 1 on a grid, and the library's Shadowing::eval agrees.
    let s = Shadowing::new(tau, omega, AzimuthTerm::None).unwrap();
    for i in 0..=20 {
        for j in 0..=20 {
            let v = AngleVariables {
                theta_i: 0.3,
                theta_r: 0.4,
                beta: i as f64 * FRAC_PI_2 / 20.0,
                theta_n: j as f64 * FRAC_PI_2 / 20.0,
                phi_n: 0.0,
                eta_i: 0.0,
                eta_r: 0.0,
            };
            let so = s.eval(&v);
            assert!(so <= 1.0 && so > 0.0, "SO = {so}");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// forms and the volume term

#[test]
fn paper_and_standard_forms_differ_by_cos2_theta_n_over_cos_cos() {
    let std_model = Model::new(1.65, 0.0, 20.0);
    let paper_model = Model {
        paper: true,
        ..std_model
    };
    let (ms, mp) = (std_model.material(), paper_model.material());
    for (ti, pi, tr, pr) in [
        (30.0, 0.0, 50.0, 180.0),
        (60.0, 10.0, 20.0, 100.0),
        (10.0, 0.0, 10.0, 0.0),
        (80.0, 0.0, 80.0, 180.0),
        (70.0, 45.0, 5.0, -100.0),
    ] {
        let g = Geometry::from_degrees(ti, pi, tr, pr).unwrap();
        let ang = reference::angles(deg(ti), deg(pi), deg(tr), deg(pr));
        let (es, ep) = (ms.evaluate(&g), mp.evaluate(&g));
        let ratio = ang.theta_n.cos().powi(2) / (deg(ti).cos() * deg(tr).cos());
        assert!(
            rel_close(ep.surface / es.surface, ratio, 1e-12),
            "paper/standard at {g:?}"
        );
        assert_mat_close(
            &normalized(&ep.pbrdf),
            &normalized(&es.pbrdf),
            1e-13,
            "same polarization",
        );
    }
}

#[test]
fn volume_term_is_eq1_and_unpolarized() {
    for paper in [false, true] {
        let bare = Model {
            paper,
            ..Model::new(1.65, 0.0, 20.0)
        };
        let with = Model {
            rho_d: 0.03,
            rho_v: 0.01,
            ..bare
        };
        let (mb, mw) = (bare.material(), with.material());
        for (ti, pi, tr, pr) in [
            (30.0, 0.0, 50.0, 180.0),
            (60.0, 10.0, 20.0, 100.0),
            (0.0, 0.0, 0.0, 0.0),
            (89.0, 0.0, 10.0, 90.0),
        ] {
            let g = Geometry::from_degrees(ti, pi, tr, pr).unwrap();
            let (eb, ew) = (mb.evaluate(&g), mw.evaluate(&g));
            let f_v = 0.03 + 2.0 * 0.01 / (deg(ti).cos() + deg(tr).cos());
            assert!(rel_close(ew.volume, f_v, 1e-14));
            assert_eq!(eb.volume, 0.0);
            assert!(rel_close(ew.pbrdf.0[0][0] - eb.pbrdf.0[0][0], f_v, 1e-12));
            for r in 0..4 {
                for c in 0..4 {
                    if (r, c) != (0, 0) {
                        assert_eq!(ew.pbrdf.0[r][c], eb.pbrdf.0[r][c], "F{r}{c}");
                    }
                }
            }
            assert_eq!(ew.surface, eb.surface);
            assert!(rel_close(ew.brdf(), ew.surface + ew.volume, 1e-14));
        }
    }
    // Volume only (a surface whose lobe is zero here): unpolarized output.
    let model = Model {
        rho_d: 0.02,
        ..Model::new(1.65, 0.0, 0.5)
    };
    let e = model
        .material()
        .evaluate(&Geometry::from_degrees(10.0, 0.0, 70.0, 0.0).unwrap());
    assert_eq!(e.surface, 0.0);
    assert_eq!(e.pbrdf.0, Mueller::diagonal([0.02, 0.0, 0.0, 0.0]).0);
    assert_eq!(e.dolp(), 0.0);
}

// ---------------------------------------------------------------------------------------------
// degenerate inputs

#[test]
fn at_or_below_the_horizon_is_the_zero_matrix() {
    for paper in [false, true] {
        let model = Model {
            paper,
            rho_d: 0.03,
            rho_v: 0.01,
            ..Model::new(1.65, 0.0, 20.0)
        };
        let m = model.material();
        for t in [90.0, 120.0, 180.0] {
            for g in [
                Geometry::from_degrees(t, 0.0, 30.0, 180.0).unwrap(),
                Geometry::from_degrees(30.0, 0.0, t, 180.0).unwrap(),
                Geometry::from_degrees(t, 10.0, t, 190.0).unwrap(),
                Geometry::new(FRAC_PI_2, 0.0, 0.2, 0.0).unwrap(),
            ] {
                let e = m.evaluate(&g);
                assert_eq!(e.pbrdf, Mueller::zero(), "{g:?}");
                assert_eq!(
                    (e.brdf(), e.dolp(), e.surface, e.volume),
                    (0.0, 0.0, 0.0, 0.0)
                );
                assert!(e.terms.is_none());
                assert!(g.angle_variables().is_none());
            }
        }
        // The angle-variable entry point agrees.
        let v = AngleVariables::in_plane_specular(FRAC_PI_2, 0.0);
        assert_eq!(m.evaluate_angles(&v).pbrdf, Mueller::zero());
    }
}

#[test]
fn just_above_the_horizon_is_finite() {
    let t = 89.999;
    for paper in [false, true] {
        for shadow in [false, true] {
            let model = Model {
                paper,
                shadow,
                rho_d: 0.03,
                rho_v: 0.01,
                ..Model::new(1.65, 0.0, 30.0)
            };
            let m = model.material();
            for g in [
                Geometry::from_degrees(t, 0.0, t, 180.0).unwrap(),
                Geometry::from_degrees(t, 0.0, t, 0.0).unwrap(),
                Geometry::from_degrees(t, 0.0, 30.0, 180.0).unwrap(),
                Geometry::from_degrees(0.0, 0.0, t, 77.0).unwrap(),
                Geometry::from_degrees(t, 0.0, t, 90.0).unwrap(),
            ] {
                let e = m.evaluate(&g);
                assert!(e.pbrdf.0.iter().flatten().all(|v| v.is_finite()), "{g:?}");
                assert!(e.brdf() > 0.0 && e.dolp().is_finite() && e.dolp() <= 1.0);
            }
        }
    }
}

fn message(e: Error) -> String {
    e.to_string()
}

fn assert_names(e: Error, name: &str, value: &str) {
    let msg = message(e);
    assert!(
        msg.contains(&format!("`{name}`")) && msg.contains(value),
        "message {msg:?} should name `{name}` and {value}"
    );
}

#[test]
fn invalid_inputs_are_errors_naming_parameter_and_value() {
    // Angles (radians and degrees).
    let e = Geometry::new(f64::NAN, 0.0, 0.1, 0.0).unwrap_err();
    assert_names(e, "theta_i", "NaN");
    let e = Geometry::new(0.1, f64::INFINITY, 0.1, 0.0).unwrap_err();
    assert_names(e, "phi_i", "inf");
    let e = Geometry::new(0.1, 0.0, -0.25, 0.0).unwrap_err();
    assert_names(e, "theta_r", "-0.25");
    let e = Geometry::new(0.1, 0.0, 0.1, f64::NEG_INFINITY).unwrap_err();
    assert_names(e, "phi_r", "-inf");
    let e = Geometry::new(3.2, 0.0, 0.1, 0.0).unwrap_err();
    assert_names(e, "theta_i", "3.2");
    let e = Geometry::from_degrees(-1.0, 0.0, 10.0, 0.0).unwrap_err();
    assert_names(e, "theta_i_deg", "-1");
    let e = Geometry::from_degrees(10.0, 0.0, 180.5, 0.0).unwrap_err();
    assert_names(e, "theta_r_deg", "180.5");
    let e = Geometry::from_degrees(10.0, 0.0, 10.0, f64::NAN).unwrap_err();
    assert_names(e, "phi_r_deg", "NaN");
    assert!(Geometry::from_degrees(180.0, 0.0, 0.0, 0.0).is_ok());

    // Material keys.
    let base = MaterialSpec::new(1.65, 15.0);
    let bad = |f: &dyn Fn(&mut MaterialSpec)| {
        let mut s = base.clone();
        f(&mut s);
        s.build().unwrap_err()
    };
    assert_names(bad(&|s| s.n = 0.0), "n", "0");
    assert_names(bad(&|s| s.n = -1.5), "n", "-1.5");
    assert_names(bad(&|s| s.n = f64::NAN), "n", "NaN");
    assert_names(bad(&|s| s.n = f64::INFINITY), "n", "inf");
    assert_names(bad(&|s| s.k = -0.5), "k", "-0.5");
    assert_names(bad(&|s| s.k = f64::NAN), "k", "NaN");
    assert_names(bad(&|s| s.sigma_deg = Some(0.0)), "sigma_deg", "0");
    assert_names(bad(&|s| s.sigma_deg = Some(-3.0)), "sigma_deg", "-3");
    // σ so small that b = 1/σ² overflows (the value is shown as Rust displays an f64).
    let e = bad(&|s| s.sigma_deg = Some(1e-200));
    assert_names(e, "sigma_deg", &format!("{:?}", 1e-200));
    assert_names(
        bad(&|s| {
            s.sigma_deg = None;
            s.b = Some(0.0);
        }),
        "b",
        "0",
    );
    assert_names(
        bad(&|s| {
            s.sigma_deg = None;
            s.b = Some(-2.0);
        }),
        "b",
        "-2",
    );
    assert_names(bad(&|s| s.a = Some(-0.1)), "a", "-0.1");
    assert_names(bad(&|s| s.a = Some(f64::NAN)), "a", "NaN");
    assert_names(bad(&|s| s.rho_d = -0.01), "rho_d", "-0.01");
    assert_names(bad(&|s| s.rho_v = -0.02), "rho_v", "-0.02");
    assert_names(bad(&|s| s.rho_v = f64::INFINITY), "rho_v", "inf");
    assert_names(bad(&|s| s.tau_deg = 0.0), "tau_deg", "0");
    assert_names(bad(&|s| s.tau_deg = -15.0), "tau_deg", "-15");
    assert_names(bad(&|s| s.omega_deg = 0.0), "omega_deg", "0");
    assert_names(bad(&|s| s.omega_deg = -40.0), "omega_deg", "-40");
    let both = message(bad(&|s| s.b = Some(10.0)));
    assert!(both.contains("sigma_deg") && both.contains("`b`") && both.contains("both"));
    let neither = message(bad(&|s| s.sigma_deg = None));
    assert!(neither.contains("sigma_deg") && neither.contains("`b`"));
    // Valid edge values are accepted: a = 0, k = 0, ρ = 0.
    let mut ok = base.clone();
    ok.a = Some(0.0);
    assert!(ok.build().is_ok());

    // The component constructors.
    assert_names(RefractiveIndex::new(0.0, 0.0).unwrap_err(), "n", "0");
    assert_names(RefractiveIndex::new(1.0, -1.0).unwrap_err(), "k", "-1");
    assert_names(Distribution::new(-1.0, 1.0).unwrap_err(), "a", "-1");
    assert_names(Distribution::new(1.0, 0.0).unwrap_err(), "b", "0");
    assert_names(Distribution::from_sigma(-0.1).unwrap_err(), "sigma", "-0.1");
    assert_names(
        Shadowing::new(0.0, 1.0, AzimuthTerm::None).unwrap_err(),
        "tau",
        "0",
    );
    assert_names(
        Shadowing::new(1.0, -1.0, AzimuthTerm::Eq3).unwrap_err(),
        "omega",
        "-1",
    );
}

// ---------------------------------------------------------------------------------------------
// the angle-variable entry point

#[test]
fn angle_variable_entry_point_matches_geometry_and_formula() {
    let (tau, omega) = (deg(reference::TAU_DEG), deg(reference::OMEGA_DEG));
    for paper in [false, true] {
        let model = Model {
            paper,
            ..Model::new(1.65, 0.0, 12.0)
        };
        let m = model.material();
        let (a, b) = (m.distribution().a(), m.distribution().b());
        for theta_deg in [0.0, 10.0, 30.0, 58.78, 75.0, 89.0] {
            let t = deg(theta_deg);
            // θN = 0: the geometric specular evaluation.
            let ev = m.evaluate_angles(&AngleVariables::in_plane_specular(t, 0.0));
            let eg = m.evaluate(&Geometry::specular(t, deg(50.0)).unwrap());
            assert!(rel_close(ev.brdf(), eg.brdf(), 1e-13));
            assert_mat_close(
                &ev.pbrdf.scaled(1.0 / eg.brdf()).0,
                &eg.pbrdf.scaled(1.0 / eg.brdf()).0,
                1e-13,
                "θN = 0",
            );
            // θN > 0: the surface term by hand, Fresnel polarization at β = θ.
            for theta_n in [0.05, 0.2, 0.5] {
                let ev = m.evaluate_angles(&AngleVariables::in_plane_specular(t, theta_n));
                let d = a * (-b * theta_n * theta_n).exp();
                let x = theta_n / omega;
                let so = (1.0 + x * (-2.0 * t / tau).exp()) / (1.0 + x);
                let r_f = reference::reflectance(model.n, 0.0, t);
                let c2 = t.cos() * t.cos();
                let want = if paper {
                    d * r_f * theta_n.cos().powi(2) * so / (4.0 * c2 * c2)
                } else {
                    d * r_f * so / (4.0 * c2)
                };
                assert!(
                    rel_close(ev.surface, want, 1e-12),
                    "f_s({theta_deg}°, θN = {theta_n}) = {}, expected {want}",
                    ev.surface
                );
                assert!(rel_close(ev.brdf(), ev.surface, 1e-15));
                assert_mat_close(
                    &normalized(&ev.pbrdf),
                    &fresnel_mueller(model.n, 0.0, t),
                    1e-12,
                    "Fresnel polarization",
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Mueller from Jones

/// A small deterministic generator (Knuth's MMIX LCG), uniform in [−1, 1).
pub(crate) struct Lcg(pub u64);
impl Lcg {
    pub fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    }
    pub fn complex(&mut self) -> C {
        C::new(self.uniform(), self.uniform())
    }
}

#[test]
fn from_jones_is_a_t_kron_t_conj_a_inverse() {
    let mut rng = Lcg(0x5eed);
    for case in 0..500 {
        let scale = [1e-3, 1.0, 30.0][case % 3];
        let t = [
            [rng.complex() * scale, rng.complex() * scale],
            [rng.complex() * scale, rng.complex() * scale],
        ];
        let got = Mueller::from_jones(&Jones(t)).0;
        let want = reference::mueller(&t);
        let s2 = scale * scale;
        assert_mat_close(&got, &want, 1e-14 * s2, "from_jones");
        // And it maps Stokes vectors as the fields map: S(T E) = M S(E).
        let (es, ep) = (rng.complex(), rng.complex());
        let out_field = (t[0][0] * es + t[0][1] * ep, t[1][0] * es + t[1][1] * ep);
        let s_in = reference::stokes(es, ep);
        let s_out = reference::stokes(out_field.0, out_field.1);
        let mapped = Mueller(got).apply(&Stokes(s_in));
        for i in 0..4 {
            assert!((mapped.0[i] - s_out[i]).abs() < 1e-13 * s2 * 4.0);
        }
    }
    // Library's Stokes of a field agrees with the definition of docs/model.md §2; (1,1,0,0) is s.
    let s = Stokes::from_field(C::new(1.0, 0.0), C::new(0.0, 0.0));
    assert_eq!(s, Stokes::s_polarized());
    let s = Stokes::from_field(C::new(0.0, 0.0), C::new(1.0, 0.0));
    assert_eq!(s, Stokes::p_polarized());
    // Mueller of a frame rotation is the rotator.
    for x in [0.1, 1.0, -2.5] {
        let got = Mueller::from_jones(&Jones::rotation(x)).0;
        let want = reference::mueller(&Jones::rotation(x).0);
        assert_mat_close(&got, &want, 1e-14, "rotation");
        assert_mat_close(&got, &Mueller::rotator(x).0, 1e-14, "rotator");
    }
    let product = mat_mul(
        &Mueller::rotator(0.3).0,
        &Mueller::diagonal([1.0, 1.0, -1.0, -1.0]).0,
    );
    let jones_product = Jones::rotation(0.3) * Jones::diagonal(C::new(1.0, 0.0), C::new(-1.0, 0.0));
    assert_mat_close(
        &Mueller::from_jones(&jones_product).0,
        &product,
        1e-14,
        "product rule",
    );
}

#[test]
fn coherency_eigenvalues_are_scale_covariant() {
    // For diag(1, a, b, c) the coherency eigenvalues are (1 ± a ± b ± c)/2 with an even number
    // of minus signs among a, b, c (sum = 2·M00). A tiny or huge pBRDF (e.g. far off the
    // specular lobe of a smooth surface, D ~ 1e-236) must be judged like its normalized self.
    for s in [1.0, 1e-200, 1e-300, 1e200] {
        let ideal = Mueller::diagonal([1.0, 1.0, -1.0, -1.0]).scaled(s);
        let mut ev = ideal.coherency_eigenvalues().map(|v| v / s);
        ev.sort_by(f64::total_cmp);
        for (got, want) in ev.iter().zip([0.0, 0.0, 0.0, 2.0]) {
            assert!((got - want).abs() < 1e-12, "scale {s}: {ev:?}");
        }
        assert!(ideal.is_physically_realizable(1e-9));
        let unphysical = Mueller::diagonal([1.0, 1.0, 1.0, -1.0]).scaled(s);
        let mut ev = unphysical.coherency_eigenvalues().map(|v| v / s);
        ev.sort_by(f64::total_cmp);
        for (got, want) in ev.iter().zip([-1.0, 1.0, 1.0, 1.0]) {
            assert!((got - want).abs() < 1e-12, "scale {s}: {ev:?}");
        }
        assert!(!unphysical.is_physically_realizable(1e-9), "scale {s}");
        let partial = Mueller::diagonal([1.0, 0.5, -0.2, 0.1]).scaled(s);
        let mut ev = partial.coherency_eigenvalues().map(|v| v / s);
        ev.sort_by(f64::total_cmp);
        let mut want = [
            (1.0 + 0.5 - 0.2 + 0.1) / 2.0,
            (1.0 + 0.5 + 0.2 - 0.1) / 2.0,
            (1.0 - 0.5 - 0.2 - 0.1) / 2.0,
            (1.0 - 0.5 + 0.2 + 0.1) / 2.0,
        ];
        want.sort_by(f64::total_cmp);
        for (got, want) in ev.iter().zip(want) {
            assert!((got - want).abs() < 1e-12, "scale {s}: {ev:?} vs {want}");
        }
    }
}

#[test]
fn degrees_of_polarization_are_scale_invariant() {
    // A fully polarized beam has DoP = 1 whatever its radiance (a pBRDF far outside a narrow
    // lobe is ~1e-160 sr⁻¹ and its squares underflow).
    for s in [1.0, 1e-160, 1e-300, 1e150] {
        let st = Stokes([1.0, 0.6, 0.0, 0.8].map(|v| v * s));
        assert!(
            (st.dop() - 1.0).abs() < 1e-15,
            "scale {s}: DoP = {}",
            st.dop()
        );
        assert!((st.dolp() - 0.6).abs() < 1e-15 && (st.docp() - 0.8).abs() < 1e-15);
    }
}
