//! A material as the user writes it (the keys of a material file) and its validation
//! (docs/model.md §8).

use crate::error::{non_negative, Error, Result};
use crate::model::distribution::Distribution;
use crate::model::material::{Material, ModelParams};
use crate::model::shadowing::{AzimuthTerm, Shadowing};
use crate::model::terms::Form;
use crate::optics::fresnel::RefractiveIndex;

/// The keys of a material file, in the order files are written (the one list every reader and
/// writer of materials uses: the TOML reader and writer, the Python `Material`; the fit's
/// parameters are a subset). [`MaterialSpec::get`] and [`MaterialSpec::set`] read and write
/// them by name.
pub const KEYS: &[&str] = &[
    "name",
    "n",
    "k",
    "sigma_deg",
    "b",
    "a",
    "form",
    "shadowing",
    "tau_deg",
    "omega_deg",
    "azimuth_term",
    "rho_d",
    "rho_v",
];

/// A material as the user writes it: the keys of a material file, in their units (degrees for
/// angles). [`MaterialSpec::build`] validates it into a [`Material`].
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialSpec {
    /// Optional display name.
    pub name: Option<String>,
    /// Real part of the refractive index (> 0).
    pub n: f64,
    /// Extinction coefficient (≥ 0; default 0).
    pub k: f64,
    /// Roughness angle σ in degrees (`b = 1/σ²`, σ in rad). Exactly one of `sigma_deg`, `b`.
    pub sigma_deg: Option<f64>,
    /// Width parameter of D in rad⁻². Exactly one of `sigma_deg`, `b`.
    pub b: Option<f64>,
    /// Amplitude of D in sr⁻¹; `None` = hemispherical normalization (default).
    pub a: Option<f64>,
    /// Surface-term form (default `standard`).
    pub form: Form,
    /// Whether SO (eq. 3) is applied (default true).
    pub shadowing: bool,
    /// τ of eq. 3 in degrees (default 15).
    pub tau_deg: f64,
    /// Ω of eq. 3 in degrees (default 40).
    pub omega_deg: f64,
    /// Azimuth factor of eq. 3 (default none).
    pub azimuth_term: AzimuthTerm,
    /// Lambertian volume constant ρ_D of eq. 1, sr⁻¹ (default 0).
    pub rho_d: f64,
    /// Non-Lambertian volume constant ρ_V of eq. 1, sr⁻¹ (default 0).
    pub rho_v: f64,
}

impl MaterialSpec {
    /// A spec with index `n`, roughness `sigma_deg`, and every other key at its default.
    pub fn new(n: f64, sigma_deg: f64) -> Self {
        Self {
            name: None,
            n,
            k: 0.0,
            sigma_deg: Some(sigma_deg),
            b: None,
            a: None,
            form: Form::Standard,
            shadowing: true,
            tau_deg: 15.0,
            omega_deg: 40.0,
            azimuth_term: AzimuthTerm::None,
            rho_d: 0.0,
            rho_v: 0.0,
        }
    }

    /// Validates every key and derives the model's quantities.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the key and its value, or
    /// [`Error::InconsistentParameters`] when `sigma_deg` and `b` are both or neither given.
    pub fn build(&self) -> Result<Material> {
        let index = RefractiveIndex::new(self.n, self.k)?;
        let b = match (self.sigma_deg, self.b) {
            (Some(s), None) => {
                let sigma = crate::error::positive("sigma_deg", s)?.to_radians();
                let b = 1.0 / (sigma * sigma);
                if !(b > 0.0 && b <= crate::error::MAX_MAGNITUDE) {
                    return Err(Error::InvalidParameter {
                        name: "sigma_deg",
                        value: s,
                        reason: "out of range: b = 1/σ² must lie in (0, 1e100]",
                    });
                }
                b
            }
            (None, Some(b)) => crate::model::distribution::checked_b("b", b)?,
            (Some(_), Some(_)) => {
                return Err(Error::InconsistentParameters(
                    "give exactly one of `sigma_deg` and `b`, not both".into(),
                ))
            }
            (None, None) => {
                return Err(Error::InconsistentParameters(
                    "missing roughness: give one of `sigma_deg` or `b`".into(),
                ))
            }
        };
        let distribution = match self.a {
            Some(a) => Distribution::new(a, b)?,
            None => Distribution::normalized(b)?,
        };
        let tau = crate::error::positive("tau_deg", self.tau_deg)?.to_radians();
        let omega = crate::error::positive("omega_deg", self.omega_deg)?.to_radians();
        let shadowing = Shadowing::new(tau, omega, self.azimuth_term)?;
        let params = ModelParams {
            distribution,
            shadowing: self.shadowing.then_some(shadowing),
            form: self.form,
            rho_d: rho("rho_d", self.rho_d)?,
            rho_v: rho("rho_v", self.rho_v)?,
        };
        Ok(Material::from_parts(self.clone(), index, params))
    }
}

