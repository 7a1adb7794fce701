//! The tables of a detection study, built once here for every adapter: `detect.csv` (one row
//! per view and range), `best.json` (the views ranked by detection range) and the per-view
//! arrays of the maps.

use super::study::{DetectStudy, RangeUncertainty, ViewResult};
use crate::fit_covariance::FitCovariance;
use crate::hemisphere::deg;
use polbrdf::analysis::detection::{estimate, Detection, MaxRange, NoiseModel, Path};
use polbrdf_io::sensor::Model;
use serde_json::{json, Value};

/// The columns of `detect.csv`: the numeric ones ([`NUMERIC`] of them, the values of a
/// [`DetectRow`]), then `feature`, `saturated`, `max_range_m`, `max_range_feature` and the
/// detection range's uncertainty (empty where none was computed).
pub const COLUMNS: [&str; 18] = [
    "theta_r_deg",
    "phi_r_deg",
    "range_m",
    "pixels_on_target",
    "snr_s0",
    "snr_dolp",
    "snr_combined",
    "polarization_contrast",
    "snr_polarization_contrast",
    "d_prime",
    "pd",
    "feature",
    "saturated",
    "max_range_m",
    "max_range_feature",
    "max_range_sigma_m",
    "max_range_lo95_m",
    "max_range_hi95_m",
];

/// How many of [`COLUMNS`] lead as numbers (`theta_r_deg` … `pd`).
pub const NUMERIC: usize = 11;

/// The columns of the detection range's uncertainty, the last of [`COLUMNS`].
pub const UNCERTAINTY_COLUMNS: [&str; 3] =
    ["max_range_sigma_m", "max_range_lo95_m", "max_range_hi95_m"];

/// `σ_R` and the 95 % interval of a view's range, NaN where there is none.
pub fn uncertainty_values(u: Option<RangeUncertainty>) -> [f64; 3] {
    match u {
        Some(RangeUncertainty::Interval {
            sigma_m,
            lo_m,
            hi_m,
        }) => [sigma_m, lo_m, hi_m],
        _ => [f64::NAN; 3],
    }
}

/// `"beyond"`, `"not detectable"`, or the range.
pub fn max_range_text(m: Option<MaxRange>) -> String {
    match m {
        None => String::new(),
        Some(MaxRange::Beyond) => "beyond".into(),
        Some(MaxRange::NotDetectable) => "not detectable".into(),
        Some(MaxRange::At { range_m, .. }) => polbrdf_io::csv_io::fmt_f64(range_m),
    }
}

/// The detection range as a number: the range, `+∞` beyond the limit, NaN when not
/// detectable or not searched (for arrays and maps).
pub fn max_range_value(m: Option<MaxRange>) -> f64 {
    match m {
        Some(MaxRange::At { range_m, .. }) => range_m,
        Some(MaxRange::Beyond) => f64::INFINITY,
        _ => f64::NAN,
    }
}

/// The polarization contrast between the two estimates and its SNR (NaN where undefined).
fn polarization_contrast(d: &Detection) -> (f64, f64) {
    estimate::polarization_contrast(&d.target, &d.background).map_or((f64::NAN, f64::NAN), |m| {
        (m.mean, m.mean / m.variance.sqrt())
    })
}

/// The indices of `views` ranked by detection range: beyond the limit first, then by range,
/// largest first, then the views not detectable; ties in view order.
pub fn ranked_order(views: &[ViewResult]) -> Vec<usize> {
    let key = |v: &ViewResult| match v.max_range {
        Some(MaxRange::Beyond) => f64::INFINITY,
        Some(MaxRange::At { range_m, .. }) => range_m,
        _ => f64::NEG_INFINITY,
    };
    let mut order: Vec<usize> = (0..views.len()).collect();
    order.sort_by(|a, b| key(&views[*b]).total_cmp(&key(&views[*a])));
    order
}

fn num(v: f64) -> Value {
    serde_json::Number::from_f64(v + 0.0).map_or(Value::Null, Value::Number)
}

