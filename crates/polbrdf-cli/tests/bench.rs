//! `polbrdf bench`: runs, reports what it promises, refuses bad options.

use crate::common::{polbrdf, stderr};

#[test]
fn bench_reports_rates_latency_emission_checksum_and_cpu_as_json() {
    let out = polbrdf(&[
        "bench",
        "--count",
        "3000",
        "--threads",
        "2",
        "--repeats",
        "5",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON on stdout");
    assert_eq!(doc["count"], 3000);
    assert_eq!(doc["material"], "paint");
    let results = doc["results"].as_array().unwrap();
    assert_eq!(results.len(), 2, "one thread and two threads");
    for r in results {
        for key in ["mueller_evals_per_s", "brdf_dolp_evals_per_s"] {
            assert!(r[key].as_f64().unwrap() > 0.0, "{key}");
        }
    }
    // The elementary-function floor: every operation timed, and the floor their weighted sum.
    let el = &doc["elementary_ns_per_element_one_thread"];
    let floor = &doc["elementary_floor"];
    let mut sum = 0.0;
    for op in ["sincos", "atan2", "exp", "sqrt", "div"] {
        let ns = el[op].as_f64().unwrap_or_else(|| panic!("{op}: {el}"));
        assert!(ns.is_finite() && ns > 0.0, "{op} = {ns}");
        sum += floor["counts"][op].as_f64().unwrap() * ns;
    }
    let floor_ns = floor["ns_per_element_one_thread"].as_f64().unwrap();
    assert!((floor_ns - sum).abs() <= 1e-9 * sum, "{floor_ns} vs {sum}");
    // The arithmetic roof: every width timed where the CPU has AVX2 and FMA (512 bits where it
    // has AVX-512F), the peaks what the best width gives (4, 8 or 16 f32 lanes per instruction,
    // 2 flops per fused multiply-add), and the widest width at that rate (within 25 %).
    let fma = &doc["fma_throughput_one_thread"];
    if doc["cpu"]["simd"]
        .as_str()
        .is_some_and(|s| s.contains("avx2") || s == "avx512")
    {
        let r128 = fma["fma_per_s_128bit"]
            .as_f64()
            .unwrap_or_else(|| panic!("{fma}"));
        let r256 = fma["fma_per_s_256bit"].as_f64().unwrap();
        assert!(r128 > 0.0 && r256 > 0.0, "{fma}");
        let r512 = fma["fma_per_s_512bit"].as_f64();
        assert_eq!(r512.is_some(), doc["cpu"]["simd"] == "avx512", "{fma}");
        let peak64 = fma["peak_f64_flops"].as_f64().unwrap();
        let best = (4.0 * r128).max(8.0 * r256).max(16.0 * r512.unwrap_or(0.0));
        assert!((peak64 - best).abs() <= 1e-9 * peak64, "{fma}");
        let widest = fma["widest_full_rate_bits"].as_u64().unwrap();
        let lanes = (widest / 32) as f64;
        let rate = match widest {
            128 => r128,
            256 => r256,
            _ => r512.unwrap(),
        };
        assert!(lanes * rate >= 0.75 * best, "{fma}");
        assert_eq!(fma["peak_f32_flops"].as_f64().unwrap(), 2.0 * peak64);
        assert_eq!(
            fma["full_width_256bit"].as_bool().unwrap(),
            2.0 * r256 > 1.5 * r128
        );
    } else {
        assert!(fma.is_null(), "{fma}");
    }
    // The write roofline: the better of plain and non-temporal stores (x86-64).
    let bw = &doc["write_bandwidth"];
    let plain = bw["plain_bytes_per_s"].as_f64().unwrap();
    let best = plain.max(bw["non_temporal_bytes_per_s"].as_f64().unwrap_or(0.0));
    assert!(
        plain > 0.0 && bw["bytes_per_s"].as_f64().unwrap() == best,
        "{bw}"
    );
    assert_eq!(
        bw["full_mueller_f32_roofline_evals_per_s"]
            .as_f64()
            .unwrap(),
        best / 64.0
    );
    // float32 stores: the paired ratio measured, and whether the engine uses them here.
    let stores = &doc["f32_non_temporal_stores"];
    assert!(
        stores["paired_ratio_one_thread"].as_f64().unwrap() > 0.0,
        "{stores}"
    );
    assert_eq!(
        stores["used"].as_bool().unwrap(),
        ::polbrdf::engine::simd::f32_streams_pay()
    );
    assert!(doc["single_eval_ns"]["kernel"].as_f64().unwrap() > 0.0);
    assert!(doc["single_eval_ns"]["reference"].as_f64().unwrap() > 0.0);
    assert!(doc["cpu"]["model"].as_str().is_some_and(|s| !s.is_empty()));
    assert!(doc["cpu"]["simd"].as_str().is_some());
    let emission = &doc["emission"];
    let positive = |v: &serde_json::Value, key: &str| {
        let x = v[key].as_f64().unwrap_or_else(|| panic!("{key}: {v}"));
        assert!(x.is_finite() && x > 0.0, "{key} = {x}");
    };
    let directions = emission["per_direction"].as_array().unwrap();
    assert_eq!(directions.len(), 9, "three materials at θ = 0°, 45°, 80°");
    for d in directions {
        assert!(d["material"].as_str().is_some(), "{d}");
        for key in [
            "one_thread_ms",
            "all_threads_ms",
            "sigma_deg",
            "nodes",
            "eps0",
        ] {
            positive(d, key);
        }
        assert!(d["theta_deg"].as_f64().is_some(), "{d}");
    }
    let table = &emission["table_90"];
    for key in ["one_thread_ms", "all_threads_ms", "eps0_sum"] {
        positive(table, key);
    }
    assert_eq!(emission["threads"], 2);
    assert_eq!(emission["same_for_all_thread_counts"], true);
    let checksum = &doc["checksum"];
    assert_eq!(checksum["same_for_all_thread_counts"], true);
    assert!(checksum["brdf_sum"].as_f64().unwrap() > 0.0);
}

#[test]
fn bench_table_goes_to_stderr_and_json_alone_to_stdout() {
    // The stream rule: standard output carries only data results (the `--json` object); the
    // table is for a person, on standard error.
    let args = [
        "bench",
        "--count",
        "1000",
        "--threads",
        "1",
        "--repeats",
        "5",
    ];
    let table = polbrdf(&args);
    assert!(table.status.success(), "{}", stderr(&table));
    assert!(
        table.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&table.stdout)
    );
    let text = stderr(&table);
    assert!(
        text.starts_with(
            "polbrdf bench: 1000 random valid geometries of `paint` through the batch API, \
             medians of 5 repeats\n"
        ),
        "{text}"
    );
    let json = polbrdf(&[&args[..], &["--json"]].concat());
    assert!(json.status.success(), "{}", stderr(&json));
    assert_eq!(stderr(&json), "", "nothing but the JSON object is printed");
    let doc: serde_json::Value = serde_json::from_slice(&json.stdout).expect("JSON on stdout");
    // Both renderings report the same run: the checksums (deterministic) agree.
    let sum = |key: &str| doc["checksum"][key].as_f64().unwrap();
    let line = format!(
        "checksum: Σ brdf = {:.12e}, Σ dolp = {:.12e}, Σ F = {:.12e} (identical for every \
         thread count)\n",
        sum("brdf_sum"),
        sum("dolp_sum"),
        sum("mueller_sum")
    );
    assert!(text.ends_with(&line), "{text}\nwanted: {line}");
}

#[test]
fn bench_refuses_too_few_repeats_and_zero_counts() {
    for args in [
        &["bench", "--count", "100", "--repeats", "3"][..],
        &["bench", "--count", "0"],
        &["bench", "--count", "100", "--threads", "0"],
    ] {
        // Option values out of range: usage errors (exit 2) naming the option.
        let out = polbrdf(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(args[args.len() - 2]),
            "{}",
            stderr(&out)
        );
    }
}
