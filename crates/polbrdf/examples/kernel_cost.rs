//! The batch kernel's cost per element on one thread, for instruction counts and timings of
//! one route at a time (docs/engine-performance.md):
//!
//! ```text
//! cargo run --release -p polbrdf --example kernel_cost -- ROUTE PRECISION COUNT [REPEATS] [LEVEL]
//! ```
//!
//! `ROUTE` is `angles` or `directions`, `PRECISION` `f64` or `f32`, `LEVEL` `best` (default),
//! `avx512`, `avx2+fma` or `portable`. It evaluates the peer benchmark's conductor
//! (`scripts/bench-peers`: n = 1.2, k = 7, σ = atan 0.2, shadowing off) at `COUNT` random
//! geometries (θ uniform in [0°, 89.9°], φ in [0°, 360°), the same as `polbrdf bench`), row
//! major, `REPEATS` times (default 1), and prints the CPU nanoseconds per element of the
//! batches' validation and of each repeat (the thread's), and a checksum. Under `valgrind --tool=callgrind` two counts give the
//! instructions per element: `(I(N₂) − I(N₁))/(N₂ − N₁)` (valgrind has no AVX-512: it runs the
//! AVX2 code).

use polbrdf::engine::{Kernel, SimdLevel};
use polbrdf::geometry::direction;
use polbrdf::sample::SplitMix64;
use polbrdf::{DirectionBatch, GeometryBatch, MaterialSpec};

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
