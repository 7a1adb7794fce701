//! Spectral indices and bands (docs/model.md §15): interpolation exact at the nodes and linear
//! between, out-of-range errors, the band quadrature (exactness, convergence), a constant
//! spectrum's band result equal to the single-wavelength one, and band DoLP from integrated
//! Stokes vectors — not from averaged DoLPs.

use polbrdf::model::SpectralSource;
use polbrdf::optics::dispersion::{Dispersion, SpectralIndex};
use polbrdf::{Band, Contrast, Error, Geometry, Illumination, MaterialSpec, Spectrum, Stokes};
use std::sync::Arc;

fn table(wl: &[f64], v: &[f64]) -> Dispersion {
    Dispersion::Table {
        wavelengths: wl.to_vec(),
        values: v.to_vec(),
    }
}

/// A metal-like index that changes strongly with λ (tabulated n and k).
fn dispersive() -> SpectralIndex {
    let wl = [0.4, 0.5, 0.6, 0.7, 0.8, 1.0];
    SpectralIndex {
        name: "test/dispersive".into(),
        n: table(&wl, &[0.5, 0.9, 1.4, 2.0, 2.6, 3.0]),
        k: Some(table(&wl, &[4.0, 3.0, 2.2, 1.5, 1.0, 0.6])),
        references: String::new(),
        comments: String::new(),
    }
}

fn spectral_spec(index: SpectralIndex, sigma_deg: f64) -> MaterialSpec {
    let mut s = MaterialSpec::new(1.0, sigma_deg);
    s.spectral = Some(SpectralSource {
        source: "test".into(),
        index: Arc::new(index),
    });
    s
}

#[test]
fn interpolation_is_exact_at_nodes_and_linear_between() {
    let idx = dispersive();
    let wl = [0.4, 0.5, 0.6, 0.7, 0.8, 1.0];
    let n = [0.5, 0.9, 1.4, 2.0, 2.6, 3.0];
    let k = [4.0, 3.0, 2.2, 1.5, 1.0, 0.6];
    for i in 0..wl.len() {
        let at = idx.at(wl[i]).unwrap();
        assert_eq!((at.n(), at.k()), (n[i], k[i]), "node {}", wl[i]);
    }
    for i in 0..wl.len() - 1 {
        for t in [0.1, 0.25, 0.5, 0.9] {
            let l = wl[i] + t * (wl[i + 1] - wl[i]);
            let at = idx.at(l).unwrap();
            let en = n[i] + t * (n[i + 1] - n[i]);
            let ek = k[i] + t * (k[i + 1] - k[i]);
            assert!((at.n() - en).abs() < 1e-14, "n at {l}: {} vs {en}", at.n());
            assert!((at.k() - ek).abs() < 1e-14, "k at {l}: {} vs {ek}", at.k());
        }
    }
}

#[test]
fn out_of_range_names_material_and_range() {
    let idx = dispersive();
    for l in [0.39, 1.01, f64::NAN, -1.0] {
        match idx.at(l) {
            Err(e @ Error::WavelengthOutOfRange { .. }) => {
                let msg = e.to_string();
                assert!(msg.contains("test/dispersive"), "{msg}");
                assert!(msg.contains("0.4") && msg.contains('1'), "{msg}");
            }
            other => panic!("λ = {l}: {other:?}"),
        }
    }
    // k's range narrower than n's: the common range applies.
    let mut narrow = dispersive();
    narrow.k = Some(table(&[0.5, 0.8], &[1.0, 2.0]));
    assert_eq!(narrow.range(), (0.5, 0.8));
    assert!(narrow.at(0.45).is_err());
    assert!(narrow.at(0.9).is_err());
    // Through the spec: build_at and index_at refuse as well, index_columns gives the position.
    let spec = spectral_spec(dispersive(), 10.0);
    assert!(spec.build_at(2.0).is_err());
    assert!(
        spec.build().is_err(),
        "a spectral material needs a wavelength"
    );
    let (pos, _) = spec.index_columns(&[0.5, 0.6, 3.0, 0.7]).unwrap_err();
    assert_eq!(pos, 2);
}

