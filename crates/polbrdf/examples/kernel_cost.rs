//! The batch kernel's cost per element on one thread, for instruction counts and timings of
//! one route at a time (docs/engine-performance.md):
//!
//! ```text
//! cargo run --release -p polbrdf --example kernel_cost -- ROUTE PRECISION COUNT [REPEATS] [LEVEL]
//! ```
//!
//! `ROUTE` is `angles` or `directions`, or `angles-fold` or `directions-fold` (below),
//! `PRECISION` `f64` or `f32`, `LEVEL` `best` (default),
//! `avx512`, `avx2+fma` or `portable`. It evaluates the peer benchmark's conductor
//! (`scripts/bench-peers`: n = 1.2, k = 7, σ = atan 0.2, shadowing off) at `COUNT` random
//! geometries (θ uniform in [0°, 89.9°], φ in [0°, 360°), the same as `polbrdf bench`), row
//! major, `REPEATS` times (default 1), and prints the CPU nanoseconds per element of the
//! batches' validation and of each repeat (the thread's), and a checksum. Under `valgrind --tool=callgrind` two counts give the
//! instructions per element: `(I(N₂) − I(N₁))/(N₂ − N₁)` (valgrind has no AVX-512: it runs the
//! AVX2 code).
//!
//! The `-fold` routes time, alternately in each repeat, the two ways of evaluating input not
//! validated yet chunk by chunk (4096 elements, as Python's `mueller` does on each thread): the
//! batch constructor's validation then the kernel (`GeometryBatch::new` or
//! `DirectionBatch::new`, then `mueller_into`), and the kernel validating each block as it
//! reads it (`Unvalidated`, `try_mueller_into`); they print both and the paired ratio of each
//! repeat, then the median.

use polbrdf::engine::{Kernel, SimdLevel};
use polbrdf::geometry::direction;
use polbrdf::sample::SplitMix64;
use polbrdf::{DirectionBatch, GeometryBatch, MaterialSpec, Unvalidated};

/// The CPU time (ns) of `clock` (the thread's, or the process's).
fn clock_ns(clock: libc::clockid_t) -> u128 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `ts` is a valid timespec to write to.
    let ok = unsafe { libc::clock_gettime(clock, &mut ts) } == 0;
    assert!(ok, "clock_gettime");
    ts.tv_sec as u128 * 1_000_000_000 + ts.tv_nsec as u128
}

