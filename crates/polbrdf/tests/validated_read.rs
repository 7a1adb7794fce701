//! Validation folded into the kernel's read (`Unvalidated`, `Kernel::try_mueller_into` and its
//! siblings; docs/engine-performance.md, "Input validation"): on valid input the bits of the
//! validated path; on an invalid element — wherever it is, the last block included — the
//! constructor's own error (element, field, index) and an output of NaN only, in both
//! precisions, both layouts, from angles and from direction vectors, at every SIMD level this
//! CPU supports, and through the one-geometry path of a material the block kernel leaves alone.

use crate::kernel::{random_geometry, random_material};
use polbrdf::engine::{Kernel, Planes, SimdLevel};
use polbrdf::geometry::direction;
use polbrdf::sample::SplitMix64 as Rng;
use polbrdf::{DirectionBatch, Error, GeometryBatch, Material, MaterialSpec, Unvalidated};

/// Not a multiple of either block size (16, 32): the last block is partial.
const N: usize = 1001;

fn bits<T: Copy + Into<f64>>(x: &[[T; 16]]) -> Vec<u64> {
    x.iter().flatten().map(|v| (*v).into().to_bits()).collect()
}

fn columns(n: usize, rng: &mut Rng) -> [Vec<f64>; 4] {
    let g: Vec<[f64; 4]> = (0..n).map(|_| random_geometry(rng)).collect();
    std::array::from_fn(|c| g.iter().map(|x| x[c]).collect())
}

/// Unit and non-unit vectors of the geometries of `cols`.
fn vectors(cols: &[Vec<f64>; 4], rng: &mut Rng) -> [Vec<[f64; 3]>; 2] {
    std::array::from_fn(|s| {
        (0..cols[0].len())
            .map(|j| {
                let scale = 2f64.powf(rng.range(-20.0, 20.0));
                direction(cols[2 * s][j], cols[2 * s + 1][j]).map(|x| x * scale)
            })
            .collect()
    })
}

/// The conductor of the peer benchmark, paint, and random materials (some with shadowing, ΦN,
/// a volume term).
fn materials(rng: &mut Rng) -> Vec<Material> {
    let mut m = vec![
        MaterialSpec {
            k: 7.0,
            shadowing: false,
            ..MaterialSpec::new(1.2, 0.2f64.atan().to_degrees())
        }
        .build()
        .unwrap(),
        polbrdf::preset("paint").unwrap().build().unwrap(),
    ];
    m.extend((0..4).map(|_| random_material(rng).build().unwrap()));
    m
}

fn kernels(m: &Material) -> impl Iterator<Item = (SimdLevel, Kernel<'_>)> {
    SimdLevel::supported()
        .into_iter()
        .map(move |level| (level, Kernel::with_level(m, level).unwrap()))
}

/// Every output of the validating methods for `raw` (elements `start ..` of it), each
/// pre-filled with 7: rows and planes in f64 and f32, with the result of each call.
struct Outputs {
    rows: Vec<[f64; 16]>,
    planes: Vec<f64>,
    rows32: Vec<[f32; 16]>,
    planes32: Vec<f32>,
    results: [Result<bool, Error>; 4],
}

fn run(k: &Kernel<'_>, raw: &Unvalidated<'_>, start: usize) -> Outputs {
    let n = raw.len() - start;
    let mut rows = vec![[7.0f64; 16]; n];
    let mut planes = vec![7.0f64; 16 * n];
    let mut rows32 = vec![[7.0f32; 16]; n];
    let mut planes32 = vec![7.0f32; 16 * n];
    let results = [
        k.try_mueller_into(raw, start, &mut rows).map(|()| false),
        k.try_mueller_planes_into(raw, start, &mut Planes::new(&mut planes, n).unwrap())
            .map(|()| false),
        k.try_mueller_f32_into(raw, start, &mut rows32),
        k.try_mueller_planes_f32_into(raw, start, &mut Planes::new(&mut planes32, n).unwrap()),
    ];
    Outputs {
        rows,
        planes,
        rows32,
        planes32,
        results,
    }
}

/// The validating methods give the validated ones' bits (rows and planes, f64 and f32).
fn assert_same_bits(label: &str, k: &Kernel<'_>, batch: &impl polbrdf::Batch, out: &Outputs) {
    let n = out.rows.len();
    let start = batch.len() - n;
    for r in &out.results {
        assert!(r.is_ok(), "{label}: {r:?}");
    }
    let mut want = vec![[0.0f64; 16]; n];
    k.mueller_into(batch, start, &mut want);
    let mut want32 = vec![[0.0f32; 16]; n];
    k.mueller_f32_into(batch, start, &mut want32);
    assert_eq!(bits(&out.rows), bits(&want), "{label}: f64 rows");
    assert_eq!(bits(&out.rows32), bits(&want32), "{label}: f32 rows");
    for j in 0..n {
        for e in 0..16 {
            assert_eq!(
                out.planes[e * n + j].to_bits(),
                want[j][e].to_bits(),
                "{label}"
            );
            assert_eq!(
                out.planes32[e * n + j].to_bits(),
                want32[j][e].to_bits(),
                "{label}"
            );
        }
    }
}

