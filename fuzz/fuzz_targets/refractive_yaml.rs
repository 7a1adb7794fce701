//! refractiveindex.info YAML files: any bytes either parse into a spectral index that gives a
//! valid N = n + ik (finite, n > 0, k ≥ 0) over its whole range, or give an error naming the
//! file; never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_refractiveindex_yaml_bytes(data, Path::new("fuzz.yml"), "fuzz") {
        Ok(index) => {
            let (lo, hi) = index.range();
            assert!(lo > 0.0 && lo <= hi && hi.is_finite(), "range {lo}–{hi}");
            // The ends, the midpoint and the eighths (points the parser checks formulas at),
            // and the geometric mean.
            let eighths = (0..=8).map(|j| lo + (hi - lo) * (f64::from(j) / 8.0));
            for l in eighths.chain([(lo * hi).sqrt()]) {
                let l = l.clamp(lo, hi);
                let n = index
                    .at(l)
                    .unwrap_or_else(|e| panic!("valid at {l} µm in {lo}–{hi}: {e}"));
                assert!(n.n().is_finite() && n.n() > 0.0, "n = {} at {l}", n.n());
                assert!(n.k().is_finite() && n.k() >= 0.0, "k = {} at {l}", n.k());
            }
            assert!(index.at(hi * 2.0 + 1.0).is_err(), "no extrapolation");
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.yml"), "{e}"),
    }
});