/// The thread's CPU time (ns).
fn cpu_ns() -> u128 {
    clock_ns(libc::CLOCK_THREAD_CPUTIME_ID)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "kernel_cost ROUTE(angles|directions) PRECISION(f64|f32) COUNT [REPEATS] [LEVEL]";
    let (route, precision) = (args.first().expect(usage), args.get(1).expect(usage));
    let n: usize = args.get(2).expect(usage).parse().expect(usage);
    let repeats: usize = args.get(3).map_or(1, |r| r.parse().expect(usage));
    let level = match args.get(4).map_or("best", String::as_str) {
        "avx512" => SimdLevel::Avx512,
        "avx2+fma" => SimdLevel::Avx2,
        "portable" => SimdLevel::Portable,
        _ => polbrdf::engine::simd_level(),
    };
    let material = MaterialSpec {
        k: 7.0,
        shadowing: false,
        ..MaterialSpec::new(1.2, 0.2f64.atan().to_degrees())
    }
    .build()
    .expect("the conductor");
    let kernel = Kernel::with_level(&material, level).expect("a level this CPU supports");
    let mut rng = SplitMix64::new(2024);
    let (t, p) = (89.9f64.to_radians(), 360f64.to_radians());
    let cols: [Vec<f64>; 4] = std::array::from_fn(|c| {
        (0..n)
            .map(|_| rng.range(0.0, if c % 2 == 0 { t } else { p }))
            .collect()
    });
    let w_i: Vec<[f64; 3]> = (0..n).map(|j| direction(cols[0][j], cols[1][j])).collect();
    let w_r: Vec<[f64; 3]> = (0..n).map(|j| direction(cols[2][j], cols[3][j])).collect();
    // The batches' validation (one pass over the inputs, on the library's thread pool: the
    // process's CPU time).
    let start = clock_ns(libc::CLOCK_PROCESS_CPUTIME_ID);
    let angles = GeometryBatch::new(&cols[0], &cols[1], &cols[2], &cols[3]).expect("angles");
    let mid = clock_ns(libc::CLOCK_PROCESS_CPUTIME_ID);
    let dirs = DirectionBatch::new(&w_i, &w_r).expect("directions");
    let end = clock_ns(libc::CLOCK_PROCESS_CPUTIME_ID);
    println!(
        "validation: angles {:.3} ns/element, directions {:.3} ns/element (process CPU)",
        (mid - start) as f64 / n as f64,
        (end - mid) as f64 / n as f64
    );
    let (mut out64, mut out32) = (vec![[0.0f64; 16]; n], vec![[0.0f32; 16]; n]);
    if let Some(route) = route.strip_suffix("-fold") {
        let inputs = Inputs {
            cols: &cols,
            w_i: &w_i,
            w_r: &w_r,
        };
        let f32 = precision == "f32";
        // On a worker of a one-thread pool, as Python's chunks run (the constructors'
        // validation is itself parallel: from outside the pool each call would pay for
        // sending its work there); each way once untimed (the output's pages), then in
        // alternating order.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("a thread pool");
        let mut ratios = pool.install(|| {
            for folded in [false, true] {
                inputs.chunks(&kernel, route, f32, folded, &mut out64, &mut out32);
            }
            let mut ratios = vec![];
            for r in 0..repeats {
                let mut ns = [0.0; 2];
                for k in 0..2 {
                    let folded = (k + r) % 2 == 1;
                    let start = cpu_ns();
                    inputs.chunks(&kernel, route, f32, folded, &mut out64, &mut out32);
                    ns[usize::from(folded)] = (cpu_ns() - start) as f64 / n as f64;
                }
                println!(
                    "validate then evaluate {:.3} ns/element, folded {:.3} ns/element: {:.3}x",
                    ns[0],
                    ns[1],
                    ns[0] / ns[1]
                );
                ratios.push(ns[0] / ns[1]);
            }
            ratios
        });
        ratios.sort_by(f64::total_cmp);
        println!(
            "{route} {precision} at {}: median speed-up of the folded validation {:.3}x",
            level.name(),
            ratios[ratios.len() / 2]
        );
        return;
    }
    let mut checksum = 0.0;
    for _ in 0..repeats {
        let start = cpu_ns();
        match (route.as_str(), precision.as_str()) {
            ("angles", "f64") => kernel.mueller_into(&angles, 0, &mut out64),
            ("directions", "f64") => kernel.mueller_into(&dirs, 0, &mut out64),
            ("angles", "f32") => {
                kernel.mueller_f32_into(&angles, 0, &mut out32);
            }
            ("directions", "f32") => {
                kernel.mueller_f32_into(&dirs, 0, &mut out32);
            }
            _ => panic!("{usage}"),
        }
        let ns = cpu_ns() - start;
        println!("{:.3} ns/element", ns as f64 / n as f64);
        checksum = if precision == "f32" {
            out32.iter().map(|r| f64::from(r[0])).sum::<f64>()
        } else {
            out64.iter().map(|r| r[0]).sum::<f64>()
        };
    }
    println!(
        "{route} {precision} at {}: checksum {checksum:.9e}",
        level.name()
    );
}

/// The benchmark's inputs, for the `-fold` routes.
struct Inputs<'a> {
    cols: &'a [Vec<f64>; 4],
    w_i: &'a [[f64; 3]],
    w_r: &'a [[f64; 3]],
}

impl Inputs<'_> {
    /// Every element, 4096 at a time: validated by the batch's constructor then evaluated, or
    /// (`folded`) validated by the kernel as it reads each block.
    fn chunks(
        &self,
        kernel: &Kernel<'_>,
        route: &str,
        f32: bool,
        folded: bool,
        out64: &mut [[f64; 16]],
        out32: &mut [[f32; 16]],
    ) {
        const CHUNK: usize = 4096;
        for start in (0..self.w_i.len()).step_by(CHUNK) {
            let r = start..(start + CHUNK).min(self.w_i.len());
            let (o64, o32) = (&mut out64[r.clone()], &mut out32[r.clone()]);
            let [ti, pi, tr, pr] = self.cols.each_ref().map(|c| &c[r.clone()]);
            let (wi, wr) = (&self.w_i[r.clone()], &self.w_r[r.clone()]);
            let angles = route == "angles";
            if folded {
                let raw = if angles {
                    Unvalidated::angles(ti, pi, tr, pr)
                } else {
                    Unvalidated::directions(wi, wr)
                }
                .expect("lengths");
                if f32 {
                    kernel.try_mueller_f32_into(&raw, 0, o32).expect("valid");
                } else {
                    kernel.try_mueller_into(&raw, 0, o64).expect("valid");
                }
            } else if angles {
                let b = GeometryBatch::new(ti, pi, tr, pr).expect("valid");
                if f32 {
                    kernel.mueller_f32_into(&b, 0, o32);
                } else {
                    kernel.mueller_into(&b, 0, o64);
                }
            } else {
                let b = DirectionBatch::new(wi, wr).expect("valid");
                if f32 {
                    kernel.mueller_f32_into(&b, 0, o32);
                } else {
                    kernel.mueller_into(&b, 0, o64);
                }
            }
        }
    }
}
