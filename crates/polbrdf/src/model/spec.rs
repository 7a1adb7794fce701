//! A material as the user writes it (the keys of a material file) and its validation
//! (docs/model.md §8).

use crate::error::{Error, Result};
use crate::model::shadowing::AzimuthTerm;
use crate::model::terms::Form;
use crate::optics::dispersion::SpectralIndex;
use crate::optics::fresnel::RefractiveIndex;
use std::sync::Arc;

/// The keys of a material file, in the order files are written (the one list every reader and
/// writer of materials uses: the TOML reader and writer, the Python `Material`; the fit's
/// parameters are a subset). [`MaterialSpec::get`] and [`MaterialSpec::set`] read and write
/// them by name.
pub const KEYS: &[&str] = &[
    "name",
    "n",
    "k",
    "index",
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
/// angles). [`MaterialSpec::build`] validates it into a [`Material`](crate::Material).
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
    /// A spectral index `N(λ)` instead of the constant `n`, `k` (key `index`): then `n` and `k`
    /// are not used, and the material is built at a wavelength ([`MaterialSpec::build_at`]).
    pub spectral: Option<SpectralSource>,
}

/// A spectral index and where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectralSource {
    /// As written in the material file: `library:<id>` or a path.
    pub source: String,
    /// The data.
    pub index: Arc<SpectralIndex>,
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
            spectral: None,
        }
    }

    /// True when the index is spectral (`index = …`).
    pub fn is_spectral(&self) -> bool {
        self.spectral.is_some()
    }

    /// The complex index at `lambda_um` (µm): the spectral index there, or the constant one
    /// (whatever λ).
    ///
    /// # Errors
    /// [`Error::WavelengthOutOfRange`] outside a spectral index's data; [`Error::InvalidParameter`]
    /// for an invalid `n`, `k` or λ.
    pub fn index_at(&self, lambda_um: f64) -> Result<RefractiveIndex> {
        crate::error::positive("wavelength_um", lambda_um)?;
        match &self.spectral {
            Some(s) => s.index.at(lambda_um),
            None => RefractiveIndex::new(self.n, self.k),
        }
    }

    /// The index at each wavelength of `wavelengths_um` (µm) as two columns `(n, k)` for the
    /// engine's per-element index ([`crate::engine::IndexColumns`]). The same wavelength is
    /// looked up once: a direct-mapped cache of recent wavelengths makes repeated ones (a
    /// broadcast `materials × wavelengths × geometries` grid) cost a comparison instead of a
    /// search of the data.
    ///
    /// # Errors
    /// `(position, error)` of the first wavelength that [`MaterialSpec::index_at`] refuses.
    pub fn index_columns(
        &self,
        wavelengths_um: &[f64],
    ) -> std::result::Result<(Vec<f64>, Vec<f64>), (usize, Error)> {
        const SLOTS: usize = 64;
        let mut cache = [(f64::NAN, 0.0, 0.0); SLOTS];
        let (mut n, mut k) = (
            Vec::with_capacity(wavelengths_um.len()),
            Vec::with_capacity(wavelengths_um.len()),
        );
        for (i, &l) in wavelengths_um.iter().enumerate() {
            // Fibonacci hashing of the bits; NaN never equals a key, so it is always looked up
            // (and refused).
            let slot = (l.to_bits().wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 58) as usize;
            let (key, cn, ck) = cache[slot];
            if key == l {
                n.push(cn);
                k.push(ck);
                continue;
            }
            let index = self.index_at(l).map_err(|e| (i, e))?;
            cache[slot] = (l, index.n(), index.k());
            n.push(index.n());
            k.push(index.k());
        }
        Ok((n, k))
    }

    /// The wavelength range (µm) of a spectral index's data, `None` for a constant index.
    pub fn wavelength_range(&self) -> Option<(f64, f64)> {
        self.spectral.as_ref().map(|s| s.index.range())
    }
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
    /// `sigma_deg`, `b`, `a`, `index`; `n` and `k` of a spectral material) or not a key.
    pub fn get(&self, key: &str) -> Option<KeyValue> {
        use KeyValue::{Bool, Number, Text};
        Some(match key {
            "name" => Text(self.name.clone()?),
            "n" if self.spectral.is_none() => Number(self.n),
            "k" if self.spectral.is_none() => Number(self.k),
            "index" => Text(self.spectral.as_ref()?.source.clone()),
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
    /// `azimuth_term`, its spelling; the numbers are checked by [`MaterialSpec::build`]. The
    /// key `index` names data to read, which the core does not do: set
    /// [`MaterialSpec::spectral`] instead (`polbrdf-io` does when it reads a file).
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
            ("index", KeyValue::Text(_)) => {
                return Err(
                    "`index` names data to read: set `spectral` (polbrdf-io reads it)".into(),
                )
            }
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
        "name" | "form" | "azimuth_term" | "index" => Some("a string"),
        "shadowing" => Some("true or false"),
        k if KEYS.contains(&k) => Some("a number"),
        _ => None,
    }
}
