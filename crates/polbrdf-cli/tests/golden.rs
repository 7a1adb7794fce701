//! The README's fit example gives the same answer as before the one-engine change
//! (`tests/data/golden/README.md`): χ² to 1e-9 relative, every parameter within 1e-6 of its
//! standard error, the standard errors and correlations to 1e-6.

use polbrdf_fit::{fit, FitOptions, Measurement, Observable, Param};
use std::path::Path;

#[test]
fn the_readme_fit_is_unchanged() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/golden");
    let golden: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("pre-engine.json")).unwrap())
            .unwrap();
    let want = &golden["fit"][0];
    let base = polbrdf_io::load_material(dir.join("paint-init.toml").to_str().unwrap()).unwrap();
    let table =
        polbrdf_io::read_measurements_csv(&dir.join("paint-goniometer-pre-engine.csv")).unwrap();
    let mut data = Vec::new();
    for (row, g) in table.geometries.iter().enumerate() {
        for col in &table.columns {
            if let Some(value) = col.values[row] {
                data.push(Measurement {
                    geometry: *g,
                    observable: Observable::parse(&col.name).unwrap(),
                    value,
                    sigma: col.sigmas.as_ref().and_then(|s| s[row]),
                    wavelength_um: None,
                });
            }
        }
    }
    let free = Param::parse_list(want["free"].as_str().unwrap()).unwrap();
    let r = fit(&base, &free, &data, &FitOptions::default()).unwrap();
    let f = |v: &serde_json::Value| v.as_f64().unwrap();
    let chi2 = f(&want["chi2"]);
    assert!(
        (r.chi2 - chi2).abs() <= 1e-9 * chi2,
        "χ² {} vs {chi2}",
        r.chi2
    );
    for j in 0..free.len() {
        let (v, s) = (f(&want["values"][j]), f(&want["stderr"][j]));
        assert!(
            (r.values[j] - v).abs() <= 1e-6 * s,
            "{}: {} vs {v} (σ {s})",
            free[j].name(),
            r.values[j]
        );
        assert!(
            (r.stderr[j] - s).abs() <= 1e-6 * s,
            "σ of {}",
            free[j].name()
        );
        for k in 0..free.len() {
            let c = f(&want["correlation"][j][k]);
            assert!((r.correlation[j][k] - c).abs() <= 1e-6, "corr {j}{k}");
        }
    }
    assert_eq!(r.dof as u64, want["dof"].as_u64().unwrap());
    assert!(r.converged);
}