#[test]
fn index_columns_match_index_at_with_repeats() {
    let spec = spectral_spec(dispersive(), 10.0);
    // Repeats in runs and cycles, and values that collide in the cache.
    let mut wl = Vec::new();
    for rep in 0..3 {
        for j in 0..200 {
            wl.push(0.4 + 0.003 * ((j * 7 + rep) % 200) as f64);
        }
    }
    let (n, k) = spec.index_columns(&wl).unwrap();
    for (i, &l) in wl.iter().enumerate() {
        let at = spec.index_at(l).unwrap();
        assert_eq!((n[i], k[i]), (at.n(), at.k()), "λ = {l}");
    }
}

#[test]
fn formulas_follow_the_database_definitions() {
    use polbrdf::optics::dispersion::formula;
    let l: f64 = 0.8;
    let l2 = l * l;
    // 1 Sellmeier with two terms.
    let c = [0.1, 0.6961663, 0.0684043, 0.4079426, 0.1162414];
    let e = (1.0 + 0.1 + c[1] * l2 / (l2 - c[2] * c[2]) + c[3] * l2 / (l2 - c[4] * c[4])).sqrt();
    assert!((formula(1, &c, l) - e).abs() < 1e-15);
    // 2 Sellmeier-2 (C_{i+1} not squared).
    let e = (1.0 + 0.1 + c[1] * l2 / (l2 - c[2]) + c[3] * l2 / (l2 - c[4])).sqrt();
    assert!((formula(2, &c, l) - e).abs() < 1e-15);
    // 3 polynomial: n² = C1 + C2 λ^C3 + C4 λ^C5.
    let p = [2.0, 0.1, 2.0, -0.01, -2.0];
    let e = (2.0 + 0.1 * l.powf(2.0) - 0.01 * l.powf(-2.0)).sqrt();
    assert!((formula(3, &p, l) - e).abs() < 1e-15);
    // 5 Cauchy: n = C1 + C2 λ^C3 …
    let e = 2.0 + 0.1 * l.powf(2.0) - 0.01 * l.powf(-2.0);
    assert!((formula(5, &p, l) - e).abs() < 1e-15);
    // 6 gases: n − 1 = C1 + C2/(C3 − λ⁻²).
    let g = [0.0, 0.05792105, 238.0185, 0.00167917, 57.362];
    let e = 1.0 + 0.05792105 / (238.0185 - 1.0 / l2) + 0.00167917 / (57.362 - 1.0 / l2);
    assert!((formula(6, &g, l) - e).abs() < 1e-15);
    // 7 Herzberger.
    let h = [1.5, 0.01, 0.001, -0.002, 1e-5, -1e-7];
    let d = l2 - 0.028;
    let e = 1.5 + 0.01 / d + 0.001 / (d * d) - 0.002 * l2 + 1e-5 * l2 * l2 - 1e-7 * l2 * l2 * l2;
    assert!((formula(7, &h, l) - e).abs() < 1e-15);
    // 8 retro: (n²−1)/(n²+2) = C1 + C2 λ²/(λ² − C3) + C4 λ²; check by inverting.
    let r = [0.2, 0.05, 0.01, 0.001];
    let n = formula(8, &r, l);
    let t = 0.2 + 0.05 * l2 / (l2 - 0.01) + 0.001 * l2;
    assert!(((n * n - 1.0) / (n * n + 2.0) - t).abs() < 1e-15);
    // 9 exotic.
    let x = [2.0, 0.02, 0.01, 0.1, 0.5, 0.04];
    let dd = l - 0.5;
    let e = (2.0 + 0.02 / (l2 - 0.01) + 0.1 * dd / (dd * dd + 0.04)).sqrt();
    assert!((formula(9, &x, l) - e).abs() < 1e-15);
    // 4 RefractiveIndex.INFO with the two pole terms and one power term.
    let q = [1.0, 0.5, 2.0, 0.1, 2.0, 0.3, 2.0, 3.0, 2.0, 0.01, 2.0];
    let e = (1.0 + 0.5 * l2 / (l2 - 0.01) + 0.3 * l2 / (l2 - 9.0) + 0.01 * l2).sqrt();
    assert!((formula(4, &q, l) - e).abs() < 1e-15);
    // Unknown formula: NaN, which the index refuses.
    assert!(formula(10, &c, l).is_nan());
}

