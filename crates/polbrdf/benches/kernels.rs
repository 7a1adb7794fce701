//! Benchmarks of the model's kernels, per element, on 4096 random valid geometries of the
//! `paint` preset (θ uniform in [0°, 89.9°], φ in [0°, 360°)), one thread. Run with
//! `cargo bench -p polbrdf --bench kernels`; divan reports medians and items per second.
//!
//! - `reference_*`: the straightforward scalar path (`Geometry::angle_variables`, the Fresnel
//!   amplitudes with the Jones and Mueller matrices, `Material::evaluate`);
//! - `kernel_*`: the vectorized batch kernel (`polbrdf::engine`), at each SIMD level this CPU
//!   supports (an unsupported level measures nothing): in f64 and f32, from angles and from
//!   direction vectors, for `paint` and for the peer benchmark's conductor
//!   (`scripts/bench-peers`: n = 1.2, k = 7, σ = atan 0.2, shadowing off, whose narrow lobe
//!   sends about a fifth of the f32 elements through D's f64 refinement). On an AVX-512 CPU
//!   the `avx2+fma` rows show what an AVX2-only CPU of the same core would do;
//! - `kernel_prepare`, `kernel_mueller_prepared`: the f64 kernel in two parts, the geometry
//!   stages (every angle) and the rest from a prepared batch;
//! - `single_*`: the latency of one evaluation.

use divan::counter::ItemsCount;
use divan::{black_box, Bencher};
use polbrdf::engine::{Kernel, SimdLevel};
use polbrdf::geometry::direction;
use polbrdf::{
    AngleVariables, Batch, DirectionBatch, Geometry, GeometryBatch, Jones, Material, MaterialSpec,
    Mueller,
};

fn main() {
    divan::main();
}

const N: usize = 4096;
const LEVELS: [&str; 3] = ["portable", "avx2+fma", "avx512"];

struct Data {
    material: Material,
    /// The peer benchmark's Beckmann-like conductor (`scripts/bench_peers.py`).
    conductor: Material,
    cols: [Vec<f64>; 4],
    /// The same geometries as unit vectors (`w_i`, `w_r`).
    dirs: [Vec<[f64; 3]>; 2],
    geometries: Vec<Geometry>,
}

impl Data {
    fn material(&self, name: &str) -> &Material {
        match name {
            "conductor" => &self.conductor,
            _ => &self.material,
        }
    }
}

/// The benchmarks' data, made once.
fn data() -> &'static Data {
    static DATA: std::sync::LazyLock<Data> = std::sync::LazyLock::new(make_data);
    &DATA
}

fn make_data() -> Data {
    let mut state = 2024u64;
    let mut next = move || {
        // SplitMix64, uniform in [0, 1)
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    };
    let theta = 89.9f64.to_radians();
    let phi = 360f64.to_radians();
    let geometries: Vec<Geometry> = (0..N)
        .map(|_| Geometry::new(next() * theta, next() * phi, next() * theta, next() * phi).unwrap())
        .collect();
    let cols = [
        geometries.iter().map(|g| g.theta_i()).collect(),
        geometries.iter().map(|g| g.phi_i()).collect(),
        geometries.iter().map(|g| g.theta_r()).collect(),
        geometries.iter().map(|g| g.phi_r()).collect(),
    ];
    let dirs = [
        geometries
            .iter()
            .map(|g| direction(g.theta_i(), g.phi_i()))
            .collect(),
        geometries
            .iter()
            .map(|g| direction(g.theta_r(), g.phi_r()))
            .collect(),
    ];
    let conductor = MaterialSpec {
        k: 7.0,
        shadowing: false,
        ..MaterialSpec::new(1.2, 0.2f64.atan().to_degrees())
    };
    Data {
        material: polbrdf::preset("paint").unwrap().build().unwrap(),
        conductor: conductor.build().unwrap(),
        cols,
        dirs,
        geometries,
    }
}

fn level(name: &str) -> Option<SimdLevel> {
    let level = match name {
        "avx512" => SimdLevel::Avx512,
        "avx2+fma" => SimdLevel::Avx2,
        _ => SimdLevel::Portable,
    };
    level.is_supported().then_some(level)
}

