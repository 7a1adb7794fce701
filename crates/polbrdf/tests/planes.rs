//! Planar output (`Planes`, docs/model.md §12, "Layouts"): the 16 planes hold exactly the bits
//! of the row-major output — in both precisions, from angles and from direction vectors, with a
//! per-element and a spectral index, at block and chunk boundaries, on the serial
//! (≤ `SERIAL_MAX` elements) and the parallel driver, through the kernel at an offset, and for
//! elements the block kernel hands to the one-geometry path.

use crate::kernel::{random_geometry, random_material};
use polbrdf::engine::batch::SERIAL_MAX;
use polbrdf::engine::{Engine, IndexColumns, Kernel, Planes};
use polbrdf::geometry::{direction, Batch};
use polbrdf::sample::SplitMix64 as Rng;
use polbrdf::{DirectionBatch, Error, GeometryBatch, MaterialSpec};

fn columns(g: &[[f64; 4]]) -> [Vec<f64>; 4] {
    std::array::from_fn(|c| g.iter().map(|x| x[c]).collect())
}

/// The planar results of `engine` on `batch` equal its row-major ones bit for bit, in f64 and
/// f32.
fn assert_planes_equal_rows(label: &str, engine: &Engine<'_>, batch: &impl Batch) {
    let n = batch.len();
    let mut rows = vec![[f64::NAN; 16]; n];
    engine.mueller_into(batch, &mut rows).unwrap();
    let mut flat = vec![f64::NAN; 16 * n];
    engine
        .mueller_planes_into(batch, &mut Planes::new(&mut flat, n).unwrap())
        .unwrap();
    let mut rows32 = vec![[f32::NAN; 16]; n];
    engine.mueller_f32_into(batch, &mut rows32).unwrap();
    let mut flat32 = vec![f32::NAN; 16 * n];
    engine
        .mueller_planes_f32_into(batch, &mut Planes::new(&mut flat32, n).unwrap())
        .unwrap();
    for j in 0..n {
        for e in 0..16 {
            assert_eq!(
                flat[e * n + j].to_bits(),
                rows[j][e].to_bits(),
                "{label}: f64 element {j} entry {e}"
            );
            assert_eq!(
                flat32[e * n + j].to_bits(),
                rows32[j][e].to_bits(),
                "{label}: f32 element {j} entry {e}"
            );
        }
    }
}

fn angle_batch(cols: &[Vec<f64>; 4]) -> GeometryBatch<'_> {
    GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).unwrap()
}

#[test]
fn planes_hold_the_row_major_bits_at_every_length() {
    let m = polbrdf::preset("paint").unwrap().build().unwrap();
    let mut rng = Rng::new(5);
    let e = Engine::new(&m);
    for n in [0, 1, 15, 17, SERIAL_MAX, SERIAL_MAX + 1, 9001] {
        let geoms: Vec<[f64; 4]> = (0..n).map(|_| random_geometry(&mut rng)).collect();
        let cols = columns(&geoms);
        let batch = angle_batch(&cols);
        assert_planes_equal_rows(&format!("n = {n}"), &e, &batch);
        // The serial driver (n ≤ SERIAL_MAX) and the parallel one give the kernel's bits.
        let mut engine = vec![[f64::NAN; 16]; n];
        e.mueller_into(&batch, &mut engine).unwrap();
        let mut kernel = vec![[f64::NAN; 16]; n];
        Kernel::new(&m).mueller_into(&batch, 0, &mut kernel);
        assert!(
            engine
                .iter()
                .flatten()
                .map(|x| x.to_bits())
                .eq(kernel.iter().flatten().map(|x| x.to_bits())),
            "n = {n}: engine vs kernel"
        );
    }
}

#[test]
fn planes_hold_the_row_major_bits_on_random_materials_and_hard_cases() {
    // Random materials on random geometries (grazing, near-specular, degenerate) take every
    // path of the kernel: blocks, D's refined tail in f32, the f64 blocks of f32 elements and
    // the one-geometry path.
    let mut rng = Rng::new(21);
    let mut specs: Vec<MaterialSpec> = (0..40).map(|_| random_material(&mut rng)).collect();
    for (n, k, sigma) in [
        (1.02, 0.0, 10.0),
        (1.5, 0.0, 0.2),
        (3.0, 1e3, 5.0),
        (0.8, 0.0, 60.0),
    ] {
        let mut s = MaterialSpec::new(n, sigma);
        s.k = k;
        specs.push(s);
    }
    for spec in specs {
        let m = spec.build().unwrap();
        let geoms: Vec<[f64; 4]> = (0..300).map(|_| random_geometry(&mut rng)).collect();
        let cols = columns(&geoms);
        assert_planes_equal_rows(&format!("{spec:?}"), &Engine::new(&m), &angle_batch(&cols));
    }
}