/// Every call failed with `want` and left only NaN in its output.
fn assert_refused(label: &str, out: &Outputs, want: &Error) {
    // (By their text: a NaN value is not equal to itself.)
    for r in &out.results {
        let e = r.as_ref().expect_err(label);
        assert_eq!(format!("{e:?}"), format!("{want:?}"), "{label}");
        assert_eq!(e.to_string(), want.to_string(), "{label}");
    }
    assert!(
        out.rows.iter().flatten().all(|x| x.is_nan()),
        "{label}: f64 rows"
    );
    assert!(out.planes.iter().all(|x| x.is_nan()), "{label}: f64 planes");
    assert!(
        out.rows32.iter().flatten().all(|x| x.is_nan()),
        "{label}: f32 rows"
    );
    assert!(
        out.planes32.iter().all(|x| x.is_nan()),
        "{label}: f32 planes"
    );
}

#[test]
fn valid_input_read_unvalidated_gives_the_validated_bits() {
    let mut rng = Rng::new(34);
    for m in materials(&mut rng) {
        let cols = columns(N, &mut rng);
        let [w_i, w_r] = vectors(&cols, &mut rng);
        let angles = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
        let dirs = DirectionBatch::new(&w_i, &w_r).unwrap();
        let raw_angles = Unvalidated::angles(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
        let raw_dirs = Unvalidated::directions(&w_i, &w_r).unwrap();
        for (level, k) in kernels(&m) {
            for start in [0, 37] {
                let label = format!("{}, start {start}", level.name());
                let out = run(&k, &raw_angles, start);
                assert_same_bits(&format!("angles, {label}"), &k, &angles, &out);
                let out = run(&k, &raw_dirs, start);
                assert_same_bits(&format!("directions, {label}"), &k, &dirs, &out);
            }
        }
    }
}

#[test]
fn an_invalid_angle_anywhere_is_the_constructors_error_and_nan() {
    let mut rng = Rng::new(35);
    let m = &materials(&mut rng)[0];
    let cols = columns(N, &mut rng);
    // Each field, each kind of fault, in the first block, in the middle and in the last
    // (partial) block, also where the block before it is whole.
    let faults = [
        (0, f64::NAN),
        (1, 1e9),
        (2, -1e-3),
        (3, f64::INFINITY),
        (0, 4.0),
    ];
    for (level, k) in kernels(m) {
        for (field, bad) in faults {
            for at in [0, 500, N - 33, N - 1] {
                let mut c = cols.clone();
                c[field][at] = bad;
                let want = GeometryBatch::new(&c[0], &c[1], &c[2], &c[3]).unwrap_err();
                assert!(
                    matches!(want, Error::InvalidAngle { index: Some(i), .. } if i == at),
                    "{want:?}"
                );
                let raw = Unvalidated::angles(&c[0], &c[1], &c[2], &c[3]).unwrap();
                let label = format!("{}: field {field} = {bad} at {at}", level.name());
                assert_refused(&label, &run(&k, &raw, 0), &want);
                // From an offset: the index in the batch's numbering.
                if at >= 7 {
                    assert_refused(&format!("{label}, start 7"), &run(&k, &raw, 7), &want);
                }
            }
        }
    }
}

#[test]
fn an_invalid_vector_is_the_constructors_error_and_nan() {
    let mut rng = Rng::new(36);
    let m = &materials(&mut rng)[1];
    let cols = columns(N, &mut rng);
    let [w_i, w_r] = vectors(&cols, &mut rng);
    for (level, k) in kernels(m) {
        for (side, bad, at) in [
            (0, [f64::NAN, 0.0, 1.0], N - 1),
            (1, [0.0, 0.0, 1e-16], N - 1),
            (1, [1e16, 0.0, 1.0], 3),
            (0, [0.0, f64::INFINITY, 1.0], N - 20),
        ] {
            let (mut wi, mut wr) = (w_i.clone(), w_r.clone());
            [&mut wi, &mut wr][side][at] = bad;
            let want = DirectionBatch::new(&wi, &wr).unwrap_err();
            let raw = Unvalidated::directions(&wi, &wr).unwrap();
            let label = format!("{}: side {side} {bad:?} at {at}", level.name());
            assert_refused(&label, &run(&k, &raw, 0), &want);
        }
        // A bad w_r early and a bad w_i late: the constructor names w_i (it checks w_i first),
        // and so do the validating methods, though the kernel meets w_r's block first.
        let (mut wi, mut wr) = (w_i.clone(), w_r.clone());
        wr[2] = [0.0; 3];
        wi[N - 1] = [f64::NAN; 3];
        let want = DirectionBatch::new(&wi, &wr).unwrap_err();
        assert!(
            matches!(want, Error::InvalidDirection { name: "w_i", index: Some(i), .. } if i == N - 1),
            "{want:?}"
        );
        let raw = Unvalidated::directions(&wi, &wr).unwrap();
        assert_refused(level.name(), &run(&k, &raw, 0), &want);
    }
}

#[test]
fn the_one_geometry_path_is_validated_too() {
    // A material beyond the block kernel's domain (every element by the one-geometry path).
    let mut s = MaterialSpec::new(1.5, 10.0);
    (s.sigma_deg, s.b, s.a) = (None, Some(30.0), Some(1e-250));
    let m = s.build().unwrap();
    let mut rng = Rng::new(37);
    let mut cols = columns(40, &mut rng);
    let raw = Unvalidated::angles(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let batch = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    let k = Kernel::new(&m);
    assert_same_bits("scalar path", &k, &batch, &run(&k, &raw, 0));
    cols[2][39] = f64::NAN;
    let want = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap_err();
    let raw = Unvalidated::angles(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap();
    assert_refused("scalar path", &run(&k, &raw, 0), &want);
}