/// Angle variables (θN, β, ΦN, η_i, η_r) in closed form.
#[divan::bench]
fn reference_geometry(bencher: Bencher<'_, '_>) {
    let d = data();
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        for g in &d.geometries {
            black_box(black_box(g).angle_variables());
        }
    });
}

/// Fresnel amplitudes, the Jones matrix of eq. 11 and its Mueller matrix, alone.
#[divan::bench]
fn reference_fresnel_mueller(bencher: Bencher<'_, '_>) {
    let d = data();
    let index = d.material.index();
    let vars: Vec<AngleVariables> = d
        .geometries
        .iter()
        .map(|g| g.angle_variables().unwrap())
        .collect();
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        for v in &vars {
            let v = black_box(v);
            let fr = index.amplitudes(v.beta);
            black_box(Mueller::from_jones(&Jones::microfacet(
                &fr, v.eta_i, v.eta_r,
            )));
        }
    });
}

/// The full pBRDF through the reference path, `Material::evaluate`.
#[divan::bench]
fn reference_pbrdf(bencher: Bencher<'_, '_>) {
    let d = data();
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        for g in &d.geometries {
            black_box(d.material.evaluate(black_box(g)));
        }
    });
}

/// Every level for each material of [`Data::material`].
const LEVEL_MATERIALS: [(&str, &str); 6] = [
    ("portable", "paint"),
    ("avx2+fma", "paint"),
    ("avx512", "paint"),
    ("portable", "conductor"),
    ("avx2+fma", "conductor"),
    ("avx512", "conductor"),
];

/// One thread of full-Mueller evaluations of `batch` into a reused output of `T` (`run`: a
/// kernel method), for the level and material of `args`.
fn full_mueller<B: Batch, T: Copy>(
    bencher: Bencher<'_, '_>,
    (name, material): (&str, &str),
    batch: impl Fn(&'static Data) -> B,
    zero: T,
    run: impl Fn(&Kernel<'_>, &B, &mut [[T; 16]]),
) {
    let Some(level) = level(name) else { return };
    let d = data();
    let batch = batch(d);
    let k = Kernel::with_level(d.material(material), level).unwrap();
    let mut out = vec![[zero; 16]; N];
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        run(&k, black_box(&batch), &mut out);
        black_box(&mut out);
    });
}

