//! The simplified Maxwell–Beard pBRDF: scalar BRDF (eqs. 1, 6) and Mueller pBRDF (eq. 9 as
//! corrected in spec §5).

use crate::distribution::Distribution;
use crate::error::{non_negative, Error, Result};
use crate::fresnel::RefractiveIndex;
use crate::geometry::{AngleVariables, Geometry};
use crate::jones::Jones;
use crate::mueller::{Mueller, Stokes};
use crate::shadowing::{AzimuthTerm, Shadowing};
use std::f64::consts::FRAC_PI_2;

/// Which surface term (spec §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Form {
    /// Eq. 1 with eq. 2 read as `f_ZBS(θN) = R_F(0)·D(θN)/(4cos²θN)`:
    /// `f_s = D·R_F(β)·SO / (4 cosθi cosθr)` (default).
    #[default]
    Standard,
    /// Eq. 6 exactly as printed: `f_s = D·R_F(β)·cos²θN·SO / (4 cos²θi cos²θr)`.
    Paper,
}

impl Form {
    /// The name used in material files (`"standard"`, `"paper"`).
    pub fn as_str(&self) -> &'static str {
        match self {
            Form::Standard => "standard",
            Form::Paper => "paper",
        }
    }
}

impl std::str::FromStr for Form {
    type Err = String;
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s {
            "standard" => Ok(Form::Standard),
            "paper" => Ok(Form::Paper),
            other => Err(format!("expected \"standard\" or \"paper\", got {other:?}")),
        }
    }
}

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
            (None, Some(b)) => crate::distribution::checked_b("b", b)?,
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
        Ok(Material {
            spec: self.clone(),
            index,
            distribution,
            shadowing: self.shadowing.then_some(shadowing),
            form: self.form,
            rho_d: rho("rho_d", self.rho_d)?,
            rho_v: rho("rho_v", self.rho_v)?,
        })
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

/// A validated material: everything the model needs to evaluate the pBRDF.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    spec: MaterialSpec,
    index: RefractiveIndex,
    distribution: Distribution,
    shadowing: Option<Shadowing>,
    form: Form,
    rho_d: f64,
    rho_v: f64,
}

/// The terms of one surface evaluation, for tracing a number back to its equation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceTerms {
    /// The angle variables used.
    pub angles: AngleVariables,
    /// `D(θN)` (eq. 4), sr⁻¹.
    pub d: f64,
    /// `R_F(β)` (eq. 1).
    pub r_f: f64,
    /// `SO` (eq. 3); 1 when shadowing is off.
    pub so: f64,
}

/// One evaluation of the model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    /// The 4×4 pBRDF `F` (sr⁻¹, psps basis): `f_s·M/M00 + f_v·diag(1,0,0,0)` (eq. 9 corrected).
    pub pbrdf: Mueller,
    /// Surface term `f_s` (eq. 1 or eq. 6), sr⁻¹.
    pub surface: f64,
    /// Volume term `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)` (eq. 1), sr⁻¹.
    pub volume: f64,
    /// The intermediate quantities; `None` at or below the horizon.
    pub terms: Option<SurfaceTerms>,
}

impl Evaluation {
    /// The zero result (a direction at or below the horizon, spec §1).
    pub fn zero() -> Self {
        Self {
            pbrdf: Mueller::zero(),
            surface: 0.0,
            volume: 0.0,
            terms: None,
        }
    }

    /// Scalar BRDF `f = F00 = f_s + f_v` (eqs. 1, 6), sr⁻¹.
    pub fn brdf(&self) -> f64 {
        self.pbrdf.0[0][0]
    }

    /// DoLP of the reflected light for unpolarized input (eq. 13).
    pub fn dolp(&self) -> f64 {
        self.pbrdf.dolp_unpolarized()
    }

    /// Reflected Stokes radiance per unit irradiance for input `s` (eq. 12).
    pub fn reflect(&self, s: &Stokes) -> Stokes {
        self.pbrdf.apply(s)
    }
}

