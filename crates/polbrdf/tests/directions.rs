//! The direction entry point (`DirectionBatch`, docs/model.md §9.11): direction vectors give
//! the results of the angles they stand for — within 1e-12·F00 on random materials and
//! geometries (degenerate ones included), in both precisions (float32 within 1e-5·F00 of
//! float64), for any length of the vectors; `φ = 0` along the normal; `z ≤ 0` is at or below
//! the horizon; bad vectors are refused with their name and index.

use crate::kernel::{random_geometry, random_material};
use polbrdf::geometry::angles::direction_angles;
use polbrdf::geometry::direction;
use polbrdf::sample::SplitMix64 as Rng;
use polbrdf::{AzimuthTerm, DirectionBatch, Engine, Error, GeometryBatch, Material, MaterialSpec};

/// Largest `|got − want|/F00(want)` over the 16 entries (∞ where F00 = 0 and `got` is not 0).
fn deviation<T: Into<f64> + Copy>(got: &[T; 16], want: &[f64; 16]) -> f64 {
    let f00 = want[0];
    let got: [f64; 16] = got.map(Into::into);
    if f00 == 0.0 {
        return if got.iter().chain(want).all(|v| *v == 0.0) {
            0.0
        } else {
            f64::INFINITY
        };
    }
    got.iter()
        .zip(want)
        .map(|(g, w)| (g - w).abs() / f00)
        .fold(0.0, f64::max)
}

/// A random direction vector for `(θ, φ)`, scaled by a random length in `10^±decades`.
fn vector(rng: &mut Rng, theta: f64, phi: f64, decades: f64) -> [f64; 3] {
    let len = 10f64.powf(rng.range(-decades, decades));
    direction(theta, phi).map(|c| c * len)
}

/// `cosθ` of a vector.
fn cos_theta(w: &[f64; 3]) -> f64 {
    w[2] / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt()
}

/// Random geometries as vectors of lengths in `10^±decades`.
fn random_pairs(rng: &mut Rng, n: usize, decades: f64) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let mut w_i = Vec::with_capacity(n);
    let mut w_r = Vec::with_capacity(n);
    for _ in 0..n {
        let [ti, pi, tr, pr] = if rng.below(8) == 0 {
            // within 1e-200 .. 1e-2 rad of the normal (the azimuth's unit vector from tiny
            // components)
            let tiny = |rng: &mut Rng| 10f64.powf(rng.range(-200.0, -2.0));
            [
                tiny(rng),
                rng.range(0.0, 7.0),
                rng.range(0.0, 1.5),
                rng.range(0.0, 7.0),
            ]
        } else {
            random_geometry(rng)
        };
        w_i.push(vector(rng, ti, pi, decades));
        w_r.push(vector(rng, tr, pr, decades));
    }
    (w_i, w_r)
}

/// The angle columns of vectors.
fn angle_columns(w_i: &[[f64; 3]], w_r: &[[f64; 3]]) -> [Vec<f64>; 4] {
    let a: Vec<_> = w_i.iter().map(|w| direction_angles(*w)).collect();
    let b: Vec<_> = w_r.iter().map(|w| direction_angles(*w)).collect();
    [
        a.iter().map(|x| x.0).collect(),
        a.iter().map(|x| x.1).collect(),
        b.iter().map(|x| x.0).collect(),
        b.iter().map(|x| x.1).collect(),
    ]
}