fn triangle() -> Band {
    Band::new("tri", vec![0.45, 0.55, 0.65], vec![0.0, 1.0, 0.0]).unwrap()
}

#[test]
fn band_quadrature_is_exact_for_low_degree() {
    // ∫ R(λ)·λ^p dλ for the triangle R, analytic, for p = 0 … 3 (R·λ^p is of degree ≤ 4 on
    // each piece: the 3-point Gauss rule is exact).
    let b = triangle();
    for step in [0.1, 0.02, 0.0071] {
        let nodes = b.nodes(step, &[]);
        for p in 0..4 {
            let got: f64 = nodes.iter().map(|(l, w)| w * l.powi(p)).sum();
            // Exact: ∫ over both legs of a linear ramp times λ^p, by a fine composite Simpson.
            let m = 20000;
            let h = 0.2 / m as f64;
            let mut exact = 0.0;
            for i in 0..=m {
                let l = 0.45 + i as f64 * h;
                let c = if i == 0 || i == m {
                    1.0
                } else if i % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                exact += c * b.response(l) * l.powi(p);
            }
            exact *= h / 3.0;
            assert!(
                (got - exact).abs() < 1e-12 * exact.abs(),
                "p = {p}, step {step}: {got} vs {exact}"
            );
        }
    }
    assert!((b.default_step() - 0.2 / 16.0).abs() < 1e-15);
    assert_eq!(b.range(), (0.45, 0.65));
    assert!((b.response(0.5) - 0.5).abs() < 1e-15);
    assert_eq!(b.response(0.7), 0.0);
}

#[test]
fn band_validation_names_the_element() {
    for (wl, r, needle) in [
        (vec![0.5], vec![1.0], "at least two"),
        (vec![0.5, 0.5], vec![1.0, 1.0], "increase strictly"),
        (vec![0.5, -0.6], vec![1.0, 1.0], "> 0"),
        (vec![0.5, 0.6], vec![1.0, -1.0], ">= 0"),
        (vec![0.5, 0.6], vec![f64::NAN, 1.0], ">= 0"),
        (vec![0.5, 0.6], vec![0.0, 0.0], "zero everywhere"),
        (vec![0.5, 0.6], vec![1.0], "response"),
    ] {
        let e = Band::new("b", wl.clone(), r.clone())
            .unwrap_err()
            .to_string();
        assert!(e.contains(needle), "{wl:?} {r:?}: {e}");
    }
}

/// Issue 35: a band's rows are bounded by the work they imply (`MAX_BAND_ROWS`, each a panel
/// edge of the quadrature): 10⁴ rows make a band, one more is an error at that row.
#[test]
fn a_band_has_at_most_max_band_rows_rows() {
    use polbrdf::analysis::spectral::MAX_BAND_ROWS;
    let wl = |n: usize| (0..n).map(|k| 8.0 + k as f64 * 1e-4).collect::<Vec<f64>>();
    let band = Band::new("b", wl(MAX_BAND_ROWS), vec![1.0; MAX_BAND_ROWS]).unwrap();
    assert_eq!(band.table().0.len(), MAX_BAND_ROWS);
    match Band::new("b", wl(MAX_BAND_ROWS + 1), vec![1.0; MAX_BAND_ROWS + 1]).unwrap_err() {
        Error::InvalidParameterAt { name, index, .. } => {
            assert_eq!((name, index), ("wavelength_um", MAX_BAND_ROWS));
        }
        other => panic!("{other:?}"),
    }
}

fn light() -> Illumination {
    Illumination::from_degrees(50.0, 0.0, Stokes::unpolarized()).unwrap()
}