impl Material {
    /// The spec this material was built from.
    pub fn spec(&self) -> &MaterialSpec {
        &self.spec
    }
    /// Display name, if any.
    pub fn name(&self) -> Option<&str> {
        self.spec.name.as_deref()
    }
    /// Complex refractive index.
    pub fn index(&self) -> RefractiveIndex {
        self.index
    }
    /// Facet distribution (eq. 4).
    pub fn distribution(&self) -> Distribution {
        self.distribution
    }
    /// Shadowing function (eq. 3), `None` when switched off.
    pub fn shadowing(&self) -> Option<Shadowing> {
        self.shadowing
    }
    /// Surface-term form.
    pub fn form(&self) -> Form {
        self.form
    }
    /// ρ_D (sr⁻¹).
    pub fn rho_d(&self) -> f64 {
        self.rho_d
    }
    /// ρ_V (sr⁻¹).
    pub fn rho_v(&self) -> f64 {
        self.rho_v
    }

    /// The full evaluation at a geometry: angle variables (spec §1, §3), then
    /// [`Material::evaluate_angles`]. Zero at or below the horizon.
    pub fn evaluate(&self, g: &Geometry) -> Evaluation {
        match g.angle_variables() {
            Some(v) => self.evaluate_angles(&v),
            None => Evaluation::zero(),
        }
    }

    /// The pBRDF `F` at a geometry (eq. 9 corrected), sr⁻¹.
    pub fn pbrdf(&self, g: &Geometry) -> Mueller {
        self.evaluate(g).pbrdf
    }

    /// The scalar BRDF `f` at a geometry (eq. 1 / eq. 6), sr⁻¹.
    pub fn brdf(&self, g: &Geometry) -> f64 {
        self.evaluate(g).brdf()
    }

    /// DoLP for unpolarized input at a geometry (eq. 13).
    pub fn dolp(&self, g: &Geometry) -> f64 {
        self.evaluate(g).dolp()
    }

    /// The angle-variable entry point (spec §5): the full evaluation from explicit
    /// (θi, θr, β, θN, ΦN, η_i, η_r). Zero when θi or θr is at or beyond π/2 (or NaN).
    ///
    /// `F = f_s·M/M00 + f_v·diag(1, 0, 0, 0)` with `M` the Mueller matrix (Bohren & Huffman) of
    /// `T = Rot(η_r)·diag(rs, rp)·Rot(−η_i)` (eq. 11); the surface part is zero when `M00 = 0`.
    pub fn evaluate_angles(&self, v: &AngleVariables) -> Evaluation {
        if !(v.theta_i < FRAC_PI_2 && v.theta_r < FRAC_PI_2) {
            return Evaluation::zero();
        }
        let fresnel = self.index.amplitudes(v.beta);
        let r_f = fresnel.reflectance();
        let d = self.distribution.eval(v.theta_n);
        let so = self.shadowing.map_or(1.0, |s| s.eval(v));
        let surface = self.surface_term(v, d, r_f, so);
        let volume = self.volume_term(v.theta_i, v.theta_r);
        let m = Mueller::from_jones(&Jones::microfacet(&fresnel, v.eta_i, v.eta_r));
        let m00 = m.0[0][0];
        // A surface term below the smallest normal f64 (~2e-308 sr⁻¹) is flushed to zero: a
        // subnormal keeps too few bits for its polarization to be meaningful (DoP could exceed 1).
        let surface = if m00 > 0.0 && surface >= f64::MIN_POSITIVE {
            surface
        } else {
            0.0
        };
        let mut f = if surface > 0.0 {
            m.scaled(surface / m00)
        } else {
            Mueller::zero()
        };
        f.0[0][0] += volume;
        Evaluation {
            pbrdf: f,
            surface,
            volume,
            terms: Some(SurfaceTerms {
                angles: *v,
                d,
                r_f,
                so,
            }),
        }
    }

    /// The scalar surface term `f_s` from its factors (eq. 1 `standard` or eq. 6 `paper`).
    fn surface_term(&self, v: &AngleVariables, d: f64, r_f: f64, so: f64) -> f64 {
        let (ci, cr) = (v.theta_i.cos(), v.theta_r.cos());
        match self.form {
            Form::Standard => d * r_f * so / (4.0 * ci * cr),
            Form::Paper => {
                let cn = v.theta_n.cos();
                d * r_f * cn * cn * so / (4.0 * ci * ci * cr * cr)
            }
        }
    }

    /// The unpolarized volume term `f_v = ρ_D + 2ρ_V/(cosθi + cosθr)` (eq. 1), sr⁻¹.
    pub fn volume_term(&self, theta_i: f64, theta_r: f64) -> f64 {
        if self.rho_v == 0.0 {
            return self.rho_d;
        }
        self.rho_d + 2.0 * self.rho_v / (theta_i.cos() + theta_r.cos())
    }
}
