//! The single-precision output of the batch engine (`Precision::F32`, docs/model.md §12): the
//! model computed in f32 within the float32 contract — every entry within
//! `1e-5·F00 + 1e-6·P + 2⁻¹⁵⁰` of float64, `P` the material's F00 at the specular direction of
//! the same θi — at every SIMD level, from angles and from direction vectors, on every test
//! vector and on random materials and geometries (grazing, near-specular, large σ, metals with
//! large k, indices near 1, the extreme bounds of the parameters, the peer benchmark's
//! conductor, a σ = 5° conductor down its lobe's tail); most elements really are computed in f32; entries beyond f32's range are
//! refused.

use crate::common::{cases, geometry, spec_of};
use crate::kernel::{random_geometry, random_material};
use polbrdf::engine::batch::STREAM_MIN;
use polbrdf::engine::{Engine, Kernel, Precision, SimdLevel};
use polbrdf::geometry::direction;
use polbrdf::sample::SplitMix64 as Rng;
use polbrdf::{DirectionBatch, Error, GeometryBatch, Material, MaterialSpec};
use std::f64::consts::{PI, TAU};

/// The float32 contract's part relative to the element's F00.
const TOL: f64 = 1e-5;

/// The float32 contract's part relative to `P`, the lobe's magnitude for the incidence (F00 at
/// the specular direction of the same θi).
const EPS: f64 = 1e-6;

/// Half the smallest positive f32 (subnormal): the absolute rounding error below f32's normal
/// range.
const HALF_SUBNORMAL: f64 = 7.006_492_321_624_085e-46; // 2⁻¹⁵⁰

/// A batch of geometries (radians).
fn columns(geoms: &[[f64; 4]]) -> [Vec<f64>; 4] {
    std::array::from_fn(|c| geoms.iter().map(|g| g[c]).collect())
}

/// `P` of each geometry: F00 of `m` (float64) at the specular direction of the same θi.
fn specular_f00(engine: &Engine<'_>, geoms: &[[f64; 4]]) -> Vec<f64> {
    let spec: Vec<[f64; 4]> = geoms
        .iter()
        .map(|g| [g[0], g[1], g[0], g[1] + PI])
        .collect();
    let cols = columns(&spec);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let mut out = vec![[f64::NAN; 16]; spec.len()];
    engine.mueller_into(&batch, &mut out).unwrap();
    out.iter().map(|f| f[0]).collect()
}

