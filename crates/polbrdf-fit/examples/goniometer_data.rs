//! Writes the synthetic goniometer data set shipped as `examples/paint-goniometer.csv`:
//! in-plane BRDF and DoLP at three incidence angles plus a backscatter sweep, from a known
//! paint (n = 1.58, σ = 11°, ρ_D = 0.025, ρ_V = 0.012 sr⁻¹), with 3 % (+1e-4 sr⁻¹) noise on the
//! BRDF and 0.01 on the DoLP (Gaussian, not clipped: a DoLP near 0 can come out slightly
//! negative, as a raw polarimeter estimate can), each with its σ column.
//!
//! `cargo run -p polbrdf-fit --example goniometer_data > examples/paint-goniometer.csv`

use polbrdf::sample::SplitMix64;
use polbrdf::{Geometry, MaterialSpec};

fn main() {
    let mut truth = MaterialSpec::new(1.58, 11.0);
    truth.rho_d = 0.025;
    truth.rho_v = 0.012;
    let m = truth.build().expect("valid material");
    let mut rng = SplitMix64::new(2015);
    println!("theta_i_deg,phi_i_deg,theta_r_deg,phi_r_deg,brdf,sigma_brdf,dolp,sigma_dolp");
    let mut row = |ti: f64, pi: f64, tr: f64, pr: f64| {
        let e = m.evaluate(&Geometry::from_degrees(ti, pi, tr, pr).expect("valid angles"));
        let sb = 0.03 * e.brdf() + 1e-4;
        let sd = 0.01;
        let b = e.brdf() + sb * rng.normal();
        // Not clipped to [0, 1]: clipping would bias the data near DoLP = 0 (backscatter).
        let d = e.dolp() + sd * rng.normal();
        println!("{ti},{pi},{tr},{pr},{b:.6e},{sb:.3e},{d:.5},{sd}");
    };
    for ti in [20.0, 40.0, 60.0] {
        for k in -16..=16 {
            let tr = 5.0 * f64::from(k);
            // Negative θr: the detector on the source's side (φr = φi).
            let (tr, pr) = if tr < 0.0 { (-tr, 0.0) } else { (tr, 180.0) };
            if (tr - ti).abs() < 1e-9 && pr == 0.0 {
                continue; // the detector cannot sit on the source
            }
            row(ti, 0.0, tr, pr);
        }
    }
    for k in 0..=10 {
        let t = 2.0 + 4.0 * f64::from(k);
        row(t, 0.0, t, 0.0);
    }
}
