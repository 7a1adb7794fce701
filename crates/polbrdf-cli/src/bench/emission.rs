//! The polarized thermal emission measurements: one `emissivity` call per material and view
//! zenith, and the 90-angle table through `emissivities`, on one thread and on the pool.

use super::timing::{median, median_seconds};
use crate::error::CliError;
use polbrdf::analysis::emission::{emissivities, emissivity, Emissivity};
use polbrdf::analysis::facets::FacetRule;
use std::hint::black_box;
use std::time::Instant;

/// The materials of the emission section: two presets and a rough paint.
pub(super) const EMISSION_MATERIALS: [&str; 3] = ["paint", "aluminium", "paint-sigma30"];
/// View zeniths (degrees) of the single-direction timings.
const EMISSION_THETAS_DEG: [f64; 3] = [0.0, 45.0, 80.0];
/// Calls per timed repeat of a single direction (the time per call is their mean).
const EMISSION_CALLS: usize = 3;

/// A preset, or `paint-sigma30`: the `paint` preset with σ = 30°.
fn emission_material(name: &str) -> Result<polbrdf::Material, CliError> {
    let spec = match name {
        "paint-sigma30" => polbrdf::MaterialSpec {
            name: Some(name.into()),
            sigma_deg: Some(30.0),
            ..polbrdf::preset("paint").map_err(CliError::Model)?
        },
        preset => polbrdf::preset(preset).map_err(CliError::Model)?,
    };
    spec.build().map_err(CliError::Model)
}

/// One `emissivity` call (default rule, both routes) toward one view direction: seconds per
/// call (medians over the repeats of the mean of [`EMISSION_CALLS`] calls), on one thread and on
/// the parallel pool.
pub(super) struct EmissionDirection {
    pub(super) material: &'static str,
    pub(super) sigma_deg: f64,
    pub(super) theta_deg: f64,
    /// Quadrature nodes of the rule per route (the call evaluates F at twice as many).
    pub(super) nodes: usize,
    pub(super) one_thread_s: f64,
    pub(super) parallel_s: f64,
    pub(super) eps: Emissivity,
}

/// Polarized thermal emission at the default accuracy: single directions, and the 90-angle
/// table θ = 0°…89° of `paint` through the batch function `emissivities` (directions in
/// parallel, each direction's nodes in parallel chunks).
pub(super) struct EmissionRun {
    pub(super) directions: Vec<EmissionDirection>,
    pub(super) table_one_thread_s: f64,
    pub(super) table_parallel_s: f64,
    /// Σ ε0 over the table.
    pub(super) table_eps0_sum: f64,
    /// The table is bit-identical on one thread and on the parallel pool, and a single call
    /// gives the table's entry at the same angle.
    pub(super) consistent: bool,
}

/// A thread pool of `threads` threads.
fn pool(threads: usize) -> Result<rayon::ThreadPool, CliError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| CliError::Invalid(format!("--threads = {threads}: {e}")))
}

/// The emission measurements ([`EmissionRun`]), medians of `repeats`, on one thread and on
/// `threads`.
pub(super) fn run_emission(repeats: usize, threads: usize) -> Result<EmissionRun, CliError> {
    let one = pool(1)?;
    let parallel = pool(threads)?;
    let directions = single_directions(repeats, threads, &one, &parallel)?;
    let m = emission_material(EMISSION_MATERIALS[0])?;
    let thetas: Vec<f64> = (0..90).map(|d| f64::from(d).to_radians()).collect();
    // The two pools interleaved, so that a change of machine load affects both alike; no
    // separate warm-up (the single directions above ran the same code).
    let pools: &[&rayon::ThreadPool] = if threads == 1 {
        &[&one]
    } else {
        &[&one, &parallel]
    };
    let mut tables = vec![Vec::new(); pools.len()];
    let mut times = vec![Vec::new(); pools.len()];
    for _ in 0..repeats {
        for (k, pool) in pools.iter().enumerate() {
            let t = Instant::now();
            tables[k] = pool
                .install(|| emissivities(black_box(&m), black_box(&thetas)))
                .map_err(CliError::Model)?;
            black_box(&tables[k]);
            times[k].push(t.elapsed().as_secs_f64());
        }
    }
    let times: Vec<f64> = times.into_iter().map(median).collect();
    let (table_one_thread_s, table_parallel_s) = (times[0], times[times.len() - 1]);
    let on_one = &tables[0];
    let on_parallel = &tables[tables.len() - 1];
    let consistent = on_one == on_parallel
        && directions
            .iter()
            .filter(|d| d.material == EMISSION_MATERIALS[0])
            .all(|d| on_one[d.theta_deg as usize] == d.eps);
    Ok(EmissionRun {
        table_one_thread_s,
        table_parallel_s,
        table_eps0_sum: on_one.iter().map(|e| e.eps.0[0]).sum(),
        consistent,
        directions,
    })
}

/// One [`EmissionDirection`] per material of [`EMISSION_MATERIALS`] and zenith of
/// [`EMISSION_THETAS_DEG`], timed on `one` (one thread) and on `parallel` (`threads`; the
/// one-thread time again when that is 1).
fn single_directions(
    repeats: usize,
    threads: usize,
    one: &rayon::ThreadPool,
    parallel: &rayon::ThreadPool,
) -> Result<Vec<EmissionDirection>, CliError> {
    let mut directions = Vec::new();
    for name in EMISSION_MATERIALS {
        let m = emission_material(name)?;
        let rule = FacetRule::for_material(&m).full();
        for theta_deg in EMISSION_THETAS_DEG {
            let t = theta_deg.to_radians();
            let eps = emissivity(&m, t).map_err(CliError::Model)?;
            let time = |pool: &rayon::ThreadPool| {
                pool.install(|| {
                    median_seconds(repeats, || {
                        for _ in 0..EMISSION_CALLS {
                            black_box(
                                emissivity(black_box(&m), black_box(t)).expect("valid angle"),
                            );
                        }
                    })
                }) / EMISSION_CALLS as f64
            };
            let one_thread_s = time(one);
            let parallel_s = if threads == 1 {
                one_thread_s
            } else {
                time(parallel)
            };
            directions.push(EmissionDirection {
                material: name,
                sigma_deg: m.distribution().sigma().to_degrees(),
                theta_deg,
                nodes: rule.nodes(t).len(),
                one_thread_s,
                parallel_s,
                eps,
            });
        }
    }
    Ok(directions)
}
