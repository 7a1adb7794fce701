//! Pure-Rust baseline for the Python timing: 10^6 random valid geometries of the `paint` preset
//! through the core's batch API, medians of several repeats.
//!
//! ```sh
//! cargo run --release -p polbrdf-python --example bench_batch [-- N REPEATS]
//! python python/examples/bench.py [N REPEATS]      # the same from Python
//! ```

use polbrdf::batch;
use polbrdf::GeometryBatch;
use std::time::Instant;

/// CPU time of the whole process (all threads), seconds: less sensitive than wall time to other
/// programs competing for the cores.
#[cfg(all(target_os = "linux", target_pointer_width = "64"))]
fn cpu_time() -> f64 {
    #[repr(C)]
    struct Timespec {
        tv_sec: i64,
        tv_nsec: i64,
    }
    extern "C" {
        fn clock_gettime(clock: i32, ts: *mut Timespec) -> i32;
    }
    const CLOCK_PROCESS_CPUTIME_ID: i32 = 2;
    let mut ts = Timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes one timespec (two 64-bit fields on 64-bit Linux) into `ts`.
    let rc = unsafe { clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    if rc == 0 {
        ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
    } else {
        f64::NAN
    }
}

#[cfg(not(all(target_os = "linux", target_pointer_width = "64")))]
fn cpu_time() -> f64 {
    f64::NAN
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median wall time and median process CPU time of `f`, in ms, after one warm-up call.
fn median_ms(repeats: usize, mut f: impl FnMut()) -> (f64, f64) {
    f(); // warm-up (thread pool, page faults)
    let (wall, cpu): (Vec<f64>, Vec<f64>) = (0..repeats)
        .map(|_| {
            let (start, c0) = (Instant::now(), cpu_time());
            f();
            let cpu = (cpu_time() - c0) * 1e3;
            (start.elapsed().as_secs_f64() * 1e3, cpu)
        })
        .unzip();
    (median(wall), median(cpu))
}

fn report(name: &str, (wall, cpu): (f64, f64)) {
    println!("rust {name:<52} wall {wall:8.1}  cpu {cpu:8.1}");
}

fn main() -> Result<(), polbrdf::Error> {
    let mut args = std::env::args().skip(1);
    let n: usize = args.next().map_or(1_000_000, |s| s.parse().expect("N"));
    let repeats: usize = args.next().map_or(7, |s| s.parse().expect("REPEATS"));
    let material = polbrdf::preset("paint")?.build()?;
    // Seed 2024: the same stream in `polbrdf bench` and python/examples/bench_batch.rs.
    let mut rng = polbrdf::sample::SplitMix64::new(2024);
    let ti = rng.uniform(0.0, 89.9f64.to_radians(), n);
    let pi = rng.uniform(0.0, 360f64.to_radians(), n);
    let tr = rng.uniform(0.0, 89.9f64.to_radians(), n);
    let pr = rng.uniform(0.0, 360f64.to_radians(), n);
    println!(
        "{n} geometries of `paint`, {} rayon threads, medians of {repeats} (ms)",
        rayon::current_num_threads()
    );

    let mut out = vec![[0.0; 16]; n];
    let t = median_ms(repeats, || {
        let b = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
        batch::mueller_into(&material, &b, &mut out).unwrap();
    });
    report("mueller (validate + mueller_into, reused output)", t);
    let t = median_ms(repeats, || {
        let b = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
        let mut out = vec![[0.0; 16]; n];
        batch::mueller_into(&material, &b, &mut out).unwrap();
        std::hint::black_box(&out);
    });
    report("mueller (validate + mueller_into, new output)", t);
    let mut out32 = vec![[0.0f32; 16]; n];
    let engine = polbrdf::Engine::new(&material);
    let t = median_ms(repeats, || {
        let b = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
        engine.mueller_f32_into(&b, &mut out32).unwrap();
    });
    report("mueller f32 (validate + mueller_f32_into, reused)", t);

    let (mut f, mut d) = (vec![0.0; n], vec![0.0; n]);
    let t = median_ms(repeats, || {
        let b = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
        batch::brdf_dolp_into(&material, &b, &mut f, &mut d).unwrap();
    });
    report("brdf+dolp (validate + brdf_dolp_into, reused out)", t);
    let t = median_ms(repeats, || {
        let b = GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
        let (mut f, mut d) = (vec![0.0; n], vec![0.0; n]);
        batch::brdf_dolp_into(&material, &b, &mut f, &mut d).unwrap();
        std::hint::black_box((&f, &d));
    });
    report("brdf+dolp (validate + brdf_dolp_into, new outputs)", t);
    let t = median_ms(repeats, || {
        std::hint::black_box(GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap());
    });
    report("validation alone (GeometryBatch::new)", t);
    Ok(())
}
