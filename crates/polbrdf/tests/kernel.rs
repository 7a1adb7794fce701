//! The fast batch kernel (`polbrdf::engine`) against the reference path
//! (`Material::evaluate`): every entry of F within 1e-12·F00, the BRDF within 1e-12 relative and
//! the DoLP within 1e-12 absolute — on every test vector and on random inputs across materials
//! and geometries (degenerate ones included), at every SIMD level this CPU supports.

use crate::common::{cases, geometry, spec_of};
use polbrdf::batch;
use polbrdf::engine::{Kernel, SimdLevel};
use polbrdf::GeometryBatch;
use polbrdf::{
    AzimuthTerm, Form, Fresnel, Geometry, Jones, Material, MaterialSpec, Mueller, RefractiveIndex,
};
use std::f64::consts::{FRAC_PI_2, PI};

const TOL: f64 = 1e-12;

use polbrdf::sample::SplitMix64 as Rng;

/// ±1 with equal probability.
fn sign(rng: &mut Rng) -> f64 {
    if rng.next_f64() < 0.5 {
        -1.0
    } else {
        1.0
    }
}

/// Largest deviation of the kernel's F from the reference, relative to the reference's F00
/// (`f64::INFINITY` when F00 = 0 and the kernel's F is not exactly zero).
fn deviation(got: &[f64; 16], want: &[f64; 16]) -> f64 {
    let f00 = want[0];
    if f00 == 0.0 {
        return if got.iter().all(|v| *v == 0.0) && want.iter().all(|v| *v == 0.0) {
            0.0
        } else {
            f64::INFINITY
        };
    }
    got.iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs() / f00.abs())
        .fold(0.0, f64::max)
}

fn brdf_dolp_deviation(b: f64, d: f64, b_ref: f64, d_ref: f64) -> f64 {
    let db = if b_ref == 0.0 {
        if b == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    } else {
        (b - b_ref).abs() / b_ref
    };
    db.max((d - d_ref).abs())
}

/// Columns of a set of geometries (radians).
fn columns(g: &[[f64; 4]]) -> [Vec<f64>; 4] {
    std::array::from_fn(|c| g.iter().map(|x| x[c]).collect())
}