/// One row of `detect.csv` (a view at a range), as values: what [`DetectStudy::csv`] prints and
/// the adapters hand over as arrays.
#[derive(Debug, Clone, PartialEq)]
pub struct DetectRow {
    /// The numeric columns of [`COLUMNS`] up to `pd`, in their order ([`NUMERIC`] values).
    pub values: [f64; NUMERIC],
    /// The feature of this row's `d'` (`feature`).
    pub feature: &'static str,
    /// Whether a channel saturated (`saturated`).
    pub saturated: bool,
    /// The view's detection range ([`max_range_text`]: a number, `"beyond"`, `"not
    /// detectable"`, or empty when not searched).
    pub max_range: Option<MaxRange>,
    /// The feature detecting at the view's detection range (empty when none).
    pub max_range_feature: &'static str,
    /// The view's `σ_R` and 95 % interval ([`UNCERTAINTY_COLUMNS`]; NaN where none).
    pub uncertainty: [f64; 3],
}

impl DetectStudy {
    /// The rows of `detect.csv`: one per view and range, view-major.
    pub fn table_rows(&self) -> impl Iterator<Item = DetectRow> + '_ {
        self.views.iter().flat_map(|v| {
            v.at_ranges.iter().map(move |d| {
                let (pc, snr_pc) = polarization_contrast(d);
                DetectRow {
                    values: [
                        deg(v.theta_r),
                        deg(v.phi_r),
                        d.range_m,
                        d.pixels,
                        d.scores.s0,
                        d.scores.dolp,
                        d.scores.combined,
                        pc,
                        snr_pc,
                        d.d_prime_n,
                        d.pd,
                    ],
                    feature: d.feature.as_str(),
                    saturated: d.saturated,
                    max_range: v.max_range,
                    max_range_feature: match v.max_range {
                        Some(MaxRange::At { feature, .. }) => feature.as_str(),
                        _ => "",
                    },
                    uncertainty: uncertainty_values(v.range_uncertainty),
                }
            })
        })
    }

    /// `detect.csv`: one row per view and range, the values of [`COLUMNS`] (docs/detection.md).
    pub fn csv(&self) -> Vec<u8> {
        let f = polbrdf_io::csv_io::fmt_f64;
        let mut t = polbrdf_io::CsvTable::new(COLUMNS);
        for r in self.table_rows() {
            let mut fields: Vec<String> = r.values.iter().map(|x| f(*x)).collect();
            fields.extend([
                r.feature.to_string(),
                u8::from(r.saturated).to_string(),
                max_range_text(r.max_range),
                r.max_range_feature.to_string(),
            ]);
            fields.extend(
                r.uncertainty
                    .iter()
                    .map(|x| if x.is_nan() { String::new() } else { f(*x) }),
            );
            t.fields(fields);
        }
        t.into_bytes()
    }

    /// The views ranked by detection range: beyond the limit first, then by range, largest
    /// first, then the views not detectable; ties in view order.
    pub fn ranked(&self) -> Vec<&ViewResult> {
        ranked_order(&self.views)
            .into_iter()
            .map(|i| &self.views[i])
            .collect()
    }

    /// The path as JSON.
    fn path_json(&self) -> Value {
        let scene_path = self.scene.air_path.as_ref().map(|p| format!("{p:?}"));
        match &self.detector.path {
            Path::Homogeneous {
                extinction_per_m,
                horizon_radiance,
            } => json!({"kind": "homogeneous", "extinction_per_m": num(*extinction_per_m),
                "horizon_radiance_band": num(*horizon_radiance), "given": scene_path}),
            Path::Table(t) => json!({"kind": "table", "rows": t.rows().count(),
                "max_range_m": num(self.detector.path.max_range().unwrap_or(f64::NAN))}),
        }
    }

    /// `best.json`: the setup, and every view ranked by detection range with `max_range_m`
    /// (a number, `"beyond"` or `"not detectable"`) and the detecting feature.
    pub fn best_json(&self) -> Value {
        let mut saturated_views = 0;
        let mut entry = |v: &ViewResult| {
            let (range, feature) = match v.max_range {
                Some(MaxRange::At { range_m, feature }) => (num(range_m), json!(feature.as_str())),
                other => (json!(max_range_text(other)), Value::Null),
            };
            let saturated = self.view_saturated(v);
            saturated_views += usize::from(saturated);
            let mut e = json!({"theta_r_deg": num(deg(v.theta_r)), "phi_r_deg": num(deg(v.phi_r)),
                   "max_range_m": range, "feature": feature, "saturated": saturated});
            if self.fits.iter().any(Option::is_some) {
                let [sigma, lo, hi] = uncertainty_values(v.range_uncertainty);
                e["max_range_sigma_m"] = num(sigma);
                e["max_range_95_m"] = if sigma.is_nan() {
                    Value::Null
                } else {
                    json!([num(lo), num(hi)])
                };
                e["uncertainty"] = json!(match v.range_uncertainty {
                    Some(RangeUncertainty::Interval { .. }) => "interval",
                    Some(RangeUncertainty::Undefined) => "undefined",
                    None if matches!(v.max_range, Some(MaxRange::At { .. })) => "not computed",
                    None => "no range",
                });
            }
            e
        };
        let ranked: Vec<Value> = self.ranked().into_iter().map(&mut entry).collect();
        let c = &self.detector.criteria;
        let noise = match self.detector.sensor.noise {
            NoiseModel::PhotonCounting(p) => json!({"model": Model::Photon.name(),
                "electrons_per_radiance": num(p.electrons_per_radiance()),
                "gain_e_per_count": num(p.gain_e_per_count)}),
            NoiseModel::Nel { nel } => json!({"model": Model::Nel.name(), "nel": num(nel)}),
        };
        json!({
            "best": ranked.first().cloned(),
            "views": ranked,
            "scene": self.scene.path.display().to_string(),
            "sensor": {"file": self.sensor.path.display().to_string(),
                       "name": self.sensor.spec.name, "noise": noise,
                       "ifov_rad": num(self.detector.sensor.ifov_rad),
                       "frames": self.detector.sensor.frames},
            "target": self.target.name,
            "background": self.background.name,
            "path": self.path_json(),
            "criteria": {"pfa": num(c.pfa), "pd": num(c.pd_required),
                         "required_d_prime": num(c.required_d_prime()),
                         "range_limit_m": num(c.range_limit_m),
                         "area_m2": num(self.detector.area_m2),
                         "features": c.features.iter().map(|f| f.as_str()).collect::<Vec<_>>()},
            "ranges_m": self.ranges_m.iter().map(|r| num(*r)).collect::<Vec<_>>(),
            "uncertainty": self.uncertainty_json(),
            "saturated_views": saturated_views,
            "warnings": self.warnings.iter().map(ToString::to_string).collect::<Vec<_>>(),
        })
    }

    /// `best.json`'s `uncertainty`: the fits, the confidence and `z`, the views given an
    /// interval; `null` without fits.
    fn uncertainty_json(&self) -> Value {
        if self.fits.iter().all(Option::is_none) {
            return Value::Null;
        }
        let fit = |f: &Option<FitCovariance>| {
            f.as_ref().map(|f| {
                json!({"source": f.source.display().to_string(),
                       "parameters": f.params.iter().map(|p| p.name()).collect::<Vec<_>>(),
                       "values": f.values.iter().map(|v| num(*v)).collect::<Vec<_>>(),
                       "sigmas": f.sigmas().into_iter().map(num).collect::<Vec<_>>(),
                       "held_fixed": f.held_fixed.iter().map(|(p, _)| p.name()).collect::<Vec<_>>()})
            })
        };
        json!({
            "method": "linear propagation, central differences (step σ/10), block-diagonal \
                       joint covariance of the two fits",
            "confidence": num(super::uncertainty::CONFIDENCE),
            "z": num(super::uncertainty::z()),
            "target_fit": fit(&self.fits[0]),
            "background_fit": fit(&self.fits[1]),
            "views": self.uncertainty_views.map_or(json!("all"), |n| json!(n)),
        })
    }

    /// Per view: the detection range ([`max_range_value`]).
    pub fn max_ranges(&self) -> Vec<f64> {
        self.views
            .iter()
            .map(|v| max_range_value(v.max_range))
            .collect()
    }

    /// Per view: `P_d` at the `k`-th row range.
    pub fn pd_at(&self, k: usize) -> Vec<f64> {
        self.views
            .iter()
            .map(|v| v.at_ranges.get(k).map_or(f64::NAN, |d| d.pd))
            .collect()
    }
}
