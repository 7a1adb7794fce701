//! Benchmarks of polarized thermal emission (`polbrdf::analysis::emission`) at the default
//! accuracy (`FacetRule::for_material`, both routes of Kirchhoff's law): the emissivity toward
//! one view direction, and a table of 90 view angles (θ = 0°…89°) through the batch function
//! `emissivities`. Run with `cargo bench -p polbrdf --bench emission`; divan reports medians.
//!
//! Materials: the `paint` preset (σ = 15°, n = 1.65), the `aluminium` preset (σ = 10°,
//! N = 1.34 + 7.3i) and a rough paint (`paint` with σ = 30°).
//!
//! - `direction_*`: one `emissivity` call at θ = 0°, 45° and 80° (the constant: θ in degrees),
//!   on every thread of rayon's global pool (a single direction splits its quadrature nodes into
//!   parallel chunks) and inside a local pool of one thread; `direction_nodes_only`, the
//!   construction of its quadrature nodes alone (serial);
//! - `table_90_*`: `emissivities` over θ = 0°…89° (the directions in parallel, each one's nodes
//!   in parallel chunks), inside a local pool of one thread and on every thread of the global
//!   pool (every logical CPU).

use divan::{black_box, Bencher};
use polbrdf::analysis::emission::{emissivities, emissivity};
use polbrdf::analysis::facets::FacetRule;
use polbrdf::Material;

fn main() {
    divan::main();
}

const MATERIALS: [&str; 3] = ["paint", "aluminium", "paint-sigma30"];

/// A preset, or `paint-sigma30`: the `paint` preset with σ = 30°.
fn material(name: &str) -> Material {
    let spec = match name {
        "paint-sigma30" => polbrdf::MaterialSpec {
            name: Some(name.into()),
            sigma_deg: Some(30.0),
            ..polbrdf::preset("paint").unwrap()
        },
        preset => polbrdf::preset(preset).unwrap(),
    };
    spec.build().unwrap()
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
}

/// One `emissivity` call toward θ = `THETA_DEG`, every thread of rayon's global pool.
#[divan::bench(consts = [0, 45, 80], args = MATERIALS)]
fn direction_all_threads<const THETA_DEG: u32>(bencher: Bencher<'_, '_>, name: &str) {
    let m = material(name);
    let t = f64::from(THETA_DEG).to_radians();
    bencher.bench_local(|| black_box(emissivity(black_box(&m), black_box(t)).unwrap()));
}

/// One `emissivity` call toward θ = `THETA_DEG` inside a rayon pool of one thread.
#[divan::bench(consts = [0, 45, 80], args = MATERIALS)]
fn direction_one_thread<const THETA_DEG: u32>(bencher: Bencher<'_, '_>, name: &str) {
    let m = material(name);
    let t = f64::from(THETA_DEG).to_radians();
    let pool = pool(1);
    bencher.bench_local(|| {
        pool.install(|| black_box(emissivity(black_box(&m), black_box(t)).unwrap()))
    });
}

/// The quadrature nodes of one direction alone (`FacetRule::nodes`, both halves of every ring,
/// as `emissivity` builds them): the serial part of a call.
#[divan::bench(consts = [0, 45, 80], args = MATERIALS)]
fn direction_nodes_only<const THETA_DEG: u32>(bencher: Bencher<'_, '_>, name: &str) {
    let rule = FacetRule::for_material(&material(name)).full();
    let t = f64::from(THETA_DEG).to_radians();
    bencher.bench_local(|| black_box(black_box(rule).nodes(black_box(t))));
}

fn thetas_90() -> Vec<f64> {
    (0..90).map(|d| f64::from(d).to_radians()).collect()
}

/// `emissivities` over the 90 view angles θ = 0°…89° inside a rayon pool of one thread.
#[divan::bench(args = MATERIALS)]
fn table_90_one_thread(bencher: Bencher<'_, '_>, name: &str) {
    let m = material(name);
    let thetas = thetas_90();
    let pool = pool(1);
    bencher.bench_local(|| {
        pool.install(|| black_box(emissivities(black_box(&m), black_box(&thetas)).unwrap()))
    });
}

/// `emissivities` over the 90 view angles θ = 0°…89°, every thread of rayon's global pool.
#[divan::bench(args = MATERIALS)]
fn table_90_all_threads(bencher: Bencher<'_, '_>, name: &str) {
    let m = material(name);
    let thetas = thetas_90();
    bencher.bench_local(|| black_box(emissivities(black_box(&m), black_box(&thetas)).unwrap()));
}