/// Evaluates `geoms` (radians) in both precisions at every SIMD level of this CPU, as angles
/// and as direction vectors (each route's f32 against its f64), checks every
/// entry against the float32 contract and returns the worst share of the contract's bound used
/// (≤ 1) and the smallest fraction of elements whose f32 result is not the f64 one rounded
/// (computed in f32).
fn check(label: &str, m: &Material, geoms: &[[f64; 4]]) -> (f64, f64) {
    let cols = columns(geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let p = specular_f00(&Engine::new(m), geoms);
    let w_i: Vec<[f64; 3]> = geoms.iter().map(|g| direction(g[0], g[1])).collect();
    let w_r: Vec<[f64; 3]> = geoms.iter().map(|g| direction(g[2], g[3])).collect();
    let dirs = DirectionBatch::new(&w_i, &w_r).unwrap();
    let (mut worst, mut in_f32) = (0.0_f64, 1.0_f64);
    for level in SimdLevel::supported() {
        let k = Kernel::with_level(m, level).unwrap();
        let mut f64s = vec![[f64::NAN; 16]; batch.len()];
        let mut f32s = vec![[f32::NAN; 16]; batch.len()];
        k.mueller_into(&batch, 0, &mut f64s);
        assert!(
            !k.mueller_f32_into(&batch, 0, &mut f32s),
            "{label}: overflow"
        );
        let (w, f) = compare(&format!("{label}, {level:?}"), &f64s, &f32s, &p, geoms);
        (worst, in_f32) = (worst.max(w), in_f32.min(f));
        // The direction route (its own geometry stages) from the same geometries as unit
        // vectors.
        k.mueller_into(&dirs, 0, &mut f64s);
        assert!(
            !k.mueller_f32_into(&dirs, 0, &mut f32s),
            "{label}: overflow"
        );
        let label = format!("{label}, directions, {level:?}");
        let (w, f) = compare(&label, &f64s, &f32s, &p, geoms);
        (worst, in_f32) = (worst.max(w), in_f32.min(f));
    }
    (worst, in_f32)
}

/// [`check`] with a given engine (a per-element or spectral index), at its SIMD level.
fn check_engine(label: &str, engine: &Engine<'_>, geoms: &[[f64; 4]]) -> (f64, f64) {
    let cols = columns(geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let mut f64s = vec![[f64::NAN; 16]; batch.len()];
    let mut f32s = vec![[f32::NAN; 16]; batch.len()];
    engine.mueller_into(&batch, &mut f64s).unwrap();
    engine.mueller_f32_into(&batch, &mut f32s).unwrap();
    compare(label, &f64s, &f32s, &specular_f00(engine, geoms), geoms)
}

/// Every entry of `f32s` against `f64s` under the contract with references `p`: the worst
/// share of the bound used and the fraction computed in f32.
fn compare(
    label: &str,
    f64s: &[[f64; 16]],
    f32s: &[[f32; 16]],
    p: &[f64],
    geoms: &[[f64; 4]],
) -> (f64, f64) {
    let mut worst = 0.0_f64;
    let mut in_f32 = 0usize;
    for (i, (a, b)) in f64s.iter().zip(f32s).enumerate() {
        let f00 = a[0];
        in_f32 += usize::from((0..16).any(|e| b[e].to_bits() != (a[e] as f32).to_bits()));
        let bound = TOL * f00 + EPS * p[i];
        for e in 0..16 {
            let err = (f64::from(b[e]) - a[e]).abs();
            assert!(
                err <= bound + HALF_SUBNORMAL,
                "{label}: element {i} {:?} entry {e}: {} vs {}: error {err:e}, F00 {f00:e}, \
                 P {:e}",
                geoms[i],
                b[e],
                a[e],
                p[i]
            );
            // A physical Mueller matrix: |F_ij| ≤ F00, so the error is within 2⁻²⁴·F00 + 2⁻¹⁵⁰.
            assert!(
                a[e].abs() <= f00 * (1.0 + 1e-12) + 1e-300,
                "{label}: element {i} entry {e}: |F| {} above F00 {f00}",
                a[e]
            );
            if f00 >= 1e-35 {
                worst = worst.max(err / bound);
            }
        }
    }
    (worst, in_f32 as f64 / geoms.len().max(1) as f64)
}

#[test]
fn float32_on_every_test_vector_is_within_1e5_of_float64() {
    let mut worst = 0.0_f64;
    for c in &cases() {
        let m = spec_of(&c.inputs).build().unwrap();
        let g = geometry(&c.inputs);
        let (w, _) = check(
            &c.id,
            &m,
            &[[g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()]],
        );
        worst = worst.max(w);
    }
    assert!(worst <= 1.0, "worst {worst:e} of the bound");
    eprintln!("float32 vs float64 on the test vectors: max |ΔF|/bound = {worst:.3}");
}

#[test]
fn float32_is_computed_in_f32_for_the_presets() {
    // Not the f64 result rounded: most elements of ordinary materials go through the f32
    // kernel (a test that would fail if single precision silently took the f64 path).
    let mut rng = Rng::new(5);
    let geoms: Vec<[f64; 4]> = (0..4000).map(|_| random_geometry(&mut rng)).collect();
    for preset in ["paint", "glass", "aluminium", "gold", "iron"] {
        let m = polbrdf::preset(preset).unwrap().build().unwrap();
        let (worst, in_f32) = check(preset, &m, &geoms);
        eprintln!(
            "{preset}: max |ΔF|/bound = {worst:.3}, {:.1} % in f32",
            100.0 * in_f32
        );
        // Random directions over the hemispheres lie mostly far from a narrow lobe, where D's
        // tail is left to f64: the rough presets are mostly f32.
        if ["paint", "aluminium"].contains(&preset) {
            assert!(
                in_f32 > 0.5,
                "{preset}: only {in_f32} of the elements computed in f32"
            );
        }
    }
}

#[test]
fn float32_with_both_directions_near_grazing_stays_in_f32() {
    // cos v = (cosθi + cosθr)/(2 cos u) has no cancellation toward the horizon (docs/model.md
    // §9.2), so grazing geometries need no f64 fallback: within 1e-5 and f32 results, for a
    // rough dielectric with SO and a smooth conductor without (where D's tail, refined, covers
    // the large θN of opposite grazing directions).
    let mut rng = Rng::new(11);
    let geoms: Vec<[f64; 4]> = (0..4000)
        .map(|_| {
            let grazing = |r: &mut Rng| (85.0 + 4.99 * r.next_f64()).to_radians();
            let ti = grazing(&mut rng);
            let tr = grazing(&mut rng);
            [ti, TAU * rng.next_f64(), tr, TAU * rng.next_f64()]
        })
        .collect();
    let paint = polbrdf::preset("paint").unwrap().build().unwrap();
    let mut metal = MaterialSpec::new(1.2, 11.3);
    metal.k = 7.0;
    metal.shadowing = false;
    let metal = metal.build().unwrap();
    for (label, m) in [("paint, grazing", &paint), ("conductor, grazing", &metal)] {
        let (worst, in_f32) = check(label, m, &geoms);
        eprintln!(
            "{label}: max |ΔF|/bound = {worst:.3}, {:.1} % in f32",
            100.0 * in_f32
        );
        assert!(in_f32 > 0.9, "{label}: {in_f32}");
    }
}

#[test]
fn float32_down_the_lobe_tail_stays_in_f32() {
    // Beyond bθN² = 20 D keeps its f32 value where the contract allows (docs/model.md §12):
    // within the contract far down the tail, and an f32 result (not the f64 one rounded) until
    // D nears f32's range.
    let m = MaterialSpec::new(1.5, 5.0).build().unwrap();
    let b = m.params().distribution.b();
    let mut geoms = vec![];
    for i in 0..2000 {
        let tr = (30.0 + 59.0 * i as f64 / 2000.0).to_radians();
        geoms.push([30f64.to_radians(), 0.2, tr, 0.2 + PI - 0.3 * (i % 3) as f64]);
    }
    let tail: Vec<[f64; 4]> = geoms
        .into_iter()
        .filter(|g| {
            let v = polbrdf::Geometry::new(g[0], g[1], g[2], g[3])
                .unwrap()
                .angle_variables();
            let y = b * v.unwrap().theta_n.powi(2);
            (25.0..60.0).contains(&y)
        })
        .collect();
    assert!(tail.len() > 300, "{}", tail.len());
    let (worst, in_f32) = check("σ = 5°, D's tail", &m, &tail);
    eprintln!(
        "D's tail: max |ΔF|/bound = {worst:.3}, {:.1} % in f32",
        100.0 * in_f32
    );
    assert!(in_f32 > 0.9, "{in_f32}");
}

/// Geometries for the contract: uniform over the hemispheres (as the peer benchmark), both
/// directions near grazing, one direction within `1e-9 .. 1e-3` rad of grazing (the other
/// anywhere), near specular.
fn contract_geometries(rng: &mut Rng) -> Vec<[f64; 4]> {
    let uniform = |r: &mut Rng| r.range(0.0, 89.9f64.to_radians());
    let phi = |r: &mut Rng| r.range(0.0, TAU);
    let near_90 = |r: &mut Rng| std::f64::consts::FRAC_PI_2 - 10f64.powf(r.range(-9.0, -3.0));
    let mut g = vec![];
    for _ in 0..3000 {
        g.push([uniform(rng), phi(rng), uniform(rng), phi(rng)]);
    }
    for _ in 0..1000 {
        let graze = |r: &mut Rng| (85.0 + 4.99 * r.next_f64()).to_radians();
        g.push([graze(rng), phi(rng), graze(rng), phi(rng)]);
    }
    for i in 0..1000 {
        let (a, b) = (near_90(rng), uniform(rng));
        let (ti, tr) = if i % 2 == 0 { (a, b) } else { (b, a) };
        g.push([ti, phi(rng), tr, phi(rng)]);
    }
    for _ in 0..1000 {
        let (t, p) = (uniform(rng), phi(rng));
        let tiny = |r: &mut Rng| r.range(-1.0, 1.0) * 10f64.powf(r.range(-8.0, -1.0));
        g.push([t, p, (t + tiny(rng)).clamp(0.0, 1.57), p + PI + tiny(rng)]);
    }
    g
}

#[test]
fn float32_contract_on_the_peer_conductor_paint_and_a_narrow_lobe() {
    // The peer benchmark's conductor (n = 1.2, k = 7, Beckmann α = 0.2: σ = atan α, no SO,
    // scripts/bench_peers.py), a σ = 5° conductor (most of its elements far down D's tail,
    // where D stays in f32 under the contract), paint (a volume term): within the contract at
    // every SIMD level, and nearly all in f32.
    let mut rng = Rng::new(34);
    let geoms = contract_geometries(&mut rng);
    let mut peer = MaterialSpec::new(1.2, 0.2f64.atan().to_degrees());
    (peer.k, peer.shadowing) = (7.0, false);
    let mut narrow = MaterialSpec::new(1.2, 5.0);
    narrow.k = 7.0;
    let paint = polbrdf::preset("paint").unwrap();
    for (label, spec) in [
        ("peer conductor", peer),
        ("σ = 5° conductor", narrow),
        ("paint", paint),
    ] {
        let m = spec.build().unwrap();
        let (worst, in_f32) = check(label, &m, &geoms);
        eprintln!(
            "{label}: max |ΔF|/bound = {worst:.3}, {:.1} % in f32",
            100.0 * in_f32
        );
        assert!(in_f32 > 0.9, "{label}: {in_f32}");
    }
}

#[test]
fn float32_with_a_per_element_and_a_spectral_index() {
    use polbrdf::engine::IndexColumns;
    use polbrdf::model::SpectralSource;
    use polbrdf::optics::dispersion::{Dispersion, SpectralIndex};
    let mut rng = Rng::new(11);
    let geoms: Vec<[f64; 4]> = (0..3000).map(|_| random_geometry(&mut rng)).collect();
    // One index per element: dielectrics, indices near 1 and below, metals.
    let n: Vec<f64> = (0..geoms.len())
        .map(|i| [1.5, 1.05, 0.7, 0.2, 2.5][i % 5])
        .collect();
    let k: Vec<f64> = (0..geoms.len())
        .map(|i| [0.0, 0.0, 0.1, 3.0, 8.0][i % 5])
        .collect();
    let m = MaterialSpec::new(1.5, 12.0).build().unwrap();
    let e = Engine::new(&m).with_index(IndexColumns::new(&n, &k).unwrap());
    let (worst, in_f32) = check_engine("per-element index", &e, &geoms);
    eprintln!(
        "per-element index: max |ΔF|/bound = {worst:.3}, {:.1} % in f32",
        100.0 * in_f32
    );
    assert!(in_f32 > 0.3, "{in_f32}");
    // A tabulated spectral index, one wavelength per element.
    let wl = vec![0.4, 0.6, 0.8, 1.0];
    let table = |v: &[f64]| Dispersion::Table {
        wavelengths: wl.clone(),
        values: v.to_vec(),
    };
    let mut s = MaterialSpec::new(1.0, 12.0);
    s.spectral = Some(SpectralSource {
        source: "test".into(),
        index: std::sync::Arc::new(SpectralIndex {
            name: "test/dispersive".into(),
            n: table(&[0.5, 1.4, 2.6, 3.0]),
            k: Some(table(&[4.0, 2.2, 1.0, 0.6])),
            references: String::new(),
            comments: String::new(),
        }),
    });
    let m = s.build_at(0.6).unwrap();
    let lambda: Vec<f64> = (0..geoms.len())
        .map(|i| 0.4 + 0.6 * ((i * 7) % 97) as f64 / 96.0)
        .collect();
    let e = Engine::new(&m).with_wavelengths(&lambda).unwrap();
    let (worst, in_f32) = check_engine("spectral index", &e, &geoms);
    eprintln!(
        "spectral index: max |ΔF|/bound = {worst:.3}, {:.1} % in f32",
        100.0 * in_f32
    );
    assert!(in_f32 > 0.3, "{in_f32}");
}

#[test]
fn float64_rounded_is_float64_rounded_bit_for_bit() {
    let m = polbrdf::preset("paint").unwrap().build().unwrap();
    let mut rng = Rng::new(9);
    let geoms: Vec<[f64; 4]> = (0..500).map(|_| random_geometry(&mut rng)).collect();
    let cols: [Vec<f64>; 4] = std::array::from_fn(|c| geoms.iter().map(|g| g[c]).collect());
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let k = Kernel::new(&m);
    let mut a = vec![[0.0f64; 16]; batch.len()];
    let mut b = vec![[0.0f32; 16]; batch.len()];
    k.mueller_into(&batch, 0, &mut a);
    k.mueller_f64_rounded_into(&batch, 0, &mut b);
    for (x, y) in a.iter().zip(&b) {
        assert_eq!(x.map(|v| (v as f32).to_bits()), y.map(f32::to_bits));
    }
}

#[test]
fn float32_on_random_materials_and_edge_cases() {
    let mut rng = Rng::new(32);
    let mut worst = 0.0_f64;
    for mi in 0..150 {
        let spec = random_material(&mut rng);
        let m = spec.build().unwrap();
        let geoms: Vec<[f64; 4]> = (0..300).map(|_| random_geometry(&mut rng)).collect();
        worst = worst.max(check(&format!("material {mi} {spec:?}"), &m, &geoms).0);
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
        (1.1, 0.0),
        (1.2, 0.01),
        (0.8, 0.0),
        (0.95, 0.3),
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
            geoms.push([t, 0.3, t, 0.3 + PI - 1e-6 * (i % 5) as f64]);
        }
        worst = worst.max(check(&format!("{spec:?}"), &m, &geoms).0);
    }
    assert!(worst <= 1.0, "worst {worst:e} of the bound");
    eprintln!("float32 vs float64 on random cases: max |ΔF|/bound = {worst:.3}");
}

#[test]
fn float32_of_large_outputs_and_partial_blocks() {
    // Beyond STREAM_MIN elements the f64 reference is written with non-temporal stores by
    // default (float32 always with plain ones); both settings of the engine; an odd length
    // leaves a partial last block.
    let m = polbrdf::preset("aluminium").unwrap().build().unwrap();
    let mut rng = Rng::new(7);
    let geoms: Vec<[f64; 4]> = (0..2 * STREAM_MIN + 37)
        .map(|_| random_geometry(&mut rng))
        .collect();
    check("aluminium", &m, &geoms);
    check_engine(
        "aluminium, f64 not streamed",
        &Engine::new(&m).streaming(false),
        &geoms,
    );
}

#[test]
fn float32_non_temporal_stores_change_no_bit() {
    // `Kernel::streaming_f32` (non-temporal stores where the output is 16-byte aligned,
    // `engine::simd::f32_streams_pay` decides for the engine): the same bits as plain stores at
    // every SIMD level and at every 4-byte offset of the output (so both aligned and not), with
    // a partial last block.
    let m = polbrdf::preset("paint").unwrap().build().unwrap();
    let mut rng = Rng::new(12);
    let geoms: Vec<[f64; 4]> = (0..1000 + 37).map(|_| random_geometry(&mut rng)).collect();
    let cols = columns(&geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let n = geoms.len();
    for level in SimdLevel::supported() {
        let k = Kernel::with_level(&m, level).unwrap();
        let mut plain = vec![[0.0f32; 16]; n];
        k.clone()
            .streaming_f32(false)
            .mueller_f32_into(&batch, 0, &mut plain);
        for shift in 0..4 {
            let mut buf = vec![f32::NAN; 16 * n + 4];
            let (rows, _) = buf[shift..shift + 16 * n].as_chunks_mut::<16>();
            k.clone()
                .streaming_f32(true)
                .mueller_f32_into(&batch, 0, rows);
            for (i, (a, b)) in rows.iter().zip(&plain).enumerate() {
                assert_eq!(
                    a.map(f32::to_bits),
                    b.map(f32::to_bits),
                    "{level:?} {shift} {i}"
                );
            }
        }
    }
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
