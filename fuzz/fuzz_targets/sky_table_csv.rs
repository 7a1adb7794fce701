//! Sky table CSV (`[sky] model = "table"`): any bytes parse into a full grid of zenith angles
//! (0° to 90°) × azimuths (in [0°, 360°)) whose interpolated Stokes radiance is finite with
//! s0 ≥ 0 (up to rounding) and a degree of polarization at most 1 (up to rounding) in every
//! direction tried, or give an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::analysis::sky::SkyRadiance;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_sky_table_csv(data, Path::new("fuzz.csv")) {
        Ok(table) => {
            let (theta, phi) = table.grid();
            assert!(theta.len() >= 2 && theta[0] == 0.0 && theta[theta.len() - 1] == 90.0);
            assert!(!phi.is_empty() && phi.iter().all(|p| (0.0..360.0).contains(p)));
            // The nodes, between them, beyond the last azimuth and below the first, and
            // directions outside the usual ranges.
            let mut dirs: Vec<(f64, f64)> = Vec::new();
            for t in [0.0, 1.0, 33.3, 45.0, 89.9, 90.0, 120.0, -5.0] {
                for p in [0.0, 0.5, 90.0, 179.9, 359.99, 360.0, -1e-20, -725.0, 1e6] {
                    dirs.push((t, p));
                }
            }
            for (&t, &p) in theta.iter().zip(phi.iter().cycle()) {
                dirs.push((t, p));
            }
            for (t, p) in dirs {
                let s = table.stokes(f64::to_radians(t), f64::to_radians(p));
                assert!(s.0.iter().all(|v| v.is_finite()), "({t}, {p}): {s:?}");
                let scale = s.0.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(s.0[0] >= -1e-12 * scale, "({t}, {p}): {s:?}");
                let pol = (s.0[1].hypot(s.0[2])).hypot(s.0[3]);
                assert!(pol <= s.0[0] + 1e-6 * scale, "({t}, {p}): {s:?}");
            }
        }
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("fuzz.csv"), "{m}");
            assert!(!m.trim_end().ends_with(':'), "an empty message: {m:?}");
        }
    }
});
