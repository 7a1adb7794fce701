//! Benchmarks of the scene contrast (docs/model.md §17–18): target against background over the
//! default viewing grid (1° × 2°, 16 200 directions), the map and the ranked, refined best
//! directions — what `polbrdf contrast --scene` computes. Run with
//! `cargo bench -p polbrdf --bench scene`; divan reports medians (3 samples each: one run takes
//! seconds).
//!
//! - `daylight_550nm`: the README's daylight example — olive paint (n = 1.65, σ = 15°,
//!   ρ_D = 0.03, ρ_V = 0.01) against dry soil (n = 1.55, σ = 35°, ρ_D = 0.07, ρ_V = 0.02) at
//!   550 nm, sun 40° from the zenith (1400 W·m⁻²·µm⁻¹), CIE clear sky (200 W·m⁻²·µm⁻¹
//!   horizontal, δ_max = 0.75);
//! - `sun_only_550nm`: the same without the sky;
//! - `thermal_10um`: the same surfaces at 305 K and 300 K at 10 µm under a 250 K thermal sky
//!   (azimuth-independent: one quadrature per view zenith).

use divan::black_box;
use polbrdf::analysis::scene::{Atmosphere, Observer, SkyModel, Sun, ThermalScene};
use polbrdf::analysis::{Contrast, RankOptions, ViewGrid};
use polbrdf::{MaterialSpec, Spectrum};

fn main() {
    divan::main();
}

fn surfaces() -> (MaterialSpec, MaterialSpec) {
    let mut paint = MaterialSpec::new(1.65, 15.0);
    paint.rho_d = 0.03;
    paint.rho_v = 0.01;
    let mut soil = MaterialSpec::new(1.55, 35.0);
    soil.rho_d = 0.07;
    soil.rho_v = 0.02;
    (paint, soil)
}

fn run(scenes: (ThermalScene, ThermalScene), spectrum: Spectrum) -> f64 {
    let (paint, soil) = surfaces();
    let c = Contrast::scene(
        Observer::new(&paint, &scenes.0, &spectrum).unwrap(),
        Observer::new(&soil, &scenes.1, &spectrum).unwrap(),
    );
    let map = c.map(&ViewGrid::from_degrees(1.0, 2.0).unwrap());
    let top = c.rank(&map, &RankOptions::default());
    top[0].delta_dolp()
}

fn day(sky: SkyModel) -> ThermalScene {
    ThermalScene {
        surface_temperature_k: None,
        sky,
        atmosphere: Atmosphere::default(),
        sun: Some(Sun::unpolarized(40f64.to_radians(), 0.0, 1400.0)),
    }
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn daylight_550nm() -> f64 {
    let sky = SkyModel::ClearSky {
        irradiance: 200.0,
        dop_max: 0.75,
    };
    black_box(run(
        (day(sky.clone()), day(sky)),
        Spectrum::Wavelength(0.55),
    ))
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn sun_only_550nm() -> f64 {
    black_box(run(
        (day(SkyModel::None), day(SkyModel::None)),
        Spectrum::Wavelength(0.55),
    ))
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn thermal_10um() -> f64 {
    let scene = |t: f64| ThermalScene {
        surface_temperature_k: Some(t),
        sky: SkyModel::Thermal {
            temperature_k: 250.0,
        },
        atmosphere: Atmosphere::default(),
        sun: None,
    };
    black_box(run(
        (scene(305.0), scene(300.0)),
        Spectrum::Wavelength(10.0),
    ))
}
