//! The benchmark's report as one JSON object (`--json`, the command's data result on standard
//! output).

use super::emission::EMISSION_MATERIALS;
use super::roofline::FLOOR_COUNTS;
use super::Bench;
use serde_json::{json, Value};

/// The whole report: the run's setting, then every measurement.
pub(super) fn document(b: &Bench) -> Value {
    let bandwidth = b.bandwidth();
    let floor_ns = b.floor_ns();
    let fma_lanes = b.fma.map(|f| f.lanes());
    json!({
        "material": "paint",
        "count": b.count,
        "repeats": b.repeats,
        "statistic": "median",
        "cpu": {"model": b.cpu, "logical_cpus": b.logical_cpus, "simd": b.simd},
        "results": results(b),
        "write_bandwidth": {
            "threads": b.threads,
            "bytes_per_s": bandwidth,
            "plain_bytes_per_s": b.plain_bw,
            "non_temporal_bytes_per_s": b.nt_bw,
            "full_mueller_roofline_evals_per_s": bandwidth / 128.0,
            "full_mueller_f32_roofline_evals_per_s": bandwidth / 64.0,
        },
        "f32_non_temporal_stores": {
            "paired_ratio_one_thread": b.store_ratio,
            "used": polbrdf::engine::simd::f32_streams_pay(),
        },
        "fma_throughput_one_thread": b.fma.map(|f| json!({
            "fma_per_s_128bit": f.r128,
            "fma_per_s_256bit": f.r256,
            "fma_per_s_512bit": f.r512,
            "widest_full_rate_bits": f.widest(),
            "peak_f32_flops": 2.0 * fma_lanes.unwrap_or(0.0),
            "peak_f64_flops": fma_lanes.unwrap_or(0.0),
            "full_width_256bit": f.full_width_256(),
        })),
        "elementary_ns_per_element_one_thread": b
            .elementary
            .iter()
            .map(|(op, ns)| (op.name().to_string(), json!(ns)))
            .collect::<serde_json::Map<_, _>>(),
        "elementary_floor": {
            "counts": FLOOR_COUNTS
                .iter()
                .map(|(op, k)| (op.name().to_string(), json!(k)))
                .collect::<serde_json::Map<_, _>>(),
            "ns_per_element_one_thread": floor_ns,
            "max_full_mueller_evals_per_s_one_thread": 1e9 / floor_ns,
        },
        "per_element_index": per_element_index(b),
        "single_eval_ns": {
            "kernel": b.latency_kernel,
            "reference": b.latency_reference,
        },
        "emission": emission(b),
        "checksum": {
            "brdf_sum": b.runs[0].brdf_sum,
            "dolp_sum": b.runs[0].dolp_sum,
            "mueller_sum": b.runs[0].mueller_sum,
            "same_for_all_thread_counts": b.consistent(),
        },
    })
}

/// The throughput of each thread count.
fn results(b: &Bench) -> Vec<Value> {
    b.runs
        .iter()
        .map(|r| {
            json!({
                "threads": r.threads,
                "mueller_evals_per_s": b.per_s(r.mueller_s),
                "mueller_f32_evals_per_s": b.per_s(r.mueller_f32_s),
                "mueller_directions_evals_per_s": b.per_s(r.directions_s),
                "mueller_directions_f32_evals_per_s": b.per_s(r.directions_f32_s),
                "brdf_dolp_evals_per_s": b.per_s(r.brdf_dolp_s),
                "mueller_seconds": r.mueller_s,
                "brdf_dolp_seconds": r.brdf_dolp_s,
            })
        })
        .collect()
}

/// The per-element index and the spectral sweep against the constant index.
fn per_element_index(b: &Bench) -> Value {
    let index = &b.index;
    json!({
        "threads": b.threads,
        "constant_index_brdf_dolp_evals_per_s": b.per_s(index.constant_s),
        "same_index_per_element_evals_per_s": b.per_s(index.same_index_s),
        "spectral_sweep_runs_evals_per_s": b.per_s(index.runs_s),
        "spectral_sweep_cycling_evals_per_s": b.per_s(index.cycling_s),
        "same_index_overhead": index.same_index_s / index.constant_s - 1.0,
        "water_constant_index_evals_per_s": b.per_s(index.water_s),
        "spectral_sweep_runs_overhead": index.runs_ratio - 1.0,
        "spectral_sweep_cycling_overhead": index.cycling_ratio - 1.0,
        "spectral_sweep_matches_one_wavelength": index.spectral_matches,
        "same_index_results_identical": index.same_index_identical,
    })
}

/// The emission timings: single directions and the 90-angle table.
fn emission(b: &Bench) -> Value {
    let emission = &b.emission;
    let per_direction: Vec<_> = emission
        .directions
        .iter()
        .map(|d| {
            json!({
                "material": d.material,
                "sigma_deg": d.sigma_deg,
                "theta_deg": d.theta_deg,
                "nodes": d.nodes,
                "one_thread_ms": 1e3 * d.one_thread_s,
                "all_threads_ms": 1e3 * d.parallel_s,
                "eps0": d.eps.eps.0[0],
            })
        })
        .collect();
    json!({
        "accuracy": "default (FacetRule::for_material), both routes",
        "threads": b.threads,
        "per_direction": per_direction,
        "table_90": {
            "material": EMISSION_MATERIALS[0],
            "theta_deg": "0..89",
            "one_thread_ms": 1e3 * emission.table_one_thread_s,
            "all_threads_ms": 1e3 * emission.table_parallel_s,
            "eps0_sum": emission.table_eps0_sum,
        },
        "same_for_all_thread_counts": emission.consistent,
    })
}