#[test]
fn planes_from_direction_vectors_and_with_per_element_indices() {
    let m = polbrdf::preset("aluminium").unwrap().build().unwrap();
    let mut rng = Rng::new(8);
    let n = SERIAL_MAX + 500;
    let geoms: Vec<[f64; 4]> = (0..n).map(|_| random_geometry(&mut rng)).collect();
    let w_i: Vec<[f64; 3]> = geoms.iter().map(|g| direction(g[0], g[1])).collect();
    let w_r: Vec<[f64; 3]> = geoms.iter().map(|g| direction(g[2], g[3])).collect();
    let dirs = DirectionBatch::new(&w_i, &w_r).unwrap();
    assert_planes_equal_rows("directions", &Engine::new(&m), &dirs);
    let nn: Vec<f64> = (0..n).map(|i| [1.5, 1.05, 0.7, 0.2][i % 4]).collect();
    let kk: Vec<f64> = (0..n).map(|i| [0.0, 0.0, 0.1, 3.0][i % 4]).collect();
    let cols = columns(&geoms);
    let e = Engine::new(&m).with_index(IndexColumns::new(&nn, &kk).unwrap());
    assert_planes_equal_rows("per-element index", &e, &angle_batch(&cols));
    // A tabulated spectral index, one wavelength per element.
    use polbrdf::optics::dispersion::{Dispersion, SpectralIndex};
    let wl: Vec<f64> = (0..n).map(|i| 0.4 + 0.001 * (i % 500) as f64).collect();
    let table = |v: &[f64]| Dispersion::Table {
        wavelengths: vec![0.4, 0.6, 0.9],
        values: v.to_vec(),
    };
    let mut s = MaterialSpec::new(1.0, 12.0);
    s.spectral = Some(polbrdf::model::SpectralSource {
        source: "test".into(),
        index: std::sync::Arc::new(SpectralIndex {
            name: "test/dispersive".into(),
            n: table(&[0.5, 1.4, 2.6]),
            k: Some(table(&[4.0, 2.2, 1.0])),
            references: String::new(),
            comments: String::new(),
        }),
    });
    let m = s.build_at(0.6).unwrap();
    let e = Engine::new(&m).with_wavelengths(&wl).unwrap();
    assert_planes_equal_rows("spectral index", &e, &angle_batch(&cols));
}

#[test]
fn kernel_planes_at_an_offset_are_the_rows_of_that_range() {
    let m = polbrdf::preset("gold").unwrap().build().unwrap();
    let mut rng = Rng::new(4);
    let geoms: Vec<[f64; 4]> = (0..100).map(|_| random_geometry(&mut rng)).collect();
    let cols = columns(&geoms);
    let batch = angle_batch(&cols);
    let k = Kernel::new(&m);
    let mut all = vec![[0.0; 16]; 100];
    k.mueller_into(&batch, 0, &mut all);
    let mut flat = vec![0.0; 16 * 37];
    k.mueller_planes_into(&batch, 41, &mut Planes::new(&mut flat, 37).unwrap());
    for j in 0..37 {
        for e in 0..16 {
            assert_eq!(flat[e * 37 + j].to_bits(), all[41 + j][e].to_bits());
        }
    }
    // Split planes fill their halves.
    let mut flat2 = vec![0.0; 16 * 37];
    let (mut a, mut b) = Planes::new(&mut flat2, 37).unwrap().split_at(20);
    k.mueller_planes_into(&batch, 41, &mut a);
    k.mueller_planes_into(&batch, 61, &mut b);
    assert_eq!(flat, flat2);
}

#[test]
fn planes_of_the_wrong_length_and_beyond_f32_are_refused() {
    let m = polbrdf::preset("paint").unwrap().build().unwrap();
    let t = [0.3, 0.5];
    let p = [0.0, 1.0];
    let batch = GeometryBatch::new(&t, &p, &t, &p).unwrap();
    let mut flat = vec![0.0; 16 * 3];
    let e = Engine::new(&m)
        .mueller_planes_into(&batch, &mut Planes::new(&mut flat, 3).unwrap())
        .unwrap_err();
    assert!(
        matches!(
            e,
            Error::LengthMismatch {
                name: "out",
                got: 3,
                expected: 2
            }
        ),
        "{e}"
    );
    let mut s = MaterialSpec::new(1.5, 5.0);
    (s.rho_d, s.rho_v) = (1e100, 1e100);
    let m = s.build().unwrap();
    let mut flat32 = vec![0.0f32; 32];
    let e = Engine::new(&m)
        .mueller_planes_f32_into(&batch, &mut Planes::new(&mut flat32, 2).unwrap())
        .unwrap_err();
    assert!(
        matches!(&e, Error::InconsistentParameters(msg) if msg.contains("float32")),
        "{e}"
    );
}