#[test]
fn directions_give_the_results_of_their_angles() {
    let mut rng = Rng::new(0xd1ec7);
    let (mut worst, mut smooth) = (0.0_f64, 0.0_f64);
    for m in 0..60 {
        let spec = random_material(&mut rng);
        let mat = spec.build().unwrap();
        let (w_i, w_r) = random_pairs(&mut rng, 500, 12.0);
        let cols = angle_columns(&w_i, &w_r);
        let angles = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
        let dirs = DirectionBatch::new(&w_i, &w_r).unwrap();
        let e = Engine::new(&mat);
        let want = e.mueller(&angles).unwrap();
        // The geometry with one angle moved by 2.2e-16 rad (relative, beyond 1).
        let moved: Vec<Vec<[f64; 16]>> = (0..4)
            .map(|k| {
                let mut c = cols.clone();
                for x in c[k].iter_mut() {
                    *x += 2.2e-16 * x.abs().max(1.0);
                }
                let b = GeometryBatch::new(&c[0], &c[1], &c[2], &c[3]).unwrap();
                e.mueller(&b).unwrap()
            })
            .collect();
        let got = e.mueller(&dirs).unwrap();
        let (mut b, mut d) = (vec![0.0; w_i.len()], vec![0.0; w_i.len()]);
        let (mut b0, mut d0) = (b.clone(), d.clone());
        e.brdf_dolp_into(&dirs, &mut b, &mut d).unwrap();
        e.brdf_dolp_into(&angles, &mut b0, &mut d0).unwrap();
        for j in 0..w_i.len() {
            // The two inputs round the same directions differently, by about 1e-16 rad: the
            // tolerance is what that does here, measured as the change of F when one angle moves
            // by 2.2e-16 (times a few: the vector's three components and its normalization).
            // Near grazing facet incidence and specular this reaches 1e-10 (eq. 3's ΦN, the
            // Fresnel amplitudes). Within 1e-9 of the horizon angles cannot tell above from on it.
            let c = cos_theta(&w_i[j]).min(cos_theta(&w_r[j]));
            if c < 1e-9 {
                continue;
            }
            let kappa = (0..4)
                .map(|k| deviation(&moved[k][j], &want[j]))
                .fold(0.0, f64::max);
            let tol = 1e-12 + 8.0 * kappa;
            let dev = deviation(&got[j], &want[j]);
            assert!(
                dev <= tol,
                "material {m} {spec:?} element {j}: w_i {:?} w_r {:?} (angles {:?}): {dev:e}·F00\n{:?}\n{:?}",
                w_i[j],
                w_r[j],
                [cols[0][j], cols[1][j], cols[2][j], cols[3][j]],
                got[j],
                want[j]
            );
            // The one-geometry path at the batch's angles.
            let reference = mat.evaluate(&dirs.get(j)).pbrdf.0;
            let reference: [f64; 16] = std::array::from_fn(|k| reference[k / 4][k % 4]);
            assert!(
                deviation(&got[j], &reference) <= tol,
                "element {j} vs reference"
            );
            assert!(
                (b[j] - b0[j]).abs() <= tol * b0[j],
                "BRDF {j}: {} vs {}",
                b[j],
                b0[j]
            );
            assert!(
                (d[j] - d0[j]).abs() <= tol,
                "DoLP {j}: {} vs {}",
                d[j],
                d0[j]
            );
            if spec.azimuth_term == AzimuthTerm::None {
                smooth = smooth.max(dev);
            }
            worst = worst.max(dev);
        }
    }
    // Without eq. 3, F is a smooth function of the directions: the two inputs agree closely
    // everywhere the angles resolve the horizon.
    eprintln!("directions vs angles: worst {worst:e}·F00, {smooth:e} without eq. 3");
    assert!(smooth <= 1e-11, "without eq. 3: {smooth:e}·F00");
}

#[test]
fn float32_from_directions_is_within_the_contract() {
    // The float32 contract (docs/model.md §12): every entry within 1e-5·F00 + 1e-6·P of
    // float64, P the F00 at the specular direction of the same incidence (w_i mirrored about
    // the normal), plus half f32's smallest subnormal.
    let mut rng = Rng::new(0xf32d);
    let mut worst = 0.0_f64;
    for _ in 0..60 {
        let mat = random_material(&mut rng).build().unwrap();
        let (w_i, w_r) = random_pairs(&mut rng, 500, 12.0);
        let dirs = DirectionBatch::new(&w_i, &w_r).unwrap();
        let e = Engine::new(&mat);
        let want = e.mueller(&dirs).unwrap();
        let mirror: Vec<[f64; 3]> = w_i.iter().map(|w| [-w[0], -w[1], w[2]]).collect();
        let spec = e
            .mueller(&DirectionBatch::new(&w_i, &mirror).unwrap())
            .unwrap();
        let mut got = vec![[0f32; 16]; w_i.len()];
        e.mueller_f32_into(&dirs, &mut got).unwrap();
        for j in 0..w_i.len() {
            let abs = got[j]
                .iter()
                .zip(&want[j])
                .map(|(g, w)| (f64::from(*g) - w).abs())
                .fold(0.0, f64::max);
            let bound = 1e-5 * want[j][0] + 1e-6 * spec[j][0];
            assert!(
                abs <= bound + 7.1e-46,
                "element {j}: w_i {:?} w_r {:?}: {abs:e}, F00 {:e}, P {:e}",
                w_i[j],
                w_r[j],
                want[j][0],
                spec[j][0]
            );
            if want[j][0] >= 1e-35 && bound > 0.0 {
                worst = worst.max(abs / bound);
            }
        }
    }
    eprintln!("float32 from directions: worst {worst:.3} of the bound");
}