/// The worst deviations (full F, BRDF+DoLP) of every supported kernel level, and of the batch
/// API, from the reference, on `geoms`. Panics naming the element when above the tolerance.
fn check(label: &str, m: &Material, geoms: &[[f64; 4]]) -> (f64, f64) {
    let cols = columns(geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let reference: Vec<_> = (0..batch.len())
        .map(|i| m.evaluate(&batch.get(i)))
        .collect();
    let (mut worst_f, mut worst_bd) = (0.0_f64, 0.0_f64);
    let mut compare = |how: &str, out: &[[f64; 16]], brdf: &[f64], dolp: &[f64]| {
        for (i, e) in reference.iter().enumerate() {
            let want = e.pbrdf.to_row_major();
            let dev = deviation(&out[i], &want);
            assert!(
                dev <= TOL,
                "{label} ({how}) element {i} {:?}: F deviates by {dev:e}·F00\n got  {:?}\n want {:?}",
                geoms[i],
                out[i],
                want
            );
            let dev_bd = brdf_dolp_deviation(brdf[i], dolp[i], e.brdf(), e.dolp());
            assert!(
                dev_bd <= TOL,
                "{label} ({how}) element {i} {:?}: brdf {} vs {}, dolp {} vs {}",
                geoms[i],
                brdf[i],
                e.brdf(),
                dolp[i],
                e.dolp()
            );
            worst_f = worst_f.max(dev);
            worst_bd = worst_bd.max(dev_bd);
        }
    };
    let n = batch.len();
    for level in SimdLevel::supported() {
        let k = Kernel::with_level(m, level).unwrap();
        let mut out = vec![[f64::NAN; 16]; n];
        let (mut b, mut d) = (vec![f64::NAN; n], vec![f64::NAN; n]);
        k.mueller_into(&batch, 0, &mut out);
        k.brdf_dolp_into(&batch, 0, &mut b, &mut d);
        compare(level.name(), &out, &b, &d);
        // The BRDF is bitwise the same through every path of the kernel.
        for i in 0..n {
            assert_eq!(
                b[i].to_bits(),
                out[i][0].to_bits(),
                "{label}: brdf vs F00 ({i})"
            );
        }
        // The AoS entry point gives the same numbers.
        let gs: Vec<Geometry> = (0..n).map(|i| batch.get(i)).collect();
        let mut ms = vec![Mueller::zero(); n];
        k.mueller_of(&gs, &mut ms);
        for (a, o) in ms.iter().zip(&out) {
            assert_eq!(a.to_row_major(), *o, "{label}: mueller_of vs mueller_into");
        }
    }
    // AoLP (and again BRDF, DoLP) through the AoLP path; single-geometry entry points.
    for level in SimdLevel::supported() {
        let k = Kernel::with_level(m, level).unwrap();
        let (mut b, mut d, mut a) = (vec![f64::NAN; n], vec![f64::NAN; n], vec![f64::NAN; n]);
        let (mut b2, mut d2) = (vec![f64::NAN; n], vec![f64::NAN; n]);
        k.brdf_dolp_into(&batch, 0, &mut b2, &mut d2);
        k.brdf_dolp_aolp_into(&batch, 0, &mut b, &mut d, &mut a);
        assert!(b == b2 && d == d2, "{label}: the AoLP path's BRDF and DoLP");
        for (i, e) in reference.iter().enumerate() {
            let dev_bd = brdf_dolp_deviation(b[i], d[i], e.brdf(), e.dolp());
            assert!(
                dev_bd <= TOL,
                "{label} ({}) element {i}: brdf/dolp {dev_bd:e}",
                level.name()
            );
            check_aolp(&format!("{label} ({}) element {i}", level.name()), a[i], e);
            if i < 200 {
                let g = batch.get(i);
                let dev = deviation(&k.pbrdf(&g).to_row_major(), &e.pbrdf.to_row_major());
                assert!(
                    dev <= TOL,
                    "{label} ({}) element {i}: single pbrdf {dev:e}",
                    level.name()
                );
                let (b1, d1) = k.brdf_dolp(&g);
                let dev_bd = brdf_dolp_deviation(b1, d1, e.brdf(), e.dolp());
                assert!(
                    dev_bd <= TOL,
                    "{label} ({}) element {i}: single brdf/dolp",
                    level.name()
                );
            }
        }
    }
    // The public batch API (parallel, best level).
    let out = batch::mueller(m, &batch).unwrap();
    let (mut b, mut d) = (vec![f64::NAN; n], vec![f64::NAN; n]);
    batch::brdf_dolp_into(m, &batch, &mut b, &mut d).unwrap();
    compare("batch", &out, &b, &d);
    let mut a = vec![f64::NAN; n];
    batch::brdf_dolp_aolp_into(m, &batch, &mut b, &mut d, &mut a).unwrap();
    compare("batch aolp path", &out, &b, &d);
    for (i, e) in reference.iter().enumerate() {
        check_aolp(&format!("{label} (batch) element {i}"), a[i], e);
    }
    (worst_f, worst_bd)
}

/// The AoLP agrees with the reference's `Stokes::aolp` of `F·(1, 0, 0, 0)` as far as F does: an
/// error of 1e-12·F00 in F10, F20 turns it by up to 1e-12/DoLP (on the circle of period π).
fn check_aolp(what: &str, got: f64, e: &polbrdf::Evaluation) {
    let want = e.reflect(&polbrdf::Stokes::unpolarized()).aolp();
    assert!(
        got > -FRAC_PI_2 - 1e-15 && got <= FRAC_PI_2 + 1e-15,
        "{what}: AoLP {got} out of range"
    );
    let dolp = e.dolp();
    if dolp <= TOL {
        // No polarization to within the tolerance (e.g. backscatter, where |rs| = |rp| up to
        // rounding): the angle is undefined.
        return;
    }
    let diff = (got - want).rem_euclid(PI);
    let diff = diff.min(PI - diff);
    let tol = 4.0 * f64::EPSILON + TOL / dolp;
    assert!(diff <= tol, "{what}: AoLP {got} vs {want} (DoLP {dolp:e})");
}

#[test]
fn mueller_of_a_rotated_diagonal_jones_matrix_is_r_md_r() {
    // The identity the kernel is built on:
    // Mueller(Rot(η_r)·diag(rs, rp)·Rot(−η_i)) = R(η_r)·M_d·R(−η_i).
    let mut rng = Rng::new(7);
    for _ in 0..2000 {
        let index = RefractiveIndex::new(rng.range(0.05, 4.0), rng.range(0.0, 6.0)).unwrap();
        let fr: Fresnel = index.amplitudes(rng.range(0.0, FRAC_PI_2));
        let (eta_i, eta_r) = (rng.range(-PI, PI), rng.range(-PI, PI));
        let want = Mueller::from_jones(&Jones::microfacet(&fr, eta_i, eta_r));
        let (rs2, rp2) = (fr.rs.norm_sqr(), fr.rp.norm_sqr());
        let x = fr.rs * fr.rp.conj();
        let (a, b, c, s) = (0.5 * (rs2 + rp2), 0.5 * (rs2 - rp2), x.re, x.im);
        let md = Mueller([
            [a, b, 0.0, 0.0],
            [b, a, 0.0, 0.0],
            [0.0, 0.0, c, s],
            [0.0, 0.0, -s, c],
        ]);
        let got = Mueller::rotator(eta_r) * md * Mueller::rotator(-eta_i);
        for i in 0..4 {
            for j in 0..4 {
                assert!(
                    (got.0[i][j] - want.0[i][j]).abs() <= 1e-15 * want.0[0][0].max(1e-300) * 8.0,
                    "entry {i}{j}: {} vs {}",
                    got.0[i][j],
                    want.0[i][j]
                );
            }
        }
    }
}

#[test]
fn every_test_vector_matches_the_reference_path() {
    let mut worst = (0.0_f64, 0.0_f64);
    let all = cases();
    assert!(all.len() >= 40);
    for c in &all {
        let m = spec_of(&c.inputs).build().unwrap();
        let g = geometry(&c.inputs);
        let (wf, wb) = check(
            &c.id,
            &m,
            &[[g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()]],
        );
        worst = (worst.0.max(wf), worst.1.max(wb));
    }
    eprintln!(
        "kernel vs reference on {} test vectors: max |ΔF|/F00 = {:e}, max brdf/dolp deviation = {:e}",
        all.len(),
        worst.0,
        worst.1
    );
}

/// A random material over the whole parameter space the kernel is meant for.
pub fn random_material(rng: &mut Rng) -> MaterialSpec {
    let (n, k) = match rng.below(4) {
        0 => (rng.range(1.15, 2.6), 0.0),                 // dielectric
        1 => (rng.range(0.2, 0.92), 0.0),                 // n < 1
        2 => (rng.range(0.05, 3.0), rng.range(0.5, 8.0)), // metal
        _ => (rng.range(1.2, 2.0), 10f64.powf(rng.range(-4.0, 0.0))), // absorbing dielectric
    };
    let mut spec = MaterialSpec::new(n, rng.range(1.0, 60.0));
    spec.k = k;
    if rng.next_f64() < 0.3 {
        spec.sigma_deg = None;
        spec.b = Some(10f64.powf(rng.range(-1.0, 3.5)));
        spec.a = Some(rng.range(0.0, 3.0));
    }
    spec.form = if rng.next_f64() < 0.3 {
        Form::Paper
    } else {
        Form::Standard
    };
    spec.shadowing = rng.next_f64() < 0.75;
    spec.azimuth_term = if rng.next_f64() < 0.3 {
        AzimuthTerm::Eq3
    } else {
        AzimuthTerm::None
    };
    spec.tau_deg = rng.range(2.0, 60.0);
    spec.omega_deg = rng.range(5.0, 80.0);
    if rng.next_f64() < 0.6 {
        spec.rho_d = rng.range(0.0, 0.1);
        spec.rho_v = if rng.next_f64() < 0.7 {
            rng.range(0.0, 0.05)
        } else {
            0.0
        };
    }
    spec
}

/// A random geometry (radians), drawn from ordinary and degenerate families.
pub fn random_geometry(rng: &mut Rng) -> [f64; 4] {
    let max = 89.999f64.to_radians();
    let theta = |rng: &mut Rng| rng.range(0.0, max);
    let phi = |rng: &mut Rng| rng.range(-2.0 * PI, 4.0 * PI);
    let tiny = |rng: &mut Rng| sign(rng) * 10f64.powf(rng.range(-14.0, -2.0));
    match rng.below(12) {
        0..=4 => [theta(rng), phi(rng), theta(rng), phi(rng)],
        5 => {
            // exactly specular
            let (t, p) = (theta(rng), phi(rng));
            [t, p, t, p + PI]
        }
        6 => {
            // exactly backscatter
            let (t, p) = (theta(rng), phi(rng));
            [t, p, t, p]
        }
        7 => {
            // near specular or near backscatter
            let (t, p) = (theta(rng), phi(rng));
            let dp = if rng.next_f64() < 0.5 { PI } else { 0.0 };
            let tr = (t + tiny(rng)).clamp(0.0, max);
            [t, p, tr, p + dp + tiny(rng)]
        }
        8 => {
            // normal incidence and/or viewing
            let p = phi(rng);
            match rng.below(3) {
                0 => [0.0, p, theta(rng), phi(rng)],
                1 => [theta(rng), p, 0.0, phi(rng)],
                _ => [0.0, p, 0.0, phi(rng)],
            }
        }
        9 => {
            // grazing
            let g = |rng: &mut Rng| rng.range(89.9f64.to_radians(), max);
            [g(rng), phi(rng), g(rng), phi(rng)]
        }
        10 => {
            // at or below the horizon
            let below = rng.range(FRAC_PI_2, PI);
            if rng.next_f64() < 0.5 {
                [below, phi(rng), theta(rng), phi(rng)]
            } else {
                [theta(rng), phi(rng), FRAC_PI_2, phi(rng)]
            }
        }
        _ => {
            // large azimuths (many turns; rarely beyond the kernel's reduction range)
            let big = if rng.next_f64() < 0.1 { 1e6 } else { 1e3 };
            [
                theta(rng),
                rng.range(-big, big),
                theta(rng),
                rng.range(-big, big),
            ]
        }
    }
}

#[test]
fn random_inputs_across_materials_match_the_reference_path() {
    let mut rng = Rng::new(20240607);
    let (materials, per_material) = (400, 300);
    let mut worst = (0.0_f64, 0.0_f64);
    for mi in 0..materials {
        let spec = random_material(&mut rng);
        let m = spec.build().unwrap();
        let geoms: Vec<[f64; 4]> = (0..per_material)
            .map(|_| random_geometry(&mut rng))
            .collect();
        let (wf, wb) = check(&format!("material {mi} {spec:?}"), &m, &geoms);
        worst = (worst.0.max(wf), worst.1.max(wb));
    }
    eprintln!(
        "kernel vs reference on {} random cases: max |ΔF|/F00 = {:e}, max brdf/dolp deviation = {:e}",
        materials * per_material,
        worst.0,
        worst.1
    );
}

#[test]
fn presets_on_random_geometries_match_the_reference_path() {
    let mut rng = Rng::new(99);
    for p in polbrdf::presets::all() {
        let m = p.spec.build().unwrap();
        let geoms: Vec<[f64; 4]> = (0..5000).map(|_| random_geometry(&mut rng)).collect();
        check(p.name, &m, &geoms);
    }
}

#[test]
fn hard_materials_match_the_reference_path() {
    // Narrow lobes, an index close to 1 (kernel falls back), n < 1 near its critical angle,
    // tiny τ and Ω, a = 0, tiny a.
    let mut rng = Rng::new(5);
    let mut specs = vec![];
    for sigma in [0.1, 0.5, 1.0, 2.0] {
        specs.push(MaterialSpec::new(1.5, sigma));
    }
    for n in [1.0, 1.001, 1.02, 1.05, 0.98, 0.7] {
        specs.push(MaterialSpec::new(n, 10.0));
    }
    let mut s = MaterialSpec::new(1.6, 20.0);
    s.tau_deg = 0.5;
    s.omega_deg = 0.5;
    s.azimuth_term = AzimuthTerm::Eq3;
    specs.push(s);
    for a in [0.0, 1e-250, 1e-100] {
        let mut s = MaterialSpec::new(1.5, 10.0);
        s.sigma_deg = None;
        s.b = Some(30.0);
        s.a = Some(a);
        specs.push(s);
    }
    for spec in specs {
        let m = spec.build().unwrap();
        let mut geoms: Vec<[f64; 4]> = (0..3000).map(|_| random_geometry(&mut rng)).collect();
        // Sweep β across the critical angle of n < 1 and the lobe of narrow ones.
        for i in 0..2000 {
            let t = i as f64 / 2000.0 * 89.9f64.to_radians();
            geoms.push([t, 0.3, t, 0.3 + PI - 1e-3 * (i % 7) as f64]);
            geoms.push([t, 0.0, t, 0.0]);
        }
        check(&format!("{spec:?}"), &m, &geoms);
    }
}

#[test]
fn extreme_valid_parameters_match_the_reference_path_and_stay_physical() {
    // The bounds of MaterialSpec::build: |N| up to 1e6, a, b, ρ up to 1e100, tiny and huge τ, Ω.
    let mut rng = Rng::new(17);
    let mut specs = vec![];
    for (n, k) in [
        (1e6, 0.0),
        (1e6, 1e6),
        (1e-3, 0.0),
        (1e-3, 1e6),
        (2.0, 1e-9),
    ] {
        specs.push(MaterialSpec::new(n, 10.0));
        specs.last_mut().unwrap().k = k;
    }
    for (a, b) in [(1e100, 1e-3), (1e100, 1e100), (0.0, 1.0), (1e-300, 2.0)] {
        let mut s = MaterialSpec::new(1.5, 10.0);
        s.sigma_deg = None;
        (s.a, s.b) = (Some(a), Some(b));
        s.form = Form::Paper;
        specs.push(s);
    }
    for (tau, omega) in [(1e-6, 1e-6), (1e4, 1e4), (0.01, 1e3)] {
        let mut s = MaterialSpec::new(1.5, 30.0);
        (s.tau_deg, s.omega_deg) = (tau, omega);
        s.azimuth_term = AzimuthTerm::Eq3;
        specs.push(s);
    }
    let mut s = MaterialSpec::new(1.5, 5.0);
    (s.rho_d, s.rho_v) = (1e100, 1e100);
    specs.push(s);
    for spec in specs {
        let m = spec.build().unwrap();
        let geoms: Vec<[f64; 4]> = (0..4000).map(|_| random_geometry(&mut rng)).collect();
        check(&format!("{spec:?}"), &m, &geoms);
        let cols = columns(&geoms);
        let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
        let out = batch::mueller(&m, &batch).unwrap();
        let (mut b, mut d) = (vec![0.0; geoms.len()], vec![0.0; geoms.len()]);
        batch::brdf_dolp_into(&m, &batch, &mut b, &mut d).unwrap();
        for i in 0..geoms.len() {
            assert!(
                out[i].iter().all(|v| v.is_finite()),
                "{spec:?}: {:?}",
                geoms[i]
            );
            assert!(out[i][0] >= 0.0 && b[i] >= 0.0);
            assert!((0.0..=1.0).contains(&d[i]), "{spec:?}: DoLP {}", d[i]);
        }
    }
}

#[test]
fn chunk_boundaries_and_partial_blocks() {
    let m = polbrdf::preset("paint").unwrap().build().unwrap();
    let mut rng = Rng::new(3);
    for n in [0, 1, 2, 7, 31, 32, 33, 63, 65, 4095, 4097, 9000] {
        let geoms: Vec<[f64; 4]> = (0..n).map(|_| random_geometry(&mut rng)).collect();
        check(&format!("n = {n}"), &m, &geoms);
    }
    // A sub-range of a batch.
    let geoms: Vec<[f64; 4]> = (0..100).map(|_| random_geometry(&mut rng)).collect();
    let cols = columns(&geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let k = Kernel::new(&m);
    let mut all = vec![[0.0; 16]; 100];
    k.mueller_into(&batch, 0, &mut all);
    let mut part = vec![[0.0; 16]; 37];
    k.mueller_into(&batch, 41, &mut part);
    assert_eq!(&all[41..78], &part[..]);
}

#[test]
fn batch_results_do_not_depend_on_the_thread_count() {
    let m = polbrdf::preset("gold").unwrap().build().unwrap();
    let mut rng = Rng::new(11);
    let geoms: Vec<[f64; 4]> = (0..20_000).map(|_| random_geometry(&mut rng)).collect();
    let cols = columns(&geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| batch::mueller(&m, &batch).unwrap());
    let many = batch::mueller(&m, &batch).unwrap();
    assert!(one == many);
}

#[test]
fn per_element_index_matches_the_one_geometry_path_of_each_index() {
    // One call over materials × wavelengths × geometries: element j with its own N_j.
    use polbrdf::engine::{Engine, IndexColumns};
    let mut rng = Rng::new(31);
    for _ in 0..40 {
        let spec = random_material(&mut rng);
        let m = spec.build().unwrap();
        let n_el = 700;
        let geoms: Vec<[f64; 4]> = (0..n_el).map(|_| random_geometry(&mut rng)).collect();
        let cols = columns(&geoms);
        let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
        // A few indices, as a sweep over wavelengths has them: blocks of equal and of mixed N.
        let table: Vec<(f64, f64)> = (0..5)
            .map(|_| match rng.below(3) {
                0 => (rng.range(1.2, 2.5), 0.0),
                1 => (rng.range(0.1, 3.0), rng.range(0.5, 8.0)),
                _ => (rng.range(1.3, 1.8), 10f64.powf(rng.range(-4.0, -1.0))),
            })
            .collect();
        let pick: Vec<usize> = (0..n_el)
            .map(|j| if j < 300 { j / 64 % 5 } else { rng.below(5) })
            .collect();
        let n: Vec<f64> = pick.iter().map(|&i| table[i].0).collect();
        let k: Vec<f64> = pick.iter().map(|&i| table[i].1).collect();
        let engine = Engine::new(&m).with_index(IndexColumns::new(&n, &k).unwrap());
        let out = engine.mueller(&batch).unwrap();
        let (mut b, mut d) = (vec![0.0; n_el], vec![0.0; n_el]);
        engine.brdf_dolp_into(&batch, &mut b, &mut d).unwrap();
        for j in 0..n_el {
            let idx = RefractiveIndex::new(n[j], k[j]).unwrap();
            let e = m.with_index(idx).evaluate(&batch.get(j));
            let dev = deviation(&out[j], &e.pbrdf.to_row_major());
            assert!(
                dev <= TOL,
                "element {j} {:?} N = {idx:?}: {dev:e}",
                geoms[j]
            );
            assert!(brdf_dolp_deviation(b[j], d[j], e.brdf(), e.dolp()) <= TOL);
            assert_eq!(b[j].to_bits(), out[j][0].to_bits());
        }
    }
}

#[test]
fn prepared_geometry_gives_exactly_the_unprepared_results() {
    use polbrdf::engine::{Engine, IndexColumns};
    let mut rng = Rng::new(41);
    for _ in 0..60 {
        let m = random_material(&mut rng).build().unwrap();
        let n_el = 1 + rng.below(3000);
        let geoms: Vec<[f64; 4]> = (0..n_el).map(|_| random_geometry(&mut rng)).collect();
        let cols = columns(&geoms);
        let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
        for level in SimdLevel::supported() {
            let k = Kernel::with_level(&m, level).unwrap();
            let prepared = k.prepare(&batch);
            assert_eq!(prepared.len(), n_el);
            let (mut a, mut p) = (vec![[0.0; 16]; n_el], vec![[0.0; 16]; n_el]);
            k.mueller_into(&batch, 0, &mut a);
            k.mueller_prepared_into(&prepared, 0, &mut p);
            assert!(a == p, "{}", level.name());
            let (mut b1, mut d1, mut b2, mut d2) = (
                vec![0.0; n_el],
                vec![0.0; n_el],
                vec![0.0; n_el],
                vec![0.0; n_el],
            );
            k.brdf_dolp_into(&batch, 0, &mut b1, &mut d1);
            k.brdf_dolp_prepared_into(&prepared, 0, &mut b2, &mut d2);
            assert!(b1 == b2 && d1 == d2, "{}", level.name());
        }
        // The parallel engine, and one prepared batch serving another material and an index.
        let e = Engine::new(&m);
        let prepared = e.prepare(&batch);
        let other = random_material(&mut rng).build().unwrap();
        let n: Vec<f64> = (0..n_el).map(|_| rng.range(1.2, 2.0)).collect();
        let kk: Vec<f64> = (0..n_el).map(|_| rng.range(0.0, 0.5)).collect();
        for engine in [
            Engine::new(&other),
            Engine::new(&other).with_index(IndexColumns::new(&n, &kk).unwrap()),
        ] {
            let mut p = vec![[0.0; 16]; n_el];
            engine.mueller_prepared_into(&prepared, &mut p).unwrap();
            assert!(engine.mueller(&batch).unwrap() == p);
            let (mut b1, mut d1, mut b2, mut d2) = (
                vec![0.0; n_el],
                vec![0.0; n_el],
                vec![0.0; n_el],
                vec![0.0; n_el],
            );
            engine.brdf_dolp_into(&batch, &mut b1, &mut d1).unwrap();
            engine
                .brdf_dolp_prepared_into(&prepared, &mut b2, &mut d2)
                .unwrap();
            assert!(b1 == b2 && d1 == d2);
        }
    }
}

#[test]
fn streamed_outputs_equal_cached_ones_bit_for_bit() {
    // With streaming (the engine's default for outputs of at least STREAM_MIN elements),
    // whole blocks go out of the transpose by non-temporal stores; otherwise by plain ones.
    // Both, through the kernel and the engine, at any alignment, give the same bits.
    let m = polbrdf::preset("gold").unwrap().build().unwrap();
    let mut rng = Rng::new(13);
    let n = batch::STREAM_MIN + 37;
    let geoms: Vec<[f64; 4]> = (0..n).map(|_| random_geometry(&mut rng)).collect();
    let cols = columns(&geoms);
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let k = Kernel::new(&m);
    let mut cached = vec![[f64::NAN; 16]; n];
    k.mueller_into(&batch, 0, &mut cached);
    let mut streamed = vec![[f64::NAN; 16]; n];
    k.clone()
        .streaming(true)
        .mueller_into(&batch, 0, &mut streamed);
    assert!(cached == streamed, "streamed vs cached");
    for stream in [false, true] {
        let mut engine = vec![[f64::NAN; 16]; n];
        polbrdf::engine::Engine::new(&m)
            .streaming(stream)
            .mueller_into(&batch, &mut engine)
            .unwrap();
        assert!(cached == engine, "engine (streaming {stream}) vs kernel");
    }
    // Destinations at every 8-byte offset from a 64-byte boundary: 32-byte aligned (256-bit
    // non-temporal stores), 16-byte aligned (their halves), and not 16-byte aligned (plain
    // stores); an odd length ends in a partial block.
    // The 64-byte boundary lies up to 7 elements in, and the shift adds up to 3 more.
    let mut flat = vec![f64::NAN; 16 * 101 + 7 + 3];
    let base = (0..8)
        .find(|o| (flat.as_ptr() as usize + 8 * o).is_multiple_of(64))
        .unwrap();
    for shift in 0..4 {
        let off = base + shift;
        let dst: &mut [[f64; 16]] = flat[off..off + 16 * 101].as_chunks_mut::<16>().0;
        dst.fill([f64::NAN; 16]);
        k.clone().streaming(true).mueller_into(&batch, 5, dst);
        assert!(
            dst == &cached[5..106],
            "streamed output {} bytes past a 64-byte boundary",
            8 * shift
        );
    }
    // Spot checks against the one-geometry path.
    for i in (0..n).step_by(997) {
        let want = m.evaluate(&batch.get(i)).pbrdf.to_row_major();
        assert!(deviation(&cached[i], &want) <= TOL, "element {i}");
    }
}

#[test]
fn elementary_functions_for_benchmarks_match_the_standard_library() {
    use polbrdf::engine::{elementary_into, Elementary};
    let n = 1000;
    let x: Vec<f64> = (0..n).map(|j| 0.0015 * j as f64).collect();
    let y: Vec<f64> = (0..n).map(|j| 0.0011 * (n - j) as f64).collect();
    for level in SimdLevel::supported() {
        for op in Elementary::ALL {
            let mut out = vec![f64::NAN; n];
            elementary_into(level, op, &x, &y, &mut out).unwrap();
            for j in 0..n {
                let want = match op {
                    Elementary::SinCos => x[j].sin() + x[j].cos(),
                    Elementary::Atan2 => y[j].atan2(x[j]),
                    Elementary::Exp => (-x[j]).exp(),
                    Elementary::Sqrt => x[j].sqrt(),
                    Elementary::Div => y[j] / x[j],
                };
                let ok = if want.is_finite() {
                    (out[j] - want).abs() <= 4.0 * f64::EPSILON * want.abs().max(1e-300)
                } else {
                    out[j] == want
                };
                assert!(
                    ok,
                    "{} {} at {j}: {} vs {want}",
                    level.name(),
                    op.name(),
                    out[j]
                );
            }
        }
    }
}

#[test]
fn the_parallel_driver_covers_every_element_once_and_keeps_errors() {
    use polbrdf::engine::batch::{try_for_chunks, CHUNK, SERIAL_MAX};
    // Never called for nothing.
    let mut none: Vec<u32> = vec![];
    let r: Result<bool, ()> = try_for_chunks(none.as_mut_slice(), |_, _| panic!("called"));
    assert_eq!(r, Ok(false));
    for n in [1, SERIAL_MAX, SERIAL_MAX + 1, 3 * CHUNK + 5, 100_003] {
        let mut marks = vec![0u32; n];
        let pos: Vec<usize> = (0..n).collect();
        let caller = std::thread::current().id();
        let overflow = try_for_chunks((marks.as_mut_slice(), pos.as_slice()), |start, (m, p)| {
            assert!(m.len() <= CHUNK && m.len() == p.len());
            if n <= SERIAL_MAX {
                // A small batch is one call on the calling thread.
                assert_eq!((start, m.len()), (0, n));
                assert_eq!(std::thread::current().id(), caller);
            }
            for (j, (x, &i)) in m.iter_mut().zip(p).enumerate() {
                assert_eq!(i, start + j, "part at {start}");
                *x += 1;
            }
            Ok::<_, ()>(start == 0)
        });
        assert_eq!(overflow, Ok(true), "n = {n}");
        assert!(marks.iter().all(|&x| x == 1), "n = {n}");
    }
    // An error of any part is returned.
    let mut v = vec![0u8; 50_000];
    let r = try_for_chunks(v.as_mut_slice(), |start, _| {
        if start > 0 {
            Err(start)
        } else {
            Ok(false)
        }
    });
    assert!(matches!(r, Err(s) if s > 0));
}
