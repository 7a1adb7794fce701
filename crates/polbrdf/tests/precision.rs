//! The single-precision output of the batch engine (`Precision::F32`, docs/model.md §12): every
//! entry is the f64 result rounded to the nearest f32 — bit for bit `(f64 result) as f32` — so
//! within `2⁻²⁴·|F_ij| + 2⁻¹⁵⁰ ≤ 1e-5·F00` (for F00 above f32's subnormal range) of float64, on
//! every test vector and on random materials and geometries (grazing, near-specular, large σ,
//! metals with large k, the extreme bounds of the parameters); entries beyond f32's range are
//! refused.

use crate::common::{cases, geometry, spec_of};
use crate::kernel::{random_geometry, random_material};
use polbrdf::engine::batch::STREAM_MIN;
use polbrdf::engine::{Engine, Precision};
use polbrdf::sample::SplitMix64 as Rng;
use polbrdf::{Error, GeometryBatch, Material, MaterialSpec};

/// The accuracy asked of the float32 path, relative to F00.
const TOL: f64 = 1e-5;

/// Half the smallest positive f32 (subnormal): the absolute rounding error below f32's normal
/// range.
const HALF_SUBNORMAL: f64 = 7.006_492_321_624_085e-46; // 2⁻¹⁵⁰

/// Evaluates `geoms` (radians) in both precisions, checks every entry and returns the worst
/// deviation relative to F00 (over elements with F00 ≥ 1e-35).
fn check(label: &str, m: &Material, geoms: &[[f64; 4]]) -> f64 {
    let cols: [Vec<f64>; 4] = std::array::from_fn(|c| geoms.iter().map(|g| g[c]).collect());
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let engine = Engine::new(m);
    let mut f64s = vec![[f64::NAN; 16]; batch.len()];
    let mut f32s = vec![[f32::NAN; 16]; batch.len()];
    engine.mueller_into(&batch, &mut f64s).unwrap();
    engine.mueller_f32_into(&batch, &mut f32s).unwrap();
    let mut worst = 0.0_f64;
    for (i, (a, b)) in f64s.iter().zip(&f32s).enumerate() {
        let f00 = a[0];
        for e in 0..16 {
            // Bit for bit the f64 result rounded to nearest.
            assert_eq!(
                b[e].to_bits(),
                (a[e] as f32).to_bits(),
                "{label}: element {i} {:?} entry {e}: {} vs {}",
                geoms[i],
                b[e],
                a[e]
            );
            let err = (f64::from(b[e]) - a[e]).abs();
            assert!(
                err <= a[e].abs() * 2f64.powi(-24) + HALF_SUBNORMAL,
                "{label}: element {i} entry {e}: error {err:e} beyond f32 rounding"
            );
            // A physical Mueller matrix: |F_ij| ≤ F00, so the error is within 2⁻²⁴·F00 + 2⁻¹⁵⁰.
            assert!(
                a[e].abs() <= f00 * (1.0 + 1e-12) + 1e-300,
                "{label}: element {i} entry {e}: |F| {} above F00 {f00}",
                a[e]
            );
            if f00 >= 1e-35 {
                let rel = err / f00;
                assert!(rel <= TOL, "{label}: element {i} entry {e}: {rel:e}·F00");
                worst = worst.max(rel);
            }
        }
    }
    worst
}

#[test]
fn float32_on_every_test_vector_is_float64_rounded() {
    let mut worst = 0.0_f64;
    for c in &cases() {
        let m = spec_of(&c.inputs).build().unwrap();
        let g = geometry(&c.inputs);
        let w = check(
            &c.id,
            &m,
            &[[g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()]],
        );
        worst = worst.max(w);
    }
    assert!(worst < 1e-7, "worst {worst:e}·F00");
    eprintln!("float32 vs float64 on the test vectors: max |ΔF|/F00 = {worst:e}");
}

#[test]
fn float32_on_random_materials_and_edge_cases() {
    let mut rng = Rng::new(32);
    let mut worst = 0.0_f64;
    for mi in 0..150 {
        let spec = random_material(&mut rng);
        let m = spec.build().unwrap();
        let geoms: Vec<[f64; 4]> = (0..300).map(|_| random_geometry(&mut rng)).collect();
        worst = worst.max(check(&format!("material {mi} {spec:?}"), &m, &geoms));
    }
    // Large σ, narrow lobes, metals with large k, near-unity and huge indices; grazing and
    // near-specular geometries come from `random_geometry`.
    let mut specs = vec![];
    for sigma in [0.2, 2.0, 45.0, 80.0] {
        specs.push(MaterialSpec::new(1.5, sigma));
    }
    for (n, k) in [
        (0.05, 10.0),
        (1.5, 40.0),
        (3.0, 1e3),
        (1e6, 1e6),
        (1.02, 0.0),
    ] {
        let mut s = MaterialSpec::new(n, 10.0);
        s.k = k;
        specs.push(s);
    }
    for spec in specs {
        let m = spec.build().unwrap();
        let mut geoms: Vec<[f64; 4]> = (0..2000).map(|_| random_geometry(&mut rng)).collect();
        for i in 0..500 {
            let t = i as f64 / 500.0 * 89.99f64.to_radians();
            geoms.push([
                t,
                0.3,
                t,
                0.3 + std::f64::consts::PI - 1e-6 * (i % 5) as f64,
            ]);
        }
        worst = worst.max(check(&format!("{spec:?}"), &m, &geoms));
    }
    assert!(worst < 1e-7, "worst {worst:e}·F00");
    eprintln!("float32 vs float64 on random cases: max |ΔF|/F00 = {worst:e}");
}

#[test]
fn float32_streaming_outputs_and_partial_blocks() {
    // Beyond 2·STREAM_MIN elements the f32 output is written with non-temporal stores; an
    // odd length leaves a partial last block.
    let m = polbrdf::preset("aluminium").unwrap().build().unwrap();
    let mut rng = Rng::new(7);
    let geoms: Vec<[f64; 4]> = (0..2 * STREAM_MIN + 37)
        .map(|_| random_geometry(&mut rng))
        .collect();
    check("aluminium, streamed", &m, &geoms);
}

#[test]
fn float32_beyond_its_range_is_refused() {
    let mut s = MaterialSpec::new(1.5, 5.0);
    (s.rho_d, s.rho_v) = (1e100, 1e100);
    let m = s.build().unwrap();
    let t = [0.3, 0.5];
    let p = [0.0, 1.0];
    let batch = GeometryBatch::new(&t, &p, &t, &p).unwrap();
    let mut out = vec![[0.0f32; 16]; 2];
    let e = Engine::new(&m)
        .mueller_f32_into(&batch, &mut out)
        .unwrap_err();
    assert!(
        matches!(&e, Error::InconsistentParameters(msg) if msg.contains("float32")),
        "{e}"
    );
    // float64 holds it.
    let mut out = vec![[0.0f64; 16]; 2];
    Engine::new(&m).mueller_into(&batch, &mut out).unwrap();
    assert!(out[0][0] > 1e99 && out[0][0].is_finite());
}

#[test]
fn precision_names() {
    assert_eq!(Precision::default(), Precision::F64);
    for p in [Precision::F64, Precision::F32] {
        assert_eq!(p.name().parse::<Precision>().unwrap(), p);
    }
    assert!("float16".parse::<Precision>().is_err());
}