#[test]
fn a_direction_of_any_length_is_the_same_direction() {
    let mut rng = Rng::new(0x5ca1e);
    let mat = MaterialSpec::new(1.5, 12.0).build().unwrap();
    let e = Engine::new(&mat);
    let (w_i, w_r) = random_pairs(&mut rng, 2000, 2.0);
    let base = e
        .mueller(&DirectionBatch::new(&w_i, &w_r).unwrap())
        .unwrap();
    // Powers of two scale exactly: the same bits. Other factors: rounding of the components.
    for (scale, tol) in [(2f64.powi(30), 0.0), (2f64.powi(-35), 0.0), (3.7e-7, 1e-12)] {
        let s =
            |w: &[[f64; 3]]| -> Vec<[f64; 3]> { w.iter().map(|v| v.map(|c| c * scale)).collect() };
        let (a, b) = (s(&w_i), s(&w_r));
        let got = e.mueller(&DirectionBatch::new(&a, &b).unwrap()).unwrap();
        for j in 0..got.len() {
            let dev = deviation(&got[j], &base[j]);
            assert!(dev <= tol, "scale {scale:e}, element {j}: {dev:e}");
        }
    }
}

#[test]
fn along_the_normal_the_azimuth_is_zero() {
    // At normal incidence the s axis of the incident beam is set by φi alone (docs/model.md
    // §1): a vector along the normal stands for φ = 0.
    let mat = MaterialSpec::new(1.6, 20.0).build().unwrap();
    let e = Engine::new(&mat);
    let (t, p) = (40f64.to_radians(), 1.1);
    let w_i = [[0.0, 0.0, 2.5]];
    let w_r = [direction(t, p)];
    let got = e
        .mueller(&DirectionBatch::new(&w_i, &w_r).unwrap())
        .unwrap()[0];
    let at = |phi_i: f64| {
        let ([ti], [pi], [tr], [pr]) = ([0.0], [phi_i], [t], [p]);
        e.mueller(&GeometryBatch::new(&[ti], &[pi], &[tr], &[pr]).unwrap())
            .unwrap()[0]
    };
    assert!(deviation(&got, &at(0.0)) <= 1e-12);
    // The azimuth matters there: another φi gives another matrix (the basis turns).
    assert!(deviation(&got, &at(1.0)) > 1e-3);
    // And so does the viewing direction's: along the normal, φr = 0.
    let w_r = [[0.0, 0.0, 1.0]];
    let w_i = [direction(t, p)];
    let got = e
        .mueller(&DirectionBatch::new(&w_i, &w_r).unwrap())
        .unwrap()[0];
    let cols = ([t], [p], [0.0], [0.0]);
    let b = GeometryBatch::new(&cols.0, &cols.1, &cols.2, &cols.3).unwrap();
    assert!(deviation(&got, &e.mueller(&b).unwrap()[0]) <= 1e-12);
}

#[test]
fn at_or_below_the_horizon_the_pbrdf_is_zero() {
    let mat = MaterialSpec::new(1.5, 10.0).build().unwrap();
    let e = Engine::new(&mat);
    let up = direction(0.5, 0.3);
    let cases = [
        [1.0, 0.0, 0.0],  // on the horizon
        [1.0, 0.0, -0.0], // on the horizon, signed zero
        [0.3, 0.4, -0.5], // below
        [0.0, 0.0, -1.0], // straight down
    ];
    for w in cases {
        for (w_i, w_r) in [([w], [up]), ([up], [w])] {
            let d = DirectionBatch::new(&w_i, &w_r).unwrap();
            let f = e.mueller(&d).unwrap()[0];
            assert!(f.iter().all(|v| *v == 0.0), "{w:?}: {f:?}");
            let mut f32s = [[1f32; 16]];
            e.mueller_f32_into(&d, &mut f32s).unwrap();
            assert!(f32s[0].iter().all(|v| *v == 0.0), "{w:?} (f32)");
        }
    }
    // Just above it (z/|w| = 1e-20, where θ rounds to 90° as an angle): above, on every path
    // (the one-geometry path at the largest angle below 90°).
    let w_i = [[1.0, 0.0, 1e-20]];
    let w_r = [direction(0.5, 3.0)];
    let d = DirectionBatch::new(&w_i, &w_r).unwrap();
    assert!(d.get(0).is_above_horizon());
    let f = e.mueller(&d).unwrap()[0];
    assert!(f[0].is_finite() && f[0] > 0.0, "{}", f[0]);
    assert!(mat.evaluate(&d.get(0)).pbrdf.0[0][0] > 0.0);
}

