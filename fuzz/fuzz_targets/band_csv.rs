//! Band CSV: any bytes parse into a valid band (strictly increasing finite wavelengths > 0, a
//! finite response ≥ 0 and not all zero) whose quadrature weights are finite, ≥ 0 and integrate
//! the response, or give an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_band_csv(data, Path::new("fuzz.csv")) {
        Ok(b) => {
            let (wl, r) = b.table();
            assert!(wl.len() >= 2 && wl.len() == r.len());
            assert!(wl.windows(2).all(|w| w[0] < w[1]) && wl[0] > 0.0);
            assert!(r.iter().all(|v| v.is_finite() && *v >= 0.0) && r.iter().any(|v| *v > 0.0));
            let (lo, hi) = b.range();
            assert!(lo < hi);
            // Bounded node counts only (a huge width over a tiny step is legitimate input).
            if (hi - lo) / b.default_step() <= 64.0 && wl.len() <= 4096 {
                let nodes = b.nodes(b.default_step(), &[]);
                assert!(nodes
                    .iter()
                    .all(|(l, w)| l.is_finite() && w.is_finite() && *w >= 0.0));
                assert!(nodes.iter().all(|(l, _)| *l >= lo && *l <= hi));
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.csv")),
    }
});