#[test]
fn constant_spectrum_band_equals_single_wavelength() {
    // A constant index: the band mean of the reflected Stokes vector equals the single-λ one.
    let target = polbrdf::preset("paint").unwrap();
    let background = polbrdf::preset("aluminium").unwrap();
    let single = Contrast::new(
        &target.build().unwrap(),
        &background.build().unwrap(),
        light(),
    );
    let band = Spectrum::Band(triangle(), None);
    let nodes = band.mean_nodes(&[&target, &background]);
    assert!(nodes.len() > 10);
    let tm = Spectrum::materials(&target, &nodes).unwrap();
    let bm = Spectrum::materials(&background, &nodes).unwrap();
    let spectral = Contrast::spectral(
        nodes
            .iter()
            .zip(tm.into_iter().zip(bm))
            .map(|((_, w), (t, b))| (*w, t, b))
            .collect(),
        light(),
    );
    for (t, p) in [(0.2, 3.0), (0.87, 3.1), (1.2, 1.0), (0.0, 0.0)] {
        let a = single.at(t, p);
        let b = spectral.at(t, p);
        for i in 0..4 {
            for (x, y) in [
                (a.target.0[i], b.target.0[i]),
                (a.background.0[i], b.background.0[i]),
            ] {
                assert!(
                    (x - y).abs() <= 1e-14 * x.abs().max(1e-300),
                    "S{i}: {x} vs {y}"
                );
            }
        }
        assert!((a.polarization_contrast() - b.polarization_contrast()).abs() < 1e-13);
    }
}

#[test]
fn band_dolp_comes_from_integrated_stokes() {
    // A strongly dispersive smooth metal seen near its Brewster-like angle: the DoLP changes
    // across the band, so the DoLP of the band-mean Stokes vector differs from the mean DoLP.
    let spec = spectral_spec(dispersive(), 4.0);
    let band = Band::new("vis", vec![0.4, 1.0], vec![1.0, 1.0]).unwrap();
    let sp = Spectrum::Band(band, None);
    let nodes = sp.mean_nodes(&[&spec]);
    let ms = Spectrum::materials(&spec, &nodes).unwrap();
    let g = Geometry::from_degrees(70.0, 0.0, 70.0, 180.0).unwrap();
    let s_in = Stokes::unpolarized();
    let mut s = Stokes([0.0; 4]);
    let mut mean_dolp = 0.0;
    for ((_, w), m) in nodes.iter().zip(&ms) {
        let out = m.pbrdf(&g).apply(&s_in);
        s = s.combine(1.0, &out, *w);
        mean_dolp += w * out.dolp();
    }
    let band_dolp = s.dolp();
    assert!(
        (band_dolp - mean_dolp).abs() > 1e-3,
        "the test needs a case where they differ: {band_dolp} vs {mean_dolp}"
    );
    // The library's band contrast reports the DoLP of the integrated Stokes vector.
    let c = Contrast::spectral(
        nodes
            .iter()
            .zip(&ms)
            .map(|((_, w), m)| (*w, m.clone(), m.clone()))
            .collect(),
        Illumination::from_degrees(70.0, 0.0, s_in).unwrap(),
    );
    let sample = c.at(70f64.to_radians(), std::f64::consts::PI);
    assert!((sample.target.dolp() - band_dolp).abs() < 1e-12);
    assert!((sample.dolp_target() - band_dolp).abs() < 1e-12);
}

#[test]
fn band_quadrature_converges_for_a_tabulated_index() {
    // Panel edges at the table's nodes: the default step agrees with one 8× finer.
    let spec = spectral_spec(dispersive(), 6.0);
    let band = Band::new("b", vec![0.42, 0.6, 0.95], vec![0.3, 1.0, 0.2]).unwrap();
    let g = Geometry::from_degrees(40.0, 0.0, 35.0, 170.0).unwrap();
    let mean = |step: Option<f64>| {
        let sp = Spectrum::Band(band.clone(), step);
        let nodes = sp.mean_nodes(&[&spec]);
        let ms = Spectrum::materials(&spec, &nodes).unwrap();
        let mut s = Stokes([0.0; 4]);
        for ((_, w), m) in nodes.iter().zip(&ms) {
            s = s.combine(1.0, &m.pbrdf(&g).apply(&Stokes::unpolarized()), *w);
        }
        s
    };
    let coarse = mean(None);
    let fine = mean(Some(band.default_step() / 8.0));
    for i in 0..3 {
        let (a, b) = (coarse.0[i], fine.0[i]);
        assert!((a - b).abs() <= 1e-9 * fine.0[0], "S{i}: {a} vs {b}");
    }
}
