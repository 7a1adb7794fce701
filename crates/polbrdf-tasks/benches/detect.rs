//! The speed of a full-hemisphere detection map (issue 37: "a 1°×2° grid, sun + clear sky, one
//! band, range search, in under 10 s on 2 cores"), through the task layer exactly as
//! `polbrdf detect` runs it (`polbrdf_tasks::detect::detect`: the scene and sensor files read,
//! both surfaces observed over the sensor's band at 16 200 views, and each view's detection
//! range searched to 50 km; the worked example of docs/detection.md). Run with
//! `cargo bench -p polbrdf-tasks --bench detect`; divan reports medians (3 samples: one run
//! takes seconds), on every thread of rayon's global pool. The first line printed names the
//! SIMD level the engine uses.
//!
//! - `daylight_sony`: `examples/detect-daylight-scene.toml` (olive paint on dry soil, sun 40°
//!   from the zenith + CIE clear sky, 23 km visibility) with
//!   `examples/sensors/sony-imx250mzr-dofp.toml` (450–650 nm);
//! - `lwir_microbolometer`: `examples/detect-lwir-scene.toml` (a 305 K painted panel on 300 K
//!   clay soil, 250 K sky, the 8–12 µm band of a spectral index) with
//!   `examples/sensors/lwir-microbolometer-dofp.toml`.

use divan::black_box;
use polbrdf_tasks::detect::{detect, DetectRequest, SceneSource, SensorSource, Views};
use std::path::PathBuf;

fn main() {
    println!(
        "SIMD level: {}; rayon threads: {}",
        polbrdf::engine::simd_level().name(),
        rayon_threads()
    );
    divan::main();
}

/// The threads the task's parallel loops run on (rayon's global pool: every logical CPU unless
/// `RAYON_NUM_THREADS` says otherwise).
fn rayon_threads() -> usize {
    std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|v| v.parse().ok())
        .filter(|n| *n > 0)
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from))
}

fn example(path: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(path)
}

/// The full-hemisphere study of `scene` with `sensor`: its longest detection range.
fn study(scene: &str, sensor: &str) -> f64 {
    let request = DetectRequest {
        scene: SceneSource::File(example(scene)),
        sensor: SensorSource::File(example(sensor)),
        views: Views::Grid((1.0, 2.0)),
        ranges_m: vec![1000.0],
        range_limit_m: 50_000.0,
        ..DetectRequest::default()
    };
    let s = detect(&request).expect("the shipped examples run");
    assert_eq!(s.views.len(), 16_200);
    s.max_ranges().into_iter().fold(0.0, f64::max)
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn daylight_sony() -> f64 {
    black_box(study(
        "detect-daylight-scene.toml",
        "sensors/sony-imx250mzr-dofp.toml",
    ))
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn lwir_microbolometer() -> f64 {
    black_box(study(
        "detect-lwir-scene.toml",
        "sensors/lwir-microbolometer-dofp.toml",
    ))
}