#[test]
fn a_hair_above_the_horizon_the_kernel_is_finite_and_agrees_with_the_angles() {
    // z/|w| far below what an f64 angle below 90° can express (down to the subnormal range,
    // the case a fuzzer found: `1/cosθ` overflowed to ∞): the kernel takes cos θ of the largest
    // angle below 90°, as the one-geometry path does, in both precisions.
    let below_90 = std::f64::consts::FRAC_PI_2.next_down();
    assert_eq!(polbrdf::geometry::angles::COS_BELOW_90, below_90.cos());
    for mat in [
        polbrdf::preset("paint").unwrap().build().unwrap(),
        MaterialSpec::new(1.5, 10.0).build().unwrap(),
    ] {
        let e = Engine::new(&mat);
        for z in [1e-17, 1e-20, 1e-200, 2.1e-313] {
            let low = [-0.5, 6e-154, z];
            for (w_i, w_r) in [
                ([low], [direction(0.5, 3.0)]),
                ([direction(0.9, 0.2)], [low]),
                ([low], [[0.5, 1e-3, z]]),
            ] {
                let d = DirectionBatch::new(&w_i, &w_r).unwrap();
                let want = mat.evaluate(&d.get(0)).pbrdf.to_row_major();
                let got = e.mueller(&d).unwrap()[0];
                assert!(got.iter().all(|v| v.is_finite()), "z = {z:e}: {got:?}");
                assert!(
                    deviation(&got, &want) <= 1e-12,
                    "z = {z:e}: {got:?} vs {want:?}"
                );
                let mut f32s = [[0f32; 16]];
                e.mueller_f32_into(&d, &mut f32s).unwrap();
                assert!(
                    deviation(&f32s[0], &want) <= 1e-5,
                    "z = {z:e} (f32): {:?}",
                    f32s[0]
                );
            }
        }
    }
}

#[test]
fn bad_vectors_are_refused_with_their_name_and_index() {
    let ok = [0.0, 0.2, 1.0];
    let bad = [
        [f64::NAN, 0.0, 1.0],
        [0.0, f64::INFINITY, 1.0],
        [0.0, 0.0, 0.0],
        [1e-16, 0.0, 0.0],
        [0.0, 2e15, 0.0],
    ];
    for v in bad {
        for (which, name) in [(0, "w_i"), (1, "w_r")] {
            let mut w = [vec![ok; 3000], vec![ok; 3000]];
            w[which][2345] = v;
            let e = DirectionBatch::new(&w[0], &w[1]).unwrap_err();
            match &e {
                Error::InvalidDirection {
                    name: n,
                    index: Some(2345),
                    ..
                } if *n == name => {}
                other => panic!("{v:?} in {name}: {other:?}"),
            }
            let msg = e.to_string();
            assert!(msg.contains(name) && msg.contains("2345"), "{msg}");
        }
    }
    // The extreme lengths themselves are accepted.
    let w = [[0.0, 0.0, 1e-15], [0.0, 1e15, 1.0]];
    assert!(DirectionBatch::new(&w, &w).is_ok());
    assert!(matches!(
        DirectionBatch::new(&[ok; 2], &[ok; 3]),
        Err(Error::LengthMismatch { .. })
    ));
    // And an output of the wrong length.
    let m: Material = MaterialSpec::new(1.5, 10.0).build().unwrap();
    let two = [ok; 2];
    let d = DirectionBatch::new(&two, &two).unwrap();
    let mut out = [[0.0; 16]; 3];
    assert!(Engine::new(&m).mueller_into(&d, &mut out).is_err());
}
