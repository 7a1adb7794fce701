//! `polbrdf bench`: throughput of the batch API on random valid geometries of the `paint`
//! preset — full Mueller and BRDF+DoLP evaluations per second on one thread and on all threads
//! (medians of several repeats), the latency of a single evaluation (through the kernel's
//! single-geometry entry point, and through the reference path `Material::evaluate`), the
//! per-element index and a spectral sweep against the constant index, polarized thermal emission
//! at the default accuracy (one view direction, and a table of 90 view angles), a checksum of the
//! results and the CPU it ran on.
//!
//! This file holds the command: its options, the measurements in order, and where the report
//! goes — the JSON object (`--json`) is the command's data result, on standard output; the
//! table is for a person, on standard error (the output layer's notes).

mod cpu;
mod emission;
mod json;
mod measure;
mod roofline;
mod table;
mod timing;

use crate::error::CliError;
use cpu::FmaRates;
use emission::EmissionRun;
use measure::{Geometries, IndexRun, Run};
use polbrdf::engine::{Elementary, Kernel};

/// `polbrdf bench`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Number of random geometries (θ uniform in [0°, 89.9°], φ uniform in [0°, 360°)).
    #[arg(long, value_name = "N", default_value_t = 1_000_000,
          value_parser = crate::values::count(1, crate::limits::BENCH_COUNT))]
    pub count: usize,
    /// Threads of the parallel runs (default: every logical CPU).
    #[arg(long, value_name = "T", value_parser = crate::values::count(1, crate::limits::THREADS))]
    pub threads: Option<usize>,
    /// Timed repeats of each measurement; the medians are reported (at least 5).
    #[arg(long, value_name = "R", default_value_t = 7,
          value_parser = crate::values::count(5, crate::limits::BENCH_REPEATS))]
    pub repeats: usize,
    /// Print the results as one JSON object on standard output instead of a table on standard
    /// error.
    #[arg(long)]
    pub json: bool,
}

/// Everything one run measured: what the report renders.
struct Bench {
    /// Geometries per batch (`--count`).
    count: usize,
    repeats: usize,
    /// Threads of the parallel runs.
    threads: usize,
    logical_cpus: usize,
    cpu: String,
    /// The kernel's SIMD level.
    simd: &'static str,
    /// One thread, then `threads` (when more than one).
    runs: Vec<Run>,
    /// Memory write bandwidth (bytes/s) with plain and with non-temporal stores.
    plain_bw: f64,
    nt_bw: Option<f64>,
    /// Nanoseconds per element of each elementary operation.
    elementary: Vec<(Elementary, f64)>,
    fma: Option<FmaRates>,
    /// float32 output, plain over non-temporal store time.
    store_ratio: f64,
    index: IndexRun,
    emission: EmissionRun,
    /// Nanoseconds per single evaluation: kernel, reference path.
    latency_kernel: f64,
    latency_reference: f64,
}

impl Bench {
    /// Evaluations per second of a batch that took `s` seconds.
    fn per_s(&self, s: f64) -> f64 {
        self.count as f64 / s
    }

    /// The roofline's bandwidth: the better of plain and non-temporal stores (the kernel
    /// streams large outputs where that pays).
    fn bandwidth(&self) -> f64 {
        self.plain_bw.max(self.nt_bw.unwrap_or(0.0))
    }

    /// Nanoseconds one full-Mueller element needs for its elementary functions
    /// ([`roofline::floor_ns`]).
    fn floor_ns(&self) -> f64 {
        roofline::floor_ns(&self.elementary)
    }

    /// The results do not depend on the thread count: one checksum for all runs.
    fn consistent(&self) -> bool {
        let runs = &self.runs;
        runs.iter().all(|r| {
            r.mueller_sum.to_bits() == runs[0].mueller_sum.to_bits()
                && r.brdf_sum.to_bits() == runs[0].brdf_sum.to_bits()
        })
    }
}

/// Runs `polbrdf bench`: the JSON object on standard output, or the table on standard error.
pub fn run(args: &Args) -> Result<(), CliError> {
    let bench = measure(args)?;
    if args.json {
        let doc = serde_json::to_string_pretty(&json::document(&bench)).expect("serializable");
        crate::output::write_output(None, (doc + "\n").as_bytes())
    } else {
        crate::output::note(&table::text(&bench));
        Ok(())
    }
}

/// Every measurement, in order: the batch API per thread count, the roofs, the per-element
/// index, emission, single-evaluation latency.
fn measure(args: &Args) -> Result<Bench, CliError> {
    // --count, --repeats (at least 5, for a meaningful median) and --threads are in range
    // (their value parsers); the default thread count is the machine's.
    let all = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = args.threads.unwrap_or(all).min(crate::limits::THREADS);
    let material = polbrdf::preset("paint")
        .and_then(|s| s.build())
        .map_err(CliError::Model)?;
    let n = args.count;
    let geometries = Geometries::random(n);
    let batch = geometries.angles()?;
    let directions = geometries.directions()?;

    let mut counts = vec![1];
    if threads != 1 {
        counts.push(threads);
    }
    let runs = counts
        .iter()
        .map(|&t| measure::run_with(t, args.repeats, &material, &batch, &directions))
        .collect::<Result<Vec<_>, _>>()?;
    let (plain_bw, nt_bw) = roofline::write_bandwidth(threads, args.repeats, n)?;
    let kernel = Kernel::new(&material);
    let elementary = roofline::elementary_ns(args.repeats, kernel.level());
    let fma = cpu::fma_rates(args.repeats);
    let store_ratio = roofline::f32_store_ratio(&material, &batch, args.repeats);
    let index = measure::run_index(args.repeats, &material, &batch)?;
    let emission = emission::run_emission(args.repeats, threads)?;
    Ok(Bench {
        count: n,
        repeats: args.repeats,
        threads,
        logical_cpus: all,
        runs,
        plain_bw,
        nt_bw,
        elementary,
        fma,
        store_ratio,
        index,
        emission,
        latency_kernel: measure::latency_ns(&batch, |g| kernel.pbrdf(g)),
        latency_reference: measure::latency_ns(&batch, |g| material.evaluate(g)),
        cpu: cpu::cpu_model(),
        simd: kernel.level().name(),
    })
}
