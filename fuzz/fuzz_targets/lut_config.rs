//! Lookup-table configurations (`polbrdf lut --config`): any bytes either parse into a table
//! whose axes are non-empty, finite and strictly increasing (wavelengths > 0, zenith angles in
//! [0°, 180°]), of 1 to MAX_ROWS rows, with distinct material names and quantities, or give an
//! error naming the file and saying what is wrong; never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf_io::lut::{parse_lut_config, MAX_ROWS};
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // The file names files to read: no devices or pseudo-files.
    let Some(text) = polbrdf_fuzz::file_text(data) else {
        return;
    };
    match parse_lut_config(text, Path::new("fuzz.toml")) {
        Ok(c) => {
            let increasing = |v: &[f64]| {
                !v.is_empty()
                    && v.iter().all(|x| x.is_finite())
                    && v.windows(2).all(|w| w[0] < w[1])
            };
            assert!(increasing(&c.wavelength_um) && c.wavelength_um[0] > 0.0);
            for axis in [&c.theta_i_deg, &c.theta_r_deg] {
                assert!(increasing(axis), "{axis:?}");
                assert!(axis.iter().all(|t| (0.0..=180.0).contains(t)), "{axis:?}");
            }
            assert!(increasing(&c.dphi_deg), "{:?}", c.dphi_deg);
            assert!((1..=MAX_ROWS).contains(&c.rows()), "{}", c.rows());
            for (i, (n, _)) in c.materials.iter().enumerate() {
                assert!(c.materials[..i].iter().all(|(m, _)| m != n), "{n}");
            }
            assert!(!c.quantities.is_empty() && c.quantities.windows(2).all(|w| w[0] < w[1]));
        }
        Err(e) => {
            let m = e.to_string();
            assert!(m.starts_with("fuzz.toml"), "{m}");
            assert!(!m.trim_end().ends_with(':'), "an empty message: {m:?}");
        }
    }
});
