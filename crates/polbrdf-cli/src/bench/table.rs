//! The benchmark's report as a table for a person (standard error, through the output layer's
//! notes): throughput, the machine's roofs, the per-element index, emission and the checksum.

use super::emission::EMISSION_MATERIALS;
use super::roofline::FLOOR_COUNTS;
use super::Bench;
use std::fmt::Write;

/// The whole table, line by line as printed.
pub(super) fn text(b: &Bench) -> String {
    let mut s = String::new();
    throughput(&mut s, b);
    roofs(&mut s, b);
    s.push('\n');
    index(&mut s, b);
    s.push('\n');
    emission(&mut s, b);
    checksum(&mut s, b);
    s
}

/// The heading (setting and CPU) and the batch API's rates per thread count.
fn throughput(s: &mut String, b: &Bench) {
    let (n, all, cpu, simd) = (b.count, b.logical_cpus, &b.cpu, b.simd);
    let _ = writeln!(
        s,
        "polbrdf bench: {n} random valid geometries of `paint` through the batch API, \
         medians of {} repeats",
        b.repeats
    );
    let _ = writeln!(
        s,
        "CPU: {cpu} ({all} logical CPUs); kernel SIMD level: {simd}"
    );
    s.push('\n');
    let _ = writeln!(
        s,
        "{:<10} {:>22} {:>22} {:>22} {:>22} {:>22}",
        "threads",
        "full Mueller",
        "full Mueller, f32",
        "from vectors",
        "from vectors, f32",
        "BRDF + DoLP"
    );
    for r in &b.runs {
        let _ = writeln!(
            s,
            "{:<10} {:>15.2} M/s   {:>15.2} M/s   {:>15.2} M/s   {:>15.2} M/s   {:>15.2} M/s",
            r.threads,
            b.per_s(r.mueller_s) / 1e6,
            b.per_s(r.mueller_f32_s) / 1e6,
            b.per_s(r.directions_s) / 1e6,
            b.per_s(r.directions_f32_s) / 1e6,
            b.per_s(r.brdf_dolp_s) / 1e6
        );
    }
}

/// The memory and arithmetic roofs and the elementary-function floor.
fn roofs(s: &mut String, b: &Bench) {
    let (n, threads, bandwidth) = (b.count, b.threads, b.bandwidth());
    let _ = writeln!(
        s,
        "memory write bandwidth ({threads} threads, {:.0} MB filled): {:.1} GB/s plain, \
         {} non-temporal — the full-Mueller roofline (the better) is {:.1} M/s in f64 \
         (128 B each), {:.1} M/s in f32",
        (n * 128) as f64 / 1e6,
        b.plain_bw / 1e9,
        b.nt_bw
            .map_or("n/a".to_string(), |b| format!("{:.1} GB/s", b / 1e9)),
        bandwidth / 128e6,
        bandwidth / 64e6
    );
    let _ = writeln!(
        s,
        "float32 output, non-temporal against plain stores (1 thread, paired CPU-time \
         ratios, median): {:.2}x — {} on this CPU",
        b.store_ratio,
        if polbrdf::engine::simd::f32_streams_pay() {
            "used"
        } else {
            "not used"
        }
    );
    if let Some(f) = b.fma {
        let (lanes, full) = (f.lanes(), f.full_width_256());
        let _ = writeln!(
            s,
            "fused multiply-adds (1 thread): {:.2} G/s in 128-bit registers, {:.2} G/s in \
             256-bit, {} in 512-bit (widest at full rate: {} bits): a peak of {:.1} GFLOP/s \
             in f32, {:.1} in f64 per thread{}",
            f.r128 / 1e9,
            f.r256 / 1e9,
            f.r512
                .map_or("n/a".to_string(), |r| format!("{:.2} G/s", r / 1e9)),
            f.widest(),
            2.0 * lanes / 1e9,
            lanes / 1e9,
            if full {
                ""
            } else {
                " — 256-bit operations at half rate (two 128-bit halves, as on AMD Zen 1): \
                 AVX2 has no more arithmetic throughput than SSE here"
            }
        );
    }
    let floor_ns = b.floor_ns();
    let list: Vec<String> = b
        .elementary
        .iter()
        .map(|(op, ns)| format!("{} {ns:.2}", op.name()))
        .collect();
    let counts: Vec<String> = FLOOR_COUNTS
        .iter()
        .map(|(op, k)| format!("{k} {}", op.name()))
        .collect();
    let _ = writeln!(
        s,
        "elementary functions (1 thread, ns per element): {}; one full-Mueller element \
         needs {} = {floor_ns:.1} ns: at most {:.1} M/s per thread with nothing else",
        list.join(", "),
        counts.join(" + "),
        1e3 / floor_ns
    );
}