fn angles(d: &'static Data) -> GeometryBatch<'static> {
    let [ti, pi, tr, pr] = &d.cols;
    GeometryBatch::new(ti, pi, tr, pr).unwrap()
}

fn vectors(d: &'static Data) -> DirectionBatch<'static> {
    DirectionBatch::new(&d.dirs[0], &d.dirs[1]).unwrap()
}

/// The full pBRDF (16 entries) through the kernel, one thread.
#[divan::bench(args = LEVEL_MATERIALS)]
fn kernel_mueller(bencher: Bencher<'_, '_>, args: (&str, &str)) {
    full_mueller(bencher, args, angles, 0.0, |k, b, o| {
        k.mueller_into(b, 0, o)
    });
}

/// The full pBRDF in single precision (the f32 kernel, `Kernel::mueller_f32_into`), one
/// thread.
#[divan::bench(args = LEVEL_MATERIALS)]
fn kernel_mueller_f32(bencher: Bencher<'_, '_>, args: (&str, &str)) {
    full_mueller(bencher, args, angles, 0.0f32, |k, b, o| {
        k.mueller_f32_into(b, 0, o);
    });
}

/// The full pBRDF from direction vectors (`DirectionBatch`), f64, one thread.
#[divan::bench(args = LEVEL_MATERIALS)]
fn kernel_mueller_directions(bencher: Bencher<'_, '_>, args: (&str, &str)) {
    full_mueller(bencher, args, vectors, 0.0, |k, b, o| {
        k.mueller_into(b, 0, o)
    });
}

/// The full pBRDF from direction vectors in single precision, one thread.
#[divan::bench(args = LEVEL_MATERIALS)]
fn kernel_mueller_directions_f32(bencher: Bencher<'_, '_>, args: (&str, &str)) {
    full_mueller(bencher, args, vectors, 0.0f32, |k, b, o| {
        k.mueller_f32_into(b, 0, o);
    });
}

/// The geometry stages alone (`Kernel::prepare`: the four sine/cosine pairs, θN, β, ΦN, the
/// cosines and the Priest–Meier pairs — every angle, as a prepared batch keeps them), one
/// thread: with [`kernel_mueller_prepared`], the f64 kernel split in two (docs/model.md §12,
/// "What an element costs").
#[divan::bench(args = LEVEL_MATERIALS)]
fn kernel_prepare(bencher: Bencher<'_, '_>, (name, material): (&str, &str)) {
    let Some(level) = level(name) else { return };
    let d = data();
    let batch = angles(d);
    let k = Kernel::with_level(d.material(material), level).unwrap();
    bencher
        .counter(ItemsCount::new(N))
        .bench_local(|| black_box(k.prepare(black_box(&batch))));
}

/// The full pBRDF from a prepared batch (the material stages, the Fresnel matrix, the
/// rotations, the transpose and the stores), one thread.
#[divan::bench(args = LEVEL_MATERIALS)]
fn kernel_mueller_prepared(bencher: Bencher<'_, '_>, (name, material): (&str, &str)) {
    let Some(level) = level(name) else { return };
    let d = data();
    let k = Kernel::with_level(d.material(material), level).unwrap();
    let prepared = k.prepare(&angles(d));
    let mut out = vec![[0.0; 16]; N];
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        k.mueller_prepared_into(black_box(&prepared), 0, &mut out);
        black_box(&mut out);
    });
}

/// BRDF and DoLP only through the kernel, one thread.
#[divan::bench(args = LEVELS)]
fn kernel_brdf_dolp(bencher: Bencher<'_, '_>, name: &str) {
    let Some(level) = level(name) else { return };
    let d = data();
    let [ti, pi, tr, pr] = &d.cols;
    let batch = GeometryBatch::new(ti, pi, tr, pr).unwrap();
    let k = Kernel::with_level(&d.material, level).unwrap();
    let (mut b, mut p) = (vec![0.0; N], vec![0.0; N]);
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        k.brdf_dolp_into(black_box(&batch), 0, &mut b, &mut p);
        black_box((&mut b, &mut p));
    });
}

/// BRDF, DoLP and AoLP through the kernel, one thread.
#[divan::bench(args = LEVELS)]
fn kernel_brdf_dolp_aolp(bencher: Bencher<'_, '_>, name: &str) {
    let Some(level) = level(name) else { return };
    let d = data();
    let [ti, pi, tr, pr] = &d.cols;
    let batch = GeometryBatch::new(ti, pi, tr, pr).unwrap();
    let k = Kernel::with_level(&d.material, level).unwrap();
    let (mut b, mut p, mut a) = (vec![0.0; N], vec![0.0; N], vec![0.0; N]);
    bencher.counter(ItemsCount::new(N)).bench_local(|| {
        k.brdf_dolp_aolp_into(black_box(&batch), 0, &mut b, &mut p, &mut a);
        black_box((&mut b, &mut p, &mut a));
    });
}

/// Latency of one evaluation through the kernel's single-geometry entry point.
#[divan::bench]
fn single_kernel_pbrdf(bencher: Bencher<'_, '_>) {
    let d = data();
    let k = Kernel::new(&d.material);
    let mut i = 0;
    bencher.bench_local(|| {
        i = (i + 1) % N;
        black_box(k.pbrdf(black_box(&d.geometries[i])))
    });
}

/// Latency of one evaluation through the reference path, `Material::evaluate`.
#[divan::bench]
fn single_reference_evaluate(bencher: Bencher<'_, '_>) {
    let d = data();
    let mut i = 0;
    bencher.bench_local(|| {
        i = (i + 1) % N;
        black_box(d.material.evaluate(black_box(&d.geometries[i])))
    });
}
