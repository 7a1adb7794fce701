//! The `best.json` document of a contrast study, built once here for every adapter (the CLI
//! writes it; Python can return the same dictionary).

use crate::contrast::{row, ContrastStudy, NullLoci, Setting, COLUMNS};
use crate::hemisphere::deg;
use crate::spectrum::spectrum_json;
use polbrdf::analysis::contrast::{ContrastSample, Illumination};
use polbrdf::analysis::SkyModel;
use polbrdf::Spectrum;
use polbrdf_io::scene::SkyKind;
use polbrdf_io::Scene;
use serde_json::{json, Value};

impl ContrastStudy {
    /// The `best.json` document (described in the README): the best direction and the listed
    /// ones, the ranking, materials, grid, and the source or the scene with its null loci.
    pub fn best_json(&self) -> Value {
        best_json(self)
    }
}

/// A number for JSON: `null` when not finite (e.g. an infinite intensity ratio).
fn num(v: f64) -> Value {
    serde_json::Number::from_f64(v + 0.0).map_or(Value::Null, Value::Number)
}

/// The source and the spectrum of a collimated study.
fn collimated_json(
    light: &Illumination,
    spectrum: Option<&Spectrum>,
    nodes: usize,
) -> (Value, Value) {
    (
        json!({
            "sun_zenith_deg": num(light.theta_i().to_degrees()),
            "sun_azimuth_deg": num(light.phi_i().to_degrees()),
            "stokes_normalized": light.stokes().0.iter().map(|v| num(*v)).collect::<Vec<_>>(),
        }),
        spectrum_json(spectrum, nodes),
    )
}

/// One direction: the values of [`COLUMNS`] by name.
fn entry(s: &ContrastSample) -> Value {
    let mut m = serde_json::Map::new();
    for (k, v) in COLUMNS.iter().zip(row(s)) {
        m.insert((*k).to_string(), num(v));
    }
    Value::Object(m)
}

/// The document (see [`ContrastStudy::best_json`]).
fn best_json(study: &ContrastStudy) -> Value {
    // As `Contrast::is_azimuth_independent`: a scene without a sun, under a sky that is the
    // same at every azimuth.
    let azimuth_independent =
        matches!(&study.setting, Setting::Scene(s) if s.thermal.is_azimuth_independent());
    let grid = &study.map.grid;
    let mut doc = json!({
        "best": study.top.first().map(entry),
        "top": study.top.iter().map(entry).collect::<Vec<_>>(),
        "ranking": {
            "by": study.options.by.as_str(),
            "min_separation_deg": num(study.rank.min_separation_deg),
            "max_zenith_deg": num(study.rank.max_zenith_deg),
            "refined": study.options.refine,
            "azimuth_independent": azimuth_independent,
        },
        "target": {"material": study.target.source, "name": study.target.name},
        "background": {"material": study.background.source, "name": study.background.name},
        "grid": {
            "theta_step_deg": num(deg(grid.theta_step())),
            "phi_step_deg": num(deg(grid.phi_step())),
            "directions": grid.len(),
        },
    });
    match &study.setting {
        Setting::Collimated {
            light,
            spectrum,
            nodes,
        } => {
            let (illumination, spectrum) = collimated_json(light, spectrum.as_ref(), *nodes);
            doc["illumination"] = illumination;
            doc["spectrum"] = spectrum;
        }
        Setting::Scene(s) => scene_json(&mut doc, s, study.nulls.as_ref(), azimuth_independent),
    }
    doc
}

/// The scene's part of the document: `scene`, `spectrum` and `polarization_null`.
fn scene_json(doc: &mut Value, s: &Scene, nulls: Option<&NullLoci>, azimuth_independent: bool) {
    let nodes = s.spectrum.integral_nodes(&[]).len();
    let locus = |v: &[(f64, f64)]| -> Vec<Value> {
        v.iter()
            .map(|(t, p)| json!([num(deg(*t)), num(deg(*p))]))
            .collect()
    };
    doc["scene"] = json!({
        "file": s.path.display().to_string(),
        "target_temperature_k": s.target.temperature_k,
        "background_temperature_k": s.background.temperature_k,
        "sky": sky_json(&s.thermal.sky),
        "transmittance": num(s.thermal.atmosphere.transmittance),
        "path_radiance": num(s.thermal.atmosphere.path_radiance),
        "units": crate::scene::radiance_units(&s.spectrum),
    });
    doc["spectrum"] = spectrum_json(Some(&s.spectrum), nodes);
    if matches!(s.spectrum, Spectrum::Band(..)) {
        doc["spectrum"]["integrated"] =
            json!("Stokes radiance, integral of response × radiance over the band");
    }
    if let Some(n) = nulls {
        doc["polarization_null"] = json!({
            "what": if azimuth_independent {
                "view directions (theta_r_deg, phi_r_deg) where S1 changes sign: the emitted and reflected polarizations cancel"
            } else {
                "none computed: with a sun or an azimuth-dependent sky S2 does not vanish, and an S1 sign change is the AoLP turning through ±45°, not a null"
            },
            "target": locus(&n.target),
            "background": locus(&n.background),
            "uniform_sky_null_temperature_k": n.uniform_sky_temperature_k.map(num),
        });
    }
}

/// A scene's sky as JSON: its model and its parameters, as the scene file names them.
pub fn sky_json(sky: &SkyModel) -> Value {
    let mut v = match sky {
        SkyModel::None => json!({}),
        SkyModel::Uniform { radiance } => json!({"radiance": num(*radiance)}),
        SkyModel::Thermal { temperature_k } => json!({"temperature_k": num(*temperature_k)}),
        SkyModel::Profile(p) => {
            let (z, l) = p.table();
            json!({"zenith_deg": z, "radiance": l})
        }
        SkyModel::ClearSky {
            irradiance,
            dop_max,
        } => json!({"irradiance": num(*irradiance), "dop_max": num(*dop_max)}),
        SkyModel::Table(t) => {
            let (z, p) = t.grid();
            json!({"theta_deg": z, "phi_deg": p})
        }
    };
    // The model's name first (the scene file's, `polbrdf_io::scene::SkyKind::name`).
    let mut out = serde_json::Map::new();
    out.insert("model".into(), json!(SkyKind::of(sky).name()));
    out.append(v.as_object_mut().expect("an object"));
    Value::Object(out)
}