/// The per-element index and the spectral sweep against the constant index, and the latency
/// of a single evaluation.
fn index(s: &mut String, b: &Bench) {
    let (threads, index) = (b.threads, &b.index);
    let _ = writeln!(
        s,
        "BRDF + DoLP with a complex index per element ({threads} threads): \
         {:.2} M/s with the material's own index; the same N in every element {:.2} M/s \
         ({:+.1} %{})",
        b.per_s(index.constant_s) / 1e6,
        b.per_s(index.same_index_s) / 1e6,
        100.0 * (index.same_index_s / index.constant_s - 1.0),
        if index.same_index_identical {
            ", identical results"
        } else {
            ", RESULTS DIFFER"
        },
    );
    let _ = writeln!(
        s,
        "spectral sweep ({threads} threads; water's tabulated index, 100 wavelengths 0.4–14 µm, \
         looked up in the engine): {:.2} M/s in runs ({:+.1} %), {:.2} M/s cycling ({:+.1} %) \
         against {:.2} M/s with water's index at 3.2 µm as a constant (time ratios: medians \
         of paired repeats){}",
        b.per_s(index.runs_s) / 1e6,
        100.0 * (index.runs_ratio - 1.0),
        b.per_s(index.cycling_s) / 1e6,
        100.0 * (index.cycling_ratio - 1.0),
        b.per_s(index.water_s) / 1e6,
        if index.spectral_matches {
            ""
        } else {
            " — DIFFERS from the material built at one wavelength"
        },
    );
    let _ = writeln!(
        s,
        "single evaluation: {:.1} ns (kernel, Kernel::pbrdf), \
         {:.1} ns (one-geometry path, Material::evaluate)",
        b.latency_kernel, b.latency_reference
    );
}

/// The emission timings: one row per material and zenith, then the 90-angle table.
fn emission(s: &mut String, b: &Bench) {
    let (threads, emission) = (b.threads, &b.emission);
    let _ = writeln!(
        s,
        "emission (default accuracy, both routes of Kirchhoff's law): one `emissivity` call, \
         ms (medians)"
    );
    // The parallel column only when it is a different pool.
    let parallel_col = |ms: String| if threads == 1 { String::new() } else { ms };
    let _ = writeln!(
        s,
        "{:<15} {:>5} {:>5} {:>7} {:>10}{} {:>9}",
        "material",
        "σ",
        "θ",
        "nodes",
        "1 thread",
        parallel_col(format!(" {:>10}", format!("{threads} threads"))),
        "ε0"
    );
    for d in &emission.directions {
        let _ = writeln!(
            s,
            "{:<15} {:>4.0}° {:>4.0}° {:>7} {:>10.3}{} {:>9.6}",
            d.material,
            d.sigma_deg,
            d.theta_deg,
            d.nodes,
            1e3 * d.one_thread_s,
            parallel_col(format!(" {:>10.3}", 1e3 * d.parallel_s)),
            d.eps.eps.0[0]
        );
    }
    let _ = writeln!(
        s,
        "90-angle table of `{}` (θ = 0°…89°, `emissivities`): {:.1} ms on 1 thread{}; \
         Σ ε0 = {:.12e}{}",
        EMISSION_MATERIALS[0],
        1e3 * emission.table_one_thread_s,
        parallel_col(format!(
            ", {:.1} ms on {threads} threads",
            1e3 * emission.table_parallel_s
        )),
        emission.table_eps0_sum,
        match (threads, emission.consistent) {
            (1, true) => " (a single call gives the same ε)",
            (_, true) => " (identical for every thread count)",
            (1, false) => " (DIFFERS from a single call)",
            (_, false) => " (DIFFERS between thread counts)",
        }
    );
}

/// The checksum of the results, and whether every thread count gave it.
fn checksum(s: &mut String, b: &Bench) {
    let _ = writeln!(
        s,
        "checksum: Σ brdf = {:.12e}, Σ dolp = {:.12e}, Σ F = {:.12e}{}",
        b.runs[0].brdf_sum,
        b.runs[0].dolp_sum,
        b.runs[0].mueller_sum,
        if b.consistent() {
            " (identical for every thread count)"
        } else {
            " (DIFFERS between thread counts)"
        }
    );
}
