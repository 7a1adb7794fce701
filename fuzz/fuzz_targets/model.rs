//! The model over arbitrary f64 inputs: invalid parameters are errors; for valid ones every
//! output is finite, F00 ≥ 0, DoLP ∈ [0, 1] and DoP ≤ 1 for a fully polarized input. Half of the
//! inputs use the raw f64 values (NaN, ∞, ±0, subnormals, 1e308 …); the other half map them into
//! the physical ranges, so the fuzzer also explores the valid region densely.
#![no_main]
use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use polbrdf::{AzimuthTerm, Form, Geometry, MaterialSpec, Stokes};

#[derive(Debug, Arbitrary)]
struct Input {
    raw: bool,
    n: f64,
    k: f64,
    sigma_deg: f64,
    a: Option<f64>,
    tau_deg: f64,
    omega_deg: f64,
    rho_d: f64,
    rho_v: f64,
    paper: bool,
    shadowing: bool,
    eq3: bool,
    angles_deg: [f64; 4],
    psi: f64,
}

/// A value in [lo, hi] from any f64 (its fractional part), log-uniform when `log`.
fn range(x: f64, lo: f64, hi: f64, log: bool) -> f64 {
    let f = if x.is_finite() { x.abs().fract() } else { 0.5 };
    if log {
        (lo.ln() + f * (hi.ln() - lo.ln())).exp()
    } else {
        lo + f * (hi - lo)
    }
}

fuzz_target!(|x: Input| {
    let v =
        |raw: f64, lo: f64, hi: f64, log: bool| if x.raw { raw } else { range(raw, lo, hi, log) };
    let spec = MaterialSpec {
        name: None,
        n: v(x.n, 0.01, 1e3, true),
        k: v(x.k, 0.0, 50.0, false),
        sigma_deg: Some(v(x.sigma_deg, 0.01, 1e4, true)),
        b: None,
        a: x.a.map(|a| v(a, 0.0, 1e3, false)),
        form: if x.paper { Form::Paper } else { Form::Standard },
        shadowing: x.shadowing,
        tau_deg: v(x.tau_deg, 0.1, 180.0, true),
        omega_deg: v(x.omega_deg, 0.1, 180.0, true),
        azimuth_term: if x.eq3 {
            AzimuthTerm::Eq3
        } else {
            AzimuthTerm::None
        },
        rho_d: v(x.rho_d, 0.0, 1.0, false),
        rho_v: v(x.rho_v, 0.0, 1.0, false),
        spectral: None,
    };
    let Ok(m) = spec.build() else { return };
    let [ti, pi, tr, pr] = x.angles_deg;
    let g = if x.raw {
        Geometry::from_degrees(ti, pi, tr, pr)
    } else {
        Geometry::from_degrees(
            range(ti, 0.0, 90.0, false),
            range(pi, -720.0, 720.0, false),
            range(tr, 0.0, 90.0, false),
            range(pr, -720.0, 720.0, false),
        )
    };
    let Ok(g) = g else { return };
    let e = m.evaluate(&g);
    let f = e.pbrdf;
    assert!(
        f.0.iter().flatten().all(|v| v.is_finite()),
        "{spec:?} {g:?}: {f:?}"
    );
    assert!(f.0[0][0] >= 0.0, "{spec:?} {g:?}");
    let d = e.dolp();
    assert!((0.0..=1.0 + 1e-12).contains(&d), "{spec:?} {g:?}: dolp {d}");
    let out = f.apply(&Stokes::linear(if x.psi.is_finite() { x.psi } else { 0.0 }));
    assert!(out.dop() <= 1.0 + 1e-9, "{spec:?} {g:?}: DoP {}", out.dop());
});