/// `0 ≤ ρ ≤ 10¹⁰⁰`.
fn rho(name: &'static str, v: f64) -> Result<f64> {
    crate::error::at_most(
        name,
        non_negative(name, v)?,
        crate::error::MAX_MAGNITUDE,
        "must be ≤ 1e100 (larger values overflow the BRDF near the horizon)",
    )
}

/// The value of one key of a material file ([`KEYS`]).
#[derive(Debug, Clone, PartialEq)]
pub enum KeyValue {
    /// A number.
    Number(f64),
    /// A string (the name, or an enumeration such as `form`).
    Text(String),
    /// `true` or `false`.
    Bool(bool),
}

impl KeyValue {
    /// What kind of value it is, for messages: `number`, `string`, `boolean`.
    pub fn kind(&self) -> &'static str {
        match self {
            KeyValue::Number(_) => "number",
            KeyValue::Text(_) => "string",
            KeyValue::Bool(_) => "boolean",
        }
    }
}

impl MaterialSpec {
    /// The value of key `key` ([`KEYS`]), `None` when it is an unset optional key (`name`,
    /// `sigma_deg`, `b`, `a`) or not a key.
    pub fn get(&self, key: &str) -> Option<KeyValue> {
        use KeyValue::{Bool, Number, Text};
        Some(match key {
            "name" => Text(self.name.clone()?),
            "n" => Number(self.n),
            "k" => Number(self.k),
            "sigma_deg" => Number(self.sigma_deg?),
            "b" => Number(self.b?),
            "a" => Number(self.a?),
            "form" => Text(self.form.as_str().into()),
            "shadowing" => Bool(self.shadowing),
            "tau_deg" => Number(self.tau_deg),
            "omega_deg" => Number(self.omega_deg),
            "azimuth_term" => Text(self.azimuth_term.as_str().into()),
            "rho_d" => Number(self.rho_d),
            "rho_v" => Number(self.rho_v),
            _ => return None,
        })
    }

    /// Every key that has a value, in [`KEYS`] order.
    pub fn entries(&self) -> Vec<(&'static str, KeyValue)> {
        KEYS.iter()
            .filter_map(|k| self.get(k).map(|v| (*k, v)))
            .collect()
    }

    /// Sets key `key` to `value`. The value is checked for its type and, for `form` and
    /// `azimuth_term`, its spelling; the numbers are checked by [`MaterialSpec::build`].
    ///
    /// # Errors
    /// What is wrong, in words (the caller adds where: file, line, key): an unknown key, a value
    /// of the wrong kind, an unknown enumeration value.
    pub fn set(&mut self, key: &str, value: KeyValue) -> std::result::Result<(), String> {
        match (key, &value) {
            ("name", KeyValue::Text(t)) => self.name = Some(t.clone()),
            ("n", KeyValue::Number(x)) => self.n = *x,
            ("k", KeyValue::Number(x)) => self.k = *x,
            ("sigma_deg", KeyValue::Number(x)) => self.sigma_deg = Some(*x),
            ("b", KeyValue::Number(x)) => self.b = Some(*x),
            ("a", KeyValue::Number(x)) => self.a = Some(*x),
            ("form", KeyValue::Text(t)) => self.form = t.parse::<Form>()?,
            ("shadowing", KeyValue::Bool(b)) => self.shadowing = *b,
            ("tau_deg", KeyValue::Number(x)) => self.tau_deg = *x,
            ("omega_deg", KeyValue::Number(x)) => self.omega_deg = *x,
            ("azimuth_term", KeyValue::Text(t)) => self.azimuth_term = t.parse::<AzimuthTerm>()?,
            ("rho_d", KeyValue::Number(x)) => self.rho_d = *x,
            ("rho_v", KeyValue::Number(x)) => self.rho_v = *x,
            (k, v) => {
                return Err(match expected(k) {
                    Some(want) => format!("expected {want}, got {}", v.kind()),
                    None => format!("unknown key `{k}` (known keys: {})", KEYS.join(", ")),
                })
            }
        }
        Ok(())
    }
}

/// What kind of value key `key` takes, in words (`a number`, `a string`, `true or false`);
/// `None` for an unknown key.
pub fn expected(key: &str) -> Option<&'static str> {
    match key {
        "name" | "form" | "azimuth_term" => Some("a string"),
        "shadowing" => Some("true or false"),
        k if KEYS.contains(&k) => Some("a number"),
        _ => None,
    }
}
