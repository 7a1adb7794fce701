//! Sky profile CSV (`[sky] model = "profile"`): any bytes parse into a profile from 0° to 90°
//! with finite radiances ≥ 0 whose interpolated radiance is finite and ≥ 0 everywhere, or give
//! an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_sky_profile_csv(data, Path::new("fuzz.csv")) {
        Ok(profile) => {
            for k in 0..=90 {
                let l = profile.at(f64::from(k).to_radians());
                assert!(l.is_finite() && l >= 0.0, "{k}°: {l}");
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.csv")),
    }
});
